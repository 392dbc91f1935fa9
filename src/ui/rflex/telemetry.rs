//! A mobile base's sensors: battery with its trend, the odometry pose and the
//! driven path, the sonar ring as a polar view around the robot, the bump
//! panels (lit when pressed) and the joystick.

// Screen coordinates are f32: drawing an f64 quantity loses nothing visible.
#![allow(clippy::cast_possible_truncation)]

use egui_plot::{Line, Plot, PlotPoints, Points};

use crate::device::rflex::Telemetry;
use crate::ui::i18n::Strings;
use crate::ui::plot;

/// Metres the polar view's edge stands for (the sonar's longest echo is 2.03 m).
const POLAR_RANGE_M: f64 = 2.2;
/// Sonars in the drawn ring.
const RING: u8 = 24;

/// Draws the panel.
pub fn ui(ui: &mut egui::Ui, telemetry: &Telemetry, words: &Strings) {
    ui.horizontal(|ui| {
        ui.heading(words.telemetry);
        let volts = telemetry.battery_volts.map_or("—".to_string(), |v| format!("{v:.2} V"));
        ui.label(egui::RichText::new(format!("{} {volts}", words.battery)).size(18.0));
        let pose = &telemetry.pose;
        ui.monospace(format!(
            "{}: x {:+.3} m  y {:+.3} m  θ {:+.3} rad",
            words.odometry, pose.x_m, pose.y_m, pose.theta_rad
        ));
    });
    ui.horizontal_top(|ui| {
        ui.vertical(|ui| {
            ui.set_width(360.0);
            Plot::new("battery-trend").height(120.0).x_axis_label("s").y_axis_label("V").allow_scroll(false).show(
                ui,
                |plot| {
                    let trend: Vec<[f64; 2]> = telemetry.battery_trend.iter().collect();
                    let bounds = plot.plot_bounds();
                    #[allow(clippy::cast_sign_loss)]
                    let columns = plot.transform().frame().width().max(1.0) as usize;
                    let thinned = plot::decimate(&trend, bounds.min()[0], bounds.max()[0], columns);
                    plot.line(Line::new(words.battery, PlotPoints::from(thinned)));
                },
            );
            Plot::new("odometry-path")
                .height(240.0)
                .data_aspect(1.0)
                .x_axis_label("x (m)")
                .y_axis_label("y (m)")
                .allow_scroll(false)
                .show(ui, |plot| {
                    // Points closer than a pixel add nothing but cost.
                    let per_pixel = plot.transform().dvalue_dpos().map(f64::abs);
                    let path = plot::thin_path(telemetry.path.iter(), per_pixel);
                    plot.line(Line::new(words.odometry, PlotPoints::from(path)));
                    let here = [telemetry.pose.x_m, telemetry.pose.y_m];
                    plot.points(Points::new("", vec![here]).radius(5.0));
                });
        });
        ui.vertical(|ui| {
            ui.label(words.sonar);
            sonar_ring(ui, telemetry);
            ui.label(words.bumpers);
            bumpers(ui, telemetry);
            let stick = telemetry
                .joystick
                .map_or("—".to_string(), |(x, y, buttons)| format!("x {x}  y {y}  buttons {buttons:08b}"));
            ui.monospace(format!("{}: {stick}", words.joystick_state));
            ui.label(format!("{}: {}", words.checksum_failures, telemetry.checksum_failures));
        });
    });
}

/// The ring around the robot, heading up: each sonar a ray to its echo.
fn sonar_ring(ui: &mut egui::Ui, telemetry: &Telemetry) {
    let size = 240.0;
    let (rect, _) = ui.allocate_exact_size(egui::vec2(size, size), egui::Sense::hover());
    let painter = ui.painter_at(rect);
    let visuals = ui.visuals();
    let center = rect.center();
    let scale = f64::from(size / 2.0 - 6.0) / POLAR_RANGE_M;
    for metres in [0.5, 1.0, 1.5, 2.0] {
        painter.circle_stroke(center, (metres * scale) as f32, visuals.widgets.noninteractive.bg_stroke);
    }
    painter.circle_filled(center, 12.0, visuals.widgets.inactive.bg_fill);
    painter.line_segment([center, center - egui::vec2(0.0, 18.0)], egui::Stroke::new(2.0, visuals.text_color()));
    for (&id, &range) in &telemetry.sonar_m {
        // Sonar 0 faces ahead (up); ids go round counter-clockwise.
        let angle = f64::from(id) * std::f64::consts::TAU / f64::from(RING);
        let direction = egui::vec2(-(angle.sin() as f32), -(angle.cos() as f32));
        match range {
            Some(metres) => {
                let end = center + direction * (metres.min(POLAR_RANGE_M) * scale) as f32;
                painter.line_segment([center, end], egui::Stroke::new(1.0, visuals.weak_text_color()));
                painter.circle_filled(end, 3.5, egui::Color32::from_rgb(40, 170, 220));
            }
            None => {
                let end = center + direction * (POLAR_RANGE_M * scale) as f32;
                painter.circle_stroke(end, 3.0, egui::Stroke::new(1.0, visuals.weak_text_color()));
            }
        }
    }
}

/// Four panels around the robot, lit when any corner is pressed.
fn bumpers(ui: &mut egui::Ui, telemetry: &Telemetry) {
    let (rect, _) = ui.allocate_exact_size(egui::vec2(120.0, 120.0), egui::Sense::hover());
    let painter = ui.painter_at(rect);
    let visuals = ui.visuals();
    let c = rect.center();
    let panels = [
        egui::Rect::from_center_size(c - egui::vec2(0.0, 45.0), egui::vec2(70.0, 16.0)),
        egui::Rect::from_center_size(c + egui::vec2(45.0, 0.0), egui::vec2(16.0, 70.0)),
        egui::Rect::from_center_size(c + egui::vec2(0.0, 45.0), egui::vec2(70.0, 16.0)),
        egui::Rect::from_center_size(c - egui::vec2(45.0, 0.0), egui::vec2(16.0, 70.0)),
    ];
    for (panel, shape) in (0u8..).zip(panels) {
        let pressed = telemetry.bumpers.get(&panel).is_some_and(|corners| *corners != 0);
        let fill = if pressed { egui::Color32::from_rgb(220, 40, 40) } else { visuals.widgets.inactive.bg_fill };
        painter.rect_filled(shape, 3.0, fill);
    }
    painter.circle_stroke(c, 30.0, visuals.widgets.noninteractive.bg_stroke);
}
