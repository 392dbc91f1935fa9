//! The earlier greedy fit ([`fit_on_samples`]): every move ends on a
//! recorded sample. Baking a project's curves keeps it, so that a project
//! written before uploads byte for byte as it did.

use super::{Board, Fit, Move, stored_row};

/// Past the first length that fails, how many longer ones are still tried.
const LOOK_PAST: usize = 4;

/// The earlier greedy fit, whose moves end on samples: from where the last
/// move ended, the longest move whose playback stays within the tolerance of
/// every sample it covers, ending on the sample it reaches (a few longer
/// lengths are tried past the first that fails, so a rounding step does not
/// end a move early). Baking keeps it, so that what a project uploads does
/// not change under it.
pub fn fit_on_samples(board: &impl Board, start: &[i32], rows: &[Vec<f64>], tolerance: f64) -> Fit {
    let mut moves = Vec::new();
    let mut anchor = start.to_vec();
    let mut at = 0;
    let mut max_error = 0.0_f64;
    while at < rows.len() {
        let longest = board.max_updates().min(rows.len() - at);
        let mut best: Option<(usize, Vec<i32>, f64)> = None;
        let mut updates = 1;
        while updates <= longest {
            let end = stored_row(board, &rows[at + updates - 1]);
            match error_within(board, &anchor, &end, &rows[at..at + updates], tolerance) {
                Some(error) => best = Some((updates, end, error)),
                None if best.as_ref().is_some_and(|(reached, ..)| updates > reached + LOOK_PAST) => break,
                None if best.is_none() => {
                    let error = error_within(board, &anchor, &end, &rows[at..=at], f64::INFINITY).unwrap_or(0.0);
                    best = Some((1, end, error));
                    break;
                }
                None => {}
            }
            updates += 1;
        }
        let Some((updates, end, error)) = best else { break };
        max_error = max_error.max(error);
        anchor.clone_from(&end);
        moves.push(Move::straight(updates, end));
        at += updates;
    }
    Fit { moves, max_error }
}

/// The largest error of one move over the samples it covers, or `None` as
/// soon as one exceeds `tolerance`.
fn error_within(board: &impl Board, from: &[i32], to: &[i32], samples: &[Vec<f64>], tolerance: f64) -> Option<f64> {
    let updates = samples.len();
    let mut worst = 0.0_f64;
    for (index, row) in samples.iter().enumerate() {
        for ((&from, &to), &wanted) in from.iter().zip(to).zip(row) {
            let error = (board.output(from, to, updates, index + 1) - wanted).abs();
            if error > tolerance {
                return None;
            }
            worst = worst.max(error);
        }
    }
    Some(worst)
}
