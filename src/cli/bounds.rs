//! Every number a user types, read with its bounds: a value outside them is
//! refused while the command line is parsed, before a port is opened or a
//! byte sent, with what the bounds are. Nothing later does arithmetic on an
//! unbounded number (a duration of 1e20 s cannot be added to a clock).

use std::time::Duration;

/// The longest `rflex drive` and `trajectory` take, s (an hour).
pub const MAX_SECONDS: f64 = 3600.0;
/// The longest a device may be given to answer, ms (ten minutes).
pub const MAX_TIMEOUT_MS: u64 = 600_000;
/// Line rates a serial port or the emulator takes.
pub const BAUD: std::ops::RangeInclusive<u32> = 300..=4_000_000;
/// The longest the emulated servo board waits before answering, ms.
pub const MAX_TURNAROUND_MS: u64 = 60_000;
/// The emulated servo board's memory, bytes (up to 1 GiB).
pub const MEMORY_BYTES: std::ops::RangeInclusive<i32> = 0..=(1 << 30);
/// Fastest a base is ever asked to go, m/s (each robot's own limit is lower).
pub const MAX_SPEED_M_PER_S: f64 = 10.0;
/// Fastest a base is ever asked to turn, rad/s.
pub const MAX_TURN_RAD_PER_S: f64 = 10.0;
/// Largest acceleration asked, m/s².
pub const MAX_ACCEL_M_PER_S2: f64 = 10.0;

fn real(text: &str) -> Result<f64, String> {
    let value: f64 = text.trim().parse().map_err(|_| format!("{text:?} is not a number"))?;
    if value.is_finite() { Ok(value) } else { Err(format!("{text:?} is not a finite number")) }
}

fn within_f64(text: &str, min: f64, max: f64, unit: &str) -> Result<f64, String> {
    let value = real(text)?;
    if (min..=max).contains(&value) { Ok(value) } else { Err(format!("{value} is outside {min}..={max} {unit}")) }
}

fn integer<T: std::str::FromStr + PartialOrd + std::fmt::Display + Copy>(
    text: &str,
    range: &std::ops::RangeInclusive<T>,
    unit: &str,
) -> Result<T, String> {
    let value: T = text
        .trim()
        .parse()
        .map_err(|_| format!("{text:?} is not a whole number in {}..={} {unit}", range.start(), range.end()))?;
    if range.contains(&value) {
        Ok(value)
    } else {
        Err(format!("{value} is outside {}..={} {unit}", range.start(), range.end()))
    }
}

/// `audio-info --sensitivity`: 0 to 1.
pub fn unit(text: &str) -> Result<f32, String> {
    // Within 0..=1: f32 holds it.
    #[allow(clippy::cast_possible_truncation)]
    within_f64(text, 0.0, 1.0, "").map(|value| value as f32)
}

/// `follow-audio --attack-ms / --release-ms`: 0.1 ms to 10 s.
pub fn positive_ms(text: &str) -> Result<f64, String> {
    within_f64(text, 0.1, 10_000.0, "ms")
}

/// `follow-audio --threshold-db`: −120 to 0 dB of full scale.
pub fn threshold_db(text: &str) -> Result<f64, String> {
    within_f64(text, -120.0, 0.0, "dB")
}

/// `follow-audio --closed / --open`: −360 to 360 degrees.
pub fn angle_deg(text: &str) -> Result<f64, String> {
    within_f64(text, -360.0, 360.0, "°")
}

/// `rflex drive --seconds`: 0 to an hour.
pub fn drive_seconds(text: &str) -> Result<f64, String> {
    within_f64(text, 0.0, MAX_SECONDS, "s")
}

/// `trajectory --seconds`: above 0, at most an hour.
pub fn trajectory_seconds(text: &str) -> Result<f64, String> {
    let value = within_f64(text, 0.0, MAX_SECONDS, "s")?;
    if value > 0.0 { Ok(value) } else { Err("--seconds must be above 0".into()) }
}

/// `--speed`, m/s, either way.
pub fn speed(text: &str) -> Result<f64, String> {
    within_f64(text, -MAX_SPEED_M_PER_S, MAX_SPEED_M_PER_S, "m/s")
}

/// `--turn`, rad/s, either way.
pub fn turn(text: &str) -> Result<f64, String> {
    within_f64(text, -MAX_TURN_RAD_PER_S, MAX_TURN_RAD_PER_S, "rad/s")
}

/// `--accel`, m/s², above 0.
pub fn accel(text: &str) -> Result<f64, String> {
    let value = within_f64(text, 0.0, MAX_ACCEL_M_PER_S2, "m/s²")?;
    if value > 0.0 { Ok(value) } else { Err("--accel must be above 0".into()) }
}

/// `--timeout-ms`: 1 ms to ten minutes.
pub fn timeout_ms(text: &str) -> Result<u64, String> {
    integer(text, &(1..=MAX_TIMEOUT_MS), "ms")
}

/// `--baud`: a rate a serial port can run.
pub fn baud(text: &str) -> Result<u32, String> {
    integer(text, &BAUD, "baud")
}

/// `sim --turnaround-ms`.
pub fn turnaround_ms(text: &str) -> Result<u64, String> {
    integer(text, &(0..=MAX_TURNAROUND_MS), "ms")
}

/// `sim --memory`.
pub fn memory_bytes(text: &str) -> Result<i32, String> {
    integer(text, &MEMORY_BYTES, "bytes")
}

/// `fit --tolerance-deg`: 0.05° (half a PLEN2 tenth) to 180°.
pub fn tolerance_deg(text: &str) -> Result<f64, String> {
    within_f64(text, 0.05, 180.0, "°")
}

/// `convert --fps`: 1..=1000 frames a second.
pub fn fps(text: &str) -> Result<f64, String> {
    within_f64(text, 1.0, 1000.0, " fps")
}

/// `fit --max-frames`: 1 to as many actions as a project holds.
pub fn max_frames(text: &str) -> Result<usize, String> {
    integer(text, &(1..=crate::project::MAX_LIST_LEN), "frames")
}

/// A PLEN2 slot, 0..=89.
pub fn slot(text: &str) -> Result<u8, String> {
    integer(text, &(0..=crate::protocol::plen2::SLOTS - 1), "(a PLEN2 slot)")
}

/// `sim --room WIDTHxDEPTH`, metres, each 0.5..=100.
pub fn room(text: &str) -> Result<(f64, f64), String> {
    let (width, depth) = text
        .split_once(['x', 'X', '×'])
        .ok_or_else(|| format!("{text:?} is not WIDTHxDEPTH in metres, e.g. 4.2x2.8"))?;
    Ok((within_f64(width, 0.5, 100.0, "m")?, within_f64(depth, 0.5, 100.0, "m")?))
}

/// `sim --start X,Y,THETA_DEG`: metres from the room's centre (±50), degrees (±360).
pub fn start(text: &str) -> Result<(f64, f64, f64), String> {
    let parts: Vec<&str> = text.split(',').collect();
    let [x, y, theta] = parts[..] else {
        return Err(format!("{text:?} is not X,Y,THETA_DEG, e.g. 1.0,-0.5,30"));
    };
    Ok((within_f64(x, -50.0, 50.0, "m")?, within_f64(y, -50.0, 50.0, "m")?, within_f64(theta, -360.0, 360.0, "°")?))
}

/// A duration of `seconds` that is known to be bounded (parsed by the functions above).
pub fn duration(seconds: f64) -> Duration {
    Duration::try_from_secs_f64(seconds.clamp(0.0, MAX_SECONDS)).unwrap_or(Duration::ZERO)
}

/// `--axis-range MIN:MAX`: the raw values a gamepad path's axes span, MIN below MAX.
pub fn axis_range(text: &str) -> Result<(i32, i32), String> {
    let bad = || format!("{text:?} is not an axis range: write MIN:MAX, e.g. -32768:32767 or 0:255");
    let (min, max) = text.split_once(':').ok_or_else(bad)?;
    let min: i32 = min.trim().parse().map_err(|_| bad())?;
    let max: i32 = max.trim().parse().map_err(|_| bad())?;
    if min < max { Ok((min, max)) } else { Err(format!("{text:?}: MIN must be below MAX")) }
}

/// `--deadman`: a gamepad button by its kernel name.
pub fn button(text: &str) -> Result<u16, String> {
    crate::gamepad::code_by_name(text)
        .filter(|code| *code >= 0x100)
        .ok_or_else(|| format!("{text:?} is not a gamepad button: use BTN_TL, BTN_TR, BTN_SOUTH, BTN_EAST, BTN_NORTH, BTN_WEST, BTN_SELECT or BTN_START"))
}

/// `--dead-zone`: the part of a stick around its centre that counts as centred, 0 to 0.9.
pub fn dead_zone(text: &str) -> Result<f64, String> {
    within_f64(text, 0.0, 0.9, "")
}

/// `--speed` / `--turn` for teleop: a top speed, above 0.
pub fn top_speed(text: &str) -> Result<f64, String> {
    let value = within_f64(text, 0.0, MAX_SPEED_M_PER_S.max(MAX_TURN_RAD_PER_S), "")?;
    if value > 0.0 { Ok(value) } else { Err("a top speed must be above 0".into()) }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_outside_their_bounds_are_refused_with_the_bounds() {
        assert_eq!(drive_seconds("1e20"), Err("100000000000000000000 is outside 0..=3600 s".into()));
        assert_eq!(drive_seconds("NaN"), Err("\"NaN\" is not a finite number".into()));
        assert_eq!(drive_seconds("-1"), Err("-1 is outside 0..=3600 s".into()));
        assert_eq!(drive_seconds("2.5"), Ok(2.5));
        assert!(trajectory_seconds("0").is_err());
        assert_eq!(baud("0"), Err("0 is outside 300..=4000000 baud".into()));
        assert_eq!(timeout_ms("18446744073709551615"), Err("18446744073709551615 is outside 1..=600000 ms".into()));
        assert!(timeout_ms("99999999999999999999999").unwrap_err().contains("not a whole number"));
        assert_eq!(slot("90"), Err("90 is outside 0..=89 (a PLEN2 slot)".into()));
        assert_eq!(accel("0"), Err("--accel must be above 0".into()));
        assert_eq!(memory_bytes("-5"), Err("-5 is outside 0..=1073741824 bytes".into()));
        assert_eq!(room("6x4.5"), Ok((6.0, 4.5)));
        assert_eq!(room("0x4"), Err("0 is outside 0.5..=100 m".into()));
        assert_eq!(start("1,-0.5,30"), Ok((1.0, -0.5, 30.0)));
        assert!(start("1,2").unwrap_err().contains("X,Y,THETA_DEG"));
    }
}

/// Slots as given on the command line.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Slots(pub Vec<u8>);

/// Parses `0-19,70` into slots.
pub fn parse_slots(text: &str) -> Result<Slots, String> {
    const FORMS: &str = "a slot (0..89), a range (0-19) or a list of them separated by commas, e.g. 0-19,70";
    if text.trim().is_empty() {
        return Err(format!("no slots given: name {FORMS}"));
    }
    let mut slots = Vec::new();
    for part in text.split(',').map(str::trim) {
        if part.is_empty() {
            return Err(format!("{text:?} has an empty item between commas: name {FORMS}"));
        }
        let bad = || format!("{part:?} is not {FORMS}");
        let (first, last) = match part.split_once('-') {
            Some((a, b)) => (a.trim().parse::<u8>().map_err(|_| bad())?, b.trim().parse::<u8>().map_err(|_| bad())?),
            None => {
                let slot = part.parse::<u8>().map_err(|_| bad())?;
                (slot, slot)
            }
        };
        if first > last || last >= crate::protocol::plen2::SLOTS {
            return Err(bad());
        }
        slots.extend(first..=last);
    }
    slots.sort_unstable();
    slots.dedup();
    Ok(Slots(slots))
}
