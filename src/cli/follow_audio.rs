//! `servo-studio follow-audio`: a sound's loudness as one servo's or joint's
//! curve (a talking skull's jaw, a PLEN2 nodding to a beat), fitted into
//! the board's steps or frames by the same fitter `fit` uses.

use std::path::PathBuf;

use clap::Args;

use super::bounds;
use super::fit::{self, FitRequest, Fitted};
use crate::audio::{self, follow};
use crate::authoring::recording::Recording;
use crate::project::Family;
use crate::project::plen2::Joint;

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
    #[arg(long, default_value_t = follow::Follow::default().attack_ms, value_parser = bounds::positive_ms)]
    pub attack_ms: f64,
    /// Time to close about two thirds of the way, ms.
    #[arg(long, default_value_t = follow::Follow::default().release_ms, value_parser = bounds::positive_ms)]
    pub release_ms: f64,
    /// Below this level (dB of full scale) the axis stays closed.
    #[arg(long, default_value_t = follow::Follow::default().threshold_db, allow_hyphen_values = true, value_parser = bounds::threshold_db)]
    pub threshold_db: f64,
    /// How far the board's playback may stray from the followed curve, degrees.
    #[arg(long, default_value_t = 1.0, allow_hyphen_values = true, value_parser = bounds::tolerance_deg)]
    pub tolerance_deg: f64,
    /// At most this many frames or steps (PLEN2: 20, what a motion holds).
    #[arg(long, allow_hyphen_values = true, value_parser = bounds::max_frames)]
    pub max_frames: Option<usize>,
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

/// Follows, fits and writes; everything is checked before the output is touched.
pub fn run(args: &FollowArgs) -> anyhow::Result<Fitted> {
    super::output_not_an_input(&args.out, &[&args.sound])?;
    super::writable_output(&args.out, args.force)?;
    let column = column(args)?;
    let analysis = audio::analyse(&args.sound, 0.5, |_| {})?;
    let settings =
        follow::Follow { attack_ms: args.attack_ms, release_ms: args.release_ms, threshold_db: args.threshold_db };
    let open = follow::openness(&analysis.found.loudness_db(), &settings);
    if open.len() < 2 {
        anyhow::bail!("{} is too short to follow (under 2 ms)", args.sound.display());
    }
    // PLEN2 recordings are in tenths of a degree (as `trajectory` writes them).
    let unit = if args.protocol == Family::Plen2 { 10.0 } else { 1.0 };
    let (closed, opened) = (args.closed * unit, args.open * unit);
    let mut times_ms = Vec::new();
    let mut rows = Vec::new();
    for ms in (0..open.len()).step_by(STEP_MS) {
        // Milliseconds of at most an hour: exact.
        #[allow(clippy::cast_precision_loss)]
        times_ms.push(ms as f64);
        rows.push(vec![closed + (opened - closed) * open[ms]]);
    }
    let recording = Recording { names: vec![column], times_ms, rows };
    let name = args
        .name
        .clone()
        .unwrap_or_else(|| args.sound.file_stem().map(|stem| stem.to_string_lossy().into_owned()).unwrap_or_default());
    let request = FitRequest {
        recording: args.sound.clone(),
        family: args.protocol,
        tolerance_deg: args.tolerance_deg,
        max_frames: args.max_frames,
        name: Some(name.clone()),
        out: args.out.clone(),
        force: args.force,
    };
    fit::write(&recording, &request, &name)
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

/// The line `follow-audio` prints.
pub fn said(fitted: &Fitted, args: &FollowArgs) -> String {
    fit::said(fitted, args.protocol, &args.out)
}
