//! The live speed limit: how fast anything sent live may turn a servo or a
//! joint (a slider click at the far end, a captured pose, Home, a gamepad
//! axis). A user holding the robot in one hand must never see a servo slam
//! across its range in 20 ms. STOP is not limited: it always goes first.

use std::time::{Duration, Instant};

use serde::{Deserialize, Serialize};

/// The limit unless the user sets another, °/s.
pub const DEFAULT_DEG_PER_S: f64 = 180.0;

/// The limits a user may set, °/s.
pub const RANGE_DEG_PER_S: std::ops::RangeInclusive<f64> = 10.0..=2000.0;

/// A PLEN2's firmware cycle: a joint is never stepped faster than this.
pub const PLEN2_CYCLE: Duration = Duration::from_micros(32_768);

/// The live speed limit (remembered between runs).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct LiveSpeed {
    /// Degrees per second, within [`RANGE_DEG_PER_S`].
    pub deg_per_s: f64,
}

impl Default for LiveSpeed {
    fn default() -> Self {
        Self { deg_per_s: DEFAULT_DEG_PER_S }
    }
}

impl LiveSpeed {
    /// The limit, kept within [`RANGE_DEG_PER_S`] (a settings file may hold anything).
    pub fn deg_per_s(self) -> f64 {
        if self.deg_per_s.is_finite() {
            self.deg_per_s.clamp(*RANGE_DEG_PER_S.start(), *RANGE_DEG_PER_S.end())
        } else {
            DEFAULT_DEG_PER_S
        }
    }

    /// The limit as kept: within [`RANGE_DEG_PER_S`].
    pub fn clamped(self) -> Self {
        Self { deg_per_s: self.deg_per_s() }
    }

    /// The servo board's move interval (10 ms units) for `distance_deg` at
    /// this speed, rounded up, at least `least`.
    pub fn interval_10ms(self, distance_deg: f64, least: i16) -> i16 {
        let units = (distance_deg.abs() / self.deg_per_s() * 100.0).ceil();
        // Clamped into i16 first.
        #[allow(clippy::cast_possible_truncation)]
        let units = units.clamp(f64::from(least), f64::from(i16::MAX)) as i16;
        units
    }
}

/// Joints walked toward a target no faster than the limit, a step per
/// PLEN2 cycle at most (the robot takes a joint angle at once: the steps are
/// what keeps it from slamming).
#[derive(Clone, Debug, PartialEq)]
pub struct Slew {
    /// What the robot was last sent, tenths of a degree.
    pub sent: [i16; 18],
    /// Where the joints are going.
    pub target: [i16; 18],
    /// When `sent` was sent.
    pub at: Instant,
}

impl Slew {
    /// A walk from `sent` (as of `now`) to `target`.
    pub fn new(sent: [i16; 18], target: [i16; 18], now: Instant) -> Self {
        Self { sent, target, at: now }
    }

    /// True once every joint is at its target.
    pub fn arrived(&self) -> bool {
        self.sent == self.target
    }

    /// The next step at `now`: the joints that move and their angles, or
    /// nothing when under a cycle has passed since the last one (or all have
    /// arrived). Each joint moves at most `speed × time since the last step`.
    pub fn step(&mut self, now: Instant, speed: LiveSpeed) -> Vec<(usize, i16)> {
        let since = now.saturating_duration_since(self.at);
        if self.arrived() || since < PLEN2_CYCLE {
            return Vec::new();
        }
        // Tenths per second × seconds; at least a tenth (else a slow limit never moves).
        let most = (speed.deg_per_s() * 10.0 * since.as_secs_f64()).floor().max(1.0);
        let mut moved = Vec::new();
        for (index, (sent, target)) in self.sent.iter_mut().zip(&self.target).enumerate() {
            if sent == target {
                continue;
            }
            let gap = f64::from(*target) - f64::from(*sent);
            // Within the gap, so within i16.
            #[allow(clippy::cast_possible_truncation)]
            let next = (f64::from(*sent) + gap.clamp(-most, most)) as i16;
            *sent = next;
            moved.push((index, next));
        }
        self.at = now;
        moved
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_servo_move_takes_the_time_its_distance_needs_at_the_limit() {
        let speed = LiveSpeed::default();
        // 180° at 180°/s: one second, 100 units of 10 ms.
        assert_eq!(speed.interval_10ms(180.0, 2), 100);
        assert_eq!(speed.interval_10ms(-90.0, 2), 50);
        // A nudge keeps the board's shortest live move.
        assert_eq!(speed.interval_10ms(1.0, 2), 2);
        assert_eq!(LiveSpeed { deg_per_s: 45.0 }.interval_10ms(90.0, 2), 200);
        // Nonsense from a settings file is kept within bounds.
        assert!((LiveSpeed { deg_per_s: f64::NAN }.deg_per_s() - DEFAULT_DEG_PER_S).abs() < 1e-9);
        assert!((LiveSpeed { deg_per_s: 0.0 }.deg_per_s() - 10.0).abs() < 1e-9);
    }

    #[test]
    fn joints_walk_to_the_target_no_faster_than_the_limit_and_no_more_often_than_a_cycle() {
        let start = Instant::now();
        let mut target = [0i16; 18];
        target[6] = 900;
        target[15] = -300;
        let mut slew = Slew::new([0; 18], target, start);
        let speed = LiveSpeed::default();
        assert!(slew.step(start + Duration::from_millis(10), speed).is_empty(), "under a cycle: nothing");
        let mut now = start;
        let mut steps = 0;
        while !slew.arrived() {
            now += PLEN2_CYCLE;
            let before = slew.sent;
            let moved = slew.step(now, speed);
            assert!(!moved.is_empty());
            for (index, angle) in moved {
                // 180°/s × 32.768 ms = 5.9° = 58 tenths at most per cycle.
                assert!((i32::from(angle) - i32::from(before[index])).abs() <= 58, "joint {index}");
            }
            steps += 1;
            assert!(steps < 1000);
        }
        // 90° at 180°/s: half a second, 16 cycles (58 tenths each, rounded down).
        assert_eq!(steps, 900usize.div_ceil(58));
        assert_eq!(slew.sent, target);
    }
}
