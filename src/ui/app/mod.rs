//! The app shell: owns the document, the link, the one running operation,
//! the window's chrome and dialogs, and one state per family ([`ServoUi`],
//! [`Plen2Ui`], [`RflexUi`]). Panels push [`Action`]s; only
//! [`StudioApp::apply`] changes anything, handing each family's actions to
//! the family that owns them.

mod apply;
mod background;
mod chrome;
mod connection;
mod dialogs;
mod doctor;
mod file_desk;
mod file_ops;
mod gamepad;
mod import;
mod lent;
mod link_desk;
mod sound;
mod tabs;

use std::io::Write;
use std::path::PathBuf;
use std::time::{Duration, Instant};

use crossbeam_channel::Receiver;

pub use background::{PortLister, system_lister};
pub use dialogs::{Picker, system_picker};
pub use file_desk::FileDesk;
pub use link_desk::{Connecting, LinkDesk};

use crate::device::speed::LiveSpeed;
use crate::link::{PortInfo, Waker};
use crate::project::{Family, Project};
use crate::ui::action::{Action, AfterUnsaved, FileRequest, Tab};
use crate::ui::board_link::BoardLink;
use crate::ui::document::Document;
use crate::ui::families::Families;
use crate::ui::family::FamilyUi;
use crate::ui::files::{self, AUTOSAVE_EVERY};
use crate::ui::i18n::Language;
use crate::ui::layout::Layout;
pub use crate::ui::remembered::Remembered;
use crate::ui::shell::{RunningOperation, Shell, ShellView, StatusLine};

/// STOP's distance from the window's right edge, points.
const STOP_MARGIN: f32 = 8.0;
/// The width kept at the toolbar's right end for STOP and Resume (wide enough in every language).
const STOP_WIDTH: f32 = 240.0;

/// The whole editor: the document, the link and what runs on it, each
/// family's side, and the desks that do the rest (files, connecting, the
/// window's own state). Only [`StudioApp::apply`] changes it.
pub struct StudioApp {
    /// The open document.
    pub document: Document,
    /// The board, when connected.
    pub link: Option<BoardLink>,
    /// The interface language.
    pub language: Language,
    /// How fast anything sent live may turn a servo or joint (a setting).
    pub live_speed: LiveSpeed,
    /// The latest message for the user.
    pub status: Option<StatusLine>,
    /// The running board operation, of whichever family.
    pub operation: Option<RunningOperation>,
    /// Each family's state and panels.
    pub families: Families,
    /// Files: opening, saving, autosave and recovery, recent files, dialogs.
    pub files: FileDesk,
    /// Connecting: the port list, a port being opened, the connection doctor, closing links.
    pub links: LinkDesk,
    /// The window: the tab shown, how it ends, what wakes it.
    pub window: Window,
    /// The editor's inputs and windows beside the document: the gamepad,
    /// the import window, the sound track, the show window.
    pub desks: Desks,
}

/// The editor's inputs and windows beside the document, each its own desk.
#[derive(Default)]
pub struct Desks {
    /// The gamepad, its live state and the binding being made.
    pub pad: crate::ui::gamepad::PadInput,
    /// File → Import from another tool…: its window and work.
    pub import: crate::ui::import::ImportDesk,
    /// The project's sound track: read, checked, played.
    pub sound: crate::ui::sound::SoundDesk,
    /// File → Show…: a show's devices and cues, played on every board.
    pub show: crate::ui::show::ShowDesk,
}

/// The window's own state.
pub struct Window {
    /// The tab shown.
    pub tab: Tab,
    /// The window may close now (the board is stopped and the work kept).
    quit_allowed: bool,
    /// Told when the process is asked to end.
    terminate: Option<Receiver<()>>,
    /// Wakes the window from other threads.
    waker: Waker,
    /// STOP was pressed and Resume not yet: nothing that moves a robot goes out.
    stopped: bool,
    /// Where STOP (and Resume) were drawn last frame, over everything.
    stop_rect: Option<egui::Rect>,
    /// The toolbar's top, where STOP is drawn level with it.
    stop_top: f32,
}

impl std::fmt::Debug for StudioApp {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("StudioApp").field("document", &self.document).field("link", &self.link).finish_non_exhaustive()
    }
}

impl StudioApp {
    /// An editor showing `project` (saved at `path`, if any). `waker` is called
    /// from other threads when there is something to show.
    pub fn new(project: impl Into<Project>, path: Option<PathBuf>, waker: Waker) -> Self {
        let project = project.into();
        let mut app = Self {
            families: Families::default(),
            document: Document::new(project, path),
            link: None,
            language: Language::detect(),
            live_speed: LiveSpeed::default(),
            status: None,
            operation: None,
            files: FileDesk::new(waker.clone()),
            links: LinkDesk::new(waker.clone()),
            window: Window {
                tab: Tab::Log,
                quit_allowed: false,
                terminate: None,
                waker,
                stopped: false,
                stop_rect: None,
                stop_top: 4.0,
            },
            desks: Desks::default(),
        };
        app.files.read_recovery_later();
        app.each_family(|family_ui, shell| family_ui.document_replaced(&shell.document.project));
        let family = app.document.project.family;
        app.window.tab = app.family_ui(family).tabs()[0];
        app
    }

    #[cfg(any(test, feature = "test-api"))]
    /// Keeps backups and the recovery file in `data_dir` instead of the
    /// platform's data folder.
    pub fn with_data_dir(mut self, data_dir: PathBuf) -> Self {
        self.files.data_dir = data_dir;
        self.files.recovery_offer = None;
        self.files.read_recovery_later();
        self
    }

    #[cfg(any(test, feature = "test-api"))]
    /// Asks for files with the editor's own picker, as where no system dialog
    /// can appear (`install`: what would give one).
    pub fn with_own_file_picker(mut self, install: &'static str) -> Self {
        self.files.no_system_dialog = Some(install);
        self
    }

    #[cfg(any(test, feature = "test-api"))]
    /// Opens file dialogs with `picker` instead of the system's (tests answer them).
    pub fn with_picker(mut self, picker: Picker) -> Self {
        self.files.picker = picker;
        self.files.no_system_dialog = None;
        self
    }

    /// Ends the editor (board stopped, work kept) when `terminated` says so.
    pub fn terminate_on(&mut self, terminated: Receiver<()>) {
        self.window.terminate = Some(terminated);
    }

    fn words(&self) -> &'static crate::ui::i18n::Strings {
        self.language.strings()
    }

    fn report(&mut self, text: impl Into<String>, is_error: bool) {
        self.status = Some(StatusLine::new(text, is_error));
    }

    /// Says something on the status line, worded by `word` in each language
    /// (said again in another when the language changes).
    fn say<T: Into<String>>(&mut self, word: impl Fn(Language) -> T, is_error: bool) {
        self.status = Some(StatusLine::worded(self.language, word, is_error));
    }

    /// The shell as a family's ui changes it, and the families' uis (borrowed apart).
    pub(crate) fn split(&mut self) -> (Shell<'_>, &mut Families) {
        let Self { document, link, status, operation, language, live_speed, files, window, families, desks, .. } = self;
        let sound = &mut desks.sound;
        let shell = Shell {
            document,
            link,
            status,
            operation,
            language: *language,
            speed: *live_speed,
            data_dir: &files.data_dir,
            waker: &window.waker,
            files: &files.work,
            sound,
        };
        (shell, families)
    }

    /// The shell as a family's ui changes it, and that family's ui.
    fn parts(&mut self, family: Family) -> (Shell<'_>, &mut dyn FamilyUi) {
        let (shell, families) = self.split();
        (shell, families.get_mut(family))
    }

    /// A family's side of the editor.
    pub fn family_ui(&self, family: Family) -> &dyn FamilyUi {
        self.families.get(family)
    }

    /// Runs `change` on every family's side of the editor, with the shell.
    fn each_family(&mut self, mut change: impl FnMut(&mut dyn FamilyUi, &mut Shell<'_>)) {
        let (mut shell, families) = self.split();
        for family_ui in families.iter_mut() {
            change(family_ui, &mut shell);
        }
    }

    /// What a family's panels draw from, and that family's ui.
    fn drawing(&mut self, family: Family) -> (ShellView<'_>, &mut dyn FamilyUi, Tab) {
        let Self { document, link, operation, language, families, window, desks, .. } = self;
        let sound = &desks.sound;
        let Window { tab, waker, .. } = window;
        let view = ShellView {
            project: &document.project,
            revision: document.revision(),
            link: link.as_ref(),
            operation: operation.as_ref(),
            language: *language,
            waker,
            folder: document.path.as_deref().and_then(std::path::Path::parent),
            sound: sound.view(&document.project),
        };
        (view, families.get_mut(family), *tab)
    }

    /// Shows `family`'s first tab when the tab shown is not one of its own.
    fn show_family_tab(&mut self, family: Family) {
        if !self.tabs(family).contains(&self.window.tab) {
            self.window.tab = self.family_ui(family).tabs()[0];
        }
    }

    /// The tabs shown for a family: its own, then the packet log.
    pub fn tabs(&self, family: Family) -> Vec<Tab> {
        let mut tabs = self.family_ui(family).tabs();
        tabs.extend([Tab::Gamepad, Tab::Log]);
        tabs
    }

    /// The layout of a family's panels.
    pub fn layout(&self, family: Family) -> Layout {
        self.family_ui(family).layout()
    }

    /// Whether STOP holds: pressed (or the board stopped) and not resumed.
    pub fn stopped(&self) -> bool {
        self.window.stopped || self.link.as_ref().is_some_and(BoardLink::stopped)
    }

    /// Where STOP was drawn last frame (over every window), for tests.
    pub fn stop_rect(&self) -> Option<egui::Rect> {
        self.window.stop_rect
    }

    /// After STOP: moves may go out again (a board holding its own stop is told), said.
    fn resume(&mut self) {
        self.window.stopped = false;
        if let Some(link) = &self.link {
            let (mut shell, family_ui) = self.parts(link.family());
            family_ui.resume(&mut shell);
        }
        self.say(|language| language.word("strings.msg_resumed"), false);
    }

    /// STOP, the family's way (always visible, Esc too), and everything the
    /// editor plays itself: previews and their sound; nothing that moves a
    /// robot goes out until Resume.
    fn stop(&mut self) {
        self.window.stopped = true;
        // The show's sound stops too, and a board's start still waiting for it never goes out.
        self.desks.sound.silence();
        // A show previewed on its stage stops where it is (its sound too), said in its log.
        let mut previewing = self.desks.show.stop_preview_said();
        // The editor's own previews, whichever family's.
        self.each_family(|family_ui, _| previewing |= family_ui.halt());
        // A show playing on several boards, or holding them: every one of them (and the editor's own).
        let show_boards = self.desks.show.playing() || self.desks.show.linked.is_some();
        if show_boards {
            self.desks.show.stop();
        }
        let Some(link) = &self.link else {
            if !show_boards {
                let said = |language: Language| {
                    if previewing {
                        language.word("strings.msg_stopped_preview")
                    } else {
                        language.strings().msg_stop_no_board
                    }
                };
                self.say(said, false);
            }
            return;
        };
        let (mut shell, family_ui) = self.parts(link.family());
        family_ui.stop(&mut shell);
    }

    /// Closes the link (off the frame): every family starts again from rest.
    fn drop_link(&mut self) {
        self.close_link();
        self.each_family(|family_ui, _| family_ui.disconnected());
    }

    /// Moves previews and streams on to `now`; whether the window should keep repainting.
    pub fn advance(&mut self, now: Instant) -> bool {
        let mut moving = false;
        self.each_family(|family_ui, shell| moving |= family_ui.tick(shell, now));
        moving
    }

    /// Draws the editor and applies what its panels asked for.
    pub fn show(&mut self, ui: &mut egui::Ui) {
        if self.window.terminate.as_ref().is_some_and(|terminated| terminated.try_recv().is_ok()) {
            self.apply(Action::Terminate);
        }
        let now = Instant::now();
        self.pump(now);
        self.links.scan_ports();
        self.poll_probe();
        self.reconnect_when_back(now);
        self.take_lent_board_back();
        self.finish_file_work(None);
        self.poll_import(ui.ctx());
        self.keep_sound();
        self.language.put_in(ui.ctx());
        let mut actions = Vec::new();
        Self::shortcuts(ui, &mut actions);
        self.poll_dialog(&mut actions);

        self.file_events(ui, now, &mut actions);
        let focused = ui.input(|input| input.focused);
        if self.feed_gamepad(now, focused) | self.advance(now) {
            ui.ctx().request_repaint();
        }
        egui::Panel::top("toolbar").show(ui, |ui| self.toolbar(ui, &mut actions));

        egui::Panel::bottom("status").show(ui, |ui| self.status_line(ui));

        let family = self.document.project.family;
        actions.extend(self.family_ui(family).while_showing(self.window.tab));
        self.show_family_tab(family);
        egui::CentralPanel::default().show(ui, |ui| self.tab_panel(ui, &mut actions));

        self.dialogs(ui, &mut actions);
        self.file_browser(ui.ctx(), &mut actions);
        self.desks.import.window(ui.ctx(), (&self.document.project, &self.files.work), self.language, &mut actions);
        let pad: Vec<(u16, f64)> =
            self.desks.pad.state.as_ref().map(|state| state.axes().collect()).unwrap_or_default();
        // A remote's poses keep to the editor's live speed limit.
        self.desks.show.live_speed.0 = self.live_speed;
        // The device that is the editor's project is the project as it is now (edited, undone, redone).
        self.desks.show.follow_editor(&self.document.project, self.document.revision());
        self.desks.show.passes.undo_reaches = self.document.beside_on_top();
        self.desks.show.window(ui.ctx(), (self.language, &pad), &mut actions);
        let follower = self.families.get(self.document.project.family).sound_follower();
        let document = (&self.document.project, follower);
        self.desks.sound.follow_window(ui.ctx(), document, self.language, &mut actions);
        let document = (&self.document.project, self.document.path.as_ref());
        self.desks.import.export_window(ui.ctx(), document, self.language, &mut actions);
        // Last, over every window, popup and dialog, whatever their size or language.
        self.stop_on_top(ui.ctx(), &mut actions);
        for action in actions {
            self.apply(action);
        }
        // A drag or a typing run is one undo step: it ends when the pointer is
        // up and no field has focus.
        if !ui.input(|input| input.pointer.any_down()) && ui.memory(|memory| memory.focused().is_none()) {
            self.document.seal();
        }
        if self.window.quit_allowed {
            ui.ctx().send_viewport_cmd(egui::ViewportCommand::Close);
        }
        if self.document.dirty {
            ui.ctx().request_repaint_after(AUTOSAVE_EVERY);
        }
        if let Some(link) = &self.link {
            let polling = self.family_ui(link.family()).polling();
            let wait = link.next_refresh(polling).saturating_duration_since(Instant::now());
            ui.ctx().request_repaint_after(wait);
        }
        // An answer the sound output owes: looked at again when it is due.
        if let Some(deadline) = self.desks.sound.next_deadline() {
            ui.ctx().request_repaint_after(deadline.saturating_duration_since(Instant::now()));
        }
    }
}

/// How long the editor, ending on a signal, waits for a board operation to
/// reach its next safe point: a request's timeout and its retries.
pub const TERMINATE_WAIT: Duration = Duration::from_secs(10);

/// How long the window's end may take, whatever a thread is doing: the link
/// stopping a base and shutting it down, a save in flight reaching the disk.
pub const EXIT_WITHIN: Duration = Duration::from_secs(2);

impl StudioApp {
    /// The window is going: the link stops a base and shuts it down (brake
    /// on), and a save in flight reaches the disk — waited for `within` at
    /// most. The sound output is not waited for (it is dropped; a sound
    /// server that does not answer keeps nothing open).
    pub fn close_within(&mut self, within: Duration) {
        let deadline = Instant::now() + within;
        self.desks.sound.silence();
        // A show's held boards: every device stopped (bases brake) and its link closed.
        self.desks.show.stop();
        self.desks.show.let_boards_go();
        self.drop_link();
        self.links.wait_for_closing(deadline);
        self.finish_file_work(Some(deadline.saturating_duration_since(Instant::now())));
    }
}

/// The key under which [`Remembered`] is stored.
pub const REMEMBERED_KEY: &str = "servo-studio";

impl StudioApp {
    /// What to remember between runs.
    pub fn remembered(&self) -> Remembered {
        let mut remembered = Remembered {
            recent: self.files.recent.clone(),
            language: self.language,
            tab: self.window.tab.name().to_string(),
            family: self.document.project.family,
            live_speed: self.live_speed,
            layouts: Family::all().iter().map(|family| self.layout(*family)).collect(),
            ..Remembered::default()
        };
        for &family in Family::all() {
            self.family_ui(family).remember(&mut remembered);
        }
        remembered
    }

    /// Restores what was remembered: the family too, unless `keep_family`
    /// (a project opened from a file, or the demo, brings its own).
    pub fn restore(&mut self, remembered: Remembered, keep_family: bool) {
        for family_ui in self.families.iter_mut() {
            family_ui.recall(&remembered);
        }
        self.files.recent = remembered.recent;
        self.language = remembered.language;
        self.live_speed = remembered.live_speed;
        for (&family, layout) in Family::all().iter().zip(remembered.layouts) {
            *self.families.get_mut(family).layout_mut() = layout;
        }
        if !keep_family {
            self.document.project.family = remembered.family;
        }
        let family = self.document.project.family;
        self.window.tab =
            self.tabs(family).into_iter().find(|tab| tab.name() == remembered.tab).unwrap_or(self.window.tab);
        self.show_family_tab(family);
    }
}

impl eframe::App for StudioApp {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        self.show(ui);
    }

    fn on_exit(&mut self, _gl: Option<&eframe::glow::Context>) {
        self.close_within(EXIT_WITHIN);
    }

    fn save(&mut self, storage: &mut dyn eframe::Storage) {
        eframe::set_value(storage, REMEMBERED_KEY, &self.remembered());
    }
}
