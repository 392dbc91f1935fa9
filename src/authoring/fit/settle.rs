//! Once the fewest moves are found, where each move ends is settled: per
//! channel, of every sequence of whole end values those moves allow (each
//! move still keeping its samples, by the board's own arithmetic), the one
//! nearest the samples at the moves' ends, in total. A channel's choice
//! does not change another's, given where the moves begin and end.

use super::{Band, Board, Move, Sample};

/// Settles `moves` (a fit of `rows` from `start` within `tolerance`), each
/// move's pacer (`pacers`, per move) kept on a line to the move's end.
pub(super) fn settle<B: Board>(
    board: &B,
    start: &[i32],
    rows: &[Vec<Sample>],
    tolerance: f64,
    moves: &mut [Move],
    pacers: &[usize],
) {
    for (channel, &from) in start.iter().enumerate() {
        let paced: Vec<bool> = pacers.iter().map(|&pacer| pacer == channel).collect();
        if let Some(values) = nearest_path(board, from, rows, tolerance, moves, (channel, &paced)) {
            for (step, value) in moves.iter_mut().zip(values) {
                step.values[channel] = value;
            }
        }
    }
}

/// The most end values a move keeps on a channel (the nearest its sample).
const KEPT: usize = 24;

/// One move's possible ends on a channel: each value with its cost so far
/// and the value the move began at.
type Layer = Vec<(i32, f64, i32)>;

/// The channel's end values nearest the samples, or `None` when a move cannot
/// keep its samples from any start (a tolerance no whole value keeps).
fn nearest_path<B: Board>(
    board: &B,
    from: i32,
    rows: &[Vec<Sample>],
    tolerance: f64,
    moves: &[Move],
    (channel, paced): (usize, &[bool]),
) -> Option<Vec<i32>> {
    let mut layers: Vec<Layer> = Vec::with_capacity(moves.len());
    let mut begin = 0;
    for (step, &paces) in moves.iter().zip(paced) {
        let samples = &rows[begin..begin + step.updates];
        let wanted = samples.last()?.get(channel)?.wanted;
        let previous: Vec<(i32, f64)> = match layers.last() {
            Some(layer) => layer.iter().map(|&(value, cost, _)| (value, cost)).collect(),
            None => vec![(from, 0.0)],
        };
        let mut layer = cheapest_ends(board, &previous, samples, (channel, paces), tolerance, wanted);
        if begin + step.updates == rows.len() {
            // The board holds the last values: kept within the tolerance of the last samples.
            let sample = samples.last()?.get(channel)?;
            let held: Layer = layer
                .iter()
                .copied()
                .filter(|&(value, ..)| (sample.low..=sample.high).contains(&i64::from(value)))
                .collect();
            if !held.is_empty() {
                layer = held;
            }
        }
        if layer.is_empty() {
            return None;
        }
        if layer.len() > KEPT {
            // A wide tolerance allows hundreds: the nearest are kept, and the value the fit chose.
            let chosen = step.values.get(channel).copied();
            layer.sort_by(|a, b| (f64::from(a.0) - wanted).abs().total_cmp(&(f64::from(b.0) - wanted).abs()));
            let keep = layer.iter().position(|entry| Some(entry.0) == chosen);
            if let Some(index) = keep.filter(|&index| index >= KEPT) {
                layer.swap(KEPT - 1, index);
            }
            layer.truncate(KEPT);
        }
        layers.push(layer);
        begin += step.updates;
    }
    // From the cheapest end, back through the values each began at.
    let last = layers.last()?;
    let mut value = last.iter().min_by(|a, b| a.1.total_cmp(&b.1))?.0;
    let mut values = vec![0; layers.len()];
    for (index, layer) in layers.iter().enumerate().rev() {
        values[index] = value;
        value = layer.iter().find(|(known, ..)| *known == value)?.2;
    }
    Some(values)
}

/// Each start's ends over `samples` on `channel`, then per end value the
/// cheapest way to it: its total distance from the samples so far, and the
/// start it comes from.
fn cheapest_ends<B: Board>(
    board: &B,
    previous: &[(i32, f64)],
    samples: &[Vec<Sample>],
    (channel, paces): (usize, bool),
    tolerance: f64,
    wanted: f64,
) -> Layer {
    let reached: Vec<(i32, f64, i32, i32)> = previous
        .iter()
        .filter_map(|&(anchor, cost)| {
            let mut band = board.band(anchor, tolerance);
            if !samples.iter().all(|row| band.push(&row[channel])) {
                return None;
            }
            let ends = if paces { band.line_ends() } else { band.ends() };
            ends.map(|(low, high)| (anchor, cost, low, high))
        })
        .collect();
    let lowest = reached.iter().map(|entry| entry.2).min().unwrap_or(0);
    let highest = reached.iter().map(|entry| entry.3).max().unwrap_or(-1);
    let mut cheapest: Vec<Option<(f64, i32)>> =
        vec![None; usize::try_from(i64::from(highest) - i64::from(lowest) + 1).unwrap_or(0)];
    for &(anchor, cost, low, high) in &reached {
        for value in low..=high {
            let total = cost + (f64::from(value) - wanted).abs();
            let slot = &mut cheapest[usize::try_from(value - lowest).unwrap_or(0)];
            if slot.is_none_or(|(known, _)| total < known) {
                *slot = Some((total, anchor));
            }
        }
    }
    (lowest..=highest)
        .zip(cheapest)
        .filter_map(|(value, cheapest)| cheapest.map(|(total, anchor)| (value, total, anchor)))
        .collect()
}
