//! The rFLEX family's driver: the driver the I/O thread runs, and the
//! non-blocking handle the editor and the command line use. The handle keeps
//! the telemetry (battery with its trend, the odometry pose and the driven
//! path, sonar ranges, bump panels, joystick), never leaves a base driving
//! (a dropped handle stops the base and shuts it down), and counts reports
//! that failed their checksum without ever using them.

mod doctor;
mod driver;
mod echoes;
mod trace;
mod words;

use std::collections::BTreeMap;
use std::time::{Duration, Instant};

use crossbeam_channel::Receiver;

pub use crate::protocol::rflex::Odometry;
pub use crate::protocol::rflex::layout::{Bump, Bumps, Layout, Ring, Transducer};
pub use doctor::Said;
pub use driver::{POLL_EVERY, REPORT_PERIOD_US, RESEND_EVERY, RflexCommand, RflexDriver, RflexEvent, SILENCE_LIMIT};
pub use echoes::{CELL_M as ECHO_CELL_M, EchoMap, FORGET_AFTER_S, echo_point, mount_point};

/// The farthest a sonar hears, metres (a range above 3000 units is no echo, at about 1476 a metre).
pub const SONAR_REACH_M: f64 = crate::protocol::rflex::SONAR_NO_ECHO_ABOVE as f64 / 1476.0;
pub use trace::Trace;

use crate::device::LogEntry;
use crate::link::{self, Connection, DisconnectReason, LinkEvent, LinkHandle, Waker};
use crate::protocol::rflex::{Axis, Conversion, Report, SkipReason};

/// The least gap between two writes: the base ignores commands sent too rapidly.
pub const WRITE_GAP: Duration = Duration::from_millis(1);
inventory::submit! {
    crate::device::family::Registered {
        family: crate::project::Family::Rflex,
        // rflex.md §1: 115200 baud; the drivers pause about 1 ms after each write.
        line: || link::LineSettings { min_write_gap: WRITE_GAP, ..link::LineSettings::new(115_200) },
        doctor: Some(crate::device::family::Doctor { rank: 2, recogniser: doctor::recogniser }),
    }
}

/// How long a dropped handle waits for its shutdown to be written.
pub const SHUTDOWN_WAIT: Duration = Duration::from_millis(500);

/// Everything the base has told, in SI units.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Telemetry {
    /// Battery, volts (from SYS_STATUS).
    pub battery_volts: Option<f64>,
    /// (seconds since the link opened, volts), oldest first, thinned when long.
    pub battery_trend: Trace,
    /// The brake, as the base reports it.
    pub brake: Option<bool>,
    /// The pose integrated from odometry since the first report.
    pub pose: Odometry,
    /// (x, y) of the pose after each report, metres, oldest first, thinned when long.
    pub path: Trace,
    /// Measured translational velocity, m/s.
    pub speed_m_per_s: f64,
    /// Measured rotational velocity, rad/s.
    pub turn_rad_per_s: f64,
    /// Latest range per sonar id, metres (`None` = no echo): only the robot's own transducers.
    pub sonar_m: BTreeMap<u8, Option<f64>>,
    /// Readings for ids the robot does not have, raw: reported as unknown, never placed.
    pub unknown_sonar: BTreeMap<u8, u16>,
    /// Every echo placed in the world at the pose it was heard from, fading.
    pub echoes: EchoMap,
    /// The bumpers' DIO data by address (the robot's bump addresses only).
    pub bumpers: BTreeMap<u16, u16>,
    /// Other digital I/O addresses and their state.
    pub digital_io: BTreeMap<u8, u16>,
    /// Joystick (x, y, buttons).
    pub joystick: Option<(i32, i32, u8)>,
    /// Reports dropped because their checksum or length was wrong.
    pub checksum_failures: u64,
    /// Bytes of noise or cut frames dropped.
    pub skipped_bytes: u64,
    /// Odometry reports seen per axis (translation, rotation).
    pub odometry_reports: (u64, u64),
    /// Status reports seen.
    pub status_reports: u64,
    /// Sonar banks of the robot seen since the sonar started reporting (for a full sweep).
    sonar_banks: std::collections::BTreeSet<u8>,
    /// The robot's layout, once a report has come.
    layout: Option<&'static Layout>,
}

impl Telemetry {
    /// Whether every bank the robot has has reported since the sonar started.
    pub fn full_sonar_sweep(&self) -> bool {
        self.layout.is_some_and(|layout| (0..layout.bank_count()).all(|bank| self.sonar_banks.contains(&bank)))
    }

    /// Whether one full set has arrived: status, odometry on both axes, a full
    /// sonar sweep and, on a robot with bumpers, digital I/O.
    pub fn complete(&self) -> bool {
        let bumpers_known =
            self.layout.is_some_and(|layout| layout.bump_addresses().is_empty()) || !self.bumpers.is_empty();
        self.battery_volts.is_some()
            && self.odometry_reports.0 > 0
            && self.odometry_reports.1 > 0
            && self.full_sonar_sweep()
            && bumpers_known
    }

    /// The robot's layout, once a report has come.
    pub fn layout(&self) -> Option<&'static Layout> {
        self.layout
    }

    /// The bumpers pressed now, in the robot's style (B21r panels and corners, Magellan bits).
    pub fn pressed(&self) -> Vec<Bump> {
        let Some(layout) = self.layout else { return Vec::new() };
        self.bumpers.iter().filter_map(|(&address, &data)| layout.bumps(address, data)).flatten().collect()
    }

    /// Whether the base has answered the start-up: a status and an odometry report.
    pub fn answered(&self) -> bool {
        self.status_reports > 0 && (self.odometry_reports.0 > 0 || self.odometry_reports.1 > 0)
    }

    /// Reports that decoded, of every kind counted here.
    pub fn reports(&self) -> u64 {
        self.status_reports + self.odometry_reports.0 + self.odometry_reports.1
    }

    /// Takes in one report that arrived `seconds` after the link opened.
    pub fn record(&mut self, conversion: &Conversion, seconds: f64, report: Report) {
        self.layout = Some(conversion.layout);
        match report {
            Report::Odometry { axis, position, velocity, .. } => match Axis::from_code(axis) {
                Some(Axis::Translation) => {
                    self.pose.update(conversion, Axis::Translation, position);
                    self.speed_m_per_s = conversion.metres(i64::from(velocity));
                    self.odometry_reports.0 += 1;
                    self.path.push([self.pose.x_m, self.pose.y_m]);
                }
                Some(Axis::Rotation) => {
                    self.pose.update(conversion, Axis::Rotation, position);
                    self.turn_rad_per_s = conversion.radians(i64::from(velocity));
                    self.odometry_reports.1 += 1;
                }
                None => {}
            },
            Report::Status { voltage_raw, brake, .. } => {
                let volts = conversion.volts(voltage_raw);
                self.battery_volts = Some(volts);
                self.brake = Some(brake != 0);
                self.status_reports += 1;
                self.battery_trend.push([seconds, volts]);
            }
            Report::Sonar { readings, .. } => {
                let layout = conversion.layout;
                for reading in readings {
                    let Some(transducer) = layout.transducer(reading.sonar_id) else {
                        self.unknown_sonar.insert(reading.sonar_id, reading.range);
                        continue;
                    };
                    self.sonar_banks.insert(reading.sonar_id / 16);
                    let range = layout.range_m(reading.range);
                    if let Some(metres) = range {
                        self.echoes.record(&self.pose, seconds, &transducer, metres);
                    }
                    self.sonar_m.insert(reading.sonar_id, range);
                }
            }
            Report::Dio { address, data, .. } => {
                if conversion.layout.bump_addresses().contains(&u16::from(address)) {
                    self.bumpers.insert(u16::from(address), data);
                } else {
                    self.digital_io.insert(address, data);
                }
            }
            Report::Joystick { x, y, buttons, .. } => self.joystick = Some((x, y, buttons)),
            Report::LcdDump { .. } | Report::Unknown(_) => {}
        }
    }
}

/// What the handle reports to its owner.
#[derive(Clone, Debug, PartialEq)]
pub enum RflexNotice {
    /// A packet-log entry.
    Log(LogEntry),
    /// The base went silent while driving; it was sent a stop.
    Silent,
    /// The link ended; nothing more will come.
    Disconnected(DisconnectReason),
}

/// A connected rFLEX base, driven without blocking. Dropping it stops the base,
/// shuts it down (brake on) and closes the link.
pub struct RflexBase {
    link: Option<LinkHandle<RflexCommand, RflexEvent>>,
    conversion: Conversion,
    opened_at: Instant,
    /// What the base has told.
    pub telemetry: Telemetry,
    /// The velocity last asked for (speed m/s, turn rad/s): what the base is told to do.
    pub commanded: (f64, f64),
    lost: bool,
    /// Round trips of status requests answered since last taken.
    answered: Vec<Duration>,
}

impl std::fmt::Debug for RflexBase {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("RflexBase").field("commanded", &self.commanded).finish_non_exhaustive()
    }
}

impl RflexBase {
    /// Starts the I/O thread over an open connection (writes spaced by at least 1 ms).
    pub fn over(connection: Connection, conversion: Conversion, waker: Waker) -> std::io::Result<Self> {
        let gap = connection.min_write_gap().max(WRITE_GAP);
        let link = link::spawn(connection.with_min_write_gap(gap), RflexDriver::new(conversion), waker)?;
        Ok(Self {
            link: Some(link),
            conversion,
            opened_at: Instant::now(),
            telemetry: Telemetry::default(),
            commanded: (0.0, 0.0),
            lost: false,
            answered: Vec::new(),
        })
    }

    fn command(&self, command: RflexCommand) {
        if let Some(link) = &self.link {
            // A closed link is reported by `pump` as a disconnect.
            let _ = link.commands().send(command);
        }
    }

    /// The robot's conversion constants.
    pub fn conversion(&self) -> Conversion {
        self.conversion
    }

    /// The start-up sequence (reports on, motion defaults; the sonar if asked).
    pub fn start(&self, sonar: bool) {
        self.command(RflexCommand::Start { sonar });
    }

    /// Holds a velocity, re-sent at 10 Hz; (0, 0) stops.
    pub fn drive(&mut self, speed_m_per_s: f64, turn_rad_per_s: f64, accel_m_per_s2: f64) {
        self.commanded = (speed_m_per_s, turn_rad_per_s);
        self.command(RflexCommand::Drive { speed_m_per_s, turn_rad_per_s, accel_m_per_s2 });
    }

    /// Stops now.
    pub fn stop(&mut self) {
        self.commanded = (0.0, 0.0);
        self.command(RflexCommand::Stop);
    }

    /// Sets or releases the brake (setting it stops first).
    pub fn set_brake(&mut self, on: bool) {
        if on {
            self.commanded = (0.0, 0.0);
        }
        self.command(RflexCommand::Brake(on));
    }

    /// Asks for the system status once; its round trip comes in [`RflexBase::round_trips`].
    pub fn ask_status(&self) {
        self.command(RflexCommand::AskStatus);
    }

    /// The round trips of status requests answered since last asked (taken in by [`RflexBase::pump`]).
    pub fn round_trips(&mut self) -> Vec<Duration> {
        std::mem::take(&mut self.answered)
    }

    /// Turns the sonar ring on or off.
    pub fn set_sonar(&self, on: bool) {
        self.command(RflexCommand::Sonar(on));
    }

    /// Whether the link has ended.
    pub fn is_lost(&self) -> bool {
        self.lost
    }

    /// The event channel, for owners that block on it (the command line).
    pub fn events(&self) -> Option<&Receiver<LinkEvent<RflexEvent>>> {
        self.link.as_ref().map(LinkHandle::events)
    }

    /// Takes in what the base sent; returns what the owner should see.
    pub fn pump(&mut self, now: Instant) -> Vec<RflexNotice> {
        let Some(link) = &self.link else { return Vec::new() };
        let events: Vec<LinkEvent<RflexEvent>> = link.events().try_iter().collect();
        let seconds = now.saturating_duration_since(self.opened_at).as_secs_f64();
        let mut notices = Vec::new();
        for event in events {
            match event {
                LinkEvent::Driver(RflexEvent::Report(report)) => {
                    self.telemetry.record(&self.conversion, seconds, report);
                }
                LinkEvent::Driver(RflexEvent::Skipped { bytes, reason }) => {
                    if reason == SkipReason::BadFrame {
                        self.telemetry.checksum_failures += 1;
                    }
                    self.telemetry.skipped_bytes += u64::try_from(bytes).unwrap_or(u64::MAX);
                }
                LinkEvent::Driver(RflexEvent::Log(entry)) => notices.push(RflexNotice::Log(entry)),
                LinkEvent::Driver(RflexEvent::StatusAnswered(round_trip)) => {
                    // Kept for whoever measures the link; the newest few, never more.
                    if self.answered.len() >= 16 {
                        self.answered.remove(0);
                    }
                    self.answered.push(round_trip);
                }
                LinkEvent::Driver(RflexEvent::Silent) => {
                    self.commanded = (0.0, 0.0);
                    notices.push(RflexNotice::Silent);
                }
                LinkEvent::Disconnected { reason } => {
                    self.lost = true;
                    self.commanded = (0.0, 0.0);
                    notices.push(RflexNotice::Disconnected(reason));
                }
            }
        }
        notices
    }

    /// Stops the base and runs the shutdown sequence (brake on), waiting at
    /// most `wait` for it to be written; then closes the link.
    pub fn shutdown(&mut self, wait: Duration) {
        let Some(link) = self.link.take() else { return };
        if !self.lost {
            let (done, written) = crossbeam_channel::bounded(1);
            if link.commands().send(RflexCommand::Shutdown { done: Some(done) }).is_ok() {
                // A lost link drops the sender: the wait ends at once.
                let _ = written.recv_timeout(wait);
            }
        }
        self.commanded = (0.0, 0.0);
        link.close();
    }
}

impl Drop for RflexBase {
    fn drop(&mut self) {
        // The app never leaves a base driving: closing the window, a panic
        // unwinding, or the command line ending all come through here.
        self.shutdown(SHUTDOWN_WAIT);
    }
}
