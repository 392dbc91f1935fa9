//! Undo and redo for the document: snapshots of the project, one per edit.
//! Consecutive edits that share a coalescing key (one slider drag, one text
//! field being typed into) make a single undo step.

use super::document::Project;
#[cfg(test)]
use super::servo::ServoProject;

/// Most undo steps kept.
pub const MAX_UNDO_STEPS: usize = 200;

/// The undo and redo stacks.
#[derive(Debug, Default)]
pub struct History {
    undo: Vec<Project>,
    redo: Vec<Project>,
    /// The key of the last recorded edit, while it may still be extended.
    open_key: Option<String>,
}

impl History {
    /// Records that the project is about to change from `before`. An edit with
    /// the same `key` as the previous one extends that undo step instead of
    /// starting a new one; `None` always starts a new step.
    pub fn record(&mut self, before: &Project, key: Option<&str>) {
        self.redo.clear();
        if self.continues(key) {
            return;
        }
        self.undo.push(before.clone());
        if self.undo.len() > MAX_UNDO_STEPS {
            self.undo.remove(0);
        }
        self.open_key = key.map(str::to_string);
    }

    /// Whether an edit with coalesce `key` joins the open step (so needs no snapshot).
    pub fn continues(&self, key: Option<&str>) -> bool {
        key.is_some() && key == self.open_key.as_deref()
    }

    /// Ends the current coalesced step (e.g. the slider was let go).
    pub fn seal(&mut self) {
        self.open_key = None;
    }

    /// Steps back: returns the project to show, given the current one.
    pub fn undo(&mut self, current: &Project) -> Option<Project> {
        let previous = self.undo.pop()?;
        self.redo.push(current.clone());
        self.open_key = None;
        Some(previous)
    }

    /// Steps forward again.
    pub fn redo(&mut self, current: &Project) -> Option<Project> {
        let next = self.redo.pop()?;
        self.undo.push(current.clone());
        self.open_key = None;
        Some(next)
    }

    /// Whether there is something to undo.
    pub fn can_undo(&self) -> bool {
        !self.undo.is_empty()
    }

    /// Whether there is something to redo.
    pub fn can_redo(&self) -> bool {
        !self.redo.is_empty()
    }

    /// Forgets everything (a new or opened document).
    pub fn clear(&mut self) {
        *self = Self::default();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn with_id(project_id: i32) -> Project {
        Project::servo(ServoProject { project_id, ..ServoProject::default() })
    }

    #[test]
    fn undo_and_redo_restore_exact_states() {
        let mut history = History::default();
        let mut current = with_id(1);
        for next in 2..=4 {
            history.record(&current, None);
            current = with_id(next);
        }
        current = history.undo(&current).unwrap();
        assert_eq!(current, with_id(3));
        current = history.undo(&current).unwrap();
        assert_eq!(current, with_id(2));
        current = history.redo(&current).unwrap();
        assert_eq!(current, with_id(3));
        // A new edit drops the redo stack.
        history.record(&current, None);
        current = with_id(9);
        assert!(!history.can_redo());
        assert_eq!(history.undo(&current).unwrap(), with_id(3));
    }

    #[test]
    fn edits_with_the_same_key_are_one_step_until_sealed() {
        let mut history = History::default();
        let mut current = with_id(0);
        for value in 1..=10 {
            history.record(&current, Some("servo 3 calibration"));
            current = with_id(value);
        }
        history.seal();
        history.record(&current, Some("servo 3 calibration"));
        current = with_id(11);
        let back = history.undo(&current).unwrap();
        assert_eq!(back, with_id(10), "the second drag is its own step");
        assert_eq!(history.undo(&back).unwrap(), with_id(0), "the first drag was one step");
        assert!(!history.can_undo());
    }

    #[test]
    fn depth_is_bounded() {
        let mut history = History::default();
        for value in 0..i32::try_from(MAX_UNDO_STEPS + 50).unwrap() {
            history.record(&with_id(value), None);
        }
        let mut current = with_id(-1);
        let mut steps = 0;
        while let Some(previous) = history.undo(&current) {
            current = previous;
            steps += 1;
        }
        assert_eq!(steps, MAX_UNDO_STEPS);
        assert_eq!(current, with_id(50));
    }
}
