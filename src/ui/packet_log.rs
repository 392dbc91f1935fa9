//! The packet log: every frame sent and received, decoded (message name and
//! fields) with its hex, and every skipped-bytes report; filterable and
//! copyable. Rows are virtualised, so a long session stays fast.

use std::collections::VecDeque;

use crate::device::LogEntry;

/// Most entries kept (the oldest are dropped).
pub const MAX_ENTRIES: usize = 20_000;

fn matches(entry: &LogEntry, filter: &str) -> bool {
    filter.is_empty() || entry.line().to_lowercase().contains(filter)
}

/// The log's entries and the panel's filter. The entries that pass the filter
/// are kept as a list, brought up to date with the entries that arrived since
/// the last frame: a frame never re-reads the whole log.
#[derive(Debug, Default)]
pub struct PacketLog {
    entries: VecDeque<LogEntry>,
    /// Sequence number of `entries[0]` (entries dropped so far).
    first: usize,
    filter: String,
    /// Sequence numbers of the entries that pass `matched_filter`, in order.
    matched: VecDeque<usize>,
    /// The filter `matched` was made for (lower case).
    matched_filter: String,
    /// Entries before this sequence number have been matched.
    matched_up_to: usize,
}

impl PacketLog {
    /// Records one entry, whatever the family.
    pub fn record(&mut self, entry: LogEntry) {
        if self.entries.len() == MAX_ENTRIES {
            self.entries.pop_front();
            self.first += 1;
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

    /// Brings the list of matching entries up to date: new entries are
    /// matched, dropped ones forgotten; only a new filter reads them all.
    fn refresh(&mut self) {
        let filter = self.filter.to_lowercase();
        if filter != self.matched_filter {
            self.matched.clear();
            self.matched_filter = filter;
            self.matched_up_to = self.first;
        }
        while self.matched.front().is_some_and(|&sequence| sequence < self.first) {
            self.matched.pop_front();
        }
        let end = self.first + self.entries.len();
        for sequence in self.matched_up_to.max(self.first)..end {
            if matches(&self.entries[sequence - self.first], &self.matched_filter) {
                self.matched.push_back(sequence);
            }
        }
        self.matched_up_to = end;
    }

    fn matched_entry(&self, row: usize) -> &LogEntry {
        &self.entries[self.matched[row] - self.first]
    }

    /// The entries that pass the filter.
    pub fn visible(&mut self) -> Vec<&LogEntry> {
        self.refresh();
        (0..self.matched.len()).map(|row| self.matched_entry(row)).collect()
    }

    #[cfg(any(test, feature = "test-api"))]
    /// Sets the filter (case-insensitive substring of the line).
    pub fn set_filter(&mut self, filter: &str) {
        self.filter = filter.to_string();
    }

    /// Draws the log.
    pub fn ui(&mut self, ui: &mut egui::Ui, words: &crate::ui::i18n::Strings) {
        self.refresh();
        ui.horizontal(|ui| {
            ui.heading(words.packet_log);
            let label = ui.label(words.filter);
            ui.add(egui::TextEdit::singleline(&mut self.filter).hint_text(words.filter_hint).desired_width(240.0))
                .labelled_by(label.id);
            if ui.button(words.copy).on_hover_text(words.copy_hint).clicked() {
                let text: Vec<String> = (0..self.matched.len()).map(|row| self.matched_entry(row).line()).collect();
                ui.ctx().copy_text(text.join("\n"));
            }
            if ui.button(words.clear).clicked() {
                self.first += self.entries.len();
                self.entries.clear();
            }
        });
        // A filter typed this frame, or a clear, applies now.
        self.refresh();
        ui.label(format!("{} / {}", self.matched.len(), self.entries.len()));
        let row_height = crate::ui::rows::text_height(ui, &egui::TextStyle::Monospace);
        egui::ScrollArea::both().auto_shrink([false, false]).stick_to_bottom(true).show_rows(
            ui,
            row_height,
            self.matched.len(),
            |ui, rows| {
                for row in rows {
                    // One line per row, never wrapped: rows are virtualised by height.
                    let line = self.matched_entry(row).line();
                    let size = egui::vec2(ui.available_width(), row_height);
                    ui.allocate_ui_with_layout(size, egui::Layout::left_to_right(egui::Align::Center), |ui| {
                        ui.set_min_height(row_height);
                        ui.add(egui::Label::new(egui::RichText::new(line).monospace()).extend());
                    });
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

    #[test]
    fn the_filtered_list_follows_new_and_dropped_entries() {
        let mut log = PacketLog::default();
        log.set_filter("Odd");
        for index in 0..MAX_ENTRIES {
            log.record(entry(index as f64, if index % 2 == 1 { "odd" } else { "even" }));
        }
        assert_eq!(log.visible().len(), MAX_ENTRIES / 2);
        // 10 more entries push the 10 oldest (5 of them odd) out.
        for index in MAX_ENTRIES..MAX_ENTRIES + 10 {
            log.record(entry(index as f64, if index % 2 == 1 { "odd" } else { "even" }));
        }
        let visible = log.visible();
        assert_eq!(visible.len(), MAX_ENTRIES / 2);
        assert_eq!(visible.first().unwrap().seconds, 11.0);
        assert_eq!(visible.last().unwrap().seconds, (MAX_ENTRIES + 9) as f64);
        log.set_filter("");
        assert_eq!(log.visible().len(), MAX_ENTRIES);
    }
}
