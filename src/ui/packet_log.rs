//! The packet log: every frame sent and received, decoded (message name and
//! fields) with its hex, and every skipped-bytes report; filterable and
//! copyable. Rows are virtualised, so a long session stays fast.

use std::collections::VecDeque;

use crate::device::board::Traffic;
use crate::protocol::board::{DecoderEvent, Frame};

/// Most entries kept (the oldest are dropped).
pub const MAX_ENTRIES: usize = 20_000;

/// One line of the log.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LogEntry {
    /// Seconds since the link opened, as text.
    pub time: String,
    /// `→` sent, `←` received, `!` skipped.
    pub direction: &'static str,
    /// Message name, or the skip reason.
    pub name: String,
    /// Decoded fields.
    pub fields: String,
    /// The frame's bytes in hex.
    pub hex: String,
}

impl LogEntry {
    /// The entry as one line of text (for copying).
    pub fn line(&self) -> String {
        format!("{} {} {} {} [{}]", self.time, self.direction, self.name, self.fields, self.hex)
    }

    fn matches(&self, filter: &str) -> bool {
        filter.is_empty() || self.line().to_lowercase().contains(&filter.to_lowercase())
    }
}

/// A message's fields: its `Debug` text without the variant name.
fn fields_of(message: &crate::protocol::board::Message) -> String {
    let text = format!("{message:?}");
    match text.find(['{', '(']) {
        Some(start) => text[start..].to_string(),
        None => String::new(),
    }
}

fn hex_of(frame: &Frame) -> String {
    let bytes = frame.to_bytes().unwrap_or_default();
    bytes.iter().map(|byte| format!("{byte:02x}")).collect::<Vec<_>>().join(" ")
}

/// The log's entries and the panel's filter.
#[derive(Debug, Default)]
pub struct PacketLog {
    entries: VecDeque<LogEntry>,
    filter: String,
}

impl PacketLog {
    /// Records one traffic event, `seconds` after the link opened.
    pub fn record(&mut self, seconds: f64, traffic: &Traffic) {
        let time = format!("{seconds:9.3}");
        let entry = match traffic {
            Traffic::Sent { frame, message } => LogEntry {
                time,
                direction: "→",
                name: message.name().to_string(),
                fields: fields_of(message),
                hex: hex_of(frame),
            },
            Traffic::Received { frame, message } => match message {
                Ok(message) => LogEntry {
                    time,
                    direction: "←",
                    name: message.name().to_string(),
                    fields: fields_of(message),
                    hex: hex_of(frame),
                },
                Err(error) => LogEntry {
                    time,
                    direction: "←",
                    name: format!("malformed {}", frame.packet_id),
                    fields: error.to_string(),
                    hex: hex_of(frame),
                },
            },
            Traffic::Skipped { bytes, reason } => LogEntry {
                time,
                direction: "!",
                name: format!("skipped {bytes} byte(s)"),
                fields: format!("{reason:?}"),
                hex: String::new(),
            },
        };
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
        self.entries.iter().filter(|entry| entry.matches(&self.filter)).collect()
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

/// Turns decoder events into log entries (used by tests and tools that decode captures).
pub fn traffic_of(event: DecoderEvent) -> Traffic {
    match event {
        DecoderEvent::Frame(frame) => {
            let message = crate::protocol::board::Message::from_frame(&frame);
            Traffic::Received { frame, message }
        }
        DecoderEvent::Skipped { bytes, reason } => Traffic::Skipped { bytes, reason },
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::protocol::board::{FrameDecoder, Message};

    #[test]
    fn frames_and_skips_are_logged_decoded_with_hex_and_filterable() {
        let mut log = PacketLog::default();
        let sent = Message::QueryActionListRequest;
        log.record(0.5, &Traffic::Sent { frame: sent.to_frame().unwrap(), message: sent });
        let mut decoder = FrameDecoder::new();
        decoder.push(&[0xaa, 0xbb]);
        decoder.push(&Message::AddActionResponse { ok: true }.encode().unwrap());
        while let Some(event) = decoder.poll() {
            log.record(0.6, &traffic_of(event));
        }
        let lines: Vec<String> = log.visible().iter().map(|entry| entry.line()).collect();
        assert_eq!(lines.len(), 3);
        assert!(
            lines[0].contains("→ QueryActionListRequest") && lines[0].contains("[13 4c 05 1d 3a 75 00 00 30]"),
            "{}",
            lines[0]
        );
        assert!(lines[1].contains("! skipped 2 byte(s) Garbage"), "{}", lines[1]);
        assert!(lines[2].contains("← AddActionResponse { ok: true } [13 4c 05 1d 4f 75 01 00 01 47]"), "{}", lines[2]);
        log.set_filter("addaction");
        assert_eq!(log.visible().len(), 1);
        log.set_filter("4f 75");
        assert_eq!(log.visible().len(), 1);
    }

    #[test]
    fn the_log_is_bounded() {
        let mut log = PacketLog::default();
        let message = Message::QueryProjectIdRequest;
        for index in 0..MAX_ENTRIES + 10 {
            log.record(index as f64, &Traffic::Sent { frame: message.to_frame().unwrap(), message: message.clone() });
        }
        assert_eq!(log.len(), MAX_ENTRIES);
    }
}
