//! Fitting a sampled movement into the fewest straight moves a board plays,
//! checked against the board's own playback at every update: a PLEN2 frame
//! is played in 16.16 steps per 32.768 ms cycle (plen2.md §6), a servo-board
//! action moves each servo linearly in 10 ms updates.
//!
//! [`fit`] chooses each move's end values freely within the tolerance: a
//! shortest path over update indices (breadth first: the fewest moves to each
//! update), where a move is possible when, for every channel, some whole end
//! value keeps the board's playback within the tolerance of every sample it
//! covers — decided exactly, sample by sample, by the channel's [`Band`] (the
//! PLEN2's integer step intervals, the servo board's slopes). Each update
//! reached keeps the end values nearest its samples, and the moves from it
//! start there. [`lower_bound`] counts the moves no fit can do without (each
//! move's start let free), so that the benchmark and the tests can say how
//! near the fit is. [`fit_on_samples`] is the earlier greedy fit whose moves
//! end on samples: baking a project's curves keeps it, so that a project
//! written before uploads byte for byte as it did.

mod arrive;
mod band;
mod bound;
mod budget;
mod greedy;
pub mod samples;
mod settle;

pub use band::{Band, HoldBand, LinearBand, Sample, StepBand, samples_of};
pub use bound::lower_bound;
pub use budget::{Budget, FitError, fit_within, widest_needed};
pub use greedy::fit_on_samples;

use crate::protocol::plen2::playback::step_value;

/// How a board plays one straight move, update by update.
pub trait Board {
    /// The most updates one move may last.
    fn max_updates(&self) -> usize;
    /// The value stored for a wanted value (whole units, in range).
    fn store(&self, value: f64) -> i32;
    /// What the board outputs at update `k` (1..=`updates`) of a move from
    /// the stored value `from` to `to`.
    fn output(&self, from: i32, to: i32, updates: usize, k: usize) -> f64;
    /// The end values of moves from `from`, sample by sample.
    type Band: Band;
    /// A fresh band for moves from the stored value `from`.
    fn band(&self, from: i32, tolerance: f64) -> Self::Band;
    /// How far below the straight line through its move its output may be
    /// (the PLEN2 floors its 16.16 value: less than one unit); for [`lower_bound`].
    fn below_line(&self) -> f64;
    /// Whether a channel may reach its end value before the move ends and
    /// hold it there (a servo board's servo, on its own interval).
    fn arrives_early(&self) -> bool {
        false
    }
}

/// A PLEN2: 32.768 ms cycles, frames of 1..=255 cycles, values in tenths of
/// a degree, the firmware's 16.16 steps ([`step_value`]).
#[derive(Clone, Copy, Debug, Default)]
pub struct Plen2Board;

impl Board for Plen2Board {
    fn max_updates(&self) -> usize {
        255
    }

    fn store(&self, value: f64) -> i32 {
        stored_i16(value)
    }

    fn output(&self, from: i32, to: i32, updates: usize, k: usize) -> f64 {
        let (from, to) = (i16::try_from(from).unwrap_or(0), i16::try_from(to).unwrap_or(0));
        let (updates, k) = (u8::try_from(updates).unwrap_or(u8::MAX), u16::try_from(k).unwrap_or(0));
        f64::from(step_value(from, to, updates, k))
    }

    type Band = StepBand;

    fn band(&self, from: i32, _tolerance: f64) -> StepBand {
        StepBand::new(from)
    }

    fn below_line(&self) -> f64 {
        1.0
    }
}

/// A servo board: 10 ms updates, a step of 1..=32767 updates, whole degrees,
/// each servo moving linearly over its own interval, then holding until the
/// step's longest ends.
#[derive(Clone, Copy, Debug, Default)]
pub struct ServoBoard;

impl Board for ServoBoard {
    fn max_updates(&self) -> usize {
        usize::from(i16::MAX.unsigned_abs())
    }

    fn store(&self, value: f64) -> i32 {
        stored_i16(value)
    }

    fn output(&self, from: i32, to: i32, updates: usize, k: usize) -> f64 {
        // Counts of at most 32767 updates: exact in f64.
        #[allow(clippy::cast_precision_loss)]
        let done = k as f64 / updates.max(1) as f64;
        f64::from(from) + f64::from(to - from) * done
    }

    type Band = HoldBand;

    fn band(&self, from: i32, tolerance: f64) -> HoldBand {
        HoldBand::new(from, tolerance)
    }

    fn below_line(&self) -> f64 {
        0.0
    }

    fn arrives_early(&self) -> bool {
        true
    }
}

/// A value rounded to a whole i16.
fn stored_i16(value: f64) -> i32 {
    if value.is_nan() {
        return 0;
    }
    // Rounded and clamped into i16 first.
    #[allow(clippy::cast_possible_truncation)]
    let stored = value.round().clamp(f64::from(i16::MIN), f64::from(i16::MAX)) as i32;
    stored
}

/// One straight move: how many updates it lasts and where each channel ends.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Move {
    /// Board updates (PLEN2 cycles, servo-board 10 ms ticks).
    pub updates: usize,
    /// Each channel's stored value at the end.
    pub values: Vec<i32>,
    /// The update each channel reaches its value at, then holds it (a
    /// servo-board step's own interval per servo); `updates` for every
    /// channel of a board whose channels all move for the whole move.
    pub arrivals: Vec<usize>,
}

impl Move {
    /// A move in which every channel moves for all of its `updates`.
    pub fn straight(updates: usize, values: Vec<i32>) -> Self {
        let arrivals = vec![updates; values.len()];
        Self { updates, values, arrivals }
    }

    /// What `channel` outputs at update `k` (1..=`updates`) from `from`.
    pub fn output(&self, board: &impl Board, channel: usize, from: i32, k: usize) -> f64 {
        let to = self.values[channel];
        let arrival = self.arrivals.get(channel).copied().unwrap_or(self.updates).clamp(1, self.updates.max(1));
        if k > arrival { f64::from(to) } else { board.output(from, to, arrival, k) }
    }
}

/// Moves that play a sampled movement back, and how close they come.
#[derive(Clone, Debug, PartialEq)]
pub struct Fit {
    /// The moves, in order.
    pub moves: Vec<Move>,
    /// The largest distance between the board's output and a sample, in the
    /// board's units (PLEN2: tenths of a degree; servo board: degrees).
    pub max_error: f64,
}

/// The updates each step of the search moves on from: the latest this many
/// of those first reached in as many moves. An earlier one rarely reaches
/// farther, and every one of the benchmark set's and the official motions'
/// fits is the same move for move with all of them tried (`cargo bench
/// --bench fit`); it halves the time of a long recording's fit.
const BEAM: usize = 8;

/// The fewest moves this fitter finds (see the module documentation).
/// `start` is where each channel is before the first update; `rows[u]` holds
/// every channel's wanted value at update `u + 1`. A tolerance no whole value
/// can keep (under half a unit) takes a one-update move to the sample there
/// anyway, from as far as the tolerance reached.
pub fn fit<B: Board>(board: &B, start: &[i32], rows: &[Vec<f64>], tolerance: f64) -> Fit {
    fit_samples(board, start, rows, &samples_of(rows, tolerance), tolerance)
}

/// As [`fit`], with the last move ending exactly on the last row's values
/// (each stored as the board stores it): a curve between two keys baked so
/// that the next move leaves from its key, as the author placed it.
pub fn fit_to_key<B: Board>(board: &B, start: &[i32], rows: &[Vec<f64>], tolerance: f64) -> Fit {
    let mut samples = samples_of(rows, tolerance);
    if let (Some(last), Some(row)) = (samples.last_mut(), rows.last()) {
        for (sample, &wanted) in last.iter_mut().zip(row) {
            let key = i64::from(board.store(wanted));
            *sample = Sample { wanted, low: key, high: key };
        }
    }
    fit_samples(board, start, rows, &samples, tolerance)
}

fn fit_samples<B: Board>(board: &B, start: &[i32], rows: &[Vec<f64>], samples: &[Vec<Sample>], tolerance: f64) -> Fit {
    let count = rows.len();
    let mut nodes: Vec<Option<Node>> = vec![None; count + 1];
    nodes[0] = Some(Node { moves: 0, begin: 0, ends: Ends::Chosen(start.to_vec()), off: 0.0, pacer: 0 });
    let mut layer = vec![0];
    let mut moves = 0;
    while nodes[count].is_none() {
        moves += 1;
        let mut next = Vec::new();
        for &begin in &layer {
            let mut reach = Reach { board, rows, samples, tolerance, moves, nodes: &mut nodes, next: &mut next };
            reach.from(begin);
        }
        if next.is_empty() {
            // No whole value keeps the tolerance: one update, to the sample there.
            let farthest = (0..count).rev().find(|&update| nodes[update].is_some()).unwrap_or(0);
            let values = stored_row(board, &rows[farthest]);
            nodes[farthest + 1] =
                Some(Node { moves, begin: farthest, ends: Ends::Chosen(values), off: f64::INFINITY, pacer: 0 });
            next.push(farthest + 1);
        }
        // Latest first: between equals, an update two places reach keeps the
        // later one's move, so that the long moves come first (a hold of 600
        // cycles: 255, 255, 90).
        next.sort_unstable_by(|a, b| b.cmp(a));
        next.truncate(BEAM);
        layer = next;
    }
    let mut fitted = Vec::new();
    let mut pacers = Vec::new();
    let mut at = count;
    while at > 0 {
        let Some(node) = nodes[at].take() else { break };
        let values = match node.ends {
            Ends::Chosen(values) => values,
            // The last: settled below.
            Ends::Within(ranges) => {
                ranges.iter().zip(&rows[at - 1]).map(|(&(low, high), &w)| board.store(w).clamp(low, high)).collect()
            }
        };
        fitted.push(Move::straight(at - node.begin, values));
        pacers.push(node.pacer);
        at = node.begin;
    }
    fitted.reverse();
    pacers.reverse();
    settle::settle(board, start, samples, tolerance, &mut fitted, &pacers);
    if board.arrives_early() {
        arrive::arrive(board, start, rows, tolerance, &mut fitted);
    }
    let max_error = largest_error(&play(board, start, &fitted), rows);
    Fit { moves: fitted, max_error }
}

/// An update the search reached: in how many moves, from where, where its
/// move may end or was chosen to, and how far from their samples its moves
/// were made to end.
#[derive(Clone, Debug)]
struct Node {
    moves: usize,
    begin: usize,
    ends: Ends,
    off: f64,
    /// The channel that moves for the whole move (its line ends at it, not
    /// an earlier arrival held): a servo-board step lasts as long as its
    /// latest servo, so one must.
    pacer: usize,
}

/// Where a move ends: each channel's range until the next move leaves from
/// it, then the values chosen in them.
#[derive(Clone, Debug)]
enum Ends {
    Within(Vec<(i32, i32)>),
    Chosen(Vec<i32>),
}

/// One step of the breadth-first search: the updates a move from one place reaches.
struct Reach<'a, B: Board> {
    board: &'a B,
    rows: &'a [Vec<f64>],
    samples: &'a [Vec<Sample>],
    tolerance: f64,
    /// The moves to the updates this step reaches.
    moves: usize,
    nodes: &'a mut [Option<Node>],
    next: &'a mut Vec<usize>,
}

impl<B: Board> Reach<'_, B> {
    /// Every update a move from `begin` reaches that no fewer moves reach.
    /// Of two ways to reach it in as many moves, the one whose moves end
    /// nearer their samples wins (a move that must overshoot a corner to end
    /// past it loses to the one ending at the corner).
    fn from(&mut self, begin: usize) {
        let Some(node) = self.nodes[begin].as_mut() else { return };
        let from = match &node.ends {
            Ends::Chosen(values) => values.clone(),
            Ends::Within(ranges) => {
                let ranges = ranges.clone();
                let values = self.ends_at(&ranges, &self.rows[begin - 1], begin);
                if let Some(node) = self.nodes[begin].as_mut() {
                    node.ends = Ends::Chosen(values.clone());
                }
                values
            }
        };
        let off = self.nodes[begin].as_ref().map_or(0.0, |node| node.off);
        let mut bands: Vec<B::Band> = from.iter().map(|&value| self.board.band(value, self.tolerance)).collect();
        let longest = self.board.max_updates().min(self.rows.len() - begin);
        for updates in 1..=longest {
            let row = &self.rows[begin + updates - 1];
            let mut open = true;
            for (band, sample) in bands.iter_mut().zip(&self.samples[begin + updates - 1]) {
                open &= band.push(sample);
            }
            // No longer move can end once every line has closed (each channel only holds).
            if !open || !bands.iter().any(Band::line_open) {
                return;
            }
            let end = begin + updates;
            let known = self.nodes[end].as_ref().map(|node| (node.moves, node.off));
            // Reached in fewer moves, or as near the samples as this can be at best.
            if known.is_some_and(|(moves, known)| moves < self.moves || known <= off) {
                continue;
            }
            let last = end == self.rows.len();
            let Some(pacer) = pacer(&bands, &self.samples[end - 1], row, self.board, last) else { continue };
            let range_of = |(channel, (band, sample)): (usize, (&B::Band, &Sample))| {
                let ends = if channel == pacer { band.line_ends() } else { band.ends() };
                // The board holds the last frame's values: they keep the last samples too.
                if last { held(ends?, sample) } else { ends }
            };
            // How far from their samples the ends must be, before anything is kept (most are not).
            let mut forced = 0.0;
            let mut open = true;
            for (pair, &wanted) in bands.iter().zip(&self.samples[end - 1]).enumerate().zip(row) {
                let Some((low, high)) = range_of(pair) else {
                    open = false;
                    break;
                };
                let stored = self.board.store(wanted);
                forced += f64::from((low - stored).max(stored - high).max(0));
            }
            let total = off + forced;
            if !open || known.is_some_and(|(_, known)| known <= total) {
                continue;
            }
            let ranges: Vec<(i32, i32)> =
                bands.iter().zip(&self.samples[end - 1]).enumerate().filter_map(range_of).collect();
            if known.is_none() {
                self.next.push(end);
            }
            self.nodes[end] = Some(Node { moves: self.moves, begin, ends: Ends::Within(ranges), off: total, pacer });
        }
    }
}

/// The channel to pace a move ending here: one whose line over the whole
/// move ends here (on a board whose channels all do, the first), the one
/// whose own sample that line may end on if any does; `None` when no
/// channel's line reaches this far (each only holds an earlier arrival).
fn pacer<B: Band>(bands: &[B], samples: &[Sample], row: &[f64], board: &impl Board, last: bool) -> Option<usize> {
    let mut first = None;
    for (channel, (band, sample)) in bands.iter().zip(samples).enumerate() {
        let ends = band.line_ends();
        let Some((low, high)) = (if last { ends.and_then(|ends| held(ends, sample)) } else { ends }) else { continue };
        if !board.arrives_early() || (low..=high).contains(&board.store(row[channel])) {
            return Some(channel);
        }
        first.get_or_insert(channel);
    }
    first
}

/// The part of `range` within the tolerance of `sample` itself.
fn held((low, high): (i32, i32), sample: &Sample) -> Option<(i32, i32)> {
    let low = i64::from(low).max(sample.low);
    let high = i64::from(high).min(sample.high);
    (low <= high).then(|| (i32::try_from(low).unwrap_or(0), i32::try_from(high).unwrap_or(0)))
}

/// The largest distance between what was played and what was wanted.
fn largest_error(played: &[Vec<f64>], rows: &[Vec<f64>]) -> f64 {
    played
        .iter()
        .zip(rows)
        .flat_map(|(out, wanted)| out.iter().zip(wanted).map(|(out, wanted)| (out - wanted).abs()))
        .fold(0.0, f64::max)
}

impl<B: Board> Reach<'_, B> {
    /// Where each channel ends a move to update `end`, of the values
    /// `ranges` allows: a move's reach is its channels' least, and each
    /// channel's depends on its own start alone. So the channel that would
    /// cut the next move shortest starts where it reaches farthest, and every
    /// other channel as near its sample as it can without cutting the move
    /// shorter than that.
    fn ends_at(&self, ranges: &[(i32, i32)], row: &[f64], end: usize) -> Vec<i32> {
        let candidates: Vec<Vec<i32>> = ranges
            .iter()
            .zip(row)
            .map(|(&(low, high), &wanted)| {
                let nearest = self.board.store(wanted).clamp(low, high);
                let mut candidates = vec![nearest];
                if end < self.rows.len() {
                    let span = high - low;
                    candidates.extend([low, high, low + span / 4, low + span / 2, high - span / 4]);
                }
                candidates.dedup();
                candidates
            })
            .collect();
        // How far the next move can go: each channel's farthest, the least of
        // them. Each reach found is kept (it was capped at a cut at least the
        // final one, so it answers "does it reach the cut" below exactly).
        let mut cut = LOOK_AHEAD;
        let mut reached: Vec<Vec<Option<usize>>> = candidates.iter().map(|values| vec![None; values.len()]).collect();
        for (channel, values) in candidates.iter().enumerate() {
            let mut farthest = 0;
            for (place, &value) in values.iter().enumerate() {
                let reach = self.reach(value, end, channel, cut);
                reached[channel][place] = Some(reach);
                farthest = farthest.max(reach);
                if farthest >= cut {
                    break;
                }
            }
            cut = farthest;
        }
        // Each channel as near its sample as it can be without cutting it shorter.
        (candidates.iter().enumerate())
            .map(|(channel, values)| {
                let keeps = values.iter().enumerate().find(|&(place, &value)| {
                    reached[channel][place].unwrap_or_else(|| self.reach(value, end, channel, cut)) >= cut
                });
                keeps.map(|(_, value)| value).or(values.first()).copied().unwrap_or(0)
            })
            .collect()
    }

    /// How many updates after `end` a move of `channel` from `value` can
    /// cover (at most `cap`).
    fn reach(&self, value: i32, end: usize, channel: usize, cap: usize) -> usize {
        let mut band = self.board.band(value, self.tolerance);
        let longest = self.board.max_updates().min(self.rows.len() - end).min(cap);
        (end..end + longest).take_while(|&update| band.push(&self.samples[update][channel])).count()
    }
}

/// How far ahead a channel's next move is followed to choose where a move ends (updates).
const LOOK_AHEAD: usize = 128;

fn stored_row(board: &impl Board, row: &[f64]) -> Vec<i32> {
    row.iter().map(|value| board.store(*value)).collect()
}

/// What the board outputs playing `moves` from `start`, one row per update.
pub fn play(board: &impl Board, start: &[i32], moves: &[Move]) -> Vec<Vec<f64>> {
    let mut rows = Vec::new();
    let mut from = start.to_vec();
    for step in moves {
        for k in 1..=step.updates {
            rows.push(from.iter().enumerate().map(|(channel, &a)| step.output(board, channel, a, k)).collect());
        }
        from.clone_from(&step.values);
    }
    rows
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rows_of(values: &[f64]) -> Vec<Vec<f64>> {
        values.iter().map(|&value| vec![value]).collect()
    }

    #[test]
    fn a_straight_line_is_one_move() {
        // 0 → 600 tenths over 100 cycles, sampled as the robot would play it.
        let rows: Vec<Vec<f64>> = (1..=100).map(|k| vec![Plen2Board.output(0, 600, 100, k)]).collect();
        let fitted = fit(&Plen2Board, &[0], &rows, 10.0);
        assert_eq!(fitted.moves, vec![Move::straight(100, vec![600])]);
        assert!(fitted.max_error < 1e-9);
        // The servo board's line, in degrees.
        let rows: Vec<Vec<f64>> = (1..=300).map(|k| vec![f64::from(k) * 0.3]).collect();
        let fitted = fit(&ServoBoard, &[0], &rows, 1.0);
        assert_eq!(fitted.moves, vec![Move::straight(300, vec![90])]);
    }

    #[test]
    fn a_ramp_with_one_corner_is_two_moves() {
        // Up 4 per update for 50 updates, then down 2 per update for 60.
        let values: Vec<f64> =
            (1..=50).map(|k| f64::from(k) * 4.0).chain((1..=60).map(|k| 200.0 - f64::from(k) * 2.0)).collect();
        let fitted = fit(&ServoBoard, &[0], &rows_of(&values), 0.5);
        assert_eq!(fitted.moves, vec![Move::straight(50, vec![200]), Move::straight(60, vec![80])]);
        assert_eq!(lower_bound(&ServoBoard, &[0], &rows_of(&values), 0.5), 2);
    }

    #[test]
    fn a_sine_within_a_known_tolerance() {
        // One period of 90·sin over 2 s at 10 ms. A chord of length h on a
        // curve of curvature ≤ 90·ω² sags by ≤ 90·ω²·h²/8; with ω = π per
        // second that bounds the moves from below and the fit from above.
        let omega = std::f64::consts::PI;
        let values: Vec<f64> = (1..=200).map(|k| 90.0 * (omega * f64::from(k) / 100.0).sin()).collect();
        let rows = rows_of(&values);
        let fitted = fit(&ServoBoard, &[0], &rows, 2.0);
        let played = play(&ServoBoard, &[0], &fitted.moves);
        assert_eq!(played.len(), rows.len());
        for (out, wanted) in played.iter().zip(&rows) {
            assert!((out[0] - wanted[0]).abs() <= 2.0, "{} vs {}", out[0], wanted[0]);
        }
        assert!(fitted.max_error <= 2.0);
        let minimum = lower_bound(&ServoBoard, &[0], &rows, 2.0);
        // Sag ≤ 2° (minus rounding) needs chords of at most ~0.42 s: at least 5 over 2 s.
        assert!(minimum >= 5, "{minimum}");
        assert!(fitted.moves.len() <= minimum + minimum / 5, "{} vs minimum {minimum}", fitted.moves.len());
    }

    #[test]
    fn a_hold_then_a_jump() {
        let values: Vec<f64> = std::iter::repeat_n(0.0, 40).chain(std::iter::once(300.0)).collect();
        let fitted = fit(&Plen2Board, &[0], &rows_of(&values), 10.0);
        assert_eq!(fitted.moves, vec![Move::straight(40, vec![0]), Move::straight(1, vec![300])]);
    }

    #[test]
    fn moves_never_exceed_what_the_board_holds_and_the_long_ones_come_first() {
        let rows = rows_of(&[5.0; 600]);
        let fitted = fit(&Plen2Board, &[5], &rows, 10.0);
        let lengths: Vec<usize> = fitted.moves.iter().map(|step| step.updates).collect();
        assert_eq!(lengths, vec![255, 255, 90]);
    }

    #[test]
    fn too_many_moves_names_the_smallest_tolerance_that_fits() {
        let omega = std::f64::consts::PI;
        let values: Vec<f64> = (1..=300).map(|k| 400.0 * (omega * f64::from(k) / 50.0).sin()).collect();
        let rows = rows_of(&values);
        let Err(FitError::Tolerance { needed, allowed, smallest, .. }) =
            fit_within(&Plen2Board, &[0], &rows, Budget { tolerance: 10.0, allowed: 4, resolution: 1.0 })
        else {
            panic!("4 frames cannot hold three periods within 1°");
        };
        assert!(needed > 4);
        assert_eq!(allowed, 4);
        assert!(fit(&Plen2Board, &[0], &rows, smallest).moves.len() <= 4);
        assert!(fit(&Plen2Board, &[0], &rows, smallest - 1.0).moves.len() > 4, "{smallest} is the smallest");
        let too_long = rows_of(&[0.0; 1000]);
        assert!(matches!(
            fit_within(&Plen2Board, &[0], &too_long, Budget { tolerance: 10.0, allowed: 3, resolution: 1.0 }),
            Err(FitError::TooLong { needed: 4, .. })
        ));
    }
}
