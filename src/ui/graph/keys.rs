//! The keys and handles on the graph: drawn over the curves, each an
//! accessible widget one can grab (named by its channel and place), the
//! drag under way drawn before it is applied, and a box that selects keys.

use egui::{Pos2, Rect, Sense, Stroke, pos2, vec2};
use egui_plot::{PlotPoint, PlotTransform};

use super::shape::{self, Which};
use super::{Curves, Drag, Graph, GraphEdit, GraphWords, Key, KeyRef};
use crate::project::Easing;

/// A key's grab size, points.
const KEY_SIZE: f32 = 12.0;
/// A handle's grab size, points.
const HANDLE_SIZE: f32 = 10.0;
/// How near (points) a dragged key's time snaps to an onset.
const SNAP_REACH: f32 = 8.0;
/// Handles are drawn for at most this many selected keys (more would hide the curves).
const MOST_HANDLES: usize = 24;

/// The drag under way as the curves should draw it (a key drag's offset as
/// the last frame worked it out: the curves are drawn before this frame's is known).
pub struct Preview<'a> {
    drag: Option<Drag>,
    selected: &'a std::collections::BTreeSet<KeyRef>,
    offset: (f64, f64),
}

impl<'a> Preview<'a> {
    pub fn of(graph: &'a Graph) -> Self {
        Self { drag: graph.drag, selected: &graph.selected, offset: graph.offset }
    }

    /// `key` (at `at`) as the drag under way has it.
    pub fn key(&self, curves: &Curves<'_>, at: KeyRef, key: Key) -> Key {
        match self.drag {
            Some(Drag::Handle { key: shaped, handles, .. }) if shaped == at => {
                Key { easing: Easing::Shaped(handles), ..key }
            }
            Some(Drag::Keys { .. }) if self.selected.contains(&at) => {
                let (dt, dv) = self.offset;
                let limits = curves.channels[at.0].limits;
                Key { t_ms: key.t_ms + dt, value: (key.value + dv).clamp(limits[0], limits[1]), ..key }
            }
            _ => key,
        }
    }
}

/// The moves' lane over the curves, on the plot's time axis.
pub fn lane(ui: &egui::Ui, rect: Rect, transform: &PlotTransform, spans: &[(f64, f64, String)]) {
    if spans.is_empty() {
        return;
    }
    let frame = transform.frame();
    let painter = ui.painter_at(Rect::from_x_y_ranges(frame.x_range(), rect.y_range()));
    let visuals = ui.visuals();
    let font = egui::TextStyle::Small.resolve(ui.style());
    for (index, (start, end, label)) in spans.iter().enumerate() {
        let x0 = transform.position_from_point_x(*start);
        let x1 = transform.position_from_point_x(*end);
        let bar = Rect::from_x_y_ranges(x0..=(x1 - 1.0).max(x0 + 1.0), rect.top() + 2.0..=rect.bottom() - 2.0);
        let fill =
            if index % 2 == 0 { visuals.widgets.inactive.bg_fill } else { visuals.widgets.noninteractive.bg_fill };
        painter.rect_filled(bar, 2.0, fill);
        let galley = painter.layout_no_wrap(label.clone(), font.clone(), visuals.text_color());
        if galley.size().x + 4.0 < bar.width() {
            painter.galley(pos2(bar.center().x - galley.size().x / 2.0, bar.top()), galley, visuals.text_color());
        }
    }
}

/// The sound's waveform under the curves, on their time axis (it zooms and
/// scrolls with them): one min/max pair per pixel column from the peak
/// pyramid, the onsets over it.
pub fn waveform(ui: &egui::Ui, rect: Rect, transform: &PlotTransform, sound: super::SoundStrip<'_>, onsets_ms: &[f64]) {
    let frame = transform.frame();
    let strip = Rect::from_x_y_ranges(frame.x_range(), rect.top() + 4.0..=rect.bottom() - 2.0);
    let painter = ui.painter_at(strip);
    let visuals = ui.visuals();
    painter.rect_filled(strip, 2.0, visuals.extreme_bg_color);
    let at = |x: f32| transform.value_from_position(pos2(x, strip.center().y)).x;
    let (from_s, to_s) =
        ((at(strip.left()) - sound.offset_ms) / 1000.0, (at(strip.right()) - sound.offset_ms) / 1000.0);
    // A strip's width in points: small and positive.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let columns = strip.width().max(1.0) as usize;
    let (low, high) = sound.peaks.range(from_s, to_s, sound.rate, columns);
    let (middle, half) = (strip.center().y, strip.height() / 2.0 - 1.0);
    let stroke = Stroke::new(1.0, visuals.widgets.inactive.fg_stroke.color);
    for (column, (low, high)) in low.iter().zip(&high).enumerate() {
        // Column indices: small.
        #[allow(clippy::cast_precision_loss)]
        let x = strip.left() + column as f32 + 0.5;
        if high > low {
            painter.vline(x, (middle - high * half)..=(middle - low * half), stroke);
        }
    }
    let onset = Stroke::new(1.0, super::ONSET);
    for t in onsets_ms {
        let x = transform.position_from_point_x(*t);
        if strip.x_range().contains(x) {
            painter.vline(x, strip.y_range(), onset);
        }
    }
}

/// The graph's keys and handles over one frame's plot.
pub struct OnGraph<'a, 'b> {
    pub graph: &'a mut Graph,
    pub curves: &'a Curves<'b>,
    pub transform: &'a PlotTransform,
    pub visible: &'a [bool],
}

impl OnGraph<'_, '_> {
    fn screen(&self, point: [f64; 2]) -> Pos2 {
        self.transform.position_from_point(&PlotPoint::new(point[0], point[1]))
    }

    fn plot(&self, pos: Pos2) -> [f64; 2] {
        let point = self.transform.value_from_position(pos);
        [point.x, point.y]
    }

    /// The keys, the handles of the selected keys' moves and the box; what
    /// the user did once a drag or a click is done.
    pub fn interact(
        &mut self,
        ui: &egui::Ui,
        plot: &egui::Response,
        id: &str,
        words: &GraphWords,
    ) -> Option<GraphEdit> {
        let frame = *self.transform.frame();
        let painter = ui.painter_at(frame);
        let mut edit = self.handles(ui, &painter, id, words);
        if let Some(done) = self.keys(ui, &painter, id, words) {
            edit = Some(done);
        }
        if let Some(done) = self.selection_box(ui, plot, &painter) {
            edit = Some(done);
        }
        if plot.hovered() {
            edit = edit.or_else(|| self.copy_paste(ui));
        }
        edit
    }

    fn keys(&mut self, ui: &egui::Ui, painter: &egui::Painter, id: &str, words: &GraphWords) -> Option<GraphEdit> {
        let frame = *self.transform.frame();
        let shift = ui.input(|input| input.modifiers.shift);
        let mut edit = None;
        let (dt, dv) = self.offset(ui);
        self.graph.offset = (dt, dv);
        let selection = ui.visuals().selection.stroke.color;
        for (c, channel) in self.curves.channels.iter().enumerate().filter(|(c, _)| self.visible[*c]) {
            for (k, key) in channel.keys.iter().enumerate() {
                let at = self.screen([key.t_ms, key.value]);
                let grabbed = matches!(self.graph.drag, Some(Drag::Keys { grabbed, .. }) if grabbed == (c, k));
                // Out of view, a key is not drawn, except the one held (its drag goes on).
                if !grabbed && !frame.expand(KEY_SIZE / 2.0).contains(at) {
                    continue;
                }
                let selected = self.graph.selected.contains(&(c, k));
                let response = ui.interact(
                    Rect::from_center_size(at, vec2(KEY_SIZE, KEY_SIZE)),
                    ui.scope_id().with((id, "key", c, k)),
                    Sense::click_and_drag(),
                );
                // Worded only when asked (accessibility, a test): not for every key every frame.
                response.widget_info(|| {
                    egui::WidgetInfo::labeled(egui::Role::Button, true, format!("{} {} #{k}", words.key, channel.name))
                });
                let response = response.on_hover_ui(|ui| {
                    ui.label(format!("{} #{k}: {:.0} ms, {:.1}°", channel.name, key.t_ms, key.value));
                });
                if response.clicked() || response.drag_started() {
                    if shift && response.clicked() {
                        if !self.graph.selected.remove(&(c, k)) {
                            self.graph.selected.insert((c, k));
                        }
                    } else if !selected {
                        if !shift {
                            self.graph.selected.clear();
                        }
                        self.graph.selected.insert((c, k));
                    }
                }
                if response.drag_started() {
                    self.graph.drag = Some(Drag::Keys { grabbed: (c, k), travel: egui::Vec2::ZERO });
                }
                if response.dragged()
                    && let Some(Drag::Keys { travel, .. }) = &mut self.graph.drag
                {
                    *travel += response.drag_delta();
                }
                if response.drag_stopped() {
                    let (dt_ms, dv_deg) = self.offset(ui);
                    self.graph.drag = None;
                    self.graph.offset = (0.0, 0.0);
                    if dt_ms != 0.0 || dv_deg != 0.0 {
                        let keys = self.graph.selected.iter().copied().collect();
                        edit = Some(GraphEdit::Move { keys, dt_ms, dv_deg });
                    }
                }
                let moving =
                    matches!(self.graph.drag, Some(Drag::Keys { .. })) && self.graph.selected.contains(&(c, k));
                let shown_at = if moving { self.screen([key.t_ms + dt, key.value + dv]) } else { at };
                let color = super::series_color(c);
                let fill = if self.graph.selected.contains(&(c, k)) { selection } else { color };
                painter.circle(shown_at, 4.5, fill, Stroke::new(1.0, ui.visuals().strong_text_color()));
            }
        }
        edit
    }

    /// The grabbed key's travel as (ms, °): its time snapped to a whole
    /// update or an onset in reach, its value kept within the limits.
    fn offset(&self, ui: &egui::Ui) -> (f64, f64) {
        let Some(Drag::Keys { grabbed: (c, k), travel }) = self.graph.drag else { return (0.0, 0.0) };
        let Some(key) = self.curves.channels.get(c).and_then(|channel| channel.keys.get(k)) else { return (0.0, 0.0) };
        let now = self.plot(self.screen([key.t_ms, key.value]) + travel);
        let reach_ms = f64::from(SNAP_REACH) / self.transform.dpos_dvalue_x().abs().max(1e-9);
        let t = crate::authoring::retime::snap(now[0], self.curves.update_ms, self.curves.onsets_ms, reach_ms);
        let t = if ui.input(|input| input.modifiers.alt) { key.t_ms } else { t };
        let limits = self.curves.channels[c].limits;
        (t - key.t_ms, now[1].clamp(limits[0], limits[1]) - key.value)
    }

    fn handles(&mut self, ui: &egui::Ui, painter: &egui::Painter, id: &str, words: &GraphWords) -> Option<GraphEdit> {
        if self.graph.selected.len() > MOST_HANDLES || matches!(self.graph.drag, Some(Drag::Keys { .. })) {
            return None;
        }
        let mut edit = None;
        let selected: Vec<KeyRef> = self.graph.selected.iter().copied().collect();
        for (c, k) in selected {
            if !self.visible.get(c).copied().unwrap_or(false) {
                continue;
            }
            let channel = &self.curves.channels[c];
            let key = channel.keys[k];
            let (from, to) = (shape::move_start(channel, k), [key.t_ms, key.value]);
            let handles = match self.graph.drag {
                Some(Drag::Handle { key: dragged, handles, .. }) if dragged == (c, k) => handles,
                _ => key.easing.handles(),
            };
            let points = shape::handle_points(from, to, handles);
            for (which, point, anchor) in [(Which::Out, points[0], from), (Which::In, points[1], to)] {
                let at = self.screen(point);
                let stroke = Stroke::new(1.0, ui.visuals().weak_text_color());
                painter.line_segment([self.screen(anchor), at], stroke);
                let response = ui.interact(
                    Rect::from_center_size(at, vec2(HANDLE_SIZE, HANDLE_SIZE)),
                    ui.scope_id().with((id, "handle", c, k, which == Which::Out)),
                    Sense::drag(),
                );
                let side = if which == Which::Out { "out" } else { "in" };
                response.widget_info(|| {
                    egui::WidgetInfo::labeled(
                        egui::Role::Button,
                        true,
                        format!("{} {side} {} #{k}", words.handle, channel.name),
                    )
                });
                if response.drag_started() {
                    self.graph.drag = Some(Drag::Handle { key: (c, k), which, handles });
                }
                if response.dragged()
                    && let Some(pointer) = response.interact_pointer_pos()
                {
                    let point = self.plot(pointer);
                    if let Some(Drag::Handle { handles, which: dragged, .. }) = &mut self.graph.drag
                        && *dragged == which
                    {
                        *handles = shape::placed(*handles, which, from, to, point);
                    }
                }
                if response.drag_stopped()
                    && let Some(Drag::Handle { handles, .. }) = self.graph.drag.take()
                {
                    edit = Some(GraphEdit::Shape { keys: vec![(c, k)], easing: Easing::Shaped(handles) });
                }
                let side = HANDLE_SIZE * 0.6;
                painter.rect_filled(
                    Rect::from_center_size(at, vec2(side, side)),
                    1.0,
                    ui.visuals().strong_text_color(),
                );
            }
        }
        edit
    }

    /// Shift+drag on the graph's background: a box that selects the keys in it.
    fn selection_box(&mut self, ui: &egui::Ui, plot: &egui::Response, painter: &egui::Painter) -> Option<GraphEdit> {
        let shift = ui.input(|input| input.modifiers.shift);
        if plot.drag_started() && shift {
            let origin = ui.input(|input| input.pointer.press_origin()).unwrap_or_default();
            let from = self.plot(origin);
            self.graph.drag = Some(Drag::Box { from, to: from });
        }
        if let Some(Drag::Box { from, to }) = self.graph.drag {
            // Where the pointer is; once it is gone (released outside), where it was last.
            let pointer = plot.interact_pointer_pos().or_else(|| ui.input(|input| input.pointer.latest_pos()));
            let to = pointer.map_or(to, |pos| self.plot(pos));
            self.graph.drag = Some(Drag::Box { from, to });
            let rect = Rect::from_two_pos(self.screen(from), self.screen(to));
            let color = ui.visuals().selection.stroke.color;
            painter.rect(rect, 0.0, color.gamma_multiply(0.15), Stroke::new(1.0, color), egui::StrokeKind::Inside);
            if plot.drag_stopped() || !plot.dragged() {
                self.graph.drag = None;
                // A box replaces the selection; with Ctrl (⌘) it adds to it.
                if !ui.input(|input| input.modifiers.command) {
                    self.graph.selected.clear();
                }
                let inside = shape::keys_in_box(self.curves.channels, self.visible, from, to);
                self.graph.selected.extend(inside);
            }
        } else if plot.clicked() && !shift {
            self.graph.selected.clear();
        }
        None
    }

    /// Ctrl+C over the graph copies the first selected key's curve; Ctrl+V
    /// gives it to every selected key's move.
    fn copy_paste(&mut self, ui: &egui::Ui) -> Option<GraphEdit> {
        let (copy, paste) = ui.input(|input| {
            let copy = input.events.iter().any(|event| matches!(event, egui::Event::Copy));
            let paste = input.events.iter().any(|event| matches!(event, egui::Event::Paste(_)));
            (copy, paste)
        });
        let first = self.graph.selected.iter().next().copied();
        if copy && let Some((c, k)) = first {
            self.graph.clipboard = Some(self.curves.channels[c].keys[k].easing);
        }
        let easing = self.graph.clipboard.filter(|_| paste && first.is_some())?;
        Some(GraphEdit::Shape { keys: self.graph.selected.iter().copied().collect(), easing })
    }
}
