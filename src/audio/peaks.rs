//! The waveform's min/max peak pyramid: level 0 holds the lowest and the
//! highest sample of every 256; each level above halves the one below. A
//! view draws from the coarsest level still finer than its pixels, so an
//! hour of sound draws as fast as a second.

/// Samples per bucket at level 0.
pub const BUCKET: usize = 256;

/// Min/max pairs at every level.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Peaks {
    /// Level `k` holds one (min, max) per `BUCKET << k` samples.
    levels: Vec<Vec<(f32, f32)>>,
    /// The bucket being filled at level 0.
    open: Option<(f32, f32, usize)>,
}

impl Peaks {
    /// No sound yet.
    pub fn new() -> Self {
        Self::default()
    }

    /// More samples (mono).
    pub fn push(&mut self, samples: &[f32]) {
        for &sample in samples {
            let (low, high, count) = self.open.unwrap_or((f32::MAX, f32::MIN, 0));
            let bucket = (low.min(sample), high.max(sample), count + 1);
            if bucket.2 == BUCKET {
                self.close((bucket.0, bucket.1));
                self.open = None;
            } else {
                self.open = Some(bucket);
            }
        }
    }

    fn close(&mut self, pair: (f32, f32)) {
        let mut pair = pair;
        let mut level = 0;
        loop {
            if self.levels.len() <= level {
                self.levels.push(Vec::new());
            }
            let list = &mut self.levels[level];
            list.push(pair);
            if !list.len().is_multiple_of(2) {
                break;
            }
            let (a, b) = (list[list.len() - 2], list[list.len() - 1]);
            pair = (a.0.min(b.0), a.1.max(b.1));
            level += 1;
        }
    }

    /// `columns` (min, max) pairs across `from_s..to_s` at `sample_rate`,
    /// each from the coarsest level that still has a pair per column.
    pub fn range(&self, from_s: f64, to_s: f64, sample_rate: u32, columns: usize) -> (Vec<f32>, Vec<f32>) {
        let (mut lows, mut highs) = (vec![0.0; columns], vec![0.0; columns]);
        let span_samples = (to_s - from_s).max(0.0) * f64::from(sample_rate);
        // Samples are counted in whole buckets: f64 to usize.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss, clippy::cast_precision_loss)]
        let per_column = (span_samples / columns.max(1) as f64).max(1.0) as usize;
        let mut level = 0;
        while level + 1 < self.levels.len() && (BUCKET << (level + 1)) <= per_column {
            level += 1;
        }
        let Some(list) = self.levels.get(level) else { return (lows, highs) };
        let size = BUCKET << level;
        for column in 0..columns {
            #[allow(clippy::cast_precision_loss, clippy::cast_possible_truncation, clippy::cast_sign_loss)]
            let sample = |share: f64| (from_s * f64::from(sample_rate) + share * span_samples) as usize;
            #[allow(clippy::cast_precision_loss)]
            let (first, last) = (
                sample(column as f64 / columns as f64) / size,
                sample((column + 1) as f64 / columns as f64).saturating_sub(1) / size,
            );
            let pairs = list.get(first..=last.max(first).min(list.len().saturating_sub(1))).unwrap_or(&[]);
            let (low, high) = pairs.iter().fold((f32::MAX, f32::MIN), |(l, h), p| (l.min(p.0), h.max(p.1)));
            if low <= high {
                (lows[column], highs[column]) = (low, high);
            }
        }
        (lows, highs)
    }

    /// The bytes the pyramid holds (for the memory bound).
    pub fn bytes(&self) -> usize {
        self.levels.iter().map(|level| level.len() * size_of::<(f32, f32)>()).sum()
    }
}
