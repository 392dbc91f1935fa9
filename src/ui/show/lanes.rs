//! The show window's timeline: the sound's lane and a lane per device, each
//! cue a block named as its row names it, the seconds under them and the
//! scrub's line; and each cue said as a line of text too.

use crate::show::Show;
use crate::show::timeline::{Block, Timeline};

use super::ShowWords;
use super::cues::cue_caption;

/// The timeline: the sound's lane, then a lane per device with its cues, on
/// one time axis, and the scrub's time as a line; where a click or a drag on
/// it puts the scrub (ms), and the span it shows (ms). What it draws costs
/// what fits its width, not the show's length: cues closer together than a
/// pixel are drawn as one block (said with how many), the seconds labelled
/// as far apart as they can be read.
pub(super) fn lanes(
    ui: &mut egui::Ui,
    (show, timeline): (&Show, &mut Timeline),
    scrub_ms: u64,
    words: &ShowWords,
) -> (Option<u64>, u64) {
    const LANE: f32 = 26.0;
    const NAMES: f32 = 130.0;
    let (count, span) = {
        let (blocks, span) = timeline.blocks(show);
        (blocks.len(), span)
    };
    let rows = u16::try_from(show.devices.len() + 1).unwrap_or(u16::MAX);
    let (rect, response) = ui.allocate_exact_size(
        egui::vec2(ui.available_width(), LANE * f32::from(rows) + 18.0),
        egui::Sense::click_and_drag(),
    );
    response.widget_info(|| egui::WidgetInfo::labeled(egui::Role::Canvas, true, words.timeline));
    let painter = ui.painter_at(rect);
    let visuals = ui.visuals();
    let width = (rect.width() - NAMES).max(1.0);
    // Spans of a show: far below f32's exact integers.
    #[allow(clippy::cast_precision_loss)]
    let x = |ms: u64| rect.left() + NAMES + width * (ms as f32 / span as f32);
    let font = egui::FontId::proportional(13.0);
    let top = |row: u16| rect.top() + LANE * f32::from(row);
    let caption_of = |block: &Block| {
        let cue = &show.cues[block.cue];
        cue_caption(&cue.start, show.devices.get(block.device), words)
    };
    // One lane: its name, and its cues as blocks, those within a pixel of each other as one.
    let lane = |row: u16,
                name: &str,
                spans: &mut dyn Iterator<Item = (u64, u64, Option<&Block>)>,
                fill: egui::Color32| {
        painter.text(
            egui::pos2(rect.left(), top(row) + LANE / 2.0),
            egui::Align2::LEFT_CENTER,
            name,
            font.clone(),
            visuals.text_color(),
        );
        painter.hline(rect.left() + NAMES..=rect.right(), top(row), visuals.widgets.noninteractive.bg_stroke);
        let draw = |(left, right, count, only): Run<'_>| {
            let block =
                egui::Rect::from_min_max(egui::pos2(left, top(row) + 4.0), egui::pos2(right, top(row) + LANE - 4.0));
            painter.rect_filled(block, 3.0, fill);
            let caption = match only {
                Some(cue) if count == 1 => caption_of(cue),
                Some(_) => crate::say!(words.lang, "show.cues_together", count),
                None => String::new(),
            };
            if !caption.is_empty() && block.width() >= 24.0 {
                painter.with_clip_rect(block.intersect(rect)).text(
                    block.left_center() + egui::vec2(4.0, 0.0),
                    egui::Align2::LEFT_CENTER,
                    caption,
                    font.clone(),
                    visuals.strong_text_color(),
                );
            }
        };
        runs(spans, &x).into_iter().for_each(draw);
    };
    let mut sound = show.sound.iter().map(|s| (s.offset_ms.max(0).unsigned_abs(), s.duration_ms, None));
    lane(0, words.sound, &mut sound, visuals.selection.bg_fill.gamma_multiply(0.5));
    for (row, device) in show.devices.iter().enumerate() {
        let mut spans = timeline.lane(row).iter().map(|block| (block.at_ms, block.length_ms, Some(block)));
        lane(u16::try_from(row + 1).unwrap_or(u16::MAX), &device.name, &mut spans, visuals.selection.bg_fill);
    }
    seconds(&painter, (span, width), &x, (top(rows) + 12.0, visuals.weak_text_color()));
    painter.vline(x(scrub_ms.min(span)), rect.top()..=top(rows), egui::Stroke::new(2.0, visuals.warn_fg_color));
    let scrubbed = scrubbed_to(&response, rect.left() + NAMES, width, span);
    said_cues(ui, (show, timeline), count, words);
    (scrubbed, span)
}

/// Where a click or a drag on the lanes puts the scrub, ms: the pointer's
/// share of the `width` px from `left` across the `span`.
fn scrubbed_to(response: &egui::Response, left: f32, width: f32, span: u64) -> Option<u64> {
    let pos = response.interact_pointer_pos().filter(|_| response.clicked() || response.dragged())?;
    // A fraction of the span: whole ms of a show.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss, clippy::cast_precision_loss)]
    let ms = (((pos.x - left) / width).clamp(0.0, 1.0) * span as f32).round() as u64;
    Some(ms)
}

/// A run of blocks closer than a pixel drawn as one: its left and right,
/// how many, and the first.
type Run<'b> = (f32, f32, usize, Option<&'b Block>);

/// `spans` (start and length, ms) where `x` puts them, those within a pixel
/// of each other joined into one run.
fn runs<'b>(spans: &mut dyn Iterator<Item = (u64, u64, Option<&'b Block>)>, x: &dyn Fn(u64) -> f32) -> Vec<Run<'b>> {
    let mut runs: Vec<Run<'b>> = Vec::new();
    for (at, length, cue) in spans {
        let (left, right) = (x(at), x(at + length).max(x(at) + 6.0));
        match runs.last_mut() {
            Some((_, to, count, _)) if left <= *to + 1.0 => {
                *to = to.max(right);
                *count += 1;
            }
            _ => runs.push((left, right, 1, cue)),
        }
    }
    runs
}

/// The seconds under the lanes at height `y`, labelled every 1, 2, 5, 10 … s:
/// as often as labels 70 px apart allow over `width` px for `span` ms.
fn seconds(
    painter: &egui::Painter,
    (span, width): (u64, f32),
    x: &dyn Fn(u64) -> f32,
    (y, color): (f32, egui::Color32),
) {
    #[allow(clippy::cast_precision_loss)]
    let px_per_s = width / (span as f32 / 1000.0);
    let every_s = [1, 2, 5, 10, 15, 30, 60, 120, 300, 600, 900, 1800, 3600]
        .into_iter()
        .find(|&step| step as f32 * px_per_s >= 70.0)
        .unwrap_or(3600);
    for second in (0..=span / 1000).step_by(every_s) {
        let label = if span >= 60_000 { format!("{}:{:02}", second / 60, second % 60) } else { format!("{second} s") };
        painter.text(
            egui::pos2(x(second * 1000), y),
            egui::Align2::CENTER_CENTER,
            label,
            egui::FontId::proportional(13.0),
            color,
        );
    }
}

/// Each cue said as text too, as its row names it, with when it starts and
/// ends (screen readers, tests): a list that scrolls, only the lines in view laid out.
fn said_cues(ui: &mut egui::Ui, (show, timeline): (&Show, &mut Timeline), count: usize, words: &ShowWords) {
    let line_height = ui.text_style_height(&egui::TextStyle::Body);
    egui::ScrollArea::vertical().id_salt("show-cue-lines").max_height(line_height * 6.0 + 12.0).show_rows(
        ui,
        line_height,
        count,
        |ui, range| {
            let (blocks, _) = timeline.blocks(show);
            for block in &blocks[range] {
                let cue = &show.cues[block.cue];
                let device = show.devices.get(block.device);
                // Whole ms of a show: exact in f64.
                #[allow(clippy::cast_precision_loss)]
                let said = format!(
                    "{} {} {:.2}–{:.2} s",
                    device.map_or("?", |device| device.name.as_str()),
                    cue_caption(&cue.start, device, words),
                    block.at_ms as f64 / 1000.0,
                    (block.at_ms + block.length_ms) as f64 / 1000.0
                );
                ui.weak(said);
            }
        },
    );
}
