//! PLEN2 commands (`plen2.md` §2) as typed values: their exact ASCII bytes,
//! and the firmware's byte-at-a-time parser (used by the emulated robot).

use super::joint::{DEVICE_IDS, NAME_LEN};

/// A `>MH` motion header.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct MotionHeader {
    /// Slot 0..=89.
    pub slot: u8,
    /// The name's 20 bytes, as stored (space-padded ASCII).
    pub name: [u8; NAME_LEN],
    /// Loop on.
    pub loop_on: bool,
    /// First looped frame.
    pub loop_begin: u8,
    /// Last looped frame.
    pub loop_end: u8,
    /// Extra passes (255 = forever).
    pub loop_count: u8,
    /// Jump on.
    pub jump_on: bool,
    /// The slot jumped to.
    pub jump_slot: u8,
    /// Frames, 1..=20 (others make the firmware drop the header).
    pub frame_count: u8,
}

/// A `>MF` motion frame.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct MotionFrame {
    /// Slot 0..=89.
    pub slot: u8,
    /// Frame index 0..=19.
    pub index: u8,
    /// Transition time, ms (32..=8191 works).
    pub transition_ms: u16,
    /// One value per device id 0..=23, tenths of a degree relative to home.
    pub values: [i16; DEVICE_IDS],
}

/// One command.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Command {
    /// `$AN`: a joint to an absolute angle (clamped to its limits).
    SetAngle {
        /// Device id.
        device: u8,
        /// Tenths of a degree, −2048..=2047.
        angle: i16,
    },
    /// `$AD`: a joint to home + diff (clamped).
    SetDiff {
        /// Device id.
        device: u8,
        /// Tenths of a degree, −2048..=2047.
        diff: i16,
    },
    /// `$HP`: every joint to home.
    HomePosition,
    /// `$PM`: play a stored motion.
    PlayMotion {
        /// Slot.
        slot: u8,
    },
    /// `$SM`: stop after the current pass.
    StopMotion,
    /// `#PU`: queue a motion; `plays` = total plays (0 = forever).
    Push {
        /// Slot.
        slot: u8,
        /// Total plays, 1..=255; 0 = forever.
        plays: u8,
    },
    /// `#PO`: start playing the queue.
    Pop,
    /// `#RI`: clear the queue and stop at once.
    ResetInterpreter,
    /// `>HO`: set a joint's home.
    SetHome {
        /// Device id.
        device: u8,
        /// Tenths of a degree.
        angle: i16,
    },
    /// `>MA`: set a joint's max.
    SetMax {
        /// Device id.
        device: u8,
        /// Tenths of a degree.
        angle: i16,
    },
    /// `>MI`: set a joint's min.
    SetMin {
        /// Device id.
        device: u8,
        /// Tenths of a degree.
        angle: i16,
    },
    /// `>JS`: factory joint settings.
    ResetJoints,
    /// `>MH`: write a motion header.
    Header(MotionHeader),
    /// `>MF`: write a motion frame.
    Frame(Box<MotionFrame>),
    /// `<JS`: joint settings as JSON.
    GetJointSettings,
    /// `<MO`: one motion as JSON.
    GetMotion {
        /// Slot.
        slot: u8,
    },
    /// `<VI`: the firmware version as JSON.
    GetVersion,
}

/// Two's complement of `value` in `digits` hex digits.
fn signed_hex(value: i16, digits: usize) -> String {
    let bits = 4 * digits;
    let mask = (1u32 << bits) - 1;
    // Two's complement in the field's width: reinterpreting the bits is the point.
    #[allow(clippy::cast_sign_loss)]
    let raw = (i32::from(value) as u32) & mask;
    format!("{raw:0digits$x}")
}

impl Command {
    /// The command's code, as sent (`$AN`, `>MF`, …).
    pub fn code(&self) -> &'static str {
        match self {
            Self::SetAngle { .. } => "$AN",
            Self::SetDiff { .. } => "$AD",
            Self::HomePosition => "$HP",
            Self::PlayMotion { .. } => "$PM",
            Self::StopMotion => "$SM",
            Self::Push { .. } => "#PU",
            Self::Pop => "#PO",
            Self::ResetInterpreter => "#RI",
            Self::SetHome { .. } => ">HO",
            Self::SetMax { .. } => ">MA",
            Self::SetMin { .. } => ">MI",
            Self::ResetJoints => ">JS",
            Self::Header(_) => ">MH",
            Self::Frame(_) => ">MF",
            Self::GetJointSettings => "<JS",
            Self::GetMotion { .. } => "<MO",
            Self::GetVersion => "<VI",
        }
    }

    /// The exact bytes sent (lower-case hex, zero-padded).
    pub fn to_ascii(&self) -> String {
        let code = self.code();
        match self {
            Self::SetAngle { device, angle: value }
            | Self::SetDiff { device, diff: value }
            | Self::SetHome { device, angle: value }
            | Self::SetMax { device, angle: value }
            | Self::SetMin { device, angle: value } => format!("{code}{device:02x}{}", signed_hex(*value, 3)),
            Self::PlayMotion { slot } | Self::GetMotion { slot } => format!("{code}{slot:02x}"),
            Self::Push { slot, plays } => format!("{code}{slot:02x}{plays:02x}"),
            Self::HomePosition
            | Self::StopMotion
            | Self::Pop
            | Self::ResetInterpreter
            | Self::ResetJoints
            | Self::GetJointSettings
            | Self::GetVersion => code.to_string(),
            Self::Header(h) => format!(
                "{code}{:02x}{}{}{:02x}{:02x}{:02x}{}{:02x}0{:02x}",
                h.slot,
                String::from_utf8_lossy(&h.name),
                u8::from(h.loop_on),
                h.loop_begin,
                h.loop_end,
                h.loop_count,
                u8::from(h.jump_on),
                h.jump_slot,
                h.frame_count
            ),
            Self::Frame(f) => {
                let mut text = format!("{code}{:02x}{:02x}{:04x}", f.slot, f.index, f.transition_ms);
                for value in f.values {
                    text.push_str(&signed_hex(value, 4));
                }
                text
            }
        }
    }

    /// The argument bytes that follow a code, or `None` for a code the firmware does not know.
    fn argument_len(code: &[u8; 3]) -> Option<usize> {
        let upper = [code[0], code[1].to_ascii_uppercase(), code[2].to_ascii_uppercase()];
        Some(match &upper {
            b"$AN" | b"$AD" | b">HO" | b">MA" | b">MI" => 5,
            b"$PM" | b"$MP" | b"<MO" => 2,
            b"#PU" => 4,
            b"$HP" | b"$SM" | b"$MS" | b"#PO" | b"#RI" | b">JS" | b"<JS" | b"<VI" => 0,
            b">MH" => 35,
            b">MF" => 104,
            _ => return None,
        })
    }
}

/// Why the firmware dropped a command.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ParseError {
    /// A group char followed by a code the firmware does not know (its lookup can crash on these).
    #[error("unknown command {0:?}")]
    UnknownCode(String),
    /// A non-hex digit where a number belongs: the whole command is dropped.
    #[error("{code}: {argument:?} is not hexadecimal")]
    BadArgument {
        /// The command.
        code: String,
        /// Its arguments.
        argument: String,
    },
    /// A `>MH` whose frame count is outside 1..=20, or a slot ≥ 90 in `>MH` / `>MF`.
    #[error("{code}: out of range ({what})")]
    OutOfRange {
        /// The command.
        code: String,
        /// What.
        what: &'static str,
    },
}

fn hex(digits: &[u8]) -> Option<u32> {
    let text = std::str::from_utf8(digits).ok()?;
    if text.is_empty() || !text.bytes().all(|b| b.is_ascii_hexdigit()) {
        return None;
    }
    u32::from_str_radix(text, 16).ok()
}

/// Reads `digits` hex digits as a signed value of that width.
fn signed(digits: &[u8]) -> Option<i16> {
    let raw = hex(digits)?;
    let bits = 4 * u32::try_from(digits.len()).ok()?;
    let value = if raw & (1 << (bits - 1)) != 0 { i64::from(raw) - (1i64 << bits) } else { i64::from(raw) };
    i16::try_from(value).ok()
}

fn byte(digits: &[u8]) -> Option<u8> {
    hex(digits).and_then(|value| u8::try_from(value).ok())
}

fn flag(digit: u8) -> Option<bool> {
    match digit {
        b'0' => Some(false),
        b'1' => Some(true),
        _ => None,
    }
}

/// Parses one command from its code and arguments (already the right length).
fn parse(code: &[u8; 3], args: &[u8]) -> Result<Command, ParseError> {
    let name = String::from_utf8_lossy(code).to_ascii_uppercase();
    let bad = || ParseError::BadArgument { code: name.clone(), argument: String::from_utf8_lossy(args).into_owned() };
    let device_angle = || -> Result<(u8, i16), ParseError> {
        Ok((byte(&args[..2]).ok_or_else(bad)?, signed(&args[2..5]).ok_or_else(bad)?))
    };
    Ok(match name.as_str() {
        "$AN" => {
            let (device, angle) = device_angle()?;
            Command::SetAngle { device, angle }
        }
        "$AD" => {
            let (device, diff) = device_angle()?;
            Command::SetDiff { device, diff }
        }
        ">HO" => {
            let (device, angle) = device_angle()?;
            Command::SetHome { device, angle }
        }
        ">MA" => {
            let (device, angle) = device_angle()?;
            Command::SetMax { device, angle }
        }
        ">MI" => {
            let (device, angle) = device_angle()?;
            Command::SetMin { device, angle }
        }
        "$HP" => Command::HomePosition,
        "$PM" | "$MP" => Command::PlayMotion { slot: byte(args).ok_or_else(bad)? },
        "$SM" | "$MS" => Command::StopMotion,
        "#PU" => Command::Push { slot: byte(&args[..2]).ok_or_else(bad)?, plays: byte(&args[2..]).ok_or_else(bad)? },
        "#PO" => Command::Pop,
        "#RI" => Command::ResetInterpreter,
        ">JS" => Command::ResetJoints,
        "<JS" => Command::GetJointSettings,
        "<VI" => Command::GetVersion,
        "<MO" => Command::GetMotion { slot: byte(args).ok_or_else(bad)? },
        ">MH" => motion_header(args, name)?,
        ">MF" => motion_frame(args, name)?,
        _ => return Err(ParseError::UnknownCode(name)),
    })
}

/// `>MH`'s arguments: a motion's header (slot, name, loop, jump, frame count).
fn motion_header(args: &[u8], name: String) -> Result<Command, ParseError> {
    let bad = || ParseError::BadArgument { code: name.clone(), argument: String::from_utf8_lossy(args).into_owned() };
    let mut name_bytes = [b' '; NAME_LEN];
    name_bytes.copy_from_slice(&args[2..22]);
    let rest = &args[22..];
    let header = MotionHeader {
        slot: byte(&args[..2]).ok_or_else(bad)?,
        name: name_bytes,
        loop_on: flag(rest[0]).ok_or_else(bad)?,
        loop_begin: byte(&rest[1..3]).ok_or_else(bad)?,
        loop_end: byte(&rest[3..5]).ok_or_else(bad)?,
        loop_count: byte(&rest[5..7]).ok_or_else(bad)?,
        jump_on: flag(rest[7]).ok_or_else(bad)?,
        jump_slot: byte(&rest[8..10]).ok_or_else(bad)?,
        frame_count: {
            // rest[10] is the extra flag, ignored by the firmware.
            byte(&rest[11..13]).ok_or_else(bad)?
        },
    };
    if !(1..=20).contains(&header.frame_count) {
        return Err(ParseError::OutOfRange { code: name, what: "frame count" });
    }
    if header.slot >= super::joint::SLOTS {
        return Err(ParseError::OutOfRange { code: name, what: "slot" });
    }
    Ok(Command::Header(header))
}

/// `>MF`'s arguments: one frame of a motion (slot, index, transition, a value per device).
fn motion_frame(args: &[u8], name: String) -> Result<Command, ParseError> {
    let bad = || ParseError::BadArgument { code: name.clone(), argument: String::from_utf8_lossy(args).into_owned() };
    let mut values = [0i16; DEVICE_IDS];
    for (index, value) in values.iter_mut().enumerate() {
        let at = 8 + 4 * index;
        *value = signed(&args[at..at + 4]).ok_or_else(bad)?;
    }
    let frame = MotionFrame {
        slot: byte(&args[..2]).ok_or_else(bad)?,
        index: byte(&args[2..4]).ok_or_else(bad)?,
        transition_ms: u16::try_from(hex(&args[4..8]).ok_or_else(bad)?).map_err(|_| bad())?,
        values,
    };
    if frame.slot >= super::joint::SLOTS {
        return Err(ParseError::OutOfRange { code: name, what: "slot" });
    }
    Ok(Command::Frame(Box::new(frame)))
}

/// The firmware's command reader: one byte at a time; bytes between commands
/// that are not `$ # > <` are ignored; a bad command is dropped whole.
#[derive(Debug, Default)]
pub struct CommandParser {
    code: Vec<u8>,
    args: Vec<u8>,
    needed: Option<usize>,
}

impl CommandParser {
    /// Takes one byte; returns a command (or why one was dropped) when one ends.
    pub fn push(&mut self, byte: u8) -> Option<Result<Command, ParseError>> {
        if self.code.is_empty() {
            if matches!(byte, b'$' | b'#' | b'>' | b'<') {
                self.code.push(byte);
            }
            return None;
        }
        if self.code.len() < 3 {
            self.code.push(byte);
            if self.code.len() < 3 {
                return None;
            }
            let code = [self.code[0], self.code[1], self.code[2]];
            match Command::argument_len(&code) {
                Some(0) => {
                    self.code.clear();
                    return Some(parse(&code, &[]));
                }
                Some(needed) => self.needed = Some(needed),
                None => {
                    self.code.clear();
                    return Some(Err(ParseError::UnknownCode(String::from_utf8_lossy(&code).into_owned())));
                }
            }
            return None;
        }
        self.args.push(byte);
        if Some(self.args.len()) < self.needed {
            return None;
        }
        let code = [self.code[0], self.code[1], self.code[2]];
        let result = parse(&code, &self.args);
        self.code.clear();
        self.args.clear();
        self.needed = None;
        Some(result)
    }
}

/// Every command in `bytes` (a helper for tests and tools).
pub fn parse_commands(bytes: &[u8]) -> Vec<Result<Command, ParseError>> {
    let mut parser = CommandParser::default();
    bytes.iter().filter_map(|&b| parser.push(b)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn golden_strings_from_plen2_md() {
        assert_eq!(Command::SetDiff { device: 4, diff: -100 }.to_ascii(), "$AD04f9c");
        assert_eq!(Command::SetAngle { device: 14, angle: 1000 }.to_ascii(), "$AN0e3e8");
        assert_eq!(Command::PlayMotion { slot: 70 }.to_ascii(), "$PM46");
        assert_eq!(Command::Push { slot: 10, plays: 3 }.to_ascii(), "#PU0a03");
        assert_eq!(Command::SetHome { device: 6, angle: 500 }.to_ascii(), ">HO061f4");
        let mut name = [b' '; NAME_LEN];
        name[..5].copy_from_slice(b"Empty");
        let header = MotionHeader {
            slot: 9,
            name,
            loop_on: false,
            loop_begin: 0,
            loop_end: 0,
            loop_count: 0,
            jump_on: false,
            jump_slot: 0,
            frame_count: 1,
        };
        let text = Command::Header(header.clone()).to_ascii();
        assert_eq!(text, ">MH09Empty               0000000000001");
        assert_eq!(text.len(), 38);
        let mut values = [0i16; DEVICE_IDS];
        values[0] = -300;
        values[23] = 1;
        let frame = Command::Frame(Box::new(MotionFrame { slot: 9, index: 0, transition_ms: 100, values }));
        let text = frame.to_ascii();
        assert_eq!(text.len(), 107);
        assert!(text.starts_with(">MF09000064fed40000"), "{text}");
        assert!(text.ends_with("0001"));
        // And the firmware reads each back.
        for command in [Command::Header(header), frame, Command::SetDiff { device: 4, diff: -100 }] {
            assert_eq!(parse_commands(command.to_ascii().as_bytes()), [Ok(command)]);
        }
    }

    #[test]
    fn the_firmware_ignores_noise_drops_bad_commands_and_reads_either_case() {
        let results = parse_commands(b"\r\nxx$an0e3e8 $ADzz100$hp<vi");
        assert_eq!(results[0], Ok(Command::SetAngle { device: 14, angle: 1000 }));
        assert!(matches!(results[1], Err(ParseError::BadArgument { .. })), "{results:?}");
        assert_eq!(results[2..], [Ok(Command::HomePosition), Ok(Command::GetVersion)]);
        assert!(matches!(parse_commands(b"$QQ")[0], Err(ParseError::UnknownCode(_))));
        assert!(matches!(
            parse_commands(b">MH09Empty               0000000000000")[0],
            Err(ParseError::OutOfRange { .. })
        ));
    }
}
