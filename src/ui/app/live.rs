//! Live moves from the editor: sliders, captured poses, played and previewed
//! actions, and buttons picked on the remote.

use super::*;

impl StudioApp {
    pub(super) fn set_pose(&mut self, servo_id: u8, degree: i16) {
        let Some(servo) = self.document.project.servo.servo(servo_id) else {
            return;
        };
        // The limits clamp every move the app sends, whatever asked for it.
        let degree = servo.clamp(degree);
        self.pose.insert(servo_id, degree);
        if let Some(link) = self.servo() {
            if link.stopped {
                self.report(self.words().msg_press_resume, true);
                return;
            }
            let servo_move = ServoMove { servo_id, degree, interval_10ms: LIVE_MOVE_INTERVAL_10MS };
            if let Err(error) = link.live_move(vec![servo_move]) {
                self.report(self.language.request_error(&error), true);
            }
        }
    }

    pub(super) fn capture_pose(&mut self, from_board: bool) {
        let project = &self.document.project.servo;
        let angle = |servo_id: u8, home: i16| -> i16 {
            if from_board {
                let read = self.servo().and_then(|link| link.servos.get(&servo_id)).map(|state| state.angle);
                read.unwrap_or(home)
            } else {
                self.pose.get(&servo_id).copied().unwrap_or(home)
            }
        };
        let steps: Vec<Step> = project
            .servos
            .iter()
            .map(|servo| Step {
                servo_id: servo.id,
                degree: servo.clamp(angle(servo.id, servo.home_deg)),
                interval_10ms: CAPTURED_STEP_INTERVAL_10MS,
            })
            .collect();
        if steps.is_empty() {
            self.report(self.words().msg_nothing_to_capture, true);
            return;
        }
        let id = next_free_id(project.actions.iter().map(|action| action.id));
        let caption = format!("{} {id}", self.language.strings().pose);
        self.document.apply(Edit::AddAction(ProjectAction { id, caption: caption.clone(), steps }), None);
        self.report(format!("{} {id} \"{caption}\"", self.words().msg_captured), false);
    }

    /// Sends an action's steps as one live move (clamped to each servo's limits)
    /// and shows the targets on the sliders.
    pub(super) fn play_action(&mut self, action_id: i32) {
        let Some(action) = self.document.project.servo.action(action_id) else { return };
        let moves: Vec<ServoMove> = action
            .steps
            .iter()
            .filter_map(|step| {
                let servo = self.document.project.servo.servo(step.servo_id)?;
                Some(ServoMove {
                    servo_id: step.servo_id,
                    degree: servo.clamp(step.degree),
                    interval_10ms: step.interval_10ms,
                })
            })
            .collect();
        let Some(link) = self.servo() else {
            self.report(self.words().msg_connect_for_play, true);
            return;
        };
        if link.stopped {
            self.report(self.words().msg_press_resume, true);
            return;
        }
        if let Err(error) = link.move_now(moves.clone()) {
            self.report(self.language.op_error(&error), true);
            return;
        }
        for servo_move in moves {
            self.pose.insert(servo_move.servo_id, servo_move.degree);
        }
    }

    /// Moves the sliders along the previewed action at `now`; ends the preview after its last step.
    pub fn advance_preview(&mut self, now: Instant) {
        let Some((action_id, started)) = self.preview else { return };
        let (trajectories, end_ms) = crate::project::action_trajectories(&self.document.project.servo, action_id);
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
    pub(super) fn pick_button(&mut self, table_index: usize, button_id: u32) {
        self.picked_button = Some(button_id);
        let Some(table) = self.document.project.servo.joystick_tables.get(table_index) else { return };
        if table.buttons.iter().any(|button| button.id == button_id) {
            self.report(format!("{} 0x{button_id:08x}", self.words().msg_picked), false);
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
        self.document.apply(Edit::SetTable { index: table_index, table }, None);
        self.report(format!("{} 0x{button_id:08x}", self.words().msg_added_button), false);
    }
}
