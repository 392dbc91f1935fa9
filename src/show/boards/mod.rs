//! A show's boards held connected by the editor: one link per device, on a
//! worker of their own, so the show window can follow its preview and its
//! record passes on every board at once (servos and joints put where the
//! stage shows them, bases driven on their drives), play the show on them,
//! and stop them all. A lost link stops every device that is following or
//! playing (bases brake) unless the show plays on without it; STOP, closing
//! the show or the editor does too.

use std::path::PathBuf;
use std::time::Duration;

use crossbeam_channel::{Receiver, Sender};

mod dead_man;
mod worker;

use std::sync::{Arc, Condvar, Mutex};

use super::Show;
use super::passes::Axis;
use super::play::{Player, Stage, Stopped};
use crate::device::speed::LiveSpeed;
use crate::link::Waker;
pub use dead_man::{DeadMan, MOST_GAP, NotDriven};
use worker::Worker;

/// How often the worker looks at its links while it waits.
const LOOK_EVERY: Duration = Duration::from_millis(20);
/// The shortest time between two follows a board is told (the rest are dropped: the newest wins).
const FOLLOW_EVERY: Duration = Duration::from_millis(20);

/// An axis held at a value while the show is followed (the pass being
/// recorded): its device's index, the axis, degrees.
pub type Held = (usize, Axis, f64);

/// What the boards' worker says.
#[derive(Clone, Debug, PartialEq)]
pub enum Heard {
    /// The device at this index answered (how long a command takes to reach it) or did not (why).
    Linked(usize, Result<Duration, Unlinked>),
    /// The device's link was lost (why); `all_stopped`: every device was stopped with it.
    Lost {
        /// The device's index.
        device: usize,
        /// Why.
        why: crate::show::alive::Loss,
        /// Whether every device was stopped (it was following or playing, and the show needs it).
        all_stopped: bool,
    },
    /// A play on the boards begins without its sound: no sound output (why).
    Silent(String),
    /// A play on the boards ended (how).
    Played(Result<crate::show::play::Ran, Stopped>),
}

/// What the editor asks of the boards.
enum Order {
    /// Follow this show from now on (a preview or a pass starting).
    Follow(Box<Show>),
    /// The show's time now, and the axis held (the pass being recorded: device index, axis, degrees).
    At(u64, Option<Held>),
    /// The preview ended: servos hold where they are, bases stop.
    Rest,
    /// Play the show on the boards with its sound.
    Play(Box<Show>, Option<PathBuf>),
    /// A remote: run this on the device (its caption), queued behind what it plays (`true`) or refused.
    Run(usize, (Run, String), bool, Sender<Result<&'static str, Refused>>),
    /// A remote: stop this device.
    StopOne(usize),
    /// A remote: an axis of the device to a value (degrees), paced and limited as a slider; the value it took.
    Pose(usize, Axis, f64, Sender<Result<f64, Refused>>),
    /// A remote: drive a base (speed m/s, turn °/s; None: a heartbeat only), taken in at this instant.
    Drive(usize, Option<(f64, f64)>, std::time::Instant, Sender<Result<Drove, Refused>>),
    /// How fast a remote's pose may move a servo or a joint.
    Speed(LiveSpeed),
}

pub use super::Run;

/// Why a device of the show was not linked.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum Unlinked {
    /// The show gives it no port.
    #[error("no port — type where it is connected")]
    NoPort,
    /// Its port did not open, or nothing answered there: what the link said.
    #[error("{0}")]
    Failed(String),
}

/// Why a remote's order was not carried out.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum Refused {
    /// The device plays something else (or the show plays).
    #[error("busy: {0}")]
    Busy(String),
    /// The device is not connected.
    #[error("{0} is not connected: check its cable and port, then connect the boards again")]
    NotConnected(String),
    /// The device cannot do it (why).
    #[error("{0}")]
    Cannot(String),
    /// The boards did not answer in time.
    #[error("the boards did not answer in time: try again (STOP is always taken at once)")]
    Late,
    /// A heartbeat that keeps nothing driving (never driven, or the dead-man stopped it).
    #[error("{0}")]
    NotDriven(NotDriven),
}

/// What a remote's drive or heartbeat did.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Drove {
    /// The speed and turn the base drives at (m/s, °/s), within its limits; None for a heartbeat.
    pub taken: Option<(f64, f64)>,
    /// How long since the previous drive or heartbeat, when the base was being driven.
    pub gap: Option<Duration>,
}

/// A device as a remote's status says it.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct DeviceStatus {
    /// Its name in the show.
    pub name: String,
    /// Its family's tag (`servo`, `plen2`, `rflex`).
    pub family: String,
    /// Its link, said ("answered (0.4 ms to reach it)", "lost: …").
    pub link: String,
    /// Its battery, when the board tells it.
    pub battery: Option<String>,
    /// What it plays now.
    pub playing: Option<String>,
    /// What it plays next.
    pub queued: Vec<String>,
    /// Whether a remote drives it (heartbeats arriving).
    pub driven: bool,
}

/// Every device's status, numbered as it changes.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct Status {
    /// Which change this is.
    pub revision: u64,
    /// Whether the show plays on the boards.
    pub show_playing: bool,
    /// Each device, in the show's order.
    pub devices: Vec<DeviceStatus>,
}

/// The status, shared between the worker and the remotes reading it.
#[derive(Debug, Default)]
pub struct Shared {
    status: Mutex<Status>,
    changed: Condvar,
}

impl Shared {
    fn publish(&self, devices: Vec<DeviceStatus>, show_playing: bool) {
        let Ok(mut status) = self.status.lock() else { return };
        if status.devices != devices || status.show_playing != show_playing {
            status.devices = devices;
            status.show_playing = show_playing;
            status.revision += 1;
            self.changed.notify_all();
        }
    }
}

/// How long a remote's run keeps its device busy, ms.
fn run_length_ms(device: &super::Device, run: &Run) -> u64 {
    match run {
        Run::Start(start) => super::timeline::cue_length_ms(device, start),
        Run::List(entries) => entries
            .iter()
            .map(|(start, plays)| {
                if *plays == 0 {
                    return u64::MAX / 4;
                }
                super::timeline::cue_length_ms(device, start).saturating_mul(u64::from(*plays))
            })
            .fold(0, u64::saturating_add),
    }
}

/// How long a remote waits for the boards to take an order.
const ANSWER_WITHIN: Duration = Duration::from_secs(2);

/// The boards of a show, connected.
pub struct Boards {
    shared: Arc<Shared>,
    orders: Sender<Order>,
    stop: Sender<String>,
    heard: Receiver<Heard>,
    worker: Option<std::thread::JoinHandle<()>>,
}

impl std::fmt::Debug for Boards {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Boards").finish_non_exhaustive()
    }
}

impl Boards {
    /// Connects every device of `show` on its port (as typed; `usb:` ids
    /// found), off the caller's thread; each says whether it answered as
    /// [`Heard::Linked`]. `waker` is called whenever something is heard.
    pub fn connect(show: &Show, waker: Waker) -> std::io::Result<Self> {
        let (orders, taken) = crossbeam_channel::unbounded();
        let (stop, stopped) = crossbeam_channel::unbounded();
        let (say, heard) = crossbeam_channel::unbounded();
        let show = show.clone();
        let shared = Arc::new(Shared::default());
        let theirs = Arc::clone(&shared);
        let worker = std::thread::Builder::new().name("show boards".into()).spawn(move || {
            let tell = |heard: Heard| {
                let _ = say.send(heard);
                waker();
            };
            let mut worker = Worker::connect(show, theirs, &tell);
            worker.serve(&taken, &stopped, &tell);
            worker.stop_all();
        })?;
        Ok(Self { shared, orders, stop, heard, worker: Some(worker) })
    }

    /// A remote: runs `run` (called `caption`) on the device at `index` —
    /// "started", or "queued" behind what it plays when `queue`; else why not.
    pub fn run(&self, index: usize, run: Run, caption: &str, queue: bool) -> Result<&'static str, Refused> {
        self.ask(|reply| Order::Run(index, (run, caption.to_string()), queue, reply))?
    }

    /// A remote: stops the device at `index` (a base brakes).
    pub fn stop_one(&self, index: usize) {
        let _ = self.orders.send(Order::StopOne(index));
    }

    /// A remote: an axis of the device at `index` to `value` degrees, paced
    /// and limited as a slider is; the value it took (within the limits).
    pub fn pose(&self, index: usize, axis: Axis, value: f64) -> Result<f64, Refused> {
        self.ask(|reply| Order::Pose(index, axis, value, reply))?
    }

    /// A remote: drives the base at `index` (speed m/s, turn °/s, held
    /// within its limits), or only keeps it driving (None); it stops once
    /// more than [`MOST_GAP`] passes after the last of these, timed from now.
    pub fn drive(&self, index: usize, drive: Option<(f64, f64)>) -> Result<Drove, Refused> {
        let taken_in = std::time::Instant::now();
        self.ask(|reply| Order::Drive(index, drive, taken_in, reply))?
    }

    /// How fast a remote's pose may move a servo or a joint (the editor's live speed).
    pub fn set_speed(&self, speed: LiveSpeed) {
        let _ = self.orders.send(Order::Speed(speed));
    }

    /// Every device's status now.
    pub fn status(&self) -> Status {
        self.shared.status.lock().map(|status| status.clone()).unwrap_or_default()
    }

    /// The status once its revision is past `seen`, or as it is after `within`.
    pub fn status_after(&self, seen: u64, within: Duration) -> Status {
        let Ok(status) = self.shared.status.lock() else { return Status::default() };
        let waited = self.shared.changed.wait_timeout_while(status, within, |status| status.revision <= seen);
        waited.map(|(status, _)| status.clone()).unwrap_or_default()
    }

    /// Sends an order with a reply and waits for it (a show playing holds the worker: said as late).
    fn ask<T>(&self, order: impl FnOnce(Sender<T>) -> Order) -> Result<T, Refused> {
        let (reply, answer) = crossbeam_channel::bounded(1);
        self.orders.send(order(reply)).map_err(|_| Refused::Late)?;
        answer.recv_timeout(ANSWER_WITHIN).map_err(|_| Refused::Late)
    }

    /// Follows `show` from now on (servo boards are let move again after a STOP).
    pub fn follow(&self, show: &Show) {
        let _ = self.orders.send(Order::Follow(Box::new(show.clone())));
    }

    /// The show's time now; `held`: the pass's device (by index), axis and value.
    pub fn at(&self, t_ms: u64, held: Option<Held>) {
        let _ = self.orders.send(Order::At(t_ms, held));
    }

    /// The preview ended: servos hold, bases stop.
    pub fn rest(&self) {
        let _ = self.orders.send(Order::Rest);
    }

    /// Plays `show` on the boards with the sound at `sound` (silent: None).
    pub fn play(&self, show: &Show, sound: Option<PathBuf>) {
        let _ = self.orders.send(Order::Play(Box::new(show.clone()), sound));
    }

    /// Stops every device at once (bases brake), whatever they do.
    pub fn stop(&self) {
        let _ = self.stop.send("STOP".into());
    }

    /// What the worker said since last asked.
    pub fn heard(&self) -> Vec<Heard> {
        self.heard.try_iter().collect()
    }

    /// The next thing the worker says, waiting up to `within`.
    pub fn hear_within(&self, within: Duration) -> Option<Heard> {
        self.heard.recv_timeout(within).ok()
    }
}

impl Drop for Boards {
    /// Every device stopped and its link closed before the boards are let go.
    fn drop(&mut self) {
        let _ = self.stop.send("the show closing".into());
        let (orders, _) = crossbeam_channel::bounded(0);
        drop(std::mem::replace(&mut self.orders, orders));
        if let Some(worker) = self.worker.take() {
            let _ = worker.join();
        }
    }
}

/// What [`play_once`] tells as it goes, for its caller to word.
#[derive(Clone, Debug, PartialEq)]
pub enum Told {
    /// The device's `usb:` id found its adapter on another port now.
    Moved {
        /// The device's name.
        device: String,
        /// Its port as the show names it.
        port: String,
        /// The port opened.
        opened: String,
    },
    /// The device answered on its port; how long a command takes to reach it.
    Answered {
        /// The device's name.
        device: String,
        /// Its port.
        port: String,
        /// How long a command takes to reach it.
        delay: Duration,
    },
    /// The device could not be linked: nothing was played.
    Unlinked {
        /// The device's name.
        device: String,
        /// Its port, if the show gives one.
        port: Option<String>,
        /// Why.
        why: Unlinked,
    },
    /// No sound output could be opened (why): the show plays silent.
    Silent(String),
    /// The run ended.
    Ran(crate::show::play::Ran),
    /// The run was stopped.
    Stopped(Stopped),
}

impl std::fmt::Display for Told {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Moved { device, port, opened } => write!(f, "{device}: {port} is {opened} now"),
            Self::Answered { device, port, delay } => {
                write!(f, "{device} answered on {port} ({:.1} ms to reach it)", delay.as_secs_f64() * 1000.0)
            }
            Self::Unlinked { device, port: None, why } => write!(f, "{device}: {why}"),
            Self::Unlinked { device, port: Some(port), why } => {
                write!(f, "{device} did not answer on {port}: {why}; nothing was played")
            }
            Self::Silent(why) => write!(f, "no sound output ({why}): playing silent"),
            Self::Ran(ran) => f.write_str(crate::show::play::ran_words(ran).trim_end()),
            Self::Stopped(stopped) => write!(f, "{stopped}"),
        }
    }
}

/// Connects every device of `show` and plays it once with its sound (from
/// `folder`), telling what happens (the show window's Play on the boards
/// when the boards are not held).
pub fn play_once(show: &Show, folder: Option<PathBuf>, stop: Receiver<String>, tell: &dyn Fn(Told)) {
    let mut stages: Vec<Box<dyn Stage>> = Vec::new();
    for device in &show.devices {
        let name = device.name.clone();
        if let Some(port) = device.port.as_deref()
            && let Ok(opened) = crate::link::by_id::resolve(port)
            && opened != port.trim()
        {
            tell(Told::Moved { device: name.clone(), port: port.to_string(), opened });
        }
        match connect_one(device) {
            Ok(linked) => {
                let port = device.port.clone().unwrap_or_default();
                tell(Told::Answered { device: name, port, delay: linked.start_delay });
                stages.push(linked.stage);
            }
            Err(why) => {
                tell(Told::Unlinked { device: name, port: device.port.clone(), why });
                return;
            }
        }
    }
    let sound = show.sound.as_ref().map(|track| folder.unwrap_or_default().join(&track.path));
    let mut player = Player::new(show, stages, sound, stop, |error| tell(Told::Silent(error)));
    match player.run() {
        Ok(ran) => tell(Told::Ran(ran)),
        Err(stopped) => tell(Told::Stopped(stopped)),
    }
}

/// Connects one device on its port (a `usb:` id found first), its link measured.
pub fn connect_one(device: &super::Device) -> Result<super::stages::Linked, Unlinked> {
    let Some(port) = &device.port else { return Err(Unlinked::NoPort) };
    let opened = crate::link::by_id::resolve(port).map_err(|error| Unlinked::Failed(format!("{error}")))?;
    super::family::connect(&opened, device).map_err(|error| Unlinked::Failed(format!("{error:#}")))
}
