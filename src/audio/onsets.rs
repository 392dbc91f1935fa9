//! Onsets (beats, syllables, clicks) by spectral flux: every 5 ms a window
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

/// Between two onsets at least this long, seconds.
const LEAST_GAP_S: f64 = 0.030;

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
            let sum: f64 = now.iter().map(|sample| f64::from(sample * sample)).sum();
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
    pub fn onsets(&self, sensitivity: f32) -> Vec<f64> {
        let sensitivity = sensitivity.clamp(0.0, 1.0);
        let flux = &self.flux;
        let lambda = 1.0 + 4.0 * (1.0 - sensitivity);
        let most = flux.iter().copied().fold(0.0_f32, f32::max);
        let floor = most * 0.3 * (1.0 - sensitivity);
        let around = 3; // frames: ±15 ms
        let neighbourhood = 40; // frames: ±200 ms
        let mut onsets: Vec<f64> = Vec::new();
        for k in 1..flux.len() {
            let (from, to) = (k.saturating_sub(around), (k + around + 1).min(flux.len()));
            if flux[from..to].iter().any(|&other| other > flux[k]) || flux[k] <= flux[k - 1] {
                continue;
            }
            let (from, to) = (k.saturating_sub(neighbourhood), (k + neighbourhood + 1).min(flux.len()));
            let near = &flux[from..to];
            // Frame counts are small.
            #[allow(clippy::cast_precision_loss)]
            let count = near.len() as f32;
            let mean = near.iter().sum::<f32>() / count;
            let spread = (near.iter().map(|f| (f - mean).powi(2)).sum::<f32>() / count).sqrt();
            if flux[k] <= mean + lambda * spread || flux[k] <= floor {
                continue;
            }
            let at = self.refine(k);
            if onsets.last().is_none_or(|last| at - last >= LEAST_GAP_S) {
                onsets.push(at);
            }
        }
        onsets
    }

    /// The loudness of each millisecond, dB of full scale (a full-scale sine is −3 dB); silence is −120.
    pub fn loudness_db(&self) -> Vec<f32> {
        self.energy_ms.iter().map(|energy| (10.0 * energy.log10()).max(-120.0)).collect()
    }

    /// The steepest rise of the 1 ms energy around frame `k`'s window, seconds.
    fn refine(&self, k: usize) -> f64 {
        let rate = u64::from(self.rate.max(1));
        let ms_of = |samples: usize| {
            let samples = u64::try_from(samples).unwrap_or(u64::MAX);
            usize::try_from(samples.saturating_mul(1000) / rate).unwrap_or(usize::MAX)
        };
        let first = ms_of((k * self.hop).saturating_sub(self.hop));
        let last = ms_of(k * self.hop + self.window + self.hop).min(self.energy_ms.len());
        let best = (first.max(1)..last)
            .max_by(|&a, &b| {
                let rise = |i: usize| self.energy_ms[i] - self.energy_ms[i - 1];
                rise(a).total_cmp(&rise(b))
            })
            .unwrap_or(first);
        // Milliseconds: an index.
        #[allow(clippy::cast_precision_loss)]
        let seconds = best as f64 / 1000.0;
        seconds
    }
}
