//! The project document: one section per board family (servo, PLEN2, rFLEX),
//! the versioned file format, derived timing, and validation. Stands alone:
//! it uses protocol field limits, nothing of link, device, sim or ui.

mod bounded;
mod document;
pub mod dynamixel;
mod easing;
mod edit;
mod family;
mod file;
pub mod gamepad;
mod history;
pub mod input;
mod kept_section;
pub mod motion_json;
pub mod plen2;
mod read;
pub mod rflex;
mod section;
mod servo;
mod sound;
mod timing;
mod trajectory;
mod validate;

pub use bounded::MAX_LIST_LEN;
pub use document::{Project, Sections};
pub use easing::{Easing, Handles};
pub use edit::{Edit, next_free_id};
pub use family::{Family, Registered};
pub use file::{
    CURRENT_VERSION, FORMAT_TAG, LoadError, Loaded, MAX_UNKNOWN_KEYS_KEPT, SaveError, atomic_write, atomic_write_all,
    from_json, load, output_path, parse, read, save, to_json,
};
pub use history::{History, LivePose, MAX_UNDO_STEPS, Step as UndoStep};
pub use kept_section::Section;
pub use section::validate;
pub use servo::{
    Action, Button, Command, JoystickTable, LinkMesh, Macro, RigAxis, RigEnd, RigJoint, Run, Servo, ServoIndex,
    ServoProject, Step,
};
pub use sound::SoundTrack;
pub use timing::{Timing, TimingError, action_duration_ms};
pub use trajectory::{
    Follower, MAX_TRACE_WORK, SAMPLE_MS, Samples, TraceError, Trajectories, action_trajectories, angle_at,
    angle_at_sorted, macro_cycle, macro_trajectories, pose_at, sample, sample_count, times_sorted, trace,
};
pub use validate::{
    ButtonSlot, ItemKind, Location, Problem, ProblemKind, Problems, Severity, has_errors, validate_plen2,
    validate_servo,
};
