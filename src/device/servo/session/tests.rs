//! Tests of the servo board session state machine.

use super::*;
use crate::protocol::servo::ButtonEvent;

fn config() -> SessionConfig {
    SessionConfig {
        response_timeout: Duration::from_millis(100),
        query_retries: 1,
        idle_gap: Duration::from_millis(20),
        traffic: false,
        line_baud: None,
    }
}

fn bytes(message: &Message) -> Vec<u8> {
    message.encode().unwrap()
}

fn sent(session: &mut Session) -> Vec<Message> {
    std::iter::from_fn(|| session.poll_transmit())
        .map(|raw| {
            let mut decoder = FrameDecoder::new();
            decoder.push(&raw);
            match decoder.poll() {
                Some(DecoderEvent::Frame(frame)) => Message::from_frame(&frame).unwrap(),
                other => panic!("not a frame: {other:?}"),
            }
        })
        .collect()
}

fn events(session: &mut Session) -> Vec<SessionEvent> {
    std::iter::from_fn(|| session.poll_event()).collect()
}

#[test]
fn one_request_in_flight_and_fifo_order() {
    let t0 = Instant::now();
    let mut session = Session::new(config());
    let first = session.submit(t0, Message::QueryProjectIdRequest).unwrap();
    let second = session.submit(t0, Message::QueryRemainPowerRequest).unwrap();
    assert_eq!(sent(&mut session), [Message::QueryProjectIdRequest], "only the first goes out");
    assert_eq!(session.pending_requests(), 2);

    session.handle_input(t0, &bytes(&Message::QueryProjectIdResponse { project_id: 7 }));
    assert_eq!(
        events(&mut session),
        [SessionEvent::Response { id: first, result: Ok(Message::QueryProjectIdResponse { project_id: 7 }) }]
    );
    assert_eq!(sent(&mut session), [Message::QueryRemainPowerRequest], "then the second");
    session.handle_input(t0, &bytes(&Message::QueryRemainPowerResponse { permil: 900 }));
    assert_eq!(
        events(&mut session),
        [SessionEvent::Response { id: second, result: Ok(Message::QueryRemainPowerResponse { permil: 900 }) }]
    );
    assert_eq!(session.poll_timeout(), None);
}

#[test]
fn a_query_is_retried_after_a_timeout_then_fails() {
    let t0 = Instant::now();
    let mut session = Session::new(config());
    let id = session.submit(t0, Message::QueryProjectIdRequest).unwrap();
    assert_eq!(sent(&mut session).len(), 1);
    assert_eq!(session.poll_timeout(), Some(t0 + Duration::from_millis(100)));

    session.handle_timeout(t0 + Duration::from_millis(99));
    assert_eq!(sent(&mut session), [], "not yet");
    let t1 = t0 + Duration::from_millis(100);
    session.handle_timeout(t1);
    assert_eq!(sent(&mut session), [Message::QueryProjectIdRequest], "retried once");
    assert_eq!(events(&mut session), []);

    session.handle_timeout(t1 + Duration::from_millis(100));
    assert_eq!(
        events(&mut session),
        [SessionEvent::Response {
            id,
            result: Err(RequestError::Timeout { request: "QueryProjectIDRequest", attempts: 2, timeout_ms: 100 })
        }]
    );
}

#[test]
fn a_retried_query_succeeds_when_the_second_response_comes() {
    let t0 = Instant::now();
    let mut session = Session::new(config());
    let id = session.submit(t0, Message::QueryActiveJoystickTableRequest).unwrap();
    session.handle_timeout(t0 + Duration::from_millis(100));
    assert_eq!(sent(&mut session).len(), 2);
    session.handle_input(
        t0 + Duration::from_millis(150),
        &bytes(&Message::QueryActiveJoystickTableResponse { table_id: 3 }),
    );
    assert_eq!(
        events(&mut session),
        [SessionEvent::Response { id, result: Ok(Message::QueryActiveJoystickTableResponse { table_id: 3 }) }]
    );
}

#[test]
fn writes_are_not_retried() {
    let t0 = Instant::now();
    let mut session = Session::new(config());
    let id = session.submit(t0, Message::ClearAllDataRequest).unwrap();
    session.handle_timeout(t0 + Duration::from_millis(100));
    assert_eq!(sent(&mut session), [Message::ClearAllDataRequest], "sent once only");
    assert!(matches!(
        events(&mut session).as_slice(),
        [SessionEvent::Response { id: got, result: Err(RequestError::Timeout { attempts: 1, .. }) }] if *got == id
    ));
}

#[test]
fn button_events_pass_through_between_a_request_and_its_response() {
    let t0 = Instant::now();
    let mut session = Session::new(config());
    let id = session.submit(t0, Message::QueryProjectIdRequest).unwrap();
    let mut stream = bytes(&Message::ButtonEventResponse { button_id: 0x8000_0001, event: ButtonEvent::Press });
    stream.extend(bytes(&Message::QueryProjectIdResponse { project_id: 5 }));
    // Split mid-frame, as a serial port delivers it.
    session.handle_input(t0, &stream[..7]);
    session.handle_input(t0, &stream[7..]);
    assert_eq!(
        events(&mut session),
        [
            SessionEvent::Button { button_id: 0x8000_0001, event: ButtonEvent::Press },
            SessionEvent::Response { id, result: Ok(Message::QueryProjectIdResponse { project_id: 5 }) },
        ]
    );
}

#[test]
fn a_frame_answering_nothing_is_unsolicited() {
    let t0 = Instant::now();
    let mut session = Session::new(config());
    session.handle_input(t0, &bytes(&Message::AddActionResponse { ok: true }));
    assert_eq!(events(&mut session), [SessionEvent::Unsolicited(Message::AddActionResponse { ok: true })]);
}

#[test]
fn a_malformed_response_is_retried_for_queries() {
    let t0 = Instant::now();
    let mut session = Session::new(config());
    let id = session.submit(t0, Message::QueryProjectIdRequest).unwrap();
    sent(&mut session);
    // 30131 with 2 content bytes instead of 4: passes the checksum, fails the layout.
    session.handle_input(t0, &Frame::new(30131, vec![1, 2]).to_bytes().unwrap());
    assert_eq!(sent(&mut session), [Message::QueryProjectIdRequest]);
    session.handle_input(t0, &Frame::new(30131, vec![1, 2]).to_bytes().unwrap());
    assert!(matches!(
        events(&mut session).as_slice(),
        [SessionEvent::Response { id: got, result: Err(RequestError::Malformed { request: "QueryProjectIDRequest", .. }) }] if *got == id
    ));
}

#[test]
fn a_response_that_begins_and_then_drips_is_incomplete_not_another_protocol() {
    let t0 = Instant::now();
    let mut session = Session::new(SessionConfig { query_retries: 0, ..config() });
    let id = session.submit(t0, Message::QueryActionListRequest).unwrap();
    sent(&mut session);
    // The action list's header, claiming 200 content bytes, then one byte every 5 ms.
    let mut header = vec![0x13, 0x4c, 0x05, 0x1d];
    header.extend_from_slice(&30011u16.to_le_bytes());
    header.extend_from_slice(&200u16.to_le_bytes());
    session.handle_input(t0 + Duration::from_millis(10), &header);
    let mut at = t0 + Duration::from_millis(15);
    while at < t0 + Duration::from_millis(200) {
        session.handle_input(at, &[0]);
        if let Some(due) = session.poll_timeout().filter(|due| *due <= at) {
            session.handle_timeout(due);
        }
        at += Duration::from_millis(5);
    }
    let responses: Vec<SessionEvent> =
        events(&mut session).into_iter().filter(|e| matches!(e, SessionEvent::Response { .. })).collect();
    assert!(
        matches!(
            responses.as_slice(),
            [SessionEvent::Response { id: got, result: Err(RequestError::Incomplete { expected: 209, received, .. }) }]
                if *got == id && (8..209).contains(received)
        ),
        "{responses:?}"
    );
    let text = match &responses[0] {
        SessionEvent::Response { result: Err(error), .. } => error.to_string(),
        other => panic!("{other:?}"),
    };
    assert!(text.contains("began but did not arrive whole") && !text.contains("not in this protocol"), "{text}");
}

#[test]
fn a_stalled_partial_frame_is_given_up_after_the_idle_gap() {
    let t0 = Instant::now();
    let mut session = Session::new(SessionConfig { traffic: true, ..config() });
    // A header claiming 200 bytes, then silence.
    session.handle_input(t0, &[0x13, 0x4c, 0x05, 0x1d, 0x33, 0x75, 200, 0]);
    assert_eq!(session.poll_timeout(), Some(t0 + Duration::from_millis(20)));
    session.handle_timeout(t0 + Duration::from_millis(20));
    assert!(matches!(
        events(&mut session).as_slice(),
        [SessionEvent::Traffic(Traffic::Skipped { bytes: 8, reason: SkipReason::Truncated { .. } })]
    ));
    assert_eq!(session.poll_timeout(), None);
}

#[test]
fn the_responses_own_header_extends_the_deadline_by_its_wire_time_and_nothing_else_does() {
    let t0 = Instant::now();
    let baud = 115_200;
    let mut session = Session::new(SessionConfig { line_baud: Some(baud), ..config() });
    session.submit(t0, Message::QueryActionListRequest).unwrap();
    let request_len = bytes(&Message::QueryActionListRequest).len();
    let on_line = session.wire_time(request_len);
    assert_eq!(session.poll_timeout(), Some(t0 + on_line + Duration::from_millis(100)));
    // A button event (a whole frame) does not move the deadline.
    let button = bytes(&Message::ButtonEventResponse { button_id: 1, event: ButtonEvent::Press });
    session.handle_input(t0 + Duration::from_millis(50), &button);
    assert_eq!(session.poll_timeout(), Some(t0 + on_line + Duration::from_millis(100)));
    // The response's header: 1000 actions follow (36,002 content bytes).
    let content_len: u16 = 2 + 1000 * 36;
    let at = t0 + Duration::from_millis(60);
    let mut header = vec![0x13, 0x4c, 0x05, 0x1d];
    header.extend_from_slice(&30011u16.to_le_bytes());
    header.extend_from_slice(&content_len.to_le_bytes());
    session.handle_input(at, &header);
    let rest = usize::from(content_len) + 9 - header.len();
    let expected = at + session.wire_time(rest) + Duration::from_millis(100);
    // The idle gap comes first, but the request waits for the whole frame.
    session.handle_input(at + Duration::from_millis(10), &[0; 16]);
    session.handle_timeout(at + Duration::from_millis(10));
    let request_deadline = session.in_flight.as_ref().map(|f| f.deadline);
    assert_eq!(request_deadline, Some(expected), "3.1 s of wire time plus the timeout");
    // More bytes do not extend it again.
    session.handle_input(at + Duration::from_millis(20), &header);
    assert_eq!(session.in_flight.as_ref().map(|f| f.deadline), Some(expected));
}

#[test]
fn a_device_that_chatters_in_another_protocol_ends_the_request_at_its_deadline() {
    let t0 = Instant::now();
    let mut session = Session::new(config());
    let id = session.submit(t0, Message::QueryProjectIdRequest).unwrap();
    sent(&mut session);
    // A byte every 5 ms, forever: none of it a frame.
    let mut at = t0;
    let deadline = t0 + Duration::from_millis(100);
    while at < deadline {
        session.handle_input(at, b"x");
        at += Duration::from_millis(5);
        if let Some(due) = session.poll_timeout().filter(|due| *due <= at) {
            session.handle_timeout(due);
        }
    }
    session.handle_timeout(deadline);
    assert_eq!(sent(&mut session), [], "not asked again: it answers, in another protocol");
    let events: Vec<SessionEvent> =
        events(&mut session).into_iter().filter(|e| matches!(e, SessionEvent::Response { .. })).collect();
    assert!(
        matches!(events.as_slice(), [SessionEvent::Response { id: got, result: Err(RequestError::NotThisProtocol { bytes: 20, .. }) }] if *got == id),
        "{events:?}"
    );
}

/// At 19200 baud a long frame takes seconds: one still arriving when a
/// request's deadline comes (the late answer to one given up on before) is
/// the protocol's own, not another protocol's bytes. The request is asked
/// again, and the retry waits for that frame to end before its own answer.
#[test]
fn a_long_frame_still_arriving_at_the_deadline_is_not_another_protocol() {
    let t0 = Instant::now();
    let baud = 19_200;
    let mut session = Session::new(SessionConfig { line_baud: Some(baud), ..config() });
    let id = session.submit(t0, Message::QueryProjectIdRequest).unwrap();
    let sent_at_first = sent(&mut session);
    assert_eq!(sent_at_first, [Message::QueryProjectIdRequest]);
    // Another packet id's frame: 4000 content bytes, of which the header and 100 came.
    let content_len: u16 = 4000;
    let mut header = vec![0x13, 0x4c, 0x05, 0x1d];
    header.extend_from_slice(&7u16.to_le_bytes());
    header.extend_from_slice(&content_len.to_le_bytes());
    session.handle_input(t0 + Duration::from_millis(10), &header);
    // The request's deadline: its own time on the line and the timeout (a foreign frame does not move it).
    let request_len = bytes(&Message::QueryProjectIdRequest).len();
    let deadline = t0 + session.wire_time(request_len) + Duration::from_millis(100);
    // The frame keeps coming, 16 bytes every 10 ms (19200 baud delivers about 19).
    let mut at = t0 + Duration::from_millis(10);
    let mut came = header.len();
    while at < deadline {
        at += Duration::from_millis(10);
        session.handle_input(at.min(deadline), &[0x55; 16]);
        came += 16;
        assert_eq!(session.pending_requests(), 1, "still waiting at {:?}", at - t0);
    }
    assert_eq!(session.poll_timeout(), Some(deadline));
    session.handle_timeout(deadline);
    let told: Vec<SessionEvent> =
        events(&mut session).into_iter().filter(|e| matches!(e, SessionEvent::Response { .. })).collect();
    assert_eq!(told, [], "not given up as another protocol: asked again");
    assert_eq!(sent(&mut session), [Message::QueryProjectIdRequest]);
    // The retry's deadline counts the rest of the frame on the line.
    let rest = usize::from(content_len) + 9 - came;
    let retry_deadline = session.in_flight.as_ref().map(|f| f.deadline).unwrap();
    assert!(retry_deadline >= deadline + session.wire_time(rest) + Duration::from_millis(100), "{retry_deadline:?}");
    // Nothing at all comes after that: a timeout, said as one.
    session.handle_timeout(retry_deadline + Duration::from_secs(10));
    let told: Vec<SessionEvent> =
        events(&mut session).into_iter().filter(|e| matches!(e, SessionEvent::Response { .. })).collect();
    assert!(
        matches!(told.as_slice(), [SessionEvent::Response { id: got, result: Err(RequestError::Timeout { .. } | RequestError::Incomplete { .. }) }] if *got == id),
        "{told:?}"
    );
}

#[test]
fn disconnect_fails_every_pending_request() {
    let t0 = Instant::now();
    let mut session = Session::new(config());
    let a = session.submit(t0, Message::QueryProjectIdRequest).unwrap();
    let b = session.submit(t0, Message::QueryMacroListRequest).unwrap();
    session.handle_disconnect("cable pulled");
    let failed = RequestError::Disconnected { reason: "cable pulled".into() };
    assert_eq!(
        events(&mut session),
        [
            SessionEvent::Response { id: a, result: Err(failed.clone()) },
            SessionEvent::Response { id: b, result: Err(failed) }
        ]
    );
    assert_eq!(session.pending_requests(), 0);
}

#[test]
fn fire_and_forget_messages_go_out_at_once() {
    let t0 = Instant::now();
    let mut session = Session::new(config());
    session.submit(t0, Message::QueryProjectIdRequest).unwrap();
    sent(&mut session);
    session.send(t0, Message::ExecuteActionExRequest { action_id: 4 }).unwrap();
    assert_eq!(sent(&mut session), [Message::ExecuteActionExRequest { action_id: 4 }]);
    assert_eq!(session.pending_requests(), 1);
}

#[test]
fn live_moves_are_coalesced_while_the_line_is_busy() {
    let t0 = Instant::now();
    // 10 000 baud: a 15-byte one-servo move (9 + 1 + 5) takes 15 ms on the wire.
    let mut session = Session::new(SessionConfig { line_baud: Some(10_000), ..config() });
    let to = |degree| [ServoMove { servo_id: 1, degree, interval_10ms: 0 }];
    session.set_live_moves(t0, &to(10));
    assert_eq!(sent(&mut session), [Message::ExecuteActionRequest { moves: to(10).to_vec() }]);
    for (ms, degree) in [(1, 20), (5, 30), (14, 40)] {
        session.set_live_moves(t0 + Duration::from_millis(ms), &to(degree));
        assert_eq!(sent(&mut session), [], "the line is busy at {ms} ms");
    }
    // Another servo joins the pending move.
    session.set_live_moves(t0 + Duration::from_millis(14), &[ServoMove { servo_id: 2, degree: -5, interval_10ms: 0 }]);
    assert_eq!(session.poll_timeout(), Some(t0 + Duration::from_millis(15)));
    session.handle_timeout(t0 + Duration::from_millis(15));
    assert_eq!(
        sent(&mut session),
        [Message::ExecuteActionRequest {
            moves: vec![to(40)[0], ServoMove { servo_id: 2, degree: -5, interval_10ms: 0 }]
        }],
        "only the latest value of each servo"
    );
    // Nothing stale follows.
    session.handle_timeout(t0 + Duration::from_secs(1));
    assert_eq!(sent(&mut session), []);
    assert_eq!(session.poll_timeout(), None);
}

/// STOP: a macro queued behind a query still waiting for its answer (a slow
/// board, a bursty bridge) never goes out after the stop; its caller is told
/// it was not sent, and the only frame sent after is the stop itself.
#[test]
fn stop_drops_every_queued_request_and_only_the_stop_goes_out() {
    let t0 = Instant::now();
    let mut session = Session::new(config());
    let asked = session.submit(t0, Message::QueryProjectIdRequest).unwrap();
    let macro_run = session.submit(t0, Message::ExecuteMacroRequest { macro_id: 4 }).unwrap();
    assert_eq!(sent(&mut session), [Message::QueryProjectIdRequest]);
    let stop = Message::SetServoParameterRequest(crate::protocol::servo::ServoSwitches {
        servo_id: 255,
        is_start: false,
        is_hold: true,
    });
    session.cancel_queued();
    session.send(t0, stop.clone()).unwrap();
    assert_eq!(
        events(&mut session),
        [SessionEvent::Response {
            id: macro_run,
            result: Err(RequestError::Stopped { request: "ExecuteMacroRequest" })
        }]
    );
    // The query's answer comes: nothing queued follows it.
    session.handle_input(t0, &bytes(&Message::QueryProjectIdResponse { project_id: 7 }));
    assert_eq!(
        events(&mut session),
        [SessionEvent::Response { id: asked, result: Ok(Message::QueryProjectIdResponse { project_id: 7 }) }]
    );
    assert_eq!(sent(&mut session), [stop]);
    assert_eq!(session.pending_requests(), 0);
}
