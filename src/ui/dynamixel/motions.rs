//! The Motions panel: the project's motions beside the one shown — its
//! steps (time, curve, each servo's angle), Play (streamed to the servos
//! from where they are) and its plot: each servo's angle over the motion,
//! the same poses the stream sends, with the playing time marked.

use std::collections::BTreeMap;
use std::time::Instant;

use egui_plot::{Line, Plot, PlotPoints, VLine};

use super::{DynamixelAction, DynamixelUi, degrees, units};
use crate::project::Easing;
use crate::project::dynamixel::{DynamixelSection, LONGEST_STEP_MS, Motion};
use crate::ui::action::Action;
use crate::ui::shell::ShellView;

/// The curves a step may take, as the picker lists them.
const EASINGS: [Easing; 5] = [Easing::Linear, Easing::EaseIn, Easing::EaseOut, Easing::EaseInOut, Easing::Hold];

/// Draws the Motions panel.
pub fn ui(family: &mut DynamixelUi, ui: &mut egui::Ui, view: &ShellView<'_>, actions: &mut Vec<Action>) {
    let language = view.language;
    let word = |key: &str| language.word(key);
    let section = DynamixelSection::of(view.project);
    let shown = family.motion.min(section.motions.len().saturating_sub(1));
    egui::Panel::left("dynamixel_motions_list").resizable(true).default_size(180.0).show(ui, |ui| {
        for (index, motion) in section.motions.iter().enumerate() {
            let caption = format!("{} · {:.1} s", motion.name, motion.duration_ms() as f64 / 1000.0);
            if ui.selectable_label(index == shown, caption).clicked() {
                actions.push(Action::family(DynamixelAction::SelectMotion(index)));
            }
        }
        if ui.button(word("dynamixel.new_motion_button")).clicked() {
            actions.push(Action::family(DynamixelAction::AddMotion));
        }
    });
    let Some(motion) = section.motions.get(shown) else {
        ui.label(word("dynamixel.no_motions"));
        return;
    };
    ui.horizontal(|ui| {
        let mut name = motion.name.clone();
        if ui.add(egui::TextEdit::singleline(&mut name).desired_width(200.0)).lost_focus() && name != motion.name {
            let mut edited = section.clone();
            edited.motions[shown].name = name;
            actions.push(Action::family(DynamixelAction::Edit(Box::new(edited))));
        }
        let playing = family.playing.is_some_and(|(index, _)| index == shown);
        if playing {
            if ui.button(word("dynamixel.stop_playing")).clicked() {
                actions.push(Action::Stop);
            }
        } else if ui
            .add_enabled(view.link.is_some() && !motion.steps.is_empty(), egui::Button::new(word("dynamixel.play")))
            .clicked()
        {
            actions.push(Action::family(DynamixelAction::Play(shown)));
        }
    });
    let edited = steps(ui, &section, shown, view.language);
    if let Some(section) = edited {
        actions.push(Action::family(DynamixelAction::Edit(Box::new(section))));
    }
    let playing_ms = family
        .playing
        .filter(|(index, _)| *index == shown)
        .map(|(_, since)| Instant::now().duration_since(since).as_secs_f64() * 1000.0);
    plot(ui, motion, &family.bus.present(), &section, playing_ms);
}

/// The motion's steps as a table (time, curve, each servo's angle, delete):
/// the section as edited, if it was.
fn steps(
    ui: &mut egui::Ui,
    section: &DynamixelSection,
    shown: usize,
    language: crate::ui::i18n::Language,
) -> Option<DynamixelSection> {
    let word = |key: &str| language.word(key);
    let motion = &section.motions[shown];
    let model_of = |id: u8| section.servo(id).map_or(0, |setup| setup.model_number);
    let ids: Vec<u8> = section.servos.iter().map(|servo| servo.id).collect();
    let mut edited: Option<DynamixelSection> = None;
    egui::ScrollArea::vertical().max_height(ui.available_height() * 0.45).show(ui, |ui| {
        egui::Grid::new("dynamixel_steps").striped(true).show(ui, |ui| {
            ui.strong("#");
            ui.strong(word("dynamixel.col_time"));
            ui.strong(word("dynamixel.col_curve"));
            for id in &ids {
                let name = section.servo(*id).map_or("", |setup| setup.name.as_str());
                ui.strong(format!("{id} {name}"));
            }
            ui.end_row();
            for (index, step) in motion.steps.iter().enumerate() {
                ui.label((index + 1).to_string());
                let mut duration_ms = step.duration_ms;
                let mut changed = ui
                    .add(egui::DragValue::new(&mut duration_ms).range(20..=LONGEST_STEP_MS).speed(10).suffix(" ms"))
                    .changed();
                let mut easing = step.easing;
                egui::ComboBox::from_id_salt(("dynamixel_easing", index)).selected_text(easing.tag()).show_ui(
                    ui,
                    |ui| {
                        for choice in EASINGS {
                            changed |= ui.selectable_value(&mut easing, choice, choice.tag()).changed();
                        }
                    },
                );
                let mut positions = step.positions.clone();
                for id in &ids {
                    match positions.get(id).copied() {
                        Some(position) => {
                            let mut deg = degrees(model_of(*id), position);
                            if ui.add(egui::DragValue::new(&mut deg).speed(0.5).fixed_decimals(1).suffix("°")).changed()
                            {
                                positions.insert(*id, units(model_of(*id), deg));
                                changed = true;
                            }
                        }
                        None => {
                            ui.label("—");
                        }
                    }
                }
                if ui.small_button("−").on_hover_text(word("dynamixel.delete_step")).clicked() {
                    let mut removed = section.clone();
                    removed.motions[shown].steps.remove(index);
                    edited = Some(removed);
                } else if changed {
                    let mut kept = section.clone();
                    kept.motions[shown].steps[index] =
                        crate::project::dynamixel::Step { duration_ms, easing, positions };
                    edited = Some(kept);
                }
                ui.end_row();
            }
        });
    });
    edited
}

/// Each servo's angle over the motion, from where the servos are: the poses the stream sends.
fn plot(
    ui: &mut egui::Ui,
    motion: &Motion,
    from: &BTreeMap<u8, u32>,
    section: &DynamixelSection,
    playing_ms: Option<f64>,
) {
    let total_ms = motion.duration_ms();
    let model_of = |id: u8| section.servo(id).map_or(0, |setup| setup.model_number);
    let mut start = from.clone();
    for step in motion.steps.iter().rev() {
        for (id, position) in &step.positions {
            start.entry(*id).or_insert(*position);
        }
    }
    let samples: Vec<(f64, BTreeMap<u8, u32>)> = (0..=total_ms / 20)
        .map(|k| {
            #[allow(clippy::cast_precision_loss)]
            let ms = (k * 20) as f64;
            (ms, motion.pose_at(&start, ms))
        })
        .collect();
    Plot::new("dynamixel_motion_plot")
        .legend(egui_plot::Legend::default())
        .allow_scroll(false)
        .x_axis_label("ms")
        .y_axis_label("°")
        .show(ui, |plot| {
            for id in start.keys() {
                let points: Vec<[f64; 2]> =
                    samples.iter().map(|(ms, pose)| [*ms, degrees(model_of(*id), pose[id])]).collect();
                let name = section.servo(*id).map_or_else(|| id.to_string(), |setup| format!("{id} {}", setup.name));
                plot.line(Line::new(name, PlotPoints::from(points)).width(2.0));
            }
            if let Some(ms) = playing_ms {
                plot.vline(VLine::new("", ms).width(1.5));
            }
        });
}
