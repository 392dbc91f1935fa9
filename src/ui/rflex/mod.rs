//! The rFLEX base's side of the editor: its state (the sonar, the drive
//! pad's request), its panels (drive, telemetry), and what it does with the
//! actions its panels push. A base is never left driving: leaving the Drive
//! tab, losing the window's focus, STOP and a closed link all stop it.

mod drive;
mod telemetry;

pub use drive::{DrivePanel, DriveView};

use crate::ui::action::{Action, RflexAction, Tab};
use crate::ui::app::{Shell, ShellView};
use crate::ui::layout::Layout;

/// The rFLEX base's state in the editor.
#[derive(Debug, Default)]
pub struct RflexUi {
    /// Whether the base's sonar ring was turned on.
    pub sonar_on: bool,
    drive: DrivePanel,
    /// How the family's panels are laid out (remembered).
    pub layout: Layout,
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

    /// Draws the tab.
    pub fn ui(&mut self, ui: &mut egui::Ui, tab: Tab, view: &ShellView<'_>, actions: &mut Vec<Action>) {
        let words = view.language.strings();
        let base = view.link.and_then(|link| link.rflex());
        match tab {
            Tab::Telemetry => match base {
                Some(base) => telemetry::ui(ui, &base.telemetry, words),
                None => {
                    ui.label(words.not_connected);
                }
            },
            _ => {
                let rflex = &view.project.rflex;
                let drive = DriveView {
                    connected: base.is_some_and(|base| !base.is_lost()),
                    settings: rflex.drive,
                    limits: rflex.robot.limits(),
                    commanded: base.map_or((0.0, 0.0), |base| base.commanded),
                    measured: base
                        .map_or((0.0, 0.0), |base| (base.telemetry.speed_m_per_s, base.telemetry.turn_rad_per_s)),
                    brake: base.and_then(|base| base.telemetry.brake),
                    sonar_on: self.sonar_on,
                };
                self.drive.ui(ui, &drive, words, actions);
            }
        }
    }
}
