//! `servo-studio follow-audio`: a sound's loudness as one servo's or joint's
//! curve (a talking skull's jaw, a PLEN2 nodding to a beat), fitted into
//! the board's steps or frames by the same fitter `fit` uses.

use std::path::PathBuf;

use clap::Args;

use anyhow::Context as _;

use super::bounds;
use super::fit::{self, FitRequest};
use crate::audio;
use crate::authoring::recording::Recording;
use crate::project::{self, Family};

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

/// How a family follows a sound, registered by the family
/// (`inventory::submit!` in `cli/<family>.rs`).
#[derive(Debug)]
pub struct SoundFollower {
    /// The family whose board plays the follow.
    pub family: Family,
    /// The recording's one column, as the family names the axis given
    /// (`--servo`, `--joint`); why not when the axis given is not one of its.
    pub column: fn(&FollowArgs) -> anyhow::Result<String>,
    /// Whether it takes `--from-slot`; `Err`: why not, and what it makes instead.
    pub from_slot: Result<(), &'static str>,
    /// Fits the curve (`openness`, 0..=1 a ms) to its board and writes it; what it wrote.
    pub follow: fn(&FollowArgs, &str, &[f64], &str) -> anyhow::Result<String>,
}

inventory::collect!(SoundFollower);

/// Follows, fits and writes — everything checked before the output is
/// touched — and says what it wrote.
pub fn run(args: &FollowArgs) -> anyhow::Result<String> {
    super::output_not_an_input(&args.out, &[&args.sound])?;
    super::writable_output(&args.out, args.force)?;
    let followers = || inventory::iter::<SoundFollower>.into_iter();
    let Some(follower) = followers().find(|follower| follower.family == args.protocol) else {
        let follows = |family: &&Family| followers().any(|follower| follower.family == **family);
        let named: Vec<&str> = Family::all().iter().filter(follows).map(|family| family.tag()).collect();
        anyhow::bail!("--protocol {}: only {} follow a sound", args.protocol, named.join(" and "));
    };
    let column = (follower.column)(args)?;
    if let (Some(_), Err(why)) = (args.from_slot, follower.from_slot) {
        anyhow::bail!("{why}");
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
    (follower.follow)(args, &column, &open, &name)
}

/// Follows as `fit` fits a recording: the curve as one column, sampled
/// every few ms, fitted by the family's fitter into one macro or motion.
pub fn fitted(args: &FollowArgs, column: &str, open: &[f64], name: &str) -> anyhow::Result<String> {
    let (closed, opened) = (args.closed, args.open);
    let mut times_ms = Vec::new();
    let mut rows = Vec::new();
    for ms in (0..open.len()).step_by(STEP_MS) {
        // Milliseconds of at most an hour: exact.
        #[allow(clippy::cast_precision_loss)]
        times_ms.push(ms as f64);
        rows.push(vec![closed + (opened - closed) * open[ms]]);
    }
    let recording = Recording { names: vec![column.to_string()], times_ms, rows };
    let request = FitRequest {
        recording: args.sound.clone(),
        family: args.protocol,
        tolerance_deg: args.tolerance_deg,
        max_frames: args.max_frames,
        name: Some(name.to_string()),
        out: args.out.clone(),
        force: args.force,
    };
    let fitted = fit::write(&recording, &request, name)?;
    Ok(fit::said(&fitted, args.protocol, &args.out))
}

/// Writes `text` to `out` whole, or nothing.
pub fn write(out: &std::path::Path, text: &str) -> anyhow::Result<()> {
    project::atomic_write(out, |file| std::io::Write::write_all(file, text.as_bytes()))
        .with_context(|| format!("cannot write {}", out.display()))
}
