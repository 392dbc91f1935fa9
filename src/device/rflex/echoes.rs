//! The sonar's echoes placed in the world: each echo at the odometry pose the
//! base had when it arrived, from its transducer's mount along its bearing
//! (each robot's own layout, rflex.md §6),
//! kept on a 5 cm grid (a wall seen a thousand times is one cell, refreshed)
//! so that the map costs what the room's size does, not what the drive's
//! length does. Old cells fade out and are forgotten.

use std::collections::BTreeMap;

use crate::protocol::rflex::Odometry;
use crate::protocol::rflex::layout::Transducer;

/// Side of a map cell, metres.
pub const CELL_M: f64 = 0.05;
/// An echo not seen again for this long is forgotten, seconds.
pub const FORGET_AFTER_S: f64 = 120.0;
/// The most cells kept (the oldest go first): 150 m of wall at 5 cm.
pub const MAX_CELLS: usize = 3_000;

/// The echo map.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct EchoMap {
    /// Cell (x, y) → when it last echoed, seconds since the link opened.
    cells: BTreeMap<(i32, i32), f64>,
    /// The newest echo's time.
    latest: f64,
}

/// Where `transducer` sits in the world at `pose`, metres.
pub fn mount_point(pose: &Odometry, transducer: &Transducer) -> [f64; 2] {
    let (x, y) = transducer.mount_m;
    let (sin, cos) = pose.theta_rad.sin_cos();
    [pose.x_m + x * cos - y * sin, pose.y_m + x * sin + y * cos]
}

/// Where `transducer` at `pose` sees an echo `range_m` away: from its mount
/// along its bearing, metres in the world.
pub fn echo_point(pose: &Odometry, transducer: &Transducer, range_m: f64) -> [f64; 2] {
    let [x, y] = mount_point(pose, transducer);
    let bearing = pose.theta_rad + transducer.bearing_rad;
    [x + range_m * bearing.cos(), y + range_m * bearing.sin()]
}

impl EchoMap {
    /// Takes one echo, seen at `seconds`.
    pub fn record(&mut self, pose: &Odometry, seconds: f64, transducer: &Transducer, range_m: f64) {
        let [x, y] = echo_point(pose, transducer, range_m);
        // Cells of 5 cm over any room a base drives in fit an i32.
        #[allow(clippy::cast_possible_truncation)]
        let cell = ((x / CELL_M).floor() as i32, (y / CELL_M).floor() as i32);
        self.cells.insert(cell, seconds);
        self.latest = self.latest.max(seconds);
        if self.cells.len() > MAX_CELLS {
            self.forget(MAX_CELLS * 9 / 10);
        }
    }

    /// Drops cells older than [`FORGET_AFTER_S`], then the oldest until at most `keep` remain.
    fn forget(&mut self, keep: usize) {
        let cutoff = self.latest - FORGET_AFTER_S;
        self.cells.retain(|_, seen| *seen >= cutoff);
        if self.cells.len() > keep {
            let mut times: Vec<f64> = self.cells.values().copied().collect();
            times.sort_by(f64::total_cmp);
            let cutoff = times[times.len() - keep];
            self.cells.retain(|_, seen| *seen >= cutoff);
        }
    }

    /// Each cell's centre (metres) and its age relative to the newest echo (seconds), within
    /// [`FORGET_AFTER_S`].
    pub fn points(&self) -> impl Iterator<Item = ([f64; 2], f64)> + '_ {
        self.cells
            .iter()
            .filter(|(_, seen)| self.latest - **seen <= FORGET_AFTER_S)
            .map(|(&(x, y), seen)| ([(f64::from(x) + 0.5) * CELL_M, (f64::from(y) + 0.5) * CELL_M], self.latest - seen))
    }

    /// Cells held.
    pub fn len(&self) -> usize {
        self.cells.len()
    }

    /// Whether the map is empty.
    pub fn is_empty(&self) -> bool {
        self.cells.is_empty()
    }

    /// Forgets every echo.
    pub fn clear(&mut self) {
        self.cells.clear();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pose(x_m: f64, y_m: f64, theta_rad: f64) -> Odometry {
        let mut pose = Odometry::default();
        (pose.x_m, pose.y_m, pose.theta_rad) = (x_m, y_m, theta_rad);
        pose
    }

    fn b21r(id: u8) -> Transducer {
        crate::protocol::rflex::B21R.layout.transducer(id).unwrap()
    }

    #[test]
    fn an_echo_lies_along_the_transducers_bearing_from_its_mount() {
        // The base ring's transducer 40 (id 177) looks ahead from 0.26 m: from (1, 2)
        // facing +y, 1 m out.
        let [x, y] = echo_point(&pose(1.0, 2.0, std::f64::consts::FRAC_PI_2), &b21r(177), 1.0);
        assert!((x - 1.0).abs() < 1e-12 && (y - 3.26).abs() < 1e-12, "{x} {y}");
        // Transducer 34 (id 145) looks 90° to the left: facing +x, it sees +y.
        let [x, y] = echo_point(&pose(0.0, 0.0, 0.0), &b21r(145), 0.74);
        assert!(x.abs() < 1e-12 && (y - 1.0).abs() < 1e-12, "{x} {y}");
        // An ATRV-Jr's front centre sonar (id 34) sits 0.308 m ahead of the centre.
        let front = crate::protocol::rflex::ATRV_JR.layout.transducer(34).unwrap();
        let [x, y] = echo_point(&pose(0.0, 0.0, 0.0), &front, 1.0);
        assert!((x - 1.3081).abs() < 1e-12 && y.abs() < 1e-12, "{x} {y}");
    }

    #[test]
    fn a_wall_seen_again_and_again_is_one_cell_refreshed() {
        let mut map = EchoMap::default();
        for tick in 0..100 {
            map.record(&pose(0.0, 0.0, 0.0), f64::from(tick) * 0.05, &b21r(177), 1.0);
        }
        assert_eq!(map.len(), 1);
        let points: Vec<_> = map.points().collect();
        assert_eq!(points.len(), 1);
        assert!((points[0].0[0] - 1.275).abs() < 1e-9, "the cell's centre: {points:?}");
        assert_eq!(points[0].1, 0.0, "seen just now");
    }

    #[test]
    fn old_echoes_fade_and_the_map_stays_bounded() {
        let mut map = EchoMap::default();
        map.record(&pose(0.0, 0.0, 0.0), 0.0, &b21r(177), 1.0);
        map.record(&pose(0.0, 0.0, 0.0), 100.0, &b21r(145), 1.0);
        let mut ages: Vec<f64> = map.points().map(|(_, age)| age).collect();
        ages.sort_by(f64::total_cmp);
        assert_eq!(ages, vec![0.0, 100.0]);
        map.record(&pose(0.0, 0.0, 0.0), 130.0, &b21r(113), 1.0);
        assert_eq!(map.points().count(), 2, "the first echo is 130 s old: forgotten");
        // A long drive past new walls never holds more than the cap.
        for step in 0..10_000 {
            map.record(&pose(f64::from(step) * 0.1, 0.0, 0.0), 130.0 + f64::from(step) * 0.01, &b21r(145), 1.0);
        }
        assert!(map.len() <= MAX_CELLS, "{}", map.len());
        assert!(map.len() > MAX_CELLS / 2, "{}", map.len());
    }
}
