//! A fourth family, for the tests only: the "echo" board — one servo, moved
//! live, that answers every move, with its own emulator. It proves the seam:
//! it plugs in by touching only the shared files `docs/ARCHITECTURE.md`
//! names (`tests::the_echo_family_touches_only_the_shared_files_named`): it
//! declares its `Family` constant and adds itself to the registries here.

mod board;
mod command;
mod link;
mod stage;

use std::time::Instant;

use serde::Deserialize;

use crate::project::{Edit, Family, Project};
use crate::ui::action::{Action, ActionOf, FamilyAction, Tab};
use crate::ui::board_link::{BoardLink, FamilyNotice, LinkStarter, StartError};
use crate::ui::family::{FamilyBoard, FamilyMemory, FamilyPad, FamilyPanels, FamilyPose, FamilyUi, Panel};
use crate::ui::i18n::Strings;
use crate::ui::layout::Layout;
use crate::ui::shell::{Shell, ShellView};
use link::{EchoHandle, Echoed, EmulatedEcho};

#[allow(non_upper_case_globals)]
impl Family {
    /// The test-only echo board: one servo, moved live, that answers every move.
    pub const Echo: Self = Self::named("echo", "Echo board");
}

// The registries: the family, after the three real ones, its project section,
// and its side of the editor.
inventory::submit! {
    crate::project::Registered { family: Family::Echo, rank: 4 }
}
inventory::submit! {
    crate::project::Section { family: Family::Echo, check: EchoSection::check, fresh: || serde_json::to_value(EchoSection::default()).unwrap_or_default() }
}

#[allow(non_upper_case_globals)]
impl Tab {
    /// The echo board's one panel.
    pub const Echo: Self = Self::named("Echo");
}

/// What an echo project keeps (its section of the project file, `"echo"`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct EchoSection {
    /// Where the servo rests, degrees (−90..=90).
    pub home_deg: i16,
}

impl EchoSection {
    /// What is wrong with a kept section, in the family's words.
    fn check(kept: &serde_json::Value) -> Vec<String> {
        match Self::deserialize(kept) {
            Ok(section) if (-90..=90).contains(&section.home_deg) => Vec::new(),
            Ok(section) => vec![format!("the echo servo's home {}° is outside −90..=90°", section.home_deg)],
            Err(error) => vec![format!("the echo section cannot be read: {error}")],
        }
    }

    /// The project's, or the default.
    fn of(project: &Project) -> Self {
        project.sections.read(Family::Echo).ok().flatten().unwrap_or_default()
    }
}

/// The echo board's panels' requests.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EchoAction {
    /// The servo to this angle (sent live when connected).
    Move(i16),
    /// Where the servo is becomes its home, kept in the project (one undo step).
    SetHome,
}

impl ActionOf for EchoAction {
    const FAMILY: Family = Family::Echo;

    fn moves_robot(&self) -> bool {
        matches!(self, Self::Move(_))
    }
}

/// The echo board's side of the editor.
#[derive(Debug, Default)]
pub struct EchoUi {
    /// Where the slider puts the servo.
    pub pose: i16,
    /// Where the board last said its servo is.
    pub echoed: Option<i16>,
    layout: Layout,
}

const PANELS: &[Panel] = &[Panel { tab: Tab::Echo, title: |_| "Echo", has_view: false }];

impl EchoUi {
    fn apply(&mut self, shell: &mut Shell<'_>, action: EchoAction) {
        match action {
            EchoAction::Move(deg) => {
                self.pose = deg.clamp(-90, 90);
                if let Some(board) = shell.link.as_ref().and_then(BoardLink::device::<EchoHandle>) {
                    board.move_to(self.pose);
                }
            }
            EchoAction::SetHome => {
                let section = EchoSection { home_deg: self.pose };
                let kept = serde_json::to_value(section).unwrap_or_default();
                shell.document.apply(Edit::SetSection(Family::Echo, kept), None);
            }
        }
    }
}

impl FamilyUi for EchoUi {
    fn family(&self) -> Family {
        Family::Echo
    }

    fn act(&mut self, shell: &mut Shell<'_>, action: Box<dyn FamilyAction>) {
        match action.into_any().downcast::<EchoAction>() {
            Ok(action) => self.apply(shell, *action),
            Err(_) => crate::ui::board_link::misrouted(Family::Echo, "an action", std::any::type_name::<EchoAction>()),
        }
    }
}

impl FamilyPanels for EchoUi {
    fn panels(&self) -> &'static [Panel] {
        PANELS
    }

    fn layout(&self) -> Layout {
        self.layout
    }

    fn layout_mut(&mut self) -> &mut Layout {
        &mut self.layout
    }

    fn ui(&mut self, ui: &mut egui::Ui, _tab: Tab, view: &ShellView<'_>, actions: &mut Vec<Action>) {
        ui.horizontal(|ui| {
            ui.label(format!("servo at {}°", self.pose));
            if ui.button("+10°").clicked() {
                actions.push(Action::family(EchoAction::Move(self.pose + 10)));
            }
            ui.label(format!("home {}°", EchoSection::of(view.project).home_deg));
            if ui.button("Set home").clicked() {
                actions.push(Action::family(EchoAction::SetHome));
            }
            if let Some(deg) = self.echoed {
                ui.label(format!("the board says {deg}°"));
            }
        });
    }
}

impl FamilyBoard for EchoUi {
    fn link_starter(&self, _baud: u32) -> LinkStarter {
        link::starter()
    }

    fn demo_link(&self, _project: &Project, waker: crate::link::Waker) -> Result<BoardLink, StartError> {
        link::demo_link(waker)
    }

    fn demo_connected(&self, _words: &Strings) -> &'static str {
        "connected to the demo echo board"
    }

    fn stop(&mut self, shell: &mut Shell<'_>) {
        if let Some(link) = shell.link.as_mut() {
            link.stop();
        }
        shell.report("the echo board stopped", false);
    }

    fn disconnected(&mut self) {
        self.echoed = None;
    }

    fn tick(&mut self, _shell: &mut Shell<'_>, _now: Instant) -> bool {
        false
    }

    fn notice(&mut self, _shell: &mut Shell<'_>, notice: FamilyNotice) {
        if let Some(Echoed(deg)) = notice.of(Family::Echo) {
            self.echoed = Some(*deg);
        }
    }
}

impl FamilyPad for EchoUi {}

impl FamilyPose for EchoUi {}

impl FamilyMemory for EchoUi {}

#[cfg(test)]
mod tests;
