//! The graph's arithmetic, apart from drawing: a channel's authored curve as
//! points, where a move's handles sit, a handle placed back into a curve,
//! and a dragged time snapped to the board's updates or an onset.

use super::{Channel, Key};
use crate::project::{Easing, Handles};

/// Points drawn along each curved move (a straight one takes its two ends).
const POINTS_PER_MOVE: u32 = 48;

/// Where a key's move starts: the key before it, or the channel's start.
pub fn move_start(channel: &Channel, key: usize) -> [f64; 2] {
    key.checked_sub(1).and_then(|before| channel.keys.get(before)).map_or(channel.start, |k| [k.t_ms, k.value])
}

/// A move from `from` to `to` with `easing`, as points (ms, °): the first one left out.
pub fn move_points(from: [f64; 2], to: [f64; 2], easing: Easing) -> Vec<[f64; 2]> {
    if easing.is_linear() {
        return vec![to];
    }
    (1..=POINTS_PER_MOVE)
        .map(|step| {
            let along = f64::from(step) / f64::from(POINTS_PER_MOVE);
            [from[0] + (to[0] - from[0]) * along, from[1] + (to[1] - from[1]) * easing.at(along)]
        })
        .collect()
}

/// The channel's whole curve as the author means it, from its start through
/// every key, `moved` standing in for keys being dragged.
pub fn curve_points(channel: &Channel, moved: impl Fn(usize, Key) -> Key) -> Vec<[f64; 2]> {
    let mut points = vec![channel.start];
    let mut from = channel.start;
    for (index, key) in channel.keys.iter().enumerate() {
        let key = moved(index, *key);
        let to = [key.t_ms, key.value];
        points.extend(move_points(from, to, key.easing));
        from = to;
    }
    points
}

/// The two handles of the move from `from` to `to`, in the graph's units (ms, °).
pub fn handle_points(from: [f64; 2], to: [f64; 2], handles: Handles) -> [[f64; 2]; 2] {
    let place = |[x, y]: [i16; 2]| {
        [from[0] + (to[0] - from[0]) * f64::from(x) / 1000.0, from[1] + (to[1] - from[1]) * f64::from(y) / 1000.0]
    };
    [place(handles.out), place(handles.arrive)]
}

/// Which handle of a move: the one leaving its start or the one arriving at its key.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Which {
    /// Leaving the start.
    Out,
    /// Arriving at the key.
    In,
}

/// `handles` with one of them placed at `point` (ms, °) on the move from
/// `from` to `to`, kept within the move. A flat move keeps the handle's way
/// (any way draws the same flat line); a move of no time keeps its time.
pub fn placed(handles: Handles, which: Which, from: [f64; 2], to: [f64; 2], point: [f64; 2]) -> Handles {
    let part = |value: f64, axis: usize, kept: i16| {
        let span = to[axis] - from[axis];
        if span.abs() < 1e-9 {
            return kept;
        }
        // Within 0..=1000 after the clamp: the cast cannot truncate.
        #[allow(clippy::cast_possible_truncation)]
        let thousandths = ((value - from[axis]) / span * 1000.0).round().clamp(0.0, 1000.0) as i16;
        thousandths
    };
    let at = |kept: [i16; 2]| [part(point[0], 0, kept[0]), part(point[1], 1, kept[1])];
    match which {
        Which::Out => Handles::new(at(handles.out), handles.arrive),
        Which::In => Handles::new(handles.out, at(handles.arrive)),
    }
}

/// The keys (channel, key) of `channels` whose place lies in the box from
/// `a` to `b` (any two corners, ms and °), of the channels `shown`.
pub fn keys_in_box(channels: &[Channel], shown: &[bool], a: [f64; 2], b: [f64; 2]) -> Vec<(usize, usize)> {
    let (t0, t1) = (a[0].min(b[0]), a[0].max(b[0]));
    let (v0, v1) = (a[1].min(b[1]), a[1].max(b[1]));
    let mut keys = Vec::new();
    for (c, channel) in channels.iter().enumerate().filter(|(c, _)| shown.get(*c).copied().unwrap_or(false)) {
        for (k, key) in channel.keys.iter().enumerate() {
            if (t0..=t1).contains(&key.t_ms) && (v0..=v1).contains(&key.value) {
                keys.push((c, k));
            }
        }
    }
    keys
}

#[cfg(test)]
mod tests {
    use super::*;

    fn channel() -> Channel {
        Channel {
            name: "knee".into(),
            start: [0.0, 0.0],
            keys: vec![
                Key { t_ms: 100.0, value: 50.0, easing: Easing::Linear },
                Key { t_ms: 300.0, value: -10.0, easing: Easing::EaseIn },
            ],
            limits: [-90.0, 90.0],
            baked: None,
        }
    }

    #[test]
    fn a_curve_runs_through_its_keys_and_bends_only_where_eased() {
        let points = curve_points(&channel(), |_, key| key);
        assert_eq!(points[0], [0.0, 0.0]);
        assert_eq!(points[1], [100.0, 50.0], "a straight move is its two ends");
        assert_eq!(*points.last().unwrap(), [300.0, -10.0]);
        assert_eq!(points.len(), 2 + 48);
        // Ease in: halfway in time, a quarter of the way.
        let half = points.iter().find(|p| (p[0] - 200.0).abs() < 1e-9).unwrap();
        assert!((half[1] - (50.0 - 60.0 * 0.25)).abs() < 1e-9, "{half:?}");
        let moved = curve_points(&channel(), |index, key| if index == 0 { Key { value: 80.0, ..key } } else { key });
        assert_eq!(moved[1], [100.0, 80.0]);
    }

    #[test]
    fn a_handle_placed_on_the_graph_comes_back_where_it_was_put_and_stays_within_its_move() {
        let (from, to) = ([100.0, 50.0], [300.0, -10.0]);
        let handles = Easing::Linear.handles();
        let shaped = placed(handles, Which::Out, from, to, [150.0, 50.0]);
        assert_eq!(shaped.out, [250, 0]);
        assert_eq!(shaped.arrive, handles.arrive);
        assert_eq!(handle_points(from, to, shaped)[0], [150.0, 50.0]);
        let beyond = placed(handles, Which::In, from, to, [400.0, -90.0]);
        assert_eq!(beyond.arrive, [1000, 1000], "kept within the move");
        let flat = placed(handles, Which::In, [0.0, 5.0], [100.0, 5.0], [50.0, 40.0]);
        assert_eq!(flat.arrive, [500, handles.arrive[1]], "a flat move keeps the way");
    }

    #[test]
    fn a_box_takes_the_keys_inside_it_of_the_channels_shown() {
        let channels = vec![channel(), channel()];
        assert_eq!(keys_in_box(&channels, &[true, true], [90.0, 60.0], [310.0, 40.0]), vec![(0, 0), (1, 0)]);
        assert_eq!(keys_in_box(&channels, &[false, true], [310.0, -20.0], [0.0, 60.0]), vec![(1, 0), (1, 1)]);
    }
}
