//! How a family's panels share the window: a list beside its editor, an
//! editor over its plot and preview, sliders or a pad beside a preview. Every
//! divider can be dragged, the lower pane can be made taller or collapsed,
//! and the sizes are remembered per family.

use egui::{Rect, Sense, UiBuilder, pos2, vec2};

/// The sizes a family's panels were left at (remembered between runs).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct Layout {
    /// Width of a list of names beside its editor, points.
    pub list_width: f32,
    /// Share of the height the pane under an editor (its plot and preview) takes, 0–1.
    pub lower_share: f32,
    /// Whether that pane is open.
    pub lower_open: bool,
    /// Width of the preview beside sliders or a pad, points.
    pub side_width: f32,
    /// Width of the values beside a plot (a PLEN2 frame's joints), points.
    pub values_width: f32,
    /// Whether the robot's preview is shown beside the panels.
    pub view_open: bool,
    /// Share of the height the settings under sliders take, 0–1.
    pub settings_share: f32,
    /// Whether the settings are open.
    pub settings_open: bool,
    /// Share of the height the graph pane under a list and its editor takes, 0–1.
    pub graph_share: f32,
    /// Whether the graph pane is open.
    pub graph_open: bool,
}

impl Default for Layout {
    fn default() -> Self {
        Self {
            list_width: 180.0,
            lower_share: 0.4,
            lower_open: true,
            side_width: 460.0,
            values_width: 500.0,
            view_open: true,
            settings_share: 0.45,
            settings_open: false,
            graph_share: 0.38,
            graph_open: true,
        }
    }
}

/// Thickness of a divider, points.
pub const DIVIDER: f32 = 8.0;

fn divider(ui: &mut egui::Ui, rect: Rect, id: egui::Id, horizontal: bool, key: &'static str) -> egui::Response {
    let label = crate::ui::i18n::Language::in_context(ui.ctx()).word(key);
    let response = ui.interact(rect, id, Sense::drag());
    response.widget_info(|| egui::WidgetInfo::labeled(egui::Role::Splitter, true, label));
    let response = response.on_hover_cursor(if horizontal {
        egui::CursorIcon::ResizeHorizontal
    } else {
        egui::CursorIcon::ResizeVertical
    });
    let visuals = ui.visuals();
    let stroke = if response.hovered() || response.dragged() {
        visuals.widgets.hovered.fg_stroke
    } else {
        visuals.widgets.noninteractive.bg_stroke
    };
    let painter = ui.painter();
    if horizontal {
        painter.vline(rect.center().x, rect.y_range(), stroke);
    } else {
        painter.hline(rect.x_range(), rect.center().y, stroke);
    }
    response
}

/// Runs `add` in its own child `Ui` over exactly `rect`, clipped to it.
pub fn inside<R>(ui: &mut egui::Ui, rect: Rect, add: impl FnOnce(&mut egui::Ui) -> R) -> R {
    ui.scope_builder(UiBuilder::new().max_rect(rect).layout(egui::Layout::top_down(egui::Align::Min)), |ui| {
        ui.set_clip_rect(rect.intersect(ui.clip_rect()));
        add(ui)
    })
    .inner
}

/// Which of two panes `add` is asked to fill.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pane {
    /// The left (or upper) one.
    First,
    /// The right (or lower) one.
    Second,
}

/// Two panes side by side filling the space left, the first `width` points
/// wide (dragging the divider between them changes it, within `min` of either
/// side). `add` fills each in turn.
pub fn columns(ui: &mut egui::Ui, id_salt: &str, width: &mut f32, min: f32, mut add: impl FnMut(&mut egui::Ui, Pane)) {
    let area = ui.available_rect_before_wrap();
    let most = (area.width() - min - DIVIDER).max(min);
    let w = width.clamp(min, most);
    let left_rect = Rect::from_min_size(area.min, vec2(w, area.height()));
    let bar = Rect::from_min_size(pos2(left_rect.right(), area.top()), vec2(DIVIDER, area.height()));
    let right_rect = Rect::from_min_max(pos2(bar.right(), area.top()), area.max);
    let response = divider(ui, bar, ui.scope_id().with((id_salt, "divider")), true, "layout.resize_panes");
    if response.dragged() {
        *width = (w + response.drag_delta().x).clamp(min, most);
    }
    inside(ui, left_rect, |ui| add(ui, Pane::First));
    inside(ui, right_rect, |ui| add(ui, Pane::Second));
    ui.allocate_rect(area, Sense::hover());
}

/// An upper pane over a lower one filling the space left. The lower pane
/// takes `share` of the height (drag the divider to change it; it keeps its
/// share as the window is resized) under a header with its `title` and a
/// toggle that collapses it; collapsed, the upper pane takes everything.
/// `add` fills each in turn.
pub fn over(
    ui: &mut egui::Ui,
    id_salt: &str,
    (share, open): (&mut f32, &mut bool),
    title: &str,
    mut add: impl FnMut(&mut egui::Ui, Pane),
) {
    let area = ui.available_rect_before_wrap();
    let header = ui.spacing().interact_size.y + 4.0;
    let min = 120.0;
    let room = (area.height() - header - DIVIDER).max(1.0);
    let most = (room - min).max(min);
    let h = if *open { (*share * room).clamp(min, most) } else { 0.0 };
    let header_top = area.bottom() - h - header;
    let bar = Rect::from_min_size(pos2(area.left(), header_top - DIVIDER), vec2(area.width(), DIVIDER));
    let upper_rect = Rect::from_min_max(area.min, pos2(area.right(), bar.top()));
    let header_rect = Rect::from_min_size(pos2(area.left(), header_top), vec2(area.width(), header));
    let lower_rect = Rect::from_min_max(pos2(area.left(), header_rect.bottom()), area.max);
    if *open {
        let response = divider(ui, bar, ui.scope_id().with((id_salt, "divider")), false, "layout.resize_lower_pane");
        if response.dragged() {
            *share = (h - response.drag_delta().y).clamp(min, most) / room;
        }
    }
    inside(ui, upper_rect, |ui| add(ui, Pane::First));
    inside(ui, header_rect, |ui| {
        ui.horizontal(|ui| {
            // The collapsing header's own arrow (drawn, so no font needs the glyph).
            let size = ui.spacing().icon_width;
            let (_, icon) = ui.allocate_exact_size(vec2(size, size), Sense::click());
            egui::collapsing_header::paint_default_icon(ui, if *open { 1.0 } else { 0.0 }, &icon);
            if icon.clicked() | ui.selectable_label(false, title).clicked() {
                *open = !*open;
            }
        });
    });
    if *open {
        inside(ui, lower_rect, |ui| add(ui, Pane::Second));
    }
    ui.allocate_rect(area, Sense::hover());
}

/// A panel with the preview on its right, `width` points wide (drag the
/// divider), while `open`; closed, the panel takes everything.
pub fn beside(
    ui: &mut egui::Ui,
    id_salt: &str,
    (width, open): (&mut f32, bool),
    mut add: impl FnMut(&mut egui::Ui, Pane),
) {
    if !open {
        add(ui, Pane::First);
        return;
    }
    let area = ui.available_rect_before_wrap();
    let min = 160.0;
    // The divider's place from the left, as `columns` keeps it.
    let mut left = (area.width() - *width - DIVIDER).max(min);
    columns(ui, id_salt, &mut left, min, |ui, pane| add(ui, pane));
    *width = (area.width() - left - DIVIDER).max(min);
}

/// Which part of a list-and-editor panel `add` is asked to fill.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Part {
    /// The list of names, on the left.
    List,
    /// The selected item's editor, on the right.
    Editor,
    /// What is under the editor (timeline, plot, values), collapsible.
    Lower,
    /// The robot's preview, on the right (while the layout has it open).
    View,
    /// The graph pane, the whole width under everything else, collapsible.
    Graph,
}

/// A list beside its editor, the editor over a collapsible lower pane
/// titled `lower_title` (none: the editor takes the height), and the preview
/// on the right while the layout has it open; the panel's sizes live in `layout`.
pub fn list_and_editor(
    ui: &mut egui::Ui,
    id_salt: &str,
    layout: &mut Layout,
    lower_title: Option<&str>,
    mut add: impl FnMut(&mut egui::Ui, Part),
) {
    let Layout { list_width, lower_share, lower_open, side_width, view_open, .. } = layout;
    columns(ui, id_salt, list_width, 140.0, |ui, pane| match pane {
        Pane::First => add(ui, Part::List),
        Pane::Second => beside(ui, &format!("{id_salt}-view"), (&mut *side_width, *view_open), |ui, pane| match pane {
            Pane::First => match lower_title {
                Some(title) => over(ui, id_salt, (&mut *lower_share, &mut *lower_open), title, |ui, pane| {
                    add(ui, if pane == Pane::First { Part::Editor } else { Part::Lower });
                }),
                None => add(ui, Part::Editor),
            },
            Pane::Second => add(ui, Part::View),
        }),
    });
}

/// [`list_and_editor`] over the graph pane titled `graph_title`, which
/// takes the whole width (its legend and its time axis need it) and
/// `layout.graph_share` of the height; collapsed, the rest takes everything.
pub fn list_editor_and_graph(
    ui: &mut egui::Ui,
    id_salt: &str,
    layout: &mut Layout,
    (lower_title, graph_title): (Option<&str>, &str),
    mut add: impl FnMut(&mut egui::Ui, Part),
) {
    let (mut share, mut open) = (layout.graph_share, layout.graph_open);
    over(ui, &format!("{id_salt}-graph"), (&mut share, &mut open), graph_title, |ui, pane| match pane {
        Pane::First => list_and_editor(ui, id_salt, layout, lower_title, &mut add),
        Pane::Second => add(ui, Part::Graph),
    });
    (layout.graph_share, layout.graph_open) = (share, open);
}

/// A floating window that stays out of the way when collapsed: its id is
/// `id` (not its title's, which changes with the language), and collapsed
/// it is parked at the bottom edge, from the right — `slot` its place along
/// it, one per window — where its title bar covers no panel's heading or tab.
pub fn parked_when_collapsed<'a>(
    window: egui::Window<'a>,
    ctx: &egui::Context,
    id: &str,
    slot: u8,
) -> egui::Window<'a> {
    let id = egui::Id::unique(id);
    let collapsed = egui::collapsing_header::CollapsingState::load(ctx, id.with("collapsing"))
        .is_some_and(|state| !state.is_open());
    // Where it stood before it was parked: it goes back there when opened.
    let before = id.with("before parked");
    let Some(mut state) = egui::AreaState::load(ctx, id) else { return window.id(id) };
    let stood: Option<egui::Pos2> = ctx.data(|data| data.get_temp(before));
    let place = match (collapsed, stood) {
        (true, _) => {
            // Its right edge at its slot's, counted from the window's right
            // (the left keeps the lower pane's headings), above the status line.
            let rect = ctx.content_rect();
            let width = state.size.map_or(PARKED_WIDTH, |size| size.x);
            let right = rect.right() - 8.0 - f32::from(slot) * PARKED_WIDTH;
            let parked = pos2(right - width, rect.bottom() - PARKED_ABOVE_BOTTOM);
            if stood.is_none() && state.left_top_pos() != parked {
                ctx.data_mut(|data| data.insert_temp(before, state.left_top_pos()));
            }
            Some(parked)
        }
        (false, Some(stood)) => {
            ctx.data_mut(|data| data.remove::<egui::Pos2>(before));
            Some(stood)
        }
        // Open: whole on the screen (a place remembered from a larger window, or a drag, may leave it hanging off).
        (false, None) => state.size.and_then(|size| {
            let rect = ctx.content_rect();
            let at = state.left_top_pos();
            let whole = pos2(
                at.x.min(rect.right() - size.x).max(rect.left()),
                at.y.min(rect.bottom() - size.y).max(rect.top()),
            );
            (whole != at).then_some(whole)
        }),
    };
    if let Some(place) = place {
        // Put where it stands (a window dragged by its title bar takes its
        // place from memory, not from `current_pos`).
        state.set_left_top_pos(place);
        let layer = egui::LayerId::new(egui::Order::Middle, id);
        ctx.memory_mut(|memory| memory.areas_mut().set_state(layer, state));
    }
    window.id(id)
}

/// How far apart parked windows are along the bottom edge.
const PARKED_WIDTH: f32 = 280.0;
/// How far above the window's bottom a parked title bar sits (above the status line).
pub const PARKED_ABOVE_BOTTOM: f32 = 64.0;

#[cfg(test)]
mod tests {
    use egui_kittest::Harness;
    use egui_kittest::kittest::Queryable;

    use super::*;

    #[test]
    fn dragging_a_divider_resizes_the_panes_and_the_lower_pane_collapses() {
        let mut layout = Layout::default();
        let mut harness = Harness::builder().with_size(vec2(1000.0, 700.0)).build_ui_state(
            |ui, layout: &mut Layout| {
                let Layout { list_width, lower_share, lower_open, .. } = layout;
                columns(ui, "test", list_width, 100.0, |ui, pane| match pane {
                    Pane::First => {
                        ui.label("left pane");
                    }
                    Pane::Second => over(ui, "test", (lower_share, lower_open), "Plot", |ui, pane| {
                        ui.label(if pane == Pane::First { "upper pane" } else { "lower pane" });
                    }),
                });
            },
            layout,
        );
        harness.run();
        let bars: Vec<Rect> = harness.query_all_by_label_contains("Resize").map(|node| node.rect()).collect();
        assert_eq!(bars.len(), 2);
        let vertical = bars.iter().find(|bar| bar.height() > bar.width()).copied().unwrap();
        harness.drag_at(vertical.center());
        harness.run();
        harness.hover_at(vertical.center() + vec2(80.0, 0.0));
        harness.run();
        harness.drop_at(vertical.center() + vec2(80.0, 0.0));
        harness.run();
        let dragged = Layout::default().list_width + 80.0;
        assert!((harness.state().list_width - dragged).abs() < 2.0, "{}", harness.state().list_width);
        layout = *harness.state();
        assert!(layout.lower_open);
        harness.get_by_label_contains("Plot").click();
        harness.run();
        assert!(!harness.state().lower_open, "collapsed");
        assert!(harness.query_by_label("lower pane").is_none());
        assert!(harness.query_by_label("upper pane").is_some());
    }

    /// A screen reader names the dividers in the interface's language.
    #[test]
    fn the_dividers_are_named_in_the_interfaces_language() {
        let mut harness = Harness::builder().with_size(vec2(800.0, 500.0)).build_ui_state(
            |ui, width: &mut f32| {
                crate::ui::i18n::Language::Korean.put_in(ui.ctx());
                columns(ui, "test", width, 100.0, |ui, _| {
                    ui.label("pane");
                });
            },
            300.0,
        );
        harness.run();
        assert!(harness.query_by_label("창 크기 조절").is_some());
        assert!(harness.query_by_label_contains("Resize").is_none());
    }
}
