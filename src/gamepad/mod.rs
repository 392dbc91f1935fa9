//! Gamepads: the kernel's input events read from an event device or a pipe
//! ([`source`]), the state they build ([`state`]), and what a stick and a
//! dead-man button mean to a mobile base ([`teleop`]).

mod event;
pub mod puppet;
mod source;
mod state;
pub mod teleop;

pub use event::*;
pub use source::{Gamepad, GamepadInfo, Gone, PadUpdate, list, read_batches, read_records};
pub use state::{DEFAULT_RANGE, PadState, Step, dead_zone};
