//! The app shell: owns the document, the link, the one running operation,
//! the window's chrome and dialogs, and one state per family ([`ServoUi`],
//! [`Plen2Ui`], [`RflexUi`]). Panels push [`Action`]s; only
//! [`StudioApp::apply`] changes anything, handing each family's actions to
//! the family that owns them.

mod connection;
mod dialogs;
mod file_ops;
mod shell;
mod tabs;

use std::io::Write;
use std::path::PathBuf;
use std::time::{Duration, Instant};

use crossbeam_channel::Receiver;

pub use dialogs::{Picker, system_picker};
pub use shell::{RunningOperation, Shell, ShellView};

use crate::device::plen2::PacingMode;
use crate::link::{Opener, Opening, PortInfo, Waker, system_opener};
use crate::project::{Family, Project};
use crate::ui::action::{Action, AfterUnsaved, FileRequest, Tab};
use crate::ui::board_link::BoardLink;
use crate::ui::connection_bar::ConnectionBar;
use crate::ui::document::Document;
use crate::ui::files::{self, AUTOSAVE_EVERY, Recovery};
use crate::ui::i18n::Language;
use crate::ui::layout::Layout;
use crate::ui::plen2::Plen2Ui;
use crate::ui::rflex::RflexUi;
use crate::ui::servo::ServoUi;

/// A line for the status bar.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct StatusLine {
    /// The text.
    pub text: String,
    /// Whether it reports a failure.
    pub is_error: bool,
}

/// A port being opened.
#[derive(Debug)]
pub struct Connecting {
    /// The opening, on its own thread.
    pub opening: Opening,
    /// The family whose driver starts once it is open.
    pub family: Family,
    /// The line rate asked for.
    pub baud: u32,
}

/// The whole editor.
pub struct StudioApp {
    /// The open document.
    pub document: Document,
    /// The board, when connected.
    pub link: Option<BoardLink>,
    /// The interface language.
    pub language: Language,
    /// The latest message for the user.
    pub status: Option<StatusLine>,
    /// A port being opened (off the UI thread), with the family and line rate to start.
    pub connecting: Option<Connecting>,
    /// The tab shown.
    pub tab: Tab,
    /// The running board operation, of whichever family.
    pub operation: Option<RunningOperation>,
    /// Folder for backups and the recovery file.
    pub data_dir: PathBuf,
    /// Recently opened or saved files, newest first.
    pub recent: Vec<PathBuf>,
    /// What waits on the "unsaved changes" question.
    pub unsaved_prompt: Option<AfterUnsaved>,
    /// Work autosaved by a session that did not end cleanly, offered at start.
    pub recovery_offer: Option<Recovery>,
    /// How a PLEN2 is paced (connection settings; remembered).
    pub plen2_pacing: PacingMode,
    /// The servo board's state and panels.
    pub servo: ServoUi,
    /// The PLEN2's state and panels.
    pub plen2: Plen2Ui,
    /// The rFLEX base's state and panels.
    pub rflex: RflexUi,
    /// The serial ports seen at the last scan.
    pub ports: Vec<PortInfo>,
    next_scan: Option<Instant>,
    /// A file dialog open, and the request it answers.
    dialog: Option<(FileRequest, Receiver<Option<PathBuf>>)>,
    last_autosave: Instant,
    quit_allowed: bool,
    waker: Waker,
    opener: Opener,
    picker: Picker,
    connection_bar: ConnectionBar,
    /// Told when the process is asked to end.
    terminate: Option<Receiver<()>>,
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
        let mut plen2 = Plen2Ui::default();
        plen2.document_replaced(&project.plen2);
        let mut app = Self {
            servo: ServoUi::new(&project.servo),
            plen2,
            rflex: RflexUi::default(),
            document: Document::new(project, path),
            link: None,
            connecting: None,
            opener: system_opener(),
            picker: system_picker(),
            language: Language::detect(),
            status: None,
            tab: Tab::default(),
            operation: None,
            data_dir: eframe::storage_dir("Servo Studio").unwrap_or_else(|| std::env::temp_dir().join("servo-studio")),
            recent: Vec::new(),
            unsaved_prompt: None,
            recovery_offer: None,
            plen2_pacing: PacingMode::default(),
            ports: Vec::new(),
            next_scan: None,
            dialog: None,
            last_autosave: Instant::now(),
            quit_allowed: false,
            waker,
            connection_bar: ConnectionBar::default(),
            terminate: None,
        };
        app.recovery_offer = files::read_recovery(&app.data_dir);
        app
    }

    /// Keeps backups and the recovery file in `data_dir` instead of the
    /// platform's data folder.
    pub fn with_data_dir(mut self, data_dir: PathBuf) -> Self {
        self.data_dir = data_dir;
        self.recovery_offer = files::read_recovery(&self.data_dir);
        self
    }

    /// Opens file dialogs with `picker` instead of the system's (tests answer them).
    pub fn with_picker(mut self, picker: Picker) -> Self {
        self.picker = picker;
        self
    }

    /// Ends the editor (board stopped, work kept) when `terminated` says so.
    pub fn terminate_on(&mut self, terminated: Receiver<()>) {
        self.terminate = Some(terminated);
    }

    fn words(&self) -> &'static crate::ui::i18n::Strings {
        self.language.strings()
    }

    fn report(&mut self, text: impl Into<String>, is_error: bool) {
        self.status = Some(StatusLine { text: text.into(), is_error });
    }

    /// The shell as a family's ui changes it.
    fn shell(&mut self) -> (Shell<'_>, &mut ServoUi, &mut Plen2Ui, &mut RflexUi) {
        let shell = Shell {
            document: &mut self.document,
            link: &mut self.link,
            status: &mut self.status,
            operation: &mut self.operation,
            language: self.language,
            data_dir: &self.data_dir,
            waker: &self.waker,
        };
        (shell, &mut self.servo, &mut self.plen2, &mut self.rflex)
    }

    /// The layout of the document's family's panels.
    pub fn layout(&self, family: Family) -> Layout {
        match family {
            Family::Servo => self.servo.layout,
            Family::Plen2 => self.plen2.layout,
            Family::Rflex => self.rflex.layout,
        }
    }

    /// Applies one action. The only place that changes the editor's state.
    pub fn apply(&mut self, action: Action) {
        match action {
            Action::Edit { edit, coalesce } => self.document.apply(edit, coalesce.as_deref()),
            Action::SealEdit => self.document.seal(),
            Action::Undo => {
                self.document.undo();
            }
            Action::Redo => {
                self.document.redo();
            }
            Action::Connect { port, baud } => self.connect(&port, baud),
            Action::CancelConnect => {
                if let Some(connecting) = self.connecting.take() {
                    self.report(self.language.connect_cancelled(&connecting.opening.port.to_string()), false);
                }
            }
            Action::ScanPorts => self.scan_ports(Instant::now()),
            Action::ConnectDemo => self.connect_demo(),
            Action::SetFamily(family) => self.set_family(family),
            Action::Disconnect => {
                self.link = None;
                self.servo.polling = false;
                self.report(self.words().msg_disconnected, false);
            }
            Action::Stop => self.stop(),
            Action::SetPacing(mode) => {
                // Takes effect at the next connection (the driver is set up then).
                if self.link.is_none() {
                    self.plen2_pacing = mode;
                }
            }
            Action::SetLanguage(language) => self.language = language,
            Action::ShowTab(tab) => self.tab = tab,
            Action::ShowView(open) => match self.document.project.family {
                Family::Servo => self.servo.layout.view_open = open,
                Family::Plen2 => self.plen2.layout.view_open = open,
                Family::Rflex => self.rflex.layout.view_open = open,
            },
            Action::AskFile(request) => {
                let answer = (self.picker)(&request, self.waker.clone());
                self.dialog = Some((request, answer));
            }
            Action::CancelOperation => {
                if let Some(operation) = &self.operation {
                    operation.cancel();
                }
            }
            Action::NewProject => self.guard_unsaved(AfterUnsaved::New),
            Action::Open(path) => self.guard_unsaved(AfterUnsaved::Open(path)),
            Action::Save => match self.document.path.clone() {
                Some(path) => {
                    self.save_to(path);
                }
                None => self.apply(Action::AskFile(FileRequest::SaveAs)),
            },
            Action::SaveAs(path) => {
                self.save_to(path);
            }
            Action::UnsavedSave => {
                let saved = match self.document.path.clone() {
                    Some(path) => self.save_to(path),
                    None => false,
                };
                if saved && let Some(next) = self.unsaved_prompt.take() {
                    self.after_unsaved(next);
                }
            }
            Action::UnsavedDiscard => {
                if let Some(next) = self.unsaved_prompt.take() {
                    self.after_unsaved(next);
                }
            }
            Action::UnsavedCancel => self.unsaved_prompt = None,
            Action::Recover => {
                if let Some(recovery) = self.recovery_offer.take() {
                    self.replace_document(recovery.project, recovery.path);
                    // Recovered work is unsaved until the user saves it.
                    self.document.dirty = true;
                    self.report(self.words().msg_recovered, false);
                }
            }
            Action::DeclineRecovery => {
                self.recovery_offer = None;
                files::clear_recovery(&self.data_dir);
            }
            Action::Autosave => {
                if self.document.dirty
                    && let Err(error) =
                        files::write_recovery(&self.data_dir, self.document.path.as_deref(), &self.document.project)
                {
                    self.report(self.language.autosave_failed(&error), true);
                }
            }
            Action::Terminate => {
                // Asked to end from outside (Ctrl-C, kill, a closing session): the board
                // first — a base stops and brakes as its link is dropped — then the work,
                // into the recovery file, then the window, without asking. An upload
                // running stops at its next safe point (never mid-packet); what it left
                // on the board, and how to restore the backup, go to the terminal.
                if let Some(operation) = &self.operation {
                    operation.cancel();
                    let summary = self.finish_operation(Some(TERMINATE_WAIT));
                    let said = match summary {
                        Some((text, _)) => text,
                        None => self.words().msg_operation_left_running.to_string(),
                    };
                    let _ = writeln!(std::io::stderr(), "servo-studio: {said}");
                }
                self.link = None;
                self.apply(Action::Autosave);
                self.quit_allowed = true;
            }
            Action::Servo(action) => {
                let (mut shell, servo, _, _) = self.shell();
                servo.apply(&mut shell, action);
            }
            Action::Plen2(action) => {
                let (mut shell, _, plen2, _) = self.shell();
                plen2.apply(&mut shell, action);
            }
            Action::Rflex(action) => {
                let (mut shell, _, _, rflex) = self.shell();
                rflex.apply(&mut shell, action);
            }
        }
    }

    /// STOP, the family's way (always visible, Esc too).
    fn stop(&mut self) {
        let Some(link) = &mut self.link else {
            self.report(self.words().msg_stop_no_board, false);
            return;
        };
        match link.family() {
            Family::Plen2 => {
                self.plen2.stopped();
                let _ = link.stop();
                self.report(self.words().msg_plen2_stopped, false);
            }
            Family::Rflex => {
                self.rflex.stopped();
                // Both axes to 0 at once (never fails; a lost link is reported by pump).
                let _ = link.stop();
                self.report(self.words().msg_base_stopped, false);
            }
            Family::Servo => match link.stop() {
                Ok(()) => self.report(self.words().msg_stopped_all, false),
                Err(error) => self.report(self.language.request_error(&error), true),
            },
        }
    }

    /// Moves previews and streams on to `now`; whether the window should keep repainting.
    pub fn advance(&mut self, now: Instant) -> bool {
        let (mut shell, servo, plen2, _) = self.shell();
        let previewing = servo.tick(&shell.document.project, now);
        let streaming = plen2.tick(&mut shell, now);
        previewing || streaming
    }

    /// Whether a PLEN2 motion is being streamed.
    pub fn streaming(&self) -> bool {
        self.plen2.streaming()
    }

    /// Draws the editor and applies what its panels asked for.
    pub fn show(&mut self, ui: &mut egui::Ui) {
        if self.terminate.as_ref().is_some_and(|terminated| terminated.try_recv().is_ok()) {
            self.apply(Action::Terminate);
        }
        let now = Instant::now();
        self.pump(now);
        self.scan_ports(now);
        let mut actions = Vec::new();
        Self::shortcuts(ui, &mut actions);
        self.poll_dialog(&mut actions);
        let words = self.language.strings();

        self.file_events(ui, now, &mut actions);
        if self.advance(now) {
            ui.ctx().request_repaint();
        }
        egui::Panel::top("toolbar").show(ui, |ui| {
            ui.horizontal(|ui| {
                self.file_menu(ui, &mut actions);
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
                let picked =
                    egui::ComboBox::from_id_salt("language").selected_text(language.name()).show_ui(ui, |ui| {
                        for option in [Language::English, Language::TraditionalChinese] {
                            ui.selectable_value(&mut language, option, option.name());
                        }
                    });
                picked.response.labelled_by(language_label.id);
                if language != self.language {
                    actions.push(Action::SetLanguage(language));
                }
                ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
                    let stop = egui::Button::new(
                        egui::RichText::new(format!("■ {}", words.stop))
                            .strong()
                            .size(18.0)
                            .color(egui::Color32::WHITE),
                    )
                    .fill(egui::Color32::from_rgb(200, 30, 30));
                    if ui.add(stop).on_hover_text("Esc").clicked() {
                        actions.push(Action::Stop);
                    }
                    if self.link.as_ref().is_some_and(BoardLink::stopped) && ui.button(words.resume).clicked() {
                        actions.push(Action::Servo(crate::ui::action::ServoAction::Resume));
                    }
                });
            });
            let status = self.link_status();
            self.connection_bar.ui(ui, &status, &self.ports, self.language, &mut actions);
            ui.horizontal(|ui| {
                let mut tab = self.tab;
                // Only the panels that apply to the document's family are offered.
                for option in Tab::for_family(self.document.project.family) {
                    ui.selectable_value(&mut tab, *option, option.title(words));
                }
                if tab != self.tab {
                    actions.push(Action::ShowTab(tab));
                }
                let family = self.document.project.family;
                if self.tab.has_view() {
                    ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
                        let mut open = self.layout(family).view_open;
                        let label = if family == Family::Rflex { words.world_view } else { words.show_preview };
                        if ui.checkbox(&mut open, label).changed() {
                            actions.push(Action::ShowView(open));
                        }
                    });
                }
            });
        });

        egui::Panel::bottom("status").show(ui, |ui| match &self.status {
            Some(line) if line.is_error => {
                ui.colored_label(ui.visuals().error_fg_color, &line.text);
            }
            Some(line) => {
                ui.label(&line.text);
            }
            None => {
                ui.label("");
            }
        });

        let family = self.document.project.family;
        if self.tab != Tab::Drive && self.rflex.drive_asked() != (0.0, 0.0) {
            // The pad and the keys live on the Drive tab: leaving it is letting go.
            actions.push(Action::Stop);
        }
        if !Tab::for_family(family).contains(&self.tab) {
            self.tab = Tab::for_family(family)[0];
        }
        egui::CentralPanel::default().show(ui, |ui| self.tab_panel(ui, &mut actions));

        self.dialogs(ui, &mut actions);
        for action in actions {
            self.apply(action);
        }
        // A drag or a typing run is one undo step: it ends when the pointer is
        // up and no field has focus.
        if !ui.input(|input| input.pointer.any_down()) && ui.memory(|memory| memory.focused().is_none()) {
            self.document.seal();
        }
        if self.quit_allowed {
            ui.ctx().send_viewport_cmd(egui::ViewportCommand::Close);
        }
        if self.document.dirty {
            ui.ctx().request_repaint_after(AUTOSAVE_EVERY);
        }
        if let Some(link) = &self.link {
            let wait = link.next_refresh(self.servo.polling).saturating_duration_since(Instant::now());
            ui.ctx().request_repaint_after(wait);
        }
        if let Some(at) = self.next_scan {
            ui.ctx().request_repaint_after(at.saturating_duration_since(now));
        }
    }
}

/// What is remembered between runs (the window's size and place are
/// remembered by eframe itself).
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Remembered {
    /// Recent files, newest first.
    pub recent: Vec<PathBuf>,
    /// The interface language.
    pub language: Language,
    /// The tab shown.
    pub tab: Tab,
    /// The board family last used.
    #[serde(default)]
    pub family: Family,
    /// How a PLEN2 is paced.
    #[serde(default)]
    pub plen2_pacing: PacingMode,
    /// How each family's panels were laid out: servo, PLEN2, rFLEX.
    #[serde(default)]
    pub layouts: [Layout; 3],
}

/// How long the editor, ending on a signal, waits for a board operation to
/// reach its next safe point: a request's timeout and its retries.
pub const TERMINATE_WAIT: Duration = Duration::from_secs(10);

/// The key under which [`Remembered`] is stored.
pub const REMEMBERED_KEY: &str = "servo-studio";

impl StudioApp {
    /// What to remember between runs.
    pub fn remembered(&self) -> Remembered {
        Remembered {
            recent: self.recent.clone(),
            language: self.language,
            tab: self.tab,
            family: self.document.project.family,
            plen2_pacing: self.plen2_pacing,
            layouts: [self.servo.layout, self.plen2.layout, self.rflex.layout],
        }
    }

    /// Restores what was remembered.
    pub fn restore(&mut self, remembered: Remembered) {
        self.recent = remembered.recent;
        self.language = remembered.language;
        self.tab = remembered.tab;
        self.plen2_pacing = remembered.plen2_pacing;
        [self.servo.layout, self.plen2.layout, self.rflex.layout] = remembered.layouts;
    }
}

impl eframe::App for StudioApp {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        self.show(ui);
    }

    fn on_exit(&mut self, _gl: Option<&eframe::glow::Context>) {
        // Dropping the link stops a base and shuts it down (brake on) before the window goes.
        self.link = None;
    }

    fn save(&mut self, storage: &mut dyn eframe::Storage) {
        eframe::set_value(storage, REMEMBERED_KEY, &self.remembered());
    }
}
