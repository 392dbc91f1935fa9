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

/// What kind of item an id belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ItemKind {
    /// A servo.
    Servo,
    /// An action.
    Action,
    /// A macro.
    Macro,
    /// A joystick table.
    Table,
}

impl ItemKind {
    /// The English word.
    pub fn word(self) -> &'static str {
        match self {
            Self::Servo => "servo",
            Self::Action => "action",
            Self::Macro => "macro",
            Self::Table => "joystick table",
        }
    }
}

/// Which button event a binding is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ButtonSlot {
    /// The press macro.
    Press,
    /// The long-press macro.
    LongPress,
    /// The release macro.
    Release,
}

/// What is wrong, as data, so that an interface can say it in its own language.
/// `Display` gives the English text.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum ProblemKind {
    /// A caption longer than the board's 32 bytes.
    CaptionTooLong {
        /// Its UTF-8 length.
        bytes: usize,
    },
    /// An id below 1 (0 is the board's "none").
    IdNotPositive {
        /// Of what.
        kind: ItemKind,
        /// The id.
        id: i32,
    },
    /// An id used twice.
    DuplicateId {
        /// Of what.
        kind: ItemKind,
        /// The id, as text.
        id: String,
    },
    /// Servo id 255, which addresses all servos.
    ReservedServoId,
    /// A servo's min above its max.
    MinAboveMax {
        /// Min, °.
        min_deg: i16,
        /// Max, °.
        max_deg: i16,
    },
    /// A servo's home outside its limits.
    HomeOutsideLimits {
        /// Home, °.
        home_deg: i16,
        /// Min, °.
        min_deg: i16,
        /// Max, °.
        max_deg: i16,
    },
    /// An action without steps.
    NoSteps,
    /// A servo with two steps in one action.
    ServoTwiceInAction {
        /// The servo.
        servo_id: u8,
    },
    /// A negative step interval.
    NegativeInterval {
        /// The interval, × 10 ms.
        interval_10ms: i16,
    },
    /// A step naming a servo the project lacks.
    MissingServo {
        /// The servo.
        servo_id: u8,
    },
    /// A step angle outside its servo's limits.
    StepOutsideLimits {
        /// The angle, °.
        degree: i16,
        /// The servo.
        servo_id: u8,
        /// Min, °.
        min_deg: i16,
        /// Max, °.
        max_deg: i16,
    },
    /// A macro without commands.
    NoCommands,
    /// More commands than one board frame holds.
    TooManyCommands {
        /// How many.
        count: usize,
        /// The most a frame holds.
        max: usize,
    },
    /// A ratio outside 1..=100.
    RatioOutOfRange {
        /// The ratio, %.
        ratio_percent: u8,
    },
    /// A loop count below 1.
    LoopBelowOne {
        /// The loop count.
        loop_count: i16,
    },
    /// A command naming a missing action.
    MissingAction {
        /// The action.
        action_id: i32,
    },
    /// A command naming a missing macro.
    MissingMacro {
        /// The macro.
        macro_id: i32,
    },
    /// A negative delay.
    NegativeDelay {
        /// The delay, ms.
        delay_ms: i32,
    },
    /// A run time the board's 32-bit field cannot hold.
    TotalTooLong {
        /// The run time, ms.
        total_ms: i64,
    },
    /// A macro that reaches itself.
    MacroCycle {
        /// The macro ids along the cycle, first repeated at the end.
        path: Vec<i32>,
    },
    /// More buttons than one board frame holds.
    TooManyButtons {
        /// How many.
        count: usize,
        /// The most a frame holds.
        max: usize,
    },
    /// A button id used twice in one table.
    DuplicateButton {
        /// The button.
        button_id: u32,
    },
    /// A button bound to a missing macro.
    MissingButtonMacro {
        /// Which binding.
        slot: ButtonSlot,
        /// The macro.
        macro_id: i32,
    },
    /// A button that runs no macro.
    ButtonRunsNothing,
    /// The active table does not exist.
    MissingActiveTable {
        /// The table.
        table_id: i32,
    },
}

impl fmt::Display for ProblemKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::CaptionTooLong { bytes } => {
                write!(f, "caption is {bytes} UTF-8 bytes; the board stores at most {STR32_LEN}")
            }
            Self::IdNotPositive { kind, id } => {
                write!(f, "{} id must be 1 or more (0 means \"none\" on the board), not {id}", kind.word())
            }
            Self::DuplicateId { kind, id } => write!(f, "duplicate {} id {id}", kind.word()),
            Self::ReservedServoId => write!(f, "servo id 255 is reserved (it addresses all servos); use 0..=254"),
            Self::MinAboveMax { min_deg, max_deg } => write!(f, "min {min_deg}° is above max {max_deg}°"),
            Self::HomeOutsideLimits { home_deg, min_deg, max_deg } => {
                write!(f, "home {home_deg}° is outside the limits {min_deg}°..{max_deg}°")
            }
            Self::NoSteps => write!(f, "has no steps: running it does nothing"),
            Self::ServoTwiceInAction { servo_id } => write!(f, "servo {servo_id} already has a step in this action"),
            Self::NegativeInterval { interval_10ms } => write!(f, "interval {interval_10ms} × 10 ms is negative"),
            Self::MissingServo { servo_id } => write!(f, "servo {servo_id} does not exist"),
            Self::StepOutsideLimits { degree, servo_id, min_deg, max_deg } => {
                write!(f, "{degree}° is outside servo {servo_id}'s limits {min_deg}°..{max_deg}°")
            }
            Self::NoCommands => write!(f, "has no commands: running it does nothing"),
            Self::TooManyCommands { count, max } => {
                write!(f, "has {count} commands; one board frame holds at most {max}")
            }
            Self::RatioOutOfRange { ratio_percent } => write!(f, "ratio {ratio_percent} % is outside 1..=100"),
            Self::LoopBelowOne { loop_count } => write!(f, "loop count {loop_count} must be 1 or more"),
            Self::MissingAction { action_id } => write!(f, "action {action_id} does not exist"),
            Self::MissingMacro { macro_id } => write!(f, "macro {macro_id} does not exist"),
            Self::NegativeDelay { delay_ms } => write!(f, "delay {delay_ms} ms is negative"),
            Self::TotalTooLong { total_ms } => {
                write!(f, "runs for {total_ms} ms, more than the board can count ({} ms)", i32::MAX)
            }
            Self::MacroCycle { path } => {
                let names: Vec<String> = path.iter().map(ToString::to_string).collect();
                write!(f, "macro cycle {}: a macro must not reach itself", names.join(" → "))
            }
            Self::TooManyButtons { count, max } => {
                write!(f, "has {count} buttons; one board frame holds at most {max}")
            }
            Self::DuplicateButton { button_id } => write!(f, "duplicate button id 0x{button_id:08x} in this table"),
            Self::MissingButtonMacro { slot, macro_id } => {
                let event = match slot {
                    ButtonSlot::Press => "press",
                    ButtonSlot::LongPress => "long-press",
                    ButtonSlot::Release => "release",
                };
                write!(f, "{event} macro {macro_id} does not exist")
            }
            Self::ButtonRunsNothing => write!(f, "runs no macro"),
            Self::MissingActiveTable { table_id } => write!(f, "active joystick table {table_id} does not exist"),
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
    /// What is wrong.
    pub kind: ProblemKind,
}

impl fmt::Display for Problem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let severity = match self.severity {
            Severity::Error => "error",
            Severity::Warning => "warning",
        };
        write!(f, "{severity}: {}: {}", self.location, self.kind)
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
    fn error(&mut self, location: &Location, kind: ProblemKind) {
        self.problems.push(Problem { severity: Severity::Error, location: location.clone(), kind });
    }

    fn warning(&mut self, location: &Location, kind: ProblemKind) {
        self.problems.push(Problem { severity: Severity::Warning, location: location.clone(), kind });
    }

    fn caption(&mut self, location: &Location, caption: &str) {
        if caption.len() > STR32_LEN {
            self.error(location, ProblemKind::CaptionTooLong { bytes: caption.len() });
        }
    }

    /// Ids must be 1..=i32::MAX: the board answers id 0 to mean "failure".
    fn positive_id(&mut self, location: &Location, kind: ItemKind, id: i32) {
        if id <= 0 {
            self.error(location, ProblemKind::IdNotPositive { kind, id });
        }
    }

    fn duplicate<T: Eq + std::hash::Hash + fmt::Display>(
        &mut self,
        seen: &mut HashSet<T>,
        location: &Location,
        kind: ItemKind,
        id: T,
    ) {
        let text = id.to_string();
        if !seen.insert(id) {
            self.error(location, ProblemKind::DuplicateId { kind, id: text });
        }
    }

    fn servos(&mut self, project: &Project) {
        let mut seen = HashSet::new();
        for servo in &project.servos {
            let at = Location::Servo { servo_id: servo.id, caption: servo.caption.clone() };
            self.duplicate(&mut seen, &at, ItemKind::Servo, servo.id);
            self.caption(&at, &servo.caption);
            if servo.id == ALL_SERVOS {
                self.error(&at, ProblemKind::ReservedServoId);
            }
            if servo.min_deg > servo.max_deg {
                self.error(&at, ProblemKind::MinAboveMax { min_deg: servo.min_deg, max_deg: servo.max_deg });
            } else if servo.home_deg < servo.min_deg || servo.home_deg > servo.max_deg {
                self.error(
                    &at,
                    ProblemKind::HomeOutsideLimits {
                        home_deg: servo.home_deg,
                        min_deg: servo.min_deg,
                        max_deg: servo.max_deg,
                    },
                );
            }
        }
    }

    fn actions(&mut self, project: &Project) {
        let mut seen = HashSet::new();
        for action in &project.actions {
            let at = Location::Action { action_id: action.id, caption: action.caption.clone() };
            self.duplicate(&mut seen, &at, ItemKind::Action, action.id);
            self.positive_id(&at, ItemKind::Action, action.id);
            self.caption(&at, &action.caption);
            if action.steps.is_empty() {
                self.warning(&at, ProblemKind::NoSteps);
            }
            let mut servos_in_action = HashSet::new();
            for (index, step) in action.steps.iter().enumerate() {
                let at = Location::Step { action_id: action.id, caption: action.caption.clone(), step: index + 1 };
                if !servos_in_action.insert(step.servo_id) {
                    self.error(&at, ProblemKind::ServoTwiceInAction { servo_id: step.servo_id });
                }
                if step.interval_10ms < 0 {
                    self.error(&at, ProblemKind::NegativeInterval { interval_10ms: step.interval_10ms });
                }
                match project.servo(step.servo_id) {
                    None => self.error(&at, ProblemKind::MissingServo { servo_id: step.servo_id }),
                    Some(servo) if servo.clamp(step.degree) != step.degree => self.error(
                        &at,
                        ProblemKind::StepOutsideLimits {
                            degree: step.degree,
                            servo_id: servo.id,
                            min_deg: servo.min_deg,
                            max_deg: servo.max_deg,
                        },
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
            self.duplicate(&mut seen, &at, ItemKind::Macro, item.id);
            self.positive_id(&at, ItemKind::Macro, item.id);
            self.caption(&at, &item.caption);
            if item.commands.is_empty() {
                self.warning(&at, ProblemKind::NoCommands);
            }
            let max = max_entries(MacroCommandRecord::WIRE_LEN);
            if item.commands.len() > max {
                self.error(&at, ProblemKind::TooManyCommands { count: item.commands.len(), max });
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
            self.error(at, ProblemKind::RatioOutOfRange { ratio_percent: command.ratio_percent });
        }
        if command.loop_count < 1 {
            self.error(at, ProblemKind::LoopBelowOne { loop_count: command.loop_count });
        }
        match command.run {
            Run::Action { action_id } if project.action(action_id).is_none() => {
                self.error(at, ProblemKind::MissingAction { action_id });
            }
            Run::Macro { macro_id } if project.macro_by_id(macro_id).is_none() => {
                self.error(at, ProblemKind::MissingMacro { macro_id });
            }
            Run::Delay { delay_ms } if delay_ms < 0 => {
                self.error(at, ProblemKind::NegativeDelay { delay_ms });
            }
            _ => {}
        }
        if let Ok(total_ms) = timing.command_total_ms(command)
            && i32::try_from(total_ms).is_err()
        {
            self.error(at, ProblemKind::TotalTooLong { total_ms });
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
                let mut cycle: Vec<i32> = path[from..].iter().map(|&p| project.macros[p].id).collect();
                cycle.push(macro_id);
                let at =
                    Location::Command { macro_id: item.id, caption: item.caption.clone(), command: command_index + 1 };
                self.error(&at, ProblemKind::MacroCycle { path: cycle });
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
            self.duplicate(&mut seen, &at, ItemKind::Table, table.id);
            self.positive_id(&at, ItemKind::Table, table.id);
            self.caption(&at, &table.caption);
            let max = max_entries(ButtonRecord::WIRE_LEN);
            if table.buttons.len() > max {
                self.error(&at, ProblemKind::TooManyButtons { count: table.buttons.len(), max });
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
                    self.error(&at, ProblemKind::DuplicateButton { button_id: button.id });
                }
                self.caption(&at, &button.caption);
                let bindings = [
                    (ButtonSlot::Press, button.press_macro),
                    (ButtonSlot::LongPress, button.long_press_macro),
                    (ButtonSlot::Release, button.release_macro),
                ];
                for (slot, macro_id) in bindings {
                    if let Some(macro_id) = macro_id
                        && project.macro_by_id(macro_id).is_none()
                    {
                        self.error(&at, ProblemKind::MissingButtonMacro { slot, macro_id });
                    }
                }
                if bindings.iter().all(|(_, macro_id)| macro_id.is_none()) {
                    self.warning(&at, ProblemKind::ButtonRunsNothing);
                }
            }
        }
        if let Some(table_id) = project.active_table
            && project.table(table_id).is_none()
        {
            self.error(&Location::Project, ProblemKind::MissingActiveTable { table_id });
        }
    }
}
