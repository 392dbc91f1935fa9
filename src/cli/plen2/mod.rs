//! The PLEN2's `board info`, `export`, `import` and `sim --protocol plen2`.

mod follow;

use std::path::Path;
use std::time::Instant;

use anyhow::{Context, bail};

use super::PortArgs;
use super::bounds::Slots;
use super::family::ImportChoices;
use super::out::say;
use super::sim::SimArgs;
use crate::device;
use crate::device::plen2::{
    self as plen2, Plen2Handle, Plen2ImportOptions, Plen2Options, Plen2Phase, Plen2Progress, SlotResult,
};
use crate::link::{self, LineSettings, PortName, no_waker};
use crate::project::{self, Family, Project};
use crate::sim::{LinkKind, Plen2Sim, Plen2Timing};

fn connect(port: &PortArgs) -> anyhow::Result<Plen2Handle> {
    let name = PortName::parse(&port.port)?;
    let settings = LineSettings { baud: port.baud(Family::Plen2), ..device::line_settings(Family::Plen2) };
    let connection = link::open(&name, &settings)?;
    let options = Plen2Options {
        mode: port.pacing(),
        reply_timeout: std::time::Duration::from_millis(port.timeout_ms(Family::Plen2)),
        line_baud: settings.baud,
        ..Plen2Options::default()
    };
    Plen2Handle::over(connection, options, no_waker()).with_context(|| format!("cannot start talking to {name}"))
}

/// A progress line per step on stderr, with what the pacing decided since the
/// last one (the handle's notices are taken in as the steps go).
fn progress_line(handle: &mut Plen2Handle, mode: plen2::PacingMode) -> impl FnMut(&Plen2Progress) + '_ {
    let began = Instant::now();
    move |progress: &Plen2Progress| {
        for notice in handle.pump(Instant::now()) {
            if let plen2::Plen2Notice::Widened(widened) = notice {
                say!("   {widened}");
            }
        }
        let phase = match progress.phase {
            Plen2Phase::Read => "reading",
            Plen2Phase::Write => "writing",
            Plen2Phase::Verify => "verifying",
        };
        say!(
            "{phase:>9} {}/{} {} ({:.1} s, {} pacing)",
            progress.done,
            progress.total,
            progress.item,
            began.elapsed().as_secs_f64(),
            mode.word()
        );
    }
}

/// `board info --protocol plen2`.
pub fn info(port: &PortArgs) -> anyhow::Result<()> {
    let handle = connect(port)?;
    let info = plen2::info(&handle.requester())?;
    super::out::line(&format!("firmware: {}", info.version))?;
    for joint in &info.joints {
        super::out::line(&format!(
            "  {:<22} min {:>5}  max {:>5}  home {:>5}  (tenths of a degree)",
            joint.joint.name(),
            joint.min_tenths_deg,
            joint.max_tenths_deg,
            joint.home_tenths_deg
        ))?;
    }
    Ok(())
}

/// `export --protocol plen2 [--slots …]` (default: all 90 slots).
pub fn export(port: &PortArgs, out: &Path, slots: Option<&Slots>) -> anyhow::Result<()> {
    let slots: Vec<u8> = slots.map_or_else(|| (0..90).collect(), |slots| slots.0.clone());
    let mut handle = connect(port)?;
    let (cancel, caught) = super::signals::cancel_on_signal("the export")?;
    let requester = handle.requester();
    let mut progress = progress_line(&mut handle, port.pacing());
    let exported = plen2::export(&requester, &slots, &mut progress, &cancel);
    let interrupt = caught.get().filter(|_| matches!(exported, Err(plen2::Plen2OpError::Cancelled)));
    let exported = super::exported(exported, interrupt, &port.port, out)?;
    let count = exported.motions.len();
    project::save(out, &Project { family: Family::Plen2, plen2: exported, ..Project::default() })?;
    say!("exported {count} motion(s) and the joint settings to {}", out.display());
    Ok(())
}

/// `import --protocol plen2`.
pub fn import(port: &PortArgs, input: &Path, loaded: &Project, choices: ImportChoices) -> anyhow::Result<()> {
    let ImportChoices { yes, force, backup_dir } = choices;
    // What the robot cannot store is refused before a port is opened, --force or not.
    plen2::storable(&loaded.plen2)
        .with_context(|| format!("{} cannot be written to a PLEN2; nothing was written", input.display()))?;
    let mut handle = connect(port)?;
    if !yes {
        super::servo::confirm(&port.port, input, backup_dir.is_some())?;
    }
    // From here a signal stops the upload between two motions, never mid-command.
    let (cancel, caught) = super::signals::cancel_on_signal("the upload")?;
    let options = Plen2ImportOptions { backup_dir, verify: true, force };
    let requester = handle.requester();
    let mut progress = progress_line(&mut handle, port.pacing());
    let report = plen2::import(&requester, &loaded.plen2, &options, &mut progress, &cancel).map_err(|failure| {
        let advice = super::restore_hint(" --protocol plen2", &port.port, failure.backup.as_deref(), &failure.left);
        let interrupt = caught.get().filter(|_| matches!(failure.error, plen2::Plen2OpError::Cancelled));
        super::import_failed(*failure, advice, interrupt, input, &port.port)
    })?;
    if let Some(backup) = &report.backup {
        say!("backup of the slots overwritten: {}", backup.display());
    }
    for (slot, result) in &report.slots {
        let word = match result {
            SlotResult::Verified => "written and verified",
            SlotResult::Written => "written",
            SlotResult::Differs => "DIFFERS after writing",
        };
        say!("slot {slot:>2}: {word}");
    }
    if report.rewritten > 0 {
        say!("{} slot(s) read back different at first and were written again", report.rewritten);
    }
    if report.joint_writes > 0 {
        say!("{} joint setting(s) written", report.joint_writes);
    }
    if !report.all_good() {
        bail!("some slots read back different from what was written; check the cable and run the import again");
    }
    Ok(())
}

/// Runs the emulated PLEN2; `--state` preloads its joint settings and slots
/// from a project file, a motion.json or a folder of them.
fn emulate(args: &SimArgs) -> anyhow::Result<()> {
    let link = args.link.unwrap_or(LinkKind::Clean);
    let mut robot = Plen2Sim::new(Plen2Timing::default()).with_link(link);
    if link != LinkKind::Clean {
        say!("the line to the robot: {link}");
    }
    if let Some(path) = &args.state {
        let plen2 = super::open_input(path)?.loaded.project.plen2;
        // A stand-in robot holds only what a robot can (check, import and trajectory refuse the same).
        plen2::storable(&plen2)
            .map_err(|error| {
                anyhow::anyhow!(
                    "cannot preload the robot from {}: {error}. Fix the motion (`servo-studio check` lists every problem) and start it again",
                    path.display()
                )
            })?;
        robot.preload(&plen2::store_commands(&plen2));
        say!(
            "preloaded {} motion(s) and {} joint setting(s) from {}",
            plen2.motions.len(),
            plen2.joints.len(),
            path.display()
        );
    }
    super::sim::serve(args, robot)
}

inventory::submit! {
    super::family::Registered {
        family: Family::Plen2,
        timeout_ms: 600,
        paced: true,
        board: Ok(super::family::BoardCommands { info, export, import }),
    }
}

inventory::submit! {
    super::sim::Emulator {
        family: Family::Plen2,
        takes: &["--state", "--link"],
        note: " (a slow line is --link slow=BAUD)",
        serve: emulate,
    }
}

inventory::submit! {
    super::fit::Fitter { family: Family::Plen2, fit: super::fit::plen2, moves: "frames" }
}

inventory::submit! {
    super::trajectory::Tracer { family: Family::Plen2, trace: super::trajectory::plen2 }
}
