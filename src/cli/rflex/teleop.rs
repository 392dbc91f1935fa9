//! `servo-studio rflex teleop`: a base driven from a gamepad, stopped at once
//! whenever anything goes wrong (see `gamepad::teleop`), braked when it ends.

use std::path::Path;
use std::time::{Duration, Instant};

use anyhow::bail;

use super::{BaseArgs, Break, Session, check_drive};
use crate::cli::out::say;
use crate::device;
use crate::gamepad::teleop::{Order, StopReason, Teleop, TeleopConfig};
use crate::gamepad::{EV_KEY, Gamepad, PadUpdate, code_name};
use crate::link::no_waker;

/// The gamepad and how its stick is read.
pub struct Pad<'a> {
    /// Its event device, file or named pipe.
    pub path: &'a Path,
    /// The raw values a path's axes span.
    pub axis_range: Option<(i32, i32)>,
    /// The part of the stick that counts as centred.
    pub dead_zone: f64,
    /// The button that must be held to drive.
    pub deadman: u16,
}

/// How often the progress line is said while driving.
const SAY_EVERY: Duration = Duration::from_millis(500);

/// Drives until the gamepad is gone (exit 1, brake set) or a signal (its status, brake set).
pub fn run(
    args: &BaseArgs,
    pad: &Pad<'_>,
    (speed, turn, accel): (Option<f64>, Option<f64>, f64),
) -> anyhow::Result<()> {
    let limits = args.robot.limits();
    let (speed, turn) = (speed.unwrap_or(limits.max_speed_m_per_s), turn.unwrap_or(limits.max_turn_rad_per_s));
    check_drive(args.robot, speed, turn, accel, 0.0)?;
    let config = TeleopConfig {
        deadman: pad.deadman,
        dead_zone: pad.dead_zone,
        max_speed_m_per_s: speed,
        max_turn_rad_per_s: turn,
        ..TeleopConfig::default()
    };
    let mut session = Session::open(args)?;
    let gamepad = Gamepad::open(pad.path, pad.axis_range, no_waker())?;
    session.start(false)?;
    session.base.set_brake(false);
    say!(
        "hold {} and move the left stick to drive (up to {speed} m/s, {turn} rad/s); release it to stop",
        code_name(EV_KEY, config.deadman)
    );
    let mut teleop = Teleop::new(config);
    let mut said = Instant::now();
    loop {
        for notice in session.base.pump(Instant::now()) {
            match notice {
                device::rflex::RflexNotice::Disconnected(reason) => {
                    return Err(session.stopped_by(Break::Lost(reason), "while driving"));
                }
                device::rflex::RflexNotice::Silent => return Err(session.stopped_by(Break::Silent, "while driving")),
                device::rflex::RflexNotice::Log(_) => {}
            }
        }
        let due = teleop.poll_timeout().unwrap_or_else(|| Instant::now() + Duration::from_millis(200));
        let order = crossbeam_channel::select! {
            recv(gamepad.updates()) -> update => match update {
                Ok((at, update)) => {
                    let order = teleop.update(at, &update);
                    if let PadUpdate::Gone(gone) = update {
                        apply(&mut session, order, accel);
                        let confirmed = session.stop_and_brake();
                        bail!(
                            "{}: {gone}; the base was stopped{}",
                            pad.path.display(),
                            if confirmed { " and its brake set" } else { " and its brake sent, but it did not confirm them: check it" }
                        );
                    }
                    order
                }
                // The reading thread ended without a word: as good as gone.
                Err(_) => teleop.update(Instant::now(), &PadUpdate::Gone(crate::gamepad::Gone::Ended)),
            },
            recv(session.woken) -> _ => teleop.poll(Instant::now()),
            recv(session.interrupts) -> interrupt => {
                apply(&mut session, teleop.halt(), accel);
                if let Ok(interrupt) = interrupt {
                    return Err(session.stopped_by(Break::Interrupted(interrupt), "while driving"));
                }
                None
            },
            default(due.saturating_duration_since(Instant::now())) => teleop.poll(Instant::now()),
        };
        if let Some(order) = order {
            let now = Instant::now();
            match order {
                Order::Stop(reason) => say!("stopped: {}", why(reason)),
                Order::Drive { speed_m_per_s, turn_rad_per_s } if now >= said + SAY_EVERY => {
                    said = now;
                    say!("driving {speed_m_per_s:+.2} m/s, {turn_rad_per_s:+.2} rad/s");
                }
                Order::Drive { .. } => {}
            }
            apply(&mut session, Some(order), accel);
        }
    }
}

fn apply(session: &mut Session, order: Option<Order>, accel: f64) {
    match order {
        Some(Order::Drive { speed_m_per_s, turn_rad_per_s }) => {
            session.base.drive(speed_m_per_s, turn_rad_per_s, accel);
        }
        Some(Order::Stop(_)) => session.base.stop(),
        None => {}
    }
}

fn why(reason: StopReason) -> &'static str {
    match reason {
        StopReason::Released => "the dead-man button was released",
        StopReason::Centred => "the stick is centred",
        StopReason::Dropped => "the gamepad's events were dropped: press the dead-man again once it is back",
        StopReason::Gone => "the gamepad is gone",
        StopReason::Halted => "stopped",
    }
}
