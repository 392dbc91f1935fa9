//! Derived run times: how long actions, macro commands and macros take.
//!
//! - All steps of an action start together; the action lasts as long as its
//!   longest step (`interval_10ms × 10` ms).
//! - A command's `totalInterval` in ms:
//!   run action → longest step × 10 × loop × 100 / ratio;
//!   delay → delay × loop;
//!   run macro → the macro's own total × loop × 100 / ratio.
//! - A macro's own total is the sum of its commands' totals (they run one after
//!   another). Divisions round down, as integer firmware arithmetic does.

use std::collections::HashMap;

use super::servo::{Action, Command, Run, ServoIndex, ServoProject};

/// Why a run time cannot be computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub enum TimingError {
    /// A command names an action the project does not have.
    #[error("action {0} does not exist")]
    MissingAction(i32),
    /// A command names a macro the project does not have.
    #[error("macro {0} does not exist")]
    MissingMacro(i32),
    /// The macro reaches itself, so it never ends.
    #[error("macro {0} is part of a cycle (it reaches itself), so it never ends")]
    Cycle(i32),
    /// A ratio of 0 % would never finish.
    #[error("ratio 0 % never finishes")]
    ZeroRatio,
}

/// The duration of an action in ms: its longest step (0 for an empty action).
pub fn action_duration_ms(action: &Action) -> i64 {
    action.steps.iter().map(|step| i64::from(step.interval_10ms.max(0)) * 10).max().unwrap_or(0)
}

/// Run times of every macro of a project, computed once.
#[derive(Debug)]
pub struct Timing<'a> {
    index: ServoIndex<'a>,
    macro_totals_ms: HashMap<i32, Result<i64, TimingError>>,
}

impl<'a> Timing<'a> {
    /// Computes the totals of all macros of `project`.
    pub fn new(project: &'a ServoProject) -> Self {
        let mut timing = Self { index: project.index(), macro_totals_ms: HashMap::new() };
        let mut visiting = Vec::new();
        for item in &project.macros {
            let _ = timing.compute_macro(item.id, &mut visiting);
        }
        timing
    }

    /// The project's actions and macros by id.
    pub fn index(&self) -> &ServoIndex<'a> {
        &self.index
    }

    /// The total run time of a macro in ms.
    pub fn macro_total_ms(&self, macro_id: i32) -> Result<i64, TimingError> {
        self.macro_totals_ms.get(&macro_id).copied().unwrap_or(Err(TimingError::MissingMacro(macro_id)))
    }

    /// A command's `totalInterval` in ms.
    pub fn command_total_ms(&self, command: &Command) -> Result<i64, TimingError> {
        let inner = match command.run {
            Run::Delay { delay_ms } => {
                return Ok(i64::from(delay_ms).saturating_mul(i64::from(command.loop_count)));
            }
            Run::Action { action_id } => {
                action_duration_ms(self.index.action(action_id).ok_or(TimingError::MissingAction(action_id))?)
            }
            Run::Macro { macro_id } => self.macro_total_ms(macro_id)?,
        };
        scale(inner, command)
    }

    fn compute_macro(&mut self, macro_id: i32, visiting: &mut Vec<i32>) -> Result<i64, TimingError> {
        if let Some(done) = self.macro_totals_ms.get(&macro_id) {
            return *done;
        }
        if visiting.contains(&macro_id) {
            return Err(TimingError::Cycle(macro_id));
        }
        let Some(item) = self.index.macro_by_id(macro_id) else {
            return Err(TimingError::MissingMacro(macro_id));
        };
        visiting.push(macro_id);
        let mut total: Result<i64, TimingError> = Ok(0);
        for command in &item.commands {
            let part = match command.run {
                Run::Macro { macro_id: inner } => {
                    self.compute_macro(inner, visiting).and_then(|inner_ms| scale(inner_ms, command))
                }
                _ => self.command_total_ms(command),
            };
            total = match (total, part) {
                (Ok(sum), Ok(part)) => Ok(sum.saturating_add(part)),
                // A cycle through this macro is the problem to report first.
                (Err(TimingError::Cycle(id)), _) | (_, Err(TimingError::Cycle(id))) => Err(TimingError::Cycle(id)),
                (Err(error), _) | (_, Err(error)) => Err(error),
            };
        }
        visiting.pop();
        self.macro_totals_ms.insert(macro_id, total);
        total
    }
}

/// `inner × loop × 100 / ratio`, rounded down.
fn scale(inner_ms: i64, command: &Command) -> Result<i64, TimingError> {
    if command.ratio_percent == 0 {
        return Err(TimingError::ZeroRatio);
    }
    Ok(inner_ms.saturating_mul(i64::from(command.loop_count)).saturating_mul(100) / i64::from(command.ratio_percent))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::project::servo::{Macro, Step};

    fn action(id: i32, intervals_10ms: &[i16]) -> Action {
        let steps = (0u8..)
            .zip(intervals_10ms)
            .map(|(servo_id, &interval_10ms)| Step::new(servo_id, 0, interval_10ms))
            .collect();
        Action { id, caption: String::new(), steps }
    }

    fn command(run: Run, ratio_percent: u8, loop_count: i16) -> Command {
        Command { run, ratio_percent, loop_count, stored_total_ms: None }
    }

    fn macro_of(id: i32, commands: Vec<Command>) -> Macro {
        Macro { id, caption: String::new(), commands }
    }

    #[test]
    fn action_lasts_as_long_as_its_longest_step() {
        assert_eq!(action_duration_ms(&action(1, &[50, 120, 7])), 1200);
        assert_eq!(action_duration_ms(&action(1, &[])), 0);
    }

    #[test]
    fn command_totals_follow_the_documented_formulas() {
        let project = ServoProject {
            actions: vec![action(1, &[50, 150])],
            macros: vec![macro_of(
                10,
                vec![command(Run::Action { action_id: 1 }, 100, 1), command(Run::Delay { delay_ms: 250 }, 40, 2)],
            )],
            ..ServoProject::default()
        };
        let timing = Timing::new(&project);
        // action: 1500 ms × 3 loops × 100 / 50 % = 9000 ms
        assert_eq!(timing.command_total_ms(&command(Run::Action { action_id: 1 }, 50, 3)), Ok(9000));
        // delay: 250 × 2, ratio ignored
        assert_eq!(timing.command_total_ms(&command(Run::Delay { delay_ms: 250 }, 40, 2)), Ok(500));
        // macro 10 = 1500 + 500 = 2000; × 2 loops × 100 / 30 % = 13333 (rounded down)
        assert_eq!(timing.macro_total_ms(10), Ok(2000));
        assert_eq!(timing.command_total_ms(&command(Run::Macro { macro_id: 10 }, 30, 2)), Ok(13333));
    }

    #[test]
    fn missing_references_and_cycles_have_no_total() {
        let project = ServoProject {
            macros: vec![
                macro_of(1, vec![Command::once(Run::Macro { macro_id: 2 })]),
                macro_of(2, vec![Command::once(Run::Macro { macro_id: 1 })]),
                macro_of(3, vec![Command::once(Run::Action { action_id: 9 })]),
                macro_of(4, vec![Command::once(Run::Macro { macro_id: 1 })]),
            ],
            ..ServoProject::default()
        };
        let timing = Timing::new(&project);
        assert_eq!(timing.macro_total_ms(1), Err(TimingError::Cycle(1)));
        assert_eq!(timing.macro_total_ms(2), Err(TimingError::Cycle(1)));
        assert_eq!(timing.macro_total_ms(4), Err(TimingError::Cycle(1)));
        assert_eq!(timing.macro_total_ms(3), Err(TimingError::MissingAction(9)));
        assert_eq!(timing.macro_total_ms(77), Err(TimingError::MissingMacro(77)));
        assert_eq!(
            timing.command_total_ms(&command(Run::Action { action_id: 9 }, 0, 1)),
            Err(TimingError::MissingAction(9))
        );
    }
}
