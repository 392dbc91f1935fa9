//! The project's sound track: a file beside the project (its path kept
//! relative to the project's file, `/` between folders), with its length
//! and a hash of its content to tell when it changed, and where it starts
//! on the motion's time.

use serde::{Deserialize, Serialize};

/// The sound a show is timed to.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct SoundTrack {
    /// The file, relative to the project's folder (absolute when outside it).
    pub path: String,
    /// How long it plays, ms (as read when it was added).
    pub duration_ms: u64,
    /// SHA-256 of the file's bytes, hex: a file changed since is noticed.
    pub sha256: String,
    /// Where the sound starts on the motion's time, ms (negative: before the motion).
    #[serde(default)]
    pub offset_ms: i64,
    /// How readily a rise counts as an onset, percent (0: only the strongest, 100: every rise).
    #[serde(default = "default_sensitivity")]
    pub sensitivity_percent: u8,
}

fn default_sensitivity() -> u8 {
    50
}

impl SoundTrack {
    /// The onset sensitivity as the detector takes it (0–1).
    pub fn sensitivity(&self) -> f32 {
        f32::from(self.sensitivity_percent.min(100)) / 100.0
    }
}
