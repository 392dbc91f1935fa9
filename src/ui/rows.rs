//! Lists that lay out only the rows in view, so that a panel costs the same
//! per frame with 5 items or 5,000: every list and table of the editor goes
//! through here, and each fills the height it is given — a bigger window
//! shows more rows, a bigger project costs nothing more.

/// Rows a drop-down shows at once (it floats over the panel).
pub const CHOICE_ROWS: usize = 12;

/// Height of one line of text in `style` as laid out: with the CJK fallback
/// font, whose line is taller than the Latin font's (a caption in Chinese
/// makes its row that tall).
pub fn text_height(ui: &egui::Ui, style: &egui::TextStyle) -> f32 {
    let font = style.resolve(ui.style());
    let galley = ui.painter().layout_no_wrap("Ag國".to_owned(), font, egui::Color32::WHITE);
    galley.size().y.max(ui.text_style_height(style))
}

/// Height of one row of interactive widgets (buttons, drag values, combo boxes).
pub fn widget_row_height(ui: &egui::Ui) -> f32 {
    ui.spacing().interact_size.y.max(text_height(ui, &egui::TextStyle::Button) + 2.0 * ui.spacing().button_padding.y)
}

/// Height of `rows` rows of `row_height` (with the spacing between them).
pub fn rows_height(ui: &egui::Ui, row_height: f32, rows: usize) -> f32 {
    #[allow(clippy::cast_precision_loss)]
    let rows = rows as f32;
    rows * (row_height + ui.spacing().item_spacing.y)
}

/// Height of a table of `rows` rows of widgets.
pub fn table_height(ui: &egui::Ui, rows: usize) -> f32 {
    rows_height(ui, widget_row_height(ui), rows)
}

/// Height of one line of a list of names.
pub fn name_row_height(ui: &egui::Ui) -> f32 {
    text_height(ui, &egui::TextStyle::Body) + 2.0 * ui.spacing().button_padding.y
}

/// Height of a list of names of `rows` rows.
pub fn list_height(ui: &egui::Ui, rows: usize) -> f32 {
    rows_height(ui, name_row_height(ui), rows)
}

/// A vertical list of `count` rows, each `row_height` tall, at most
/// `max_height` high; `add_row` is called for the rows in view only.
pub fn list(
    ui: &mut egui::Ui,
    id_salt: &str,
    row_height: f32,
    count: usize,
    max_height: f32,
    mut add_row: impl FnMut(&mut egui::Ui, usize),
) {
    scrolled(ui, id_salt, row_height, count, max_height, None, |ui, rows| {
        for index in rows {
            // Every row exactly as tall as declared (a Latin caption's line is
            // shorter than a Chinese one's), so the rows in view are the rows laid out.
            let size = egui::vec2(ui.available_width(), row_height);
            ui.allocate_ui_with_layout(size, egui::Layout::left_to_right(egui::Align::Center), |ui| {
                ui.set_min_height(row_height);
                add_row(ui, index);
            });
        }
    });
}

/// A list of names (one selectable line each) filling the height left.
pub fn names(ui: &mut egui::Ui, id_salt: &str, count: usize, add_row: impl FnMut(&mut egui::Ui, usize)) {
    let row_height = name_row_height(ui);
    let height = ui.available_height();
    list(ui, id_salt, row_height, count, height, add_row);
}

/// What a row's ↑ ↓ × buttons asked for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Reorder {
    /// Swap with the row above.
    Up,
    /// Swap with the row below.
    Down,
    /// Remove the row.
    Remove,
}

impl Reorder {
    /// Applies the change to the row at `position` of `items`.
    pub fn apply<T>(self, items: &mut Vec<T>, position: usize) {
        match self {
            Self::Up if position > 0 => items.swap(position, position - 1),
            Self::Down if position + 1 < items.len() => items.swap(position, position + 1),
            Self::Remove if position < items.len() => {
                items.remove(position);
            }
            _ => {}
        }
    }
}

/// The ↑ ↓ × buttons of the row at `position` of `count` (↑ off on the first
/// row, ↓ on the last).
pub fn reorder_buttons(ui: &mut egui::Ui, position: usize, count: usize, remove_hint: &str) -> Option<Reorder> {
    let mut asked = None;
    if ui.add_enabled(position > 0, egui::Button::new("↑").small()).clicked() {
        asked = Some(Reorder::Up);
    }
    if ui.add_enabled(position + 1 < count, egui::Button::new("↓").small()).clicked() {
        asked = Some(Reorder::Down);
    }
    if ui.small_button("×").on_hover_text(remove_hint).clicked() {
        asked = Some(Reorder::Remove);
    }
    asked
}

/// A striped grid of `count` rows with no heading, at most `max_height`
/// high; `add_row` fills the cells of the rows in view only (the grid ends
/// each row). Column widths are remembered from frame to frame.
pub fn grid(
    ui: &mut egui::Ui,
    id_salt: &str,
    count: usize,
    max_height: f32,
    mut add_row: impl FnMut(&mut egui::Ui, usize),
) {
    let row_height = widget_row_height(ui);
    scrolled(ui, id_salt, row_height, count, max_height, None, |ui, rows| {
        // Cells closer together than loose widgets: a row's buttons read as one row.
        ui.spacing_mut().item_spacing.x = 3.0;
        // Columns as narrow as their widgets (↑ ↓ × need no interact-sized cell):
        // a row of a dozen buttons fits a pane at 1280×800.
        egui::Grid::new(id_salt).striped(true).min_row_height(row_height).min_col_width(0.0).show(ui, |ui| {
            for index in rows {
                add_row(ui, index);
                ui.end_row();
            }
        });
    });
}

/// A vertical scroll area of `count` rows of `row_height`, at most
/// `max_height` high (scrolled to `scroll_to_row` if given), that hands
/// `add_rows` the range of rows in view.
fn scrolled(
    ui: &mut egui::Ui,
    id_salt: &str,
    row_height: f32,
    count: usize,
    max_height: f32,
    scroll_to_row: Option<usize>,
    add_rows: impl FnOnce(&mut egui::Ui, std::ops::Range<usize>),
) {
    ui.scope(|ui| {
        solid_scroll_bar(ui);
        let mut area = egui::ScrollArea::vertical().id_salt(id_salt).max_height(max_height).auto_shrink([false, true]);
        if let Some(row) = scroll_to_row {
            // The row a little below the top, with the ones before it in sight.
            let above = row.saturating_sub(2);
            area = area.vertical_scroll_offset(rows_height(ui, row_height, above));
        }
        area.show_rows(ui, row_height, count, add_rows);
    });
}

/// A striped table of `count` rows under a heading row that stays in place,
/// at most `max_height` high (the heading included); `add_row` fills the cells
/// of the rows in view only, one `row.col(…)` per column.
pub fn table(
    ui: &mut egui::Ui,
    id_salt: &str,
    heading: &[&str],
    count: usize,
    max_height: f32,
    add_row: impl FnMut(&mut egui_extras::TableRow<'_, '_>, usize),
) {
    table_with_id(ui, id_salt, heading, f32::INFINITY, count, max_height, add_row);
}

/// A [`table`] whose first column (a row's name: it labels the row's
/// fields) is at most `first_width` wide, its text cut to it.
pub fn table_with_id(
    ui: &mut egui::Ui,
    id_salt: &str,
    heading: &[&str],
    first_width: f32,
    count: usize,
    max_height: f32,
    mut add_row: impl FnMut(&mut egui_extras::TableRow<'_, '_>, usize),
) {
    let row_height = widget_row_height(ui) + 2.0;
    ui.scope(|ui| {
        solid_scroll_bar(ui);
        egui_extras::TableBuilder::new(ui)
            .id_salt(id_salt)
            .striped(true)
            .column(egui_extras::Column::auto().at_most(first_width).clip(true))
            .columns(egui_extras::Column::auto(), heading.len().saturating_sub(1))
            .cell_layout(egui::Layout::left_to_right(egui::Align::Center))
            .min_scrolled_height(0.0)
            .max_scroll_height(max_height - row_height)
            .auto_shrink([false, true])
            .header(row_height, |mut header| {
                for text in heading {
                    header.col(|ui| {
                        ui.strong(*text);
                    });
                }
            })
            .body(|body| {
                body.rows(row_height, count, |mut row| {
                    let index = row.index();
                    add_row(&mut row, index);
                });
            });
    });
}

/// A combo box whose drop-down lays out only the choices in view (a project
/// may offer 500 actions to pick from). `choice(i)` is the i-th value and its
/// text; picking one sets `current`.
pub fn combo<V: PartialEq>(
    ui: &mut egui::Ui,
    id_salt: impl egui::AsIdSalt,
    selected_text: String,
    current: &mut V,
    count: usize,
    choice: impl Fn(usize) -> (V, String),
) -> egui::Response {
    let row_height = name_row_height(ui);
    let height = list_height(ui, CHOICE_ROWS);
    egui::ComboBox::from_id_salt(id_salt)
        .selected_text(selected_text)
        .height(height + row_height)
        .show_ui(ui, |ui| {
            // Just opened (not drawn the frame before): show the current choice.
            let shown_at = ui.scope_id().with("shown at");
            let pass = ui.ctx().cumulative_pass_nr();
            let opened = ui.data(|data| data.get_temp::<u64>(shown_at)).is_none_or(|last| last + 1 < pass);
            ui.data_mut(|data| data.insert_temp(shown_at, pass));
            let scroll_to = opened.then(|| (0..count).find(|&index| choice(index).0 == *current)).flatten();
            scrolled(ui, "choices", row_height, count, height, scroll_to, |ui, rows| {
                for index in rows {
                    let (value, text) = choice(index);
                    ui.selectable_value(current, value, text);
                }
            });
        })
        .response
}

/// A scroll bar that is always drawn when a list is longer than its height
/// (egui's default floats and shows only on hover): the user sees at once
/// that there is more.
fn solid_scroll_bar(ui: &mut egui::Ui) {
    ui.spacing_mut().scroll = egui::style::ScrollStyle::solid();
}

/// A move's curve picker: `names` in `Easing::ALL` order then a shaped
/// curve's (shaped on the graph; picking a preset replaces it), `hint` on hover.
pub fn curve(
    ui: &mut egui::Ui,
    id_salt: impl egui::AsIdSalt,
    easing: &mut crate::project::Easing,
    names: [&str; 6],
    hint: &str,
) -> egui::Response {
    use crate::project::Easing;
    let shown = Easing::ALL.iter().position(|curve| curve == easing).map_or(names[5], |at| names[at]);
    egui::ComboBox::from_id_salt(id_salt)
        .selected_text(shown)
        .width(96.0)
        .show_ui(ui, |ui| {
            for (curve, name) in Easing::ALL.into_iter().zip(names) {
                ui.selectable_value(easing, curve, name);
            }
        })
        .response
        .on_hover_text(hint)
}

/// Whether the row selected (a joint, a servo) changed since the last frame
/// this was asked under `key`: a row selected from elsewhere (the 3D view)
/// then has its slider take the keyboard focus, so the arrow keys nudge it.
pub fn selection_changed<T>(ui: &egui::Ui, key: &str, selected: Option<&T>) -> bool
where
    T: Clone + PartialEq + Send + Sync + 'static,
{
    let id = ui.scope_id().with(key);
    let before: Option<Option<T>> = ui.data(|data| data.get_temp(id));
    ui.data_mut(|data| data.insert_temp(id, selected.cloned()));
    before.is_some_and(|before| before.as_ref() != selected)
}

/// The nudge asked for by keys pressed on a focused slider, in steps (←/→/↑/↓
/// 1, with Shift or PageUp/PageDown 10), consumed so that the slider does not
/// also move by its own step.
pub fn keyboard_nudge(ui: &egui::Ui) -> i32 {
    ui.input_mut(|input| {
        let mut delta = 0i32;
        for (key, step) in [
            (egui::Key::ArrowRight, 1),
            (egui::Key::ArrowUp, 1),
            (egui::Key::ArrowLeft, -1),
            (egui::Key::ArrowDown, -1),
        ] {
            // Shift first: a plain match would also take Shift+key (shift is ignored logically).
            delta += 10 * step * i32::try_from(input.count_and_consume_key(egui::Modifiers::SHIFT, key)).unwrap_or(0);
            delta += step * i32::try_from(input.count_and_consume_key(egui::Modifiers::NONE, key)).unwrap_or(0);
        }
        delta += 10 * i32::try_from(input.count_and_consume_key(egui::Modifiers::NONE, egui::Key::PageUp)).unwrap_or(0);
        delta -=
            10 * i32::try_from(input.count_and_consume_key(egui::Modifiers::NONE, egui::Key::PageDown)).unwrap_or(0);
        delta
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reordering_moves_or_removes_the_row_and_ignores_what_cannot_be_done() {
        let cases: [(Reorder, usize, [char; 3], &str); 6] = [
            (Reorder::Up, 1, ['a', 'b', 'c'], "bac"),
            (Reorder::Up, 0, ['a', 'b', 'c'], "abc"),
            (Reorder::Down, 1, ['a', 'b', 'c'], "acb"),
            (Reorder::Down, 2, ['a', 'b', 'c'], "abc"),
            (Reorder::Remove, 2, ['a', 'b', 'c'], "ab"),
            (Reorder::Remove, 3, ['a', 'b', 'c'], "abc"),
        ];
        for (asked, position, items, expected) in cases {
            let mut items = items.to_vec();
            asked.apply(&mut items, position);
            assert_eq!(items.iter().collect::<String>(), expected, "{asked:?} at {position}");
        }
    }
}

/// How a span is to be retimed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Retime {
    /// Each time is multiplied by this.
    pub factor: f64,
    /// Dragged on the total: part of one gesture (one undo step).
    pub dragging: bool,
}

/// How near a sound's onset a dragged total must come to snap to it, ms.
pub const SNAP_MS: f64 = 30.0;

/// A span's times scaled: "Retime ×0.5 ×2 total [ms]", the span lasting
/// `total_ms` now; the total can be typed or dragged. A dragged total that
/// comes within [`SNAP_MS`] of one of `onsets_ms` (the sound's onsets, from
/// the span's start) snaps to it, so the span ends on the beat.
pub fn retime(ui: &mut egui::Ui, words: &crate::ui::i18n::Strings, total_ms: f64, onsets_ms: &[f64]) -> Option<Retime> {
    let mut asked = None;
    ui.label(words.retime);
    if ui.small_button("×0.5").clicked() {
        asked = Some(Retime { factor: 0.5, dragging: false });
    }
    if ui.small_button("×2").clicked() {
        asked = Some(Retime { factor: 2.0, dragging: false });
    }
    let label = ui.label(words.to_total);
    let mut total = total_ms.round();
    let drag = egui::DragValue::new(&mut total).range(10.0..=3_600_000.0).speed(10.0).suffix(" ms");
    let response = ui.add(drag).labelled_by(label.id);
    if response.dragged() {
        total = crate::authoring::retime::snap(total, 0.0, onsets_ms, SNAP_MS).max(10.0);
    }
    if response.changed() && (total - total_ms.round()).abs() >= 1.0 {
        let factor = crate::authoring::retime::factor_to_total(total_ms, total);
        asked = Some(Retime { factor, dragging: response.dragged() });
    }
    asked
}

/// "● Record", or while recording "■ Stop recording" and where it is (the
/// count-in, then the seconds recorded). Some(true): start; Some(false): stop.
pub fn record(
    ui: &mut egui::Ui,
    words: &crate::ui::i18n::Strings,
    phase: Option<crate::authoring::recording::Phase>,
    hint: &str,
) -> Option<bool> {
    use crate::authoring::recording::Phase;
    let Some(phase) = phase else {
        return ui.button(words.record).on_hover_text(hint).clicked().then_some(true);
    };
    let stop = ui.button(words.stop_recording).clicked();
    let (text, color) = match phase {
        Phase::CountIn(left) => (format!("{} {:.0}…", words.count_in, left.ceil()), ui.visuals().warn_fg_color),
        Phase::Recording(for_s) => (format!("● {} {for_s:.1} s", words.recording), ui.visuals().error_fg_color),
    };
    ui.colored_label(color, text);
    stop.then_some(false)
}
