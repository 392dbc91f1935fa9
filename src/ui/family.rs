//! The seam between the shell and a board family's side of the editor. The
//! shell (`ui::app`) knows families only through [`FamilyUi`]: their tabs and
//! panels, the pickers they add to the connection bar, what they say about a
//! connected board, what they do when STOP is pressed, a link is made or
//! lost, a document is replaced, time passes or their operation ends.
//! Each family's own actions reach it through its [`Action`] variant.

use std::time::{Duration, Instant};

use crate::gamepad::PadUpdate;
use crate::gamepad::puppet::Cue;
use crate::link::Waker;
use crate::project::LivePose;
use crate::project::gamepad::Fire;
use crate::project::{Family, Project};
use crate::ui::action::{Action, FamilyAction, Tab};
use crate::ui::board_link::{BoardLink, FamilyNotice, LinkStarter, StartError};
use crate::ui::gamepad::PadTarget;
use crate::ui::i18n::Strings;
use crate::ui::layout::Layout;
use crate::ui::remembered::Remembered;
use crate::ui::shell::StatusLine;
use crate::ui::shell::{Shell, ShellView};
use crate::ui::sound::follow::SoundFollower;

/// One of a family's tabs.
#[derive(Clone, Copy, Debug)]
pub struct Panel {
    /// The tab.
    pub tab: Tab,
    /// Its title.
    pub title: fn(&Strings) -> &'static str,
    /// Whether the robot's preview (or a base's world view) is beside it.
    pub has_view: bool,
}

/// A board family's side of the editor: what it is and its own actions,
/// with each capability the shell asks of it a trait of its own — its
/// panels, its board, the gamepad, the live pose, what it remembers — and
/// what cross-family panels ask of it (the sound's follow).
pub trait FamilyUi: std::any::Any + FamilyPanels + FamilyBoard + FamilyPad + FamilyPose + FamilyMemory {
    /// The family it edits.
    fn family(&self) -> Family;

    /// A new document was opened in the editor.
    fn document_replaced(&mut self, _project: &Project) {}

    /// Applies one of its own actions (see [`Action::family`]).
    fn act(&mut self, shell: &mut Shell<'_>, action: Box<dyn FamilyAction>);

    /// How the sound's loudness moves one of its axes (None: it has none, as a base).
    fn sound_follower(&self) -> Option<&dyn SoundFollower> {
        None
    }
}

/// A family's panels: its tabs, how they are laid out and drawn, its toolbar buttons.
pub trait FamilyPanels {
    /// Its own tabs, in order (the shell adds the packet log); the first is
    /// where a switch to the family lands.
    fn panels(&self) -> &'static [Panel];

    /// Its own tabs, in order.
    fn tabs(&self) -> Vec<Tab> {
        self.panels().iter().map(|panel| panel.tab).collect()
    }

    /// A tab's title.
    fn tab_title(&self, tab: Tab, words: &Strings) -> &'static str {
        self.panels().iter().find(|panel| panel.tab == tab).map_or(words.packet_log, |panel| (panel.title)(words))
    }

    /// Whether the tab has the robot's preview (or a base's world view) beside it.
    fn has_view(&self, tab: Tab) -> bool {
        self.panels().iter().any(|panel| panel.tab == tab && panel.has_view)
    }

    /// The caption of the checkbox that shows or hides that view.
    fn view_caption(&self, words: &Strings) -> &'static str {
        words.show_preview
    }

    /// How its panels are laid out (remembered).
    fn layout(&self) -> Layout;

    /// How its panels are laid out, to change.
    fn layout_mut(&mut self) -> &mut Layout;

    /// Draws one of its tabs, filling the space it is given.
    fn ui(&mut self, ui: &mut egui::Ui, tab: Tab, view: &ShellView<'_>, actions: &mut Vec<Action>);

    /// Its own buttons in the toolbar, beside STOP.
    fn toolbar(&mut self, _ui: &mut egui::Ui, _view: &ShellView<'_>, _actions: &mut Vec<Action>) {}

    /// What showing `tab` this frame asks for (a base's pad stops once its tab is left).
    fn while_showing(&self, _tab: Tab) -> Option<Action> {
        None
    }
}

/// An emulated board served on a loopback port: its server (it stops when
/// this is dropped) and the port to open.
pub type DemoServer = (Box<dyn std::any::Any + Send>, String);

/// A family's board: how its link is started (a port, the built-in
/// emulator), what is said of it, STOP, and what the family does as the
/// link comes, goes, speaks, works and ends its operations.
pub trait FamilyBoard {
    /// Its own pickers in the connection bar (enabled only while no link is open).
    fn connection_extras(&mut self, _ui: &mut egui::Ui, _view: &ShellView<'_>, _actions: &mut Vec<Action>) {}

    /// How its driver is started over a port being opened at `baud`, as its
    /// pickers choose now.
    fn link_starter(&self, baud: u32) -> LinkStarter;

    /// Starts its built-in emulated board in this process, preloaded with the
    /// project where the board stores one, and connects to it (at the board's own line rate).
    fn demo_link(&self, project: &Project, waker: Waker) -> Result<BoardLink, StartError>;

    /// Starts its built-in emulated board, preloaded as its demo is, as a
    /// server on a loopback port any link opens (`tcp://127.0.0.1:N`): the
    /// editor's demo board lent to remote control. The server (kept alive
    /// while held) and its port; none for a family no show plays.
    fn demo_server(&self, _project: &Project, _waker: Waker) -> Option<Result<DemoServer, StartError>> {
        None
    }

    /// What the connection bar says of its connected board, after "connected to …".
    fn link_details(&self, _link: &BoardLink, _words: &Strings) -> Vec<String> {
        Vec::new()
    }

    /// What the status line says once its built-in emulated board is connected.
    fn demo_connected(&self, words: &Strings) -> &'static str;

    /// STOP, the family's way (the link is connected and of this family).
    fn stop(&mut self, shell: &mut Shell<'_>);

    /// STOP's part in the editor's own playback, a board or not: its previews
    /// stop where they are. Whether one was playing.
    fn halt(&mut self) -> bool {
        false
    }

    /// After STOP, moves may go out again (a board that holds a stop of its own is told).
    fn resume(&mut self, _shell: &mut Shell<'_>) {}

    /// A link was made: the family starts from rest.
    fn connected(&mut self, _project: &Project) {}

    /// The link is gone (disconnected, lost, the window closing).
    fn disconnected(&mut self) {}

    /// Moves previews and streams on to `now`; whether the window should keep repainting.
    fn tick(&mut self, _shell: &mut Shell<'_>, _now: Instant) -> bool {
        false
    }

    /// Takes its running operation's outcome when it has ended (waiting up to
    /// `wait`; None: not at all); returns the whole summary it left, worded in every language.
    fn finish_operation(&mut self, _shell: &mut Shell<'_>, _wait: Option<Duration>) -> Option<StatusLine> {
        None
    }

    /// A notice from its own link (or from STOP that could not be sent).
    fn notice(&mut self, _shell: &mut Shell<'_>, _notice: FamilyNotice) {}

    /// Whether the board is asked for its state continuously (the link polls then).
    fn polling(&self) -> bool {
        false
    }
}

/// A family and the gamepad: what an axis can move, what a button can
/// fire, and the updates it keeps for itself (a base's stick).
pub trait FamilyPad {
    /// What a gamepad axis can move (its servos, its joints).
    fn pad_targets(&self, _project: &Project) -> Vec<PadTarget> {
        Vec::new()
    }

    /// What a gamepad button can fire, with names.
    fn pad_fires(&self, _project: &Project, words: &Strings) -> Vec<(Fire, String)> {
        vec![(Fire::Stop, words.stop.to_string())]
    }

    /// The family's action for what a binding asks for.
    fn pad_cue(&self, cue: Cue) -> Option<Action> {
        (cue == Cue::Fire(Fire::Stop)).then_some(Action::Stop)
    }

    /// Buttons the family keeps for itself (an rFLEX base's dead-man).
    fn pad_reserved(&self) -> &'static [u16] {
        &[]
    }

    /// The gamepad's updates for the family's own use (a base driven by its
    /// stick); `armed`: whether the window lets the pad act now (focused, not
    /// in test mode). Whether the window should keep repainting.
    fn pad_drive(
        &mut self,
        _shell: &mut Shell<'_>,
        _now: Instant,
        _updates: &[(Instant, PadUpdate)],
        _armed: bool,
        _tab: Tab,
    ) -> bool {
        false
    }
}

/// A family's live pose (its sliders'), as undo records and restores it.
pub trait FamilyPose {
    /// Its live pose, as an undo step records it (None: it has none).
    fn live_pose(&self) -> Option<LivePose> {
        None
    }

    /// Moves its live pose back to `pose` (an undo or redo of a turn in the 3D view).
    fn restore_pose(&mut self, _shell: &mut Shell<'_>, _pose: LivePose) {}
}

/// What a family remembers between runs.
pub trait FamilyMemory {
    /// Writes its own settings into what is remembered between runs.
    fn remember(&self, _remembered: &mut Remembered) {}

    /// Takes its own settings back from what was remembered.
    fn recall(&mut self, _remembered: &Remembered) {}
}
