//! Record passes, the puppeteer's way: one axis (a servo, a PLEN2 joint)
//! recorded while the show's sound and every other track play, then the
//! next — mouth first, then head, then arms. Every pass of a device is
//! joined into one macro (servo board: its actions, each servo on its own
//! interval) or one motion (PLEN2) fitted within a tolerance, started by one
//! cue at the first pass's start; joining again replaces what the passes
//! made before, so each pass stays its own step to undo. What a pass may
//! record on a device, and how its passes join, are its family's to say
//! (`show::family::Records`, beside its show stage).

use std::collections::BTreeMap;

use std::ops::RangeInclusive;

use super::family::{Capability, Lacks};
use super::{Cue, Show, Start};
use crate::project::{Family, Project};

pub use super::at::Axis;

/// One recorded pass: a device's axis, in degrees, at times of the show (ms).
#[derive(Clone, Debug, PartialEq)]
pub struct Pass {
    /// The device, by name.
    pub device: String,
    /// What was moved.
    pub axis: Axis,
    /// (show time ms, degrees), in time order.
    pub samples: Vec<(u64, f64)>,
}

/// What a device's passes made in its project, replaced when they join again.
#[derive(Clone, Debug, PartialEq)]
pub struct Made {
    /// What its cue starts: the macro or the motion the passes became.
    pub start: Start,
    /// What else was added to run it (a servo board's actions), by id.
    pub parts: Vec<i32>,
    /// Whether its moves are steps (a servo board) or frames (a PLEN2).
    pub moves_are: Moves,
}

/// What a device's moves are called.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Moves {
    /// Steps, each servo on its own interval (a servo board's actions).
    Steps,
    /// Frames of every joint (a PLEN2's motion).
    Frames,
}

/// How a join went.
#[derive(Clone, Debug, PartialEq)]
pub struct Joined {
    /// What the passes made.
    pub made: Made,
    /// Steps (servo board) or frames (PLEN2).
    pub moves: usize,
    /// The largest distance from a recorded sample, degrees.
    pub max_error_deg: f64,
    /// The tolerance, degrees (widened past 1° when a PLEN2's 20 frames needed it).
    pub tolerance_deg: f64,
}

/// Why passes could not be joined.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum JoinError {
    /// The show has no such device.
    #[error("{0} is not a device of this show: pick one of its servo boards or PLEN2s to record a pass of")]
    NoDevice(String),
    /// The device's family records no passes (a base), named.
    #[error("{device}: {lacks}; pick another device's axis")]
    Cannot {
        /// The device.
        device: String,
        /// Its family, and what it lacks.
        lacks: Lacks,
    },
    /// Fewer than two samples.
    #[error("the pass is too short to fit: record for longer")]
    TooShort,
    /// Longer than a PLEN2 motion's 20 frames hold at any tolerance.
    #[error("{0}'s passes last too long for one motion of 20 frames: record shorter passes")]
    TooLong(String),
    /// No slot left on the PLEN2.
    #[error("{0} has no free motion slot left: remove a motion it does not need from its project, then record again")]
    NoSlot(String),
}

/// What record passes make on a device of a family, registered by the
/// family beside its show stage (`inventory::submit!`).
#[derive(Debug)]
pub struct FamilyPasses {
    /// The family.
    pub family: Family,
    /// The axes a pass may record, captioned as the show window lists them,
    /// each with the range it moves in (degrees).
    pub axes: fn(&Project) -> Vec<Recordable>,
    /// Joins the passes (the latest of each axis) over `span` (show ms) into
    /// the project of the device called `device`: what they made, and how.
    pub join: Join,
    /// Takes out of the project what passes made before.
    pub forget: fn(&mut Project, &Made),
}

/// An axis a pass may record: the axis, its caption, the range it moves in (degrees).
pub type Recordable = (Axis, String, RangeInclusive<f64>);

/// Joins the passes into a device's project: the project, the latest pass
/// of each axis, their span (show ms), the device's name.
pub type Join = fn(&mut Project, &Latest<'_>, (u64, u64), &str) -> Result<Joined, JoinError>;

/// The latest pass of each axis of a device.
pub type Latest<'a> = BTreeMap<Axis, &'a Pass>;

inventory::collect!(FamilyPasses);

/// What record passes make on `family`'s devices, or that it records none (named).
pub fn of(family: Family) -> Result<&'static FamilyPasses, Lacks> {
    inventory::iter::<FamilyPasses>
        .into_iter()
        .find(|entry| entry.family == family)
        .ok_or(Lacks { family, lacks: Capability::Record })
}

/// The tolerance passes are fitted within, degrees.
pub const TOLERANCE_DEG: f64 = 1.0;

/// Joins every pass of `device` into its project (replacing what `before`
/// made) and cues it at the first pass's start.
pub fn join(show: &mut Show, passes: &[Pass], device: &str, before: Option<&Made>) -> Result<Joined, JoinError> {
    let index = show.devices.iter().position(|d| d.name == device).ok_or_else(|| JoinError::NoDevice(device.into()))?;
    let mine: Vec<&Pass> = passes.iter().filter(|pass| pass.device == device && pass.samples.len() >= 2).collect();
    let from = mine.iter().filter_map(|pass| pass.samples.first()).map(|s| s.0).min().ok_or(JoinError::TooShort)?;
    let to = mine.iter().filter_map(|pass| pass.samples.last()).map(|s| s.0).max().ok_or(JoinError::TooShort)?;
    // The latest pass of each axis.
    let mut axes: BTreeMap<Axis, &Pass> = BTreeMap::new();
    for pass in &mine {
        axes.insert(pass.axis, pass);
    }
    let family = show.devices[index].project.family;
    let records = of(family).map_err(|lacks| JoinError::Cannot { device: device.into(), lacks })?;
    forget(show, index, before);
    let joined = (records.join)(&mut show.devices[index].project, &axes, (from, to), device)?;
    show.cues.push(Cue { device: device.into(), at_ms: from, start: joined.made.start });
    Ok(joined)
}

/// Takes what passes made before out of the device's project (as its family
/// made it), and its cues.
fn forget(show: &mut Show, index: usize, before: Option<&Made>) {
    let Some(made) = before else { return };
    let device = &mut show.devices[index];
    if let Ok(records) = of(device.project.family) {
        (records.forget)(&mut device.project, made);
    }
    let name = device.name.clone();
    show.cues.retain(|cue| !(cue.device == name && cue.start == made.start));
}

/// Each axis's value at show time `t_ms`: its pass's samples joined by
/// lines, held before its first and after its last.
fn value_at(pass: &Pass, t_ms: f64) -> f64 {
    let samples = &pass.samples;
    let after = samples.partition_point(|&(at, _)| (at as f64) <= t_ms);
    match (after.checked_sub(1).map(|i| samples[i]), samples.get(after)) {
        (Some((t0, v0)), Some(&(t1, v1))) if t1 > t0 => v0 + (v1 - v0) * (t_ms - t0 as f64) / (t1 - t0) as f64,
        (Some((_, v)), _) | (None, Some(&(_, v))) => v,
        (None, None) => 0.0,
    }
}

/// Rows of every axis at each board update from `from` to `to` (the first:
/// where they start), each value times `unit` — what a family's join fits.
pub fn rows(axes: &BTreeMap<Axis, &Pass>, (from, to): (u64, u64), update_ms: f64, unit: f64) -> Vec<Vec<f64>> {
    // Whole ms of a show: exact in f64; update counts of an hour at most.
    #[allow(clippy::cast_precision_loss, clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let updates = (((to - from) as f64) / update_ms).ceil().max(1.0) as usize;
    (0..=updates)
        .map(|k| {
            #[allow(clippy::cast_precision_loss)]
            let t = from as f64 + k as f64 * update_ms;
            axes.values().map(|pass| value_at(pass, t) * unit).collect()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use crate::project::{Family, Project, Run, Servo, ServoProject};

    fn servo_show() -> Show {
        let servos = vec![Servo::new(1, "mouth"), Servo::new(2, "head")];
        Show::of_one("skull", Project::servo(ServoProject { servos, ..ServoProject::default() }))
    }

    fn pass(device: &str, axis: Axis, from: u64, to: u64, curve: impl Fn(f64) -> f64) -> Pass {
        let samples = (from..=to).step_by(16).map(|t| (t, curve(t as f64 / 1000.0))).collect();
        Pass { device: device.into(), axis, samples }
    }

    /// The mouth, then the head: one macro plays both, each within 1° of its
    /// pass at every update of the board's own trace; joining again replaces it.
    #[test]
    fn passes_of_a_servo_board_join_into_one_macro_that_plays_each_within_the_tolerance() {
        let mut show = servo_show();
        let mouth = pass("skull", Axis::Servo(1), 500, 1500, |t| 40.0 * (t - 0.5));
        let head = pass("skull", Axis::Servo(2), 800, 2600, |t| 30.0 * (std::f64::consts::TAU * t / 1.8).sin());
        let first = join(&mut show, std::slice::from_ref(&mouth), "skull", None).unwrap();
        let passes = vec![mouth.clone(), head.clone()];
        let joined = join(&mut show, &passes, "skull", Some(&first.made)).unwrap();
        let project = &show.devices[0].project.servo;
        assert_eq!(project.macros.len(), 1, "the second join replaced the first");
        let Start::Macro(macro_id) = joined.made.start else { panic!("{:?}", joined.made) };
        assert_eq!(joined.made.moves_are, Moves::Steps);
        assert_eq!(project.actions.len(), joined.made.parts.len(), "the first join's actions were taken out");
        assert_eq!(show.cues, vec![Cue { device: "skull".into(), at_ms: 500, start: Start::Macro(macro_id) }]);
        let (trajectories, _) = crate::project::trace(project, Run::Macro { macro_id }, 10_000.0).unwrap();
        for t in (510..2600).step_by(10) {
            let pose = crate::project::pose_at(project, &trajectories, (t - 500) as f64);
            // Each servo within its own pass (the head comes from home before its pass begins).
            for (index, pass) in [&mouth, &head].iter().enumerate() {
                if t < pass.samples[0].0 + 10 {
                    continue;
                }
                let wanted = value_at(pass, t as f64);
                assert!(
                    (pose[index] - wanted).abs() <= TOLERANCE_DEG + 1e-9,
                    "servo {} at {t} ms: {} for {wanted}",
                    index + 1,
                    pose[index]
                );
            }
        }
        assert!(joined.max_error_deg <= TOLERANCE_DEG && joined.moves >= 2);
    }

    #[test]
    fn a_plen2_pass_becomes_a_motion_of_at_most_20_frames_in_a_free_slot() {
        let mut show = Show::of_one("plen", Project::empty(Family::Plen2));
        let arm = pass("plen", Axis::Joint(1), 0, 3000, |t| 45.0 * (std::f64::consts::TAU * t / 1.5).sin());
        let joined = join(&mut show, &[arm], "plen", None).unwrap();
        assert_eq!(joined.made, Made { start: Start::Slot(89), parts: Vec::new(), moves_are: Moves::Frames });
        let motion = &show.devices[0].project.plen2.motions[0];
        assert!((1..=20).contains(&motion.frames.len()), "{}", motion.frames.len());
        assert!(joined.max_error_deg <= joined.tolerance_deg + 1e-9);
        assert_eq!(show.cues[0].start, Start::Slot(89));
        assert!(show.check().is_ok());
        assert_eq!(join(&mut show, &[], "plen", None), Err(JoinError::TooShort));
        assert_eq!(join(&mut show, &[], "nobody", None), Err(JoinError::NoDevice("nobody".into())));
    }

    /// A base records no passes: refused naming its family, and nothing is
    /// added to its project or cued.
    #[test]
    fn a_device_whose_family_records_no_passes_is_refused_by_name() {
        let mut show = Show::of_one("base", Project::empty(Family::Rflex));
        let before = show.clone();
        let drive = pass("base", Axis::Servo(1), 0, 1000, |t| t);
        let refused = join(&mut show, &[drive], "base", None).unwrap_err();
        assert_eq!(refused.to_string(), "base: an rFLEX base cannot record a pass; pick another device's axis");
        assert_eq!(show, before);
    }
}
