//! How a move runs between two poses: the curve a user means. The boards
//! play only straight moves, so an eased move is baked into straight pieces
//! before it is sent (`authoring::bake`); the project keeps the curve.
//!
//! A curve is one of five presets or a cubic Bézier shaped on the graph
//! (`Easing::Shaped`): its two handles in thousandths of the move's time and
//! of its way, the way kept within 0..=1000 so that a curve never runs past
//! either of its keys (a servo never passes the limits its keys keep).

use serde::{Deserialize, Serialize};

/// The curve of one move, from where the servo or joint was to where it goes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Easing {
    /// Constant speed (what the board does on its own).
    #[default]
    Linear,
    /// Starts slowly, arrives fast (quadratic).
    EaseIn,
    /// Starts fast, arrives slowly (quadratic).
    EaseOut,
    /// Slow at both ends (quadratic each half).
    EaseInOut,
    /// Stays, then jumps at the end.
    Hold,
    /// A cubic Bézier shaped by its two handles.
    Shaped(Handles),
}

/// The two inner control points of a move's cubic Bézier, from (0, 0) to
/// (1000, 1000): x in thousandths of the move's time, y of its way. Each lies
/// within 0..=1000 on both axes, so the curve goes forward in time and stays
/// between its keys.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct Handles {
    /// The handle leaving the move's start: time, way (thousandths).
    #[serde(deserialize_with = "thousandths")]
    pub out: [i16; 2],
    /// The handle arriving at the move's end: time, way (thousandths).
    #[serde(rename = "in", deserialize_with = "thousandths")]
    pub arrive: [i16; 2],
}

fn thousandths<'de, D: serde::Deserializer<'de>>(deserializer: D) -> Result<[i16; 2], D::Error> {
    let pair = <[i16; 2]>::deserialize(deserializer)?;
    if pair.iter().all(|value| (0..=1000).contains(value)) {
        Ok(pair)
    } else {
        Err(serde::de::Error::custom(format!("a handle {pair:?} outside 0..=1000 (thousandths of the move)")))
    }
}

impl Handles {
    /// Handles at `out` and `arrive` (thousandths), each moved within 0..=1000.
    pub fn new(out: [i16; 2], arrive: [i16; 2]) -> Self {
        let within = |pair: [i16; 2]| pair.map(|value| value.clamp(0, 1000));
        Self { out: within(out), arrive: within(arrive) }
    }

    /// The part of the way covered at `t`, the part of the time gone: the
    /// curve's parameter found where its time is `t` (the time goes forward,
    /// so a bisection finds it), then its way there.
    pub fn at(self, t: f64) -> f64 {
        let t = t.clamp(0.0, 1.0);
        let [x1, y1] = self.out.map(|value| f64::from(value) / 1000.0);
        let [x2, y2] = self.arrive.map(|value| f64::from(value) / 1000.0);
        let cubic = |s: f64, p1: f64, p2: f64| {
            let r = 1.0 - s;
            3.0 * r * r * s * p1 + 3.0 * r * s * s * p2 + s * s * s
        };
        let (mut low, mut high) = (0.0_f64, 1.0_f64);
        for _ in 0..52 {
            let middle = 0.5 * (low + high);
            if cubic(middle, x1, x2) < t {
                low = middle;
            } else {
                high = middle;
            }
        }
        cubic(0.5 * (low + high), y1, y2)
    }
}

impl Easing {
    /// Every curve, in the order menus list them.
    pub const ALL: [Self; 5] = [Self::Linear, Self::EaseIn, Self::EaseOut, Self::EaseInOut, Self::Hold];

    /// The part of the way covered at `t`, the part of the time gone (0..=1).
    pub fn at(self, t: f64) -> f64 {
        let t = t.clamp(0.0, 1.0);
        match self {
            Self::Shaped(handles) => handles.at(t),
            Self::Linear => t,
            Self::EaseIn => t * t,
            Self::EaseOut => 1.0 - (1.0 - t) * (1.0 - t),
            Self::EaseInOut if t < 0.5 => 2.0 * t * t,
            Self::EaseInOut => 1.0 - 2.0 * (1.0 - t) * (1.0 - t),
            Self::Hold if t < 1.0 => 0.0,
            Self::Hold => 1.0,
        }
    }

    /// True for the board's own straight move (nothing to bake; not written in files).
    // serde's skip_serializing_if passes a reference.
    #[allow(clippy::trivially_copy_pass_by_ref)]
    pub fn is_linear(&self) -> bool {
        *self == Self::Linear
    }

    /// The handles that draw it on the graph: a preset's own Bézier (linear,
    /// ease in and ease out exactly; ease in-out and hold as near as one cubic
    /// comes). Moving one makes the move `Shaped` from there.
    pub fn handles(self) -> Handles {
        let third = 333;
        match self {
            Self::Linear => Handles::new([third, third], [1000 - third, 1000 - third]),
            Self::EaseIn => Handles::new([third, 0], [1000 - third, third]),
            Self::EaseOut => Handles::new([third, 1000 - third], [1000 - third, 1000]),
            Self::EaseInOut => Handles::new([500, 0], [500, 1000]),
            Self::Hold => Handles::new([1000, 0], [1000, 0]),
            Self::Shaped(handles) => handles,
        }
    }

    /// Its name in files and on the command line.
    pub fn tag(self) -> &'static str {
        match self {
            Self::Shaped(_) => "shaped",
            Self::Linear => "linear",
            Self::EaseIn => "ease_in",
            Self::EaseOut => "ease_out",
            Self::EaseInOut => "ease_in_out",
            Self::Hold => "hold",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_curve_starts_at_0_ends_at_1_and_never_goes_back() {
        for easing in Easing::ALL {
            assert!(easing.at(0.0).abs() < 1e-12, "{easing:?}");
            assert!((easing.at(1.0) - 1.0).abs() < 1e-12, "{easing:?}");
            let mut before = 0.0;
            for step in 0..=1000 {
                let now = easing.at(f64::from(step) / 1000.0);
                assert!(now >= before - 1e-12 && now <= 1.0 + 1e-12, "{easing:?} at {step}");
                before = now;
            }
        }
        assert!((Easing::EaseIn.at(0.5) - 0.25).abs() < 1e-12);
        assert!((Easing::EaseOut.at(0.5) - 0.75).abs() < 1e-12);
        assert!((Easing::EaseInOut.at(0.5) - 0.5).abs() < 1e-12);
        assert!(Easing::Hold.at(0.999).abs() < 1e-12);
    }

    #[test]
    fn a_shaped_curve_goes_forward_stays_between_its_keys_and_matches_the_presets_it_draws() {
        // Linear, ease in and ease out are cubics of their own: their handles draw them exactly
        // (to the thousandths the handles are kept in).
        for preset in [Easing::Linear, Easing::EaseIn, Easing::EaseOut] {
            let shaped = Easing::Shaped(preset.handles());
            for step in 0..=100 {
                let t = f64::from(step) / 100.0;
                assert!((shaped.at(t) - preset.at(t)).abs() < 2e-3, "{preset:?} at {t}");
            }
        }
        // An S the other way round: fast, flat, fast.
        let handles = Handles::new([0, 900], [1000, 100]);
        let mut before = 0.0;
        for step in 0..=1000 {
            let now = handles.at(f64::from(step) / 1000.0);
            assert!((-1e-12..=1.0 + 1e-12).contains(&now), "{now}");
            assert!(now >= before - 1e-9, "forward only");
            before = now;
        }
        assert!((handles.at(0.5) - 0.5).abs() < 1e-9, "symmetric");
        assert!(handles.at(0.1) > 0.2, "fast at first: {}", handles.at(0.1));
        assert_eq!(Handles::new([-50, 1200], [500, 500]).out, [0, 1000], "kept within the move");
    }

    #[test]
    fn a_shaped_curve_is_written_with_its_handles_and_a_handle_outside_the_move_is_refused() {
        let easing = Easing::Shaped(Handles::new([250, 0], [750, 1000]));
        let text = serde_json::to_string(&easing).unwrap();
        assert_eq!(text, r#"{"shaped":{"out":[250,0],"in":[750,1000]}}"#);
        assert_eq!(serde_json::from_str::<Easing>(&text).unwrap(), easing);
        assert_eq!(serde_json::to_string(&Easing::EaseIn).unwrap(), r#""ease_in""#, "presets as before");
        let error = serde_json::from_str::<Easing>(r#"{"shaped":{"out":[250,1500],"in":[750,1000]}}"#).unwrap_err();
        assert!(error.to_string().contains("outside 0..=1000"), "{error}");
    }
}
