//! The app shell: owns the document, the board link and the panels; panels
//! push [`Action`]s and only [`StudioApp::apply`] changes anything.

mod board;
mod connection;
mod file_ops;
mod live;
mod plen2;
mod tabs;

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::time::Instant;

use crate::device::servo::Phase;
use crate::device::servo::{ButtonEvent, ServoHandle, ServoMove};
use crate::link::{Opener, Opening, PortName, Waker, system_opener};
use crate::project::{Action as ProjectAction, Edit, Family, Project, ServoProject, Step, next_free_id};
use crate::project::{has_errors, validate_servo};
use crate::ui::action::{Action, AfterUnsaved, BoardIntent, Tab};
use crate::ui::action_panel::ActionPanel;
use crate::ui::board_link::{BoardLink, LinkNotice};
use crate::ui::board_panel::{BoardResult, PendingConfirm};
use crate::ui::connection_bar::{ConnectionBar, LinkStatus};
use crate::ui::document::Document;
use crate::ui::drive_panel::DrivePanel;
use crate::ui::files::{self, AUTOSAVE_EVERY, Recovery};
use crate::ui::i18n::Language;
use crate::ui::job::{Job, JobKind, JobOutcome};
use crate::ui::joystick_panel::JoystickPanel;
use crate::ui::macro_panel::MacroPanel;
use crate::ui::servo_panel::ServoPanel;

/// Interval of a live move, in 10 ms: two frames' worth, so that a dragged
/// servo follows smoothly instead of jumping at full speed.
pub const LIVE_MOVE_INTERVAL_10MS: i16 = 2;
/// Interval given to each step of a captured pose, in 10 ms.
pub const CAPTURED_STEP_INTERVAL_10MS: i16 = 50;

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
    /// Slider values per servo id.
    pub pose: BTreeMap<u8, i16>,
    /// Reading angles back continuously.
    pub polling: bool,
    /// The interface language.
    pub language: Language,
    /// The latest message for the user.
    pub status: Option<StatusLine>,
    /// Remote button events seen, newest last.
    pub button_events: Vec<(u32, ButtonEvent)>,
    /// A port being opened (off the UI thread), with the family and line rate to start.
    pub connecting: Option<Connecting>,
    /// The tab shown.
    pub tab: Tab,
    /// The running board operation.
    pub job: Option<Job>,
    /// A board comparison waiting for the user's go-ahead.
    pub pending: Option<PendingConfirm>,
    /// The outcome of the last board operation.
    pub board_result: Option<BoardResult>,
    /// Folder for backups and the recovery file.
    pub data_dir: PathBuf,
    /// Recently opened or saved files, newest first.
    pub recent: Vec<PathBuf>,
    /// What waits on the "unsaved changes" question.
    pub unsaved_prompt: Option<AfterUnsaved>,
    /// Work autosaved by a session that did not end cleanly, offered at start.
    pub recovery_offer: Option<Recovery>,
    last_autosave: Instant,
    quit_allowed: bool,
    /// Picking a button on the remote into this table (index).
    pub picking: Option<usize>,
    /// The button last picked on the remote.
    pub picked_button: Option<u32>,
    /// An action being previewed on the sliders, and when it started.
    pub preview: Option<(i32, Instant)>,
    compare_intent: Option<BoardIntent>,
    /// The project's size on the board (or why it cannot be stored), for a document revision and language.
    footprint: crate::ui::derive::Derived<(u64, Language), Result<usize, String>>,
    /// The PLEN2 section's problems, per document revision (the motion editor marks them every frame).
    plen2_problems: Option<(u64, Vec<crate::project::Problem>)>,
    /// The robot panel's slot map, for (document revision, robot reads).
    plen2_slots: Option<((u64, u64), Vec<crate::ui::plen2_board::SlotCell>)>,
    /// Robots read so far (a new read invalidates the slot map).
    plen2_robot_reads: u64,
    compared_board: Option<ServoProject>,
    waker: Waker,
    opener: Opener,
    connection_bar: ConnectionBar,
    servo_panel: ServoPanel,
    macro_panel: MacroPanel,
    joystick_panel: JoystickPanel,
    drive_panel: DrivePanel,
    motions_panel: crate::ui::plen2_motions::MotionsPanel,
    play_lists_panel: crate::ui::plen2_play_lists::PlayListsPanel,
    /// Every PLEN2 joint's angle on the sliders, tenths of a degree, device-map order.
    pub plen2_pose: [i16; 18],
    plen2_stream: Option<plen2::Stream>,
    /// The running PLEN2 operation.
    pub plen2_job: Option<crate::ui::plen2_job::Plen2Job>,
    /// What the robot held when last read.
    pub plen2_robot: Option<crate::project::plen2::Plen2Project>,
    /// The last PLEN2 operation's outcome, in words.
    pub plen2_result: Option<String>,
    /// Whether the base's sonar ring was turned on.
    pub sonar_on: bool,
    /// How a PLEN2 is paced (connection settings; remembered).
    pub plen2_pacing: crate::device::plen2::PacingMode,
    action_panel: ActionPanel,
    /// Told when the process is asked to end.
    terminate: Option<crossbeam_channel::Receiver<()>>,
}

impl std::fmt::Debug for StudioApp {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("StudioApp").field("document", &self.document).field("link", &self.link).finish_non_exhaustive()
    }
}

impl StudioApp {
    /// An editor showing `project` (saved at `path`, if any). `waker` is called
    /// from the I/O thread when the board has something to show.
    pub fn new(project: impl Into<Project>, path: Option<PathBuf>, waker: Waker) -> Self {
        let project = project.into();
        let pose = project.servo.servos.iter().map(|servo| (servo.id, servo.home_deg)).collect();
        let mut app = Self {
            document: Document::new(project, path),
            link: None,
            connecting: None,
            opener: system_opener(),
            pose,
            polling: false,
            language: Language::detect(),
            status: None,
            button_events: Vec::new(),
            tab: Tab::default(),
            job: None,
            pending: None,
            board_result: None,
            data_dir: eframe::storage_dir("Servo Studio").unwrap_or_else(|| std::env::temp_dir().join("servo-studio")),
            recent: Vec::new(),
            unsaved_prompt: None,
            recovery_offer: None,
            last_autosave: Instant::now(),
            quit_allowed: false,
            compare_intent: None,
            footprint: crate::ui::derive::Derived::default(),
            plen2_problems: None,
            plen2_slots: None,
            plen2_robot_reads: 0,
            compared_board: None,
            waker,
            connection_bar: ConnectionBar::default(),
            servo_panel: ServoPanel::default(),
            macro_panel: MacroPanel::default(),
            action_panel: ActionPanel::default(),
            preview: None,
            joystick_panel: JoystickPanel::default(),
            drive_panel: DrivePanel::default(),
            motions_panel: crate::ui::plen2_motions::MotionsPanel::default(),
            play_lists_panel: crate::ui::plen2_play_lists::PlayListsPanel::default(),
            plen2_pose: crate::project::plen2::Joint::ALL.map(crate::project::plen2::Joint::factory_home_tenths_deg),
            plen2_stream: None,
            plen2_job: None,
            plen2_robot: None,
            plen2_result: None,
            sonar_on: false,
            plen2_pacing: crate::device::plen2::PacingMode::default(),
            picking: None,
            picked_button: None,
            terminate: None,
        };
        app.recovery_offer = files::read_recovery(&app.data_dir);
        app
    }

    /// Ends the editor (board stopped, work kept) when `terminated` says so.
    pub fn terminate_on(&mut self, terminated: crossbeam_channel::Receiver<()>) {
        self.terminate = Some(terminated);
    }

    /// Keeps backups and the recovery file in `data_dir` instead of the
    /// platform's data folder.
    pub fn with_data_dir(mut self, data_dir: PathBuf) -> Self {
        self.data_dir = data_dir;
        self.recovery_offer = files::read_recovery(&self.data_dir);
        self
    }

    fn words(&self) -> &'static crate::ui::i18n::Strings {
        self.language.strings()
    }

    fn report(&mut self, text: impl Into<String>, is_error: bool) {
        self.status = Some(StatusLine { text: text.into(), is_error });
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
            Action::ConnectDemo => match BoardLink::demo(&self.document.project, self.plen2_pacing, self.waker.clone())
            {
                Ok(link) => {
                    self.sonar_on = self.document.project.rflex.drive.sonar_on_connect;
                    let words = self.words();
                    let text = match self.document.project.family {
                        Family::Servo => words.msg_connected_demo,
                        Family::Plen2 => words.msg_connected_demo_plen2,
                        Family::Rflex => words.msg_connected_demo_rflex,
                    };
                    self.report(text, false);
                    self.link = Some(link);
                }
                Err(error) => self.report(self.language.start_error(&error), true),
            },
            Action::SetFamily(family) => self.set_family(family),
            Action::Disconnect => {
                self.link = None;
                self.polling = false;
                self.report(self.words().msg_disconnected, false);
            }
            Action::SetPose { servo_id, degree } => self.set_pose(servo_id, degree),
            Action::SetHold { servo_id, hold } => {
                if let Some(servo) = self.servo_mut() {
                    servo.set_hold(servo_id, hold);
                }
            }
            Action::Stop => match &mut self.link {
                Some(link) if link.plen2().is_some() => {
                    self.plen2_stream = None;
                    let _ = link.stop();
                    self.report(self.words().msg_plen2_stopped, false);
                }
                Some(link) if link.rflex().is_some() => {
                    self.drive_panel = DrivePanel::default();
                    // A base: both axes to 0 at once (never fails; a lost link is reported by pump).
                    let _ = link.stop();
                    self.report(self.words().msg_base_stopped, false);
                }
                Some(link) => match link.stop() {
                    Ok(()) => self.report(self.words().msg_stopped_all, false),
                    Err(error) => self.report(self.language.request_error(&error), true),
                },
                None => self.report(self.words().msg_stop_no_board, false),
            },
            Action::Drive { speed_m_per_s, turn_rad_per_s } => {
                // Never past what the robot's preset allows, whatever a file or a panel asked for.
                let limits = self.document.project.rflex.robot.limits();
                let speed = speed_m_per_s.clamp(-limits.max_speed_m_per_s, limits.max_speed_m_per_s);
                let turn = turn_rad_per_s.clamp(-limits.max_turn_rad_per_s, limits.max_turn_rad_per_s);
                let accel = self.document.project.rflex.drive.accel_m_per_s2.min(limits.max_accel_m_per_s2);
                if let Some(base) = self.link.as_mut().and_then(BoardLink::rflex_mut) {
                    base.drive(speed, turn, accel);
                }
            }
            Action::SetJoint { joint, tenths } => self.set_joint(joint, tenths),
            Action::Plen2Home => self.plen2_home(),
            Action::PlayMotion(slot) => self.play_motion(slot),
            Action::PlayFrom { slot, frame } => self.play_from(slot, frame),
            Action::PlayList(index) => self.play_list(index),
            Action::CaptureFrame { slot } => self.capture_frame(slot),
            Action::Plen2Board(intent) => self.plen2_board(intent),
            Action::SaveMotionJson { slot, path } => {
                if let Some(motion) = self.document.project.plen2.motions.iter().find(|m| m.slot == slot) {
                    let text = crate::project::motion_json::motion_to_json(motion);
                    match crate::project::atomic_write(&path, |file| std::io::Write::write_all(file, text.as_bytes())) {
                        Ok(()) => self.report(format!("{} {}", self.words().msg_saved, path.display()), false),
                        Err(source) => {
                            self.report(self.language.save_error(&crate::project::SaveError { path, source }), true);
                        }
                    }
                }
            }
            Action::SetRobot(robot) => {
                if self.link.is_none() {
                    self.document.apply(Edit::SetRflexRobot(robot), None);
                }
            }
            Action::SetBrake(on) => {
                if let Some(base) = self.link.as_mut().and_then(BoardLink::rflex_mut) {
                    base.set_brake(on);
                }
            }
            Action::SetSonar(on) => {
                if let Some(base) = self.link.as_ref().and_then(BoardLink::rflex) {
                    base.set_sonar(on);
                    self.sonar_on = on;
                }
            }
            Action::Resume => {
                if let Some(servo) = self.servo_mut() {
                    servo.resume();
                    self.report(self.words().msg_resumed, false);
                }
            }
            Action::CapturePose { from_board } => self.capture_pose(from_board),
            Action::SetPolling(polling) => self.polling = polling,
            Action::SetLanguage(language) => self.language = language,
            Action::SetPacing(mode) => {
                // Takes effect at the next connection (the driver is set up then).
                if self.link.is_none() {
                    self.plen2_pacing = mode;
                }
            }
            Action::ShowTab(tab) => self.tab = tab,
            Action::BoardCompare(intent) => self.board_compare(intent),
            Action::BoardConfirm => self.board_confirm(),
            Action::BoardDismiss => {
                self.pending = None;
                self.compared_board = None;
            }
            Action::BoardCancel => {
                if let Some(job) = &self.job {
                    job.cancel();
                }
                if let Some(job) = &self.plen2_job {
                    job.cancel();
                }
            }
            Action::NewProject => self.guard_unsaved(AfterUnsaved::New),
            Action::Open(path) => self.guard_unsaved(AfterUnsaved::Open(path)),
            Action::Save => match self.document.path.clone() {
                Some(path) => {
                    self.save_to(path);
                }
                None => self.report(self.words().msg_no_file, true),
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
            Action::PlayAction(action_id) => self.play_action(action_id),
            Action::PreviewAction(action_id) => self.preview = Some((action_id, Instant::now())),
            Action::RunMacro(macro_id) => match self.servo_mut() {
                Some(servo) => servo.run_macro(macro_id),
                None => self.report(self.words().msg_connect_for_macro, true),
            },
            Action::PickButton { table_index } => match self.servo_mut() {
                Some(servo) => {
                    servo.subscribe_buttons(true);
                    self.picking = table_index;
                }
                None => self.report(self.words().msg_connect_for_pick, true),
            },
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
                // into the recovery file, then the window, without asking.
                self.link = None;
                self.apply(Action::Autosave);
                self.quit_allowed = true;
            }
        }
    }

    /// Draws the editor and applies what its panels asked for.
    pub fn show(&mut self, ui: &mut egui::Ui) {
        if self.terminate.as_ref().is_some_and(|terminated| terminated.try_recv().is_ok()) {
            self.apply(Action::Terminate);
        }
        let now = Instant::now();
        self.pump(now);
        let mut actions = Vec::new();
        Self::shortcuts(ui, &mut actions);
        let words = self.language.strings();

        self.file_events(ui, now, &mut actions);
        if self.preview.is_some() {
            self.advance_preview(now);
            ui.ctx().request_repaint();
        }
        if self.streaming() {
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
                        actions.push(Action::Resume);
                    }
                });
            });
            self.connection_bar.ui(ui, &self.link_status(), self.language, words, &mut actions);
            ui.horizontal(|ui| {
                let mut tab = self.tab;
                // Only the panels that apply to the document's family are offered.
                for option in Tab::for_family(self.document.project.family) {
                    ui.selectable_value(&mut tab, *option, option.title(words));
                }
                if tab != self.tab {
                    actions.push(Action::ShowTab(tab));
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
        if self.tab != Tab::Drive && self.drive_panel.asked() != (0.0, 0.0) {
            // The pad and the keys live on the Drive tab: leaving it is letting go.
            actions.push(Action::Stop);
        }
        if !Tab::for_family(family).contains(&self.tab) {
            self.tab = Tab::for_family(family)[0];
        }
        egui::CentralPanel::default().show(ui, |ui| self.tab_panel(ui, words, &mut actions));

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
            let wait = link.next_refresh(self.polling).saturating_duration_since(Instant::now());
            ui.ctx().request_repaint_after(wait);
        }
    }
}

/// What is remembered between runs (the window's size and place are
/// remembered by eframe itself).
#[derive(Clone, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
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
    pub plen2_pacing: crate::device::plen2::PacingMode,
}

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
        }
    }

    /// Restores what was remembered.
    pub fn restore(&mut self, remembered: Remembered) {
        self.recent = remembered.recent;
        self.language = remembered.language;
        self.tab = remembered.tab;
        self.plen2_pacing = remembered.plen2_pacing;
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
