//! The echo board's link: its handle as the shell holds it, and how it
//! starts, over a port or on its emulated board.

use std::time::Instant;

use super::board::{BoardEvent, EchoBoard, EchoCommand, EchoDriver};
use crate::link::{Connection, LinkEvent, LinkHandle, Waker};
use crate::project::{Family, Project};
use crate::sim::{SimHandle, spawn_in_memory};
use crate::ui::board_link::{BoardLink, FamilyLink, FamilyNotice, LinkNotice, LinkStarter, StartError};
use crate::ui::packet_log::PacketLog;

/// The board answered a move: its servo is at this angle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Echoed(pub i16);

/// A connected echo board.
#[derive(Debug)]
pub struct EchoHandle {
    link: LinkHandle<EchoCommand, i16>,
}

impl EchoHandle {
    /// Starts the I/O thread over an opened connection.
    pub fn over(connection: Connection, waker: Waker) -> std::io::Result<Self> {
        Ok(Self { link: crate::link::spawn(connection, EchoDriver::default(), waker)? })
    }

    /// The servo to `deg`, live.
    pub fn move_to(&self, deg: i16) {
        // A closed link is reported by `pump`.
        let _ = self.link.commands().send(EchoCommand::Move(deg));
    }

    /// Stops the servo where it is.
    pub fn halt(&self) {
        let _ = self.link.commands().send(EchoCommand::Stop);
    }

    /// What the link said: each echo (the servo's angle), or its end.
    pub fn events(&self) -> &crossbeam_channel::Receiver<LinkEvent<i16>> {
        self.link.events()
    }
}

impl FamilyLink for EchoHandle {
    fn family(&self) -> Family {
        Family::Echo
    }

    fn pump(&mut self, _now: Instant, _polling: bool, _log: &mut PacketLog) -> Vec<LinkNotice> {
        self.link
            .events()
            .try_iter()
            .map(|event| match event {
                LinkEvent::Driver(deg) => LinkNotice::Family(FamilyNotice::new(Echoed(deg))),
                LinkEvent::Disconnected { reason } => LinkNotice::Disconnected(reason),
            })
            .collect()
    }

    fn stop(&mut self) -> Option<FamilyNotice> {
        let _ = self.link.commands().send(EchoCommand::Stop);
        None
    }
}

/// Starts the echo driver over an opened connection.
pub(super) fn starter() -> LinkStarter {
    Box::new(|_: &Project, connection, waker| Ok(Box::new(EchoHandle::over(connection, waker)?)))
}

/// Starts the emulated echo board in this process and connects to it.
pub(super) fn demo_link(waker: Waker) -> Result<BoardLink, StartError> {
    let (board, connection) = spawn_in_memory(EchoBoard::default(), waker.clone())?;
    Ok(BoardLink::demo(Box::new(EchoHandle::over(connection, waker)?), board))
}

/// The emulated echo board behind a demo link.
pub type EmulatedEcho = SimHandle<(), BoardEvent>;
