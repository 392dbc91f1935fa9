//! The servo family's packet-log entries: each frame as its message name and
//! its fields the way a person reads them (`servo 1 → 72°, 20 ms`).

use super::session::Traffic;
use crate::device::{Direction, LogEntry, hex};
use crate::protocol::servo::{
    ActionRecord, AngleUnit, ButtonEvent, CommandType, JoystickTableRecord, ListEntry, MacroRecord, Message, ServoMove,
    ServoParameter, ServoSwitches, TransmissionMode,
};

fn yes_no(ok: bool) -> &'static str {
    if ok { "ok" } else { "refused" }
}

fn moves(moves: &[ServoMove]) -> String {
    let parts: Vec<String> = moves
        .iter()
        .map(|m| format!("servo {} → {}°, {} ms", m.servo_id, m.degree, i32::from(m.interval_10ms) * 10))
        .collect();
    parts.join("; ")
}

fn list(entries: &[ListEntry]) -> String {
    let parts: Vec<String> = entries.iter().map(|entry| format!("{} {:?}", entry.id, entry.caption)).collect();
    format!("{} item(s): {}", entries.len(), parts.join(", "))
}

fn switches(s: &ServoSwitches) -> String {
    let servo = if s.servo_id == crate::protocol::servo::ALL_SERVOS {
        "all servos".to_string()
    } else {
        format!("servo {}", s.servo_id)
    };
    format!(
        "{servo}: {}, {}",
        if s.is_start { "running" } else { "stopped" },
        if s.is_hold { "holding" } else { "released" }
    )
}

fn unit(unit: AngleUnit) -> &'static str {
    match unit {
        AngleUnit::Degree => "degrees",
        AngleUnit::Adc => "ADC",
    }
}

fn action(record: &ActionRecord) -> String {
    format!("action {} {:?}: {}", record.action_id, record.caption, moves(&record.steps))
}

fn macro_record(record: &MacroRecord) -> String {
    let commands: Vec<String> = record
        .commands
        .iter()
        .map(|c| {
            let what = match c.command_type {
                CommandType::RunAction => format!("action {}", c.command_id),
                CommandType::Delay => format!("wait {} ms", c.command_id),
                CommandType::RunMacro => format!("macro {}", c.command_id),
            };
            format!("{what} at {} % × {}, total {} ms", c.ratio_percent, c.loop_count, c.total_interval_ms)
        })
        .collect();
    format!("macro {} {:?}: {}", record.macro_id, record.caption, commands.join("; "))
}

fn parameters(servos: &[ServoParameter]) -> String {
    let parts: Vec<String> =
        servos.iter().map(|p| format!("servo {} {:?} offset {}°", p.servo_id, p.caption, p.adjusted_degree)).collect();
    parts.join("; ")
}

fn table(record: &JoystickTableRecord) -> String {
    let buttons: Vec<String> = record
        .buttons
        .iter()
        .map(|b| {
            format!(
                "0x{:08x} {:?}: press {}, long {}, release {}{}",
                b.button_id,
                b.caption,
                b.press_macro,
                b.long_press_macro,
                b.up_macro,
                if b.uninterruptible { ", uninterruptible" } else { "" }
            )
        })
        .collect();
    format!("table {} {:?}: {}", record.table_id, record.caption, buttons.join("; "))
}

fn event(event: ButtonEvent) -> &'static str {
    match event {
        ButtonEvent::Press => "press",
        ButtonEvent::LongPress => "long press",
        ButtonEvent::Release => "release",
    }
}

/// A message's fields in words.
pub fn fields(message: &Message) -> String {
    use Message as M;
    match message {
        M::TransmissionModeSettingRequest { mode } | M::TransmissionModeSettingResponse { mode } => match mode {
            TransmissionMode::Old => "old protocol".into(),
            TransmissionMode::New => "new protocol".into(),
        },
        M::ClearAllDataRequest
        | M::QueryMemorySizeRequest
        | M::QueryRemainPowerRequest
        | M::QueryServoListRequest
        | M::QueryActionListRequest
        | M::QueryMacroListRequest
        | M::QueryServoParameterRequest
        | M::QueryProjectIdRequest
        | M::QueryJoystickTableListRequest
        | M::QueryActiveJoystickTableRequest => String::new(),
        M::ClearAllDataResponse { ok }
        | M::AddActionResponse { ok }
        | M::DeleteActionResponse { ok }
        | M::AddMacroResponse { ok }
        | M::DeleteMacroResponse { ok }
        | M::ExecuteMacroResponse { ok }
        | M::AddServoParameterResponse { ok }
        | M::WriteProjectIdResponse { ok }
        | M::AddJoystickTableResponse { ok }
        | M::DeleteJoystickTableResponse { ok }
        | M::SetActiveJoystickTableResponse { ok }
        | M::SubscribeButtonEventResponse { ok } => yes_no(*ok).into(),
        M::QueryMemorySizeResponse { free_bytes, total_bytes } => match total_bytes {
            Some(total) => format!("{free_bytes} of {total} bytes free"),
            None => format!("{free_bytes} bytes free"),
        },
        M::QueryRemainPowerResponse { permil } => format!("battery {}", super::battery_text(*permil)),
        M::SendDummyDataRequest { data } => format!("{} byte(s)", data.len()),
        M::QueryServoListResponse { servo_ids } => {
            let ids: Vec<String> = servo_ids.iter().map(ToString::to_string).collect();
            format!("servos {}", ids.join(", "))
        }
        M::QueryServoRequest { servo_id } if *servo_id == crate::protocol::servo::ALL_SERVOS => "all servos".into(),
        M::QueryServoRequest { servo_id } => format!("servo {servo_id}"),
        M::QueryServoResponse { servos } => {
            let parts: Vec<String> = servos.iter().map(|s| format!("servo {} at {}°", s.servo_id, s.angle)).collect();
            parts.join(", ")
        }
        M::SetServoParameterRequest(s) | M::SetServoParameterResponse(s) => switches(s),
        M::SetAngleUnitRequest { servo_id, unit: u } | M::SetAngleUnitResponse { servo_id, unit: u } => {
            format!("servo {servo_id} in {}", unit(*u))
        }
        M::ExecuteActionRequest { moves: m } => moves(m),
        M::ExecuteActionExRequest { action_id } | M::QueryActionRequest { action_id } => format!("action {action_id}"),
        M::DeleteActionRequest { action_id } => format!("action {action_id}"),
        M::QueryActionListResponse { actions: entries }
        | M::QueryMacroListResponse { macros: entries }
        | M::QueryJoystickTableListResponse { tables: entries } => list(entries),
        M::QueryActionResponse { action: Some(record) } | M::AddActionRequest(record) => action(record),
        M::QueryActionResponse { action: None }
        | M::QueryMacroResponse { macro_record: None }
        | M::QueryJoystickTableResponse { table: None } => "not found".into(),
        M::QueryMacroRequest { macro_id }
        | M::DeleteMacroRequest { macro_id }
        | M::ExecuteMacroRequest { macro_id } => {
            format!("macro {macro_id}")
        }
        M::QueryMacroResponse { macro_record: Some(record) } | M::AddMacroRequest(record) => macro_record(record),
        M::QueryServoParameterResponse { servos } | M::AddServoParameterRequest { servos } => parameters(servos),
        M::WriteProjectIdRequest { project_id } | M::QueryProjectIdResponse { project_id } => {
            format!("project {project_id}")
        }
        M::QueryJoystickTableRequest { table_id }
        | M::DeleteJoystickTableRequest { table_id }
        | M::SetActiveJoystickTableRequest { table_id }
        | M::QueryActiveJoystickTableResponse { table_id } => format!("table {table_id}"),
        M::QueryJoystickTableResponse { table: Some(record) } | M::AddJoystickTableRequest(record) => table(record),
        M::SubscribeButtonEventRequest { subscribe } => (if *subscribe { "on" } else { "off" }).into(),
        M::ButtonEventResponse { button_id, event: e } => format!("button 0x{button_id:08x} {}", event(*e)),
        M::Unknown { packet_id, content } => format!("id {packet_id}, {} byte(s)", content.len()),
    }
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

    #[test]
    fn fields_read_as_words_not_debug_syntax() {
        let message =
            Message::ExecuteActionRequest { moves: vec![ServoMove { servo_id: 1, degree: 72, interval_10ms: 2 }] };
        assert_eq!(fields(&message), "servo 1 → 72°, 20 ms");
        assert_eq!(fields(&Message::QueryRemainPowerResponse { permil: 815 }), "battery 81.5 %");
        assert_eq!(fields(&Message::AddActionResponse { ok: false }), "refused");
        let text = fields(&Message::ButtonEventResponse { button_id: 0x10, event: ButtonEvent::LongPress });
        assert_eq!(text, "button 0x00000010 long press");
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
