//! rFLEX frames as a person reads them in the packet log.

use crate::protocol::rflex::{Axis, Command, Conversion, Report};

fn axis(code: u8) -> &'static str {
    match Axis::from_code(code) {
        Some(Axis::Translation) => "translation",
        Some(Axis::Rotation) => "rotation",
        None => "axis ?",
    }
}

/// A command's fields in words, with SI values where the robot's constants give them.
pub fn command(command: &Command, conversion: &Conversion) -> String {
    match command {
        Command::SystemStatus | Command::JoystickState | Command::MotionDefaults => String::new(),
        Command::BrakeSet => "brake on".into(),
        Command::BrakeRelease => "brake off".into(),
        Command::OdometryReports { period_us: 0, .. } => "off".into(),
        Command::OdometryReports { period_us, axis_mask } => {
            format!("every {} ms, axes {axis_mask:#b}", period_us / 1000)
        }
        Command::AxisSetDir { axis: code, speed, acceleration, direction, .. } => {
            let sign = if *direction == 0 { "−" } else { "" };
            match Axis::from_code(*code) {
                Some(Axis::Rotation) => format!(
                    "rotation {sign}{:.3} rad/s ({speed} units), accel {acceleration}",
                    conversion.radians(i64::from(*speed))
                ),
                _ => format!(
                    "{} {sign}{:.3} m/s ({speed} units), accel {:.2} m/s²",
                    axis(*code),
                    conversion.metres(i64::from(*speed)),
                    conversion.metres(i64::from(*acceleration))
                ),
            }
        }
        Command::AxisSetPos { axis: code, position, velocity, .. } => {
            format!("{} to {position} at {velocity}", axis(*code))
        }
        Command::SonarRun { mode, .. } => (if *mode == 0 { "off" } else { "on" }).into(),
        Command::DioReports { period_us: 0 } => "off".into(),
        Command::DioReports { period_us } => format!("every {} ms", period_us / 1000),
        Command::IrRun { mode, .. } => (if *mode == 0 { "off" } else { "on" }).into(),
        Command::Unknown(frame) => format!("port {} opcode {}, {} byte(s)", frame.port, frame.opcode, frame.data.len()),
    }
}

/// A report's fields in words.
pub fn report(report: &Report, conversion: &Conversion) -> String {
    match report {
        Report::Odometry { axis: code, position, velocity, .. } => match Axis::from_code(*code) {
            Some(Axis::Rotation) => format!(
                "rotation at {:.3} rad, {:.3} rad/s",
                conversion.radians(i64::from(*position)),
                conversion.radians(i64::from(*velocity))
            ),
            _ => format!(
                "{} at {:.3} m, {:.3} m/s",
                axis(*code),
                conversion.metres(i64::from(*position)),
                conversion.metres(i64::from(*velocity))
            ),
        },
        Report::Status { voltage_raw, brake, .. } => {
            format!("battery {:.2} V, brake {}", conversion.volts(*voltage_raw), if *brake == 0 { "off" } else { "on" })
        }
        Report::Sonar { readings, .. } => {
            let parts: Vec<String> = readings
                .iter()
                .map(|r| match conversion.layout.range_m(r.range) {
                    Some(metres) => format!("{} {metres:.2} m", r.sonar_id),
                    None => format!("{} —", r.sonar_id),
                })
                .collect();
            parts.join(", ")
        }
        Report::Dio { address, data, .. } => format!("address {address:#04x} = {data:#06b}"),
        Report::Joystick { x, y, buttons, .. } => format!("x {x}, y {y}, buttons {buttons:#010b}"),
        Report::LcdDump { row, count, .. } => format!("row {row}, {count} byte(s)"),
        Report::Unknown(frame) => format!("port {} opcode {}, {} byte(s)", frame.port, frame.opcode, frame.data.len()),
    }
}
