//! Validation: every problem of a project, each with where it is.

use std::collections::{HashMap, HashSet};
use std::fmt;

use super::model::{Command, Project, Run};
use super::timing::Timing;
use crate::protocol::board::{ALL_SERVOS, ButtonRecord, MAX_CONTENT_LEN, MacroCommandRecord, STR32_LEN};

/// How serious a problem is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Severity {
    /// Worth a look; the project can still be uploaded.
    Warning,
    /// The project cannot be uploaded until this is fixed.
    Error,
}

/// Where in a project a problem is. Indices are 1-based, as a person counts.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Location {
    /// The project as a whole.
    Project,
    /// A servo.
    Servo {
        /// Its id.
        servo_id: u8,
        /// Its caption.
        caption: String,
    },
    /// An action.
    Action {
        /// Its id.
        action_id: i32,
        /// Its caption.
        caption: String,
    },
    /// One step of an action.
    Step {
        /// The action's id.
        action_id: i32,
        /// The action's caption.
        caption: String,
        /// The step's position, from 1.
        step: usize,
    },
    /// A macro.
    Macro {
        /// Its id.
        macro_id: i32,
        /// Its caption.
        caption: String,
    },
    /// One command of a macro.
    Command {
        /// The macro's id.
        macro_id: i32,
        /// The macro's caption.
        caption: String,
        /// The command's position, from 1.
        command: usize,
    },
    /// A joystick table.
    Table {
        /// Its id.
        table_id: i32,
        /// Its caption.
        caption: String,
    },
    /// A button of a joystick table.
    Button {
        /// The table's id.
        table_id: i32,
        /// The table's caption.
        table_caption: String,
        /// The button's id.
        button_id: u32,
        /// The button's caption.
        caption: String,
    },
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Project => write!(f, "project"),
            Self::Servo { servo_id, caption } => write!(f, "servo {servo_id} {caption:?}"),
            Self::Action { action_id, caption } => write!(f, "action {action_id} {caption:?}"),
            Self::Step { action_id, caption, step } => write!(f, "action {action_id} {caption:?}, step {step}"),
            Self::Macro { macro_id, caption } => write!(f, "macro {macro_id} {caption:?}"),
            Self::Command { macro_id, caption, command } => {
                write!(f, "macro {macro_id} {caption:?}, command {command}")
            }
            Self::Table { table_id, caption } => write!(f, "joystick table {table_id} {caption:?}"),
            Self::Button { table_id, table_caption, button_id, caption } => {
                write!(f, "joystick table {table_id} {table_caption:?}, button 0x{button_id:08x} {caption:?}")
            }
        }
    }
}

/// One problem found in a project.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Problem {
    /// How serious it is.
    pub severity: Severity,
    /// Where it is.
    pub location: Location,
    /// What is wrong, in words.
    pub message: String,
}

impl fmt::Display for Problem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let severity = match self.severity {
            Severity::Error => "error",
            Severity::Warning => "warning",
        };
        write!(f, "{severity}: {}: {}", self.location, self.message)
    }
}

/// Whether any problem is an error.
pub fn has_errors(problems: &[Problem]) -> bool {
    problems.iter().any(|problem| problem.severity == Severity::Error)
}

/// Every problem of `project`, in document order.
pub fn validate(project: &Project) -> Vec<Problem> {
    let mut check = Checker { problems: Vec::new() };
    check.servos(project);
    check.actions(project);
    check.macros(project);
    check.tables(project);
    check.problems
}

/// Largest number of entries of `entry_len` bytes that fits one frame after a
/// 38-byte record header (id, caption, count).
fn max_entries(entry_len: usize) -> usize {
    (MAX_CONTENT_LEN - 38) / entry_len
}

struct Checker {
    problems: Vec<Problem>,
}

impl Checker {
    fn error(&mut self, location: &Location, message: String) {
        self.problems.push(Problem { severity: Severity::Error, location: location.clone(), message });
    }

    fn warning(&mut self, location: &Location, message: String) {
        self.problems.push(Problem { severity: Severity::Warning, location: location.clone(), message });
    }

    fn caption(&mut self, location: &Location, caption: &str) {
        if caption.len() > STR32_LEN {
            self.error(
                location,
                format!("caption is {} UTF-8 bytes; the board stores at most {STR32_LEN}", caption.len()),
            );
        }
    }

    /// Ids must be 1..=i32::MAX: the board answers id 0 to mean "failure".
    fn positive_id(&mut self, location: &Location, kind: &str, id: i32) {
        if id <= 0 {
            self.error(location, format!("{kind} id must be 1 or more (0 means \"none\" on the board), not {id}"));
        }
    }

    fn duplicate<T: Eq + std::hash::Hash + fmt::Display>(
        &mut self,
        seen: &mut HashSet<T>,
        location: &Location,
        kind: &str,
        id: T,
    ) {
        let text = id.to_string();
        if !seen.insert(id) {
            self.error(location, format!("duplicate {kind} id {text}"));
        }
    }

    fn servos(&mut self, project: &Project) {
        let mut seen = HashSet::new();
        for servo in &project.servos {
            let at = Location::Servo { servo_id: servo.id, caption: servo.caption.clone() };
            self.duplicate(&mut seen, &at, "servo", servo.id);
            self.caption(&at, &servo.caption);
            if servo.id == ALL_SERVOS {
                self.error(&at, "servo id 255 is reserved (it addresses all servos); use 0..=254".into());
            }
            if servo.min_deg > servo.max_deg {
                self.error(&at, format!("min {}° is above max {}°", servo.min_deg, servo.max_deg));
            } else if servo.home_deg < servo.min_deg || servo.home_deg > servo.max_deg {
                self.error(
                    &at,
                    format!("home {}° is outside the limits {}°..{}°", servo.home_deg, servo.min_deg, servo.max_deg),
                );
            }
        }
    }

    fn actions(&mut self, project: &Project) {
        let mut seen = HashSet::new();
        for action in &project.actions {
            let at = Location::Action { action_id: action.id, caption: action.caption.clone() };
            self.duplicate(&mut seen, &at, "action", action.id);
            self.positive_id(&at, "action", action.id);
            self.caption(&at, &action.caption);
            if action.steps.is_empty() {
                self.warning(&at, "has no steps: running it does nothing".into());
            }
            let mut servos_in_action = HashSet::new();
            for (index, step) in action.steps.iter().enumerate() {
                let at = Location::Step { action_id: action.id, caption: action.caption.clone(), step: index + 1 };
                if !servos_in_action.insert(step.servo_id) {
                    self.error(&at, format!("servo {} already has a step in this action", step.servo_id));
                }
                if step.interval_10ms < 0 {
                    self.error(&at, format!("interval {} × 10 ms is negative", step.interval_10ms));
                }
                match project.servo(step.servo_id) {
                    None => self.error(&at, format!("servo {} does not exist", step.servo_id)),
                    Some(servo) if servo.clamp(step.degree) != step.degree => self.error(
                        &at,
                        format!(
                            "{}° is outside servo {}'s limits {}°..{}°",
                            step.degree, servo.id, servo.min_deg, servo.max_deg
                        ),
                    ),
                    Some(_) => {}
                }
            }
        }
    }

    fn macros(&mut self, project: &Project) {
        let timing = Timing::new(project);
        let mut seen = HashSet::new();
        for item in &project.macros {
            let at = Location::Macro { macro_id: item.id, caption: item.caption.clone() };
            self.duplicate(&mut seen, &at, "macro", item.id);
            self.positive_id(&at, "macro", item.id);
            self.caption(&at, &item.caption);
            if item.commands.is_empty() {
                self.warning(&at, "has no commands: running it does nothing".into());
            }
            let max = max_entries(MacroCommandRecord::WIRE_LEN);
            if item.commands.len() > max {
                self.error(&at, format!("has {} commands; one board frame holds at most {max}", item.commands.len()));
            }
            for (index, command) in item.commands.iter().enumerate() {
                let at = Location::Command { macro_id: item.id, caption: item.caption.clone(), command: index + 1 };
                self.command(project, &timing, &at, command);
            }
        }
        self.cycles(project);
    }

    fn command(&mut self, project: &Project, timing: &Timing<'_>, at: &Location, command: &Command) {
        if !(1..=100).contains(&command.ratio_percent) {
            self.error(at, format!("ratio {} % is outside 1..=100", command.ratio_percent));
        }
        if command.loop_count < 1 {
            self.error(at, format!("loop count {} must be 1 or more", command.loop_count));
        }
        match command.run {
            Run::Action { action_id } if project.action(action_id).is_none() => {
                self.error(at, format!("action {action_id} does not exist"));
            }
            Run::Macro { macro_id } if project.macro_by_id(macro_id).is_none() => {
                self.error(at, format!("macro {macro_id} does not exist"));
            }
            Run::Delay { delay_ms } if delay_ms < 0 => {
                self.error(at, format!("delay {delay_ms} ms is negative"));
            }
            _ => {}
        }
        if let Ok(total_ms) = timing.command_total_ms(command)
            && i32::try_from(total_ms).is_err()
        {
            self.error(at, format!("runs for {total_ms} ms, more than the board can count ({} ms)", i32::MAX));
        }
    }

    /// Reports each macro cycle once, at the command that closes it.
    fn cycles(&mut self, project: &Project) {
        let index: HashMap<i32, usize> =
            project.macros.iter().enumerate().rev().map(|(position, item)| (item.id, position)).collect();
        // 0 = not visited, 1 = on the current path, 2 = done.
        let mut state = vec![0u8; project.macros.len()];
        let mut path = Vec::new();
        for start in 0..project.macros.len() {
            self.visit(project, &index, start, &mut state, &mut path);
        }
    }

    fn visit(
        &mut self,
        project: &Project,
        index: &HashMap<i32, usize>,
        position: usize,
        state: &mut [u8],
        path: &mut Vec<usize>,
    ) {
        if state[position] != 0 {
            return;
        }
        state[position] = 1;
        path.push(position);
        let item = &project.macros[position];
        for (command_index, command) in item.commands.iter().enumerate() {
            let Run::Macro { macro_id } = command.run else {
                continue;
            };
            let Some(&next) = index.get(&macro_id) else {
                continue;
            };
            if state[next] == 1 {
                let from = path.iter().position(|&p| p == next).unwrap_or(0);
                let mut names: Vec<String> = path[from..].iter().map(|&p| project.macros[p].id.to_string()).collect();
                names.push(macro_id.to_string());
                let at =
                    Location::Command { macro_id: item.id, caption: item.caption.clone(), command: command_index + 1 };
                self.error(&at, format!("macro cycle {}: a macro must not reach itself", names.join(" → ")));
            } else {
                self.visit(project, index, next, state, path);
            }
        }
        path.pop();
        state[position] = 2;
    }

    fn tables(&mut self, project: &Project) {
        let mut seen = HashSet::new();
        for table in &project.joystick_tables {
            let at = Location::Table { table_id: table.id, caption: table.caption.clone() };
            self.duplicate(&mut seen, &at, "joystick table", table.id);
            self.positive_id(&at, "joystick table", table.id);
            self.caption(&at, &table.caption);
            let max = max_entries(ButtonRecord::WIRE_LEN);
            if table.buttons.len() > max {
                self.error(&at, format!("has {} buttons; one board frame holds at most {max}", table.buttons.len()));
            }
            let mut buttons = HashSet::new();
            for button in &table.buttons {
                let at = Location::Button {
                    table_id: table.id,
                    table_caption: table.caption.clone(),
                    button_id: button.id,
                    caption: button.caption.clone(),
                };
                if !buttons.insert(button.id) {
                    self.error(&at, format!("duplicate button id 0x{:08x} in this table", button.id));
                }
                self.caption(&at, &button.caption);
                let bindings = [
                    ("press", button.press_macro),
                    ("long-press", button.long_press_macro),
                    ("release", button.release_macro),
                ];
                for (event, macro_id) in bindings {
                    if let Some(macro_id) = macro_id
                        && project.macro_by_id(macro_id).is_none()
                    {
                        self.error(&at, format!("{event} macro {macro_id} does not exist"));
                    }
                }
                if bindings.iter().all(|(_, macro_id)| macro_id.is_none()) {
                    self.warning(&at, "runs no macro".into());
                }
            }
        }
        if let Some(table_id) = project.active_table
            && project.table(table_id).is_none()
        {
            self.error(&Location::Project, format!("active joystick table {table_id} does not exist"));
        }
    }
}
