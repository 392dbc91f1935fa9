//! Following a sound's loudness: a talking skull's jaw opens while it
//! speaks, a PLEN2 nods on each beat. The loudness of each millisecond
//! (averaged over the last [`LEVEL_WINDOW_MS`]) is gated: below the
//! threshold the axis is closed, within [`FULL_BELOW_LOUDEST_DB`] of the
//! loudest it is fully open, and linear in dB between. An attack and a
//! release then smooth how fast it opens and closes, as a compressor's
//! follower does.

/// The level is the mean energy of this many milliseconds.
pub const LEVEL_WINDOW_MS: usize = 10;

/// Within this many dB of the loudest level the axis is fully open.
pub const FULL_BELOW_LOUDEST_DB: f32 = 6.0;

/// How the loudness is followed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Follow {
    /// Time to open about two thirds of the way (63 %), ms.
    pub attack_ms: f64,
    /// Time to close about two thirds of the way, ms.
    pub release_ms: f64,
    /// Below this level (dB of full scale) the axis is closed.
    pub threshold_db: f64,
}

impl Default for Follow {
    /// 10 ms attack (a syllable's start is not lost), 80 ms release (the jaw
    /// does not chatter between syllables), −30 dB threshold (breath and hiss stay closed).
    fn default() -> Self {
        Self { attack_ms: 10.0, release_ms: 80.0, threshold_db: -30.0 }
    }
}

/// How open the axis is at each millisecond, 0 (closed) to 1 (open), from the loudness of each millisecond in dB.
pub fn openness(loudness_db: &[f32], follow: &Follow) -> Vec<f64> {
    let energy: Vec<f64> = loudness_db.iter().map(|db| 10f64.powf(f64::from(*db) / 10.0)).collect();
    let mut sum = 0.0;
    let level_db: Vec<f64> = (0..energy.len())
        .map(|ms| {
            sum += energy[ms];
            if ms >= LEVEL_WINDOW_MS {
                sum -= energy[ms - LEVEL_WINDOW_MS];
            }
            // At most LEVEL_WINDOW_MS: exact.
            #[allow(clippy::cast_precision_loss)]
            let count = (ms + 1).min(LEVEL_WINDOW_MS) as f64;
            10.0 * (sum.max(1e-12) / count).log10()
        })
        .collect();
    let loudest = level_db.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let full = (loudest - f64::from(FULL_BELOW_LOUDEST_DB)).max(follow.threshold_db + 1.0);
    let rise = 1.0 - (-1.0 / follow.attack_ms.max(0.1)).exp();
    let fall = 1.0 - (-1.0 / follow.release_ms.max(0.1)).exp();
    let mut open = 0.0;
    level_db
        .iter()
        .map(|db| {
            let target = ((db - follow.threshold_db) / (full - follow.threshold_db)).clamp(0.0, 1.0);
            open += (target - open) * if target > open { rise } else { fall };
            open
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// −120 dB with bursts at −10 dB over `bursts` (ms).
    fn level(len: usize, bursts: &[(usize, usize)]) -> Vec<f32> {
        (0..len).map(|ms| if bursts.iter().any(|(a, b)| (*a..*b).contains(&ms)) { -10.0 } else { -120.0 }).collect()
    }

    #[test]
    fn opens_within_the_attack_and_closes_within_the_release() {
        let follow = Follow { attack_ms: 10.0, release_ms: 50.0, threshold_db: -30.0 };
        let open = openness(&level(1000, &[(200, 400)]), &follow);
        assert!(open[..200].iter().all(|o| *o == 0.0), "closed before the burst");
        // Five attack times (plus the level's window) after the burst starts: open.
        assert!(open[200 + LEVEL_WINDOW_MS + 50] > 0.99, "{}", open[260]);
        assert!(open[300] > 0.99);
        // Just after the burst, still mostly open; five release times later, closed.
        assert!(open[400 + LEVEL_WINDOW_MS] > 0.7, "{}", open[410]);
        assert!(open[400 + LEVEL_WINDOW_MS + 250] < 0.01, "{}", open[660]);
    }

    /// An hour of sound at every common rate, 8 to 192 kHz (those that a
    /// millisecond does not divide among them), and at 500 Hz (a sample
    /// spans two milliseconds): a tone burst every 61.7 s.
    /// The axis opens within one servo-board update (10 ms) of every burst,
    /// the last as the first — the envelope keeps the sound's own time.
    #[test]
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss, clippy::cast_precision_loss)]
    fn the_axis_opens_within_one_board_update_of_every_burst_of_an_hour_at_any_rate() {
        for rate in [500u32, 8_000, 11_025, 22_050, 44_100, 48_000, 88_200, 96_000, 176_400, 192_000] {
            let mut envelope = super::super::onsets::Envelope::new(rate);
            let per_s = rate as usize;
            let bursts_s: Vec<f64> = (0..58).map(|k| 1.5 + 61.7 * f64::from(k)).collect();
            let burst: Vec<f32> =
                (0..per_s / 5).map(|i| (i as f32 * std::f32::consts::TAU * 440.0 / rate as f32).sin() * 0.9).collect();
            let silence = vec![0.0f32; per_s];
            let mut at = 0usize;
            let to = |envelope: &mut super::super::onsets::Envelope, at: &mut usize, until: usize| {
                while *at < until {
                    let take = (until - *at).min(silence.len());
                    envelope.push(&silence[..take]);
                    *at += take;
                }
            };
            for start_s in &bursts_s {
                // A burst's first sample: the first at or after its time.
                let start = (start_s * f64::from(rate)).ceil() as usize;
                to(&mut envelope, &mut at, start);
                envelope.push(&burst);
                at += burst.len();
            }
            to(&mut envelope, &mut at, 3600 * per_s);
            let energy = envelope.finish();
            assert_eq!(energy.len(), 3_600_000, "{rate} Hz: an hour of milliseconds");
            let loudness: Vec<f32> = energy.iter().map(|e| (10.0 * e.log10()).max(-120.0)).collect();
            let open = openness(&loudness, &Follow::default());
            for start_s in &bursts_s {
                let start_ms = (start_s * 1000.0).floor() as usize;
                let opened = (start_ms.saturating_sub(50)..open.len()).find(|&ms| open[ms] > 0.01).unwrap();
                assert!(
                    (start_ms..=start_ms + 10).contains(&opened),
                    "{rate} Hz: a burst at {start_s} s opens the axis at {opened} ms"
                );
            }
        }
    }

    #[test]
    fn below_the_threshold_stays_closed() {
        let quiet: Vec<f32> = vec![-45.0; 500];
        let follow = Follow::default();
        assert!(openness(&quiet, &follow).iter().all(|o| *o == 0.0));
    }
}
