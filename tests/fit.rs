//! The fitter (`authoring::fit`) against the moves no fit can do without
//! (`lower_bound`), on the benchmark's recordings and on the official PLEN2
//! motions: every fit plays within its tolerance at every update, by the
//! board's own arithmetic, and takes at most 1.2 times the bound — so at most
//! 1.2 times the true minimum. And a fit refused for its budget names the
//! smallest tolerance this fitter meets in it.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use servo_studio::authoring::fit::{
    Board, Budget, FitError, Plen2Board, ServoBoard, fit, fit_within, lower_bound, play, samples,
};
use servo_studio::device::plen2::playback::{self, StoredMotions};
use servo_studio::project::plen2::Plen2Project;
use servo_studio::protocol::plen2::DEVICE_IDS;

/// Fits, checks the playback sample by sample, and returns (moves, bound).
fn fitted(board: &impl Board, start: &[i32], rows: &[Vec<f64>], tolerance: f64, what: &str) -> (usize, usize) {
    let fitted = fit(board, start, rows, tolerance);
    let played = play(board, start, &fitted.moves);
    assert_eq!(played.len(), rows.len(), "{what}: the moves last as long as the recording");
    for (update, (out, wanted)) in played.iter().zip(rows).enumerate() {
        for (channel, (out, wanted)) in out.iter().zip(wanted).enumerate() {
            assert!(
                (out - wanted).abs() <= tolerance,
                "{what}: update {}, channel {channel}: {out} for {wanted}",
                update + 1
            );
        }
    }
    assert!(fitted.moves.iter().all(|step| (1..=board.max_updates()).contains(&step.updates)), "{what}");
    (fitted.moves.len(), lower_bound(board, start, rows, tolerance))
}

fn within_a_fifth((moves, bound): (usize, usize), what: &str) {
    assert!(bound >= 1, "{what}");
    assert!(moves >= bound, "{what}: {moves} moves under the bound {bound}: the bound is wrong");
    assert!(moves * 5 <= bound * 6, "{what}: {moves} moves, bound {bound}");
}

#[test]
fn the_fit_takes_at_most_a_fifth_more_than_the_bound_on_every_recording() {
    for tolerance_deg in [1.0, 0.5] {
        for (name, rows) in samples::recordings(32.768, 400.0) {
            let what = format!("PLEN2 {name} within {tolerance_deg}°");
            let start = vec![0; rows[0].len()];
            within_a_fifth(fitted(&Plen2Board, &start, &rows, tolerance_deg * 10.0, &what), &what);
        }
        for (name, rows) in samples::recordings(10.0, 40.0) {
            let what = format!("servo {name} within {tolerance_deg}°");
            let start = vec![0; rows[0].len()];
            within_a_fifth(fitted(&ServoBoard, &start, &rows, tolerance_deg, &what), &what);
        }
    }
}

#[test]
fn the_official_motions_fit_within_a_fifth_of_the_bound_in_no_more_frames_than_they_hold() {
    let Some(folder) = crate::common::shared("plen2/motions") else { return };
    let motions = servo_studio::project::motion_json::load_motions(&folder).unwrap();
    assert_eq!(motions.len(), 90);
    let project = Plen2Project { motions, ..Plen2Project::default() };
    let stored = StoredMotions::new(&project);
    for motion in &project.motions {
        // 30 s at most (the walks loop forever).
        let played = playback::play(&stored, motion.slot, [0; DEVICE_IDS], 916);
        let rows: Vec<Vec<f64>> =
            played.cycles.iter().map(|values| values.iter().map(|&value| f64::from(value)).collect()).collect();
        if rows.is_empty() {
            continue;
        }
        for tolerance in [10.0, 5.0] {
            let what = format!("slot {} {} within {}°", motion.slot, motion.name, tolerance / 10.0);
            let (moves, bound) = fitted(&Plen2Board, &[0; DEVICE_IDS], &rows, tolerance, &what);
            within_a_fifth((moves, bound), &what);
            if rows.len() < 916 {
                // Played once through: its own frames play it exactly, so the fewest are no more.
                assert!(
                    moves <= motion.frames.len(),
                    "{what}: {moves} frames, the motion holds {}",
                    motion.frames.len()
                );
            }
        }
    }
}

#[test]
fn a_fit_refused_for_its_budget_names_the_smallest_tolerance_this_fitter_meets() {
    let rows = samples::sines(6.0, 32.768, 4, 400.0);
    let start = [0; 4];
    let allowed = fit(&Plen2Board, &start, &rows, 10.0).moves.len() - 3;
    let budget = Budget { tolerance: 10.0, allowed, resolution: 1.0 };
    let Err(FitError::Tolerance { smallest, .. }) = fit_within(&Plen2Board, &start, &rows, budget) else {
        panic!("fewer frames than the fit takes within 1°");
    };
    // Every tolerance from the one asked, a tenth of a degree at a time: the first that fits.
    let first = (0..)
        .map(|steps| 10.0 + f64::from(steps))
        .find(|&tolerance| fit(&Plen2Board, &start, &rows, tolerance).moves.len() <= allowed)
        .unwrap();
    assert!(first > 10.0);
    assert_eq!(smallest, first, "the smallest within a tenth of a degree");
}
