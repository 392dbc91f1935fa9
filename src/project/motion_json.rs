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

/// A motion from the text of a motion.json.
pub fn motion_from_json(text: &str) -> Result<Motion, String> {
    let value: Value = serde_json::from_str(text).map_err(|error| error.to_string())?;
    let slot = narrow(int(&value["slot"], "slot")?, "slot")?;
    let name = value["name"].as_str().ok_or("no name")?.to_string();
    let mut loop_range = None;
    let mut jump_slot = None;
    for code in value["codes"].as_array().map_or(&[][..], Vec::as_slice) {
        let args: Vec<i64> =
            code["arguments"].as_array().map_or(Ok(Vec::new()), |a| a.iter().map(|v| int(v, "argument")).collect())?;
        match (code["method"].as_str(), args.as_slice()) {
            (Some("loop"), [begin, end, count]) => {
                loop_range = Some(LoopRange {
                    begin_frame: narrow(*begin, "loop begin")?,
                    end_frame: narrow(*end, "loop end")?,
                    count: narrow(*count, "loop count")?,
                });
            }
            (Some("jump"), [slot]) => jump_slot = Some(narrow(*slot, "jump slot")?),
            (method, _) => return Err(format!("unknown code {method:?}")),
        }
    }
    let mut frames = Vec::new();
    for frame in value["frames"].as_array().ok_or("no frames")? {
        let mut pose = Pose::default();
        for output in frame["outputs"].as_array().ok_or("a frame without outputs")? {
            let device = output["device"].as_str().ok_or("an output without a device name")?;
            let joint = joint_by_name(device).ok_or_else(|| format!("unknown device {device:?}"))?;
            pose.set(joint, narrow(int(&output["value"], "value")?, "value")?);
        }
        let transition_ms = narrow(int(&frame["transition_time_ms"], "transition_time_ms")?, "transition_time_ms")?;
        frames.push(Frame { transition_ms, values_tenths_deg: pose });
    }
    Ok(Motion { slot, name, frames, loop_range, jump_slot })
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

/// The motions of one motion.json, or of every `*.json` in a folder (by file name).
pub fn load_motions(path: &Path) -> Result<Vec<Motion>, MotionJsonError> {
    let io = |source| MotionJsonError::Io { path: path.to_path_buf(), source };
    let files: Vec<PathBuf> = if path.is_dir() {
        let mut files: Vec<PathBuf> = std::fs::read_dir(path)
            .map_err(io)?
            .filter_map(Result::ok)
            .map(|entry| entry.path())
            .filter(|file| file.extension().is_some_and(|ext| ext.eq_ignore_ascii_case("json")))
            .collect();
        files.sort();
        files
    } else {
        vec![path.to_path_buf()]
    };
    files
        .iter()
        .map(|file| {
            let text =
                std::fs::read_to_string(file).map_err(|source| MotionJsonError::Io { path: file.clone(), source })?;
            motion_from_json(&text).map_err(|reason| MotionJsonError::NotAMotion { path: file.clone(), reason })
        })
        .collect()
}

/// Whether the text is a motion.json rather than a project file.
pub fn looks_like_motion(text: &str) -> bool {
    serde_json::from_str::<Value>(text)
        .is_ok_and(|value| value.get("frames").is_some() && value.get("format").is_none())
}
