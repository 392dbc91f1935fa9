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
    /// STOP was pressed while it still waited to be sent: it was not.
    #[error("{request}: STOP was pressed before it was sent: it was not sent")]
    Stopped {
        /// The request's name.
        request: &'static str,
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
    /// Whether a frame of this protocol (its header and length seen) was
    /// arriving: a long one still coming at a slow baud is not garbage.
    in_frame: bool,
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

    /// STOP: drops every live move target and every request still queued
    /// (a macro or an action queued behind a slow answer would move the
    /// servos after it); each dropped request is answered "stopped". The
    /// request on the wire is the board's to answer.
    pub fn cancel_queued(&mut self) {
        self.live.clear();
        let stopped: Vec<SessionEvent> = self
            .queue
            .drain(..)
            .map(|request| SessionEvent::Response {
                id: request.id,
                result: Err(RequestError::Stopped { request: request.message.name() }),
            })
            .collect();
        self.events.extend(stopped);
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

    #[cfg(test)]
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
        // The request must first cross the line (behind whatever was written
        // before it), and the board answers once a frame it is still sending ends.
        let on_the_line = self.line_free_at.map_or(now, |free| free.max(now));
        let incoming = self.decoder.pending_header().map_or(Duration::ZERO, |(_, frame_len)| {
            self.wire_time(frame_len.saturating_sub(self.decoder.pending_len()))
        });
        let deadline = on_the_line + incoming + self.config.response_timeout;
        let in_frame = self.decoder.pending_header().is_some();
        self.in_flight = Some(InFlight { request, deadline, sized: false, expected: 0, bytes: 0, frames: 0, in_frame });
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
        if let Some(in_flight) = &mut self.in_flight {
            in_flight.in_frame = true;
        }
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
            let Some(InFlight { request, bytes, frames, sized, expected, in_frame, .. }) = self.in_flight.take() else {
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
            } else if bytes > 0 && frames == 0 && !in_frame {
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
mod tests;
