//! The Blender servo-animation add-on's JSON export, in every layout its
//! releases wrote: `fps`, `frames`, and one position per animation frame —
//! per frame (`positions`: [{id: value}], since 2024), per servo (`servos`:
//! id → `name`, `positions`, 2022–2023), or per bone (`positions`, or in
//! 1.0 `pulses`: bone → list, values as strings until mid-2022) — in
//! whatever unit the bone's servo settings map to (default 150..600 over 180°).

mod json;
mod loose;

use serde_json::{Map, Value, json};

use super::format::{Format, ReadError};
use super::source::{Body, Clip, Source, Unit};

/// The add-on's default servo settings: positions 150..=600 over 180°, 90° neutral.
pub const ADDON_DEFAULT: Unit = Unit { zero: 375.0, per_degree: 2.5, label: "add-on positions" };
/// Pulse widths: 1500 µs at 0°, 2000 µs over 180°.
pub const MICROSECONDS: Unit = Unit { zero: 1500.0, per_degree: 2000.0 / 180.0, label: "µs" };
/// Servo angles 0..180 with 90 at the centre.
pub const ANGLE_0_180: Unit = Unit { zero: 90.0, per_degree: 1.0, label: "0..180°" };
/// The key Servo Studio adds to what it writes, saying the unit (other readers ignore it).
const UNIT_KEY: &str = "servo_studio_unit";

/// Reads an add-on export.
pub fn read(text: &str) -> Result<Source, ReadError> {
    let export = json::read(text.trim_start_matches('\u{feff}'))?;
    let fps = export.fps.ok_or_else(|| at("fps", "no frame rate (fps): is this the add-on's JSON export?"))?;
    if !(fps > 0.0 && fps <= 1000.0) {
        return Err(at("fps", format!("{fps} frames per second is not a frame rate")));
    }
    let (mut channels, columns) = export
        .servos
        .or(export.frames)
        .or(export.bones)
        .or(export.pulses)
        .ok_or_else(|| at("", "no servos, positions or pulses: is this the add-on's JSON export?"))?;
    let frames = columns.first().map_or(0, Vec::len);
    if let Some((channel, column)) = channels.iter().zip(&columns).find(|(_, column)| column.len() != frames) {
        return Err(at(&channel.key, format!("{} positions where the first servo has {frames}", column.len())));
    }
    if frames == 0 {
        return Err(at("servos", "no positions at all"));
    }
    for (channel, column) in channels.iter_mut().zip(&columns) {
        channel.unit = export.unit.unwrap_or_else(|| guess_unit(column));
    }
    let rows = (0..frames).map(|frame| columns.iter().map(|column| column[frame]).collect()).collect();
    let name = export.scene.unwrap_or_else(|| "animation".to_string());
    Ok(Source {
        format: Format::Blender,
        channels,
        clips: vec![Clip::new(name, Body::Samples { fps, rows })],
        dropped: Vec::new(),
        notes: Vec::new(),
    })
}

fn at(element: &str, message: impl Into<String>) -> ReadError {
    ReadError { line: None, element: (!element.is_empty()).then(|| element.to_string()), message: message.into() }
}

/// The unit a servo's positions most likely are: µs past 600, the add-on's
/// default 150..=600, else angles 0..180.
pub fn guess_unit(positions: &[f64]) -> Unit {
    let (low, high) = positions.iter().fold((f64::MAX, f64::MIN), |(low, high), v| (low.min(*v), high.max(*v)));
    if high > 600.0 {
        MICROSECONDS
    } else if low >= 150.0 {
        ADDON_DEFAULT
    } else {
        ANGLE_0_180
    }
}

/// One servo's positions for [`write`].
pub struct Written<'a> {
    /// Its id in the export.
    pub id: String,
    /// Its bone's name.
    pub name: &'a str,
    /// One position per frame.
    pub positions: Vec<f64>,
}

/// An add-on export: `servos` at `fps`, positions in `unit` (said in a key of its own).
pub fn write(fps: f64, scene: &str, unit: Unit, servos: &[Written<'_>]) -> String {
    let frames = servos.first().map_or(0, |servo| servo.positions.len());
    // Frame counts far below 2^52.
    #[allow(clippy::cast_precision_loss)]
    let seconds = (frames as f64 / fps).round();
    let mut by_id = Map::new();
    for servo in servos {
        let positions: Vec<Value> = servo.positions.iter().map(|p| json!((p * 100.0).round() / 100.0)).collect();
        by_id.insert(servo.id.clone(), json!({ "name": servo.name, "positions": positions }));
    }
    let value = json!({
        "description": "Blender Servo Animation Positions",
        "fps": fps,
        "frames": frames,
        "seconds": seconds,
        "bones": servos.len(),
        "armature": "Servo Studio",
        "file": "",
        "scene": scene,
        "servos": by_id,
        UNIT_KEY: { "zero": unit.zero, "per_degree": unit.per_degree },
    });
    serde_json::to_string_pretty(&value).unwrap_or_default()
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::float_cmp)]
    use super::*;

    #[test]
    fn both_layouts_are_read_and_units_guessed() {
        let new = r#"{"description":"x","fps":30,"frames":3,"servos":{"3":{"name":"Jaw","positions":[1500,1600,2000]},"7":{"name":"Eye","positions":[90,100,80]}}}"#;
        let source = read(new).unwrap();
        assert_eq!(source.channels[0].name, "Jaw");
        assert_eq!(source.channels[0].unit, MICROSECONDS);
        assert_eq!(source.channels[1].unit, ANGLE_0_180);
        let Body::Samples { fps, rows } = &source.clips[0].body else { panic!() };
        assert_eq!((*fps, rows[2].clone()), (30.0, vec![2000.0, 80.0]));
        let old = r#"{"fps":24,"positions":{"Bone":[375,400]}}"#;
        assert_eq!(read(old).unwrap().channels[0].unit, ADDON_DEFAULT);
    }

    #[test]
    fn what_servo_studio_writes_reads_back_in_its_unit() {
        let text =
            write(50.0, "s", MICROSECONDS, &[Written { id: "1".into(), name: "a", positions: vec![1000.0, 1500.5] }]);
        let source = read(&text).unwrap();
        assert_eq!(source.channels[0].unit.per_degree, MICROSECONDS.per_degree);
        let Body::Samples { rows, .. } = &source.clips[0].body else { panic!() };
        assert_eq!(rows[1], [1500.5]);
    }

    #[test]
    fn bad_exports_say_where() {
        assert_eq!(read("{\n\"fps\": 30,\n\"servos\": [\n").unwrap_err().line, Some(4));
        let word = read(r#"{"fps":30,"servos":{"1":{"positions":[1, "x"]}}}"#).unwrap_err();
        assert_eq!(word.element.as_deref(), Some("servos.1.positions[1]"), "{word}");
        assert!(read(r#"{"servos":{}}"#).unwrap_err().message.contains("fps"));
        assert!(read("[1,2]").unwrap_err().message.contains("not a JSON object"));
        // A unit key of another shape says no unit; the rest is read on.
        let odd = read(r#"{"servo_studio_unit": [1, {"zero": 2}], "fps": 30, "servos": {"1": {"positions": [1, 2]}}}"#);
        assert_eq!(odd.unwrap().channels[0].unit, ANGLE_0_180);
        let hinted = r#"{"servo_studio_unit": {"zero": 1500, "per_degree": 10, "x": null}, "fps": 30, "servos": {"1": {"positions": [1, 2]}}}"#;
        assert_eq!(read(hinted).unwrap().channels[0].unit.per_degree, 10.0);
        let late = read("{\"fps\": 30,\n\"positions\": [{\"1\": 375}, {\"1\": true}]}").unwrap_err();
        assert_eq!((late.line, late.element.as_deref()), (Some(2), Some("positions[1].1")), "{late}");
    }
}
