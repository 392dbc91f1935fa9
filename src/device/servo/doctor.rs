//! The servo board's side of the connection doctor: its project-id and memory
//! queries (`board.md` §1), and what it says to them.

use std::any::Any;
use std::fmt;
use std::sync::Arc;

use crate::device::family::{Heard, Identity, Recogniser, Said as SaidTrait};
use crate::project::Family;
use crate::protocol::servo::{DecoderEvent, FrameDecoder, Message};

/// What a servo board said of itself: its project id (0 = none) and memory, when it said.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Said {
    /// The stored project's id.
    pub project_id: Option<i32>,
    /// Free and total memory, bytes.
    pub memory: Option<(i32, Option<i32>)>,
}

impl SaidTrait for Said {
    fn family(&self) -> Family {
        Family::Servo
    }

    fn merged(&self, earlier: &dyn Any) -> Option<Arc<dyn SaidTrait>> {
        let earlier = earlier.downcast_ref::<Self>()?;
        let merged =
            Self { project_id: self.project_id.or(earlier.project_id), memory: self.memory.or(earlier.memory) };
        Some(Arc::new(merged))
    }
}

impl fmt::Display for Said {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "servo board")?;
        match self.project_id {
            Some(0) => write!(f, ", no project")?,
            Some(id) => write!(f, ", project {id}")?,
            None => {}
        }
        match self.memory {
            Some((free, Some(total))) => write!(f, ", {free} of {total} bytes free"),
            Some((free, None)) => write!(f, ", {free} bytes free"),
            None => Ok(()),
        }
    }
}

/// Reads servo frames out of whatever comes.
#[derive(Debug, Default)]
pub(super) struct Doctor {
    frames: FrameDecoder,
}

/// A fresh servo reader, as the doctor registry wants it.
pub(super) fn recogniser() -> Box<dyn Recogniser> {
    Box::new(Doctor::default())
}

impl Recogniser for Doctor {
    fn requests(&self) -> Vec<Vec<u8>> {
        [Message::QueryProjectIdRequest, Message::QueryMemorySizeRequest]
            .iter()
            .filter_map(|message| message.encode().ok())
            .collect()
    }

    fn read(&mut self, bytes: &[u8]) -> Vec<Heard> {
        self.frames.push(bytes);
        let mut heard = Vec::new();
        while let Some(event) = self.frames.poll() {
            let DecoderEvent::Frame(frame) = event else { continue };
            let said = match Message::from_frame(&frame) {
                Ok(Message::QueryProjectIdResponse { project_id }) => {
                    Said { project_id: Some(project_id), memory: None }
                }
                Ok(Message::QueryMemorySizeResponse { free_bytes, total_bytes }) => {
                    Said { project_id: None, memory: Some((free_bytes, total_bytes)) }
                }
                // Any whole frame with a right checksum is a servo board talking.
                _ => Said::default(),
            };
            heard.push(Heard::Said(Identity::new(said)));
        }
        heard
    }
}
