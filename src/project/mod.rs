//! The project document: the serde model, the versioned file format,
//! derived timing, and validation. Stands alone: no protocol I/O, no UI.

mod edit;
mod file;
mod history;
mod model;
mod timing;
mod trajectory;
mod validate;

pub use edit::{Edit, next_free_id};
pub use file::{CURRENT_VERSION, FORMAT_TAG, LoadError, SaveError, atomic_write, from_json, load, save, to_json};
pub use history::{History, MAX_UNDO_STEPS};
pub use model::{Action, BoardKind, Button, Command, JoystickTable, Macro, Project, Run, Servo, Step};
pub use timing::{Timing, TimingError, action_duration_ms};
pub use trajectory::{Trajectories, action_trajectories, angle_at, macro_trajectories};
pub use validate::{ButtonSlot, ItemKind, Location, Problem, ProblemKind, Severity, has_errors, validate};
