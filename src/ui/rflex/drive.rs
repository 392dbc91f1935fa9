//! The Drive panel for a mobile base: a drag pad and the arrow keys for
//! translation and rotation within the project's limits, a big STOP (Space,
//! Esc), brake and sonar toggles, and the commanded and measured velocities.
//! It never leaves a base driving: releasing the pad or the keys, or the
//! window losing focus, sends a stop in the same frame.

// Screen coordinates are f32: drawing an f64 quantity loses nothing visible.
#![allow(clippy::cast_possible_truncation)]

use crate::project::Edit;
use crate::project::rflex::{DriveSettings, SpeedLimits};
use crate::ui::action::Action;
use crate::ui::i18n::Strings;
use crate::ui::rflex::action::RflexAction;
use crate::ui::rflex::captions::RflexWords;

/// Side of the drag pad, points.
const PAD_SIZE: f32 = 220.0;

/// What the panel shows.
#[derive(Debug)]
pub struct DriveView {
    /// Whether a base is connected (else nothing is sent).
    pub connected: bool,
    /// The project's limits.
    pub settings: DriveSettings,
    /// The most the robot's preset allows (the settings never go past it).
    pub limits: SpeedLimits,
    /// What the base is told (m/s, rad/s).
    pub commanded: (f64, f64),
    /// What the base reports (m/s, rad/s).
    pub measured: (f64, f64),
    /// The brake as the base reports it.
    pub brake: Option<bool>,
    /// Whether the sonar ring was turned on.
    pub sonar_on: bool,
}

/// The panel's own state: the velocity it last asked for.
#[derive(Debug, Default)]
pub struct DrivePanel {
    asked: (f64, f64),
}

/// The velocity the held arrow keys ask for.
fn from_keys(ui: &egui::Ui, settings: &DriveSettings) -> (f64, f64) {
    ui.input(|input| {
        let axis = |plus: egui::Key, minus: egui::Key| {
            f64::from(i8::from(input.key_down(plus)) - i8::from(input.key_down(minus)))
        };
        (
            axis(egui::Key::ArrowUp, egui::Key::ArrowDown) * settings.max_speed_m_per_s,
            axis(egui::Key::ArrowLeft, egui::Key::ArrowRight) * settings.max_turn_rad_per_s,
        )
    })
}

impl DrivePanel {
    /// What the panel asked for last (for tests and the status line).
    pub fn asked(&self) -> (f64, f64) {
        self.asked
    }

    fn ask(&mut self, wanted: (f64, f64), actions: &mut Vec<Action>) {
        if wanted == self.asked {
            return;
        }
        self.asked = wanted;
        // A key or the pad let go stops the base at once (a drive of nothing):
        // it is no STOP, so the next key drives again without Resume.
        actions.push(Action::family(RflexAction::Drive { speed_m_per_s: wanted.0, turn_rad_per_s: wanted.1 }));
    }

    /// Draws the panel.
    pub fn ui(&mut self, ui: &mut egui::Ui, view: &DriveView, words: &Strings, actions: &mut Vec<Action>) {
        if !view.connected {
            // Nothing to drive: forget what was asked, so a new link starts at rest.
            self.asked = (0.0, 0.0);
        }
        ui.horizontal(|ui| self.buttons(ui, view, words, actions));
        ui.label(words.rflex().pad_hint);
        ui.horizontal_top(|ui| {
            let (rect, response) = ui.allocate_exact_size(egui::vec2(PAD_SIZE, PAD_SIZE), egui::Sense::drag());
            let painter = ui.painter_at(rect);
            let visuals = ui.visuals();
            painter.rect_filled(rect, 8.0, visuals.extreme_bg_color);
            painter.line_segment([rect.center_top(), rect.center_bottom()], visuals.widgets.noninteractive.bg_stroke);
            painter.line_segment([rect.left_center(), rect.right_center()], visuals.widgets.noninteractive.bg_stroke);
            let half = f64::from(PAD_SIZE / 2.0);
            let settings = view.settings;
            let from_pad = response.interact_pointer_pos().filter(|_| response.dragged()).map(|pointer| {
                let offset = (pointer - rect.center())
                    .clamp(egui::vec2(-PAD_SIZE, -PAD_SIZE) / 2.0, egui::vec2(PAD_SIZE, PAD_SIZE) / 2.0);
                (
                    -f64::from(offset.y) / half * settings.max_speed_m_per_s,
                    -f64::from(offset.x) / half * settings.max_turn_rad_per_s,
                )
            });
            // The marker shows what is asked for.
            let marker = rect.center()
                + egui::vec2(
                    (-self.asked.1 / settings.max_turn_rad_per_s.max(1e-9) * half) as f32,
                    (-self.asked.0 / settings.max_speed_m_per_s.max(1e-9) * half) as f32,
                );
            painter.circle_filled(marker, 10.0, visuals.selection.bg_fill);
            ui.vertical(|ui| readings(ui, view, words, actions));
            // Keys count only when no field has the keyboard, and only while the window has focus.
            let keys_free = ui.memory(|memory| memory.focused().is_none());
            let focused = ui.input(|input| input.focused);
            if keys_free && ui.input_mut(|input| input.consume_key(egui::Modifiers::NONE, egui::Key::Space)) {
                self.asked = (0.0, 0.0);
                actions.push(Action::Stop);
            }
            if view.connected && !focused {
                // Keys and the pad do nothing without the window's focus: say why.
                ui.colored_label(ui.visuals().warn_fg_color, words.rflex().drive_needs_focus);
            }
            let wanted = if !view.connected || !focused {
                (0.0, 0.0)
            } else if let Some(pad) = from_pad {
                pad
            } else if keys_free {
                from_keys(ui, &settings)
            } else {
                (0.0, 0.0)
            };
            if view.connected {
                self.ask(wanted, actions);
            }
        });
    }

    /// STOP, the brake and the sonar.
    fn buttons(&mut self, ui: &mut egui::Ui, view: &DriveView, words: &Strings, actions: &mut Vec<Action>) {
        ui.heading(words.drive);
        let stop = egui::Button::new(
            egui::RichText::new(format!("■ {}", words.stop)).strong().size(22.0).color(egui::Color32::WHITE),
        )
        .fill(egui::Color32::from_rgb(200, 30, 30))
        .min_size(egui::vec2(140.0, 40.0));
        if ui.add(stop).on_hover_text("Space / Esc").clicked() {
            self.asked = (0.0, 0.0);
            actions.push(Action::Stop);
        }
        let braked = view.brake.unwrap_or(true);
        let brake = ui.add_enabled(view.connected, egui::Button::new(words.brake).selected(braked));
        if brake.clicked() {
            self.asked = (0.0, 0.0);
            actions.push(Action::family(RflexAction::SetBrake(!braked)));
        }
        if ui.add_enabled(view.connected, egui::Button::new(words.rflex().sonar).selected(view.sonar_on)).clicked() {
            actions.push(Action::family(RflexAction::SetSonar(!view.sonar_on)));
        }
    }
}

/// What is commanded and measured, and the drive limits (one undo step per drag).
fn readings(ui: &mut egui::Ui, view: &DriveView, words: &Strings, actions: &mut Vec<Action>) {
    let settings = view.settings;
    let row = |ui: &mut egui::Ui, label: &str, (speed, turn): (f64, f64)| {
        ui.monospace(format!("{label:<10} {speed:+.2} m/s  {turn:+.2} rad/s"));
    };
    row(ui, words.commanded, view.commanded);
    row(ui, words.rflex().measured, view.measured);
    ui.separator();
    let mut changed = settings;
    let limits = view.limits;
    let speed = 0.05..=limits.max_speed_m_per_s;
    ui.add(egui::Slider::new(&mut changed.max_speed_m_per_s, speed).text(words.rflex().max_speed));
    let turn = 0.1..=limits.max_turn_rad_per_s;
    ui.add(egui::Slider::new(&mut changed.max_turn_rad_per_s, turn).text(words.rflex().max_turn));
    let accel = 0.1..=limits.max_accel_m_per_s2;
    ui.add(egui::Slider::new(&mut changed.accel_m_per_s2, accel).text(words.rflex().acceleration));
    if changed != settings {
        actions.push(Action::Edit { edit: Edit::SetRflexDrive(changed), coalesce: Some("rflex drive".into()) });
    }
}

#[cfg(test)]
mod tests {
    use egui_kittest::Harness;
    use egui_kittest::kittest::Queryable;

    use super::*;
    use crate::project::rflex::Robot;
    use crate::ui::i18n::Language;

    type Panel = (DrivePanel, Vec<Action>);

    fn drive(connected: bool) -> Harness<'static, Panel> {
        let view = DriveView {
            connected,
            settings: DriveSettings::default(),
            limits: Robot::B21r.limits(),
            commanded: (0.0, 0.0),
            measured: (0.0, 0.0),
            brake: Some(true),
            sonar_on: false,
        };
        Harness::builder()
            .with_size(egui::vec2(760.0, 420.0))
            .with_context_setup(crate::ui::fonts::install)
            .build_ui_state(
                move |ui, (panel, actions): &mut Panel| panel.ui(ui, &view, Language::English.strings(), actions),
                (DrivePanel::default(), Vec::new()),
            )
    }

    fn drove(actions: &[Action]) -> Vec<(f64, f64)> {
        actions
            .iter()
            .filter_map(|action| match action.family_action() {
                Some(RflexAction::Drive { speed_m_per_s, turn_rad_per_s }) => Some((*speed_m_per_s, *turn_rad_per_s)),
                _ => None,
            })
            .collect()
    }

    #[test]
    fn an_arrow_held_drives_at_the_top_speed_and_letting_go_stops_in_the_same_frame() {
        let mut harness = drive(true);
        harness.run();
        harness.key_down(egui::Key::ArrowUp);
        harness.key_down(egui::Key::ArrowLeft);
        harness.step();
        let top = DriveSettings::default();
        let asked = drove(&harness.state().1);
        assert_eq!(asked.last(), Some(&(top.max_speed_m_per_s, top.max_turn_rad_per_s)), "{asked:?}");
        harness.key_up(egui::Key::ArrowUp);
        harness.key_up(egui::Key::ArrowLeft);
        harness.step();
        let stopped = Action::family(RflexAction::Drive { speed_m_per_s: 0.0, turn_rad_per_s: 0.0 });
        assert_eq!(harness.state().1.last(), Some(&stopped), "released: stopped at once");
        assert_eq!(harness.state().0.asked(), (0.0, 0.0));
    }

    #[test]
    fn space_stops_a_base_driving_on_its_keys() {
        let mut harness = drive(true);
        harness.key_down(egui::Key::ArrowDown);
        harness.step();
        assert_eq!(drove(&harness.state().1), [(-DriveSettings::default().max_speed_m_per_s, 0.0)]);
        harness.key_press(egui::Key::Space);
        harness.step();
        assert!(harness.state().1.contains(&Action::Stop));
        harness.key_up(egui::Key::ArrowDown);
    }

    #[test]
    fn with_no_base_nothing_is_sent_and_brake_and_sonar_are_off() {
        let mut harness = drive(false);
        harness.key_down(egui::Key::ArrowUp);
        harness.step();
        harness.get_by_label("Brake").click();
        harness.get_by_label("Sonar").click();
        harness.step();
        harness.key_up(egui::Key::ArrowUp);
        harness.step();
        assert_eq!(harness.state().1, [], "no command without a base");
    }
}
