//! A board's stored contents as protocol records, and the conversion to and
//! from a project. Both the upload (project → board) and the backup (board →
//! project) go through here, and so does the emulated board's storage.

use crate::project::{
    Action, BoardKind, Button, Command, JoystickTable, Macro, Project, Run, Servo, Step, Timing, TimingError,
};
use crate::protocol::board::{
    ActionRecord, ButtonRecord, CommandType, EncodeError, JoystickTableRecord, MacroCommandRecord, MacroRecord,
    Message, ServoMove, ServoParameter,
};

/// Everything a servo board stores, in the order the board lists it.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct BoardImage {
    /// `projectID` (0 = none).
    pub project_id: i32,
    /// Stored servo parameters (30101).
    pub servos: Vec<ServoParameter>,
    /// Stored actions.
    pub actions: Vec<ActionRecord>,
    /// Stored macros, with `totalInterval` filled in.
    pub macros: Vec<MacroRecord>,
    /// Stored joystick tables.
    pub tables: Vec<JoystickTableRecord>,
    /// The active table (0 = none).
    pub active_table: i32,
}

/// A project cannot be turned into board records.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ImageError {
    /// A macro's run time cannot be computed (dangling reference or cycle).
    #[error("macro {macro_id}, command {command}: {error}")]
    Timing {
        /// The macro.
        macro_id: i32,
        /// The command, from 1.
        command: usize,
        /// Why.
        error: TimingError,
    },
    /// A command's run time does not fit the board's 32-bit field.
    #[error("macro {macro_id}, command {command}: runs for {total_ms} ms, more than the board can count")]
    TooLong {
        /// The macro.
        macro_id: i32,
        /// The command, from 1.
        command: usize,
        /// The run time.
        total_ms: i64,
    },
}

impl BoardImage {
    /// The records a project becomes on the board.
    pub fn from_project(project: &Project) -> Result<Self, ImageError> {
        let timing = Timing::new(project);
        let servos = project
            .servos
            .iter()
            .map(|servo| ServoParameter {
                servo_id: servo.id,
                adjusted_degree: servo.calibration_offset_deg,
                caption: servo.caption.clone(),
            })
            .collect();
        let actions = project
            .actions
            .iter()
            .map(|action| ActionRecord {
                action_id: action.id,
                caption: action.caption.clone(),
                steps: action
                    .steps
                    .iter()
                    .map(|step| ServoMove {
                        servo_id: step.servo_id,
                        degree: step.degree,
                        interval_10ms: step.interval_10ms,
                    })
                    .collect(),
            })
            .collect();
        let mut macros = Vec::with_capacity(project.macros.len());
        for item in &project.macros {
            let mut commands = Vec::with_capacity(item.commands.len());
            for (index, command) in item.commands.iter().enumerate() {
                let at = index + 1;
                let total_ms = timing.command_total_ms(command).map_err(|error| ImageError::Timing {
                    macro_id: item.id,
                    command: at,
                    error,
                })?;
                let total_interval_ms = i32::try_from(total_ms).map_err(|_| ImageError::TooLong {
                    macro_id: item.id,
                    command: at,
                    total_ms,
                })?;
                let (command_type, command_id) = match command.run {
                    Run::Action { action_id } => (CommandType::RunAction, action_id),
                    Run::Delay { delay_ms } => (CommandType::Delay, delay_ms),
                    Run::Macro { macro_id } => (CommandType::RunMacro, macro_id),
                };
                commands.push(MacroCommandRecord {
                    command_id,
                    command_type,
                    ratio_percent: command.ratio_percent,
                    loop_count: command.loop_count,
                    total_interval_ms,
                });
            }
            macros.push(MacroRecord { macro_id: item.id, caption: item.caption.clone(), commands });
        }
        let tables = project
            .joystick_tables
            .iter()
            .map(|table| JoystickTableRecord {
                table_id: table.id,
                caption: table.caption.clone(),
                buttons: table
                    .buttons
                    .iter()
                    .map(|button| ButtonRecord {
                        button_id: button.id,
                        caption: button.caption.clone(),
                        press_macro: button.press_macro.unwrap_or(0),
                        long_press_macro: button.long_press_macro.unwrap_or(0),
                        up_macro: button.release_macro.unwrap_or(0),
                        uninterruptible: button.uninterruptible,
                    })
                    .collect(),
            })
            .collect();
        Ok(Self {
            project_id: project.project_id,
            servos,
            actions,
            macros,
            tables,
            active_table: project.active_table.unwrap_or(0),
        })
    }

    /// The project these records describe. The board does not store the
    /// client-side limits: each servo gets ±180°, widened to cover its steps,
    /// and home 0. A servo that steps name but the board has no parameters for
    /// is added without a caption, so that the project validates.
    pub fn to_project(&self) -> Project {
        let mut servos: Vec<Servo> = self
            .servos
            .iter()
            .map(|parameter| Servo {
                calibration_offset_deg: parameter.adjusted_degree,
                ..Servo::new(parameter.servo_id, parameter.caption.clone())
            })
            .collect();
        for step in self.actions.iter().flat_map(|action| &action.steps) {
            if !servos.iter().any(|servo| servo.id == step.servo_id) {
                servos.push(Servo::new(step.servo_id, ""));
            }
            if let Some(servo) = servos.iter_mut().find(|servo| servo.id == step.servo_id) {
                servo.min_deg = servo.min_deg.min(step.degree);
                servo.max_deg = servo.max_deg.max(step.degree);
            }
        }
        let none_if_zero = |id: i32| (id != 0).then_some(id);
        Project {
            board: BoardKind::ServoBoard,
            project_id: self.project_id,
            servos,
            actions: self
                .actions
                .iter()
                .map(|record| Action {
                    id: record.action_id,
                    caption: record.caption.clone(),
                    steps: record
                        .steps
                        .iter()
                        .map(|step| Step {
                            servo_id: step.servo_id,
                            degree: step.degree,
                            interval_10ms: step.interval_10ms,
                        })
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

    /// The bytes these records occupy in board memory, as the emulated board
    /// counts them: the content of every add request, plus 4 bytes each for
    /// the project id and the active table id.
    pub fn footprint_bytes(&self) -> Result<usize, EncodeError> {
        let mut total = 8;
        if !self.servos.is_empty() {
            total += Message::AddServoParameterRequest { servos: self.servos.clone() }.encode_content()?.len();
        }
        for action in &self.actions {
            total += Message::AddActionRequest(action.clone()).encode_content()?.len();
        }
        for record in &self.macros {
            total += Message::AddMacroRequest(record.clone()).encode_content()?.len();
        }
        for table in &self.tables {
            total += Message::AddJoystickTableRequest(table.clone()).encode_content()?.len();
        }
        Ok(total)
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
