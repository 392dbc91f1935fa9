//! The editor window's chrome around the panels: the toolbar, STOP drawn
//! above every window, the status line.

use super::{STOP_MARGIN, STOP_WIDTH, StudioApp};
use crate::ui::action::{Action, Tab};
use crate::ui::i18n::Language;

impl StudioApp {
    /// The toolbar: File and Settings, undo / redo, the language, STOP and
    /// the family's buttons; the connection bar; the tabs.
    pub(super) fn toolbar(&mut self, ui: &mut egui::Ui, actions: &mut Vec<Action>) {
        let words = self.language.strings();
        ui.horizontal(|ui| {
            self.file_menu(ui, actions);
            self.settings_menu(ui, actions);
            ui.separator();
            if ui.add_enabled(self.document.can_undo(), egui::Button::new(words.undo)).clicked() {
                actions.push(Action::Undo);
            }
            if ui.add_enabled(self.document.can_redo(), egui::Button::new(words.redo)).clicked() {
                actions.push(Action::Redo);
            }
            ui.separator();
            let mut language = self.language;
            let language_label = ui.label(words.language);
            let picked = egui::ComboBox::from_id_salt("language").selected_text(language.name()).show_ui(ui, |ui| {
                for option in Language::ALL {
                    ui.selectable_value(&mut language, option, option.name());
                }
            });
            picked.response.labelled_by(language_label.id);
            if language != self.language {
                actions.push(Action::SetLanguage(language));
            }
            ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
                // STOP (and Resume) are drawn over everything at the end of the frame
                // (`stop_on_top`): here their place is kept, so nothing else is put there.
                let (kept, _) = ui.allocate_exact_size(egui::vec2(STOP_WIDTH, 26.0), egui::Sense::hover());
                self.window.stop_top = kept.min.y;
                let (view, family_ui, _) = self.drawing(self.document.project.family);
                family_ui.toolbar(ui, &view, actions);
            });
        });
        let status = self.link_status();
        let family = self.document.project.family;
        let (ports, language) = (std::mem::take(&mut self.links.ports), self.language);
        let mut bar = std::mem::take(&mut self.links.bar);
        let (view, family_ui, _) = self.drawing(family);
        bar.ui(ui, (&status, &ports, language), actions, |ui, actions| {
            family_ui.connection_extras(ui, &view, actions);
        });
        (self.links.ports, self.links.bar) = (ports, bar);
        ui.horizontal(|ui| {
            let family_ui = self.family_ui(family);
            let mut tab = self.window.tab;
            // Only the panels that apply to the document's family are offered.
            for option in self.tabs(family) {
                let title = match option {
                    Tab::Log => words.packet_log,
                    Tab::Gamepad => words.gamepad,
                    _ => family_ui.tab_title(option, words),
                };
                ui.selectable_value(&mut tab, option, title);
            }
            if tab != self.window.tab {
                actions.push(Action::ShowTab(tab));
            }
            if ![Tab::Log, Tab::Gamepad].contains(&self.window.tab) && family_ui.has_view(self.window.tab) {
                ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
                    let mut open = family_ui.layout().view_open;
                    if ui.checkbox(&mut open, family_ui.view_caption(words)).changed() {
                        actions.push(Action::ShowView(open));
                    }
                });
            }
        });
    }

    /// STOP — and Resume while STOP holds — in a layer above every window,
    /// popup and dialog (which are drawn below it), at the toolbar's right
    /// end: whole and clickable whatever else is open.
    pub(super) fn stop_on_top(&mut self, ctx: &egui::Context, actions: &mut Vec<Action>) {
        let words = self.language.strings();
        let stopped = self.stopped();
        // At the window's right edge, level with the toolbar, whatever the
        // toolbar's own width: STOP never moves and is never pushed off the
        // window; Resume appears to its left while STOP holds.
        let right = ctx.content_rect().max.x - STOP_MARGIN;
        let at = egui::pos2(right - STOP_WIDTH, self.window.stop_top);
        let mut drawn = egui::Rect::NOTHING;
        egui::Area::new(egui::Id::unique("STOP")).order(egui::Order::Tooltip).fixed_pos(at).show(ctx, |ui| {
            ui.set_width(STOP_WIDTH);
            ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
                let stop = egui::Button::new(
                    egui::RichText::new(format!("■ {}", words.stop)).strong().size(18.0).color(egui::Color32::WHITE),
                )
                .fill(egui::Color32::from_rgb(200, 30, 30));
                let stop = ui.add(stop).on_hover_text("Esc");
                if stop.clicked() {
                    actions.push(Action::Stop);
                }
                drawn = stop.rect;
                if stopped {
                    let resume = ui.button(self.language.word("strings.resume"));
                    if resume.clicked() {
                        actions.push(Action::Resume);
                    }
                    drawn = drawn.union(resume.rect);
                }
            });
        });
        self.window.stop_rect = Some(drawn);
    }

    /// The status line.
    pub(super) fn status_line(&self, ui: &mut egui::Ui) {
        match &self.status {
            Some(line) if line.is_error => {
                ui.colored_label(ui.visuals().error_fg_color, &line.text);
            }
            Some(line) => {
                ui.label(&line.text);
            }
            None => {
                ui.label("");
            }
        }
    }
}
