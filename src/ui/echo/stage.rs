//! The echo board on a show's stage: its own kind of cue (`"move": DEG`,
//! the servo to an angle), its servo posed by a remote and followed by a
//! preview, stopped at STOP; asked twice a second (a move to where it is,
//! which it echoes), lost once it stops answering. Registered here, in the
//! family's own folder, like the real families' stages.

use std::collections::BTreeMap;
use std::time::{Duration, Instant};

use super::EchoSection;
use super::link::EchoHandle;
use crate::device::speed::LiveSpeed;
use crate::link::{self, LineSettings, LinkEvent, PortName, no_waker};
use crate::project::{Family, Project};
use crate::show::alive::{Alive, Loss, SILENT_AFTER};
use crate::show::at::{Now, Posed};
use crate::show::family::{Poses, ShowFamily};
use crate::show::passes::Axis;
use crate::show::play::Stage;
use crate::show::stages::{LinkDelay, Linked, ROUND_TRIPS};
use crate::show::timeline::{FamilyTimeline, Lane, latest};
use crate::show::{Device, Start};

/// Its kind of cue in a show file.
const MOVE: &str = "move";

inventory::submit! {
    ShowFamily {
        family: Family::Echo,
        connect,
        first_stored: |_| None,
        takes: |start| matches!(start, Start::Family(cue) if cue.kind == MOVE),
        new_cue: Some(|project| crate::show::family::FamilyCue::named(MOVE, f64::from(EchoSection::of(project).home_deg)).ok().map(Start::Family)),
        holds: |_, start| matches!(start, Start::Family(cue) if cue.kind == MOVE),
        runs: None,
        poses: Some(Poses { axes: |_| vec![("servo".to_string(), Axis::Servo(0))], alias: |_, _| None }),
        drives: false,
        cues: &[MOVE],
    }
}
inventory::submit! {
    FamilyTimeline { family: Family::Echo, lane: || Box::new(EchoLane) }
}

/// The echo board on the show's timeline: it works nothing out to keep.
#[derive(Debug)]
struct EchoLane;

impl Lane for EchoLane {
    fn length_ms(&mut self, _project: &Project, _start: &Start) -> u64 {
        // A move is at once: it keeps the board busy for no time.
        0
    }

    /// Where the servo is: at home before the first cue, then where the latest moved it.
    fn posed_at(&mut self, device: &Device, cues: &[(u64, Start)], t_ms: u64) -> Posed {
        let deg = match latest(cues, t_ms) {
            Some((_, Start::Family(cue))) => cue.value,
            _ => f64::from(EchoSection::of(&device.project).home_deg),
        };
        Posed::Servos(BTreeMap::from([(0, deg)]))
    }
}

/// An angle the echo board takes: whole degrees within ±180.
fn whole_deg(deg: f64) -> i16 {
    // Finite and clamped: fits.
    #[allow(clippy::cast_possible_truncation)]
    let whole = if deg.is_finite() { deg.clamp(-180.0, 180.0).round() as i16 } else { 0 };
    whole
}

/// Connects the echo board on `port`, its link measured on moves to home, each echoed.
fn connect(port: &PortName, line: &LineSettings, device: &Device) -> anyhow::Result<Linked> {
    let handle = EchoHandle::over(link::open(port, line)?, no_waker())?;
    let home = EchoSection::of(&device.project).home_deg;
    let mut round_trips = Vec::with_capacity(ROUND_TRIPS);
    for _ in 0..ROUND_TRIPS {
        let asked = Instant::now();
        handle.move_to(home);
        match handle.events().recv_timeout(SILENT_AFTER) {
            Ok(LinkEvent::Driver(_)) => round_trips.push(asked.elapsed()),
            Ok(LinkEvent::Disconnected { reason }) => anyhow::bail!("the echo board's link ended: {reason:?}"),
            Err(_) => anyhow::bail!("the echo board echoed nothing within {} s", SILENT_AFTER.as_secs()),
        }
    }
    let link = LinkDelay::from_round_trips(&round_trips);
    let stage = EchoStage { handle, link, at: home, alive: Alive::new(Instant::now()), lost: None };
    Ok(Linked { stage: Box::new(stage), start_delay: link.one_way, link })
}

struct EchoStage {
    handle: EchoHandle,
    link: LinkDelay,
    /// Where its servo was last sent.
    at: i16,
    alive: Alive,
    lost: Option<Loss>,
}

impl EchoStage {
    fn move_to(&mut self, deg: f64) -> i16 {
        self.at = whole_deg(deg);
        self.handle.move_to(self.at);
        self.at
    }
}

impl Stage for EchoStage {
    fn start_delay(&self, _start: &Start) -> Duration {
        self.link.one_way
    }

    fn start_uncertainty(&self, _start: &Start) -> Duration {
        self.link.spread
    }

    fn start(&mut self, start: &Start) -> Result<(), String> {
        let Start::Family(cue) = start else { return Err(format!("an Echo board cannot start {start}")) };
        self.move_to(cue.value);
        Ok(())
    }

    fn stop(&mut self) {
        self.handle.halt();
    }

    fn tick(&mut self, now: Instant) {
        for event in self.handle.events().try_iter() {
            match event {
                LinkEvent::Driver(_) => self.alive.heard(now),
                LinkEvent::Disconnected { reason } => self.lost = Some(Loss::Link(reason)),
            }
        }
        if self.alive.ask(now) {
            // Where it is already: a question it answers, and no move.
            self.handle.move_to(self.at);
        }
        if let Some(quiet) = self.alive.silent(now) {
            self.lost.get_or_insert_with(|| Loss::silence(quiet));
        }
    }

    fn lost(&self) -> Option<Loss> {
        self.lost.clone()
    }

    fn follow(&mut self, now: &Now) -> Result<(), String> {
        if let Now::Posed(Posed::Servos(degrees)) = now
            && let Some(&deg) = degrees.get(&0)
            && whole_deg(deg) != self.at
        {
            self.move_to(deg);
        }
        Ok(())
    }

    fn pose(&mut self, axis: Axis, value_deg: f64, _speed: LiveSpeed) -> Result<f64, String> {
        if axis != Axis::Servo(0) {
            return Err("an Echo board has one servo".into());
        }
        Ok(f64::from(self.move_to(value_deg)))
    }
}
