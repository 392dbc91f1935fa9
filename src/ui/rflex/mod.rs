//! The rFLEX base's side of the editor: its state (the sonar, the drive
//! pad's request), its panels (drive, telemetry), and what it does with the
//! actions its panels push. A base is never left driving: leaving the Drive
//! tab, losing the window's focus, STOP and a closed link all stop it.

mod drive;
mod telemetry;
mod world;

pub use drive::{DrivePanel, DriveView};
pub use world::WorldView;

use crate::ui::action::{Action, RflexAction, Tab};
use crate::ui::app::{Shell, ShellView};
use crate::ui::layout::{self, Layout, Pane};

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
}

impl Default for RflexUi {
    fn default() -> Self {
        Self {
            sonar_on: false,
            drive: DrivePanel::default(),
            world: WorldView::default(),
            // The world view is the larger part of the base's panels.
            layout: Layout { side_width: 520.0, ..Layout::default() },
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
                    let words = shell.words();
                    shell.report(if on { words.msg_brake_on } else { words.msg_brake_released }, false);
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

    /// A new connection: the sonar as the project starts it, the pad at rest.
    pub fn connected(&mut self, sonar_on_connect: bool) {
        self.sonar_on = sonar_on_connect;
        self.drive = DrivePanel::default();
    }

    /// The base was told to stop (STOP, silence): the pad forgets what it asked.
    pub fn stopped(&mut self) {
        self.drive = DrivePanel::default();
    }

    /// What the pad asks the base for now (m/s, rad/s).
    pub fn drive_asked(&self) -> (f64, f64) {
        self.drive.asked()
    }

    /// Draws the tab: the drive pad or the telemetry, with the world view beside it.
    pub fn ui(&mut self, ui: &mut egui::Ui, tab: Tab, view: &ShellView<'_>, actions: &mut Vec<Action>) {
        let words = view.language.strings();
        let base = view.link.and_then(|link| link.rflex());
        let telemetry = base.map(|base| &base.telemetry);
        let Self { drive, world, layout, sonar_on } = self;
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
            }
        });
    }
}
