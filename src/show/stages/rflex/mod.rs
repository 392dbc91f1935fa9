//! An rFLEX base on a show's stage: timed drives, driven while followed or
//! by a remote within its project's and its robot's limits, stopped and
//! braked at STOP. It reports ten times a second once started: that is how
//! it is known to be there.

mod lane;

use std::time::{Duration, Instant};

use super::{LinkDelay, Linked, ROUND_TRIPS};
use crate::audio::together::link_delay;
use crate::device::rflex::{RflexBase, RflexNotice};
use crate::link::{self, LineSettings, PortName, no_waker};
use crate::project::rflex::SpeedLimits;
use crate::show::alive::{Alive, Loss, SILENT_AFTER};
use crate::show::at::Now;
use crate::show::play::Stage;
use crate::show::{Device, Start};

/// How often a base being connected is looked at for its answers.
const LOOK_EVERY: Duration = Duration::from_millis(5);

inventory::submit! {
    crate::show::family::ShowFamily {
        family: crate::project::Family::Rflex,
        connect,
        // Its cues are drives, each given in full: it stores nothing to start.
        first_stored: |_| None,
        takes: |start| matches!(start, Start::Drive { .. }),
        // A slow drive of a second, to be set as the show needs.
        new_cue: Some(|_| Some(Start::Drive { speed_m_s: 0.2, turn_deg_s: 0.0, for_ms: 1000 })),
        holds: |_, start| {
            matches!(*start, Start::Drive { speed_m_s, turn_deg_s, .. } if speed_m_s.is_finite() && turn_deg_s.is_finite())
        },
        runs: None,
        poses: None,
        drives: true,
        cues: &[],
    }
}

/// Connects the base on `port`: started, then its link measured on status
/// requests, each waited for; a base that answers none within
/// [`SILENT_AFTER`] did not answer.
fn connect(port: &PortName, settings: &LineSettings, device: &Device) -> anyhow::Result<Linked> {
    let connection = link::open(port, settings)?;
    let mut base = RflexBase::over(connection, device.project.rflex.robot.conversion(), no_waker())?;
    // The start-up asks for its status once: the first round trip.
    base.start(false);
    let mut round_trips = Vec::with_capacity(ROUND_TRIPS);
    while round_trips.len() < ROUND_TRIPS {
        let asked = Instant::now();
        if !round_trips.is_empty() {
            base.ask_status();
        }
        let answered = answered_within(&mut base, asked + SILENT_AFTER)?;
        round_trips.push(answered);
    }
    let link = LinkDelay::from_round_trips(&round_trips);
    let limits = device.project.rflex.limits();
    let reports = base.telemetry.reports();
    let alive = Alive::new(Instant::now());
    let stage = RflexStage { base, link, alive, reports, limits, baud: settings.baud, lost: None, driving: None };
    let start_delay = stage.start_delay(&Start::Drive { speed_m_s: 0.0, turn_deg_s: 0.0, for_ms: 0 });
    Ok(Linked { stage: Box::new(stage), start_delay, link })
}

/// The round trip of the next status request answered, waiting until `deadline`.
fn answered_within(base: &mut RflexBase, deadline: Instant) -> anyhow::Result<Duration> {
    loop {
        let now = Instant::now();
        for notice in base.pump(now) {
            if let RflexNotice::Disconnected(reason) = notice {
                anyhow::bail!("{reason}");
            }
        }
        if let Some(round_trip) = base.round_trips().into_iter().next() {
            return Ok(round_trip);
        }
        if now >= deadline {
            anyhow::bail!(
                "nothing answered its status request within {:.1} s (is it an rFLEX base, powered, at 115200 baud?)",
                SILENT_AFTER.as_secs_f64()
            );
        }
        // Until the link has something for `pump` (left on its channel for it), or a moment passed.
        if let Some(events) = base.events() {
            let mut select = crossbeam_channel::Select::new();
            select.recv(events);
            let _ = select.ready_deadline(deadline.min(now + LOOK_EVERY));
        }
    }
}

struct RflexStage {
    base: RflexBase,
    link: LinkDelay,
    /// Its signs of life: the reports it sends ten times a second.
    alive: Alive,
    /// Reports taken in so far.
    reports: u64,
    /// Its project's drive limits, never past the robot's: every drive is held within them.
    limits: SpeedLimits,
    baud: u32,
    lost: Option<Loss>,
    /// The drive last told while following (None: not yet).
    driving: Option<Option<(f64, f64)>>,
}

impl RflexStage {
    /// Drives at (speed m/s, turn °/s) held within the limits, brake let go;
    /// or stops and brakes (None). What it drives at.
    fn set_driving(&mut self, driving: Option<(f64, f64)>) -> Option<(f64, f64)> {
        let held = driving.map(|(speed_m_s, turn_deg_s)| {
            let (speed, turn) = self.limits.hold(speed_m_s, turn_deg_s.to_radians());
            (speed, turn.to_degrees())
        });
        if self.driving == Some(held) {
            return held;
        }
        self.driving = Some(held);
        match held {
            Some((speed_m_s, turn_deg_s)) => {
                self.base.set_brake(false);
                self.base.drive(speed_m_s, turn_deg_s.to_radians(), self.limits.max_accel_m_per_s2);
            }
            None => {
                self.base.stop();
                self.base.set_brake(true);
            }
        }
        held
    }
}

impl Stage for RflexStage {
    fn start_delay(&self, _start: &Start) -> Duration {
        // A velocity command's frame: under 40 bytes.
        link_delay(40, self.baud, self.link.one_way)
    }

    fn start_uncertainty(&self, _start: &Start) -> Duration {
        self.link.spread
    }

    fn lasts(&self, start: &Start) -> Option<Duration> {
        let Start::Drive { for_ms, .. } = *start else { return None };
        Some(Duration::from_millis(for_ms))
    }

    fn start(&mut self, start: &Start) -> Result<(), String> {
        let Start::Drive { speed_m_s, turn_deg_s, .. } = *start else {
            return Err(format!("an rFLEX base cannot start {start}"));
        };
        self.set_driving(Some((speed_m_s, turn_deg_s)));
        Ok(())
    }

    fn stop(&mut self) {
        self.base.stop();
        self.base.set_brake(true);
        self.driving = Some(None);
    }

    fn drive(&mut self, drive: (f64, f64)) -> Result<(f64, f64), String> {
        Ok(self.set_driving(Some(drive)).unwrap_or_default())
    }

    fn follow(&mut self, now: &Now) -> Result<(), String> {
        let Now::Driving(driving) = *now else { return Ok(()) };
        self.set_driving(driving);
        Ok(())
    }

    fn tick(&mut self, now: Instant) {
        for notice in self.base.pump(now) {
            if let RflexNotice::Disconnected(reason) = notice {
                self.lost = Some(Loss::Link(reason.clone()));
            }
        }
        let reports = self.base.telemetry.reports();
        if reports > self.reports {
            self.reports = reports;
            self.alive.heard(now);
        }
        // Its driver asks for its status twice a second and it reports ten times a second:
        // expected to be heard from, as if asked.
        self.alive.ask(now);
        if let Some(quiet) = self.alive.silent(now) {
            self.lost.get_or_insert_with(|| Loss::silence(quiet));
        }
    }

    fn lost(&self) -> Option<Loss> {
        self.lost.clone().or_else(|| self.base.is_lost().then_some(Loss::Ended))
    }
}
