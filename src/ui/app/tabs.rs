//! The tab shown in the middle of the window: the family's own panels, or
//! the packet log every family shares.

use super::StudioApp;
use crate::project::Family;
use crate::ui::action::{Action, Tab};
use crate::ui::app::ShellView;
use crate::ui::board_link::BoardLink;

impl StudioApp {
    /// Draws the current tab's panel, filling the space it is given.
    pub(super) fn tab_panel(&mut self, ui: &mut egui::Ui, actions: &mut Vec<Action>) {
        let family = self.document.project.family;
        let words = self.language.strings();
        if self.tab == Tab::Log {
            match &mut self.link {
                Some(link) => link.log.ui(ui, words),
                None => {
                    ui.label(words.not_connected);
                    if !BoardLink::supports(family) {
                        ui.label(self.language.family_not_in_build(family));
                    }
                }
            }
            return;
        }
        let view = ShellView {
            project: &self.document.project,
            revision: self.document.revision(),
            link: self.link.as_ref(),
            operation: self.operation.as_ref(),
            language: self.language,
        };
        match family {
            Family::Servo => self.servo.ui(ui, self.tab, &view, actions),
            Family::Plen2 => self.plen2.ui(ui, self.tab, &view, actions),
            Family::Rflex => self.rflex.ui(ui, self.tab, &view, actions),
        }
    }
}
