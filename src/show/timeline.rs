//! What each device of a show does over time, worked out once for the show
//! as it stands and looked up after: how long each cue keeps its device busy
//! (the lanes' blocks), each servo macro's trace, each PLEN2 motion's
//! playback and where each base's drives have taken it by each cue. A frame
//! then costs what it shows, not the show's length: an hour-long show of
//! four devices draws as fast as a minute's (`benches/ui.rs` measures it).
//!
//! Every answer is the one [`super::at`] and [`super::play::cue_length_ms`]
//! give: they are worked out by the same functions, once.

use std::collections::HashMap;
use std::hash::{Hash, Hasher};

use super::at::Axis;
use super::at::{Now, Posed, arc, driving_at, hold, trace_pose};
use super::{Place, Show, Start};
use crate::device::plen2::playback::{self, DEVICE_IDS, Playback, StoredMotions};
use crate::project::{Family, Project, Run, Trajectories, times_sorted};

/// The longest a motion is played for its length, ms (a motion that loops forever: ten minutes).
const LONGEST_MOTION_MS: f64 = 600_000.0;
/// The longest a servo macro is traced, ms: an hour.
const LONGEST_CUE_MS: f64 = 3_600_000.0;

/// The device at `index` at `t_ms` of the show (`None`: no such device).
/// (The show window keeps a [`Timeline`]: the same answer, worked out once.)
pub fn posed_at(show: &Show, index: usize, t_ms: u64) -> Option<Posed> {
    Timeline::default().posed_at(show, index, t_ms)
}

/// The device at `index` at `t_ms`, as its board follows it; `held`: an
/// axis of it held at a value (degrees), the pass being recorded.
pub fn now_at(show: &Show, index: usize, t_ms: u64, held: Option<(Axis, f64)>) -> Option<Now> {
    let device = show.devices.get(index)?;
    if device.project.family == Family::Rflex {
        return Some(Now::Driving(driving_at(show, &device.name, t_ms)));
    }
    let mut posed = posed_at(show, index, t_ms)?;
    if let Some((axis, value)) = held {
        hold(&mut posed, axis, value);
    }
    Some(Now::Posed(posed))
}

/// How long a cue keeps its device busy, ms, from the device's project.
/// (The show window keeps a [`Timeline`]: the same answer, worked out once.)
pub fn cue_length_ms(device: &super::Device, start: &Start) -> u64 {
    let ms = match *start {
        Start::Macro(id) => macro_trace(device, id).map_or(0.0, |(_, end)| end),
        Start::Slot(slot) => motion_playback(device, slot, longest_motion_cycles()).duration_ms(),
        Start::Drive { for_ms, .. } => return for_ms,
        Start::Family(_) => return family_length_ms(device, start),
    };
    whole_ms(ms)
}

/// A family's part of the show's timeline, for a family added since the
/// first three (theirs are worked out here), registered by the family beside
/// its show stage (`inventory::submit!`).
#[derive(Debug)]
pub struct FamilyTimeline {
    /// The family.
    pub family: Family,
    /// Where a device holding `project` is `since_ms` after its latest cue
    /// started `start` (`None`: before its first cue, at home).
    pub posed: fn(&Project, Option<(&Start, u64)>) -> Posed,
    /// How long a cue keeps a device holding `project` busy, ms.
    pub length_ms: fn(&Project, &Start) -> u64,
}

inventory::collect!(FamilyTimeline);

/// `family`'s part of the timeline, if it registered one.
fn family_timeline(family: Family) -> Option<&'static FamilyTimeline> {
    inventory::iter::<FamilyTimeline>.into_iter().find(|entry| entry.family == family)
}

/// How long a cue of a family added since the first three keeps its device busy, as the family says.
fn family_length_ms(device: &super::Device, start: &Start) -> u64 {
    family_timeline(device.project.family).map_or(0, |timeline| (timeline.length_ms)(&device.project, start))
}

/// A length in ms, whole (a part of one counts as one).
fn whole_ms(ms: f64) -> u64 {
    // Non-negative, under an hour.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let whole = ms.max(0.0).ceil() as u64;
    whole
}

/// A servo board's macro traced as the board plays it (at most an hour), and when it ends; none: it does not trace.
fn macro_trace(device: &super::Device, macro_id: i32) -> Option<(Trajectories, f64)> {
    if device.project.family != Family::Servo {
        return None;
    }
    crate::project::trace(&device.project.servo, Run::Macro { macro_id }, LONGEST_CUE_MS).ok()
}

/// A PLEN2's motion in `slot` played from home, at most `cycles` long (plen2.md §6).
fn motion_playback(device: &super::Device, slot: u8, cycles: usize) -> Playback {
    if device.project.family != Family::Plen2 {
        return Playback { from: [0; DEVICE_IDS], cycles: Vec::new(), frames: Vec::new(), ended: true };
    }
    let stored = StoredMotions::new(&device.project.plen2);
    playback::play(&stored, slot, [0; DEVICE_IDS], cycles)
}

/// The most cycles a cue's motion is followed for its length.
fn longest_motion_cycles() -> usize {
    // Cycle counts from a bounded time.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let cycles = (LONGEST_MOTION_MS / Playback::CYCLE_MS) as usize;
    cycles
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

/// A servo macro's trace, when it ends, and whether its times never go back.
type Traced = (Trajectories, f64, bool);

/// A PLEN2 motion's playback as far as it was asked for.
#[derive(Debug)]
struct Played {
    playback: Playback,
    asked: usize,
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
    /// Each device's cues: (start ms, cue index), by start.
    cues: HashMap<usize, Vec<(u64, usize)>>,
    /// Each servo macro's trace, its end, and whether its times never go back (none: it does not trace).
    traces: HashMap<(usize, i32), Option<Traced>>,
    /// Each PLEN2 motion's playback from home.
    plays: HashMap<(usize, u8), Played>,
    /// Each base's place as each of its cues starts, in its cues' order.
    places: HashMap<usize, Vec<Place>>,
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
        match cue.start {
            Start::Macro(id) => (0u8, i64::from(id)).hash(&mut hasher),
            Start::Slot(slot) => (1u8, i64::from(slot)).hash(&mut hasher),
            Start::Drive { speed_m_s, turn_deg_s, for_ms } => {
                (2u8, speed_m_s.to_bits(), turn_deg_s.to_bits(), for_ms).hash(&mut hasher);
            }
            Start::Family(cue) => (3u8, cue.kind, cue.value.to_bits()).hash(&mut hasher),
        }
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
                let length_ms = self.length_ms(show, device, cue.start);
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

    /// How long `start` keeps device `device` busy, ms (as [`super::play::cue_length_ms`]).
    fn length_ms(&mut self, show: &Show, device: usize, start: Start) -> u64 {
        let ms = match start {
            Start::Macro(id) => self.trace(show, device, id).map_or(0.0, |(_, end, _)| *end),
            Start::Slot(slot) => {
                let cycles = longest_motion_cycles();
                self.playback(show, device, slot, cycles).map_or(0.0, Playback::duration_ms)
            }
            Start::Drive { for_ms, .. } => return for_ms,
            Start::Family(_) => return show.devices.get(device).map_or(0, |owner| family_length_ms(owner, &start)),
        };
        whole_ms(ms)
    }

    fn trace(&mut self, show: &Show, device: usize, macro_id: i32) -> Option<&Traced> {
        let entry = self.traces.entry((device, macro_id)).or_insert_with(|| {
            let (trajectories, end) = macro_trace(show.devices.get(device)?, macro_id)?;
            let sorted = times_sorted(&trajectories);
            Some((trajectories, end, sorted))
        });
        entry.as_ref()
    }

    /// The PLEN2 motion's playback, at least `cycles` long unless it ended by itself.
    fn playback(&mut self, show: &Show, device: usize, slot: u8, cycles: usize) -> Option<&Playback> {
        let owner = show.devices.get(device)?;
        if owner.project.family != Family::Plen2 {
            return None;
        }
        let played = self
            .plays
            .entry((device, slot))
            .or_insert_with(|| Played { playback: motion_playback(owner, slot, cycles), asked: cycles });
        if played.asked < cycles && !played.playback.ended {
            // Asked past what was played: twice as far (a scrub moving on costs a replay now and then).
            let asked = cycles.max(played.asked * 2);
            *played = Played { playback: motion_playback(owner, slot, asked), asked };
        }
        Some(&played.playback)
    }

    /// Device `index`'s cues, by start.
    fn cues_of(&mut self, show: &Show, index: usize) -> &[(u64, usize)] {
        self.cues.entry(index).or_insert_with(|| {
            let name = show.devices.get(index).map(|device| device.name.as_str()).unwrap_or_default();
            let mut cues: Vec<(u64, usize)> = show
                .cues
                .iter()
                .enumerate()
                .filter(|(_, cue)| cue.device == name)
                .map(|(i, cue)| (cue.at_ms, i))
                .collect();
            cues.sort_by_key(|&(at, _)| at);
            cues
        })
    }

    /// The device at `index` at `t_ms` of the show, as [`super::at::posed_at`] has it.
    pub fn posed_at(&mut self, show: &Show, index: usize, t_ms: u64) -> Option<Posed> {
        let device = show.devices.get(index)?;
        let family = device.project.family;
        let cues = self.cues_of(show, index);
        // The cues started by then: the latest is what the device does.
        let started = cues.partition_point(|&(at, _)| at <= t_ms);
        let latest = started.checked_sub(1).map(|k| cues[k]);
        if family == Family::Rflex {
            return Some(Posed::Base(self.base_at(show, index, started, t_ms)));
        }
        let latest = latest.and_then(|(at, cue)| Some((at, show.cues.get(cue)?.start)));
        if let Some(timeline) = family_timeline(family) {
            let since = latest.as_ref().map(|(at_ms, start)| (start, t_ms - at_ms));
            return Some((timeline.posed)(&device.project, since));
        }
        if family == Family::Plen2 {
            let mut values = [0; DEVICE_IDS];
            if let Some((at_ms, Start::Slot(slot))) = latest {
                values = self.joints_at(show, index, slot, t_ms - at_ms);
            }
            return Some(Posed::Joints(values));
        }
        if family != Family::Servo {
            // A family with no place on the timeline (one that plays in no
            // show: `Show::problems` names it) has no pose, never a servo board's.
            return None;
        }
        let servo = &device.project.servo;
        let mut angles = servo.servos.iter().map(|s| (s.id, f64::from(s.home_deg))).collect();
        if let Some((at_ms, Start::Macro(macro_id))) = latest
            && let Some((trajectories, _, sorted)) = self.trace(show, index, macro_id)
        {
            // Whole ms of a show: exact in f64.
            #[allow(clippy::cast_precision_loss)]
            let since = (t_ms - at_ms) as f64;
            angles = trace_pose(servo, (trajectories, *sorted), since);
        }
        Some(Posed::Servos(angles))
    }

    /// A PLEN2's joints `since_ms` after its motion in `slot` started (held at its end).
    fn joints_at(&mut self, show: &Show, index: usize, slot: u8, since_ms: u64) -> [i16; DEVICE_IDS] {
        // Whole ms and cycle counts of at most an hour.
        #[allow(clippy::cast_precision_loss, clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let done = (since_ms as f64 / Playback::CYCLE_MS) as usize;
        if done == 0 {
            return [0; DEVICE_IDS];
        }
        let Some(played) = self.playback(show, index, slot, done) else { return [0; DEVICE_IDS] };
        // After `done` whole cycles, `done` steps were output (cycles[k] is step k + 1's).
        played.cycles.get(done - 1).or(played.cycles.last()).copied().unwrap_or(played.from)
    }

    /// Where a base is at `t_ms`, its first `started` cues begun: from where
    /// the cue before the latest left it, the latest's arc until now.
    fn base_at(&mut self, show: &Show, index: usize, started: usize, t_ms: u64) -> Place {
        let Some(device) = show.devices.get(index) else { return Place::default() };
        let cues = self.cues_of(show, index).to_vec();
        let places = self.places.entry(index).or_insert_with(|| {
            // The place as each cue starts: each drive runs until its time is up or the next cue starts.
            let mut places = Vec::with_capacity(cues.len());
            let mut at = device.place;
            for (k, &(start, cue)) in cues.iter().enumerate() {
                places.push(at);
                let next = cues.get(k + 1).map_or(u64::MAX, |&(later, _)| later);
                at = drive_to(at, show.cues[cue].start, start, next);
            }
            places
        });
        let Some(latest) = started.checked_sub(1) else { return device.place };
        let (start, cue) = cues[latest];
        drive_to(places[latest], show.cues[cue].start, start, t_ms)
    }
}

/// Where `start` (a drive begun at `at_ms`) takes a base from `from` by
/// `until_ms` (or by its end, if sooner); not a drive: where it is.
fn drive_to(from: Place, start: Start, at_ms: u64, until_ms: u64) -> Place {
    let Start::Drive { speed_m_s, turn_deg_s, for_ms } = start else { return from };
    let until = (at_ms + for_ms).min(until_ms);
    // Whole ms of a show: exact in f64.
    #[allow(clippy::cast_precision_loss)]
    let seconds = until.saturating_sub(at_ms) as f64 / 1000.0;
    arc(from, speed_m_s, turn_deg_s, seconds)
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

    /// Where a base is, worked out from every cue again (the way before the timeline).
    fn driven_again(show: &Show, index: usize, t_ms: u64) -> Place {
        let device = &show.devices[index];
        let mut cues: Vec<&Cue> = show.cues.iter().filter(|c| c.device == device.name && c.at_ms <= t_ms).collect();
        cues.sort_by_key(|cue| cue.at_ms);
        let mut at = device.place;
        for (k, cue) in cues.iter().enumerate() {
            let next = cues.get(k + 1).map_or(u64::MAX, |later| later.at_ms);
            at = drive_to(at, cue.start, cue.at_ms, next.min(t_ms));
        }
        at
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
            let Posed::Base(place) = kept.posed_at(&show, 2, t).unwrap() else { panic!() };
            let again = driven_again(&show, 2, t);
            assert!((place.x_m - again.x_m).abs() < 1e-9 && (place.heading_deg - again.heading_deg).abs() < 1e-9);
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

    #[test]
    fn an_arc_ends_where_a_circle_says() {
        // A quarter circle of radius 1 m from the origin heading +x, turning left.
        let quarter = std::f64::consts::FRAC_PI_2;
        let end = arc(Place::default(), quarter, 90.0, 1.0);
        assert!(
            (end.x_m - 1.0).abs() < 1e-9 && (end.y_m - 1.0).abs() < 1e-9 && (end.heading_deg - 90.0).abs() < 1e-9,
            "{end:?}"
        );
    }
}
