//! Whether a device held by a show still answers: a link can stay open —
//! a TCP bridge, a USB adapter with the board's power gone — while nothing
//! answers behind it. Each stage asks its device a harmless question every
//! [`ASK_EVERY`] (a base reports on its own) and calls it lost once its
//! questions have gone unanswered for [`SILENT_AFTER`] — counted from the
//! first question after its last answer, so time in which nobody asked (the
//! player busy connecting another device) is never taken for silence.
//! Sans-IO: time comes in.

use std::time::{Duration, Instant};

/// How often a held device is asked whether it is there.
pub const ASK_EVERY: Duration = Duration::from_millis(500);
/// A device that answered nothing for this long is lost (its link may still be open).
pub const SILENT_AFTER: Duration = Duration::from_secs(2);

/// A device's signs of life.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Alive {
    /// When it last answered (or was connected).
    heard: Instant,
    /// When the question now out was asked.
    asked: Option<Instant>,
    /// When the first question since its last answer was asked.
    waiting_since: Option<Instant>,
}

impl Alive {
    /// Connected and answering at `now`.
    pub fn new(now: Instant) -> Self {
        Self { heard: now, asked: None, waiting_since: None }
    }

    /// It answered (anything that decodes as its protocol) at `at`.
    pub fn heard(&mut self, at: Instant) {
        self.heard = self.heard.max(at);
        self.asked = None;
        self.waiting_since = None;
    }

    /// The question out was withdrawn before it could be answered (STOP
    /// drops what is queued): no sign either way, so the wait starts again
    /// with the next question.
    pub fn withdrawn(&mut self) {
        self.asked = None;
        self.waiting_since = None;
    }

    /// Whether to ask it now: the last answer is [`ASK_EVERY`] old, and so is
    /// the last question (a question lost on the way is asked again). Noted
    /// as asked when it says so.
    pub fn ask(&mut self, now: Instant) -> bool {
        let due = |since: Instant| now.saturating_duration_since(since) >= ASK_EVERY;
        if due(self.heard) && self.asked.is_none_or(due) {
            self.asked = Some(now);
            self.waiting_since.get_or_insert(now);
            return true;
        }
        false
    }

    /// How long its questions have gone unanswered, once that is [`SILENT_AFTER`] or more.
    pub fn silent(&self, now: Instant) -> Option<Duration> {
        self.waiting_since.map(|since| now.saturating_duration_since(since)).filter(|quiet| *quiet >= SILENT_AFTER)
    }
}

/// Why a device held by a show is gone: kept as what happened, said in the
/// interface's language when it is shown (English here, as the command line
/// prints it).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum Loss {
    /// Its link ended.
    #[error("{0}")]
    Link(crate::link::DisconnectReason),
    /// It stopped answering though its link is open, for this many ms.
    #[error(
        "it stopped answering: nothing came back for {:.1} s (asked every {:.1} s) though its link is open — is it powered, or its bridge hung?",
        Loss::seconds(*quiet_ms),
        ASK_EVERY.as_secs_f64()
    )]
    Silent {
        /// How long its questions went unanswered, ms.
        quiet_ms: u64,
    },
    /// Its driver lost the link, saying no more.
    #[error("the link ended")]
    Ended,
    /// It never answered (a show played on without it).
    #[error("it did not answer")]
    NoAnswer,
}

impl Loss {
    /// A device silent for `quiet`.
    pub fn silence(quiet: Duration) -> Self {
        Self::Silent { quiet_ms: u64::try_from(quiet.as_millis()).unwrap_or(u64::MAX) }
    }

    /// Milliseconds as seconds.
    // Milliseconds far below 2^52.
    #[allow(clippy::cast_precision_loss)]
    pub fn seconds(ms: u64) -> f64 {
        ms as f64 / 1000.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_device_answering_is_asked_twice_a_second_and_never_silent() {
        let t0 = Instant::now();
        let mut alive = Alive::new(t0);
        assert!(!alive.ask(t0 + Duration::from_millis(100)));
        for tick in 1..100u32 {
            let now = t0 + ASK_EVERY * tick;
            assert!(alive.ask(now), "asked at tick {tick}");
            assert!(!alive.ask(now), "once");
            // Answered the moment it was asked (a round trip later, it is asked that much later).
            alive.heard(now);
            assert_eq!(alive.silent(now + Duration::from_millis(40)), None);
        }
    }

    #[test]
    fn a_device_that_stops_answering_is_asked_again_and_called_silent_after_the_limit() {
        let t0 = Instant::now();
        let mut alive = Alive::new(t0);
        let first = t0 + ASK_EVERY;
        assert!(alive.ask(first));
        assert!(!alive.ask(first + Duration::from_millis(200)), "its question is out");
        assert!(alive.ask(first + ASK_EVERY), "a question lost on the way is asked again");
        assert_eq!(alive.silent(first + SILENT_AFTER - Duration::from_millis(1)), None);
        assert_eq!(alive.silent(first + SILENT_AFTER), Some(SILENT_AFTER), "counted from the first question");
        assert!(Loss::silence(SILENT_AFTER).to_string().contains("nothing came back for 2.0 s"));
    }

    #[test]
    fn time_in_which_nobody_asked_is_not_silence() {
        let t0 = Instant::now();
        let mut alive = Alive::new(t0);
        // The player was busy for 5 s (connecting another device): nothing was asked.
        let back = t0 + Duration::from_secs(5);
        assert_eq!(alive.silent(back), None);
        assert!(alive.ask(back));
        assert_eq!(alive.silent(back + Duration::from_millis(100)), None, "its question has only just gone out");
        alive.heard(back + Duration::from_millis(20));
        assert_eq!(alive.silent(back + SILENT_AFTER * 2), None, "it answered");
    }

    #[test]
    fn a_question_withdrawn_by_stop_is_no_sign_of_silence() {
        let t0 = Instant::now();
        let mut alive = Alive::new(t0);
        // STOP after STOP: each question is dropped before the device could answer.
        for tick in 1..20u32 {
            let now = t0 + ASK_EVERY * tick;
            assert!(alive.ask(now));
            alive.withdrawn();
            assert_eq!(alive.silent(now + Duration::from_millis(100)), None, "tick {tick}");
        }
    }
}
