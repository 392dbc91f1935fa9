//! What a gamepad can do on a PLEN2: its axes move joints (within each
//! joint's limits, sent live, coalesced and paced as a slider is), its buttons
//! play the robot's motions, the project's play lists, or STOP.

use crate::gamepad::puppet::Cue;
use crate::project::gamepad::{AxisTarget, Fire};
use crate::project::plen2::{Joint, Plen2Project};
use crate::ui::action::Action;
use crate::ui::gamepad::PadTarget;
use crate::ui::i18n::Strings;
use crate::ui::plen2::action::Plen2Action;

/// Every joint, where the sliders have it.
pub fn targets(project: &Plen2Project, pose: &[i16; 18]) -> Vec<PadTarget> {
    Joint::ALL
        .iter()
        .zip(pose)
        .map(|(joint, tenths)| {
            let setting = super::joints::limits(project, *joint);
            PadTarget {
                target: AxisTarget::Joint(*joint),
                name: joint.name().to_string(),
                limits: (f64::from(setting.min_tenths_deg) / 10.0, f64::from(setting.max_tenths_deg) / 10.0),
                at: f64::from(*tenths) / 10.0,
            }
        })
        .collect()
}

/// Every motion of the project (by its slot), every play list, and STOP.
pub fn fires(project: &Plen2Project, words: &Strings) -> Vec<(Fire, String)> {
    let mut fires = vec![(Fire::Stop, words.stop.to_string())];
    fires.extend(
        project
            .motions
            .iter()
            .map(|motion| (Fire::Motion(motion.slot), format!("{} {} {}", words.slot, motion.slot, motion.name))),
    );
    fires.extend(
        project
            .play_lists
            .iter()
            .enumerate()
            .map(|(index, list)| (Fire::PlayList(index), format!("{} {} {}", words.play_lists, index + 1, list.name))),
    );
    fires
}

/// The PLEN2's action for a binding's cue.
pub fn cue(cue: Cue) -> Option<Action> {
    match cue {
        Cue::Move { target: AxisTarget::Joint(joint), degrees } => {
            // Within the joint's limits already (±90.0°): an i16 holds it in tenths.
            #[allow(clippy::cast_possible_truncation)]
            let tenths = (degrees * 10.0).round() as i16;
            Some(Action::family(Plen2Action::SetJoint { joint, tenths }))
        }
        Cue::Fire(Fire::Motion(slot)) => Some(Action::family(Plen2Action::PlayMotion(slot))),
        Cue::Fire(Fire::PlayList(index)) => Some(Action::family(Plen2Action::PlayList(index))),
        Cue::Fire(Fire::Stop) => Some(Action::Stop),
        _ => None,
    }
}
