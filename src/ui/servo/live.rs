//! Live moves from the servo panels: sliders, captured poses, played and
//! previewed actions, and buttons picked on the remote.

use std::time::{Duration, Instant};

use super::ServoLink;
use super::{CAPTURED_STEP_INTERVAL_10MS, LIVE_MOVE_INTERVAL_10MS, ServoUi};
use crate::authoring::bake_servo;
use crate::authoring::fit::{self, Board, ServoBoard};
use crate::authoring::fitted::{self, SERVO_UPDATE_MS};
use crate::device::servo::{Known, ServoMove};
use crate::device::speed::LiveSpeed;
use crate::project::{Action as ProjectAction, Edit, Run, ServoProject, Step, next_free_id};
use crate::ui::i18n::Worded;
use crate::ui::servo::captions::ServoWords;
use crate::ui::shell::Shell;
use std::collections::BTreeMap;

/// A part of what is played live: steps sent together, then at least
/// `wait_ms` (a delay) before the next.
#[derive(Clone, Debug, PartialEq)]
pub struct Part {
    steps: Vec<Step>,
    wait_ms: u64,
}

/// At most this many parts are played from one click (a macro of long loops
/// is cut there rather than planned for hours).
const MOST_PARTS: usize = 10_000;

/// The parts of `action` at `speed` (ratio / 100) from `angles` (moved on to
/// where it ends): a curved one as its straight sub-steps.
fn action_parts(action: &ProjectAction, angles: &mut BTreeMap<u8, f64>, speed: f64, parts: &mut Vec<Part>) {
    let pieces = if bake_servo::is_curved(action) {
        bake_servo::bake_action(action, angles, bake_servo::DEFAULT_TOLERANCE_DEG, 1).0
    } else {
        vec![action.clone()]
    };
    for piece in pieces {
        let steps = piece
            .steps
            .iter()
            .map(|step| {
                // A slowed step lasts at most what one step can (32767 × 10 ms).
                #[allow(clippy::cast_possible_truncation)]
                let interval = (f64::from(step.interval_10ms.max(0)) / speed).round().min(f64::from(i16::MAX)) as i16;
                Step::new(step.servo_id, step.degree, interval)
            })
            .collect();
        parts.push(Part { steps, wait_ms: 0 });
    }
    for step in &action.steps {
        angles.insert(step.servo_id, f64::from(step.degree));
    }
}

/// The parts `command` plays at `speed`, as the board runs it (a delay is not
/// slowed by the ratio; a macro already running is not entered again).
fn command_parts(
    project: &ServoProject,
    command: &crate::project::Command,
    speed: f64,
    (angles, running): (&mut BTreeMap<u8, f64>, &mut Vec<i32>),
    parts: &mut Vec<Part>,
) {
    let speed = speed * f64::from(command.ratio_percent.max(1)) / 100.0;
    for _ in 0..command.loop_count.max(0) {
        if parts.len() >= MOST_PARTS {
            return;
        }
        match command.run {
            Run::Action { action_id } => {
                if let Some(action) = project.action(action_id) {
                    action_parts(action, angles, speed, parts);
                }
            }
            Run::Delay { delay_ms } => {
                parts.push(Part { steps: Vec::new(), wait_ms: u64::from(delay_ms.max(0).unsigned_abs()) });
            }
            Run::Macro { macro_id } => {
                let Some(item) = project.macro_by_id(macro_id).filter(|_| !running.contains(&macro_id)) else { return };
                running.push(macro_id);
                for inner in &item.commands {
                    command_parts(project, inner, speed, (&mut *angles, &mut *running), parts);
                }
                running.pop();
            }
        }
    }
}

impl ServoUi {
    /// A live move of `servo` to `degree`, from where it is now (along its
    /// last live move; else where the board last read it; else the slider's
    /// last value), its interval from the distance at the live speed limit,
    /// at least `least` (10 ms units). Remembered for the next one. Where the
    /// servo cannot be known (the board moved it on its own: a macro, a remote
    /// button, a STOP mid-move) and no reading has come since, the move is
    /// timed from the far end of its limits: slow, never a slam.
    fn limited_move(
        &mut self,
        speed: LiveSpeed,
        (servo, degree): (&crate::project::Servo, i16),
        (shown, reading, read_at): (i16, Option<i16>, Option<Instant>),
        least: i16,
    ) -> ServoMove {
        let known = Known { shown: Some(shown), reading, read_at };
        self.live.limited_move((servo, f64::from(degree)), known, (speed, least), Instant::now())
    }

    /// The board moves the servos on its own from `now` for `running` (a
    /// macro, a remote button, a STOP): where they are is not known until
    /// the board is read after that.
    pub(super) fn board_moved_them(&mut self, project: &ServoProject, now: Instant, running: Duration) {
        self.live.board_moved_them(project.servos.iter().map(|servo| servo.id), now + running);
    }

    /// Runs a stored macro on the board; with a sound track, the sound starts
    /// with it (its point for the motion's start heard as the board starts
    /// moving, the command sent the line's time early).
    pub(super) fn run_macro(&mut self, shell: &mut Shell<'_>, macro_id: i32) {
        let Some(servo) = shell.servo_mut() else {
            shell.say(|language| language.strings().servo().msg_connect_for_macro, true);
            return;
        };
        let requester = servo.requester();
        let baud = crate::device::servo::DEFAULT_BAUD;
        let delay = crate::device::servo::run_macro_delay(macro_id, baud, Duration::ZERO);
        let start = move || {
            // The reply is the board's to give; a lost one is the link's to report.
            let _ = requester.run_macro(macro_id);
        };
        let waker = shell.waker.clone();
        if !shell.sound.play_with_board(&shell.document.project, 0.0, (delay, waker), start)
            && let Some(servo) = shell.servo_mut()
        {
            servo.run_macro(macro_id);
        }
        let project = &shell.document.project.servo;
        let running = crate::project::Timing::new(project).macro_total_ms(macro_id).unwrap_or(0);
        let running = Duration::from_millis(u64::try_from(running).unwrap_or(0));
        self.board_moved_them(project, Instant::now(), running);
    }

    pub(super) fn set_pose(&mut self, shell: &mut Shell<'_>, servo_id: u8, degree: i16) {
        let Some(servo) = shell.document.project.servo.servo(servo_id) else {
            return;
        };
        // The limits clamp every move the app sends, whatever asked for it.
        let degree = servo.clamp(degree);
        let before = self.pose.insert(servo_id, degree).unwrap_or(servo.home_deg);
        let speed = shell.speed;
        if let Some(link) = shell.servo() {
            if link.stopped {
                shell.say(|language| language.strings().servo().msg_press_resume, true);
                return;
            }
            let reading = link.servos.get(&servo_id).map(|state| state.angle);
            let from = (before, reading, link.servos_read_at);
            let servo_move = self.limited_move(speed, (servo, degree), from, LIVE_MOVE_INTERVAL_10MS);
            if let Err(error) = link.live_move(vec![servo_move]) {
                shell.say(|language| error.worded(language), true);
            }
        }
    }

    /// Back to `pose` (an undone turn in the 3D view): each servo that differs
    /// is moved there live, at the live speed limit.
    pub fn restore_pose(&mut self, shell: &mut Shell<'_>, pose: BTreeMap<u8, i16>) {
        self.turning = None;
        for (servo_id, degree) in pose {
            if self.pose.get(&servo_id) != Some(&degree) {
                self.set_pose(shell, servo_id, degree);
            }
        }
    }

    pub(super) fn capture_pose(&mut self, shell: &mut Shell<'_>, from_board: bool) {
        let project = &shell.document.project.servo;
        let read = shell.servo().map(|link| &link.servos);
        let angle = |servo_id: u8, home: i16| -> i16 {
            if from_board {
                read.and_then(|servos| servos.get(&servo_id)).map_or(home, |state| state.angle)
            } else {
                self.pose.get(&servo_id).copied().unwrap_or(home)
            }
        };
        let steps: Vec<Step> = project
            .servos
            .iter()
            .map(|servo| Step::new(servo.id, servo.clamp(angle(servo.id, servo.home_deg)), CAPTURED_STEP_INTERVAL_10MS))
            .collect();
        if steps.is_empty() {
            shell.say(|language| language.strings().servo().msg_nothing_to_capture, true);
            return;
        }
        let id = next_free_id(project.actions.iter().map(|action| action.id));
        let caption = format!("{} {id}", shell.words().pose);
        shell.document.apply(Edit::AddAction(ProjectAction { id, caption: caption.clone(), steps }), None);
        shell.say(|language| format!("{} {id} \"{caption}\"", language.strings().servo().msg_captured), false);
    }

    /// Fits what was recorded into steps — one action each, and a macro
    /// running them in order — and adds them (one undo step); says how it went.
    pub(super) fn finish_recording(&mut self, shell: &mut Shell<'_>) {
        let Some(recorder) = self.recording.take() else { return };
        let captions = shell.words().servo();
        let project = &shell.document.project.servo;
        let names = project.servos.iter().map(|servo| servo.id.to_string()).collect();
        let rows = recorder.finish(names).map(|recorded| recorded.resample(SERVO_UPDATE_MS)).unwrap_or_default();
        let Some((first, rest)) = rows.split_first().filter(|(_, rest)| !rest.is_empty()) else {
            shell.say(|language| language.strings().msg_nothing_recorded, true);
            return;
        };
        // From where the servos were when recording began, within 1°.
        let start: Vec<i32> = first.iter().map(|&value| ServoBoard.store(value)).collect();
        let fitted = fit::fit(&ServoBoard, &start, rest, 1.0);
        let ids: Vec<u8> = project.servos.iter().map(|servo| servo.id).collect();
        let mut changed = project.clone();
        let macro_id = next_free_id(changed.macros.iter().map(|item| item.id));
        let caption = format!("{} {macro_id}", captions.recording_caption);
        let mut added = fitted::servo_actions(&fitted, &ids, 0, &caption);
        for action in &mut added {
            action.id = next_free_id(changed.actions.iter().map(|known| known.id));
            changed.actions.push(action.clone());
        }
        changed.macros.push(fitted::macro_running(macro_id, &caption, &added));
        shell.document.apply(Edit::ReplaceAll(Box::new(changed)), None);
        // Update counts at most an hour's: exact.
        #[allow(clippy::cast_precision_loss)]
        let seconds = rest.len() as f64 * SERVO_UPDATE_MS / 1000.0;
        shell.say(
            |language| {
                let (shared, captions) = (language.strings(), language.strings().servo());
                format!(
                    "{}: {seconds:.1} s → {} {} {macro_id} \"{caption}\" · {} {:.1}°",
                    shared.msg_recorded,
                    added.len(),
                    if added.len() == 1 { captions.action_run_by_macro } else { captions.actions_run_by_macro },
                    shared.largest_error,
                    fitted.max_error
                )
            },
            false,
        );
    }

    /// Sends an action's steps as one live move (clamped to each servo's limits)
    /// and shows the targets on the sliders.
    /// Where each servo is now, as far as the editor knows: the board's
    /// reading, else the slider.
    fn where_now(&self, shell: &Shell<'_>) -> BTreeMap<u8, f64> {
        let read = shell.servo().map(|link| &link.servos);
        shell
            .document
            .project
            .servo
            .servos
            .iter()
            .map(|servo| {
                let shown = self.pose.get(&servo.id).copied().unwrap_or(servo.home_deg);
                let reading = read.and_then(|servos| servos.get(&servo.id)).map(|state| state.angle);
                (servo.id, f64::from(reading.unwrap_or(shown)))
            })
            .collect()
    }

    /// Plays an action of the project on the board now, from where its servos
    /// are: a curved one as its straight sub-steps, one after another (the
    /// tick sends the next when the last is done).
    pub(super) fn play_action(&mut self, shell: &mut Shell<'_>, action_id: i32) {
        let project = &shell.document.project.servo;
        let Some(action) = project.action(action_id) else { return };
        let mut angles = self.where_now(shell);
        let mut parts = Vec::new();
        action_parts(action, &mut angles, 1.0, &mut parts);
        self.play_parts(shell, parts);
    }

    /// Plays a macro on the board live from its command `from` (its own
    /// commands on, what they run flattened into parts), from where the servos are.
    pub(super) fn play_macro_from(&mut self, shell: &mut Shell<'_>, macro_id: i32, from: usize) {
        let project = &shell.document.project.servo;
        let Some(item) = project.macro_by_id(macro_id) else { return };
        let mut angles = self.where_now(shell);
        let mut parts = Vec::new();
        let mut running = vec![macro_id];
        for command in item.commands.iter().skip(from) {
            command_parts(project, command, 1.0, (&mut angles, &mut running), &mut parts);
        }
        self.play_parts(shell, parts);
    }

    fn play_parts(&mut self, shell: &mut Shell<'_>, parts: Vec<Part>) {
        if shell.servo().is_none() {
            shell.say(|language| language.strings().servo().msg_connect_for_play, true);
            return;
        }
        self.playing = parts.into();
        self.playing_until = None;
        self.play_next(shell, Instant::now());
    }

    /// Sends the next part of what is being played, if the last is done.
    pub(super) fn play_next(&mut self, shell: &mut Shell<'_>, now: Instant) {
        if self.playing_until.is_some_and(|until| now < until) {
            return;
        }
        self.playing_until = None;
        let Some(part) = self.playing.pop_front() else { return };
        let project = &shell.document.project.servo;
        let read = shell.servo().map(|link| &link.servos);
        let read_at = shell.servo().and_then(|link| link.servos_read_at);
        let mut moves = Vec::new();
        for step in &part.steps {
            let Some(servo) = project.servo(step.servo_id) else { continue };
            let shown = self.pose.get(&step.servo_id).copied().unwrap_or(servo.home_deg);
            let reading = read.and_then(|servos| servos.get(&step.servo_id)).map(|state| state.angle);
            // The step's own interval, or longer when the live speed limit needs it.
            let least = step.interval_10ms.max(1);
            let degree = servo.clamp(step.degree);
            moves.push(self.limited_move(shell.speed, (servo, degree), (shown, reading, read_at), least));
        }
        let Some(link) = shell.servo() else {
            self.playing.clear();
            shell.say(|language| language.strings().servo().msg_connect_for_play, true);
            return;
        };
        if link.stopped {
            self.playing.clear();
            shell.say(|language| language.strings().servo().msg_press_resume, true);
            return;
        }
        if !moves.is_empty()
            && let Err(error) = link.move_now(moves.clone())
        {
            self.playing.clear();
            shell.say(|language| error.worded(language), true);
            return;
        }
        let longest = moves.iter().map(|m| u64::from(m.interval_10ms.max(0).unsigned_abs()) * 10).max().unwrap_or(0);
        self.playing_until = Some(now + Duration::from_millis(longest.max(part.wait_ms)));
        for servo_move in moves {
            self.pose.insert(servo_move.servo_id, servo_move.degree);
        }
    }

    /// Moves the sliders along the previewed action at `now`; ends the preview after its last step.
    pub fn advance_preview(&mut self, project: &ServoProject, now: Instant) {
        let Some((action_id, started)) = self.preview else { return };
        let (trajectories, end_ms) = crate::project::action_trajectories(project, action_id);
        let elapsed_ms = now.saturating_duration_since(started).as_secs_f64() * 1000.0;
        for (servo_id, points) in &trajectories {
            if let Some(angle) = crate::project::angle_at(points, elapsed_ms) {
                // Within the servo's limits, as every step is.
                #[allow(clippy::cast_possible_truncation)]
                let degree = angle.round() as i16;
                self.pose.insert(*servo_id, degree);
            }
        }
        if elapsed_ms >= end_ms {
            self.preview = None;
        }
    }

    /// Selects the pressed button in the table, adding it if the table lacks it.
    pub(super) fn pick_button(&mut self, shell: &mut Shell<'_>, table_index: usize, button_id: u32) {
        self.picked_button = Some(button_id);
        let Some(table) = shell.document.project.servo.joystick_tables.get(table_index) else { return };
        if table.buttons.iter().any(|button| button.id == button_id) {
            shell.say(|language| format!("{} 0x{button_id:08x}", language.strings().servo().msg_picked), false);
            return;
        }
        let mut table = table.clone();
        table.buttons.push(crate::project::Button {
            id: button_id,
            caption: String::new(),
            press_macro: None,
            long_press_macro: None,
            release_macro: None,
            uninterruptible: false,
        });
        shell.document.apply(Edit::SetTable { index: table_index, table }, None);
        shell.say(|language| format!("{} 0x{button_id:08x}", language.strings().servo().msg_added_button), false);
    }
}
