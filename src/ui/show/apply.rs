//! What the show window's actions do: `ShowDesk::apply`, one arm an action,
//! each longer one in a function of its own.

use std::path::PathBuf;

use super::{Linked, ShowAction, ShowDesk};
use crate::link::Waker;
use crate::project::Project;
use crate::show::Show;
use crate::ui::i18n::{Language, Worded};
use crate::ui::shell::StatusLine;

impl ShowDesk {
    /// Takes an action of the window; `project` is the open one, `waker` repaints when a show says something.
    pub fn apply(
        &mut self,
        action: ShowAction,
        (project, language): (&Project, Language),
        waker: &Waker,
    ) -> Option<StatusLine> {
        match action {
            ShowAction::Open(path) => return self.open(path, language),
            ShowAction::OpenProject => self.opened_project(project),
            ShowAction::AddOpenProject => self.add_open_project(project),
            ShowAction::AddFromFile(path) => return self.add_from(&path, language),
            ShowAction::Boards(true) => return self.connect_boards(language, waker),
            ShowAction::Boards(false) => self.let_boards_go(),
            ShowAction::RemoteWindow => self.remote.open = true,
            ShowAction::Remote(true) => return self.serve(project, language, waker),
            ShowAction::Remote(false) => {
                self.remote.stop(None);
                // The boards remote control connected go with it; boards the user connected stay.
                if self.boards_for_remote {
                    self.let_boards_go();
                }
            }
            ShowAction::Play => self.play(waker.clone()),
            ShowAction::StopAll => self.stop(),
            ShowAction::Preview(true) => self.start_preview(waker),
            ShowAction::Preview(false) => self.stage.stop_preview(),
            ShowAction::RecordPass(true) => {
                let Some(session) = &self.session else { return None };
                if self.passes.begin(&session.show, self.stage.scrub_ms) {
                    return self.apply(ShowAction::Preview(true), (project, language), waker);
                }
            }
            ShowAction::RecordPass(false) => self.end_pass(),
            // The editor's Undo takes a pass back (one history): see `undo_pass`.
            ShowAction::UndoPass => {}
            ShowAction::Save(path) => return self.save(path, language),
            ShowAction::Close => {
                self.stop();
                self.let_boards_go();
                self.session = None;
            }
        }
        None
    }

    /// Opens the show at `path`, or says why not.
    fn open(&mut self, path: PathBuf, language: Language) -> Option<StatusLine> {
        match Show::open(&path) {
            Ok(show) => self.opened(Some(path), show),
            Err(error) => {
                let said = |language: Language| format!("{}: {}", path.display(), error.worded(language));
                return Some(StatusLine::worded(language, said, true));
            }
        }
        None
    }

    /// The open project joins the show as a device (the editor's, when it is the first).
    fn add_open_project(&mut self, project: &Project) {
        if let Some(session) = &mut self.session {
            let name = session.add("board", project.clone());
            // One device is the editor's project: the first added.
            if session.editor_index().is_none() {
                session.editor = Some(name);
            }
        }
    }

    /// Connects every device of the show on its port, or says why not.
    fn connect_boards(&mut self, language: Language, waker: &Waker) -> Option<StatusLine> {
        let session = self.session.as_ref()?;
        self.linked = None;
        self.boards_for_remote = false;
        match Linked::connect(&session.with_ports(), waker.clone()) {
            Ok(linked) => self.linked = Some(linked),
            Err(error) => {
                let said = |language: Language| crate::say!(language, "show_said.cannot_connect", error);
                return Some(StatusLine::worded(language, said, true));
            }
        }
        None
    }

    /// The preview starts, with the show's sound where it has one.
    fn start_preview(&mut self, waker: &Waker) {
        let Some(session) = &self.session else { return };
        let folder = session.path.as_ref().and_then(|path| path.parent());
        let sound =
            session.show.sound.as_ref().map(|track| (crate::ui::sound::resolve(&track.path, folder), track.offset_ms));
        self.stage.start_preview(sound, waker);
    }

    /// Saves the show to `path` (atomically), or says why not.
    fn save(&mut self, path: PathBuf, language: Language) -> Option<StatusLine> {
        let session = self.session.as_mut()?;
        let text = session.show.to_json();
        if let Err(error) = crate::project::atomic_write_all(&[(path.as_path(), text.as_bytes())]) {
            let said =
                |language: Language| crate::say!(language, "show_said.cannot_save", file = path.display(), error);
            return Some(StatusLine::worded(language, said, true));
        }
        session.path = Some(path);
        None
    }
}
