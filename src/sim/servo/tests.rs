//! Tests of the emulated servo board.

use super::*;
use crate::protocol::servo::{ActionRecord, CommandType, Frame, MacroRecord, ServoParameter};

/// Feeds `message` at `now` and returns every response the board sends by `until`.
fn ask(sim: &mut ServoSim, now: Instant, message: &Message, until: Instant) -> Vec<Message> {
    sim.handle_input(now, &message.encode().unwrap());
    if let Some(deadline) = sim.poll_timeout().filter(|deadline| *deadline <= until) {
        sim.handle_timeout(deadline);
    }
    let mut decoder = FrameDecoder::new();
    while let Some(bytes) = sim.poll_transmit(until) {
        decoder.push(&bytes);
    }
    std::iter::from_fn(|| decoder.poll())
        .filter_map(|event| match event {
            DecoderEvent::Frame(frame) => Some(Message::from_frame(&frame).unwrap()),
            DecoderEvent::Skipped { .. } => None,
        })
        .collect()
}

fn angle_of(responses: &[Message], servo_id: u8) -> i16 {
    match responses {
        [Message::QueryServoResponse { servos }] => servos.iter().find(|s| s.servo_id == servo_id).unwrap().angle,
        other => panic!("unexpected {other:?}"),
    }
}

#[test]
fn servos_move_linearly_over_their_interval() {
    let t0 = Instant::now();
    let mut sim = ServoSim::new(SimConfig::default(), ServoImage::default());
    let moves = vec![ServoMove { servo_id: 2, degree: 90, interval_10ms: 100 }];
    assert_eq!(ask(&mut sim, t0, &Message::ExecuteActionRequest { moves }, t0), []);
    let query = Message::QueryServoRequest { servo_id: 2 };
    assert_eq!(angle_of(&ask(&mut sim, t0 + Duration::from_millis(500), &query, t0 + Duration::from_secs(9)), 2), 45);
    assert_eq!(angle_of(&ask(&mut sim, t0 + Duration::from_millis(1000), &query, t0 + Duration::from_secs(9)), 2), 90);
    // An unknown servo: an empty answer.
    let later = t0 + Duration::from_secs(10);
    let unknown = ask(&mut sim, later, &Message::QueryServoRequest { servo_id: 200 }, later);
    assert_eq!(unknown, [Message::QueryServoResponse { servos: vec![] }]);
}

#[test]
fn memory_shrinks_with_what_is_stored_and_a_full_board_refuses() {
    let t0 = Instant::now();
    let config = SimConfig { total_memory_bytes: 100, ..SimConfig::default() };
    let mut sim = ServoSim::new(config, ServoImage::default());
    assert_eq!(
        ask(&mut sim, t0, &Message::QueryMemorySizeRequest, t0),
        [Message::QueryMemorySizeResponse { free_bytes: 92, total_bytes: Some(100) }]
    );
    let action = |action_id| {
        Message::AddActionRequest(ActionRecord {
            action_id,
            caption: "a".into(),
            steps: vec![ServoMove { servo_id: 1, degree: 0, interval_10ms: 1 }],
        })
    };
    assert_eq!(ask(&mut sim, t0, &action(1), t0), [Message::AddActionResponse { ok: true }]);
    assert_eq!(
        ask(&mut sim, t0, &Message::QueryMemorySizeRequest, t0),
        [Message::QueryMemorySizeResponse { free_bytes: 49, total_bytes: Some(100) }]
    );
    // Each action takes 43 bytes: a second fits (49 free), a third does not (6 free).
    assert_eq!(ask(&mut sim, t0, &action(2), t0), [Message::AddActionResponse { ok: true }]);
    assert_eq!(ask(&mut sim, t0, &action(3), t0), [Message::AddActionResponse { ok: false }]);
    assert_eq!(sim.image().actions.len(), 2);
}

#[test]
fn failure_responses_for_missing_items() {
    let t0 = Instant::now();
    let mut sim = ServoSim::new(SimConfig::default(), ServoImage::default());
    assert_eq!(
        ask(&mut sim, t0, &Message::QueryActionRequest { action_id: 5 }, t0),
        [Message::QueryActionResponse { action: None }]
    );
    assert_eq!(
        ask(&mut sim, t0, &Message::DeleteMacroRequest { macro_id: 5 }, t0),
        [Message::DeleteMacroResponse { ok: false }]
    );
    assert_eq!(
        ask(&mut sim, t0, &Message::SetActiveJoystickTableRequest { table_id: 5 }, t0),
        [Message::SetActiveJoystickTableResponse { ok: false }]
    );
}

#[test]
fn a_stored_macro_runs_its_actions_in_time() {
    let t0 = Instant::now();
    let image = ServoImage {
        servos: vec![ServoParameter { servo_id: 1, adjusted_degree: 0, caption: String::new() }],
        actions: vec![
            ActionRecord {
                action_id: 1,
                caption: String::new(),
                steps: vec![ServoMove { servo_id: 1, degree: 60, interval_10ms: 50 }],
            },
            ActionRecord {
                action_id: 2,
                caption: String::new(),
                steps: vec![ServoMove { servo_id: 1, degree: -60, interval_10ms: 50 }],
            },
        ],
        macros: vec![MacroRecord {
            macro_id: 9,
            caption: String::new(),
            commands: vec![
                crate::protocol::servo::MacroCommandRecord {
                    command_id: 1,
                    command_type: CommandType::RunAction,
                    ratio_percent: 100,
                    loop_count: 1,
                    total_interval_ms: 500,
                },
                crate::protocol::servo::MacroCommandRecord {
                    command_id: 2,
                    command_type: CommandType::RunAction,
                    ratio_percent: 100,
                    loop_count: 1,
                    total_interval_ms: 500,
                },
            ],
        }],
        ..ServoImage::default()
    };
    let mut sim = ServoSim::new(SimConfig::default(), image);
    assert_eq!(
        ask(&mut sim, t0, &Message::ExecuteMacroRequest { macro_id: 9 }, t0),
        [Message::ExecuteMacroResponse { ok: true }]
    );
    assert_eq!(sim.angle(1, t0 + Duration::from_millis(500)), Some(60));
    // The second action starts at 500 ms: the board applies it when its time comes.
    assert_eq!(sim.poll_timeout(), Some(t0 + Duration::from_millis(500)));
    sim.handle_timeout(t0 + Duration::from_millis(500));
    assert_eq!(sim.angle(1, t0 + Duration::from_millis(1000)), Some(-60));
}

/// Loops inside loops that would play for years (32767 turns, eight deep)
/// are laid out only so far: the board answers at once and stays responsive.
#[test]
fn a_macro_of_loops_inside_loops_is_laid_out_only_so_far() {
    let t0 = Instant::now();
    let command = |command_id, command_type| crate::protocol::servo::MacroCommandRecord {
        command_id,
        command_type,
        ratio_percent: 100,
        loop_count: i16::MAX,
        total_interval_ms: 0,
    };
    let macros = (1..=9)
        .map(|macro_id| MacroRecord {
            macro_id,
            caption: String::new(),
            commands: if macro_id == 9 {
                vec![command(1, CommandType::RunAction), command(1, CommandType::Delay)]
            } else {
                vec![command(macro_id + 1, CommandType::RunMacro)]
            },
        })
        .collect();
    let image = ServoImage {
        servos: vec![ServoParameter { servo_id: 1, adjusted_degree: 0, caption: String::new() }],
        actions: vec![ActionRecord {
            action_id: 1,
            caption: String::new(),
            steps: vec![ServoMove { servo_id: 1, degree: 30, interval_10ms: 1 }],
        }],
        macros,
        ..ServoImage::default()
    };
    let mut sim = ServoSim::new(SimConfig::default(), image);
    assert_eq!(
        ask(&mut sim, t0, &Message::ExecuteMacroRequest { macro_id: 1 }, t0),
        [Message::ExecuteMacroResponse { ok: true }]
    );
    assert!(sim.schedule.len() <= usize::try_from(playing::MOST_TURNS).unwrap());
    assert!(sim.schedule.iter().all(|(at, _)| *at <= t0 + playing::HORIZON + Duration::from_secs(1)));
    let later = t0 + Duration::from_millis(50);
    assert_eq!(angle_of(&ask(&mut sim, later, &Message::QueryServoRequest { servo_id: 1 }, later), 1), 30);
}

#[test]
fn a_line_rate_delays_requests_and_responses_by_their_wire_time() {
    let t0 = Instant::now();
    let config = SimConfig { baud: Some(10_000), turnaround: Duration::from_millis(2), ..SimConfig::default() };
    let mut sim = ServoSim::new(config, ServoImage::default());
    // 9 request bytes at 1 ms each arrive at 9 ms; the 13-byte response leaves
    // after 2 ms of turnaround and 13 ms on the wire: at 24 ms.
    sim.handle_input(t0, &Message::QueryProjectIdRequest.encode().unwrap());
    assert_eq!(sim.poll_timeout(), Some(t0 + Duration::from_millis(9)));
    sim.handle_timeout(t0 + Duration::from_millis(9));
    assert_eq!(sim.poll_timeout(), Some(t0 + Duration::from_millis(24)));
    assert_eq!(sim.poll_transmit(t0 + Duration::from_millis(23)), None);
    let bytes = sim.poll_transmit(t0 + Duration::from_millis(24)).unwrap();
    assert_eq!(bytes, Message::QueryProjectIdResponse { project_id: 0 }.encode().unwrap());
}

#[test]
fn a_long_response_trickles_out_at_the_line_rate_instead_of_arriving_at_its_end() {
    let t0 = Instant::now();
    let config = SimConfig { baud: Some(10_000), ..SimConfig::default() };
    let actions = (1..=10)
        .map(|action_id| ActionRecord { action_id, caption: format!("a{action_id}"), steps: Vec::new() })
        .collect();
    let mut sim = ServoSim::new(config, ServoImage { actions, ..ServoImage::default() });
    sim.handle_input(t0, &Message::QueryActionListRequest.encode().unwrap());
    let arrived = t0 + Duration::from_millis(9);
    sim.handle_timeout(arrived);
    // 2 + 10 × 36 content bytes + 9 of framing = 371 bytes, 1 ms each on the wire.
    let first = arrived + Duration::from_millis(64);
    assert_eq!(sim.poll_timeout(), Some(first), "the first 64 bytes, once they have crossed");
    assert_eq!(sim.poll_transmit(first).map(|piece| piece.len()), Some(64));
    let mut received = 64;
    let end = arrived + Duration::from_millis(371);
    while let Some(piece) = sim.poll_transmit(end) {
        received += piece.len();
    }
    assert_eq!(received, 371);
}

#[test]
fn button_events_only_while_subscribed() {
    let t0 = Instant::now();
    let mut sim = ServoSim::new(SimConfig::default(), ServoImage::default());
    sim.handle_command(t0, SimCommand::Button { button_id: 3, event: ButtonEvent::Press });
    assert_eq!(sim.poll_transmit(t0), None);
    ask(&mut sim, t0, &Message::SubscribeButtonEventRequest { subscribe: true }, t0);
    sim.handle_command(t0, SimCommand::Button { button_id: 3, event: ButtonEvent::Press });
    let bytes = sim.poll_transmit(t0).unwrap();
    assert_eq!(bytes, Frame::new(40081, vec![3, 0, 0, 0, 1]).to_bytes().unwrap());
}

#[test]
fn a_released_servo_can_be_turned_by_hand() {
    let t0 = Instant::now();
    let mut sim = ServoSim::new(SimConfig::default(), ServoImage::default());
    sim.handle_command(t0, SimCommand::TurnByHand { servo_id: 1, angle: 33 });
    assert_eq!(sim.angle(1, t0), Some(0), "holding torque: it does not give");
    let release =
        Message::SetServoParameterRequest(ServoSwitches { servo_id: ALL_SERVOS, is_start: true, is_hold: false });
    ask(&mut sim, t0, &release, t0);
    sim.handle_command(t0, SimCommand::TurnByHand { servo_id: 1, angle: 33 });
    assert_eq!(sim.angle(1, t0), Some(33));
}
