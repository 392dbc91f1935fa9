//! The servo family's packet-log entries: each frame as its message name and
//! its fields the way a person reads them (`servo 1 → 72°, 20 ms`).

use super::session::Traffic;
use crate::device::{Direction, LogEntry, hex};
use crate::protocol::servo::Message;

/// A message's fields in words (the protocol's message table says how).
pub fn fields(message: &Message) -> String {
    message.fields_in_words()
}

/// The log entry for one traffic event, `seconds` after the link opened.
pub fn log_entry(seconds: f64, traffic: &Traffic) -> LogEntry {
    let frame_hex = |frame: &crate::protocol::servo::Frame| hex(&frame.to_bytes().unwrap_or_default());
    match traffic {
        Traffic::Sent { frame, message } => LogEntry {
            seconds,
            direction: Direction::Sent,
            name: message.name().to_string(),
            fields: fields(message),
            hex: frame_hex(frame),
        },
        Traffic::Received { frame, message: Ok(message) } => LogEntry {
            seconds,
            direction: Direction::Received,
            name: message.name().to_string(),
            fields: fields(message),
            hex: frame_hex(frame),
        },
        Traffic::Received { frame, message: Err(error) } => LogEntry {
            seconds,
            direction: Direction::Received,
            name: format!("malformed {}", frame.packet_id),
            fields: error.to_string(),
            hex: frame_hex(frame),
        },
        Traffic::Skipped { bytes, reason } => LogEntry {
            seconds,
            direction: Direction::Skipped,
            name: format!("skipped {bytes} byte(s)"),
            fields: reason.to_string(),
            hex: String::new(),
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::protocol::servo::{AngleUnit, ButtonEvent, ServoMove};

    #[test]
    fn fields_read_as_words_not_debug_syntax() {
        let message =
            Message::ExecuteActionRequest { moves: vec![ServoMove { servo_id: 1, degree: 72, interval_10ms: 2 }] };
        assert_eq!(fields(&message), "servo 1 → 72°, 20 ms");
        assert_eq!(fields(&Message::QueryRemainPowerResponse { permil: 815 }), "battery 81.5 %");
        assert_eq!(fields(&Message::AddActionResponse { ok: false }), "refused");
        let text = fields(&Message::ButtonEventResponse { button_id: 0x10, event: ButtonEvent::LongPress });
        assert_eq!(text, "button 0x00000010, long press");
        let memory = Message::QueryMemorySizeResponse { free_bytes: 100, total_bytes: Some(4096) };
        assert_eq!(fields(&memory), "100 bytes free, 4096 bytes in all");
        let unit = Message::SetAngleUnitRequest { servo_id: 0xFF, unit: AngleUnit::Degree };
        assert_eq!(fields(&unit), "all servos, angles in degrees");
        assert_eq!(fields(&Message::QueryActionResponse { action: None }), "not found");
    }

    #[test]
    fn decoded_frames_and_skips_become_log_entries_with_their_bytes() {
        use crate::protocol::servo::{DecoderEvent, FrameDecoder};
        let sent = Message::QueryActionListRequest;
        let entry = log_entry(0.5, &Traffic::Sent { frame: sent.to_frame().unwrap(), message: sent });
        assert_eq!(entry.line(), "    0.500 → QueryActionListRequest  [13 4c 05 1d 3a 75 00 00 30]");
        let mut decoder = FrameDecoder::new();
        decoder.push(&[0xaa, 0xbb]);
        decoder.push(&Message::AddActionResponse { ok: true }.encode().unwrap());
        let mut lines = Vec::new();
        while let Some(event) = decoder.poll() {
            let traffic = match event {
                DecoderEvent::Frame(frame) => Traffic::Received { message: Message::from_frame(&frame), frame },
                DecoderEvent::Skipped { bytes, reason } => Traffic::Skipped { bytes, reason },
            };
            lines.push(log_entry(0.6, &traffic).line());
        }
        assert_eq!(
            lines,
            [
                "    0.600 ! skipped 2 byte(s) not a frame []",
                "    0.600 ← AddActionResponse ok [13 4c 05 1d 4f 75 01 00 01 47]"
            ]
        );
    }
}
