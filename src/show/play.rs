//! Playing a show on its boards together: each cue's start command goes out
//! its device's own delay (the command's time on the line, the link's
//! latency, the board's wait for its next update) before the moment it is
//! due on the show's clock — the sound's, when there is one — so every device
//! starts moving on time. STOP, a signal or a lost link stops every device
//! (bases brake). Devices are [`Stage`]s, so the player is tested in process
//! against the emulators and used by `servo-studio play`.

use std::path::PathBuf;
use std::time::{Duration, Instant};

use crossbeam_channel::Receiver;

use super::alive::Loss;
use super::{Show, Start};
use crate::audio::output::{Playing, Speakers};
use crate::audio::together::PREROLL;
use crate::device::speed::LiveSpeed;

/// How far ahead of its first cue a show without sound starts its clock.
pub const LEAD: Duration = Duration::from_millis(300);
/// How often the player looks at its devices' links (and keeps bases' commands fresh) while it waits.
const LOOK_EVERY: Duration = Duration::from_millis(20);

/// A connected device the player drives.
pub trait Stage: Send {
    /// How long after a start command is written the device starts moving.
    fn start_delay(&self, start: &Start) -> Duration;
    /// How far the device's start may be from when it was due, either way,
    /// as far as can be known: its link's spread, a board's wait for its next update.
    fn start_uncertainty(&self, start: &Start) -> Duration {
        let _ = start;
        Duration::ZERO
    }
    /// What that uncertainty is made of, as the play log says it.
    fn uncertainty_of(&self) -> &'static str {
        "its link's spread"
    }
    /// How long what `start` starts goes on before the player stops the
    /// device (a timed drive); `None`: it ends by itself.
    fn lasts(&self, start: &Start) -> Option<Duration> {
        let _ = start;
        None
    }
    /// Writes the start of a cue.
    fn start(&mut self, start: &Start) -> Result<(), String>;
    /// Stops the device where it is (a base stops and brakes).
    fn stop(&mut self);
    /// Called while the player waits: keep the link's commands fresh.
    fn tick(&mut self, now: Instant) {
        let _ = now;
    }
    /// Why its link is gone, if it is.
    fn lost(&self) -> Option<Loss>;
    /// Lets the device move again after [`Stage::stop`] (a servo board
    /// stopped holds its servos until told to go on).
    fn resume(&mut self) {}
    /// Puts the device where the show has it now — the editor's preview and
    /// record passes followed on the boards: servos and joints moved there
    /// live within their limits, a base driven at its drive now.
    fn follow(&mut self, now: &super::at::Now) -> Result<(), String> {
        let _ = now;
        Ok(())
    }
    /// Plays a list of (start, plays) in order (a PLEN2's play list).
    fn start_list(&mut self, entries: &[(Start, u8)]) -> Result<(), String> {
        let _ = entries;
        Err("it has no play lists".into())
    }
    /// Moves one axis to `value_deg` (a servo's angle; a joint's from home),
    /// within its limits and no faster than `speed` — as a slider does; the value it took.
    fn pose(&mut self, axis: super::at::Axis, value_deg: f64, speed: LiveSpeed) -> Result<f64, String> {
        let _ = (axis, value_deg, speed);
        Err("it has no servo or joint to pose: drive it".into())
    }
    /// Drives at (speed m/s, turn °/s) until told otherwise or stopped (a
    /// base), held within its limits; the (speed, turn) it drives at.
    fn drive(&mut self, drive: (f64, f64)) -> Result<(f64, f64), String> {
        let _ = drive;
        Err("only a base is driven".into())
    }
    /// Its battery, said, when the board tells it.
    fn battery(&self) -> Option<String> {
        None
    }
}

/// A device whose link is gone (why), played on without: it starts nothing and says it is lost.
#[derive(Debug)]
pub struct Gone(pub Loss);

impl Stage for Gone {
    fn start_delay(&self, _start: &Start) -> Duration {
        Duration::ZERO
    }

    fn start(&mut self, _start: &Start) -> Result<(), String> {
        Ok(())
    }

    fn stop(&mut self) {}

    fn lost(&self) -> Option<Loss> {
        Some(self.0.clone())
    }
}

/// Why a run ended early.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum Stopped {
    /// A signal or STOP: every device was stopped.
    #[error("stopped by {0}: every device was stopped")]
    Asked(String),
    /// A device's link was lost: every device was stopped.
    #[error("the link to {device} was lost ({why}): every device was stopped")]
    Lost {
        /// The device.
        device: String,
        /// Why.
        why: Loss,
    },
    /// A start could not be written: every device was stopped.
    #[error("{device} could not be started ({why}): every device was stopped")]
    Failed {
        /// The device.
        device: String,
        /// Why.
        why: String,
    },
}

/// One cue sent: whose, when it was due to be written, when it was.
#[derive(Clone, Debug, PartialEq)]
pub struct Sent {
    /// The device.
    pub device: String,
    /// What it started.
    pub start: Start,
    /// When the device was due to start moving.
    pub moving_at: Instant,
    /// When the command was due to be written (its delay before `moving_at`).
    pub due_at: Instant,
    /// When it was written (never before `due_at`).
    pub sent_at: Instant,
    /// How far its start may still be off either way, as far as can be known
    /// (its link's spread; a PLEN2's wait for its next cycle).
    pub uncertain: Duration,
    /// What that is made of, as the play log says it ("its link's spread").
    pub uncertain_of: &'static str,
}

impl Sent {
    /// How late it was written, ms.
    pub fn late_ms(&self) -> f64 {
        self.sent_at.saturating_duration_since(self.due_at).as_secs_f64() * 1000.0
    }

    /// How far its start may be off either way, ms, besides being written late.
    pub fn uncertain_ms(&self) -> f64 {
        self.uncertain.as_secs_f64() * 1000.0
    }

    /// The most its device's start can be off its cue, ms, as far as can be
    /// known: written late, plus what its link and its board's cycle leave open.
    pub fn skew_ms(&self) -> f64 {
        self.late_ms() + self.uncertain_ms()
    }
}

/// What one run did.
#[derive(Clone, Debug, PartialEq)]
pub struct Ran {
    /// When the show's 0 was (the sound's point heard, or the clock's start).
    pub zero: Instant,
    /// Each cue, as sent.
    pub sent: Vec<Sent>,
    /// When it ended.
    pub ended: Instant,
    /// Whether the sound played.
    pub with_sound: bool,
    /// Devices whose link was lost and that the show played on without: name, why.
    pub lost: Vec<(String, Loss)>,
}

/// The show, its devices (in the show's order) and what it plays through.
pub struct Player<'a> {
    /// The show.
    pub show: &'a Show,
    /// A stage per device, in the show's order.
    pub stages: Vec<Box<dyn Stage>>,
    /// Where the sound plays, when it does; and the sound's file.
    pub sound: Option<(Speakers, PathBuf)>,
    /// STOP and signals: anything arriving ends the run, named by what arrived.
    pub stop: Receiver<String>,
}

impl<'a> Player<'a> {
    /// The one way a show's player is made — by `play`, by the show window's
    /// Play on the boards and by the held boards: `show` on `stages` (one per
    /// device, in its order), its sound from the file at `sound` through the
    /// system's sound server, stopped by anything arriving on `stop`. With no
    /// sound output the show plays silent, and `silent` is told why.
    pub fn new(
        show: &'a Show,
        stages: Vec<Box<dyn Stage>>,
        sound: Option<PathBuf>,
        stop: Receiver<String>,
        silent: impl FnOnce(String),
    ) -> Self {
        let sound = sound.and_then(|path| match Speakers::connect() {
            Ok(speakers) => Some((speakers, path)),
            Err(error) => {
                silent(error.to_string());
                None
            }
        });
        Self { show, stages, sound, stop }
    }
}

/// What a run keeps of the devices while it plays.
#[derive(Default)]
struct Going {
    /// Drives that end at an instant, by device.
    drives: Vec<(Instant, usize)>,
    /// Devices lost and played on without: their index, name and why.
    lost: Vec<(usize, String, Loss)>,
}

impl Player<'_> {
    /// Plays the show once through.
    pub fn run(&mut self) -> Result<Ran, Stopped> {
        let offset_ms = self.show.sound.as_ref().map_or(0, |sound| sound.offset_ms);
        let (zero, playing) = self.zero(offset_ms);
        let mut plan: Vec<(Instant, usize, Start, Instant)> = Vec::new();
        for cue in &self.show.cues {
            let Some(index) = self.show.devices.iter().position(|device| device.name == cue.device) else { continue };
            let moving_at = zero + Duration::from_millis(cue.at_ms);
            let due = moving_at.checked_sub(self.stages[index].start_delay(&cue.start)).unwrap_or(moving_at);
            plan.push((due, index, cue.start, moving_at));
        }
        plan.sort_by_key(|(due, ..)| *due);
        let end = zero + Duration::from_millis(self.length_ms());
        let mut sent = Vec::new();
        let mut going = Going::default();
        for (due, index, start, moving_at) in plan {
            self.wait_until(due, &mut going)?;
            if going.lost.iter().any(|(gone, ..)| *gone == index) {
                continue;
            }
            let sent_at = Instant::now();
            let device = self.show.devices[index].name.clone();
            if let Err(why) = self.stages[index].start(&start) {
                self.stop_all();
                return Err(Stopped::Failed { device, why });
            }
            if let Some(lasts) = self.stages[index].lasts(&start) {
                going.drives.push((moving_at + lasts, index));
            }
            let stage = &self.stages[index];
            let (uncertain, uncertain_of) = (stage.start_uncertainty(&start), stage.uncertainty_of());
            sent.push(Sent { device, start, moving_at, due_at: due, sent_at, uncertain, uncertain_of });
        }
        self.wait_until(end, &mut going)?;
        drop(playing);
        let lost = going.lost.into_iter().map(|(_, name, why)| (name, why)).collect();
        Ok(Ran { zero, sent, ended: Instant::now(), with_sound: self.sound.is_some(), lost })
    }

    /// The show's 0: when the sound's point (its start plus the offset) is heard, or a lead from now.
    fn zero(&self, offset_ms: i64) -> (Instant, Option<Playing>) {
        let lead = LEAD.max(self.longest_delay());
        if let Some((speakers, path)) = &self.sound {
            // The sound's time at the show's 0 (a negative offset: the sound started before).
            #[allow(clippy::cast_precision_loss)]
            let point_s = (-offset_ms).max(0) as f64 / 1000.0;
            let preroll = PREROLL.max(lead).as_secs_f64();
            if let Ok(playing) = speakers.play(path, point_s - preroll)
                && let Ok(heard) = playing.heard_at(point_s)
            {
                return (heard, Some(playing));
            }
        }
        (Instant::now() + lead, None)
    }

    fn longest_delay(&self) -> Duration {
        self.show
            .cues
            .iter()
            .filter_map(|cue| {
                let index = self.show.devices.iter().position(|device| device.name == cue.device)?;
                Some(self.stages[index].start_delay(&cue.start))
            })
            .max()
            .unwrap_or_default()
    }

    /// How long the show lasts, ms: its last cue's end, or the sound's.
    pub fn length_ms(&self) -> u64 {
        let sound = self.show.sound.as_ref().map_or(0, |sound| {
            u64::try_from(i64::try_from(sound.duration_ms).unwrap_or(i64::MAX).saturating_add(sound.offset_ms))
                .unwrap_or(0)
        });
        self.show
            .cues
            .iter()
            .filter_map(|cue| {
                Some(cue.at_ms + super::timeline::cue_length_ms(self.show.device(&cue.device)?, &cue.start))
            })
            .chain([sound])
            .max()
            .unwrap_or(0)
    }

    /// Waits until `until`, keeping links fresh, stopping drives that are done,
    /// and ending the run on STOP, a signal or a lost link (unless its device
    /// plays on without it: then the others go on).
    fn wait_until(&mut self, until: Instant, going: &mut Going) -> Result<(), Stopped> {
        loop {
            let now = Instant::now();
            going.drives.retain(|&(done, index)| {
                if done <= now {
                    self.stages[index].stop();
                }
                done > now
            });
            self.look(now, going)?;
            if now >= until {
                return Ok(());
            }
            let next =
                going.drives.iter().map(|(done, _)| *done).min().unwrap_or(until).min(until).min(now + LOOK_EVERY);
            if let Ok(what) = self.stop.recv_deadline(next) {
                self.stop_all();
                return Err(Stopped::Asked(what));
            }
        }
    }

    /// Keeps every device's link fresh and looks whether one was lost: one
    /// the show plays on without is left behind (noted in `going`); any other
    /// stops every device and ends the run.
    fn look(&mut self, now: Instant, going: &mut Going) -> Result<(), Stopped> {
        for (index, (stage, device)) in self.stages.iter_mut().zip(&self.show.devices).enumerate() {
            if going.lost.iter().any(|(gone, ..)| *gone == index) {
                continue;
            }
            stage.tick(now);
            let Some(why) = stage.lost() else { continue };
            if device.play_on_without {
                // It may still hear though it cannot answer: a base is not left driving.
                stage.stop();
                going.lost.push((index, device.name.clone(), why));
                going.drives.retain(|&(_, driving)| driving != index);
                continue;
            }
            let device = device.name.clone();
            self.stop_all();
            return Err(Stopped::Lost { device, why });
        }
        Ok(())
    }

    /// Waits until `until` between runs (nothing playing): links kept fresh,
    /// and a device the show needs that is lost meanwhile, STOP or a signal
    /// end the wait (every device stopped).
    pub fn wait_between(&mut self, until: Instant) -> Result<(), Stopped> {
        self.wait_until(until, &mut Going::default())
    }

    /// Stops every device (bases stop and brake).
    pub fn stop_all(&mut self) {
        for stage in &mut self.stages {
            stage.stop();
        }
    }
}

/// What a run did, a line each: every start and how late it was written,
/// every device played on without, and when it ended.
pub fn ran_words(ran: &Ran) -> String {
    let mut lines: Vec<String> = ran
        .sent
        .iter()
        .map(|sent| format!("{} started {}, {:.2} ms late", sent.device, sent.start, sent.late_ms()))
        .collect();
    for (device, why) in &ran.lost {
        lines.push(format!("the link to {device} was lost ({why}): the show played on without it"));
    }
    lines.push(format!("ended after {:.2} s", ran.ended.saturating_duration_since(ran.zero).as_secs_f64()));
    lines.join("\n")
}
