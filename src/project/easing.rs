//! How a move runs between two poses: the curve a user means. The boards
//! play only straight moves, so an eased move is baked into straight pieces
//! before it is sent (`authoring::bake`); the project keeps the curve.

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
}

impl Easing {
    /// Every curve, in the order menus list them.
    pub const ALL: [Self; 5] = [Self::Linear, Self::EaseIn, Self::EaseOut, Self::EaseInOut, Self::Hold];

    /// The part of the way covered at `t`, the part of the time gone (0..=1).
    pub fn at(self, t: f64) -> f64 {
        let t = t.clamp(0.0, 1.0);
        match self {
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

    /// Its name in files and on the command line.
    pub fn tag(self) -> &'static str {
        match self {
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
}
