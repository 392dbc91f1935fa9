//! A history of points that stays bounded however long the session runs: the
//! latest points at full rate, older ones thinned by halving, so an hour of
//! driving costs as much to keep and to draw as a few minutes.

use std::collections::VecDeque;

/// Points, oldest first: the last `recent` at full rate; before them, at most
/// `thinned` points spread evenly over the rest of the session (when that part
/// fills up, every other point is dropped and from then on only every second,
/// fourth, … point joins it).
#[derive(Clone, Debug, PartialEq)]
pub struct Trace {
    older: Vec<[f64; 2]>,
    /// Points that reach `older` one in `stride`.
    stride: usize,
    /// Points aged out since the last one kept.
    since_kept: usize,
    recent: VecDeque<[f64; 2]>,
    recent_len: usize,
    thinned: usize,
}

impl Default for Trace {
    /// The last 600 points at full rate (a minute of odometry, five of battery
    /// readings), 2,000 before them.
    fn default() -> Self {
        Self::new(600, 2_000)
    }
}

impl Trace {
    /// A trace keeping `recent` points at full rate and at most `thinned` before them.
    pub fn new(recent: usize, thinned: usize) -> Self {
        Self {
            older: Vec::new(),
            stride: 1,
            since_kept: 0,
            recent: VecDeque::new(),
            recent_len: recent.max(1),
            thinned: thinned.max(2),
        }
    }

    /// Adds the newest point.
    pub fn push(&mut self, point: [f64; 2]) {
        self.recent.push_back(point);
        if self.recent.len() > self.recent_len
            && let Some(aged) = self.recent.pop_front()
        {
            if self.since_kept == 0 {
                self.older.push(aged);
            }
            self.since_kept = (self.since_kept + 1) % self.stride;
            if self.older.len() >= self.thinned {
                let mut index = 0;
                self.older.retain(|_| {
                    index += 1;
                    index % 2 == 1
                });
                self.stride *= 2;
                self.since_kept = 1 % self.stride;
            }
        }
    }

    /// The points kept, oldest first.
    pub fn iter(&self) -> impl Iterator<Item = [f64; 2]> + '_ {
        self.older.iter().chain(&self.recent).copied()
    }

    /// Number of points kept (never more than `recent + thinned`).
    pub fn len(&self) -> usize {
        self.older.len() + self.recent.len()
    }

    /// Whether no point has been added.
    pub fn is_empty(&self) -> bool {
        self.recent.is_empty()
    }

    /// The newest point.
    pub fn last(&self) -> Option<[f64; 2]> {
        self.recent.back().copied()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_hour_is_kept_in_bounded_room_spanning_the_whole_session() {
        let mut trace = Trace::new(600, 2_000);
        // An hour at 10 Hz.
        for tick in 0..36_000 {
            trace.push([f64::from(tick) * 0.1, f64::from(tick % 50)]);
        }
        assert!(trace.len() <= 2_600, "{} points", trace.len());
        assert!(trace.len() >= 1_600, "{} points", trace.len());
        let points: Vec<[f64; 2]> = trace.iter().collect();
        assert_eq!(points[0], [0.0, 0.0], "the session's start is still there");
        assert_eq!(trace.last(), Some([3_599.9, 49.0]));
        assert!(points.windows(2).all(|pair| pair[0][0] < pair[1][0]), "oldest first");
        // The last minute at full rate.
        let recent = &points[points.len() - 600..];
        assert!(recent.windows(2).all(|pair| (pair[1][0] - pair[0][0] - 0.1).abs() < 1e-6));
        // The thinned part evenly spaced.
        let older = &points[..points.len() - 600];
        let gaps: Vec<f64> = older.windows(2).map(|pair| pair[1][0] - pair[0][0]).collect();
        let (low, high) = gaps.iter().fold((f64::MAX, f64::MIN), |(l, h), g| (l.min(*g), h.max(*g)));
        assert!(high <= 2.0 * low + 1e-6, "gaps {low}..{high}");
    }

    #[test]
    fn a_short_session_is_kept_whole() {
        let mut trace = Trace::new(600, 2_000);
        for tick in 0..1_000 {
            trace.push([f64::from(tick), 0.0]);
        }
        assert_eq!(trace.len(), 1_000);
        assert!(trace.iter().enumerate().all(|(i, p)| p[0] == i as f64));
    }
}
