//! A mobile base's sensors in numbers: battery with its trend, the odometry
//! pose, the pressed bump panels, the joystick, the reports dropped. Where
//! they are in the world (path, sonar, bumpers) the world view beside shows.

use egui_plot::{Line, Plot, PlotPoints};

use crate::device::rflex::Telemetry;
use crate::ui::i18n::Strings;
use crate::ui::plot;
use crate::ui::rflex::captions::RflexWords;

/// Draws the panel.
pub fn ui(ui: &mut egui::Ui, telemetry: &Telemetry, words: &Strings) {
    ui.horizontal(|ui| {
        ui.heading(words.telemetry);
        let volts = telemetry.battery_volts.map_or("—".to_string(), |v| format!("{v:.2} V"));
        ui.label(egui::RichText::new(format!("{} {volts}", words.battery)).size(18.0));
        let pose = &telemetry.pose;
        ui.monospace(format!(
            "{}: x {:+.3} m  y {:+.3} m  θ {:+.3} rad",
            words.rflex().odometry,
            pose.x_m,
            pose.y_m,
            pose.theta_rad
        ));
    });
    Plot::new("battery-trend").height(160.0).x_axis_label("s").y_axis_label("V").allow_scroll(false).show(ui, |plot| {
        let trend: Vec<[f64; 2]> = telemetry.battery_trend.iter().collect();
        let bounds = plot.plot_bounds();
        #[allow(clippy::cast_sign_loss, clippy::cast_possible_truncation)]
        let columns = plot.transform().frame().width().max(1.0) as usize;
        let thinned = plot::decimate(&trend, bounds.min()[0], bounds.max()[0], columns);
        plot.line(Line::new(words.battery, PlotPoints::from(thinned)));
    });
    // In the robot's style: a B21r's panels with their corners, a Magellan's bumpers.
    let pressed: Vec<String> = telemetry
        .pressed()
        .iter()
        .map(|bump| match bump {
            crate::device::rflex::Bump::Panel { panel, corners } => format!("{panel} ({corners:04b})"),
            crate::device::rflex::Bump::Bit { bumper } => format!("#{bumper}"),
        })
        .collect();
    let pressed = if pressed.is_empty() { "—".to_string() } else { pressed.join(", ") };
    ui.label(format!("{}: {pressed}", words.bumpers));
    let stick = telemetry
        .joystick
        .map_or("—".to_string(), |(x, y, buttons)| format!("x {x}  y {y}  {} {buttons:08b}", words.pad_buttons));
    ui.monospace(format!("{}: {stick}", words.rflex().joystick_state));
    ui.label(format!("{}: {}", words.checksum_failures, telemetry.checksum_failures));
    let echoing = telemetry.sonar_m.values().filter(|range| range.is_some()).count();
    let of = telemetry.layout().map_or(telemetry.sonar_m.len(), |layout| layout.sonar_count());
    let unknown = telemetry.unknown_sonar.len();
    let unknown = if unknown == 0 { String::new() } else { format!(" (+{unknown} ?)") };
    ui.label(format!("{}: {echoing}/{of}{unknown}", words.rflex().sonar))
        .on_hover_text(words.rflex().sonar_unknown_hint);
}

#[cfg(test)]
mod tests {
    use egui_kittest::Harness;
    use egui_kittest::kittest::Queryable;

    use super::*;
    use crate::ui::i18n::Language;

    fn panel(telemetry: Telemetry, language: Language) -> Harness<'static, Telemetry> {
        Harness::builder()
            .with_size(egui::vec2(900.0, 500.0))
            .with_context_setup(crate::ui::fonts::install)
            .build_ui_state(
                move |ui, telemetry: &mut Telemetry| super::ui(ui, telemetry, language.strings()),
                telemetry,
            )
    }

    #[test]
    fn the_numbers_of_a_base_are_shown_and_the_unknown_as_dashes() {
        let mut telemetry = Telemetry::default();
        let harness = panel(telemetry.clone(), Language::English);
        assert!(harness.query_by_label_contains("Battery —").is_some(), "no battery read yet");
        assert!(harness.query_by_label_contains("x +0.000 m").is_some());

        telemetry.battery_volts = Some(24.376);
        telemetry.joystick = Some((12, -3, 0b101));
        telemetry.checksum_failures = 2;
        telemetry.sonar_m.insert(0, Some(1.5));
        telemetry.sonar_m.insert(1, None);
        telemetry.unknown_sonar.insert(40, 700);
        let harness = panel(telemetry, Language::English);
        assert!(harness.query_by_label_contains("24.38 V").is_some(), "volts to the hundredth");
        assert!(harness.query_by_label_contains("x 12  y -3  Buttons 00000101").is_some());
        assert!(harness.query_by_label_contains(": 2").is_some(), "checksum failures counted");
        assert!(harness.query_by_label_contains("1/2 (+1 ?)").is_some(), "echoing of known, unknown ids apart");
    }

    #[test]
    fn the_panel_speaks_traditional_chinese() {
        let harness = panel(Telemetry::default(), Language::TraditionalChinese);
        let words = Language::TraditionalChinese.strings();
        assert!(harness.query_by_label_contains(words.battery).is_some());
        assert!(harness.query_by_label(words.telemetry).is_some());
    }
}
