//! A sound file read once, as it streams: WAV, FLAC, MP3 and OGG/Vorbis
//! decoded by `symphonia` (pure Rust), each packet mixed to mono and handed
//! to the analyses — a min/max peak pyramid to draw the waveform at any zoom
//! ([`peaks`]), the onsets (beats, syllables) by spectral flux
//! ([`onsets`]) — and then dropped: the decoded samples are never held
//! whole, so an hour of 48 kHz stereo costs the pyramid's few megabytes.

pub mod follow;
pub mod onsets;
pub mod output;
pub mod peaks;
mod rises;
mod stream;
pub mod together;

use std::path::{Path, PathBuf};

pub use onsets::{Found, Onsets};
pub use peaks::Peaks;
pub use stream::Reader;

/// The largest sound file read, bytes: three hours of CD-quality WAV.
pub const MAX_SOUND_BYTES: u64 = 2 << 30;
/// The sample rates read, samples a second: what WAV, FLAC, MP3 and Vorbis
/// files are written at, from telephone-grade to studio masters.
pub const SAMPLE_RATES: std::ops::RangeInclusive<u32> = 100..=768_000;
/// The most channels read (what the decoders know: 7.1 and more).
pub const MAX_CHANNELS: usize = 32;
/// The longest sound read, seconds (four hours: a show, not a recording of a day).
pub const MAX_SOUND_SECONDS: u64 = 4 * 3600;

/// Why a sound file could not be read.
#[derive(Debug, thiserror::Error)]
pub enum AudioError {
    /// Not a regular file within [`MAX_SOUND_BYTES`] (a named pipe, a
    /// device, a link to one), or not readable: refused before reading.
    #[error(transparent)]
    Input(#[from] crate::project::input::ReadError),
    /// The file says a sample rate outside [`SAMPLE_RATES`].
    #[error(
        "{path} says it is sampled at {rate} Hz: Servo Studio reads sounds sampled at 100 Hz to 768 kHz (is the file damaged?)"
    )]
    Rate {
        /// The file.
        path: PathBuf,
        /// What it says.
        rate: u64,
    },
    /// The file says more channels than [`MAX_CHANNELS`].
    #[error("{path} says it has {channels} channels: Servo Studio reads up to 32")]
    Channels {
        /// The file.
        path: PathBuf,
        /// What it says.
        channels: usize,
    },
    /// The sound plays longer than [`MAX_SOUND_SECONDS`].
    #[error("{path} plays {} min or more: Servo Studio reads sounds of up to 4 hours (cut it to the show's length)", .seconds / 60)]
    TooLong {
        /// The file.
        path: PathBuf,
        /// How long it says it is (or has been found to be so far), seconds.
        seconds: u64,
    },
    /// The decoder stopped on data it could not make sense of.
    #[error("{path} is damaged: the decoder stopped on it ({what}); export it again from the program that made it")]
    Damaged {
        /// The file.
        path: PathBuf,
        /// What the decoder was doing.
        what: String,
    },
    /// The file could not be opened.
    #[error("cannot open the sound {path}: {source}")]
    Open {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// Not a sound this editor reads.
    #[error("{path} is not a sound Servo Studio reads (WAV, FLAC, MP3, OGG/Vorbis): {reason}")]
    Format {
        /// The file.
        path: PathBuf,
        /// What the decoder said.
        reason: String,
    },
    /// It holds no audio track, or one without a sample rate.
    #[error("{path} holds no audio track")]
    NoTrack {
        /// The file.
        path: PathBuf,
    },
}

/// What a sound holds: its shape and what was found in it.
#[derive(Clone, Debug, PartialEq)]
pub struct Analysis {
    /// Samples a second.
    pub sample_rate: u32,
    /// Channels (mixed to one for the analyses).
    pub channels: u16,
    /// Samples per channel.
    pub frames: u64,
    /// The waveform's peaks, for drawing.
    pub peaks: Peaks,
    /// The onsets found at the sensitivity asked, seconds from the start.
    pub onsets_s: Vec<f64>,
    /// The onset flux and the loudness, to pick onsets at another sensitivity
    /// or follow the loudness without reading the sound again.
    pub found: Found,
}

impl Analysis {
    /// How long it plays, seconds.
    pub fn duration_s(&self) -> f64 {
        // Sample counts stay far below 2^52.
        #[allow(clippy::cast_precision_loss)]
        let frames = self.frames as f64;
        frames / f64::from(self.sample_rate.max(1))
    }
}

/// Reads and analyses the sound in `path`; `progress` hears the share read
/// so far (0–1) as it goes, when the file says how long it is.
pub fn analyse(path: &Path, sensitivity: f32, mut progress: impl FnMut(f32)) -> Result<Analysis, AudioError> {
    let mut reader = Reader::open(path)?;
    let (sample_rate, expected) = (reader.rate(), reader.expected_frames());
    let mut peaks = Peaks::new();
    let mut onsets = Onsets::new(sample_rate);
    let mut frames = 0u64;
    let mut mono = Vec::new();
    while let Some((chunk, count)) = reader.next_chunk()? {
        mono.clear();
        // Channel counts are small.
        #[allow(clippy::cast_precision_loss)]
        let scale = 1.0 / count as f32;
        mono.extend(chunk.chunks_exact(count).map(|frame| frame.iter().sum::<f32>() * scale));
        peaks.push(&mono);
        onsets.push(&mono);
        frames += mono.len() as u64;
        if frames > MAX_SOUND_SECONDS.saturating_mul(u64::from(sample_rate)) {
            return Err(AudioError::TooLong {
                path: path.to_path_buf(),
                seconds: frames / u64::from(sample_rate.max(1)),
            });
        }
        if let Some(total) = expected.filter(|total| *total > 0) {
            // A share for a progress bar.
            #[allow(clippy::cast_precision_loss, clippy::cast_possible_truncation)]
            let share = (frames as f64 / total as f64).min(1.0) as f32;
            progress(share);
        }
    }
    let found = onsets.finish();
    let channels = reader.channels();
    Ok(Analysis { sample_rate, channels, frames, peaks, onsets_s: found.onsets(sensitivity), found })
}

/// A 16-bit PCM WAV file of `channels` channels at `rate`, from mono samples
/// (-1..1) copied to each channel: the sound tests and benches write.
pub fn pcm16_wav(samples: &[f32], rate: u32, channels: u16) -> Vec<u8> {
    // A WAV holds at most 4 GiB of samples: longer is cut there.
    let data_len = u32::try_from(samples.len() * 2 * usize::from(channels)).unwrap_or(u32::MAX - 36);
    let mut out = Vec::new();
    out.extend(b"RIFF");
    out.extend((36 + data_len).to_le_bytes());
    out.extend(b"WAVEfmt ");
    out.extend(16u32.to_le_bytes());
    out.extend(1u16.to_le_bytes());
    out.extend(channels.to_le_bytes());
    out.extend(rate.to_le_bytes());
    out.extend((rate * 2 * u32::from(channels)).to_le_bytes());
    out.extend((2 * channels).to_le_bytes());
    out.extend(16u16.to_le_bytes());
    out.extend(b"data");
    out.extend(data_len.to_le_bytes());
    for sample in samples {
        #[allow(clippy::cast_possible_truncation)]
        let value = (sample.clamp(-1.0, 1.0) * 32_000.0) as i16;
        for _ in 0..channels {
            out.extend(value.to_le_bytes());
        }
    }
    out
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A click track: a short decaying burst of noise at each of `at_s`, over a quiet hiss.
    pub(crate) fn clicks(at_s: &[f64], seconds: f64, rate: u32) -> Vec<f32> {
        let mut walk = 0x9e37_79b9_u32;
        let mut noise = move || {
            walk ^= walk << 13;
            walk ^= walk >> 17;
            walk ^= walk << 5;
            #[allow(clippy::cast_precision_loss)]
            let unit = walk as f32 / u32::MAX as f32;
            unit * 2.0 - 1.0
        };
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let len = (seconds * f64::from(rate)) as usize;
        let mut samples: Vec<f32> = (0..len).map(|_| noise() * 0.003).collect();
        for &t in at_s {
            #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
            let start = (t * f64::from(rate)) as usize;
            for i in 0..(rate as usize / 50) {
                #[allow(clippy::cast_precision_loss)]
                let decay = (-(i as f32) / (rate as f32 / 400.0)).exp();
                if let Some(sample) = samples.get_mut(start + i) {
                    *sample += noise() * 0.8 * decay;
                }
            }
        }
        samples
    }

    #[test]
    fn a_generated_click_track_reads_with_its_shape_and_every_click_found_within_10_ms() {
        let dir = tempfile::tempdir().unwrap();
        // Irregular times (no beat grid to lean on), some close together.
        let at: Vec<f64> =
            vec![0.25, 0.61, 0.83, 1.4, 1.52, 2.05, 2.9, 3.333, 3.5, 4.71, 5.0, 5.95, 6.4, 7.77, 8.1, 9.25];
        for (rate, channels) in [(44_100, 1), (48_000, 2)] {
            let path = dir.path().join(format!("clicks-{rate}.wav"));
            std::fs::write(&path, pcm16_wav(&clicks(&at, 10.0, rate), rate, channels)).unwrap();
            let mut shares = Vec::new();
            let analysis = analyse(&path, 0.5, |share| shares.push(share)).unwrap();
            assert_eq!((analysis.sample_rate, analysis.channels), (rate, channels));
            assert!((analysis.duration_s() - 10.0).abs() < 1e-3, "{}", analysis.duration_s());
            assert!(shares.windows(2).all(|w| w[0] <= w[1]) && shares.last() == Some(&1.0), "progress to the end");
            assert_eq!(analysis.onsets_s.len(), at.len(), "{rate} Hz: {:?}", analysis.onsets_s);
            for (found, click) in analysis.onsets_s.iter().zip(&at) {
                assert!((found - click).abs() < 0.010, "{rate} Hz: a click at {click} s found at {found} s");
            }
            // The peaks hold the clicks and the quiet between them.
            let (low, high) = analysis.peaks.range(0.0, 0.2, analysis.sample_rate, 4);
            assert!(high.iter().all(|h| *h < 0.01) && low.iter().all(|l| *l > -0.01), "quiet before the first click");
            let (_, high) = analysis.peaks.range(0.25, 0.26, analysis.sample_rate, 1);
            assert!(high[0] > 0.3, "loud at a click");
        }
    }

    #[test]
    fn what_is_not_a_sound_is_a_clear_error_naming_the_file() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("song.wav");
        std::fs::write(&path, b"this is no sound at all").unwrap();
        let error = analyse(&path, 0.5, |_| {}).unwrap_err().to_string();
        assert!(error.contains("song.wav") && error.contains("WAV, FLAC, MP3, OGG"), "{error}");
        let missing = analyse(&dir.path().join("gone.mp3"), 0.5, |_| {}).unwrap_err().to_string();
        assert!(missing.contains("gone.mp3"), "{missing}");
    }
}
