//! The open document: the project, its undo history, its file and whether it
//! has unsaved changes.

use std::path::PathBuf;
use std::sync::atomic::{AtomicU64, Ordering};

use crate::project::{Edit, History, LivePose, Project, UndoStep};

/// The project being edited.
#[derive(Debug, Default)]
pub struct Document {
    /// The project.
    pub project: Project,
    /// Where it is saved, if it has been.
    pub path: Option<PathBuf>,
    /// Changed since it was last saved or opened.
    pub dirty: bool,
    history: History,
    revision: u64,
}

/// What an undo or redo changed.
#[derive(Clone, Debug, PartialEq)]
pub enum Undone {
    /// The project.
    Project,
    /// The live pose: the live side moves to it.
    Pose(LivePose),
    /// An edit made beside the project (a show's pass): its keeper takes it back or brings it again.
    Beside,
}

/// Revisions are unique across documents, so a cache keyed by one never
/// mistakes a newly opened project for the previous one.
static NEXT_REVISION: AtomicU64 = AtomicU64::new(1);

fn next_revision() -> u64 {
    NEXT_REVISION.fetch_add(1, Ordering::Relaxed)
}

impl Document {
    /// A document showing `project`, saved at `path`.
    pub fn new(project: Project, path: Option<PathBuf>) -> Self {
        Self { project, path, dirty: false, history: History::default(), revision: next_revision() }
    }

    /// Changes whenever the project does: a key for caches of derived data.
    pub fn revision(&self) -> u64 {
        self.revision
    }

    /// Applies an edit as one undo step, or as part of the open step with the
    /// same `coalesce` key (one slider drag is one step).
    pub fn apply(&mut self, edit: Edit, coalesce: Option<&str>) {
        if self.history.continues(coalesce) {
            // Part of the open step (a drag): its snapshot is taken, and a large
            // project is not copied again every frame of the drag.
            if edit.apply(&mut self.project) {
                self.dirty = true;
                self.revision = next_revision();
            }
            return;
        }
        let before = self.project.clone();
        if edit.apply(&mut self.project) && self.project != before {
            self.history.record(&before, coalesce);
            self.dirty = true;
            self.revision = next_revision();
        }
    }

    /// Closes the current coalesced undo step.
    pub fn seal(&mut self) {
        self.history.seal();
    }

    /// Records that the live pose is about to change from `before` (a turn in the 3D view), as one undo step.
    pub fn record_pose(&mut self, before: LivePose) {
        self.history.record_pose(before);
    }

    /// Records an edit made beside the project (a show window's pass) as one
    /// undo step; `project`: what it made of the project too, if anything.
    pub fn apply_beside(&mut self, project: Option<Project>) {
        match project {
            Some(project) if project != self.project => {
                self.history.record_beside(Some(&self.project));
                self.project = project;
                self.dirty = true;
                self.revision = next_revision();
            }
            _ => self.history.record_beside(None),
        }
    }

    /// Whether the step undo would take back was made beside the project.
    pub fn beside_on_top(&self) -> bool {
        self.history.beside_on_top()
    }

    /// Whether the step redo would bring back was made beside the project.
    pub fn beside_to_redo(&self) -> bool {
        self.history.beside_to_redo()
    }

    /// Forgets the steps made beside the project (their keeper closed).
    pub fn forget_beside(&mut self) {
        self.history.forget_beside();
    }

    /// Undoes the last step and says what it was, for the side that keeps
    /// it to follow (`pose_now`: the live pose of that family now, for redo).
    pub fn undo(&mut self, pose_now: impl FnOnce(&LivePose) -> LivePose) -> Option<Undone> {
        let step = self.history.undo(&self.project, pose_now)?;
        Some(self.show(step))
    }

    /// Redoes the last undone step, as [`Self::undo`].
    pub fn redo(&mut self, pose_now: impl FnOnce(&LivePose) -> LivePose) -> Option<Undone> {
        let step = self.history.redo(&self.project, pose_now)?;
        Some(self.show(step))
    }

    fn show(&mut self, step: UndoStep) -> Undone {
        let mut project_back = |project: Box<Project>| {
            self.project = *project;
            self.dirty = true;
            self.revision = next_revision();
        };
        match step {
            UndoStep::Project(project) => {
                project_back(project);
                Undone::Project
            }
            UndoStep::Pose(pose) => Undone::Pose(pose),
            UndoStep::Beside(project) => {
                if let Some(project) = project {
                    project_back(project);
                }
                Undone::Beside
            }
        }
    }

    /// Whether there is something to undo.
    pub fn can_undo(&self) -> bool {
        self.history.can_undo()
    }

    /// Whether there is something to redo.
    pub fn can_redo(&self) -> bool {
        self.history.can_redo()
    }
}
