//! The link desk: what connecting needs besides the link itself — the port
//! list (read on its own thread), a port being opened, the connection
//! doctor, the connection bar's own state, and links being closed.

use std::time::{Duration, Instant};

use crossbeam_channel::{Receiver, RecvTimeoutError, Sender};

use super::PortLister;
use super::doctor::Doctor;
use crate::link::{Opener, Opening, PortInfo, Waker, system_opener};
use crate::project::Family;
use crate::ui::board_link::BoardLink;
use crate::ui::connection_bar::ConnectionBar;

/// A port being opened.
pub struct Connecting {
    /// The opening, on its own thread.
    pub opening: Opening,
    /// The family whose driver starts once it is open.
    pub family: Family,
    /// The line rate asked for.
    pub baud: u32,
    /// How its driver is started.
    pub starter: crate::ui::board_link::LinkStarter,
    /// A lost link being made again: a port not there yet is not an error.
    pub quiet: bool,
}

impl std::fmt::Debug for Connecting {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Connecting")
            .field("opening", &self.opening)
            .field("family", &self.family)
            .finish_non_exhaustive()
    }
}

/// Connecting, apart from the link.
pub struct LinkDesk {
    /// A port being opened (off the UI thread), with the family and line rate to start.
    pub connecting: Option<Connecting>,
    /// The serial ports seen at the last scan.
    pub ports: Vec<PortInfo>,
    pub(super) opener: Opener,
    pub(super) lister: PortLister,
    pub(super) scanner: Option<PortScanner>,
    /// Links being closed on their own threads.
    pub(super) closing: Vec<std::thread::JoinHandle<()>>,
    pub(super) bar: ConnectionBar,
    pub(super) doctor: Doctor,
    /// The board lent to remote control, to connect to again when it comes back.
    pub(super) lent: Option<super::lent::Lent>,
    waker: Waker,
}

impl LinkDesk {
    /// Nothing connecting yet; ports opened and listed the system's way.
    pub(super) fn new(waker: Waker) -> Self {
        Self {
            connecting: None,
            ports: Vec::new(),
            opener: system_opener(),
            lister: super::system_lister(),
            scanner: None,
            closing: Vec::new(),
            bar: ConnectionBar::default(),
            doctor: Doctor::default(),
            lent: None,
            waker,
        }
    }
}

/// How often the port list is read again.
const RESCAN_EVERY: Duration = Duration::from_secs(2);

/// The port list, read on its own thread.
#[derive(Debug)]
pub(super) struct PortScanner {
    lists: Receiver<Vec<PortInfo>>,
    /// Dropped with the scanner: the thread ends at its next turn.
    _stop: Sender<()>,
}

impl PortScanner {
    pub(super) fn start(lister: PortLister, waker: Waker) -> Option<Self> {
        let (lists_tx, lists) = crossbeam_channel::bounded(1);
        let (stop, stopped) = crossbeam_channel::bounded::<()>(0);
        std::thread::Builder::new()
            .name("port list".into())
            .spawn(move || {
                loop {
                    // A failed scan leaves the last list; the port can still be typed.
                    // A list the window has not taken yet is newer than none: this one waits for the next turn.
                    if let Ok(ports) = lister()
                        && lists_tx.try_send(ports).is_ok()
                    {
                        waker();
                    }
                    match stopped.recv_timeout(RESCAN_EVERY) {
                        Err(RecvTimeoutError::Timeout) => {}
                        _ => break,
                    }
                }
            })
            .ok()?;
        Some(Self { lists, _stop: stop })
    }
}

impl LinkDesk {
    /// Takes the newest port list, starting the scanner the first time.
    pub(super) fn scan_ports(&mut self) {
        if self.scanner.is_none() {
            self.scanner = PortScanner::start(self.lister.clone(), self.waker.clone());
        }
        if let Some(ports) = self.scanner.as_ref().and_then(|scanner| scanner.lists.try_iter().last()) {
            self.ports = ports;
        }
    }

    /// Reads ports with `lister` from now on (the scanner starts again).
    #[cfg(any(test, feature = "test-api"))]
    pub(super) fn list_with(&mut self, lister: PortLister) {
        self.lister = lister;
        self.scanner = None;
    }

    /// Closes `link` without waiting for it: a base's shutdown (stop, then
    /// brake) finishes on its own thread; the window's end waits for it.
    pub(super) fn close(&mut self, link: BoardLink) {
        // No thread: the link is shut down here, as the closure is dropped.
        if let Ok(closing) = std::thread::Builder::new().name("link shutdown".into()).spawn(move || drop(link)) {
            self.closing.push(closing);
        }
        self.closing.retain(|closing| !closing.is_finished());
    }

    /// Waits for every link being closed (the window is going: the base must
    /// have stopped), until `deadline` at the latest.
    pub(super) fn wait_for_closing(&mut self, deadline: Instant) {
        // Not joined blindly: a link stuck in a write (a pulled USB adapter
        // the kernel has not let go of yet) must not keep the window open.
        while self.closing.iter().any(|closing| !closing.is_finished()) && Instant::now() < deadline {
            std::thread::sleep(Duration::from_millis(5));
        }
        for closing in self.closing.drain(..) {
            if closing.is_finished() {
                let _ = closing.join();
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use super::*;
    use crate::ui::ServoBoardLink;

    #[test]
    fn the_port_list_arrives_from_its_own_thread_and_a_new_lister_starts_again() {
        let (waker, woken) = crossbeam_channel::unbounded::<()>();
        let waker: Waker = Arc::new(move || {
            let _ = waker.send(());
        });
        let mut desk = LinkDesk::new(waker);
        let port = |name: &str| PortInfo { name: name.into(), description: String::new() };
        let first = vec![port("/dev/ttyUSB0")];
        let listed = first.clone();
        desk.list_with(Arc::new(move || Ok(listed.clone())));
        desk.scan_ports();
        while desk.ports.is_empty() {
            woken.recv_timeout(Duration::from_secs(10)).expect("the list came");
            desk.scan_ports();
        }
        assert_eq!(desk.ports, first);
        desk.list_with(Arc::new(move || Ok(vec![port("/dev/ttyACM0")])));
        assert!(desk.scanner.is_none(), "the old scanner is dropped");
        desk.scan_ports();
        // A wake may still come from the old scanner: wait for the new list itself.
        while desk.ports[0].name != "/dev/ttyACM0" {
            woken.recv_timeout(Duration::from_secs(10)).expect("the new list came");
            desk.scan_ports();
        }
    }

    /// A link whose closing never ends (a write the kernel holds) is waited
    /// for until the deadline, not for ever: the window's end is bounded.
    #[test]
    fn a_link_that_never_finishes_closing_is_waited_for_until_the_deadline_only() {
        let mut desk = LinkDesk::new(crate::link::no_waker());
        let (_never, held) = crossbeam_channel::bounded::<()>(0);
        desk.closing.push(std::thread::spawn(move || {
            let _ = held.recv();
        }));
        let (done, finished) = crossbeam_channel::bounded(1);
        std::thread::spawn(move || {
            desk.wait_for_closing(Instant::now() + Duration::from_millis(200));
            let _ = done.send(desk.closing.len());
        });
        assert_eq!(finished.recv_timeout(Duration::from_secs(30)), Ok(0), "it returned, the stuck closing let go");
    }

    #[test]
    fn a_closed_link_is_waited_for_only_at_the_end() {
        let mut desk = LinkDesk::new(crate::link::no_waker());
        let project = crate::project::Project::default();
        let link = crate::ui::servo_demo_link(&project, crate::sim::SimConfig::default(), crate::link::no_waker())
            .expect("the demo board starts");
        let heard = link.demo_board().expect("the emulated board").events().clone();
        desk.close(link);
        desk.wait_for_closing(Instant::now() + Duration::from_secs(60));
        assert!(desk.closing.is_empty());
        // The link and its emulated board are gone once waited for: the board's events end.
        let deadline = Instant::now() + Duration::from_secs(10);
        loop {
            match heard.recv_deadline(deadline) {
                Ok(_) => {}
                Err(RecvTimeoutError::Disconnected) => break,
                Err(RecvTimeoutError::Timeout) => panic!("the emulated board still runs"),
            }
        }
    }
}
