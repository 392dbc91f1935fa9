//! Velocity commands in SI units (`rflex.md` §3): one drive command is two
//! MOT_AXIS_SET_DIR frames, translation then rotation; the rotational speed
//! avoids the `0x1B` bytes every reference driver avoids.

use super::Conversion;
use super::message::{Axis, Command};

/// Torque sent with a translation command.
pub const TRANSLATION_TORQUE: u32 = 30_000;
/// Torque sent with a rotation command.
pub const ROTATION_TORQUE: u32 = 35_000;
/// Acceleration sent with a rotation command, angle units/s².
pub const ROTATION_ACCELERATION: u32 = 100_000;

/// The rotational-speed quirk, exactly as `rflex.md` §2 states it, in order:
/// bits 8–15 = `1B` → bits 0–15 become `1AFF` (bits 0–7 ≤ 127) or `1C00`;
/// then bits 24–31 = `1B` → `1C` (bits 16–23 > 127) or `1A` with bits 16–23 `FF`.
pub fn avoid_escape_bytes(speed: u32) -> u32 {
    let mut speed = speed;
    if (speed >> 8) & 0xff == 0x1b {
        let low = if speed & 0xff <= 127 { 0x1aff } else { 0x1c00 };
        speed = (speed & 0xffff_0000) | low;
    }
    if speed >> 24 == 0x1b {
        speed = if (speed >> 16) & 0xff > 127 {
            (speed & 0x00ff_ffff) | 0x1c00_0000
        } else {
            (speed & 0x0000_ffff) | 0x1aff_0000
        };
    }
    speed
}

/// A value in SI units as base units: truncated toward zero, saturating.
fn units(value: f64, per_unit: f64) -> u32 {
    let scaled = (value * per_unit).trunc().abs();
    if scaled.is_nan() {
        return 0;
    }
    // Saturates: a speed beyond u32 is clamped, never wrapped.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let out = scaled.min(f64::from(u32::MAX)) as u32;
    out
}

impl Conversion {
    /// Metres as distance units.
    pub fn distance_units(&self, metres: f64) -> u32 {
        units(metres, self.distance_units_per_m)
    }

    /// Radians as angle units.
    pub fn angle_units(&self, radians: f64) -> u32 {
        units(radians, self.angle_units_per_rad)
    }

    /// Distance units as metres.
    pub fn metres(&self, distance_units: i64) -> f64 {
        // Odometry counters are far below 2^52: exact in f64.
        #[allow(clippy::cast_precision_loss)]
        let value = distance_units as f64;
        value / self.distance_units_per_m
    }

    /// Angle units as radians.
    pub fn radians(&self, angle_units: i64) -> f64 {
        #[allow(clippy::cast_precision_loss)]
        let value = angle_units as f64;
        value / self.angle_units_per_rad
    }

    /// SYS_STATUS raw voltage as volts.
    pub fn volts(&self, voltage_raw: u32) -> f64 {
        f64::from(voltage_raw) / 100.0 + self.power_offset_volts
    }

    /// The two frames of one velocity command: translation at `speed_m_per_s`
    /// with `acceleration_m_per_s2`, rotation at `turn_rad_per_s`.
    pub fn drive(&self, speed_m_per_s: f64, turn_rad_per_s: f64, acceleration_m_per_s2: f64) -> [Command; 2] {
        [
            Command::AxisSetDir {
                axis: Axis::Translation.code(),
                speed: self.distance_units(speed_m_per_s),
                acceleration: self.distance_units(acceleration_m_per_s2),
                torque: TRANSLATION_TORQUE,
                direction: u8::from(speed_m_per_s >= 0.0),
            },
            Command::AxisSetDir {
                axis: Axis::Rotation.code(),
                speed: avoid_escape_bytes(self.angle_units(turn_rad_per_s)),
                acceleration: ROTATION_ACCELERATION,
                torque: ROTATION_TORQUE,
                direction: u8::from(turn_rad_per_s >= 0.0),
            },
        ]
    }

    /// The stop: both axes at speed 0, direction 1.
    pub fn stop(&self, acceleration_m_per_s2: f64) -> [Command; 2] {
        self.drive(0.0, 0.0, acceleration_m_per_s2)
    }
}
