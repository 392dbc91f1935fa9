//! `servo-studio fit`: a recording made elsewhere (the CSV `trajectory`
//! writes) fitted into the fewest frames / steps whose playback on the board
//! stays within a tolerance, written as a motion.json (PLEN2) or a project
//! whose macro runs one action per fitted step (servo board).

use std::path::{Path, PathBuf};

use anyhow::Context;

use crate::authoring::fit::{self, Board, Budget, Fit, FitError, Plen2Board, ServoBoard};
use crate::authoring::fitted::{self, PLEN2_UPDATE_MS, SERVO_UPDATE_MS};
use crate::authoring::recording::Recording;
use crate::project::plen2::{JOINTS, Joint, MAX_FRAMES, Motion};
use crate::project::{self, Family, Project, Servo, ServoProject};

/// What `fit` is asked.
#[derive(Clone, Debug)]
pub struct FitRequest {
    /// The CSV recording.
    pub recording: PathBuf,
    /// Which board plays it.
    pub family: Family,
    /// How far playback may stray from the recording, degrees.
    pub tolerance_deg: f64,
    /// At most this many frames / steps (PLEN2: at most 20, the default).
    pub max_frames: Option<usize>,
    /// The motion's or macro's name (default: the recording's file name).
    pub name: Option<String>,
    /// The file to write.
    pub out: PathBuf,
    /// Replace a read-only output.
    pub force: bool,
}

/// What was fitted, for the summary line.
#[derive(Clone, Debug, PartialEq)]
pub struct Fitted {
    /// Frames (PLEN2) or actions (servo board).
    pub moves: usize,
    /// Largest deviation, degrees.
    pub max_error_deg: f64,
    /// How long the recording plays, s.
    pub seconds: f64,
}

/// Fits and writes; everything is checked before the output is touched.
pub fn run(request: &FitRequest) -> anyhow::Result<Fitted> {
    super::output_not_an_input(&request.out, &[&request.recording])?;
    super::writable_output(&request.out, request.force)?;
    let text = project::input::read_text(&request.recording, project::input::MAX_PROJECT_BYTES)?;
    let recording =
        Recording::parse(&text).with_context(|| format!("{} is not a recording", request.recording.display()))?;
    let name = request.name.clone().unwrap_or_else(|| {
        request.recording.file_stem().map(|stem| stem.to_string_lossy().into_owned()).unwrap_or_default()
    });
    write(&recording, request, &name)
}

/// Fits a recording however it was made (a CSV, a sound's loudness) and writes the result to `request.out`.
pub fn write(recording: &Recording, request: &FitRequest, name: &str) -> anyhow::Result<Fitted> {
    let family = request.family;
    let Some(fitter) = fitter(family) else {
        let fitting: Vec<&str> =
            Family::all().iter().filter(|other| fitter(**other).is_some()).map(|other| other.tag()).collect();
        anyhow::bail!(
            "--protocol {family}: the {} stores no motions to fit; give {}",
            family.name(),
            fitting.join(" or ")
        )
    };
    let (written, fitted) = (fitter.fit)(recording, request, name)?;
    project::atomic_write(&request.out, |file| std::io::Write::write_all(file, written.as_bytes()))
        .with_context(|| format!("cannot write {}", request.out.display()))?;
    Ok(fitted)
}

/// How a family fits a recording, registered by the family
/// (`inventory::submit!` in `cli/<family>.rs`).
#[derive(Debug)]
pub struct Fitter {
    /// The family whose board plays the fit.
    pub family: Family,
    /// Fits: the file it writes, and what was fitted.
    pub fit: fn(&Recording, &FitRequest, &str) -> anyhow::Result<(String, Fitted)>,
    /// What its fitted moves are called ("frames").
    pub moves: &'static str,
}

inventory::collect!(Fitter);

fn fitter(family: Family) -> Option<&'static Fitter> {
    inventory::iter::<Fitter>.into_iter().find(|fitter| fitter.family == family)
}

/// A PLEN2 motion.json: the recording's joints in `Joint::ALL` order (a joint it lacks stays at 0, home).
pub fn plen2(recording: &Recording, request: &FitRequest, name: &str) -> anyhow::Result<(String, Fitted)> {
    let mut columns = Vec::new();
    for column in &recording.names {
        let Some(joint) = Joint::ALL.into_iter().find(|joint| joint.name() == column) else {
            let names: Vec<&str> = Joint::ALL.iter().map(|joint| joint.name()).collect();
            anyhow::bail!("column {column:?} is not a PLEN2 joint (they are: {})", names.join(", "));
        };
        columns.push(joint.index());
    }
    let rows: Vec<Vec<f64>> = recording
        .resample(PLEN2_UPDATE_MS)
        .into_iter()
        .map(|row| {
            let mut values = vec![0.0; JOINTS];
            for (&index, value) in columns.iter().zip(row) {
                values[index] = value;
            }
            values
        })
        .collect();
    let allowed = request.max_frames.unwrap_or(MAX_FRAMES);
    if allowed > MAX_FRAMES {
        anyhow::bail!("--max-frames {allowed}: a PLEN2 motion holds at most {MAX_FRAMES} frames");
    }
    // `$PM` from power-up: every joint's frame buffer at 0 (plen2.md §6), as `trajectory` plays.
    let budget = Budget { tolerance: request.tolerance_deg * 10.0, allowed, resolution: 1.0 };
    let fit = fitted_within(&Plen2Board, &[0; JOINTS], &rows, budget, (10.0, "frames"))?;
    if !name.is_ascii() || name.len() > 20 {
        anyhow::bail!("--name {name:?}: a PLEN2 motion's name is at most 20 ASCII characters");
    }
    let motion = Motion {
        slot: 0,
        name: name.to_string(),
        frames: fitted::plen2_frames(&fit),
        loop_range: None,
        jump_slot: None,
    };
    let summary = summary(&fit, 10.0, rows.len(), PLEN2_UPDATE_MS);
    Ok((project::motion_json::motion_to_json(&motion), summary))
}

/// The servo id a column names: `servo N`, `N caption` or `N` (as `trajectory` writes them).
fn servo_column(column: &str) -> Option<(u8, String)> {
    let rest = column.strip_prefix("servo ").unwrap_or(column);
    let (id, caption) = rest.split_once(' ').unwrap_or((rest, ""));
    let id: u8 = id.parse().ok().filter(|id| *id != 255)?;
    let caption = if column.starts_with("servo ") { String::new() } else { caption.to_string() };
    Some((id, caption))
}

/// A servo project: one action per step, macro 1 running them in order.
pub fn servo(recording: &Recording, request: &FitRequest, name: &str) -> anyhow::Result<(String, Fitted)> {
    let mut servos: Vec<Servo> = Vec::new();
    for column in &recording.names {
        let Some((id, caption)) = servo_column(column) else {
            anyhow::bail!("column {column:?} names no servo: write `servo N`, `N caption` or `N` (N 0..=254)");
        };
        if servos.iter().any(|servo| servo.id == id) {
            anyhow::bail!("servo {id} has two columns");
        }
        servos.push(Servo::new(id, fitted::caption_within(&caption, 32)));
    }
    let rows = recording.resample(SERVO_UPDATE_MS);
    let Some((first, rest)) = rows.split_first() else { anyhow::bail!("the recording has no rows") };
    let start: Vec<i32> = first.iter().map(|value| ServoBoard.store(*value)).collect();
    for (servo, &home) in servos.iter_mut().zip(&start) {
        servo.home_deg = servo.clamp(i16::try_from(home).unwrap_or(0));
    }
    let allowed = request.max_frames.unwrap_or(project::MAX_LIST_LEN);
    let budget = Budget { tolerance: request.tolerance_deg, allowed, resolution: 0.1 };
    let fit = fitted_within(&ServoBoard, &start, rest, budget, (1.0, "steps"))?;
    let ids: Vec<u8> = servos.iter().map(|servo| servo.id).collect();
    let actions = fitted::servo_actions(&fit, &ids, 1, name);
    let macros = vec![fitted::macro_running(1, name, &actions)];
    let summary = summary(&fit, 1.0, rest.len(), SERVO_UPDATE_MS);
    let project = Project::servo(ServoProject { servos, actions, macros, ..ServoProject::default() });
    Ok((project::to_json(&project), summary))
}

/// [`fit::fit_within`], its error said as [`fit_error_said`] says it.
fn fitted_within(
    board: &impl Board,
    start: &[i32],
    rows: &[Vec<f64>],
    budget: Budget,
    (per_degree, moves): (f64, &str),
) -> anyhow::Result<Fit> {
    let tolerance = budget.tolerance;
    fit::fit_within(board, start, rows, budget)
        .map_err(|error| anyhow::anyhow!(fit_error_said(&error, (per_degree, moves), tolerance)))
}

/// A fit's error in degrees (to 0.1°) and in the board's own word for a
/// move (`frames` on a PLEN2, `steps` on a servo board); `tolerance` in the
/// board's units (`per_degree` of them a degree).
pub fn fit_error_said(error: &FitError, (per_degree, moves): (f64, &str), tolerance: f64) -> String {
    match error {
        FitError::Tolerance { needed, allowed, smallest, .. } => format!(
            "{needed} {moves} are needed to stay within {}° and at most {allowed} are allowed: the smallest tolerance that fits is --tolerance-deg {}. Nothing was written",
            tenths(tolerance / per_degree),
            tenths(smallest / per_degree)
        ),
        FitError::TooLong { updates, needed, allowed, .. } => format!(
            "the recording lasts {updates} board updates: that takes at least {needed} {moves} at any tolerance, and at most {allowed} are allowed. Nothing was written"
        ),
    }
}

/// Degrees to a tenth, as a person writes them ("6.1", "2").
pub fn tenths(degrees: f64) -> String {
    let rounded = (degrees * 10.0).round() / 10.0;
    format!("{rounded}")
}

fn summary(fit: &Fit, per_degree: f64, updates: usize, update_ms: f64) -> Fitted {
    // Update counts far below 2^52: exact.
    #[allow(clippy::cast_precision_loss)]
    let seconds = updates as f64 * update_ms / 1000.0;
    Fitted { moves: fit.moves.len(), max_error_deg: fit.max_error / per_degree, seconds }
}

/// The line `fit` prints.
pub fn said(fitted: &Fitted, family: Family, out: &Path) -> String {
    let what = fitter(family).map_or("moves", |fitter| fitter.moves);
    format!(
        "{} {what} for {:.3} s, largest error {:.2}°: wrote {}",
        fitted.moves,
        fitted.seconds,
        fitted.max_error_deg,
        out.display()
    )
}
