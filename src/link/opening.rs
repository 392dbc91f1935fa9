//! Opening a port off the caller's thread: a serial port can take seconds to
//! open (a USB adapter waking up) and a TCP connect waits for its timeout, and
//! the editor's window must keep drawing meanwhile, with a Cancel.

use std::sync::Arc;

use crossbeam_channel::{Receiver, TryRecvError};

use super::connection::Connection;
use super::io_thread::Waker;
use super::port::{LineSettings, LinkError, PortName};

/// What opens a port: [`super::open`] in the app, a test double in tests.
pub type Opener = Arc<dyn Fn(&PortName, &LineSettings) -> Result<Connection, LinkError> + Send + Sync>;

/// The opener that opens real ports.
pub fn system_opener() -> Opener {
    Arc::new(super::open)
}

/// A port being opened on a helper thread. Dropping it cancels: a connection
/// that arrives afterwards is closed at once.
#[derive(Debug)]
pub struct Opening {
    /// What is being opened.
    pub port: PortName,
    outcome: Receiver<Result<Connection, LinkError>>,
}

impl Opening {
    /// Starts opening `port` with `opener`; `waker` is called when it is done.
    pub fn start(port: PortName, settings: LineSettings, opener: Opener, waker: Waker) -> Self {
        let (sender, outcome) = crossbeam_channel::bounded(1);
        let name = port.clone();
        let spawned = std::thread::Builder::new().name(format!("open {port}")).spawn(move || {
            let result = opener(&name, &settings);
            // Cancelled: the receiver is gone and the connection is dropped (closed) here.
            let _ = sender.send(result);
            waker();
        });
        if let Err(error) = spawned {
            let (sender, failed) = crossbeam_channel::bounded(1);
            let _ = sender.send(Err(LinkError::Open { port: port.to_string(), source: error }));
            return Self { port, outcome: failed };
        }
        Self { port, outcome }
    }

    /// The outcome, once the port is open or has failed to open.
    pub fn poll(&self) -> Option<Result<Connection, LinkError>> {
        match self.outcome.try_recv() {
            Ok(result) => Some(result),
            Err(TryRecvError::Empty) => None,
            Err(TryRecvError::Disconnected) => Some(Err(LinkError::Open {
                port: self.port.to_string(),
                source: std::io::Error::other("the opening thread stopped"),
            })),
        }
    }
}

#[cfg(test)]
mod tests {
    use std::time::Duration;

    use super::*;

    #[test]
    fn a_slow_open_reports_when_done_and_a_cancelled_one_closes_its_connection() {
        let (release, released) = crossbeam_channel::bounded::<()>(0);
        let (peer_tx, peer_rx) = crossbeam_channel::unbounded();
        let opener: Opener = Arc::new(move |_, _| {
            let _ = released.recv();
            let (ours, theirs) = Connection::memory_pair();
            let _ = peer_tx.send(theirs);
            Ok(ours)
        });
        let (woken_tx, woken) = crossbeam_channel::unbounded();
        let waker: Waker = Arc::new(move || {
            let _ = woken_tx.send(());
        });
        let port = PortName::parse("/dev/slow").unwrap();
        let settings = LineSettings::new(115_200);
        let opening = Opening::start(port.clone(), settings, opener.clone(), waker.clone());
        assert!(opening.poll().is_none(), "still opening");
        release.send(()).unwrap();
        woken.recv_timeout(Duration::from_secs(5)).unwrap();
        assert!(opening.poll().unwrap().is_ok());
        let _first_peer = peer_rx.recv_timeout(Duration::from_secs(5)).unwrap();

        // Cancel: drop the opening before the opener finishes.
        let cancelled = Opening::start(port, settings, opener, waker);
        drop(cancelled);
        release.send(()).unwrap();
        let mut theirs = peer_rx.recv_timeout(Duration::from_secs(5)).unwrap();
        woken.recv_timeout(Duration::from_secs(5)).unwrap();
        // The cancelled connection was dropped, so its peer reads end of stream.
        let mut byte = [0u8; 1];
        assert_eq!(std::io::Read::read(&mut theirs.reader, &mut byte).unwrap(), 0);
    }
}
