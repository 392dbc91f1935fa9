//! A preview's time cursor: drag it to scrub, Space (or its button) to play at
//! real speed, ×0.5 or ×0.25, looping, with no robot attached. Time is the
//! window's own (egui's input time), so a test steps it frame by frame.

use crate::ui::i18n::Strings;

/// The speeds offered.
pub const SPEEDS: [f64; 3] = [1.0, 0.5, 0.25];

/// Where a preview is in time, and whether it plays.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transport {
    /// The cursor, ms from the start.
    pub t_ms: f64,
    /// Playing: since when (the window's time, s) and from where (ms).
    playing: Option<(f64, f64)>,
    /// Real speed ×1, ×0.5 or ×0.25.
    pub speed: f64,
    /// The bar as last drawn: its left edge, its width and the span it shows, ms.
    drawn: Option<(f32, f32, f64)>,
}

impl Default for Transport {
    fn default() -> Self {
        Self { t_ms: 0.0, playing: None, speed: 1.0, drawn: None }
    }
}

impl Transport {
    /// Whether it plays.
    pub fn is_playing(&self) -> bool {
        self.playing.is_some()
    }

    /// While it plays: since when (the window's time, s) and from where (ms).
    pub fn playing_from(&self) -> Option<(f64, f64)> {
        self.playing
    }

    /// Stops where it is (STOP); whether it was playing.
    pub fn halt(&mut self) -> bool {
        self.playing.take().is_some()
    }

    /// Plays from the cursor, or stops where it is.
    pub fn toggle(&mut self, now_s: f64) {
        self.playing = match self.playing {
            Some(_) => None,
            None => Some((now_s, self.t_ms)),
        };
    }

    /// Puts the cursor at `t_ms` (playing on from there if it plays).
    pub fn seek(&mut self, t_ms: f64, now_s: f64) {
        self.t_ms = t_ms.max(0.0);
        if self.playing.is_some() {
            self.playing = Some((now_s, self.t_ms));
        }
    }

    /// Moves the cursor on to `now_s` while playing, looping over `0..end_ms`.
    pub fn advance(&mut self, now_s: f64, end_ms: f64) {
        if let Some((since, from)) = self.playing {
            let t = from + (now_s - since).max(0.0) * 1000.0 * self.speed;
            self.t_ms = if end_ms > 0.0 { t % end_ms } else { 0.0 };
        } else if end_ms > 0.0 && self.t_ms > end_ms {
            self.t_ms = end_ms;
        }
    }

    /// The span the bar last showed, ms.
    pub fn span_ms(&self) -> Option<f64> {
        self.drawn.map(|(_, _, span)| span)
    }

    /// Where on the screen the bar last drew time `t_ms` (the same x as the
    /// sound lane's and the graph's for the same time: one axis).
    pub fn x_of(&self, t_ms: f64) -> Option<f32> {
        let (left, width, span) = self.drawn?;
        // Positions on a bar of a few hundred points: f32 is plenty.
        #[allow(clippy::cast_possible_truncation)]
        let along = (t_ms / span.max(1e-9)).clamp(0.0, 1.0) as f32;
        Some(left + width * along)
    }

    /// The row: play / pause, the speed, and the cursor over `0..end_ms` with
    /// a tick at each of `marks` (frames, steps). `end_ms` is the show's span:
    /// the longer of the motion and its sound (`SoundView::span_ms`), so the
    /// bar, the sound lane and the graph share one time axis. Space plays and
    /// pauses while no field has the keyboard. Keeps the window repainting
    /// while it plays.
    pub fn ui(&mut self, ui: &mut egui::Ui, end_ms: f64, marks: &[f64], words: &Strings) {
        let now = ui.input(|input| input.time);
        let keys_free = ui.memory(|memory| memory.focused().is_none());
        if keys_free && ui.input_mut(|input| input.consume_key(egui::Modifiers::NONE, egui::Key::Space)) {
            self.toggle(now);
        }
        self.advance(now, end_ms);
        ui.horizontal(|ui| {
            let text = if self.is_playing() { words.pause } else { words.play };
            if ui.button(text).on_hover_text(words.space_plays).clicked() {
                self.toggle(now);
            }
            let mut speed = self.speed;
            egui::ComboBox::from_id_salt("preview-speed")
                .selected_text(format!("×{speed}"))
                .width(56.0)
                .show_ui(ui, |ui| {
                    for option in SPEEDS {
                        ui.selectable_value(&mut speed, option, format!("×{option}"));
                    }
                })
                .response
                .widget_info(|| egui::WidgetInfo::labeled(egui::Role::ComboBox, true, words.preview_speed));
            if speed != self.speed {
                // The cursor stays where it is; from now on at the new speed.
                self.seek(self.t_ms, now);
                self.speed = speed;
            }
            ui.label(format!("{:.2} / {:.2} s", self.t_ms / 1000.0, end_ms / 1000.0));
        });
        let width = ui.available_width();
        let (rect, response) = ui.allocate_exact_size(egui::vec2(width, 20.0), egui::Sense::click_and_drag());
        response.widget_info(|| egui::WidgetInfo::slider(true, self.t_ms, words.time_cursor));
        if let Some(pointer) = response.interact_pointer_pos()
            && (response.dragged() || response.clicked())
        {
            let fraction = f64::from(((pointer.x - rect.left()) / rect.width().max(1.0)).clamp(0.0, 1.0));
            self.seek(fraction * end_ms, now);
        }
        let painter = ui.painter_at(rect);
        let visuals = ui.visuals();
        let bar = rect.shrink2(egui::vec2(0.0, 6.0));
        self.drawn = Some((bar.left(), bar.width(), end_ms));
        painter.rect_filled(bar, 3.0, visuals.extreme_bg_color);
        // Positions on a bar of a few hundred points: f32 is plenty.
        #[allow(clippy::cast_possible_truncation)]
        let x_of = |t: f64| bar.left() + bar.width() * (t / end_ms.max(1e-9)).clamp(0.0, 1.0) as f32;
        for mark in marks {
            painter.vline(x_of(*mark), bar.y_range(), visuals.widgets.noninteractive.bg_stroke);
        }
        let x = x_of(self.t_ms);
        painter.rect_filled(
            egui::Rect::from_min_max(bar.min, egui::pos2(x, bar.bottom())),
            3.0,
            visuals.selection.bg_fill,
        );
        painter.vline(x, rect.y_range(), egui::Stroke::new(2.0, visuals.strong_text_color()));
        if self.is_playing() {
            ui.ctx().request_repaint();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn playing_moves_the_cursor_at_the_speed_and_loops() {
        let mut transport = Transport::default();
        transport.toggle(10.0);
        transport.advance(10.5, 2000.0);
        assert!((transport.t_ms - 500.0).abs() < 1e-9);
        transport.advance(12.5, 2000.0);
        assert!((transport.t_ms - 500.0).abs() < 1e-9, "looped: 2500 ms is 500 ms into the next pass");
        transport.speed = 0.25;
        transport.seek(0.0, 13.0);
        transport.advance(15.0, 2000.0);
        assert!((transport.t_ms - 500.0).abs() < 1e-9, "2 s at ×0.25");
        transport.toggle(15.0);
        transport.advance(20.0, 2000.0);
        assert!((transport.t_ms - 500.0).abs() < 1e-9, "stopped");
    }
}
