//! A base's cues in the show window: each a drive — its speed, its turn and
//! how long it lasts — set by dragging.

use crate::project::{Family, Project};
use crate::show::Start;
use crate::ui::show_cue::{CueUi, CueWords};

inventory::submit! {
    CueUi { family: Family::Rflex, caption, choose }
}

/// "drive 0.20 m/s 15°/s".
fn caption(start: &Start, _project: Option<&Project>, words: &CueWords) -> Option<String> {
    let Start::Drive { speed_m_s, turn_deg_s, .. } = *start else { return None };
    Some(format!("{} {speed_m_s:.2} m/s {turn_deg_s:.0}°/s", words.drive_word))
}

/// Its speed, turn and length.
fn choose(ui: &mut egui::Ui, (_, named): (usize, egui::Id), start: &mut Start, _project: &Project, _words: &CueWords) {
    let Start::Drive { speed_m_s, turn_deg_s, for_ms } = start else { return };
    ui.horizontal(|ui| {
        ui.add(egui::DragValue::new(speed_m_s).range(-1.5..=1.5).speed(0.01).suffix(" m/s")).labelled_by(named);
        ui.add(egui::DragValue::new(turn_deg_s).range(-180.0..=180.0).speed(1.0).suffix(" °/s")).labelled_by(named);
        let mut seconds = *for_ms as f64 / 1000.0;
        if ui
            .add(egui::DragValue::new(&mut seconds).range(0.0..=600.0).speed(0.05).suffix(" s"))
            .labelled_by(named)
            .changed()
        {
            // Seconds within ten minutes: whole ms.
            #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
            let ms = (seconds * 1000.0).round().max(0.0) as u64;
            *for_ms = ms;
        }
    });
}
