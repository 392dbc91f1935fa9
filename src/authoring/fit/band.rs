//! Per channel, the end values a move may take: as the samples of a move are
//! added one by one, the range of end values whose playback keeps every one
//! of them within the tolerance, in the board's own arithmetic — exact
//! integer intervals for the PLEN2's 16.16 steps, slopes for the servo
//! board's linear steps. Each sample costs O(1).

/// A sample as a band reads it: the value wanted, and the whole values
/// within the tolerance of it (worked out once per fit).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// The value wanted.
    pub wanted: f64,
    /// The lowest whole value within the tolerance.
    pub low: i64,
    /// The highest whole value within the tolerance.
    pub high: i64,
}

impl Sample {
    /// `wanted`, within `tolerance`.
    pub fn new(wanted: f64, tolerance: f64) -> Self {
        let (low, high) = whole_within(wanted, tolerance);
        Self { wanted, low, high }
    }
}

/// Every sample of `rows`, within `tolerance`.
pub fn samples_of(rows: &[Vec<f64>], tolerance: f64) -> Vec<Vec<Sample>> {
    rows.iter().map(|row| row.iter().map(|&wanted| Sample::new(wanted, tolerance)).collect()).collect()
}

/// The end values a move from one anchor may take, sample by sample.
pub trait Band {
    /// Adds the next sample (update `k`, counted from 1); false once no move
    /// of any length from this anchor can keep every sample so far.
    fn push(&mut self, sample: &Sample) -> bool;
    /// The lowest and highest end values of a move over exactly the samples
    /// added whose playback keeps every one of them; `None` when none does.
    fn ends(&self) -> Option<(i32, i32)>;
    /// As [`Band::ends`], of the moves in which the channel moves until the
    /// move's end (not arriving early and holding, on a board that allows it).
    fn line_ends(&self) -> Option<(i32, i32)> {
        self.ends()
    }
    /// Whether a line over the samples so far is still possible (so that the
    /// channel may pace a longer move, or end one at all).
    fn line_open(&self) -> bool {
        true
    }
}

/// The smallest and the largest whole values within `tolerance` of `wanted`,
/// as `(value − wanted).abs() <= tolerance` decides it (what the fit's check uses).
fn whole_within(wanted: f64, tolerance: f64) -> (i64, i64) {
    let within = |value: i64| {
        // Values of an i16 range and a little beyond: exact in f64.
        #[allow(clippy::cast_precision_loss)]
        let value = value as f64;
        (value - wanted).abs() <= tolerance
    };
    // Bounded to a little beyond an i16's range before converting.
    #[allow(clippy::cast_possible_truncation)]
    let (mut low, mut high) = (
        (wanted - tolerance).ceil().clamp(-70_000.0, 70_000.0) as i64,
        (wanted + tolerance).floor().clamp(-70_000.0, 70_000.0) as i64,
    );
    while low <= high && !within(low) {
        low += 1;
    }
    while low > high.saturating_sub(1) && within(low - 1) {
        low -= 1;
    }
    while high >= low && !within(high) {
        high -= 1;
    }
    while within(high + 1) {
        high += 1;
    }
    (low, high)
}

/// The PLEN2's moves: at cycle `k` a joint is at `from + ⌊d·k / 65536⌋`,
/// where `d = trunc((to − from)·65536 / cycles)` (plen2.md §6). Each sample
/// bounds `d` to an integer interval (independent of the move's length); a
/// length then bounds `to`.
#[derive(Clone, Debug)]
pub struct StepBand {
    from: i64,
    cycles: i64,
    low: i64,
    high: i64,
}

/// 1.0 in 16.16.
const ONE: i64 = 65_536;

impl StepBand {
    /// Moves from the frame value `from` (the tolerance is in each [`Sample`]'s whole values).
    pub fn new(from: i32) -> Self {
        Self { from: i64::from(from), cycles: 0, low: i64::MIN, high: i64::MAX }
    }
}

impl Band for StepBand {
    fn push(&mut self, sample: &Sample) -> bool {
        self.cycles += 1;
        let k = self.cycles;
        let (low, high) = (sample.low, sample.high);
        // ⌊d·k/ONE⌋ ≥ low − from  ⇔  d ≥ ⌈(low − from)·ONE / k⌉;
        // ⌊d·k/ONE⌋ ≤ high − from ⇔  d·k < (high − from + 1)·ONE ⇔ d ≤ ⌊((high − from + 1)·ONE − 1) / k⌋.
        self.low = self.low.max(-floor_div(-(low - self.from) * ONE, k));
        self.high = self.high.min(floor_div((high - self.from + 1) * ONE - 1, k));
        self.low <= self.high
    }

    fn ends(&self) -> Option<(i32, i32)> {
        let cycles = self.cycles;
        if cycles == 0 || cycles > 255 || self.low > self.high {
            return None;
        }
        // The step d(Δ) = trunc(Δ·ONE / cycles) grows with Δ = to − from: the
        // smallest Δ whose step is at least `low`, the largest whose step is at most `high`.
        let first =
            if self.low > 0 { div_ceil(self.low * cycles, ONE) } else { ((self.low - 1) * cycles).div_euclid(ONE) + 1 };
        let last = if self.high < 0 {
            (self.high * cycles).div_euclid(ONE)
        } else {
            div_ceil((self.high + 1) * cycles, ONE) - 1
        };
        let lowest = (self.from + first).max(i64::from(i16::MIN));
        let highest = (self.from + last).min(i64::from(i16::MAX));
        (lowest <= highest).then(|| (i32::try_from(lowest).unwrap_or(0), i32::try_from(highest).unwrap_or(0)))
    }
}

/// ⌊value⌋ of a value within an i16's range: a cast corrected by one (no
/// call to `floor`, which a band's every sample would otherwise pay).
fn fast_floor(value: f64) -> i32 {
    // Within an i16's range (clamped by the caller): the cast is exact.
    #[allow(clippy::cast_possible_truncation)]
    let truncated = value as i32;
    if f64::from(truncated) > value { truncated - 1 } else { truncated }
}

/// ⌈a / b⌉ for b > 0.
fn div_ceil(a: i64, b: i64) -> i64 {
    a.div_euclid(b) + i64::from(a.rem_euclid(b) != 0)
}

/// ⌊a / k⌋ for a cycle count k (1..=255) and |a| far below 2^52: a float
/// division truncated (a cast, not a call to `floor`), corrected to the exact
/// integer (faster than an integer division).
fn floor_div(a: i64, k: i64) -> i64 {
    // |a| < 2^52 and k ≤ 255: exact in f64, and the quotient fits an i64;
    // truncation is within one of the floor, which the checks below correct.
    #[allow(clippy::cast_precision_loss, clippy::cast_possible_truncation)]
    let mut quotient = (a as f64 / k as f64) as i64;
    if quotient * k > a {
        quotient -= 1;
    } else if (quotient + 1) * k <= a {
        quotient += 1;
    }
    quotient
}

/// The servo board's moves: at update `k` of `updates` a servo is at
/// `from + (to − from)·k / updates`. Each sample bounds the slope `(to −
/// from) / updates`; a length then bounds `to`. A hair inside the exact
/// bounds, so that the check in floating point agrees.
#[derive(Clone, Debug)]
pub struct LinearBand {
    from: f64,
    tolerance: f64,
    updates: u32,
    low: f64,
    high: f64,
}

/// How far inside its exact bounds an end value is taken (degrees × updates).
const INSIDE: f64 = 1e-6;

impl LinearBand {
    /// Moves from the stored value `from`.
    pub fn new(from: i32, tolerance: f64) -> Self {
        Self { from: f64::from(from), tolerance, updates: 0, low: f64::NEG_INFINITY, high: f64::INFINITY }
    }
}

impl Band for LinearBand {
    fn push(&mut self, sample: &Sample) -> bool {
        let wanted = sample.wanted;
        self.updates += 1;
        let per_update = f64::from(self.updates).recip();
        self.low = self.low.max((wanted - self.tolerance - self.from) * per_update);
        self.high = self.high.min((wanted + self.tolerance - self.from) * per_update);
        self.low <= self.high
    }

    fn ends(&self) -> Option<(i32, i32)> {
        let updates = f64::from(self.updates);
        let limit = |value: f64| value.max(f64::from(i16::MIN)).min(f64::from(i16::MAX));
        let lowest = -fast_floor(-limit(self.from + self.low * updates + INSIDE));
        let highest = fast_floor(limit(self.from + self.high * updates - INSIDE));
        (self.updates > 0 && lowest <= highest).then_some((lowest, highest))
    }
}

/// The servo board's moves, each servo with its own interval: within a step
/// a servo moves linearly to its angle over its own interval (at most the
/// step's) and holds there until the step's longest interval ends (an action
/// lasts its longest step: `project::timing`). After `L` samples a channel
/// may end where a line over all `L` ends ([`LinearBand`]), or where a line
/// over fewer ends if every later sample keeps that value: those are kept as
/// whole values ([`Runs`]), narrowed by each new sample.
#[derive(Clone, Debug)]
pub struct HoldBand {
    line: LinearBand,
    line_open: bool,
    held: Runs,
}

/// Whole values as bits from a base value: the held values of a channel are
/// all within the tolerance of its latest sample, so a few bits cover them
/// (a wider tolerance keeps the 64 nearest the base: fewer end values, every
/// one still keeping its samples). Integer work only: a band is made for
/// every channel of every move the fitter tries, and pushed every update.
#[derive(Clone, Copy, Debug, Default)]
struct Runs {
    base: i64,
    bits: u64,
}

/// The bits of the values from `low` to `high`, from `base` (none outside 0..64).
fn bits_of(base: i64, low: i64, high: i64) -> u64 {
    let (low, high) = ((low - base).max(0), (high - base).min(63));
    if low > high {
        return 0;
    }
    let width = high - low + 1;
    let ones = if width >= 64 { u64::MAX } else { (1u64 << width) - 1 };
    ones << low
}

impl Runs {
    /// Adds the values from `low` to `high`.
    fn add(&mut self, (low, high): (i64, i64)) {
        if self.bits == 0 {
            self.base = low;
        } else if low < self.base {
            // Lower than any kept: based on it, the highest kept may fall off.
            let shift = u32::try_from(self.base - low).unwrap_or(u32::MAX);
            self.bits = self.bits.checked_shl(shift).unwrap_or(0);
            self.base = low;
        }
        self.bits |= bits_of(self.base, low, high);
    }

    /// Keeps the values from `low` to `high`.
    fn narrow(&mut self, low: i64, high: i64) {
        self.bits &= bits_of(self.base, low, high);
    }

    /// The widest run of values.
    fn widest(&self) -> Option<(i64, i64)> {
        let (mut best, mut bits, mut at): (Option<(i64, i64)>, u64, i64) = (None, self.bits, 0);
        while bits != 0 {
            let skip = i64::from(bits.trailing_zeros());
            bits = bits.checked_shr(u32::try_from(skip).unwrap_or(64)).unwrap_or(0);
            at += skip;
            let width = i64::from(bits.trailing_ones());
            let run = (self.base + at, self.base + at + width - 1);
            if best.is_none_or(|(low, high)| width > high - low) {
                best = Some(run);
            }
            bits = bits.checked_shr(u32::try_from(width).unwrap_or(64)).unwrap_or(0);
            at += width;
        }
        best
    }
}

impl HoldBand {
    /// Moves from the stored value `from`.
    pub fn new(from: i32, tolerance: f64) -> Self {
        Self { line: LinearBand::new(from, tolerance), line_open: true, held: Runs::default() }
    }
}

impl Band for HoldBand {
    fn push(&mut self, sample: &Sample) -> bool {
        // Arriving before this update: where the line ends so far, then held.
        if self.line_open
            && let Some((low, high)) = self.line.ends()
        {
            // Only what this sample keeps is worth adding.
            let (low, high) = (i64::from(low).max(sample.low), i64::from(high).min(sample.high));
            if low <= high {
                self.held.add((low, high));
            }
        }
        if self.held.bits != 0 {
            self.held.narrow(sample.low, sample.high);
        }
        self.line_open = self.line_open && self.line.push(sample);
        self.line_open || self.held.bits != 0
    }

    /// The widest run of the line's ends and the held ones (every value of
    /// it keeps every sample; a value between two runs would not).
    fn ends(&self) -> Option<(i32, i32)> {
        if self.held.bits == 0 {
            return self.line_ends();
        }
        let mut runs = self.held;
        if let Some((low, high)) = self.line_ends() {
            runs.add((i64::from(low), i64::from(high)));
        }
        let (low, high) = runs.widest()?;
        Some((i32::try_from(low).ok()?, i32::try_from(high).ok()?))
    }

    fn line_ends(&self) -> Option<(i32, i32)> {
        if self.line_open { self.line.ends() } else { None }
    }

    fn line_open(&self) -> bool {
        self.line_open
    }
}

#[cfg(test)]
use crate::protocol::plen2::playback::step_value;

/// What the PLEN2 plays at cycle `k` of a move (for the tests here).
#[cfg(test)]
fn played(from: i32, to: i32, cycles: i64, k: i64) -> f64 {
    let narrow = |value: i32| i16::try_from(value).unwrap_or(0);
    f64::from(step_value(narrow(from), narrow(to), u8::try_from(cycles).unwrap_or(0), u16::try_from(k).unwrap_or(0)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Repeatable draws in `0..range` (xorshift from `seed`).
    fn draws(mut seed: u64) -> impl FnMut(i64) -> i64 {
        move |range: i64| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            i64::try_from(seed % u64::try_from(range).unwrap()).unwrap()
        }
    }

    /// Every end value a brute-force search over the firmware's arithmetic
    /// finds, and no other, for many anchors, samples and tolerances.
    #[test]
    fn the_plen2_band_holds_exactly_the_ends_the_firmware_keeps_within() {
        let mut next = draws(0x2545_f491);
        let mut kept = 0;
        for _ in 0..400 {
            let from = i32::try_from(next(1200) - 600).unwrap();
            let cycles = next(40) + 1;
            let slope = (next(2000) - 1000) as f64 / 100.0;
            let tolerance = (next(40) as f64) / 4.0 + 0.5;
            let samples: Vec<f64> =
                (1..=cycles).map(|k| f64::from(from) + slope * k as f64 + (next(100) as f64 - 50.0) / 40.0).collect();
            let mut band = StepBand::new(from);
            let open = samples.iter().all(|&wanted| band.push(&Sample::new(wanted, tolerance)));
            let keeps = |to: i32| {
                (1..=cycles).all(|k| {
                    (played(from, to, cycles, k) - samples[usize::try_from(k - 1).unwrap()]).abs() <= tolerance
                })
            };
            let brute: Vec<i32> = (from - 2000..=from + 2000).filter(|&to| keeps(to)).collect();
            match band.ends() {
                Some((lowest, highest)) => {
                    assert!(open);
                    kept += 1;
                    assert_eq!(brute, (lowest..=highest).collect::<Vec<_>>(), "from {from}, {cycles} cycles");
                }
                None => assert!(brute.is_empty(), "missed {brute:?} from {from}, {cycles} cycles"),
            }
        }
        assert!(kept > 100, "most cases keep some end value: {kept} of 400");
    }

    #[test]
    fn the_fast_floor_is_floor() {
        for tenths in -400_000..=400_000 {
            let value = f64::from(tenths) / 10.0 + 0.05;
            assert_eq!(f64::from(fast_floor(value)), value.floor(), "{value}");
            assert_eq!(f64::from(fast_floor(f64::from(tenths))), f64::from(tenths));
        }
    }

    #[test]
    fn the_fast_floor_division_is_the_exact_one() {
        for k in 1..=255_i64 {
            for a in (-70_000 * ONE..=70_000 * ONE).step_by(9_999_991).chain(-3 * k..=3 * k) {
                assert_eq!(floor_div(a, k), a.div_euclid(k), "{a} / {k}");
            }
        }
    }

    /// Every end value the servo board's band gives keeps every sample with
    /// some interval of the servo's own (a line to it, then held), found by
    /// brute force over intervals and values; and it gives one whenever the
    /// brute force finds one.
    #[test]
    fn the_servo_band_with_early_arrivals_gives_only_ends_some_interval_keeps() {
        let mut next = draws(0x9e37_79b9);
        let mut held = 0;
        for _ in 0..600 {
            let from = i32::try_from(next(200) - 100).unwrap();
            let updates = usize::try_from(next(30) + 1).unwrap();
            let arrive = next(i64::try_from(updates).unwrap()) + 1;
            let slope = (next(800) - 400) as f64 / 100.0;
            let tolerance = (next(8) as f64) / 4.0 + 0.5;
            let samples: Vec<f64> = (1..=updates as i64)
                .map(|k| f64::from(from) + slope * k.min(arrive) as f64 + (next(100) as f64 - 50.0) / 60.0)
                .collect();
            let mut band = HoldBand::new(from, tolerance);
            let open = samples.iter().all(|&wanted| band.push(&Sample::new(wanted, tolerance)));
            let keeps = |to: i32| {
                (1..=updates).any(|arrival| {
                    samples.iter().enumerate().all(|(index, &wanted)| {
                        let out = if index + 1 >= arrival {
                            f64::from(to)
                        } else {
                            f64::from(from) + f64::from(to - from) * (index + 1) as f64 / arrival as f64
                        };
                        (out - wanted).abs() <= tolerance
                    })
                })
            };
            let brute: Vec<i32> = (from - 400..=from + 400).filter(|&to| keeps(to)).collect();
            match band.ends() {
                Some((lowest, highest)) => {
                    assert!(open);
                    assert!((lowest..=highest).all(keeps), "from {from}: {lowest}..={highest}, brute {brute:?}");
                    held += usize::from(band.line_ends().is_none());
                }
                None => assert!(brute.is_empty(), "missed {brute:?} from {from}, {updates} updates"),
            }
        }
        assert!(held > 50, "many cases keep only a held value: {held} of 600");
    }

    #[test]
    fn the_servo_band_holds_the_ends_whose_line_keeps_every_sample() {
        // From 0, samples on the line to 30 over 10 updates, within 0.5°.
        let mut band = LinearBand::new(0, 0.5);
        for k in 1..=10 {
            assert!(band.push(&Sample::new(3.0 * f64::from(k), 0.5)));
        }
        assert_eq!(band.ends(), Some((30, 30)));
        // A wider tolerance takes the neighbours whose line stays within it
        // (28 and 32 stray 2° at the last update).
        let mut band = LinearBand::new(0, 2.05);
        for k in 1..=10 {
            band.push(&Sample::new(3.0 * f64::from(k), 2.05));
        }
        assert_eq!(band.ends(), Some((28, 32)));
        // A sample off the line ends it.
        assert!(!band.push(&Sample::new(60.0, 2.05)));
        assert_eq!(band.ends(), None);
    }
}
