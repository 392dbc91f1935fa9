//! Onsets (beats, syllables, clicks): spectral-flux peaks and loudness
//! rises, gated by what is heard (docs/audio.md). For the flux, every 5 ms a window
//! of about 12 ms is Hann-weighted and transformed (`rustfft`); the flux is
//! how much the log magnitudes rose from the window before, summed over the
//! bins. A flux that is the highest within ±15 ms and stands above its
//! neighbourhood's mean by more than `λ` of its spread is an onset, where λ
//! falls as the sensitivity (0–1) rises. The onset's time is then refined on
//! a 1 ms energy envelope: the steepest rise near the flux's peak. Both the
//! flux and the envelope are kept (a few bytes per 5 ms and per ms); the
//! samples are not.
//!
//! Times are the sound's own, exactly: the envelope's millisecond `m` holds
//! the samples whose time falls in it (`i · 1000 / rate` rounded down), so
//! at 44.1 kHz some hold 44 samples and some 45, and below 1 kHz a sample
//! spans several (each holds its level); a flux frame is `hop` samples
//! after the one before, its time counted in samples.

use std::sync::Arc;

use rustfft::num_complex::Complex;
use rustfft::{Fft, FftPlanner};

use super::rises::Loudness;

/// Between two onsets at least this long, ms.
const LEAST_GAP_MS: usize = 30;

/// How far ahead of an attack an encoder's pre-echo reaches, ms.
const PRE_ECHO_MS: usize = 50;

/// The detector, fed as the sound is read.
pub struct Onsets {
    rate: u32,
    hop: usize,
    window: Vec<f32>,
    fft: Arc<dyn Fft<f32>>,
    /// Samples not yet framed; `start` is the first one's index in the sound.
    pending: Vec<f32>,
    start: usize,
    previous: Vec<f32>,
    flux: Vec<f32>,
    envelope: Envelope,
    scratch: Vec<Complex<f32>>,
}

/// The mean energy (square) of each millisecond of a sound, built as it streams.
#[derive(Clone, Debug)]
pub struct Envelope {
    rate: u64,
    /// Samples so far.
    samples: u64,
    /// Each finished millisecond's mean energy.
    energy_ms: Vec<f32>,
    /// The millisecond being filled: its sum of squares and its samples.
    open: (f64, u32),
}

impl Envelope {
    /// An envelope of a sound at `rate` (above 0).
    pub fn new(rate: u32) -> Self {
        Self { rate: u64::from(rate.max(1)), samples: 0, energy_ms: Vec::new(), open: (0.0, 0) }
    }

    /// The millisecond sample `index` falls in.
    fn ms_of(&self, index: u64) -> usize {
        // An index's millisecond: below 2^64 / 1000 samples (centuries at any rate).
        usize::try_from(index.saturating_mul(1000) / self.rate).unwrap_or(usize::MAX)
    }

    /// Closes the open millisecond and every one before `ms` (a sound below
    /// 1 kHz: a sample spans several, each holding its level).
    fn close_until(&mut self, ms: usize) {
        while self.energy_ms.len() < ms {
            let level = match self.open {
                (sum, count) if count > 0 => {
                    // Mean energy of the millisecond's samples.
                    #[allow(clippy::cast_possible_truncation)]
                    let mean = (sum / f64::from(count)) as f32;
                    mean
                }
                _ => self.energy_ms.last().copied().unwrap_or(0.0),
            };
            self.energy_ms.push(level);
            self.open = (0.0, 0);
        }
    }

    /// More samples (mono).
    pub fn push(&mut self, mut samples: &[f32]) {
        while !samples.is_empty() {
            let ms = self.ms_of(self.samples);
            if ms > self.energy_ms.len() {
                self.close_until(ms);
            }
            // The samples left in this millisecond: up to the first whose time is in the next.
            let next =
                (u64::try_from(ms).unwrap_or(u64::MAX).saturating_add(1)).saturating_mul(self.rate).div_ceil(1000);
            let left = next.saturating_sub(self.samples).max(1);
            let (now, rest) = samples.split_at(usize::try_from(left).unwrap_or(usize::MAX).min(samples.len()));
            // Eight squares at a time in f32 (a millisecond holds at most 768
            // samples: exact to a part in 10^6), then in f64: an hour of sound is
            // 2.3 billion samples at 192 kHz, fast enough even unoptimised.
            let mut eights = now.chunks_exact(8);
            let mut sum = 0.0f64;
            for eight in &mut eights {
                if let Ok([a, b, c, d, e, f, g, h]) = <[f32; 8]>::try_from(eight) {
                    sum += f64::from(a * a + b * b + c * c + d * d + e * e + f * f + g * g + h * h);
                }
            }
            for &sample in eights.remainder() {
                sum += f64::from(sample * sample);
            }
            // A millisecond's samples: at most 768.
            #[allow(clippy::cast_possible_truncation)]
            let count = now.len() as u32;
            self.open = (self.open.0 + sum, self.open.1 + count);
            self.samples += u64::try_from(now.len()).unwrap_or(u64::MAX);
            samples = rest;
        }
    }

    /// Every millisecond's mean energy, to the sound's end (a last partial
    /// millisecond counts as a whole one).
    pub fn finish(mut self) -> Vec<f32> {
        let end = usize::try_from((self.samples.saturating_mul(1000)).div_ceil(self.rate)).unwrap_or(usize::MAX);
        self.close_until(end);
        self.energy_ms
    }
}

impl std::fmt::Debug for Onsets {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Onsets").field("rate", &self.rate).field("frames", &self.flux.len()).finish_non_exhaustive()
    }
}

impl Onsets {
    /// A detector for sound at `rate`.
    pub fn new(rate: u32) -> Self {
        let rate_samples = rate as usize;
        let size = (rate_samples * 12 / 1000).next_power_of_two().max(64);
        // A Hann window.
        #[allow(clippy::cast_precision_loss)]
        let window = (0..size).map(|i| 0.5 - 0.5 * (std::f32::consts::TAU * i as f32 / size as f32).cos()).collect();
        Self {
            rate,
            hop: (rate_samples / 200).max(1),
            window,
            fft: FftPlanner::new().plan_fft_forward(size),
            pending: Vec::new(),
            start: 0,
            previous: vec![0.0; size / 2],
            flux: Vec::new(),
            envelope: Envelope::new(rate),
            scratch: vec![Complex::default(); size],
        }
    }

    /// More samples (mono).
    pub fn push(&mut self, samples: &[f32]) {
        self.envelope.push(samples);
        self.pending.extend_from_slice(samples);
        let size = self.window.len();
        let mut at = 0;
        while at + size <= self.pending.len() {
            for (slot, (sample, weight)) in
                self.scratch.iter_mut().zip(self.pending[at..at + size].iter().zip(&self.window))
            {
                *slot = Complex::new(sample * weight, 0.0);
            }
            self.fft.process(&mut self.scratch);
            let mut flux = 0.0;
            for (bin, previous) in self.scratch[..size / 2].iter().zip(self.previous.iter_mut()) {
                let magnitude = (1.0 + 100.0 * bin.norm()).ln();
                flux += (magnitude - *previous).max(0.0);
                *previous = magnitude;
            }
            self.flux.push(flux);
            at += self.hop;
        }
        self.pending.drain(..at.min(self.pending.len()));
        self.start += at;
    }

    /// What was found: the flux and the envelope, from which onsets are
    /// picked at any sensitivity without reading the sound again.
    pub fn finish(self) -> Found {
        Found {
            rate: self.rate,
            hop: self.hop,
            window: self.window.len(),
            flux: self.flux,
            energy_ms: self.envelope.finish(),
        }
    }
}

/// A sound's onset flux and 1 ms energy envelope, kept after reading: a few
/// bytes per 5 ms and per ms.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Found {
    rate: u32,
    hop: usize,
    window: usize,
    flux: Vec<f32>,
    /// Each millisecond's mean energy.
    energy_ms: Vec<f32>,
}

impl Found {
    /// The onsets at `sensitivity` (0: only the strongest, 1: every rise), seconds from the start.
    ///
    /// Two kinds of rise are heard, then gated:
    /// - a **flux** peak (a new sound's spectrum: a beat, a click, a plosive,
    ///   a vowel after a consonant), timed at the steepest rise of the 1 ms
    ///   energy near it;
    /// - a **loudness** rise (the energy of the next 25 ms over that of the
    ///   25 ms before, in dB: a soft start — a nasal, an `r`, a vowel out of
    ///   silence — that brings little flux), timed where that ratio peaks, at
    ///   the start of the rise. The sound's first millisecond counts as a
    ///   rise out of silence: a voice at the first sample has its onset.
    ///
    /// Every onset must be *heard*: the sound after it reaches within 40 dB
    /// of the sound's loud level and is louder than the sound just before it.
    /// So a noise floor, a gap's silence and a fade-out have none. Of
    /// candidates closer than 30 ms one onset is kept: a flux peak's time
    /// when there is one, else the rise's.
    pub fn onsets(&self, sensitivity: f32) -> Vec<f64> {
        let sensitivity = sensitivity.clamp(0.0, 1.0);
        let loudness = Loudness::new(&self.energy_ms);
        // (ms, whether a rise): flux peaks sort first at the same ms.
        let mut candidates: Vec<(usize, bool)> =
            self.flux_peaks(sensitivity).into_iter().map(|k| (self.refine(k), false)).collect();
        candidates.extend(loudness.rises(sensitivity).into_iter().map(|ms| (ms, true)));
        candidates.retain(|&(ms, _)| loudness.heard(ms));
        candidates.sort_unstable();
        // A rise 20 dB under an attack that follows within 50 ms is the
        // attack's pre-echo (an MP3's or a Vorbis block's noise smeared ahead
        // of it), not a sound of its own.
        let attacks: Vec<usize> = candidates.iter().filter(|(_, rise)| !rise).map(|&(ms, _)| ms).collect();
        candidates.retain(|&(ms, rise)| {
            let next = attacks.partition_point(|&attack| attack <= ms);
            !rise
                || !attacks[next..]
                    .iter()
                    .take_while(|&&attack| attack <= ms + PRE_ECHO_MS)
                    .any(|&attack| loudness.level(attack) >= loudness.level(ms) * 100.0)
        });
        // Runs of candidates each under 30 ms from the one before are one onset: the
        // first flux peak's time (a sharp attack, timed at its steepest rise,
        // not where an encoder's pre-echo begins), else the first rise's.
        let mut chosen: Vec<usize> = Vec::new();
        let mut run: Vec<(usize, bool)> = Vec::new();
        let close = |run: &mut Vec<(usize, bool)>, chosen: &mut Vec<usize>| {
            let pick = run.iter().find(|(_, rise)| !rise).or(run.first()).map(|&(ms, _)| ms);
            if let Some(ms) = pick
                && chosen.last().is_none_or(|&last| ms >= last + LEAST_GAP_MS)
            {
                chosen.push(ms);
            }
            run.clear();
        };
        for candidate in candidates {
            if run.last().is_some_and(|&(last, _)| candidate.0 >= last + LEAST_GAP_MS) {
                close(&mut run, &mut chosen);
            }
            run.push(candidate);
        }
        close(&mut run, &mut chosen);
        // Milliseconds: indices.
        #[allow(clippy::cast_precision_loss)]
        let onsets = chosen.into_iter().map(|ms| ms as f64 / 1000.0).collect();
        onsets
    }

    /// The flux frames that stand out: the highest within ±15 ms, above
    /// their ±200 ms neighbourhood's mean by `λ` of its spread. The frame
    /// before the first is silence.
    fn flux_peaks(&self, sensitivity: f32) -> Vec<usize> {
        let flux = &self.flux;
        let lambda = 1.0 + 4.0 * (1.0 - sensitivity);
        let most = flux.iter().copied().fold(0.0_f32, f32::max);
        let floor = most * 0.3 * (1.0 - sensitivity);
        let around = 3; // frames: ±15 ms
        let neighbourhood = 40; // frames: ±200 ms
        let mut peaks = vec![];
        for k in 0..flux.len() {
            let (from, to) = (k.saturating_sub(around), (k + around + 1).min(flux.len()));
            let before = if k == 0 { 0.0 } else { flux[k - 1] };
            if flux[from..to].iter().any(|&other| other > flux[k]) || flux[k] <= before {
                continue;
            }
            let (from, to) = (k.saturating_sub(neighbourhood), (k + neighbourhood + 1).min(flux.len()));
            let near = &flux[from..to];
            // Frame counts are small.
            #[allow(clippy::cast_precision_loss)]
            let count = near.len() as f32;
            let mean = near.iter().sum::<f32>() / count;
            let spread = (near.iter().map(|f| (f - mean).powi(2)).sum::<f32>() / count).sqrt();
            if flux[k] > mean + lambda * spread && flux[k] > floor {
                peaks.push(k);
            }
        }
        peaks
    }

    /// The loudness of each millisecond, dB of full scale (a full-scale sine is −3 dB); silence is −120.
    pub fn loudness_db(&self) -> Vec<f32> {
        self.energy_ms.iter().map(|energy| (10.0 * energy.log10()).max(-120.0)).collect()
    }

    /// The millisecond of the steepest rise of the 1 ms energy around frame `k`'s window.
    fn refine(&self, k: usize) -> usize {
        let rate = u64::from(self.rate.max(1));
        let ms_of = |samples: usize| {
            let samples = u64::try_from(samples).unwrap_or(u64::MAX);
            usize::try_from(samples.saturating_mul(1000) / rate).unwrap_or(usize::MAX)
        };
        let first = ms_of((k * self.hop).saturating_sub(self.hop));
        let last = ms_of(k * self.hop + self.window + self.hop).min(self.energy_ms.len());
        if k == 0 {
            // The first frame rises out of the silence before the sound.
            return 0;
        }
        (first.max(1)..last)
            .max_by(|&a, &b| {
                let rise = |i: usize| self.energy_ms[i] - self.energy_ms[i - 1];
                rise(a).total_cmp(&rise(b))
            })
            .unwrap_or(first)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A vowel-like sound: a 140 Hz buzz (its first ten harmonics) at `level`.
    fn buzz(rate: u32, seconds: f64, level: impl Fn(f64) -> f32) -> Vec<f32> {
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let length = (seconds * f64::from(rate)) as usize;
        (0..length)
            .map(|i| {
                #[allow(clippy::cast_precision_loss)]
                let t = i as f64 / f64::from(rate);
                let wave: f64 =
                    (1..=10).map(|h| (std::f64::consts::TAU * 140.0 * f64::from(h) * t).sin() / f64::from(h)).sum();
                #[allow(clippy::cast_possible_truncation)]
                let sample = (wave * 0.3) as f32 * level(t);
                sample
            })
            .collect()
    }

    fn onsets(samples: &[f32], rate: u32) -> Vec<f64> {
        let mut onsets = Onsets::new(rate);
        onsets.push(samples);
        onsets.finish().onsets(0.5)
    }

    #[test]
    fn a_voice_at_the_first_sample_has_its_onset() {
        let rate = 22_050;
        let found = onsets(&buzz(rate, 0.5, |_| 1.0), rate);
        assert_eq!(found, vec![0.0]);
    }

    #[test]
    fn a_slow_fade_out_and_the_silence_after_it_have_no_onset() {
        let rate = 44_100;
        // 0.3 s of silence, a vowel from 0.3 s held to 0.8 s, faded out over 2 s, then silence.
        let level = |t: f64| match t {
            t if t < 0.3 => 0.0,
            t if t < 0.8 => 1.0,
            #[allow(clippy::cast_possible_truncation)]
            t => (1.0 - (t - 0.8) / 2.0).max(0.0) as f32,
        };
        let found = onsets(&buzz(rate, 3.5, level), rate);
        assert_eq!(found.len(), 1, "{found:?}");
        assert!((found[0] - 0.3).abs() <= 0.005, "{found:?}");
    }

    #[test]
    fn a_soft_start_is_found_where_it_starts() {
        // A nasal-like start: the buzz rising over 80 ms from silence at 0.4 s, whose
        // flux is spread thin; the onset is at its start, not where it is loudest.
        let rate = 16_000;
        #[allow(clippy::cast_possible_truncation)]
        let level = |t: f64| if t < 0.4 { 0.0 } else { ((t - 0.4) / 0.08).min(1.0) as f32 };
        let found = onsets(&buzz(rate, 1.0, level), rate);
        assert_eq!(found.len(), 1, "{found:?}");
        assert!((found[0] - 0.4).abs() <= 0.030, "{found:?}");
    }
}
