//! What a gamepad can do on a servo board: its axes move servos (within each
//! servo's limits, sent live as a slider is), its buttons play the project's
//! actions, run the board's macros, or STOP.

use std::collections::BTreeMap;

use crate::gamepad::puppet::Cue;
use crate::project::ServoProject;
use crate::project::gamepad::{AxisTarget, Fire};
use crate::ui::action::Action;
use crate::ui::gamepad::PadTarget;
use crate::ui::i18n::Strings;
use crate::ui::servo::action::ServoAction;
use crate::ui::servo::captions::ServoWords;

/// Every servo of the project, where the sliders have it.
pub fn targets(project: &ServoProject, pose: &BTreeMap<u8, i16>) -> Vec<PadTarget> {
    project
        .servos
        .iter()
        .map(|servo| PadTarget {
            target: AxisTarget::Servo(servo.id),
            name: format!("#{} {}", servo.id, servo.caption),
            limits: (f64::from(servo.min_deg), f64::from(servo.max_deg)),
            at: f64::from(pose.get(&servo.id).copied().unwrap_or(servo.home_deg)),
        })
        .collect()
}

/// Every action and macro of the project, and STOP.
pub fn fires(project: &ServoProject, words: &Strings) -> Vec<(Fire, String)> {
    let mut fires = vec![(Fire::Stop, words.stop.to_string())];
    fires.extend(
        project
            .actions
            .iter()
            .map(|action| (Fire::Action(action.id), format!("{} {} {}", words.actions, action.id, action.caption))),
    );
    fires.extend(
        project
            .macros
            .iter()
            .map(|run| (Fire::Macro(run.id), format!("{} {} {}", words.servo().macro_word, run.id, run.caption))),
    );
    fires
}

/// The servo board's action for a binding's cue.
pub fn cue(cue: Cue) -> Option<Action> {
    match cue {
        Cue::Move { target: AxisTarget::Servo(servo_id), degrees } => {
            // Within the servo's limits already; an i16 holds any servo angle.
            #[allow(clippy::cast_possible_truncation)]
            let degree = degrees.round() as i16;
            Some(Action::family(ServoAction::SetPose { servo_id, degree }))
        }
        Cue::Fire(Fire::Action(id)) => Some(Action::family(ServoAction::PlayAction(id))),
        Cue::Fire(Fire::Macro(id)) => Some(Action::family(ServoAction::RunMacro(id))),
        Cue::Fire(Fire::Stop) => Some(Action::Stop),
        _ => None,
    }
}
