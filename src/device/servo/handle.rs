//! The servo family's non-blocking handle: commands in, typed notices out.
//! It keeps the board's status up to date (project id, battery, memory, servo
//! states) with asynchronous requests whose answers are picked up by
//! [`ServoHandle::pump`], owns the STOP frame, and turns traffic into
//! family-neutral packet-log entries. Nothing here ever blocks its caller.

use std::collections::BTreeMap;
use std::time::{Duration, Instant};

use crossbeam_channel::Receiver;

use super::client::{ServoBoard, ServoEvent};
use super::session::{RequestError, SessionConfig};
use super::{Requester, log};
use crate::device::LogEntry;
use crate::link::{Connection, DisconnectReason, LinkEvent, Waker};
use crate::protocol::servo::{ALL_SERVOS, ButtonEvent, Message, ServoMove, ServoStatus, ServoSwitches};

/// How often status (project id, battery, memory) is refreshed.
const STATUS_EVERY: Duration = Duration::from_secs(2);
/// How often angles are read back while polling is on.
const ANGLES_EVERY: Duration = Duration::from_millis(100);

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Query {
    RunMacro,
    Subscribe,
    ProjectId,
    Battery,
    Memory,
    Angles,
    Switches,
}

/// What a servo board reports to the owner of its handle.
#[derive(Clone, Debug, PartialEq)]
pub enum ServoNotice {
    /// Something could not be sent; the text says why.
    SendFailed(crate::protocol::servo::EncodeError),
    /// A request failed.
    RequestFailed(RequestError),
    /// The board refused to run a macro (it does not store it).
    MacroRefused,
    /// The link ended.
    Disconnected(DisconnectReason),
    /// A remote button event.
    Button {
        /// `buttonID`.
        button_id: u32,
        /// What happened.
        event: ButtonEvent,
    },
    /// A packet-log entry (when the session logs traffic).
    Log(LogEntry),
}

/// A connected servo board, driven without blocking. Dropping it closes the link.
pub struct ServoHandle {
    board: ServoBoard,
    requester: Requester,
    /// The board's project id, once read.
    pub project_id: Option<i32>,
    /// Battery in ‰, once read.
    pub battery_permil: Option<i16>,
    /// Free and total memory, once read.
    pub memory: Option<(i32, Option<i32>)>,
    /// The latest servo states read back.
    pub servos: BTreeMap<u8, ServoStatus>,
    /// When they were read.
    pub servos_read_at: Option<Instant>,
    /// Servos were stopped with STOP and not resumed.
    pub stopped: bool,
    opened_at: Instant,
    inflight: Vec<(Query, Receiver<Result<Message, RequestError>>)>,
    next_status_at: Instant,
    next_angles_at: Instant,
}

impl std::fmt::Debug for ServoHandle {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ServoHandle").field("board", &self.board).finish_non_exhaustive()
    }
}

impl ServoHandle {
    /// Starts the I/O thread over an open connection, logging traffic.
    pub fn over(connection: Connection, line_baud: Option<u32>, waker: Waker) -> std::io::Result<Self> {
        let config = SessionConfig { line_baud, traffic: true, ..SessionConfig::default() };
        let board = ServoBoard::over(connection, config, waker)?;
        let requester = board.requester();
        let now = Instant::now();
        Ok(Self {
            board,
            requester,
            project_id: None,
            battery_permil: None,
            memory: None,
            servos: BTreeMap::new(),
            servos_read_at: None,
            stopped: false,
            opened_at: now,
            inflight: Vec::new(),
            next_status_at: now,
            next_angles_at: now,
        })
    }

    /// A requester for worker threads (upload, read back).
    pub fn requester(&self) -> Requester {
        self.requester.clone()
    }

    fn ask(&mut self, query: Query, message: Message) {
        if self.inflight.iter().any(|(pending, _)| *pending == query) {
            return;
        }
        if let Ok(reply) = self.requester.request_async(message) {
            self.inflight.push((query, reply));
        }
    }

    /// Picks up answers and events, and asks for fresh status when due.
    /// Returns what the user should see; `Disconnected` means drop this link.
    pub fn pump(&mut self, now: Instant, polling: bool) -> Vec<ServoNotice> {
        let mut notices = Vec::new();
        for event in self.board.events().try_iter() {
            match event {
                LinkEvent::Driver(ServoEvent::Button { button_id, event }) => {
                    notices.push(ServoNotice::Button { button_id, event });
                }
                LinkEvent::Driver(ServoEvent::SendFailed(error)) => {
                    notices.push(ServoNotice::SendFailed(error));
                }
                LinkEvent::Driver(ServoEvent::Traffic(traffic)) => {
                    let seconds = now.saturating_duration_since(self.opened_at).as_secs_f64();
                    notices.push(ServoNotice::Log(log::log_entry(seconds, &traffic)));
                }
                LinkEvent::Driver(ServoEvent::Unsolicited(_)) => {}
                LinkEvent::Disconnected { reason } => {
                    notices.push(ServoNotice::Disconnected(reason));
                }
            }
        }
        let mut still = Vec::new();
        for (query, reply) in std::mem::take(&mut self.inflight) {
            match reply.try_recv() {
                Ok(Ok(Message::ExecuteMacroResponse { ok: false })) => {
                    notices.push(ServoNotice::MacroRefused);
                }
                Ok(Ok(message)) => self.absorb(message),
                Ok(Err(error)) => {
                    if !matches!(error, RequestError::Disconnected { .. }) {
                        notices.push(ServoNotice::RequestFailed(error));
                    }
                }
                Err(crossbeam_channel::TryRecvError::Empty) => still.push((query, reply)),
                Err(crossbeam_channel::TryRecvError::Disconnected) => {}
            }
        }
        self.inflight = still;
        if now >= self.next_status_at {
            self.next_status_at = now + STATUS_EVERY;
            self.ask(Query::ProjectId, Message::QueryProjectIdRequest);
            self.ask(Query::Battery, Message::QueryRemainPowerRequest);
            self.ask(Query::Memory, Message::QueryMemorySizeRequest);
            // Torque switches show once the servos' states are known.
            self.ask(Query::Angles, Message::QueryServoRequest { servo_id: ALL_SERVOS });
        }
        if polling && now >= self.next_angles_at {
            self.next_angles_at = now + ANGLES_EVERY;
            self.ask(Query::Angles, Message::QueryServoRequest { servo_id: ALL_SERVOS });
        }
        notices
    }

    /// When the link next needs a frame to refresh its status.
    pub fn next_refresh(&self, polling: bool) -> Instant {
        if polling { self.next_angles_at.min(self.next_status_at) } else { self.next_status_at }
    }

    fn absorb(&mut self, message: Message) {
        match message {
            Message::QueryProjectIdResponse { project_id } => self.project_id = Some(project_id),
            Message::QueryRemainPowerResponse { permil } => self.battery_permil = Some(permil),
            Message::QueryMemorySizeResponse { free_bytes, total_bytes } => {
                self.memory = Some((free_bytes, total_bytes));
            }
            Message::QueryServoResponse { servos } => {
                self.servos = servos.into_iter().map(|servo| (servo.servo_id, servo)).collect();
                self.servos_read_at = Some(Instant::now());
            }
            Message::SetServoParameterResponse(switches) => {
                for servo in self
                    .servos
                    .values_mut()
                    .filter(|s| switches.servo_id == ALL_SERVOS || s.servo_id == switches.servo_id)
                {
                    servo.is_hold = switches.is_hold;
                    servo.is_start = switches.is_start;
                }
            }
            _ => {}
        }
    }

    /// Sends a live move (coalesced by the session).
    pub fn live_move(&self, moves: Vec<ServoMove>) -> Result<(), RequestError> {
        self.requester.live_move(moves)
    }

    /// STOP: drops queued moves and stops every servo where it is, holding
    /// torque, ahead of any queued request.
    pub fn stop(&mut self) -> Result<(), RequestError> {
        self.stopped = true;
        let all = ServoSwitches { servo_id: ALL_SERVOS, is_start: false, is_hold: true };
        self.requester.stop(Message::SetServoParameterRequest(all))
    }

    /// Lets servos move again after a STOP.
    pub fn resume(&mut self) {
        self.stopped = false;
        let all = ServoSwitches { servo_id: ALL_SERVOS, is_start: true, is_hold: true };
        self.ask(Query::Switches, Message::SetServoParameterRequest(all));
    }

    /// Moves servos now, each over its own interval (an action played live).
    pub fn move_now(&self, moves: Vec<ServoMove>) -> Result<(), super::OpError> {
        self.requester.move_servos(moves)
    }

    /// Runs a stored macro; a refusal comes back as an error notice.
    pub fn run_macro(&mut self, macro_id: i32) {
        if let Ok(reply) = self.requester.request_async(Message::ExecuteMacroRequest { macro_id }) {
            self.inflight.push((Query::RunMacro, reply));
        }
    }

    /// Starts or stops the board's button events.
    pub fn subscribe_buttons(&mut self, subscribe: bool) {
        if let Ok(reply) = self.requester.request_async(Message::SubscribeButtonEventRequest { subscribe }) {
            self.inflight.push((Query::Subscribe, reply));
        }
    }

    /// Holds or releases one servo's torque.
    pub fn set_hold(&mut self, servo_id: u8, hold: bool) {
        let switches = ServoSwitches { servo_id, is_start: !self.stopped, is_hold: hold };
        if let Some(servo) = self.servos.get_mut(&servo_id) {
            servo.is_hold = hold;
        }
        // Not de-duplicated: each toggle must reach the board.
        if let Ok(reply) = self.requester.request_async(Message::SetServoParameterRequest(switches)) {
            self.inflight.push((Query::Switches, reply));
        }
    }
}
