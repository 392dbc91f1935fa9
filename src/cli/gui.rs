//! `servo-studio gui`: the editor window, from the command line — the file
//! it opens checked first, a missing desktop said plainly, and a signal to
//! the terminal that started it ending it safely (the board stopped, the
//! work kept) with the signal's status.

use std::path::{Path, PathBuf};

use crate::project::{self, Family};

/// Opens the editor, with `file` if given; with `demo` and no file, on the sample robot.
pub fn run(
    file: Option<&Path>,
    demo: bool,
    protocol: Option<Family>,
    (import, show): (Option<PathBuf>, Option<PathBuf>),
) -> anyhow::Result<()> {
    // A show file (double-clicked in a file manager: `gui FILE`) opens as the show it is.
    let (file, show) = match file {
        Some(path) if show.is_none() && crate::show::Show::is_show_file(path) => (None, Some(path.to_path_buf())),
        _ => (file, show),
    };
    let (project, path) = match file {
        // A project file, or the PLEN community's motion.json (one file or a folder):
        // a motion.json or a folder of them is saved as a new project.
        Some(path) => {
            let opened = super::open_input(path)?;
            super::warn_unknown(path, &opened.loaded);
            let saved_to = (opened.kind == project::input::InputKind::ProjectFile).then(|| path.to_path_buf());
            (Some(opened.loaded.project), saved_to)
        }
        None => (None, None),
    };
    if let Some(missing) = no_display() {
        anyhow::bail!("cannot open the window: {missing}. Run it in a desktop session (X11 or Wayland)");
    }
    // Ctrl-C or kill in the terminal that started the editor: the base stops, the work is kept.
    let caught = super::signals::Caught::default();
    let interrupts = super::signals::listen().ok().map(|interrupts| {
        let (forward, forwarded) = crossbeam_channel::unbounded();
        let caught = caught.clone();
        std::thread::spawn(move || {
            for interrupt in interrupts {
                caught.set(interrupt);
                let _ = forward.send(());
            }
        });
        forwarded
    });
    let start = crate::ui::Start { project, path, demo, family: protocol, interrupts, import, show };
    let ended = crate::ui::run(start);
    if let Some(interrupt) = caught.get() {
        // Ended by a signal: the shell stopped the board and kept the work; the status says so.
        return Err(
            anyhow::Error::new(super::Exit(interrupt.exit_code)).context(format!("the editor ended on {interrupt}"))
        );
    }
    ended.map_err(|error| {
        anyhow::anyhow!(
            "cannot open the window: {}. On Linux, a desktop session (X11 or Wayland) and OpenGL drivers are needed",
            without_source_paths(&error.to_string())
        )
    })
}

/// On Linux, why no window can open (no display named at all), if so.
fn no_display() -> Option<&'static str> {
    let set = |name: &str| std::env::var_os(name).is_some_and(|value| !value.is_empty());
    (cfg!(target_os = "linux") && !set("DISPLAY") && !set("WAYLAND_DISPLAY") && !set("WAYLAND_SOCKET"))
        .then_some("no desktop session: neither DISPLAY nor WAYLAND_DISPLAY is set")
}

/// `text` without the source locations a library put in its messages
/// (`os error at /root/.cargo/registry/…/mod.rs:765: `): they mean nothing to a user.
fn without_source_paths(text: &str) -> String {
    let mut out = String::new();
    let mut rest = text;
    while let Some(at) = rest.find(" at /") {
        let after = &rest[at + 4..];
        let Some(end) = after.find(".rs:") else { break };
        let tail = &after[end + 4..];
        let digits = tail.len() - tail.trim_start_matches(|c: char| c.is_ascii_digit()).len();
        out.push_str(&rest[..at]);
        rest = &tail[digits..];
    }
    out.push_str(rest);
    out.trim().trim_end_matches('.').to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_library_message_loses_its_source_paths() {
        let text = "winit EventLoopError: os error at /root/.cargo/registry/src/index.crates.io-1949cf8c6b5b557f/winit-0.30.13/src/platform_impl/linux/mod.rs:765: neither WAYLAND_DISPLAY nor DISPLAY is set.";
        assert_eq!(
            without_source_paths(text),
            "winit EventLoopError: os error: neither WAYLAND_DISPLAY nor DISPLAY is set"
        );
        assert_eq!(without_source_paths("plain words"), "plain words");
    }
}
