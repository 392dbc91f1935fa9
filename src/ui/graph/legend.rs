//! The graph's legend: every channel's colour and whole name as a list that
//! scrolls both ways (a name is never cut), a click showing or hiding its
//! curve, a solo toggle showing it alone, and All / None.

use super::{Channel, GraphWords};
use crate::ui::plot::series_color;

/// Room beside a name: the swatch, the solo toggle, the margins, points.
const BESIDE_NAME: f32 = 96.0;

/// The width that shows the widest name whole, within reason (a very long
/// name still shows whole: the list scrolls sideways).
pub fn natural_width(ui: &egui::Ui, channels: &[Channel], words: &GraphWords) -> f32 {
    let font = egui::TextStyle::Body.resolve(ui.style());
    let widest = channels
        .iter()
        .map(|channel| channel.name.as_str())
        .chain([words.all, words.none])
        .map(|name| {
            ui.fonts_mut(|fonts| fonts.layout_no_wrap(name.to_owned(), font.clone(), egui::Color32::WHITE)).size().x
        })
        .fold(0.0_f32, f32::max);
    (widest + BESIDE_NAME).clamp(140.0, 420.0)
}

/// Draws the legend; a click changes `shown` or `solo`.
pub fn show(
    ui: &mut egui::Ui,
    id: &str,
    channels: &[Channel],
    (shown, solo): (&mut Vec<bool>, &mut Option<usize>),
    words: &GraphWords,
) {
    ui.horizontal(|ui| {
        if ui.small_button(words.all).clicked() {
            shown.iter_mut().for_each(|on| *on = true);
            *solo = None;
        }
        if ui.small_button(words.none).clicked() {
            shown.iter_mut().for_each(|on| *on = false);
            *solo = None;
        }
    });
    ui.style_mut().wrap_mode = Some(egui::TextWrapMode::Extend);
    let row_height = ui.spacing().interact_size.y.max(crate::ui::rows::name_row_height(ui));
    egui::ScrollArea::both().id_salt((id, "legend")).auto_shrink([false, false]).show_rows(
        ui,
        row_height,
        channels.len(),
        |ui, rows| {
            for c in rows {
                ui.horizontal(|ui| {
                    ui.set_min_height(row_height);
                    entry(ui, (c, &channels[c].name), (shown, solo), words);
                });
            }
        },
    );
}

fn entry(
    ui: &mut egui::Ui,
    (c, name): (usize, &str),
    (shown, solo): (&mut [bool], &mut Option<usize>),
    words: &GraphWords,
) {
    let soloed = *solo == Some(c);
    let on = solo.map_or(shown[c], |only| only == c);
    if ui.selectable_label(soloed, words.solo).on_hover_text(words.solo).clicked() {
        *solo = if soloed { None } else { Some(c) };
    }
    let (swatch, text) = if on {
        (series_color(c), ui.visuals().text_color())
    } else {
        (ui.visuals().weak_text_color(), ui.visuals().weak_text_color())
    };
    let font = egui::TextStyle::Body.resolve(ui.style());
    let mut label = egui::text::LayoutJob::default();
    label.append(if on { "● " } else { "○ " }, 0.0, egui::TextFormat::simple(font.clone(), swatch));
    label.append(name, 0.0, egui::TextFormat::simple(font, text));
    if ui.add(egui::Button::new(label).frame(false)).on_hover_text(words.toggle_hint).clicked() {
        if solo.is_some() {
            // Leaving solo: back to the channels shown before, this one flipped from what was seen.
            *solo = None;
        }
        shown[c] = !on;
    }
}
