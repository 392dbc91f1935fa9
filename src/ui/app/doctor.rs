//! The connection doctor in the window: a port asked which board it is, off
//! the frame (Find board, and Hardware = Auto, which then connects as the
//! family that answered); and a link lost to a pulled cable, made again by
//! itself when the same device comes back (same port, same USB identity).

use super::*;
use crate::device::probe::{self, ProbeOptions, ProbeResult};
use crate::link::{DisconnectReason, LinkError, PortName};
use crate::ui::connection_bar::DoctorLine;

/// How often a lost link's port is looked for.
const RETRY_EVERY: Duration = Duration::from_secs(2);

/// The doctor's state.
#[derive(Debug, Default)]
pub(super) struct Doctor {
    probing: Option<Probing>,
    /// What the last probe found, shown under the bar.
    line: Option<DoctorLine>,
    /// The port and line rate of the link now open (what a lost link is made again with).
    current: Option<Current>,
    lost: Option<Lost>,
}

#[derive(Debug)]
struct Probing {
    port: String,
    connect: bool,
    done: Receiver<Result<ProbeResult, LinkError>>,
}

/// The link open now, as it was made.
#[derive(Clone, Debug)]
struct Current {
    port: String,
    baud: u32,
    family: Family,
    /// What the port list said of it (a USB device's ids and serial number).
    description: Option<String>,
}

#[derive(Debug)]
struct Lost {
    link: Current,
    next_try: Instant,
    /// A different device was seen on the port (said once).
    other_said: bool,
}

impl StudioApp {
    /// Asks the board on `port` which family it is, off the frame; with
    /// `connect`, connects to it as that family once known.
    pub(super) fn find_board(&mut self, port: &str, connect: bool) {
        let name = match PortName::parse(port) {
            Ok(name) => name,
            Err(error) => {
                self.report(self.language.link_error(&error), true);
                return;
            }
        };
        if self.link.is_some() || self.connecting.is_some() || self.doctor.probing.is_some() {
            return;
        }
        self.doctor.lost = None;
        let (sender, done) = crossbeam_channel::bounded(1);
        let (opener, waker) = (self.opener.clone(), self.waker.clone());
        let spawned = std::thread::Builder::new().name(format!("probe {name}")).spawn(move || {
            let _ = sender.send(probe::probe_port(&name, &opener, &ProbeOptions::default()));
            waker();
        });
        if let Err(error) = spawned {
            self.report(self.language.no_worker(&error), true);
            return;
        }
        self.report(self.language.probing(port), false);
        self.doctor.line = Some(DoctorLine { text: self.language.probing(port), offer: None, busy: true });
        self.doctor.probing = Some(Probing { port: port.to_string(), connect, done });
    }

    /// Whether a port is being asked which board it is.
    pub fn finding_board(&self) -> bool {
        self.doctor.probing.is_some()
    }

    /// Whether a lost link waits for its device to come back.
    pub fn waiting_to_reconnect(&self) -> bool {
        self.doctor.lost.is_some()
    }

    /// What the doctor says under the bar.
    pub(super) fn doctor_line(&self) -> Option<DoctorLine> {
        self.doctor.line.clone()
    }

    /// Takes the probe's answer: says it, and (Hardware = Auto) connects as the family that answered.
    pub(super) fn poll_probe(&mut self) {
        let Some(probing) = &self.doctor.probing else { return };
        let Ok(outcome) = probing.done.try_recv() else { return };
        let Some(Probing { port, connect, .. }) = self.doctor.probing.take() else { return };
        let result = match outcome {
            Ok(result) => result,
            Err(error) => {
                let text = self.language.link_error(&error);
                self.doctor.line = Some(DoctorLine { text: text.clone(), offer: None, busy: false });
                self.report(text, true);
                return;
            }
        };
        let text = self.language.probe_result(&port, &result);
        let offer = result.found.as_ref().map(|found| (port.clone(), found.identity.family(), found.baud));
        self.doctor.line = Some(DoctorLine { text: text.clone(), offer: offer.clone(), busy: false });
        match (connect, offer) {
            (true, Some((port, family, baud))) => self.connect_found(&port, family, baud),
            (true, None) => self.report(self.language.auto_found_nothing(&port, &result), true),
            (false, found) => self.report(text, found.is_none()),
        }
    }

    /// Connects to `port` as `family` (the document's family becomes it, one undo step) at `baud`.
    pub(super) fn connect_found(&mut self, port: &str, family: Family, baud: u32) {
        if self.link.is_some() || self.connecting.is_some() {
            return;
        }
        if family != self.document.project.family {
            self.set_family(family);
        }
        self.connect(port, baud);
    }

    /// A link was made to `port` at `baud`: remembered, so that it can be made again if lost.
    pub(super) fn link_made(&mut self, port: &str, baud: u32, family: Family) {
        let description = self.ports.iter().find(|info| info.name == port).map(|info| info.description.clone());
        let again = self.doctor.lost.take().is_some_and(|lost| lost.link.port == port);
        self.doctor.current = Some(Current { port: port.to_string(), baud, family, description });
        self.doctor.line = None;
        if again {
            self.report(self.language.reconnected(port), false);
        }
    }

    /// The link ended. A pulled cable or a board that lost power (not the
    /// user, not the demo board) is waited for, to be made again.
    pub(super) fn link_ended(&mut self, reason: &DisconnectReason) {
        let current = self.doctor.current.take();
        let physical = matches!(
            reason,
            DisconnectReason::ClosedByPeer | DisconnectReason::ReadFailed(_) | DisconnectReason::WriteFailed(_)
        );
        match current.filter(|_| physical) {
            Some(link) => {
                self.report(self.language.lost_waiting(reason, &link.port), true);
                self.doctor.lost = Some(Lost { link, next_try: Instant::now() + RETRY_EVERY, other_said: false });
            }
            None => self.report(self.language.link_ended(reason), true),
        }
    }

    /// The user closed the link or chose another: nothing is made again by itself.
    pub(super) fn forget_link(&mut self) {
        self.doctor.current = None;
        self.doctor.lost = None;
    }

    /// A lost link's device, back on its port (and the same device, when the
    /// port list names it): connected to again, as it was.
    pub(super) fn reconnect_when_back(&mut self, now: Instant) {
        if self.link.is_some() || self.connecting.is_some() {
            return;
        }
        let Some(lost) = &mut self.doctor.lost else { return };
        if now < lost.next_try {
            return;
        }
        lost.next_try = now + RETRY_EVERY;
        let link = lost.link.clone();
        let listed = self.ports.iter().find(|info| info.name == link.port);
        let back = match (listed, &link.description) {
            (Some(info), Some(was)) if &info.description != was => {
                if !lost.other_said {
                    lost.other_said = true;
                    let text = self.language.other_device(&link.port, &info.description);
                    self.report(text, true);
                }
                false
            }
            (Some(_), _) => true,
            // Not in the list (a pseudo-terminal, a typed path): there when its path is.
            (None, _) => match PortName::parse(&link.port) {
                Ok(PortName::Serial(path)) => std::path::Path::new(&path).exists(),
                Ok(PortName::Tcp(_)) => true,
                Err(_) => false,
            },
        };
        if back && link.family == self.document.project.family {
            self.connect_quietly(&link.port, link.baud);
        }
    }
}
