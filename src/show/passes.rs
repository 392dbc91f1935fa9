//! Record passes, the puppeteer's way: one axis (a servo, a PLEN2 joint)
//! recorded while the show's sound and every other track play, then the
//! next — mouth first, then head, then arms. Every pass of a device is
//! joined into one macro (servo board: its actions, each servo on its own
//! interval) or one motion (PLEN2) fitted within a tolerance, started by one
//! cue at the first pass's start; joining again replaces what the passes
//! made before, so each pass stays its own step to undo.

use std::collections::BTreeMap;

use super::{Cue, Show, Start};
use crate::authoring::fit::{self, Budget, FitError, Plen2Board, ServoBoard};
use crate::authoring::fitted::{self, PLEN2_UPDATE_MS, SERVO_UPDATE_MS};
use crate::project::plen2::{JOINTS, MAX_FRAMES, Motion};
use crate::project::{Family, next_free_id};

/// What a pass moves.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Axis {
    /// A servo board's servo, by id.
    Servo(u8),
    /// A PLEN2 joint, by device id (0..18).
    Joint(u8),
}

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
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Made {
    /// A servo board's actions and the macro running them.
    Servo {
        /// The actions' ids.
        actions: Vec<i32>,
        /// The macro's id.
        macro_id: i32,
    },
    /// A PLEN2's motion, by slot.
    Plen2 {
        /// Its slot.
        slot: u8,
    },
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
    /// The show has no such device, or it is a base.
    #[error("{0} is not a servo board or a PLEN2 of this show: pick one of those to record a pass of")]
    NoDevice(String),
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
    forget(show, index, before);
    let joined = if family == Family::Servo {
        join_servo(show, index, &axes, (from, to))?
    } else if family == Family::Plen2 {
        join_plen2(show, index, &axes, (from, to))?
    } else {
        return Err(JoinError::NoDevice(device.into()));
    };
    let start = match joined.made {
        Made::Servo { macro_id, .. } => Start::Macro(macro_id),
        Made::Plen2 { slot } => Start::Slot(slot),
    };
    show.cues.push(Cue { device: device.into(), at_ms: from, start });
    Ok(joined)
}

/// Takes what passes made before out of the device's project, and its cues.
fn forget(show: &mut Show, index: usize, before: Option<&Made>) {
    let Some(made) = before else { return };
    let device = &mut show.devices[index];
    let name = device.name.clone();
    match made {
        Made::Servo { actions, macro_id } => {
            device.project.servo.actions.retain(|action| !actions.contains(&action.id));
            device.project.servo.macros.retain(|m| m.id != *macro_id);
            show.cues.retain(|cue| !(cue.device == name && cue.start == Start::Macro(*macro_id)));
        }
        Made::Plen2 { slot } => {
            device.project.plen2.motions.retain(|m| m.slot != *slot);
            show.cues.retain(|cue| !(cue.device == name && cue.start == Start::Slot(*slot)));
        }
    }
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

/// Rows of every axis at each board update from `from` to `to` (the first: where they start).
fn rows(axes: &BTreeMap<Axis, &Pass>, (from, to): (u64, u64), update_ms: f64, unit: f64) -> Vec<Vec<f64>> {
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

fn join_servo(
    show: &mut Show,
    index: usize,
    axes: &BTreeMap<Axis, &Pass>,
    span: (u64, u64),
) -> Result<Joined, JoinError> {
    let ids: Vec<u8> =
        axes.keys().filter_map(|axis| if let Axis::Servo(id) = axis { Some(*id) } else { None }).collect();
    let rows = rows(axes, span, SERVO_UPDATE_MS, 1.0);
    let rest = rows.get(1..).filter(|rest| !rest.is_empty()).ok_or(JoinError::TooShort)?;
    let project = &mut show.devices[index].project.servo;
    // From where the servos are when the cue starts it: home (a board's start of a show).
    let home = |id: &u8| project.servos.iter().find(|s| s.id == *id).map_or(0, |s| i32::from(s.home_deg));
    let start: Vec<i32> = ids.iter().map(home).collect();
    let fitted = fit::fit(&ServoBoard, &start, rest, TOLERANCE_DEG);
    let macro_id = next_free_id(project.macros.iter().map(|m| m.id));
    let mut actions = fitted::servo_actions(&fitted, &ids, 0, "pass");
    for action in &mut actions {
        action.id = next_free_id(project.actions.iter().map(|known| known.id));
        project.actions.push(action.clone());
    }
    project.macros.push(fitted::macro_running(macro_id, "Recorded passes", &actions));
    let made = Made::Servo { actions: actions.iter().map(|a| a.id).collect(), macro_id };
    Ok(Joined { made, moves: actions.len(), max_error_deg: fitted.max_error, tolerance_deg: TOLERANCE_DEG })
}

fn join_plen2(
    show: &mut Show,
    index: usize,
    axes: &BTreeMap<Axis, &Pass>,
    span: (u64, u64),
) -> Result<Joined, JoinError> {
    let device = &mut show.devices[index];
    let name = device.name.clone();
    // All 18 joints, the recorded ones from their passes, the others at home.
    let recorded = rows(axes, span, PLEN2_UPDATE_MS, 10.0);
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
    let used: Vec<u8> = device.project.plen2.motions.iter().map(|m| m.slot).collect();
    let slot = (0..90u8).rev().find(|slot| !used.contains(slot)).ok_or(JoinError::NoSlot(name))?;
    let frames = fitted::plen2_frames(&fitted);
    let moves = frames.len();
    device.project.plen2.motions.push(Motion {
        slot,
        name: "passes".into(),
        frames,
        loop_range: None,
        jump_slot: None,
    });
    device.project.plen2.motions.sort_by_key(|m| m.slot);
    Ok(Joined {
        made: Made::Plen2 { slot },
        moves,
        max_error_deg: fitted.max_error / 10.0,
        tolerance_deg: tolerance / 10.0,
    })
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use crate::project::{Project, Run, Servo, ServoProject};

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
        let Made::Servo { macro_id, ref actions } = joined.made else { panic!() };
        assert_eq!(project.actions.len(), actions.len());
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
        let Made::Plen2 { slot } = joined.made else { panic!() };
        assert_eq!(slot, 89);
        let motion = &show.devices[0].project.plen2.motions[0];
        assert!((1..=20).contains(&motion.frames.len()), "{}", motion.frames.len());
        assert!(joined.max_error_deg <= joined.tolerance_deg + 1e-9);
        assert_eq!(show.cues[0].start, Start::Slot(89));
        assert!(show.check().is_ok());
        assert_eq!(join(&mut show, &[], "plen", None), Err(JoinError::TooShort));
        assert_eq!(join(&mut show, &[], "nobody", None), Err(JoinError::NoDevice("nobody".into())));
    }
}
