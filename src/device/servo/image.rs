//! A board's stored contents ([`ServoImage`], protocol records) converted to
//! and from a project, and compared. Both the upload (project → board) and
//! the backup (board → project) go through here.

use crate::authoring::bake_servo::{BakedServo, DEFAULT_TOLERANCE_DEG, bake_servo};
use crate::project::{Action, Button, Command, JoystickTable, Macro, Run, Servo, ServoProject, Step, Timing};
pub use crate::protocol::servo::ServoImage;
use crate::protocol::servo::{
    ActionRecord, ButtonRecord, CommandType, JoystickTableRecord, MacroCommandRecord, MacroRecord, STR32_LEN,
    ServoMove, ServoParameter,
};

/// A project cannot be written onto a board at all (whatever `--force` says).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ImageError {
    /// A caption longer than the board's 32-byte field.
    #[error("{item}: the caption is {bytes} UTF-8 bytes; the board stores at most {STR32_LEN}. Shorten it")]
    CaptionTooLong {
        /// Whose caption, e.g. `action 3 "揮手"`.
        item: String,
        /// Its length.
        bytes: usize,
    },
}

fn caption(item: impl FnOnce() -> String, caption: &str) -> Result<String, ImageError> {
    if caption.len() > STR32_LEN {
        return Err(ImageError::CaptionTooLong { item: item(), bytes: caption.len() });
    }
    Ok(caption.to_string())
}

/// The `totalInterval` written for `command`: the one the board stored, while
/// the command is unedited; else the derived one. A total that cannot be
/// derived (a missing action, a cycle) is written as 0 and one past the
/// board's counter as its largest value: validation reports both, and only a
/// forced restore gets this far with them.
fn total_interval_ms(timing: &Timing<'_>, command: &Command) -> i32 {
    if let Some(stored_ms) = command.stored_total_ms {
        return stored_ms;
    }
    match timing.command_total_ms(command) {
        Ok(total_ms) => i32::try_from(total_ms).unwrap_or(if total_ms < 0 { i32::MIN } else { i32::MAX }),
        Err(_) => 0,
    }
}

impl ServoImage {
    /// The records a project becomes on the board, its curves baked into
    /// straight steps at the default tolerance ([`bake_servo`]). Content Servo
    /// Studio would not author (a servo twice in an action, dangling
    /// references) is kept as it is, so that a backup restores exactly; only
    /// what cannot be encoded at all is refused.
    pub fn from_project(project: &ServoProject) -> Result<Self, ImageError> {
        Self::within(project, None).map(|(image, _)| image)
    }

    /// As [`Self::from_project`], the curves' tolerance widened until the
    /// records fit `total_bytes` of the board (when known); also what baking cost.
    pub fn within(project: &ServoProject, total_bytes: Option<i64>) -> Result<(Self, BakedServo), ImageError> {
        let fits = |stored: &ServoProject| {
            let bytes = Self::from_stored(stored).ok().and_then(|image| image.footprint_bytes().ok());
            total_bytes.is_none_or(|total| bytes.is_some_and(|bytes| i64::try_from(bytes).is_ok_and(|b| b <= total)))
        };
        let baked = bake_servo(project, DEFAULT_TOLERANCE_DEG, fits);
        Ok((Self::from_stored(&baked.project)?, baked))
    }

    /// The records of a project with only straight steps.
    fn from_stored(project: &ServoProject) -> Result<Self, ImageError> {
        let timing = Timing::new(project);
        let mut servos = Vec::with_capacity(project.servos.len());
        for servo in &project.servos {
            servos.push(ServoParameter {
                servo_id: servo.id,
                adjusted_degree: servo.calibration_offset_deg,
                caption: caption(|| format!("servo {} {:?}", servo.id, servo.caption), &servo.caption)?,
            });
        }
        let mut actions = Vec::with_capacity(project.actions.len());
        for action in &project.actions {
            actions.push(ActionRecord {
                action_id: action.id,
                caption: caption(|| format!("action {} {:?}", action.id, action.caption), &action.caption)?,
                steps: action
                    .steps
                    .iter()
                    .map(|step| ServoMove {
                        servo_id: step.servo_id,
                        degree: step.degree,
                        interval_10ms: step.interval_10ms,
                    })
                    .collect(),
            });
        }
        let mut macros = Vec::with_capacity(project.macros.len());
        for item in &project.macros {
            let commands = item
                .commands
                .iter()
                .map(|command| {
                    let (command_type, command_id) = match command.run {
                        Run::Action { action_id } => (CommandType::RunAction, action_id),
                        Run::Delay { delay_ms } => (CommandType::Delay, delay_ms),
                        Run::Macro { macro_id } => (CommandType::RunMacro, macro_id),
                    };
                    MacroCommandRecord {
                        command_id,
                        command_type,
                        ratio_percent: command.ratio_percent,
                        loop_count: command.loop_count,
                        total_interval_ms: total_interval_ms(&timing, command),
                    }
                })
                .collect();
            macros.push(MacroRecord {
                macro_id: item.id,
                caption: caption(|| format!("macro {} {:?}", item.id, item.caption), &item.caption)?,
                commands,
            });
        }
        let tables = table_records(project)?;
        Ok(Self {
            project_id: project.project_id,
            servos,
            actions,
            macros,
            tables,
            active_table: project.active_table.unwrap_or(0),
        })
    }

    /// The project these records describe, keeping everything: each macro
    /// command's stored total, and content Servo Studio would not author. The
    /// board does not store the client-side limits: each servo gets ±180°,
    /// widened to cover its steps, and home 0. A servo that steps name but the
    /// board has no parameters for stays out of the servo list (adding it
    /// would add a record on restore); validation points it out.
    pub fn to_project(&self) -> ServoProject {
        let mut servos: Vec<Servo> = self
            .servos
            .iter()
            .map(|parameter| Servo {
                calibration_offset_deg: parameter.adjusted_degree,
                ..Servo::new(parameter.servo_id, parameter.caption.clone())
            })
            .collect();
        for step in self.actions.iter().flat_map(|action| &action.steps) {
            for servo in servos.iter_mut().filter(|servo| servo.id == step.servo_id) {
                servo.min_deg = servo.min_deg.min(step.degree);
                servo.max_deg = servo.max_deg.max(step.degree);
            }
        }
        let none_if_zero = |id: i32| (id != 0).then_some(id);
        ServoProject {
            project_id: self.project_id,
            servos,
            meshes: Vec::new(),
            actions: self
                .actions
                .iter()
                .map(|record| Action {
                    id: record.action_id,
                    caption: record.caption.clone(),
                    steps: record
                        .steps
                        .iter()
                        .map(|step| Step::new(step.servo_id, step.degree, step.interval_10ms))
                        .collect(),
                })
                .collect(),
            macros: self
                .macros
                .iter()
                .map(|record| Macro {
                    id: record.macro_id,
                    caption: record.caption.clone(),
                    commands: record
                        .commands
                        .iter()
                        .map(|command| Command {
                            run: match command.command_type {
                                CommandType::RunAction => Run::Action { action_id: command.command_id },
                                CommandType::Delay => Run::Delay { delay_ms: command.command_id },
                                CommandType::RunMacro => Run::Macro { macro_id: command.command_id },
                            },
                            ratio_percent: command.ratio_percent,
                            loop_count: command.loop_count,
                            stored_total_ms: Some(command.total_interval_ms),
                        })
                        .collect(),
                })
                .collect(),
            joystick_tables: self
                .tables
                .iter()
                .map(|record| JoystickTable {
                    id: record.table_id,
                    caption: record.caption.clone(),
                    buttons: record
                        .buttons
                        .iter()
                        .map(|button| Button {
                            id: button.button_id,
                            caption: button.caption.clone(),
                            press_macro: none_if_zero(button.press_macro),
                            long_press_macro: none_if_zero(button.long_press_macro),
                            release_macro: none_if_zero(button.up_macro),
                            uninterruptible: button.uninterruptible,
                        })
                        .collect(),
                })
                .collect(),
            active_table: none_if_zero(self.active_table),
        }
    }

    /// Every difference between `self` (what was meant) and `actual` (what the
    /// board holds). Empty when they match exactly.
    pub fn differences(&self, actual: &Self) -> Vec<Difference> {
        let mut out = Vec::new();
        if self.project_id != actual.project_id {
            out.push(Difference::ProjectId { expected: self.project_id, actual: actual.project_id });
        }
        diff_items(&mut out, RecordKind::Servo, &self.servos, &actual.servos, |s| i64::from(s.servo_id));
        diff_items(&mut out, RecordKind::Action, &self.actions, &actual.actions, |a| i64::from(a.action_id));
        diff_items(&mut out, RecordKind::Macro, &self.macros, &actual.macros, |m| i64::from(m.macro_id));
        diff_items(&mut out, RecordKind::Table, &self.tables, &actual.tables, |t| i64::from(t.table_id));
        if self.active_table != actual.active_table {
            out.push(Difference::ActiveTable { expected: self.active_table, actual: actual.active_table });
        }
        out
    }
}

/// A project's joystick tables as the board stores them (no macro: 0).
fn table_records(project: &ServoProject) -> Result<Vec<JoystickTableRecord>, ImageError> {
    let mut tables = Vec::with_capacity(project.joystick_tables.len());
    for table in &project.joystick_tables {
        let mut buttons = Vec::with_capacity(table.buttons.len());
        for button in &table.buttons {
            buttons.push(ButtonRecord {
                button_id: button.id,
                caption: caption(
                    || format!("joystick table {} button 0x{:08x} {:?}", table.id, button.id, button.caption),
                    &button.caption,
                )?,
                press_macro: button.press_macro.unwrap_or(0),
                long_press_macro: button.long_press_macro.unwrap_or(0),
                up_macro: button.release_macro.unwrap_or(0),
                uninterruptible: button.uninterruptible,
            });
        }
        tables.push(JoystickTableRecord {
            table_id: table.id,
            caption: caption(|| format!("joystick table {} {:?}", table.id, table.caption), &table.caption)?,
            buttons,
        });
    }
    Ok(tables)
}

/// Which kind of stored record a difference is about: the project's own item kinds.
pub use crate::project::ItemKind as RecordKind;

/// One difference between a project and a board, as data; `Display` gives English.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Difference {
    /// The project ids differ.
    ProjectId {
        /// The project's.
        expected: i32,
        /// The board's.
        actual: i32,
    },
    /// In the project, not on the board.
    Missing {
        /// Of what.
        kind: RecordKind,
        /// Its id.
        id: i64,
    },
    /// On both, with different contents.
    Differs {
        /// Of what.
        kind: RecordKind,
        /// Its id.
        id: i64,
    },
    /// On the board, not in the project.
    Extra {
        /// Of what.
        kind: RecordKind,
        /// Its id.
        id: i64,
    },
    /// The same records in another order.
    Order {
        /// Of what.
        kind: RecordKind,
    },
    /// The active tables differ.
    ActiveTable {
        /// The project's.
        expected: i32,
        /// The board's.
        actual: i32,
    },
}

impl std::fmt::Display for Difference {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::ProjectId { expected, actual } => write!(f, "project id: expected {expected}, board has {actual}"),
            Self::Missing { kind, id } => write!(f, "{} {id}: missing on the board", kind.word()),
            Self::Differs { kind, id } => write!(f, "{} {id}: differs on the board", kind.word()),
            Self::Extra { kind, id } => write!(f, "{} {id}: on the board but not in the project", kind.word()),
            Self::Order { kind } => write!(f, "{}s: stored in a different order", kind.word()),
            Self::ActiveTable { expected, actual } => {
                write!(f, "active table: expected {expected}, board has {actual}")
            }
        }
    }
}

fn diff_items<T: PartialEq>(
    out: &mut Vec<Difference>,
    kind: RecordKind,
    expected: &[T],
    actual: &[T],
    id: impl Fn(&T) -> i64,
) {
    let before = out.len();
    for item in expected {
        match actual.iter().find(|other| id(other) == id(item)) {
            None => out.push(Difference::Missing { kind, id: id(item) }),
            Some(other) if other != item => out.push(Difference::Differs { kind, id: id(item) }),
            Some(_) => {}
        }
    }
    for item in actual {
        if !expected.iter().any(|other| id(other) == id(item)) {
            out.push(Difference::Extra { kind, id: id(item) });
        }
    }
    let same_ids = expected.len() == actual.len() && expected.iter().zip(actual).all(|(a, b)| id(a) == id(b));
    if !same_ids && out.len() == before {
        out.push(Difference::Order { kind });
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::project::Command;

    #[test]
    fn a_stored_total_is_written_back_and_an_edited_command_gets_the_derived_one() {
        let action = Action { id: 1, caption: "a".into(), steps: vec![Step::new(1, 0, 50)] };
        let kept = Command { stored_total_ms: Some(777), ..Command::once(Run::Action { action_id: 1 }) };
        let derived = Command::once(Run::Action { action_id: 1 });
        let dangling = Command::once(Run::Macro { macro_id: 999 });
        let project = ServoProject {
            actions: vec![action],
            macros: vec![Macro { id: 2, caption: "m".into(), commands: vec![kept, derived, dangling] }],
            ..ServoProject::default()
        };
        let image = ServoImage::from_project(&project).unwrap();
        let totals: Vec<i32> = image.macros[0].commands.iter().map(|c| c.total_interval_ms).collect();
        assert_eq!(totals, [777, 500, 0]);
        // Back to a project: every total the board holds is kept.
        let back = image.to_project();
        let stored: Vec<Option<i32>> = back.macros[0].commands.iter().map(|c| c.stored_total_ms).collect();
        assert_eq!(stored, [Some(777), Some(500), Some(0)]);
        assert_eq!(ServoImage::from_project(&back).unwrap(), image);
    }

    #[test]
    fn a_caption_over_32_bytes_cannot_be_written_at_all() {
        let project = ServoProject {
            actions: vec![Action { id: 4, caption: "揮手揮手揮手揮手揮手揮手".into(), steps: Vec::new() }],
            ..ServoProject::default()
        };
        let error = ServoImage::from_project(&project).unwrap_err();
        assert_eq!(
            error,
            ImageError::CaptionTooLong { item: "action 4 \"揮手揮手揮手揮手揮手揮手\"".into(), bytes: 36 }
        );
        assert!(error.to_string().contains("Shorten it"), "{error}");
    }
}
