//! The PLEN2's side of the editor: its state (the joints' pose, a motion
//! streamed live, what the robot held when read, the last operation's
//! outcome), its panels (joints, motions, play lists, robot), and what it
//! does with the actions its panels push.

mod action;
mod board;
mod captions;
mod follow;
mod graph;
mod joints;
mod link;
mod live;
mod motions;
mod operations;
mod pad;
mod play_lists;
mod preview;
mod show_cue;
mod words;

use crate::authoring::recording::Recorder;
use crate::ui::i18n::Worded;
pub use action::{Plen2Action, Plen2Intent};
use std::path::PathBuf;
use std::time::Instant;

pub use board::{SlotCell, slot_map};
pub use link::Plen2BoardLink;
pub(crate) use link::Plen2Link;
pub use live::homes;
pub use operations::{Plen2Failure, Plen2Kind, Plen2Operation, Plen2Outcome, Plen2Result};

use crate::device::plen2;
use crate::device::plen2::{PacingMode, Plen2Item};
use crate::project::plen2::{Joint, Plen2Project};
use crate::project::{Edit, Family, LivePose, Project};
use crate::ui::action::{Action, Tab};
use crate::ui::board_link::{BoardLink, FamilyNotice, LinkStarter, StartError};
use crate::ui::family::{FamilyBoard, FamilyMemory, FamilyPad, FamilyPanels, FamilyPose, FamilyUi, Panel};
use crate::ui::i18n::{Language, Strings};
use crate::ui::layout::{Layout, Pane};
use crate::ui::operation::Operation;
use crate::ui::plen2::captions::Plen2Words;
use crate::ui::shell::{RunningOperation, Shell, ShellView};

#[allow(non_upper_case_globals)]
impl Tab {
    /// PLEN2 joint sliders and settings.
    pub const Joints: Self = Self::named("Joints");
    /// PLEN2 motions in their slots.
    pub const Motions: Self = Self::named("Motions");
    /// PLEN2 play lists.
    pub const PlayLists: Self = Self::named("PlayLists");
}

/// The PLEN2's state in the editor.
#[derive(Debug)]
pub struct Plen2Ui {
    /// Every joint's angle on the sliders, tenths of a degree, device-map order.
    pub pose: [i16; 18],
    /// The joint selected (its slider row, its link in the 3D view).
    pub selected_joint: Option<Joint>,
    /// The pose before the joint being turned in the 3D view was grabbed.
    turning: Option<[i16; 18]>,
    stream: Option<live::Stream>,
    /// Joints walked toward the sliders at the live speed limit.
    slew: Option<crate::device::speed::Slew>,
    /// The live pose being recorded into a motion.
    recording: Option<live::Recording>,
    /// What the robot held when last read.
    pub robot: Option<Plen2Project>,
    /// Robots read so far (a new read invalidates the slot map).
    robot_reads: u64,
    /// The last operation's outcome.
    pub result: Option<Plen2Result>,
    /// The PLEN2 section's problems, per document revision (the motion editor marks them every frame).
    problems: Option<(u64, crate::project::Problems)>,
    /// The robot panel's slot map, for (document revision, robot reads).
    slots: Option<((u64, u64), Vec<SlotCell>)>,
    motions: motions::MotionsPanel,
    play_lists: play_lists::PlayListsPanel,
    /// The 3D preview.
    pub preview: preview::Preview,
    /// How the family's panels are laid out (remembered).
    pub layout: Layout,
    /// How the robot is paced (connection settings; remembered; used from the next connection).
    pub pacing: PacingMode,
    /// Files being written off the frame.
    writing: Vec<Writing>,
}

/// A file being written off the frame: what the robot held, or a motion.json.
#[derive(Debug)]
struct Writing {
    path: PathBuf,
    done: crossbeam_channel::Receiver<Result<(), crate::project::SaveError>>,
    /// The robot's contents (its result shows in the robot panel), else a motion (on the status line).
    export: bool,
}

impl Default for Plen2Ui {
    fn default() -> Self {
        Self {
            pose: homes(&Plen2Project::default()),
            selected_joint: None,
            turning: None,
            stream: None,
            slew: None,
            recording: None,
            robot: None,
            robot_reads: 0,
            result: None,
            problems: None,
            slots: None,
            motions: motions::MotionsPanel::default(),
            play_lists: play_lists::PlayListsPanel::default(),
            preview: preview::Preview::default(),
            layout: Layout::default(),
            pacing: PacingMode::default(),
            writing: Vec::new(),
        }
    }
}

impl Plen2Ui {
    /// Applies one of the family's actions.
    pub fn apply(&mut self, shell: &mut Shell<'_>, action: Plen2Action) {
        match action {
            Plen2Action::SetJoint { joint, tenths } => self.set_joint(shell, joint, tenths),
            Plen2Action::SelectJoint(joint) => self.selected_joint = joint,
            Plen2Action::TurnJoint { joint, by_tenths } => self.turn_joint(shell, joint, by_tenths),
            Plen2Action::Pose(pose) => {
                self.turning.get_or_insert(self.pose);
                self.set_pose(shell, pose);
            }
            Plen2Action::TurnDone => {
                if let Some(before) = self.turning.take()
                    && before != self.pose
                {
                    shell.document.record_pose(LivePose::indexed(Family::Plen2, &before));
                }
            }
            Plen2Action::Home => self.home(shell),
            Plen2Action::PlayMotion(slot) => self.play_motion(shell, slot),
            Plen2Action::PlayFrom { slot, frame } => self.play_from(shell, slot, frame),
            Plen2Action::PlayList(index) => self.play_list(shell, index),
            Plen2Action::CaptureFrame { slot } => self.capture_frame(shell, slot),
            Plen2Action::Record { slot } => {
                let after = self.motions.selected_frame();
                self.recording = Some(live::Recording { slot, after, recorder: Recorder::new() });
            }
            Plen2Action::StopRecording => self.finish_recording(shell),
            Plen2Action::Robot(intent) => self.robot_operation(shell, intent),
            Plen2Action::SetPacing(mode) => {
                // Takes effect at the next connection (the driver is set up then).
                if shell.link.is_none() {
                    self.pacing = mode;
                }
            }
            Plen2Action::SaveMotionJson { slot, path } => {
                if let Some(motion) = shell.document.project.plen2.motions.iter().find(|m| m.slot == slot) {
                    // Written off the frame; the status line says how it went (tick).
                    // As the robot stores it: curves baked into straight frames.
                    let stored = plen2::stored_motion(motion);
                    let text = crate::project::motion_json::motion_to_json(&stored);
                    let done = shell.files.write(path.clone(), text.into_bytes());
                    self.writing.push(Writing { path, done, export: false });
                }
            }
        }
    }

    fn start(&mut self, shell: &mut Shell<'_>, kind: Plen2Kind, project: Plen2Project) {
        let Some(robot) = shell.plen2() else {
            shell.say(|language| language.strings().msg_connect_first, true);
            return;
        };
        let requester = robot.requester();
        self.result = None;
        let backups = shell.data_dir.join("backups");
        let job_kind = kind.clone();
        let operation = Operation::start(
            kind,
            shell.waker.clone(),
            move |report, cancel| operations::run(&job_kind, &requester, &project, backups, report, cancel),
            |error| Plen2Outcome::Failed(Plen2Failure::Thread(error)),
        );
        *shell.operation = Some(RunningOperation::new(operation));
    }

    fn robot_operation(&mut self, shell: &mut Shell<'_>, intent: Plen2Intent) {
        if shell.operation.is_some() {
            return;
        }
        let plen2 = shell.document.project.plen2.clone();
        match intent {
            Plen2Intent::Read => self.start(shell, Plen2Kind::Read, plen2),
            Plen2Intent::Upload => {
                let document = Project { family: Family::Plen2, plen2: plen2.clone(), ..Project::default() };
                let errors = crate::project::validate(&document).errors_only();
                if !errors.has_errors() {
                    self.start(shell, Plen2Kind::Upload, plen2);
                } else {
                    self.result = Some(Plen2Result::Invalid(errors));
                }
            }
            Plen2Intent::WriteJoints => self.start(shell, Plen2Kind::WriteJoints, plen2),
            Plen2Intent::FactoryReset => self.start(shell, Plen2Kind::FactoryReset, plen2),
            Plen2Intent::ReadIntoProject => {
                if let Some(robot) = self.robot.clone() {
                    let mut plen2 = robot;
                    plen2.play_lists = shell.document.project.plen2.play_lists.clone();
                    shell.document.apply(Edit::SetPlen2(Box::new(plen2)), None);
                    self.result = Some(Plen2Result::ReadIntoProject);
                }
            }
            Plen2Intent::ExportToFile(path) => {
                if let Some(robot) = self.robot.clone() {
                    let document = Project { family: Family::Plen2, plen2: robot, ..Project::default() };
                    let done = shell.files.save(path.clone(), &document);
                    self.writing.push(Writing { path, done, export: true });
                }
            }
        }
    }

    /// Files written off the frame: what each gave.
    fn finish_writing(&mut self, shell: &mut Shell<'_>) {
        let language = shell.language;
        let writing = std::mem::take(&mut self.writing);
        for file in writing {
            let Ok(result) = file.done.try_recv() else {
                self.writing.push(file);
                continue;
            };
            match (file.export, result) {
                (true, Ok(())) => self.result = Some(Plen2Result::Exported(file.path)),
                (true, Err(error)) => self.result = Some(Plen2Result::ExportFailed(language.save_error(&error))),
                (false, Ok(())) => {
                    shell.say(|language| format!("{} {}", language.strings().msg_saved, file.path.display()), false);
                }
                (false, Err(error)) => shell.say(|language| language.save_error(&error), true),
            }
        }
    }

    /// The family's operation ended.
    pub fn finish(&mut self, outcome: Plen2Outcome) {
        self.result = Some(match outcome {
            Plen2Outcome::Read(robot) => {
                let count = robot.motions.len();
                self.robot = Some(*robot);
                self.robot_reads += 1;
                Plen2Result::Read(count)
            }
            Plen2Outcome::Uploaded(report) => Plen2Result::Uploaded(report),
            Plen2Outcome::JointsWritten(count) => Plen2Result::JointsWritten(count),
            Plen2Outcome::Failed(failure) => Plen2Result::Failed(failure),
            Plen2Outcome::Cancelled => Plen2Result::Cancelled,
        });
    }

    /// The last operation's outcome, whole (the status line shows its first line), and whether it is an error.
    pub fn summary(&self, language: Language) -> Option<(String, bool)> {
        Some(self.result.as_ref()?.words(language))
    }
}

impl FamilyUi for Plen2Ui {
    fn sound_follower(&self) -> Option<&dyn crate::ui::sound::follow::SoundFollower> {
        Some(&follow::Plen2Follower)
    }

    fn act(&mut self, shell: &mut Shell<'_>, action: Box<dyn crate::ui::action::FamilyAction>) {
        match action.into_any().downcast::<Plen2Action>() {
            Ok(action) => self.apply(shell, *action),
            Err(_) => {
                crate::ui::board_link::misrouted(Family::Plen2, "an action", std::any::type_name::<Plen2Action>());
            }
        }
    }

    fn family(&self) -> Family {
        Family::Plen2
    }

    /// A new document: the joints go home.
    fn document_replaced(&mut self, project: &Project) {
        self.pose = homes(&project.plen2);
        self.stream = None;
        self.slew = None;
        self.recording = None;
    }
}

impl FamilyPanels for Plen2Ui {
    fn panels(&self) -> &'static [Panel] {
        &[
            Panel { tab: Tab::Joints, title: |words| words.joints, has_view: true },
            Panel { tab: Tab::Motions, title: |words| words.motions, has_view: true },
            Panel { tab: Tab::PlayLists, title: |words| words.play_lists, has_view: false },
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
        let project = &view.project.plen2;
        let words = view.language.strings();
        let connected = view.link.is_some_and(|link| link.plen2().is_some());
        // Recording samples the pose every frame, whichever tab shows, on the window's clock.
        let now_s = ui.input(|input| input.time);
        let phase = self.recording.as_mut().map(|recording| {
            let homes = homes(project);
            let values: Vec<f64> =
                self.pose.iter().zip(&homes).map(|(&at, &home)| f64::from(at) - f64::from(home)).collect();
            recording.recorder.sample(now_s, &values);
            ui.ctx().request_repaint();
            recording.recorder.phase(now_s)
        });
        match tab {
            Tab::Motions => {
                // Validated once per revision, not every frame.
                let revision = view.revision;
                if self.problems.as_ref().is_none_or(|(at, _)| *at != revision) {
                    self.problems = Some((revision, crate::project::validate_plen2(project)));
                }
                let problems = self.problems.as_ref().map_or(&[][..], |(_, problems)| &problems[..]);
                let panes = (&mut self.layout, &mut self.preview, &self.pose);
                self.motions.ui(ui, (view, problems), panes, actions);
            }
            Tab::PlayLists => self.play_lists.ui(ui, project, connected, &mut self.layout, words, actions),
            Tab::Board => {
                // Compared once per document revision and robot read, not every frame.
                let key = (view.revision, self.robot_reads);
                if self.slots.as_ref().is_none_or(|(at, _)| *at != key) {
                    self.slots = Some((key, slot_map(project, self.robot.as_ref())));
                }
                let robot = board::RobotView {
                    slots: self.slots.as_ref().map_or(&[][..], |(_, slots)| slots.as_slice()),
                    robot_read: self.robot.is_some(),
                    connected,
                    operation: view.operation(),
                    result: self.result.as_ref(),
                };
                board::robot_panel(ui, &robot, view.language, actions);
            }
            _ => {
                let joints = joints::JointsView {
                    project,
                    pose: &self.pose,
                    connected,
                    capture_slot: self.motions.selected_slot(project),
                    recording: phase,
                    selected: self.selected_joint,
                };
                let (mut side, open) = (self.layout.side_width, self.layout.view_open);
                let (layout, preview) = (&mut self.layout, &mut self.preview);
                crate::ui::layout::beside(ui, "plen2-joints", (&mut side, open), |ui, pane| match pane {
                    Pane::First => joints::ui(ui, &joints, layout, words, actions),
                    Pane::Second => preview.joints(ui, (project, &self.pose), self.selected_joint, words, actions),
                });
                self.layout.side_width = side;
            }
        }
    }
}

impl FamilyBoard for Plen2Ui {
    fn connection_extras(&mut self, ui: &mut egui::Ui, view: &ShellView<'_>, actions: &mut Vec<Action>) {
        let language = view.language;
        let words = language.strings();
        let pacing_label = ui.label(words.pacing);
        let mut pacing = self.pacing;
        let picked = egui::ComboBox::from_id_salt("pacing-picker")
            .selected_text(words::pacing_name(language, pacing))
            .show_ui(ui, |ui| {
                for option in PacingMode::ALL {
                    ui.selectable_value(&mut pacing, option, words::pacing_name(language, option));
                }
            });
        picked.response.labelled_by(pacing_label.id).on_hover_text(words.plen2().pacing_hint);
        if pacing != self.pacing {
            actions.push(Action::family(Plen2Action::SetPacing(pacing)));
        }
    }

    fn link_starter(&self, baud: u32) -> LinkStarter {
        link::starter(baud, self.pacing)
    }

    fn demo_link(&self, project: &Project, waker: crate::link::Waker) -> Result<BoardLink, StartError> {
        link::demo_link(project, self.pacing, waker)
    }

    fn notice(&mut self, shell: &mut Shell<'_>, notice: FamilyNotice) {
        if let Some(plen2::Plen2Notice::Widened(widened)) = notice.of(Family::Plen2) {
            // Not an error: the upload goes on, more carefully.
            shell.say(|language| widened.worded(language), false);
        }
    }

    fn demo_server(
        &self,
        _project: &Project,
        waker: crate::link::Waker,
    ) -> Option<Result<crate::ui::family::DemoServer, StartError>> {
        Some(link::demo_server(waker))
    }

    fn demo_connected(&self, words: &Strings) -> &'static str {
        words.plen2().msg_connected_demo_plen2
    }

    fn stop(&mut self, shell: &mut Shell<'_>) {
        // No motion is streamed and no joint walked any more; the robot stops and goes home.
        self.stream = None;
        self.slew = None;
        if let Some(link) = shell.link.as_mut() {
            let _ = link.stop();
        }
        shell.say(|language| language.strings().plen2().msg_plen2_stopped, false);
    }

    fn disconnected(&mut self) {
        self.stream = None;
        self.slew = None;
    }

    fn halt(&mut self) -> bool {
        self.preview.transport.halt()
    }

    /// Moves a streamed motion on, and takes written files' answers; whether something still plays.
    fn tick(&mut self, shell: &mut Shell<'_>, now: Instant) -> bool {
        self.finish_writing(shell);
        self.advance_slew(shell, now) | self.advance_stream(shell, now)
    }

    fn finish_operation(
        &mut self,
        shell: &mut Shell<'_>,
        wait: Option<std::time::Duration>,
    ) -> Option<crate::ui::shell::StatusLine> {
        let (_, outcome) = RunningOperation::finished::<Plen2Kind, Plen2Outcome, Plen2Item>(shell.operation, wait)?;
        self.finish(outcome);
        let (_, is_error) = self.summary(shell.language)?;
        Some(crate::ui::shell::StatusLine::worded(
            shell.language,
            |language| self.summary(language).map(|(text, _)| text).unwrap_or_default(),
            is_error,
        ))
    }
}

impl FamilyPad for Plen2Ui {
    fn pad_targets(&self, project: &Project) -> Vec<crate::ui::gamepad::PadTarget> {
        pad::targets(&project.plen2, &self.pose)
    }

    fn pad_fires(&self, project: &Project, words: &Strings) -> Vec<(crate::project::gamepad::Fire, String)> {
        pad::fires(&project.plen2, words)
    }

    fn pad_cue(&self, cue: crate::gamepad::puppet::Cue) -> Option<Action> {
        pad::cue(cue)
    }
}

impl FamilyPose for Plen2Ui {
    fn live_pose(&self) -> Option<LivePose> {
        Some(LivePose::indexed(Family::Plen2, &self.pose))
    }

    fn restore_pose(&mut self, shell: &mut Shell<'_>, pose: LivePose) {
        if pose.family == Family::Plen2 {
            Plen2Ui::restore_pose(self, shell, pose.to_array());
        }
    }
}

impl FamilyMemory for Plen2Ui {
    fn remember(&self, remembered: &mut crate::ui::remembered::Remembered) {
        remembered.plen2_pacing = self.pacing;
    }

    fn recall(&mut self, remembered: &crate::ui::remembered::Remembered) {
        self.pacing = remembered.plen2_pacing;
    }
}
