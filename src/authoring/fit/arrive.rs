//! When each channel of a settled move reaches its end value, on a board
//! whose channels may arrive early and hold (a servo board: one interval per
//! servo in a step). The fit chose end values some arrival keeps within the
//! tolerance; this finds that arrival — the latest, so that a servo moves as
//! slowly as it may.

use super::{Board, Move};

/// Sets each move's arrivals (a fit of `rows` from `start` within
/// `tolerance`). A step lasts as long as its latest servo: a move in which
/// every channel arrives early becomes two, the second a pause holding
/// every value until the move's end.
pub(super) fn arrive(board: &impl Board, start: &[i32], rows: &[Vec<f64>], tolerance: f64, moves: &mut Vec<Move>) {
    let mut from = start.to_vec();
    let mut begin = 0;
    let mut arrived = Vec::with_capacity(moves.len());
    for mut step in moves.drain(..) {
        let covered = &rows[begin..begin + step.updates];
        for (channel, arrival) in step.arrivals.iter_mut().enumerate() {
            let wanted: Vec<f64> = covered.iter().map(|row| row[channel]).collect();
            *arrival =
                latest_arrival(board, from[channel], step.values[channel], &wanted, tolerance).unwrap_or(step.updates);
        }
        from.clone_from(&step.values);
        begin += step.updates;
        let latest = step.arrivals.iter().copied().max().unwrap_or(step.updates);
        if latest < step.updates {
            let pause = Move::straight(step.updates - latest, step.values.clone());
            step.updates = latest;
            arrived.push(step);
            arrived.push(pause);
        } else {
            arrived.push(step);
        }
    }
    *moves = arrived;
}

/// The latest update at which a line from `from` may reach `to`, then hold
/// it, keeping every `wanted` value within `tolerance`; `None` when none does.
fn latest_arrival(board: &impl Board, from: i32, to: i32, wanted: &[f64], tolerance: f64) -> Option<usize> {
    let within = |out: f64, wanted: f64| (out - wanted).abs() <= tolerance;
    // The earliest arrival the hold allows: every sample after it keeps `to`.
    let held_from = wanted.iter().rposition(|&value| !within(f64::from(to), value)).map_or(1, |last| last + 1).max(1);
    (held_from..=wanted.len())
        .rev()
        .find(|&arrival| (1..=arrival).all(|k| within(board.output(from, to, arrival, k), wanted[k - 1])))
}

#[cfg(test)]
mod tests {
    use super::super::{ServoBoard, fit, play};

    #[test]
    fn a_servo_that_arrives_early_holds_while_the_other_still_moves() {
        // Channel 0 climbs 60° over 30 updates then stays; channel 1 climbs over all 90.
        let rows: Vec<Vec<f64>> = (1..=90).map(|k| vec![f64::from(k.min(30)) * 2.0, f64::from(k) * 0.5]).collect();
        let fitted = fit(&ServoBoard, &[0, 0], &rows, 0.5);
        assert_eq!(fitted.moves.len(), 1, "{:?}", fitted.moves);
        assert_eq!(fitted.moves[0].values, vec![60, 45]);
        assert_eq!(fitted.moves[0].arrivals, vec![30, 90]);
        let played = play(&ServoBoard, &[0, 0], &fitted.moves);
        assert!((played[29][0] - 60.0).abs() < 1e-9 && (played[89][0] - 60.0).abs() < 1e-9);
        assert!((played[89][1] - 45.0).abs() < 1e-9);
        // Both arrive early, then pause: the step lasts as long as its latest
        // servo, so the pause is a step of its own.
        let rows: Vec<Vec<f64>> = (1..=90).map(|k| vec![f64::from(k.min(30)) * 2.0, f64::from(k.min(40))]).collect();
        let fitted = fit(&ServoBoard, &[0, 0], &rows, 0.5);
        let shape: Vec<(usize, Vec<usize>)> =
            fitted.moves.iter().map(|step| (step.updates, step.arrivals.clone())).collect();
        assert_eq!(shape, vec![(40, vec![30, 40]), (50, vec![50, 50])]);
        assert_eq!(play(&ServoBoard, &[0, 0], &fitted.moves).len(), 90);
    }
}
