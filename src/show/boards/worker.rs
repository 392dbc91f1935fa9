//! The boards' worker: a stage per device, taking the editor's and a
//! remote's orders, keeping links fresh, stopping a base whose heartbeats
//! stop, and keeping the status a remote reads.

use std::collections::VecDeque;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::{Duration, Instant};

use crossbeam_channel::Receiver;

use super::{
    DeadMan, DeviceStatus, Drove, FOLLOW_EVERY, Heard, Held, LOOK_EVERY, NotDriven, Order, Refused, Run, Shared,
    connect_one,
};
use crate::device::speed::LiveSpeed;
use crate::show::Show;
use crate::show::alive::Loss;
use crate::show::at::Now;
use crate::show::play::{Gone, Player, Stage, Stopped};
use crate::show::timeline::now_at;

/// What a device does for a remote.
#[derive(Debug, Default)]
struct Doing {
    /// What it plays and until when.
    playing: Option<(String, Instant)>,
    /// What plays after it (when the remote asked to queue).
    queue: VecDeque<(Run, String)>,
    /// A base's dead-man while a remote drives it.
    dead_man: DeadMan,
    /// Its link, said.
    link: String,
    /// Its battery, said, when the board tells it.
    battery: Option<String>,
}

/// The worker's side: a stage per device (None: it did not answer or is lost).
pub(super) struct Worker {
    show: Show,
    stages: Vec<Option<Box<dyn Stage>>>,
    /// The show being followed, and when each board was last told.
    following: Option<(Show, Vec<Option<Instant>>)>,
    /// The newest time not yet told (it waits for [`FOLLOW_EVERY`]).
    pending: Option<(u64, Option<Held>)>,
    /// What each device does for a remote.
    doing: Vec<Doing>,
    /// Whether a show plays on the boards.
    show_playing: bool,
    /// The status a remote reads.
    shared: Arc<Shared>,
    /// How fast a remote's pose may move a servo or a joint.
    speed: LiveSpeed,
}

impl Worker {
    /// Connects every device in turn, saying how each answered.
    pub(super) fn connect(show: Show, shared: Arc<Shared>, tell: &dyn Fn(Heard)) -> Self {
        let mut stages = Vec::new();
        let mut doing = Vec::new();
        for (index, device) in show.devices.iter().enumerate() {
            let (stage, link) = match connect_one(device) {
                Ok(linked) => {
                    let delay = linked.start_delay;
                    tell(Heard::Linked(index, Ok(delay)));
                    (Some(linked.stage), format!("answered ({:.1} ms to reach it)", delay.as_secs_f64() * 1000.0))
                }
                Err(why) => {
                    tell(Heard::Linked(index, Err(why.clone())));
                    (None, format!("did not answer: {why}"))
                }
            };
            stages.push(stage);
            doing.push(Doing { link, ..Doing::default() });
        }
        let speed = LiveSpeed::default();
        let worker = Self { show, stages, following: None, pending: None, doing, show_playing: false, shared, speed };
        worker.publish();
        worker
    }

    /// Takes orders until the editor lets the boards go.
    pub(super) fn serve(&mut self, orders: &Receiver<Order>, stop: &Receiver<String>, tell: &dyn Fn(Heard)) {
        loop {
            let wait = if self.pending.is_some() { FOLLOW_EVERY / 2 } else { LOOK_EVERY };
            crossbeam_channel::select! {
                recv(orders) -> order => match order {
                    Ok(order) => {
                        self.take(order, stop, tell);
                        // Every order already waiting is taken before time is looked at: a
                        // heartbeat queued behind another is never judged late for the queue.
                        while let Ok(order) = orders.try_recv() {
                            self.take(order, stop, tell);
                        }
                    }
                    Err(_) => return,
                },
                recv(stop) -> why => {
                    self.stop_all();
                    if why.is_err() {
                        return;
                    }
                }
                default(wait) => {}
            }
            self.tell_pending();
            self.look(tell);
            self.remote_tick();
            self.publish();
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
                    let _ = stage.follow(&Now::Driving(None));
                }
            }
            Order::Play(show, sound) => {
                self.following = None;
                self.show_playing = true;
                self.publish();
                let played = self.play(&show, sound, stop, tell);
                self.show_playing = false;
                tell(Heard::Played(played));
            }
            Order::Run(index, run, queue, reply) => {
                let ran = self.run(index, run, queue);
                // Published before the answer: what the remote reads next says
                // what it was just told ("queued" is in the status it asks for).
                self.publish();
                let _ = reply.send(ran);
            }
            Order::StopOne(index) => self.stop_one(index),
            Order::Pose(index, axis, value, reply) => {
                let speed = self.speed;
                let posed = self.stage(index).and_then(|stage| stage.pose(axis, value, speed).map_err(Refused::Cannot));
                let _ = reply.send(posed);
            }
            Order::Drive(index, drive, taken_in, reply) => {
                let drove = self.drive(index, drive, taken_in);
                self.publish();
                let _ = reply.send(drove);
            }
            Order::Speed(speed) => self.speed = speed,
        }
    }

    /// The stage of a connected device.
    fn stage(&mut self, index: usize) -> Result<&mut Box<dyn Stage>, Refused> {
        let name = self.show.devices.get(index).map_or_else(String::new, |device| device.name.clone());
        self.stages.get_mut(index).and_then(Option::as_mut).ok_or(Refused::NotConnected(name))
    }

    /// Starts `run` on the device now, or after what it plays (`queue`), or says it is busy.
    fn run(&mut self, index: usize, (run, caption): (Run, String), queue: bool) -> Result<&'static str, Refused> {
        self.stage(index)?;
        if self.show_playing || self.following.is_some() {
            return Err(Refused::Busy("the show is playing on the boards".into()));
        }
        let now = Instant::now();
        let doing = &mut self.doing[index];
        if let Some((what, until)) = &doing.playing
            && *until > now
        {
            if queue {
                doing.queue.push_back((run, caption));
                return Ok("queued");
            }
            return Err(Refused::Busy(format!("it is playing {what}")));
        }
        self.start(index, &run, caption)?;
        Ok("started")
    }

    fn start(&mut self, index: usize, run: &Run, caption: String) -> Result<(), Refused> {
        let length = super::run_length_ms(&self.show.devices[index], run);
        let stage = self.stage(index)?;
        // A start that lasts its own time (a timed drive) is the show's, not a remote's stick.
        let timed = matches!(run, Run::Start(start) if stage.lasts(start).is_some());
        stage.resume();
        let started = match run {
            Run::Start(start) => stage.start(start),
            Run::List(entries) => stage.start_list(entries),
        };
        started.map_err(Refused::Cannot)?;
        let until = Instant::now().checked_add(Duration::from_millis(length)).unwrap_or_else(far_future);
        self.doing[index].playing = Some((caption, until));
        if timed {
            // No heartbeat keeps it going.
            self.doing[index].dead_man.release();
        }
        Ok(())
    }

    fn stop_one(&mut self, index: usize) {
        self.halt(index);
        if let Some(doing) = self.doing.get_mut(index) {
            doing.dead_man.release();
        }
    }

    /// The device stopped where it is (a base brakes); nothing it played or had queued goes on.
    fn halt(&mut self, index: usize) {
        if let Ok(stage) = self.stage(index) {
            stage.stop();
        }
        if let Some(doing) = self.doing.get_mut(index) {
            doing.playing = None;
            doing.queue.clear();
        }
    }

    /// A base driven by a remote, taken in at `taken_in` (None: only a
    /// heartbeat); each keeps it driving for [`super::MOST_GAP`] more.
    fn drive(&mut self, index: usize, drive: Option<(f64, f64)>, taken_in: Instant) -> Result<Drove, Refused> {
        if self.show_playing {
            return Err(Refused::Busy("the show is playing on the boards".into()));
        }
        let stage = self.stage(index)?;
        let Some(drive) = drive else {
            return match self.doing[index].dead_man.heartbeat(taken_in) {
                Ok(gap) => Ok(Drove { taken: None, gap: Some(gap) }),
                Err(late @ NotDriven::Stopped(_)) => {
                    // Too late: stopped now, as the dead-man would have (the worker had not looked yet).
                    self.halt(index);
                    Err(Refused::NotDriven(late))
                }
                Err(not_driven) => Err(Refused::NotDriven(not_driven)),
            };
        };
        let taken = stage.drive(drive).map_err(Refused::Cannot)?;
        let gap = self.doing[index].dead_man.drive(taken_in);
        Ok(Drove { taken: Some(taken), gap })
    }

    /// A remote's side of time passing: a base whose heartbeats stopped
    /// stops (and brakes); a device that ended what it played takes the next queued.
    fn remote_tick(&mut self) {
        let now = Instant::now();
        for index in 0..self.doing.len() {
            if self.doing[index].dead_man.expired(now) {
                self.halt(index);
            }
            if self.doing[index].playing.as_ref().is_some_and(|(_, until)| *until <= now) {
                self.doing[index].playing = None;
                if let Some((run, caption)) = self.doing[index].queue.pop_front() {
                    let _ = self.start(index, &run, caption);
                }
            }
            if let Some(Some(stage)) = self.stages.get(index) {
                self.doing[index].battery = stage.battery();
            }
        }
    }

    /// Writes the status a remote reads (and wakes those waiting), when it changed.
    fn publish(&self) {
        let now = Instant::now();
        let devices: Vec<DeviceStatus> = self
            .show
            .devices
            .iter()
            .zip(&self.doing)
            .map(|(device, doing)| DeviceStatus {
                name: device.name.clone(),
                family: device.project.family.tag().to_string(),
                link: doing.link.clone(),
                battery: doing.battery.clone(),
                playing: doing.playing.as_ref().filter(|(_, until)| *until > now).map(|(what, _)| what.clone()),
                queued: doing.queue.iter().map(|(_, caption)| caption.clone()).collect(),
                driven: doing.dead_man.driven(),
            })
            .collect();
        self.shared.publish(devices, self.show_playing);
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
    /// every device while they follow or a remote drives them.
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
            self.doing[device] = Doing { link: format!("lost: {why}"), ..Doing::default() };
            let needed = !self.show.devices.get(device).is_some_and(|device| device.play_on_without);
            let all_stopped = needed
                && (self.following.is_some() || self.doing.iter().any(|d| d.playing.is_some() || d.dead_man.driven()));
            if all_stopped {
                self.stop_all();
            }
            tell(Heard::Lost { device, why, all_stopped });
        }
    }

    /// Plays `show` once on the boards (the same player as `servo-studio
    /// play`); what it says at the end. Every device must be connected,
    /// unless the show plays on without it.
    fn play(
        &mut self,
        show: &Show,
        sound: Option<PathBuf>,
        stop: &Receiver<String>,
        tell: &dyn Fn(Heard),
    ) -> Result<crate::show::play::Ran, Stopped> {
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
                let mut stage = stage.take().unwrap_or_else(|| Box::new(Gone(Loss::NoAnswer)));
                stage.resume();
                stage
            })
            .collect();
        // No sound output: the show plays silent, and says so (as `play` and a play from the show window do).
        let mut player = Player::new(show, stages, sound, stop.clone(), |error| tell(Heard::Silent(error)));
        let ran = player.run();
        for (slot, stage) in self.stages.iter_mut().zip(player.stages) {
            *slot = (stage.lost().is_none()).then_some(stage);
        }
        ran
    }

    /// Every device stopped (bases brake); nothing follows, plays or is queued.
    pub(super) fn stop_all(&mut self) {
        for stage in self.stages.iter_mut().flatten() {
            stage.stop();
        }
        self.following = None;
        for doing in &mut self.doing {
            doing.playing = None;
            doing.queue.clear();
            doing.dead_man.release();
        }
    }
}

/// An instant far enough ahead to stand for "never ends".
fn far_future() -> Instant {
    Instant::now() + Duration::from_secs(86_400 * 365)
}
