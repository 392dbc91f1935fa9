//! The rFLEX base's side of the editor: its state (the sonar, the drive
//! pad's request), its panels (drive, telemetry), and what it does with the
//! actions its panels push. A base is never left driving: leaving the Drive
//! tab, losing the window's focus, STOP and a closed link all stop it.

mod action;
mod captions;
mod drive;
mod link;
mod pad;
mod show_cue;
mod telemetry;
mod words;
mod world;

pub use action::RflexAction;
pub use drive::{DrivePanel, DriveView};
pub use link::RflexBoardLink;
pub(crate) use link::RflexLink;
pub use world::WorldView;

use crate::device::rflex::RflexNotice;
use crate::gamepad::puppet::Cue;
use crate::project::gamepad::Fire;
use crate::project::rflex::Robot;
use crate::project::{Family, Project};
use crate::ui::action::{Action, Tab};
use crate::ui::board_link::{BoardLink, FamilyNotice, LinkStarter, StartError};
use crate::ui::family::{FamilyBoard, FamilyMemory, FamilyPad, FamilyPanels, FamilyPose, FamilyUi, Panel};
use crate::ui::i18n::Strings;
use crate::ui::layout::{self, Layout, Pane};
use crate::ui::rflex::captions::RflexWords;
use crate::ui::shell::{Shell, ShellView};

#[allow(non_upper_case_globals)]
impl Tab {
    /// Driving a mobile base.
    pub const Drive: Self = Self::named("Drive");
    /// A mobile base's sensors.
    pub const Telemetry: Self = Self::named("Telemetry");
}

/// The rFLEX base's state in the editor.
#[derive(Debug)]
pub struct RflexUi {
    /// Whether the base's sonar ring was turned on.
    pub sonar_on: bool,
    drive: DrivePanel,
    /// The world view's camera (the Drive and Telemetry tabs share it).
    pub world: WorldView,
    /// How the family's panels are laid out (remembered).
    pub layout: Layout,
    /// A gamepad driving the base.
    pub pad: pad::PadDrive,
}

impl Default for RflexUi {
    fn default() -> Self {
        Self {
            sonar_on: false,
            drive: DrivePanel::default(),
            world: WorldView::default(),
            // The world view is the larger part of the base's panels.
            layout: Layout { side_width: 520.0, ..Layout::default() },
            pad: pad::PadDrive::default(),
        }
    }
}

impl RflexUi {
    /// Applies one of the family's actions.
    pub fn apply(&mut self, shell: &mut Shell<'_>, action: RflexAction) {
        match action {
            RflexAction::Drive { speed_m_per_s, turn_rad_per_s } => {
                // Never past what the robot's preset allows, whatever a file or a panel asked for.
                let rflex = &shell.document.project.rflex;
                let limits = rflex.robot.limits();
                let speed = speed_m_per_s.clamp(-limits.max_speed_m_per_s, limits.max_speed_m_per_s);
                let turn = turn_rad_per_s.clamp(-limits.max_turn_rad_per_s, limits.max_turn_rad_per_s);
                let accel = rflex.drive.accel_m_per_s2.min(limits.max_accel_m_per_s2);
                if let Some(base) = shell.rflex_mut() {
                    base.drive(speed, turn, accel);
                }
            }
            RflexAction::SetRobot(robot) => {
                if shell.link.is_none() {
                    shell.document.apply(crate::project::Edit::SetRflexRobot(robot), None);
                }
            }
            RflexAction::SetBrake(on) => {
                if let Some(base) = shell.rflex_mut() {
                    base.set_brake(on);
                    // The connection message said "braked": the status follows the brake.
                    let said = |language: crate::ui::i18n::Language| {
                        let words = language.strings().rflex();
                        if on { words.msg_brake_on } else { words.msg_brake_released }
                    };
                    shell.say(said, false);
                }
            }
            RflexAction::SetSonar(on) => {
                if let Some(base) = shell.rflex_mut() {
                    base.set_sonar(on);
                    self.sonar_on = on;
                }
            }
            RflexAction::ClearMap => {
                if let Some(base) = shell.rflex_mut() {
                    base.telemetry.echoes.clear();
                }
            }
        }
    }

    /// What the pad asks the base for now (m/s, rad/s).
    pub fn drive_asked(&self) -> (f64, f64) {
        self.drive.asked()
    }
}

impl FamilyUi for RflexUi {
    fn act(&mut self, shell: &mut Shell<'_>, action: Box<dyn crate::ui::action::FamilyAction>) {
        match action.into_any().downcast::<RflexAction>() {
            Ok(action) => self.apply(shell, *action),
            Err(_) => {
                crate::ui::board_link::misrouted(Family::Rflex, "an action", std::any::type_name::<RflexAction>());
            }
        }
    }

    fn family(&self) -> Family {
        Family::Rflex
    }
}

impl FamilyPanels for RflexUi {
    fn panels(&self) -> &'static [Panel] {
        &[
            Panel { tab: Tab::Drive, title: |words| words.drive, has_view: true },
            Panel { tab: Tab::Telemetry, title: |words| words.telemetry, has_view: true },
        ]
    }

    fn view_caption(&self, words: &Strings) -> &'static str {
        words.rflex().world_view
    }

    fn layout(&self) -> Layout {
        self.layout
    }

    fn layout_mut(&mut self) -> &mut Layout {
        &mut self.layout
    }

    fn while_showing(&self, tab: Tab) -> Option<Action> {
        // The pad, the keys and the gamepad live on the Drive tab: leaving it is letting go.
        let driving = self.drive_asked() != (0.0, 0.0) || self.pad.driving();
        (tab != Tab::Drive && driving)
            .then(|| Action::family(RflexAction::Drive { speed_m_per_s: 0.0, turn_rad_per_s: 0.0 }))
    }

    /// Draws the tab: the drive pad or the telemetry, with the world view beside it.
    fn ui(&mut self, ui: &mut egui::Ui, tab: Tab, view: &ShellView<'_>, actions: &mut Vec<Action>) {
        let words = view.language.strings();
        let base = view.link.and_then(|link| link.rflex());
        let telemetry = base.map(|base| &base.telemetry);
        let Self { drive, world, layout, sonar_on, pad } = self;
        let open = layout.view_open;
        layout::beside(ui, "rflex-world", (&mut layout.side_width, open), |ui, pane| match (pane, tab) {
            (Pane::Second, _) => world::panel(ui, world, telemetry, words, actions),
            (Pane::First, Tab::Telemetry) => match telemetry {
                Some(telemetry) => telemetry::ui(ui, telemetry, words),
                None => {
                    ui.label(words.not_connected);
                }
            },
            (Pane::First, _) => {
                let rflex = &view.project.rflex;
                let shown = DriveView {
                    connected: base.is_some_and(|base| !base.is_lost()),
                    settings: rflex.drive,
                    limits: rflex.robot.limits(),
                    commanded: base.map_or((0.0, 0.0), |base| base.commanded),
                    measured: base
                        .map_or((0.0, 0.0), |base| (base.telemetry.speed_m_per_s, base.telemetry.turn_rad_per_s)),
                    brake: base.and_then(|base| base.telemetry.brake),
                    sonar_on: *sonar_on,
                };
                drive.ui(ui, &shown, words, actions);
                ui.separator();
                pad.ui(ui, words);
            }
        });
    }
}

impl FamilyBoard for RflexUi {
    fn connection_extras(&mut self, ui: &mut egui::Ui, view: &ShellView<'_>, actions: &mut Vec<Action>) {
        let words = view.language.strings();
        let current = view.project.rflex.robot;
        let robot_label = ui.label(words.robot);
        let mut robot = current;
        let picked =
            egui::ComboBox::from_id_salt("robot-picker").selected_text(robot_name(current)).show_ui(ui, |ui| {
                for option in [Robot::B21r, Robot::AtrvJr, Robot::Magellan] {
                    ui.selectable_value(&mut robot, option, robot_name(option));
                }
            });
        picked.response.labelled_by(robot_label.id);
        if robot != current {
            actions.push(Action::family(RflexAction::SetRobot(robot)));
        }
    }

    fn link_details(&self, link: &BoardLink, words: &Strings) -> Vec<String> {
        let volts = link.rflex().and_then(|base| base.telemetry.battery_volts);
        volts.map(|volts| format!("{} {volts:.2} V", words.battery)).into_iter().collect()
    }

    fn link_starter(&self, _baud: u32) -> LinkStarter {
        link::starter()
    }

    fn demo_link(&self, project: &Project, waker: crate::link::Waker) -> Result<BoardLink, StartError> {
        link::demo_link(project, waker)
    }

    fn demo_connected(&self, words: &Strings) -> &'static str {
        words.rflex().msg_connected_demo_rflex
    }

    fn demo_server(
        &self,
        project: &Project,
        waker: crate::link::Waker,
    ) -> Option<Result<crate::ui::family::DemoServer, StartError>> {
        Some(link::demo_server(project, waker))
    }

    fn stop(&mut self, shell: &mut Shell<'_>) {
        self.disconnected();
        self.pad.halt(shell);
        if let Some(link) = shell.link.as_mut() {
            // Both axes to 0 at once (never fails; a lost link is reported by pump).
            let _ = link.stop();
        }
        shell.say(|language| language.strings().rflex().msg_base_stopped, false);
    }

    /// A new connection: the sonar as the project starts it, the pad at rest.
    fn connected(&mut self, project: &Project) {
        self.sonar_on = project.rflex.drive.sonar_on_connect;
        self.drive = DrivePanel::default();
    }

    /// The base was told to stop (STOP, silence, a lost link): the pad forgets what it asked.
    fn disconnected(&mut self) {
        self.drive = DrivePanel::default();
    }

    fn notice(&mut self, shell: &mut Shell<'_>, notice: FamilyNotice) {
        if notice.of::<RflexNotice>(Family::Rflex) == Some(&RflexNotice::Silent) {
            self.disconnected();
            shell.say(|language| language.strings().rflex().msg_base_silent, true);
        }
    }
}

impl FamilyPad for RflexUi {
    /// Drives the base by the gamepad's stick while the Drive tab is shown.
    fn pad_drive(
        &mut self,
        shell: &mut Shell<'_>,
        now: std::time::Instant,
        updates: &[(std::time::Instant, crate::gamepad::PadUpdate)],
        armed: bool,
        tab: Tab,
    ) -> bool {
        let rflex = &shell.document.project.rflex;
        let (settings, accel) = (rflex.drive, rflex.drive.accel_m_per_s2.min(rflex.robot.limits().max_accel_m_per_s2));
        self.pad.drive(shell, now, updates, armed && tab == Tab::Drive, &settings, accel)
    }

    fn pad_fires(&self, _project: &Project, words: &Strings) -> Vec<(Fire, String)> {
        vec![(Fire::Stop, words.stop.to_string()), (Fire::Brake, words.brake.to_string())]
    }

    fn pad_cue(&self, cue: Cue) -> Option<Action> {
        match cue {
            Cue::Fire(Fire::Stop) => Some(Action::Stop),
            Cue::Fire(Fire::Brake) => Some(Action::family(RflexAction::SetBrake(true))),
            _ => None,
        }
    }

    fn pad_reserved(&self) -> &'static [u16] {
        &[crate::gamepad::BTN_TL]
    }
}

impl FamilyPose for RflexUi {}

impl FamilyMemory for RflexUi {}

/// A robot preset's name.
fn robot_name(robot: Robot) -> &'static str {
    match robot {
        Robot::B21r => "B21r",
        Robot::AtrvJr => "ATRV-Jr",
        Robot::Magellan => "Magellan",
        Robot::Custom { .. } => "custom",
    }
}
