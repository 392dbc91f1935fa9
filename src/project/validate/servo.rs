//! Validation of the servo section: every problem, each with where it is.

use std::collections::{HashMap, HashSet};
use std::fmt;

use super::super::servo::{Command, Run, ServoProject};
use super::super::timing::Timing;
use super::{ButtonSlot, ItemKind, Location, Problem, ProblemKind, Problems, Severity};
use crate::protocol::servo::{ALL_SERVOS, ButtonRecord, MAX_CONTENT_LEN, MacroCommandRecord, STR32_LEN};

/// Every problem of a servo section, in document order.
pub fn validate_servo(project: &ServoProject) -> Problems {
    let mut check = Checker { problems: Problems::new() };
    check.servos(project);
    check.rig(project);
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
    problems: Problems,
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

    fn servos(&mut self, project: &ServoProject) {
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

    /// Every rigged servo's parent is a rigged servo, and no ring of parents.
    fn rig(&mut self, project: &ServoProject) {
        let parents: HashMap<u8, Option<u8>> =
            project.servos.iter().filter_map(|servo| servo.rig.map(|rig| (servo.id, rig.parent))).collect();
        let mut reported = HashSet::new();
        for servo in &project.servos {
            let Some(rig) = servo.rig else { continue };
            let at = Location::Servo { servo_id: servo.id, caption: servo.caption.clone() };
            if let Some(parent) = rig.parent
                && !parents.contains_key(&parent)
            {
                self.error(&at, ProblemKind::RigUnknownParent { parent });
                continue;
            }
            if let Some(twin) = rig.mirror
                && (twin == servo.id || !parents.contains_key(&twin))
            {
                self.warning(&at, ProblemKind::RigUnknownTwin { twin });
            }
            // Up the parents: back at this servo is a ring (each ring said once).
            let mut path = vec![servo.id];
            let mut next = rig.parent;
            while let Some(parent) = next {
                if parent == servo.id {
                    path.push(parent);
                    let mut members: Vec<u8> = path.clone();
                    members.sort_unstable();
                    members.dedup();
                    if reported.insert(members) {
                        self.error(&at, ProblemKind::RigCycle { path });
                    }
                    break;
                }
                if path.contains(&parent) || path.len() > parents.len() {
                    // A ring further up, reported from one of its own servos.
                    break;
                }
                path.push(parent);
                next = parents.get(&parent).copied().flatten();
            }
        }
    }

    fn actions(&mut self, project: &ServoProject) {
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

    fn macros(&mut self, project: &ServoProject) {
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
                self.command(&timing, &at, command);
            }
        }
        self.cycles(project);
    }

    fn command(&mut self, timing: &Timing<'_>, at: &Location, command: &Command) {
        if !(1..=100).contains(&command.ratio_percent) {
            self.error(at, ProblemKind::RatioOutOfRange { ratio_percent: command.ratio_percent });
        }
        if command.loop_count < 1 {
            self.error(at, ProblemKind::LoopBelowOne { loop_count: command.loop_count });
        }
        match command.run {
            Run::Action { action_id } if timing.index().action(action_id).is_none() => {
                self.error(at, ProblemKind::MissingAction { action_id });
            }
            Run::Macro { macro_id } if timing.index().macro_by_id(macro_id).is_none() => {
                self.error(at, ProblemKind::MissingMacro { macro_id });
            }
            Run::Delay { delay_ms } if delay_ms < 0 => {
                self.error(at, ProblemKind::NegativeDelay { delay_ms });
            }
            _ => {}
        }
        if let Ok(total_ms) = timing.command_total_ms(command) {
            if i32::try_from(total_ms).is_err() {
                self.error(at, ProblemKind::TotalTooLong { total_ms });
            }
            // A total read from a board is written back as it was, until the command is edited.
            if let Some(stored_ms) = command.stored_total_ms
                && i64::from(stored_ms) != total_ms
            {
                self.warning(at, ProblemKind::StoredTotalDiffers { stored_ms, derived_ms: total_ms });
            }
        }
    }

    /// Reports each macro cycle once, at the command that closes it.
    fn cycles(&mut self, project: &ServoProject) {
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
        project: &ServoProject,
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

    fn tables(&mut self, project: &ServoProject) {
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
