//! Servo Studio's own file picker, for a desktop that has no file-dialog
//! service (no desktop portal with a file chooser and no zenity: a bare X
//! session, a kiosk, some Raspberry Pi images), where the system's dialog
//! would never appear. A window lists a folder's folders and the files the
//! request is for — a project, a show, a sound, a mesh, a map, another tool's
//! file — to open one, or to name one to save (a file already there is
//! replaced only when asked twice). It reads folders when it enters them;
//! it writes nothing: the path chosen goes where the system's would.

use std::path::{Path, PathBuf};

use crate::ui::action::FileRequest;
use crate::ui::i18n::Language;

/// What the user did with the picker.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// This path was chosen.
    Chosen(PathBuf),
    /// Nothing was.
    Cancelled,
}

/// One thing in the folder shown.
#[derive(Clone, Debug, PartialEq, Eq)]
struct Entry {
    name: String,
    folder: bool,
}

/// The picker, open for one request.
#[derive(Debug)]
pub struct FileBrowser {
    /// A name is typed to save under (else a file is picked to open).
    saving: bool,
    /// The kind of file asked for, and the endings it may have.
    kind: String,
    extensions: Vec<String>,
    /// The folder shown, and the path typed above it.
    folder: PathBuf,
    typed_folder: String,
    entries: Vec<Entry>,
    /// The file name chosen or typed.
    name: String,
    /// Every file is listed, not only the kind asked for.
    every_file: bool,
    /// The name of a file that exists, saved over once asked again.
    replacing: Option<String>,
    /// Why the folder could not be read.
    unreadable: Option<String>,
}

impl FileBrowser {
    /// A picker for `request`, starting in `folder`.
    pub fn for_request(request: &FileRequest, folder: &Path) -> Self {
        let project = (crate::ui::action::PROJECT_FILE, vec!["json".to_string()]);
        let (saving, (kind, extensions), name) = match request {
            FileRequest::Open => (false, project, String::new()),
            FileRequest::SaveAs | FileRequest::SaveAsThenContinue => (true, project, "project.json".into()),
            FileRequest::Export(export) => {
                (true, (export.kind, vec![export.extension.to_string()]), export.name.clone())
            }
            FileRequest::Pick(pick) => {
                (false, (pick.kind, pick.extensions.iter().map(ToString::to_string).collect()), String::new())
            }
        };
        let mut browser = Self {
            saving,
            kind: kind.to_string(),
            extensions,
            folder: PathBuf::new(),
            typed_folder: String::new(),
            entries: Vec::new(),
            name,
            every_file: false,
            replacing: None,
            unreadable: None,
        };
        browser.enter(folder.to_path_buf());
        browser
    }

    /// Shows `folder`: its folders, then the files asked for, each by name.
    fn enter(&mut self, folder: PathBuf) {
        self.typed_folder = folder.display().to_string();
        self.replacing = None;
        match std::fs::read_dir(&folder) {
            Ok(read) => {
                let mut entries: Vec<Entry> = read
                    .flatten()
                    .filter_map(|entry| {
                        let name = entry.file_name().to_string_lossy().into_owned();
                        // Followed through links, as a dialog does.
                        let folder = std::fs::metadata(entry.path()).is_ok_and(|metadata| metadata.is_dir());
                        (!name.starts_with('.')).then_some(Entry { name, folder })
                    })
                    .collect();
                entries.sort_by(|a, b| {
                    b.folder.cmp(&a.folder).then_with(|| a.name.to_lowercase().cmp(&b.name.to_lowercase()))
                });
                self.entries = entries;
                self.unreadable = None;
                self.folder = folder;
            }
            Err(error) => self.unreadable = Some(format!("{}: {error}", folder.display())),
        }
    }

    /// Whether `name` is a file of the kind asked for.
    fn wanted(&self, name: &str) -> bool {
        self.every_file
            || self.extensions.iter().any(|extension| {
                Path::new(name).extension().is_some_and(|ending| ending.eq_ignore_ascii_case(extension.as_str()))
            })
    }

    /// The path chosen now, if one can be: the name typed or picked, in the folder shown.
    fn chosen(&self) -> Option<PathBuf> {
        let name = self.name.trim();
        (!name.is_empty()).then(|| self.folder.join(name))
    }

    /// Draws the picker; what the user did, once they did.
    pub fn ui(&mut self, ctx: &egui::Context, language: Language) -> Option<Outcome> {
        let title = language.word(if self.saving { "browser.title_save" } else { "browser.title_open" });
        let mut outcome = None;
        let mut open = true;
        egui::Window::new(title)
            .id(egui::Id::unique("file browser"))
            .collapsible(false)
            .default_size([640.0, 440.0])
            .anchor(egui::Align2::CENTER_CENTER, [0.0, 0.0])
            .open(&mut open)
            .show(ctx, |ui| outcome = self.contents(ui, language));
        if !open {
            outcome = Some(Outcome::Cancelled);
        }
        outcome
    }

    /// Up, Home and the folder typed: where to go, if asked.
    fn folder_bar(&mut self, ui: &mut egui::Ui, language: Language) -> Option<PathBuf> {
        let mut go_to = None;
        ui.horizontal(|ui| {
            if ui.button(language.word("browser.up")).clicked()
                && let Some(parent) = self.folder.parent()
            {
                go_to = Some(parent.to_path_buf());
            }
            if ui.button(language.word("browser.home")).clicked()
                && let Some(home) = home()
            {
                go_to = Some(home);
            }
            let folder_label = ui.label(language.word("browser.folder"));
            let typed = ui
                .add(egui::TextEdit::singleline(&mut self.typed_folder).desired_width(f32::INFINITY))
                .labelled_by(folder_label.id);
            if typed.lost_focus() && ui.input(|input| input.key_pressed(egui::Key::Enter)) {
                go_to = Some(PathBuf::from(self.typed_folder.trim()));
            }
        });
        go_to
    }

    /// The folder's entries (folders, and the files wanted): a folder clicked
    /// goes into `go_to`, a file clicked is the name, a file double-clicked is chosen.
    fn listing(&mut self, ui: &mut egui::Ui, language: Language, go_to: &mut Option<PathBuf>) -> Option<Outcome> {
        let mut outcome = None;
        let listed_height = (ui.available_height() - 90.0).max(120.0);
        egui::ScrollArea::vertical().max_height(listed_height).auto_shrink([false, false]).show(ui, |ui| {
            let mut shown = 0;
            for entry in self.entries.clone() {
                if !entry.folder && !self.wanted(&entry.name) {
                    continue;
                }
                shown += 1;
                // A folder reads as one (a path's slash), in any script and any font.
                let shown_as = if entry.folder { format!("{}/", entry.name) } else { entry.name.clone() };
                let selected = !entry.folder && entry.name == self.name;
                let row = ui.selectable_label(selected, shown_as);
                if entry.folder && (row.double_clicked() || row.clicked()) {
                    *go_to = Some(self.folder.join(&entry.name));
                } else if row.clicked() {
                    self.name.clone_from(&entry.name);
                    self.replacing = None;
                } else if row.double_clicked() {
                    self.name.clone_from(&entry.name);
                    outcome = self.confirm();
                }
            }
            if shown == 0 {
                ui.weak(language.word("browser.empty"));
            }
        });
        outcome
    }

    fn contents(&mut self, ui: &mut egui::Ui, language: Language) -> Option<Outcome> {
        let mut go_to = self.folder_bar(ui, language);
        ui.separator();
        let mut outcome = self.listing(ui, language, &mut go_to);
        if let Some(folder) = go_to {
            self.enter(folder);
        }
        ui.separator();
        ui.horizontal(|ui| {
            let name_label = ui.label(language.word("browser.name"));
            let typed = ui
                .add_enabled(
                    self.saving,
                    egui::TextEdit::singleline(&mut self.name).desired_width(320.0).hint_text(self.kind.as_str()),
                )
                .labelled_by(name_label.id);
            if typed.changed() {
                self.replacing = None;
            }
            if self.saving && typed.lost_focus() && ui.input(|input| input.key_pressed(egui::Key::Enter)) {
                outcome = self.confirm();
            }
            ui.checkbox(&mut self.every_file, language.word("browser.every_file"));
        });
        if let Some(why) = &self.unreadable {
            ui.colored_label(ui.visuals().error_fg_color, crate::say!(language, "browser.unreadable", why));
        }
        if let Some(name) = &self.replacing {
            ui.colored_label(ui.visuals().warn_fg_color, crate::say!(language, "browser.replace", name));
        }
        ui.horizontal(|ui| {
            let confirm = language.word(if self.saving { "browser.save" } else { "browser.open" });
            if ui.add_enabled(self.chosen().is_some(), egui::Button::new(confirm)).clicked() {
                outcome = self.confirm();
            }
            if ui.button(language.word("browser.cancel")).clicked() {
                outcome = Some(Outcome::Cancelled);
            }
            ui.weak(format!("{} (*.{})", self.kind, self.extensions.join(", *.")));
        });
        outcome
    }

    /// The path chosen, if it may be taken now: to open, a file that is there;
    /// to save, a name not there, or one there asked for twice (then replaced).
    fn confirm(&mut self) -> Option<Outcome> {
        let path = self.chosen()?;
        if path.is_dir() {
            self.enter(path);
            return None;
        }
        if !self.saving {
            return path.is_file().then_some(Outcome::Chosen(path));
        }
        if path.exists() && self.replacing.as_deref() != Some(self.name.trim()) {
            self.replacing = Some(self.name.trim().to_string());
            return None;
        }
        Some(Outcome::Chosen(path))
    }
}

/// The user's home folder.
fn home() -> Option<PathBuf> {
    std::env::var_os("HOME").or_else(|| std::env::var_os("USERPROFILE")).map(PathBuf::from)
}

/// Why the system's file dialog cannot appear here, if it cannot: on Linux
/// it needs a desktop portal that has a file chooser (on a session bus), or
/// zenity (rfd falls back to it); elsewhere the system always has one. What
/// to install, when so.
pub fn no_system_dialog() -> Option<&'static str> {
    #[cfg(all(unix, not(target_os = "macos")))]
    {
        let on_path = std::env::var_os("PATH")
            .is_some_and(|path| std::env::split_paths(&path).any(|folder| folder.join("zenity").is_file()));
        let bus = std::env::var_os("DBUS_SESSION_BUS_ADDRESS").is_some()
            || std::env::var_os("XDG_RUNTIME_DIR").is_some_and(|runtime| Path::new(&runtime).join("bus").exists());
        let data_dirs: Vec<PathBuf> = std::env::var_os("XDG_DATA_DIRS").filter(|dirs| !dirs.is_empty()).map_or_else(
            || vec![PathBuf::from("/usr/local/share"), PathBuf::from("/usr/share")],
            |dirs| std::env::split_paths(&dirs).collect(),
        );
        return judged(on_path, bus, &data_dirs);
    }
    #[allow(unreachable_code)]
    None
}

/// What to install for a system file dialog, given whether zenity is on the
/// path, a session bus is there, and the data folders a portal is looked for in.
fn judged(zenity: bool, bus: bool, data_dirs: &[PathBuf]) -> Option<&'static str> {
    if zenity {
        return None;
    }
    let portal =
        data_dirs.iter().any(|dir| dir.join("dbus-1/services/org.freedesktop.portal.Desktop.service").is_file());
    let chooser = data_dirs.iter().any(|dir| {
        std::fs::read_dir(dir.join("xdg-desktop-portal/portals")).is_ok_and(|portals| {
            portals.flatten().any(|portal| {
                std::fs::read_to_string(portal.path())
                    .is_ok_and(|text| text.contains("org.freedesktop.impl.portal.FileChooser"))
            })
        })
    });
    (!(bus && portal && chooser))
        .then_some("xdg-desktop-portal-gtk (or another desktop portal with a file chooser), or zenity")
}

#[cfg(test)]
mod tests {
    use super::*;
    use egui_kittest::Harness;
    use egui_kittest::kittest::Queryable;

    fn folder_with_files() -> tempfile::TempDir {
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir(dir.path().join("shows")).unwrap();
        std::fs::write(dir.path().join("skull.json"), "{}").unwrap();
        std::fs::write(dir.path().join("notes.txt"), "").unwrap();
        std::fs::write(dir.path().join("shows/finale.json"), "{}").unwrap();
        dir
    }

    /// The picker in a harness of its own; what it answered lands in the state.
    fn picker(browser: FileBrowser) -> Harness<'static, (FileBrowser, Option<Outcome>)> {
        Harness::builder().with_size(egui::vec2(900.0, 600.0)).build_ui_state(
            |ui, (browser, outcome): &mut (FileBrowser, Option<Outcome>)| {
                if outcome.is_none() {
                    *outcome = browser.ui(ui.ctx(), Language::English);
                }
            },
            (browser, None),
        )
    }

    #[test]
    fn a_project_is_opened_from_a_folder_entered_and_other_files_are_not_offered() {
        let dir = folder_with_files();
        let mut harness = picker(FileBrowser::for_request(&FileRequest::Open, dir.path()));
        harness.run();
        assert!(harness.query_by_label_contains("notes.txt").is_none(), "only the kind asked for");
        harness.get_by_label_contains("shows").click();
        harness.run();
        assert_eq!(harness.state().0.folder, dir.path().join("shows"));
        harness.get_by_label_contains("finale.json").click();
        harness.run();
        harness.get_by_label("Open").click();
        harness.run();
        assert_eq!(harness.state().1, Some(Outcome::Chosen(dir.path().join("shows/finale.json"))));
    }

    #[test]
    fn a_name_is_typed_to_save_and_a_file_there_is_replaced_only_when_asked_twice() {
        let dir = folder_with_files();
        let mut harness = picker(FileBrowser::for_request(&FileRequest::SaveAs, dir.path()));
        harness.run();
        harness.get_by_label_contains("skull.json").click();
        harness.run();
        harness.get_by_label("Save").click();
        harness.run();
        assert_eq!(harness.state().1, None, "not at once: it is there");
        assert!(harness.query_by_label_contains("skull.json exists").is_some());
        harness.get_by_label("Save").click();
        harness.run();
        assert_eq!(harness.state().1, Some(Outcome::Chosen(dir.path().join("skull.json"))));
        // A new name: at once.
        let mut harness = picker(FileBrowser::for_request(&FileRequest::SaveAs, dir.path()));
        harness.run();
        harness.state_mut().0.name = "new.json".into();
        harness.run();
        harness.get_by_label("Save").click();
        harness.run();
        assert_eq!(harness.state().1, Some(Outcome::Chosen(dir.path().join("new.json"))));
    }

    #[test]
    fn the_system_dialog_is_there_with_zenity_or_a_portal_that_has_a_file_chooser_on_a_bus() {
        let share = tempfile::tempdir().unwrap();
        let dirs = [share.path().to_path_buf()];
        assert!(judged(false, true, &dirs).is_some(), "a bare X session: nothing");
        assert_eq!(judged(true, false, &dirs), None, "zenity alone does");
        std::fs::create_dir_all(share.path().join("dbus-1/services")).unwrap();
        std::fs::write(share.path().join("dbus-1/services/org.freedesktop.portal.Desktop.service"), "").unwrap();
        assert!(judged(false, true, &dirs).is_some(), "a portal with no backend that chooses files: nothing");
        std::fs::create_dir_all(share.path().join("xdg-desktop-portal/portals")).unwrap();
        std::fs::write(
            share.path().join("xdg-desktop-portal/portals/gtk.portal"),
            "[portal]\nInterfaces=org.freedesktop.impl.portal.FileChooser;org.freedesktop.impl.portal.AppChooser\n",
        )
        .unwrap();
        assert_eq!(judged(false, true, &dirs), None, "a portal that chooses files, on a bus");
        assert!(judged(false, false, &dirs).is_some(), "no session bus: no portal");
    }

    #[test]
    fn a_folder_that_cannot_be_read_is_said_and_cancel_chooses_nothing() {
        let dir = folder_with_files();
        let mut browser = FileBrowser::for_request(&FileRequest::Open, dir.path());
        browser.enter(dir.path().join("no such folder"));
        assert_eq!(browser.folder, dir.path(), "still where it was");
        let mut harness = picker(browser);
        harness.run();
        assert!(harness.query_by_label_contains("cannot read").is_some());
        harness.get_by_label("Cancel").click();
        harness.run();
        assert_eq!(harness.state().1, Some(Outcome::Cancelled));
    }
}
