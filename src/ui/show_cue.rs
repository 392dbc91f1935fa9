//! How each family's kinds of cue read and are chosen in the show window,
//! registered by the family beside its side of the editor
//! (`ui/<family>/show_cue.rs`): the show window (`ui/show/cues.rs`, its lanes
//! and its log) asks here and names no family. It sits below the families'
//! folders, with the few words their cues are said in.

use crate::project::{Family, Project};
use crate::show::Start;

/// The words a family's cues are said in, in the interface's language.
#[derive(Clone, Copy, Debug)]
pub struct CueWords {
    /// "macro".
    pub macro_word: &'static str,
    /// "motion".
    pub motion_word: &'static str,
    /// "drive".
    pub drive_word: &'static str,
}

/// How a family's kinds of cue read and are chosen in the show window,
/// registered by the family beside its side of the editor
/// (`ui/<family>/show_cue.rs`). A family's own kind of cue
/// (`Start::Family`) with none registered reads as its kind and its number,
/// and is set as a number (`ui/show/cues.rs`).
#[derive(Debug)]
pub struct CueUi {
    /// The family.
    pub family: Family,
    /// What `start` starts, in these words, named as `project` names it
    /// when it is known (its macro's caption); none: not a kind of its.
    pub caption: fn(&Start, Option<&Project>, &CueWords) -> Option<String>,
    /// Chooses what a cue (number, label) of a device holding `project`
    /// starts, among what it holds; `start` is of a kind the family takes.
    pub choose: fn(&mut egui::Ui, (usize, egui::Id), &mut Start, &Project, &CueWords),
}

inventory::collect!(CueUi);

/// Chooses `value` among what a device stores (`items`: each with its
/// caption), as a cue's (number, label) combo box; `shown`: the one now.
pub fn stored_choice<T: PartialEq>(
    ui: &mut egui::Ui,
    (index, named): (usize, egui::Id),
    value: &mut T,
    shown: String,
    items: impl IntoIterator<Item = (T, String)>,
) {
    egui::ComboBox::from_id_salt(("cue-start", index))
        .selected_text(shown)
        .width(200.0)
        .show_ui(ui, |ui| {
            for (item, caption) in items {
                ui.selectable_value(value, item, caption);
            }
        })
        .response
        .labelled_by(named);
}

/// `family`'s, if it registered one.
pub fn of(family: Family) -> Option<&'static CueUi> {
    every().find(|entry| entry.family == family)
}

/// Every family's, as each registered it.
pub fn every() -> impl Iterator<Item = &'static CueUi> {
    inventory::iter::<CueUi>.into_iter()
}
