//! Another tool's motions straight onto DYNAMIXEL IDs (`convert --to
//! dynamixel`): each channel of a RoboPlus `.mtn` or R+ `.mtnx` is the
//! servo of that ID, its values kept in the servo's own units — a `.mtn`'s AX
//! units (1024 over 300°) as an AX-12A's, its MX units (4096 over 360°) as an
//! MX-28's; an R+ pose in degrees as the units of the servo its robot
//! declares (±150°: an AX's 1024 over 300°; ±180°: an X-series' 4096 over
//! 360°). Each page (or flow) is a motion whose steps reach each pose when
//! the tool's controller reaches it — the key's move, then its pause held,
//! at the page's speed rate, repeated as the page repeats — with the step
//! ends rounded to whole milliseconds from the motion's start, so that no
//! rounding adds up.

use std::collections::BTreeMap;

use super::build::{BuildError, Selection, selected};
use super::report::Report;
use super::source::{Body, Channel, Clip, Source, Timing, Unit};
use crate::project::dynamixel::{DynamixelSection, LONGEST_STEP_MS, Motion, ServoSetup, Step, units};
use crate::project::{Easing, Family, Project};
use crate::protocol::dynamixel::table::{KNOWN, known};

/// An AX-12A's model number (AX units).
const AX_12A: u16 = 12;
/// An MX-28's model number on Protocol 1.0 (MX units).
const MX_28: u16 = 29;
/// An XL430-W250's model number (degrees of a ±180° servo).
const XL430: u16 = 1060;

/// The model whose units a channel's values are: the servo the file names
/// when it is one of the models known by name, else told by its units.
fn model_of(channel: &Channel) -> u16 {
    let named = channel.motor.as_deref().and_then(|motor| {
        let motor = motor.to_ascii_uppercase().replace(['-', ' '], "");
        KNOWN.iter().find(|model| {
            let name = model.name.to_ascii_uppercase().replace(['-', ' '], "");
            // "AX-12A" names the AX-12A, "AX-12" too; "MX-28" the 1.0 MX-28.
            name == motor || (name.starts_with(&motor) && !name.contains('('))
        })
    });
    if let Some(model) = named {
        return model.number;
    }
    let (unit, limits) = (channel.unit, channel.limits);
    if unit == super::robotis::AX {
        AX_12A
    } else if unit == super::robotis::MX {
        MX_28
    } else if limits.is_some_and(|(low, high)| low >= -150.0 && high <= 150.0) {
        AX_12A
    } else {
        XL430
    }
}

/// `raw` (in `unit`) as a position of a servo of `model`.
fn position(raw: f64, unit: Unit, model: u16) -> u32 {
    if unit == super::robotis::AX || unit == super::robotis::MX {
        // Already the servo's own units.
        // A raw position of the file: whole and within its table.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let raw = raw.round().max(0.0) as u32;
        return raw;
    }
    // Within the servo's table: a pose at its very end (150° of an AX) is its last position.
    let top = known(model).map_or(u32::MAX, |model| model.layout.top_position);
    units(model, (raw - unit.zero) / unit.per_degree).min(top)
}

/// Ends of moves and holds, ms from a motion's start, as steps.
struct Steps {
    steps: Vec<Step>,
    /// Where the motion is, ms (unrounded).
    at_ms: f64,
    /// Where the last step ended, whole ms.
    ended_ms: u64,
}

impl Steps {
    fn new() -> Self {
        Self { steps: Vec::new(), at_ms: 0.0, ended_ms: 0 }
    }

    /// A step to `positions` ending `span_ms` on (a hold: none when it rounds to nothing).
    fn push(&mut self, span_ms: f64, positions: &BTreeMap<u8, u32>, hold: bool) {
        self.at_ms += span_ms.max(0.0);
        // Milliseconds of a motion: within u64.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let end = self.at_ms.round() as u64;
        let span = end.saturating_sub(self.ended_ms);
        if span == 0 && hold {
            return;
        }
        // A move takes at least a millisecond; a step at most a minute.
        let duration_ms = u32::try_from(span.clamp(1, u64::from(LONGEST_STEP_MS))).unwrap_or(LONGEST_STEP_MS);
        self.ended_ms += u64::from(duration_ms);
        self.steps.push(Step { duration_ms, easing: Easing::Linear, positions: positions.clone() });
    }
}

/// The steps of `clip` played once at `rate`, onto `steps`.
fn play(source: &Source, clip: &Clip, rate: f64, models: &[Option<(u8, u16)>], steps: &mut Steps, depth: u8) {
    let rate = rate * if clip.speed > 0.0 { clip.speed } else { 1.0 };
    for _ in 0..clip.repeat.max(1) {
        match &clip.body {
            Body::Keys(keys) => {
                for key in keys {
                    let positions: BTreeMap<u8, u32> = key
                        .values
                        .iter()
                        .zip(&source.channels)
                        .zip(models)
                        .filter_map(|((value, channel), model)| {
                            let (id, model) = (*model)?;
                            Some((id, position((*value)?, channel.unit, model)))
                        })
                        .collect();
                    let (move_ms, hold_ms) = match key.timing.at_rate(rate) {
                        Timing::Move { move_ms, hold_ms } => (move_ms, hold_ms),
                        Timing::Frame { duration_ms } => (duration_ms, 0.0),
                    };
                    steps.push(move_ms, &positions, false);
                    steps.push(hold_ms, &positions, true);
                }
            }
            Body::Chain(links) if depth < 8 => {
                for link in links {
                    if let Some(linked) = source.clips.get(link.clip) {
                        // A unit played "until stopped" plays once here: a motion ends.
                        for _ in 0..link.plays.max(1) {
                            play(source, linked, rate * link.speed, models, steps, depth + 1);
                        }
                    }
                }
            }
            Body::Chain(_) | Body::Samples { .. } => {}
        }
    }
}

/// The clips `selection` picks, onto DYNAMIXEL IDs.
pub fn build(source: &Source, selection: &Selection) -> Result<(Project, Report), BuildError> {
    let chosen = selected(source, selection)?;
    let mut dropped = source.dropped.clone();
    // Each channel whose key is an ID 0..=252, with the model its units are.
    let models: Vec<Option<(u8, u16)>> = source
        .channels
        .iter()
        .map(|channel| {
            let id: u8 = channel.key.parse().ok().filter(|id| *id <= 252)?;
            Some((id, model_of(channel)))
        })
        .collect();
    for (channel, model) in source.channels.iter().zip(&models) {
        if model.is_none() {
            dropped.push(format!("channel {:?}: not a DYNAMIXEL ID (0..=252)", channel.key));
        }
    }
    let servos: Vec<ServoSetup> = source
        .channels
        .iter()
        .zip(&models)
        .filter_map(|(channel, model)| {
            let (id, model_number) = (*model)?;
            Some(ServoSetup { id, name: channel.name.clone(), model_number, profile: None })
        })
        .collect();
    let mut motions = Vec::new();
    let mut converted = Vec::new();
    for index in chosen {
        let clip = &source.clips[index];
        if matches!(clip.body, Body::Samples { .. }) {
            dropped.push(format!("{:?}: sampled positions (convert it --to servo to fit them)", clip.name));
            continue;
        }
        let mut steps = Steps::new();
        play(source, clip, 1.0, &models, &mut steps, 0);
        if steps.steps.is_empty() {
            continue;
        }
        let name = clip.number.map_or_else(|| clip.name.clone(), |number| format!("{number} {}", clip.name));
        // Milliseconds of a motion: exact in f64.
        #[allow(clippy::cast_precision_loss)]
        let seconds = steps.ended_ms as f64 / 1000.0;
        converted.push(format!("motion {} {name:?}: {} steps, {seconds:.3} s", motions.len() + 1, steps.steps.len()));
        motions.push(Motion { name, steps: steps.steps });
    }
    let mut project = Project::empty(Family::Dynamixel);
    project.sections.set(Family::Dynamixel, DynamixelSection { servos, motions }.kept());
    Ok((project, Report { converted, approximated: Vec::new(), dropped, notes: source.notes.clone() }))
}
