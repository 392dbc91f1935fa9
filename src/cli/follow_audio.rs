//! `servo-studio follow-audio`: a sound's loudness as one servo's or joint's
//! curve (a talking skull's jaw, a PLEN2 nodding to a beat), fitted into
//! the board's steps or frames by the same fitter `fit` uses.

use std::path::PathBuf;

use clap::Args;

use anyhow::Context as _;

use super::bounds;
use super::fit::{self, FitRequest};
use crate::audio;
use crate::authoring::fitted::PLEN2_UPDATE_MS;
use crate::authoring::follow::{self, Follower};
use crate::authoring::recording::Recording;
use crate::project::plen2::{Joint, MAX_FRAMES, Motion, SLOTS};
use crate::project::{self, Family, Project};

/// The sound is followed at this step, ms (the fitter resamples at the board's own update).
const STEP_MS: usize = 5;

/// `follow-audio`'s arguments.
#[derive(Clone, Debug, Args)]
#[command(group = clap::ArgGroup::new("axis").required(true).args(["servo", "joint"]))]
pub struct FollowArgs {
    /// The sound (WAV, FLAC, MP3, OGG/Vorbis).
    pub sound: PathBuf,
    /// The board that plays it: plen2 or servo.
    #[arg(long, value_parser = super::parse_family)]
    pub protocol: Family,
    /// The servo that follows (servo board), 0–254.
    #[arg(long, value_parser = clap::value_parser!(u8).range(0..=254))]
    pub servo: Option<u8>,
    /// The joint that follows (PLEN2), by its name (`left_shoulder_pitch`…).
    #[arg(long)]
    pub joint: Option<String>,
    /// The angle in silence, degrees (PLEN2: relative to home).
    #[arg(long, allow_hyphen_values = true, value_parser = bounds::angle_deg)]
    pub closed: f64,
    /// The angle at the loudest, degrees.
    #[arg(long, allow_hyphen_values = true, value_parser = bounds::angle_deg)]
    pub open: f64,
    /// Time to open about two thirds of the way, ms.
    #[arg(long, default_value_t = audio::follow::Follow::default().attack_ms, value_parser = bounds::positive_ms)]
    pub attack_ms: f64,
    /// Time to close about two thirds of the way, ms.
    #[arg(long, default_value_t = audio::follow::Follow::default().release_ms, value_parser = bounds::positive_ms)]
    pub release_ms: f64,
    /// Below this level (dB of full scale) the axis stays closed.
    #[arg(long, default_value_t = audio::follow::Follow::default().threshold_db, allow_hyphen_values = true, value_parser = bounds::threshold_db)]
    pub threshold_db: f64,
    /// How far the board's playback may stray from the followed curve, degrees.
    #[arg(long, default_value_t = 1.0, allow_hyphen_values = true, value_parser = bounds::tolerance_deg)]
    pub tolerance_deg: f64,
    /// At most this many frames or steps (PLEN2: 20, what a motion holds).
    #[arg(long, allow_hyphen_values = true, value_parser = bounds::max_frames)]
    pub max_frames: Option<usize>,
    /// PLEN2: a chain of motions in the slots from this one on (each up to 20
    /// frames, jumping to the next, played as one), written as a project —
    /// into --out when it is a PLEN2 project already, replacing what those
    /// slots hold — as the editor's "from slot" does. Without it: one motion.json.
    #[arg(long, value_parser = clap::value_parser!(u8).range(0..=89), conflicts_with = "max_frames")]
    pub from_slot: Option<u8>,
    /// The motion's or macro's name (default: the sound's file name).
    #[arg(long)]
    pub name: Option<String>,
    /// The file to write.
    #[arg(long)]
    pub out: PathBuf,
    /// Replace the output file even when it is read-only.
    #[arg(long)]
    pub force: bool,
}

/// Follows, fits and writes — everything checked before the output is
/// touched — and says what it wrote.
pub fn run(args: &FollowArgs) -> anyhow::Result<String> {
    super::output_not_an_input(&args.out, &[&args.sound])?;
    super::writable_output(&args.out, args.force)?;
    let column = column(args)?;
    if args.from_slot.is_some() && args.protocol != Family::Plen2 {
        anyhow::bail!("--from-slot is for a PLEN2's motion slots: a servo board's follow is one macro");
    }
    let analysis = audio::analyse(&args.sound, 0.5, |_| {})?;
    let settings = audio::follow::Follow {
        attack_ms: args.attack_ms,
        release_ms: args.release_ms,
        threshold_db: args.threshold_db,
    };
    let open = audio::follow::openness(&analysis.found.loudness_db(), &settings);
    if open.len() < 2 {
        anyhow::bail!("{} is too short to follow (under 2 ms)", args.sound.display());
    }
    let name = args
        .name
        .clone()
        .unwrap_or_else(|| args.sound.file_stem().map(|stem| stem.to_string_lossy().into_owned()).unwrap_or_default());
    if args.protocol == Family::Plen2 {
        return plen2(args, &column, &open, &name);
    }
    let (closed, opened) = (args.closed, args.open);
    let mut times_ms = Vec::new();
    let mut rows = Vec::new();
    for ms in (0..open.len()).step_by(STEP_MS) {
        // Milliseconds of at most an hour: exact.
        #[allow(clippy::cast_precision_loss)]
        times_ms.push(ms as f64);
        rows.push(vec![closed + (opened - closed) * open[ms]]);
    }
    let recording = Recording { names: vec![column], times_ms, rows };
    let request = FitRequest {
        recording: args.sound.clone(),
        family: args.protocol,
        tolerance_deg: args.tolerance_deg,
        max_frames: args.max_frames,
        name: Some(name.clone()),
        out: args.out.clone(),
        force: args.force,
    };
    let fitted = fit::write(&recording, &request, &name)?;
    Ok(fit::said(&fitted, args.protocol, &args.out))
}

/// A PLEN2 joint follows as the editor's follow does (the same curve at the
/// robot's cycles, the same fit and chain): one motion.json, or with
/// `--from-slot` a chain of motions in a project.
fn plen2(args: &FollowArgs, joint: &str, open: &[f64], name: &str) -> anyhow::Result<String> {
    let joint = Joint::ALL.into_iter().find(|known| known.name() == joint).context("a PLEN2 joint")?;
    if !name.is_ascii() || name.len() > 20 {
        anyhow::bail!("--name {name:?}: a PLEN2 motion's name is at most 20 ASCII characters");
    }
    let follower = Follower { closed_deg: args.closed, open_deg: args.open, tolerance_deg: args.tolerance_deg };
    let (slots, frames_allowed) = match args.from_slot {
        Some(first) => ((first..SLOTS).collect::<Vec<u8>>(), None),
        None => (vec![0], Some(args.max_frames.unwrap_or(MAX_FRAMES))),
    };
    let fitted = match frames_allowed {
        Some(allowed) if allowed > MAX_FRAMES => {
            anyhow::bail!("--max-frames {allowed}: a PLEN2 motion holds at most {MAX_FRAMES} frames")
        }
        Some(allowed) if allowed < MAX_FRAMES => follow::plen2_within(open, joint, follower, allowed),
        _ => follow::plen2(open, joint, follower, slots.len()),
    };
    let chain = fitted
        .map_err(|error| anyhow::anyhow!(fit::fit_error_said(&error, (10.0, "frames"), args.tolerance_deg * 10.0)))?;
    // Update counts far below 2^52.
    #[allow(clippy::cast_precision_loss)]
    let seconds = chain.cycles as f64 * PLEN2_UPDATE_MS / 1000.0;
    let shifted = if chain.shift_ms == 0 {
        String::new()
    } else {
        format!(
            ", played {:+} ms against the sound (under half a cycle, where the robot's own start falls anyway)",
            chain.shift_ms
        )
    };
    let error_deg = chain.max_error_tenths / 10.0;
    let Some(first) = args.from_slot else {
        let motion = Motion {
            slot: 0,
            name: name.to_string(),
            frames: chain.motions.concat(),
            loop_range: None,
            jump_slot: None,
        };
        let written = project::motion_json::motion_to_json(&motion);
        write(&args.out, &written)?;
        return Ok(format!(
            "{} frames for {seconds:.3} s, largest error {error_deg:.2}°{shifted}: wrote {}",
            motion.frames.len(),
            args.out.display()
        ));
    };
    let into = existing_plen2(&args.out)?;
    let (made, replaced) = follow::placed(&into.plen2, &slots, &chain, name);
    let used: Vec<String> = slots[..chain.motions.len()].iter().map(u8::to_string).collect();
    write(&args.out, &project::to_json(&Project { plen2: made, ..into }))?;
    let replaced = if replaced.is_empty() {
        String::new()
    } else {
        let listed: Vec<String> = replaced.iter().map(|(slot, name)| format!("{slot} {name}")).collect();
        format!("; replaced: {}", listed.join(", "))
    };
    Ok(format!(
        "{} frames in {} motions from slot {first} (slots {}, each jumping to the next) for {seconds:.3} s, largest error {error_deg:.2}°{shifted}{replaced}: wrote {}",
        chain.frames(),
        chain.motions.len(),
        used.join(", "),
        args.out.display()
    ))
}

/// The PLEN2 project `out` holds, to add a chain to; an empty one when there
/// is no such file yet. Any other file there is refused, never replaced.
fn existing_plen2(out: &std::path::Path) -> anyhow::Result<Project> {
    if !out.exists() {
        return Ok(Project::empty(Family::Plen2));
    }
    let text = project::input::read_text(out, project::input::MAX_PROJECT_BYTES)?;
    match project::from_json(&text) {
        Ok(project) if project.family == Family::Plen2 => Ok(project),
        Ok(project) => anyhow::bail!(
            "{} is a {} project: --from-slot adds motions to a PLEN2 project (give a new file or a PLEN2 project)",
            out.display(),
            project.family.name()
        ),
        Err(error) => anyhow::bail!(
            "{} is not a PLEN2 project ({error}): --from-slot adds motions to a PLEN2 project; give a new file or a PLEN2 project",
            out.display()
        ),
    }
}

fn write(out: &std::path::Path, text: &str) -> anyhow::Result<()> {
    project::atomic_write(out, |file| std::io::Write::write_all(file, text.as_bytes()))
        .with_context(|| format!("cannot write {}", out.display()))
}

/// The recording's one column: the servo or the joint, as the family names it.
fn column(args: &FollowArgs) -> anyhow::Result<String> {
    match (args.protocol, args.servo, &args.joint) {
        (Family::Servo, Some(id), None) => Ok(format!("servo {id}")),
        (Family::Plen2, None, Some(joint)) => {
            if Joint::ALL.iter().any(|known| known.name() == joint) {
                return Ok(joint.clone());
            }
            let names: Vec<&str> = Joint::ALL.iter().map(|joint| joint.name()).collect();
            anyhow::bail!("--joint {joint:?} is not a PLEN2 joint (they are: {})", names.join(", "))
        }
        (Family::Servo, None, Some(_)) => {
            anyhow::bail!("--joint names a PLEN2 joint: a servo board follows with --servo N")
        }
        (Family::Plen2, Some(_), None) => {
            anyhow::bail!("--servo is for a servo board: a PLEN2 follows with --joint NAME")
        }
        (family, _, _) => anyhow::bail!("--protocol {family}: only servo and plen2 follow a sound"),
    }
}
