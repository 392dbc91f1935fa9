//! A servo board's cues in the show window: each starts one of its macros,
//! chosen by id and caption.

use crate::project::{Family, Project};
use crate::show::Start;
use crate::ui::show_cue::{CueUi, CueWords, stored_choice};

inventory::submit! {
    CueUi { family: Family::Servo, caption, choose }
}

/// "macro 3 wave" (without the caption when the macro is not known).
fn caption(start: &Start, project: Option<&Project>, words: &CueWords) -> Option<String> {
    let Start::Macro(id) = *start else { return None };
    let caption = project.and_then(|project| project.servo.macro_by_id(id)).map(|m| m.caption.as_str());
    Some(format!("{} {id} {}", words.macro_word, caption.unwrap_or_default()).trim_end().to_string())
}

/// One of the project's macros.
fn choose(ui: &mut egui::Ui, cue: (usize, egui::Id), start: &mut Start, project: &Project, words: &CueWords) {
    let Start::Macro(id) = start else { return };
    let shown = caption(&Start::Macro(*id), Some(project), words).unwrap_or_default();
    let items =
        project.servo.macros.iter().map(|item| (item.id, format!("{} {} {}", words.macro_word, item.id, item.caption)));
    stored_choice(ui, cue, id, shown, items);
}
