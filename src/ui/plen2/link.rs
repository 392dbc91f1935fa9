//! The PLEN2's link: its handle as the shell holds it, and how it starts,
//! over a port or on the built-in emulated robot.

use std::time::Instant;

use crate::device::plen2::{PacingMode, Plen2Handle, Plen2Notice, Plen2Options};
use crate::link::Waker;
use crate::project::{Family, Project};
use crate::sim::{Plen2Sim, Plen2SimCommand, Plen2SimEvent, Plen2Timing, SimHandle, spawn_in_memory, spawn_tcp};
use crate::ui::board_link::{BoardLink, FamilyLink, FamilyNotice, LinkNotice, LinkStarter, StartError};
use crate::ui::packet_log::PacketLog;
use crate::ui::shell::Shell;

/// The emulated PLEN2's line rate (its USB serial's).
const DEMO_BAUD: u32 = 2_000_000;

impl FamilyLink for Plen2Handle {
    fn family(&self) -> Family {
        Family::Plen2
    }

    fn pump(&mut self, now: Instant, _polling: bool, log: &mut PacketLog) -> Vec<LinkNotice> {
        let mut out = Vec::new();
        for notice in Plen2Handle::pump(self, now) {
            match notice {
                Plen2Notice::Log(entry) => log.record(entry),
                Plen2Notice::Disconnected(reason) => out.push(LinkNotice::Disconnected(reason)),
                notice @ Plen2Notice::Widened(_) => out.push(LinkNotice::Family(FamilyNotice::new(notice))),
            }
        }
        out
    }

    /// The robot stops and goes home (never fails; a lost link is reported by `pump`).
    fn stop(&mut self) -> Option<FamilyNotice> {
        Plen2Handle::stop(self);
        None
    }
}

/// Starts the PLEN2's driver over an opened connection at `baud`, paced as `pacing` says.
pub(super) fn starter(baud: u32, pacing: PacingMode) -> LinkStarter {
    Box::new(move |_: &Project, connection, waker| {
        let options = Plen2Options { mode: pacing, line_baud: baud, ..Plen2Options::default() };
        Ok(Box::new(Plen2Handle::over(connection, options, waker)?))
    })
}

/// Starts the emulated PLEN2 in this process (factory-fresh) and connects to it.
pub(super) fn demo_link(project: &Project, pacing: PacingMode, waker: Waker) -> Result<BoardLink, StartError> {
    let (sim, connection) = spawn_in_memory(Plen2Sim::new(Plen2Timing::default()), waker.clone())?;
    let handle = starter(DEMO_BAUD, pacing)(project, connection, waker)?;
    Ok(BoardLink::demo(handle, sim))
}

/// The demo PLEN2 as a server on a loopback port (the editor's demo lent to remote control).
pub(super) fn demo_server(waker: Waker) -> Result<crate::ui::family::DemoServer, StartError> {
    let server = spawn_tcp(Plen2Sim::new(Plen2Timing::default()), crate::sim::LOOPBACK_ANY, waker)?;
    let port = server.port_name.clone();
    Ok((Box::new(server), port))
}

/// A link as a PLEN2's (the shell's `BoardLink` names no family).
pub trait Plen2BoardLink {
    /// The PLEN2, when one is connected.
    fn plen2(&self) -> Option<&Plen2Handle>;
    /// The PLEN2, mutably.
    fn plen2_mut(&mut self) -> Option<&mut Plen2Handle>;
    /// The emulated PLEN2, when this is its demo.
    fn demo_plen2(&self) -> Option<&SimHandle<Plen2SimCommand, Plen2SimEvent>>;
}

impl Plen2BoardLink for BoardLink {
    fn plen2(&self) -> Option<&Plen2Handle> {
        self.device()
    }

    fn plen2_mut(&mut self) -> Option<&mut Plen2Handle> {
        self.device_mut()
    }

    fn demo_plen2(&self) -> Option<&SimHandle<Plen2SimCommand, Plen2SimEvent>> {
        self.emulated()
    }
}

/// The connected PLEN2 through the shell.
pub(crate) trait Plen2Link {
    /// The connected PLEN2.
    fn plen2(&self) -> Option<&Plen2Handle>;
    /// The connected PLEN2, mutably.
    fn plen2_mut(&mut self) -> Option<&mut Plen2Handle>;
}

impl Plen2Link for Shell<'_> {
    fn plen2(&self) -> Option<&Plen2Handle> {
        self.link.as_ref().and_then(Plen2BoardLink::plen2)
    }

    fn plen2_mut(&mut self) -> Option<&mut Plen2Handle> {
        self.link.as_mut().and_then(Plen2BoardLink::plen2_mut)
    }
}
