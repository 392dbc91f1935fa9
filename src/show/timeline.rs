//! What each device of a show does over time, worked out once for the show
//! as it stands and looked up after: how long each cue keeps its device busy
//! (the lanes' blocks) and where each device is at each moment, as its family
//! works it out ([`Lane`], registered beside its show stage: a servo board's
//! macros traced, a PLEN2's motions played as the firmware plays them, a
//! base's drives followed from its place). A frame then costs what it shows,
//! not the show's length: an hour-long show of four devices draws as fast as
//! a minute's (`benches/ui.rs` measures it).
//!
//! Every answer is the one [`posed_at`] and [`cue_length_ms`] give: they are
//! worked out by the same lanes, once.

use std::collections::HashMap;
use std::hash::{Hash, Hasher};

use super::at::{Axis, Now, Posed, hold};
use super::{Device, Show, Start};
use crate::project::{Family, Project};

/// The device at `index` at `t_ms` of the show (`None`: no such device, or
/// one of a family with no place on the timeline).
/// (The show window keeps a [`Timeline`]: the same answer, worked out once.)
pub fn posed_at(show: &Show, index: usize, t_ms: u64) -> Option<Posed> {
    Timeline::default().posed_at(show, index, t_ms)
}

/// The device at `index` at `t_ms`, as its board follows it; `held`: an
/// axis of it held at a value (degrees), the pass being recorded.
pub fn now_at(show: &Show, index: usize, t_ms: u64, held: Option<(Axis, f64)>) -> Option<Now> {
    let device = show.devices.get(index)?;
    let mut lane = lane_of(device.project.family)?;
    match lane.now_at(device, &cues_of(show, &device.name), t_ms) {
        Now::Posed(mut posed) => {
            if let Some((axis, value)) = held {
                hold(&mut posed, axis, value);
            }
            Some(Now::Posed(posed))
        }
        driving => Some(driving),
    }
}

/// How long a cue keeps its device busy, ms, from the device's project.
/// (The show window keeps a [`Timeline`]: the same answer, worked out once.)
pub fn cue_length_ms(device: &Device, start: &Start) -> u64 {
    lane_of(device.project.family).map_or(0, |mut lane| lane.length_ms(&device.project, start))
}

/// One device's part of the show's timeline, as its family works it out;
/// kept while the show is unchanged, so what it works out once (a macro's
/// trace, a motion's playback) it may keep.
pub trait Lane: std::fmt::Debug {
    /// How long `start` keeps a device holding `project` busy, ms (0: a cue it does not take).
    fn length_ms(&mut self, project: &Project, start: &Start) -> u64;
    /// Where `device` is `t_ms` into the show; `cues`: its cues (when, what), by when.
    fn posed_at(&mut self, device: &Device, cues: &[(u64, Start)], t_ms: u64) -> Posed;
    /// What its board is told to follow at `t_ms`: its pose, unless it drives.
    fn now_at(&mut self, device: &Device, cues: &[(u64, Start)], t_ms: u64) -> Now {
        Now::Posed(self.posed_at(device, cues, t_ms))
    }
}

/// A family's part of the show's timeline, registered by the family beside
/// its show stage (`inventory::submit!`): a new lane for a device of it.
#[derive(Debug)]
pub struct FamilyTimeline {
    /// The family.
    pub family: Family,
    /// A lane for one device of it, nothing worked out yet.
    pub lane: fn() -> Box<dyn Lane>,
}

inventory::collect!(FamilyTimeline);

/// A new lane for a device of `family`; none: it has no place on the timeline.
fn lane_of(family: Family) -> Option<Box<dyn Lane>> {
    inventory::iter::<FamilyTimeline>.into_iter().find(|entry| entry.family == family).map(|entry| (entry.lane)())
}

/// The latest of `cues` (when, what; by when) started by `t_ms`, if any has.
pub fn latest(cues: &[(u64, Start)], t_ms: u64) -> Option<(u64, Start)> {
    let started = cues.partition_point(|&(at, _)| at <= t_ms);
    started.checked_sub(1).map(|k| cues[k])
}

/// A length in ms, whole (a part of one counts as one).
pub fn whole_ms(ms: f64) -> u64 {
    // Non-negative, under an hour.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let whole = ms.max(0.0).ceil() as u64;
    whole
}

/// The cues of the device called `name`: (when, what), by when (in the show's order at the same time).
fn cues_of(show: &Show, name: &str) -> Vec<(u64, Start)> {
    let mut cues: Vec<(u64, Start)> =
        show.cues.iter().filter(|cue| cue.device == name).map(|cue| (cue.at_ms, cue.start)).collect();
    cues.sort_by_key(|&(at, _)| at);
    cues
}

/// A cue on the timeline.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Block {
    /// Its device, by index in the show.
    pub device: usize,
    /// The cue, by index in the show's cues.
    pub cue: usize,
    /// When it starts, ms.
    pub at_ms: u64,
    /// How long it keeps its device busy, ms.
    pub length_ms: u64,
}

/// The show's devices over time, kept while the show is unchanged.
#[derive(Debug, Default)]
pub struct Timeline {
    /// What the show was when this was worked out (its cues, devices, sound and projects' revision).
    key: Option<u64>,
    /// Each cue naming a device of the show, in the show's order; the span they and the sound take.
    blocks: Option<(Vec<Block>, u64)>,
    /// Each device's blocks, by start.
    lanes: Vec<Vec<Block>>,
    /// Each device's cues: (when, what), by when.
    cues: HashMap<usize, Vec<(u64, Start)>>,
    /// Each device's lane (none: its family has no place on the timeline).
    worked: HashMap<usize, Option<Box<dyn Lane>>>,
    /// The show's first problem, once looked for.
    problem: Option<Option<super::ShowError>>,
}

/// A fingerprint of what the timeline is worked out from: the cues, the
/// devices (names, families, places), the sound's span and `projects` (a revision
/// the owner changes whenever a device's project does).
fn key(show: &Show, projects: u64) -> u64 {
    let mut hasher = std::collections::hash_map::DefaultHasher::new();
    projects.hash(&mut hasher);
    for device in &show.devices {
        (&device.name, device.project.family.tag()).hash(&mut hasher);
        let place = device.place;
        (place.x_m.to_bits(), place.y_m.to_bits(), place.heading_deg.to_bits()).hash(&mut hasher);
    }
    show.sound.as_ref().map(|sound| (sound.offset_ms, sound.duration_ms)).hash(&mut hasher);
    for cue in &show.cues {
        (&cue.device, cue.at_ms).hash(&mut hasher);
        cue.start.fingerprint(&mut hasher);
    }
    hasher.finish()
}

impl Timeline {
    /// Starts again if `show` (or, by `projects`, a device's project) changed since.
    pub fn keep_to(&mut self, show: &Show, projects: u64) {
        let now = key(show, projects);
        if self.key != Some(now) {
            *self = Self { key: Some(now), ..Self::default() };
        }
    }

    /// Every cue as a block, and the span the timeline shows (ms, at least a second).
    pub fn blocks(&mut self, show: &Show) -> (&[Block], u64) {
        if self.blocks.is_none() {
            let mut blocks = Vec::new();
            for (cue_index, cue) in show.cues.iter().enumerate() {
                let Some(device) = show.devices.iter().position(|d| d.name == cue.device) else { continue };
                let project = &show.devices[device].project;
                let length_ms = self.worked(show, device).map_or(0, |lane| lane.length_ms(project, &cue.start));
                blocks.push(Block { device, cue: cue_index, at_ms: cue.at_ms, length_ms });
            }
            let mut lanes = vec![Vec::new(); show.devices.len()];
            for block in &blocks {
                lanes[block.device].push(*block);
            }
            for lane in &mut lanes {
                lane.sort_by_key(|block| block.at_ms);
            }
            self.lanes = lanes;
            let sound = show.sound.as_ref().map(|s| s.offset_ms.max(0).unsigned_abs() + s.duration_ms);
            let span = blocks.iter().map(|b| b.at_ms + b.length_ms).chain(sound).max().unwrap_or(0).max(1000);
            self.blocks = Some((blocks, span));
        }
        let (blocks, span) = self.blocks.as_ref().map_or((&[][..], 1000), |(b, s)| (b.as_slice(), *s));
        (blocks, span)
    }

    /// The show's first problem ([`Show::check`]), looked for once.
    pub fn problem(&mut self, show: &Show) -> Option<&super::ShowError> {
        self.problem.get_or_insert_with(|| show.check().err()).as_ref()
    }

    /// Device `device`'s blocks, by start (once [`Self::blocks`] has worked them out).
    pub fn lane(&self, device: usize) -> &[Block] {
        self.lanes.get(device).map_or(&[], Vec::as_slice)
    }

    /// Device `index`'s lane, made once; none: no such device, or its family has no place on the timeline.
    fn worked(&mut self, show: &Show, index: usize) -> Option<&mut Box<dyn Lane>> {
        let family = show.devices.get(index)?.project.family;
        self.worked.entry(index).or_insert_with(|| lane_of(family)).as_mut()
    }

    /// The device at `index` at `t_ms` of the show, as [`posed_at`] has it.
    pub fn posed_at(&mut self, show: &Show, index: usize, t_ms: u64) -> Option<Posed> {
        let device = show.devices.get(index)?;
        let cues = self.cues.entry(index).or_insert_with(|| cues_of(show, &device.name));
        let family = device.project.family;
        let lane = self.worked.entry(index).or_insert_with(|| lane_of(family)).as_mut()?;
        Some(lane.posed_at(device, cues, t_ms))
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use crate::project::plen2::{Frame, LoopRange, Motion, Plen2Project, Pose};
    use crate::project::{Action, Command, Macro, Project, Run, Servo, ServoProject, Step};
    use crate::show::Cue;

    /// A servo board with servo 1, its action 1 of `steps` run by macro 1.
    pub(super) fn jaw(steps: Vec<Step>) -> Project {
        let action = Action { id: 1, caption: "nod".into(), steps };
        let macros =
            vec![Macro { id: 1, caption: "m".into(), commands: vec![Command::once(Run::Action { action_id: 1 })] }];
        Project::servo(ServoProject {
            servos: vec![Servo::new(1, "jaw")],
            actions: vec![action],
            macros,
            ..ServoProject::default()
        })
    }

    /// A show of `servo` ("skull"), a PLEN2 ("plen") holding `frames` in
    /// slot 2 (looped over `loop_range`) and a base ("base"), with no cues.
    pub(super) fn three(servo: Project, frames: Vec<Frame>, loop_range: Option<LoopRange>) -> Show {
        let motion = Motion { slot: 2, name: "sway".into(), frames, loop_range, jump_slot: None };
        let mut plen = Project::empty(Family::Plen2);
        plen.plen2 = Plen2Project { motions: vec![motion], ..Plen2Project::default() };
        let mut show = Show::of_one("skull", servo);
        show.add_device("plen", plen);
        show.add_device("base", Project::empty(Family::Rflex));
        show
    }

    /// An hour of a servo board's macro every 7 s, a PLEN2's looping motion
    /// cued every minute, and a base driving and turning every 5 s.
    fn hour() -> Show {
        let servo = jaw(vec![Step::new(1, 90, 100), Step::new(1, -30, 150)]);
        let (mut up, mut down) = (Pose::default(), Pose::default());
        up.0[0] = 320;
        down.0[0] = -150;
        let frames = vec![Frame::new(32 * 10, up), Frame::new(32 * 7, down)];
        let mut show = three(servo, frames, Some(LoopRange { begin_frame: 0, end_frame: 1, count: 255 }));
        for at_ms in (0..3_600_000).step_by(7000) {
            show.cues.push(Cue { device: "skull".into(), at_ms, start: Start::Macro(1) });
        }
        for at_ms in (0..3_600_000).step_by(60_000) {
            show.cues.push(Cue { device: "plen".into(), at_ms: at_ms + 500, start: Start::Slot(2) });
        }
        for (k, at_ms) in (0..3_600_000u64).step_by(5000).enumerate() {
            let turn = if k % 2 == 0 { 0.0 } else { 45.0 };
            let start = Start::Drive { speed_m_s: 0.2, turn_deg_s: turn, for_ms: 3000 + (k as u64 % 3) * 1500 };
            show.cues.push(Cue { device: "base".into(), at_ms, start });
        }
        show
    }

    #[test]
    fn one_timeline_scrubbed_back_and_forth_says_what_a_fresh_look_says() {
        let show = hour();
        let mut kept = Timeline::default();
        kept.keep_to(&show, 0);
        // Forward, back, far ahead, back to the start: the caches grow and are reused.
        let times = [0, 250, 90_000, 61_000, 3_599_000, 1_234_567, 500, 2_000_000, 60_532, 3_600_000];
        for t in times {
            for index in 0..show.devices.len() {
                let fresh = Timeline::default().posed_at(&show, index, t).unwrap();
                assert_eq!(kept.posed_at(&show, index, t).unwrap(), fresh, "device {index} at {t} ms");
            }
        }
        // The looping motion is still moving an hour in, as the firmware plays it.
        let Posed::Joints(at) = kept.posed_at(&show, 1, 3_540_500 + 32 * 5 + 10).unwrap() else { panic!() };
        assert_eq!(at[0], 160);
        // Every block's length is the cue's own.
        let (blocks, span) = kept.blocks(&show);
        assert_eq!(blocks.len(), show.cues.len());
        for block in blocks {
            let cue = &show.cues[block.cue];
            let device = &show.devices[block.device];
            assert_eq!(block.length_ms, cue_length_ms(device, &cue.start), "{cue:?}");
        }
        assert!(span >= 3_600_000, "{span}");
    }

    #[test]
    fn a_changed_cue_or_project_is_worked_out_again() {
        let mut show = hour();
        let mut timeline = Timeline::default();
        timeline.keep_to(&show, 0);
        let before = timeline.blocks(&show).0[0];
        show.cues[0].at_ms += 100;
        timeline.keep_to(&show, 0);
        assert_eq!(timeline.blocks(&show).0[0].at_ms, before.at_ms + 100, "a moved cue");
        // A project changed: its owner says so by its revision.
        show.devices[0].project.servo.actions[0].steps[0] = Step::new(1, 90, 300);
        timeline.keep_to(&show, 0);
        assert_eq!(timeline.blocks(&show).0[0].length_ms, before.length_ms, "the same revision: kept");
        timeline.keep_to(&show, 1);
        let now = cue_length_ms(&show.devices[0], &Start::Macro(1));
        assert_ne!(now, before.length_ms);
        assert_eq!(timeline.blocks(&show).0[0].length_ms, now, "a new revision: worked out again");
    }
}

#[cfg(test)]
mod at_tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use crate::project::Step;
    use crate::project::plen2::{Frame, Pose};
    use crate::show::Cue;
    use crate::show::Place;

    fn show() -> Show {
        let mut pose = Pose::default();
        pose.0[0] = 320;
        let mut show = tests::three(tests::jaw(vec![Step::new(1, 90, 100)]), vec![Frame::new(32 * 10, pose)], None);
        show.devices[2].place = Place { x_m: 1.0, y_m: 0.0, heading_deg: 90.0 };
        show.cues = vec![
            Cue { device: "skull".into(), at_ms: 1000, start: Start::Macro(1) },
            Cue { device: "plen".into(), at_ms: 0, start: Start::Slot(2) },
            Cue {
                device: "base".into(),
                at_ms: 0,
                start: Start::Drive { speed_m_s: 0.5, turn_deg_s: 0.0, for_ms: 2000 },
            },
            Cue {
                device: "base".into(),
                at_ms: 3000,
                start: Start::Drive { speed_m_s: 0.0, turn_deg_s: 90.0, for_ms: 1000 },
            },
        ];
        show
    }

    #[test]
    fn a_servo_board_is_home_before_its_cue_then_follows_its_macro() {
        let show = show();
        let angle = |t| match posed_at(&show, 0, t).unwrap() {
            Posed::Servos(angles) => angles[&1],
            other => panic!("{other:?}"),
        };
        assert!((angle(500) - 0.0).abs() < 1e-9, "home before its cue");
        assert!((angle(1500) - 45.0).abs() < 1e-6, "half way through the 1 s step: {}", angle(1500));
        assert!((angle(5000) - 90.0).abs() < 1e-9, "held at the end");
    }

    #[test]
    fn a_plen2_follows_the_firmware_s_cycles_and_a_base_its_drives() {
        let show = show();
        let Posed::Joints(values) = posed_at(&show, 1, 5 * 32 + 20).unwrap() else { panic!() };
        assert_eq!(values[0], 160, "half of 32.0° after 5 of 10 cycles");
        let Posed::Joints(values) = posed_at(&show, 1, 60_000).unwrap() else { panic!() };
        assert_eq!(values[0], 320, "held at its last frame");
        let place = |t| match posed_at(&show, 2, t).unwrap() {
            Posed::Base(place) => place,
            other => panic!("{other:?}"),
        };
        // Heading 90°: 0.5 m/s along +y for 2 s, then still, then a quarter turn in place.
        let at = place(1000);
        assert!((at.x_m - 1.0).abs() < 1e-9 && (at.y_m - 0.5).abs() < 1e-9, "{at:?}");
        let at = place(2500);
        assert!((at.y_m - 1.0).abs() < 1e-9, "stopped after its 2 s: {at:?}");
        let at = place(9000);
        assert!((at.heading_deg - 180.0).abs() < 1e-9 && (at.y_m - 1.0).abs() < 1e-9, "{at:?}");
        assert!(posed_at(&show, 3, 0).is_none());
    }
}
