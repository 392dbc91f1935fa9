//! A fit within a budget of moves: the fit, or why it cannot be, naming the
//! smallest tolerance this fitter meets in the moves allowed.

use super::{Board, Fit, fit, lower_bound};

/// Why a movement cannot be fitted into the moves allowed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum FitError {
    /// More moves are needed at this tolerance; a wider one fits.
    #[error(
        "{needed} moves (PLEN2 frames, servo-board steps) are needed within {tolerance} and at most {allowed} are allowed; the smallest tolerance that fits is {smallest}"
    )]
    Tolerance {
        /// Moves the fit needs at the tolerance asked for.
        needed: usize,
        /// The most allowed.
        allowed: usize,
        /// The tolerance asked for, board units.
        tolerance: f64,
        /// The smallest tolerance (in steps of the resolution asked) that fits.
        smallest: f64,
    },
    /// Too long for the moves allowed at any tolerance.
    #[error(
        "{updates} updates need at least {needed} moves of at most {longest} updates each, and at most {allowed} are allowed"
    )]
    TooLong {
        /// Updates to fit.
        updates: usize,
        /// Moves needed at the least.
        needed: usize,
        /// The most updates in one move.
        longest: usize,
        /// The most moves allowed.
        allowed: usize,
    },
}

/// What a fit may cost: how far it may stray, how many moves it may take,
/// and the steps in which a wider tolerance is looked for (board units).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Budget {
    /// How far the board's output may stray from a sample.
    pub tolerance: f64,
    /// The most moves.
    pub allowed: usize,
    /// The steps of a wider tolerance (a PLEN2's tenth of a degree, say).
    pub resolution: f64,
}

/// [`fit`] with at most `budget.allowed` moves. When the tolerance needs
/// more, the error names the smallest tolerance that fits.
pub fn fit_within(board: &impl Board, start: &[i32], rows: &[Vec<f64>], budget: Budget) -> Result<Fit, FitError> {
    let Budget { tolerance, allowed, .. } = budget;
    let fitted = fit(board, start, rows, tolerance);
    if fitted.moves.len() <= allowed {
        return Ok(fitted);
    }
    let longest = board.max_updates();
    let needed = rows.len().div_ceil(longest);
    if needed > allowed {
        return Err(FitError::TooLong { updates: rows.len(), needed, longest, allowed });
    }
    let (smallest, _) = widest_needed(board, start, rows, budget);
    Err(FitError::Tolerance { needed: fitted.moves.len(), allowed, tolerance, smallest })
}

/// The smallest tolerance at or above the budget's, in steps of its
/// resolution, whose fit takes at most the moves allowed, and that fit.
/// Below the smallest tolerance whose [`lower_bound`] allows it (found by
/// halves: a wider tolerance never raises the bound) no fit can; from there
/// each step is fitted in turn, so that the tolerance named is the smallest
/// this fitter meets. Assumes the movement is short enough for the moves at
/// some tolerance.
pub fn widest_needed(board: &impl Board, start: &[i32], rows: &[Vec<f64>], budget: Budget) -> (f64, Fit) {
    let Budget { tolerance, allowed, resolution } = budget;
    let resolution = resolution.max(f64::EPSILON);
    let span = rows
        .iter()
        .flatten()
        .chain(start.iter().map(|&value| f64::from(value)).collect::<Vec<_>>().iter())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(low, high), &value| (low.min(value), high.max(value)));
    let widest = (span.1 - span.0).max(0.0) + 1.0;
    // Steps of the resolution from the tolerance asked: a handful of thousands at most.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let last = ((widest - tolerance) / resolution).ceil().max(1.0) as u64;
    let at = |steps: u64| {
        // Step counts far below 2^52: exact.
        #[allow(clippy::cast_precision_loss)]
        let widened = tolerance + steps as f64 * resolution;
        widened
    };
    let (mut low, mut high) = (0, last);
    if lower_bound(board, start, rows, at(low)) > allowed {
        while high - low > 1 {
            let middle = low + (high - low) / 2;
            if lower_bound(board, start, rows, at(middle)) <= allowed {
                high = middle;
            } else {
                low = middle;
            }
        }
        low = high;
    }
    for steps in low..last {
        let fitted = fit(board, start, rows, at(steps));
        if fitted.moves.len() <= allowed {
            return (at(steps), fitted);
        }
    }
    (at(last), fit(board, start, rows, at(last)))
}
