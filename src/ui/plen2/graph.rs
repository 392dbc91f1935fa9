//! A PLEN2 motion on the graph pane: a channel per joint, a key at the end
//! of every frame on the robot's clock (whole 32.768 ms cycles, from every
//! joint at 0 at power-up, as the bake and `trajectory` count), values in
//! degrees relative to home within the joint's limits, and what the robot
//! plays (the baked frames through the firmware's playback) when the motion
//! has curves. A frame holds one curve for all its joints: shaping the move
//! into one joint's key shapes that frame's move for every joint.

use crate::authoring::bake;
use crate::authoring::fitted::{PLEN2_UPDATE_MS, transition_ms};
use crate::device::plen2::playback::cycles_for;
use crate::project::plen2::{Joint, MAX_TRANSITION_MS, MIN_TRANSITION_MS, Motion, Plen2Project};
use crate::ui::graph::{Channel, GraphEdit, Key};

/// Each frame's end on the robot's clock, in whole cycles from the start.
fn ends_in_cycles(motion: &Motion) -> Vec<i64> {
    motion
        .frames
        .iter()
        .scan(0_i64, |at, frame| {
            *at += i64::from(cycles_for(frame.transition_ms));
            Some(*at)
        })
        .collect()
}

#[allow(clippy::cast_precision_loss)]
fn ms(cycles: i64) -> f64 {
    // Cycle counts of at most 20 × 255: exact.
    cycles as f64 * PLEN2_UPDATE_MS
}

/// The motion's joints as the graph draws them, and its frames' lane.
pub fn curves(project: &Plen2Project, motion: &Motion) -> (Vec<Channel>, Vec<(f64, f64, String)>) {
    let ends = ends_in_cycles(motion);
    // What the robot plays, drawn when it is not the keys' straight lines: a
    // shaped frame, or the motions a chain plays on into.
    let chained = !project.chained(motion).is_empty();
    let played = (bake::has_curves(motion) || chained).then(|| played(project, motion));
    let channels = Joint::ALL
        .into_iter()
        .map(|joint| {
            let setting = super::joints::limits(project, joint);
            let keys = motion
                .frames
                .iter()
                .zip(&ends)
                .map(|(frame, &end)| Key {
                    t_ms: ms(end),
                    value: f64::from(frame.values_tenths_deg.get(joint)) / 10.0,
                    easing: frame.easing,
                })
                .collect();
            let relative = |limit: i16| f64::from(limit - setting.home_tenths_deg) / 10.0;
            Channel {
                name: joint.name().to_string(),
                start: [0.0, 0.0],
                keys,
                limits: [relative(setting.min_tenths_deg), relative(setting.max_tenths_deg)],
                baked: played.as_ref().map(|rows| {
                    let device = usize::from(joint.device_id());
                    let mut points = vec![[0.0, 0.0]];
                    points.extend(
                        rows.iter().zip(1..).map(|(values, cycle)| [ms(cycle), f64::from(values[device]) / 10.0]),
                    );
                    points
                }),
            }
        })
        .collect();
    let lane = ends
        .iter()
        .enumerate()
        .map(|(f, &end)| (ms(end - i64::from(cycles_for(motion.frames[f].transition_ms))), ms(end), format!("#{f}")))
        .collect();
    (channels, lane)
}

/// What the robot plays of one pass of the motion's frames, cycle by cycle
/// (values by device id, tenths) — on through the motions it jumps to, as
/// one, when they end (a chain, as a followed sound is written); else this
/// motion alone, once (a loop or a jump back would run for ever).
fn played(project: &Plen2Project, motion: &Motion) -> Vec<[i16; crate::device::plen2::playback::DEVICE_IDS]> {
    use crate::device::plen2::playback::{self, StoredMotions};
    let chain = project.chained(motion);
    let ends = chain.last().is_some_and(|last| last.jump_slot.is_none() && last.loop_range.is_none())
        && chain.iter().all(|m| m.loop_range.is_none())
        && motion.loop_range.is_none();
    let motions: Vec<Motion> = if ends {
        std::iter::once(motion.clone()).chain(chain.into_iter().cloned()).collect()
    } else {
        vec![Motion { loop_range: None, jump_slot: None, ..motion.clone() }]
    };
    let cycles = 20 * 256 * motions.len();
    let stored = Plen2Project { motions, ..Plen2Project::default() };
    playback::play(&StoredMotions::new(&stored), motion.slot, [0; playback::DEVICE_IDS], cycles).cycles
}

/// `motion` with the graph's edit applied: keys moved in time retime their
/// frames (a whole number of cycles; the frame after a moved key gives up
/// the time so later keys stay, and no frame leaves 1..=255 cycles: the
/// move is cut short to the nearest that keeps them), values kept within
/// each joint's limits; a shaped move is its frame's curve.
pub fn apply(project: &Plen2Project, motion: &Motion, edit: &GraphEdit) -> Motion {
    let mut changed = motion.clone();
    match edit {
        GraphEdit::Shape { keys, easing } => {
            for &(_, f) in keys {
                if let Some(frame) = changed.frames.get_mut(f) {
                    frame.easing = *easing;
                }
            }
        }
        GraphEdit::Move { keys, dt_ms, dv_deg } => {
            // Whole cycles, as the robot counts them.
            #[allow(clippy::cast_possible_truncation)]
            let cycles = (dt_ms / PLEN2_UPDATE_MS).round() as i64;
            let frames: std::collections::BTreeSet<usize> = keys.iter().map(|&(_, f)| f).collect();
            retime(&mut changed, &frames, cycles);
            // Tenths of a degree: the cast cannot overflow an i16 range once clamped.
            #[allow(clippy::cast_possible_truncation)]
            let tenths = (dv_deg * 10.0).round() as i32;
            for &(c, f) in keys {
                let (Some(&joint), Some(frame)) = (Joint::ALL.get(c), changed.frames.get_mut(f)) else { continue };
                let setting = super::joints::limits(project, joint);
                let (low, high) = (
                    setting.min_tenths_deg - setting.home_tenths_deg,
                    setting.max_tenths_deg - setting.home_tenths_deg,
                );
                let value =
                    (i32::from(frame.values_tenths_deg.get(joint)) + tenths).clamp(i32::from(low), i32::from(high));
                frame.values_tenths_deg.set(joint, i16::try_from(value).unwrap_or(0));
            }
        }
    }
    changed
}

/// The ends of `frames` moved by `cycles` (or as near as keeps every frame's cycles in range).
fn retime(motion: &mut Motion, frames: &std::collections::BTreeSet<usize>, cycles: i64) {
    if cycles == 0 || frames.is_empty() {
        return;
    }
    let ends = ends_in_cycles(motion);
    let (fewest, most) = (i64::from(cycles_for(MIN_TRANSITION_MS)).max(1), i64::from(cycles_for(MAX_TRANSITION_MS)));
    let lengths = |by: i64| -> Vec<i64> {
        let moved: Vec<i64> =
            ends.iter().enumerate().map(|(f, &end)| if frames.contains(&f) { end + by } else { end }).collect();
        moved
            .iter()
            .scan(0, |before, &end| {
                let length = end - *before;
                *before = end;
                Some(length)
            })
            .collect()
    };
    let fits = |by: i64| lengths(by).iter().all(|length| (fewest..=most).contains(length));
    let mut by = cycles;
    while by != 0 && !fits(by) {
        by -= by.signum();
    }
    if by == 0 {
        return;
    }
    let original: Vec<i64> = lengths(0);
    for ((frame, new), old) in motion.frames.iter_mut().zip(lengths(by)).zip(original) {
        if new != old {
            frame.transition_ms = transition_ms(usize::try_from(new).unwrap_or(1));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::project::Easing;
    use crate::project::plen2::{Frame, Pose};

    fn motion() -> Motion {
        let mut pose = Pose::default();
        pose.set(Joint::LeftKneePitch, 300);
        Motion {
            slot: 1,
            name: "m".into(),
            frames: vec![Frame::new(320, pose), Frame::new(640, Pose::default()), Frame::new(320, pose)],
            loop_range: None,
            jump_slot: None,
        }
    }

    #[test]
    fn keys_sit_at_the_frames_ends_on_the_robots_clock() {
        let (channels, lane) = curves(&Plen2Project::default(), &motion());
        assert_eq!(channels.len(), 18);
        let knee = &channels[Joint::LeftKneePitch.index()];
        let times: Vec<f64> = knee.keys.iter().map(|key| key.t_ms).collect();
        assert_eq!(times, vec![10.0 * PLEN2_UPDATE_MS, 30.0 * PLEN2_UPDATE_MS, 40.0 * PLEN2_UPDATE_MS]);
        assert_eq!(knee.keys[0].value, 30.0);
        assert!(knee.baked.is_none(), "no curves: the robot plays the keys as drawn");
        assert_eq!(lane[1], (10.0 * PLEN2_UPDATE_MS, 30.0 * PLEN2_UPDATE_MS, "#1".to_string()));
    }

    #[test]
    fn a_key_moved_in_time_retimes_its_frame_and_the_next_so_later_keys_stay() {
        let project = Plen2Project::default();
        let knee = Joint::LeftKneePitch.index();
        let edit = GraphEdit::Move { keys: vec![(knee, 0)], dt_ms: 3.0 * PLEN2_UPDATE_MS + 5.0, dv_deg: 100.0 };
        let moved = apply(&project, &motion(), &edit);
        let transitions: Vec<u16> = moved.frames.iter().map(|frame| frame.transition_ms).collect();
        assert_eq!(transitions, vec![13 * 32, 17 * 32, 320]);
        // Within the factory ±90° around home (500): frames are relative to home.
        assert_eq!(moved.frames[0].values_tenths_deg.get(Joint::LeftKneePitch), 900 - 500);
        // Too far: cut to the nearest that leaves frame #1 its one cycle.
        let far = GraphEdit::Move { keys: vec![(knee, 0)], dt_ms: 100.0 * PLEN2_UPDATE_MS, dv_deg: 0.0 };
        let moved = apply(&project, &motion(), &far);
        let cycles: Vec<u8> = moved.frames.iter().map(|frame| cycles_for(frame.transition_ms)).collect();
        assert_eq!(cycles, vec![29, 1, 10]);
        // Two keys of one frame, on different joints, move it once.
        let both = GraphEdit::Move { keys: vec![(0, 2), (knee, 2)], dt_ms: -2.0 * PLEN2_UPDATE_MS, dv_deg: 0.0 };
        let moved = apply(&project, &motion(), &both);
        assert_eq!(moved.frames[2].transition_ms, 8 * 32);
        assert_eq!(moved.frames[1].transition_ms, 640, "untouched");
    }

    #[test]
    fn shaping_one_joints_move_shapes_its_frame() {
        let shaped = Easing::Shaped(crate::project::Handles::new([100, 0], [900, 1000]));
        let edit = GraphEdit::Shape { keys: vec![(3, 1)], easing: shaped };
        let moved = apply(&Plen2Project::default(), &motion(), &edit);
        assert_eq!(moved.frames[1].easing, shaped);
        assert_eq!(moved.frames[0].easing, Easing::Linear);
        let (channels, _) = curves(&Plen2Project::default(), &moved);
        assert!(channels.iter().all(|channel| channel.baked.is_some()), "a curve: what the robot plays is drawn");
    }
}
