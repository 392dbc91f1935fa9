//! Record passes in the show window: pick a device (a servo board or a
//! PLEN2) and one of its axes, press **● Record pass**: the show previews on
//! the stage with its sound from the time shown while the axis's slider (or
//! its arrow keys) is recorded, the figure following it; **■ Stop pass**
//! joins it with the device's earlier passes into one macro or motion
//! (`show::passes`), cued at the first pass's start. **Undo pass** takes the
//! last pass back, the show as it was before it.

use crate::ui::i18n::{Said, Worded};
use std::collections::BTreeMap;

use super::{ShowAction, ShowWords};
use crate::show::Show;
use crate::show::passes::{self, Axis, Made, Moves, Pass};
use crate::ui::Action;

/// The passes recorded, the one being recorded, and the steps to undo.
#[derive(Debug, Default)]
pub struct Passes {
    /// Every pass kept, in the order recorded.
    pub recorded: Vec<Pass>,
    /// The pass being recorded.
    pub recording: Option<Pass>,
    /// What each device's passes made in its project.
    made: BTreeMap<String, Made>,
    /// Before each pass joined: the show, the passes and what they made, and what the pass said.
    undo: Vec<Kept>,
    /// After each pass taken back, to join it again.
    redo: Vec<Kept>,
    /// The device picked, and its axis.
    device: Option<String>,
    axis: Option<Axis>,
    /// The axis's value now, degrees.
    pub value: f64,
    /// The device and axis `value` is of (another picked: it is taken from the show).
    value_of: Option<(String, Axis)>,
    /// The value when the axis was picked (moved since: the hand's, kept).
    value_at_pick: Option<f64>,
    /// The gamepad axis that moves it (by code), instead of the slider.
    pub pad_axis: Option<u16>,
    /// Whether the editor's Undo would take back a pass now (nothing edited since the last).
    pub undo_reaches: bool,
}

/// The show and the passes at one step of the history, and the line the
/// pass between it and the next said (taken off the log while it is undone).
#[derive(Debug)]
struct Kept {
    show: Show,
    recorded: Vec<Pass>,
    made: BTreeMap<String, Made>,
    said: Said,
}

impl Passes {
    /// Picks the device and axis the next pass records (as the row's boxes do).
    pub fn pick(&mut self, device: &str, axis: Axis) {
        (self.device, self.axis) = (Some(device.to_string()), Some(axis));
        self.value_at_pick = Some(self.value);
    }

    /// The device and axis picked, when both are.
    fn picked(&self) -> Option<(String, Axis)> {
        self.device.clone().zip(self.axis)
    }

    /// The value starts where the picked axis is in `show` at `t_ms` (as
    /// the stage shows it), once per axis picked: a pass never starts from
    /// a value left by another axis; the hand moves it from there.
    pub fn settle(&mut self, show: &Show, t_ms: u64) {
        let picked = self.picked();
        if picked.is_none() || picked == self.value_of {
            return;
        }
        let moved_since_picked = self.value_at_pick.is_some_and(|at_pick| at_pick != self.value);
        if !moved_since_picked
            && let Some((device, axis)) = &picked
            && let Some(index) = show.devices.iter().position(|each| each.name == *device)
            && let Some(value) = crate::show::timeline::posed_at(show, index, t_ms)
                .and_then(|posed| crate::show::at::axis_value(&posed, *axis))
        {
            self.value = value;
        }
        self.value_of = picked;
    }

    /// Begins a pass of the picked axis (none picked: nothing), from where it
    /// is in `show` at `t_ms` unless the hand has moved it since it was picked.
    pub fn begin(&mut self, show: &Show, t_ms: u64) -> bool {
        self.settle(show, t_ms);
        let Some((device, axis)) = self.picked() else { return false };
        self.recording = Some(Pass { device, axis, samples: Vec::new() });
        true
    }

    /// Takes the axis's value at show time `t_ms` (once per time).
    pub fn sample(&mut self, t_ms: u64) {
        let value = self.value;
        if let Some(pass) = &mut self.recording
            && pass.samples.last().is_none_or(|&(at, _)| at < t_ms)
        {
            pass.samples.push((t_ms, value));
        }
    }

    /// Ends the pass and joins it into the show; what to say, and the
    /// device it joined into (none: it did not join, said why).
    pub fn end(&mut self, show: &mut Show) -> Option<(Said, Option<String>)> {
        let pass = self.recording.take()?;
        let device = pass.device.clone();
        let before = (show.clone(), self.recorded.clone(), self.made.clone());
        let mut recorded = self.recorded.clone();
        recorded.push(pass);
        match passes::join(show, &recorded, &device, self.made.get(&device)) {
            Ok(joined) => {
                self.recorded = recorded;
                self.made.insert(device.clone(), joined.made.clone());
                let passes = self.recorded.iter().filter(|p| p.device == device).count();
                let said = super::said_by(|words| {
                    let cut = cut_short(show, &device, &joined.made, words);
                    let (language, moves) = (words.lang, joined.moves);
                    let (error, tolerance) = (joined.max_error_deg, joined.tolerance_deg);
                    let line = if joined.made.moves_are == Moves::Steps {
                        crate::say!(language, "show.passes_joined_steps", device, passes, moves, error, tolerance)
                    } else {
                        crate::say!(language, "show.passes_joined_frames", device, passes, moves, error, tolerance)
                    };
                    format!("{line}{cut}")
                });
                let (show, recorded, made) = before;
                self.undo.push(Kept { show, recorded, made, said: said.clone() });
                self.redo.clear();
                Some((said, Some(device)))
            }
            Err(error) => Some((Said::new(|language| format!("{device}: {}", error.worded(language))), None)),
        }
    }

    /// Takes the last pass back: the show and the passes as they were before
    /// it, its line off the log `said`. Whether there was one.
    pub fn undo(&mut self, show: &mut Show, said: &mut Vec<Said>) -> bool {
        let Some(kept) = self.undo.pop() else { return false };
        let now = self.swap(kept, show);
        if let Some(at) = said.iter().rposition(|line| *line == now.said) {
            said.remove(at);
        }
        self.redo.push(now);
        true
    }

    /// Joins the last pass taken back again, its line back on the log.
    pub fn redo(&mut self, show: &mut Show, said: &mut Vec<Said>) -> bool {
        let Some(kept) = self.redo.pop() else { return false };
        let now = self.swap(kept, show);
        said.push(now.said.clone());
        self.undo.push(now);
        true
    }

    /// Puts `kept` in place, returning what stood there (with `kept`'s line).
    fn swap(&mut self, kept: Kept, show: &mut Show) -> Kept {
        let Kept { show: then, recorded, made, said } = kept;
        Kept {
            show: std::mem::replace(show, then),
            recorded: std::mem::replace(&mut self.recorded, recorded),
            made: std::mem::replace(&mut self.made, made),
            said,
        }
    }

    /// Whether a pass can be taken back (the editor's Undo reaches it).
    pub fn can_undo(&self) -> bool {
        self.undo_reaches && !self.undo.is_empty()
    }
}

/// What the device's other cues do to what its passes made: a board plays
/// one macro or motion at a time, so a later cue of it cuts the passes short.
fn cut_short(show: &Show, device: &str, made: &Made, words: &ShowWords) -> String {
    let mine = made.start;
    let cue = show.cues.iter().find(|c| c.device == device && c.start == mine).map(|c| c.at_ms);
    let (Some(start), Some(joined)) = (cue, show.device(device)) else { return String::new() };
    let end = start + crate::show::timeline::cue_length_ms(joined, &mine);
    match show
        .cues
        .iter()
        .filter(|c| c.device == device && c.start != mine && c.at_ms > start && c.at_ms < end)
        .map(|c| c.at_ms)
        .min()
    {
        // Whole ms of a show: exact in f64.
        #[allow(clippy::cast_precision_loss)]
        Some(at) => format!(" — {} {:.2} s", words.cut_short_at, at as f64 / 1000.0),
        None => String::new(),
    }
}

/// The axes a device's passes may record, captioned, as its family lists
/// them (none for a family that records no passes).
fn axes(show: &Show, device: &str) -> Vec<(Axis, String)> {
    recordable(show, device).into_iter().map(|(axis, caption, _)| (axis, caption)).collect()
}

/// Each axis a device's passes may record, its caption and its range, as its family says.
fn recordable(show: &Show, device: &str) -> Vec<passes::Recordable> {
    let Some(device) = show.device(device) else { return Vec::new() };
    passes::of(device.project.family).map(|records| (records.axes)(&device.project)).unwrap_or_default()
}

/// The range an axis moves in, degrees.
fn range(show: &Show, device: &str, axis: Axis) -> std::ops::RangeInclusive<f64> {
    let found = recordable(show, device).into_iter().find(|(each, _, _)| *each == axis);
    found.map_or(-90.0..=90.0, |(_, _, range)| range)
}

/// Where a gamepad axis (−1 … 1) puts an axis moving in `range`: its low end to its high end.
pub fn from_pad(value: f64, range: &std::ops::RangeInclusive<f64>) -> f64 {
    let (low, high) = (*range.start(), *range.end());
    low + (value.clamp(-1.0, 1.0) + 1.0) / 2.0 * (high - low)
}

/// The pass row: device, axis, what moves it (the slider or a gamepad
/// axis, `pad`: each moved axis of the gamepad in use, by code), the
/// axis's slider, Record / Stop, Undo pass.
pub(super) fn passes_ui(
    ui: &mut egui::Ui,
    (show, pad, t_ms): (&Show, &[(u16, f64)], u64),
    passes: &mut Passes,
    editable: bool,
    words: &ShowWords,
    actions: &mut Vec<Action>,
) {
    let recording = passes.recording.is_some();
    ui.horizontal(|ui| {
        let label = ui.label(words.record_pass_of);
        let recordable: Vec<String> =
            show.devices.iter().filter(|d| passes::of(d.project.family).is_ok()).map(|d| d.name.clone()).collect();
        let (mut device, mut axis) = (passes.device.clone(), passes.axis);
        ui.add_enabled_ui(editable && !recording, |ui| {
            egui::ComboBox::from_id_salt("pass-device")
                .selected_text(device.clone().unwrap_or_default())
                .show_ui(ui, |ui| {
                    for name in &recordable {
                        ui.selectable_value(&mut device, Some(name.clone()), name);
                    }
                })
                .response
                .labelled_by(label.id);
            let choices = device.as_deref().map(|d| axes(show, d)).unwrap_or_default();
            let shown = choices.iter().find(|(a, _)| Some(*a) == axis).map(|(_, c)| c.clone()).unwrap_or_default();
            egui::ComboBox::from_id_salt("pass-axis")
                .selected_text(shown)
                .show_ui(ui, |ui| {
                    for (choice, caption) in &choices {
                        ui.selectable_value(&mut axis, Some(*choice), caption);
                    }
                })
                .response
                .labelled_by(label.id);
        });
        if device != passes.device {
            // Another device: its own axes.
            (passes.device, passes.axis) = (device, None);
        } else if axis != passes.axis
            && let (Some(device), Some(axis)) = (device, axis)
        {
            passes.pick(&device, axis);
        }
        if !recording {
            passes.settle(show, t_ms);
        }
        if let Some((device, axis)) = passes.picked() {
            input_ui(ui, passes, pad, (words, label.id));
            let range = range(show, &device, axis);
            if let Some(value) = passes.pad_axis.and_then(|code| pad.iter().find(|(c, _)| *c == code)) {
                passes.value = from_pad(value.1, &range);
            }
            // Wide enough for a hand to draw with (its arrow keys nudge it too).
            ui.spacing_mut().slider_width = 320.0;
            let value = ui.add(egui::Slider::new(&mut passes.value, range).suffix("°").fixed_decimals(1));
            value.labelled_by(label.id);
        }
        let (caption, action) = if recording {
            (words.stop_pass, ShowAction::RecordPass(false))
        } else {
            (words.record_pass, ShowAction::RecordPass(true))
        };
        if ui.add_enabled(editable && passes.picked().is_some(), egui::Button::new(caption)).clicked() {
            actions.push(Action::Show(action));
        }
        if ui.add_enabled(!recording && passes.can_undo(), egui::Button::new(words.undo_pass)).clicked() {
            actions.push(Action::Show(ShowAction::UndoPass));
        }
    });
}

/// What moves the axis: the slider, or one of the gamepad's axes.
fn input_ui(ui: &mut egui::Ui, passes: &mut Passes, pad: &[(u16, f64)], (words, label): (&ShowWords, egui::Id)) {
    let name = |code: u16| crate::gamepad::code_name(crate::gamepad::EV_ABS, code);
    let shown = passes.pad_axis.map_or_else(|| words.by_slider.to_string(), name);
    let _ = egui::ComboBox::from_id_salt("pass-input")
        .selected_text(shown)
        .show_ui(ui, |ui| {
            ui.selectable_value(&mut passes.pad_axis, None, words.by_slider);
            for &(code, _) in pad {
                ui.selectable_value(&mut passes.pad_axis, Some(code), name(code));
            }
            if pad.is_empty() {
                ui.label(words.no_pad_axis);
            }
        })
        .response
        .labelled_by(label);
}

#[cfg(test)]
mod tests {
    #[test]
    fn a_gamepad_axis_spans_the_axis_range() {
        let range = -30.0..=90.0;
        assert!((super::from_pad(-1.0, &range) + 30.0).abs() < 1e-9);
        assert!((super::from_pad(0.0, &range) - 30.0).abs() < 1e-9);
        assert!((super::from_pad(1.0, &range) - 90.0).abs() < 1e-9);
        assert!((super::from_pad(7.0, &range) - 90.0).abs() < 1e-9, "clamped");
    }
}
