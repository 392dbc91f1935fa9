//! The servo board's link: its handle as the shell holds it, and how it
//! starts, over a port or on the built-in emulated board.

use std::time::Instant;

use crate::device::servo::{ServoHandle, ServoImage, ServoNotice};
use crate::link::Waker;
use crate::project::{Family, Project};
use crate::sim::{ServoSim, SimConfig, SimHandle, spawn_in_memory, spawn_tcp};
use crate::ui::board_link::{BoardLink, FamilyLink, FamilyNotice, LinkNotice, LinkStarter, StartError};
use crate::ui::packet_log::PacketLog;
use crate::ui::shell::Shell;

impl FamilyLink for ServoHandle {
    fn family(&self) -> Family {
        Family::Servo
    }

    fn pump(&mut self, now: Instant, polling: bool, log: &mut PacketLog) -> Vec<LinkNotice> {
        let mut out = Vec::new();
        for notice in ServoHandle::pump(self, now, polling) {
            match notice {
                ServoNotice::Log(entry) => log.record(entry),
                ServoNotice::Disconnected(reason) => out.push(LinkNotice::Disconnected(reason)),
                notice => out.push(LinkNotice::Family(FamilyNotice::new(notice))),
            }
        }
        out
    }

    fn stop(&mut self) -> Option<FamilyNotice> {
        ServoHandle::stop(self).err().map(|error| FamilyNotice::new(ServoNotice::RequestFailed(error)))
    }

    fn next_refresh(&self, polling: bool) -> Instant {
        ServoHandle::next_refresh(self, polling)
    }

    fn stopped(&self) -> bool {
        self.stopped
    }
}

/// Starts the servo driver over an opened connection at `baud`.
pub(super) fn starter(baud: u32) -> LinkStarter {
    Box::new(move |_: &Project, connection, waker| Ok(Box::new(ServoHandle::over(connection, Some(baud), waker)?)))
}

/// Starts the emulated servo board in this process, configured by `config`
/// (faults, memory…) and preloaded with the project's servo section, and
/// connects to it.
pub fn demo_link(project: &Project, config: SimConfig, waker: Waker) -> Result<BoardLink, StartError> {
    let image = ServoImage::from_project(&project.servo).unwrap_or_default();
    let (sim, connection) = spawn_in_memory(ServoSim::new(config, image), waker.clone())?;
    let handle = ServoHandle::over(connection, None, waker)?;
    Ok(BoardLink::demo(Box::new(handle), sim))
}

/// The demo board as a server on a loopback port (the editor's demo lent to remote control).
pub fn demo_server(project: &Project, waker: Waker) -> Result<crate::ui::family::DemoServer, StartError> {
    let image = ServoImage::from_project(&project.servo).unwrap_or_default();
    let server = spawn_tcp(ServoSim::new(SimConfig::default(), image), crate::sim::LOOPBACK_ANY, waker)?;
    let port = server.port_name.clone();
    Ok((Box::new(server), port))
}

/// A link as a servo board's (the shell's `BoardLink` names no family).
pub trait ServoBoardLink {
    /// The servo board's handle, when a servo board is connected.
    fn servo(&self) -> Option<&ServoHandle>;
    /// The servo board's handle, mutably.
    fn servo_mut(&mut self) -> Option<&mut ServoHandle>;
    /// The emulated servo board, when this is its demo.
    fn demo_board(&self) -> Option<&SimHandle>;
}

impl ServoBoardLink for BoardLink {
    fn servo(&self) -> Option<&ServoHandle> {
        self.device()
    }

    fn servo_mut(&mut self) -> Option<&mut ServoHandle> {
        self.device_mut()
    }

    fn demo_board(&self) -> Option<&SimHandle> {
        self.emulated()
    }
}

/// The connected servo board through the shell.
pub(crate) trait ServoLink {
    /// The connected servo board.
    fn servo(&self) -> Option<&ServoHandle>;
    /// The connected servo board, mutably.
    fn servo_mut(&mut self) -> Option<&mut ServoHandle>;
}

impl ServoLink for Shell<'_> {
    fn servo(&self) -> Option<&ServoHandle> {
        self.link.as_ref().and_then(ServoBoardLink::servo)
    }

    fn servo_mut(&mut self) -> Option<&mut ServoHandle> {
        self.link.as_mut().and_then(ServoBoardLink::servo_mut)
    }
}
