//! The servo board over a link: the driver the I/O thread runs, the owner's
//! handle, and a cloneable [`Requester`] for blocking request/response calls
//! from worker threads.

use std::collections::HashMap;
use std::io;
use std::time::Instant;

use crossbeam_channel::{Receiver, Sender};

use super::session::{RequestError, RequestId, Session, SessionConfig, SessionEvent, Traffic};
use crate::link::{self, Connection, Driver, LineSettings, LinkError, LinkEvent, LinkHandle, PortName, Waker};
use crate::project::Family;
use crate::protocol::servo::{ButtonEvent, Message};

/// Where a request's outcome goes.
pub type Reply = Sender<Result<Message, RequestError>>;

/// What the owner asks of the board driver.
#[derive(Debug)]
pub enum ServoCommand {
    /// Send a request and deliver its response (or error) to `reply`.
    Request {
        /// The request.
        message: Message,
        /// Where the outcome goes.
        reply: Reply,
    },
    /// Send a message that has no response (e.g. 20060).
    Send {
        /// The message.
        message: Message,
    },
    /// Drop pending live moves, then send `message` at once (the STOP path).
    Stop {
        /// What stops the servos (e.g. 20030 for all servos).
        message: Message,
    },
    /// Live move targets (20050), coalesced: the latest value per servo wins.
    LiveMove {
        /// The targets.
        moves: Vec<crate::protocol::servo::ServoMove>,
    },
}

/// What the board driver reports to its owner (responses go to each request's reply).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ServoEvent {
    /// A remote-control button event.
    Button {
        /// `buttonID`.
        button_id: u32,
        /// What happened.
        event: ButtonEvent,
    },
    /// A frame that answers no request.
    Unsolicited(Message),
    /// A packet-log entry.
    Traffic(Traffic),
    /// A message could not be sent.
    SendFailed(crate::protocol::servo::EncodeError),
}

/// The driver the I/O thread runs for a servo board.
#[derive(Debug)]
pub struct ServoDriver {
    session: Session,
    replies: HashMap<RequestId, Reply>,
    events: std::collections::VecDeque<ServoEvent>,
}

impl ServoDriver {
    /// A driver with the given session timing.
    pub fn new(config: SessionConfig) -> Self {
        Self { session: Session::new(config), replies: HashMap::new(), events: std::collections::VecDeque::new() }
    }

    fn drain_session(&mut self) {
        while let Some(event) = self.session.poll_event() {
            match event {
                SessionEvent::Response { id, result } => {
                    if let Some(reply) = self.replies.remove(&id) {
                        // The asker may have given up (cancelled); that is fine.
                        let _ = reply.send(result);
                    }
                }
                SessionEvent::Button { button_id, event } => {
                    self.events.push_back(ServoEvent::Button { button_id, event });
                }
                SessionEvent::Unsolicited(message) => {
                    self.events.push_back(ServoEvent::Unsolicited(message));
                }
                SessionEvent::Traffic(entry) => self.events.push_back(ServoEvent::Traffic(entry)),
            }
        }
    }
}

impl Driver for ServoDriver {
    type Command = ServoCommand;
    type Event = ServoEvent;

    /// STOP goes out even when the owner closes right after sending it.
    fn is_last_word(&self, command: &ServoCommand) -> bool {
        matches!(command, ServoCommand::Stop { .. })
    }

    fn handle_command(&mut self, now: Instant, command: ServoCommand) {
        match command {
            ServoCommand::Request { message, reply } => match self.session.submit(now, message) {
                Ok(id) => {
                    self.replies.insert(id, reply);
                }
                Err(error) => {
                    let _ = reply.send(Err(RequestError::Encode(error)));
                }
            },
            ServoCommand::Send { message } => {
                if let Err(error) = self.session.send(now, message) {
                    self.events.push_back(ServoEvent::SendFailed(error));
                }
            }
            ServoCommand::LiveMove { moves } => self.session.set_live_moves(now, &moves),
            ServoCommand::Stop { message } => {
                self.session.cancel_queued();
                if let Err(error) = self.session.send(now, message) {
                    self.events.push_back(ServoEvent::SendFailed(error));
                }
            }
        }
        self.drain_session();
    }

    fn handle_input(&mut self, now: Instant, bytes: &[u8]) {
        self.session.handle_input(now, bytes);
        self.drain_session();
    }

    fn handle_timeout(&mut self, now: Instant) {
        self.session.handle_timeout(now);
        self.drain_session();
    }

    fn handle_disconnect(&mut self, reason: &str) {
        self.session.handle_disconnect(reason);
        self.drain_session();
    }

    fn poll_transmit(&mut self, _now: Instant) -> Option<Vec<u8>> {
        self.session.poll_transmit()
    }

    fn poll_event(&mut self) -> Option<ServoEvent> {
        self.events.pop_front()
    }

    fn poll_timeout(&self) -> Option<Instant> {
        self.session.poll_timeout()
    }
}

/// A connected servo board. Dropping it closes the link.
#[derive(Debug)]
pub struct ServoBoard {
    link: LinkHandle<ServoCommand, ServoEvent>,
}

impl ServoBoard {
    /// Opens `port` at `baud` with the servo family's line settings and starts
    /// the I/O thread. Where the session times bytes on the line, it times
    /// them at this `baud` (a request at 19200 baud takes six times its time
    /// at 115200: its response deadline must count it).
    pub fn connect(port: &PortName, baud: u32, config: SessionConfig, waker: Waker) -> Result<Self, LinkError> {
        let config = SessionConfig { line_baud: config.line_baud.map(|_| baud), ..config };
        let settings = LineSettings { baud, ..crate::device::line_settings(Family::Servo) };
        let connection = link::open(port, &settings)?;
        let description = connection.description.clone();
        Self::over(connection, config, waker).map_err(|source| LinkError::Open { port: description, source })
    }

    /// Starts the I/O thread over an already open connection.
    pub fn over(connection: Connection, config: SessionConfig, waker: Waker) -> io::Result<Self> {
        Ok(Self { link: link::spawn(connection, ServoDriver::new(config), waker)? })
    }

    /// A handle for requests, cloneable into worker threads.
    pub fn requester(&self) -> Requester {
        Requester { commands: self.link.commands() }
    }

    /// Button events, unsolicited frames, the packet log, and the disconnect.
    pub fn events(&self) -> &Receiver<LinkEvent<ServoEvent>> {
        self.link.events()
    }

    /// What the board is connected through.
    pub fn description(&self) -> &str {
        self.link.description()
    }
}

/// Sends requests to a board and waits for their responses.
#[derive(Clone, Debug)]
pub struct Requester {
    commands: Sender<ServoCommand>,
}

impl Requester {
    /// Sends `message` and waits for its response. The session bounds the
    /// wait (timeouts, retries); a lost link ends it with `Disconnected`.
    pub fn request(&self, message: Message) -> Result<Message, RequestError> {
        self.request_async(message)?.recv().unwrap_or_else(|_| Err(lost()))
    }

    /// Sends `message`; its outcome arrives on the returned receiver.
    pub fn request_async(&self, message: Message) -> Result<Receiver<Result<Message, RequestError>>, RequestError> {
        let (reply, outcome) = crossbeam_channel::bounded(1);
        self.commands.send(ServoCommand::Request { message, reply }).map_err(|_| lost())?;
        Ok(outcome)
    }

    /// Sends a message that has no response.
    pub fn send(&self, message: Message) -> Result<(), RequestError> {
        self.commands.send(ServoCommand::Send { message }).map_err(|_| lost())
    }

    /// Drops pending live moves and sends `message` at once, ahead of queued
    /// requests; its response, if any, arrives as an unsolicited event.
    pub fn stop(&self, message: Message) -> Result<(), RequestError> {
        self.commands.send(ServoCommand::Stop { message }).map_err(|_| lost())
    }

    /// Sets live move targets; the session coalesces them: at most one move is
    /// on the line, and the latest value per servo wins.
    pub fn live_move(&self, moves: Vec<crate::protocol::servo::ServoMove>) -> Result<(), RequestError> {
        self.commands.send(ServoCommand::LiveMove { moves }).map_err(|_| lost())
    }
}

fn lost() -> RequestError {
    RequestError::Disconnected { reason: "the link is closed".into() }
}

#[cfg(test)]
mod tests {

    use super::*;
    use crate::protocol::servo::{ALL_SERVOS, ServoSwitches};

    /// The owner sends STOP and closes the link at once (the command line's
    /// Ctrl-C, a show closing): whichever the I/O thread sees first, the stop
    /// still goes out. (A coin toss each time: twenty in a row.)
    #[test]
    fn a_stop_sent_just_before_the_close_still_goes_out() {
        let stop =
            Message::SetServoParameterRequest(ServoSwitches { servo_id: ALL_SERVOS, is_start: false, is_hold: true });
        let expected = stop.encode().unwrap();
        for _ in 0..20 {
            let (mut board, ours) = Connection::memory_pair();
            let link = link::spawn(ours, ServoDriver::new(SessionConfig::default()), link::no_waker()).unwrap();
            link.commands().send(ServoCommand::Stop { message: stop.clone() }).unwrap();
            link.close();
            let mut heard = Vec::new();
            board.reader_mut().read_to_end(&mut heard).unwrap();
            assert!(heard.windows(expected.len()).any(|sent| sent == expected), "{heard:02x?}");
        }
    }
}
