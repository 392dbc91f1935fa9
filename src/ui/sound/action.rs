//! What the sound lane and its dialogs ask of the editor (its own file: the
//! shell's action type names it, and the sound desk names the shell's).

use std::path::PathBuf;

/// What a sound action asks.
#[derive(Clone, Debug, PartialEq)]
pub enum SoundAction {
    /// Add this file as the project's sound track (replacing any).
    Add(PathBuf),
    /// The project's sound is now this file (keeping the offset and sensitivity).
    Locate(PathBuf),
    /// Keep the changed file, as it is now.
    AcceptChanged,
    /// No sound track.
    Remove,
    /// Where the sound starts on the motion's time, ms.
    SetOffset(i64),
    /// Onset sensitivity, percent.
    SetSensitivity(u8),
    /// Open the follow-the-sound dialog.
    OpenFollow,
    /// Play the sound from the motion's `from_ms` (the preview started, or went on from elsewhere).
    Play {
        /// The motion's time, ms.
        from_ms: f64,
    },
    /// Stop the sound.
    Silence,
    /// A short grain at the motion's `at_ms` (scrubbing).
    Grain {
        /// The motion's time, ms.
        at_ms: f64,
    },
}
