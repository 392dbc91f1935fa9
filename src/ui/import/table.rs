//! The import window's joint map table: a row per channel of the file — what
//! it drives, its zero, units per degree, reversed, offset, and its angle now.

use super::{ImportWords, Session, words};
use crate::interchange::map::Target;
use crate::project::Family;
use crate::project::plen2::Joint;

/// The joint map as a table: a row per channel.
pub(super) fn map_table(ui: &mut egui::Ui, session: &mut Session, now: &[Option<f64>], words: &ImportWords) {
    use egui_extras::{Column, TableBuilder};
    let family = session.family;
    let channels = session.source.channels.clone();
    TableBuilder::new(ui)
        .striped(true)
        .column(Column::auto().at_least(56.0))
        .column(Column::auto().at_least(90.0).clip(true))
        .column(Column::auto().at_least(170.0))
        .column(Column::auto().at_least(64.0))
        .column(Column::auto().at_least(64.0))
        .column(Column::auto().at_least(40.0))
        .column(Column::auto().at_least(56.0))
        .column(Column::remainder().at_least(56.0))
        .header(22.0, |mut header| {
            for head in [
                words.channel,
                words.name,
                words.drives,
                words.zero,
                words.per_degree,
                words.reversed,
                words.offset,
                words.now,
            ] {
                header.col(|ui| {
                    ui.strong(head);
                });
            }
        })
        .body(|body| {
            body.rows(24.0, channels.len(), |mut row| {
                let index = row.index();
                let channel = &channels[index];
                let Some(entry) = session.map.entries.iter_mut().find(|e| e.source == channel.key) else { return };
                // Each row's widgets are named by the channel (screen readers, tests).
                let mut named = egui::Id::NULL;
                row.col(|ui| {
                    named = ui.label(&channel.key).id;
                });
                row.col(|ui| {
                    ui.label(&channel.name);
                });
                row.col(|ui| target_picker(ui, &mut entry.target, (family, &channel.key, named), words));
                row.col(|ui| {
                    ui.add(egui::DragValue::new(&mut entry.zero).speed(1.0)).labelled_by(named);
                });
                row.col(|ui| {
                    let mut per = entry.per_degree;
                    let response =
                        ui.add(egui::DragValue::new(&mut per).speed(0.01).max_decimals(3)).labelled_by(named);
                    if response.changed() && per != 0.0 {
                        entry.per_degree = per;
                    }
                });
                row.col(|ui| {
                    let mut reversed = entry.direction < 0;
                    if ui.checkbox(&mut reversed, "").labelled_by(named).on_hover_text(words.reversed).changed() {
                        entry.direction = if reversed { -1 } else { 1 };
                    }
                });
                row.col(|ui| {
                    ui.add(egui::DragValue::new(&mut entry.offset_deg).speed(0.5).suffix("°")).labelled_by(named);
                });
                row.col(|ui| {
                    let shown = now.get(index).copied().flatten().filter(|_| entry.target.is_some());
                    ui.label(shown.map_or_else(|| "—".to_string(), |d| format!("{d:.1}")));
                });
            });
        });
}

fn target_picker(
    ui: &mut egui::Ui,
    target: &mut Option<Target>,
    (family, key, named): (Family, &str, egui::Id),
    words: &ImportWords,
) {
    let shown = target.map_or_else(|| words.not_imported.to_string(), |t| words::target(t, words));
    let picked =
        egui::ComboBox::from_id_salt(("import-target", key)).selected_text(shown).width(160.0).show_ui(ui, |ui| {
            ui.selectable_value(target, None, words.not_imported);
            match family {
                Family::Plen2 => {
                    for joint in Joint::ALL {
                        ui.selectable_value(target, Some(Target::Joint(joint)), words::joint(joint, words));
                    }
                }
                _ => {
                    for id in 0..=254u8 {
                        ui.selectable_value(target, Some(Target::Servo(id)), words::target(Target::Servo(id), words));
                    }
                }
            }
        });
    picked.response.labelled_by(named);
}
