//! A show's boards held connected by the editor: one link per device, on a
//! worker of their own, so the show window can follow its preview and its
//! record passes on every board at once (servos and joints put where the
//! stage shows them, bases driven on their drives), play the show on them,
//! and stop them all. A lost link stops every device that is following or
//! playing (bases brake) unless the show plays on without it; STOP, closing
//! the show or the editor does too.

use std::path::PathBuf;
use std::time::{Duration, Instant};

use crossbeam_channel::{Receiver, Sender};

use super::Show;
use super::at::now_at;
use super::passes::Axis;
use super::play::{Player, Stage, Stopped};
use crate::link::Waker;

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
    /// A line for the user.
    Said(String),
    /// The device at this index answered (how long a command takes to reach it) or did not (why).
    Linked(usize, Result<Duration, String>),
    /// The device's link was lost (why); `all_stopped`: every device was stopped with it.
    Lost {
        /// The device's index.
        device: usize,
        /// What the link said.
        why: String,
        /// Whether every device was stopped (it was following or playing, and the show needs it).
        all_stopped: bool,
    },
    /// A play on the boards ended (how).
    Played(Result<String, Stopped>),
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
}

/// The boards of a show, connected.
pub struct Boards {
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
        let worker = std::thread::Builder::new().name("show boards".into()).spawn(move || {
            let tell = |heard: Heard| {
                let _ = say.send(heard);
                waker();
            };
            let mut worker = Worker::connect(show, &tell);
            worker.serve(&taken, &stopped, &tell);
            worker.stop_all();
        })?;
        Ok(Self { orders, stop, heard, worker: Some(worker) })
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

/// The worker's side: a stage per device (None: it did not answer or is lost).
struct Worker {
    show: Show,
    stages: Vec<Option<Box<dyn Stage>>>,
    /// The show being followed, and when each board was last told.
    following: Option<(Show, Vec<Option<Instant>>)>,
    /// The newest time not yet told (it waits for [`FOLLOW_EVERY`]).
    pending: Option<(u64, Option<Held>)>,
}

impl Worker {
    /// Connects every device in turn, saying how each answered.
    fn connect(show: Show, tell: &dyn Fn(Heard)) -> Self {
        let mut stages = Vec::new();
        for (index, device) in show.devices.iter().enumerate() {
            let stage = match connect_one(device) {
                Ok((stage, delay)) => {
                    tell(Heard::Linked(index, Ok(delay)));
                    Some(stage)
                }
                Err(why) => {
                    tell(Heard::Linked(index, Err(why)));
                    None
                }
            };
            stages.push(stage);
        }
        Self { show, stages, following: None, pending: None }
    }

    /// Takes orders until the editor lets the boards go.
    fn serve(&mut self, orders: &Receiver<Order>, stop: &Receiver<String>, tell: &dyn Fn(Heard)) {
        loop {
            let wait = if self.pending.is_some() { FOLLOW_EVERY / 2 } else { LOOK_EVERY };
            crossbeam_channel::select! {
                recv(orders) -> order => match order {
                    Ok(order) => self.take(order, stop, tell),
                    Err(_) => return,
                },
                recv(stop) -> why => {
                    self.stop_all();
                    self.following = None;
                    if why.is_err() {
                        return;
                    }
                }
                default(wait) => {}
            }
            self.tell_pending();
            self.look(tell);
        }
    }

    fn take(&mut self, order: Order, stop: &Receiver<String>, tell: &dyn Fn(Heard)) {
        match order {
            Order::Follow(show) => {
                for stage in self.stages.iter_mut().flatten() {
                    stage.resume();
                }
                let told = vec![None; show.devices.len()];
                self.following = Some((*show, told));
            }
            Order::At(t_ms, held) => self.pending = Some((t_ms, held)),
            Order::Rest => {
                self.tell_pending();
                self.following = None;
                for stage in self.stages.iter_mut().flatten() {
                    // A base at rest; servos and joints hold where they are.
                    let _ = stage.follow(&super::at::Now::Driving(None));
                }
            }
            Order::Play(show, sound) => {
                self.following = None;
                let played = self.play(&show, sound, stop);
                tell(Heard::Played(played));
            }
        }
    }

    /// Tells every following board where the show has it now.
    fn tell_pending(&mut self) {
        let (Some((t_ms, held)), Some((show, told))) = (self.pending, &mut self.following) else { return };
        let now = Instant::now();
        if told.iter().flatten().any(|at| now.saturating_duration_since(*at) < FOLLOW_EVERY) {
            return;
        }
        self.pending = None;
        for (index, (stage, told)) in self.stages.iter_mut().zip(told.iter_mut()).enumerate() {
            let Some(stage) = stage else { continue };
            let held = held.filter(|(device, ..)| *device == index).map(|(_, axis, value)| (axis, value));
            let Some(at) = now_at(show, index, t_ms, held) else { continue };
            if stage.follow(&at).is_ok() {
                *told = Some(now);
            }
        }
    }

    /// Keeps links fresh and says which was lost: one the show needs stops
    /// every device while they follow.
    fn look(&mut self, tell: &dyn Fn(Heard)) {
        let now = Instant::now();
        let mut lost = Vec::new();
        for (index, slot) in self.stages.iter_mut().enumerate() {
            let Some(stage) = slot else { continue };
            stage.tick(now);
            if let Some(why) = stage.lost() {
                lost.push((index, why));
                *slot = None;
            }
        }
        for (device, why) in lost {
            let needed = !self.show.devices.get(device).is_some_and(|device| device.play_on_without);
            let all_stopped = needed && self.following.is_some();
            if all_stopped {
                self.stop_all();
                self.following = None;
            }
            tell(Heard::Lost { device, why, all_stopped });
        }
    }

    /// Plays `show` once on the boards (the same player as `servo-studio
    /// play`); what it says at the end. Every device must be connected,
    /// unless the show plays on without it.
    fn play(&mut self, show: &Show, sound: Option<PathBuf>, stop: &Receiver<String>) -> Result<String, Stopped> {
        let missing = show
            .devices
            .iter()
            .zip(&self.stages)
            .find(|(device, stage)| stage.is_none() && !device.play_on_without)
            .map(|(device, _)| device.name.clone());
        if let Some(device) = missing {
            let why = "it is not connected: connect the boards again".to_string();
            return Err(Stopped::Failed { device, why });
        }
        let stages: Vec<Box<dyn Stage>> = self
            .stages
            .iter_mut()
            .map(|stage| {
                let mut stage = stage.take().unwrap_or_else(|| Box::new(Gone));
                stage.resume();
                stage
            })
            .collect();
        let sound = sound.and_then(|path| crate::audio::output::Speakers::connect().ok().map(|out| (out, path)));
        let mut player = Player { show, stages, sound, stop: stop.clone() };
        let ran = player.run();
        for (slot, stage) in self.stages.iter_mut().zip(player.stages) {
            *slot = (stage.lost().is_none()).then_some(stage);
        }
        ran.map(|ran| super::play::ran_words(&ran))
    }

    fn stop_all(&mut self) {
        for stage in self.stages.iter_mut().flatten() {
            stage.stop();
        }
    }
}

/// A device that did not answer, played on without.
struct Gone;

impl Stage for Gone {
    fn start_delay(&self, _start: &super::Start) -> Duration {
        Duration::ZERO
    }

    fn start(&mut self, _start: &super::Start) -> Result<(), String> {
        Ok(())
    }

    fn stop(&mut self) {}

    fn lost(&self) -> Option<String> {
        Some("it did not answer".into())
    }
}

/// Connects every device of `show` and plays it once with its sound (from
/// `folder`), saying what happens (the show window's Play on the boards
/// when the boards are not held).
pub fn play_once(show: &Show, folder: Option<PathBuf>, stop: Receiver<String>, tell: &dyn Fn(String)) {
    let mut stages: Vec<Box<dyn Stage>> = Vec::new();
    for device in &show.devices {
        let Some(port) = device.port.as_deref() else {
            tell(format!("{}: no port — type where it is connected", device.name));
            return;
        };
        if let Ok(opened) = crate::link::by_id::resolve(port)
            && opened != port.trim()
        {
            tell(format!("{}: {port} is {opened} now", device.name));
        }
        match connect_one(device) {
            Ok((stage, delay)) => {
                tell(answered(&device.name, port, delay));
                stages.push(stage);
            }
            Err(error) => {
                tell(format!("{} did not answer on {port}: {error}; nothing was played", device.name));
                return;
            }
        }
    }
    let sound = show.sound.as_ref().and_then(|track| {
        let path = folder.unwrap_or_default().join(&track.path);
        match crate::audio::output::Speakers::connect() {
            Ok(speakers) => Some((speakers, path)),
            Err(error) => {
                tell(format!("no sound output ({error}): playing silent"));
                None
            }
        }
    });
    let mut player = Player { show, stages, sound, stop };
    match player.run() {
        Ok(ran) => crate::show::play::ran_words(&ran).lines().for_each(|line| tell(line.to_string())),
        Err(stopped) => tell(stopped.to_string()),
    }
}

/// "NAME answered on PORT (… ms to reach it)".
fn answered(name: &str, port: &str, delay: Duration) -> String {
    format!("{name} answered on {port} ({:.1} ms to reach it)", delay.as_secs_f64() * 1000.0)
}

/// Connects one device on its port (a `usb:` id found first).
pub fn connect_one(device: &super::Device) -> Result<(Box<dyn Stage>, Duration), String> {
    let Some(port) = &device.port else { return Err("no port — type where it is connected".into()) };
    let opened = crate::link::by_id::resolve(port).map_err(|error| format!("{error}"))?;
    super::stages::connect(&opened, device).map_err(|error| format!("{error:#}"))
}
