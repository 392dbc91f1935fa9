//! A PLEN2's cues in the show window: each starts the motion in one of its
//! slots, chosen by slot and name.

use crate::project::{Family, Project};
use crate::show::Start;
use crate::ui::show_cue::{CueUi, CueWords, stored_choice};

inventory::submit! {
    CueUi { family: Family::Plen2, caption, choose }
}

/// "motion 2 bow" (without the name when the motion is not known).
fn caption(start: &Start, project: Option<&Project>, words: &CueWords) -> Option<String> {
    let Start::Slot(slot) = *start else { return None };
    let motion = project.and_then(|project| project.plen2.motions.iter().find(|m| m.slot == slot));
    let name = motion.map(|m| m.name.as_str()).unwrap_or_default();
    Some(format!("{} {slot} {name}", words.motion_word).trim_end().to_string())
}

/// One of the project's motions.
fn choose(ui: &mut egui::Ui, cue: (usize, egui::Id), start: &mut Start, project: &Project, words: &CueWords) {
    let Start::Slot(slot) = start else { return };
    let shown = caption(&Start::Slot(*slot), Some(project), words).unwrap_or_default();
    let items = project.plen2.motions.iter().map(|m| (m.slot, format!("{} {} {}", words.motion_word, m.slot, m.name)));
    stored_choice(ui, cue, slot, shown, items);
}
