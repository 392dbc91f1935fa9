//! The connection doctor: which family answers on a port, at which baud,
//! what it says of itself, and how its link delivers.
//!
//! Each family registers its side ([`Recogniser`], in `device/<family>/doctor.rs`).
//! Only requests that change nothing on any of the three families go out: a
//! servo board's project-id and memory queries, a PLEN2's `<VI` and `<JS`,
//! an rFLEX base's system-status request. Each is harmless to the other two:
//! the servo board drops bytes until its magic (`board.md` D4), the rFLEX
//! waits for `1B 02`, and the PLEN2 ignores every byte between commands that
//! is not `$ # > <` (`plen2.md` §1) — which no servo or rFLEX probe contains
//! ([`requests`] is tested for it, and against the three emulators).
//!
//! [`ProbeDriver`] is sans-IO (a [`crate::link::Driver`]): every byte that
//! comes is offered to every family's reader, so a slow answer to an
//! earlier probe is still recognised. The same measuring the PLEN2's adaptive
//! pacing does ([`super::plen2::Pacer`]) gives the link's latency, clumps and
//! rate. [`probe_port`] runs it over a real port, at each family's line rate.

use std::collections::VecDeque;
use std::time::{Duration, Instant};

use super::family::doctored;
pub use super::family::{Heard, Identity, Recogniser, Said, SameSaid};
use super::plen2::{LinkReport, Pacer, Pacing, PacingMode};
use crate::link::{self, Connection, LineSettings, LinkError, LinkEvent, Opener, PortName, no_waker};
use crate::project::Family;

/// The requests that ask `family` who it is, in the order they go out (none
/// for a family the doctor does not ask).
pub fn requests(family: Family) -> Vec<Vec<u8>> {
    doctored()
        .into_iter()
        .find(|(asked, _)| *asked == family)
        .map(|(_, doctor)| (doctor.recogniser)().requests())
        .unwrap_or_default()
}

/// A device that answered.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Found {
    /// Who it is.
    pub identity: Identity,
    /// The line rate it answered at.
    pub baud: u32,
    /// How its replies arrived.
    pub link: LinkReport,
}

/// What one probe of a port found.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ProbeResult {
    /// The device that answered, if one did.
    pub found: Option<Found>,
    /// Bytes that came and were no family's reply.
    pub unrecognised: usize,
}

/// A request on its way, and when it gives up.
#[derive(Debug)]
struct Asking {
    family: Family,
    /// The requests of this family still to go after this one.
    rest: VecDeque<Vec<u8>>,
    /// When the request left (its write returned): the reply is timed from there.
    deadline: Option<Instant>,
    began: Option<Instant>,
}

/// The probe as a link driver: one line rate, the families to try at it.
#[derive(Debug)]
pub struct ProbeDriver {
    baud: u32,
    plan: VecDeque<Family>,
    asking: Option<Asking>,
    timeout: Duration,
    /// Every asked family's reader: each reads every byte that comes.
    readers: Vec<(Family, Box<dyn Recogniser>)>,
    meter: Pacer,
    identity: Option<Identity>,
    heard: usize,
    output: VecDeque<Vec<u8>>,
    result: Option<ProbeResult>,
    told: bool,
}

/// The longest any one request may take once its reply is coming (a PLEN2's
/// joint settings over a slow Bluetooth bridge).
const LONGEST_REPLY: Duration = Duration::from_secs(5);

impl ProbeDriver {
    /// Tries `families` in order at `baud`; each request is given `timeout`
    /// to begin its reply, and as long between two of its bytes.
    pub fn new(baud: u32, families: &[Family], timeout: Duration) -> Self {
        let readers = doctored().into_iter().map(|(family, doctor)| (family, (doctor.recogniser)())).collect();
        let mut driver = Self {
            baud,
            plan: families.iter().copied().collect(),
            asking: None,
            timeout,
            readers,
            meter: Pacer::new(PacingMode::Adaptive, Pacing::default(), baud),
            identity: None,
            heard: 0,
            output: VecDeque::new(),
            result: None,
            told: false,
        };
        driver.next_family();
        driver
    }

    /// The outcome, once every request is answered or given up.
    pub fn result(&self) -> Option<&ProbeResult> {
        self.result.as_ref()
    }

    fn next_family(&mut self) {
        self.asking = None;
        let Some(family) = self.plan.pop_front() else { return self.finish() };
        let mut rest: VecDeque<Vec<u8>> = requests(family).into();
        let Some(first) = rest.pop_front() else { return self.next_family() };
        self.asking = Some(Asking { family, rest, deadline: None, began: None });
        self.send(family, first);
    }

    fn send(&mut self, family: Family, bytes: Vec<u8>) {
        if let Some((_, reader)) = self.readers.iter_mut().find(|(reader, _)| *reader == family) {
            reader.asking(&bytes);
        }
        self.output.push_back(bytes);
    }

    /// The family's next request, or the end: it answered.
    fn next_request(&mut self) {
        self.meter.reply_ended();
        let Some(asking) = &mut self.asking else { return };
        match asking.rest.pop_front() {
            Some(bytes) => {
                asking.deadline = None;
                asking.began = None;
                let family = asking.family;
                self.send(family, bytes);
            }
            None => self.finish(),
        }
    }

    fn finish(&mut self) {
        self.asking = None;
        self.plan.clear();
        if self.result.is_none() {
            let found =
                self.identity.clone().map(|identity| Found { identity, baud: self.baud, link: self.meter.report() });
            let unrecognised = if found.is_some() { 0 } else { self.heard };
            self.result = Some(ProbeResult { found, unrecognised });
        }
    }

    /// A reply of `family` was recognised as `identity` (merged with what it said before).
    fn recognised(&mut self, identity: Identity) {
        let family = identity.family();
        let merged = match self.identity.take() {
            Some(earlier) if earlier.family() != family => earlier,
            Some(earlier) => identity.after(&earlier),
            None => identity,
        };
        let asked = self.asking.as_ref().map(|asking| asking.family);
        self.identity = Some(merged);
        if asked == Some(family) {
            self.next_request();
        } else {
            // A late answer to an earlier family's probe: that is who is there.
            self.finish();
        }
    }

    /// Every family's reader reads `bytes`; what they heard moves the probe on.
    fn read(&mut self, bytes: &[u8]) {
        let mut heard = Vec::new();
        for (family, reader) in &mut self.readers {
            heard.extend(reader.read(bytes).into_iter().map(|said| (*family, said)));
        }
        for (family, said) in heard {
            if self.result.is_some() {
                return;
            }
            match said {
                Heard::Said(identity) => self.recognised(identity),
                // Read for its timing only, once the family has said who it is.
                Heard::Answered if self.identity.as_ref().is_some_and(|identity| identity.family() == family) => {
                    self.next_request();
                }
                Heard::Answered => {}
            }
        }
    }
}

impl link::Driver for ProbeDriver {
    type Command = ();
    type Event = ProbeResult;

    fn handle_command(&mut self, _now: Instant, (): ()) {}

    fn handle_input(&mut self, now: Instant, bytes: &[u8]) {
        if self.result.is_some() {
            return;
        }
        self.heard += bytes.len();
        if let Some(asking) = &mut self.asking {
            self.meter.reply_bytes(now, bytes.len());
            let began = *asking.began.get_or_insert(now);
            asking.deadline = Some((now + self.timeout).min(began + LONGEST_REPLY));
        }
        self.read(bytes);
    }

    fn handle_timeout(&mut self, now: Instant) {
        let expired = self.asking.as_ref().and_then(|asking| asking.deadline).is_some_and(|deadline| now >= deadline);
        if !expired {
            return;
        }
        // The family did not answer (or stopped answering): forget what it
        // began and go on with the next — or end, if it had already said who it is.
        self.meter.reset();
        for (_, reader) in &mut self.readers {
            reader.abandon();
        }
        if self.identity.is_some() { self.finish() } else { self.next_family() }
    }

    fn handle_disconnect(&mut self, _reason: &str) {
        self.finish();
    }

    fn poll_transmit(&mut self, _now: Instant) -> Option<Vec<u8>> {
        self.output.pop_front()
    }

    fn handle_written(&mut self, now: Instant, _bytes: usize) {
        if let Some(asking) = &mut self.asking
            && asking.deadline.is_none()
        {
            asking.deadline = Some(now + self.timeout);
            self.meter.watch_reply(now, now);
        }
    }

    fn poll_event(&mut self) -> Option<ProbeResult> {
        if self.told {
            return None;
        }
        let result = self.result.clone()?;
        self.told = true;
        Some(result)
    }

    fn poll_timeout(&self) -> Option<Instant> {
        self.asking.as_ref().and_then(|asking| asking.deadline)
    }

    fn wants_close(&self) -> bool {
        self.told
    }
}

/// How to probe a port.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ProbeOptions {
    /// One line rate for every family; `None`: each family's own.
    pub baud: Option<u32>,
    /// How long a request may wait for its reply to begin.
    pub timeout: Duration,
}

impl Default for ProbeOptions {
    fn default() -> Self {
        Self { baud: None, timeout: Duration::from_millis(500) }
    }
}

/// The line rates tried, and the families asked at each: each family's own
/// (`device::line_settings`), or every family at the one given.
pub fn plan(baud: Option<u32>) -> Vec<(u32, Vec<Family>)> {
    if let Some(baud) = baud {
        return vec![(baud, Family::all().to_vec())];
    }
    let mut groups: Vec<(u32, Vec<Family>)> = Vec::new();
    // In the doctor's order (the PLEN2 first: USB CDC answers at any rate, and fastest).
    for (family, _) in doctored() {
        for baud in super::family::doctor_rates(family, super::line_settings(family).baud) {
            match groups.iter_mut().find(|(rate, _)| *rate == baud) {
                Some((_, families)) => families.push(family),
                None => groups.push((baud, vec![family])),
            }
        }
    }
    groups
}

/// The longest a probe at one line rate can take: every request given up
/// after its longest reply, and then some.
fn longest_probe(families: usize, timeout: Duration) -> Duration {
    (LONGEST_REPLY + timeout) * u32::try_from(families * 2 + 1).unwrap_or(u32::MAX)
}

/// Probes `port` (opened with `opener`, once per line rate): the first family
/// that answers ends it. Blocks for at most a few seconds per line rate.
pub fn probe_port(port: &PortName, opener: &Opener, options: &ProbeOptions) -> Result<ProbeResult, LinkError> {
    let mut unrecognised = 0;
    for (baud, families) in plan(options.baud) {
        let gap = families.iter().map(|family| super::line_settings(*family).min_write_gap).max().unwrap_or_default();
        let settings = LineSettings { min_write_gap: gap, ..LineSettings::new(baud) };
        let connection: Connection = opener(port, &settings)?;
        let driver = ProbeDriver::new(baud, &families, options.timeout);
        let handle = link::spawn(connection, driver, no_waker())
            .map_err(|source| LinkError::Open { port: port.to_string(), source })?;
        let give_up = Instant::now() + longest_probe(families.len(), options.timeout);
        let mut result = None;
        while let Ok(event) = handle.events().recv_deadline(give_up) {
            match event {
                LinkEvent::Driver(outcome) => result = Some(outcome),
                LinkEvent::Disconnected { .. } => break,
            }
        }
        drop(handle);
        let result = result.unwrap_or_default();
        if result.found.is_some() {
            return Ok(result);
        }
        unrecognised += result.unrecognised;
    }
    Ok(ProbeResult { found: None, unrecognised })
}

impl ProbeResult {
    /// What the probe found, in English: who answered, at which line rate,
    /// and how the link delivers — or what to check when nothing did.
    pub fn describe(&self, baud: Option<u32>) -> String {
        match &self.found {
            Some(found) => format!("{} at {} baud; link: {}", found.identity, found.baud, found.link),
            None if self.unrecognised > 0 => format!(
                "{} came, in no family's protocol: a different device, or another line rate{}",
                super::bytes(self.unrecognised),
                if baud.is_some() { "" } else { " (try --baud)" }
            ),
            None => "nothing answered: is the device powered, its cable in, and (PLEN2) DTR wired?".to_string(),
        }
    }
}
