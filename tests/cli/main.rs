//! The command line, run as a user runs it: one test binary (each binary links the whole crate, egui
//! included, so the suites share one).

#[path = "../common/mod.rs"]
mod common;

mod commands;
mod hostile;
mod robust;
mod servo;
mod trajectory;
