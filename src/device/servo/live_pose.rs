//! The live-pose rule of a servo board, in one place: what the editor's
//! sliders and played steps, a show's held boards and a remote pose send.
//! A servo is moved within its limits, timed from where it is now at the
//! live speed limit; where it cannot be known, from the far end of its
//! limits — slow, never a slam.

use std::collections::BTreeMap;
use std::time::{Duration, Instant};

use crate::device::speed::LiveSpeed;
use crate::project::Servo;
use crate::protocol::servo::ServoMove;

/// What the sender knows of where a servo is, besides its own live moves.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Known {
    /// What the sender shows for it (a slider's last value); `None`: nothing.
    pub shown: Option<i16>,
    /// Its angle as the board last read it.
    pub reading: Option<i16>,
    /// When the board's servos were last read.
    pub read_at: Option<Instant>,
}

/// A live move as sent: the board turns the servo linearly from `from` to
/// `to` over `interval`.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Moving {
    from: f64,
    to: i16,
    start: Instant,
    interval: Duration,
}

impl Moving {
    /// Where the servo is at `now`, by the board's linear move.
    fn at(&self, now: Instant) -> f64 {
        let done = now.saturating_duration_since(self.start).as_secs_f64() / self.interval.as_secs_f64().max(1e-9);
        self.from + (f64::from(self.to) - self.from) * done.min(1.0)
    }
}

/// A board's servos as its live moves left them.
#[derive(Clone, Debug, Default)]
pub struct LivePose {
    /// Each servo's last move, by id.
    moving: BTreeMap<u8, Moving>,
    /// Servos the board moved on its own (a macro, a remote button, a STOP),
    /// by id: where they are is not known until a reading after this instant.
    unsure: BTreeMap<u8, Instant>,
}

impl LivePose {
    /// A live move of `servo` to `wanted` degrees, clamped into its limits,
    /// from where it is at `now` (along its last live move; else the board's
    /// reading; else what the sender shows; else, or when the board moved it
    /// on its own since it was last read, the far end of its limits), its
    /// interval from the distance at `speed`, at least `least` (10 ms units).
    /// Remembered for the next one.
    pub fn limited_move(
        &mut self,
        (servo, wanted): (&Servo, f64),
        known: Known,
        (speed, least): (LiveSpeed, i16),
        now: Instant,
    ) -> ServoMove {
        // Degrees of a servo: a finite value within ±180 once clamped.
        #[allow(clippy::cast_possible_truncation)]
        let degree = servo.clamp(if wanted.is_finite() { wanted.clamp(-180.0, 180.0).round() as i16 } else { 0 });
        let unsure = self.unsure.remove(&servo.id).is_some_and(|since| known.read_at.is_none_or(|at| at <= since));
        let here = match (unsure, self.moving.get(&servo.id)) {
            (false, Some(moving)) => moving.at(now),
            (false, None) => match known.reading.or(known.shown) {
                Some(degree) => f64::from(degree),
                None => servo.farther_limit(f64::from(degree)),
            },
            (true, _) => servo.farther_limit(f64::from(degree)),
        };
        let interval_10ms = speed.interval_10ms(f64::from(degree) - here, least);
        self.moved(servo.id, (here, degree), now, interval_10ms);
        ServoMove { servo_id: servo.id, degree, interval_10ms }
    }

    /// A move sent by another rule (a show's timeline followed): servo `id`
    /// from `from` to `to` degrees over `interval_10ms` from `now`.
    pub fn moved(&mut self, id: u8, (from, to): (f64, i16), now: Instant, interval_10ms: i16) {
        let interval = Duration::from_millis(u64::from(interval_10ms.unsigned_abs()) * 10);
        self.moving.insert(id, Moving { from, to, start: now, interval });
    }

    /// Where servo `id` is at `now` by its last live move, if it was moved live
    /// and the board has not moved it on its own since.
    pub fn at(&self, id: u8, now: Instant) -> Option<f64> {
        if self.unsure.contains_key(&id) {
            return None;
        }
        self.moving.get(&id).map(|moving| moving.at(now))
    }

    /// The board moves `servos` on its own until `until` (a macro, a remote
    /// button, a STOP): where they are is not known until a reading after that.
    pub fn board_moved_them(&mut self, servos: impl IntoIterator<Item = u8>, until: Instant) {
        self.moving.clear();
        for id in servos {
            self.unsure.insert(id, until);
        }
    }

    /// Everything forgotten (a new connection).
    pub fn clear(&mut self) {
        self.moving.clear();
        self.unsure.clear();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn servo() -> Servo {
        let mut servo = Servo::new(3, "arm");
        servo.min_deg = -60;
        servo.max_deg = 90;
        servo
    }

    /// The rule every sender shares: clamped into the limits, timed from
    /// where the servo is at the live speed limit, from the far end of its
    /// limits where that is not known, along a move still under way.
    #[test]
    fn a_live_move_is_clamped_and_timed_from_where_the_servo_is() {
        let (servo, now) = (servo(), Instant::now());
        let speed = LiveSpeed { deg_per_s: 100.0 };
        let mut pose = LivePose::default();
        // Not known at all: from the far end of its limits from the target (−60° for 90°).
        let first = pose.limited_move((&servo, 500.0), Known::default(), (speed, 2), now);
        assert_eq!(first.degree, 90, "clamped into its limits");
        assert_eq!(first.interval_10ms, 150, "150° at 100°/s from the far end");
        // Half-way along that move, a move back to 15° is timed from 15°: the servo is there.
        let half = now + Duration::from_millis(750);
        let back = pose.limited_move((&servo, 15.0), Known::default(), (speed, 2), half);
        assert_eq!(back.interval_10ms, 2, "at least the least interval: it is already there");
        // A slider's value is used only when nothing better is known.
        let mut fresh = LivePose::default();
        let shown = Known { shown: Some(0), ..Known::default() };
        assert_eq!(fresh.limited_move((&servo, 50.0), shown, (speed, 2), now).interval_10ms, 50);
        // The board moved it on its own: from the far end again until a reading after that.
        fresh.board_moved_them([3], now + Duration::from_secs(1));
        let stale = Known { reading: Some(50), read_at: Some(now), ..shown };
        assert_eq!(fresh.limited_move((&servo, 40.0), stale, (speed, 2), now).interval_10ms, 100, "from −60°");
        fresh.board_moved_them([3], now);
        let read = Known { reading: Some(50), read_at: Some(now + Duration::from_millis(10)), ..shown };
        assert_eq!(fresh.limited_move((&servo, 60.0), read, (speed, 2), now).interval_10ms, 10);
        assert_eq!(pose.limited_move((&servo, f64::NAN), Known::default(), (speed, 2), half).degree, 0);
    }
}
