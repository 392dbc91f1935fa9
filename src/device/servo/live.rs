//! Live operations: move servos now, run what the board stores, switch torque,
//! and read the board's state. Thin typed calls over [`Requester`].

use super::client::Requester;
use super::item::Item;
use super::ops::OpError;
#[cfg(any(test, feature = "test-api"))]
use crate::protocol::servo::{AngleUnit, ServoSwitches};
use crate::protocol::servo::{Message, ServoMove, ServoStatus};

fn ask(requester: &Requester, item: &Item, message: Message) -> Result<Message, OpError> {
    requester.request(message).map_err(|source| OpError::Request { item: item.clone(), source })
}

fn refused_unless(ok: bool, item: &Item) -> Result<(), OpError> {
    if ok { Ok(()) } else { Err(OpError::Refused { item: item.clone() }) }
}

fn unexpected(item: &Item, response: &Message) -> OpError {
    OpError::Unexpected { item: item.clone(), response: response.name() }
}

impl Requester {
    /// Moves servos now (20050, no response). `interval_10ms` is the move's duration.
    pub fn move_servos(&self, moves: Vec<ServoMove>) -> Result<(), OpError> {
        self.send(Message::ExecuteActionRequest { moves })
            .map_err(|source| OpError::Request { item: Item::MoveServos, source })
    }

    /// Runs a stored action (20060, no response).
    pub fn run_action(&self, action_id: i32) -> Result<(), OpError> {
        self.send(Message::ExecuteActionExRequest { action_id })
            .map_err(|source| OpError::Request { item: Item::RunAction(action_id), source })
    }

    /// Runs a stored macro (30090).
    pub fn run_macro(&self, macro_id: i32) -> Result<(), OpError> {
        let item = Item::RunMacro(macro_id);
        match ask(self, &item, Message::ExecuteMacroRequest { macro_id })? {
            Message::ExecuteMacroResponse { ok } => refused_unless(ok, &item),
            other => Err(unexpected(&item, &other)),
        }
    }

    #[cfg(any(test, feature = "test-api"))]
    /// Sets a servo's (or all servos', id 0xFF) run and hold switches (20030).
    pub fn set_servo_switches(&self, switches: ServoSwitches) -> Result<ServoSwitches, OpError> {
        let item = Item::ServoSwitches(switches.servo_id);
        match ask(self, &item, Message::SetServoParameterRequest(switches))? {
            Message::SetServoParameterResponse(now) => Ok(now),
            other => Err(unexpected(&item, &other)),
        }
    }

    #[cfg(any(test, feature = "test-api"))]
    /// Sets a servo's (or all servos', id 0xFF) angle unit (20040).
    pub fn set_angle_unit(&self, servo_id: u8, unit: AngleUnit) -> Result<AngleUnit, OpError> {
        let item = Item::AngleUnit(servo_id);
        match ask(self, &item, Message::SetAngleUnitRequest { servo_id, unit })? {
            Message::SetAngleUnitResponse { unit, .. } => Ok(unit),
            other => Err(unexpected(&item, &other)),
        }
    }

    /// Reads one servo's (or all servos', id 0xFF) live state (20020).
    pub fn query_servos(&self, servo_id: u8) -> Result<Vec<ServoStatus>, OpError> {
        let item = Item::ServoState(servo_id);
        match ask(self, &item, Message::QueryServoRequest { servo_id })? {
            Message::QueryServoResponse { servos } => Ok(servos),
            other => Err(unexpected(&item, &other)),
        }
    }

    /// Remaining battery in ‰ (10040).
    pub fn battery_permil(&self) -> Result<i16, OpError> {
        match ask(self, &Item::Battery, Message::QueryRemainPowerRequest)? {
            Message::QueryRemainPowerResponse { permil } => Ok(permil),
            other => Err(unexpected(&Item::Battery, &other)),
        }
    }

    /// Free and total memory in bytes (10030).
    pub fn memory(&self) -> Result<(i32, Option<i32>), OpError> {
        match ask(self, &Item::MemorySize, Message::QueryMemorySizeRequest)? {
            Message::QueryMemorySizeResponse { free_bytes, total_bytes } => Ok((free_bytes, total_bytes)),
            other => Err(unexpected(&Item::MemorySize, &other)),
        }
    }

    /// The board's project id (30130; 0 = none).
    pub fn project_id(&self) -> Result<i32, OpError> {
        match ask(self, &Item::ProjectId, Message::QueryProjectIdRequest)? {
            Message::QueryProjectIdResponse { project_id } => Ok(project_id),
            other => Err(unexpected(&Item::ProjectId, &other)),
        }
    }

    /// Subscribes to (or cancels) remote button events (40070).
    pub fn subscribe_buttons(&self, subscribe: bool) -> Result<(), OpError> {
        let item = &Item::ButtonEvents;
        match ask(self, item, Message::SubscribeButtonEventRequest { subscribe })? {
            Message::SubscribeButtonEventResponse { ok } => refused_unless(ok, item),
            other => Err(unexpected(item, &other)),
        }
    }
}
