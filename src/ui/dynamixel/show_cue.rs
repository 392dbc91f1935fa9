//! A DYNAMIXEL bus's cues in the show window: each streams one of the
//! project's motions, chosen by number and name.

use crate::project::dynamixel::DynamixelSection;
use crate::project::{Family, Project};
use crate::show::Start;
use crate::show::family::FamilyCue;
use crate::ui::show_cue::{CueUi, CueWords, stored_choice};

inventory::submit! {
    CueUi { family: Family::Dynamixel, caption, choose }
}

/// The motion number a cue of its kind takes (from 1).
fn number(start: &Start) -> Option<usize> {
    let Start::Family(cue) = start else { return None };
    // Whole numbers from 1: a motion's number.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    (cue.kind == "motion" && cue.value >= 1.0 && cue.value.fract() == 0.0).then_some(cue.value as usize)
}

/// "motion 2 wave 揮手" (without the name when the motion is not known).
fn caption(start: &Start, project: Option<&Project>, words: &CueWords) -> Option<String> {
    let number = number(start)?;
    let section = project.map(DynamixelSection::of).unwrap_or_default();
    let name = section.motions.get(number - 1).map(|motion| motion.name.clone()).unwrap_or_default();
    Some(format!("{} {number} {name}", words.motion_word).trim_end().to_string())
}

/// One of the project's motions.
fn choose(ui: &mut egui::Ui, cue: (usize, egui::Id), start: &mut Start, project: &Project, words: &CueWords) {
    let Some(mut chosen) = number(start) else { return };
    let shown = caption(start, Some(project), words).unwrap_or_default();
    let section = DynamixelSection::of(project);
    let items = section
        .motions
        .iter()
        .enumerate()
        .map(|(index, motion)| (index + 1, format!("{} {} {}", words.motion_word, index + 1, motion.name)));
    stored_choice(ui, cue, &mut chosen, shown, items);
    #[allow(clippy::cast_precision_loss)]
    if let Ok(cue) = FamilyCue::named("motion", chosen as f64) {
        *start = Start::Family(cue);
    }
}
