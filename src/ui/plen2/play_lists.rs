//! PLEN2 play lists: motions queued with a number of plays (`#PU` … `#PO`).
//! The lists on the left, the selected list's entries on the right; only the
//! rows in view are laid out.

use crate::project::Edit;
use crate::project::plen2::{PlayEntry, PlayList, Plen2Project};
use crate::ui::action::Action;
use crate::ui::i18n::Strings;
use crate::ui::layout::{self, Layout, Pane};
use crate::ui::plen2::action::Plen2Action;
use crate::ui::plen2::captions::Plen2Words;
use crate::ui::rows;

/// The panel's own state: which list is open.
#[derive(Debug, Default)]
pub struct PlayListsPanel {
    selected: usize,
}

fn edit(project: &Plen2Project, change: impl FnOnce(&mut Plen2Project)) -> Action {
    let mut changed = project.clone();
    change(&mut changed);
    Action::Edit { edit: Edit::SetPlen2(Box::new(changed)), coalesce: Some("plen2 play lists".into()) }
}

impl PlayListsPanel {
    /// Draws the panel.
    pub fn ui(
        &mut self,
        ui: &mut egui::Ui,
        project: &Plen2Project,
        connected: bool,
        layout: &mut Layout,
        words: &Strings,
        actions: &mut Vec<Action>,
    ) {
        ui.horizontal(|ui| {
            ui.heading(words.play_lists);
            if ui.button(words.plen2().add_play_list).clicked() {
                let name = format!("{} {}", words.play_lists, project.play_lists.len() + 1);
                actions.push(edit(project, |p| p.play_lists.push(PlayList { name, entries: Vec::new() })));
                self.selected = project.play_lists.len();
            }
        });
        if project.play_lists.is_empty() {
            return;
        }
        self.selected = self.selected.min(project.play_lists.len() - 1);
        let selected = self.selected;
        let mut picked = None;
        layout::columns(ui, "play-lists", &mut layout.list_width, 140.0, |ui, pane| match pane {
            Pane::First => {
                rows::names(ui, "play-lists", project.play_lists.len(), |ui, index| {
                    let list = &project.play_lists[index];
                    let text = format!("{} ({})", list.name, list.entries.len());
                    if ui.selectable_label(index == selected, text).clicked() {
                        picked = Some(index);
                    }
                });
            }
            Pane::Second => self.editor(ui, project, connected, words, actions),
        });
        if let Some(index) = picked {
            self.selected = index;
        }
    }

    fn editor(
        &self,
        ui: &mut egui::Ui,
        project: &Plen2Project,
        connected: bool,
        words: &Strings,
        actions: &mut Vec<Action>,
    ) {
        let index = self.selected;
        let list = &project.play_lists[index];
        ui.horizontal(|ui| {
            let mut name = list.name.clone();
            if ui.text_edit_singleline(&mut name).changed() {
                actions.push(edit(project, |p| p.play_lists[index].name = name));
            }
            if ui
                .add_enabled(connected && !list.entries.is_empty(), egui::Button::new(words.plen2().play_on_robot))
                .on_hover_text("#RI, #PU…, #PO")
                .clicked()
            {
                actions.push(Action::family(Plen2Action::PlayList(index)));
            }
            if ui.button(words.plen2().add_entry).clicked() {
                let slot = project.motions.first().map_or(0, |m| m.slot);
                actions.push(edit(project, |p| p.play_lists[index].entries.push(PlayEntry { slot, plays: 1 })));
            }
            if ui.button(words.remove).clicked() {
                actions.push(edit(project, |p| {
                    p.play_lists.remove(index);
                }));
            }
        });
        let height = ui.available_height();
        rows::grid(ui, "play-list-entries", list.entries.len(), height, |ui, position| {
            let entry = &list.entries[position];
            let mut changed = *entry;
            ui.label(format!("{}", position + 1));
            let name = project.motions.iter().find(|m| m.slot == entry.slot).map_or("—", |m| m.name.as_str());
            let motions = &project.motions;
            let shown = format!("{} {name}", entry.slot);
            rows::combo(ui, ("plen2-entry", index, position), shown, &mut changed.slot, motions.len(), |i| {
                (motions[i].slot, format!("{} {}", motions[i].slot, motions[i].name))
            });
            ui.horizontal(|ui| {
                ui.label(words.plen2().plays);
                ui.add(egui::DragValue::new(&mut changed.plays));
            });
            if changed != *entry {
                actions.push(edit(project, |p| p.play_lists[index].entries[position] = changed));
            }
            if ui.small_button("×").on_hover_text(words.remove).clicked() {
                actions.push(edit(project, |p| {
                    p.play_lists[index].entries.remove(position);
                }));
            }
        });
    }
}
