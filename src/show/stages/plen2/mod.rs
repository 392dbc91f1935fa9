//! A PLEN2 on a show's stage: motions and play lists started, joints
//! followed and posed within their limits a cycle at a time, asked its
//! version twice a second (the robot acknowledges nothing else, so this is
//! how it is known to be there).

mod lane;

use std::time::{Duration, Instant};

use crossbeam_channel::Receiver;

use super::{LinkDelay, Linked};
use crate::authoring::fit::{self as fit, Budget, FitError, Plen2Board};
use crate::authoring::fitted::{self, PLEN2_UPDATE_MS};
use crate::device::plen2::playback::{CYCLE_US, DEVICE_IDS, Settings, joint_settings};
use crate::device::plen2::{
    Command as Plen2Command, Plen2Handle, Plen2Notice, Plen2Options, Plen2Requester, ReplyError, play_motion_delay,
};
use crate::device::speed::{LiveSpeed, Slew};
use crate::link::{self, LineSettings, PortName, no_waker};
use crate::project::Project;
use crate::project::plen2::Joint;
use crate::project::plen2::{JOINTS, MAX_FRAMES, Motion};
use crate::show::alive::{Alive, Loss};
use crate::show::at::{Now, Posed};
use crate::show::boards::Run;
use crate::show::passes::{self, Axis, JoinError, Joined, Made, Moves, TOLERANCE_DEG};
use crate::show::play::Stage;
use crate::show::{Device, Start};

inventory::submit! {
    crate::show::family::ShowFamily {
        family: crate::project::Family::Plen2,
        connect,
        first_stored: |project| project.plen2.motions.iter().map(|m| m.slot).min().map(Start::Slot),
        takes: |start| matches!(start, Start::Slot(_)),
        new_cue: None,
        holds: |project, start| matches!(*start, Start::Slot(slot) if project.plen2.motions.iter().any(|m| m.slot == slot)),
        runs: Some(crate::show::family::Runs { find: motion_named, listed: motions_listed }),
        poses: Some(crate::show::family::Poses {
            axes: |_| Joint::ALL.iter().map(|joint| (joint.name().to_string(), Axis::Joint(joint.device_id()))).collect(),
            // A joint's device id, as well as its name.
            alias: |_, name| name.parse::<u8>().ok().and_then(Joint::from_device_id).map(|joint| Axis::Joint(joint.device_id())),
        }),
        drives: false,
        cues: &[],
    }
}

/// Every pass of a PLEN2 joined into one motion of at most 20 frames in a
/// free slot, fitted within the tolerance (widened when the frames need it).
fn join(project: &mut Project, axes: &passes::Latest<'_>, span: (u64, u64), device: &str) -> Result<Joined, JoinError> {
    let name = device.to_string();
    // All 18 joints, the recorded ones from their passes, the others at home.
    let recorded = passes::rows(axes, span, PLEN2_UPDATE_MS, 10.0);
    let joints: Vec<usize> =
        axes.keys().filter_map(|axis| if let Axis::Joint(id) = axis { Some(usize::from(*id)) } else { None }).collect();
    let rows: Vec<Vec<f64>> = recorded
        .iter()
        .map(|row| {
            let mut all = vec![0.0; JOINTS];
            for (&joint, &value) in joints.iter().zip(row) {
                if let Some(slot) = all.get_mut(joint) {
                    *slot = value;
                }
            }
            all
        })
        .collect();
    let rest = rows.get(1..).filter(|rest| !rest.is_empty()).ok_or(JoinError::TooShort)?;
    // From home, where the robot stands before its cue.
    let start = vec![0; JOINTS];
    let budget = Budget { tolerance: TOLERANCE_DEG * 10.0, allowed: MAX_FRAMES, resolution: 1.0 };
    let (fitted, tolerance) = match fit::fit_within(&Plen2Board, &start, rest, budget) {
        Ok(fitted) => (fitted, budget.tolerance),
        Err(FitError::Tolerance { .. }) => {
            let (wider, fitted) = fit::widest_needed(&Plen2Board, &start, rest, budget);
            (fitted, wider)
        }
        Err(FitError::TooLong { .. }) => return Err(JoinError::TooLong(name)),
    };
    let used: Vec<u8> = project.plen2.motions.iter().map(|m| m.slot).collect();
    let slot = (0..90u8).rev().find(|slot| !used.contains(slot)).ok_or(JoinError::NoSlot(name))?;
    let frames = fitted::plen2_frames(&fitted);
    let moves = frames.len();
    project.plen2.motions.push(Motion { slot, name: "passes".into(), frames, loop_range: None, jump_slot: None });
    project.plen2.motions.sort_by_key(|m| m.slot);
    Ok(Joined {
        made: Made { start: Start::Slot(slot), parts: Vec::new(), moves_are: Moves::Frames },
        moves,
        max_error_deg: fitted.max_error / 10.0,
        tolerance_deg: tolerance / 10.0,
    })
}

/// What a PLEN2's passes made, taken out: their motion.
fn forget(project: &mut Project, made: &Made) {
    if let Start::Slot(slot) = made.start {
        project.plen2.motions.retain(|m| m.slot != slot);
    }
}

/// A PLEN2's joints, by name, each within ±90° of home.
fn recorded_axes(_: &Project) -> Vec<passes::Recordable> {
    Joint::ALL.iter().map(|joint| (Axis::Joint(joint.device_id()), joint.name().to_string(), -90.0..=90.0)).collect()
}

inventory::submit! {
    passes::FamilyPasses { family: crate::project::Family::Plen2, axes: recorded_axes, join, forget }
}

/// Its motions (slot, name) and play lists (name, how many entries), as a remote lists them.
fn motions_listed(project: &Project) -> Vec<crate::show::family::Listed> {
    let plen2 = &project.plen2;
    let motions = plen2.motions.iter().map(|m| serde_json::json!({ "slot": m.slot, "name": m.name }));
    let lists = plen2.play_lists.iter().map(|l| serde_json::json!({ "name": l.name, "entries": l.entries.len() }));
    vec![("motions", motions.collect()), ("play_lists", lists.collect())]
}

/// The motion `what` names (its slot or its name), or the play list (its name).
fn motion_named(project: &Project, what: &str) -> Result<crate::show::family::Named, String> {
    let number: Option<i64> = what.trim().parse().ok();
    let plen2 = &project.plen2;
    if let Some(m) = plen2.motions.iter().find(|m| number == Some(i64::from(m.slot)) || m.name == what) {
        return Ok((Run::Start(Start::Slot(m.slot)), format!("motion {} {}", m.slot, m.name)));
    }
    if let Some(list) = plen2.play_lists.iter().find(|list| list.name == what) {
        let entries = list.entries.iter().map(|entry| (Start::Slot(entry.slot), entry.plays)).collect();
        return Ok((Run::List(entries), format!("play list {}", list.name)));
    }
    Err(format!("no motion or play list {what:?}"))
}

/// Connects the PLEN2 on `port`: the driver's own probe (which also sets its
/// pacing), then its link measured on version questions.
fn connect(port: &PortName, settings: &LineSettings, device: &Device) -> anyhow::Result<Linked> {
    let connection = link::open(port, settings)?;
    let mut handle = Plen2Handle::over(connection, Plen2Options::default(), no_waker())?;
    let requester = handle.requester();
    requester.probe().map_err(|error| anyhow::anyhow!(error.to_string()))?;
    let link =
        LinkDelay::measured(|| requester.get(Plen2Command::GetVersion).map(|_| ()).map_err(|error| error.to_string()))?;
    let lost = handle.pump(Instant::now()).into_iter().find_map(|notice| match notice {
        Plen2Notice::Disconnected(reason) => Some(Loss::Link(reason)),
        _ => None,
    });
    let settings = joint_settings(&device.project.plen2);
    let alive = Alive::new(Instant::now());
    let stage = Plen2Stage { handle, requester, link, lost, alive, asking: None, settings, sent: None, slew: None };
    let start_delay = stage.start_delay(&Start::Slot(0));
    Ok(Linked { stage: Box::new(stage), start_delay, link })
}

impl Plen2Stage {
    /// Asks its version twice a second, taking the answer in when it came:
    /// an answer is a sign of life; none for long, the robot is lost.
    fn ask_alive(&mut self, now: Instant) {
        if let Some(answer) = &self.asking {
            match answer.try_recv() {
                Ok(Ok(_)) => {
                    self.alive.heard(now);
                    self.asking = None;
                }
                Ok(Err(ReplyError::Stopped)) => {
                    self.alive.withdrawn();
                    self.asking = None;
                }
                Ok(Err(_)) | Err(crossbeam_channel::TryRecvError::Disconnected) => self.asking = None,
                Err(crossbeam_channel::TryRecvError::Empty) => {}
            }
        }
        if self.asking.is_none() && self.alive.ask(now) {
            self.asking = self.requester.ask(Plen2Command::GetVersion).ok();
        }
        if let Some(quiet) = self.alive.silent(now) {
            self.lost.get_or_insert_with(|| Loss::silence(quiet));
        }
    }
}

struct Plen2Stage {
    handle: Plen2Handle,
    requester: Plen2Requester,
    link: LinkDelay,
    lost: Option<Loss>,
    /// Its signs of life: asked its version twice a second.
    alive: Alive,
    /// The version question out.
    asking: Option<Receiver<Result<Vec<u8>, ReplyError>>>,
    /// Each joint's home and limits, by device id.
    settings: Settings,
    /// The joints' values last told while following (from home).
    sent: Option<[i16; DEVICE_IDS]>,
    /// A remote's pose, walked toward a cycle at a time (absolute, by joint), and how fast.
    slew: Option<(Slew, LiveSpeed)>,
}

impl Stage for Plen2Stage {
    fn start_delay(&self, start: &Start) -> Duration {
        let Start::Slot(slot) = *start else { return Duration::ZERO };
        play_motion_delay(slot, self.link.one_way)
    }

    fn start_uncertainty(&self, _start: &Start) -> Duration {
        // It starts at its next cycle: the start's delay counts half of one.
        self.link.spread + Duration::from_micros(CYCLE_US / 2)
    }

    fn uncertainty_of(&self) -> &'static str {
        "its link's spread and half its cycle"
    }

    fn start(&mut self, start: &Start) -> Result<(), String> {
        let Start::Slot(slot) = *start else { return Err(format!("a PLEN2 cannot start {start}")) };
        self.requester.send(Plen2Command::PlayMotion { slot }).map_err(|error| error.to_string())
    }

    fn stop(&mut self) {
        self.handle.stop();
        // STOP sends the joints home (`$HP`).
        self.sent = Some([0; DEVICE_IDS]);
        self.slew = None;
    }

    fn follow(&mut self, now: &Now) -> Result<(), String> {
        let Now::Posed(Posed::Joints(values)) = now else { return Ok(()) };
        let before = self.sent.unwrap_or([i16::MIN; DEVICE_IDS]);
        let moves: Vec<(u8, i16)> = Joint::ALL
            .iter()
            .map(|joint| (joint.device_id(), usize::from(joint.device_id())))
            .filter(|&(_, device)| before[device] != values[device])
            .map(|(id, device)| {
                let (home, min, max) = self.settings[device];
                (id, home.saturating_add(values[device]).clamp(min.min(max), max.max(min)))
            })
            .collect();
        self.sent = Some(*values);
        if !moves.is_empty() {
            // Coalesced and paced by the driver, as the sliders are.
            self.handle.move_joints(moves);
        }
        Ok(())
    }

    fn tick(&mut self, now: Instant) {
        for notice in self.handle.pump(now) {
            if let Plen2Notice::Disconnected(reason) = notice {
                self.lost = Some(Loss::Link(reason.clone()));
            }
        }
        self.ask_alive(now);
        if let Some((slew, speed)) = &mut self.slew {
            let moves: Vec<(u8, i16)> = slew
                .step(now, *speed)
                .into_iter()
                .map(|(index, angle)| (Joint::ALL[index].device_id(), angle))
                .collect();
            if !moves.is_empty() {
                self.handle.move_joints(moves);
            }
        }
    }

    fn start_list(&mut self, entries: &[(Start, u8)]) -> Result<(), String> {
        let entries = entries
            .iter()
            .map(|&(start, plays)| match start {
                Start::Slot(slot) => Ok((slot, plays)),
                other => Err(format!("a PLEN2's play list plays motions, not {other}")),
            })
            .collect::<Result<Vec<(u8, u8)>, String>>()?;
        let entries = entries.as_slice();
        self.slew = None;
        self.handle.queue_list(entries);
        self.requester.send(Plen2Command::Pop).map_err(|error| error.to_string())
    }

    fn pose(&mut self, axis: Axis, value_deg: f64, speed: LiveSpeed) -> Result<f64, String> {
        let Axis::Joint(device) = axis else { return Err("a PLEN2's axes are joints".into()) };
        let joint = Joint::from_device_id(device).ok_or(format!("no joint {device}"))?;
        let (home, min, max) = self.settings[usize::from(device)];
        // Tenths of a degree of a finite value within ±180°.
        #[allow(clippy::cast_possible_truncation)]
        let tenths = (value_deg.clamp(-180.0, 180.0) * 10.0).round() as i16;
        let target = home.saturating_add(tenths).clamp(min.min(max), max.max(min));
        let now = Instant::now();
        let (slew, pace) = self.slew.get_or_insert_with(|| {
            // Where the joints are: where they were last told, else home.
            let told = self.sent.unwrap_or([0; DEVICE_IDS]);
            let at: [i16; 18] = std::array::from_fn(|index| {
                let id = usize::from(Joint::ALL[index].device_id());
                self.settings[id].0.saturating_add(told[id])
            });
            (Slew::new(at, at, now), speed)
        });
        slew.target[joint.index()] = target;
        *pace = speed;
        Ok(f64::from(target - home) / 10.0)
    }

    fn lost(&self) -> Option<Loss> {
        self.lost.clone()
    }
}
