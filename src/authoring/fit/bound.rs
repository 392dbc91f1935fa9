//! How many moves no fit can do without. A fit's moves are a path whose
//! corners sit at whole updates and at whole values (the values a board
//! stores), each move a straight line — for the PLEN2, within its 16.16
//! steps of a line: its output is the line floored, so the line stays in the
//! sample's band widened by one unit, and its end lies within
//! [`LINE_TO_END`] of the frame value. The bound counts the fewest moves of
//! such paths, breadth first, keeping at each update every corner value any
//! path of so many moves reaches (per channel, the whole values between the
//! lowest and the highest: more than the board can, so never more moves than
//! the board needs). Moves are otherwise real lines: no board's arithmetic
//! is needed to trust it. On a board whose channels may arrive early and
//! hold (a servo board), a channel's move may also be a line to a whole
//! value at an earlier update, then that value: the values such holds keep
//! are carried along, so the bound counts those moves too.

use super::Board;

/// How far the end of a PLEN2 move's line may be from its frame value: its
/// step is truncated, so the line ends short by less than `cycles / 65536`.
const LINE_TO_END: f64 = 255.0 / 65_536.0;

/// The fewest moves any fit of `rows` from `start` within `tolerance` needs
/// (see the module documentation); 0 for no rows.
pub fn lower_bound(board: &impl Board, start: &[i32], rows: &[Vec<f64>], tolerance: f64) -> usize {
    let count = rows.len();
    let channels = rows.first().map_or(0, Vec::len);
    // corners[u]: per channel, the lowest and highest whole value a path reaches update u at.
    let mut corners: Vec<Option<Vec<(f64, f64)>>> = vec![None; count + 1];
    corners[0] = Some((0..channels).map(|c| f64::from(start.get(c).copied().unwrap_or(0))).map(|v| (v, v)).collect());
    let mut changed = vec![false; count + 1];
    changed[0] = true;
    let band = Band { low: -tolerance - 1e-9, high: tolerance + board.below_line() + 1e-9 };
    let near = if board.below_line() > 0.0 { LINE_TO_END } else { 1e-9 };
    let mut moves = 0;
    while corners[count].is_none() {
        moves += 1;
        let mut next = corners.clone();
        let mut next_changed = vec![false; count + 1];
        for begin in (0..count).filter(|&update| changed[update]) {
            let Some(from) = corners[begin].clone() else { continue };
            let mut lines: Vec<Lines> = from.iter().map(|&(low, high)| Lines::starting(low, high)).collect();
            // Per channel, the whole values an earlier arrival may hold (boards that allow it).
            let mut held: Vec<Option<(f64, f64)>> = vec![None; channels];
            let longest = board.max_updates().min(count - begin);
            for updates in 1..=longest {
                let k = f64::from(u32::try_from(updates).unwrap_or(u32::MAX));
                let row = &rows[begin + updates - 1];
                if board.arrives_early() && updates > 1 {
                    for ((held, line), &wanted) in held.iter_mut().zip(&lines).zip(row) {
                        *held = hold(hull(*held, line.whole_ends(k - 1.0, near)), wanted, tolerance);
                    }
                }
                let mut open = true;
                for ((line, held), &wanted) in lines.iter_mut().zip(&held).zip(row) {
                    open &= line.keep(k, wanted + band.low, wanted + band.high) || held.is_some();
                }
                if !open || lines.iter().all(|line| line.corners.is_empty()) {
                    break;
                }
                // A step lasts as long as its latest channel: one must end its line here.
                let paced = !board.arrives_early() || lines.iter().any(|line| line.whole_ends(k, near).is_some());
                let ends: Option<Vec<(f64, f64)>> = lines
                    .iter()
                    .zip(&held)
                    .map(|(line, &held)| hull(held, line.whole_ends(k, near)))
                    .collect::<Option<_>>()
                    .filter(|_| paced);
                if let Some(ends) = ends {
                    let end = begin + updates;
                    let merged = match &next[end] {
                        Some(known) => known.iter().zip(&ends).map(|(a, b)| (a.0.min(b.0), a.1.max(b.1))).collect(),
                        None => ends,
                    };
                    if next[end].as_ref() != Some(&merged) {
                        next[end] = Some(merged);
                        next_changed[end] = true;
                    }
                }
            }
        }
        if !next_changed.iter().any(|&changed| changed) {
            // Nothing new: no path within the tolerance (under half a unit); one move per update left.
            let farthest = (0..=count).rev().find(|&update| corners[update].is_some()).unwrap_or(0);
            return moves - 1 + (count - farthest);
        }
        corners = next;
        changed = next_changed;
    }
    moves
}

/// The smallest range holding both (either may be empty).
fn hull(a: Option<(f64, f64)>, b: Option<(f64, f64)>) -> Option<(f64, f64)> {
    match (a, b) {
        (Some(a), Some(b)) => Some((a.0.min(b.0), a.1.max(b.1))),
        (one, None) | (None, one) => one,
    }
}

/// The whole values of `range` that hold within `tolerance` of `wanted`.
fn hold(range: Option<(f64, f64)>, wanted: f64, tolerance: f64) -> Option<(f64, f64)> {
    let (low, high) = range?;
    let low = low.max((wanted - tolerance - 1e-9).ceil());
    let high = high.min((wanted + tolerance + 1e-9).floor());
    (low <= high).then_some((low, high))
}

/// A sample's band, relative to it.
struct Band {
    low: f64,
    high: f64,
}

/// The straight lines `value(k) = a + s·k` still possible, as the convex
/// polygon of their `(a, s)`.
#[derive(Clone, Debug)]
struct Lines {
    corners: Vec<(f64, f64)>,
}

/// Wider than any slope of an i16 channel.
const FAR: f64 = 1e7;

impl Lines {
    /// The lines starting between `low` and `high`.
    fn starting(low: f64, high: f64) -> Self {
        if low >= high {
            return Self { corners: vec![(low, -FAR), (low, FAR)] };
        }
        Self { corners: vec![(low, -FAR), (high, -FAR), (high, FAR), (low, FAR)] }
    }

    /// Keeps the lines with `low ≤ a + s·k ≤ high`; false when none is left.
    fn keep(&mut self, k: f64, low: f64, high: f64) -> bool {
        self.clip(|(a, s)| a + s * k - low);
        self.clip(|(a, s)| high - a - s * k);
        !self.corners.is_empty()
    }

    /// The whole values within `near` of where a line ends at `k`: lowest and highest.
    fn whole_ends(&self, k: f64, near: f64) -> Option<(f64, f64)> {
        let (low, high) = self
            .corners
            .iter()
            .map(|&(a, s)| a + s * k)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(low, high), end| (low.min(end), high.max(end)));
        let (low, high) = ((low - near).ceil(), (high + near).floor());
        (low <= high).then_some((low, high))
    }

    /// Keeps the part where `inside` is at least 0 (Sutherland–Hodgman, one edge).
    fn clip(&mut self, inside: impl Fn((f64, f64)) -> f64) {
        let corners = std::mem::take(&mut self.corners);
        let count = corners.len();
        for (index, &here) in corners.iter().enumerate() {
            let there = corners[(index + 1) % count];
            let (now, then) = (inside(here), inside(there));
            if now >= 0.0 {
                self.corners.push(here);
            }
            if (now >= 0.0) != (then >= 0.0) && count > 1 {
                let part = now / (now - then);
                self.corners.push((here.0 + (there.0 - here.0) * part, here.1 + (there.1 - here.1) * part));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::{ServoBoard, fit};
    use super::*;

    #[test]
    fn a_line_needs_one_move_and_a_corner_two() {
        let line: Vec<Vec<f64>> = (1..=100).map(|k| vec![f64::from(k) * 0.5]).collect();
        assert_eq!(lower_bound(&ServoBoard, &[0], &line, 0.1), 1);
        let corner: Vec<Vec<f64>> = (1..=50)
            .map(|k| vec![f64::from(k) * 2.0])
            .chain((1..=50).map(|k| vec![100.0 - f64::from(k) * 2.0]))
            .collect();
        assert_eq!(lower_bound(&ServoBoard, &[0], &corner, 0.5), 2);
        assert_eq!(fit(&ServoBoard, &[0], &corner, 0.5).moves.len(), 2);
    }

    #[test]
    fn the_first_move_starts_where_the_channels_are_and_corners_are_whole_values() {
        // A level line at 40 from a start at 0: the first move must climb to it.
        let level = vec![vec![40.0]; 50];
        assert_eq!(lower_bound(&ServoBoard, &[40], &level, 0.5), 1);
        assert_eq!(lower_bound(&ServoBoard, &[0], &level, 0.5), 2);
        // Samples at 0.5 then 1.5, within 0.2: no whole value is near enough to
        // be a corner at the first update, so the first move must cover both.
        let rows = vec![vec![0.5], vec![1.0], vec![1.5], vec![2.0]];
        assert_eq!(lower_bound(&ServoBoard, &[0], &rows, 0.2), 1);
    }
}
