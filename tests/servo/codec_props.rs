//! Property tests of the board codec: round trips, chunking, garbage, and
//! arbitrary bytes. Run longer with `PROPTEST_CASES=1000000` (see README).

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::needless_pass_by_value)]

use proptest::prelude::*;
use servo_studio::protocol::servo::{
    ActionRecord, AngleUnit, ButtonEvent, ButtonRecord, CommandType, DecoderEvent, Frame, FrameDecoder,
    JoystickTableRecord, ListEntry, MAGIC, MESSAGE_TABLE, MacroCommandRecord, MacroRecord, Message, ServoMove,
    ServoParameter, ServoStatus, ServoSwitches, TransmissionMode, truncate_utf8,
};

/// The case count: `default`, or `PROPTEST_CASES` when set (for long fuzzing runs).
fn cases(default: u32) -> ProptestConfig {
    let cases = std::env::var("PROPTEST_CASES").ok().and_then(|value| value.parse().ok()).unwrap_or(default);
    ProptestConfig::with_cases(cases)
}

fn caption() -> impl Strategy<Value = String> {
    "[a-zA-Z0-9 _動作巨集手臂揮左右一二三]{0,12}".prop_map(|text| truncate_utf8(&text, 32).to_string())
}

fn nonzero_id() -> impl Strategy<Value = i32> {
    any::<i32>().prop_filter("0 means failure", |id| *id != 0)
}

fn servo_move() -> impl Strategy<Value = ServoMove> {
    (any::<u8>(), any::<i16>(), any::<i16>()).prop_map(|(servo_id, degree, interval_10ms)| ServoMove {
        servo_id,
        degree,
        interval_10ms,
    })
}

fn list_entries() -> impl Strategy<Value = Vec<ListEntry>> {
    prop::collection::vec((any::<i32>(), caption()).prop_map(|(id, caption)| ListEntry { id, caption }), 0..5)
}

fn action(id: BoxedStrategy<i32>) -> impl Strategy<Value = ActionRecord> {
    (id, caption(), prop::collection::vec(servo_move(), 0..70)).prop_map(|(action_id, caption, steps)| ActionRecord {
        action_id,
        caption,
        steps,
    })
}

fn macro_record(id: BoxedStrategy<i32>) -> impl Strategy<Value = MacroRecord> {
    let command_type = prop_oneof![Just(CommandType::RunAction), Just(CommandType::Delay), Just(CommandType::RunMacro)];
    let command = (any::<i32>(), command_type, any::<u8>(), any::<i16>(), any::<i32>()).prop_map(
        |(command_id, command_type, ratio_percent, loop_count, total_interval_ms)| MacroCommandRecord {
            command_id,
            command_type,
            ratio_percent,
            loop_count,
            total_interval_ms,
        },
    );
    (id, caption(), prop::collection::vec(command, 0..8)).prop_map(|(macro_id, caption, commands)| MacroRecord {
        macro_id,
        caption,
        commands,
    })
}

fn table(id: BoxedStrategy<i32>) -> impl Strategy<Value = JoystickTableRecord> {
    let button = (any::<u32>(), caption(), any::<i32>(), any::<i32>(), any::<i32>(), any::<bool>()).prop_map(
        |(button_id, caption, press_macro, long_press_macro, up_macro, uninterruptible)| ButtonRecord {
            button_id,
            caption,
            press_macro,
            long_press_macro,
            up_macro,
            uninterruptible,
        },
    );
    (id, caption(), prop::collection::vec(button, 0..6)).prop_map(|(table_id, caption, buttons)| JoystickTableRecord {
        table_id,
        caption,
        buttons,
    })
}

fn servo_parameters() -> impl Strategy<Value = Vec<ServoParameter>> {
    prop::collection::vec(
        (any::<u8>(), any::<i16>(), caption()).prop_map(|(servo_id, adjusted_degree, caption)| ServoParameter {
            servo_id,
            adjusted_degree,
            caption,
        }),
        0..6,
    )
}

fn switches() -> impl Strategy<Value = ServoSwitches> {
    (any::<u8>(), any::<bool>(), any::<bool>()).prop_map(|(servo_id, is_start, is_hold)| ServoSwitches {
        servo_id,
        is_start,
        is_hold,
    })
}

/// Every message of the protocol, with arbitrary valid fields.
fn message() -> BoxedStrategy<Message> {
    use Message as M;
    let mode = || prop_oneof![Just(TransmissionMode::Old), Just(TransmissionMode::New)];
    let unit = || prop_oneof![Just(AngleUnit::Degree), Just(AngleUnit::Adc)];
    let event = prop_oneof![Just(ButtonEvent::Press), Just(ButtonEvent::LongPress), Just(ButtonEvent::Release)];
    let ok = || any::<bool>();
    let id = || any::<i32>();
    let any_id = || any::<i32>().boxed();
    let status = (any::<u8>(), any::<i16>(), any::<i16>(), any::<i16>(), any::<i16>(), any::<bool>(), any::<bool>())
        .prop_map(|(servo_id, angle, current_adc, temperature_adc, servo_type, is_start, is_hold)| ServoStatus {
            servo_id,
            angle,
            current_adc,
            temperature_adc,
            servo_type,
            is_start,
            is_hold,
        });
    let unknown_id = any::<u16>().prop_filter("undefined id", |id| MESSAGE_TABLE.iter().all(|(known, _)| known != id));
    prop_oneof![
        mode().prop_map(|mode| M::TransmissionModeSettingRequest { mode }),
        mode().prop_map(|mode| M::TransmissionModeSettingResponse { mode }),
        Just(M::ClearAllDataRequest),
        ok().prop_map(|ok| M::ClearAllDataResponse { ok }),
        Just(M::QueryMemorySizeRequest),
        (id(), prop::option::of(id()))
            .prop_map(|(free_bytes, total_bytes)| { M::QueryMemorySizeResponse { free_bytes, total_bytes } }),
        Just(M::QueryRemainPowerRequest),
        any::<i16>().prop_map(|permil| M::QueryRemainPowerResponse { permil }),
        prop::collection::vec(any::<u8>(), 0..40).prop_map(|data| M::SendDummyDataRequest { data }),
        Just(M::QueryServoListRequest),
        prop::collection::vec(any::<u8>(), 0..30).prop_map(|servo_ids| M::QueryServoListResponse { servo_ids }),
        any::<u8>().prop_map(|servo_id| M::QueryServoRequest { servo_id }),
        prop::collection::vec(status, 0..6).prop_map(|servos| M::QueryServoResponse { servos }),
        switches().prop_map(M::SetServoParameterRequest),
        switches().prop_map(M::SetServoParameterResponse),
        (any::<u8>(), unit()).prop_map(|(servo_id, unit)| M::SetAngleUnitRequest { servo_id, unit }),
        (any::<u8>(), unit()).prop_map(|(servo_id, unit)| M::SetAngleUnitResponse { servo_id, unit }),
        prop::collection::vec(servo_move(), 0..20).prop_map(|moves| M::ExecuteActionRequest { moves }),
        id().prop_map(|action_id| M::ExecuteActionExRequest { action_id }),
        Just(M::QueryActionListRequest),
        list_entries().prop_map(|actions| M::QueryActionListResponse { actions }),
        id().prop_map(|action_id| M::QueryActionRequest { action_id }),
        prop::option::of(action(nonzero_id().boxed())).prop_map(|action| M::QueryActionResponse { action }),
        action(any_id()).prop_map(M::AddActionRequest),
        ok().prop_map(|ok| M::AddActionResponse { ok }),
        id().prop_map(|action_id| M::DeleteActionRequest { action_id }),
        ok().prop_map(|ok| M::DeleteActionResponse { ok }),
        Just(M::QueryMacroListRequest),
        list_entries().prop_map(|macros| M::QueryMacroListResponse { macros }),
        id().prop_map(|macro_id| M::QueryMacroRequest { macro_id }),
        prop::option::of(macro_record(nonzero_id().boxed()))
            .prop_map(|macro_record| M::QueryMacroResponse { macro_record }),
        macro_record(any_id()).prop_map(M::AddMacroRequest),
        ok().prop_map(|ok| M::AddMacroResponse { ok }),
        id().prop_map(|macro_id| M::DeleteMacroRequest { macro_id }),
        ok().prop_map(|ok| M::DeleteMacroResponse { ok }),
        id().prop_map(|macro_id| M::ExecuteMacroRequest { macro_id }),
        ok().prop_map(|ok| M::ExecuteMacroResponse { ok }),
        Just(M::QueryServoParameterRequest),
        servo_parameters().prop_map(|servos| M::QueryServoParameterResponse { servos }),
        servo_parameters().prop_map(|servos| M::AddServoParameterRequest { servos }),
        ok().prop_map(|ok| M::AddServoParameterResponse { ok }),
        id().prop_map(|project_id| M::WriteProjectIdRequest { project_id }),
        ok().prop_map(|ok| M::WriteProjectIdResponse { ok }),
        Just(M::QueryProjectIdRequest),
        id().prop_map(|project_id| M::QueryProjectIdResponse { project_id }),
        Just(M::QueryJoystickTableListRequest),
        list_entries().prop_map(|tables| M::QueryJoystickTableListResponse { tables }),
        id().prop_map(|table_id| M::QueryJoystickTableRequest { table_id }),
        prop::option::of(table(nonzero_id().boxed())).prop_map(|table| M::QueryJoystickTableResponse { table }),
        table(any_id()).prop_map(M::AddJoystickTableRequest),
        ok().prop_map(|ok| M::AddJoystickTableResponse { ok }),
        id().prop_map(|table_id| M::DeleteJoystickTableRequest { table_id }),
        ok().prop_map(|ok| M::DeleteJoystickTableResponse { ok }),
        id().prop_map(|table_id| M::SetActiveJoystickTableRequest { table_id }),
        ok().prop_map(|ok| M::SetActiveJoystickTableResponse { ok }),
        Just(M::QueryActiveJoystickTableRequest),
        id().prop_map(|table_id| M::QueryActiveJoystickTableResponse { table_id }),
        ok().prop_map(|subscribe| M::SubscribeButtonEventRequest { subscribe }),
        ok().prop_map(|ok| M::SubscribeButtonEventResponse { ok }),
        (any::<u32>(), event).prop_map(|(button_id, event)| M::ButtonEventResponse { button_id, event }),
        (unknown_id, prop::collection::vec(any::<u8>(), 0..40))
            .prop_map(|(packet_id, content)| M::Unknown { packet_id, content }),
    ]
    .boxed()
}

/// Bytes that hold no magic: what a noisy line adds between frames.
fn garbage() -> impl Strategy<Value = Vec<u8>> {
    prop::collection::vec(prop_oneof![any::<u8>(), Just(0x13), Just(0x4c), Just(0x05)], 0..24)
        .prop_filter("holds no magic", |bytes| bytes.windows(4).all(|window| window != MAGIC))
}

/// All events of `decoder` until it needs more bytes.
fn drain(decoder: &mut FrameDecoder) -> Vec<DecoderEvent> {
    std::iter::from_fn(|| decoder.poll()).collect()
}

/// Frames and skipped byte count of a whole stream, with the line going quiet at its end.
fn decode_all(chunks: &[&[u8]]) -> (Vec<Frame>, usize) {
    let mut decoder = FrameDecoder::new();
    let mut events = Vec::new();
    for chunk in chunks {
        decoder.push(chunk);
        events.extend(drain(&mut decoder));
    }
    decoder.abandon_partial();
    events.extend(drain(&mut decoder));
    assert_eq!(decoder.pending_len(), 0);
    let mut frames = Vec::new();
    let mut skipped = 0;
    for event in events {
        match event {
            DecoderEvent::Frame(frame) => frames.push(frame),
            DecoderEvent::Skipped { bytes, .. } => skipped += bytes,
        }
    }
    (frames, skipped)
}

/// Splits `bytes` at the given cut points (taken modulo its length).
fn split_at_cuts<'a>(bytes: &'a [u8], cuts: &[usize]) -> Vec<&'a [u8]> {
    let mut points: Vec<usize> = cuts.iter().map(|cut| cut % (bytes.len() + 1)).collect();
    points.push(0);
    points.push(bytes.len());
    points.sort_unstable();
    points.windows(2).map(|pair| &bytes[pair[0]..pair[1]]).collect()
}

proptest! {
    #![proptest_config(cases(2_000))]

    #[test]
    fn every_message_round_trips(message in message()) {
        let bytes = message.encode().unwrap();
        let (frames, skipped) = decode_all(&[&bytes]);
        prop_assert_eq!(skipped, 0);
        prop_assert_eq!(frames.len(), 1);
        prop_assert_eq!(frames[0].packet_id, message.packet_id());
        prop_assert_eq!(Message::from_frame(&frames[0]).unwrap(), message);
    }

    #[test]
    fn any_chunking_decodes_the_same_frames(
        messages in prop::collection::vec(message(), 1..6),
        cuts in prop::collection::vec(any::<usize>(), 0..12),
    ) {
        let stream: Vec<u8> = messages.iter().flat_map(|m| m.encode().unwrap()).collect();
        let (whole, _) = decode_all(&[&stream]);
        let (chunked, skipped) = decode_all(&split_at_cuts(&stream, &cuts));
        prop_assert_eq!(skipped, 0);
        prop_assert_eq!(&chunked, &whole);
        let decoded: Vec<Message> = chunked.iter().map(|f| Message::from_frame(f).unwrap()).collect();
        prop_assert_eq!(decoded, messages);
    }

    #[test]
    fn garbage_between_frames_never_loses_a_frame(
        pieces in prop::collection::vec((garbage(), message()), 1..6),
        tail in garbage(),
        cuts in prop::collection::vec(any::<usize>(), 0..12),
    ) {
        let mut stream = Vec::new();
        let mut garbage_len = tail.len();
        for (noise, message) in &pieces {
            stream.extend_from_slice(noise);
            garbage_len += noise.len();
            stream.extend(message.encode().unwrap());
        }
        stream.extend_from_slice(&tail);
        let (frames, skipped) = decode_all(&split_at_cuts(&stream, &cuts));
        let decoded: Vec<Message> = frames.iter().map(|f| Message::from_frame(f).unwrap()).collect();
        let expected: Vec<Message> = pieces.into_iter().map(|(_, message)| message).collect();
        prop_assert_eq!(decoded, expected);
        prop_assert_eq!(skipped, garbage_len);
    }
}

proptest! {
    // The bulk of the suite's random cases: arbitrary bytes and arbitrary content.
    #![proptest_config(cases(60_000))]

    #[test]
    fn arbitrary_bytes_never_panic_and_every_byte_is_accounted_for(
        bytes in prop::collection::vec(prop_oneof![3 => any::<u8>(), 1 => Just(0x13), 1 => Just(0x4c), 1 => Just(0x05), 1 => Just(0x1d)], 0..200),
        cuts in prop::collection::vec(any::<usize>(), 0..4),
    ) {
        let (frames, skipped) = decode_all(&split_at_cuts(&bytes, &cuts));
        let frame_bytes: usize = frames.iter().map(Frame::wire_len).sum();
        prop_assert_eq!(frame_bytes + skipped, bytes.len());
        for frame in &frames {
            let _ = Message::from_frame(frame);
        }
    }
}

proptest! {
    #![proptest_config(cases(50_000))]

    #[test]
    fn arbitrary_content_of_any_defined_id_never_panics_and_decodes_stably(
        index in 0..MESSAGE_TABLE.len(),
        content in prop::collection::vec(any::<u8>(), 0..120),
    ) {
        let packet_id = MESSAGE_TABLE[index].0;
        if let Ok(message) = Message::decode(packet_id, &content) {
            // What decodes must re-encode to something that decodes the same.
            let again = Message::from_frame(&message.to_frame().unwrap()).unwrap();
            prop_assert_eq!(again, message);
        }
    }
}
