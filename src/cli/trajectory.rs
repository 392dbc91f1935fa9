//! `servo-studio trajectory`: what the robot outputs over time, as a CSV for
//! scripts and spreadsheets — one row per board update, `t_ms` then one
//! column per joint or servo, by name. PLEN2: one row per 32.768 ms cycle
//! from cycle 0 of `$PM`, the frame value in tenths of a degree relative to
//! home before clamping (plen2.md §6). Servo board: one row per 10 ms, the
//! angle in degrees, as the action plot draws it.

use std::io::Write;
use std::path::Path;

use anyhow::Context;

use crate::device::plen2::playback::{self, Playback, StoredMotions};
use crate::project::{self, Family, Project};
use crate::protocol::plen2::{DEVICE_IDS, Joint};

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

/// The most values a trajectory file holds (rows × columns, about 350 MB of
/// CSV): more is refused before anything is written, with what would fit.
pub const MAX_VALUES: usize = 50_000_000;

/// Writes rows as they are made; counts them.
pub struct Rows<'a> {
    writer: std::io::BufWriter<&'a mut std::fs::File>,
    count: usize,
}

impl Rows<'_> {
    /// Writes one row.
    pub fn push(&mut self, row: &str) -> std::io::Result<()> {
        self.writer.write_all(row.as_bytes())?;
        self.writer.write_all(b"\n")?;
        self.count += 1;
        Ok(())
    }
}

/// Refuses output larger than [`MAX_VALUES`].
fn within_cap(rows: usize, columns: usize, step_ms: f64) -> anyhow::Result<()> {
    let values = rows.saturating_mul(columns.max(1));
    if values > MAX_VALUES {
        // Small counts: exact in f64.
        #[allow(clippy::cast_precision_loss)]
        let fits_s = (MAX_VALUES / columns.max(1)) as f64 * step_ms / 1000.0;
        anyhow::bail!(
            "the trajectory would be {rows} rows × {columns} columns, more than the {MAX_VALUES} values a trajectory file may hold; ask for at most --seconds {:.1}. Nothing was written",
            fits_s.floor().max(0.1)
        );
    }
    Ok(())
}

/// A PLEN2 motion's playback, checked it can be played: the header, then one row per cycle.
fn plen2_rows(project: &Project, slot: u8, from_slot: Option<u8>, max_cycles: usize) -> anyhow::Result<Vec<String>> {
    let plen2 = &project.plen2;
    let known = |slot: u8| plen2.motions.iter().any(|motion| motion.slot == slot);
    if !known(slot) {
        anyhow::bail!("there is no motion in slot {slot} (slots: {})", slots(project));
    }
    if let Some(previous) = from_slot
        && !known(previous)
    {
        anyhow::bail!("--from-slot {previous}: there is no motion in that slot (slots: {})", slots(project));
    }
    // A motion the robot cannot store (over 20 frames, say) cannot be played either.
    crate::device::plen2::storable(plen2).map_err(|error| anyhow::anyhow!("{error}; it cannot be played"))?;
    within_cap(max_cycles, Joint::ALL.len() + 1, Playback::CYCLE_MS)?;
    let stored = StoredMotions::new(plen2);
    let from = from_slot.map_or([0; DEVICE_IDS], |previous| playback::after(&stored, previous, max_cycles));
    let Playback { cycles, ended, .. } = playback::play(&stored, slot, from, max_cycles);
    if !ended && !cycles.is_empty() {
        // A loop of count 0 or 255, or a jump to a slot ≥ 90 (plen2.md §6).
        super::out::say!(
            "note: motion {slot} never ends on the robot (it loops forever, or jumps to a slot it cannot play and replays itself): the CSV stops after {} cycles (--seconds)",
            cycles.len()
        );
    }
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

/// What a servo action or macro does, traced up to `max_ms`: the trajectories and how long they run.
fn servo_trace(project: &Project, subject: Subject, max_ms: f64) -> anyhow::Result<(project::Trajectories, f64)> {
    let servo = &project.servo;
    let run = match subject {
        Subject::Action(id) if servo.action(id).is_none() => anyhow::bail!("there is no action {id}"),
        Subject::Macro(id) if servo.macro_by_id(id).is_none() => anyhow::bail!("there is no macro {id}"),
        Subject::Action(action_id) => project::Run::Action { action_id },
        Subject::Macro(macro_id) => project::Run::Macro { macro_id },
        Subject::Slot { .. } => anyhow::bail!("--slot is for PLEN2 motions: give --action or --macro"),
    };
    // As the board plays it: curves baked into straight steps.
    let (stored, run) = crate::authoring::bake_servo::stored_run(servo, run);
    let (trajectories, end_ms) = project::trace(&stored, run, max_ms).map_err(|error| match subject {
        Subject::Macro(id) => anyhow::anyhow!("macro {id}: {error}; nothing was written"),
        _ => anyhow::anyhow!("{error}; nothing was written"),
    })?;
    let end_ms = end_ms.min(max_ms);
    within_cap(project::sample_count(end_ms).saturating_add(1), servo.servos.len() + 1, project::SAMPLE_MS)?;
    Ok((trajectories, end_ms))
}

/// Writes a servo trajectory row by row as it is sampled.
fn write_servo(
    rows: &mut Rows<'_>,
    project: &Project,
    trajectories: &project::Trajectories,
    end_ms: f64,
) -> std::io::Result<()> {
    let servo = &project.servo;
    let names = servo.servos.iter().map(|s| {
        field(&if s.caption.is_empty() { format!("servo {}", s.id) } else { format!("{} {}", s.id, s.caption) })
    });
    rows.push(&std::iter::once("t_ms".to_string()).chain(names).collect::<Vec<_>>().join(","))?;
    let mut samples = project::Samples::new(servo, trajectories);
    let mut row = String::new();
    for index in 0..project::sample_count(end_ms) {
        // Exact for any sample count written.
        #[allow(clippy::cast_precision_loss)]
        let t_ms = index as f64 * project::SAMPLE_MS;
        row.clear();
        row.push_str(&format!("{t_ms:.0}"));
        for angle in samples.at(t_ms) {
            row.push(',');
            row.push_str(&format!("{angle:.2}"));
        }
        rows.push(&row)?;
    }
    Ok(())
}

/// Writes a trajectory's rows.
pub type WriteRows<'a> = Box<dyn FnOnce(&mut Rows<'_>) -> std::io::Result<()> + 'a>;

/// A family's trajectory, traced and checked before anything is written: its
/// rows, written when the output is opened, and the time between two of them.
pub struct Traced<'a> {
    /// Time between two rows, ms (one board update).
    pub step_ms: f64,
    /// Writes the header and the rows.
    pub write: WriteRows<'a>,
}

/// How a family traces what a project plays, registered by the family
/// (`inventory::submit!` in `cli/<family>.rs`).
#[derive(Debug)]
pub struct Tracer {
    /// The family.
    pub family: Family,
    /// Traces `subject` up to a time, ms, checked before anything is written.
    pub trace: for<'a> fn(&'a Project, &Path, Subject, f64) -> anyhow::Result<Traced<'a>>,
}

inventory::collect!(Tracer);

/// A PLEN2 motion's playback (`--slot`), up to `max_ms`.
pub fn plen2(project: &Project, input: &Path, subject: Subject, max_ms: f64) -> anyhow::Result<Traced<'static>> {
    let Subject::Slot { slot, from_slot } = subject else {
        anyhow::bail!("{} holds PLEN2 motions: give --slot N", input.display())
    };
    // Cycle counts from bounded seconds: small and non-negative.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let max_cycles = (max_ms / Playback::CYCLE_MS).floor() as usize + 1;
    let lines = plen2_rows(project, slot, from_slot, max_cycles)?;
    let write = move |rows: &mut Rows<'_>| lines.iter().try_for_each(|line| rows.push(line));
    Ok(Traced { step_ms: Playback::CYCLE_MS, write: Box::new(write) })
}

/// A servo board action's or macro's playback, up to `max_ms`.
pub fn servo<'a>(project: &'a Project, input: &Path, subject: Subject, max_ms: f64) -> anyhow::Result<Traced<'a>> {
    if let Subject::Slot { .. } = subject {
        anyhow::bail!("{} is a servo board project: give --action N or --macro N", input.display())
    }
    let (trajectories, end_ms) = servo_trace(project, subject, max_ms)?;
    let write = move |rows: &mut Rows<'_>| write_servo(rows, project, &trajectories, end_ms);
    Ok(Traced { step_ms: project::SAMPLE_MS, write: Box::new(write) })
}

/// Writes the trajectory of `subject` in `input` to `out`; `seconds` caps a
/// motion that never ends. Returns the rows written and the time they cover.
/// Everything is checked before the file is touched.
pub fn run(input: &Path, subject: Subject, seconds: f64, out: &Path, force: bool) -> anyhow::Result<(usize, f64)> {
    super::output_not_an_input(out, &[input])?;
    let loaded = super::open_input(input)?.loaded;
    super::warn_unknown(input, &loaded);
    let project = loaded.project;
    super::writable_output(out, force)?;
    let max_ms = super::bounds::duration(seconds).as_secs_f64() * 1000.0;
    let family = project.family;
    let Some(tracer) = inventory::iter::<Tracer>.into_iter().find(|tracer| tracer.family == family) else {
        anyhow::bail!("{} is a project for the {}: it has no stored motions to play", input.display(), family.name())
    };
    let Traced { step_ms, write } = (tracer.trace)(&project, input, subject, max_ms)?;
    let mut count = 0;
    project::atomic_write(out, |file| {
        let mut rows = Rows { writer: std::io::BufWriter::new(file), count: 0 };
        write(&mut rows)?;
        rows.writer.flush()?;
        count = rows.count.saturating_sub(1);
        Ok(())
    })
    .with_context(|| format!("cannot write {}", out.display()))?;
    // Row counts are far below 2^52.
    #[allow(clippy::cast_precision_loss)]
    let covered = count.saturating_sub(1) as f64 * step_ms / 1000.0;
    Ok((count, covered))
}
