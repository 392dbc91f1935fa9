//! Validation of the PLEN2 section, per `plen2.md`.

use std::collections::HashSet;

use super::{Location, Problem, ProblemKind, Problems, Severity};
use crate::project::plen2::{Motion, Plen2Project};
use crate::protocol::plen2::playback::cycles_for;
use crate::protocol::plen2::{
    ANGLE_LIMIT_TENTHS_DEG, MAX_FRAMES, MAX_TRANSITION_MS, MIN_TRANSITION_MS, NAME_LEN, QUEUE_LEN, SLOTS,
};

fn error(problems: &mut Problems, location: &Location, kind: ProblemKind) {
    problems.push(Problem { severity: Severity::Error, location: location.clone(), kind });
}

fn warning(problems: &mut Problems, location: &Location, kind: ProblemKind) {
    problems.push(Problem { severity: Severity::Warning, location: location.clone(), kind });
}

fn range(problems: &mut Problems, at: &Location, field: &'static str, value: i64, min: i64, max: i64) {
    if !(min..=max).contains(&value) {
        error(problems, at, ProblemKind::OutOfRange { field, value, min, max });
    }
}

/// Every problem of a PLEN2 section, in document order.
pub fn validate_plen2(project: &Plen2Project) -> Problems {
    let mut problems = Problems::new();
    let limit = i64::from(ANGLE_LIMIT_TENTHS_DEG);
    let mut joints = HashSet::new();
    for setting in &project.joints {
        let at = Location::Joint { joint: setting.joint.name() };
        if !joints.insert(setting.joint) {
            error(&mut problems, &at, ProblemKind::DuplicateJoint);
        }
        range(&mut problems, &at, "min", setting.min_tenths_deg.into(), -limit, limit);
        range(&mut problems, &at, "max", setting.max_tenths_deg.into(), -limit, limit);
        range(
            &mut problems,
            &at,
            "home",
            setting.home_tenths_deg.into(),
            setting.min_tenths_deg.into(),
            setting.max_tenths_deg.into(),
        );
    }
    let slots: HashSet<u8> = project.motions.iter().map(|motion| motion.slot).collect();
    let mut seen = HashSet::new();
    for motion in &project.motions {
        motion_problems(&mut problems, motion, &slots, &mut seen);
    }
    for (index, list) in project.play_lists.iter().enumerate() {
        let at = Location::PlayList { index: index + 1, name: list.name.clone() };
        range(
            &mut problems,
            &at,
            "entries",
            i64::try_from(list.entries.len()).unwrap_or(i64::MAX),
            1,
            QUEUE_LEN as i64,
        );
        for entry in &list.entries {
            if !slots.contains(&entry.slot) {
                problems.push(Problem {
                    severity: Severity::Warning,
                    location: at.clone(),
                    kind: ProblemKind::MissingMotion { slot: entry.slot },
                });
            }
        }
    }
    problems
}

fn motion_problems(problems: &mut Problems, motion: &Motion, slots: &HashSet<u8>, seen: &mut HashSet<u8>) {
    let at = Location::Motion { slot: motion.slot, name: motion.name.clone() };
    range(problems, &at, "slot", motion.slot.into(), 0, i64::from(SLOTS) - 1);
    if !seen.insert(motion.slot) {
        error(problems, &at, ProblemKind::DuplicateSlot { slot: motion.slot });
    }
    if motion.name.len() > NAME_LEN {
        error(problems, &at, ProblemKind::NameTooLong { bytes: motion.name.len(), max: NAME_LEN });
    }
    if !motion.name.bytes().all(|byte| (0x20..0x7f).contains(&byte)) {
        error(problems, &at, ProblemKind::NameNotAscii);
    }
    let frames = motion.frames.len();
    if frames == 0 {
        error(problems, &at, ProblemKind::NoFrames);
    }
    range(problems, &at, "frames", i64::try_from(frames).unwrap_or(i64::MAX), 1, MAX_FRAMES as i64);
    if let Some(range) = motion.loop_range
        && (range.begin_frame > range.end_frame || usize::from(range.end_frame) >= frames)
    {
        error(
            problems,
            &at,
            ProblemKind::BadLoopRange { begin_frame: range.begin_frame, end_frame: range.end_frame, frames },
        );
    }
    if motion.loop_range.is_some_and(|range| range.count == 0) {
        warning(problems, &at, ProblemKind::LoopRunsForever);
    }
    match motion.jump_slot {
        // It cannot be what was meant: an error, so import needs --force.
        Some(jump) if jump >= SLOTS => error(problems, &at, ProblemKind::JumpBeyondSlots { slot: jump }),
        Some(jump) if !slots.contains(&jump) => warning(problems, &at, ProblemKind::MissingMotion { slot: jump }),
        _ => {}
    }
    let limit = 2 * i64::from(ANGLE_LIMIT_TENTHS_DEG);
    for (index, frame) in motion.frames.iter().enumerate() {
        let at = Location::Frame { slot: motion.slot, name: motion.name.clone(), frame: index + 1 };
        let transition_ms = frame.transition_ms;
        match (cycles_for(transition_ms), index) {
            // plen2.md §6: the first frame of `$PM` divides by zero; a later one is skipped.
            (0, 0) => error(problems, &at, ProblemKind::FirstFrameZeroCycles { transition_ms }),
            (0, _) => warning(problems, &at, ProblemKind::FrameSkipped { transition_ms }),
            _ => range(
                problems,
                &at,
                "transition_ms",
                transition_ms.into(),
                MIN_TRANSITION_MS.into(),
                MAX_TRANSITION_MS.into(),
            ),
        }
        for joint in crate::project::plen2::Joint::ALL {
            // Named by its joint: `left_knee_pitch 2000 is outside -1800..=1800`.
            range(problems, &at, joint.name(), frame.values_tenths_deg.get(joint).into(), -limit, limit);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::project::plen2::{Frame, Pose};

    #[test]
    fn a_short_transition_is_named_with_its_motion_and_frame() {
        let frame = Frame::new(100, Pose::default());
        let mut motion =
            Motion { slot: 70, name: "Walk Forward".into(), frames: vec![frame; 3], loop_range: None, jump_slot: None };
        motion.frames[2].transition_ms = 9000;
        let project = Plen2Project { motions: vec![motion], ..Plen2Project::default() };
        let problems = validate_plen2(&project);
        let texts: Vec<String> = problems.iter().map(ToString::to_string).collect();
        assert_eq!(texts, ["error: motion 70 \"Walk Forward\", frame 3: transition_ms 9000 is outside 32..=8191"]);
    }

    /// plen2.md §6: what the robot really does with these motions, said by check.
    #[test]
    fn motions_the_robot_plays_unlike_their_file_are_said_so() {
        let frame = Frame::new(100, Pose::default());
        let motion =
            |slot: u8| Motion { slot, name: "M".into(), frames: vec![frame; 3], loop_range: None, jump_slot: None };
        let mut forever = motion(1);
        forever.loop_range = Some(crate::project::plen2::LoopRange { begin_frame: 0, end_frame: 1, count: 0 });
        let mut beyond = motion(2);
        beyond.jump_slot = Some(90);
        let mut first = motion(3);
        first.frames[0].transition_ms = 20;
        let mut later = motion(4);
        later.frames[1].transition_ms = 8192;
        let project = Plen2Project { motions: vec![forever, beyond, first, later], ..Plen2Project::default() };
        let texts: Vec<String> = validate_plen2(&project).iter().map(ToString::to_string).collect();
        assert_eq!(
            texts,
            [
                "warning: motion 1 \"M\": loop count 0 runs forever: the robot counts it down to 255 (give 1 for two passes, 255 to say forever)",
                "error: motion 2 \"M\": jump to slot 90: the robot has slots 0..=89, so it replays this motion forever instead",
                "error: motion 3 \"M\", frame 1: transition_ms 20 is 0 cycles of 32 ms: as the first frame the robot divides by zero (what it does is undefined); give 32..=8191",
                "warning: motion 4 \"M\", frame 2: transition_ms 8192 is 0 cycles of 32 ms: the robot skips this frame (its pose is never shown, the next frame starts from it)",
            ]
        );
    }
}
