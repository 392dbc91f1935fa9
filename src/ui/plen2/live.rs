//! The PLEN2's live side: joints moved live, playing on the robot (stored
//! motions, play lists, or a motion streamed from any frame), and frames
//! captured from the pose.

use std::time::Instant;

use super::Plen2Link;
use super::Plen2Ui;
use super::joints::limits;
use crate::authoring::bake::{DEFAULT_TOLERANCE_TENTHS, bake_plen2};
use crate::authoring::fit::{self, Budget, FitError, Plen2Board};
use crate::authoring::fitted::{PLEN2_UPDATE_MS, plen2_frames};
use crate::authoring::recording::Recorder;
use crate::device::plen2::playback::{self, DEVICE_IDS, StoredMotions};
use crate::device::speed::{PLEN2_CYCLE, Slew};
use crate::project::Edit;
use crate::project::plen2::MAX_FRAMES;
use crate::project::plen2::{Frame, Joint, Motion, Plen2Project, Pose};
use crate::ui::plen2::captions::Plen2Words;
use crate::ui::shell::Shell;

/// A motion played from one of its frames by streaming its poses live.
#[derive(Debug)]
pub struct Stream {
    motion: Motion,
    frame: usize,
    started: Instant,
    from: [i16; 18],
}

/// The live pose being recorded into a motion.
#[derive(Debug)]
pub struct Recording {
    /// The motion's slot.
    pub slot: u8,
    /// The frame the fitted frames go after.
    pub after: usize,
    /// What was sampled.
    pub recorder: Recorder,
}

/// Every joint's home, as the project's joint settings (else the factory's) say.
pub fn homes(project: &Plen2Project) -> [i16; 18] {
    Joint::ALL.map(|joint| limits(project, joint).home_tenths_deg)
}

impl Plen2Ui {
    /// Sends every joint's angle (coalesced and paced by the driver).
    fn send_pose(&self, shell: &mut Shell<'_>) {
        let moves: Vec<(u8, i16)> = Joint::ALL.iter().map(|j| (j.device_id(), self.pose[j.index()])).collect();
        if let Some(robot) = shell.plen2_mut() {
            robot.move_joints(moves);
        }
    }

    pub(super) fn set_joint(&mut self, shell: &mut Shell<'_>, joint: Joint, tenths: i16) {
        let setting = limits(&shell.document.project.plen2, joint);
        let low = setting.min_tenths_deg.min(setting.max_tenths_deg);
        let high = setting.max_tenths_deg.max(setting.min_tenths_deg);
        // The limits clamp every move the app sends.
        let tenths = tenths.clamp(low, high);
        let before = self.pose;
        self.pose[joint.index()] = tenths;
        self.stream = None;
        self.walk_to_pose(shell, before, Instant::now());
    }

    /// A joint turned in the 3D view: to where it was when the drag began, plus `by_tenths`.
    pub(super) fn turn_joint(&mut self, shell: &mut Shell<'_>, joint: Joint, by_tenths: i32) {
        let before = *self.turning.get_or_insert(self.pose);
        self.selected_joint = Some(joint);
        let tenths = i32::from(before[joint.index()]).saturating_add(by_tenths);
        let tenths = i16::try_from(tenths.clamp(i32::from(i16::MIN), i32::from(i16::MAX))).unwrap_or(0);
        self.set_joint(shell, joint, tenths);
    }

    /// Every joint to `pose` (absolute tenths, by joint index), each clamped
    /// to its limits, walked at the live speed limit.
    pub(super) fn set_pose(&mut self, shell: &mut Shell<'_>, pose: [i16; 18]) {
        let before = self.pose;
        for joint in Joint::ALL {
            let setting = limits(&shell.document.project.plen2, joint);
            let low = setting.min_tenths_deg.min(setting.max_tenths_deg);
            let high = setting.max_tenths_deg.max(setting.min_tenths_deg);
            self.pose[joint.index()] = pose[joint.index()].clamp(low, high);
        }
        self.stream = None;
        self.walk_to_pose(shell, before, Instant::now());
    }

    /// Back to `pose` (an undone turn in the 3D view), walked at the live speed limit.
    pub fn restore_pose(&mut self, shell: &mut Shell<'_>, pose: [i16; 18]) {
        let before = self.pose;
        self.pose = pose;
        self.turning = None;
        self.stream = None;
        self.walk_to_pose(shell, before, Instant::now());
    }

    /// Home at the live speed limit: the joints are walked there (a `$HP`
    /// would send them at once).
    pub(super) fn home(&mut self, shell: &mut Shell<'_>) {
        let before = self.pose;
        self.pose = homes(&shell.document.project.plen2);
        self.stream = None;
        self.walk_to_pose(shell, before, Instant::now());
    }

    /// Starts (or redirects) the walk toward the sliders' pose from where the
    /// robot was last sent (`before` when no walk is under way); the first
    /// step goes at once.
    fn walk_to_pose(&mut self, shell: &mut Shell<'_>, before: [i16; 18], now: Instant) {
        if shell.plen2_mut().is_none() {
            self.slew = None;
            return;
        }
        let slew = match self.slew.take() {
            Some(mut slew) => {
                slew.target = self.pose;
                slew
            }
            None => Slew::new(before, self.pose, now.checked_sub(PLEN2_CYCLE).unwrap_or(now)),
        };
        self.slew = Some(slew);
        self.advance_slew(shell, now);
    }

    /// Sends the walk's next step if a cycle has passed; whether it still walks.
    pub fn advance_slew(&mut self, shell: &mut Shell<'_>, now: Instant) -> bool {
        let speed = shell.speed;
        let Some(slew) = &mut self.slew else { return false };
        let moved = slew.step(now, speed);
        let arrived = slew.arrived();
        if !moved.is_empty()
            && let Some(robot) = shell.plen2_mut()
        {
            robot.move_joints(moved.into_iter().map(|(index, angle)| (Joint::ALL[index].device_id(), angle)).collect());
        }
        if arrived {
            self.slew = None;
        }
        !arrived
    }

    pub(super) fn capture_frame(&mut self, shell: &mut Shell<'_>, slot: u8) {
        let homes = homes(&shell.document.project.plen2);
        let mut pose = Pose::default();
        for joint in Joint::ALL {
            pose.set(joint, self.pose[joint.index()].saturating_sub(homes[joint.index()]));
        }
        let mut plen2 = shell.document.project.plen2.clone();
        let Some(motion) = plen2.motions.iter_mut().find(|m| m.slot == slot) else { return };
        if motion.frames.len() >= MAX_FRAMES {
            let full = crate::project::ProblemKind::OutOfRange { field: "frames", value: 21, min: 1, max: 20 };
            shell.say(|language| language.problem(&full), true);
            return;
        }
        motion.frames.push(Frame::new(500, pose));
        shell.document.apply(Edit::SetPlen2(Box::new(plen2)), None);
    }

    pub(super) fn play_from(&mut self, shell: &Shell<'_>, slot: u8, frame: usize) {
        let Some(authored) = shell.document.project.plen2.motions.iter().find(|m| m.slot == slot) else {
            return;
        };
        // As the robot stores it: curves baked into straight frames, from the authored frame's first piece.
        let baked = bake_plen2(authored, DEFAULT_TOLERANCE_TENTHS);
        let frame = baked.source.iter().position(|&source| source == frame).unwrap_or(0);
        self.slew = None;
        self.stream = Some(Stream { motion: baked.motion, frame, started: Instant::now(), from: self.pose });
    }

    /// Fits what was recorded into frames and inserts them after the frame
    /// selected when recording began (one undo step); says how it went.
    pub(super) fn finish_recording(&mut self, shell: &mut Shell<'_>) {
        let Some(Recording { slot, after, recorder }) = self.recording.take() else { return };
        let names = Joint::ALL.iter().map(|joint| joint.name().to_string()).collect();
        let Some(recorded) = recorder.finish(names) else {
            shell.say(|language| language.strings().msg_nothing_recorded, true);
            return;
        };
        let rows = recorded.resample(PLEN2_UPDATE_MS);
        let mut plen2 = shell.document.project.plen2.clone();
        let Some(motion) = plen2.motions.iter_mut().find(|m| m.slot == slot) else { return };
        let allowed = MAX_FRAMES.saturating_sub(motion.frames.len());
        if allowed == 0 {
            shell.say(|language| language.strings().plen2().msg_no_room, true);
            return;
        }
        // From the frame it goes after (the robot's frame buffer holds it then).
        let after = after.min(motion.frames.len().saturating_sub(1));
        let start: Vec<i32> =
            motion.frames.get(after).map_or([0; 18], |frame| frame.values_tenths_deg.0).map(i32::from).to_vec();
        let tolerance = DEFAULT_TOLERANCE_TENTHS;
        let budget = Budget { tolerance, allowed, resolution: 1.0 };
        let (fitted, widened) = match fit::fit_within(&Plen2Board, &start, &rows, budget) {
            Ok(fitted) => (fitted, None),
            Err(FitError::Tolerance { .. }) => {
                let (wider, fitted) = fit::widest_needed(&Plen2Board, &start, &rows, budget);
                (fitted, Some(wider))
            }
            Err(FitError::TooLong { .. }) => {
                shell.say(|language| language.strings().plen2().msg_recording_too_long, true);
                return;
            }
        };
        let frames = plen2_frames(&fitted);
        let count = frames.len();
        let at = if motion.frames.is_empty() { 0 } else { after + 1 };
        motion.frames.splice(at..at, frames);
        shell.document.apply(Edit::SetPlen2(Box::new(plen2)), None);
        // Update counts at most an hour's: exact.
        #[allow(clippy::cast_precision_loss)]
        let seconds = rows.len() as f64 * PLEN2_UPDATE_MS / 1000.0;
        let said = |language: crate::ui::i18n::Language| {
            let (shared, captions) = (language.strings(), language.strings().plen2());
            let mut said = format!(
                "{}: {seconds:.1} s → {count} {} {after} · {} {:.1}°",
                shared.msg_recorded,
                captions.frames_inserted_after,
                shared.largest_error,
                fitted.max_error / 10.0
            );
            if let Some(wider) = widened {
                said.push_str(&format!(" ({} → {:.1}°)", captions.tolerance_widened, wider / 10.0));
            }
            said
        };
        shell.say(said, false);
    }

    /// Plays a play list: `#RI` and a `#PU` each at once, then `#PO`, which
    /// starts the first motion, with the sound as `start_with_sound` sends it.
    pub(super) fn play_list(&mut self, shell: &mut Shell<'_>, index: usize) {
        let Some(list) = shell.document.project.plen2.play_lists.get(index) else { return };
        let entries: Vec<(u8, u8)> = list.entries.iter().map(|e| (e.slot, e.plays)).collect();
        let last = entries.last().copied();
        let Some(robot) = shell.plen2_mut() else { return };
        robot.queue_list(&entries);
        start_with_sound(shell, crate::device::plen2::Command::Pop);
        // Where the last motion leaves the robot (one played forever never ends).
        if let Some((slot, _)) = last.filter(|&(_, plays)| plays > 0) {
            self.after_playing(shell, slot);
        }
    }

    /// Plays a motion stored on the robot (`$PM`), with the sound as
    /// `start_with_sound` sends it.
    pub(super) fn play_motion(&mut self, shell: &mut Shell<'_>, slot: u8) {
        start_with_sound(shell, crate::device::plen2::Command::PlayMotion { slot });
        self.after_playing(shell, slot);
    }

    /// The sliders to where `slot` leaves the robot (the project's motion
    /// played through the firmware's playback, plen2.md §6), so that a joint
    /// moved next is walked from there and not from where the sliders were:
    /// the robot reports no angles. A motion the project lacks, or one that
    /// never ends, leaves them be.
    fn after_playing(&mut self, shell: &Shell<'_>, slot: u8) {
        /// An hour of cycles: longer is playing on as far as the editor is concerned.
        const HOUR_OF_CYCLES: usize = 110_000;
        let project = &shell.document.project.plen2;
        if !project.motions.iter().any(|motion| motion.slot == slot) {
            return;
        }
        let stored = StoredMotions::new(project);
        if !playback::play(&stored, slot, [0; DEVICE_IDS], HOUR_OF_CYCLES).ended {
            return;
        }
        let settings = playback::joint_settings(project);
        let end = playback::clamped(&playback::after(&stored, slot, HOUR_OF_CYCLES), &settings);
        self.slew = None;
        self.stream = None;
        for joint in Joint::ALL {
            let device = usize::from(joint.device_id());
            self.pose[joint.index()] = settings[device].0.saturating_add(end[device]);
        }
    }

    /// Moves the streamed motion on to `now`; whether it still plays.
    pub fn advance_stream(&mut self, shell: &mut Shell<'_>, now: Instant) -> bool {
        let Some(stream) = &self.stream else { return false };
        let homes = homes(&shell.document.project.plen2);
        let elapsed = now.saturating_duration_since(stream.started).as_secs_f64() * 1000.0;
        let mut from = stream.from;
        let mut t = 0.0;
        let mut pose = None;
        for frame in stream.motion.frames.iter().skip(stream.frame) {
            let target: [i16; 18] = Joint::ALL.map(|j| homes[j.index()].saturating_add(frame.values_tenths_deg.get(j)));
            let span = f64::from(frame.transition_ms);
            if elapsed < t + span {
                let share = (elapsed - t) / span.max(1.0);
                #[allow(clippy::cast_possible_truncation)]
                let at = std::array::from_fn(|i| {
                    (f64::from(from[i]) + (f64::from(target[i]) - f64::from(from[i])) * share).round() as i16
                });
                pose = Some(at);
                break;
            }
            t += span;
            from = target;
        }
        match pose {
            Some(pose) => self.pose = pose,
            None => {
                self.pose = from;
                self.stream = None;
            }
        }
        self.send_pose(shell);
        self.stream.is_some()
    }
}

/// Sends `start`, a command that starts a motion (`$PM`, `#PO`). With a
/// sound track, the sound starts with it: its point for the show's start is
/// heard as the joints first move (the command goes out its time on the line
/// and half the firmware's update before, plen2.md §6). STOP before then
/// stops the sound and the command never goes out.
fn start_with_sound(shell: &mut Shell<'_>, start: crate::device::plen2::Command) {
    let Some(robot) = shell.plen2_mut() else { return };
    robot.stopped = false;
    let requester = robot.requester();
    let delay = crate::device::plen2::start_delay(&start, std::time::Duration::ZERO);
    let waker = shell.waker.clone();
    let on_time = requester.clone();
    let command = start.clone();
    // A lost command is the link's to report.
    let send = move || drop(on_time.send(command));
    if !shell.sound.play_with_board(&shell.document.project, 0.0, (delay, waker), send) {
        let _ = requester.send(start);
    }
}
