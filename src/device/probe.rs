//! The connection doctor: which family answers on a port, at which baud,
//! what it says of itself, and how its link delivers.
//!
//! Only requests that change nothing on any of the three families go out: a
//! servo board's project-id and memory queries, a PLEN2's `<VI` and `<JS`,
//! an rFLEX base's system-status request. Each is harmless to the other two:
//! the servo board drops bytes until its magic (`board.md` D4), the rFLEX
//! waits for `1B 02`, and the PLEN2 ignores every byte between commands that
//! is not `$ # > <` (`plen2.md` §1) — which no servo or rFLEX probe contains
//! ([`requests`] is tested for it, and against the three emulators).
//!
//! [`ProbeDriver`] is sans-IO (a [`crate::link::Driver`]): every byte that
//! comes is offered to all three families' readers, so a slow answer to an
//! earlier probe is still recognised. The same measuring the PLEN2's adaptive
//! pacing does ([`super::plen2::Pacer`]) gives the link's latency, clumps and
//! rate. [`probe_port`] runs it over a real port, at each family's line rate.

use std::collections::VecDeque;
use std::time::{Duration, Instant};

use super::plen2::{LinkReport, Pacer, Pacing, PacingMode};
use crate::link::{self, Connection, LineSettings, LinkError, LinkEvent, Opener, PortName, no_waker};
use crate::project::Family;
use crate::protocol::plen2::{Command as Plen2Command, ReplyEvent, ReplyKind, ReplyReader, decode_version};
use crate::protocol::{rflex, servo};

/// The requests that ask `family` who it is, in the order they go out.
pub fn requests(family: Family) -> Vec<Vec<u8>> {
    match family {
        Family::Servo => [servo::Message::QueryProjectIdRequest, servo::Message::QueryMemorySizeRequest]
            .iter()
            .filter_map(|message| message.encode().ok())
            .collect(),
        Family::Plen2 => [Plen2Command::GetVersion, Plen2Command::GetJointSettings]
            .iter()
            .map(|command| command.to_ascii().into_bytes())
            .collect(),
        Family::Rflex => rflex::Command::SystemStatus.to_frame().to_bytes().into_iter().collect(),
        // The doctor knows how to ask these three only.
        _ => Vec::new(),
    }
}

/// What a device said of itself.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Identity {
    /// A servo board: its project id (0 = none) and memory, when it said.
    Servo {
        /// The stored project's id.
        project_id: Option<i32>,
        /// Free and total memory, bytes.
        memory: Option<(i32, Option<i32>)>,
    },
    /// A PLEN2: "PLEN2 Cytisus 1.4.2".
    Plen2 {
        /// Device, codename and version.
        version: String,
    },
    /// An rFLEX base: its battery (raw, before the robot's offset) and brake.
    Rflex {
        /// Volts × 100, raw.
        voltage_raw: u32,
        /// Whether the brake is set.
        braked: bool,
    },
}

impl Identity {
    /// The family it belongs to.
    pub fn family(&self) -> Family {
        match self {
            Self::Servo { .. } => Family::Servo,
            Self::Plen2 { .. } => Family::Plen2,
            Self::Rflex { .. } => Family::Rflex,
        }
    }
}

impl std::fmt::Display for Identity {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Servo { project_id, memory } => {
                write!(f, "servo board")?;
                match project_id {
                    Some(0) => write!(f, ", no project")?,
                    Some(id) => write!(f, ", project {id}")?,
                    None => {}
                }
                match memory {
                    Some((free, Some(total))) => write!(f, ", {free} of {total} bytes free"),
                    Some((free, None)) => write!(f, ", {free} bytes free"),
                    None => Ok(()),
                }
            }
            Self::Plen2 { version } => write!(f, "{version}"),
            Self::Rflex { voltage_raw, braked } => write!(
                f,
                "rFLEX base, battery {:.2} V raw, brake {}",
                f64::from(*voltage_raw) / 100.0,
                if *braked { "set" } else { "released" }
            ),
        }
    }
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
    servo: servo::FrameDecoder,
    rflex: rflex::FrameDecoder,
    plen2: ReplyReader,
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
        let mut driver = Self {
            baud,
            plan: families.iter().copied().collect(),
            asking: None,
            timeout,
            servo: servo::FrameDecoder::new(),
            rflex: rflex::FrameDecoder::new(),
            plen2: ReplyReader::new(),
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
        if family == Family::Plen2 {
            let kind = if bytes == Plen2Command::GetVersion.to_ascii().as_bytes() {
                ReplyKind::Version
            } else {
                ReplyKind::JointSettings
            };
            self.plen2.expect(kind);
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
        let merged = match (self.identity.take(), identity) {
            (
                Some(Identity::Servo { project_id, memory }),
                Identity::Servo { project_id: new_id, memory: new_memory },
            ) => Identity::Servo { project_id: new_id.or(project_id), memory: new_memory.or(memory) },
            (Some(earlier), _) if earlier.family() != family => earlier,
            (_, identity) => identity,
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

    fn read_servo(&mut self, bytes: &[u8]) {
        self.servo.push(bytes);
        while let Some(event) = self.servo.poll() {
            let servo::DecoderEvent::Frame(frame) = event else { continue };
            match servo::Message::from_frame(&frame) {
                Ok(servo::Message::QueryProjectIdResponse { project_id }) => {
                    self.recognised(Identity::Servo { project_id: Some(project_id), memory: None });
                }
                Ok(servo::Message::QueryMemorySizeResponse { free_bytes, total_bytes }) => {
                    self.recognised(Identity::Servo { project_id: None, memory: Some((free_bytes, total_bytes)) });
                }
                // Any whole frame with a right checksum is a servo board talking.
                _ => self.recognised(Identity::Servo { project_id: None, memory: None }),
            }
        }
    }

    fn read_rflex(&mut self, bytes: &[u8]) {
        self.rflex.push(bytes);
        while let Some(event) = self.rflex.poll() {
            let rflex::DecoderEvent::Frame { frame, .. } = event else { continue };
            if let Ok(rflex::Report::Status { voltage_raw, brake, .. }) = rflex::Report::from_frame(&frame) {
                self.recognised(Identity::Rflex { voltage_raw, braked: brake != 0 });
            }
        }
    }

    fn read_plen2(&mut self, bytes: &[u8]) {
        self.plen2.push(bytes);
        while let Some(event) = self.plen2.poll() {
            match event {
                ReplyEvent::Complete { kind: ReplyKind::Version, bytes } => {
                    if let Some(version) = decode_version(&bytes) {
                        let version = format!("{} {} {}", version.device, version.codename, version.version);
                        self.recognised(Identity::Plen2 { version });
                    }
                }
                // The joint settings were read for their timing only.
                ReplyEvent::Complete { kind: ReplyKind::JointSettings, .. }
                    if matches!(self.identity, Some(Identity::Plen2 { .. })) =>
                {
                    self.next_request();
                }
                _ => {}
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
        self.read_servo(bytes);
        self.read_rflex(bytes);
        self.read_plen2(bytes);
    }

    fn handle_timeout(&mut self, now: Instant) {
        let expired = self.asking.as_ref().and_then(|asking| asking.deadline).is_some_and(|deadline| now >= deadline);
        if !expired {
            return;
        }
        // The family did not answer (or stopped answering): forget what it
        // began and go on with the next — or end, if it had already said who it is.
        self.meter.reset();
        self.plen2.abandon();
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
            self.meter.watch_reply(now);
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
    // The PLEN2 first: USB CDC answers at any rate, and it answers fastest.
    for family in [Family::Plen2, Family::Servo, Family::Rflex] {
        let baud = super::line_settings(family).baud;
        match groups.iter_mut().find(|(rate, _)| *rate == baud) {
            Some((_, families)) => families.push(family),
            None => groups.push((baud, vec![family])),
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
