//! Typed edits of a project: everything the editor changes goes through one of
//! these, so that undo, autosave and validation see every change in one place.

use super::document::Project;
use super::family::Family;
use super::servo::{Action, JoystickTable, Macro, Servo, ServoProject};

/// One change to a project.
#[derive(Clone, Debug, PartialEq)]
pub enum Edit {
    /// Replace the servo at `index`.
    SetServo {
        /// Position in the servo list.
        index: usize,
        /// The new servo.
        servo: Servo,
    },
    /// Append a servo.
    AddServo(Servo),
    /// Remove the servo at `index`.
    RemoveServo {
        /// Position in the servo list.
        index: usize,
    },
    /// Replace the action at `index`.
    SetAction {
        /// Position in the action list.
        index: usize,
        /// The new action.
        action: Action,
    },
    /// Append an action.
    AddAction(Action),
    /// Remove the action at `index`.
    RemoveAction {
        /// Position in the action list.
        index: usize,
    },
    /// Replace the macro at `index`.
    SetMacro {
        /// Position in the macro list.
        index: usize,
        /// The new macro.
        item: Macro,
    },
    /// Append a macro.
    AddMacro(Macro),
    /// Remove the macro at `index`.
    RemoveMacro {
        /// Position in the macro list.
        index: usize,
    },
    /// Replace the joystick table at `index`.
    SetTable {
        /// Position in the table list.
        index: usize,
        /// The new table.
        table: JoystickTable,
    },
    /// Append a joystick table.
    AddTable(JoystickTable),
    /// Remove the joystick table at `index`.
    RemoveTable {
        /// Position in the table list.
        index: usize,
    },
    /// Choose the active table.
    SetActiveTable(Option<i32>),
    /// Set the project id.
    SetProjectId(i32),
    /// Replace the whole servo section (e.g. read from a board).
    ReplaceAll(Box<ServoProject>),
    /// Switch the family the project is for (each section is kept).
    SetFamily(Family),
    /// Choose the rFLEX robot (its conversion constants).
    SetRflexRobot(super::rflex::Robot),
    /// Change the rFLEX drive limits.
    SetRflexDrive(super::rflex::DriveSettings),
    /// Replace a family's gamepad bindings.
    SetGamepad(Family, Box<super::gamepad::Mapping>),
    /// Replace the PLEN2 section (motions, play lists, joint settings).
    SetPlen2(Box<super::plen2::Plen2Project>),
    /// Replace the section a family added since the first three keeps (`null`: none).
    SetSection(Family, serde_json::Value),
    /// Set or remove the project's sound track.
    SetSound(Option<super::SoundTrack>),
}

fn set<T>(items: &mut [T], index: usize, value: T) -> bool {
    match items.get_mut(index) {
        Some(slot) => {
            *slot = value;
            true
        }
        None => false,
    }
}

fn remove<T>(items: &mut Vec<T>, index: usize) -> bool {
    if index < items.len() {
        items.remove(index);
        true
    } else {
        false
    }
}

impl Edit {
    /// Applies the edit; false (and no change) when its index is out of range,
    /// or its family keeps no such part.
    pub fn apply(self, project: &mut Project) -> bool {
        match self.apply_outside_servo(project) {
            Ok(applied) => applied,
            Err(edit) => edit.apply_servo(&mut project.servo),
        }
    }

    /// An edit of the project's family, another family's section or the
    /// bindings: applied (`Ok`); any other is given back.
    fn apply_outside_servo(self, project: &mut Project) -> Result<bool, Self> {
        match self {
            Self::SetFamily(family) => project.family = family,
            Self::SetRflexRobot(robot) => project.rflex.robot = robot,
            Self::SetRflexDrive(drive) => project.rflex.drive = drive,
            Self::SetPlen2(plen2) => project.plen2 = *plen2,
            Self::SetSection(family, section) => project.sections.set(family, section),
            Self::SetSound(sound) => project.sound = sound,
            Self::SetGamepad(family, mapping) => {
                let Some(bindings) = project.gamepad.of_mut(family) else { return Ok(false) };
                *bindings = *mapping;
            }
            servo => return Err(servo),
        }
        Ok(true)
    }

    /// An edit of the servo section.
    fn apply_servo(self, project: &mut ServoProject) -> bool {
        match self {
            Self::SetFamily(_)
            | Self::SetRflexRobot(_)
            | Self::SetRflexDrive(_)
            | Self::SetPlen2(_)
            | Self::SetSection(..)
            | Self::SetSound(_)
            | Self::SetGamepad(..) => false,
            Self::SetServo { index, servo } => set(&mut project.servos, index, servo),
            Self::AddServo(servo) => {
                project.servos.push(servo);
                true
            }
            Self::RemoveServo { index } => remove(&mut project.servos, index),
            Self::SetAction { index, action } => set(&mut project.actions, index, action),
            Self::AddAction(action) => {
                project.actions.push(action);
                true
            }
            Self::RemoveAction { index } => remove(&mut project.actions, index),
            Self::SetMacro { index, mut item } => {
                if let Some(old) = project.macros.get(index) {
                    keep_stored_totals(&old.commands, &mut item);
                }
                set(&mut project.macros, index, item)
            }
            Self::AddMacro(item) => {
                project.macros.push(item);
                true
            }
            Self::RemoveMacro { index } => remove(&mut project.macros, index),
            Self::SetTable { index, table } => set(&mut project.joystick_tables, index, table),
            Self::AddTable(table) => {
                project.joystick_tables.push(table);
                true
            }
            Self::RemoveTable { index } => remove(&mut project.joystick_tables, index),
            Self::SetActiveTable(table_id) => {
                project.active_table = table_id;
                true
            }
            Self::SetProjectId(project_id) => {
                project.project_id = project_id;
                true
            }
            Self::ReplaceAll(replacement) => {
                *project = *replacement;
                true
            }
        }
    }
}

/// A command keeps the total a board stored only while it is unchanged (moving
/// it is no change); an edited command's total is derived again.
fn keep_stored_totals(old: &[super::servo::Command], item: &mut Macro) {
    for command in &mut item.commands {
        if command.stored_total_ms.is_some() && !old.contains(command) {
            command.stored_total_ms = None;
        }
    }
}

/// The smallest id of 1 or more that `used` does not contain.
pub fn next_free_id(used: impl IntoIterator<Item = i32>) -> i32 {
    let mut used: Vec<i32> = used.into_iter().filter(|id| *id > 0).collect();
    used.sort_unstable();
    let mut candidate = 1;
    for id in used {
        if id == candidate {
            candidate += 1;
        } else if id > candidate {
            break;
        }
    }
    candidate
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edits_apply_and_out_of_range_changes_nothing() {
        let mut project = Project::default();
        assert!(Edit::AddServo(Servo::new(1, "a")).apply(&mut project));
        assert!(Edit::SetServo { index: 0, servo: Servo::new(1, "b") }.apply(&mut project));
        assert_eq!(project.servo.servos[0].caption, "b");
        let before = project.clone();
        assert!(!Edit::SetServo { index: 5, servo: Servo::new(9, "x") }.apply(&mut project));
        assert!(!Edit::RemoveAction { index: 0 }.apply(&mut project));
        assert_eq!(project, before);
        assert!(Edit::SetActiveTable(Some(3)).apply(&mut project));
        assert_eq!(project.servo.active_table, Some(3));
    }

    #[test]
    fn an_edited_command_loses_its_stored_total_and_a_moved_one_keeps_it() {
        use crate::project::{Command, Run};
        let stored = |run, total| Command { stored_total_ms: Some(total), ..Command::once(run) };
        let first = stored(Run::Action { action_id: 1 }, 1234);
        let second = stored(Run::Delay { delay_ms: 10 }, 99);
        let item = Macro { id: 5, caption: String::new(), commands: vec![first, second] };
        let mut project = Project::servo(ServoProject { macros: vec![item.clone()], ..ServoProject::default() });

        // Reordered: nothing about either command changed.
        let mut moved = item.clone();
        moved.commands.reverse();
        assert!(Edit::SetMacro { index: 0, item: moved }.apply(&mut project));
        let totals: Vec<_> = project.servo.macros[0].commands.iter().map(|c| c.stored_total_ms).collect();
        assert_eq!(totals, [Some(99), Some(1234)]);

        // The ratio of one changed: its total is derived from now on.
        let mut edited = project.servo.macros[0].clone();
        edited.commands[1].ratio_percent = 50;
        assert!(Edit::SetMacro { index: 0, item: edited }.apply(&mut project));
        let totals: Vec<_> = project.servo.macros[0].commands.iter().map(|c| c.stored_total_ms).collect();
        assert_eq!(totals, [Some(99), None]);
    }

    #[test]
    fn next_free_id_fills_the_first_gap() {
        assert_eq!(next_free_id([]), 1);
        assert_eq!(next_free_id([1, 2, 4]), 3);
        assert_eq!(next_free_id([3, 1, 2]), 4);
        assert_eq!(next_free_id([-5, 0, 2]), 1);
    }
}
