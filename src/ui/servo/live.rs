//! Live moves from the servo panels: sliders, captured poses, played and
//! previewed actions, and buttons picked on the remote.

use std::time::{Duration, Instant};

use super::ServoLink;
use super::{CAPTURED_STEP_INTERVAL_10MS, LIVE_MOVE_INTERVAL_10MS, ServoUi};
use crate::authoring::bake_servo;
use crate::authoring::fit::{self, Board, ServoBoard};
use crate::authoring::fitted::{self, SERVO_UPDATE_MS};
use crate::device::servo::ServoMove;
use crate::project::{Action as ProjectAction, Edit, ServoProject, Step, next_free_id};
use crate::ui::servo::captions::ServoWords;
use crate::ui::shell::Shell;
use crate::ui::speed::LiveSpeed;

/// A live move as sent: the board turns the servo linearly from `from` to
/// `to` over `interval`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Moving {
    from: f64,
    to: i16,
    start: Instant,
    interval: Duration,
}

impl Moving {
    /// Where the servo is at `now`, by the board's linear move.
    fn at(&self, now: Instant) -> f64 {
        let done = now.saturating_duration_since(self.start).as_secs_f64() / self.interval.as_secs_f64().max(1e-9);
        self.from + (f64::from(self.to) - self.from) * done.min(1.0)
    }
}

impl ServoUi {
    /// A live move of `servo_id` to `degree`, from where it is now (along its
    /// last live move; else where the board last read it; else the slider's
    /// last value), its interval from the distance at the live speed limit,
    /// at least `least` (10 ms units). Remembered for the next one.
    fn limited_move(
        &mut self,
        speed: LiveSpeed,
        servo_id: u8,
        degree: i16,
        from: (i16, Option<i16>),
        least: i16,
    ) -> ServoMove {
        let now = Instant::now();
        let (shown, reading) = from;
        let here =
            self.moving.get(&servo_id).map_or_else(|| f64::from(reading.unwrap_or(shown)), |moving| moving.at(now));
        let interval_10ms = speed.interval_10ms(f64::from(degree) - here, least);
        let interval = Duration::from_millis(u64::from(interval_10ms.unsigned_abs()) * 10);
        self.moving.insert(servo_id, Moving { from: here, to: degree, start: now, interval });
        ServoMove { servo_id, degree, interval_10ms }
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
                shell.report(shell.words().servo().msg_press_resume, true);
                return;
            }
            let reading = link.servos.get(&servo_id).map(|state| state.angle);
            let servo_move = self.limited_move(speed, servo_id, degree, (before, reading), LIVE_MOVE_INTERVAL_10MS);
            if let Err(error) = link.live_move(vec![servo_move]) {
                shell.report(shell.language.request_error(&error), true);
            }
        }
    }

    /// Back to `pose` (an undone turn in the 3D view): each servo that differs
    /// is moved there live, at the live speed limit.
    pub fn restore_pose(&mut self, shell: &mut Shell<'_>, pose: std::collections::BTreeMap<u8, i16>) {
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
            shell.report(shell.words().servo().msg_nothing_to_capture, true);
            return;
        }
        let id = next_free_id(project.actions.iter().map(|action| action.id));
        let caption = format!("{} {id}", shell.words().pose);
        shell.document.apply(Edit::AddAction(ProjectAction { id, caption: caption.clone(), steps }), None);
        shell.report(format!("{} {id} \"{caption}\"", shell.words().servo().msg_captured), false);
    }

    /// Fits what was recorded into steps — one action each, and a macro
    /// running them in order — and adds them (one undo step); says how it went.
    pub(super) fn finish_recording(&mut self, shell: &mut Shell<'_>) {
        let Some(recorder) = self.recording.take() else { return };
        let (shared, captions) = (shell.words(), shell.words().servo());
        let project = &shell.document.project.servo;
        let names = project.servos.iter().map(|servo| servo.id.to_string()).collect();
        let rows = recorder.finish(names).map(|recorded| recorded.resample(SERVO_UPDATE_MS)).unwrap_or_default();
        let Some((first, rest)) = rows.split_first().filter(|(_, rest)| !rest.is_empty()) else {
            shell.report(shared.msg_nothing_recorded, true);
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
        shell.report(
            format!(
                "{}: {seconds:.1} s → {} {} {macro_id} \"{caption}\" · {} {:.1}°",
                shared.msg_recorded,
                added.len(),
                captions.actions_run_by_macro,
                shared.largest_error,
                fitted.max_error
            ),
            false,
        );
    }

    /// Sends an action's steps as one live move (clamped to each servo's limits)
    /// and shows the targets on the sliders.
    /// Plays an action of the project on the board now, from where its servos
    /// are: a curved one as its straight sub-steps, one after another (the
    /// tick sends the next when the last is done).
    pub(super) fn play_action(&mut self, shell: &mut Shell<'_>, action_id: i32) {
        let project = &shell.document.project.servo;
        let Some(action) = project.action(action_id) else { return };
        self.playing.clear();
        let parts = if bake_servo::is_curved(action) {
            let read = shell.servo().map(|link| &link.servos);
            let from: std::collections::BTreeMap<u8, f64> = action
                .steps
                .iter()
                .filter_map(|step| {
                    let servo = project.servo(step.servo_id)?;
                    let shown = self.pose.get(&step.servo_id).copied().unwrap_or(servo.home_deg);
                    let reading = read.and_then(|servos| servos.get(&step.servo_id)).map(|state| state.angle);
                    Some((step.servo_id, f64::from(reading.unwrap_or(shown))))
                })
                .collect();
            bake_servo::bake_action(action, &from, bake_servo::DEFAULT_TOLERANCE_DEG, 1).0
        } else {
            vec![action.clone()]
        };
        self.playing = parts.into_iter().map(|part| part.steps).collect();
        self.play_next(shell, Instant::now());
    }

    /// Sends the next part of the action being played, if the last is done.
    pub(super) fn play_next(&mut self, shell: &mut Shell<'_>, now: Instant) {
        if self.playing_until.is_some_and(|until| now < until) {
            return;
        }
        self.playing_until = None;
        let Some(steps) = self.playing.pop_front() else { return };
        let project = &shell.document.project.servo;
        let read = shell.servo().map(|link| &link.servos);
        let mut moves = Vec::new();
        for step in &steps {
            let Some(servo) = project.servo(step.servo_id) else { continue };
            let shown = self.pose.get(&step.servo_id).copied().unwrap_or(servo.home_deg);
            let reading = read.and_then(|servos| servos.get(&step.servo_id)).map(|state| state.angle);
            // The step's own interval, or longer when the live speed limit needs it.
            let least = step.interval_10ms.max(1);
            moves.push(self.limited_move(
                shell.speed,
                step.servo_id,
                servo.clamp(step.degree),
                (shown, reading),
                least,
            ));
        }
        let Some(link) = shell.servo() else {
            self.playing.clear();
            shell.report(shell.words().servo().msg_connect_for_play, true);
            return;
        };
        if link.stopped {
            self.playing.clear();
            shell.report(shell.words().servo().msg_press_resume, true);
            return;
        }
        if let Err(error) = link.move_now(moves.clone()) {
            self.playing.clear();
            shell.report(shell.language.op_error(&error), true);
            return;
        }
        let longest = moves.iter().map(|m| m.interval_10ms.max(0).unsigned_abs()).max().unwrap_or(0);
        self.playing_until = Some(now + Duration::from_millis(u64::from(longest) * 10));
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
            shell.report(format!("{} 0x{button_id:08x}", shell.words().servo().msg_picked), false);
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
        shell.report(format!("{} 0x{button_id:08x}", shell.words().servo().msg_added_button), false);
    }
}
