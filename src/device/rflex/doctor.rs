//! The rFLEX base's side of the connection doctor: a system-status request
//! (`rflex.md` §2), and the battery and brake it reports.

use std::fmt;

use crate::device::family::{Heard, Identity, Recogniser, Said as SaidTrait};
use crate::project::Family;
use crate::protocol::rflex::{Command, DecoderEvent, FrameDecoder, Report};

/// What an rFLEX base said of itself: its battery (raw, before the robot's offset) and brake.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Said {
    /// Volts × 100, raw.
    pub voltage_raw: u32,
    /// Whether the brake is set.
    pub braked: bool,
}

impl SaidTrait for Said {
    fn family(&self) -> Family {
        Family::Rflex
    }
}

impl fmt::Display for Said {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "rFLEX base, battery {:.2} V raw, brake {}",
            f64::from(self.voltage_raw) / 100.0,
            if self.braked { "set" } else { "released" }
        )
    }
}

/// Reads rFLEX frames out of whatever comes.
#[derive(Debug)]
pub(super) struct Doctor {
    frames: FrameDecoder,
}

/// A fresh rFLEX reader, as the doctor registry wants it.
pub(super) fn recogniser() -> Box<dyn Recogniser> {
    Box::new(Doctor { frames: FrameDecoder::new() })
}

impl Recogniser for Doctor {
    fn requests(&self) -> Vec<Vec<u8>> {
        Command::SystemStatus.to_frame().to_bytes().into_iter().collect()
    }

    fn read(&mut self, bytes: &[u8]) -> Vec<Heard> {
        self.frames.push(bytes);
        let mut heard = Vec::new();
        while let Some(event) = self.frames.poll() {
            let DecoderEvent::Frame { frame, .. } = event else { continue };
            if let Ok(Report::Status { voltage_raw, brake, .. }) = Report::from_frame(&frame) {
                heard.push(Heard::Said(Identity::new(Said { voltage_raw, braked: brake != 0 })));
            }
        }
        heard
    }
}
