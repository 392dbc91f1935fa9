//! Files and the window's chrome: open / save / unsaved-changes question,
//! autosave, dropped files, the File menu, dialogs and shortcuts.

use super::*;
use crate::ui::file_browser::{FileBrowser, Outcome};

impl StudioApp {
    pub(super) fn replace_document(&mut self, project: Project, path: Option<PathBuf>) {
        self.document = Document::new(project, path);
        self.each_family(|family_ui, shell| family_ui.document_replaced(&shell.document.project));
    }

    /// What a file read off the frame gave.
    pub(super) fn opened(
        &mut self,
        path: PathBuf,
        result: Result<crate::project::input::Opened, crate::project::input::OpenError>,
    ) {
        use crate::project::input::InputKind;
        match result {
            Ok(opened) => {
                let loaded = opened.loaded;
                let unknown = loaded.unknown_key_count();
                if unknown == 0 {
                    self.say(|language| format!("{} {}", language.strings().msg_opened, path.display()), false);
                } else {
                    // A misspelt key changes nothing in the editor: say so.
                    self.say(|language| language.opened_with_unknown_keys(&path, &loaded.unknown_keys, unknown), true);
                }
                match opened.kind {
                    InputKind::ProjectFile => {
                        files::remember(&mut self.files.recent, &path);
                        self.replace_document(loaded.project, Some(path));
                    }
                    // The PLEN community's motion.json (one file, or a folder of them) opens
                    // as a new, unsaved PLEN2 project.
                    InputKind::Motions => {
                        self.replace_document(loaded.project, None);
                        self.document.dirty = true;
                    }
                }
            }
            Err(error) => self.say(|language| language.open_error(&path, &error), true),
        }
    }

    pub(super) fn after_unsaved(&mut self, next: AfterUnsaved) {
        match next {
            AfterUnsaved::New => {
                self.replace_document(Project::empty(self.document.project.family), None);
                self.say(|language| language.strings().msg_new_project, false);
            }
            AfterUnsaved::Open(path) => self.files.open_later(path),
            AfterUnsaved::Quit => {
                self.files.clear_recovery_later();
                self.window.quit_allowed = true;
            }
        }
    }

    /// Asks about unsaved changes before `next`, or does it at once.
    pub(super) fn guard_unsaved(&mut self, next: AfterUnsaved) {
        if self.document.dirty {
            self.files.unsaved_prompt = Some(next);
        } else {
            self.after_unsaved(next);
        }
    }

    /// Writes the recovery file if there are unsaved changes and it is due.
    pub fn autosave_if_due(&mut self, now: Instant) {
        if self.document.dirty && now.saturating_duration_since(self.files.last_autosave) >= AUTOSAVE_EVERY {
            self.apply(Action::Autosave);
            self.files.last_autosave = now;
        }
    }

    /// Dropped files, the window's close button, and the autosave tick.
    pub(super) fn file_events(&mut self, ui: &egui::Ui, now: Instant, actions: &mut Vec<Action>) {
        let dropped: Vec<PathBuf> = ui.ctx().input(|input| {
            input
                .raw
                .dropped_files
                .iter()
                .map(|file| file.path().to_path_buf())
                .filter(|path| !path.as_os_str().is_empty())
                .collect()
        });
        if let Some(path) = dropped.into_iter().next() {
            actions.push(Action::Open(path));
        }
        if ui.ctx().input(|input| input.viewport().close_requested())
            && self.document.dirty
            && !self.window.quit_allowed
        {
            ui.ctx().send_viewport_cmd(egui::ViewportCommand::CancelClose);
            self.files.unsaved_prompt = Some(AfterUnsaved::Quit);
        }
        self.autosave_if_due(now);
    }

    pub(super) fn file_menu(&self, ui: &mut egui::Ui, actions: &mut Vec<Action>) {
        let words = self.language.strings();
        ui.menu_button(words.file, |ui| {
            if ui.button(words.new_project).clicked() {
                actions.push(Action::NewProject);
            }
            // Dialogs open off the frame: the window keeps drawing (and a base keeps
            // being watched) while the user looks for a file.
            let asking = self.asking_for_file();
            if ui.add_enabled(!asking, egui::Button::new(words.open)).clicked() {
                actions.push(Action::AskFile(FileRequest::Open));
            }
            if ui.button(words.save).clicked() {
                actions.push(Action::Save);
            }
            if ui.add_enabled(!asking, egui::Button::new(words.save_as)).clicked() {
                actions.push(Action::AskFile(FileRequest::SaveAs));
            }
            ui.separator();
            let import = crate::ui::import::words(self.language).title;
            if ui.add_enabled(!asking, egui::Button::new(import)).clicked() {
                actions.push(crate::ui::import::ask_file(self.language));
            }
            let export = crate::ui::import::words(self.language).export_title;
            if ui.button(export).clicked() {
                actions.push(Action::Import(crate::ui::action::ImportAction::OpenExport));
            }
            ui.separator();
            let show = crate::ui::show::words(self.language).title;
            if ui.add_enabled(!asking, egui::Button::new(show)).clicked() {
                actions.push(Action::AskFile(FileRequest::Pick(crate::ui::action::Pick {
                    kind: self.language.word("files.show_or_project"),
                    extensions: &["json"],
                    then: std::sync::Arc::new(|path| Action::Show(crate::ui::show::ShowAction::Open(path))),
                })));
            }
            if !self.files.recent.is_empty() {
                ui.separator();
                ui.label(words.recent);
                for path in &self.files.recent {
                    if ui.button(path.display().to_string()).clicked() {
                        actions.push(Action::Open(path.clone()));
                    }
                }
            }
        });
    }

    /// Settings: the live speed limit, remote control.
    pub(super) fn settings_menu(&self, ui: &mut egui::Ui, actions: &mut Vec<Action>) {
        let words = self.language.strings();
        ui.menu_button(words.settings, |ui| {
            ui.horizontal(|ui| {
                let label = ui.label(words.live_speed_limit);
                let mut deg_per_s = self.live_speed.deg_per_s();
                let drag = egui::DragValue::new(&mut deg_per_s)
                    .range(crate::device::speed::RANGE_DEG_PER_S)
                    .speed(1.0)
                    .suffix(" °/s");
                let response = ui.add(drag).labelled_by(label.id).on_hover_text(words.live_speed_hint);
                if response.changed() {
                    actions.push(Action::SetLiveSpeed(deg_per_s));
                }
            });
            if ui.button(crate::ui::show::words(self.language).remote_menu).clicked() {
                actions.push(Action::Show(crate::ui::show::ShowAction::RemoteWindow));
                ui.close();
            }
        });
    }

    /// The "unsaved changes" question and the recovery offer.
    pub(super) fn dialogs(&self, ui: &egui::Ui, actions: &mut Vec<Action>) {
        let words = self.language.strings();
        if let Some(recovery) = &self.files.recovery_offer {
            egui::Window::new(words.recover_title).collapsible(false).resizable(false).show(ui.ctx(), |ui| {
                let file = recovery.path.as_ref().map_or_else(|| "—".to_string(), |p| p.display().to_string());
                ui.label(format!("{} {} ({file})", words.recover_body, recovery.saved_at));
                ui.horizontal(|ui| {
                    if ui.button(words.recover).clicked() {
                        actions.push(Action::Recover);
                    }
                    if ui.button(words.discard).clicked() {
                        actions.push(Action::DeclineRecovery);
                    }
                });
            });
        }
        if self.files.unsaved_prompt.is_some() {
            egui::Window::new(words.unsaved_title).collapsible(false).resizable(false).show(ui.ctx(), |ui| {
                ui.label(words.unsaved_question);
                ui.horizontal(|ui| {
                    if self.document.path.is_some() {
                        if ui.button(words.save).clicked() {
                            actions.push(Action::UnsavedSave);
                        }
                    } else if ui.add_enabled(self.files.dialog.is_none(), egui::Button::new(words.save_as)).clicked() {
                        actions.push(Action::AskFile(FileRequest::SaveAsThenContinue));
                    }
                    if ui.button(words.discard).clicked() {
                        actions.push(Action::UnsavedDiscard);
                    }
                    if ui.button(words.cancel).clicked() {
                        actions.push(Action::UnsavedCancel);
                    }
                });
            });
        }
    }

    pub(super) fn shortcuts(ui: &egui::Ui, actions: &mut Vec<Action>) {
        ui.input_mut(|input| {
            if input.consume_key(egui::Modifiers::NONE, egui::Key::Escape) {
                actions.push(Action::Stop);
            }
            if input.consume_key(egui::Modifiers::COMMAND | egui::Modifiers::SHIFT, egui::Key::Z)
                || input.consume_key(egui::Modifiers::COMMAND, egui::Key::Y)
            {
                actions.push(Action::Redo);
            }
            if input.consume_key(egui::Modifiers::COMMAND, egui::Key::Z) {
                actions.push(Action::Undo);
            }
        });
    }

    /// Asks for a file: the system's dialog, or — where none can appear —
    /// the editor's own picker, starting in the document's folder (said once).
    pub(super) fn ask_file(&mut self, request: FileRequest) {
        let Some(install) = self.files.no_system_dialog else {
            let answer = (self.files.picker)(&request, self.window.waker.clone());
            self.files.dialog = Some((request, answer));
            return;
        };
        if self.files.browser.is_none() {
            self.say(|language| crate::say!(language, "browser.no_service", install), false);
        }
        let folder = self.document.path.as_deref().and_then(std::path::Path::parent).map_or_else(
            || std::env::var_os("HOME").map_or_else(|| PathBuf::from("."), PathBuf::from),
            std::path::Path::to_path_buf,
        );
        let browser = FileBrowser::for_request(&request, &folder);
        self.files.browser = Some((request, browser));
    }

    /// Draws the editor's own file picker when it is open; its answer's actions.
    pub(super) fn file_browser(&mut self, ctx: &egui::Context, actions: &mut Vec<Action>) {
        let Some((_, browser)) = &mut self.files.browser else { return };
        let Some(outcome) = browser.ui(ctx, self.language) else { return };
        let Some((request, _)) = self.files.browser.take() else { return };
        if let Outcome::Chosen(path) = outcome {
            actions.extend(dialogs::answered(&request, path));
        }
    }

    /// Takes the answer of an open file dialog: the actions that waited for it.
    pub(super) fn poll_dialog(&mut self, actions: &mut Vec<Action>) {
        let Some((_, answer)) = &self.files.dialog else { return };
        let chosen = match answer.try_recv() {
            Ok(chosen) => chosen,
            Err(crossbeam_channel::TryRecvError::Empty) => return,
            // The dialog's thread ended without an answer: nothing was chosen.
            Err(crossbeam_channel::TryRecvError::Disconnected) => None,
        };
        let Some((request, _)) = self.files.dialog.take() else { return };
        if let Some(path) = chosen {
            actions.extend(dialogs::answered(&request, path));
        }
    }

    /// Whether a file dialog (the system's or the editor's own) is open.
    pub fn asking_for_file(&self) -> bool {
        self.files.dialog.is_some() || self.files.browser.is_some()
    }
}
