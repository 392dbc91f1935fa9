//! Eased moves baked into the straight moves a board plays. A PLEN2 frame
//! with a curve becomes as many straight frames as keep the robot's own
//! playback (16.16 steps per 32.768 ms cycle, plen2.md §6) within the
//! tolerance of the curve at every cycle; together they take the frame's
//! cycles. A linear frame is kept exactly as it is. When a motion's baked
//! frames would not fit in the 20 a motion holds, the tolerance is widened
//! (in tenths of a degree) until they do, and the bake says so.
//!
//! Where a frame starts: frame 0 from the frame buffer at power-up (every
//! joint at 0, as `trajectory` plays it), every other frame from the one
//! before it. A loop's first frame is baked for its first pass; on later
//! passes the robot approaches it from the loop's last frame, so an eased
//! first frame of a loop bends the same way but from there.

use super::fit::{self, Plen2Board};
use super::fitted;
use crate::project::Easing;
use crate::project::plen2::{Frame, JOINTS, LoopRange, MAX_FRAMES, Motion};
use crate::protocol::plen2::playback::cycles_for;

/// The tolerance a curve is baked to unless the budget is short: 1°, in tenths.
pub const DEFAULT_TOLERANCE_TENTHS: f64 = 10.0;

/// A motion as the robot will store it, and what baking cost.
#[derive(Clone, Debug, PartialEq)]
pub struct Baked {
    /// Only straight frames; loop and jump moved to the baked indices.
    pub motion: Motion,
    /// For each baked frame, the authored frame it comes from.
    pub source: Vec<usize>,
    /// The tolerance used, tenths (above the one asked when the budget was short).
    pub tolerance_tenths: f64,
    /// The largest distance between the curve and the robot's output at any cycle, tenths.
    pub max_error_tenths: f64,
}

impl Baked {
    /// True when the tolerance had to be widened to fit the frames a motion holds.
    pub fn widened(&self, asked_tenths: f64) -> bool {
        self.tolerance_tenths > asked_tenths
    }
}

/// `motion` baked at `tolerance_tenths`, widened when its frames would not
/// fit in [`MAX_FRAMES`] (a motion already over 20 authored frames is baked
/// as straight as it can be and left for `check` to refuse).
pub fn bake_plen2(motion: &Motion, tolerance_tenths: f64) -> Baked {
    if motion.frames.iter().all(|frame| frame.easing.is_linear()) {
        return Baked {
            motion: motion.clone(),
            source: (0..motion.frames.len()).collect(),
            tolerance_tenths,
            max_error_tenths: 0.0,
        };
    }
    let baked = bake_at(motion, tolerance_tenths);
    if baked.motion.frames.len() <= MAX_FRAMES {
        return baked;
    }
    // A wider tolerance never takes more frames; the widest takes one per frame.
    let (mut low, mut high) = (0u32, 3600u32);
    let mut best = bake_at(motion, tolerance_tenths + f64::from(high));
    if best.motion.frames.len() > MAX_FRAMES {
        return best;
    }
    while high - low > 1 {
        let middle = low + (high - low) / 2;
        let tried = bake_at(motion, tolerance_tenths + f64::from(middle));
        if tried.motion.frames.len() <= MAX_FRAMES {
            high = middle;
            best = tried;
        } else {
            low = middle;
        }
    }
    best
}

fn bake_at(motion: &Motion, tolerance_tenths: f64) -> Baked {
    let mut frames = Vec::new();
    let mut source = Vec::new();
    let mut max_error = 0.0_f64;
    let mut from = [0i16; JOINTS];
    for (index, frame) in motion.frames.iter().enumerate() {
        let cycles = usize::from(cycles_for(frame.transition_ms));
        if frame.easing.is_linear() || cycles <= 1 {
            frames.push(Frame::new(frame.transition_ms, frame.values_tenths_deg));
            source.push(index);
        } else {
            let (pieces, error) = eased_frames(&from, frame, cycles, tolerance_tenths);
            max_error = max_error.max(error);
            source.extend(std::iter::repeat_n(index, pieces.len()));
            frames.extend(pieces);
        }
        from = frame.values_tenths_deg.0;
    }
    let first_of = |authored: u8| source.iter().position(|&s| s == usize::from(authored));
    let last_of = |authored: u8| source.iter().rposition(|&s| s == usize::from(authored));
    let loop_range = motion.loop_range.map(|range| LoopRange {
        begin_frame: first_of(range.begin_frame).and_then(|at| u8::try_from(at).ok()).unwrap_or(range.begin_frame),
        end_frame: last_of(range.end_frame).and_then(|at| u8::try_from(at).ok()).unwrap_or(range.end_frame),
        count: range.count,
    });
    Baked {
        motion: Motion { frames, loop_range, ..motion.clone() },
        source,
        tolerance_tenths,
        max_error_tenths: max_error,
    }
}

/// The wanted value of every joint at each cycle of an eased frame from `from`.
pub fn eased_rows(from: &[i16; JOINTS], frame: &Frame, cycles: usize) -> Vec<Vec<f64>> {
    (1..=cycles)
        .map(|k| {
            // Cycle counts of at most 255: exact.
            #[allow(clippy::cast_precision_loss)]
            let along = frame.easing.at(k as f64 / cycles as f64);
            from.iter()
                .zip(&frame.values_tenths_deg.0)
                .map(|(&a, &b)| f64::from(a) + (f64::from(b) - f64::from(a)) * along)
                .collect()
        })
        .collect()
}

fn eased_frames(from: &[i16; JOINTS], frame: &Frame, cycles: usize, tolerance: f64) -> (Vec<Frame>, f64) {
    let rows = eased_rows(from, frame, cycles);
    let start: Vec<i32> = from.iter().map(|&value| i32::from(value)).collect();
    // A curve shaped on the graph takes the fewest frames (ends chosen within
    // the tolerance, the last on its key); a preset keeps its earlier frames,
    // so a project written before stores the same bytes.
    let fitted = if matches!(frame.easing, Easing::Shaped(_)) {
        fit::fit_to_key(&Plen2Board, &start, &rows, tolerance)
    } else {
        fit::fit_on_samples(&Plen2Board, &start, &rows, tolerance)
    };
    (fitted::plen2_frames(&fitted), fitted.max_error)
}

/// True when any frame of the motion has a curve.
pub fn has_curves(motion: &Motion) -> bool {
    motion.frames.iter().any(|frame| frame.easing != Easing::Linear)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::project::plen2::{Joint, Pose};

    fn pose(knee: i16, shoulder: i16) -> Pose {
        let mut pose = Pose::default();
        pose.set(Joint::LeftKneePitch, knee);
        pose.set(Joint::RightShoulderRoll, shoulder);
        pose
    }

    fn motion(frames: Vec<Frame>) -> Motion {
        Motion { slot: 3, name: "eased".into(), frames, loop_range: None, jump_slot: None }
    }

    #[test]
    fn a_motion_without_curves_is_stored_as_it_is() {
        let authored = motion(vec![Frame::new(100, pose(333, -77)), Frame::new(250, pose(-123, 45))]);
        let baked = bake_plen2(&authored, DEFAULT_TOLERANCE_TENTHS);
        assert_eq!(baked.motion, authored);
        assert!(!has_curves(&authored));
    }

    #[test]
    fn a_short_budget_widens_the_tolerance_and_moves_the_loop() {
        // 10 eased frames of 2 s swinging ±90°: at 1° each takes several pieces.
        let frames: Vec<Frame> = (0..10)
            .map(|index| {
                let mut frame = Frame::new(2048, pose(if index % 2 == 0 { 900 } else { -900 }, 0));
                frame.easing = Easing::EaseInOut;
                frame
            })
            .collect();
        let mut authored = motion(frames);
        authored.loop_range = Some(LoopRange { begin_frame: 2, end_frame: 9, count: 255 });
        let tight = bake_at(&authored, DEFAULT_TOLERANCE_TENTHS);
        assert!(tight.motion.frames.len() > MAX_FRAMES, "{}", tight.motion.frames.len());
        let baked = bake_plen2(&authored, DEFAULT_TOLERANCE_TENTHS);
        assert!(baked.widened(DEFAULT_TOLERANCE_TENTHS));
        assert!(baked.motion.frames.len() <= MAX_FRAMES);
        assert!(
            bake_at(&authored, baked.tolerance_tenths - 1.0).motion.frames.len() > MAX_FRAMES,
            "the smallest that fits"
        );
        assert!(baked.max_error_tenths <= baked.tolerance_tenths);
        let range = baked.motion.loop_range.expect("still looping");
        assert_eq!(baked.source[usize::from(range.begin_frame)], 2);
        assert_eq!(usize::from(range.begin_frame), baked.source.iter().position(|&s| s == 2).unwrap());
        assert_eq!(usize::from(range.end_frame), baked.motion.frames.len() - 1);
    }

    #[test]
    fn a_shaped_frame_takes_no_more_frames_than_its_preset_and_lands_on_its_key() {
        for preset in [Easing::EaseIn, Easing::EaseOut] {
            let mut eased = Frame::new(2048, pose(900, -450));
            eased.easing = preset;
            let mut shaped = eased;
            shaped.easing = Easing::Shaped(preset.handles());
            let after = Frame::new(500, pose(0, 0));
            let by_preset = bake_plen2(&motion(vec![eased, after]), DEFAULT_TOLERANCE_TENTHS);
            let by_handles = bake_plen2(&motion(vec![shaped, after]), DEFAULT_TOLERANCE_TENTHS);
            assert!(
                by_handles.motion.frames.len() <= by_preset.motion.frames.len(),
                "{preset:?}: {} vs {}",
                by_handles.motion.frames.len(),
                by_preset.motion.frames.len()
            );
            assert!(by_handles.max_error_tenths <= DEFAULT_TOLERANCE_TENTHS + 1e-9);
            // The last piece of the curve ends on the key, so the next frame leaves from it.
            let last_piece = by_handles.source.iter().rposition(|&s| s == 0).unwrap();
            assert_eq!(by_handles.motion.frames[last_piece].values_tenths_deg, pose(900, -450));
            // And the robot's own playback stays within 1° of the curve at every cycle.
            let moves: Vec<fit::Move> = by_handles.motion.frames[..=last_piece]
                .iter()
                .map(|frame| {
                    fit::Move::straight(
                        usize::from(cycles_for(frame.transition_ms)),
                        frame.values_tenths_deg.0.iter().map(|&v| i32::from(v)).collect(),
                    )
                })
                .collect();
            let played = fit::play(&Plen2Board, &[0; JOINTS], &moves);
            let knee = Joint::LeftKneePitch.index();
            let cycles = usize::from(cycles_for(2048));
            assert_eq!(played.len(), cycles);
            for (cycle, values) in played.iter().take(cycles).enumerate() {
                #[allow(clippy::cast_precision_loss)]
                let wanted = 900.0 * shaped.easing.at((cycle + 1) as f64 / cycles as f64);
                assert!((values[knee] - wanted).abs() <= 10.0 + 1e-9, "cycle {cycle}: {} vs {wanted}", values[knee]);
            }
        }
    }
}
