//! The rFLEX driver the I/O thread runs: the start-up and shutdown sequences
//! of `rflex.md` §3, a held velocity re-sent at 10 Hz, an explicit stop when
//! released, and status polling. Sans-IO: time comes in as `now`.

use std::collections::VecDeque;
use std::time::{Duration, Instant};

use crossbeam_channel::Sender;

use crate::device::{Direction, LogEntry, hex};
use crate::link::Driver;
use crate::protocol::rflex::{Command, Conversion, DecoderEvent, FrameDecoder, Report, SkipReason};

/// A held velocity is sent again this often (the reference drivers' 10 Hz).
pub const RESEND_EVERY: Duration = Duration::from_millis(100);
/// Status and joystick are asked for this often once started.
pub const POLL_EVERY: Duration = Duration::from_millis(500);
/// Reports asked for this often (µs on the wire): 10 Hz.
pub const REPORT_PERIOD_US: u32 = 100_000;
/// While driving, a base that sends no report that decodes for this long is
/// treated as lost: the driver stops it.
pub const SILENCE_LIMIT: Duration = Duration::from_millis(1000);

/// What the owner asks of the driver.
#[derive(Debug)]
pub enum RflexCommand {
    /// The start-up sequence: odometry reports on (10 Hz, both axes), digital
    /// I/O reports on, motion defaults; the sonar on if asked; status polling.
    Start {
        /// Turn the sonar ring on too.
        sonar: bool,
    },
    /// Hold a velocity (re-sent at 10 Hz); zero speed and turn is a stop.
    Drive {
        /// m/s.
        speed_m_per_s: f64,
        /// rad/s.
        turn_rad_per_s: f64,
        /// m/s².
        accel_m_per_s2: f64,
    },
    /// Ask for the system status once (its answer's round trip is reported).
    AskStatus,
    /// Stop now: both axes at speed 0, once.
    Stop,
    /// Set (true) or release (false) the brake.
    Brake(bool),
    /// Sonar ring on or off.
    Sonar(bool),
    /// The shutdown sequence: stop, motion defaults, odometry off, digital I/O
    /// off, sonar off, IR off, brake on. `done` is told once it is written.
    Shutdown {
        /// Told when every byte of the sequence has been handed to the port.
        done: Option<Sender<()>>,
    },
}

/// What the driver reports to its owner.
#[derive(Clone, Debug, PartialEq)]
pub enum RflexEvent {
    /// A report whose checksum and layout are right.
    Report(Report),
    /// Bytes dropped (a frame that failed its checksum, noise, a cut frame): counted, never used.
    Skipped {
        /// How many.
        bytes: usize,
        /// Why.
        reason: SkipReason,
    },
    /// A packet-log entry.
    Log(LogEntry),
    /// The base said nothing for [`SILENCE_LIMIT`] while driving: the driver sent a stop.
    Silent,
    /// A status request was answered, this long after it was sent (a round trip on the link).
    StatusAnswered(Duration),
}

/// Status requests older than this are not waited for (their answer was lost).
const STATUS_FORGOTTEN: Duration = Duration::from_secs(2);

/// The driver.
#[derive(Debug)]
pub struct RflexDriver {
    conversion: Conversion,
    decoder: FrameDecoder,
    opened_at: Option<Instant>,
    output: VecDeque<Vec<u8>>,
    events: VecDeque<RflexEvent>,
    /// The held velocity: (speed, turn, accel) and when it is next sent.
    held: Option<((f64, f64, f64), Instant)>,
    accel_m_per_s2: f64,
    next_poll: Option<Instant>,
    last_heard: Option<Instant>,
    shutdown_done: Option<Sender<()>>,
    /// When each status request still unanswered was sent, oldest first
    /// (the base answers them in order: a status report each).
    status_asked: VecDeque<Instant>,
}

impl RflexDriver {
    /// A driver for a base with these conversion constants.
    pub fn new(conversion: Conversion) -> Self {
        Self {
            conversion,
            decoder: FrameDecoder::new(),
            opened_at: None,
            output: VecDeque::new(),
            events: VecDeque::new(),
            held: None,
            accel_m_per_s2: 0.5,
            next_poll: None,
            last_heard: None,
            shutdown_done: None,
            status_asked: VecDeque::new(),
        }
    }

    fn seconds(&mut self, now: Instant) -> f64 {
        now.saturating_duration_since(*self.opened_at.get_or_insert(now)).as_secs_f64()
    }

    fn send(&mut self, now: Instant, command: &Command) {
        if *command == Command::SystemStatus {
            self.status_asked.retain(|asked| now.saturating_duration_since(*asked) < STATUS_FORGOTTEN);
            self.status_asked.push_back(now);
        }
        let frame = command.to_frame();
        // Every command of rflex.md fits its LEN byte.
        let Ok(bytes) = frame.to_bytes() else { return };
        let seconds = self.seconds(now);
        self.events.push_back(RflexEvent::Log(LogEntry {
            seconds,
            direction: Direction::Sent,
            name: command.name().to_string(),
            fields: super::words::command(command, &self.conversion),
            hex: hex(&bytes),
        }));
        self.output.push_back(bytes);
    }

    fn send_drive(&mut self, now: Instant, (speed, turn, accel): (f64, f64, f64)) {
        for command in self.conversion.drive(speed, turn, accel) {
            self.send(now, &command);
        }
    }

    fn stop(&mut self, now: Instant) {
        self.held = None;
        let accel = self.accel_m_per_s2;
        for command in self.conversion.stop(accel) {
            self.send(now, &command);
        }
    }
}

impl Driver for RflexDriver {
    type Command = RflexCommand;
    type Event = RflexEvent;

    /// A stop, a brake set and the shutdown sequence go out even when the
    /// owner closes right after sending them: a base never keeps driving.
    fn is_last_word(&self, command: &RflexCommand) -> bool {
        matches!(command, RflexCommand::Stop | RflexCommand::Brake(true) | RflexCommand::Shutdown { .. })
    }

    fn handle_command(&mut self, now: Instant, command: RflexCommand) {
        match command {
            RflexCommand::Start { sonar } => {
                self.send(now, &Command::OdometryReports { period_us: REPORT_PERIOD_US, axis_mask: 3 });
                self.send(now, &Command::DioReports { period_us: REPORT_PERIOD_US });
                self.send(now, &Command::MotionDefaults);
                if sonar {
                    self.send(now, &sonar_run(true));
                }
                self.send(now, &Command::SystemStatus);
                self.next_poll = Some(now + POLL_EVERY);
                self.last_heard = Some(now);
            }
            RflexCommand::Drive { speed_m_per_s, turn_rad_per_s, accel_m_per_s2 } => {
                self.accel_m_per_s2 = accel_m_per_s2;
                if speed_m_per_s == 0.0 && turn_rad_per_s == 0.0 {
                    self.stop(now);
                } else {
                    let velocity = (speed_m_per_s, turn_rad_per_s, accel_m_per_s2);
                    // A change goes out at once; the same velocity keeps its 10 Hz rhythm.
                    let unchanged = self.held.is_some_and(|(held, _)| held == velocity);
                    if !unchanged {
                        self.send_drive(now, velocity);
                        self.held = Some((velocity, now + RESEND_EVERY));
                    }
                    self.last_heard.get_or_insert(now);
                }
            }
            RflexCommand::AskStatus => self.send(now, &Command::SystemStatus),
            RflexCommand::Stop => self.stop(now),
            RflexCommand::Brake(on) => {
                if on {
                    self.stop(now);
                    self.send(now, &Command::BrakeSet);
                    // Ask at once, so the owner can see the base confirm it.
                    self.send(now, &Command::SystemStatus);
                } else {
                    self.send(now, &Command::BrakeRelease);
                }
            }
            RflexCommand::Sonar(on) => self.send(now, &sonar_run(on)),
            RflexCommand::Shutdown { done } => {
                self.stop(now);
                self.send(now, &Command::MotionDefaults);
                self.send(now, &Command::OdometryReports { period_us: 0, axis_mask: 0 });
                self.send(now, &Command::DioReports { period_us: 0 });
                self.send(now, &sonar_run(false));
                self.send(now, &Command::IrRun { parameters: [0; 5], mode: 0 });
                self.send(now, &Command::BrakeSet);
                self.next_poll = None;
                self.shutdown_done = done;
            }
        }
    }

    fn handle_input(&mut self, now: Instant, bytes: &[u8]) {
        self.decoder.push(bytes);
        let seconds = self.seconds(now);
        while let Some(event) = self.decoder.poll() {
            match event {
                DecoderEvent::Frame { frame, stuffed } => {
                    let wire = if stuffed { frame.to_stuffed_bytes() } else { frame.to_bytes() };
                    let hex_text = wire.map(|bytes| hex(&bytes)).unwrap_or_default();
                    match Report::from_frame(&frame) {
                        Ok(report) => {
                            // Only a report that decodes counts as the base answering:
                            // noise or another protocol's bytes are no sign of life.
                            self.last_heard = Some(now);
                            if matches!(report, Report::Status { .. })
                                && let Some(asked) = self.status_asked.pop_front()
                            {
                                self.events.push_back(RflexEvent::StatusAnswered(now.saturating_duration_since(asked)));
                            }
                            self.events.push_back(RflexEvent::Log(LogEntry {
                                seconds,
                                direction: Direction::Received,
                                name: report.name().to_string(),
                                fields: super::words::report(&report, &self.conversion),
                                hex: hex_text,
                            }));
                            self.events.push_back(RflexEvent::Report(report));
                        }
                        Err(error) => self.events.push_back(RflexEvent::Log(LogEntry {
                            seconds,
                            direction: Direction::Received,
                            name: "malformed".into(),
                            fields: error.to_string(),
                            hex: hex_text,
                        })),
                    }
                }
                DecoderEvent::Skipped { bytes, reason } => {
                    self.events.push_back(RflexEvent::Log(LogEntry {
                        seconds,
                        direction: Direction::Skipped,
                        name: format!("skipped {bytes} byte(s)"),
                        fields: reason.to_string(),
                        hex: String::new(),
                    }));
                    self.events.push_back(RflexEvent::Skipped { bytes, reason });
                }
            }
        }
    }

    fn handle_timeout(&mut self, now: Instant) {
        if let Some((velocity, due)) = self.held
            && now >= due
        {
            if self.last_heard.is_some_and(|heard| now.saturating_duration_since(heard) >= SILENCE_LIMIT) {
                // Driving blind is never right: stop and say so.
                self.stop(now);
                self.events.push_back(RflexEvent::Silent);
            } else {
                self.send_drive(now, velocity);
                // Keep the 10 Hz rhythm; never fall behind by more than one period.
                self.held = Some((velocity, (due + RESEND_EVERY).max(now)));
            }
        }
        if let Some(due) = self.next_poll
            && now >= due
        {
            self.send(now, &Command::SystemStatus);
            self.send(now, &Command::JoystickState);
            self.next_poll = Some((due + POLL_EVERY).max(now));
        }
    }

    fn handle_disconnect(&mut self, _reason: &str) {
        self.held = None;
        self.next_poll = None;
        self.output.clear();
        // The owner waiting for the shutdown learns that it will not come.
        self.shutdown_done = None;
    }

    fn poll_transmit(&mut self, _now: Instant) -> Option<Vec<u8>> {
        let next = self.output.pop_front();
        if next.is_none()
            && let Some(done) = self.shutdown_done.take()
        {
            // Asked again with nothing queued: everything before has been written.
            let _ = done.send(());
        }
        next
    }

    fn poll_event(&mut self) -> Option<RflexEvent> {
        self.events.pop_front()
    }

    fn poll_timeout(&self) -> Option<Instant> {
        [self.held.map(|(_, due)| due), self.next_poll].into_iter().flatten().min()
    }
}

/// SONAR_RUN on (30000, 0, 0, mode 2) or off (all zero).
fn sonar_run(on: bool) -> Command {
    if on {
        Command::SonarRun { echo_delay: 30_000, ping_delay: 0, set_delay: 0, mode: 2 }
    } else {
        Command::SonarRun { echo_delay: 0, ping_delay: 0, set_delay: 0, mode: 0 }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::protocol::rflex::{B21R, FrameDecoder};

    fn sent(driver: &mut RflexDriver) -> Vec<Command> {
        let mut decoder = FrameDecoder::new();
        while let Some(bytes) = driver.poll_transmit(Instant::now()) {
            decoder.push(&bytes);
        }
        std::iter::from_fn(|| decoder.poll())
            .filter_map(|event| match event {
                DecoderEvent::Frame { frame, .. } => Command::from_frame(&frame).ok(),
                DecoderEvent::Skipped { .. } => None,
            })
            .collect()
    }

    #[test]
    fn start_and_shutdown_follow_the_reference_sequences() {
        let mut driver = RflexDriver::new(B21R);
        let t0 = Instant::now();
        driver.handle_command(t0, RflexCommand::Start { sonar: true });
        let start = sent(&mut driver);
        let names: Vec<&str> = start.iter().map(Command::name).collect();
        assert_eq!(names, ["MOT_SYSTEM_REPORT_REQ", "DIO_REPORTS_REQ", "MOT_SET_DEFAULTS", "SONAR_RUN", "SYS_STATUS"]);
        assert_eq!(start[0], Command::OdometryReports { period_us: 100_000, axis_mask: 3 });
        let (done, told) = crossbeam_channel::bounded(1);
        driver.handle_command(t0, RflexCommand::Shutdown { done: Some(done) });
        let names: Vec<&'static str> = sent(&mut driver).iter().map(Command::name).collect();
        assert_eq!(
            names,
            [
                "MOT_AXIS_SET_DIR",
                "MOT_AXIS_SET_DIR",
                "MOT_SET_DEFAULTS",
                "MOT_SYSTEM_REPORT_REQ",
                "DIO_REPORTS_REQ",
                "SONAR_RUN",
                "IR_RUN",
                "MOT_BRAKE_SET"
            ]
        );
        assert!(told.try_recv().is_ok(), "the owner is told once it is all written");
    }

    #[test]
    fn a_held_velocity_is_resent_at_10_hz_and_a_release_stops_at_once() {
        let mut driver = RflexDriver::new(B21R);
        let t0 = Instant::now();
        driver.handle_command(t0, RflexCommand::Start { sonar: false });
        sent(&mut driver);
        let drive = RflexCommand::Drive { speed_m_per_s: 0.5, turn_rad_per_s: 0.0, accel_m_per_s2: 0.5 };
        driver.handle_command(t0, drive);
        assert_eq!(sent(&mut driver).len(), 2, "translation then rotation");
        assert_eq!(driver.poll_timeout(), Some(t0 + RESEND_EVERY));
        // The same velocity again (a key still held) keeps the rhythm, it does not flood.
        driver.handle_command(
            t0 + Duration::from_millis(30),
            RflexCommand::Drive { speed_m_per_s: 0.5, turn_rad_per_s: 0.0, accel_m_per_s2: 0.5 },
        );
        assert!(sent(&mut driver).is_empty());
        driver.handle_input(t0 + Duration::from_millis(90), &[]);
        driver.handle_timeout(t0 + RESEND_EVERY);
        let resent = sent(&mut driver);
        assert_eq!(resent, B21R.drive(0.5, 0.0, 0.5).to_vec());
        // Released: the stop goes out at once, and nothing is re-sent after it.
        driver.handle_command(t0 + Duration::from_millis(150), RflexCommand::Stop);
        assert_eq!(sent(&mut driver), B21R.stop(0.5).to_vec());
        assert_eq!(driver.poll_timeout(), Some(t0 + POLL_EVERY), "only the status poll is left");
    }

    #[test]
    fn each_status_answered_is_paired_with_its_request_oldest_first() {
        let mut driver = RflexDriver::new(B21R);
        let t0 = Instant::now();
        driver.handle_command(t0, RflexCommand::AskStatus);
        driver.handle_command(t0 + Duration::from_millis(5), RflexCommand::AskStatus);
        sent(&mut driver);
        let status = Report::Status { timestamp: 1, voltage_raw: 2400, brake: 1 }.to_frame(1).to_bytes().unwrap();
        driver.handle_input(t0 + Duration::from_millis(40), &status);
        driver.handle_input(t0 + Duration::from_millis(50), &status);
        let answered: Vec<RflexEvent> =
            std::iter::from_fn(|| driver.poll_event()).filter(|e| matches!(e, RflexEvent::StatusAnswered(_))).collect();
        assert_eq!(
            answered,
            [
                RflexEvent::StatusAnswered(Duration::from_millis(40)),
                RflexEvent::StatusAnswered(Duration::from_millis(45))
            ]
        );
    }

    #[test]
    fn a_silent_base_is_stopped() {
        let mut driver = RflexDriver::new(B21R);
        let t0 = Instant::now();
        driver.handle_command(t0, RflexCommand::Start { sonar: false });
        driver.handle_command(t0, RflexCommand::Drive { speed_m_per_s: 0.3, turn_rad_per_s: 0.0, accel_m_per_s2: 0.5 });
        sent(&mut driver);
        let mut at = t0;
        while driver.held.is_some() {
            at = driver.poll_timeout().unwrap();
            driver.handle_timeout(at);
        }
        assert!(at >= t0 + SILENCE_LIMIT);
        assert!(std::iter::from_fn(|| driver.poll_event()).any(|event| event == RflexEvent::Silent));
        let last_two: Vec<Command> =
            sent(&mut driver).into_iter().filter(|c| matches!(c, Command::AxisSetDir { .. })).rev().take(2).collect();
        assert!(last_two.iter().all(|c| matches!(c, Command::AxisSetDir { speed: 0, .. })), "{last_two:?}");
    }
}
