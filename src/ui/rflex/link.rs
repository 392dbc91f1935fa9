//! The rFLEX base's link: its handle as the shell holds it, and how it
//! starts, over a port or on the built-in emulated base.

use std::time::Instant;

use crate::device::rflex::{RflexBase, RflexNotice};
use crate::link::{Connection, Waker};
use crate::project::{Family, Project};
use crate::sim::{RflexSim, RflexSimCommand, RflexSimConfig, RflexSimEvent, SimHandle, spawn_in_memory, spawn_tcp};
use crate::ui::board_link::{BoardLink, FamilyLink, FamilyNotice, LinkNotice, LinkStarter, StartError};
use crate::ui::packet_log::PacketLog;
use crate::ui::shell::Shell;

impl FamilyLink for RflexBase {
    fn family(&self) -> Family {
        Family::Rflex
    }

    fn pump(&mut self, now: Instant, _polling: bool, log: &mut PacketLog) -> Vec<LinkNotice> {
        let mut out = Vec::new();
        for notice in RflexBase::pump(self, now) {
            match notice {
                RflexNotice::Log(entry) => log.record(entry),
                RflexNotice::Disconnected(reason) => out.push(LinkNotice::Disconnected(reason)),
                notice @ RflexNotice::Silent => out.push(LinkNotice::Family(FamilyNotice::new(notice))),
            }
        }
        out
    }

    /// Both axes to speed 0 at once (never fails; a lost link is reported by `pump`).
    fn stop(&mut self) -> Option<FamilyNotice> {
        RflexBase::stop(self);
        None
    }
}

/// Starts the base's driver over an opened connection and its start-up
/// sequence (the sonar on if the project says so).
fn start(project: &Project, connection: Connection, waker: Waker) -> Result<RflexBase, StartError> {
    let base = RflexBase::over(connection, project.rflex.robot.conversion(), waker)?;
    base.start(project.rflex.drive.sonar_on_connect);
    Ok(base)
}

/// Starts the base's driver over an opened connection (its line rate is the port's).
pub(super) fn starter() -> LinkStarter {
    Box::new(|project: &Project, connection, waker| Ok(Box::new(start(project, connection, waker)?)))
}

/// Starts the emulated base in this process, with the project's robot's
/// conversion constants, and connects to it.
pub(super) fn demo_link(project: &Project, waker: Waker) -> Result<BoardLink, StartError> {
    let config = RflexSimConfig { conversion: project.rflex.robot.conversion(), ..RflexSimConfig::default() };
    let (sim, connection) = spawn_in_memory(RflexSim::new(config), waker.clone())?;
    Ok(BoardLink::demo(Box::new(start(project, connection, waker)?), sim))
}

/// The demo base as a server on a loopback port (the editor's demo lent to remote control).
pub(super) fn demo_server(project: &Project, waker: Waker) -> Result<crate::ui::family::DemoServer, StartError> {
    let config = RflexSimConfig { conversion: project.rflex.robot.conversion(), ..RflexSimConfig::default() };
    let server = spawn_tcp(RflexSim::new(config), crate::sim::LOOPBACK_ANY, waker)?;
    let port = server.port_name.clone();
    Ok((Box::new(server), port))
}

/// A link as a mobile base's (the shell's `BoardLink` names no family).
pub trait RflexBoardLink {
    /// The mobile base, when one is connected.
    fn rflex(&self) -> Option<&RflexBase>;
    /// The mobile base, mutably.
    fn rflex_mut(&mut self) -> Option<&mut RflexBase>;
    /// The emulated base, when this is its demo.
    fn demo_base(&self) -> Option<&SimHandle<RflexSimCommand, RflexSimEvent>>;
}

impl RflexBoardLink for BoardLink {
    fn rflex(&self) -> Option<&RflexBase> {
        self.device()
    }

    fn rflex_mut(&mut self) -> Option<&mut RflexBase> {
        self.device_mut()
    }

    fn demo_base(&self) -> Option<&SimHandle<RflexSimCommand, RflexSimEvent>> {
        self.emulated()
    }
}

/// The connected base through the shell.
pub(crate) trait RflexLink {
    /// The connected base, mutably.
    fn rflex_mut(&mut self) -> Option<&mut RflexBase>;
}

impl RflexLink for Shell<'_> {
    fn rflex_mut(&mut self) -> Option<&mut RflexBase> {
        self.link.as_mut().and_then(RflexBoardLink::rflex_mut)
    }
}
