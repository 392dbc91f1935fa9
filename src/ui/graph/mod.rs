//! The graph pane: each channel's curve over time, its legend beside it as a
//! list that never cuts a name (click to show or hide, solo one), the
//! moves' lane above the curves on the same time axis, and what the board
//! plays drawn dashed against what the author means. Keys are the ends of
//! the authored moves: drag one (or a box-selected set) in time and value;
//! the move into a selected key shows its Bézier handles, drag one to shape
//! it. The graph edits nothing itself: it says what was done as a
//! [`GraphEdit`], once per drag, and the family applies it as one undo step.

mod keys;
mod legend;
pub mod shape;
mod words;

use std::collections::BTreeSet;

use egui_plot::{Line, LineStyle, Plot, PlotPoints};

pub use words::{GraphWords, words};

use crate::project::{Easing, Handles};
use crate::ui::i18n::Language;
use crate::ui::layout::{self, Pane};
use crate::ui::plot::{decimate, series_color};

/// One channel's curve, as its family authored it.
#[derive(Clone, Debug, PartialEq)]
pub struct Channel {
    /// Its name, shown whole in the legend.
    pub name: String,
    /// Where its first move starts: ms, °.
    pub start: [f64; 2],
    /// The ends of its moves, in time order.
    pub keys: Vec<Key>,
    /// The lowest and the highest value a key may take, °.
    pub limits: [f64; 2],
    /// What the board plays (ms, °), when it differs from the curve drawn
    /// (a curve baked into straight moves); `None` when it plays the keys as drawn.
    pub baked: Option<Vec<[f64; 2]>>,
}

/// The end of one move: when, where, and the curve of the move into it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Key {
    /// ms from the start of the graph.
    pub t_ms: f64,
    /// °.
    pub value: f64,
    /// The curve of the move arriving here.
    pub easing: Easing,
}

/// A key: its channel's place among the channels, its own among the keys.
pub type KeyRef = (usize, usize);

/// What the graph shows.
#[derive(Clone, Copy, Debug)]
pub struct Curves<'a> {
    /// The channels, in legend order.
    pub channels: &'a [Channel],
    /// The moves' lane above the curves: each span's start, end (ms) and label.
    pub lane: &'a [(f64, f64, String)],
    /// One board update, ms: a dragged key's time snaps to whole ones.
    pub update_ms: f64,
    /// Other times a dragged key snaps to (a sound's onsets), ms.
    pub onsets_ms: &'a [f64],
    /// The preview's time cursor, ms.
    pub cursor_ms: Option<f64>,
    /// Whether the keys can be moved and shaped here (a macro's lines are
    /// its actions' steps, edited there: drawn only).
    pub editable: bool,
    /// The sound's waveform, drawn under the curves on their time axis.
    pub sound: Option<SoundStrip<'a>>,
}

/// The colour of a sound's onsets, on the graphs and on the sound lane.
pub const ONSET: egui::Color32 = egui::Color32::from_rgb(240, 150, 40);

/// A sound's onsets (ms, on the motion's time) and waveform, as a pane hands them to the graph.
pub type SoundMarks<'a> = (&'a [f64], Option<SoundStrip<'a>>);

/// A sound as the graph draws it under its curves.
#[derive(Clone, Copy, Debug)]
pub struct SoundStrip<'a> {
    /// Its peak pyramid.
    pub peaks: &'a crate::audio::Peaks,
    /// Its samples a second.
    pub rate: u32,
    /// Where it starts on the motion's time, ms.
    pub offset_ms: f64,
    /// Where it ends on the motion's time, ms.
    pub end_ms: f64,
}

/// What the user did on the graph, for the family to apply as one edit.
#[derive(Clone, Debug, PartialEq)]
pub enum GraphEdit {
    /// The keys moved together by `dt_ms` (snapped: the grabbed key lands on
    /// a whole update or an onset) and `dv_deg` (the family keeps each within
    /// its channel's limits).
    Move {
        /// The keys moved.
        keys: Vec<KeyRef>,
        /// In time, ms.
        dt_ms: f64,
        /// In value, °.
        dv_deg: f64,
    },
    /// The moves into `keys` given `easing` (a handle dragged, a curve pasted, a preset picked).
    Shape {
        /// The keys whose moves change.
        keys: Vec<KeyRef>,
        /// Their new curve.
        easing: Easing,
    },
}

/// A drag under way.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Drag {
    /// The selected keys, grabbed by one of them; the pointer's travel, points.
    Keys { grabbed: KeyRef, travel: egui::Vec2 },
    /// A handle of the move into `key`, where it is now.
    Handle { key: KeyRef, which: shape::Which, handles: Handles },
    /// A selection box from a corner to where the pointer is (ms, °).
    Box { from: [f64; 2], to: [f64; 2] },
}

/// The pane's own state: what is shown, selected and copied, the drag under
/// way, the legend's width (0 until it is first measured).
#[derive(Debug, Default)]
pub struct Graph {
    shown: Vec<bool>,
    solo: Option<usize>,
    selected: BTreeSet<KeyRef>,
    clipboard: Option<Easing>,
    drag: Option<Drag>,
    /// A key drag's offset (ms, °) as the last frame worked it out.
    offset: (f64, f64),
    /// While a drag is under way, whether the view fitted the curves before
    /// it: the view holds still under the pointer, then fits again as it did.
    held_view: Option<egui::Vec2b>,
    legend_width: f32,
}

/// Channels shown at first: more would be an unreadable tangle; the legend
/// shows the rest on a click.
pub const SHOWN_FIRST: usize = 8;

impl Graph {
    /// Whether each channel is drawn (solo counted).
    fn visible(&self) -> Vec<bool> {
        match self.solo {
            Some(only) => (0..self.shown.len()).map(|c| c == only).collect(),
            None => self.shown.clone(),
        }
    }

    /// The selection and the shown flags kept to `channels` (a key removed, a channel added).
    fn keep_to(&mut self, channels: &[Channel]) {
        if self.shown.len() != channels.len() {
            self.shown = (0..channels.len()).map(|c| c < SHOWN_FIRST).collect();
            self.solo = None;
        }
        self.selected.retain(|&(c, k)| channels.get(c).is_some_and(|channel| k < channel.keys.len()));
    }

    /// Draws the pane in the space left: its tools, the legend, the lane and
    /// the curves. Returns what the user did, once a drag or a click is done.
    pub fn show(&mut self, ui: &mut egui::Ui, id: &str, curves: &Curves<'_>, language: Language) -> Option<GraphEdit> {
        let words = words(language);
        self.keep_to(curves.channels);
        let mut edit = if curves.editable { self.tools(ui, curves, words) } else { None };
        if self.legend_width <= 0.0 {
            self.legend_width = legend::natural_width(ui, curves.channels, words);
        }
        let mut width = self.legend_width;
        layout::columns(ui, &format!("{id}-legend"), &mut width, 120.0, |ui, pane| match pane {
            Pane::First => legend::show(ui, id, curves.channels, (&mut self.shown, &mut self.solo), words),
            Pane::Second => {
                if let Some(done) = self.curves(ui, id, curves, words) {
                    edit = Some(done);
                }
            }
        });
        self.legend_width = width;
        edit
    }

    /// The row over the graph: the selection, its curve, copy and paste, the help.
    fn tools(&mut self, ui: &mut egui::Ui, curves: &Curves<'_>, words: &GraphWords) -> Option<GraphEdit> {
        let mut edit = None;
        let keys: Vec<KeyRef> = self.selected.iter().copied().collect();
        let first = keys.first().and_then(|&(c, k)| curves.channels.get(c)?.keys.get(k)).map(|key| key.easing);
        ui.horizontal(|ui| {
            ui.label(format!("{} {}", keys.len(), words.selected));
            ui.add_enabled_ui(first.is_some(), |ui| {
                let label = ui.label(words.curve);
                let mut picked = first.unwrap_or_default();
                egui::ComboBox::from_id_salt("graph-preset")
                    .selected_text(preset_name(picked, words))
                    .show_ui(ui, |ui| {
                        for preset in Easing::ALL {
                            ui.selectable_value(&mut picked, preset, preset_name(preset, words));
                        }
                    })
                    .response
                    .labelled_by(label.id);
                if first.is_some_and(|was| was != picked) {
                    edit = Some(GraphEdit::Shape { keys: keys.clone(), easing: picked });
                }
            });
            if ui.add_enabled(first.is_some(), egui::Button::new(words.copy_curve)).clicked() {
                self.clipboard = first;
            }
            let can_paste = self.clipboard.is_some() && !keys.is_empty();
            if ui.add_enabled(can_paste, egui::Button::new(words.paste_curve)).clicked()
                && let Some(easing) = self.clipboard
            {
                edit = Some(GraphEdit::Shape { keys: keys.clone(), easing });
            }
            ui.label("?").on_hover_text(words.how);
            if curves.channels.iter().any(|channel| channel.baked.is_some()) {
                ui.weak(words.baked);
            }
        });
        edit
    }

    /// The lane over the curves, the curves, their keys and handles.
    fn curves(&mut self, ui: &mut egui::Ui, id: &str, curves: &Curves<'_>, words: &GraphWords) -> Option<GraphEdit> {
        let area = ui.available_rect_before_wrap();
        let lane_height = if curves.lane.is_empty() { 0.0 } else { 20.0 };
        let lane_rect = egui::Rect::from_min_size(area.min, egui::vec2(area.width(), lane_height));
        let strip_height = if curves.sound.is_some() { 36.0 } else { 0.0 };
        let strip_rect = egui::Rect::from_min_max(egui::pos2(area.left(), area.bottom() - strip_height), area.max);
        let plot_rect = egui::Rect::from_min_max(
            egui::pos2(area.left(), lane_rect.bottom()),
            egui::pos2(area.right(), strip_rect.top()),
        );
        let visible = self.visible();
        let shift = ui.input(|input| input.modifiers.shift);
        let dragging = self.drag.is_some();
        let mut held_view = self.held_view.take();
        let preview = keys::Preview::of(self);
        let cursor_color = ui.visuals().strong_text_color();
        let response = layout::inside(ui, plot_rect, |ui| {
            Plot::new((id, "graph"))
                .width(plot_rect.width())
                .height(plot_rect.height())
                .x_axis_label("ms")
                .y_axis_label(words.angle_axis)
                .y_grid_spacer(egui_plot::uniform_grid_spacer(degree_steps))
                .y_axis_min_width(36.0)
                .allow_scroll(false)
                // One time axis with the play bar and the sound lane: from 0 to the longer of motion and sound.
                .include_x(0.0)
                .include_x(curves.sound.map_or(0.0, |sound| sound.end_ms))
                // Room around the curves: a key at the top or the bottom stays clear of the axes.
                .set_margin_fraction(egui::vec2(0.03, 0.12))
                .allow_drag(!shift && self.drag.is_none())
                .show(ui, |plot| {
                    // A key dragged past the curves' extent would move the view under the pointer.
                    match (dragging, held_view) {
                        (true, None) => held_view = Some(plot.auto_bounds()),
                        (false, Some(fitted)) => {
                            plot.set_auto_bounds(fitted);
                            held_view = None;
                        }
                        _ => {}
                    }
                    if dragging {
                        plot.set_auto_bounds(false);
                    }
                    let bounds = plot.plot_bounds();
                    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
                    let columns = plot.transform().frame().width().max(1.0) as usize;
                    for (c, channel) in curves.channels.iter().enumerate().filter(|(c, _)| visible[*c]) {
                        let color = series_color(c);
                        if let Some(baked) = &channel.baked {
                            let thinned = decimate(baked, bounds.min()[0], bounds.max()[0], columns);
                            let line = Line::new(format!("{} ~", channel.name), PlotPoints::from(thinned));
                            plot.line(line.color(color.gamma_multiply(0.8)).style(LineStyle::dashed_dense()));
                        }
                        let points = shape::curve_points(channel, |k, key| preview.key(curves, (c, k), key));
                        plot.line(Line::new(channel.name.as_str(), PlotPoints::from(points)).color(color).width(2.0));
                    }
                    // The sound's onsets: keys dragged near one snap to it.
                    let onset = ONSET.gamma_multiply(0.6);
                    for t in curves.onsets_ms.iter().filter(|t| (bounds.min()[0]..=bounds.max()[0]).contains(*t)) {
                        plot.vline(egui_plot::VLine::new("", *t).color(onset).width(1.0));
                    }
                    if let Some(t) = curves.cursor_ms {
                        plot.vline(egui_plot::VLine::new("", t).color(cursor_color).width(1.5));
                    }
                })
        });
        self.held_view = held_view;
        keys::lane(ui, lane_rect, &response.transform, curves.lane);
        if let Some(sound) = curves.sound {
            keys::waveform(ui, strip_rect, &response.transform, sound, curves.onsets_ms);
        }
        if !curves.editable {
            return None;
        }
        let mut on_graph = keys::OnGraph { graph: self, curves, transform: &response.transform, visible: &visible };
        on_graph.interact(ui, &response.response, id, words)
    }
}

/// The value axis's three grid steps for the range in view, in degrees a
/// servo is thought of in (5°, 10°, 30°, 90°…), about a quarter, an eighth
/// and a twenty-fourth of it: the axis is labelled even over a few degrees.
// egui_plot hands the spacer its input by value.
#[allow(clippy::needless_pass_by_value)]
fn degree_steps(input: egui_plot::GridInput) -> [f64; 3] {
    // Each a multiple of the one before: the three steps' marks fall on one another.
    const STEPS: [f64; 9] = [0.1, 0.5, 1.0, 5.0, 10.0, 30.0, 90.0, 180.0, 360.0];
    let range = (input.bounds.1 - input.bounds.0).abs().max(1e-3);
    let at_least = |part: f64| STEPS.iter().copied().find(|step| *step >= range / part).unwrap_or(720.0);
    [at_least(24.0), at_least(8.0), at_least(4.0)]
}

fn preset_name(easing: Easing, words: &GraphWords) -> &'static str {
    Easing::ALL.iter().position(|preset| *preset == easing).map_or(words.presets[5], |at| words.presets[at])
}
