//! What a family's ui reaches of the shell: while it applies an action
//! ([`Shell`]: the document, the link, the status line, the operation slot),
//! and while it draws ([`ShellView`], read only).

use std::any::Any;
use std::path::Path;
use std::time::Duration;

use crate::link::Waker;
use crate::project::Project;
use crate::ui::board_link::BoardLink;
use crate::ui::document::Document;
use crate::ui::files::FileWork;
use crate::ui::i18n::{Language, Said, Strings};
use crate::ui::operation::Operation;

/// A line for the status bar, kept as what it means ([`Said`]): another
/// language chosen while it shows says it again in that language.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct StatusLine {
    /// The text, in the language shown.
    pub text: String,
    /// Whether it reports a failure.
    pub is_error: bool,
    /// What it means, in every language.
    said: Said,
}

impl StatusLine {
    /// A line that is the same in every language.
    pub fn new(text: impl Into<String>, is_error: bool) -> Self {
        let text = text.into();
        Self { said: Said::fixed(text.clone()), text, is_error }
    }

    /// A line worded by `word` in every language, shown in `language`.
    pub fn worded<T: Into<String>>(language: Language, word: impl Fn(Language) -> T, is_error: bool) -> Self {
        Self::said(language, Said::new(word), is_error)
    }

    /// A line saying `said`, shown in `language`.
    pub fn said(language: Language, said: Said, is_error: bool) -> Self {
        Self { text: said.in_(language).to_string(), is_error, said }
    }

    /// Its first line only, in every language.
    pub fn first_line(&self) -> Self {
        let said = self.said.map(|text| text.lines().next().unwrap_or_default().to_string());
        let text = self.text.lines().next().unwrap_or_default().to_string();
        Self { text, is_error: self.is_error, said }
    }

    /// Says it again in `language`.
    pub fn reword(&mut self, language: Language) {
        self.text = self.said.in_(language).to_string();
    }
}

/// A board operation as the shell holds it, whatever its family's types.
pub trait Running: Any + std::fmt::Debug {
    /// Asks it to stop after its current step.
    fn cancel(&self);
    /// Itself, for the family that started it to find it again.
    fn as_any(&self) -> &dyn Any;
    /// Itself, mutably.
    fn as_any_mut(&mut self) -> &mut dyn Any;
    /// Itself, boxed as anything.
    fn into_any(self: Box<Self>) -> Box<dyn Any>;
}

impl<K, O, I> Running for Operation<K, O, I>
where
    K: std::fmt::Debug + 'static,
    O: std::fmt::Debug + Send + 'static,
    I: std::fmt::Debug + Clone + Send + 'static,
{
    fn cancel(&self) {
        Operation::cancel(self);
    }
    fn as_any(&self) -> &dyn Any {
        self
    }
    fn as_any_mut(&mut self) -> &mut dyn Any {
        self
    }
    fn into_any(self: Box<Self>) -> Box<dyn Any> {
        self
    }
}

/// The one board operation running, of whichever family. The shell only
/// cancels it; the family that started it knows its type and takes it back
/// with [`RunningOperation::get`] / [`RunningOperation::take`].
#[derive(Debug)]
pub struct RunningOperation(Box<dyn Running>);

impl RunningOperation {
    /// Holds `operation`.
    pub fn new(operation: impl Running) -> Self {
        Self(Box::new(operation))
    }

    /// Asks it to stop after its current step.
    pub fn cancel(&self) {
        self.0.cancel();
    }

    /// The operation, if it is a `T`.
    pub fn get<T: 'static>(&self) -> Option<&T> {
        self.0.as_any().downcast_ref()
    }

    /// The operation, mutably, if it is a `T`.
    pub fn get_mut<T: 'static>(&mut self) -> Option<&mut T> {
        self.0.as_any_mut().downcast_mut()
    }

    /// The operation itself, if it is a `T`.
    pub fn take<T: 'static>(slot: &mut Option<Self>) -> Option<T> {
        slot.as_ref()?.get::<T>()?;
        let running = slot.take()?;
        running.0.into_any().downcast().ok().map(|operation| *operation)
    }

    /// The outcome of the `Operation<K, O, I>` in `slot`, if that is what runs
    /// and it has ended (waiting up to `wait` for it; None: not at all); the
    /// operation is taken out of the slot with its outcome.
    pub fn finished<K, O, I>(slot: &mut Option<Self>, wait: Option<Duration>) -> Option<(Operation<K, O, I>, O)>
    where
        K: std::fmt::Debug + 'static,
        O: std::fmt::Debug + Send + 'static,
        I: std::fmt::Debug + Clone + Send + 'static,
    {
        let operation = slot.as_mut()?.get_mut::<Operation<K, O, I>>()?;
        let outcome = match wait {
            None => operation.poll(),
            Some(wait) => operation.wait(wait),
        }?;
        Some((Self::take(slot)?, outcome))
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
    /// How fast anything sent live may turn a servo or joint.
    pub speed: crate::device::speed::LiveSpeed,
    /// Where backups go (under `backups/`).
    pub data_dir: &'a Path,
    /// Wakes the window from other threads.
    pub waker: &'a Waker,
    /// Writes files off the frame (exports).
    pub files: &'a FileWork,
    /// The project's sound: played together with the board.
    pub sound: &'a mut crate::ui::sound::SoundDesk,
}

impl Shell<'_> {
    /// The interface's words.
    pub fn words(&self) -> &'static Strings {
        self.language.strings()
    }

    /// Says something on the status line that is the same in every language.
    pub fn report(&mut self, text: impl Into<String>, is_error: bool) {
        *self.status = Some(StatusLine::new(text, is_error));
    }

    /// Says something on the status line, worded by `word` in each language
    /// (said again in another when the language changes).
    pub fn say<T: Into<String>>(&mut self, word: impl Fn(Language) -> T, is_error: bool) {
        *self.status = Some(StatusLine::worded(self.language, word, is_error));
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
    /// Wakes the window from other threads (a family's own readers: a gamepad).
    pub waker: &'a Waker,
    /// The folder of the project's file (files it names are relative to it), once saved or opened.
    pub folder: Option<&'a Path>,
    /// The project's sound, as read.
    pub sound: crate::ui::sound::SoundView<'a>,
}

impl<'a> ShellView<'a> {
    /// The running operation, if it is a `T` (a family's own operation type).
    pub fn operation<T: 'static>(&self) -> Option<&'a T> {
        self.operation.and_then(RunningOperation::get)
    }
}
