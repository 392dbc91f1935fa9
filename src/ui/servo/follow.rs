//! A servo follows the sound: its actions, one per fitted step, and a macro
//! running them (the follow dialog, `ui::sound::follow`, asks for them).

use crate::authoring::fitted::SERVO_UPDATE_MS;
use crate::authoring::follow;
use crate::project::{Edit, Project, next_free_id};
use crate::ui::i18n::Said;
use crate::ui::sound::follow::{Follower, SoundFollower, Target, Words, fit_error, said_by};

/// A servo board's side of following the sound.
pub struct ServoFollower;

impl SoundFollower for ServoFollower {
    fn axes(&self, project: &Project) -> Vec<(usize, String)> {
        let servos = &project.servo.servos;
        servos.iter().map(|servo| (usize::from(servo.id), format!("{} {}", servo.id, servo.caption))).collect()
    }

    fn axis_word(&self, words: &Words) -> &'static str {
        words.servo
    }

    fn make(
        &self,
        project: &Project,
        axis: usize,
        open: &[f64],
        (follower, _): (Follower, Target),
        words: &Words,
    ) -> Result<(Vec<Edit>, Said), Said> {
        let servo_id = u8::try_from(axis).map_err(|_| said_by(|words| words.no_servo.to_string()))?;
        let servo = &project.servo;
        // Ids after every one in use: the fitted actions take the next ones in a row.
        let first = servo.actions.iter().map(|action| action.id).max().unwrap_or(0).saturating_add(1);
        let macro_id = next_free_id(servo.macros.iter().map(|item| item.id));
        match follow::servo(open, servo_id, follower, (first, macro_id, words.title)) {
            Ok((made, running, _)) => {
                let count = made.len();
                let said = said_by(|words| crate::say!(words.lang, "follow.made_steps", count, macro_id));
                let mut edits: Vec<Edit> = made.into_iter().map(Edit::AddAction).collect();
                edits.push(Edit::AddMacro(running));
                Ok((edits, said))
            }
            Err(error) => Err(said_by(|words| fit_error(&error, (1.0, SERVO_UPDATE_MS), words.steps, words))),
        }
    }
}
