//! `servo-studio trajectory`: what the robot outputs over time, as a CSV for
//! scripts and spreadsheets — one row per board update, `t_ms` then one
//! column per joint or servo, by name. PLEN2: one row per 32.768 ms cycle
//! from cycle 0 of `$PM`, the frame value in tenths of a degree relative to
//! home before clamping (plen2.md §6). Servo board: one row per 10 ms, the
//! angle in degrees, as the action plot draws it.

use std::io::Write;
use std::path::Path;

use anyhow::Context;

use servo_studio::device::plen2::playback::{self, Playback, StoredMotions};
use servo_studio::project::{self, Family, Project};
use servo_studio::protocol::plen2::{DEVICE_IDS, Joint};

/// What to play.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Subject {
    /// A PLEN2 motion, after the motion in `from_slot` (power-up if none).
    Slot {
        /// The motion.
        slot: u8,
        /// The motion played before it.
        from_slot: Option<u8>,
    },
    /// A servo board action.
    Action(i32),
    /// A servo board macro.
    Macro(i32),
}

/// A CSV field, quoted when it must be (a caption may hold a comma or a quote).
fn field(text: &str) -> String {
    if text.contains([',', '"', '\n', '\r']) { format!("\"{}\"", text.replace('"', "\"\"")) } else { text.to_string() }
}

/// The rows of a PLEN2 motion's playback: header, then one per cycle.
fn plen2_rows(project: &Project, slot: u8, from_slot: Option<u8>, max_cycles: usize) -> anyhow::Result<Vec<String>> {
    let plen2 = &project.plen2;
    let known = |slot: u8| plen2.motions.iter().any(|motion| motion.slot == slot);
    if !known(slot) {
        anyhow::bail!("there is no motion in slot {slot} (slots: {})", slots(project));
    }
    let stored = StoredMotions::new(plen2);
    let from = match from_slot {
        Some(previous) if !known(previous) => {
            anyhow::bail!("--from-slot {previous}: there is no motion in that slot (slots: {})", slots(project))
        }
        Some(previous) => playback::after(&stored, previous, max_cycles),
        None => [0; DEVICE_IDS],
    };
    let Playback { cycles, .. } = playback::play(&stored, slot, from, max_cycles);
    let mut rows = vec![
        std::iter::once("t_ms".to_string())
            .chain(Joint::ALL.map(|j| j.name().to_string()))
            .collect::<Vec<_>>()
            .join(","),
    ];
    for (index, values) in cycles.iter().enumerate() {
        // Exact for any cycle count written.
        #[allow(clippy::cast_precision_loss)]
        let t_ms = index as f64 * Playback::CYCLE_MS;
        let mut row = format!("{t_ms:.3}");
        for joint in Joint::ALL {
            row.push(',');
            row.push_str(&values[usize::from(joint.device_id())].to_string());
        }
        rows.push(row);
    }
    Ok(rows)
}

fn slots(project: &Project) -> String {
    let slots: Vec<String> = project.plen2.motions.iter().map(|motion| motion.slot.to_string()).collect();
    if slots.is_empty() { "none".into() } else { slots.join(", ") }
}

/// The rows of a servo action's or macro's trajectory: header, then one per 10 ms.
fn servo_rows(project: &Project, subject: Subject, max_ms: f64) -> anyhow::Result<Vec<String>> {
    let servo = &project.servo;
    let (trajectories, end_ms) = match subject {
        Subject::Action(id) => {
            if servo.action(id).is_none() {
                anyhow::bail!("there is no action {id}");
            }
            project::action_trajectories(servo, id)
        }
        Subject::Macro(id) => {
            if servo.macro_by_id(id).is_none() {
                anyhow::bail!("there is no macro {id}");
            }
            project::macro_trajectories(servo, id)
        }
        Subject::Slot { .. } => anyhow::bail!("--slot is for PLEN2 motions: give --action or --macro"),
    };
    let names = servo.servos.iter().map(|s| {
        field(&if s.caption.is_empty() { format!("servo {}", s.id) } else { format!("{} {}", s.id, s.caption) })
    });
    let mut rows = vec![std::iter::once("t_ms".to_string()).chain(names).collect::<Vec<_>>().join(",")];
    for (index, angles) in project::sample(servo, &trajectories, end_ms.min(max_ms)).iter().enumerate() {
        // Exact for any sample count written.
        #[allow(clippy::cast_precision_loss)]
        let t_ms = index as f64 * project::SAMPLE_MS;
        let mut row = format!("{t_ms:.0}");
        for angle in angles {
            row.push(',');
            row.push_str(&format!("{angle:.2}"));
        }
        rows.push(row);
    }
    Ok(rows)
}

/// Writes the trajectory of `subject` in `input` to `out`; `seconds` caps a
/// motion that never ends. Returns the rows written and the time they cover.
pub fn run(input: &Path, subject: Subject, seconds: f64, out: &Path) -> anyhow::Result<(usize, f64)> {
    if !(seconds.is_finite() && seconds > 0.0) {
        anyhow::bail!("--seconds must be a positive number of seconds, not {seconds}");
    }
    let loaded = super::plen2::load_input(input)?;
    super::warn_unknown(input, &loaded.unknown_keys);
    let project = loaded.project;
    let rows = match (project.family, subject) {
        (Family::Plen2, Subject::Slot { slot, from_slot }) => {
            // Cycle counts from seconds: small and non-negative.
            #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
            let max_cycles = (seconds * 1000.0 / Playback::CYCLE_MS).floor() as usize + 1;
            plen2_rows(&project, slot, from_slot, max_cycles)?
        }
        (Family::Plen2, _) => anyhow::bail!("{} holds PLEN2 motions: give --slot N", input.display()),
        (Family::Servo, Subject::Slot { .. }) => {
            anyhow::bail!("{} is a servo board project: give --action N or --macro N", input.display())
        }
        (Family::Servo, subject) => servo_rows(&project, subject, seconds * 1000.0)?,
        (Family::Rflex, _) => {
            anyhow::bail!("{} is an rFLEX project: a base has no stored motions to play", input.display())
        }
    };
    let step_ms = if project.family == Family::Plen2 { Playback::CYCLE_MS } else { project::SAMPLE_MS };
    project::atomic_write(out, |file| {
        let mut writer = std::io::BufWriter::new(file);
        for row in &rows {
            writer.write_all(row.as_bytes())?;
            writer.write_all(b"\n")?;
        }
        writer.flush()
    })
    .with_context(|| format!("cannot write {}", out.display()))?;
    let count = rows.len() - 1;
    // Row counts are far below 2^52.
    #[allow(clippy::cast_precision_loss)]
    let covered = count.saturating_sub(1) as f64 * step_ms / 1000.0;
    Ok((count, covered))
}
