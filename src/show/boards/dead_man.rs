//! A base a remote drives keeps driving only while its drives and heartbeats
//! come at most [`MOST_GAP`] apart (a 5 Hz sender's 200 ms with room to
//! spare). Each is timed when the server took it in, not when the boards'
//! worker got to it; once the gap is passed the base is stopped, and a late
//! heartbeat is told what happened and what to send. Sans-IO: time comes in.

use std::time::{Duration, Instant};

/// The most time between two drives or heartbeats while a remote drives a base.
pub const MOST_GAP: Duration = Duration::from_millis(300);

/// A base's dead-man, as a remote drives it.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct DeadMan {
    /// The last drive or heartbeat taken in, while driven.
    last: Option<Instant>,
    /// When the dead-man stopped it: how long after its last beat.
    stopped_after: Option<Duration>,
}

/// Why a heartbeat does not keep a base driving.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum NotDriven {
    /// Nothing drives it (never driven, or stopped by STOP or a play).
    #[error("it is not being driven: send a drive first (POST /devices/NAME/drive)")]
    Never,
    /// The dead-man stopped it: this long passed after its last drive or heartbeat.
    #[error(
        "the dead-man stopped it: {} ms passed after its last drive or heartbeat, and at most {} ms may (send them at 5 Hz or more); it stays stopped until a drive is sent",
        .0.as_millis(),
        MOST_GAP.as_millis()
    )]
    Stopped(Duration),
}

impl DeadMan {
    /// A drive taken in at `at`: the base is driven from then; the gap since the previous beat, if it was driven.
    pub fn drive(&mut self, at: Instant) -> Option<Duration> {
        let gap = self.last.map(|last| at.saturating_duration_since(last));
        self.last = Some(at);
        self.stopped_after = None;
        gap
    }

    /// A heartbeat taken in at `at`: the gap since the last beat when it keeps
    /// the base driving; else why not (one that came too late stops it, as
    /// the dead-man would have).
    pub fn heartbeat(&mut self, at: Instant) -> Result<Duration, NotDriven> {
        let Some(last) = self.last else {
            return Err(self.stopped_after.map_or(NotDriven::Never, NotDriven::Stopped));
        };
        let gap = at.saturating_duration_since(last);
        if gap > MOST_GAP {
            self.last = None;
            self.stopped_after = Some(gap);
            return Err(NotDriven::Stopped(gap));
        }
        self.last = Some(at);
        Ok(gap)
    }

    /// Whether the base must be stopped now: driven, and its last beat more than [`MOST_GAP`] ago.
    pub fn expired(&mut self, now: Instant) -> bool {
        let Some(last) = self.last else { return false };
        let gap = now.saturating_duration_since(last);
        if gap <= MOST_GAP {
            return false;
        }
        self.last = None;
        self.stopped_after = Some(gap);
        true
    }

    /// Stopped for another reason (STOP, a play, a lost link): not driven, nothing to explain.
    pub fn release(&mut self) {
        *self = Self::default();
    }

    /// Whether a remote drives it now.
    pub fn driven(&self) -> bool {
        self.last.is_some()
    }

    /// When the dead-man last stopped it, how long after its last beat.
    pub fn stopped_after(&self) -> Option<Duration> {
        self.stopped_after
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const MS: fn(u64) -> Duration = Duration::from_millis;

    #[test]
    fn heartbeats_at_exactly_5_hz_keep_a_base_driving_for_a_minute() {
        let t0 = Instant::now();
        let mut dead_man = DeadMan::default();
        assert_eq!(dead_man.drive(t0), None);
        for beat in 1..=300u32 {
            let at = t0 + MS(200) * beat;
            // The worker looks every 20 ms between beats: never expired.
            for look in 1..10u32 {
                assert!(!dead_man.expired(at - MS(200) + MS(20) * look), "beat {beat}, look {look}");
            }
            assert_eq!(dead_man.heartbeat(at), Ok(MS(200)));
        }
        assert!(dead_man.driven());
    }

    #[test]
    fn a_base_stops_just_past_the_gap_and_a_late_heartbeat_says_why_and_what_to_send() {
        let t0 = Instant::now();
        let mut dead_man = DeadMan::default();
        dead_man.drive(t0);
        assert!(!dead_man.expired(t0 + MOST_GAP), "exactly the gap is still allowed");
        assert!(dead_man.expired(t0 + MOST_GAP + MS(20)), "stopped by the next look");
        assert!(!dead_man.driven());
        let late = dead_man.heartbeat(t0 + MS(400)).unwrap_err();
        assert_eq!(late, NotDriven::Stopped(MS(320)));
        let said = late.to_string();
        assert!(said.contains("320 ms") && said.contains("300 ms") && said.contains("until a drive is sent"), "{said}");
        // A drive drives again.
        assert_eq!(dead_man.drive(t0 + MS(500)), None);
        assert_eq!(dead_man.heartbeat(t0 + MS(650)), Ok(MS(150)));
    }

    #[test]
    fn a_heartbeat_taken_in_too_late_stops_the_base_even_before_the_worker_looked() {
        let t0 = Instant::now();
        let mut dead_man = DeadMan::default();
        dead_man.drive(t0);
        assert_eq!(dead_man.heartbeat(t0 + MS(301)), Err(NotDriven::Stopped(MS(301))));
        assert!(!dead_man.driven());
        assert_eq!(DeadMan::default().heartbeat(t0), Err(NotDriven::Never));
        dead_man.release();
        assert_eq!(dead_man.heartbeat(t0), Err(NotDriven::Never), "STOP leaves nothing to explain");
    }
}
