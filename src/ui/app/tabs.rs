//! The tab shown in the middle of the window: each family's panels, given
//! what they draw from the app's state.

use super::StudioApp;
use crate::device::servo::ServoImage;
use crate::project::{Family, validate_plen2};
use crate::ui::action::{Action, Tab};
use crate::ui::board_link::BoardLink;
use crate::ui::board_panel::{self, BoardView};
use crate::ui::drive_panel::DriveView;
use crate::ui::i18n::Strings;
use crate::ui::joystick_panel::JoystickView;
use crate::ui::plen2_board::slot_map;
use crate::ui::servo_panel::ServoView;

impl StudioApp {
    /// Draws the current tab's panel.
    pub(super) fn tab_panel(&mut self, ui: &mut egui::Ui, words: &'static Strings, actions: &mut Vec<Action>) {
        let family = self.document.project.family;
        match self.tab {
            Tab::Servos => {
                let view = ServoView {
                    project: &self.document.project.servo,
                    pose: &self.pose,
                    readback: self.link.as_ref().and_then(BoardLink::servo).map(|servo| &servo.servos),
                    polling: self.polling,
                };
                self.servo_panel.ui(ui, &view, words, actions);
                ui.separator();
                let open = &mut self.servo_panel.settings_open;
                crate::ui::servo_panel::settings_ui(ui, open, &self.document.project.servo, words, actions);
            }
            Tab::Actions => {
                let revision = self.document.revision();
                self.action_panel.ui(ui, &self.document.project.servo, revision, self.link.is_some(), words, actions);
            }
            Tab::Macros => {
                let revision = self.document.revision();
                self.macro_panel.ui(ui, &self.document.project.servo, revision, self.link.is_some(), words, actions);
            }
            Tab::Joystick => {
                let view = JoystickView {
                    project: &self.document.project.servo,
                    events: &self.button_events,
                    picked: self.picked_button,
                    picking: self.picking.is_some(),
                    connected: self.link.is_some(),
                };
                self.joystick_panel.ui(ui, &view, words, actions);
            }
            Tab::Drive => {
                let base = self.link.as_ref().and_then(BoardLink::rflex);
                let view = DriveView {
                    connected: base.is_some_and(|base| !base.is_lost()),
                    settings: self.document.project.rflex.drive,
                    limits: self.document.project.rflex.robot.limits(),
                    commanded: base.map_or((0.0, 0.0), |base| base.commanded),
                    measured: base
                        .map_or((0.0, 0.0), |base| (base.telemetry.speed_m_per_s, base.telemetry.turn_rad_per_s)),
                    brake: base.and_then(|base| base.telemetry.brake),
                    sonar_on: self.sonar_on,
                };
                self.drive_panel.ui(ui, &view, words, actions);
            }
            Tab::Joints => {
                let view = crate::ui::plen2_joints::JointsView {
                    project: &self.document.project.plen2,
                    pose: &self.plen2_pose,
                    connected: self.link.as_ref().is_some_and(|link| link.plen2().is_some()),
                    capture_slot: self.motions_panel.selected_slot(&self.document.project.plen2),
                };
                crate::ui::plen2_joints::ui(ui, &view, words, actions);
            }
            Tab::Motions => {
                // Validated once per revision, not every frame.
                let revision = self.document.revision();
                if self.plen2_problems.as_ref().is_none_or(|(at, _)| *at != revision) {
                    self.plen2_problems = Some((revision, validate_plen2(&self.document.project.plen2)));
                }
                let problems = self.plen2_problems.as_ref().map_or(&[][..], |(_, problems)| problems.as_slice());
                let connected = self.link.as_ref().is_some_and(|link| link.plen2().is_some());
                self.motions_panel.ui(
                    ui,
                    &self.document.project.plen2,
                    (revision, problems),
                    connected,
                    words,
                    actions,
                );
            }
            Tab::PlayLists => {
                let connected = self.link.as_ref().is_some_and(|link| link.plen2().is_some());
                self.play_lists_panel.ui(ui, &self.document.project.plen2, connected, words, actions);
            }
            Tab::Board if family == Family::Plen2 => {
                // Compared once per document revision and robot read, not every frame.
                let key = (self.document.revision(), self.plen2_robot_reads);
                if self.plen2_slots.as_ref().is_none_or(|(at, _)| *at != key) {
                    let slots = slot_map(&self.document.project.plen2, self.plen2_robot.as_ref());
                    self.plen2_slots = Some((key, slots));
                }
                let view = crate::ui::plen2_board::RobotView {
                    slots: self.plen2_slots.as_ref().map_or(&[][..], |(_, slots)| slots.as_slice()),
                    robot_read: self.plen2_robot.is_some(),
                    connected: self.link.as_ref().is_some_and(|link| link.plen2().is_some()),
                    job: self.plen2_job.as_ref(),
                    result: self.plen2_result.as_deref(),
                };
                crate::ui::plen2_board::robot_panel(ui, &view, words, actions);
            }
            Tab::Telemetry => match self.link.as_ref().and_then(BoardLink::rflex) {
                Some(base) => crate::ui::telemetry_panel::ui(ui, &base.telemetry, words),
                None => {
                    ui.label(words.not_connected);
                }
            },
            Tab::Log => match &mut self.link {
                Some(link) => link.log.ui(ui, words),
                None => {
                    ui.label(words.not_connected);
                    if !BoardLink::supports(family) {
                        ui.label(self.language.family_not_in_build(family));
                    }
                }
            },
            Tab::Board => {
                // Encoding every record takes milliseconds on a large project: once per
                // revision, off the frame path then.
                let language = self.language;
                let footprint = self.footprint.get(ui.ctx(), (self.document.revision(), language), || {
                    let project = self.document.project.servo.clone();
                    move || {
                        ServoImage::from_project(&project)
                            .map_err(|error| language.op_error(&crate::device::servo::OpError::Image(error)))
                            .and_then(|image| image.footprint_bytes().map_err(|error| error.to_string()))
                    }
                });
                let project_bytes = footprint.map_or(Ok(0), |(_, bytes)| bytes.clone());
                let view = BoardView {
                    connected: self.link.is_some(),
                    project_bytes,
                    board_total_bytes: self
                        .servo()
                        .and_then(|servo| servo.memory)
                        .map(|(free, total)| i64::from(total.unwrap_or(free))),
                    job: self.job.as_ref(),
                    pending: self.pending.as_ref(),
                    result: self.board_result.as_ref(),
                };
                board_panel::ui(ui, &view, words, actions);
            }
        }
    }
}
