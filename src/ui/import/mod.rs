//! File → Import from another tool…: a Maestro settings file, a RoboPlus
//! `.mtn`, an R+ Motion `.mtnx` or Blender add-on JSON is read off the frame,
//! its joint map (guessed from ids and names) is edited in a table while a 3D
//! figure plays the motion through it, and Create adds what it makes to the
//! open project as one undo step. The desk keeps its own state; the shell
//! hands it its actions and takes back what it finished (`poll`).

mod check;
use check::{Checked, landings};
mod export;
mod played;
mod table;
mod words;

use std::path::PathBuf;
use std::sync::Arc;

use crossbeam_channel::Receiver;

use crate::device::plen2::playback::DEVICE_IDS;
use crate::figure::{self, Chain};
use crate::interchange::build::{self, Built, Options, Selection};
use crate::interchange::map::{JointMap, Target};
use crate::interchange::{Body, Format, Source, preview};
use crate::project::input::{MAX_PROJECT_BYTES, read_bytes, read_text};
use crate::project::{Family, Project};
pub use crate::ui::action::ImportAction;
use crate::ui::action::{Action, Export, FileRequest, Pick};
use crate::ui::files::FileWork;
use crate::ui::i18n::Language;
use crate::ui::view3d::{Scene, View};
pub use export::{ExportSession, ExportTo};
pub use words::{ImportWords, note, words};

/// What the desk finished, for the shell.
#[derive(Debug)]
pub enum Finished {
    /// Something could not be done: the status line says it.
    Failed(String),
    /// A conversion to add to the project.
    Built(Box<Built>),
    /// The joint map was written.
    MapSaved(PathBuf),
    /// An export was written: where, and what it holds.
    Exported(PathBuf, crate::interchange::Report),
}

/// An open import: the file, its map, and where the preview is.
#[derive(Debug)]
pub struct Session {
    /// The file read.
    pub path: PathBuf,
    /// What it holds.
    pub source: Source,
    /// The project's family when it was opened.
    pub family: Family,
    /// The joint map being edited.
    pub map: JointMap,
    /// The clip previewed and converted (`None`: all of them).
    pub clip: Option<usize>,
    /// Fitted animations' tolerance, degrees.
    pub tolerance_deg: f64,
    /// The preview's time, ms.
    pub time_ms: f64,
    /// Whether the preview plays.
    pub playing: bool,
    /// What Create made: the report, shown until the window is closed.
    pub done: Option<crate::interchange::Report>,
}

/// The import desk: a file being read, the open session, work running.
#[derive(Default)]
pub struct ImportDesk {
    reading: Option<(PathBuf, Receiver<Result<Source, String>>)>,
    loading_map: Option<Receiver<Result<JointMap, String>>>,
    saving_map: Option<(PathBuf, Receiver<Result<(), String>>)>,
    building: Option<Receiver<Result<Built, String>>>,
    writing_export: Option<(PathBuf, Receiver<Result<crate::interchange::Report, String>>)>,
    /// The export window's choices, when open.
    pub exporting: Option<ExportSession>,
    /// The window's content, when open.
    pub session: Option<Session>,
    view: View,
    plen2_chain: Option<Chain>,
    /// What the board will play of the session as it stands: worked out off the frame.
    checking: Option<(u64, Receiver<Checked>)>,
    /// The last of it, for the choices it was worked out for (their hash).
    checked: Option<(u64, Checked)>,
}

impl std::fmt::Debug for ImportDesk {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ImportDesk").field("session", &self.session).finish_non_exhaustive()
    }
}

/// The file dialog for File → Import from another tool….
pub fn ask_file(language: Language) -> Action {
    Action::AskFile(FileRequest::Pick(Pick {
        kind: language.word("files.other_tools"),
        extensions: &["xml", "txt", "mtn", "mtnx", "json"],
        then: Arc::new(|path| Action::Import(ImportAction::Read(path))),
    }))
}

fn read_source(path: &std::path::Path) -> Result<Source, String> {
    let bytes = read_bytes(path, MAX_PROJECT_BYTES).map_err(|error| error.to_string())?;
    let decoded = crate::interchange::text::decode(bytes).map_err(|error| format!("{}: {error}", path.display()))?;
    let format = Format::guess(&decoded.text).ok_or_else(|| {
        format!("{} is not a file Servo Studio can import (a Maestro settings file, RoboPlus .mtn, R+ Motion .mtnx or Blender servo-animation JSON)", path.display())
    })?;
    crate::interchange::read_decoded(Some(format), &decoded)
        .map_err(|error| format!("{} ({}): {error} — {}", path.display(), format.name(), error.what_to_try(format)))?
        .ok_or_else(|| path.display().to_string())
}

impl ImportDesk {
    /// Takes an action of the import window.
    pub fn apply(&mut self, action: ImportAction, files: &FileWork, project: &Project) {
        match action {
            ImportAction::Read(path) => {
                let reading = path.clone();
                self.reading = Some((path, files.run(move |_| read_source(&reading))));
            }
            ImportAction::LoadMap(path) => {
                self.loading_map = Some(files.run(move |_| {
                    let text = read_text(&path, MAX_PROJECT_BYTES).map_err(|error| error.to_string())?;
                    JointMap::from_json(&text).map_err(|error| format!("{}: {error}", path.display()))
                }));
            }
            ImportAction::SaveMap(path) => {
                let Some(session) = &self.session else { return };
                let bytes = session.map.to_json().into_bytes();
                let writing = path.clone();
                let done = files.run(move |writer| writer(&writing, &bytes).map_err(|error| error.to_string()));
                self.saving_map = Some((path, done));
            }
            ImportAction::Create => {
                let Some(session) = &self.session else { return };
                let source = session.source.clone();
                let map = session.map.clone();
                let selection = session
                    .clip
                    .map_or(Selection::All, |clip| Selection::Named(session.source.clips[clip].name.clone()));
                let options = Options { family: project.family, selection, tolerance_deg: session.tolerance_deg };
                self.building =
                    Some(files.run(move |_| build::build(&source, &map, &options).map_err(|error| error.to_string())));
            }
            ImportAction::Close => {
                self.session = None;
                self.view = View::default();
            }
            ImportAction::OpenExport => self.exporting = Some(ExportSession::new(project)),
            ImportAction::CloseExport => self.exporting = None,
            ImportAction::Export(path) => {
                let Some(session) = self.exporting.clone() else { return };
                let project = project.clone();
                let writing = path.clone();
                let done = files.run(move |writer| {
                    let (text, report) = export::exported(&session, &project)?;
                    writer(&writing, text.as_bytes())
                        .map_err(|error| format!("cannot write {}: {error}", writing.display()))?;
                    Ok(report)
                });
                self.writing_export = Some((path, done));
            }
        }
    }

    /// Whether work runs (the window keeps repainting until it ends).
    pub fn busy(&self) -> bool {
        self.reading.is_some()
            || self.loading_map.is_some()
            || self.saving_map.is_some()
            || self.building.is_some()
            || self.writing_export.is_some()
    }

    /// Takes what finished off the frame; `family` is the project's.
    pub fn poll(&mut self, family: Family) -> Vec<Finished> {
        let mut finished = Vec::new();
        if let Some((path, done)) = &self.reading
            && let Some(result) = taken(done)
        {
            let path = path.clone();
            self.reading = None;
            match result {
                Ok(source) => {
                    let map = JointMap::for_source(&source, family, None);
                    let clip = if source.clips.len() > 1 { None } else { Some(0).filter(|_| !source.clips.is_empty()) };
                    self.session = Some(Session {
                        path,
                        source,
                        family,
                        map,
                        clip,
                        tolerance_deg: 1.0,
                        time_ms: 0.0,
                        playing: false,
                        done: None,
                    });
                    self.view = View::default();
                }
                Err(error) => finished.push(Finished::Failed(error)),
            }
        }
        if let Some(done) = &self.loading_map
            && let Some(result) = taken(done)
        {
            self.loading_map = None;
            match (result, self.session.as_mut()) {
                (Ok(map), Some(session)) => {
                    session.map = JointMap::for_source(&session.source, session.family, Some(&map));
                }
                (Err(error), _) => finished.push(Finished::Failed(error)),
                (Ok(_), None) => {}
            }
        }
        if let Some((path, done)) = &self.saving_map
            && let Some(result) = taken(done)
        {
            let path = path.clone();
            self.saving_map = None;
            finished.push(result.map_or_else(Finished::Failed, |()| Finished::MapSaved(path)));
        }
        if let Some((path, done)) = &self.writing_export
            && let Some(result) = taken(done)
        {
            let path = path.clone();
            self.writing_export = None;
            finished.push(result.map_or_else(Finished::Failed, |report| Finished::Exported(path, report)));
        }
        if let Some((key, done)) = &self.checking
            && let Some(result) = taken(done)
        {
            self.checked = Some((*key, result));
            self.checking = None;
        }
        if let Some(done) = &self.building
            && let Some(result) = taken(done)
        {
            self.building = None;
            finished.push(result.map_or_else(Finished::Failed, |built| Finished::Built(Box::new(built))));
        }
        finished
    }

    /// Shows what Create made, until the window is closed.
    pub fn created(&mut self, report: crate::interchange::Report) {
        if let Some(session) = &mut self.session {
            session.done = Some(report);
        }
    }

    /// The export window, when open.
    pub fn export_window(
        &mut self,
        ctx: &egui::Context,
        (project, path): (&Project, Option<&PathBuf>),
        language: Language,
        actions: &mut Vec<Action>,
    ) {
        let words = words(language);
        let Some(session) = self.exporting.as_mut() else { return };
        let mut open = true;
        egui::Window::new(words.export_title).open(&mut open).collapsible(false).resizable(false).show(ctx, |ui| {
            export::ui(ui, session, (project, path), words, actions);
        });
        if !open {
            actions.push(Action::Import(ImportAction::CloseExport));
        }
    }

    /// The window, when a file is open.
    pub fn window(
        &mut self,
        ctx: &egui::Context,
        (project, files): (&Project, &FileWork),
        language: Language,
        actions: &mut Vec<Action>,
    ) {
        let words = words(language);
        if let Some((path, _)) = &self.reading {
            egui::Window::new(words.title).collapsible(false).show(ctx, |ui| {
                ui.horizontal(|ui| {
                    ui.spinner();
                    ui.label(format!("{} {}", words.reading, path.display()));
                });
            });
        }
        let Some(mut session) = self.session.take() else { return };
        if session.done.is_none() && project.family != Family::Rflex {
            self.check(&session, project, files);
        }
        let mut open = true;
        let room = ctx.content_rect().size() - egui::vec2(40.0, 60.0);
        let window = crate::ui::layout::parked_when_collapsed(egui::Window::new(words.title), ctx, "import-window", 1);
        window.open(&mut open).resizable(true).default_size(egui::vec2(980.0, 600.0).min(room)).max_size(room).show(
            ctx,
            |ui| {
                if let Some(report) = &session.done {
                    report_ui(ui, report, words, actions);
                } else {
                    self.session_ui(ui, &mut session, project, words, actions);
                }
            },
        );
        if session.playing {
            let shown = session.source.clips.get(session.clip.unwrap_or(0));
            let length = shown.map_or(0.0, |clip| preview::length_ms(&session.source, clip));
            session.time_ms += f64::from(ctx.input(|input| input.stable_dt)) * 1000.0;
            if session.time_ms > length {
                session.time_ms = 0.0;
            }
            ctx.request_repaint();
        }
        self.session = Some(session);
        if !open {
            actions.push(Action::Import(ImportAction::Close));
        }
    }

    fn session_ui(
        &mut self,
        ui: &mut egui::Ui,
        session: &mut Session,
        project: &Project,
        words: &ImportWords,
        actions: &mut Vec<Action>,
    ) {
        header_ui(ui, session, project.family, words);
        if project.family == Family::Rflex {
            ui.colored_label(ui.visuals().warn_fg_color, words.rflex);
        }
        if project.family != session.family {
            session.family = project.family;
            session.map = JointMap::for_source(&session.source, project.family, None);
        }
        landings(session, project, words).ui(ui, words);
        let clip = session.clip.unwrap_or(0);
        let file_length = session.source.clips.get(clip).map_or(0.0, |c| preview::length_ms(&session.source, c));
        // What the board plays, once worked out; the file's own motion until then.
        let board = match self.board(session) {
            Some(Ok((_, Some(played)))) => Some(played),
            _ => None,
        };
        let length = board.map_or(file_length, |played| played.length_ms.max(file_length));
        let now = match board {
            Some(played) => played.degrees_at(&session.source, &session.map, session.time_ms),
            None => session
                .source
                .clips
                .get(clip)
                .map(|c| preview::degrees_at(&session.source, c, &session.map, session.time_ms))
                .unwrap_or_default(),
        };
        ui.separator();
        let height = (ui.available_height() - 34.0).max(160.0);
        let width = ui.available_width();
        ui.allocate_ui(egui::vec2(width, height), |ui| {
            use egui_extras::{Size, StripBuilder};
            StripBuilder::new(ui).size(Size::remainder().at_least(360.0)).size(Size::exact(330.0)).horizontal(
                |mut strip| {
                    strip.cell(|ui| table::map_table(ui, session, &now, words));
                    strip.cell(|ui| self.preview_ui(ui, session, project, (&now, length), words));
                },
            );
        });
        ui.separator();
        self.buttons_ui(ui, session, project, words, actions);
    }

    /// Load map…, Save map…, Cancel and Create.
    fn buttons_ui(
        &self,
        ui: &mut egui::Ui,
        session: &Session,
        project: &Project,
        words: &ImportWords,
        actions: &mut Vec<Action>,
    ) {
        ui.horizontal(|ui| {
            if ui.button(words.load_map).clicked() {
                actions.push(Action::AskFile(FileRequest::Pick(Pick {
                    kind: words.joint_map,
                    extensions: &["json"],
                    then: Arc::new(|path| Action::Import(ImportAction::LoadMap(path))),
                })));
            }
            if ui.button(words.save_map).clicked() {
                let offered = format!(
                    "{}.map.json",
                    session.path.file_stem().map_or_else(|| "joints".into(), |s| s.to_string_lossy())
                );
                actions.push(Action::AskFile(FileRequest::Export(Export::json(offered, words.joint_map, |path| {
                    Action::Import(ImportAction::SaveMap(path))
                }))));
            }
            ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
                let can = project.family != Family::Rflex
                    && !self.busy()
                    && session.map.entries.iter().any(|e| e.target.is_some());
                if ui.add_enabled(can, egui::Button::new(words.create)).clicked() {
                    actions.push(Action::Import(ImportAction::Create));
                }
                if self.building.is_some() {
                    ui.spinner();
                }
                if ui.button(words.cancel).clicked() {
                    actions.push(Action::Import(ImportAction::Close));
                }
            });
        });
    }

    /// The figure at the preview's time, the play button and time slider, and what the file held that is left out.
    fn preview_ui(
        &mut self,
        ui: &mut egui::Ui,
        session: &mut Session,
        project: &Project,
        (now, length): (&[Option<f64>], f64),
        words: &ImportWords,
    ) {
        let size = egui::vec2(ui.available_width(), (ui.available_height() - 90.0).clamp(120.0, 330.0));
        let (rect, _) = ui.allocate_exact_size(size, egui::Sense::hover());
        match self.scene(session, project, now) {
            Some(scene) => {
                self.view.show(ui, rect, &scene, words.title);
            }
            None => {
                ui.put(rect, egui::Label::new(words.no_rig).wrap());
            }
        }
        ui.horizontal(|ui| {
            let caption = if session.playing { words.pause } else { words.play };
            if ui.add_enabled(!session.source.clips.is_empty(), egui::Button::new(caption)).clicked() {
                session.playing = !session.playing;
            }
            let mut seconds = session.time_ms / 1000.0;
            let label = ui.label(words.time);
            let slider = egui::Slider::new(&mut seconds, 0.0..=(length / 1000.0).max(0.001)).max_decimals(2);
            if ui.add(slider).labelled_by(label.id).changed() {
                session.time_ms = seconds * 1000.0;
            }
        });
        let approximated = self.board_ui(ui, session, words);
        if !session.source.dropped.is_empty() || !approximated.is_empty() {
            egui::ScrollArea::vertical().id_salt("import-left-out").show(ui, |ui| {
                for (head, notes) in [(words.report_heads[1], &approximated), (words.left_out, &session.source.dropped)]
                {
                    if notes.is_empty() {
                        continue;
                    }
                    ui.label(egui::RichText::new(head).strong());
                    for line in notes {
                        ui.label(format!("• {}", note(line, words)));
                    }
                }
            });
        }
    }

    /// The figure posed at the preview's time: the PLEN2, or the project's rig.
    fn scene(&mut self, session: &Session, project: &Project, now: &[Option<f64>]) -> Option<Scene> {
        let targets = session
            .source
            .channels
            .iter()
            .zip(now)
            .filter_map(|(channel, degrees)| Some((session.map.entry(&channel.key)?.target?, (*degrees)?)));
        match project.family {
            Family::Plen2 => {
                let chain = self.plen2_chain.get_or_insert_with(figure::plen2::chain);
                let mut values = [0i16; DEVICE_IDS];
                for (target, degrees) in targets {
                    if let Target::Joint(joint) = target {
                        // Tenths of a degree within ±180°.
                        #[allow(clippy::cast_possible_truncation)]
                        let tenths = (degrees * 10.0).round().clamp(-1800.0, 1800.0) as i16;
                        values[usize::from(joint.device_id())] = tenths;
                    }
                }
                let placed = chain.pose(&figure::plen2::angles(chain, &values));
                Some(Scene { solids: chain.dress(&placed, false), ..Scene::default() })
            }
            Family::Servo => {
                if project.servo.servos.iter().all(|servo| servo.rig.is_none()) {
                    return None;
                }
                let (chain, index_of) = figure::rig::chain(&project.servo);
                let degrees = targets.filter_map(|(target, degrees)| match target {
                    Target::Servo(id) => Some((id, degrees)),
                    Target::Joint(_) => None,
                });
                let angles = figure::rig::angles(&project.servo, &index_of, &degrees.collect(), chain.links.len());
                let placed = chain.pose(&angles);
                let ground = placed.iter().map(|p| p.position.z).fold(f32::MAX, f32::min);
                Some(Scene {
                    solids: chain.dress(&placed, false),
                    ground_z: ground.min(0.0) - 10.0,
                    ..Scene::default()
                })
            }
            // A base, or any other family: no figure to play it on.
            _ => None,
        }
    }
}

fn taken<T>(done: &Receiver<T>) -> Option<T> {
    match done.try_recv() {
        Ok(value) => Some(value),
        Err(crossbeam_channel::TryRecvError::Empty) => None,
        // The worker is gone: nothing will come (the caller says so).
        Err(crossbeam_channel::TryRecvError::Disconnected) => None,
    }
}

/// The file's name and format, the motion chosen, the board, and the fit's tolerance.
fn header_ui(ui: &mut egui::Ui, session: &mut Session, family: Family, words: &ImportWords) {
    let name = session
        .path
        .file_name()
        .map_or_else(|| session.path.display().to_string(), |n| n.to_string_lossy().into_owned());
    ui.label(egui::RichText::new(format!("{name} — {}", words::format(session.source.format, words))).strong());
    ui.horizontal(|ui| {
        let label = ui.label(words.motion);
        let shown = session.clip.map_or_else(
            || format!("{} ({})", words.all, session.source.clips.len()),
            |clip| clip_name(&session.source, clip),
        );
        egui::ComboBox::from_id_salt("import-clip")
            .selected_text(shown)
            .show_ui(ui, |ui| {
                ui.selectable_value(&mut session.clip, None, format!("{} ({})", words.all, session.source.clips.len()));
                for clip in 0..session.source.clips.len() {
                    ui.selectable_value(&mut session.clip, Some(clip), clip_name(&session.source, clip));
                }
            })
            .response
            .labelled_by(label.id);
        ui.separator();
        ui.label(format!("{} {}", words.for_board, words::family(family, words)));
        if session.source.clips.iter().any(|clip| matches!(clip.body, Body::Samples { .. })) {
            ui.separator();
            let label = ui.label(words.tolerance);
            ui.add(egui::DragValue::new(&mut session.tolerance_deg).range(0.05..=180.0).speed(0.05))
                .labelled_by(label.id);
        }
    });
}

fn clip_name(source: &Source, clip: usize) -> String {
    let item = &source.clips[clip];
    item.number.map_or_else(|| item.name.clone(), |number| format!("{number}: {}", item.name))
}

fn report_ui(ui: &mut egui::Ui, report: &crate::interchange::Report, words: &ImportWords, actions: &mut Vec<Action>) {
    ui.heading(words.imported);
    egui::ScrollArea::vertical().max_height(420.0).show(ui, |ui| {
        let all = [&report.converted, &report.approximated, &report.dropped, &report.notes];
        for (head, notes) in words.report_heads.iter().zip(all) {
            if notes.is_empty() {
                continue;
            }
            ui.strong(*head);
            for line in notes {
                ui.label(format!("• {}", note(line, words)));
            }
        }
    });
    if ui.button(words.close).clicked() {
        actions.push(Action::Import(ImportAction::Close));
    }
}
