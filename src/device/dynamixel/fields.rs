//! What the driver writes to a servo's control table and reads back out of
//! it, as pure functions: a read, a write and a sync write in either
//! protocol; the spans a round of readings and a servo's limits take; and
//! those spans' bytes read as [`Limits`] and a [`Reading`].

use std::time::Instant;

use super::{Limits, Reading};
use crate::protocol::dynamixel::table::Known;
use crate::protocol::dynamixel::{BROADCAST, Packet, Protocol, instruction};

/// A field the driver writes: its name (a refusal says it) and where a model keeps it (address, size).
pub(super) type Writable = (&'static str, fn(&Known) -> Option<(u16, u8)>);
/// Torque Enable.
pub(super) const TORQUE: Writable = ("torque", |model| Some((model.layout.at.torque, 1)));
/// The LED.
pub(super) const LED: Writable = ("LED", |model| Some((model.layout.at.led, 1)));
/// Profile Velocity (an AX: Moving Speed).
pub(super) const PROFILE_VELOCITY: Writable =
    ("profile velocity", |model| Some((model.layout.at.speed, model.layout.at.position_size)));
/// Profile Acceleration (an AX has none).
pub(super) const PROFILE_ACCELERATION: Writable =
    ("profile acceleration", |model| model.layout.at.acceleration.map(|addr| (addr, 4)));

/// A read of `len` bytes at `addr` of servo `id`, in its protocol.
pub(super) fn read(protocol: Protocol, id: u8, addr: u16, len: u16) -> Packet {
    let params = match protocol {
        Protocol::Two => [addr.to_le_bytes(), len.to_le_bytes()].concat(),
        // 1.0 addresses and lengths are one byte each (its tables end below 256).
        #[allow(clippy::cast_possible_truncation)]
        Protocol::One => vec![addr as u8, len as u8],
    };
    Packet::instruction(protocol, id, instruction::READ, params)
}

/// A write of `value` in `size` bytes at `addr` of servo `id`.
pub(super) fn write(protocol: Protocol, id: u8, addr: u16, value: u32, size: u8) -> Packet {
    let mut params = match protocol {
        Protocol::Two => addr.to_le_bytes().to_vec(),
        #[allow(clippy::cast_possible_truncation)]
        Protocol::One => vec![addr as u8],
    };
    params.extend(&value.to_le_bytes()[..usize::from(size)]);
    Packet::instruction(protocol, id, instruction::WRITE, params)
}

/// A sync write of `size` bytes at `addr`, each servo its value.
pub(super) fn sync_write(protocol: Protocol, addr: u16, size: u8, values: &[(u8, u32)]) -> Packet {
    let mut params = match protocol {
        Protocol::Two => [addr.to_le_bytes(), u16::from(size).to_le_bytes()].concat(),
        #[allow(clippy::cast_possible_truncation)]
        Protocol::One => vec![addr as u8, size],
    };
    for (id, value) in values {
        params.push(*id);
        params.extend(&value.to_le_bytes()[..usize::from(size)]);
    }
    Packet::instruction(protocol, BROADCAST, instruction::SYNC_WRITE, params)
}

/// `len` (≤ 4) little-endian bytes of `data` at `at`, if it holds them.
pub(super) fn le(data: &[u8], at: usize, len: usize) -> Option<u32> {
    let bytes = data.get(at..at + len)?;
    let mut word = [0; 4];
    word[..len].copy_from_slice(bytes);
    Some(u32::from_le_bytes(word))
}

/// The span a round reads of a model: from its load to past its temperature
/// (2.0: 126..=146; 1.0: 36..=43, from its present position).
pub(super) fn reading_span(model: &Known) -> (u16, u16) {
    let at = model.layout.at;
    let first = at.present.min(at.load).min(at.voltage).min(at.temperature);
    let last = at.present.max(at.load).max(at.voltage).max(at.temperature);
    (first, last - first + 1)
}

/// The span a servo's limits take: its temperature limit to past its position limits.
pub(super) fn limits_span(model: &Known) -> (u16, u16) {
    let at = model.layout.at;
    let first = at.temperature_limit.min(at.limits.0).min(at.limits.1);
    let end = (at.limits.0.max(at.limits.1) + u16::from(at.position_size)).max(at.temperature_limit + 1);
    (first, end - first)
}

/// The limits in the bytes of [`limits_span`]; an AX whose limits are both 0
/// turns as a wheel, and its range is its whole table.
pub(super) fn limits_of(model: &Known, params: &[u8]) -> Option<Limits> {
    let at = model.layout.at;
    let (base, _) = limits_span(model);
    let field = |addr: u16, len: u8| le(params, usize::from(addr - base), usize::from(len));
    let size = at.position_size;
    let (lowest, highest, temperature) =
        (field(at.limits.0, size)?, field(at.limits.1, size)?, field(at.temperature_limit, 1)?);
    let (lowest, highest) =
        if lowest == 0 && highest == 0 { (0, model.layout.top_position) } else { (lowest, highest) };
    // A one-byte field.
    #[allow(clippy::cast_possible_truncation)]
    Some(Limits { lowest, highest, temperature_limit_c: temperature as u8 })
}

/// A round's reading in the bytes of [`reading_span`] (`two`: Protocol 2.0),
/// with the servo's hardware errors as last known, come `at`.
pub(super) fn reading_of(model: &Known, two: bool, params: &[u8], hardware_error: u8, at: Instant) -> Option<Reading> {
    let fields = model.layout.at;
    let (base, _) = reading_span(model);
    let field = |addr: u16, len: u8| le(params, usize::from(addr - base), usize::from(len));
    let voltage_size = if two { 2 } else { 1 };
    let position = field(fields.present, fields.position_size)?;
    let load = field(fields.load, 2)?;
    let voltage = field(fields.voltage, voltage_size)?;
    let temperature = field(fields.temperature, 1)?;
    let load_percent = if two {
        // A signed 2-byte value, 0.1 % a unit.
        #[allow(clippy::cast_possible_truncation)]
        let signed = load as u16 as i16;
        f64::from(signed) / 10.0
    } else {
        // 0..=1023 of the most torque, bit 10 the direction (clockwise negative).
        let magnitude = f64::from(load & 0x3FF) / 1023.0 * 100.0;
        if load & 0x400 != 0 { -magnitude } else { magnitude }
    };
    // A one-byte field.
    #[allow(clippy::cast_possible_truncation)]
    Some(Reading {
        position,
        load_percent,
        volts: f64::from(voltage) / 10.0,
        temperature_c: temperature as u8,
        hardware_error,
        at,
    })
}
