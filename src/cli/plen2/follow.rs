//! `follow-audio` for a PLEN2: a joint follows as the editor's follow does
//! (the same curve at the robot's cycles, the same fit and chain): one
//! motion.json, or with `--from-slot` a chain of motions in a project.

use anyhow::Context as _;

use crate::authoring::fitted::PLEN2_UPDATE_MS;
use crate::authoring::follow::{self, Follower};
use crate::cli::fit;
use crate::cli::follow_audio::{FollowArgs, SoundFollower, write};
use crate::project::plen2::{Joint, MAX_FRAMES, Motion, SLOTS};
use crate::project::{self, Family, Project};

inventory::submit! {
    SoundFollower { family: Family::Plen2, column, from_slot: Ok(()), follow: plen2 }
}

/// The recording's one column: the joint `--joint` names.
fn column(args: &FollowArgs) -> anyhow::Result<String> {
    match (args.servo, &args.joint) {
        (None, Some(joint)) => {
            if Joint::ALL.iter().any(|known| known.name() == joint) {
                return Ok(joint.clone());
            }
            let names: Vec<&str> = Joint::ALL.iter().map(|joint| joint.name()).collect();
            anyhow::bail!("--joint {joint:?} is not a PLEN2 joint (they are: {})", names.join(", "))
        }
        _ => anyhow::bail!("--servo is for a servo board: a PLEN2 follows with --joint NAME"),
    }
}

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
