//! The recordings the fit is measured on (`cargo bench --bench fit` and the
//! tests): smooth sums of sines, triangle waves (sharp corners), damped
//! oscillations and holds joined by quick ramps, sampled at a board's update.

use std::f64::consts::TAU;

/// One recording: its name and its rows (`rows[u]`: every channel at update `u + 1`).
pub type Recording = (&'static str, Vec<Vec<f64>>);

/// `seconds` of `channels` channels, `value(c, t)` sampled every `update_ms` from the first update.
fn sampled(seconds: f64, update_ms: f64, channels: usize, value: impl Fn(f64, f64) -> f64) -> Vec<Vec<f64>> {
    // Bounded recordings: a few thousand updates.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let count = (seconds * 1000.0 / update_ms) as usize;
    (1..=count)
        .map(|k| {
            // Counts far below 2^52.
            #[allow(clippy::cast_precision_loss)]
            let t = k as f64 * update_ms / 1000.0;
            (0..channels)
                .map(|channel| {
                    #[allow(clippy::cast_precision_loss)]
                    let c = channel as f64;
                    value(c, t)
                })
                .collect()
        })
        .collect()
}

/// Each channel a sum of two sines of its own frequencies (0.1..0.6 Hz),
/// starting at 0, of amplitude `amplitude`.
pub fn sines(seconds: f64, update_ms: f64, channels: usize, amplitude: f64) -> Vec<Vec<f64>> {
    sampled(seconds, update_ms, channels, |c, t| {
        let (f1, f2) = (0.1 + 0.02 * c, 0.25 + 0.02 * c);
        amplitude * (0.7 * (TAU * f1 * t).sin() + 0.3 * (TAU * f2 * t + c).sin() - 0.3 * c.sin())
    })
}

/// The set, for a board updating every `update_ms` whose values are
/// `amplitude` at full swing.
pub fn recordings(update_ms: f64, amplitude: f64) -> Vec<Recording> {
    let triangle = |phase: f64| 4.0 * (phase - (phase + 0.5).floor()).abs() - 1.0;
    vec![
        ("sines, 18 channels", sines(8.0, update_ms, 18, amplitude)),
        (
            "corners, 6 channels",
            sampled(8.0, update_ms, 6, |c, t| amplitude * (triangle(t / (1.5 + 0.3 * c) + 0.25) - triangle(0.25))),
        ),
        (
            "damped, 6 channels",
            sampled(8.0, update_ms, 6, |c, t| amplitude * (-t / 3.0).exp() * (TAU * (0.6 + 0.1 * c) * t).sin()),
        ),
        (
            "holds and ramps, 4 channels",
            sampled(8.0, update_ms, 4, |c, t| {
                let (second, into) = (t.floor(), t.fract());
                let level = |s: f64| amplitude * ((s * 1.7 + c * 2.3).sin() * 0.9);
                let ramp = (into / 0.15).min(1.0);
                let before = if second < 1.0 { 0.0 } else { level(second - 1.0) };
                before + (level(second) - before) * ramp
            }),
        ),
    ]
}
