//! Loudness rises: where a sound gets louder, on its 1 ms energy envelope —
//! the soft starts (a nasal, an `r`, a vowel out of silence) that bring
//! little spectral flux — and whether an onset is heard at all.

/// The windows a loudness rise compares, ms.
const RISE_MS: usize = 25;

/// How soon after an onset its sound must be heard, ms.
const HEARD_MS: usize = 60;

/// An energy below any sound's (−100 dBFS), so silence over silence is no rise.
const SILENT: f64 = 1e-10;

/// A sound's 1 ms energy envelope with its running sums: the mean energy of
/// any stretch in constant time.
pub(super) struct Loudness<'a> {
    energy_ms: &'a [f32],
    /// `sums[i]`: the energy of milliseconds `0..i`.
    sums: Vec<f64>,
    /// The energy of the loudest 10 ms (of each 10 ms stretch).
    loud: f64,
}

impl<'a> Loudness<'a> {
    pub(super) fn new(energy_ms: &'a [f32]) -> Self {
        let mut sums = Vec::with_capacity(energy_ms.len() + 1);
        let mut total = 0.0;
        sums.push(total);
        for energy in energy_ms {
            total += f64::from(*energy);
            sums.push(total);
        }
        let loud = energy_ms
            .chunks(10)
            .map(|chunk| chunk.iter().map(|e| f64::from(*e)).sum::<f64>() / 10.0)
            .fold(0.0, f64::max);
        Self { energy_ms, sums, loud }
    }

    /// The mean energy of the `length` milliseconds ending at `to` (before
    /// the sound's start and after its end is silence).
    fn mean(&self, to: usize, length: usize) -> f64 {
        let end = to.min(self.energy_ms.len());
        let start = to.saturating_sub(length).min(end);
        // Window lengths are tens of milliseconds.
        #[allow(clippy::cast_precision_loss)]
        let length = length.max(1) as f64;
        (self.sums[end] - self.sums[start]) / length
    }

    /// The mean energy of the `RISE_MS` before `ms`.
    fn before(&self, ms: usize) -> f64 {
        self.mean(ms, RISE_MS)
    }

    /// The mean energy of the `RISE_MS` from `ms`.
    fn after(&self, ms: usize) -> f64 {
        self.mean(ms + RISE_MS, RISE_MS)
    }

    /// The mean energy of the 10 ms from `ms`: an onset's level.
    pub(super) fn level(&self, ms: usize) -> f64 {
        self.mean(ms + 10, 10)
    }

    /// How much louder the `RISE_MS` from `ms` are than the `RISE_MS` before, dB.
    fn rise_db(&self, ms: usize) -> f64 {
        10.0 * ((self.after(ms) + SILENT) / (self.before(ms) + SILENT)).log10()
    }

    /// Where the loudness rises by more than 15 − 12·sensitivity dB (9 dB at
    /// the default 0.5) at the highest such rise within ±15 ms, each timed
    /// at the start of its rise.
    pub(super) fn rises(&self, sensitivity: f32) -> Vec<usize> {
        let least_db = 15.0 - 12.0 * f64::from(sensitivity);
        let rise: Vec<f64> = (0..self.energy_ms.len()).map(|ms| self.rise_db(ms)).collect();
        let around = 15;
        (0..rise.len())
            .filter(|&ms| {
                let from = ms.saturating_sub(around);
                rise[ms] > least_db
                    && rise[from..(ms + around + 1).min(rise.len())]
                        .iter()
                        .enumerate()
                        // The first of equal highs.
                        .all(|(i, &other)| other < rise[ms] || (other <= rise[ms] && from + i >= ms))
            })
            .map(|ms| self.rise_start(ms))
            .collect()
    }

    /// Where a rise found at `ms` starts: the first millisecond from `ms` on
    /// that is 6 dB above the `RISE_MS` before it (a short click keeps the
    /// ratio flat for as long as the window holds it whole).
    fn rise_start(&self, ms: usize) -> usize {
        let above = (self.before(ms) + SILENT) * 4.0;
        let end = (ms + RISE_MS).min(self.energy_ms.len());
        (ms..end).find(|&i| f64::from(self.energy_ms[i]) > above).unwrap_or(ms)
    }

    /// Whether an onset at `ms` is heard: within `HEARD_MS` the sound
    /// reaches 40 dB of its loudest 10 ms, and the `RISE_MS` from it are
    /// louder than the `RISE_MS` before.
    pub(super) fn heard(&self, ms: usize) -> bool {
        let reaches = (0..HEARD_MS / 10).any(|step| self.level(ms + step * 10) >= self.loud * 1e-4);
        reaches && self.after(ms) > self.before(ms)
    }
}
