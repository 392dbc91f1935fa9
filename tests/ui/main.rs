//! The editor's window, driven through egui_kittest: one test binary (each binary links the whole crate, egui
//! included, so the suites share one).

#[path = "../common/mod.rs"]
mod common;

mod actions;
mod board;
mod connect;
mod doctor;
mod drive;
mod files;
mod frames;
mod gamepad;
mod log;
mod macros_joystick;
mod plen2;
mod pose3d;
mod preview;
mod rows;
mod servos;
