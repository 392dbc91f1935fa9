//! The echo board on the command line, registered here like the real
//! families' entries in `cli/<family>.rs`: `servo-studio sim --protocol echo`
//! serves its emulator (with `--log`, every move and stop a line), and the
//! board commands say it stores nothing to read or write. `play` and `serve`
//! take it through its show stage (`stage.rs`).

use super::board::{BoardEvent, EchoBoard};
use crate::cli::family::Registered;
use crate::cli::sim::{Emulator, SimArgs};
use crate::project::Family;

inventory::submit! {
    Emulator { family: Family::Echo, takes: &[], note: "", serve: emulate }
}
inventory::submit! {
    Registered {
        family: Family::Echo,
        timeout_ms: 1000,
        paced: false,
        board: Err("echo boards: they store nothing (pose one with servo-studio serve)"),
    }
}

fn emulate(args: &SimArgs) -> anyhow::Result<()> {
    crate::cli::sim::serve(args, EchoBoard::default())
}

impl crate::sim::Received for BoardEvent {
    fn received(&self) -> Option<String> {
        Some(match self {
            Self::Moved(deg) => format!("M {deg}"),
            Self::Stopped => "S".to_string(),
        })
    }
}
