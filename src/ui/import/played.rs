//! What the board will play of an import, for the window's preview: the
//! conversion Create would make, traced as the board plays it (a servo
//! board's steps at its 10 ms updates within each servo's limits; a PLEN2's
//! frames through the firmware's playback, clamped to its joints' settings),
//! and where that differs from the file, by how much.

use crate::device::plen2::playback::{self, DEVICE_IDS, Playback, StoredMotions};
use crate::interchange::build::{Built, Start};
use crate::interchange::map::{JointMap, Target};
use crate::interchange::{Body, Source, Timing, preview};
use crate::project::{Project, Run, ServoProject, Trajectories, angle_at, trace};

/// The longest a preview traces, ms (a motion that never ends is cut there).
const MAX_MS: f64 = 600_000.0;

/// The board's playback of one clip.
#[derive(Debug)]
pub struct Played {
    track: Track,
    /// How long it plays, ms (at most [`MAX_MS`]).
    pub length_ms: f64,
    /// The largest difference from the file, if any is over a tenth of a degree.
    pub differs: Option<Difference>,
}

/// Where the board plays farthest from the file.
#[derive(Clone, Debug, PartialEq)]
pub struct Difference {
    /// The channel, by index in the source.
    pub channel: usize,
    /// How far, degrees.
    pub degrees: f64,
    /// When, ms.
    pub at_ms: f64,
    /// Whether the board holds it there at a limit (a servo's, a joint's).
    pub limited: bool,
}

#[derive(Debug)]
enum Track {
    /// A servo board: each servo's points, and its limits and home, by id.
    Servo(Trajectories, Vec<(u8, f64, f64, f64)>),
    /// A PLEN2: every cycle's joint values, tenths relative to home, clamped and as the frames ask.
    Plen2(Vec<[i16; DEVICE_IDS]>, Vec<[i16; DEVICE_IDS]>),
}

impl Played {
    /// `clip` of `source` as `built` plays it on the board of `project`
    /// (whose servos and joint settings it keeps), compared with the file.
    pub fn new(source: &Source, map: &JointMap, clip: usize, built: &Built, project: &Project) -> Option<Self> {
        let start = built.starts.iter().find(|(index, _)| *index == clip)?.1;
        let (track, length_ms, step_ms) = match start {
            Start::Macro(macro_id) => {
                let (points, end) = trace(&built.project.servo, Run::Macro { macro_id }, MAX_MS).ok()?;
                (Track::Servo(points, limits(&built.project.servo, &project.servo)), end.min(MAX_MS), 10.0)
            }
            Start::Slot(slot) => {
                let cycles = plen2_cycles(built, &[(slot, 1)], project);
                (Track::Plen2(cycles.0, cycles.1), cycles.2, Playback::CYCLE_MS)
            }
            Start::PlayList(index) => {
                let list = built.project.plen2.play_lists.get(index)?;
                let entries: Vec<(u8, u8)> = list.entries.iter().map(|e| (e.slot, e.plays)).collect();
                let cycles = plen2_cycles(built, &entries, project);
                (Track::Plen2(cycles.0, cycles.1), cycles.2, Playback::CYCLE_MS)
            }
        };
        let mut played = Self { track, length_ms, differs: None };
        played.differs = played.difference(source, map, clip, step_ms);
        Some(played)
    }

    /// Each channel's degrees at `time_ms` as the board plays it (`None`: not mapped).
    pub fn degrees_at(&self, source: &Source, map: &JointMap, time_ms: f64) -> Vec<Option<f64>> {
        source.channels.iter().map(|channel| self.target_at(map.entry(&channel.key)?.target?, time_ms)).collect()
    }

    fn target_at(&self, target: Target, time_ms: f64) -> Option<f64> {
        self.target_limited(target, time_ms).map(|(degrees, _)| degrees)
    }

    /// Where the board has `target` at `time_ms`, and whether a limit holds it there.
    fn target_limited(&self, target: Target, time_ms: f64) -> Option<(f64, bool)> {
        match (&self.track, target) {
            (Track::Servo(points, servos), Target::Servo(id)) => {
                let &(_, low, high, home) = servos.iter().find(|(servo, ..)| *servo == id)?;
                let angle = points.get(&id).and_then(|points| angle_at(points, time_ms)).unwrap_or(home);
                Some((angle.clamp(low, high), angle < low || angle > high))
            }
            (Track::Plen2(cycles, asked), Target::Joint(joint)) => {
                // Cycle counts far below 2^52, non-negative.
                #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
                let cycle =
                    ((time_ms.max(0.0) / Playback::CYCLE_MS).floor() as usize).min(cycles.len().checked_sub(1)?);
                let device = usize::from(joint.device_id());
                Some((f64::from(cycles[cycle][device]) / 10.0, cycles[cycle][device] != asked[cycle][device]))
            }
            _ => None,
        }
    }

    /// The farthest the board is from the file over the clip, each file
    /// sample matched with the board within half an update of it (so whole
    /// updates are not counted as a difference; a move cut short, a limit
    /// or a step the board cannot make is).
    fn difference(&self, source: &Source, map: &JointMap, clip: usize, step_ms: f64) -> Option<Difference> {
        let clip_ref = source.clips.get(clip)?;
        let length = preview::length_ms(source, clip_ref).min(self.length_ms).min(MAX_MS);
        let mut worst: Option<Difference> = None;
        // Where a file starts its channels it does not say (a RoboPlus or R+
        // page moves from wherever the robot is): compared once its first key is reached.
        let mut time = if source.channels.iter().all(|channel| channel.home.is_some()) {
            0.0
        } else {
            first_key_ms(source, clip_ref, 0)
        };
        while time <= length {
            let file = preview::degrees_at(source, clip_ref, map, time);
            // Keys are kept on the board's updates (their rounding said apart):
            // matched within half an update. Samples are fitted at the updates
            // themselves: compared there, as the fit measures its error.
            let shifts: &[f64] = if matches!(clip_ref.body, Body::Samples { .. }) {
                &[0.0]
            } else {
                &[-step_ms / 2.0, 0.0, step_ms / 2.0]
            };
            let near: Vec<Vec<Option<f64>>> =
                shifts.iter().map(|shift| self.degrees_at(source, map, (time + shift).max(0.0))).collect();
            for (channel, wanted) in file.iter().enumerate() {
                let Some(wanted) = wanted else { continue };
                let off =
                    near.iter().filter_map(|row| row[channel]).map(|got| (got - wanted).abs()).fold(f64::MAX, f64::min);
                if off < f64::MAX && off > worst.as_ref().map_or(0.1, |w| w.degrees) {
                    let limited = map
                        .entry(&source.channels[channel].key)
                        .and_then(|entry| entry.target)
                        .and_then(|target| self.target_limited(target, time))
                        .is_some_and(|(_, limited)| limited);
                    worst = Some(Difference { channel, degrees: off, at_ms: time, limited });
                }
            }
            time += step_ms;
        }
        worst
    }
}

/// When a clip's first key is reached, ms (a chain: its first clip's).
fn first_key_ms(source: &Source, clip: &crate::interchange::Clip, depth: usize) -> f64 {
    match &clip.body {
        Body::Keys(keys) => {
            keys.first().map_or(0.0, |key| match key.timing {
                Timing::Move { move_ms, .. } => move_ms,
                Timing::Frame { duration_ms } => duration_ms,
            }) / clip.speed
        }
        Body::Chain(links) if depth < 8 => links
            .first()
            .and_then(|link| Some(first_key_ms(source, source.clips.get(link.clip)?, depth + 1) / link.speed))
            .unwrap_or(0.0),
        _ => 0.0,
    }
}

/// Each servo of the conversion with the limits and home it will have: the
/// project's own where it has that servo (an import keeps them), else the conversion's.
fn limits(built: &ServoProject, project: &ServoProject) -> Vec<(u8, f64, f64, f64)> {
    built
        .servos
        .iter()
        .map(|servo| {
            let kept = project.servo(servo.id).unwrap_or(servo);
            (servo.id, f64::from(kept.min_deg), f64::from(kept.max_deg), f64::from(kept.home_deg))
        })
        .collect()
}

/// Motions played one after another (each `plays` times) from power-up:
/// every cycle clamped to the project's joint settings and as the frames ask, and how long, ms.
fn plen2_cycles(built: &Built, entries: &[(u8, u8)], project: &Project) -> Plen2Cycles {
    let stored = StoredMotions::new(&built.project.plen2);
    let settings = playback::joint_settings(&project.plen2);
    // Cycle counts from a bounded time.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let max_cycles = (MAX_MS / Playback::CYCLE_MS) as usize;
    let mut asked: Vec<[i16; DEVICE_IDS]> = Vec::new();
    let mut from = [0; DEVICE_IDS];
    for &(slot, plays) in entries {
        for _ in 0..plays.max(1) {
            let left = max_cycles.saturating_sub(asked.len());
            if left == 0 {
                break;
            }
            let played = playback::play(&stored, slot, from, left);
            from = played.cycles.last().copied().unwrap_or(from);
            asked.extend(played.cycles);
        }
    }
    let clamped = asked.iter().map(|values| playback::clamped(values, &settings)).collect();
    // Cycle counts far below 2^52.
    #[allow(clippy::cast_precision_loss)]
    let length = asked.len().saturating_sub(1) as f64 * Playback::CYCLE_MS;
    (clamped, asked, length)
}

/// Every cycle clamped, every cycle as asked, and how long, ms.
type Plen2Cycles = (Vec<[i16; DEVICE_IDS]>, Vec<[i16; DEVICE_IDS]>, f64);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::interchange::build::{self, Options, Selection};
    use crate::project::Family;

    /// Every real fixture of another tool (`tests/fixtures/interchange`).
    fn fixtures() -> Vec<std::path::PathBuf> {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/interchange");
        let mut files = Vec::new();
        for folder in std::fs::read_dir(root).unwrap().flatten().filter(|entry| entry.path().is_dir()) {
            for file in std::fs::read_dir(folder.path()).unwrap().flatten() {
                let path = file.path();
                let format = path.extension().and_then(|e| e.to_str()).unwrap_or_default();
                if ["xml", "txt", "mtn", "mtnx", "json"].contains(&format)
                    && !path.to_string_lossy().ends_with(".map.json")
                {
                    files.push(path);
                }
            }
        }
        files.sort();
        files
    }

    /// The degrees a conversion says its fit keeps within ("… within 1.00° (asked 1°)").
    fn fitted_within(line: &str) -> Option<f64> {
        let (_, after) = line.split_once(" within ")?;
        after.split('°').next()?.parse().ok()
    }

    /// The preview's figure is the conversion's: on every real file of the
    /// other tools, for every clip on each family, where the conversion says
    /// how far its fit strays, the preview finds the board that far from the
    /// file (a hundredth of a degree apart at most), never farther.
    #[test]
    fn the_previews_figure_is_the_conversions_on_every_real_fixture() {
        let mut compared = 0;
        for path in fixtures() {
            let Ok(source) = super::super::read_source(&path) else { continue };
            for family in [Family::Servo, Family::Plen2] {
                let map = JointMap::for_source(&source, family, None);
                let project = Project { family, ..Project::default() };
                for (index, clip) in source.clips.iter().enumerate() {
                    let selection = Selection::Named(clip.name.clone());
                    let options = Options { family, selection, tolerance_deg: 1.0 };
                    let Ok(built) = build::build(&source, &map, &options) else { continue };
                    let Some(played) = Played::new(&source, &map, index, &built, &project) else { continue };
                    let Some(within) = built.report.converted.iter().find_map(|line| fitted_within(line)) else {
                        continue;
                    };
                    let shown = played.differs.as_ref().map_or(0.0, |differs| differs.degrees);
                    let file = path.file_name().unwrap().to_string_lossy();
                    assert!(
                        (shown - within).abs() <= 0.01 || (within <= 0.1 && shown <= 0.1),
                        "{file} {:?} on a {family:?}: the preview says {shown:.3}°, the conversion {within:.2}° ({:?})",
                        clip.name,
                        built.report.converted
                    );
                    compared += 1;
                }
            }
        }
        assert!(compared >= 4, "the Blender fixtures' clips were compared: {compared}");
    }
}
