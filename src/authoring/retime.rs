//! Retiming: a span of frames or steps played faster or slower, each time
//! scaled and kept within what the board takes.

use crate::project::Step;
use crate::project::plen2::{Frame, MAX_TRANSITION_MS, MIN_TRANSITION_MS};

/// The factor that makes a span of `current_ms` last `total_ms` (1 for an empty span).
pub fn factor_to_total(current_ms: f64, total_ms: f64) -> f64 {
    if current_ms > 0.0 && total_ms.is_finite() && total_ms > 0.0 { total_ms / current_ms } else { 1.0 }
}

/// Each frame's transition scaled by `factor`, rounded, within 32..=8191 ms.
pub fn scale_frames(frames: &mut [Frame], factor: f64) {
    for frame in frames {
        let scaled = (f64::from(frame.transition_ms) * factor).round();
        // Clamped into the u16 range first.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let scaled = scaled.clamp(f64::from(MIN_TRANSITION_MS), f64::from(MAX_TRANSITION_MS)) as u16;
        frame.transition_ms = scaled;
    }
}

/// Each step's interval scaled by `factor`, rounded, at least one 10 ms unit
/// (a step of 0 stays 0: it is a jump, not a move).
pub fn scale_steps(steps: &mut [Step], factor: f64) {
    for step in steps.iter_mut().filter(|step| step.interval_10ms > 0) {
        let scaled = (f64::from(step.interval_10ms) * factor).round();
        // Clamped into the i16 range first.
        #[allow(clippy::cast_possible_truncation)]
        let scaled = scaled.clamp(1.0, f64::from(i16::MAX)) as i16;
        step.interval_10ms = scaled;
    }
}

/// `t_ms` snapped: to an onset within `reach_ms` if there is one (the
/// nearest), else to the nearest whole board update.
pub fn snap(t_ms: f64, update_ms: f64, onsets_ms: &[f64], reach_ms: f64) -> f64 {
    let nearest_onset = onsets_ms
        .iter()
        .copied()
        .filter(|onset| (onset - t_ms).abs() <= reach_ms)
        .min_by(|a, b| (a - t_ms).abs().total_cmp(&(b - t_ms).abs()));
    match nearest_onset {
        Some(onset) => onset,
        None if update_ms > 0.0 => (t_ms / update_ms).round() * update_ms,
        None => t_ms,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::project::plen2::Pose;

    #[test]
    fn frames_scale_within_what_the_robot_takes() {
        let mut frames: Vec<Frame> = [100, 250, 8000, 40].map(|ms| Frame::new(ms, Pose::default())).to_vec();
        scale_frames(&mut frames[1..=2], 2.0);
        let times: Vec<u16> = frames.iter().map(|frame| frame.transition_ms).collect();
        assert_eq!(times, vec![100, 500, 8191, 40], "only the span; the robot's 8191 ms at most");
        scale_frames(&mut frames, 0.5);
        let times: Vec<u16> = frames.iter().map(|frame| frame.transition_ms).collect();
        assert_eq!(times, vec![50, 250, 4096, 32], "the robot's 32 ms at least");
        let factor = factor_to_total(f64::from(50 + 250), 900.0);
        scale_frames(&mut frames[..2], factor);
        assert_eq!(frames[0].transition_ms + frames[1].transition_ms, 900);
        assert!((factor_to_total(0.0, 500.0) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn steps_scale_and_a_jump_stays_a_jump() {
        let mut steps = vec![Step::new(1, 10, 50), Step::new(2, 20, 0), Step::new(3, 30, 1)];
        scale_steps(&mut steps, 0.5);
        assert_eq!(steps.iter().map(|step| step.interval_10ms).collect::<Vec<_>>(), vec![25, 0, 1]);
        scale_steps(&mut steps, 2000.0);
        assert_eq!(steps.iter().map(|step| step.interval_10ms).collect::<Vec<_>>(), vec![i16::MAX, 0, 2000]);
    }

    #[test]
    fn a_time_snaps_to_an_onset_in_reach_else_to_a_whole_update() {
        assert!((snap(100.0, 32.768, &[], 5.0) - 98.304).abs() < 1e-9);
        assert!((snap(100.0, 32.768, &[103.0, 96.0], 5.0) - 103.0).abs() < 1e-9, "the nearest onset");
        assert!((snap(100.0, 32.768, &[120.0], 5.0) - 98.304).abs() < 1e-9, "out of reach");
        assert!((snap(14.0, 10.0, &[], 0.0) - 10.0).abs() < 1e-9);
    }
}
