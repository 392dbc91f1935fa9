//! The PLEN2 family's driver: the paced driver the I/O thread runs, a blocking
//! requester for worker threads (upload, export), the non-blocking handle the
//! editor uses, and the operations (export, import with backup and
//! verification, joint settings).

mod convert;
mod doctor;
mod driver;
mod link_report;
mod messages;
mod ops;
mod pacer;
pub mod playback;

use std::time::Instant;

use crossbeam_channel::Sender;

pub use convert::{
    NotStorable, Unstorable, frames_of, motion_commands, motion_from_reply, storable, store_commands, stored_motion,
};
pub use doctor::Said;
pub use driver::{
    ERASED_REPLY_BYTES, Pacing, Plen2Command, Plen2Driver, Plen2Event, Plen2Options, REPLY_IDLE, RESYNC, ReplyError,
    ReplyNews, ReplySender,
};
pub use ops::{
    Plen2Import, Plen2ImportFailure, Plen2ImportOptions, Plen2ImportReport, Plen2Info, Plen2Item, Plen2OpError,
    Plen2Phase, Plen2Progress, SlotResult, export, import, info, read_joint_settings, read_slot, read_slot_noting,
    write_joint_settings,
};
pub use pacer::{
    CLUMP_GAP, LinkReport, Pacer, PacingMode, RING_WINDOW_BYTES, SAFE_BURST, SAFE_PAUSE, WidenReason, Widened,
};

use crate::device::LogEntry;

inventory::submit! {
    crate::device::family::Registered {
        family: crate::project::Family::Plen2,
        // plen2.md §1: USB CDC at 2,000,000 baud; DTR must be asserted.
        line: || link::LineSettings::new(BAUD),
        // First: USB CDC answers at any rate, and it answers fastest.
        doctor: Some(crate::device::family::Doctor { rank: 0, recogniser: doctor::recogniser }),
    }
}
use crate::link::{self, Connection, DisconnectReason, LinkEvent, LinkHandle, Waker};
pub use crate::protocol::plen2::Command;

/// The PLEN2's line rate (USB CDC; plen2.md §1).
pub const BAUD: u32 = 2_000_000;

/// How long after `$PM` for `slot` is sent the robot's joints first move,
/// as best it can be known: the command's time on the line after the link's
/// `latency`, then the wait for the firmware's next 32.768 ms update ("cycle 0
/// is the first update after `$PM` is read", plen2.md §6). That update's timer
/// runs free, so the wait is anything up to a cycle: half a cycle is counted,
/// which keeps a sound started with the motion within half an update of it.
pub fn play_motion_delay(slot: u8, latency: std::time::Duration) -> std::time::Duration {
    start_delay(&Command::PlayMotion { slot }, latency)
}

/// The same for `command`, which starts a motion: `$PM`, or `#PO` starting
/// the queued ones (a popped `#PU` plays as `$PM` does, plen2.md §6).
pub fn start_delay(command: &Command, latency: std::time::Duration) -> std::time::Duration {
    let on_line = crate::audio::together::link_delay(command.to_ascii().len(), BAUD, latency);
    on_line + std::time::Duration::from_micros(playback::CYCLE_US / 2)
}

/// A sent command the robot is still predicted to be working on.
#[derive(Debug)]
pub struct Finished(crossbeam_channel::Receiver<Result<(), ReplyError>>);

impl Finished {
    /// Waits until the robot should have finished it (or STOP dropped it).
    pub fn wait(self) -> Result<(), ReplyError> {
        self.0.recv().unwrap_or(Err(ReplyError::Disconnected))
    }
}

/// Blocking calls to a PLEN2 from a worker thread.
#[derive(Clone, Debug)]
pub struct Plen2Requester {
    commands: Sender<Plen2Command>,
}

impl Plen2Requester {
    /// Sends a command, paced; returns once it is queued.
    pub fn send(&self, command: Command) -> Result<(), ReplyError> {
        self.commands.send(Plen2Command::Send { command, done: None }).map_err(|_| ReplyError::Disconnected)
    }

    /// Sends a command and waits until the robot should have finished it (EEPROM included).
    pub fn send_and_wait(&self, command: Command) -> Result<(), ReplyError> {
        self.send_then_finished(command)?.wait()
    }

    /// Sends a command; the answer says when the robot should have finished
    /// it (EEPROM included), so more can be queued behind it meanwhile.
    pub fn send_then_finished(&self, command: Command) -> Result<Finished, ReplyError> {
        let (done, finished) = crossbeam_channel::bounded(1);
        self.commands.send(Plen2Command::Send { command, done: Some(done) }).map_err(|_| ReplyError::Disconnected)?;
        Ok(Finished(finished))
    }

    /// Sends a getter and waits for its reply. If none comes, the firmware's
    /// parser may be stuck inside a command whose bytes were lost: the resync
    /// bytes end it, and the getter is sent once more.
    pub fn get(&self, command: Command) -> Result<Vec<u8>, ReplyError> {
        self.get_noting(command, &mut |_| {})
    }

    /// Before an upload: lets the adaptive pacing see how the link delivers
    /// (a reply is read once per session, if none was yet).
    pub fn probe(&self) -> Result<(), ReplyError> {
        let (reply, outcome) = crossbeam_channel::bounded(1);
        self.commands.send(Plen2Command::Probe { reply }).map_err(|_| ReplyError::Disconnected)?;
        outcome.recv().unwrap_or(Err(ReplyError::Disconnected)).map(|_| ())
    }

    /// Sends a getter, paced, without waiting: its reply (or why none came) arrives on the returned receiver.
    pub fn ask(
        &self,
        command: Command,
    ) -> Result<crossbeam_channel::Receiver<Result<Vec<u8>, ReplyError>>, ReplyError> {
        let (reply, outcome) = crossbeam_channel::bounded(1);
        self.commands.send(Plen2Command::Get { command, reply, news: None }).map_err(|_| ReplyError::Disconnected)?;
        Ok(outcome)
    }

    /// A slot read back different: the adaptive pacing widens its margins.
    pub fn read_back_differed(&self) -> Result<(), ReplyError> {
        self.commands.send(Plen2Command::ReadBackDiffered).map_err(|_| ReplyError::Disconnected)
    }

    /// As [`Plen2Requester::get`], telling `on_news` what the reply turns out
    /// to be while it still arrives (an erased slot takes long).
    pub fn get_noting(&self, command: Command, on_news: &mut dyn FnMut(ReplyNews)) -> Result<Vec<u8>, ReplyError> {
        match self.get_once(command.clone(), on_news) {
            Err(ReplyError::Timeout { .. }) => {
                self.commands.send(Plen2Command::Resync).map_err(|_| ReplyError::Disconnected)?;
                self.get_once(command, on_news)
            }
            other => other,
        }
    }

    fn get_once(&self, command: Command, on_news: &mut dyn FnMut(ReplyNews)) -> Result<Vec<u8>, ReplyError> {
        let (reply, outcome) = crossbeam_channel::bounded(1);
        let (news, told) = crossbeam_channel::unbounded();
        self.commands
            .send(Plen2Command::Get { command, reply, news: Some(news) })
            .map_err(|_| ReplyError::Disconnected)?;
        loop {
            crossbeam_channel::select! {
                recv(outcome) -> result => return result.unwrap_or(Err(ReplyError::Disconnected)),
                recv(told) -> news => match news {
                    Ok(news) => on_news(news),
                    // The driver dropped it with the reply: the outcome is there.
                    Err(_) => return outcome.recv().unwrap_or(Err(ReplyError::Disconnected)),
                },
            }
        }
    }
}

/// What the handle reports to its owner.
#[derive(Clone, Debug, PartialEq)]
pub enum Plen2Notice {
    /// A packet-log entry.
    Log(LogEntry),
    /// The adaptive pacing widened its margins (said in the log and on the progress line).
    Widened(Widened),
    /// The link ended.
    Disconnected(DisconnectReason),
}

/// A connected PLEN2, driven without blocking. Dropping it closes the link.
pub struct Plen2Handle {
    link: LinkHandle<Plen2Command, Plen2Event>,
    pacing: PacingMode,
    /// STOP was pressed and nothing moved since.
    pub stopped: bool,
}

impl std::fmt::Debug for Plen2Handle {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Plen2Handle").field("link", &self.link).finish_non_exhaustive()
    }
}

impl Plen2Handle {
    /// Starts the I/O thread over an open connection.
    pub fn over(connection: Connection, options: Plen2Options, waker: Waker) -> std::io::Result<Self> {
        let link = link::spawn(connection, Plen2Driver::new(options), waker)?;
        // The link is measured before anything relies on it (plen2.md §5: the
        // first EEPROM write must not overrun the ring, whatever the line).
        let (reply, _) = crossbeam_channel::bounded(1);
        let _ = link.commands().send(Plen2Command::Probe { reply });
        Ok(Self { link, pacing: options.mode, stopped: false })
    }

    /// How uploads on this link are paced.
    pub fn pacing(&self) -> PacingMode {
        self.pacing
    }

    /// A requester for worker threads.
    pub fn requester(&self) -> Plen2Requester {
        Plen2Requester { commands: self.link.commands() }
    }

    fn command(&self, command: Plen2Command) {
        // A closed link is reported by `pump`.
        let _ = self.link.commands().send(command);
    }

    fn send(&self, command: Command) {
        self.command(Plen2Command::Send { command, done: None });
    }

    /// Joints to absolute angles, coalesced (the latest per joint wins), paced.
    pub fn move_joints(&mut self, moves: Vec<(u8, i16)>) {
        self.stopped = false;
        self.command(Plen2Command::LiveAngles(moves));
    }

    /// Every joint to home (`$HP`).
    pub fn home(&self) {
        self.send(Command::HomePosition);
    }

    /// Plays a stored motion (`$PM`).
    pub fn play(&mut self, slot: u8) {
        self.stopped = false;
        self.send(Command::PlayMotion { slot });
    }

    /// Queues motions to be played one after another (`#RI`, a `#PU` each):
    /// `#PO` starts them.
    pub fn queue_list(&mut self, entries: &[(u8, u8)]) {
        self.stopped = false;
        self.send(Command::ResetInterpreter);
        for &(slot, plays) in entries {
            self.send(Command::Push { slot, plays });
        }
    }

    /// STOP: `#RI` (clear the queue, stop at once) then `$HP`, ahead of everything queued.
    pub fn stop(&mut self) {
        self.stopped = true;
        self.command(Plen2Command::Stop);
    }

    /// Takes in what the robot sent.
    pub fn pump(&mut self, _now: Instant) -> Vec<Plen2Notice> {
        self.link
            .events()
            .try_iter()
            .map(|event| match event {
                LinkEvent::Driver(Plen2Event::Log(entry)) => Plen2Notice::Log(entry),
                LinkEvent::Driver(Plen2Event::Widened(widened)) => Plen2Notice::Widened(widened),
                LinkEvent::Disconnected { reason } => Plen2Notice::Disconnected(reason),
            })
            .collect()
    }
}
