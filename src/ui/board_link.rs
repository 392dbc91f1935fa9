//! The app shell's side of a connection: one board of one family, the demo
//! board when there is one, and the packet log. The family's handle in
//! `device` does the talking; this only routes its notices to the shell.

use std::time::Instant;

use crate::device::LogEntry;
use crate::device::servo::{RequestError, ServoHandle, ServoImage, ServoNotice};
use crate::link::{Connection, DisconnectReason, Waker};
use crate::project::{Family, Project};
use crate::sim::{ServoSim, SimConfig, SimHandle, spawn_in_memory};
use crate::ui::packet_log::PacketLog;

/// Something the app shell should show the user.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum LinkNotice {
    /// Something could not be sent; the text says why.
    SendFailed(String),
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
        event: crate::device::servo::ButtonEvent,
    },
}

/// The connected board's driver, by family.
#[derive(Debug)]
pub enum Device {
    /// A servo controller board.
    Servo(ServoHandle),
}

/// A connected board as the app shell sees it.
pub struct BoardLink {
    device: Device,
    demo: Option<SimHandle>,
    /// What it is connected to.
    pub label: String,
    /// Every frame sent and received.
    pub log: PacketLog,
}

impl std::fmt::Debug for BoardLink {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("BoardLink").field("label", &self.label).finish_non_exhaustive()
    }
}

/// Why a connection could not start, for the status line.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum StartError {
    /// This build has no driver for the family yet.
    Unsupported(Family),
    /// The I/O thread (or the demo board) could not start.
    Thread(String),
}

impl BoardLink {
    /// Whether this build has a driver for `family`.
    pub fn supports(family: Family) -> bool {
        family == Family::Servo
    }

    /// Starts `family`'s driver over an opened connection.
    pub fn start(family: Family, connection: Connection, baud: u32, waker: Waker) -> Result<Self, StartError> {
        let label = connection.description.clone();
        let device = match family {
            Family::Servo => Device::Servo(
                ServoHandle::over(connection, Some(baud), waker)
                    .map_err(|error| StartError::Thread(error.to_string()))?,
            ),
            other => return Err(StartError::Unsupported(other)),
        };
        Ok(Self { device, demo: None, label, log: PacketLog::default() })
    }

    /// Starts the emulated board of the project's family in this process,
    /// preloaded with the project, and connects to it.
    pub fn demo(project: &Project, waker: Waker) -> Result<Self, StartError> {
        Self::demo_with(project, SimConfig::default(), waker)
    }

    /// Like [`BoardLink::demo`], with the emulated board configured (faults, memory…).
    pub fn demo_with(project: &Project, sim_config: SimConfig, waker: Waker) -> Result<Self, StartError> {
        if project.family != Family::Servo {
            return Err(StartError::Unsupported(project.family));
        }
        let image = ServoImage::from_project(&project.servo).unwrap_or_default();
        let thread = |error: std::io::Error| StartError::Thread(error.to_string());
        let (sim, connection) = spawn_in_memory(ServoSim::new(sim_config, image), waker.clone()).map_err(thread)?;
        let handle = ServoHandle::over(connection, None, waker).map_err(thread)?;
        Ok(Self { device: Device::Servo(handle), demo: Some(sim), label: String::new(), log: PacketLog::default() })
    }

    /// The family connected.
    pub fn family(&self) -> Family {
        match self.device {
            Device::Servo(_) => Family::Servo,
        }
    }

    /// Whether this is the in-process demo board.
    pub fn is_demo(&self) -> bool {
        self.demo.is_some()
    }

    /// The emulated board, when this is the demo.
    pub fn demo_board(&self) -> Option<&SimHandle> {
        self.demo.as_ref()
    }

    /// The servo board's handle, when a servo board is connected.
    pub fn servo(&self) -> Option<&ServoHandle> {
        match &self.device {
            Device::Servo(handle) => Some(handle),
        }
    }

    /// The servo board's handle, mutably.
    pub fn servo_mut(&mut self) -> Option<&mut ServoHandle> {
        match &mut self.device {
            Device::Servo(handle) => Some(handle),
        }
    }

    /// Servos (or joints, or wheels) were stopped with STOP and not resumed.
    pub fn stopped(&self) -> bool {
        match &self.device {
            Device::Servo(handle) => handle.stopped,
        }
    }

    /// STOP, the family's way: for a servo board, drop queued moves and stop
    /// every servo where it is, holding torque, ahead of any queued request.
    pub fn stop(&mut self) -> Result<(), RequestError> {
        match &mut self.device {
            Device::Servo(handle) => handle.stop(),
        }
    }

    /// Picks up what the board sent; records the packet log.
    pub fn pump(&mut self, now: Instant, polling: bool) -> Vec<LinkNotice> {
        let notices = match &mut self.device {
            Device::Servo(handle) => handle.pump(now, polling),
        };
        let mut out = Vec::new();
        for notice in notices {
            match notice {
                ServoNotice::Log(entry) => self.record(entry),
                ServoNotice::SendFailed(text) => out.push(LinkNotice::SendFailed(text)),
                ServoNotice::RequestFailed(error) => out.push(LinkNotice::RequestFailed(error)),
                ServoNotice::MacroRefused => out.push(LinkNotice::MacroRefused),
                ServoNotice::Disconnected(reason) => out.push(LinkNotice::Disconnected(reason)),
                ServoNotice::Button { button_id, event } => out.push(LinkNotice::Button { button_id, event }),
            }
        }
        out
    }

    fn record(&mut self, entry: LogEntry) {
        self.log.record(entry);
    }

    /// When the link next needs a frame to refresh its status.
    pub fn next_refresh(&self, polling: bool) -> Instant {
        match &self.device {
            Device::Servo(handle) => handle.next_refresh(polling),
        }
    }
}
