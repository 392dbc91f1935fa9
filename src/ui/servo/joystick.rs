//! Joystick mapping: tables and their buttons (caption, press / long-press /
//! release macros, uninterruptible), the active table, live button events, and
//! "press a button to pick it".

use crate::device::servo::ButtonEvent;
use crate::project::{Button, Edit, JoystickTable, ServoProject, next_free_id};
use crate::ui::action::Action;
use crate::ui::i18n::Strings;
use crate::ui::layout::{self, Layout, Pane};
use crate::ui::rows;
use crate::ui::servo::action::ServoAction;
use crate::ui::servo::captions::ServoWords;

/// What the panel draws besides the project.
#[derive(Debug)]
pub struct JoystickView<'a> {
    /// The project.
    pub project: &'a ServoProject,
    /// Button events seen, newest last.
    pub events: &'a [(u32, ButtonEvent)],
    /// The button picked on the remote (highlighted).
    pub picked: Option<u32>,
    /// Waiting for a button press to pick.
    pub picking: bool,
    /// A board is connected.
    pub connected: bool,
}

/// The panel's own state: which table is open.
#[derive(Debug, Default)]
pub struct JoystickPanel {
    selected: usize,
}

fn event_name(event: ButtonEvent, words: &Strings) -> &'static str {
    match event {
        ButtonEvent::Press => words.servo().event_press,
        ButtonEvent::LongPress => words.servo().event_long_press,
        ButtonEvent::Release => words.servo().event_release,
    }
}

impl JoystickPanel {
    /// The table shown, if any.
    pub fn selected(&self, project: &ServoProject) -> Option<usize> {
        (!project.joystick_tables.is_empty()).then(|| self.selected.min(project.joystick_tables.len() - 1))
    }

    /// Draws the panel: the tables (and the live button events under them)
    /// beside the selected table's buttons, which fill the height.
    pub fn ui(
        &mut self,
        ui: &mut egui::Ui,
        view: &JoystickView<'_>,
        layout: &mut Layout,
        words: &Strings,
        actions: &mut Vec<Action>,
    ) {
        let project = view.project;
        ui.horizontal(|ui| {
            ui.heading(words.joystick);
            if ui.button(words.servo().add_table).clicked() {
                let id = next_free_id(project.joystick_tables.iter().map(|t| t.id));
                let table = JoystickTable { id, caption: format!("{} {id}", words.servo().table), buttons: Vec::new() };
                actions.push(Action::Edit { edit: Edit::AddTable(table), coalesce: None });
                self.selected = project.joystick_tables.len();
            }
        });
        let Some(index) = self.selected(project) else {
            ui.label(words.servo().no_tables);
            return;
        };
        self.selected = index;
        let selected = &mut self.selected;
        layout::columns(ui, "joystick", &mut layout.list_width, 140.0, |ui, pane| match pane {
            Pane::First => {
                let count = project.joystick_tables.len();
                // The tables take what the live events (a dozen lines) leave.
                let events = ui.text_style_height(&egui::TextStyle::Monospace) * 13.0 + 24.0;
                ui.allocate_ui(egui::vec2(ui.available_width(), (ui.available_height() - events).max(80.0)), |ui| {
                    rows::names(ui, "joystick-tables", count, |ui, position| {
                        let table = &project.joystick_tables[position];
                        let active = if project.active_table == Some(table.id) { " ★" } else { "" };
                        let text = format!("{} {}{active}", table.id, table.caption);
                        if ui.selectable_label(position == index, text).clicked() {
                            *selected = position;
                        }
                    });
                });
                ui.separator();
                ui.label(words.servo().live_events);
                for (button_id, event) in view.events.iter().rev().take(12) {
                    ui.monospace(format!("0x{button_id:08x} {}", event_name(*event, words)));
                }
            }
            Pane::Second => Self::table_editor(ui, view, index, words, actions),
        });
    }

    fn table_editor(
        ui: &mut egui::Ui,
        view: &JoystickView<'_>,
        index: usize,
        words: &Strings,
        actions: &mut Vec<Action>,
    ) {
        let project = view.project;
        let table = &project.joystick_tables[index];
        Self::table_header(ui, view, index, words, actions);
        let heading = [
            words.button,
            words.caption,
            words.servo().on_press,
            words.servo().on_long_press,
            words.servo().on_release,
            words.uninterruptible,
            "",
        ];
        let height = ui.available_height();
        rows::table(ui, "buttons", &heading, table.buttons.len(), height, |row, position| {
            Self::button_row(row, position, view, index, words, actions);
        });
    }

    /// The table's caption, Active and Remove; Pick a button and Add button.
    fn table_header(
        ui: &mut egui::Ui,
        view: &JoystickView<'_>,
        index: usize,
        words: &Strings,
        actions: &mut Vec<Action>,
    ) {
        let project = view.project;
        let table = &project.joystick_tables[index];
        let set = |table: JoystickTable, key: Option<String>| set_table(index, table, key);
        ui.horizontal(|ui| {
            let label = ui.label(format!("{} {}", words.servo().table, table.id));
            let mut caption = table.caption.clone();
            if ui.text_edit_singleline(&mut caption).labelled_by(label.id).changed() {
                actions
                    .push(set(JoystickTable { caption, ..table.clone() }, Some(format!("table {} caption", table.id))));
            }
            let mut active = project.active_table == Some(table.id);
            if ui.checkbox(&mut active, words.servo().active).changed() {
                actions.push(Action::Edit { edit: Edit::SetActiveTable(active.then_some(table.id)), coalesce: None });
            }
            if ui.button(words.remove).clicked() {
                actions.push(Action::Edit { edit: Edit::RemoveTable { index }, coalesce: None });
            }
        });
        ui.horizontal(|ui| {
            let pick_text = if view.picking { words.servo().waiting_for_button } else { words.servo().pick_button };
            if ui.add_enabled(view.connected, egui::Button::new(pick_text).selected(view.picking)).clicked() {
                actions.push(Action::family(ServoAction::PickButton { table_index: (!view.picking).then_some(index) }));
            }
            if ui.button(words.servo().add_button).clicked() {
                let used: Vec<i32> = table.buttons.iter().filter_map(|b| i32::try_from(b.id).ok()).collect();
                let id = u32::try_from(next_free_id(used)).unwrap_or(1);
                let mut more = table.clone();
                more.buttons.push(Button {
                    id,
                    caption: String::new(),
                    press_macro: None,
                    long_press_macro: None,
                    release_macro: None,
                    uninterruptible: false,
                });
                actions.push(set(more, None));
            }
        });
    }

    /// One button's row: its id, caption, the three macros it runs, uninterruptible, remove.
    fn button_row(
        row: &mut egui_extras::TableRow<'_, '_>,
        position: usize,
        view: &JoystickView<'_>,
        index: usize,
        words: &Strings,
        actions: &mut Vec<Action>,
    ) {
        let project = view.project;
        let table = &project.joystick_tables[index];
        let set = |table: JoystickTable, key: Option<String>| set_table(index, table, key);
        let button = &table.buttons[position];
        let with = |changed: Button, key: Option<String>| {
            let mut table = table.clone();
            table.buttons[position] = changed;
            set(table, key)
        };
        let mut row_id = egui::Id::NULL;
        row.col(|ui| {
            let id_text = format!("0x{:08x}", button.id);
            let label = if view.picked == Some(button.id) {
                ui.label(egui::RichText::new(format!("→ {id_text}")).strong())
            } else {
                ui.monospace(id_text)
            };
            row_id = label.id;
        });
        row.col(|ui| {
            let mut caption = button.caption.clone();
            if ui.add(egui::TextEdit::singleline(&mut caption).desired_width(140.0)).labelled_by(row_id).changed() {
                actions.push(with(
                    Button { caption, ..button.clone() },
                    Some(format!("table {} button {} caption", table.id, button.id)),
                ));
            }
        });
        for (slot, current) in [(0, button.press_macro), (1, button.long_press_macro), (2, button.release_macro)] {
            row.col(|ui| {
                if let Some(chosen) = macro_cell(ui, project, (position, slot, current), row_id) {
                    let mut changed = button.clone();
                    match slot {
                        0 => changed.press_macro = chosen,
                        1 => changed.long_press_macro = chosen,
                        _ => changed.release_macro = chosen,
                    }
                    actions.push(with(changed, None));
                }
            });
        }
        row.col(|ui| {
            let mut uninterruptible = button.uninterruptible;
            if ui.checkbox(&mut uninterruptible, "").labelled_by(row_id).changed() {
                actions.push(with(Button { uninterruptible, ..button.clone() }, None));
            }
        });
        row.col(|ui| {
            if ui.button("×").on_hover_text(words.remove).clicked() {
                let mut fewer = table.clone();
                fewer.buttons.remove(position);
                actions.push(set(fewer, None));
            }
        });
    }
}

/// A button's macro for one of its events ("—" for none, then every macro); the one picked when it changes.
fn macro_cell(
    ui: &mut egui::Ui,
    project: &ServoProject,
    (position, slot, current): (usize, usize, Option<i32>),
    row_id: egui::Id,
) -> Option<Option<i32>> {
    let macro_text = |id: Option<i32>| match id {
        None => "—".to_string(),
        Some(id) => project.macro_by_id(id).map_or_else(|| format!("{id} ?"), |m| format!("{} {}", m.id, m.caption)),
    };
    let mut chosen = current;
    let all = &project.macros;
    // "—" (none) first, then every macro.
    rows::combo(ui, ("macro", position, slot), macro_text(current), &mut chosen, all.len() + 1, |i| {
        match i.checked_sub(1).and_then(|i| all.get(i)) {
            Some(item) => (Some(item.id), format!("{} {}", item.id, item.caption)),
            None => (None, "—".to_string()),
        }
    })
    .labelled_by(row_id);
    (chosen != current).then_some(chosen)
}

/// Replaces the table at `index` (edits sharing `key` form one undo step).
fn set_table(index: usize, table: JoystickTable, key: Option<String>) -> Action {
    Action::Edit { edit: Edit::SetTable { index, table }, coalesce: key }
}
