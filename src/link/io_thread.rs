//! The one I/O thread: the only code that touches a port. It drives a sans-IO
//! [`Driver`] (a protocol session, or an emulated board): commands in over a
//! channel, bytes in from the port, timeouts from the driver's own deadline;
//! bytes out to the port, events out over a channel.
//!
//! A helper thread blocks in the port's `read` and forwards what arrives, so
//! the I/O thread wakes the moment bytes, a command, or a deadline arrives,
//! with no polling sleep anywhere on the path.

use std::io::{self, Read};
use std::sync::Arc;
use std::thread::JoinHandle;
use std::time::Instant;

use crossbeam_channel::{Receiver, Select, Sender};

use super::connection::Connection;
use super::driver::Driver;
use super::output::Output;

/// How long the owner's last words (see [`Driver::is_last_word`]) may take
/// to go out once it has closed the link.
pub const LAST_WORDS: std::time::Duration = std::time::Duration::from_millis(500);

/// Why a link ended, as data (an interface words it in its own language);
/// `Display` gives English.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum DisconnectReason {
    /// The owner closed it.
    #[error("the link was closed")]
    Closed,
    /// The driver asked to close it (e.g. an emulated board's injected disconnect).
    #[error("the link was closed by the driver")]
    ClosedByDriver,
    /// The other end closed the port or connection.
    #[error("the port was closed by the other end")]
    ClosedByPeer,
    /// Reading failed: usually a pulled cable or a board that lost power.
    #[error("reading from the port failed: {0} (was the cable pulled?)")]
    ReadFailed(String),
    /// Writing failed: usually a pulled cable or a board that lost power.
    #[error("writing to the port failed: {0} (was the cable pulled?)")]
    WriteFailed(String),
    /// The link's helper thread could not start or stopped.
    #[error("the link's reader thread failed: {0}")]
    ThreadFailed(String),
}

/// What the I/O thread reports.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum LinkEvent<E> {
    /// An event of the driver.
    Driver(E),
    /// The link ended; nothing more will come.
    Disconnected {
        /// Why.
        reason: DisconnectReason,
    },
}

/// Called after the I/O thread has queued events, to wake the owner (the GUI
/// passes a closure that requests a repaint).
pub type Waker = Arc<dyn Fn() + Send + Sync>;

/// A waker that does nothing, for owners that block on the event channel.
pub fn no_waker() -> Waker {
    Arc::new(|| {})
}

/// The owner's side of a running link. Dropping it closes the link and waits
/// for the I/O thread to release the port.
pub struct LinkHandle<C, E> {
    commands: Sender<C>,
    /// Dropping this tells the I/O thread to end, even while workers still
    /// hold clones of `commands`.
    close: Option<Sender<()>>,
    events: Receiver<LinkEvent<E>>,
    thread: Option<JoinHandle<()>>,
    description: String,
}

impl<C, E> std::fmt::Debug for LinkHandle<C, E> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("LinkHandle").field("description", &self.description).finish_non_exhaustive()
    }
}

impl<C, E> LinkHandle<C, E> {
    /// A sender for commands; clone it freely (e.g. for an operation's worker thread).
    pub fn commands(&self) -> Sender<C> {
        self.commands.clone()
    }

    /// The event receiver.
    pub fn events(&self) -> &Receiver<LinkEvent<E>> {
        &self.events
    }

    /// What the link is connected to.
    pub fn description(&self) -> &str {
        &self.description
    }

    /// Closes the link and waits for the I/O thread to release the port.
    pub fn close(self) {
        drop(self);
    }
}

impl<C, E> Drop for LinkHandle<C, E> {
    fn drop(&mut self) {
        self.close = None;
        if let Some(thread) = self.thread.take() {
            // A panic inside the thread has already been reported as a disconnect.
            let _ = thread.join();
        }
    }
}

/// The owner's channels, as the I/O thread sees them.
pub struct Owner<C> {
    /// Commands for the driver.
    pub commands: Receiver<C>,
    /// Disconnected when the owner wants the link closed.
    pub close: Receiver<()>,
}

enum Input {
    /// Bytes and when the port handed them over (not when this thread got to them).
    Bytes(Vec<u8>, Instant),
    Ended(DisconnectReason),
}

/// Starts the I/O thread for `driver` over `connection`.
pub fn spawn<D: Driver>(
    connection: Connection,
    driver: D,
    waker: Waker,
) -> io::Result<LinkHandle<D::Command, D::Event>> {
    let (command_tx, command_rx) = crossbeam_channel::unbounded();
    let (close_tx, close_rx) = crossbeam_channel::bounded(0);
    let (event_tx, event_rx) = crossbeam_channel::unbounded();
    let description = connection.description.clone();
    let thread = std::thread::Builder::new().name(format!("io {description}")).spawn(move || {
        let owner = Owner { commands: command_rx, close: close_rx };
        run(connection, driver, &owner, &event_tx, &waker);
    })?;
    Ok(LinkHandle { commands: command_tx, close: Some(close_tx), events: event_rx, thread: Some(thread), description })
}

/// Drives `driver` over `connection` on the calling thread until the link
/// ends, then hands the driver back (a server keeps its state across clients).
pub fn run<D: Driver>(
    connection: Connection,
    mut driver: D,
    owner: &Owner<D::Command>,
    events: &Sender<LinkEvent<D::Event>>,
    waker: &Waker,
) -> D {
    let Connection { reader, mut writer, shutdown, half_close, keep, min_write_gap, .. } = connection;
    let (input_tx, input_rx) = crossbeam_channel::unbounded();
    let (stop_tx, stop_rx) = crossbeam_channel::bounded::<()>(0);
    let reader_thread =
        std::thread::Builder::new().name("io reader".into()).spawn(move || read_loop(reader, &input_tx, &stop_rx));
    let reason = match &reader_thread {
        Ok(_) => {
            let mut output = Output::new(&mut *writer, min_write_gap);
            drive(&mut driver, &mut output, owner, &input_rx, events, waker)
        }
        Err(error) => DisconnectReason::ThreadFailed(error.to_string()),
    };
    if let Some(half_close) = half_close.filter(|_| matches!(reason, DisconnectReason::Closed)) {
        // Every byte written (a stop, a brake) has reached the board once it
        // closes its side in turn, as a board or its bridge does at once: waited for, briefly.
        half_close();
        let deadline = Instant::now() + PEER_CLOSES_WITHIN;
        while let Ok(Input::Bytes(..)) = input_rx.recv_deadline(deadline) {}
    }
    driver.handle_disconnect(&reason.to_string());
    forward_events(&mut driver, events);
    let _ = events.send(LinkEvent::Disconnected { reason });
    waker();
    // Release the port: stop and wake the reader, then wait for it to let go
    // (at once for TCP and memory, within one read timeout for serial ports).
    drop(stop_tx);
    drop(input_rx);
    if let Some(shutdown) = shutdown {
        shutdown();
    }
    drop(writer);
    if let Ok(handle) = reader_thread {
        let _ = handle.join();
    }
    drop(keep);
    driver
}

/// Drives `driver` with no link at all — its clock, its commands, its
/// events; whatever it would write goes nowhere, as a real board's output
/// does with no cable in — until `next` yields (e.g. the next client of a
/// server) or the owner closes. Returns what `next` yielded, or `None`.
pub fn idle<D: Driver, T>(
    driver: &mut D,
    owner: &Owner<D::Command>,
    next: &Receiver<T>,
    events: &Sender<LinkEvent<D::Event>>,
    waker: &Waker,
) -> Option<T> {
    loop {
        let now = Instant::now();
        if driver.poll_timeout().is_some_and(|deadline| deadline <= now) {
            driver.handle_timeout(now);
        }
        while driver.poll_transmit(now).is_some() {}
        if forward_events(driver, events) {
            waker();
        }
        let mut select = Select::new();
        let command_index = select.recv(&owner.commands);
        let close_index = select.recv(&owner.close);
        let next_index = select.recv(next);
        let operation = match driver.poll_timeout() {
            Some(deadline) => match select.select_deadline(deadline) {
                Ok(operation) => operation,
                Err(_) => continue,
            },
            None => select.select(),
        };
        match operation.index() {
            index if index == command_index => match operation.recv(&owner.commands) {
                Ok(command) => driver.handle_command(Instant::now(), command),
                Err(_) => return None,
            },
            index if index == close_index => {
                let _ = operation.recv(&owner.close);
                return None;
            }
            index if index == next_index => return operation.recv(next).ok(),
            _ => {}
        }
    }
}

fn forward_events<D: Driver>(driver: &mut D, events: &Sender<LinkEvent<D::Event>>) -> bool {
    let mut any = false;
    while let Some(event) = driver.poll_event() {
        // The owner may have gone; then nobody needs the event.
        let _ = events.send(LinkEvent::Driver(event));
        any = true;
    }
    any
}

/// Runs until the link ends; returns why.
fn drive<D: Driver>(
    driver: &mut D,
    output: &mut Output<'_>,
    owner: &Owner<D::Command>,
    input: &Receiver<Input>,
    events: &Sender<LinkEvent<D::Event>>,
    waker: &Waker,
) -> DisconnectReason {
    loop {
        let now = Instant::now();
        if driver.poll_timeout().is_some_and(|deadline| deadline <= now) {
            driver.handle_timeout(now);
        }
        if let Err(error) = output.flush_from(driver, now) {
            return DisconnectReason::WriteFailed(error.to_string());
        }
        if forward_events(driver, events) {
            waker();
        }
        if driver.wants_close() {
            return DisconnectReason::ClosedByDriver;
        }
        let mut select = Select::new();
        let command_index = select.recv(&owner.commands);
        let close_index = select.recv(&owner.close);
        let input_index = select.recv(input);
        let deadline = match (driver.poll_timeout(), output.ready_at()) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        };
        let operation = match deadline {
            Some(deadline) => match select.select_deadline(deadline) {
                Ok(operation) => operation,
                Err(_) => continue, // deadline reached: handled at the top (timeouts, held bytes)
            },
            None => select.select(),
        };
        let now = Instant::now();
        match operation.index() {
            index if index == command_index => match operation.recv(&owner.commands) {
                Ok(command) => driver.handle_command(now, command),
                Err(_) => return DisconnectReason::Closed,
            },
            index if index == close_index => {
                let _ = operation.recv(&owner.close);
                // A close and a command sent just before it can be ready at
                // once, and either may be picked first: a stop sent on the
                // way out still goes out (on a loaded machine it did not).
                last_words(driver, output, owner);
                return DisconnectReason::Closed;
            }
            index if index == input_index => match operation.recv(input) {
                // The time they arrived: a thread scheduled late must not make
                // bytes that came apart look as if they came together.
                Ok(Input::Bytes(bytes, arrived)) => driver.handle_input(arrived.min(now), &bytes),
                Ok(Input::Ended(reason)) => return reason,
                Err(_) => return DisconnectReason::ThreadFailed("the port reader stopped".into()),
            },
            _ => {}
        }
    }
}

/// The owner has closed the link: the last words still queued (a base's
/// stop and brake) are carried out and written, within [`LAST_WORDS`];
/// every other command is dropped.
fn last_words<D: Driver>(driver: &mut D, output: &mut Output<'_>, owner: &Owner<D::Command>) {
    let mut said = false;
    for command in owner.commands.try_iter() {
        if driver.is_last_word(&command) {
            driver.handle_command(Instant::now(), command);
            said = true;
        }
    }
    if !said {
        return;
    }
    let deadline = Instant::now() + LAST_WORDS;
    loop {
        let now = Instant::now();
        if output.flush_from(driver, now).is_err() {
            return;
        }
        match output.ready_at() {
            // Every byte the driver had went out.
            None => return,
            Some(_) if now >= deadline => return,
            // The write gap or a full port: the owner waits for this thread, so wait here.
            Some(at) => std::thread::sleep(at.min(deadline).saturating_duration_since(now).max(WAIT_STEP)),
        }
    }
}

/// How long a closing TCP link waits for the board to close its side after ours.
pub const PEER_CLOSES_WITHIN: std::time::Duration = std::time::Duration::from_millis(250);

/// The shortest wait between tries to write last words.
const WAIT_STEP: std::time::Duration = std::time::Duration::from_millis(1);

fn read_loop(mut reader: Box<dyn Read + Send>, input: &Sender<Input>, stop: &Receiver<()>) {
    let mut buffer = vec![0u8; 4096];
    loop {
        if matches!(stop.try_recv(), Err(crossbeam_channel::TryRecvError::Disconnected)) {
            return;
        }
        let ended = match reader.read(&mut buffer) {
            Ok(0) => DisconnectReason::ClosedByPeer,
            Ok(len) => {
                if input.send(Input::Bytes(buffer[..len].to_vec(), Instant::now())).is_err() {
                    return;
                }
                continue;
            }
            Err(error)
                if matches!(
                    error.kind(),
                    io::ErrorKind::TimedOut | io::ErrorKind::WouldBlock | io::ErrorKind::Interrupted
                ) =>
            {
                continue;
            }
            Err(error) => DisconnectReason::ReadFailed(error.to_string()),
        };
        let _ = input.send(Input::Ended(ended));
        return;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::VecDeque;
    use std::time::Duration;

    /// A driver that writes what it is told, some of it as last words.
    struct Told {
        out: VecDeque<Vec<u8>>,
    }

    impl Driver for Told {
        /// Whether a last word, and its bytes.
        type Command = (bool, Vec<u8>);
        type Event = ();
        fn handle_command(&mut self, _: Instant, (_, bytes): (bool, Vec<u8>)) {
            self.out.push_back(bytes);
        }
        fn handle_input(&mut self, _: Instant, _: &[u8]) {}
        fn handle_timeout(&mut self, _: Instant) {}
        fn handle_disconnect(&mut self, _: &str) {}
        fn poll_transmit(&mut self, _: Instant) -> Option<Vec<u8>> {
            self.out.pop_front()
        }
        fn poll_event(&mut self) -> Option<()> {
            None
        }
        fn poll_timeout(&self) -> Option<Instant> {
            None
        }
        fn is_last_word(&self, (last, _): &(bool, Vec<u8>)) -> bool {
            *last
        }
    }

    /// The owner sends a stop and closes at once; the thread finds both
    /// ready, and a select picks either first. Whichever it picks, the stop
    /// goes out before the link ends; a command that is no last word, found
    /// queued at the close, does not. (Each pick is a coin toss: twenty runs
    /// would all pass without the last words with a chance of one in a million.)
    #[test]
    fn a_last_word_sent_just_before_the_close_goes_out_whichever_the_thread_sees_first() {
        for _ in 0..20 {
            let (commands, command_rx) = crossbeam_channel::unbounded();
            let (close, close_rx) = crossbeam_channel::bounded::<()>(0);
            let (_input, input_rx) = crossbeam_channel::unbounded();
            let (events, _events) = crossbeam_channel::unbounded();
            commands.send((true, b"STOP".to_vec())).unwrap();
            drop(close);
            let owner = Owner { commands: command_rx, close: close_rx };
            let mut port: Vec<u8> = Vec::new();
            let mut output = Output::new(&mut port, Duration::ZERO);
            let mut driver = Told { out: VecDeque::new() };
            let reason = drive(&mut driver, &mut output, &owner, &input_rx, &events, &no_waker());
            assert_eq!(reason, DisconnectReason::Closed);
            drop(output);
            assert_eq!(port, b"STOP", "the stop went out");
        }
        // Found queued at the close, a command that is no last word is dropped.
        let (commands, command_rx) = crossbeam_channel::unbounded();
        commands.send((false, b"MOVE".to_vec())).unwrap();
        let (close, close_rx) = crossbeam_channel::bounded::<()>(0);
        drop(close);
        let owner = Owner { commands: command_rx, close: close_rx };
        let mut port: Vec<u8> = Vec::new();
        let mut output = Output::new(&mut port, Duration::ZERO);
        last_words(&mut Told { out: VecDeque::new() }, &mut output, &owner);
        drop(output);
        assert!(port.is_empty(), "nothing but last words at the close");
    }

    /// Closing a TCP link: the last words are written and our side
    /// half-closed (a FIN after them); the close waits for the board to close
    /// its side — here it never does, so the close takes the whole bound — and
    /// the board, reading later, finds every byte and then the end.
    #[test]
    fn a_tcp_link_waits_for_the_board_to_close_its_side_after_the_last_words() {
        let listener = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
        let address = listener.local_addr().unwrap();
        let (closed, told) = crossbeam_channel::bounded::<()>(1);
        let board = std::thread::spawn(move || {
            let (mut stream, _) = listener.accept().unwrap();
            // Reads nothing, closes nothing, until the owner's close has returned.
            let _ = told.recv();
            let mut heard = Vec::new();
            stream.read_to_end(&mut heard).unwrap();
            heard
        });
        let stream = std::net::TcpStream::connect(address).unwrap();
        let connection = Connection::from_tcp(stream, "board".into()).unwrap();
        let link = spawn(connection, Told { out: VecDeque::new() }, no_waker()).unwrap();
        link.commands().send((true, b"STOP".to_vec())).unwrap();
        let began = Instant::now();
        link.close();
        assert!(began.elapsed() >= PEER_CLOSES_WITHIN, "the close waited for the board: {:?}", began.elapsed());
        closed.send(()).unwrap();
        assert_eq!(board.join().unwrap(), b"STOP", "every byte, then the end");
    }
}
