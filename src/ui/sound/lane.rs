//! The sound lane under a preview's time cursor: the waveform (from the
//! peak pyramid, so any zoom draws alike), the onsets in orange, the
//! motion's frames or steps as ticks and the cursor, all on the motion's
//! time. Click to put the cursor there; drag the waveform sideways to move
//! where the sound starts (or type the offset in ms); Ctrl + wheel zooms
//! round the pointer, the wheel scrolls. It also keeps the sound in step
//! with the cursor: Play plays the sound from the cursor, a drag of the
//! stopped cursor plays short grains.

use egui::{Stroke, vec2};

use super::{Problem, SoundAction, SoundView};
use crate::ui::action::{Action, FileRequest, Pick};
use crate::ui::i18n::Language;
use crate::ui::transport::Transport;

/// The lane's height, points.
const HEIGHT: f32 = 64.0;
/// A grain no closer to the last than this, ms of motion time.
const GRAIN_STEP_MS: f64 = 40.0;

/// The onsets' colour (the graphs' too).
pub use crate::ui::graph::ONSET;

/// The transport as last seen: where it plays from (if it plays), its speed, its cursor.
type Seen = (Option<(f64, f64)>, f64, f64);

/// One preview's lane: its zoom and scroll, and the cursor as last seen.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SoundLane {
    /// The motion time at the left edge and the ms per point; None: the whole show fits.
    window: Option<(f64, f64)>,
    /// The transport as last seen: where it plays from (if it plays), its speed, its cursor.
    seen: Option<Seen>,
    /// Where the last grain was played.
    grain_at: Option<f64>,
    /// The offset when a drag of the waveform began.
    dragged_from: Option<i64>,
    /// As last drawn: the lane's left edge, and the time there and per point.
    drawn: Option<(f32, f64, f64)>,
}

crate::words! {
    /// The lane's words.
    #[derive(Debug)]
    pub struct LaneWords in "lane" {
        /// "Sound".
        pub sound: &'static str,
        /// "Add a sound…".
        pub add: &'static str,
        /// "Starts at".
        pub offset: &'static str,
        /// Its hover.
        pub offset_hint: &'static str,
        /// "Onsets".
        pub sensitivity: &'static str,
        /// Its hover.
        pub sensitivity_hint: &'static str,
        /// "Remove".
        pub remove: &'static str,
        /// "Follow the sound…".
        pub follow: &'static str,
        /// "Locate…".
        pub locate: &'static str,
        /// "Keep it as it is now".
        pub accept: &'static str,
        /// "is missing".
        pub missing: &'static str,
        /// "changed since the show was timed to it".
        pub changed: &'static str,
        /// "cannot be read".
        pub unreadable: &'static str,
        /// "Reading the sound".
        pub reading: &'static str,
        /// The lane's hover: how to use it.
        pub lane_hint: &'static str,
        /// The kind of file, in the dialog.
        pub kind: &'static str,
        /// "no sound output" (no sound server): the motion plays on alone.
        pub no_output: &'static str,
        /// "the sound server" (when its address is the system's).
        pub the_server: &'static str,
    }
}

/// The lane's words in `language`.
pub fn words(language: Language) -> &'static LaneWords {
    LaneWords::of(language)
}

/// The endings the sound dialog offers.
const SOUND_FILES: &[&str] = &["wav", "flac", "mp3", "ogg", "oga"];

/// A request for a sound file, becoming `then`.
fn pick(words: &LaneWords, then: fn(std::path::PathBuf) -> SoundAction) -> Action {
    Action::AskFile(FileRequest::Pick(Pick {
        kind: words.kind,
        extensions: SOUND_FILES,
        then: std::sync::Arc::new(move |path| Action::Sound(then(path))),
    }))
}

impl SoundLane {
    /// Where on the screen the lane last drew time `t_ms`.
    pub fn x_of(&self, t_ms: f64) -> Option<f32> {
        let (left, start, per_point) = self.drawn?;
        // Points on a screen: f32 is plenty.
        #[allow(clippy::cast_possible_truncation)]
        let x = left + ((t_ms - start) / per_point) as f32;
        Some(x)
    }

    /// The lane, under the transport's row: keeps the sound in step with the
    /// cursor, and draws the sound on the motion's time (`0..end_ms`, ticks at `marks`).
    pub fn ui(
        &mut self,
        ui: &mut egui::Ui,
        sound: SoundView<'_>,
        (transport, end_ms, marks): (&mut Transport, f64, &[f64]),
        language: Language,
        actions: &mut Vec<Action>,
    ) {
        let words = words(language);
        self.follow(transport, sound, actions);
        let Some(track) = sound.track else {
            if sound.progress.is_some() {
                Self::progress(ui, sound, words);
            } else if ui.small_button(words.add).clicked() {
                actions.push(pick(words, SoundAction::Add));
            }
            return;
        };
        self.header(ui, sound, track, words, actions);
        if sound.progress.is_some() {
            Self::progress(ui, sound, words);
        }
        let Some(read) = sound.read else { return };
        // Lengths within an hour: exact in f64.
        #[allow(clippy::cast_precision_loss)]
        let (offset, sound_end) = (track.offset_ms as f64, track.offset_ms as f64 + read.duration_s() * 1000.0);
        let width = ui.available_width().max(1.0);
        let (rect, response) = ui.allocate_exact_size(vec2(width, HEIGHT), egui::Sense::click_and_drag());
        let response = response.on_hover_text(words.lane_hint);
        let whole = end_ms.max(sound_end).max(1.0);
        let (start, per_point) = self.window.unwrap_or((0.0, whole / f64::from(width)));
        self.zoom_and_scroll(ui, &response, rect, (start, per_point), whole);
        let (start, per_point) = self.window.unwrap_or((start, per_point));
        let t_of = |x: f32| start + f64::from(x - rect.left()) * per_point;
        self.drawn = Some((rect.left(), start, per_point));
        if response.clicked()
            && let Some(pointer) = response.interact_pointer_pos()
        {
            transport.seek(t_of(pointer.x).clamp(0.0, whole), ui.input(|input| input.time));
        }
        self.drag_offset(&response, per_point, track.offset_ms, actions);
        paint(ui, rect, (sound, read, offset), (start, per_point), (transport.t_ms, end_ms, marks));
    }

    /// The lane's row: the file, the offset, the onsets' sensitivity, what is wrong and what to do.
    fn header(
        &mut self,
        ui: &mut egui::Ui,
        sound: SoundView<'_>,
        track: &crate::project::SoundTrack,
        words: &LaneWords,
        actions: &mut Vec<Action>,
    ) {
        ui.horizontal_wrapped(|ui| {
            ui.label(format!("{}: {}", words.sound, track.path));
            if let Some(read) = sound.read {
                ui.weak(format!("{:.2} s", read.duration_s()));
            }
            let label = ui.label(words.offset);
            let mut offset = track.offset_ms;
            let field = ui.add(egui::DragValue::new(&mut offset).speed(5.0).suffix(" ms")).labelled_by(label.id);
            if field.on_hover_text(words.offset_hint).changed() {
                actions.push(Action::Sound(SoundAction::SetOffset(offset)));
            }
        });
        ui.horizontal_wrapped(|ui| {
            let label = ui.label(words.sensitivity);
            ui.spacing_mut().slider_width = 90.0;
            let mut percent = track.sensitivity_percent;
            let slider = ui.add(egui::Slider::new(&mut percent, 0..=100).suffix(" %")).labelled_by(label.id);
            if slider.on_hover_text(words.sensitivity_hint).changed() {
                actions.push(Action::Sound(SoundAction::SetSensitivity(percent)));
            }
            if sound.read.is_some() && ui.small_button(words.follow).clicked() {
                actions.push(Action::Sound(SoundAction::OpenFollow));
            }
            if ui.small_button(words.remove).clicked() {
                actions.push(Action::Sound(SoundAction::Remove));
            }
        });
        let Some(problem) = sound.problem else { return };
        ui.horizontal_wrapped(|ui| {
            let (file, what) = match problem {
                Problem::Missing(file) => (file.display().to_string(), words.missing.to_string()),
                Problem::Changed(file) => (file.display().to_string(), words.changed.to_string()),
                Problem::Unreadable(why) => (track.path.clone(), format!("{}: {why}", words.unreadable)),
            };
            ui.colored_label(ui.visuals().error_fg_color, format!("{file} {what}"));
            if matches!(problem, Problem::Changed(_)) && ui.small_button(words.accept).clicked() {
                actions.push(Action::Sound(SoundAction::AcceptChanged));
            }
            if ui.small_button(words.locate).clicked() {
                actions.push(pick(words, SoundAction::Locate));
            }
            if ui.small_button(words.remove).clicked() {
                actions.push(Action::Sound(SoundAction::Remove));
            }
        });
    }

    /// A progress bar while the sound is read.
    fn progress(ui: &mut egui::Ui, sound: SoundView<'_>, words: &LaneWords) {
        let share = sound.progress.unwrap_or(0.0);
        ui.add(egui::ProgressBar::new(share).show_percentage().text(format!(
            "{} {:.0} %",
            words.reading,
            share * 100.0
        )));
    }

    /// Ctrl + wheel zooms round the pointer; the wheel (or a sideways swipe) scrolls.
    fn zoom_and_scroll(
        &mut self,
        ui: &egui::Ui,
        response: &egui::Response,
        rect: egui::Rect,
        (start, per_point): (f64, f64),
        whole: f64,
    ) {
        if !response.hovered() {
            return;
        }
        let (zoom, scroll, pointer) =
            ui.input(|input| (input.zoom_delta(), input.smooth_scroll_delta, input.pointer.hover_pos()));
        let mut window = (start, per_point);
        if zoom != 1.0 {
            let at = pointer.map_or(rect.center().x, |pointer| pointer.x);
            let anchor = start + f64::from(at - rect.left()) * per_point;
            let per = (per_point / f64::from(zoom)).clamp(0.05, whole / f64::from(rect.width().max(1.0)) * 4.0);
            window = (anchor - f64::from(at - rect.left()) * per, per);
        } else if scroll.x != 0.0 || scroll.y != 0.0 {
            let along = if scroll.x == 0.0 { scroll.y } else { scroll.x };
            window.0 -= f64::from(along) * per_point;
        } else {
            return;
        }
        window.0 = window.0.clamp(-whole, whole);
        self.window = Some(window);
    }

    /// Dragging the waveform sideways moves where the sound starts (one undo step per drag).
    fn drag_offset(&mut self, response: &egui::Response, per_point: f64, offset_ms: i64, actions: &mut Vec<Action>) {
        if response.drag_started() {
            self.dragged_from = Some(offset_ms);
        }
        if let Some(from) = self.dragged_from
            && response.dragged()
        {
            let moved = response.total_drag_delta().map_or(0.0, |delta| f64::from(delta.x)) * per_point;
            // Within an hour of ms either way.
            #[allow(clippy::cast_possible_truncation)]
            let offset = from + moved.round() as i64;
            if offset != offset_ms {
                actions.push(Action::Sound(SoundAction::SetOffset(offset)));
            }
        }
        if response.drag_stopped() {
            self.dragged_from = None;
        }
    }

    /// Keeps the sound in step with the transport: plays from the cursor when
    /// it starts playing (at ×1 only; slower, the motion plays alone), again
    /// when it loops or is moved while playing, stops when it stops; a moved
    /// cursor while stopped plays a grain.
    fn follow(&mut self, transport: &Transport, sound: SoundView<'_>, actions: &mut Vec<Action>) {
        let now = (transport.playing_from(), transport.speed, transport.t_ms);
        let Some((was_playing, was_speed, was_t)) = self.seen.replace(now) else { return };
        if sound.read.is_none() {
            return;
        }
        let (playing, speed, t) = now;
        let restarted = playing.is_some() && (playing != was_playing || speed != was_speed || t + 1.0 < was_t);
        if restarted && speed == 1.0 {
            actions.push(Action::Sound(SoundAction::Play { from_ms: t }));
        } else if restarted || (playing.is_none() && was_playing.is_some()) {
            actions.push(Action::Sound(SoundAction::Silence));
        } else if playing.is_none() && t != was_t && self.grain_at.is_none_or(|at| (at - t).abs() >= GRAIN_STEP_MS) {
            self.grain_at = Some(t);
            actions.push(Action::Sound(SoundAction::Grain { at_ms: t }));
        }
        if playing.is_some() {
            self.grain_at = None;
        }
    }
}

/// The lane's picture: the waveform (one min/max pair per point column, from
/// the pyramid), the motion's ticks, the onsets, the cursor and the motion's end.
fn paint(
    ui: &egui::Ui,
    rect: egui::Rect,
    (sound, read, offset): (SoundView<'_>, &crate::audio::Analysis, f64),
    (start, per_point): (f64, f64),
    (cursor_ms, end_ms, marks): (f64, f64, &[f64]),
) {
    // Points across a lane: f32 is plenty.
    #[allow(clippy::cast_possible_truncation)]
    let x_of = |t: f64| rect.left() + ((t - start) / per_point) as f32;
    let t_of = |x: f32| start + f64::from(x - rect.left()) * per_point;
    let painter = ui.painter_at(rect);
    let visuals = ui.visuals();
    painter.rect_filled(rect, 2.0, visuals.extreme_bg_color);
    // A lane's width in points: small and positive.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let columns = rect.width().max(1.0) as usize;
    let (from_s, to_s) = ((start - offset) / 1000.0, (t_of(rect.right()) - offset) / 1000.0);
    let (low, high) = read.peaks.range(from_s, to_s, read.sample_rate, columns);
    let middle = rect.center().y;
    let half = rect.height() / 2.0 - 2.0;
    let wave = Stroke::new(1.0, visuals.widgets.inactive.fg_stroke.color);
    for (column, (low, high)) in low.iter().zip(&high).enumerate() {
        // Column indices: small.
        #[allow(clippy::cast_precision_loss)]
        let x = rect.left() + column as f32 + 0.5;
        if high > low {
            painter.vline(x, (middle - high * half)..=(middle - low * half), wave);
        }
    }
    for mark in marks {
        painter.vline(x_of(*mark), rect.y_range(), visuals.widgets.noninteractive.bg_stroke);
    }
    for onset in sound.onsets_ms() {
        let x = x_of(onset);
        if rect.x_range().contains(x) {
            painter.vline(x, rect.top()..=rect.top() + 10.0, Stroke::new(2.0, ONSET));
            painter.vline(x, rect.y_range(), Stroke::new(1.0, ONSET.gamma_multiply(0.5)));
        }
    }
    painter.vline(x_of(cursor_ms), rect.y_range(), Stroke::new(2.0, visuals.strong_text_color()));
    if end_ms > 0.0 {
        painter.vline(x_of(end_ms), rect.y_range(), Stroke::new(1.0, visuals.warn_fg_color));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn playing_the_cursor_plays_the_sound_and_stopping_stops_it() {
        let analysis = crate::audio::Analysis {
            sample_rate: 8000,
            channels: 1,
            frames: 8000,
            peaks: crate::audio::Peaks::new(),
            onsets_s: Vec::new(),
            found: crate::audio::Found::default(),
        };
        let sound = SoundView { read: Some(&analysis), ..SoundView::NONE };
        let mut lane = SoundLane::default();
        let mut transport = Transport::default();
        let mut actions = Vec::new();
        lane.follow(&transport, sound, &mut actions);
        assert!(actions.is_empty(), "nothing at first sight");
        transport.seek(250.0, 1.0);
        lane.follow(&transport, sound, &mut actions);
        assert!(matches!(actions.pop(), Some(Action::Sound(SoundAction::Grain { at_ms })) if at_ms == 250.0));
        transport.toggle(2.0);
        lane.follow(&transport, sound, &mut actions);
        assert!(matches!(actions.pop(), Some(Action::Sound(SoundAction::Play { from_ms })) if from_ms == 250.0));
        transport.advance(2.5, 10_000.0);
        lane.follow(&transport, sound, &mut actions);
        assert!(actions.is_empty(), "playing on: nothing new");
        transport.toggle(2.6);
        lane.follow(&transport, sound, &mut actions);
        assert_eq!(actions.pop(), Some(Action::Sound(SoundAction::Silence)));
        transport.speed = 0.5;
        transport.toggle(3.0);
        lane.follow(&transport, sound, &mut actions);
        assert_eq!(actions.pop(), Some(Action::Sound(SoundAction::Silence)), "at ×0.5 the motion plays alone");
    }
}
