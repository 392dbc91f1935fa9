//! Motions from the tools people used before, and back: Pololu Maestro
//! settings files, ROBOTIS RoboPlus Motion `.mtn` and R+ Motion `.mtnx`, and
//! the Blender servo-animation add-on's JSON. Each is read into a [`Source`]
//! (the tool's own units and timing), a [`JointMap`] says which channel drives
//! which servo or PLEN2 joint and how its units become degrees, and [`build`]
//! makes servo-board actions and macros or PLEN2 motions and play lists from
//! them, saying what was approximated and what was dropped ([`Report`]).
//! [`export`] writes a servo project as a Maestro settings file and any
//! motion as add-on JSON. Uses `project` and `authoring` (the fitter) only;
//! the rules are in docs/import-export.md.

mod blender;
pub mod bounds;
pub mod build;
pub mod dynamixel;
pub mod export;
mod format;
mod maestro;
pub mod map;
pub mod merge;
pub mod preview;
mod read;
mod report;
mod robotis;
mod source;
pub mod text;
mod xml;

pub use format::{Format, ReadError};
pub use map::{JointMap, MapEntry, Target};
pub use read::{read, read_decoded};
pub use report::{COUNTED, Report, count};
pub use source::{Body, Channel, Clip, Key, Link, Source, Timing, Unit};
