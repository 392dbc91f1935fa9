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
    /// What the last probe found, a line per port, shown under the bar.
    lines: Vec<DoctorLine>,
    /// The port and line rate of the link now open (what a lost link is made again with).
    current: Option<Current>,
    lost: Option<Lost>,
    /// Each port's first-byte latency, as the last probe of it measured.
    latency: std::collections::BTreeMap<String, Duration>,
}

/// Ports being asked, one after another, on a helper thread.
#[derive(Debug)]
struct Probing {
    /// Connect to what answers (Hardware = Auto; one port).
    connect: bool,
    /// Each port's answer, as it comes.
    done: Receiver<(String, Result<ProbeResult, LinkError>)>,
    /// Ports not answered yet.
    left: usize,
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
        if let Err(error) = PortName::parse(port) {
            self.say(|language| language.link_error(&error), true);
            return;
        }
        self.ask(&[port.to_string()], connect);
    }

    /// Asks every port the computer lists which board is on it.
    pub(super) fn find_every_board(&mut self) {
        let ports: Vec<String> = self.links.ports.iter().map(|info| info.name.clone()).collect();
        if ports.is_empty() {
            self.say(|language| language.strings().msg_no_ports, true);
            return;
        }
        self.ask(&ports, false);
    }

    fn ask(&mut self, ports: &[String], connect: bool) {
        if self.link.is_some() || self.links.connecting.is_some() || self.links.doctor.probing.is_some() {
            return;
        }
        self.links.doctor.lost = None;
        let (sender, done) = crossbeam_channel::unbounded();
        let (opener, waker, asked) = (self.links.opener.clone(), self.window.waker.clone(), ports.to_vec());
        let spawned = std::thread::Builder::new().name("probe".into()).spawn(move || {
            for port in asked {
                let result =
                    PortName::parse(&port).and_then(|name| probe::probe_port(&name, &opener, &ProbeOptions::default()));
                if sender.send((port, result)).is_err() {
                    return;
                }
                waker();
            }
        });
        if let Err(error) = spawned {
            self.say(|language| language.no_worker(&error), true);
            return;
        }
        self.say(|language| language.probing(&ports.join(", ")), false);
        self.links.doctor.lines = ports
            .iter()
            .map(|port| DoctorLine { port: port.clone(), text: self.language.probing(port), offer: None, busy: true })
            .collect();
        self.links.doctor.probing = Some(Probing { connect, done, left: ports.len() });
    }

    /// Whether a port is being asked which board it is.
    pub fn finding_board(&self) -> bool {
        self.links.doctor.probing.is_some()
    }

    /// Whether a lost link waits for its device to come back.
    pub fn waiting_to_reconnect(&self) -> bool {
        self.links.doctor.lost.is_some()
    }

    /// What the doctor says under the bar, a line per port.
    pub(super) fn doctor_lines(&self) -> Vec<DoctorLine> {
        self.links.doctor.lines.clone()
    }

    /// Takes the probes' answers: says each, and (Hardware = Auto) connects as the family that answered.
    pub(super) fn poll_probe(&mut self) {
        let Some(probing) = &self.links.doctor.probing else { return };
        let answers: Vec<_> = probing.done.try_iter().collect();
        let connect = probing.connect;
        for (port, outcome) in answers {
            if let Some(latency) = outcome.as_ref().ok().and_then(|result| result.found.as_ref()?.link.latency) {
                self.links.doctor.latency.insert(port.clone(), latency);
            }
            let (text, offer) = match &outcome {
                Ok(result) => (
                    self.language.probe_result(&port, result),
                    result.found.as_ref().map(|found| (found.identity.family(), found.baud)),
                ),
                Err(error) => (self.language.link_error(error), None),
            };
            let line = DoctorLine { port: port.clone(), text: text.clone(), offer, busy: false };
            match self.links.doctor.lines.iter_mut().find(|shown| shown.busy && shown.port == port) {
                Some(shown) => *shown = line,
                None => self.links.doctor.lines.push(line),
            }
            if let Some(probing) = &mut self.links.doctor.probing {
                probing.left = probing.left.saturating_sub(1);
            }
            match (connect, offer, &outcome) {
                (true, Some((family, baud)), _) => self.connect_found(&port, family, baud),
                (true, None, Ok(result)) => self.say(|language| language.auto_found_nothing(&port, result), true),
                (_, offer, _) => {
                    let said = |language: Language| match &outcome {
                        Ok(result) => language.probe_result(&port, result),
                        Err(error) => language.link_error(error),
                    };
                    self.say(said, offer.is_none());
                }
            }
        }
        if self.links.doctor.probing.as_ref().is_some_and(|probing| probing.left == 0) {
            self.links.doctor.probing = None;
        }
    }

    /// The first-byte latency the doctor measured on the port now open, if it asked it.
    pub(super) fn measured_latency(&self) -> Option<Duration> {
        let current = self.links.doctor.current.as_ref()?;
        self.links.doctor.latency.get(&current.port).copied()
    }

    /// The port and line rate of the link now open (none for the demo board).
    pub(super) fn link_port(&self) -> Option<(String, u32)> {
        let current = self.links.doctor.current.as_ref()?;
        Some((current.port.clone(), current.baud))
    }

    /// Connects to `port` as `family` (the document's family becomes it, one undo step) at `baud`.
    pub(super) fn connect_found(&mut self, port: &str, family: Family, baud: u32) {
        if self.link.is_some() || self.links.connecting.is_some() {
            return;
        }
        if family != self.document.project.family {
            self.set_family(family);
        }
        self.connect(port, baud);
    }

    /// A link was made to `port` at `baud`: remembered, so that it can be made again if lost.
    pub(super) fn link_made(&mut self, port: &str, baud: u32, family: Family) {
        let description = self.links.ports.iter().find(|info| info.name == port).map(|info| info.description.clone());
        let again = self.links.doctor.lost.take().is_some_and(|lost| lost.link.port == port);
        self.links.doctor.current = Some(Current { port: port.to_string(), baud, family, description });
        self.links.doctor.lines.clear();
        if again {
            self.say(|language| language.reconnected(port), false);
        }
    }

    /// The link ended. A pulled cable or a board that lost power (not the
    /// user, not the demo board) is waited for, to be made again.
    pub(super) fn link_ended(&mut self, reason: &DisconnectReason) {
        let current = self.links.doctor.current.take();
        let physical = matches!(
            reason,
            DisconnectReason::ClosedByPeer | DisconnectReason::ReadFailed(_) | DisconnectReason::WriteFailed(_)
        );
        match current.filter(|_| physical) {
            Some(link) => {
                self.say(|language| language.lost_waiting(reason, &link.port), true);
                self.links.doctor.lost = Some(Lost { link, next_try: Instant::now() + RETRY_EVERY, other_said: false });
            }
            None => self.say(|language| language.link_ended(reason), true),
        }
    }

    /// The user closed the link or chose another: nothing is made again by itself.
    pub(super) fn forget_link(&mut self) {
        self.links.doctor.current = None;
        self.links.doctor.lost = None;
    }

    /// A lost link's device, back on its port (and the same device, when the
    /// port list names it): connected to again, as it was.
    pub(super) fn reconnect_when_back(&mut self, now: Instant) {
        if self.link.is_some() || self.links.connecting.is_some() {
            return;
        }
        let Some(lost) = &mut self.links.doctor.lost else { return };
        if now < lost.next_try {
            return;
        }
        lost.next_try = now + RETRY_EVERY;
        let link = lost.link.clone();
        let listed = self.links.ports.iter().find(|info| info.name == link.port);
        let back = match (listed, &link.description) {
            (Some(info), Some(was)) if &info.description != was => {
                if !lost.other_said {
                    lost.other_said = true;
                    let said = StatusLine::worded(
                        self.language,
                        |language| language.other_device(&link.port, &info.description),
                        true,
                    );
                    self.status = Some(said);
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
