//! Running an emulated board of any family: in-process, behind a
//! pseudo-terminal, or on TCP. The runners take any emulator that is a
//! [`Driver`] (the server side of its protocol).

use std::io;
use std::net::{SocketAddr, TcpListener};
use std::thread::JoinHandle;

use crossbeam_channel::{Receiver, Sender};

use super::servo::{SimCommand, SimEvent};
use crate::link::{Connection, Driver, LinkEvent, LinkHandle, Owner, Waker, idle, run, spawn};

/// A running emulated board; `C` and `E` are its emulator's commands and
/// events (the servo board's by default).
pub struct SimHandle<C = SimCommand, E = SimEvent> {
    /// The port a client connects to (`/dev/pts/N`, `tcp://127.0.0.1:PORT`,
    /// or `memory` for the in-process board).
    pub port_name: String,
    inner: Inner<C, E>,
}

enum Inner<C, E> {
    Link(LinkHandle<C, E>),
    Server {
        commands: Sender<C>,
        events: Receiver<LinkEvent<E>>,
        close: Option<Sender<()>>,
        thread: Option<JoinHandle<()>>,
        address: SocketAddr,
    },
}

impl<C, E> std::fmt::Debug for SimHandle<C, E> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SimHandle").field("port_name", &self.port_name).finish_non_exhaustive()
    }
}

impl<C, E> SimHandle<C, E> {
    /// Sends a command to the board (e.g. a button press on the remote).
    pub fn command(&self, command: C) {
        // If the board has stopped, there is nobody to press buttons for.
        let _ = match &self.inner {
            Inner::Link(link) => link.commands().send(command),
            Inner::Server { commands, .. } => commands.send(command),
        };
    }

    /// What the board reports (requests handled, disconnects).
    pub fn events(&self) -> &Receiver<LinkEvent<E>> {
        match &self.inner {
            Inner::Link(link) => link.events(),
            Inner::Server { events, .. } => events,
        }
    }
}

impl<C, E> Drop for SimHandle<C, E> {
    fn drop(&mut self) {
        if let Inner::Server { close, thread, address, .. } = &mut self.inner {
            *close = None;
            // The board's thread sees the close at once; the accept thread blocks
            // in `accept`: a throwaway connection wakes it.
            if let Some(thread) = thread.take() {
                let _ = thread.join();
            }
            let _ = std::net::TcpStream::connect(*address);
        }
    }
}

/// An in-process emulator's handle and the client's end of its link.
pub type InMemory<D> = (SimHandle<<D as Driver>::Command, <D as Driver>::Event>, Connection);

/// Runs `sim` in this process; returns its handle and the client's end of the link.
pub fn spawn_in_memory<D: Driver>(sim: D, waker: Waker) -> io::Result<InMemory<D>> {
    let (board_end, client_end) = Connection::memory_pair();
    let link = spawn(board_end, sim, waker)?;
    Ok((SimHandle { port_name: "memory".into(), inner: Inner::Link(link) }, client_end))
}

/// Runs `sim` behind a pseudo-terminal; clients open [`SimHandle::port_name`].
#[cfg(unix)]
pub fn spawn_pty<D: Driver>(sim: D, waker: Waker) -> io::Result<SimHandle<D::Command, D::Event>> {
    use serialport::SerialPort;
    let to_io = |error: serialport::Error| io::Error::other(error.description);
    let (mut master, slave) = serialport::TTYPort::pair().map_err(to_io)?;
    master.set_timeout(crate::link::READ_WAKE).map_err(to_io)?;
    let port_name = slave.name().ok_or_else(|| io::Error::other("the pseudo-terminal has no name"))?;
    let mut connection = Connection::from_serial(Box::new(master), port_name.clone())?;
    // Keep the client's end open ourselves, so that the board's end never
    // reads "end of file" between clients: the board outlives each of them.
    connection.keep_alive(Box::new(slave));
    let link = spawn(connection, sim, waker)?;
    Ok(SimHandle { port_name, inner: Inner::Link(link) })
}

/// Runs `sim` as a TCP server on `address` (port 0 picks one). One client at
/// a time; the board keeps its contents from one client to the next, and
/// runs on its own between clients (its clock, its dead-man), as a real
/// board does with no cable in.
pub fn spawn_tcp<D: Driver>(sim: D, address: SocketAddr, waker: Waker) -> io::Result<SimHandle<D::Command, D::Event>> {
    let listener = TcpListener::bind(address)?;
    let port_name = format!("tcp://{}", listener.local_addr()?);
    let (command_tx, command_rx) = crossbeam_channel::unbounded();
    let (close_tx, close_rx) = crossbeam_channel::bounded::<()>(0);
    let (event_tx, event_rx) = crossbeam_channel::unbounded();
    let (client_tx, client_rx) = crossbeam_channel::bounded::<std::net::TcpStream>(0);
    let wake_listener = listener.local_addr()?;
    // Accepting blocks: it has a thread of its own, handing each client over.
    let accept_close = close_rx.clone();
    std::thread::Builder::new().name("sim tcp accept".into()).spawn(move || {
        for stream in listener.incoming() {
            if matches!(accept_close.try_recv(), Err(crossbeam_channel::TryRecvError::Disconnected)) {
                return;
            }
            let Ok(stream) = stream else { continue };
            if client_tx.send(stream).is_err() {
                return;
            }
        }
    })?;
    let thread = std::thread::Builder::new().name("sim tcp".into()).spawn(move || {
        let owner = Owner { commands: command_rx, close: close_rx };
        let mut sim = sim;
        while let Some(stream) = idle(&mut sim, &owner, &client_rx, &event_tx, &waker) {
            let description = stream.peer_addr().map_or_else(|_| "client".to_string(), |peer| peer.to_string());
            let Ok(connection) = Connection::from_tcp(stream, description) else {
                continue;
            };
            sim = run(connection, sim, &owner, &event_tx, &waker);
            if matches!(owner.close.try_recv(), Err(crossbeam_channel::TryRecvError::Disconnected)) {
                return;
            }
        }
    })?;
    Ok(SimHandle {
        port_name,
        inner: Inner::Server {
            commands: command_tx,
            events: event_rx,
            close: Some(close_tx),
            thread: Some(thread),
            address: wake_listener,
        },
    })
}
