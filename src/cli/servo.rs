//! The commands that talk to a servo board.

use std::io::{BufRead, IsTerminal};
use std::path::Path;
use std::time::Duration;

use anyhow::{Context, bail};
use indicatif::{ProgressBar, ProgressStyle};

use super::PortArgs;
use super::bounds::Slots;
use super::family::ImportChoices;
use super::out::say;
use super::sim::SimArgs;
use crate::device::servo::ServoImage;
use crate::device::servo::{self as device, ImportOptions, Phase, Progress, Requester, ServoBoard, SessionConfig};
use crate::interchange::count;
use crate::link::{self, PortName, no_waker};
use crate::project::{self, Family, Project};
use crate::sim::{ServoSim, SimConfig};

fn session_config(port: &PortArgs) -> SessionConfig {
    SessionConfig {
        response_timeout: Duration::from_millis(port.timeout_ms(Family::Servo)),
        ..SessionConfig::default()
    }
}

fn connect(port: &PortArgs) -> anyhow::Result<ServoBoard> {
    let name = PortName::parse(&port.port)?;
    Ok(ServoBoard::connect(&name, port.baud(Family::Servo), session_config(port), no_waker())?)
}

/// A progress bar on stderr (hidden when stderr is not a terminal).
fn progress_bar() -> (ProgressBar, impl FnMut(&Progress)) {
    let bar = ProgressBar::new(0);
    bar.set_style(
        ProgressStyle::with_template("{prefix:>8} [{bar:30}] {pos}/{len} {wide_msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> "),
    );
    let shown = bar.clone();
    let update = move |progress: &Progress| {
        shown.set_prefix(match progress.phase {
            Phase::Read => "reading",
            Phase::Write => "writing",
            Phase::Verify => "verifying",
        });
        shown.set_length(u64::try_from(progress.total).unwrap_or(u64::MAX));
        shown.set_position(u64::try_from(progress.done).unwrap_or(u64::MAX));
        shown.set_message(progress.item.to_string());
    };
    (bar, update)
}

pub fn ports() -> anyhow::Result<()> {
    let ports = link::list_ports()?;
    if ports.is_empty() {
        super::out::line("no serial ports found (a board on a network bridge is reached as tcp://HOST:PORT)")?;
    }
    for port in ports {
        super::out::line(&format!("{}\t{}", port.name, port.description))?;
    }
    Ok(())
}

/// `export` (a servo board has no slots: `--slots` is refused before it is read).
pub fn export(port: &PortArgs, out: &Path, slots: Option<&Slots>) -> anyhow::Result<()> {
    if slots.is_some() {
        bail!("--slots is for PLEN2 motions; a servo board has no slots. Nothing was read");
    }
    let board = connect(port)?;
    let (cancel, caught) = super::signals::cancel_on_signal("the export")?;
    let (bar, mut update) = progress_bar();
    let exported = device::export(&board.requester(), &mut update, &cancel);
    bar.finish_and_clear();
    let interrupt = caught.get().filter(|_| matches!(exported, Err(device::OpError::Cancelled)));
    let exported = super::exported(exported, interrupt, &port.port, out)?;
    project::save(out, &Project::servo(exported.clone()))?;
    say!(
        "exported project {} ({}, {}, {}, {}) to {}",
        exported.project_id,
        count(exported.servos.len(), "servo", "servos"),
        count(exported.actions.len(), "action", "actions"),
        count(exported.macros.len(), "macro", "macros"),
        count(exported.joystick_tables.len(), "joystick table", "joystick tables"),
        out.display()
    );
    Ok(())
}

pub fn confirm(port: &str, input: &Path, backup: bool) -> anyhow::Result<()> {
    let stdin = std::io::stdin();
    if !stdin.is_terminal() {
        bail!(
            "refusing to overwrite the board on {port} without confirmation (standard input is not a terminal); pass --yes"
        );
    }
    super::out::say_partial(format_args!(
        "This erases everything on the board on {port} and writes {}.{} Type yes to continue: ",
        input.display(),
        if backup { " A backup of the board is saved first." } else { " No backup is saved (--no-backup)." }
    ));
    let mut answer = String::new();
    stdin.lock().read_line(&mut answer)?;
    if answer.trim() != "yes" {
        bail!("not confirmed; the board is unchanged");
    }
    Ok(())
}

pub fn import(port: &PortArgs, input: &Path, loaded: &Project, choices: ImportChoices) -> anyhow::Result<()> {
    let ImportChoices { yes, force, backup_dir } = choices;
    // Refuse before connecting and before asking: nothing is written either way.
    let problems = project::validate_servo(&loaded.servo).errors_only();
    if problems.has_errors() && !force {
        return Err(device::OpError::Invalid { problems })
            .with_context(|| format!("{} was not imported into {}", input.display(), port.port));
    }
    let board = connect(port)?;
    if !yes {
        confirm(&port.port, input, backup_dir.is_some())?;
    }
    // From here a signal stops the upload at the next request, never mid-packet.
    let (cancel, caught) = super::signals::cancel_on_signal("the upload")?;
    let options = ImportOptions { backup_dir, verify: true, force };
    let (bar, mut update) = progress_bar();
    let requester: Requester = board.requester();
    let report = device::import(&requester, &loaded.servo, &options, &mut update, &cancel);
    bar.finish_and_clear();
    let report = report.map_err(|failure| {
        let advice = super::restore_hint("", &port.port, failure.backup.as_deref(), &failure.left);
        let interrupt = caught.get().filter(|_| matches!(failure.error, device::OpError::Cancelled));
        super::import_failed(*failure, advice, interrupt, input, &port.port)
    })?;
    if let Some(backup) = &report.backup {
        say!("backup of the previous contents: {}", backup.display());
    }
    say!("wrote {} item(s) to {} and verified them", report.written, port.port);
    if let Some(curves) = report.curves {
        let widened = if curves.widened() { ", widened from 1° to fit the board's memory" } else { "" };
        say!(
            "curves stored as straight steps within {:.1}° of them (tolerance {:.1}°{widened})",
            f64::from(curves.max_error_tenths) / 10.0,
            f64::from(curves.tolerance_tenths) / 10.0
        );
    }
    Ok(())
}

pub fn info(port: &PortArgs) -> anyhow::Result<()> {
    let board = connect(port)?;
    let info = device::board_info(&board.requester())?;
    let print = |text: String| super::out::line(&text);
    print(format!("project id: {}", info.project_id))?;
    match info.total_bytes {
        Some(total) => print(format!("memory: {} of {total} bytes free", info.free_bytes))?,
        None => print(format!("memory: {} bytes free", info.free_bytes))?,
    }
    print(format!("battery: {}", device::battery_text(info.battery_permil)))?;
    print(format!("servos: {}", info.servos.len()))?;
    for servo in &info.servos {
        print(format!(
            "  servo {:>3}: angle {:>5}  current {:>5}  temperature {:>5}  type {}  {}  {}",
            servo.servo_id,
            servo.angle,
            servo.current_adc,
            servo.temperature_adc,
            servo.servo_type,
            if servo.is_start { "running" } else { "stopped" },
            if servo.is_hold { "holding" } else { "released" },
        ))?;
    }
    Ok(())
}

/// Runs the emulated servo board; `--state` preloads it from a servo project.
fn emulate(args: &SimArgs) -> anyhow::Result<()> {
    let image = match &args.state {
        Some(path) => {
            let loaded = project::read(path)
                .with_context(|| format!("cannot preload the board from {}", path.display()))?
                .project;
            if loaded.family != Family::Servo {
                bail!(
                    "{} is a {} project; the emulated servo board takes a servo project",
                    path.display(),
                    loaded.family
                );
            }
            ServoImage::from_project(&loaded.servo)
                .with_context(|| format!("{} cannot be stored on a board", path.display()))?
        }
        None => ServoImage::default(),
    };
    let defaults = SimConfig::default();
    let config = SimConfig {
        total_memory_bytes: args.memory.unwrap_or(defaults.total_memory_bytes),
        baud: args.baud,
        turnaround: Duration::from_millis(args.turnaround_ms.unwrap_or(0)),
        faults: args.faults.clone().unwrap_or_default(),
        ..defaults
    };
    super::sim::serve(args, ServoSim::new(config, image))
}

inventory::submit! {
    super::family::Registered {
        family: Family::Servo,
        timeout_ms: 1000,
        paced: false,
        board: Ok(super::family::BoardCommands { info, export, import }),
    }
}

inventory::submit! {
    super::sim::Emulator {
        family: Family::Servo,
        takes: &["--state", "--baud", "--turnaround-ms", "--memory", "--faults"],
        note: "",
        serve: emulate,
    }
}

inventory::submit! {
    super::fit::Fitter {
        family: Family::Servo,
        fit: super::fit::servo,
        moves: "steps (one action each, run in order by macro 1)",
    }
}

inventory::submit! {
    super::follow_audio::SoundFollower {
        family: Family::Servo,
        column: |args| match (args.servo, &args.joint) {
            (Some(id), None) => Ok(format!("servo {id}")),
            _ => anyhow::bail!("--joint names a PLEN2 joint: a servo board follows with --servo N"),
        },
        from_slot: Err("--from-slot is for a PLEN2's motion slots: a servo board's follow is one macro"),
        follow: super::follow_audio::fitted,
    }
}

inventory::submit! {
    super::trajectory::Tracer { family: Family::Servo, trace: super::trajectory::servo }
}
