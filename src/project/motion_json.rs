//! The PLEN community's `motion.json` (the official Motion Editor's format,
//! `plen2.md` §4): one motion per file, devices named, `@`-keys optional. One
//! file or a folder of them opens; a motion saves so the official editor opens it.

use std::path::{Path, PathBuf};

use serde_json::{Value, json};

use super::plen2::{Frame, Joint, LoopRange, Motion, Pose};

/// A motion.json could not be read.
#[derive(Debug, thiserror::Error)]
pub enum MotionJsonError {
    /// The file or folder could not be read.
    #[error("cannot read {path}: {source}")]
    Io {
        /// The path.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// Not JSON, or not a motion.
    #[error("{path}: not a PLEN2 motion.json: {reason}")]
    NotAMotion {
        /// The file.
        path: PathBuf,
        /// What is wrong.
        reason: String,
    },
    /// A folder without any `*.json` file.
    #[error("{path} holds no motion.json (*.json) files")]
    Empty {
        /// The folder.
        path: PathBuf,
    },
}

fn joint_by_name(name: &str) -> Option<Joint> {
    Joint::ALL.into_iter().find(|joint| joint.name() == name)
}

fn int(value: &Value, what: &str) -> Result<i64, String> {
    value.as_i64().ok_or_else(|| format!("{what} is not a whole number"))
}

fn narrow<T: TryFrom<i64>>(value: i64, what: &str) -> Result<T, String> {
    T::try_from(value).map_err(|_| format!("{what} {value} is out of range"))
}

/// The keys a motion.json may hold at each level (the official editor's, `@` ones included).
const MOTION_KEYS: [&str; 7] = ["slot", "name", "codes", "frames", "@frame_length", "@index", "@metadata"];
const CODE_KEYS: [&str; 2] = ["method", "arguments"];
const FRAME_KEYS: [&str; 3] = ["transition_time_ms", "outputs", "@index"];
const OUTPUT_KEYS: [&str; 2] = ["device", "value"];

/// Notes the keys of `value` (an object) that are not in `known`, at `at`.
fn note_unknown(value: &Value, known: &[&str], at: &str, unknown: &mut Vec<String>) {
    if let Some(object) = value.as_object() {
        for key in object.keys().filter(|key| !known.contains(&key.as_str())) {
            unknown.push(if at.is_empty() { key.clone() } else { format!("{at}.{key}") });
        }
    }
}

/// A motion from the text of a motion.json, and the keys it held that the
/// official format does not have (ignored; named so that a misspelling shows).
/// Errors name the frame (from 1) and the joint they are about. A UTF-8
/// byte-order mark is skipped.
pub fn read_motion(text: &str) -> Result<(Motion, Vec<String>), String> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let value: Value = serde_json::from_str(text).map_err(|error| error.to_string())?;
    let mut unknown = Vec::new();
    note_unknown(&value, &MOTION_KEYS, "", &mut unknown);
    let slot = narrow(int(&value["slot"], "slot")?, "slot")?;
    let name = value["name"].as_str().ok_or("no name")?.to_string();
    let mut loop_range = None;
    let mut jump_slot = None;
    for (index, code) in value["codes"].as_array().map_or(&[][..], Vec::as_slice).iter().enumerate() {
        let at = format!("codes[{index}]");
        note_unknown(code, &CODE_KEYS, &at, &mut unknown);
        let args: Vec<i64> = code["arguments"]
            .as_array()
            .map_or(Ok(Vec::new()), |a| a.iter().map(|v| int(v, &format!("{at}: an argument"))).collect())?;
        match (code["method"].as_str(), args.as_slice()) {
            (Some("loop"), [begin, end, count]) => {
                loop_range = Some(LoopRange {
                    begin_frame: narrow(*begin, "loop begin")?,
                    end_frame: narrow(*end, "loop end")?,
                    count: narrow(*count, "loop count")?,
                });
            }
            (Some("jump"), [slot]) => jump_slot = Some(narrow(*slot, "jump slot")?),
            (Some(method @ ("loop" | "jump")), _) => {
                return Err(format!("{at}: {method} takes {} argument(s)", if method == "loop" { 3 } else { 1 }));
            }
            (Some(method), _) => return Err(format!("{at}: unknown code {method:?} (known: loop, jump)")),
            (None, _) => return Err(format!("{at}: a code without a method")),
        }
    }
    let mut frames = Vec::new();
    for (index, frame) in value["frames"].as_array().ok_or("no frames")?.iter().enumerate() {
        let at = format!("frame {}", index + 1);
        note_unknown(frame, &FRAME_KEYS, &format!("frames[{index}]"), &mut unknown);
        let mut pose = Pose::default();
        let mut seen = Vec::new();
        for (output_index, output) in
            frame["outputs"].as_array().ok_or_else(|| format!("{at}: no outputs"))?.iter().enumerate()
        {
            note_unknown(output, &OUTPUT_KEYS, &format!("frames[{index}].outputs[{output_index}]"), &mut unknown);
            let device = output["device"].as_str().ok_or_else(|| format!("{at}: an output without a device name"))?;
            let joint = joint_by_name(device).ok_or_else(|| format!("{at}: unknown device {device:?}"))?;
            if seen.contains(&joint) {
                return Err(format!("{at}: {device} is listed twice"));
            }
            seen.push(joint);
            let value = int(&output["value"], &format!("{at}, {device}: value"))?;
            pose.set(joint, narrow(value, &format!("{at}, {device}: value"))?);
        }
        let transition_ms = narrow(
            int(&frame["transition_time_ms"], &format!("{at}: transition_time_ms"))?,
            &format!("{at}: transition_time_ms"),
        )?;
        frames.push(Frame::new(transition_ms, pose));
    }
    Ok((Motion { slot, name, frames, loop_range, jump_slot }, unknown))
}

/// The motion.json of a motion (keys sorted, as the official editor writes them).
pub fn motion_to_json(motion: &Motion) -> String {
    let mut codes = Vec::new();
    if let Some(range) = motion.loop_range {
        codes.push(json!({"method": "loop", "arguments": [range.begin_frame, range.end_frame, range.count]}));
    }
    if let Some(slot) = motion.jump_slot {
        codes.push(json!({"method": "jump", "arguments": [slot]}));
    }
    let frames: Vec<Value> = motion
        .frames
        .iter()
        .enumerate()
        .map(|(index, frame)| {
            let outputs: Vec<Value> = Joint::ALL
                .iter()
                .map(|joint| json!({"device": joint.name(), "value": frame.values_tenths_deg.get(*joint)}))
                .collect();
            json!({"@index": index, "outputs": outputs, "transition_time_ms": frame.transition_ms})
        })
        .collect();
    let value = json!({
        "@frame_length": motion.frames.len(),
        "codes": codes,
        "frames": frames,
        "name": motion.name,
        "slot": motion.slot,
    });
    let mut text = serde_json::to_string_pretty(&value).unwrap_or_default();
    text.push('\n');
    text
}

/// The motion.json files `path` stands for: itself, or every `*.json` of a
/// folder in file-name order. A folder without any is an error.
pub fn motion_files(path: &Path) -> Result<Vec<PathBuf>, MotionJsonError> {
    if !path.is_dir() {
        return Ok(vec![path.to_path_buf()]);
    }
    let io = |source| MotionJsonError::Io { path: path.to_path_buf(), source };
    let mut files: Vec<PathBuf> = std::fs::read_dir(path)
        .map_err(io)?
        .filter_map(Result::ok)
        .map(|entry| entry.path())
        .filter(|file| file.is_file() && file.extension().is_some_and(|ext| ext.eq_ignore_ascii_case("json")))
        .collect();
    if files.is_empty() {
        return Err(MotionJsonError::Empty { path: path.to_path_buf() });
    }
    files.sort();
    Ok(files)
}

/// Reads one motion.json file: its motion and its unknown keys.
pub fn read_motion_file(file: &Path) -> Result<(Motion, Vec<String>), MotionJsonError> {
    let text =
        std::fs::read_to_string(file).map_err(|source| MotionJsonError::Io { path: file.to_path_buf(), source })?;
    read_motion(&text).map_err(|reason| MotionJsonError::NotAMotion { path: file.to_path_buf(), reason })
}

/// The motions of one motion.json, or of every `*.json` in a folder (by file name).
pub fn load_motions(path: &Path) -> Result<Vec<Motion>, MotionJsonError> {
    motion_files(path)?.iter().map(|file| read_motion_file(file).map(|(motion, _)| motion)).collect()
}

/// Whether the text is a motion.json rather than a project file (read
/// without building the document: a 200 MB project costs no memory here).
/// Its top-level keys decide, as far as they can be read: a motion.json cut
/// short after its `"frames"` key is still a motion.json (and is told so, with
/// where it breaks), not "a project file with no format". A Blender
/// servo-animation export has `"frames"` too, but also its `"fps"` or
/// `"servos"`, which no motion.json has: it is not taken for one.
pub fn looks_like_motion(text: &str) -> bool {
    use serde::Deserializer as _;

    /// The top-level keys seen: (`format`, `frames`, a Blender export's own: `fps`, `servos`).
    struct Keys<'a>(&'a std::cell::Cell<(bool, bool, bool)>);

    impl<'de> serde::de::Visitor<'de> for Keys<'_> {
        type Value = ();

        fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
            f.write_str("a JSON object")
        }

        fn visit_map<A: serde::de::MapAccess<'de>>(self, mut map: A) -> Result<(), A::Error> {
            while let Some(key) = map.next_key::<std::borrow::Cow<'de, str>>()? {
                let (format, frames, blender) = self.0.get();
                self.0.set((
                    format || key == "format",
                    frames || key == "frames",
                    blender || matches!(key.as_ref(), "fps" | "servos" | "positions" | "pulses" | "armature"),
                ));
                map.next_value::<serde::de::IgnoredAny>()?;
            }
            Ok(())
        }
    }

    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let seen = std::cell::Cell::new((false, false, false));
    // An error (a file cut short) leaves the keys read before it.
    let _ = serde_json::Deserializer::from_str(text).deserialize_map(Keys(&seen));
    let (format, frames, blender) = seen.get();
    frames && !format && !blender
}
