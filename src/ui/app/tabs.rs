//! The tab shown in the middle of the window: the family's own panels, or
//! the packet log every family shares.

use super::StudioApp;
use crate::ui::action::{Action, Tab};

impl StudioApp {
    /// Draws the current tab's panel, filling the space it is given.
    pub(super) fn tab_panel(&mut self, ui: &mut egui::Ui, actions: &mut Vec<Action>) {
        let family = self.document.project.family;
        let words = self.language.strings();
        if self.window.tab == Tab::Gamepad {
            self.gamepad_panel(ui, actions);
            return;
        }
        if self.window.tab == Tab::Log {
            match &mut self.link {
                Some(link) => link.log.ui(ui, words),
                None => {
                    ui.label(words.not_connected);
                }
            }
            return;
        }
        let (view, family_ui, tab) = self.drawing(family);
        family_ui.ui(ui, tab, &view, actions);
    }
}
