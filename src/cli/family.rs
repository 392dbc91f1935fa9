//! What the command line's board commands know of a family, registered by the
//! family itself (`inventory::submit!` in `cli/<family>.rs`): its reply
//! timeout, whether `--pacing` applies, and its `board info`, `export` and
//! `import`. `sim`, `fit` and `trajectory` keep their own entries, in their
//! files. Nothing here lists the families.

use std::path::{Path, PathBuf};

use super::PortArgs;
use super::bounds::Slots;
use crate::project::{Family, Project};

/// A family's part of the command line.
#[derive(Debug)]
pub struct Registered {
    /// The family.
    pub family: Family,
    /// How long its device may take to answer by default, ms (on top of the bytes' time).
    pub timeout_ms: u64,
    /// Whether `--pacing` (PLEN2 uploads) applies to it.
    pub paced: bool,
    /// What it does with a board's contents; `Err`: why it has no such commands, and what to use.
    pub board: Result<BoardCommands, &'static str>,
}

/// `board info`, `export` and `import` for one family.
#[derive(Debug)]
pub struct BoardCommands {
    /// Prints what the board holds and says.
    pub info: fn(&PortArgs) -> anyhow::Result<()>,
    /// Reads the board into a project file (`--slots`, when given, picks PLEN2 motions).
    pub export: fn(&PortArgs, &Path, Option<&Slots>) -> anyhow::Result<()>,
    /// Writes a project onto the board.
    pub import: fn(&PortArgs, &Path, &Project, ImportChoices) -> anyhow::Result<()>,
}

/// How `import` runs.
#[derive(Debug)]
pub struct ImportChoices {
    /// Do not ask.
    pub yes: bool,
    /// Write even when validation finds errors.
    pub force: bool,
    /// Where the backup goes; `None` = no backup.
    pub backup_dir: Option<PathBuf>,
}

inventory::collect!(Registered);

/// The command line's entry of `family`, if it registered one.
pub fn registered(family: Family) -> Option<&'static Registered> {
    inventory::iter::<Registered>.into_iter().find(|entry| entry.family == family)
}

/// `family`'s board commands, or why it has none (`what`: the command refused).
pub fn board(family: Family, what: &str) -> anyhow::Result<&'static BoardCommands> {
    match registered(family).map(|entry| &entry.board) {
        Some(Ok(commands)) => Ok(commands),
        Some(Err(why)) => anyhow::bail!("{what} does not apply to {why}"),
        None => anyhow::bail!("{what} does not apply to the {} (it has no command-line tools)", family.name()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_family_with_a_board_registers_its_commands_and_the_others_say_what_to_use() {
        assert!(board(Family::Servo, "export").is_ok());
        assert!(board(Family::Plen2, "export").is_ok());
        let refused = board(Family::Rflex, "export").map(|_| ()).unwrap_err().to_string();
        assert!(refused.starts_with("export does not apply to rFLEX bases"), "{refused}");
        assert!(refused.contains("servo-studio rflex status"), "{refused}");
        // A family that registered nothing with the command line.
        let refused = board(Family::named("none", "None board"), "import").map(|_| ()).unwrap_err().to_string();
        assert!(refused.ends_with("(it has no command-line tools)"), "{refused}");
        assert_eq!(registered(Family::Plen2).map(|entry| (entry.timeout_ms, entry.paced)), Some((600, true)));
        assert_eq!(registered(Family::Servo).map(|entry| (entry.timeout_ms, entry.paced)), Some((1000, false)));
    }
}
