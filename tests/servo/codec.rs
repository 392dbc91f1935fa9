//! Golden bytes from `board.md`, and the typed errors of malformed content.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::needless_pass_by_value)]

use servo_studio::protocol::servo::{
    ActionRecord, ButtonEvent, ButtonRecord, CommandType, ContentError, EncodeError, Frame, FrameDecoder,
    JoystickTableRecord, MESSAGE_TABLE, MacroCommandRecord, MacroRecord, Message, ServoMove, ServoStatus,
    ServoSwitches, is_request_id, message_name,
};

fn hex(text: &str) -> Vec<u8> {
    text.split_whitespace().map(|byte| u8::from_str_radix(byte, 16).unwrap()).collect()
}

/// Encodes `message`, compares with `golden`, and decodes `golden` back.
fn assert_golden(message: Message, golden: &str) {
    let bytes = hex(golden);
    assert_eq!(message.encode().unwrap(), bytes, "encoding {}", message.name());
    let mut decoder = FrameDecoder::new();
    decoder.push(&bytes);
    let Some(servo_studio::protocol::servo::DecoderEvent::Frame(frame)) = decoder.poll() else {
        panic!("golden bytes of {} do not decode to a frame", message.name());
    };
    assert_eq!(Message::from_frame(&frame).unwrap(), message);
    assert_eq!(decoder.poll(), None);
}

#[test]
fn golden_query_action_list_request() {
    assert_golden(Message::QueryActionListRequest, "13 4c 05 1d 3a 75 00 00 30");
}

#[test]
fn golden_add_action_response_ok() {
    assert_golden(Message::AddActionResponse { ok: true }, "13 4c 05 1d 4f 75 01 00 01 47");
}

#[test]
fn golden_execute_action_request() {
    let moves = vec![
        ServoMove { servo_id: 1, degree: -90, interval_10ms: 50 },
        ServoMove { servo_id: 2, degree: 45, interval_10ms: 100 },
    ];
    assert_golden(
        Message::ExecuteActionRequest { moves },
        "13 4c 05 1d 52 4e 0b 00 02 01 a6 ff 32 00 02 2d 00 64 00 99",
    );
}

#[test]
fn golden_button_event_response() {
    assert_golden(
        Message::ButtonEventResponse { button_id: 0x8000_0001, event: ButtonEvent::Release },
        "13 4c 05 1d 91 9c 05 00 01 00 00 80 04 38",
    );
}

#[test]
fn golden_add_action_request_with_cjk_caption() {
    let action = ActionRecord {
        action_id: 7,
        caption: "揮手".into(),
        steps: vec![ServoMove { servo_id: 3, degree: -45, interval_10ms: 20 }],
    };
    assert_golden(
        Message::AddActionRequest(action),
        "13 4c 05 1d 4e 75 2b 00 07 00 00 00 e6 8f ae e6 89 8b 00 00 00 00 00 00 00 00 00 00 00 00 00 00 \
         00 00 00 00 00 00 00 00 00 00 00 00 01 00 03 d3 ff 14 00 7d",
    );
}

#[test]
fn golden_query_memory_size_response() {
    assert_golden(
        Message::QueryMemorySizeResponse { free_bytes: 1000, total_bytes: Some(4096) },
        "13 4c 05 1d 2f 27 08 00 e8 03 00 00 00 10 00 00 da",
    );
}

#[test]
fn golden_add_macro_request() {
    let record = MacroRecord {
        macro_id: 100,
        caption: "M".into(),
        commands: vec![
            MacroCommandRecord {
                command_id: 7,
                command_type: CommandType::RunAction,
                ratio_percent: 50,
                loop_count: 2,
                total_interval_ms: 6000,
            },
            MacroCommandRecord {
                command_id: 500,
                command_type: CommandType::Delay,
                ratio_percent: 100,
                loop_count: 1,
                total_interval_ms: 500,
            },
        ],
    };
    assert_golden(
        Message::AddMacroRequest(record),
        "13 4c 05 1d 76 75 3e 00 64 00 00 00 4d 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 \
         00 00 00 00 00 00 00 00 00 00 00 00 02 00 07 00 00 00 00 32 02 00 70 17 00 00 f4 01 00 00 01 64 \
         01 00 f4 01 00 00 6f",
    );
}

#[test]
fn golden_add_joystick_table_request() {
    let table = JoystickTableRecord {
        table_id: 1,
        caption: String::new(),
        buttons: vec![ButtonRecord {
            button_id: 0xffff_ffff,
            caption: "A".into(),
            press_macro: 1,
            long_press_macro: 0,
            up_macro: 2,
            uninterruptible: true,
        }],
    };
    assert_golden(
        Message::AddJoystickTableRequest(table),
        "13 4c 05 1d 5e 9c 57 00 01 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 \
         00 00 00 00 00 00 00 00 00 00 00 00 01 00 ff ff ff ff 41 00 00 00 00 00 00 00 00 00 00 00 00 00 \
         00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 01 00 00 00 00 00 00 00 02 00 00 00 01 15",
    );
}

#[test]
fn golden_query_servo_response() {
    let servo = ServoStatus {
        servo_id: 5,
        angle: -30,
        current_adc: 120,
        temperature_adc: 300,
        servo_type: 1,
        is_start: true,
        is_hold: false,
    };
    assert_golden(
        Message::QueryServoResponse { servos: vec![servo] },
        "13 4c 05 1d 35 4e 0c 00 01 05 e2 ff 78 00 2c 01 01 00 01 00 9e",
    );
}

#[test]
fn golden_small_messages() {
    assert_golden(
        Message::SetServoParameterRequest(ServoSwitches { servo_id: 0xff, is_start: true, is_hold: false }),
        "13 4c 05 1d 3e 4e 03 00 ff 01 00 10",
    );
    assert_golden(Message::SubscribeButtonEventRequest { subscribe: true }, "13 4c 05 1d 86 9c 01 00 01 a5");
    assert_golden(
        Message::QueryProjectIdResponse { project_id: 0x1234_5678 },
        "13 4c 05 1d b3 75 04 00 78 56 34 12 c1",
    );
}

#[test]
fn the_table_lists_all_sixty_ids_once_with_request_response_parity() {
    assert_eq!(MESSAGE_TABLE.len(), 60);
    let mut ids: Vec<u16> = MESSAGE_TABLE.iter().map(|(id, _)| *id).collect();
    ids.sort_unstable();
    ids.dedup();
    assert_eq!(ids.len(), 60);
    assert_eq!(ids.first(), Some(&10010));
    assert_eq!(ids.last(), Some(&40081));
    for (id, name) in MESSAGE_TABLE {
        assert_eq!(is_request_id(id), name.ends_with("Request"), "{id} {name}");
        // Every defined id has a decoder arm: an empty content is either a valid
        // message or a typed error naming this message, never `Unknown`.
        match Message::decode(id, &[]) {
            Ok(message) => assert_eq!(message.name(), name),
            Err(error) => assert!(error.to_string().starts_with(name), "{error}"),
        }
    }
}

#[test]
fn unknown_ids_decode_to_unknown_and_re_encode_unchanged() {
    let message = Message::decode(12345, &[1, 2, 3]).unwrap();
    assert_eq!(message, Message::Unknown { packet_id: 12345, content: vec![1, 2, 3] });
    assert_eq!(message.name(), "Unknown");
    assert_eq!(message_name(12345), None);
    assert_eq!(Message::from_frame(&message.to_frame().unwrap()).unwrap(), message);
}

#[test]
fn too_short_content_names_message_field_expected_and_actual() {
    // QueryActionResponse: id 7, then only 10 of the caption's 32 bytes.
    let mut content = 7i32.to_le_bytes().to_vec();
    content.extend_from_slice(&[0; 10]);
    assert_eq!(
        Message::decode(30021, &content).unwrap_err(),
        ContentError::TooShort {
            message: "QueryActionResponse",
            field: "actionCaption",
            expected_bytes: 32,
            actual_bytes: 10
        }
    );
}

#[test]
fn trailing_bytes_are_an_error() {
    assert_eq!(
        Message::decode(30031, &[1, 0]).unwrap_err(),
        ContentError::TrailingBytes { message: "AddActionResponse", expected_len: 1, actual_len: 2 }
    );
}

#[test]
fn negative_count_is_an_error() {
    let content = (-3i16).to_le_bytes();
    assert_eq!(
        Message::decode(30011, &content).unwrap_err(),
        ContentError::NegativeCount { message: "QueryActionListResponse", field: "actionCount", actual: -3 }
    );
}

#[test]
fn count_beyond_the_content_is_an_error_not_an_allocation() {
    // 32767 buttons announced, none present.
    let mut content = 1i32.to_le_bytes().to_vec();
    content.extend_from_slice(&[0; 32]);
    content.extend_from_slice(&i16::MAX.to_le_bytes());
    assert_eq!(
        Message::decode(40021, &content).unwrap_err(),
        ContentError::TooShort {
            message: "QueryJoystickTableResponse",
            field: "buttonCount",
            expected_bytes: 32767 * 49,
            actual_bytes: 0
        }
    );
}

#[test]
fn undefined_enum_values_are_typed_errors() {
    let err = Message::decode(40081, &[1, 0, 0, 0, 3]).unwrap_err();
    assert_eq!(
        err,
        ContentError::InvalidValue {
            message: "ButtonEventResponse",
            field: "event",
            expected: "1 (press), 2 (long press) or 4 (release)",
            actual: 3
        }
    );
    assert!(matches!(
        Message::decode(20040, &[1, 9]).unwrap_err(),
        ContentError::InvalidValue { field: "unitType", actual: 9, .. }
    ));
}

#[test]
fn failure_responses_decode_to_none_whatever_follows_the_zero_id() {
    // Id 0, then 32 arbitrary bytes and a zero count (38 bytes), as the page says.
    let mut content = vec![0, 0, 0, 0];
    content.extend_from_slice(&[0xAB; 32]);
    content.extend_from_slice(&[0, 0]);
    assert_eq!(Message::decode(30021, &content).unwrap(), Message::QueryActionResponse { action: None });
    assert_eq!(Message::decode(30061, &content).unwrap(), Message::QueryMacroResponse { macro_record: None });
    assert_eq!(Message::decode(40021, &content[..4]).unwrap(), Message::QueryJoystickTableResponse { table: None });
    // Encoding a failure writes the full 38 bytes.
    assert_eq!(Message::QueryActionResponse { action: None }.encode_content().unwrap().len(), 38);
}

#[test]
fn memory_size_response_also_accepts_the_originals_four_bytes() {
    assert_eq!(
        Message::decode(10031, &500i32.to_le_bytes()).unwrap(),
        Message::QueryMemorySizeResponse { free_bytes: 500, total_bytes: None }
    );
}

#[test]
fn too_many_entries_is_an_encode_error() {
    let moves = vec![ServoMove { servo_id: 0, degree: 0, interval_10ms: 0 }; 256];
    assert_eq!(
        Message::ExecuteActionRequest { moves }.encode().unwrap_err(),
        EncodeError::TooMany { message: "ExecuteActionRequest", field: "servoCount", max: 255, actual: 256 }
    );
}

#[test]
fn frame_wire_length_is_content_plus_nine() {
    assert_eq!(Frame::new(1, vec![0; 5]).wire_len(), 14);
}

/// The twelve responses whose content is a `result` byte (`board.md` §2)
/// say so through `result()`; nothing else has one.
#[test]
fn the_result_byte_is_read_from_every_response_that_has_one() {
    let with_result = [10021, 30031, 30041, 30071, 30081, 30091, 30111, 30121, 40031, 40041, 40051, 40071];
    for id in with_result {
        assert_eq!(Message::decode(id, &[1]).unwrap().result(), Some(true), "{id}");
        assert_eq!(Message::decode(id, &[0]).unwrap().result(), Some(false), "{id}");
    }
    for (id, _) in MESSAGE_TABLE.iter().filter(|(id, _)| !with_result.contains(id)) {
        let Ok(message) = Message::decode(*id, &[1]) else { continue };
        assert_eq!(message.result(), None, "{id}");
    }
    assert_eq!(Message::QueryProjectIdResponse { project_id: 1 }.result(), None);
}
