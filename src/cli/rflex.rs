//! `servo-studio rflex status | drive`, and the emulated base for `sim --protocol rflex`.

use std::io::IsTerminal;
use std::sync::Arc;
use std::time::{Duration, Instant};

use anyhow::{Context, bail};
use clap::{Args, Subcommand};
use crossbeam_channel::Receiver;

use super::PortArgs;
use super::bounds;
use super::out::say;
use super::signals::{self, Interrupt};
use super::sim::SimArgs;
use crate::device::{self, rflex::RflexBase};
use crate::link::{self, LineSettings, PortName, Waker};
use crate::project::Family;
use crate::project::rflex::Robot;
use crate::sim::{RflexSim, RflexSimConfig};

mod teleop;

/// `servo-studio rflex …`
#[derive(Debug, Subcommand)]
pub enum RflexCommand {
    /// Start the reports, wait for one full set (status, odometry on both axes,
    /// a full sonar sweep, digital I/O), print it as one JSON object, shut the reports down.
    Status {
        /// The base.
        #[command(flatten)]
        base: BaseArgs,
    },
    /// Release the brake, drive for a while at 10 Hz, stop, and shut down with the brake set.
    Drive {
        /// The base.
        #[command(flatten)]
        base: BaseArgs,
        /// Translational speed, m/s (negative: backwards).
        #[arg(long, allow_hyphen_values = true, value_parser = bounds::speed)]
        speed: f64,
        /// Rotational speed, rad/s (positive: left).
        #[arg(long, default_value_t = 0.0, allow_hyphen_values = true, value_parser = bounds::turn)]
        turn: f64,
        /// Translational acceleration, m/s².
        #[arg(long, default_value_t = 0.5, allow_hyphen_values = true, value_parser = bounds::accel)]
        accel: f64,
        /// How long to drive, seconds.
        #[arg(long, allow_hyphen_values = true, value_parser = bounds::drive_seconds)]
        seconds: f64,
    },
    /// Drive a base from a gamepad: hold the dead-man button (the left
    /// shoulder, BTN_TL) and the left stick drives (up forward, left turns
    /// left), scaled to the robot's top speeds, with a dead zone. The base is
    /// stopped at once when the dead-man is released, the stick centred, the
    /// gamepad's events dropped (until known again) or the gamepad gone — then
    /// the brake is set and the command exits 1 — and on Ctrl-C or kill.
    Teleop {
        /// The base.
        #[command(flatten)]
        base: BaseArgs,
        /// The gamepad: an event device (/dev/input/eventN), or a file or named
        /// pipe of Linux `struct input_event` records.
        #[arg(long)]
        gamepad: std::path::PathBuf,
        /// Full stick forward, m/s (default: the robot's top speed).
        #[arg(long, allow_hyphen_values = true, value_parser = bounds::top_speed)]
        speed: Option<f64>,
        /// Full stick to the side, rad/s (default: the robot's top turn rate).
        #[arg(long, allow_hyphen_values = true, value_parser = bounds::top_speed)]
        turn: Option<f64>,
        /// Acceleration, m/s².
        #[arg(long, default_value_t = 0.5, allow_hyphen_values = true, value_parser = bounds::accel)]
        accel: f64,
        /// The raw values the gamepad path's axes span (an event device says its own).
        #[arg(long, allow_hyphen_values = true, value_parser = bounds::axis_range)]
        axis_range: Option<(i32, i32)>,
        /// The part of the stick around its centre that counts as centred, 0 to 0.9.
        #[arg(long, default_value_t = 0.15, allow_hyphen_values = true, value_parser = bounds::dead_zone)]
        dead_zone: f64,
        /// The dead-man button, by its kernel name (BTN_TL, BTN_TR, BTN_SOUTH, …).
        #[arg(long, default_value = "BTN_TL", value_parser = bounds::button)]
        deadman: u16,
    },
}

/// Where the base is and which robot it is.
#[derive(Debug, Args)]
pub struct BaseArgs {
    /// The port.
    #[command(flatten)]
    pub port: PortArgs,
    /// The robot: b21r, atrv-jr or magellan (its conversion constants).
    #[arg(long, value_parser = super::parse_robot, default_value = "b21r")]
    pub robot: Robot,
}

/// Runs `servo-studio rflex …`.
pub fn run(command: &RflexCommand) -> anyhow::Result<()> {
    let (RflexCommand::Status { base } | RflexCommand::Drive { base, .. } | RflexCommand::Teleop { base, .. }) =
        command;
    if let Some(family) = base.port.protocol
        && family != Family::Rflex
    {
        bail!("`servo-studio rflex` talks to rFLEX bases; --protocol {family} does not apply. Nothing was sent");
    }
    base.port.applies_to(Family::Rflex)?;
    match command {
        RflexCommand::Status { base } => status(base),
        RflexCommand::Drive { base, speed, turn, accel, seconds } => drive(base, *speed, *turn, *accel, *seconds),
        RflexCommand::Teleop { base, gamepad, speed, turn, accel, axis_range, dead_zone, deadman } => {
            let pad = teleop::Pad { path: gamepad, axis_range: *axis_range, dead_zone: *dead_zone, deadman: *deadman };
            teleop::run(base, &pad, (*speed, *turn, *accel))
        }
    }
}

/// A waker that lets the command line sleep until the base says something.
fn waker() -> (Waker, Receiver<()>) {
    let (sender, woken) = crossbeam_channel::bounded(1);
    (
        Arc::new(move || {
            let _ = sender.try_send(());
        }),
        woken,
    )
}

fn connect(args: &BaseArgs, waker: Waker) -> anyhow::Result<RflexBase> {
    let name = PortName::parse(&args.port.port)?;
    let settings = LineSettings { baud: args.port.baud(Family::Rflex), ..device::line_settings(Family::Rflex) };
    let connection = link::open(&name, &settings)?;
    RflexBase::over(connection, args.robot.conversion(), waker)
        .with_context(|| format!("cannot start talking to {name}"))
}

fn lost(reason: &link::DisconnectReason) -> anyhow::Error {
    anyhow::anyhow!(
        "the link to the base was lost ({reason}); the base stops by itself once its dead-man timeout runs out. Check the cable and the base's power"
    )
}

/// Why waiting on the base ended early.
enum Break {
    /// The link ended.
    Lost(link::DisconnectReason),
    /// The base sent nothing that decodes for a second while driving; the driver sent a stop.
    Silent,
    /// A signal asked the command to end.
    Interrupted(Interrupt),
}

/// The base, and what wakes the command line: the base's events and signals.
struct Session {
    base: RflexBase,
    woken: Receiver<()>,
    interrupts: Receiver<Interrupt>,
    port: String,
    timeout: Duration,
}

impl Session {
    fn open(args: &BaseArgs) -> anyhow::Result<Self> {
        // Listen before connecting: from here on a signal never leaves the base driving.
        let interrupts = signals::listen().context("cannot listen for Ctrl-C")?;
        let (waker, woken) = waker();
        let base = connect(args, waker)?;
        let timeout = Duration::from_millis(args.port.timeout_ms(Family::Rflex));
        Ok(Self { base, woken, interrupts, port: args.port.port.clone(), timeout })
    }

    /// Pumps the base until `done`, the deadline, or a reason to stop.
    fn wait(
        &mut self,
        deadline: Instant,
        mut each: impl FnMut(&RflexBase),
        done: impl Fn(&RflexBase) -> bool,
    ) -> Result<bool, Break> {
        loop {
            for notice in self.base.pump(Instant::now()) {
                match notice {
                    device::rflex::RflexNotice::Disconnected(reason) => return Err(Break::Lost(reason)),
                    device::rflex::RflexNotice::Silent => return Err(Break::Silent),
                    device::rflex::RflexNotice::Log(_) => {}
                }
            }
            if let Ok(interrupt) = self.interrupts.try_recv() {
                return Err(Break::Interrupted(interrupt));
            }
            each(&self.base);
            if done(&self.base) {
                return Ok(true);
            }
            if Instant::now() >= deadline {
                return Ok(false);
            }
            // Woken by the base, a signal, or the deadline.
            crossbeam_channel::select! {
                recv(self.woken) -> _ => {}
                recv(self.interrupts) -> interrupt => {
                    if let Ok(interrupt) = interrupt {
                        return Err(Break::Interrupted(interrupt));
                    }
                }
                default(deadline.saturating_duration_since(Instant::now())) => {}
            }
        }
    }

    /// Starts the reports and waits for the base to answer: a status and an
    /// odometry report, within the timeout. Nothing moves before that.
    fn start(&mut self, sonar: bool) -> anyhow::Result<()> {
        self.base.start(sonar);
        let deadline = Instant::now() + self.timeout;
        match self.wait(deadline, |_| {}, |base| base.telemetry.answered()) {
            Ok(true) => Ok(()),
            Ok(false) => {
                let telemetry = self.base.telemetry.clone();
                self.base.shutdown(device::rflex::SHUTDOWN_WAIT);
                if telemetry.skipped_bytes > 0 && telemetry.reports() == 0 {
                    bail!(
                        "{}: the device answers, but not in the rFLEX protocol ({} and no report): is it an rFLEX base? (try --protocol servo or --protocol plen2); nothing was driven",
                        self.port,
                        device::bytes(usize::try_from(telemetry.skipped_bytes).unwrap_or(usize::MAX))
                    );
                }
                bail!(
                    "{}: the base did not answer the start-up within {} ms (a status and an odometry report); nothing was driven. Is it an rFLEX base, switched on, at the right baud rate? A slow link needs a longer --timeout-ms",
                    self.port,
                    self.timeout.as_millis()
                )
            }
            Err(stop) => Err(self.stopped_by(stop, "before driving: nothing moved")),
        }
    }

    /// Stops the base and sets its brake, then waits for its reports to
    /// confirm both (a status saying braked, odometry saying still); shuts
    /// the reports down either way. Returns whether the base confirmed.
    fn stop_and_brake(&mut self) -> bool {
        self.base.set_brake(true);
        let (status_before, odometry_before) =
            (self.base.telemetry.status_reports, self.base.telemetry.odometry_reports.0);
        let deadline = Instant::now() + self.timeout.max(Duration::from_millis(500));
        let confirmed = |base: &RflexBase| {
            let t = &base.telemetry;
            t.status_reports > status_before
                && t.brake == Some(true)
                && t.odometry_reports.0 > odometry_before
                && t.speed_m_per_s.abs() < 0.005
                && t.turn_rad_per_s.abs() < 0.005
        };
        // A second signal while stopping changes nothing: the stop is already on its way.
        let mut result = self.wait(deadline, |_| {}, confirmed);
        while let Err(Break::Interrupted(_)) = result {
            result = self.wait(deadline, |_| {}, confirmed);
        }
        let confirmed = matches!(result, Ok(true));
        self.base.shutdown(device::rflex::SHUTDOWN_WAIT);
        confirmed
    }

    /// The error for a wait that ended early: after a stop, the brake and the
    /// shutdown where the link still allows them.
    fn stopped_by(&mut self, stop: Break, context: &str) -> anyhow::Error {
        match stop {
            Break::Lost(reason) => lost(&reason),
            Break::Silent => {
                let confirmed = self.stop_and_brake();
                anyhow::anyhow!(
                    "{}: the base stopped answering (no report for {} ms) {context}; a stop was sent and the brake set{}",
                    self.port,
                    device::rflex::SILENCE_LIMIT.as_millis(),
                    if confirmed { "" } else { ", but the base did not confirm it: check it" }
                )
            }
            Break::Interrupted(interrupt) => {
                let confirmed = self.stop_and_brake();
                let state = if confirmed {
                    "the base stopped and its brake is set"
                } else {
                    "a stop and the brake were sent, but the base did not confirm them: check it"
                };
                anyhow::Error::new(super::Exit(interrupt.exit_code))
                    .context(format!("interrupted by {interrupt} {context}: {state}"))
            }
        }
    }
}

fn status(args: &BaseArgs) -> anyhow::Result<()> {
    let mut session = Session::open(args)?;
    session.start(true)?;
    let wait = session.timeout.max(Duration::from_millis(3000));
    let complete = match session.wait(Instant::now() + wait, |_| {}, |base| base.telemetry.complete()) {
        Ok(complete) => complete,
        Err(stop) => return Err(session.stopped_by(stop, "while reading the base")),
    };
    session.base.shutdown(device::rflex::SHUTDOWN_WAIT);
    if !complete {
        bail!(
            "{}: no full set of reports within {} ms (status, odometry, sonar sweep, digital I/O). Is it an rFLEX base, switched on, at the right baud rate?",
            args.port.port,
            wait.as_millis()
        );
    }
    let telemetry = &session.base.telemetry;
    let layout = session.base.conversion().layout;
    // Each sonar by transducer (rflex.md §6): its ring, bearing, mount, range and raw id.
    let sonar: Vec<serde_json::Value> = layout
        .transducers()
        .iter()
        .map(|t| {
            serde_json::json!({
                "transducer": t.number,
                "id": t.id,
                "ring": t.ring.name(),
                "bearing_deg": (t.bearing_rad.to_degrees() * 1000.0).round() / 1000.0,
                "mount_m": [t.mount_m.0, t.mount_m.1],
                "range_m": telemetry.sonar_m.get(&t.id).copied().flatten(),
            })
        })
        .collect();
    let unknown: Vec<serde_json::Value> =
        telemetry.unknown_sonar.iter().map(|(id, raw)| serde_json::json!({"id": id, "raw": raw})).collect();
    let bumpers: Vec<serde_json::Value> = telemetry
        .pressed()
        .iter()
        .map(|bump| match bump {
            device::rflex::Bump::Panel { panel, corners } => serde_json::json!({"panel": panel, "corners": corners}),
            device::rflex::Bump::Bit { bumper } => serde_json::json!({"bumper": bumper}),
        })
        .collect();
    let report = serde_json::json!({
        "robot": args.robot.name(),
        "battery_volts": telemetry.battery_volts,
        "brake": telemetry.brake,
        "x_m": telemetry.pose.x_m,
        "y_m": telemetry.pose.y_m,
        "theta_rad": telemetry.pose.theta_rad,
        "sonar": sonar,
        "unknown_sonar": unknown,
        "bumpers_pressed": bumpers,
        "checksum_failures": telemetry.checksum_failures,
    });
    super::out::line(&report.to_string())?;
    Ok(())
}

/// Refuses what the robot must never be asked for; nothing is sent then.
fn check_drive(robot: Robot, speed: f64, turn: f64, accel: f64, seconds: f64) -> anyhow::Result<()> {
    if !(seconds.is_finite()
        && seconds >= 0.0
        && speed.is_finite()
        && turn.is_finite()
        && accel.is_finite()
        && accel > 0.0)
    {
        bail!("--seconds must be 0 or more, --speed and --turn numbers, --accel above 0; nothing was sent");
    }
    let limits = robot.limits();
    let name = robot.name();
    if speed.abs() > limits.max_speed_m_per_s {
        bail!(
            "--speed {speed} m/s is faster than the {name}'s limit of {} m/s; nothing was sent",
            limits.max_speed_m_per_s
        );
    }
    if turn.abs() > limits.max_turn_rad_per_s {
        bail!(
            "--turn {turn} rad/s is faster than the {name}'s limit of {} rad/s; nothing was sent",
            limits.max_turn_rad_per_s
        );
    }
    if accel > limits.max_accel_m_per_s2 {
        bail!(
            "--accel {accel} m/s² is more than the {name}'s limit of {} m/s²; nothing was sent",
            limits.max_accel_m_per_s2
        );
    }
    Ok(())
}

fn drive(args: &BaseArgs, speed: f64, turn: f64, accel: f64, seconds: f64) -> anyhow::Result<()> {
    check_drive(args.robot, speed, turn, accel, seconds)?;
    let mut session = Session::open(args)?;
    session.start(false)?;
    session.base.set_brake(false);
    session.base.drive(speed, turn, accel);
    let began = Instant::now();
    let terminal = std::io::stderr().is_terminal();
    let mut next_line = began;
    let mut line = |base: &RflexBase| {
        let now = Instant::now();
        if now < next_line {
            return;
        }
        next_line = now + Duration::from_millis(500);
        let t = &base.telemetry;
        let distance = t.pose.x_m.hypot(t.pose.y_m);
        let battery = t.battery_volts.map_or("—".to_string(), |v| format!("{v:.2} V"));
        let text = format!(
            "driving {:.1}/{seconds:.1} s: {distance:.2} m from the start, {:.2} m/s, battery {battery}",
            now.saturating_duration_since(began).as_secs_f64(),
            t.speed_m_per_s
        );
        if terminal {
            super::out::say_partial(format_args!("\r{text}   "));
        } else {
            say!("{text}");
        }
    };
    let deadline = began + bounds::duration(seconds);
    let driven = session.wait(deadline, &mut line, |_| false);
    if terminal {
        say!("");
    }
    if let Err(stop) = driven {
        return Err(session.stopped_by(stop, "while driving"));
    }
    let confirmed = session.stop_and_brake();
    let t = session.base.telemetry.clone();
    let summary = format!(
        "drove {seconds:.2} s: {:.2} m from the start, heading {:.2} rad",
        t.pose.x_m.hypot(t.pose.y_m),
        t.pose.theta_rad
    );
    if !confirmed {
        let brake = match t.brake {
            Some(true) => "set",
            Some(false) => "released",
            None => "unknown",
        };
        bail!(
            "{summary}; a stop and the brake were sent, but the base did not confirm them within {} ms (its last report: {:.2} m/s, brake {brake}). Check the base",
            session.timeout.max(Duration::from_millis(500)).as_millis(),
            t.speed_m_per_s
        );
    }
    say!("{summary}; stopped, brake set");
    Ok(())
}

/// Runs the emulated base, in its room.
fn emulate(args: &SimArgs) -> anyhow::Result<()> {
    super::sim::serve(args, RflexSim::new(rflex_config(args)?))
}

/// The emulated base's config: its robot, its room and where it stands in it
/// (refused when the robot would not fit there).
fn rflex_config(args: &SimArgs) -> anyhow::Result<RflexSimConfig> {
    let defaults = RflexSimConfig::default();
    let conversion = args.robot.unwrap_or_default().conversion();
    let room_m = args.room.unwrap_or(defaults.room_m);
    let (x, y, theta_deg) = args.start.unwrap_or((0.0, 0.0, 0.0));
    let radius = conversion.layout.body_radius_m;
    if x.abs() > room_m.0 / 2.0 - radius || y.abs() > room_m.1 / 2.0 - radius {
        bail!(
            "--start {x},{y}: the base (a radius of {radius} m) does not fit there in a {} × {} m room; nothing was started",
            room_m.0,
            room_m.1
        );
    }
    Ok(RflexSimConfig {
        conversion,
        stuffed: args.stuffed,
        noise: args.noise.clone().unwrap_or_default(),
        room_m,
        start: (x, y, theta_deg.to_radians()),
        body_panels_only: args.body_panels_only,
        ..defaults
    })
}

inventory::submit! {
    super::family::Registered {
        family: Family::Rflex,
        timeout_ms: 1000,
        paced: false,
        board: Err(
            "rFLEX bases (they store no project); use `servo-studio rflex status` to read one and `servo-studio rflex drive` to drive it",
        ),
    }
}

inventory::submit! {
    super::sim::Emulator {
        family: Family::Rflex,
        takes: &["--robot", "--room", "--start", "--stuffed", "--noise", "--body-panels-only"],
        note: " (a base stores nothing to preload)",
        serve: emulate,
    }
}
