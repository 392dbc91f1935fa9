//! `servo-studio rflex status | drive`, and the emulated base for `sim --protocol rflex`.

use std::io::{IsTerminal, Write};
use std::sync::Arc;
use std::time::{Duration, Instant};

use anyhow::{Context, bail};
use clap::{Args, Subcommand};
use crossbeam_channel::Receiver;

use super::PortArgs;
use super::servo::SimArgs;
use servo_studio::device::{self, rflex::RflexBase};
use servo_studio::link::{self, LineSettings, PortName, Waker};
use servo_studio::project::Family;
use servo_studio::project::rflex::Robot;
use servo_studio::sim::{RflexSim, RflexSimConfig};

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
        #[arg(long, allow_hyphen_values = true)]
        speed: f64,
        /// Rotational speed, rad/s (positive: left).
        #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
        turn: f64,
        /// Translational acceleration, m/s².
        #[arg(long, default_value_t = 0.5)]
        accel: f64,
        /// How long to drive, seconds.
        #[arg(long)]
        seconds: f64,
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
    match command {
        RflexCommand::Status { base } => status(base),
        RflexCommand::Drive { base, speed, turn, accel, seconds } => drive(base, *speed, *turn, *accel, *seconds),
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

/// Pumps the base until `done` or the deadline; fails at once if the link is lost.
fn pump_until(
    base: &mut RflexBase,
    woken: &Receiver<()>,
    deadline: Instant,
    mut each: impl FnMut(&RflexBase),
    done: impl Fn(&RflexBase) -> bool,
) -> anyhow::Result<bool> {
    loop {
        for notice in base.pump(Instant::now()) {
            if let device::rflex::RflexNotice::Disconnected(reason) = notice {
                return Err(lost(&reason));
            }
        }
        each(base);
        if done(base) {
            return Ok(true);
        }
        if Instant::now() >= deadline {
            return Ok(false);
        }
        // Woken by the base, or by the deadline.
        let _ = woken.recv_deadline(deadline);
    }
}

fn status(args: &BaseArgs) -> anyhow::Result<()> {
    let (waker, woken) = waker();
    let mut base = connect(args, waker)?;
    base.start(true);
    let wait = Duration::from_millis(args.port.timeout_ms.max(3000));
    let complete = pump_until(&mut base, &woken, Instant::now() + wait, |_| {}, |base| base.telemetry.complete())?;
    if !complete {
        bail!(
            "{}: no full set of reports within {} ms (status, odometry, sonar sweep, digital I/O). Is it an rFLEX base, switched on, at the right baud rate?",
            args.port.port,
            wait.as_millis()
        );
    }
    let telemetry = &base.telemetry;
    let sonar: serde_json::Map<String, serde_json::Value> =
        telemetry.sonar_m.iter().map(|(id, range)| (id.to_string(), serde_json::json!(range))).collect();
    let bumpers: serde_json::Map<String, serde_json::Value> =
        telemetry.bumpers.iter().map(|(panel, corners)| (panel.to_string(), serde_json::json!(corners))).collect();
    let report = serde_json::json!({
        "battery_volts": telemetry.battery_volts,
        "brake": telemetry.brake,
        "x_m": telemetry.pose.x_m,
        "y_m": telemetry.pose.y_m,
        "theta_rad": telemetry.pose.theta_rad,
        "sonar_m": sonar,
        "bumpers": bumpers,
        "checksum_failures": telemetry.checksum_failures,
    });
    println!("{report}");
    base.shutdown(device::rflex::SHUTDOWN_WAIT);
    Ok(())
}

fn drive(args: &BaseArgs, speed: f64, turn: f64, accel: f64, seconds: f64) -> anyhow::Result<()> {
    if !(seconds.is_finite() && seconds >= 0.0 && speed.is_finite() && turn.is_finite() && accel > 0.0) {
        bail!("--seconds must be 0 or more, --speed and --turn numbers, --accel above 0");
    }
    let (waker, woken) = waker();
    let mut base = connect(args, waker)?;
    base.start(false);
    base.set_brake(false);
    base.drive(speed, turn, accel);
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
            eprint!("\r{text}   ");
        } else {
            eprintln!("{text}");
        }
    };
    let deadline = began + Duration::from_secs_f64(seconds);
    // A lost link returns here at once, with the handle dropped (it cannot send a stop).
    pump_until(&mut base, &woken, deadline, &mut line, |_| false)?;
    base.stop();
    // Let the stop take effect while reports still come, then shut down (brake on).
    pump_until(&mut base, &woken, Instant::now() + Duration::from_millis(150), &mut line, |_| false)?;
    let t = base.telemetry.clone();
    base.shutdown(device::rflex::SHUTDOWN_WAIT);
    if terminal {
        eprintln!();
    }
    eprintln!(
        "drove {:.2} s: {:.2} m from the start, heading {:.2} rad; stopped, brake set",
        seconds,
        t.pose.x_m.hypot(t.pose.y_m),
        t.pose.theta_rad
    );
    std::io::stderr().flush()?;
    Ok(())
}

/// `servo-studio sim --protocol rflex`.
pub fn sim(args: &SimArgs) -> anyhow::Result<()> {
    let config = RflexSimConfig {
        conversion: args.robot.conversion(),
        stuffed: args.stuffed,
        noise: args.noise.clone(),
        ..RflexSimConfig::default()
    };
    super::servo::serve(args, RflexSim::new(config))
}
