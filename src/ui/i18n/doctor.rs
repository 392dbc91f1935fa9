//! The connection doctor's sentences (what answered on a port, how its link
//! delivers, a lost link waiting for its device to come back) and the
//! gamepad's (a binding in conflict).

use std::time::Duration;

use super::{Language, Worded};
use crate::device::plen2::LinkReport;
use crate::device::probe::{Identity, ProbeResult};
use crate::say;

impl Language {
    /// A port is being asked who is there.
    pub fn probing(self, port: &str) -> String {
        say!(self, "doctor.probing", port)
    }

    /// What the doctor found on `port`.
    pub fn probe_result(self, port: &str, result: &ProbeResult) -> String {
        if self == Self::English {
            return format!("{port}: {}", result.describe(None));
        }
        let text = match &result.found {
            Some(found) => {
                let (identity, link) = (found.identity.worded(self), self.link_report(&found.link));
                say!(self, "doctor.found", identity, baud = found.baud, link)
            }
            None if result.unrecognised > 0 => say!(self, "doctor.unrecognised", bytes = result.unrecognised),
            None => say!(self, "doctor.nothing_answered"),
        };
        say!(self, "doctor.on_port", port, text)
    }

    /// Hardware = Auto, and nothing on `port` said which board it is.
    pub fn auto_found_nothing(self, port: &str, result: &ProbeResult) -> String {
        say!(self, "doctor.auto_found_nothing", result = self.probe_result(port, result))
    }

    /// The link ended on its own (a pulled cable): it is made again when the device comes back.
    pub fn lost_waiting(self, reason: &crate::link::DisconnectReason, port: &str) -> String {
        say!(self, "doctor.lost_waiting", why = self.disconnect_reason(reason), port)
    }

    /// The lost link was made again.
    pub fn reconnected(self, port: &str) -> String {
        say!(self, "doctor.reconnected", port)
    }

    /// Another device appeared where the lost one was: it is not connected to by itself.
    pub fn other_device(self, port: &str, description: &str) -> String {
        say!(self, "doctor.other_device", port, description)
    }

    /// How a link delivers, as the doctor measured it.
    fn link_report(self, link: &LinkReport) -> String {
        let ms = |d: Duration| d.as_secs_f64() * 1000.0;
        let Some(latency) = link.latency else { return say!(self, "doctor.not_measured") };
        let mut parts = vec![say!(self, "doctor.first_byte_after", ms = ms(latency))];
        if link.late > crate::device::plen2::CLUMP_GAP {
            parts.push(say!(self, "doctor.late_by", ms = ms(link.late)));
        }
        if !link.clump_gap.is_zero() {
            parts.push(say!(self, "doctor.in_clumps", ms = ms(link.clump_gap)));
        } else if link.whole {
            parts.push(say!(self, "doctor.whole"));
        } else {
            parts.push(say!(self, "doctor.smooth"));
        }
        if let Some(rate) = link.bytes_per_s {
            parts.push(say!(self, "doctor.bytes_per_s", rate));
        }
        parts.join(self.word("file.list_comma"))
    }
}

/// Why gamepad bindings cannot all work.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PadConflict<'a> {
    /// A button bound more than once.
    Button(&'a str),
    /// A binding on the rFLEX dead-man.
    Deadman(&'a str),
    /// A servo or joint two axes move.
    Target(&'a str),
}

impl Language {
    /// A gamepad conflict, in this language.
    pub fn pad_conflict(self, conflict: PadConflict<'_>) -> String {
        match conflict {
            PadConflict::Button(name) => say!(self, "pad.bound_twice", name),
            PadConflict::Deadman(name) => say!(self, "pad.deadman", name),
            PadConflict::Target(name) => say!(self, "pad.two_axes", name),
        }
    }
}

/// How a family words what its devices say of themselves: each family's
/// `words.rs` submits one (`inventory::submit!`), for its own `Said`.
pub struct SaidWords(pub fn(&Identity, Language) -> Option<String>);

inventory::collect!(SaidWords);

/// What a device said, worded by its family (in English as the device layer says it
/// when the family words nothing).
impl Worded for Identity {
    fn worded(&self, language: Language) -> String {
        inventory::iter::<SaidWords>
            .into_iter()
            .find_map(|words| (words.0)(self, language))
            .unwrap_or_else(|| self.to_string())
    }
}
