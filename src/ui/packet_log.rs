//! The packet log: every frame sent and received, decoded (message name and
//! fields) with its hex, and every skipped-bytes report; filterable and
//! copyable. Rows are virtualised, so a long session stays fast.

use std::collections::VecDeque;

use crate::device::LogEntry;

/// Most entries kept (the oldest are dropped).
pub const MAX_ENTRIES: usize = 20_000;

fn matches(entry: &LogEntry, filter: &str) -> bool {
    filter.is_empty() || entry.line().to_lowercase().contains(&filter.to_lowercase())
}

/// The log's entries and the panel's filter.
#[derive(Debug, Default)]
pub struct PacketLog {
    entries: VecDeque<LogEntry>,
    filter: String,
}

impl PacketLog {
    /// Records one entry, whatever the family.
    pub fn record(&mut self, entry: LogEntry) {
        if self.entries.len() == MAX_ENTRIES {
            self.entries.pop_front();
        }
        self.entries.push_back(entry);
    }

    /// Number of entries kept.
    pub fn len(&self) -> usize {
        self.entries.len()
    }

    /// Whether the log is empty.
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// The entries that pass the filter.
    pub fn visible(&self) -> Vec<&LogEntry> {
        self.entries.iter().filter(|entry| matches(entry, &self.filter)).collect()
    }

    /// Sets the filter (case-insensitive substring of the line).
    pub fn set_filter(&mut self, filter: &str) {
        self.filter = filter.to_string();
    }

    /// Draws the log.
    pub fn ui(&mut self, ui: &mut egui::Ui, words: &crate::ui::i18n::Strings) {
        ui.horizontal(|ui| {
            ui.heading(words.packet_log);
            let label = ui.label(words.filter);
            ui.add(egui::TextEdit::singleline(&mut self.filter).hint_text(words.filter_hint).desired_width(240.0))
                .labelled_by(label.id);
            if ui.button(words.copy).on_hover_text(words.copy_hint).clicked() {
                let text: Vec<String> = self.visible().iter().map(|entry| entry.line()).collect();
                ui.ctx().copy_text(text.join("\n"));
            }
            if ui.button(words.clear).clicked() {
                self.entries.clear();
            }
            ui.label(format!("{} / {}", self.visible().len(), self.entries.len()));
        });
        let visible = self.visible();
        let row_height = ui.text_style_height(&egui::TextStyle::Monospace) + 2.0;
        egui::ScrollArea::both().auto_shrink([false, false]).stick_to_bottom(true).show_rows(
            ui,
            row_height,
            visible.len(),
            |ui, rows| {
                for entry in &visible[rows] {
                    // One line per row, never wrapped: rows are virtualised by height.
                    ui.add(egui::Label::new(egui::RichText::new(entry.line()).monospace()).extend());
                }
            },
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::device::Direction;

    fn entry(seconds: f64, name: &str) -> LogEntry {
        LogEntry { seconds, direction: Direction::Sent, name: name.into(), fields: String::new(), hex: "13 4c".into() }
    }

    #[test]
    fn entries_are_filtered_by_any_part_of_their_line() {
        let mut log = PacketLog::default();
        log.record(entry(0.5, "QueryActionListRequest"));
        log.record(entry(0.6, "AddActionResponse"));
        log.set_filter("addaction");
        assert_eq!(log.visible().len(), 1);
        log.set_filter("13 4C");
        assert_eq!(log.visible().len(), 2);
    }

    #[test]
    fn the_log_is_bounded() {
        let mut log = PacketLog::default();
        for index in 0..MAX_ENTRIES + 10 {
            log.record(entry(index as f64, "QueryProjectIDRequest"));
        }
        assert_eq!(log.len(), MAX_ENTRIES);
    }
}
