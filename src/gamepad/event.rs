//! Linux input events as the kernel writes them (`struct input_event`, 24
//! bytes on 64-bit Linux: the time as two 64-bit words, then type, code and
//! value), read from an event device or from any file or pipe carrying them.

/// Bytes of one `struct input_event` on 64-bit Linux.
pub const EVENT_SIZE: usize = 24;

/// `EV_SYN`: a frame ends (`SYN_REPORT`) or events were lost (`SYN_DROPPED`).
pub const EV_SYN: u16 = 0x00;
/// `EV_KEY`: a button (value 1 pressed, 0 released, 2 auto-repeat).
pub const EV_KEY: u16 = 0x01;
/// `EV_ABS`: an absolute axis.
pub const EV_ABS: u16 = 0x03;
/// `SYN_REPORT`: the events since the last one form one state change.
pub const SYN_REPORT: u16 = 0;
/// `SYN_DROPPED`: the kernel's buffer overran; the state is unknown until resynchronised.
pub const SYN_DROPPED: u16 = 3;

/// The left stick across (`ABS_X`): left is low.
pub const ABS_X: u16 = 0x00;
/// The left stick up and down (`ABS_Y`): up is low.
pub const ABS_Y: u16 = 0x01;
/// The left trigger (`ABS_Z`).
pub const ABS_Z: u16 = 0x02;
/// The right stick across (`ABS_RX`).
pub const ABS_RX: u16 = 0x03;
/// The right stick up and down (`ABS_RY`).
pub const ABS_RY: u16 = 0x04;
/// The right trigger (`ABS_RZ`).
pub const ABS_RZ: u16 = 0x05;
/// The d-pad across (`ABS_HAT0X`).
pub const ABS_HAT0X: u16 = 0x10;
/// The d-pad up and down (`ABS_HAT0Y`).
pub const ABS_HAT0Y: u16 = 0x11;

/// `BTN_SOUTH` (A / cross).
pub const BTN_SOUTH: u16 = 0x130;
/// `BTN_EAST` (B / circle).
pub const BTN_EAST: u16 = 0x131;
/// `BTN_NORTH` (X on Linux's layout / triangle).
pub const BTN_NORTH: u16 = 0x133;
/// `BTN_WEST` (Y / square).
pub const BTN_WEST: u16 = 0x134;
/// `BTN_TL`: the left shoulder, the dead-man button by default.
pub const BTN_TL: u16 = 0x136;
/// `BTN_TR`: the right shoulder.
pub const BTN_TR: u16 = 0x137;
/// `BTN_SELECT`.
pub const BTN_SELECT: u16 = 0x13a;
/// `BTN_START`.
pub const BTN_START: u16 = 0x13b;

/// One input event, without its time (the reader stamps when it arrived).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct RawEvent {
    /// `EV_SYN`, `EV_KEY`, `EV_ABS`, …
    pub kind: u16,
    /// Which button or axis.
    pub code: u16,
    /// Pressed / released, or the axis position.
    pub value: i32,
}

impl RawEvent {
    /// A button pressed (`true`) or released.
    pub fn key(code: u16, pressed: bool) -> Self {
        Self { kind: EV_KEY, code, value: i32::from(pressed) }
    }

    /// An axis at `value`.
    pub fn abs(code: u16, value: i32) -> Self {
        Self { kind: EV_ABS, code, value }
    }

    /// The end of a frame.
    pub fn report() -> Self {
        Self { kind: EV_SYN, code: SYN_REPORT, value: 0 }
    }

    /// The kernel lost events.
    pub fn dropped() -> Self {
        Self { kind: EV_SYN, code: SYN_DROPPED, value: 0 }
    }

    /// Reads one record (the machine's own byte order, as the kernel writes it).
    pub fn from_bytes(bytes: &[u8; EVENT_SIZE]) -> Self {
        Self {
            kind: u16::from_ne_bytes([bytes[16], bytes[17]]),
            code: u16::from_ne_bytes([bytes[18], bytes[19]]),
            value: i32::from_ne_bytes([bytes[20], bytes[21], bytes[22], bytes[23]]),
        }
    }

    /// The record, stamped `micros` after the epoch (for tools and tests that write a pipe).
    pub fn to_bytes(self, micros: u64) -> [u8; EVENT_SIZE] {
        let mut bytes = [0u8; EVENT_SIZE];
        bytes[..8].copy_from_slice(&(micros / 1_000_000).to_ne_bytes());
        bytes[8..16].copy_from_slice(&(micros % 1_000_000).to_ne_bytes());
        bytes[16..18].copy_from_slice(&self.kind.to_ne_bytes());
        bytes[18..20].copy_from_slice(&self.code.to_ne_bytes());
        bytes[20..24].copy_from_slice(&self.value.to_ne_bytes());
        bytes
    }
}

/// A gamepad's button or axis code by its kernel name (`BTN_TL`, `ABS_Y`), for the command line.
pub fn code_by_name(name: &str) -> Option<u16> {
    let names: [(&str, u16); 18] = [
        ("BTN_SOUTH", BTN_SOUTH),
        ("BTN_EAST", BTN_EAST),
        ("BTN_NORTH", BTN_NORTH),
        ("BTN_WEST", BTN_WEST),
        ("BTN_TL", BTN_TL),
        ("BTN_TR", BTN_TR),
        ("BTN_SELECT", BTN_SELECT),
        ("BTN_START", BTN_START),
        ("ABS_X", ABS_X),
        ("ABS_Y", ABS_Y),
        ("ABS_Z", ABS_Z),
        ("ABS_RX", ABS_RX),
        ("ABS_RY", ABS_RY),
        ("ABS_RZ", ABS_RZ),
        ("ABS_HAT0X", ABS_HAT0X),
        ("ABS_HAT0Y", ABS_HAT0Y),
        ("BTN_A", BTN_SOUTH),
        ("BTN_B", BTN_EAST),
    ];
    names.iter().find(|(known, _)| known.eq_ignore_ascii_case(name.trim())).map(|(_, code)| *code)
}

/// A code's kernel name, or its number.
pub fn code_name(kind: u16, code: u16) -> String {
    let known: &[(u16, &str)] = match kind {
        EV_KEY => &[
            (BTN_SOUTH, "BTN_SOUTH"),
            (BTN_EAST, "BTN_EAST"),
            (BTN_NORTH, "BTN_NORTH"),
            (BTN_WEST, "BTN_WEST"),
            (BTN_TL, "BTN_TL"),
            (BTN_TR, "BTN_TR"),
            (BTN_SELECT, "BTN_SELECT"),
            (BTN_START, "BTN_START"),
        ],
        EV_ABS => &[
            (ABS_X, "ABS_X"),
            (ABS_Y, "ABS_Y"),
            (ABS_Z, "ABS_Z"),
            (ABS_RX, "ABS_RX"),
            (ABS_RY, "ABS_RY"),
            (ABS_RZ, "ABS_RZ"),
            (ABS_HAT0X, "ABS_HAT0X"),
            (ABS_HAT0Y, "ABS_HAT0Y"),
        ],
        _ => &[],
    };
    known
        .iter()
        .find(|(value, _)| *value == code)
        .map_or_else(|| format!("{kind}:{code:#x}"), |(_, name)| (*name).into())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The kernel's layout: 16 bytes of time, then type, code, value.
    #[test]
    fn a_record_is_read_at_the_kernels_offsets() {
        let mut bytes = [0u8; EVENT_SIZE];
        bytes[16..18].copy_from_slice(&EV_KEY.to_ne_bytes());
        bytes[18..20].copy_from_slice(&BTN_TL.to_ne_bytes());
        bytes[20..24].copy_from_slice(&1i32.to_ne_bytes());
        assert_eq!(RawEvent::from_bytes(&bytes), RawEvent::key(BTN_TL, true));
        let axis = RawEvent::abs(ABS_Y, -32768);
        assert_eq!(RawEvent::from_bytes(&axis.to_bytes(1_500_000)), axis);
        assert_eq!(&axis.to_bytes(1_500_000)[..8], &1u64.to_ne_bytes());
        assert_eq!(&axis.to_bytes(1_500_000)[8..16], &500_000u64.to_ne_bytes());
        assert_eq!(code_by_name("btn_tl"), Some(BTN_TL));
        assert_eq!(code_name(EV_ABS, ABS_Y), "ABS_Y");
    }
}
