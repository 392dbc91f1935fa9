//! rFLEX mobile bases (`rflex.md`): big-endian frames with an XOR checksum and
//! optional byte stuffing, the commands and reports as typed values, and SI ⇄
//! base-unit conversion for the robot presets. Sans-IO: bytes in, values out.

mod decoder;
mod drive;
mod frame;
pub mod layout;
mod message;

pub use decoder::{DecoderEvent, FrameDecoder, SkipReason};
pub use drive::{ROTATION_ACCELERATION, ROTATION_TORQUE, TRANSLATION_TORQUE, avoid_escape_bytes};
pub use frame::{ETX, Frame, MAX_DATA_LEN, OVERHEAD_LEN, STX, TooLong, checksum, port};
pub use message::{Axis, Command, LayoutError, Report, SonarReading};

/// Converts between SI units and a base's own units (`rflex.md` §5), and
/// where its sensors are (§6).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Conversion {
    /// Distance units per metre.
    pub distance_units_per_m: f64,
    /// Angle units per radian.
    pub angle_units_per_rad: f64,
    /// Added to the raw voltage / 100 to get volts.
    pub power_offset_volts: f64,
    /// Its sonar banks, transducers, range scale and bump panels.
    pub layout: &'static layout::Layout,
}

/// B21r: 103000 units/m, 35000 units/rad, +1.2 V.
pub const B21R: Conversion = Conversion {
    distance_units_per_m: 103_000.0,
    angle_units_per_rad: 35_000.0,
    power_offset_volts: 1.2,
    layout: &layout::B21R,
};
/// ATRV-Jr: 90810 units/m, 37000 units/rad, +1.2 V.
pub const ATRV_JR: Conversion = Conversion {
    distance_units_per_m: 90_810.0,
    angle_units_per_rad: 37_000.0,
    power_offset_volts: 1.2,
    layout: &layout::ATRV_JR,
};
/// Magellan: 31387 units/m, 4654.2 units/rad, +0 V.
pub const MAGELLAN: Conversion = Conversion {
    distance_units_per_m: 31_387.0,
    angle_units_per_rad: 4_654.2,
    power_offset_volts: 0.0,
    layout: &layout::MAGELLAN,
};

/// A sonar range above this is "no echo".
pub const SONAR_NO_ECHO_ABOVE: u16 = layout::NO_ECHO_RAW;

/// The odometry pose integrated from MOT_SYSTEM_REPORTs (`rflex.md` §4): the
/// first report of each axis sets the origin; then θ += Δbearing (normalised
/// to [−π, π]) and (x, y) += Δdistance along θ.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Odometry {
    /// Metres east of the start.
    pub x_m: f64,
    /// Metres north of the start.
    pub y_m: f64,
    /// Heading, radians in [−π, π].
    pub theta_rad: f64,
    last_distance: Option<i32>,
    last_bearing: Option<i32>,
}

impl Odometry {
    /// Takes one axis's position report.
    pub fn update(&mut self, conversion: &Conversion, axis: Axis, position: i32) {
        match axis {
            Axis::Translation => {
                if let Some(last) = self.last_distance {
                    let d = conversion.metres(i64::from(position.wrapping_sub(last)));
                    self.x_m += d * self.theta_rad.cos();
                    self.y_m += d * self.theta_rad.sin();
                }
                self.last_distance = Some(position);
            }
            Axis::Rotation => {
                if let Some(last) = self.last_bearing {
                    let turned = conversion.radians(i64::from(position.wrapping_sub(last)));
                    self.theta_rad = normalise(self.theta_rad + turned);
                }
                self.last_bearing = Some(position);
            }
        }
    }

    /// Whether both axes have reported at least once.
    pub fn started(&self) -> bool {
        self.last_distance.is_some() && self.last_bearing.is_some()
    }
}

/// An angle in [−π, π].
pub fn normalise(angle: f64) -> f64 {
    let tau = std::f64::consts::TAU;
    let wrapped = (angle + std::f64::consts::PI).rem_euclid(tau) - std::f64::consts::PI;
    if wrapped < -std::f64::consts::PI { wrapped + tau } else { wrapped }
}
