//! The editor's gamepad: read once a frame and handed to the family shown —
//! its own use (a base's stick), its bindings (the puppeteer), and the
//! binding being made by pressing or moving — and the Gamepad tab.

use super::*;
use crate::gamepad::{Gone, PadUpdate};
use crate::ui::action::Bind;
use crate::ui::gamepad::PadPanel;

impl StudioApp {
    /// Reads `path` as the gamepad (None: lets it go, stopping what it drove).
    pub(super) fn use_gamepad(&mut self, path: Option<PathBuf>) {
        if self.desks.pad.in_use() {
            // Letting go is the gamepad going away: whatever it drove stops.
            let now = Instant::now();
            let gone = [(now, PadUpdate::Gone(Gone::Ended))];
            let family = self.document.project.family;
            let tab = self.window.tab;
            let (mut shell, family_ui) = self.parts(family);
            family_ui.pad_drive(&mut shell, now, &gone, false, tab);
        }
        if let Err(error) = self.desks.pad.choose(path, &self.window.waker) {
            self.report(error, true);
        }
    }

    /// Starts (or stops) waiting for a button or an axis to bind.
    pub(super) fn bind_pad(&mut self, bind: Option<Bind>) {
        self.desks.pad.binding =
            bind.filter(|_| self.desks.pad.in_use()).map(|bind| (bind, self.desks.pad.state.clone()));
    }

    /// Takes what the gamepad sent and lets it act; `focused`: whether the
    /// window has the focus (a gamepad acts only then). Whether the window
    /// should keep repainting.
    pub(super) fn feed_gamepad(&mut self, now: Instant, focused: bool) -> bool {
        let (updates, gone) = self.desks.pad.take();
        if !self.desks.pad.in_use() && updates.is_empty() {
            // No gamepad: nothing to do (and nothing to work out) this frame.
            return false;
        }
        let family = self.document.project.family;
        let armed = focused && !self.desks.pad.test_mode && self.desks.pad.binding.is_none();
        let tab = self.window.tab;
        let mapping = self.document.project.gamepad.of(family).clone();
        let mut actions = Vec::new();
        let (targets, fires) = {
            let family_ui = self.family_ui(family);
            (family_ui.pad_targets(&self.document.project), family_ui.pad_fires(&self.document.project, self.words()))
        };
        if !updates.is_empty() {
            actions.extend(self.desks.pad.bound(family, &mapping, &targets, &fires));
        }
        let cues = self.desks.pad.cues(&mapping, now, &updates, &targets);
        let (mut shell, family_ui) = self.parts(family);
        let mut moving = family_ui.pad_drive(&mut shell, now, &updates, armed, tab);
        if armed {
            actions.extend(cues.into_iter().filter_map(|cue| family_ui.pad_cue(cue)));
        }
        moving |= self.desks.pad.moving(&mapping);
        for action in actions {
            self.apply(action);
        }
        if let Some(why) = gone {
            self.say(|language| format!("{}: {why}", language.strings().msg_pad_gone), true);
        }
        moving
    }

    /// The Gamepad tab.
    pub(super) fn gamepad_panel(&mut self, ui: &mut egui::Ui, actions: &mut Vec<Action>) {
        let family = self.document.project.family;
        let words = self.language.strings();
        let family_ui = self.family_ui(family);
        let targets = family_ui.pad_targets(&self.document.project);
        let mapping = self.document.project.gamepad.of(family);
        // What a button can fire is listed only for the buttons bound or being bound (a
        // large project's thousand actions are not named every frame for nothing).
        let fires = if mapping.buttons.is_empty() && self.desks.pad.binding.is_none() {
            Vec::new()
        } else {
            family_ui.pad_fires(&self.document.project, words)
        };
        let view = PadPanel {
            family,
            mapping,
            targets: &targets,
            fires: &fires,
            reserved: family_ui.pad_reserved(),
            waker: &self.window.waker,
        };
        crate::ui::gamepad::panel(ui, &mut self.desks.pad, &view, words, actions);
    }
}
