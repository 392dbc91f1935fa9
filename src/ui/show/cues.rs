//! The show window's cues, a row each: which device, when (seconds), and
//! what it starts, chosen as its family registered (`ui::show_cue::CueUi`: one of a
//! servo board's macros, a PLEN2's motions, a base's drive…); added, changed
//! and removed, the show checked as it is edited.

use super::ShowWords;
use crate::show::{Cue, Show, Start, family};
use crate::ui::show_cue::{self, CueWords};

/// The cues' table; `editable` while no show plays.
pub(super) fn cues_ui(ui: &mut egui::Ui, show: &mut Show, editable: bool, words: &ShowWords) {
    let mut remove = None;
    // Only the rows in view are laid out: an hour of cues costs a frame what a dozen do.
    let row_height = ui.spacing().interact_size.y;
    let names: Vec<String> = show.devices.iter().map(|d| d.name.clone()).collect();
    let heads = [words.device, words.at, words.starts];
    ui.horizontal(|ui| {
        ui.add_sized([70.0, row_height], egui::Label::new(egui::RichText::new("#").strong()));
        for (head, width) in heads.into_iter().zip([130.0, 90.0, 260.0]) {
            ui.add_sized([width, row_height], egui::Label::new(egui::RichText::new(head).strong()));
        }
    });
    let rows = show.cues.len();
    egui::ScrollArea::vertical().id_salt("show-cues").max_height((row_height + 4.0) * 12.0).show_rows(
        ui,
        row_height,
        rows,
        |ui, range| {
            for index in range {
                ui.horizontal(|ui| {
                    if cue_row(ui, (show, &names, index), editable, words) {
                        remove = Some(index);
                    }
                });
            }
        },
    );
    if let Some(index) = remove {
        show.cues.remove(index);
    }
    if ui.add_enabled(editable && !show.devices.is_empty(), egui::Button::new(words.add_cue)).clicked() {
        let device = &show.devices[0];
        if let Some(start) = first_start(device) {
            show.cues.push(Cue { device: device.name.clone(), at_ms: 0, start });
        }
    }
}

/// One cue's row: its number, device, time and start, and Remove (whether it was clicked).
fn cue_row(
    ui: &mut egui::Ui,
    (show, names, index): (&mut Show, &[String], usize),
    editable: bool,
    words: &ShowWords,
) -> bool {
    // Each row's widgets are named by the cue's number (screen readers, tests).
    let named =
        ui.add_sized([70.0, ui.spacing().interact_size.y], egui::Label::new(format!("{} {}", words.cue, index + 1))).id;
    let Some(cue) = show.cues.get_mut(index) else { return false };
    ui.add_enabled_ui(editable, |ui| {
        egui::ComboBox::from_id_salt(("cue-device", index))
            .selected_text(cue.device.clone())
            .width(122.0)
            .show_ui(ui, |ui| {
                for name in names {
                    ui.selectable_value(&mut cue.device, name.clone(), name);
                }
            })
            .response
            .labelled_by(named);
    });
    let mut seconds = cue.at_ms as f64 / 1000.0;
    let time = ui
        .add_enabled(editable, egui::DragValue::new(&mut seconds).range(0.0..=3600.0).speed(0.01).suffix(" s"))
        .labelled_by(named);
    if time.changed() {
        // Seconds within an hour: whole ms.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let ms = (seconds * 1000.0).round().max(0.0) as u64;
        cue.at_ms = ms;
    }
    let device = show.devices.iter().find(|d| d.name == cue.device);
    ui.add_enabled_ui(editable, |ui| start_ui(ui, (index, named, &mut cue.start), device, words));
    ui.add_enabled(editable, egui::Button::new(words.remove)).clicked()
}

/// What a new cue of a device starts, as its family says: its lowest macro
/// or motion, a slow drive of a second…; none for a family that plays in no show.
fn first_start(device: &crate::show::Device) -> Option<Start> {
    family::of(device.project.family)
        .ok()
        .and_then(|entry| entry.new_cue.unwrap_or(entry.first_stored)(&device.project))
}

/// What a cue starts, chosen among what its device holds.
fn start_ui(
    ui: &mut egui::Ui,
    (index, named, start): (usize, egui::Id, &mut Start),
    device: Option<&crate::show::Device>,
    words: &ShowWords,
) {
    let Some(device) = device else { return };
    let family = device.project.family;
    // A cue moved to a device of another family starts what that one holds first.
    let fits = family::of(family).is_ok_and(|entry| (entry.takes)(start));
    if !fits && let Some(first) = first_start(device) {
        *start = first;
    }
    if let Some(entry) = show_cue::of(family) {
        (entry.choose)(ui, (index, named), start, &device.project, &cue_words(words));
    } else if let Start::Family(cue) = start {
        // A family's own kind of cue: the number it takes, named by its kind.
        ui.horizontal(|ui| {
            ui.label(cue.kind);
            ui.add(egui::DragValue::new(&mut cue.value).speed(1.0)).labelled_by(named);
        });
    }
}

/// A cue's caption: what it starts, in these words, named as its device
/// names it (its macro's caption, its motion's name) when it is known.
pub(super) fn cue_caption(start: &Start, device: Option<&crate::show::Device>, words: &ShowWords) -> String {
    let words = &cue_words(words);
    let own =
        device.and_then(|device| (show_cue::of(device.project.family)?.caption)(start, Some(&device.project), words));
    own.or_else(|| show_cue::every().find_map(|entry| (entry.caption)(start, None, words)))
        .unwrap_or_else(|| start.to_string())
}

/// The words a family's cues are said in, in the show window's language.
fn cue_words(words: &ShowWords) -> CueWords {
    CueWords { macro_word: words.macro_word, motion_word: words.motion_word, drive_word: words.drive_word }
}
