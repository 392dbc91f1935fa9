//! What an installed Servo Studio carries beside its binary, made from the
//! command line's own definitions: a man page for the command and for each
//! subcommand (`clap_mangen`), and shell completions (`clap_complete`). The
//! Debian package installs the copies kept in `assets/man` and
//! `assets/completions`, which a test keeps equal to what these make.

use std::path::{Path, PathBuf};

use anyhow::Context;
use clap::CommandFactory;

use super::Cli;
use super::out::say;

/// The manual's date: when this version's pages were made (with the version, not each build).
const MANUAL_DATE: &str = "2026-11-29";
/// Where the pages come from, as their footers say.
const SOURCE: &str = concat!("servo-studio ", env!("CARGO_PKG_VERSION"));

/// The command as the pages and completions describe it: the package's
/// version alone (a commit hash would make every build's pages differ).
fn command() -> clap::Command {
    Cli::command().version(env!("CARGO_PKG_VERSION"))
}

/// Prints the completions for `shell` on standard output.
pub fn completions(shell: clap_complete::Shell) -> anyhow::Result<()> {
    let mut script = Vec::new();
    clap_complete::generate(shell, &mut command(), "servo-studio", &mut script);
    super::out::bytes(&script)?;
    Ok(())
}

/// Writes `servo-studio.1` and a `servo-studio-SUB.1` for each subcommand
/// (`servo-studio-rflex-drive.1` for one nested) into `out`, saying each.
pub fn man_pages(out: &Path) -> anyhow::Result<()> {
    std::fs::create_dir_all(out).with_context(|| format!("cannot make {}", out.display()))?;
    for (name, page) in pages() {
        let path: PathBuf = out.join(format!("{name}.1"));
        std::fs::write(&path, page).with_context(|| format!("cannot write {}", path.display()))?;
        say!("wrote {}", path.display());
    }
    Ok(())
}

/// Every page: its name (`servo-studio-board-info`) and its roff.
pub fn pages() -> Vec<(String, Vec<u8>)> {
    let mut pages = Vec::new();
    let mut pending = vec![(command(), "servo-studio".to_string(), "servo-studio".to_string())];
    while let Some((command, name, invoked)) = pending.pop() {
        for sub in command.get_subcommands().filter(|sub| !sub.is_hide_set()) {
            let sub_name = format!("{name}-{}", sub.get_name());
            let sub_invoked = format!("{invoked} {}", sub.get_name());
            pending.push((sub.clone(), sub_name, sub_invoked));
        }
        let page = command.clone().name(name.clone()).bin_name(invoked).version(env!("CARGO_PKG_VERSION"));
        let mut roff = Vec::new();
        if clap_mangen::Man::new(page)
            .title(name.to_uppercase())
            .section("1")
            .date(MANUAL_DATE)
            .source(SOURCE)
            .manual("Servo Studio Manual")
            .render(&mut roff)
            .is_ok()
        {
            pages.push((name, roff));
        }
    }
    pages.sort();
    pages
}
