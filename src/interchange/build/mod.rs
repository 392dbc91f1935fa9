//! A [`Source`] and a [`JointMap`] made into what a board stores: servo-board
//! servos, actions and macros, or PLEN2 motions and play lists.

mod plen2;
mod servo;

use super::map::{JointMap, MapEntry, Target};
use super::report::Report;
use super::source::{Body, Channel, Clip, Key, Source, Timing};
use crate::project::{Family, Project};

/// How fast a move of no time is made to go, °/s: the live speed limit's
/// default (`device::speed::DEFAULT_DEG_PER_S`), the rule that keeps a servo from slamming.
pub const LIVE_DEG_PER_S: f64 = 180.0;

/// Which clips to convert.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub enum Selection {
    /// Every clip.
    #[default]
    All,
    /// The clip of this name (a Maestro sequence, an R+ page or flow) and what it plays.
    Named(String),
    /// The RoboPlus page of this number and the pages it leads to.
    Page(u32),
}

/// How to convert.
#[derive(Clone, Debug, PartialEq)]
pub struct Options {
    /// The board it is for.
    pub family: Family,
    /// Which clips.
    pub selection: Selection,
    /// Sampled animations (Blender): how far the board's playback may stray, degrees.
    pub tolerance_deg: f64,
}

impl Options {
    /// Every clip for `family`, fitted within 1°.
    pub fn new(family: Family) -> Self {
        Self { family, selection: Selection::All, tolerance_deg: 1.0 }
    }
}

/// A conversion that cannot be made.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum BuildError {
    /// The selection names nothing in the file.
    #[error("{wanted} is not in the file; it holds: {held}")]
    NotFound {
        /// What was asked for.
        wanted: String,
        /// What there is.
        held: String,
    },
    /// Nothing to convert.
    #[error("the file holds no motion to convert")]
    Empty,
    /// No channel is mapped to the family's servos or joints.
    #[error("no channel drives a {family}: give a joint map (--map) that says which channel drives which")]
    Unmapped {
        /// The family's name.
        family: &'static str,
    },
    /// The target cannot hold it.
    #[error("{0}")]
    TooBig(String),
    /// A sampled animation the board cannot follow within the tolerance.
    #[error("{0}")]
    Fit(String),
}

/// What a conversion made.
#[derive(Clone, Debug, PartialEq)]
pub struct Built {
    /// A project of the family asked for, holding only what was converted.
    pub project: Project,
    /// What was converted, approximated and dropped.
    pub report: Report,
    /// Where each converted clip (by index in the source) starts playing.
    pub starts: Vec<(usize, Start)>,
}

/// What plays a converted clip on the board.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Start {
    /// A servo board's macro, by id.
    Macro(i32),
    /// A PLEN2 motion, by slot.
    Slot(u8),
    /// A PLEN2 play list, by index.
    PlayList(usize),
}

/// Converts `source` through `map` for `options.family`.
pub fn build(source: &Source, map: &JointMap, options: &Options) -> Result<Built, BuildError> {
    let clips = selected(source, &options.selection)?;
    let mapped: Vec<Option<&MapEntry>> = source
        .channels
        .iter()
        .map(|channel| {
            map.entry(&channel.key).filter(|entry| entry.target.is_some_and(|t| t.family() == options.family))
        })
        .collect();
    if mapped.iter().all(Option::is_none) {
        return Err(BuildError::Unmapped { family: options.family.name() });
    }
    let mut report = Report::default();
    for note in &source.dropped {
        report.dropped(note.clone());
    }
    for note in &source.notes {
        report.noted(note.clone());
    }
    for (channel, entry) in source.channels.iter().zip(&mapped) {
        if entry.is_none() {
            let name = if channel.name.is_empty() { String::new() } else { format!(" ({})", channel.name) };
            report.dropped(format!("channel {}{name}: not mapped", channel.key));
        }
    }
    let input = Input { source, mapped, clips, tolerance_deg: options.tolerance_deg };
    let mut starts = Vec::new();
    let project = match options.family {
        Family::Servo => Project::servo(servo::build(&input, &mut report, &mut starts)?),
        Family::Plen2 => {
            let mut project = Project::empty(Family::Plen2);
            project.plen2 = plen2::build(&input, &mut report, &mut starts)?;
            project
        }
        Family::Rflex => return Err(BuildError::Unmapped { family: "rFLEX base (it stores no motions)" }),
        other => return Err(BuildError::Unmapped { family: other.name() }),
    };
    Ok(Built { project, report, starts })
}

/// What both families' builders read.
struct Input<'a> {
    source: &'a Source,
    /// Per source channel: its map entry when it drives this family.
    mapped: Vec<Option<&'a MapEntry>>,
    /// The clips to convert, by index, in file order.
    clips: Vec<usize>,
    tolerance_deg: f64,
}

impl Input<'_> {
    fn clip(&self, index: usize) -> &Clip {
        &self.source.clips[index]
    }

    /// Each mapped channel's degrees for a key's raw values (`None`: not driven).
    fn degrees(&self, values: &[Option<f64>]) -> Vec<Option<f64>> {
        self.mapped.iter().zip(values).map(|(entry, value)| Some(entry.as_ref()?.degrees((*value)?))).collect()
    }

    /// The mapped channels' targets, in channel order.
    fn targets(&self) -> impl Iterator<Item = (usize, Target, &Channel)> + '_ {
        self.mapped
            .iter()
            .enumerate()
            .filter_map(|(index, entry)| Some((index, entry.as_ref()?.target?, &self.source.channels[index])))
    }
}

/// The clips a selection names, with every clip they lead to.
pub(crate) fn selected(source: &Source, selection: &Selection) -> Result<Vec<usize>, BuildError> {
    if source.clips.is_empty() {
        return Err(BuildError::Empty);
    }
    let held = || {
        let names: Vec<String> = source
            .clips
            .iter()
            .map(|clip| clip.number.map_or_else(|| format!("{:?}", clip.name), |n| format!("page {n} {:?}", clip.name)))
            .collect();
        names.join(", ")
    };
    let start = match selection {
        Selection::All => return Ok((0..source.clips.len()).collect()),
        Selection::Named(name) => source.clips.iter().position(|clip| &clip.name == name),
        Selection::Page(number) => source.clips.iter().position(|clip| clip.number == Some(*number)),
    };
    let wanted = match selection {
        Selection::Named(name) => format!("{name:?}"),
        Selection::Page(number) => format!("page {number}"),
        Selection::All => String::new(),
    };
    let start = start.ok_or_else(|| BuildError::NotFound { wanted, held: held() })?;
    let mut chosen = vec![start];
    let mut at = 0;
    while let Some(&index) = chosen.get(at) {
        let clip = &source.clips[index];
        let mut leads: Vec<usize> = clip.next.into_iter().chain(clip.exit).collect();
        if let Body::Chain(links) = &clip.body {
            leads.extend(links.iter().map(|link| link.clip));
        }
        for lead in leads {
            if !chosen.contains(&lead) {
                chosen.push(lead);
            }
        }
        at += 1;
    }
    chosen.sort_unstable();
    Ok(chosen)
}

/// Where a Maestro frame leaves each channel, how long the move takes and
/// whether a channel was cut short (the frame ended before it arrived): every
/// channel heads for its target at its speed limit — `speed` raw units per
/// 10 ms, or, at 0 ("as fast as the servo goes"), the live speed limit, so
/// that no servo slams.
struct FrameMove {
    /// Per channel: where it is when the frame ends (degrees).
    end: Vec<Option<f64>>,
    /// Per channel: how long it moves, 10 ms units.
    updates: Vec<u32>,
    cut_short: bool,
}

fn frame_move(input: &Input<'_>, from: &[Option<f64>], raw: &[Option<f64>], duration_ms: f64) -> FrameMove {
    let frame_updates = (duration_ms / 10.0).round();
    let mut out = FrameMove { end: from.to_vec(), updates: vec![0; from.len()], cut_short: false };
    for (index, entry) in input.mapped.iter().enumerate() {
        let (Some(entry), Some(target_raw)) = (entry, raw[index]) else { continue };
        let target = entry.degrees(target_raw);
        let start = from[index].unwrap_or(target);
        let speed = input.source.channels[index].speed.unwrap_or(0.0);
        let needed = if speed > 0.0 {
            ((target - start).abs() * entry.per_degree.abs() / speed).ceil()
        } else {
            ((target - start).abs() / LIVE_DEG_PER_S * 100.0).ceil()
        };
        let (end, updates) = if needed > frame_updates && needed > 0.0 {
            out.cut_short = true;
            (start + (target - start) * frame_updates / needed, frame_updates)
        } else {
            (target, needed)
        };
        out.end[index] = Some(end);
        // Whole, small, non-negative counts.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let updates = updates.max(0.0).min(f64::from(u32::MAX)) as u32;
        out.updates[index] = updates;
    }
    out
}

/// The note for a frame cut short.
const CUT_SHORT: &str = "a Maestro frame shorter than a channel's speed limit needs: the servo goes as far as the Maestro gets it before the next frame";
/// The note for a jump.
const JUMP: &str =
    "a move of no time (a jump): it takes as long as the live speed limit (180°/s) needs, so that no servo slams";

/// How a key's time is spent, in ms at the clip's speed, and whether it is a Maestro frame.
/// A flow's keys one after another — each page's keys as often as the flow
/// plays it, at the page's and the flow's speed — when every page is keys
/// played once with nothing after it (an R+ page) and there are at most
/// `most`: played on one clock, no page's rounding to the board's updates
/// adds to the next's.
fn flow_keys(input: &Input<'_>, flow: &Clip, links: &[super::source::Link], most: usize) -> Option<Vec<Key>> {
    let mut keys = Vec::new();
    for link in links {
        let page = input.clip(link.clip);
        let Body::Keys(page_keys) = &page.body else { return None };
        if link.plays == 0 || page.repeat > 1 || page.next.is_some() {
            return None;
        }
        let rate = page.speed * link.speed / flow.speed;
        let plays = usize::try_from(link.plays).ok()?;
        if keys.len() + page_keys.len().saturating_mul(plays) > most {
            return None;
        }
        for _ in 0..plays {
            keys.extend(page_keys.iter().map(|key| Key { timing: key.timing.at_rate(rate), ..key.clone() }));
        }
    }
    Some(keys)
}

fn timing(clip: &Clip, timing: Timing) -> (f64, f64, bool) {
    match timing {
        Timing::Move { move_ms, hold_ms } => (move_ms / clip.speed, hold_ms / clip.speed, false),
        Timing::Frame { duration_ms } => (duration_ms / clip.speed, 0.0, true),
    }
}
