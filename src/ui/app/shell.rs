//! What a family's ui reaches of the shell: while it applies an action
//! ([`Shell`]: the document, the link, the status line, the operation slot),
//! and while it draws ([`ShellView`], read only).

use std::path::Path;

use crate::device::plen2::Plen2Handle;
use crate::device::rflex::RflexBase;
use crate::device::servo::ServoHandle;
use crate::link::Waker;
use crate::project::Project;
use crate::ui::board_link::BoardLink;
use crate::ui::document::Document;
use crate::ui::i18n::{Language, Strings};
use crate::ui::operation::Operation;
use crate::ui::plen2::{Plen2Kind, Plen2Outcome};
use crate::ui::servo::{ServoKind, ServoOutcome};

use super::StatusLine;

/// The one board operation running, of whichever family.
#[derive(Debug)]
pub enum RunningOperation {
    /// A servo board's.
    Servo(Operation<ServoKind, ServoOutcome>),
    /// A PLEN2's.
    Plen2(Operation<Plen2Kind, Plen2Outcome>),
}

impl RunningOperation {
    /// Asks it to stop after its current step.
    pub fn cancel(&self) {
        match self {
            Self::Servo(operation) => operation.cancel(),
            Self::Plen2(operation) => operation.cancel(),
        }
    }
}

/// The shell, as a family's ui changes it.
pub struct Shell<'a> {
    /// The open document.
    pub document: &'a mut Document,
    /// The board, when connected.
    pub link: &'a mut Option<BoardLink>,
    /// The status line.
    pub status: &'a mut Option<StatusLine>,
    /// The running board operation (one at a time).
    pub operation: &'a mut Option<RunningOperation>,
    /// The interface language.
    pub language: Language,
    /// Where backups go (under `backups/`).
    pub data_dir: &'a Path,
    /// Wakes the window from other threads.
    pub waker: &'a Waker,
}

impl Shell<'_> {
    /// The interface's words.
    pub fn words(&self) -> &'static Strings {
        self.language.strings()
    }

    /// Says something on the status line.
    pub fn report(&mut self, text: impl Into<String>, is_error: bool) {
        *self.status = Some(StatusLine { text: text.into(), is_error });
    }

    /// The connected servo board.
    pub fn servo(&self) -> Option<&ServoHandle> {
        self.link.as_ref().and_then(BoardLink::servo)
    }

    /// The connected servo board, mutably.
    pub fn servo_mut(&mut self) -> Option<&mut ServoHandle> {
        self.link.as_mut().and_then(BoardLink::servo_mut)
    }

    /// The connected PLEN2.
    pub fn plen2(&self) -> Option<&Plen2Handle> {
        self.link.as_ref().and_then(BoardLink::plen2)
    }

    /// The connected PLEN2, mutably.
    pub fn plen2_mut(&mut self) -> Option<&mut Plen2Handle> {
        self.link.as_mut().and_then(BoardLink::plen2_mut)
    }

    /// The connected base, mutably.
    pub fn rflex_mut(&mut self) -> Option<&mut RflexBase> {
        self.link.as_mut().and_then(BoardLink::rflex_mut)
    }
}

/// The shell, as a family's ui draws from it.
#[derive(Clone, Copy)]
pub struct ShellView<'a> {
    /// The project.
    pub project: &'a Project,
    /// Its revision (derived data is cached per revision).
    pub revision: u64,
    /// The board, when connected.
    pub link: Option<&'a BoardLink>,
    /// The running board operation.
    pub operation: Option<&'a RunningOperation>,
    /// The interface language.
    pub language: Language,
}

impl<'a> ShellView<'a> {
    /// The running servo board operation, if that is what runs.
    pub fn servo_operation(&self) -> Option<&'a Operation<ServoKind, ServoOutcome>> {
        match self.operation {
            Some(RunningOperation::Servo(operation)) => Some(operation),
            _ => None,
        }
    }

    /// The running PLEN2 operation, if that is what runs.
    pub fn plen2_operation(&self) -> Option<&'a Operation<Plen2Kind, Plen2Outcome>> {
        match self.operation {
            Some(RunningOperation::Plen2(operation)) => Some(operation),
            _ => None,
        }
    }
}
