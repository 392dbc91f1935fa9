//! The board session: a sans-IO state machine that matches each request to its
//! response by message id (response id = request id + 1), one request in
//! flight, the rest queued in order; retries idempotent queries on timeout; and
//! passes unsolicited button events (40081) through, also between a request and
//! its response. Time comes in as `now`, so every behaviour is tested without
//! sleeping.

use std::collections::VecDeque;
use std::time::{Duration, Instant};

use crate::protocol::servo::{
    ContentError, DecoderEvent, EncodeError, Frame, FrameDecoder, Message, ServoMove, SkipReason,
};

/// Timing of a session.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SessionConfig {
    /// How long the board may take to answer, on top of the time the request
    /// and its response need on the line at `line_baud`. Incoming bytes never
    /// extend it: only the response's own header, which says how many bytes
    /// are still to come, extends the deadline by their wire time.
    pub response_timeout: Duration,
    /// How many times an idempotent query is sent again after a timeout.
    pub query_retries: u8,
    /// How long the line may stay quiet inside a frame before the decoder
    /// gives that frame up and re-scans what it holds.
    pub idle_gap: Duration,
    /// Whether to report every frame sent and received ([`SessionEvent::Traffic`]).
    pub traffic: bool,
    /// The line rate, used to pace live moves: a new move goes out only when
    /// the bytes before it have had time to cross the line (`None`: no pacing).
    pub line_baud: Option<u32>,
}

impl Default for SessionConfig {
    fn default() -> Self {
        Self {
            response_timeout: Duration::from_millis(1000),
            query_retries: 2,
            idle_gap: Duration::from_millis(100),
            traffic: false,
            line_baud: Some(115_200),
        }
    }
}

/// Identifies one submitted request.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct RequestId(pub u64);

/// Why a request got no usable response.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum RequestError {
    /// No response came in time, after every retry.
    #[error(
        "{request}: no response within {timeout_ms} ms ({attempts} attempt(s)). Check that the board is powered, the baud rate matches, and the cable is in; a slow link may need a longer timeout"
    )]
    Timeout {
        /// The request's name.
        request: &'static str,
        /// How many times it was sent.
        attempts: u8,
        /// The timeout each attempt had, on top of the line time, ms.
        timeout_ms: u64,
    },
    /// Bytes came, but nothing in them was a frame of this protocol.
    #[error(
        "{request}: the device answers, but not in this protocol ({} and no servo-board frame): is it a servo board?", crate::device::bytes(*.bytes)
    )]
    NotThisProtocol {
        /// The request's name.
        request: &'static str,
        /// How many bytes came while waiting.
        bytes: usize,
    },
    /// The awaited response began (its header came) but the rest did not
    /// arrive in time: a line too slow or losing bytes, not another protocol.
    #[error(
        "{request}: the response began but did not arrive whole within {timeout_ms} ms after its header ({received} of its {expected} bytes, {attempts} attempt(s)). The line is too slow or loses bytes: check the baud rate and the cable"
    )]
    Incomplete {
        /// The request's name.
        request: &'static str,
        /// Bytes of the response that came.
        received: usize,
        /// Its whole length, as its header gives it.
        expected: usize,
        /// How many times it was sent.
        attempts: u8,
        /// The timeout each attempt had, on top of the line time, ms.
        timeout_ms: u64,
    },
    /// The response came but its content does not match its layout.
    #[error("{request}: malformed response: {error}")]
    Malformed {
        /// The request's name.
        request: &'static str,
        /// What is wrong with it.
        error: ContentError,
    },
    /// The request cannot be encoded.
    #[error(transparent)]
    Encode(#[from] EncodeError),
    /// The link ended before the response came.
    #[error("the link to the board was lost: {reason}")]
    Disconnected {
        /// Why the link ended.
        reason: String,
    },
}

/// One entry of the packet log.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Traffic {
    /// A frame written to the board.
    Sent {
        /// The frame.
        frame: Frame,
        /// What it says.
        message: Message,
    },
    /// A frame received from the board.
    Received {
        /// The frame.
        frame: Frame,
        /// What it says, or why it cannot be read.
        message: Result<Message, ContentError>,
    },
    /// Bytes dropped while resynchronising.
    Skipped {
        /// How many.
        bytes: usize,
        /// Why.
        reason: SkipReason,
    },
}

/// What the session reports.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum SessionEvent {
    /// The outcome of a request.
    Response {
        /// Which request.
        id: RequestId,
        /// Its response, or why there is none.
        result: Result<Message, RequestError>,
    },
    /// A remote-control button event (40081).
    Button {
        /// `buttonID`.
        button_id: u32,
        /// What happened.
        event: crate::protocol::servo::ButtonEvent,
    },
    /// A frame that answers no pending request.
    Unsolicited(Message),
    /// Packet-log entry (only when [`SessionConfig::traffic`] is on).
    Traffic(Traffic),
}

#[derive(Debug)]
struct Pending {
    id: RequestId,
    message: Message,
    frame: Frame,
    bytes: Vec<u8>,
    retries_left: u8,
    attempts: u8,
}

#[derive(Debug)]
struct InFlight {
    request: Pending,
    /// Fixed when the request is written; moved later only once, by the
    /// response's own header (never by other bytes).
    deadline: Instant,
    /// Whether the response's header has set the deadline.
    sized: bool,
    /// The response's whole length, once its header came.
    expected: usize,
    /// Bytes received since the request was written.
    bytes: usize,
    /// Frames of this protocol among them: whole ones, and ones that began
    /// with the magic but came damaged (a bad checksum, cut short).
    frames: usize,
}

/// The session state machine (see the module documentation).
#[derive(Debug)]
pub struct Session {
    config: SessionConfig,
    decoder: FrameDecoder,
    queue: VecDeque<Pending>,
    in_flight: Option<InFlight>,
    outbox: VecDeque<Vec<u8>>,
    events: VecDeque<SessionEvent>,
    next_id: u64,
    last_input: Option<Instant>,
    /// Live move targets not sent yet, one per servo: the latest value wins.
    live: Vec<ServoMove>,
    /// When the bytes written so far will have crossed the line.
    line_free_at: Option<Instant>,
}

/// Whether a request only reads, so that sending it twice is harmless.
pub fn is_idempotent(message: &Message) -> bool {
    matches!(message.name(), name if name.starts_with("Query"))
}

impl Session {
    /// A session with the given timing.
    pub fn new(config: SessionConfig) -> Self {
        Self {
            config,
            decoder: FrameDecoder::new(),
            queue: VecDeque::new(),
            in_flight: None,
            outbox: VecDeque::new(),
            events: VecDeque::new(),
            next_id: 0,
            last_input: None,
            live: Vec::new(),
            line_free_at: None,
        }
    }

    fn wire_time(&self, len: usize) -> Duration {
        self.config
            .line_baud
            .map_or(Duration::ZERO, |baud| Duration::from_secs_f64(10.0 * len as f64 / f64::from(baud.max(1))))
    }

    fn write(&mut self, now: Instant, bytes: Vec<u8>) {
        let start = self.line_free_at.map_or(now, |free| free.max(now));
        self.line_free_at = Some(start + self.wire_time(bytes.len()));
        self.outbox.push_back(bytes);
    }

    /// Sets live move targets (20050). Moves are coalesced: at most one is on
    /// the line at a time, and while one is, newer targets replace older ones
    /// per servo, so the latest value always goes out and nothing stale does.
    pub fn set_live_moves(&mut self, now: Instant, moves: &[ServoMove]) {
        for servo_move in moves {
            match self.live.iter_mut().find(|pending| pending.servo_id == servo_move.servo_id) {
                Some(pending) => *pending = *servo_move,
                None => self.live.push(*servo_move),
            }
        }
        self.flush_live(now);
    }

    /// Drops live move targets not sent yet (STOP: nothing queued may follow).
    pub fn cancel_live_moves(&mut self) {
        self.live.clear();
    }

    fn flush_live(&mut self, now: Instant) {
        if self.live.is_empty() || self.line_free_at.is_some_and(|free| free > now) {
            return;
        }
        let message = Message::ExecuteActionRequest { moves: std::mem::take(&mut self.live) };
        // At most 255 servos exist, so a live move always encodes.
        if let Ok(frame) = message.to_frame()
            && let Ok(bytes) = frame.to_bytes()
        {
            self.write(now, bytes);
            self.log(|| Traffic::Sent { frame, message });
        }
    }

    /// Queues a request that expects a response; queries are retried on timeout.
    pub fn submit(&mut self, now: Instant, message: Message) -> Result<RequestId, EncodeError> {
        let retries = if is_idempotent(&message) { self.config.query_retries } else { 0 };
        self.submit_with_retries(now, message, retries)
    }

    /// Queues a request with an explicit retry count.
    pub fn submit_with_retries(
        &mut self,
        now: Instant,
        message: Message,
        retries: u8,
    ) -> Result<RequestId, EncodeError> {
        let frame = message.to_frame()?;
        let bytes = frame.to_bytes()?;
        self.next_id += 1;
        let id = RequestId(self.next_id);
        self.queue.push_back(Pending { id, message, frame, bytes, retries_left: retries, attempts: 0 });
        self.start_next(now);
        Ok(id)
    }

    /// Sends a message that has no response (20050, 20060, 10050) at once,
    /// ahead of queued requests.
    pub fn send(&mut self, now: Instant, message: Message) -> Result<(), EncodeError> {
        let frame = message.to_frame()?;
        self.write(now, frame.to_bytes()?);
        self.log(|| Traffic::Sent { frame, message });
        Ok(())
    }

    /// Requests waiting, including the one in flight.
    pub fn pending_requests(&self) -> usize {
        self.queue.len() + usize::from(self.in_flight.is_some())
    }

    fn log(&mut self, entry: impl FnOnce() -> Traffic) {
        if self.config.traffic {
            self.events.push_back(SessionEvent::Traffic(entry()));
        }
    }

    fn start_next(&mut self, now: Instant) {
        if self.in_flight.is_some() {
            return;
        }
        if let Some(request) = self.queue.pop_front() {
            self.transmit(now, request);
        }
    }

    fn transmit(&mut self, now: Instant, mut request: Pending) {
        request.attempts += 1;
        self.write(now, request.bytes.clone());
        let (frame, message) = (request.frame.clone(), request.message.clone());
        self.log(|| Traffic::Sent { frame, message });
        // The request must first cross the line (behind whatever was written before it).
        let on_the_line = self.line_free_at.map_or(now, |free| free.max(now));
        let deadline = on_the_line + self.config.response_timeout;
        self.in_flight = Some(InFlight { request, deadline, sized: false, expected: 0, bytes: 0, frames: 0 });
    }

    /// Bytes received from the board.
    pub fn handle_input(&mut self, now: Instant, bytes: &[u8]) {
        self.last_input = Some(now);
        if let Some(in_flight) = &mut self.in_flight {
            in_flight.bytes += bytes.len();
        }
        self.decoder.push(bytes);
        self.drain_decoder(now);
        self.size_response(now);
    }

    /// Once the header of the awaited response has arrived, the rest of it
    /// is known: the deadline becomes its wire time from now plus the timeout.
    fn size_response(&mut self, now: Instant) {
        let Some((packet_id, frame_len)) = self.decoder.pending_header() else { return };
        let pending = self.decoder.pending_len();
        let wire = self.wire_time(frame_len.saturating_sub(pending));
        let timeout = self.config.response_timeout;
        if let Some(in_flight) = &mut self.in_flight
            && !in_flight.sized
            && in_flight.request.frame.packet_id.checked_add(1) == Some(packet_id)
        {
            in_flight.sized = true;
            in_flight.expected = frame_len;
            in_flight.deadline = in_flight.deadline.max(now + wire + timeout);
        }
    }

    fn drain_decoder(&mut self, now: Instant) {
        while let Some(event) = self.decoder.poll() {
            match event {
                DecoderEvent::Frame(frame) => self.handle_frame(now, &frame),
                DecoderEvent::Skipped { bytes, reason } => {
                    if reason != SkipReason::Garbage
                        && let Some(in_flight) = &mut self.in_flight
                    {
                        // A frame of ours, damaged on the way: asking again may help.
                        in_flight.frames += 1;
                    }
                    self.log(|| Traffic::Skipped { bytes, reason });
                }
            }
        }
    }

    fn handle_frame(&mut self, now: Instant, frame: &Frame) {
        if let Some(in_flight) = &mut self.in_flight {
            in_flight.frames += 1;
        }
        let decoded = Message::from_frame(frame);
        if self.config.traffic {
            self.events
                .push_back(SessionEvent::Traffic(Traffic::Received { frame: frame.clone(), message: decoded.clone() }));
        }
        let answers_in_flight =
            self.in_flight.as_ref().is_some_and(|f| f.request.frame.packet_id.checked_add(1) == Some(frame.packet_id));
        if answers_in_flight {
            let Some(InFlight { request, .. }) = self.in_flight.take() else {
                return;
            };
            match decoded {
                Ok(message) => self.events.push_back(SessionEvent::Response { id: request.id, result: Ok(message) }),
                Err(error) => self.retry_or_fail(now, request, |request| RequestError::Malformed { request, error }),
            }
            self.start_next(now);
            return;
        }
        match decoded {
            Ok(Message::ButtonEventResponse { button_id, event }) => {
                self.events.push_back(SessionEvent::Button { button_id, event });
            }
            Ok(message) => self.events.push_back(SessionEvent::Unsolicited(message)),
            // Already in the packet log; nothing waits for it.
            Err(_) => {}
        }
    }

    fn retry_or_fail(&mut self, now: Instant, mut request: Pending, error: impl FnOnce(&'static str) -> RequestError) {
        if request.retries_left > 0 {
            request.retries_left -= 1;
            self.transmit(now, request);
        } else {
            let error = error(request.message.name());
            self.events.push_back(SessionEvent::Response { id: request.id, result: Err(error) });
        }
    }

    /// Called when `now` has reached [`Session::poll_timeout`].
    pub fn handle_timeout(&mut self, now: Instant) {
        self.flush_live(now);
        if self.decoder.pending_len() > 0 && self.last_input.is_some_and(|at| now >= at + self.config.idle_gap) {
            self.decoder.abandon_partial();
            self.drain_decoder(now);
        }
        if self.in_flight.as_ref().is_some_and(|f| now >= f.deadline) {
            let Some(InFlight { request, bytes, frames, sized, expected, .. }) = self.in_flight.take() else {
                return;
            };
            let timeout_ms = u64::try_from(self.config.response_timeout.as_millis()).unwrap_or(u64::MAX);
            if sized {
                // Its header came, the rest is late (or was given up as cut short): a slow
                // or lossy line, not another protocol; asking again may get it whole.
                let attempts = request.attempts;
                let received = bytes.min(expected);
                self.retry_or_fail(now, request, |request| RequestError::Incomplete {
                    request,
                    received,
                    expected,
                    attempts,
                    timeout_ms,
                });
            } else if bytes > 0 && frames == 0 {
                // Something answers, in another protocol: asking again will not help.
                let error = RequestError::NotThisProtocol { request: request.message.name(), bytes };
                self.events.push_back(SessionEvent::Response { id: request.id, result: Err(error) });
            } else {
                let attempts = request.attempts;
                self.retry_or_fail(now, request, |request| RequestError::Timeout { request, attempts, timeout_ms });
            }
            self.start_next(now);
        }
    }

    /// The link is gone: every pending request fails with `reason`.
    pub fn handle_disconnect(&mut self, reason: &str) {
        let pending = self.in_flight.take().map(|f| f.request).into_iter().chain(self.queue.drain(..));
        let failed: Vec<SessionEvent> = pending
            .map(|request| SessionEvent::Response {
                id: request.id,
                result: Err(RequestError::Disconnected { reason: reason.to_string() }),
            })
            .collect();
        self.events.extend(failed);
        self.outbox.clear();
        self.live.clear();
    }

    /// Bytes to write now.
    pub fn poll_transmit(&mut self) -> Option<Vec<u8>> {
        self.outbox.pop_front()
    }

    /// The next event.
    pub fn poll_event(&mut self) -> Option<SessionEvent> {
        self.events.pop_front()
    }

    /// When [`Session::handle_timeout`] is next needed.
    pub fn poll_timeout(&self) -> Option<Instant> {
        let response = self.in_flight.as_ref().map(|f| f.deadline);
        let idle =
            (self.decoder.pending_len() > 0).then(|| self.last_input.map(|at| at + self.config.idle_gap)).flatten();
        let live = if self.live.is_empty() { None } else { self.line_free_at };
        [response, idle, live].into_iter().flatten().min()
    }
}

#[cfg(test)]
mod tests {
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
        session
            .set_live_moves(t0 + Duration::from_millis(14), &[ServoMove { servo_id: 2, degree: -5, interval_10ms: 0 }]);
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
}
