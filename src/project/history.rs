//! Undo and redo for the document: snapshots of the project, one per edit.
//! Consecutive edits that share a coalescing key (one slider drag, one text
//! field being typed into) make a single undo step. A turn of a joint in the
//! 3D view changes the live pose, which no file holds: its step keeps the
//! pose from before it, in the same order as the edits.

use std::collections::BTreeMap;

use super::document::Project;
#[cfg(test)]
use super::servo::ServoProject;

/// The live pose (what the sliders hold), in its family's terms: each axis's
/// value by its number — a servo board's servos, degrees by id; a PLEN2's
/// joints, tenths of a degree by device-map index. Any family keeps its own.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LivePose {
    /// The family whose pose it is.
    pub family: super::Family,
    /// Each axis's value, by its number.
    pub values: BTreeMap<u8, i16>,
}

impl LivePose {
    /// `family`'s pose, values by axis number.
    pub fn new(family: super::Family, values: BTreeMap<u8, i16>) -> Self {
        Self { family, values }
    }

    /// `family`'s pose from values in axis order (0, 1, …).
    pub fn indexed(family: super::Family, values: &[i16]) -> Self {
        Self { family, values: (0..=u8::MAX).zip(values.iter().copied()).collect() }
    }

    /// The values in axis order, `N` of them (an axis it lacks is 0).
    pub fn to_array<const N: usize>(&self) -> [i16; N] {
        let mut values = [0; N];
        for (&axis, &value) in &self.values {
            if let Some(slot) = values.get_mut(usize::from(axis)) {
                *slot = value;
            }
        }
        values
    }

    /// The family whose pose it is.
    pub fn family(&self) -> super::Family {
        self.family
    }
}

/// What one undo step brings back.
#[derive(Clone, Debug, PartialEq)]
pub enum Step {
    /// The project before an edit.
    Project(Box<Project>),
    /// The live pose before a turn in the 3D view.
    Pose(LivePose),
    /// An edit made beside the project (a pass recorded in the show window,
    /// which keeps its own before and after): the project before it, when
    /// the edit changed the project too.
    Beside(Option<Box<Project>>),
}

/// Most undo steps kept.
pub const MAX_UNDO_STEPS: usize = 200;

/// The undo and redo stacks.
#[derive(Debug, Default)]
pub struct History {
    undo: Vec<Step>,
    redo: Vec<Step>,
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
        self.push(Step::Project(Box::new(before.clone())));
        self.open_key = key.map(str::to_string);
    }

    /// Records that the live pose is about to change from `before` (a turn in the 3D view).
    pub fn record_pose(&mut self, before: LivePose) {
        self.redo.clear();
        self.push(Step::Pose(before));
        self.open_key = None;
    }

    /// Records an edit made beside the project (see [`Step::Beside`]):
    /// `before` is the project before it, when it changes the project too.
    pub fn record_beside(&mut self, before: Option<&Project>) {
        self.redo.clear();
        self.push(Step::Beside(before.map(|project| Box::new(project.clone()))));
        self.open_key = None;
    }

    /// Whether the step undo would take back is one made beside the project.
    pub fn beside_on_top(&self) -> bool {
        matches!(self.undo.last(), Some(Step::Beside(_)))
    }

    /// Whether the step redo would bring back is one made beside the project.
    pub fn beside_to_redo(&self) -> bool {
        matches!(self.redo.last(), Some(Step::Beside(_)))
    }

    /// Forgets what was made beside the project (its keeper is gone: the
    /// show window closed): a step that changed the project too stays, as an
    /// edit of the project; the rest go.
    pub fn forget_beside(&mut self) {
        let keep = |steps: &mut Vec<Step>| {
            steps.retain(|step| !matches!(step, Step::Beside(None)));
            for step in steps.iter_mut() {
                if let Step::Beside(Some(project)) = step {
                    *step = Step::Project(project.clone());
                }
            }
        };
        keep(&mut self.undo);
        keep(&mut self.redo);
    }

    fn push(&mut self, step: Step) {
        self.undo.push(step);
        if self.undo.len() > MAX_UNDO_STEPS {
            self.undo.remove(0);
        }
    }

    /// Whether an edit with coalesce `key` joins the open step (so needs no snapshot).
    pub fn continues(&self, key: Option<&str>) -> bool {
        key.is_some() && key == self.open_key.as_deref()
    }

    /// Ends the current coalesced step (e.g. the slider was let go).
    pub fn seal(&mut self) {
        self.open_key = None;
    }

    /// Steps back: returns what to show, given the current project and
    /// `pose_now`, the current live pose of the family a pose step is of.
    pub fn undo(&mut self, current: &Project, pose_now: impl FnOnce(&LivePose) -> LivePose) -> Option<Step> {
        let previous = self.undo.pop()?;
        self.redo.push(Self::now(&previous, current, pose_now));
        self.open_key = None;
        Some(previous)
    }

    /// Steps forward again.
    pub fn redo(&mut self, current: &Project, pose_now: impl FnOnce(&LivePose) -> LivePose) -> Option<Step> {
        let next = self.redo.pop()?;
        self.undo.push(Self::now(&next, current, pose_now));
        self.open_key = None;
        Some(next)
    }

    /// What stands now in place of `step`.
    fn now(step: &Step, current: &Project, pose_now: impl FnOnce(&LivePose) -> LivePose) -> Step {
        match step {
            Step::Project(_) => Step::Project(Box::new(current.clone())),
            Step::Pose(pose) => Step::Pose(pose_now(pose)),
            Step::Beside(before) => Step::Beside(before.as_ref().map(|_| Box::new(current.clone()))),
        }
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
    use crate::project::Family;

    fn with_id(project_id: i32) -> Project {
        Project::servo(ServoProject { project_id, ..ServoProject::default() })
    }

    fn undo(history: &mut History, current: &Project) -> Option<Project> {
        match history.undo(current, Clone::clone)? {
            Step::Project(project) => Some(*project),
            other => panic!("not a project step: {other:?}"),
        }
    }

    fn redo(history: &mut History, current: &Project) -> Option<Project> {
        match history.redo(current, Clone::clone)? {
            Step::Project(project) => Some(*project),
            other => panic!("not a project step: {other:?}"),
        }
    }

    #[test]
    fn a_step_made_beside_the_project_is_one_step_in_order_and_outlives_its_keeper_as_an_edit() {
        let mut history = History::default();
        history.record(&with_id(1), None);
        history.record_beside(Some(&with_id(2)));
        history.record_beside(None);
        assert!(history.beside_on_top());
        assert_eq!(history.undo(&with_id(3), Clone::clone), Some(Step::Beside(None)));
        assert!(history.beside_to_redo());
        // Undone, the step that changed the project too brings back the project before it; redo, the one after.
        assert_eq!(history.undo(&with_id(3), Clone::clone), Some(Step::Beside(Some(Box::new(with_id(2))))));
        assert_eq!(history.redo(&with_id(2), Clone::clone), Some(Step::Beside(Some(Box::new(with_id(3))))));
        // The show closed: the step without a project goes, the other stays as an edit of the project.
        history.forget_beside();
        assert!(!history.beside_on_top() && !history.can_redo());
        assert_eq!(undo(&mut history, &with_id(3)), Some(with_id(2)));
        assert_eq!(undo(&mut history, &with_id(2)), Some(with_id(1)));
        assert!(!history.can_undo());
    }

    #[test]
    fn a_pose_step_sits_between_edits_and_redo_brings_the_pose_it_replaced() {
        let mut history = History::default();
        history.record(&with_id(1), Some("drag"));
        history.record_pose(LivePose::indexed(Family::Plen2, &[5; 18]));
        // The turn closed the drag's step: the next edit with the same key is its own step.
        history.record(&with_id(2), Some("drag"));
        let current = with_id(3);
        assert_eq!(undo(&mut history, &current), Some(with_id(2)));
        let turned = LivePose::indexed(Family::Plen2, &[7; 18]);
        assert_eq!(
            history.undo(&with_id(2), |_| turned.clone()),
            Some(Step::Pose(LivePose::indexed(Family::Plen2, &[5; 18])))
        );
        assert_eq!(undo(&mut history, &with_id(2)), Some(with_id(1)));
        assert_eq!(redo(&mut history, &with_id(1)), Some(with_id(2)));
        assert_eq!(history.redo(&with_id(2), |_| LivePose::indexed(Family::Plen2, &[5; 18])), Some(Step::Pose(turned)));
        // A new turn drops what could be redone.
        history.record_pose(LivePose::new(Family::Servo, BTreeMap::from([(1, 90)])));
        assert!(!history.can_redo());
    }

    #[test]
    fn undo_and_redo_restore_exact_states() {
        let mut history = History::default();
        let mut current = with_id(1);
        for next in 2..=4 {
            history.record(&current, None);
            current = with_id(next);
        }
        current = undo(&mut history, &current).unwrap();
        assert_eq!(current, with_id(3));
        current = undo(&mut history, &current).unwrap();
        assert_eq!(current, with_id(2));
        current = redo(&mut history, &current).unwrap();
        assert_eq!(current, with_id(3));
        // A new edit drops the redo stack.
        history.record(&current, None);
        current = with_id(9);
        assert!(!history.can_redo());
        assert_eq!(undo(&mut history, &current).unwrap(), with_id(3));
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
        let back = undo(&mut history, &current).unwrap();
        assert_eq!(back, with_id(10), "the second drag is its own step");
        assert_eq!(undo(&mut history, &back).unwrap(), with_id(0), "the first drag was one step");
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
        while let Some(previous) = undo(&mut history, &current) {
            current = previous;
            steps += 1;
        }
        assert_eq!(steps, MAX_UNDO_STEPS);
        assert_eq!(current, with_id(50));
    }
}
