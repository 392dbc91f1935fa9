//! The DYNAMIXEL bus's link: its handle as the shell holds it, and how it
//! starts, over a port (scanned at once) or on the built-in emulated bus.

use std::time::Instant;

use crate::device::dynamixel::{DynamixelCommand, DynamixelEvent, DynamixelHandle, ONE_IDS};
use crate::link::{Connection, LinkEvent, Waker};
use crate::project::{Family, Project};
use crate::sim::dynamixel::DynamixelBus;
use crate::sim::spawn_in_memory;
use crate::ui::board_link::{BoardLink, FamilyLink, FamilyNotice, LinkNotice, LinkStarter, StartError};
use crate::ui::packet_log::PacketLog;

impl FamilyLink for DynamixelHandle {
    fn family(&self) -> Family {
        Family::Dynamixel
    }

    fn pump(&mut self, _now: Instant, _polling: bool, log: &mut PacketLog) -> Vec<LinkNotice> {
        let mut notices = Vec::new();
        for event in self.events().try_iter() {
            match event {
                LinkEvent::Driver(DynamixelEvent::Logged(logged)) => log.record(logged.entry()),
                LinkEvent::Driver(event) => notices.push(LinkNotice::Family(FamilyNotice::new(event))),
                LinkEvent::Disconnected { reason } => notices.push(LinkNotice::Disconnected(reason)),
            }
        }
        notices
    }

    /// STOP: every servo held where it is (never fails; a lost link is said by `pump`).
    fn stop(&mut self) -> Option<FamilyNotice> {
        self.send(DynamixelCommand::Hold);
        None
    }
}

/// The handle over `connection`, its scan begun.
fn start(connection: Connection, waker: Waker) -> Result<DynamixelHandle, StartError> {
    let handle = DynamixelHandle::over(connection, waker)?;
    handle.send(DynamixelCommand::Scan { one: ONE_IDS });
    Ok(handle)
}

/// Starts the driver over an opened connection.
pub(super) fn starter() -> LinkStarter {
    Box::new(|_: &Project, connection, waker| Ok(Box::new(start(connection, waker)?)))
}

/// Starts the emulated bus (an XL430, an XM430 and an AX-12A) in this process and connects to it.
pub(super) fn demo_link(waker: Waker) -> Result<BoardLink, StartError> {
    let (bus, connection) = spawn_in_memory(DynamixelBus::demo(), waker.clone())?;
    Ok(BoardLink::demo(Box::new(start(connection, waker)?), bus))
}

/// The demo bus as a server on a loopback port (the editor's demo lent to a show or a remote).
pub(super) fn demo_server(waker: Waker) -> Result<crate::ui::family::DemoServer, StartError> {
    let server = crate::sim::spawn_tcp(DynamixelBus::demo(), crate::sim::LOOPBACK_ANY, waker)?;
    let port = server.port_name.clone();
    Ok((Box::new(server), port))
}

/// The emulated bus behind a demo link.
#[cfg(test)]
pub type EmulatedBus = crate::sim::SimHandle<crate::sim::dynamixel::BusCommand, crate::sim::dynamixel::BusEvent>;
