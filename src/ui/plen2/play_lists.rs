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
            let name_label = ui.label(words.name);
            if ui.text_edit_singleline(&mut name).labelled_by(name_label.id).changed() {
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
            let place = ui.label(format!("{}", position + 1));
            let name = project.motions.iter().find(|m| m.slot == entry.slot).map_or("—", |m| m.name.as_str());
            let motions = &project.motions;
            let shown = format!("{} {name}", entry.slot);
            rows::combo(ui, ("plen2-entry", index, position), shown, &mut changed.slot, motions.len(), |i| {
                (motions[i].slot, format!("{} {}", motions[i].slot, motions[i].name))
            })
            .labelled_by(place.id);
            ui.horizontal(|ui| {
                let plays = ui.label(words.plen2().plays);
                ui.add(egui::DragValue::new(&mut changed.plays)).labelled_by(plays.id);
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

#[cfg(test)]
mod tests {
    use egui_kittest::Harness;
    use egui_kittest::kittest::Queryable;

    use super::*;
    use crate::project::plen2::Motion;
    use crate::ui::i18n::Language;

    struct Panel {
        panel: PlayListsPanel,
        project: Plen2Project,
        connected: bool,
        actions: Vec<Action>,
    }

    fn panel(project: Plen2Project, connected: bool) -> Harness<'static, Panel> {
        let state = Panel { panel: PlayListsPanel::default(), project, connected, actions: Vec::new() };
        Harness::builder()
            .with_size(egui::vec2(900.0, 500.0))
            .with_context_setup(crate::ui::fonts::install)
            .build_ui_state(
                |ui, state: &mut Panel| {
                    let mut layout = Layout::default();
                    let words = Language::English.strings();
                    state.panel.ui(ui, &state.project, state.connected, &mut layout, words, &mut state.actions);
                },
                state,
            )
    }

    fn robot() -> Plen2Project {
        let wave = Motion { slot: 7, name: "wave".into(), frames: Vec::new(), loop_range: None, jump_slot: None };
        let list = PlayList { name: "show".into(), entries: vec![PlayEntry { slot: 7, plays: 2 }] };
        Plen2Project { motions: vec![wave], play_lists: vec![list], ..Plen2Project::default() }
    }

    /// The project the last edit asked for.
    fn edited(harness: &Harness<'static, Panel>) -> Plen2Project {
        match harness.state().actions.last() {
            Some(Action::Edit { edit: Edit::SetPlen2(project), coalesce }) => {
                assert_eq!(coalesce.as_deref(), Some("plen2 play lists"));
                (**project).clone()
            }
            other => panic!("an edit of the play lists, not {other:?}"),
        }
    }

    #[test]
    fn a_list_shows_its_motions_by_slot_and_name_and_grows_by_the_first_motion() {
        let mut harness = panel(robot(), false);
        harness.run();
        assert!(harness.query_by_label("show (1)").is_some(), "the list with its length");
        assert!(harness.query(egui_kittest::kittest::By::new().value("7 wave")).is_some(), "an entry names its motion");
        harness.get_by_label("Add motion").click();
        harness.run();
        assert_eq!(
            edited(&harness).play_lists[0].entries,
            [PlayEntry { slot: 7, plays: 2 }, PlayEntry { slot: 7, plays: 1 }]
        );
    }

    #[test]
    fn play_on_robot_needs_a_robot_and_a_new_list_is_added_empty() {
        let mut harness = panel(robot(), false);
        harness.run();
        harness.get_by_label("Play on robot").click();
        harness.run();
        assert!(harness.state().actions.is_empty(), "not connected: nothing to play on");
        harness.state_mut().connected = true;
        harness.run();
        harness.get_by_label("Play on robot").click();
        harness.run();
        assert_eq!(harness.state().actions, [Action::family(Plen2Action::PlayList(0))]);
        harness.get_by_label("Add play list").click();
        harness.run();
        let added = &edited(&harness).play_lists[1];
        assert_eq!((added.name.as_str(), added.entries.len()), ("Play lists 2", 0));
    }
}
