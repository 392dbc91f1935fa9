//! The devices a show plays on, connected: a servo board, a PLEN2 or an
//! rFLEX base behind its port, each a [`Stage`] the player starts and stops.

use std::time::{Duration, Instant};

use anyhow::bail;

use super::play::Stage;
use super::{Device, Start};
use crate::audio::together::link_delay;
use crate::device::plen2::{
    Command as Plen2Command, Plen2Handle, Plen2Notice, Plen2Options, Plen2Requester, start_delay,
};
use crate::device::rflex::{RflexBase, RflexNotice};
use crate::device::servo::{DEFAULT_BAUD, Requester, ServoBoard, SessionConfig};
use crate::device::{self};
use crate::link::{self, LineSettings, LinkEvent, PortName, no_waker};
use crate::project::Family;
use crate::protocol::servo::{ALL_SERVOS, Message, ServoSwitches};

/// Connects `device` on `port`: its stage and the delay of its first cue's start.
pub fn connect(port: &str, device: &Device) -> anyhow::Result<(Box<dyn Stage>, Duration)> {
    let family = device.project.family;
    let name = PortName::parse(port)?;
    let settings = device::line_settings(family);
    if family == Family::Servo {
        let board = ServoBoard::connect(&name, DEFAULT_BAUD, SessionConfig::default(), no_waker())?;
        let latency = round_trip(|| {
            board.requester().request(Message::QueryMemorySizeRequest).map(|_| ()).map_err(|e| e.to_string())
        })?;
        let stage = ServoStage { requester: board.requester(), latency, board, lost: None };
        let delay = stage.start_delay(&Start::Macro(0));
        return Ok((Box::new(stage), delay));
    }
    if family == Family::Plen2 {
        let connection = link::open(&name, &LineSettings { ..settings })?;
        let mut handle = Plen2Handle::over(connection, Plen2Options::default(), no_waker())?;
        let requester = handle.requester();
        let latency = round_trip(|| requester.probe().map_err(|e| e.to_string()))?;
        let lost = handle.pump(Instant::now()).into_iter().find_map(|notice| match notice {
            Plen2Notice::Disconnected(reason) => Some(reason.to_string()),
            _ => None,
        });
        let stage = Plen2Stage { handle, requester, latency, lost };
        let delay = stage.start_delay(&Start::Slot(0));
        return Ok((Box::new(stage), delay));
    }
    if family == Family::Rflex {
        let connection = link::open(&name, &settings)?;
        let base = RflexBase::over(connection, device.project.rflex.robot.conversion(), no_waker())?;
        base.start(false);
        let stage =
            RflexStage { base, accel: device.project.rflex.drive.accel_m_per_s2, baud: settings.baud, lost: None };
        let delay = stage.start_delay(&Start::Drive { speed_m_s: 0.0, turn_deg_s: 0.0, for_ms: 0 });
        return Ok((Box::new(stage), delay));
    }
    bail!("a {} cannot play in a show", family.name())
}

/// Half the shortest of three round trips: the link's one-way latency, as well as it can be known.
fn round_trip(mut ask: impl FnMut() -> Result<(), String>) -> anyhow::Result<Duration> {
    let mut shortest = Duration::MAX;
    for _ in 0..3 {
        let asked = Instant::now();
        ask().map_err(|error| anyhow::anyhow!(error))?;
        shortest = shortest.min(asked.elapsed());
    }
    Ok(shortest / 2)
}

struct ServoStage {
    board: ServoBoard,
    requester: Requester,
    latency: Duration,
    lost: Option<String>,
}

impl Stage for ServoStage {
    fn start_delay(&self, start: &Start) -> Duration {
        let Start::Macro(macro_id) = *start else { return Duration::ZERO };
        let bytes = Message::ExecuteMacroRequest { macro_id }.encode().map_or(16, |bytes| bytes.len());
        link_delay(bytes, DEFAULT_BAUD, self.latency)
    }

    fn start(&mut self, start: &Start) -> Result<(), String> {
        let Start::Macro(macro_id) = *start else { return Err(format!("a servo board cannot start {start:?}")) };
        self.requester.send(Message::ExecuteMacroRequest { macro_id }).map_err(|error| error.to_string())
    }

    fn stop(&mut self) {
        let all = ServoSwitches { servo_id: ALL_SERVOS, is_start: false, is_hold: true };
        let _ = self.requester.stop(Message::SetServoParameterRequest(all));
    }

    fn tick(&mut self, _now: Instant) {
        for event in self.board.events().try_iter() {
            if let LinkEvent::Disconnected { reason } = event {
                self.lost = Some(reason.to_string());
            }
        }
    }

    fn lost(&self) -> Option<String> {
        self.lost.clone()
    }
}

struct Plen2Stage {
    handle: Plen2Handle,
    requester: Plen2Requester,
    latency: Duration,
    lost: Option<String>,
}

impl Stage for Plen2Stage {
    fn start_delay(&self, start: &Start) -> Duration {
        let Start::Slot(slot) = *start else { return Duration::ZERO };
        start_delay(&Plen2Command::PlayMotion { slot }, self.latency)
    }

    fn start(&mut self, start: &Start) -> Result<(), String> {
        let Start::Slot(slot) = *start else { return Err(format!("a PLEN2 cannot start {start:?}")) };
        self.requester.send(Plen2Command::PlayMotion { slot }).map_err(|error| error.to_string())
    }

    fn stop(&mut self) {
        self.handle.stop();
    }

    fn tick(&mut self, now: Instant) {
        for notice in self.handle.pump(now) {
            if let Plen2Notice::Disconnected(reason) = notice {
                self.lost = Some(reason.to_string());
            }
        }
    }

    fn lost(&self) -> Option<String> {
        self.lost.clone()
    }
}

struct RflexStage {
    base: RflexBase,
    accel: f64,
    baud: u32,
    lost: Option<String>,
}

impl Stage for RflexStage {
    fn start_delay(&self, _start: &Start) -> Duration {
        // A velocity command's frame: under 40 bytes.
        link_delay(40, self.baud, Duration::ZERO)
    }

    fn start(&mut self, start: &Start) -> Result<(), String> {
        let Start::Drive { speed_m_s, turn_deg_s, .. } = *start else {
            return Err(format!("an rFLEX base cannot start {start:?}"));
        };
        self.base.set_brake(false);
        self.base.drive(speed_m_s, turn_deg_s.to_radians(), self.accel);
        Ok(())
    }

    fn stop(&mut self) {
        self.base.stop();
        self.base.set_brake(true);
    }

    fn tick(&mut self, now: Instant) {
        for notice in self.base.pump(now) {
            if let RflexNotice::Disconnected(reason) = notice {
                self.lost = Some(reason.to_string());
            }
        }
    }

    fn lost(&self) -> Option<String> {
        self.lost.clone().or_else(|| self.base.is_lost().then(|| "the link ended".to_string()))
    }
}
