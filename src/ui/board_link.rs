//! The app shell's side of a connection: one board of one family, the demo
//! board when there is one, and the packet log. Each family brings its own
//! link ([`FamilyLink`]: its handle in `device`, which does the talking) and
//! starts it, or its built-in emulated board, itself (its `FamilyUi`); this
//! holds whichever it is, records the packet log and routes the family's
//! notices back to that family only. It names no family.

use std::any::Any;
use std::time::{Duration, Instant};

use crate::link::{Connection, DisconnectReason, Waker};
use crate::project::{Family, Project};
use crate::ui::i18n::{Language, Worded};
use crate::ui::packet_log::PacketLog;

/// Something a link reports to the shell.
#[derive(Debug)]
pub enum LinkNotice {
    /// The link ended.
    Disconnected(DisconnectReason),
    /// Something only the family's ui understands and words.
    Family(FamilyNotice),
}

/// A notice in a family's own type, which only that family takes back.
pub struct FamilyNotice(Box<dyn Any + Send>);

impl std::fmt::Debug for FamilyNotice {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("FamilyNotice")
    }
}

impl FamilyNotice {
    /// Wraps a family's notice.
    pub fn new(notice: impl Any + Send) -> Self {
        Self(Box::new(notice))
    }

    /// The notice, if it is a `T`; else itself back.
    pub fn take<T: Any>(self) -> Result<T, Self> {
        self.0.downcast().map(|notice| *notice).map_err(Self)
    }

    /// The notice, if it is a `T`.
    pub fn get<T: Any>(&self) -> Option<&T> {
        self.0.downcast_ref()
    }

    /// The notice `family` was handed, which must be its own `T`: any other
    /// type is a routing bug, loud in tests ([`misrouted`]).
    pub fn of<T: Any>(&self, family: Family) -> Option<&T> {
        let notice = self.get();
        if notice.is_none() {
            misrouted(family, "a notice", &format!("not a {}", std::any::type_name::<T>()));
        }
        notice
    }
}

/// One family's connection, as the shell holds it: the family's handle on its
/// I/O thread.
pub trait FamilyLink: Any + Send {
    /// The family it talks to.
    fn family(&self) -> Family;

    /// Picks up what the board sent: log entries go to `log`, everything else
    /// is returned (a family's own notices wrapped in [`LinkNotice::Family`]).
    fn pump(&mut self, now: Instant, polling: bool, log: &mut PacketLog) -> Vec<LinkNotice>;

    /// STOP, the family's way, ahead of anything queued; a notice when it could not be sent.
    fn stop(&mut self) -> Option<FamilyNotice>;

    /// When the link next needs a frame to refresh what it shows.
    fn next_refresh(&self, _polling: bool) -> Instant {
        Instant::now() + TELEMETRY_EVERY
    }

    /// Whether the board was stopped with STOP and not resumed.
    fn stopped(&self) -> bool {
        false
    }
}

/// How a family's driver is started over an opened connection, as its pickers
/// chose when the port was asked for.
pub type LinkStarter = Box<dyn FnOnce(&Project, Connection, Waker) -> Result<Box<dyn FamilyLink>, StartError> + Send>;

/// A connected board as the app shell sees it.
pub struct BoardLink {
    device: Box<dyn FamilyLink>,
    demo: Option<Box<dyn Any + Send>>,
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
    /// The I/O thread (or the demo board) could not start.
    Thread(String),
}

impl Worded for StartError {
    fn worded(&self, language: Language) -> String {
        match self {
            Self::Thread(text) if language == Language::English => format!("cannot start the connection: {text}"),
            Self::Thread(_) => crate::say!(language, "status.no_thread"),
        }
    }
}

impl From<std::io::Error> for StartError {
    fn from(error: std::io::Error) -> Self {
        Self::Thread(error.to_string())
    }
}

/// How often a board without polling is redrawn while connected (a base's telemetry).
const TELEMETRY_EVERY: Duration = Duration::from_millis(100);

impl BoardLink {
    /// A connection to `label` through the family's `device`.
    pub fn new(device: Box<dyn FamilyLink>, label: impl Into<String>) -> Self {
        Self { device, demo: None, label: label.into(), log: PacketLog::default() }
    }

    /// A connection to the family's built-in emulated board, `board`, kept
    /// running as long as the link.
    pub fn demo(device: Box<dyn FamilyLink>, board: impl Any + Send) -> Self {
        Self { demo: Some(Box::new(board)), ..Self::new(device, String::new()) }
    }

    /// The family connected.
    pub fn family(&self) -> Family {
        self.device.family()
    }

    /// Whether this is the in-process demo board.
    pub fn is_demo(&self) -> bool {
        self.demo.is_some()
    }

    /// The family's handle, if it is a `T`.
    pub fn device<T: Any>(&self) -> Option<&T> {
        let device: &dyn Any = &*self.device;
        device.downcast_ref()
    }

    /// The family's handle, mutably, if it is a `T`.
    pub fn device_mut<T: Any>(&mut self) -> Option<&mut T> {
        let device: &mut dyn Any = &mut *self.device;
        device.downcast_mut()
    }

    /// The emulated board behind the demo, if it is a `T`.
    pub fn emulated<T: Any>(&self) -> Option<&T> {
        self.demo.as_deref()?.downcast_ref()
    }

    /// The board was stopped with STOP and not resumed.
    pub fn stopped(&self) -> bool {
        self.device.stopped()
    }

    /// STOP, the family's way; a notice for the family when it could not be sent.
    pub fn stop(&mut self) -> Option<FamilyNotice> {
        self.device.stop()
    }

    /// Picks up what the board sent; records the packet log.
    pub fn pump(&mut self, now: Instant, polling: bool) -> Vec<LinkNotice> {
        self.device.pump(now, polling, &mut self.log)
    }

    /// When the link next needs a frame to refresh what it shows.
    pub fn next_refresh(&self, polling: bool) -> Instant {
        self.device.next_refresh(polling)
    }
}

/// A family was handed an action or a notice of another family's type: the
/// shell routed it wrong. A panic in debug builds (every test), so that it
/// is never silently dropped; said on standard error in a release build,
/// where the user's work goes on.
pub fn misrouted(family: Family, what: &str, type_name: &str) {
    let said = format!(
        "the {} family was handed {what} that is not its own ({type_name}): the shell routed it wrong",
        family.name()
    );
    if cfg!(debug_assertions) {
        panic!("{said}");
    }
    eprintln!("servo-studio: error: {said}");
}
