//! The app shell's side of a connection: one board of one family, the demo
//! board when there is one, and the packet log. The family's handle in
//! `device` does the talking; this only routes its notices to the shell.

use std::time::{Duration, Instant};

use crate::device::plen2::{PacingMode, Plen2Handle, Plen2Notice, Plen2Options};
use crate::device::rflex::{RflexBase, RflexNotice};
use crate::device::servo::{RequestError, ServoHandle, ServoImage, ServoNotice};
use crate::link::{Connection, DisconnectReason, Waker};
use crate::project::{Family, Project};
use crate::sim::{
    Plen2Sim, Plen2SimCommand, Plen2SimEvent, Plen2Timing, RflexSim, RflexSimCommand, RflexSimConfig, RflexSimEvent,
    ServoSim, SimConfig, SimHandle, spawn_in_memory,
};
use crate::ui::packet_log::PacketLog;

/// Something the app shell should show the user.
#[derive(Clone, Debug, PartialEq)]
pub enum LinkNotice {
    /// Something could not be sent; the text says why.
    SendFailed(crate::device::servo::EncodeError),
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
    /// A mobile base went silent while driving and was sent a stop.
    BaseSilent,
    /// The PLEN2's adaptive pacing widened its margins.
    PacingWidened(crate::device::plen2::Widened),
}

/// The connected board's driver, by family.
#[derive(Debug)]
// One per window: the size of the largest variant costs nothing worth a box.
#[allow(clippy::large_enum_variant)]
pub enum Device {
    /// A servo controller board.
    Servo(ServoHandle),
    /// An rFLEX mobile base.
    Rflex(RflexBase),
    /// A PLEN2 humanoid.
    Plen2(Plen2Handle),
}

/// The emulated board behind the demo, by family.
#[derive(Debug)]
pub enum Demo {
    /// The emulated servo board.
    Servo(SimHandle),
    /// The emulated rFLEX base.
    Rflex(SimHandle<RflexSimCommand, RflexSimEvent>),
    /// The emulated PLEN2.
    Plen2(SimHandle<Plen2SimCommand, Plen2SimEvent>),
}

/// A connected board as the app shell sees it.
pub struct BoardLink {
    device: Device,
    demo: Option<Demo>,
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

impl From<std::io::Error> for StartError {
    fn from(error: std::io::Error) -> Self {
        Self::Thread(error.to_string())
    }
}

/// How a family's driver is started: what the connection bar and the family's own pickers chose.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LinkOptions {
    /// The line rate asked for.
    pub baud: u32,
    /// How a PLEN2 is paced.
    pub pacing: PacingMode,
}

impl Default for LinkOptions {
    fn default() -> Self {
        Self { baud: 115_200, pacing: PacingMode::default() }
    }
}

/// How often a mobile base's telemetry is redrawn while connected.
const TELEMETRY_EVERY: Duration = Duration::from_millis(100);

impl BoardLink {
    /// Whether this build has a driver for `family`.
    pub fn supports(family: Family) -> bool {
        matches!(family, Family::Servo | Family::Rflex | Family::Plen2)
    }

    /// Starts the driver of the project's family over an opened connection
    /// (a PLEN2 paced as `options` say).
    pub fn start(
        project: &Project,
        connection: Connection,
        LinkOptions { baud, pacing }: LinkOptions,
        waker: Waker,
    ) -> Result<Self, StartError> {
        let label = connection.description.clone();
        let device = match project.family {
            Family::Servo => Device::Servo(ServoHandle::over(connection, Some(baud), waker)?),
            Family::Rflex => {
                let base = RflexBase::over(connection, project.rflex.robot.conversion(), waker)?;
                base.start(project.rflex.drive.sonar_on_connect);
                Device::Rflex(base)
            }
            Family::Plen2 => {
                let options = Plen2Options { mode: pacing, line_baud: baud, ..Plen2Options::default() };
                Device::Plen2(Plen2Handle::over(connection, options, waker)?)
            }
        };
        Ok(Self { device, demo: None, label, log: PacketLog::default() })
    }

    /// Starts the emulated board of the project's family in this process,
    /// preloaded with the project, and connects to it.
    /// (The demo's line rate is the family's own; `options` give the rest.)
    pub fn demo(project: &Project, options: LinkOptions, waker: Waker) -> Result<Self, StartError> {
        Self::demo_with(project, SimConfig::default(), options, waker)
    }

    /// Like [`BoardLink::demo`], with the emulated servo board configured (faults, memory…).
    pub fn demo_with(
        project: &Project,
        sim_config: SimConfig,
        options: LinkOptions,
        waker: Waker,
    ) -> Result<Self, StartError> {
        match project.family {
            Family::Servo => {
                let image = ServoImage::from_project(&project.servo).unwrap_or_default();
                let (sim, connection) = spawn_in_memory(ServoSim::new(sim_config, image), waker.clone())?;
                let handle = ServoHandle::over(connection, None, waker)?;
                Ok(Self {
                    device: Device::Servo(handle),
                    demo: Some(Demo::Servo(sim)),
                    label: String::new(),
                    log: PacketLog::default(),
                })
            }
            Family::Rflex => {
                let config =
                    RflexSimConfig { conversion: project.rflex.robot.conversion(), ..RflexSimConfig::default() };
                let (sim, connection) = spawn_in_memory(RflexSim::new(config), waker.clone())?;
                let mut link = Self::start(project, connection, LinkOptions { baud: 115_200, ..options }, waker)?;
                link.demo = Some(Demo::Rflex(sim));
                link.label = String::new();
                Ok(link)
            }
            Family::Plen2 => {
                let (sim, connection) = spawn_in_memory(Plen2Sim::new(Plen2Timing::default()), waker.clone())?;
                let mut link = Self::start(project, connection, LinkOptions { baud: 2_000_000, ..options }, waker)?;
                link.demo = Some(Demo::Plen2(sim));
                link.label = String::new();
                Ok(link)
            }
        }
    }

    /// The family connected.
    pub fn family(&self) -> Family {
        match self.device {
            Device::Servo(_) => Family::Servo,
            Device::Rflex(_) => Family::Rflex,
            Device::Plen2(_) => Family::Plen2,
        }
    }

    /// Whether this is the in-process demo board.
    pub fn is_demo(&self) -> bool {
        self.demo.is_some()
    }

    /// The emulated servo board, when this is its demo.
    pub fn demo_board(&self) -> Option<&SimHandle> {
        match &self.demo {
            Some(Demo::Servo(sim)) => Some(sim),
            _ => None,
        }
    }

    /// The emulated rFLEX base, when this is its demo.
    pub fn demo_base(&self) -> Option<&SimHandle<RflexSimCommand, RflexSimEvent>> {
        match &self.demo {
            Some(Demo::Rflex(sim)) => Some(sim),
            _ => None,
        }
    }

    /// The servo board's handle, when a servo board is connected.
    pub fn servo(&self) -> Option<&ServoHandle> {
        match &self.device {
            Device::Servo(handle) => Some(handle),
            _ => None,
        }
    }

    /// The servo board's handle, mutably.
    pub fn servo_mut(&mut self) -> Option<&mut ServoHandle> {
        match &mut self.device {
            Device::Servo(handle) => Some(handle),
            _ => None,
        }
    }

    /// The mobile base, when one is connected.
    pub fn rflex(&self) -> Option<&RflexBase> {
        match &self.device {
            Device::Rflex(base) => Some(base),
            _ => None,
        }
    }

    /// The mobile base, mutably.
    pub fn rflex_mut(&mut self) -> Option<&mut RflexBase> {
        match &mut self.device {
            Device::Rflex(base) => Some(base),
            _ => None,
        }
    }

    /// The PLEN2, when one is connected.
    pub fn plen2(&self) -> Option<&Plen2Handle> {
        match &self.device {
            Device::Plen2(handle) => Some(handle),
            _ => None,
        }
    }

    /// The PLEN2, mutably.
    pub fn plen2_mut(&mut self) -> Option<&mut Plen2Handle> {
        match &mut self.device {
            Device::Plen2(handle) => Some(handle),
            _ => None,
        }
    }

    /// The emulated PLEN2, when this is its demo.
    pub fn demo_plen2(&self) -> Option<&SimHandle<Plen2SimCommand, Plen2SimEvent>> {
        match &self.demo {
            Some(Demo::Plen2(sim)) => Some(sim),
            _ => None,
        }
    }

    /// Servos were stopped with STOP and not resumed (a base has no such state).
    pub fn stopped(&self) -> bool {
        match &self.device {
            Device::Servo(handle) => handle.stopped,
            Device::Rflex(_) | Device::Plen2(_) => false,
        }
    }

    /// STOP, the family's way: for a servo board, drop queued moves and stop
    /// every servo where it is, holding torque, ahead of any queued request;
    /// for a base, both axes to speed 0 at once.
    pub fn stop(&mut self) -> Result<(), RequestError> {
        match &mut self.device {
            Device::Servo(handle) => handle.stop(),
            Device::Rflex(base) => {
                base.stop();
                Ok(())
            }
            Device::Plen2(handle) => {
                handle.stop();
                Ok(())
            }
        }
    }

    /// Picks up what the board sent; records the packet log.
    pub fn pump(&mut self, now: Instant, polling: bool) -> Vec<LinkNotice> {
        let mut out = Vec::new();
        match &mut self.device {
            Device::Servo(handle) => {
                for notice in handle.pump(now, polling) {
                    match notice {
                        ServoNotice::Log(entry) => self.log.record(entry),
                        ServoNotice::SendFailed(text) => out.push(LinkNotice::SendFailed(text)),
                        ServoNotice::RequestFailed(error) => out.push(LinkNotice::RequestFailed(error)),
                        ServoNotice::MacroRefused => out.push(LinkNotice::MacroRefused),
                        ServoNotice::Disconnected(reason) => out.push(LinkNotice::Disconnected(reason)),
                        ServoNotice::Button { button_id, event } => out.push(LinkNotice::Button { button_id, event }),
                    }
                }
            }
            Device::Rflex(base) => {
                for notice in base.pump(now) {
                    match notice {
                        RflexNotice::Log(entry) => self.log.record(entry),
                        RflexNotice::Silent => out.push(LinkNotice::BaseSilent),
                        RflexNotice::Disconnected(reason) => out.push(LinkNotice::Disconnected(reason)),
                    }
                }
            }
            Device::Plen2(handle) => {
                for notice in handle.pump(now) {
                    match notice {
                        Plen2Notice::Log(entry) => self.log.record(entry),
                        Plen2Notice::Disconnected(reason) => out.push(LinkNotice::Disconnected(reason)),
                        Plen2Notice::Widened(widened) => out.push(LinkNotice::PacingWidened(widened)),
                    }
                }
            }
        }
        out
    }

    /// When the link next needs a frame to refresh what it shows.
    pub fn next_refresh(&self, polling: bool) -> Instant {
        match &self.device {
            Device::Servo(handle) => handle.next_refresh(polling),
            Device::Rflex(_) | Device::Plen2(_) => Instant::now() + TELEMETRY_EVERY,
        }
    }
}
