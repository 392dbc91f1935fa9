//! The servo board's side of the editor: its state (the sliders' pose, the
//! board operation's comparison and result, button picking, the preview),
//! its panels (sliders, actions, macros, joystick, board), and what it does
//! with the actions its panels push.

mod action;
mod actions;
mod board;
mod captions;
mod follow;
mod graph;
mod joystick;
mod link;
mod live;
mod macros;
mod operations;
mod pad;
mod played;
mod preview;
mod rig;
mod show_cue;
mod sliders;
mod words;

pub use action::{BoardIntent, ServoAction};
use std::collections::BTreeMap;
use std::time::Instant;

use crossbeam_channel::Receiver;

pub use actions::timeline_bars;
pub(crate) use link::ServoLink;
pub use link::{ServoBoardLink, demo_link};
pub use operations::{BoardResult, PendingConfirm, ServoFailure, ServoKind, ServoOperation, ServoOutcome};

use crate::device::servo::{ButtonEvent, ServoImage, ServoNotice};
use crate::project::{Family, Project, ServoProject};
use crate::sim::SimConfig;
use crate::ui::action::{Action, Tab};
use crate::ui::board_link::{BoardLink, FamilyNotice, LinkStarter, StartError};
use crate::ui::derive::Derived;
use crate::ui::family::{FamilyBoard, FamilyMemory, FamilyPad, FamilyPanels, FamilyPose, FamilyUi, Panel};
use crate::ui::i18n::Worded;
use crate::ui::i18n::{Language, Strings};
use crate::ui::layout::Layout;
use crate::ui::servo::captions::ServoWords;
use crate::ui::shell::{Shell, ShellView};

#[allow(non_upper_case_globals)]
impl Tab {
    /// Servo sliders.
    pub const Servos: Self = Self::named("Servos");
    /// The action editor.
    pub const Actions: Self = Self::named("Actions");
    /// The macro composer.
    pub const Macros: Self = Self::named("Macros");
    /// The board remote's joystick tables.
    pub const Joystick: Self = Self::named("Joystick");
    /// Upload / read / export (the PLEN2 has one too).
    pub const Board: Self = Self::named("Board");
}

/// Interval of a live move, in 10 ms: two frames' worth, so that a dragged
/// servo follows smoothly instead of jumping at full speed.
pub const LIVE_MOVE_INTERVAL_10MS: i16 = 2;
/// Interval given to each step of a captured pose, in 10 ms.
pub const CAPTURED_STEP_INTERVAL_10MS: i16 = 50;

/// The servo board's state in the editor.
#[derive(Debug, Default)]
pub struct ServoUi {
    /// Slider values per servo id.
    pub pose: BTreeMap<u8, i16>,
    /// The servo selected (its slider row, its link in the 3D view).
    pub selected_servo: Option<u8>,
    /// The pose before the servo being turned in the 3D view was grabbed.
    turning: Option<BTreeMap<u8, i16>>,
    /// Reading angles back continuously.
    pub polling: bool,
    /// Remote button events seen, newest last.
    pub button_events: Vec<(u32, ButtonEvent)>,
    /// Picking a button on the remote into this table (index).
    pub picking: Option<usize>,
    /// The button last picked on the remote.
    pub picked_button: Option<u32>,
    /// An action being previewed on the sliders, and when it started.
    pub preview: Option<(i32, Instant)>,
    /// The parts of an action being played on the board still to send (a
    /// curved action is played as its straight sub-steps).
    playing: std::collections::VecDeque<live::Part>,
    /// When the part last sent is done.
    playing_until: Option<Instant>,
    /// The servos as the live moves sent left them (the board moves each
    /// linearly) and those it moved on its own: the live-pose rule every
    /// sender to a servo board shares.
    live: crate::device::servo::LivePose,
    /// The sliders being recorded.
    recording: Option<crate::authoring::recording::Recorder>,
    /// A board comparison waiting for the user's go-ahead.
    pub pending: Option<PendingConfirm>,
    /// The outcome of the last board operation.
    pub board_result: Option<BoardResult>,
    compare_intent: Option<BoardIntent>,
    /// The board's contents being written to a file (off the frame).
    exporting: Option<(std::path::PathBuf, Receiver<Result<(), crate::project::SaveError>>)>,
    compared_board: Option<ServoProject>,
    /// The project's size on the board (or why it cannot be stored), for a document revision and language.
    footprint: Derived<(u64, Language), Result<usize, String>>,
    sliders: sliders::ServoPanel,
    actions: actions::ActionPanel,
    macros: macros::MacroPanel,
    joystick: joystick::JoystickPanel,
    /// The 3D preview of the robot.
    pub figure: preview::Preview,
    /// How the family's panels are laid out (remembered).
    pub layout: Layout,
}

impl ServoUi {
    /// The state for a project: every slider at its servo's home.
    pub fn new(project: &ServoProject) -> Self {
        Self { pose: homes(project), ..Self::default() }
    }

    /// A new document: the sliders go home, comparisons are dropped.
    fn replace_document(&mut self, project: &ServoProject) {
        self.pose = homes(project);
        self.turning = None;
        self.selected_servo = None;
        self.pending = None;
        self.compared_board = None;
        self.preview = None;
    }

    /// Applies one of the family's actions.
    pub fn apply(&mut self, shell: &mut Shell<'_>, action: ServoAction) {
        match action {
            ServoAction::Record => self.recording = Some(crate::authoring::recording::Recorder::new()),
            ServoAction::StopRecording => self.finish_recording(shell),
            ServoAction::SetPose { servo_id, degree } => self.set_pose(shell, servo_id, degree),
            ServoAction::SelectServo(servo_id) => self.selected_servo = servo_id,
            ServoAction::TurnServo { servo_id, by_deg } => {
                let before = self.turning.get_or_insert_with(|| self.pose.clone());
                let home = shell.document.project.servo.servo(servo_id).map_or(0, |servo| servo.home_deg);
                let degree = i32::from(before.get(&servo_id).copied().unwrap_or(home)).saturating_add(by_deg);
                let degree = i16::try_from(degree.clamp(i32::from(i16::MIN), i32::from(i16::MAX))).unwrap_or(home);
                self.selected_servo = Some(servo_id);
                self.set_pose(shell, servo_id, degree);
            }
            ServoAction::SetMesh { servo_id, path } => {
                let folder = shell.document.path.as_deref().and_then(std::path::Path::parent);
                let changed = rig::with_mesh(&shell.document.project.servo, servo_id, &path, folder);
                shell.document.apply(crate::project::Edit::ReplaceAll(Box::new(changed)), None);
            }
            ServoAction::Pose(degrees) => {
                self.turning.get_or_insert_with(|| self.pose.clone());
                for (servo_id, degree) in degrees {
                    if self.pose.get(&servo_id) != Some(&degree) {
                        self.set_pose(shell, servo_id, degree);
                    }
                }
            }
            ServoAction::TurnDone => {
                if let Some(before) = self.turning.take()
                    && before != self.pose
                {
                    shell.document.record_pose(crate::project::LivePose::new(Family::Servo, before));
                }
            }
            ServoAction::SetHold { servo_id, hold } => {
                if let Some(servo) = shell.servo_mut() {
                    servo.set_hold(servo_id, hold);
                }
            }
            ServoAction::CapturePose { from_board } => self.capture_pose(shell, from_board),
            ServoAction::SetPolling(polling) => self.polling = polling,
            ServoAction::BoardCompare(intent) => self.board_compare(shell, intent),
            ServoAction::BoardConfirm => self.board_confirm(shell),
            ServoAction::BoardDismiss => {
                self.pending = None;
                self.compared_board = None;
            }
            ServoAction::PlayAction(action_id) => self.play_action(shell, action_id),
            ServoAction::PlayMacroFrom { macro_id, command } => self.play_macro_from(shell, macro_id, command),
            ServoAction::PreviewAction(action_id) => self.preview = Some((action_id, Instant::now())),
            ServoAction::RunMacro(macro_id) => self.run_macro(shell, macro_id),
            ServoAction::PickButton { table_index } => match shell.servo_mut() {
                Some(servo) => {
                    servo.subscribe_buttons(true);
                    self.picking = table_index;
                }
                None => shell.say(|language| language.strings().servo().msg_connect_for_pick, true),
            },
        }
    }

    /// A remote button event arrived.
    pub fn button(&mut self, shell: &mut Shell<'_>, button_id: u32, event: ButtonEvent) {
        self.button_events.push((button_id, event));
        // The board may run a macro for it on its own.
        self.board_moved_them(&shell.document.project.servo, Instant::now(), std::time::Duration::ZERO);
        if let Some(table_index) = self.picking.take() {
            self.pick_button(shell, table_index, button_id);
        }
    }

    fn board_tab(&mut self, ui: &mut egui::Ui, view: &ShellView<'_>, actions: &mut Vec<Action>) {
        // Encoding every record takes milliseconds on a large project: once per
        // revision, off the frame path then.
        let language = view.language;
        let footprint = self.footprint.get(ui.ctx(), (view.revision, language), || {
            let project = view.project.servo.clone();
            move || {
                ServoImage::from_project(&project)
                    .map_err(|error| crate::device::servo::OpError::Image(error).worded(language))
                    .and_then(|image| image.footprint_bytes().map_err(|error| error.worded(language)))
            }
        });
        let project_bytes = footprint.map_or(Ok(0), |(_, bytes)| bytes.clone());
        let servo = view.link.and_then(|link| link.servo());
        let board = board::BoardView {
            connected: view.link.is_some(),
            project_bytes,
            board_total_bytes: servo
                .and_then(|servo| servo.memory)
                .map(|(free, total)| i64::from(total.unwrap_or(free))),
            operation: view.operation(),
            pending: self.pending.as_ref(),
            result: self.board_result.as_ref(),
        };
        board::ui(ui, &board, language, actions);
    }

    /// The last operation's outcome, whole (the status line shows its first line), and whether it is an error.
    pub fn summary(&self, language: Language) -> Option<(String, bool)> {
        let words = language.strings();
        if self.pending.is_some() {
            return Some((words.servo().msg_board_compared.to_string(), false));
        }
        let result = self.board_result.as_ref()?;
        if let Some(error) = result.error_text(language) {
            return Some((error, true));
        }
        let text = match result {
            BoardResult::Uploaded { items, .. } => format!("{} {}", words.uploaded_items, items.len()),
            BoardResult::ReadIntoProject => words.read_done.to_string(),
            BoardResult::Exported(path) => format!("{} {}", words.saved_board_to, path.display()),
            _ => words.cancelled.to_string(),
        };
        Some((text, false))
    }
}

impl FamilyUi for ServoUi {
    fn sound_follower(&self) -> Option<&dyn crate::ui::sound::follow::SoundFollower> {
        Some(&follow::ServoFollower)
    }

    fn act(&mut self, shell: &mut Shell<'_>, action: Box<dyn crate::ui::action::FamilyAction>) {
        match action.into_any().downcast::<ServoAction>() {
            Ok(action) => self.apply(shell, *action),
            Err(_) => {
                crate::ui::board_link::misrouted(Family::Servo, "an action", std::any::type_name::<ServoAction>());
            }
        }
    }

    fn family(&self) -> Family {
        Family::Servo
    }

    fn document_replaced(&mut self, project: &Project) {
        self.recording = None;
        self.playing.clear();
        self.replace_document(&project.servo);
    }
}

impl FamilyPanels for ServoUi {
    fn panels(&self) -> &'static [Panel] {
        &[
            Panel { tab: Tab::Servos, title: |words| words.servos, has_view: true },
            Panel { tab: Tab::Actions, title: |words| words.actions, has_view: true },
            Panel { tab: Tab::Macros, title: |words| words.macros, has_view: true },
            Panel { tab: Tab::Joystick, title: |words| words.joystick, has_view: false },
            Panel { tab: Tab::Board, title: |words| words.board, has_view: false },
        ]
    }

    fn layout(&self) -> Layout {
        self.layout
    }

    fn layout_mut(&mut self) -> &mut Layout {
        &mut self.layout
    }

    fn ui(&mut self, ui: &mut egui::Ui, tab: Tab, view: &ShellView<'_>, actions: &mut Vec<Action>) {
        let project = &view.project.servo;
        let words = view.language.strings();
        self.figure.set_folder(view.folder);
        let connected = view.link.is_some();
        // Recording samples the sliders every frame, whichever tab shows, on the window's clock.
        let now_s = ui.input(|input| input.time);
        let phase = self.recording.as_mut().map(|recorder| {
            let values: Vec<f64> = project
                .servos
                .iter()
                .map(|servo| f64::from(self.pose.get(&servo.id).copied().unwrap_or(servo.home_deg)))
                .collect();
            recorder.sample(now_s, &values);
            ui.ctx().request_repaint();
            recorder.phase(now_s)
        });
        match tab {
            Tab::Actions => self.actions.ui(ui, view, (&mut self.layout, &mut self.figure), actions),
            Tab::Macros => self.macros.ui(ui, view, (&mut self.layout, &mut self.figure), actions),
            Tab::Joystick => {
                let joystick = joystick::JoystickView {
                    project,
                    events: &self.button_events,
                    picked: self.picked_button,
                    picking: self.picking.is_some(),
                    connected,
                };
                self.joystick.ui(ui, &joystick, &mut self.layout, words, actions);
            }
            Tab::Board => self.board_tab(ui, view, actions),
            _ => {
                let sliders = sliders::ServoView {
                    project,
                    pose: &self.pose,
                    readback: view.link.and_then(|link| link.servo()).map(|servo| &servo.servos),
                    polling: self.polling,
                    recording: phase,
                    selected: self.selected_servo,
                };
                let (mut side, open) = (self.layout.side_width, self.layout.view_open);
                let (panel, layout, figure) = (&mut self.sliders, &mut self.layout, &mut self.figure);
                crate::ui::layout::beside(ui, "servo-sliders", (&mut side, open), |ui, pane| match pane {
                    crate::ui::layout::Pane::First => panel.ui(ui, &sliders, layout, words, actions),
                    crate::ui::layout::Pane::Second => {
                        figure.live(ui, (project, &self.pose), self.selected_servo, words, actions);
                    }
                });
                self.layout.side_width = side;
            }
        }
    }
}

impl FamilyBoard for ServoUi {
    fn link_details(&self, link: &BoardLink, words: &Strings) -> Vec<String> {
        let Some(servo) = link.servo() else { return Vec::new() };
        let mut parts = Vec::new();
        if let Some(project_id) = servo.project_id {
            parts.push(format!("{} {project_id}", words.project));
        }
        if let Some(permil) = servo.battery_permil {
            parts.push(format!("{} {}", words.battery, crate::device::servo::battery_text(permil)));
        }
        if let Some((free, total)) = servo.memory {
            parts.push(match total {
                Some(total) => format!("{} {free} / {total} B", words.servo().free_memory),
                None => format!("{} {free} B", words.servo().free_memory),
            });
        }
        parts
    }

    fn link_starter(&self, baud: u32) -> LinkStarter {
        link::starter(baud)
    }

    fn demo_link(&self, project: &Project, waker: crate::link::Waker) -> Result<BoardLink, StartError> {
        demo_link(project, SimConfig::default(), waker)
    }

    fn demo_connected(&self, words: &Strings) -> &'static str {
        words.servo().msg_connected_demo
    }

    fn demo_server(
        &self,
        project: &Project,
        waker: crate::link::Waker,
    ) -> Option<Result<crate::ui::family::DemoServer, StartError>> {
        Some(link::demo_server(project, waker))
    }

    fn stop(&mut self, shell: &mut Shell<'_>) {
        // Held wherever they were: where is read again, not guessed.
        self.board_moved_them(&shell.document.project.servo, Instant::now(), std::time::Duration::ZERO);
        self.playing.clear();
        let Some(link) = shell.link.as_mut() else { return };
        match link.stop() {
            None => shell.say(|language| language.strings().servo().msg_stopped_all, false),
            Some(failed) => self.notice(shell, failed),
        }
    }

    fn halt(&mut self) -> bool {
        let previewing = self.figure.transport.halt() | self.preview.take().is_some();
        self.playing.clear();
        previewing
    }

    fn resume(&mut self, shell: &mut Shell<'_>) {
        if let Some(servo) = shell.servo_mut() {
            servo.resume();
        }
    }

    fn connected(&mut self, project: &Project) {
        self.polling = false;
        // Where the servos stand is known once the board is first read.
        self.board_moved_them(&project.servo, Instant::now(), std::time::Duration::ZERO);
    }

    fn disconnected(&mut self) {
        self.polling = false;
        self.live.clear();
        self.playing.clear();
    }

    /// Moves the previewed action on (the sliders follow it); whether it still plays.
    fn tick(&mut self, shell: &mut Shell<'_>, now: Instant) -> bool {
        self.finish_export(shell.language);
        self.advance_preview(&shell.document.project.servo, now);
        self.play_next(shell, now);
        self.preview.is_some() || !self.playing.is_empty()
    }

    fn finish_operation(
        &mut self,
        shell: &mut Shell<'_>,
        wait: Option<std::time::Duration>,
    ) -> Option<crate::ui::shell::StatusLine> {
        let (operation, outcome) = crate::ui::shell::RunningOperation::finished(shell.operation, wait)?;
        self.finish(&operation, outcome);
        let (_, is_error) = self.summary(shell.language)?;
        Some(crate::ui::shell::StatusLine::worded(
            shell.language,
            |language| self.summary(language).map(|(text, _)| text).unwrap_or_default(),
            is_error,
        ))
    }

    fn notice(&mut self, shell: &mut Shell<'_>, notice: FamilyNotice) {
        let Some(notice) = notice.of::<ServoNotice>(Family::Servo).cloned() else { return };
        match notice {
            ServoNotice::Button { button_id, event } => self.button(shell, button_id, event),
            ServoNotice::SendFailed(error) => shell.say(|language| words::send_failed(language, &error), true),
            ServoNotice::RequestFailed(error) => shell.say(|language| error.worded(language), true),
            ServoNotice::MacroRefused => shell.say(|language| language.strings().servo().msg_macro_refused, true),
            // The link takes these itself.
            ServoNotice::Log(_) | ServoNotice::Disconnected(_) => {}
        }
    }

    fn polling(&self) -> bool {
        self.polling
    }
}

impl FamilyPad for ServoUi {
    fn pad_targets(&self, project: &Project) -> Vec<crate::ui::gamepad::PadTarget> {
        pad::targets(&project.servo, &self.pose)
    }

    fn pad_fires(&self, project: &Project, words: &Strings) -> Vec<(crate::project::gamepad::Fire, String)> {
        pad::fires(&project.servo, words)
    }

    fn pad_cue(&self, cue: crate::gamepad::puppet::Cue) -> Option<Action> {
        pad::cue(cue)
    }
}

impl FamilyPose for ServoUi {
    fn live_pose(&self) -> Option<crate::project::LivePose> {
        Some(crate::project::LivePose::new(Family::Servo, self.pose.clone()))
    }

    fn restore_pose(&mut self, shell: &mut Shell<'_>, pose: crate::project::LivePose) {
        if pose.family == Family::Servo {
            ServoUi::restore_pose(self, shell, pose.values);
        }
    }
}

impl FamilyMemory for ServoUi {}

fn homes(project: &ServoProject) -> BTreeMap<u8, i16> {
    project.servos.iter().map(|servo| (servo.id, servo.home_deg)).collect()
}
