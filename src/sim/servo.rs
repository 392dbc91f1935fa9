//! The emulated servo board: the server side of the board protocol, reusing
//! the codec. A sans-IO state machine (it implements [`Driver`]), so the same
//! code runs in-process for the demo, behind a pseudo-terminal, on TCP, and
//! stepped by tests with fake time.

use std::collections::VecDeque;
use std::time::{Duration, Instant};

use super::faults::{Faults, hits};
use crate::link::Driver;
use crate::protocol::servo::{
    ALL_SERVOS, AngleUnit, ButtonEvent, DecoderEvent, FrameDecoder, ListEntry, Message, ServoImage, ServoMove,
    ServoStatus, ServoSwitches, TransmissionMode,
};

/// Bytes a throttled line hands over at once (a USB-serial adapter's packet).
const TX_PIECE: usize = 64;

/// How the emulated board behaves.
#[derive(Clone, Debug)]
pub struct SimConfig {
    /// Total memory for stored data, in bytes.
    pub total_memory_bytes: i32,
    /// Reported battery, in ‰.
    pub battery_permil: i16,
    /// Servos physically attached (besides those with stored parameters).
    pub attached_servos: Vec<u8>,
    /// Line rate to emulate in both directions (`None` = as fast as the link goes).
    pub baud: Option<u32>,
    /// Time the board takes between a request's last byte and its response.
    pub turnaround: Duration,
    /// Faults to inject.
    pub faults: Faults,
}

impl Default for SimConfig {
    fn default() -> Self {
        Self {
            total_memory_bytes: 256 * 1024,
            battery_permil: 870,
            attached_servos: (1..=16).collect(),
            baud: None,
            turnaround: Duration::ZERO,
            faults: Faults::default(),
        }
    }
}

/// Commands to the emulated board from its owner (a test, or the demo's UI).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum SimCommand {
    /// A button on the remote: sent as 40081 if a client has subscribed.
    Button {
        /// `buttonID`.
        button_id: u32,
        /// What happened.
        event: ButtonEvent,
    },
    /// Someone turns a released servo by hand (teaching with torque off).
    TurnByHand {
        /// The servo.
        servo_id: u8,
        /// Where it ends up.
        angle: i16,
    },
}

/// What the emulated board reports to its owner.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum SimEvent {
    /// A request was handled (after any fault).
    Handled(Message),
    /// A macro began: when each of its steps starts on the board's clock (a
    /// show's sound is measured against these).
    MacroSteps {
        /// The macro.
        macro_id: i32,
        /// Each step's start, in order.
        steps: Vec<Instant>,
    },
}

/// One servo's live state: a linear move from `from` to `to` over `start..end`.
#[derive(Clone, Debug)]
struct ServoState {
    servo_id: u8,
    from: i16,
    to: i16,
    start: Instant,
    end: Instant,
    switches: ServoSwitches,
    unit: AngleUnit,
}

impl ServoState {
    fn angle(&self, now: Instant) -> i16 {
        if now >= self.end || self.end <= self.start {
            return self.to;
        }
        let total = (self.end - self.start).as_secs_f64();
        let done = now.saturating_duration_since(self.start).as_secs_f64();
        let angle = f64::from(self.from) + (f64::from(self.to) - f64::from(self.from)) * done / total;
        // Between two i16 values, so it fits.
        #[allow(clippy::cast_possible_truncation)]
        let angle = angle.round() as i16;
        angle
    }
}

/// The emulated board (see the module documentation).
#[derive(Debug)]
pub struct ServoSim {
    config: SimConfig,
    image: ServoImage,
    servos: Vec<ServoState>,
    mode: TransmissionMode,
    subscribed: bool,
    decoder: FrameDecoder,
    /// Received bytes not yet "arrived" at the emulated line rate.
    inbound: VecDeque<(Instant, Vec<u8>)>,
    /// Bytes to send, each at its time.
    outbound: VecDeque<(Instant, Vec<u8>)>,
    rx_line_free: Option<Instant>,
    tx_line_free: Option<Instant>,
    /// Moves scheduled by running macros.
    schedule: Vec<(Instant, Vec<ServoMove>)>,
    events: VecDeque<SimEvent>,
    frames_received: u64,
    responses: u64,
    closed: bool,
}

impl ServoSim {
    /// A board with the given behaviour, storing `image`.
    pub fn new(config: SimConfig, image: ServoImage) -> Self {
        let now = Instant::now();
        let mut ids: Vec<u8> = config.attached_servos.clone();
        ids.extend(image.servos.iter().map(|servo| servo.servo_id));
        ids.sort_unstable();
        ids.dedup();
        let servos = ids
            .into_iter()
            .filter(|id| *id != ALL_SERVOS)
            .map(|servo_id| ServoState {
                servo_id,
                from: 0,
                to: 0,
                start: now,
                end: now,
                switches: ServoSwitches { servo_id, is_start: true, is_hold: true },
                unit: AngleUnit::Degree,
            })
            .collect();
        Self {
            config,
            image,
            servos,
            mode: TransmissionMode::New,
            subscribed: false,
            decoder: FrameDecoder::new(),
            inbound: VecDeque::new(),
            outbound: VecDeque::new(),
            rx_line_free: None,
            tx_line_free: None,
            schedule: Vec::new(),
            events: VecDeque::new(),
            frames_received: 0,
            responses: 0,
            closed: false,
        }
    }

    /// What the board stores now.
    pub fn image(&self) -> &ServoImage {
        &self.image
    }

    /// A servo's angle at `now`.
    pub fn angle(&self, servo_id: u8, now: Instant) -> Option<i16> {
        self.servos.iter().find(|s| s.servo_id == servo_id).map(|s| s.angle(now))
    }

    fn byte_time(&self) -> Option<Duration> {
        // 8N1: ten bits per byte.
        self.config.baud.map(|baud| Duration::from_secs_f64(10.0 / f64::from(baud.max(1))))
    }

    fn wire_time(&self, len: usize) -> Duration {
        self.byte_time().map_or(Duration::ZERO, |byte| byte * u32::try_from(len).unwrap_or(u32::MAX))
    }

    fn used_bytes(&self) -> i32 {
        i32::try_from(self.image.footprint_bytes().unwrap_or(usize::MAX)).unwrap_or(i32::MAX)
    }

    fn fits_after(&self, change: impl FnOnce(&mut ServoImage)) -> bool {
        let mut trial = self.image.clone();
        change(&mut trial);
        trial.footprint_bytes().is_ok_and(|bytes| bytes <= usize::try_from(self.config.total_memory_bytes).unwrap_or(0))
    }

    /// Queues a response frame, with any faults, to go out after the turnaround.
    fn respond(&mut self, now: Instant, message: &Message) {
        self.responses += 1;
        let count = self.responses;
        let faults = &self.config.faults;
        let mut burst: Vec<u8> = Vec::new();
        if hits(faults.garbage_every, count) {
            // Noise, including a partial magic that must not fool the client.
            burst.extend_from_slice(&[0x00, 0xff, 0x13, 0x4c, 0x05, 0x42, 0x13]);
        }
        if self.subscribed && hits(faults.button_every, count) {
            let event = Message::ButtonEventResponse {
                button_id: 0x8000_0000 | u32::try_from(count).unwrap_or(0),
                event: ButtonEvent::Press,
            };
            burst.extend(event.encode().unwrap_or_default());
        }
        if !hits(faults.drop_every, count) {
            let mut bytes = message.encode().unwrap_or_default();
            if hits(faults.corrupt_every, count)
                && let Some(last) = bytes.last_mut()
            {
                *last = last.wrapping_add(1);
            }
            burst.extend(bytes);
        }
        if !burst.is_empty() {
            self.transmit(now + self.config.turnaround, burst);
        }
    }

    /// Sends `bytes` as a UART does: each piece leaves once its wire time has
    /// passed (a long response trickles in, it does not arrive all at once at
    /// the end), in pieces of a USB-serial adapter's packet size.
    fn transmit(&mut self, ready: Instant, bytes: Vec<u8>) {
        let mut at = self.tx_line_free.map_or(ready, |free| free.max(ready));
        if self.config.baud.is_none() {
            self.outbound.push_back((at, bytes));
            self.tx_line_free = Some(at);
            return;
        }
        for piece in bytes.chunks(TX_PIECE) {
            at += self.wire_time(piece.len());
            self.outbound.push_back((at, piece.to_vec()));
        }
        self.tx_line_free = Some(at);
    }

    fn handle_message(&mut self, now: Instant, message: Message) {
        // Each group answers the messages it knows: `Some(response)` (a response or none), else `None`.
        let response = self
            .board_answer(now, &message)
            .or_else(|| self.store_answer(now, &message))
            .or_else(|| self.remote_answer(&message))
            // Test data and anything a board would not answer: discarded.
            .flatten();
        if let Some(response) = response {
            self.respond(now, &response);
        }
        self.events.push_back(SimEvent::Handled(message));
    }

    /// The line, memory, power, the servos and live moves (1xxxx, 20xxx).
    fn board_answer(&mut self, now: Instant, message: &Message) -> Option<Option<Message>> {
        use Message as M;
        let image = &mut self.image;
        Some(match message {
            M::TransmissionModeSettingRequest { mode } => {
                self.mode = *mode;
                Some(M::TransmissionModeSettingResponse { mode: self.mode })
            }
            M::ClearAllDataRequest => {
                *image = ServoImage::default();
                Some(M::ClearAllDataResponse { ok: true })
            }
            M::QueryMemorySizeRequest => Some(M::QueryMemorySizeResponse {
                free_bytes: self.config.total_memory_bytes.saturating_sub(self.used_bytes()),
                total_bytes: Some(self.config.total_memory_bytes),
            }),
            M::QueryRemainPowerRequest => Some(M::QueryRemainPowerResponse { permil: self.config.battery_permil }),
            M::QueryServoListRequest => {
                Some(M::QueryServoListResponse { servo_ids: self.servos.iter().map(|s| s.servo_id).collect() })
            }
            M::QueryServoRequest { servo_id } => Some(M::QueryServoResponse {
                servos: self
                    .servos
                    .iter()
                    .filter(|s| *servo_id == ALL_SERVOS || s.servo_id == *servo_id)
                    .map(|s| ServoStatus {
                        servo_id: s.servo_id,
                        angle: s.angle(now),
                        current_adc: if s.angle(now) == s.to { 12 } else { 180 },
                        temperature_adc: 310,
                        servo_type: 1,
                        is_start: s.switches.is_start,
                        is_hold: s.switches.is_hold,
                    })
                    .collect(),
            }),
            M::SetServoParameterRequest(switches) => {
                for state in self
                    .servos
                    .iter_mut()
                    .filter(|s| switches.servo_id == ALL_SERVOS || s.servo_id == switches.servo_id)
                {
                    let angle = state.angle(now);
                    state.switches = ServoSwitches { servo_id: state.servo_id, ..*switches };
                    if !switches.is_start || !switches.is_hold {
                        // Stopped or released: the servo stays where it is.
                        state.from = angle;
                        state.to = angle;
                        state.end = now;
                    }
                }
                Some(M::SetServoParameterResponse(*switches))
            }
            M::SetAngleUnitRequest { servo_id, unit } => {
                for state in self.servos.iter_mut().filter(|s| *servo_id == ALL_SERVOS || s.servo_id == *servo_id) {
                    state.unit = *unit;
                }
                Some(M::SetAngleUnitResponse { servo_id: *servo_id, unit: *unit })
            }
            M::ExecuteActionRequest { moves } => {
                self.start_moves(now, moves, 100);
                None
            }
            M::ExecuteActionExRequest { action_id } => {
                if let Some(action) = image.actions.iter().find(|a| a.action_id == *action_id).cloned() {
                    self.start_moves(now, &action.steps, 100);
                }
                None
            }
            _ => return None,
        })
    }

    /// Actions, macros, servo parameters and the project id (30xxx).
    fn store_answer(&mut self, now: Instant, message: &Message) -> Option<Option<Message>> {
        use Message as M;
        let image = &mut self.image;
        Some(match message {
            M::QueryActionListRequest => Some(M::QueryActionListResponse {
                actions: image
                    .actions
                    .iter()
                    .map(|a| ListEntry { id: a.action_id, caption: a.caption.clone() })
                    .collect(),
            }),
            M::QueryActionRequest { action_id } => Some(M::QueryActionResponse {
                action: image.actions.iter().find(|a| a.action_id == *action_id).cloned(),
            }),
            M::AddActionRequest(record) => {
                Some(M::AddActionResponse { ok: self.add(record, |a| a.action_id, |image| &mut image.actions) })
            }
            M::DeleteActionRequest { action_id } => {
                let before = image.actions.len();
                image.actions.retain(|a| a.action_id != *action_id);
                Some(M::DeleteActionResponse { ok: image.actions.len() < before })
            }
            M::QueryMacroListRequest => Some(M::QueryMacroListResponse {
                macros: image.macros.iter().map(|m| ListEntry { id: m.macro_id, caption: m.caption.clone() }).collect(),
            }),
            M::QueryMacroRequest { macro_id } => Some(M::QueryMacroResponse {
                macro_record: image.macros.iter().find(|m| m.macro_id == *macro_id).cloned(),
            }),
            M::AddMacroRequest(record) => {
                Some(M::AddMacroResponse { ok: self.add(record, |m| m.macro_id, |image| &mut image.macros) })
            }
            M::DeleteMacroRequest { macro_id } => {
                let before = image.macros.len();
                image.macros.retain(|m| m.macro_id != *macro_id);
                Some(M::DeleteMacroResponse { ok: image.macros.len() < before })
            }
            M::ExecuteMacroRequest { macro_id } => {
                let exists = image.macros.iter().any(|m| m.macro_id == *macro_id);
                if exists {
                    let before = self.schedule.len();
                    self.schedule_macro(now, *macro_id, 100, 0);
                    let steps = self.schedule[before..].iter().map(|(at, _)| *at).collect();
                    self.events.push_back(SimEvent::MacroSteps { macro_id: *macro_id, steps });
                    self.apply_schedule(now);
                }
                Some(M::ExecuteMacroResponse { ok: exists })
            }
            M::QueryServoParameterRequest => Some(M::QueryServoParameterResponse { servos: image.servos.clone() }),
            M::AddServoParameterRequest { servos } => {
                let ok = self.fits_after(|trial| merge_servos(trial, servos));
                if ok {
                    merge_servos(&mut self.image, servos);
                }
                Some(M::AddServoParameterResponse { ok })
            }
            M::WriteProjectIdRequest { project_id } => {
                image.project_id = *project_id;
                Some(M::WriteProjectIdResponse { ok: true })
            }
            M::QueryProjectIdRequest => Some(M::QueryProjectIdResponse { project_id: image.project_id }),
            _ => return None,
        })
    }

    /// Joystick tables and button events (40xxx).
    fn remote_answer(&mut self, message: &Message) -> Option<Option<Message>> {
        use Message as M;
        let image = &mut self.image;
        Some(match message {
            M::QueryJoystickTableListRequest => Some(M::QueryJoystickTableListResponse {
                tables: image.tables.iter().map(|t| ListEntry { id: t.table_id, caption: t.caption.clone() }).collect(),
            }),
            M::QueryJoystickTableRequest { table_id } => Some(M::QueryJoystickTableResponse {
                table: image.tables.iter().find(|t| t.table_id == *table_id).cloned(),
            }),
            M::AddJoystickTableRequest(record) => {
                Some(M::AddJoystickTableResponse { ok: self.add(record, |t| t.table_id, |image| &mut image.tables) })
            }
            M::DeleteJoystickTableRequest { table_id } => {
                let before = image.tables.len();
                image.tables.retain(|t| t.table_id != *table_id);
                if image.active_table == *table_id {
                    image.active_table = 0;
                }
                Some(M::DeleteJoystickTableResponse { ok: image.tables.len() < before })
            }
            M::SetActiveJoystickTableRequest { table_id } => {
                let ok = image.tables.iter().any(|t| t.table_id == *table_id);
                if ok {
                    image.active_table = *table_id;
                }
                Some(M::SetActiveJoystickTableResponse { ok })
            }
            M::QueryActiveJoystickTableRequest => {
                let table_id = match (image.active_table, image.tables.as_slice()) {
                    (0, [only]) => only.table_id,
                    (active, _) => active,
                };
                Some(M::QueryActiveJoystickTableResponse { table_id })
            }
            M::SubscribeButtonEventRequest { subscribe } => {
                self.subscribed = *subscribe;
                Some(M::SubscribeButtonEventResponse { ok: true })
            }
            _ => return None,
        })
    }

    fn refused(&self, id: i32) -> bool {
        self.config.faults.refuse_add.contains(&id)
    }

    /// Stores (or replaces) a record in the list `list` picks, if its id is
    /// valid, not refused by a fault, and the result fits in memory.
    fn add<T: Clone>(
        &mut self,
        record: &T,
        id: impl Fn(&T) -> i32 + Copy,
        list: impl Fn(&mut ServoImage) -> &mut Vec<T> + Copy,
    ) -> bool {
        if id(record) == 0 || self.refused(id(record)) {
            return false;
        }
        let ok = self.fits_after(|trial| upsert(list(trial), record.clone(), id));
        if ok {
            upsert(list(&mut self.image), record.clone(), id);
        }
        ok
    }

    fn process_inbound(&mut self, now: Instant) {
        while self.inbound.front().is_some_and(|(at, _)| *at <= now) {
            let Some((at, bytes)) = self.inbound.pop_front() else {
                break;
            };
            self.decoder.push(&bytes);
            while let Some(event) = self.decoder.poll() {
                let DecoderEvent::Frame(frame) = event else {
                    continue;
                };
                self.frames_received += 1;
                if self.config.faults.disconnect_after.is_some_and(|limit| self.frames_received > limit) {
                    self.closed = true;
                    return;
                }
                // A real board drops what it cannot parse.
                if let Ok(message) = Message::from_frame(&frame) {
                    self.handle_message(at, message);
                }
            }
        }
    }
}

fn upsert<T>(items: &mut Vec<T>, item: T, id: impl Fn(&T) -> i32) {
    match items.iter_mut().find(|existing| id(existing) == id(&item)) {
        Some(existing) => *existing = item,
        None => items.push(item),
    }
}

fn merge_servos(image: &mut ServoImage, servos: &[crate::protocol::servo::ServoParameter]) {
    for servo in servos {
        match image.servos.iter_mut().find(|s| s.servo_id == servo.servo_id) {
            Some(existing) => *existing = servo.clone(),
            None => image.servos.push(servo.clone()),
        }
    }
}

impl Driver for ServoSim {
    type Command = SimCommand;
    type Event = SimEvent;

    fn handle_command(&mut self, now: Instant, command: SimCommand) {
        match command {
            SimCommand::Button { button_id, event } => {
                if self.subscribed {
                    let bytes = Message::ButtonEventResponse { button_id, event }.encode().unwrap_or_default();
                    self.transmit(now, bytes);
                }
            }
            SimCommand::TurnByHand { servo_id, angle } => {
                if let Some(state) = self.servos.iter_mut().find(|s| s.servo_id == servo_id && !s.switches.is_hold) {
                    state.from = angle;
                    state.to = angle;
                    state.end = now;
                }
            }
        }
    }

    fn handle_input(&mut self, now: Instant, bytes: &[u8]) {
        // At a line rate, the last byte arrives one wire time after the line is free.
        let start = self.rx_line_free.map_or(now, |free| free.max(now));
        let arrived = start + self.wire_time(bytes.len());
        self.rx_line_free = Some(arrived);
        self.inbound.push_back((arrived, bytes.to_vec()));
        self.process_inbound(now);
    }

    fn handle_timeout(&mut self, now: Instant) {
        self.process_inbound(now);
        self.apply_schedule(now);
    }

    fn handle_disconnect(&mut self, _reason: &str) {
        self.inbound.clear();
        self.outbound.clear();
    }

    fn poll_transmit(&mut self, now: Instant) -> Option<Vec<u8>> {
        if self.outbound.front().is_some_and(|(at, _)| *at <= now) {
            return self.outbound.pop_front().map(|(_, bytes)| bytes);
        }
        None
    }

    fn poll_event(&mut self) -> Option<SimEvent> {
        self.events.pop_front()
    }

    fn poll_timeout(&self) -> Option<Instant> {
        [
            self.inbound.front().map(|(at, _)| *at),
            self.outbound.front().map(|(at, _)| *at),
            self.schedule.iter().map(|(at, _)| *at).min(),
        ]
        .into_iter()
        .flatten()
        .min()
    }

    fn wants_close(&self) -> bool {
        self.closed
    }
}

mod playing;
#[cfg(test)]
mod tests;
