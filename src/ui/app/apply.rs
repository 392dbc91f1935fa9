//! The one place that changes the editor's state: every action a panel,
//! a shortcut or a dialog pushed, applied in order.

use super::*;
use crate::device::speed::LiveSpeed;
use crate::project::LivePose;
use crate::ui::document::Undone;
use crate::ui::show::ShowAction;

impl StudioApp {
    /// Applies one action. The only place that changes the editor's state.
    pub fn apply(&mut self, action: Action) {
        match action {
            Action::Edit { edit, coalesce } => self.document.apply(edit, coalesce.as_deref()),
            Action::Undo | Action::Redo => self.undo_redo(action == Action::Undo),
            Action::Connect { port, baud } => {
                self.forget_link();
                self.connect(&port, baud);
            }
            Action::FindBoard { port, connect } => self.find_board(&port, connect),
            Action::FindEveryBoard => self.find_every_board(),
            Action::ConnectFound { port, family, baud } => {
                self.forget_link();
                self.connect_found(&port, family, baud);
            }
            Action::CancelConnect => {
                self.forget_link();
                if let Some(connecting) = self.links.connecting.take() {
                    self.say(|language| language.connect_cancelled(&connecting.opening.port.to_string()), false);
                }
            }
            Action::ConnectDemo => self.connect_demo(),
            Action::SetFamily(family) => self.set_family(family),
            Action::Disconnect => {
                self.forget_link();
                self.drop_link();
                self.say(|language| language.strings().msg_disconnected, false);
            }
            Action::Stop => self.stop(),
            Action::Resume => self.resume(),
            Action::Import(action) => self.desks.import.apply(action, &self.files.work, &self.document.project),
            Action::Show(action) if self.stopped() && action.moves_robots() => {
                self.say(|language| language.word("strings.msg_press_resume"), true);
            }
            Action::Show(action) => self.apply_show(action),
            Action::Sound(action) => self.apply_sound(action),
            Action::SetLanguage(language) => {
                self.language = language;
                // What the status line says, said again in the new language.
                if let Some(status) = &mut self.status {
                    status.reword(language);
                }
            }
            Action::SetLiveSpeed(deg_per_s) => self.live_speed = LiveSpeed { deg_per_s }.clamped(),
            Action::ShowTab(tab) => self.window.tab = tab,
            Action::UseGamepad(path) => self.use_gamepad(path),
            Action::PadTestMode(on) => self.desks.pad.test_mode = on,
            Action::BindPad(bind) => self.bind_pad(bind),
            Action::ShowView(open) => {
                let (_, family_ui) = self.parts(self.document.project.family);
                family_ui.layout_mut().view_open = open;
            }
            Action::AskFile(request) => self.ask_file(request),
            Action::CancelOperation => {
                if let Some(operation) = &self.operation {
                    operation.cancel();
                }
            }
            Action::NewProject
            | Action::Open(_)
            | Action::Save
            | Action::SaveAs(_)
            | Action::UnsavedSave
            | Action::UnsavedDiscard
            | Action::UnsavedCancel
            | Action::Recover
            | Action::DeclineRecovery
            | Action::Autosave
            | Action::Terminate => self.apply_file(action),
            // After STOP nothing that moves a robot goes out until Resume: refused, and said.
            Action::Family(action) if action.moves_robot() && self.stopped() => {
                self.say(|language| language.word("strings.msg_press_resume"), true);
            }
            Action::Family(action) => {
                let (mut shell, families) = self.split();
                families.get_mut(action.owner()).act(&mut shell, action);
            }
        }
    }

    /// The document's file, the unsaved-changes question, autosave and recovery, and the end.
    fn apply_file(&mut self, action: Action) {
        match action {
            Action::NewProject => self.guard_unsaved(AfterUnsaved::New),
            Action::Open(path) => self.guard_unsaved(AfterUnsaved::Open(path)),
            Action::Save => match self.document.path.clone() {
                Some(path) => self.save_to(path, None),
                None => self.apply(Action::AskFile(FileRequest::SaveAs)),
            },
            Action::SaveAs(path) => self.save_to(path, None),
            Action::UnsavedSave => {
                // Goes on once saved: after the Save as… just asked for, or a save to the file's own path.
                if let Some(next) = self.files.unsaved_prompt.clone() {
                    match self.files.continue_after_save(next) {
                        Ok(()) => {}
                        Err(next) => {
                            if let Some(path) = self.document.path.clone() {
                                self.save_to(path, Some(next));
                            }
                        }
                    }
                }
            }
            Action::UnsavedDiscard => {
                if let Some(next) = self.files.unsaved_prompt.take() {
                    self.after_unsaved(next);
                }
            }
            Action::UnsavedCancel => self.files.unsaved_prompt = None,
            Action::Recover => {
                if let Some(recovery) = self.files.recovery_offer.take() {
                    self.replace_document(recovery.project, recovery.path);
                    // Recovered work is unsaved until the user saves it.
                    self.document.dirty = true;
                    self.say(|language| language.strings().msg_recovered, false);
                }
            }
            Action::DeclineRecovery => {
                self.files.recovery_offer = None;
                self.files.clear_recovery_later();
            }
            // Nothing unsaved: nothing to keep.
            Action::Autosave if self.document.dirty => self.autosave_later(),
            Action::Terminate => self.terminate(),
            // Every other action is applied by `apply`.
            _ => {}
        }
    }

    /// Undo or redo one step; a turn in the 3D view is undone by moving the live pose back.
    fn undo_redo(&mut self, undo: bool) {
        let (mut shell, families) = self.split();
        // A turn in the 3D view is undone by moving the live pose back.
        let now = |pose: &LivePose| families.get(pose.family()).live_pose().unwrap_or_else(|| pose.clone());
        let undone = if undo { shell.document.undo(now) } else { shell.document.redo(now) };
        match undone {
            Some(Undone::Pose(pose)) => families.get_mut(pose.family()).restore_pose(&mut shell, pose),
            // A show's pass: the show window takes it back or joins it again.
            Some(Undone::Beside) if undo => self.desks.show.undo_pass(),
            Some(Undone::Beside) => self.desks.show.redo_pass(),
            Some(Undone::Project) | None => {}
        }
    }

    /// A show window's action, then what it made of the editor's history: a
    /// pass joined is one undo step (and an edit of the project when it was
    /// recorded on it); a show opened or closed takes its passes' steps with it.
    fn apply_show(&mut self, action: ShowAction) {
        let opens_or_closes = matches!(action, ShowAction::Open(_) | ShowAction::OpenProject | ShowAction::Close);
        if action == ShowAction::UndoPass {
            if self.document.beside_on_top() {
                self.undo_redo(true);
            }
            return;
        }
        if action == ShowAction::Remote(true) {
            self.lend_board_to_remote();
        }
        if let Some(said) = self.desks.show.apply(action, (&self.document.project, self.language), &self.window.waker) {
            self.status = Some(said);
        }
        if let Some(project) = self.desks.show.take_joined() {
            self.document.apply_beside(project);
        }
        if opens_or_closes {
            self.document.forget_beside();
        }
    }

    /// Asked to end from outside (Ctrl-C, kill, a closing session): the board
    /// first — a base stops and brakes as its link is dropped — then the work,
    /// into the recovery file, then the window, without asking.
    fn terminate(&mut self) {
        // Asked to end from outside (Ctrl-C, kill, a closing session): the board
        // first — a base stops and brakes as its link is dropped — then the work,
        // into the recovery file, then the window, without asking. An upload
        // running stops at its next safe point (never mid-packet); what it left
        // on the board, and how to restore the backup, go to the terminal.
        if let Some(operation) = &self.operation {
            operation.cancel();
            let summary = self.finish_operation(Some(TERMINATE_WAIT));
            let said = match summary {
                Some(said) => said.text,
                None => self.words().msg_operation_left_running.to_string(),
            };
            let _ = writeln!(std::io::stderr(), "servo-studio: {said}");
        }
        self.drop_link();
        self.apply(Action::Autosave);
        // The work must be on disk before the process goes.
        self.finish_file_work(Some(TERMINATE_WAIT));
        self.window.quit_allowed = true;
    }
}
