//! Emulated boards, with fault injection. Today: the servo board.

mod board;
mod faults;
mod runner;

pub use board::{BoardSim, SimCommand, SimConfig, SimEvent};
pub use faults::{Faults, FaultsError};
pub use runner::{SimHandle, spawn_in_memory, spawn_pty, spawn_tcp};
