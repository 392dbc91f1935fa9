//! Servo Studio: pose robot servos live, author actions and macros, bind them to
//! remote-control buttons, and back up and upload servo controller boards.
//!
//! Layers, top to bottom (see `docs/ARCHITECTURE.md`): `cli` → `device` →
//! `link` / [`protocol`]; [`project`] stands alone; [`figure`] (the robot as
//! a posed 3D figure) uses the project and the PLEN2's device map.

pub mod audio;
pub mod authoring;
pub mod cli;
pub mod device;
pub mod figure;
pub mod gamepad;
pub mod interchange;
pub mod link;
pub mod project;
pub mod protocol;
pub mod remote;
pub mod show;
pub mod sim;
pub mod ui;
