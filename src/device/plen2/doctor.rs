//! The PLEN2's side of the connection doctor: `<VI` and `<JS` (`plen2.md` §2),
//! and the version it says.

use std::fmt;

use crate::device::family::{Heard, Identity, Recogniser, Said as SaidTrait};
use crate::project::Family;
use crate::protocol::plen2::{Command, ReplyEvent, ReplyKind, ReplyReader, decode_version};

/// What a PLEN2 said of itself: device, codename and version ("PLEN2 Cytisus 1.4.2").
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Said {
    /// Device, codename and version.
    pub version: String,
}

impl SaidTrait for Said {
    fn family(&self) -> Family {
        Family::Plen2
    }
}

impl fmt::Display for Said {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.version)
    }
}

/// Reads PLEN2 replies out of whatever comes; it must know what it asked.
#[derive(Debug)]
pub(super) struct Doctor {
    replies: ReplyReader,
}

/// A fresh PLEN2 reader, as the doctor registry wants it.
pub(super) fn recogniser() -> Box<dyn Recogniser> {
    Box::new(Doctor { replies: ReplyReader::new() })
}

impl Recogniser for Doctor {
    fn requests(&self) -> Vec<Vec<u8>> {
        [Command::GetVersion, Command::GetJointSettings].iter().map(|command| command.to_ascii().into_bytes()).collect()
    }

    fn asking(&mut self, request: &[u8]) {
        let kind = if request == Command::GetVersion.to_ascii().as_bytes() {
            ReplyKind::Version
        } else {
            ReplyKind::JointSettings
        };
        self.replies.expect(kind);
    }

    fn read(&mut self, bytes: &[u8]) -> Vec<Heard> {
        self.replies.push(bytes);
        let mut heard = Vec::new();
        while let Some(event) = self.replies.poll() {
            match event {
                ReplyEvent::Complete { kind: ReplyKind::Version, bytes } => {
                    if let Some(version) = decode_version(&bytes) {
                        let version = format!("{} {} {}", version.device, version.codename, version.version);
                        heard.push(Heard::Said(Identity::new(Said { version })));
                    }
                }
                // The joint settings are read for their timing only.
                ReplyEvent::Complete { kind: ReplyKind::JointSettings, .. } => heard.push(Heard::Answered),
                _ => {}
            }
        }
        heard
    }

    fn abandon(&mut self) {
        self.replies.abandon();
    }
}
