//! A sound and a board started together: the sound is started a little
//! early (and again earlier, should the output be slower to start than
//! that), when its starting point will be heard is read off the output's
//! clock, and the board's start command goes out the link's delay
//! before that moment, so the first step and the sound's point are heard
//! and seen at once. From there both run on their own clocks (the sound
//! server's and the board's), which on a minute drift far less than one
//! board update.

use std::path::Path;
use std::time::{Duration, Instant};

use super::output::{OutputError, Playing, Speakers};

/// The sound starts this much before its point, so its clock can be read before the board must start.
pub const PREROLL: Duration = Duration::from_millis(300);
/// The most it starts before its point, for an output slow to start.
pub const LONGEST_PREROLL: Duration = Duration::from_secs(5);

/// What was started.
#[derive(Debug)]
pub struct Together {
    /// The sound, playing.
    pub playing: Playing,
    /// When the sound's point is heard, and the board is meant to start moving.
    pub moving_at: Instant,
    /// When the start command was due: the link's delay before `moving_at`.
    pub due_at: Instant,
    /// When the start command went out (never before `due_at`).
    pub sent_at: Instant,
}

/// Plays `sound` so that `sound_s` (seconds from its start) is heard as the
/// board starts moving; `start_board` sends the board its start command and
/// is called `link_delay` before that.
pub fn start(
    speakers: &Speakers,
    sound: &Path,
    sound_s: f64,
    link_delay: Duration,
    start_board: impl FnOnce(),
) -> Result<Together, OutputError> {
    let mut preroll = PREROLL;
    loop {
        let playing = speakers.play(sound, sound_s - preroll.as_secs_f64())?;
        let moving_at = playing.heard_at(sound_s)?;
        let send_at = moving_at.checked_sub(link_delay).unwrap_or(moving_at);
        let late = Instant::now().saturating_duration_since(send_at);
        if let Some(longer) = longer_preroll(preroll, late) {
            // The output took longer to start than the sound's lead (a device
            // waking up, a plugin): again, with a lead that covers it.
            drop(playing);
            preroll = longer;
            continue;
        }
        wait_until(send_at);
        let sent_at = Instant::now();
        start_board();
        return Ok(Together { playing, moving_at, due_at: send_at, sent_at });
    }
}

/// The lead to start again with when the board's start was already `late`
/// once the sound's clock was read; None to go on (on time, or the longest lead tried).
fn longer_preroll(preroll: Duration, late: Duration) -> Option<Duration> {
    (!late.is_zero() && preroll < LONGEST_PREROLL).then(|| (preroll + late * 2).min(LONGEST_PREROLL))
}

/// Waits for `deadline`: asleep until the last 2 ms, then yielding (a sleep
/// overshoots by up to a scheduler's tick).
fn wait_until(deadline: Instant) {
    let margin = Duration::from_millis(2);
    if let Some(long) = deadline.checked_duration_since(Instant::now()).and_then(|left| left.checked_sub(margin)) {
        std::thread::sleep(long);
    }
    while Instant::now() < deadline {
        std::thread::yield_now();
    }
}

/// The time the board needs to act on a command of `bytes` at `baud` (ten
/// bits a byte) after a link `latency` (the connection doctor's first-byte delay).
pub fn link_delay(bytes: usize, baud: u32, latency: Duration) -> Duration {
    let bits = u64::try_from(bytes).unwrap_or(u64::MAX).saturating_mul(10);
    latency + Duration::from_micros(bits.saturating_mul(1_000_000) / u64::from(baud.max(1)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_output_slower_to_start_than_the_lead_is_started_again_with_a_lead_that_covers_it() {
        let ms = Duration::from_millis;
        assert_eq!(longer_preroll(PREROLL, Duration::ZERO), None, "on time");
        assert_eq!(longer_preroll(PREROLL, ms(1700)), Some(ms(3700)), "twice the lateness more");
        assert_eq!(longer_preroll(ms(3700), ms(1800)), Some(LONGEST_PREROLL));
        assert_eq!(longer_preroll(LONGEST_PREROLL, ms(10)), None, "the longest lead is not tried again");
    }
}
