//! rFLEX mobile bases (`rflex.md`): the facts the project format needs today —
//! the robot presets' conversion constants. The frame codec joins them here.

/// Converts between SI units and a base's own units (`rflex.md` §5).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Conversion {
    /// Distance units per metre.
    pub distance_units_per_m: f64,
    /// Angle units per radian.
    pub angle_units_per_rad: f64,
    /// Added to the raw voltage / 100 to get volts.
    pub power_offset_volts: f64,
}

/// B21r: 103000 units/m, 35000 units/rad, +1.2 V.
pub const B21R: Conversion =
    Conversion { distance_units_per_m: 103_000.0, angle_units_per_rad: 35_000.0, power_offset_volts: 1.2 };
/// ATRV-Jr: 90810 units/m, 37000 units/rad, +1.2 V.
pub const ATRV_JR: Conversion =
    Conversion { distance_units_per_m: 90_810.0, angle_units_per_rad: 37_000.0, power_offset_volts: 1.2 };
/// Magellan: 31387 units/m, 4654.2 units/rad, +0 V.
pub const MAGELLAN: Conversion =
    Conversion { distance_units_per_m: 31_387.0, angle_units_per_rad: 4_654.2, power_offset_volts: 0.0 };
