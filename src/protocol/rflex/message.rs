//! rFLEX commands (client → base, `rflex.md` §3) and reports (base → client,
//! §4) as typed values. Opcodes repeat across directions (port 1 opcode 1 is
//! both the status request and the status report), so each direction decodes
//! with its own type.

use super::frame::{Frame, port};

/// Reads big-endian fields out of a frame's data.
struct Reader<'a> {
    data: &'a [u8],
    at: usize,
}

/// A frame whose data does not have the layout its opcode needs.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{name}: expected at least {expected} data bytes, got {actual}")]
pub struct LayoutError {
    /// The message.
    pub name: &'static str,
    /// Bytes needed.
    pub expected: usize,
    /// Bytes that came.
    pub actual: usize,
}

impl<'a> Reader<'a> {
    fn new(name: &'static str, data: &'a [u8], expected: usize) -> Result<Self, LayoutError> {
        if data.len() < expected {
            return Err(LayoutError { name, expected, actual: data.len() });
        }
        Ok(Self { data, at: 0 })
    }

    fn u8(&mut self) -> u8 {
        let value = self.data.get(self.at).copied().unwrap_or(0);
        self.at += 1;
        value
    }

    fn u16(&mut self) -> u16 {
        u16::from_be_bytes([self.u8(), self.u8()])
    }

    fn u32(&mut self) -> u32 {
        u32::from_be_bytes([self.u8(), self.u8(), self.u8(), self.u8()])
    }

    fn i32(&mut self) -> i32 {
        i32::from_be_bytes([self.u8(), self.u8(), self.u8(), self.u8()])
    }

    fn rest(&self) -> &'a [u8] {
        self.data.get(self.at..).unwrap_or_default()
    }
}

/// One axis of the motion module.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Axis {
    /// `0`: forward / backward, in distance units.
    Translation,
    /// `1`: turning, in angle units.
    Rotation,
}

impl Axis {
    /// The axis number on the wire.
    pub fn code(self) -> u8 {
        match self {
            Self::Translation => 0,
            Self::Rotation => 1,
        }
    }

    /// The axis with this number (2 and 3 are unused).
    pub fn from_code(code: u8) -> Option<Self> {
        match code {
            0 => Some(Self::Translation),
            1 => Some(Self::Rotation),
            _ => None,
        }
    }
}

/// What a client sends.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Command {
    /// SYS_STATUS request (port 1, opcode 1).
    SystemStatus,
    /// JSTK_GET_STATE request (port 3, opcode 0).
    JoystickState,
    /// MOT_SYSTEM_REPORT_REQ (port 2, opcode 34): odometry reports every
    /// `period_us` for the axes in `axis_mask`; (0, 0) turns them off.
    OdometryReports {
        /// Report period, µs (100000 = 10 Hz).
        period_us: u32,
        /// Bit per axis (3 = axes 0 and 1).
        axis_mask: u32,
    },
    /// MOT_SET_DEFAULTS (port 2, opcode 10).
    MotionDefaults,
    /// MOT_BRAKE_SET (port 2, opcode 11).
    BrakeSet,
    /// MOT_BRAKE_RELEASE (port 2, opcode 12).
    BrakeRelease,
    /// MOT_AXIS_SET_DIR (port 2, opcode 7): run an axis at a speed.
    AxisSetDir {
        /// The axis.
        axis: u8,
        /// Speed magnitude, base units/s.
        speed: u32,
        /// Acceleration, base units/s².
        acceleration: u32,
        /// Torque.
        torque: u32,
        /// 1 forward (velocity ≥ 0), 0 backward.
        direction: u8,
    },
    /// MOT_AXIS_SET_POS (port 2, opcode 8): move an axis to a position.
    AxisSetPos {
        /// The axis.
        axis: u8,
        /// Speed, base units/s.
        velocity: u32,
        /// Acceleration, base units/s².
        acceleration: u32,
        /// Torque.
        torque: u32,
        /// Target position, base units.
        position: u32,
    },
    /// SONAR_RUN (port 4, id 4, opcode 0).
    SonarRun {
        /// Echo delay (30000).
        echo_delay: u32,
        /// Ping delay (0).
        ping_delay: u32,
        /// Set delay (0).
        set_delay: u32,
        /// 2 on, 0 off.
        mode: u8,
    },
    /// DIO_REPORTS_REQ (port 5, opcode 0): digital I/O reports every `period_us` (0 = off).
    DioReports {
        /// Report period, µs.
        period_us: u32,
    },
    /// IR_RUN (port 6, opcode 0): five u32 and a mode byte (all zero = off).
    IrRun {
        /// The five parameters (0, 70, 10, 20, 150 to turn on).
        parameters: [u32; 5],
        /// 2 on, 0 off.
        mode: u8,
    },
    /// A frame this codec does not know.
    Unknown(Frame),
}

/// Opcode numbers.
mod opcode {
    pub const SYS_LCD_DUMP: u8 = 0;
    pub const SYS_STATUS: u8 = 1;
    pub const JSTK_GET_STATE: u8 = 0;
    pub const MOT_AXIS_SET_DIR: u8 = 7;
    pub const MOT_AXIS_SET_POS: u8 = 8;
    pub const MOT_SET_DEFAULTS: u8 = 10;
    pub const MOT_BRAKE_SET: u8 = 11;
    pub const MOT_BRAKE_RELEASE: u8 = 12;
    pub const MOT_SYSTEM_REPORT: u8 = 33;
    pub const MOT_SYSTEM_REPORT_REQ: u8 = 34;
    pub const SONAR_RUN: u8 = 0;
    pub const SONAR_REPORT: u8 = 2;
    pub const DIO_REPORTS_REQ: u8 = 0;
    pub const DIO_REPORT: u8 = 1;
    pub const IR_RUN: u8 = 0;
}

fn be(values: &[u32]) -> Vec<u8> {
    values.iter().flat_map(|value| value.to_be_bytes()).collect()
}

impl Command {
    /// The frame this command is sent as.
    pub fn to_frame(&self) -> Frame {
        let frame = |port, opcode, data| Frame { port, id: 0, opcode, data };
        match self {
            Self::SystemStatus => frame(port::SYSTEM, opcode::SYS_STATUS, Vec::new()),
            Self::JoystickState => frame(port::JOYSTICK, opcode::JSTK_GET_STATE, Vec::new()),
            Self::OdometryReports { period_us, axis_mask } => {
                frame(port::MOTION, opcode::MOT_SYSTEM_REPORT_REQ, be(&[*period_us, *axis_mask]))
            }
            Self::MotionDefaults => frame(port::MOTION, opcode::MOT_SET_DEFAULTS, Vec::new()),
            Self::BrakeSet => frame(port::MOTION, opcode::MOT_BRAKE_SET, Vec::new()),
            Self::BrakeRelease => frame(port::MOTION, opcode::MOT_BRAKE_RELEASE, Vec::new()),
            Self::AxisSetDir { axis, speed, acceleration, torque, direction } => {
                let mut data = vec![*axis];
                data.extend(be(&[*speed, *acceleration, *torque]));
                data.push(*direction);
                frame(port::MOTION, opcode::MOT_AXIS_SET_DIR, data)
            }
            Self::AxisSetPos { axis, velocity, acceleration, torque, position } => {
                let mut data = vec![*axis];
                data.extend(be(&[*velocity, *acceleration, *torque, *position]));
                frame(port::MOTION, opcode::MOT_AXIS_SET_POS, data)
            }
            Self::SonarRun { echo_delay, ping_delay, set_delay, mode } => {
                let mut data = be(&[*echo_delay, *ping_delay, *set_delay]);
                data.push(*mode);
                Frame { port: port::SONAR, id: 4, opcode: opcode::SONAR_RUN, data }
            }
            Self::DioReports { period_us } => frame(port::DIO, opcode::DIO_REPORTS_REQ, be(&[*period_us])),
            Self::IrRun { parameters, mode } => {
                let mut data = be(parameters);
                data.push(*mode);
                frame(port::IR, opcode::IR_RUN, data)
            }
            Self::Unknown(frame) => frame.clone(),
        }
    }

    /// The command a frame carries (what a base reads).
    pub fn from_frame(frame: &Frame) -> Result<Self, LayoutError> {
        let data = frame.data.as_slice();
        Ok(match (frame.port, frame.opcode) {
            (port::SYSTEM, opcode::SYS_STATUS) => Self::SystemStatus,
            (port::JOYSTICK, opcode::JSTK_GET_STATE) => Self::JoystickState,
            (port::MOTION, opcode::MOT_SYSTEM_REPORT_REQ) => {
                let mut r = Reader::new("MOT_SYSTEM_REPORT_REQ", data, 8)?;
                Self::OdometryReports { period_us: r.u32(), axis_mask: r.u32() }
            }
            (port::MOTION, opcode::MOT_SET_DEFAULTS) => Self::MotionDefaults,
            (port::MOTION, opcode::MOT_BRAKE_SET) => Self::BrakeSet,
            (port::MOTION, opcode::MOT_BRAKE_RELEASE) => Self::BrakeRelease,
            (port::MOTION, opcode::MOT_AXIS_SET_DIR) => {
                let mut r = Reader::new("MOT_AXIS_SET_DIR", data, 14)?;
                Self::AxisSetDir {
                    axis: r.u8(),
                    speed: r.u32(),
                    acceleration: r.u32(),
                    torque: r.u32(),
                    direction: r.u8(),
                }
            }
            (port::MOTION, opcode::MOT_AXIS_SET_POS) => {
                let mut r = Reader::new("MOT_AXIS_SET_POS", data, 17)?;
                Self::AxisSetPos {
                    axis: r.u8(),
                    velocity: r.u32(),
                    acceleration: r.u32(),
                    torque: r.u32(),
                    position: r.u32(),
                }
            }
            (port::SONAR, opcode::SONAR_RUN) => {
                let mut r = Reader::new("SONAR_RUN", data, 13)?;
                Self::SonarRun { echo_delay: r.u32(), ping_delay: r.u32(), set_delay: r.u32(), mode: r.u8() }
            }
            (port::DIO, opcode::DIO_REPORTS_REQ) => {
                let mut r = Reader::new("DIO_REPORTS_REQ", data, 4)?;
                Self::DioReports { period_us: r.u32() }
            }
            (port::IR, opcode::IR_RUN) => {
                let mut r = Reader::new("IR_RUN", data, 21)?;
                Self::IrRun { parameters: [r.u32(), r.u32(), r.u32(), r.u32(), r.u32()], mode: r.u8() }
            }
            _ => Self::Unknown(frame.clone()),
        })
    }

    /// The message's name as the reference drivers call it.
    pub fn name(&self) -> &'static str {
        match self {
            Self::SystemStatus => "SYS_STATUS",
            Self::JoystickState => "JSTK_GET_STATE",
            Self::OdometryReports { .. } => "MOT_SYSTEM_REPORT_REQ",
            Self::MotionDefaults => "MOT_SET_DEFAULTS",
            Self::BrakeSet => "MOT_BRAKE_SET",
            Self::BrakeRelease => "MOT_BRAKE_RELEASE",
            Self::AxisSetDir { .. } => "MOT_AXIS_SET_DIR",
            Self::AxisSetPos { .. } => "MOT_AXIS_SET_POS",
            Self::SonarRun { .. } => "SONAR_RUN",
            Self::DioReports { .. } => "DIO_REPORTS_REQ",
            Self::IrRun { .. } => "IR_RUN",
            Self::Unknown(_) => "unknown",
        }
    }
}

/// One sonar reading of a SONAR_REPORT.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct SonarReading {
    /// bank × 16 + index.
    pub sonar_id: u8,
    /// Range in sonar units (B21r: / 1476 = metres; above 3000 = no echo).
    pub range: u16,
}

/// What a base sends.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Report {
    /// MOT_SYSTEM_REPORT (port 2, opcode 33): one axis's odometry.
    Odometry {
        /// Unknown leading field.
        unknown: u32,
        /// The base's timestamp.
        timestamp: u32,
        /// The axis (0 translation, 1 rotation).
        axis: u8,
        /// Distance (axis 0) or bearing (axis 1), base units.
        position: i32,
        /// Velocity, base units/s.
        velocity: i32,
        /// Acceleration.
        acceleration: u32,
        /// Torque.
        torque: u32,
    },
    /// SYS_STATUS (port 1, opcode 1).
    Status {
        /// The base's timestamp.
        timestamp: u32,
        /// Battery, volts × 100 before the robot's offset.
        voltage_raw: u32,
        /// Brake set (1) or released (0).
        brake: u8,
    },
    /// SONAR_REPORT (port 4, opcode 2).
    Sonar {
        /// Unknown leading field.
        unknown: u32,
        /// The base's timestamp.
        timestamp: u32,
        /// The readings, in order.
        readings: Vec<SonarReading>,
    },
    /// DIO_REPORT (port 5, opcode 1).
    Dio {
        /// The base's timestamp.
        timestamp: u32,
        /// The address (B21r bump panels: 0x40..).
        address: u8,
        /// The state (bump panels: low 4 bits = pressed corners).
        data: u16,
    },
    /// JSTK_GET_STATE reply (port 3, opcode 0).
    Joystick {
        /// The base's timestamp.
        timestamp: u32,
        /// Stick x.
        x: i32,
        /// Stick y.
        y: i32,
        /// Buttons, a bit each.
        buttons: u8,
    },
    /// SYS_LCD_DUMP (port 1, opcode 0): one row of the 320×240 1-bit screen.
    LcdDump {
        /// The base's timestamp.
        timestamp: u32,
        /// The row.
        row: u8,
        /// The byte count.
        count: u8,
        /// The pixels (40 bytes a row).
        pixels: Vec<u8>,
    },
    /// A frame this codec does not know.
    Unknown(Frame),
}

impl Report {
    /// The report a frame carries (what a client reads).
    pub fn from_frame(frame: &Frame) -> Result<Self, LayoutError> {
        let data = frame.data.as_slice();
        Ok(match (frame.port, frame.opcode) {
            (port::MOTION, opcode::MOT_SYSTEM_REPORT) => {
                let mut r = Reader::new("MOT_SYSTEM_REPORT", data, 25)?;
                Self::Odometry {
                    unknown: r.u32(),
                    timestamp: r.u32(),
                    axis: r.u8(),
                    position: r.i32(),
                    velocity: r.i32(),
                    acceleration: r.u32(),
                    torque: r.u32(),
                }
            }
            (port::SYSTEM, opcode::SYS_STATUS) => {
                let mut r = Reader::new("SYS_STATUS", data, 9)?;
                Self::Status { timestamp: r.u32(), voltage_raw: r.u32(), brake: r.u8() }
            }
            (port::SONAR, opcode::SONAR_REPORT) => {
                let mut r = Reader::new("SONAR_REPORT", data, 8)?;
                let unknown = r.u32();
                let timestamp = r.u32();
                let readings = r
                    .rest()
                    .chunks_exact(3)
                    .map(|c| SonarReading { sonar_id: c[0], range: u16::from_be_bytes([c[1], c[2]]) })
                    .collect();
                Self::Sonar { unknown, timestamp, readings }
            }
            (port::DIO, opcode::DIO_REPORT) => {
                let mut r = Reader::new("DIO_REPORT", data, 7)?;
                Self::Dio { timestamp: r.u32(), address: r.u8(), data: r.u16() }
            }
            (port::JOYSTICK, opcode::JSTK_GET_STATE) => {
                let mut r = Reader::new("JSTK_GET_STATE", data, 13)?;
                Self::Joystick { timestamp: r.u32(), x: r.i32(), y: r.i32(), buttons: r.u8() }
            }
            (port::SYSTEM, opcode::SYS_LCD_DUMP) => {
                let mut r = Reader::new("SYS_LCD_DUMP", data, 6)?;
                Self::LcdDump { timestamp: r.u32(), row: r.u8(), count: r.u8(), pixels: r.rest().to_vec() }
            }
            _ => Self::Unknown(frame.clone()),
        })
    }

    /// The frame a base sends this report as, with its running number `id`.
    pub fn to_frame(&self, id: u8) -> Frame {
        let frame = |port, opcode, data| Frame { port, id, opcode, data };
        match self {
            Self::Odometry { unknown, timestamp, axis, position, velocity, acceleration, torque } => {
                let mut data = be(&[*unknown, *timestamp]);
                data.push(*axis);
                data.extend(position.to_be_bytes());
                data.extend(velocity.to_be_bytes());
                data.extend(be(&[*acceleration, *torque]));
                frame(port::MOTION, opcode::MOT_SYSTEM_REPORT, data)
            }
            Self::Status { timestamp, voltage_raw, brake } => {
                let mut data = be(&[*timestamp, *voltage_raw]);
                data.push(*brake);
                frame(port::SYSTEM, opcode::SYS_STATUS, data)
            }
            Self::Sonar { unknown, timestamp, readings } => {
                let mut data = be(&[*unknown, *timestamp]);
                for reading in readings {
                    data.push(reading.sonar_id);
                    data.extend(reading.range.to_be_bytes());
                }
                frame(port::SONAR, opcode::SONAR_REPORT, data)
            }
            Self::Dio { timestamp, address, data: state } => {
                let mut data = be(&[*timestamp]);
                data.push(*address);
                data.extend(state.to_be_bytes());
                frame(port::DIO, opcode::DIO_REPORT, data)
            }
            Self::Joystick { timestamp, x, y, buttons } => {
                let mut data = be(&[*timestamp]);
                data.extend(x.to_be_bytes());
                data.extend(y.to_be_bytes());
                data.push(*buttons);
                frame(port::JOYSTICK, opcode::JSTK_GET_STATE, data)
            }
            Self::LcdDump { timestamp, row, count, pixels } => {
                let mut data = be(&[*timestamp]);
                data.extend([*row, *count]);
                data.extend(pixels);
                frame(port::SYSTEM, opcode::SYS_LCD_DUMP, data)
            }
            Self::Unknown(unknown) => unknown.clone(),
        }
    }

    /// The message's name as the reference drivers call it.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Odometry { .. } => "MOT_SYSTEM_REPORT",
            Self::Status { .. } => "SYS_STATUS",
            Self::Sonar { .. } => "SONAR_REPORT",
            Self::Dio { .. } => "DIO_REPORT",
            Self::Joystick { .. } => "JSTK_GET_STATE",
            Self::LcdDump { .. } => "SYS_LCD_DUMP",
            Self::Unknown(_) => "unknown",
        }
    }
}
