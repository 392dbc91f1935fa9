//! A DYNAMIXEL bus on a show's stage: its kind of cue (`"motion": N`, the
//! project's N-th motion, streamed from where the servos are), its servos
//! posed by a remote (by ID or caption) and followed by a preview, held at
//! STOP. At connect it finds the servos its project lists (each must answer)
//! and measures its link on pings; while held, the servos' readings say it
//! is there (a ping when they stop), and a bus that goes quiet, or a servo of
//! it said silent, is lost.

mod lane;

use std::collections::BTreeMap;
use std::time::{Duration, Instant};

use crate::device::dynamixel::{DynamixelCommand, DynamixelEvent, DynamixelHandle, Found, Limits};
use crate::device::speed::LiveSpeed;
use crate::link::{self, LineSettings, LinkEvent, PortName, no_waker};
use crate::project::dynamixel::{DynamixelSection, Motion, degrees, units};
use crate::project::{Family, Project};
use crate::show::alive::{Alive, Loss, SILENT_AFTER};
use crate::show::at::{Axis, Now, Posed};
use crate::show::family::{FamilyCue, Listed, Named, Poses, Runs, ShowFamily};
use crate::show::play::Stage;
use crate::show::stages::{LinkDelay, Linked, ROUND_TRIPS};
use crate::show::{Device, Run, Start};

/// Its kind of cue in a show file: `"motion": N`, the N-th motion (from 1).
pub const MOTION: &str = "motion";

/// The time between two streamed frames.
const FRAME: Duration = Duration::from_millis(20);

inventory::submit! {
    ShowFamily {
        family: Family::Dynamixel,
        connect,
        first_stored: |project| motion_cue(project, 1),
        takes: |start| matches!(start, Start::Family(cue) if cue.kind == MOTION),
        new_cue: None,
        holds: |project, start| motion_of(project, start).is_some(),
        runs: Some(Runs { find, listed }),
        poses: Some(Poses { axes, alias }),
        drives: false,
        cues: &[MOTION],
    }
}

/// The cue that plays the `number`-th motion of `project`, if it holds one.
fn motion_cue(project: &Project, number: usize) -> Option<Start> {
    let count = DynamixelSection::of(project).motions.len();
    #[allow(clippy::cast_precision_loss)]
    (1..=count).contains(&number).then(|| FamilyCue::named(MOTION, number as f64).ok().map(Start::Family)).flatten()
}

/// The motion a start plays, if `project` holds it.
fn motion_of(project: &Project, start: &Start) -> Option<Motion> {
    let Start::Family(cue) = start else { return None };
    if cue.kind != MOTION || cue.value.fract() != 0.0 || cue.value < 1.0 {
        return None;
    }
    // A whole number of at least 1.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let index = cue.value as usize - 1;
    DynamixelSection::of(project).motions.get(index).cloned()
}

/// What a remote names to run: a motion by number (from 1) or by name.
fn find(project: &Project, what: &str) -> Result<Named, String> {
    let section = DynamixelSection::of(project);
    let index = match what.trim().parse::<usize>() {
        Ok(number) if (1..=section.motions.len()).contains(&number) => Some(number - 1),
        Ok(_) => None,
        Err(_) => section.motions.iter().position(|motion| motion.name == what),
    };
    let index = index.ok_or_else(|| format!("no motion {what:?} (it holds {})", section.motions.len()))?;
    let start = motion_cue(project, index + 1).ok_or_else(|| format!("no motion {what:?}"))?;
    Ok((Run::Start(start), format!("motion {} {}", index + 1, section.motions[index].name)))
}

/// What it keeps to run, as a remote lists it: its motions (the other families' keys empty).
fn listed(project: &Project) -> Vec<Listed> {
    let motions = DynamixelSection::of(project)
        .motions
        .iter()
        .enumerate()
        .map(|(index, motion)| {
            serde_json::json!({ "number": index + 1, "name": motion.name, "duration_ms": motion.duration_ms() })
        })
        .collect();
    vec![("macros", Vec::new()), ("motions", motions), ("play_lists", Vec::new())]
}

/// Its servos, each by its ID as a remote names it.
fn axes(project: &Project) -> Vec<(String, Axis)> {
    DynamixelSection::of(project).servos.iter().map(|servo| (servo.id.to_string(), Axis::Servo(servo.id))).collect()
}

/// A servo by its caption.
fn alias(project: &Project, name: &str) -> Option<Axis> {
    DynamixelSection::of(project)
        .servos
        .iter()
        .find(|servo| !servo.name.is_empty() && servo.name == name)
        .map(|servo| Axis::Servo(servo.id))
}

/// Connects the bus on `port`: every servo the project lists found, then the link measured on pings.
fn connect(port: &PortName, line: &LineSettings, device: &Device) -> anyhow::Result<Linked> {
    let section = DynamixelSection::of(&device.project);
    let wanted: Vec<u8> = section.servos.iter().map(|servo| servo.id).collect();
    let (Some(&lowest), Some(&highest)) = (wanted.iter().min(), wanted.iter().max()) else {
        anyhow::bail!("its project lists no servo: capture a pose or scan the bus in the editor first");
    };
    let handle = DynamixelHandle::over(link::open(port, line)?, no_waker())?;
    handle.send(DynamixelCommand::Scan { one: lowest..=highest });
    let mut found: BTreeMap<u8, (Found, Option<Limits>)> = BTreeMap::new();
    let mut present = BTreeMap::new();
    let deadline = Instant::now() + SILENT_AFTER + Duration::from_secs(5);
    while !wanted.iter().all(|id| found.get(id).is_some_and(|(_, limits)| limits.is_some()) && present.contains_key(id))
    {
        let left = deadline.saturating_duration_since(Instant::now());
        match handle.events().recv_timeout(left) {
            Ok(LinkEvent::Driver(DynamixelEvent::Found(servo))) => {
                found.insert(servo.id, (servo, None));
            }
            Ok(LinkEvent::Driver(DynamixelEvent::Limits { id, limits })) => {
                if let Some(entry) = found.get_mut(&id) {
                    entry.1 = Some(limits);
                }
            }
            Ok(LinkEvent::Driver(DynamixelEvent::Reading { id, reading })) => {
                present.insert(id, reading.position);
            }
            Ok(LinkEvent::Driver(DynamixelEvent::Scanned { .. })) => {
                if let Some(missing) = wanted.iter().find(|id| !found.contains_key(id)) {
                    anyhow::bail!(
                        "servo {missing} of its project did not answer on the bus (is it powered, at this baud rate?)"
                    );
                }
            }
            Ok(LinkEvent::Driver(_)) => {}
            Ok(LinkEvent::Disconnected { reason }) => anyhow::bail!("the bus's link ended: {reason}"),
            Err(_) => anyhow::bail!("the bus did not say where its servos are within {} s", SILENT_AFTER.as_secs() + 5),
        }
    }
    // Live moves (a remote's pose) at each servo's own profile, as the editor sets it.
    for servo in &section.servos {
        let profile = servo.live_profile();
        let (velocity, acceleration) = (profile.velocity, profile.acceleration);
        handle.send(DynamixelCommand::Profile { id: servo.id, velocity, acceleration });
    }
    let first = section.servos[0].id;
    let protocol = found[&first].0.protocol;
    let mut round_trips = Vec::with_capacity(ROUND_TRIPS);
    while round_trips.len() < ROUND_TRIPS {
        let asked = Instant::now();
        handle.send(DynamixelCommand::Ping { id: first, protocol });
        loop {
            match handle.events().recv_timeout(SILENT_AFTER) {
                Ok(LinkEvent::Driver(DynamixelEvent::Pong { .. })) => break,
                Ok(LinkEvent::Driver(DynamixelEvent::Reading { id, reading })) => {
                    present.insert(id, reading.position);
                }
                Ok(LinkEvent::Driver(_)) => {}
                Ok(LinkEvent::Disconnected { reason }) => anyhow::bail!("the bus's link ended: {reason}"),
                Err(_) => anyhow::bail!("servo {first} answered no ping within {} s", SILENT_AFTER.as_secs()),
            }
        }
        round_trips.push(asked.elapsed());
    }
    let link = LinkDelay::from_round_trips(&round_trips);
    let servos = found.into_iter().map(|(id, (servo, limits))| (id, Held { found: servo, limits })).collect();
    let project = device.project.clone();
    let stage =
        DynamixelStage { handle, project, link, servos, present, alive: Alive::new(Instant::now()), lost: None };
    Ok(Linked { stage: Box::new(stage), start_delay: link.one_way, link })
}

/// A servo the stage holds.
struct Held {
    found: Found,
    limits: Option<Limits>,
}

impl Held {
    /// `position` within its limits.
    fn clamp(&self, position: u32) -> u32 {
        let top = self.found.model().map_or(4095, |model| model.layout.top_position);
        let (lowest, highest) = self.limits.map_or((0, top), |limits| (limits.lowest, limits.highest.min(top)));
        position.clamp(lowest, highest.max(lowest))
    }
}

struct DynamixelStage {
    handle: DynamixelHandle,
    /// What it plays: a DYNAMIXEL stores nothing, so the show's project is all there is.
    project: Project,
    link: LinkDelay,
    servos: BTreeMap<u8, Held>,
    /// Where each servo last said it is.
    present: BTreeMap<u8, u32>,
    alive: Alive,
    lost: Option<Loss>,
}

impl DynamixelStage {
    /// Servo `id` to `deg` from its centre, within its limits; the degrees it took.
    fn goal_deg(&mut self, id: u8, deg: f64) -> Option<f64> {
        let held = self.servos.get(&id)?;
        let model = held.found.model_number;
        let position = held.clamp(units(model, deg));
        self.handle.send(DynamixelCommand::Goal { id, position });
        Some(degrees(model, position))
    }
}

impl Stage for DynamixelStage {
    fn start_delay(&self, _start: &Start) -> Duration {
        self.link.one_way
    }

    fn start_uncertainty(&self, _start: &Start) -> Duration {
        self.link.spread
    }

    /// Streams the motion from where the servos are.
    fn start(&mut self, start: &Start) -> Result<(), String> {
        let motion = motion_of(&self.project, start).ok_or_else(|| format!("its project holds no {start}"))?;
        let every_ms = FRAME.as_secs_f64() * 1000.0;
        let frames = motion
            .frames(&self.present, every_ms)
            .into_iter()
            .map(|pose| {
                pose.into_iter()
                    .filter_map(|(id, position)| self.servos.get(&id).map(|held| (id, held.clamp(position))))
                    .collect()
            })
            .collect();
        self.handle.send(DynamixelCommand::Stream { frames, every: FRAME });
        Ok(())
    }

    fn stop(&mut self) {
        self.handle.send(DynamixelCommand::Hold);
    }

    fn tick(&mut self, now: Instant) {
        for event in self.handle.events().try_iter() {
            match event {
                LinkEvent::Driver(DynamixelEvent::Reading { id, reading }) => {
                    self.present.insert(id, reading.position);
                    self.alive.heard(now);
                }
                LinkEvent::Driver(DynamixelEvent::Pong { .. }) => self.alive.heard(now),
                // A servo of the show that stops answering stops the show, as a lost link does.
                LinkEvent::Driver(DynamixelEvent::Silent { .. }) => {
                    self.lost.get_or_insert(Loss::silence(crate::device::dynamixel::SILENT_AFTER));
                }
                LinkEvent::Driver(_) => {}
                LinkEvent::Disconnected { reason } => self.lost = Some(Loss::Link(reason)),
            }
        }
        if self.alive.ask(now)
            && let Some(held) = self.servos.values().next()
        {
            self.handle.send(DynamixelCommand::Ping { id: held.found.id, protocol: held.found.protocol });
        }
        if let Some(quiet) = self.alive.silent(now) {
            self.lost.get_or_insert_with(|| Loss::silence(quiet));
        }
    }

    fn lost(&self) -> Option<Loss> {
        self.lost.clone()
    }

    fn follow(&mut self, now: &Now) -> Result<(), String> {
        if let Now::Posed(Posed::Servos(degrees)) = now {
            for (id, deg) in degrees {
                self.goal_deg(*id, *deg);
            }
        }
        Ok(())
    }

    fn pose(&mut self, axis: Axis, value_deg: f64, _speed: LiveSpeed) -> Result<f64, String> {
        let Axis::Servo(id) = axis else { return Err("a DYNAMIXEL bus has servos, not joints".into()) };
        self.goal_deg(id, value_deg).ok_or_else(|| format!("no servo {id} on the bus"))
    }
}
