//! File → Export for another tool…: a servo project's macros as a Maestro
//! settings file, or one macro or PLEN2 motion as Blender add-on JSON,
//! written off the frame (the same exporters as `convert`).

use std::path::{Path, PathBuf};

use super::words::ImportWords;
use crate::interchange::{Report, export};
use crate::project::{Family, Project};
use crate::ui::action::{Action, Export, FileRequest, ImportAction};

/// What is written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ExportTo {
    /// A Maestro settings file: every macro a sequence.
    Maestro,
    /// Add-on JSON: one macro or motion.
    Blender,
}

/// The export window's choices.
#[derive(Clone, Debug, PartialEq)]
pub struct ExportSession {
    /// The format.
    pub to: ExportTo,
    /// The macro (servo board) or slot (PLEN2) written as add-on JSON.
    pub subject: Option<i32>,
    /// Add-on JSON's frame rate.
    pub fps: f64,
}

impl ExportSession {
    /// The choices a project starts with: a Maestro file for a servo project, else its first motion as JSON.
    pub fn new(project: &Project) -> Self {
        let to = if project.family == Family::Servo { ExportTo::Maestro } else { ExportTo::Blender };
        Self { to, subject: subjects(project).first().map(|(id, _)| *id), fps: 30.0 }
    }
}

/// The macros (servo board) or motions (PLEN2) a project offers: id or slot, and name.
fn subjects(project: &Project) -> Vec<(i32, String)> {
    match project.family {
        Family::Servo => project.servo.macros.iter().map(|m| (m.id, format!("{} {}", m.id, m.caption))).collect(),
        Family::Plen2 => {
            project.plen2.motions.iter().map(|m| (i32::from(m.slot), format!("{} {}", m.slot, m.name))).collect()
        }
        // A base, or any other family: nothing to export.
        _ => Vec::new(),
    }
}

/// Writes `session`'s export of `project`: the text and what was converted.
pub fn exported(session: &ExportSession, project: &Project) -> Result<(String, Report), String> {
    match (session.to, project.family, session.subject) {
        (ExportTo::Maestro, Family::Servo, _) => export::maestro(&project.servo, None).map_err(|e| e.to_string()),
        (ExportTo::Maestro, ..) => Err("a Maestro settings file is written from a servo board's project".into()),
        (ExportTo::Blender, Family::Servo, Some(id)) => {
            export::blender_servo(&project.servo, id, session.fps, None).map_err(|e| e.to_string())
        }
        (ExportTo::Blender, Family::Plen2, Some(slot)) => {
            let slot = u8::try_from(slot).map_err(|_| format!("there is no motion in slot {slot}"))?;
            export::blender_plen2(&project.plen2, slot, session.fps, None).map_err(|e| e.to_string())
        }
        (ExportTo::Blender, ..) => Err("nothing to export: the project holds no macro or motion".into()),
    }
}

/// The file name offered.
fn offered(session: &ExportSession, project: &Project, path: Option<&Path>) -> String {
    let stem = path.and_then(Path::file_stem).map_or_else(|| "project".into(), |s| s.to_string_lossy().into_owned());
    match session.to {
        ExportTo::Maestro => format!("{stem}.maestro.xml"),
        ExportTo::Blender => {
            let name = subjects(project)
                .into_iter()
                .find(|(id, _)| Some(*id) == session.subject)
                .map_or(stem, |(_, name)| name);
            format!("{}.json", name.replace(['/', '\\'], "_"))
        }
    }
}

/// The export window's content.
pub fn ui(
    ui: &mut egui::Ui,
    session: &mut ExportSession,
    (project, path): (&Project, Option<&PathBuf>),
    words: &ImportWords,
    actions: &mut Vec<Action>,
) {
    ui.horizontal(|ui| {
        let label = ui.label(words.format);
        let shown = if session.to == ExportTo::Maestro { words.formats[0] } else { words.formats[1] };
        egui::ComboBox::from_id_salt("export-format")
            .selected_text(shown)
            .show_ui(ui, |ui| {
                if project.family == Family::Servo {
                    ui.selectable_value(&mut session.to, ExportTo::Maestro, words.formats[0]);
                }
                ui.selectable_value(&mut session.to, ExportTo::Blender, words.formats[1]);
            })
            .response
            .labelled_by(label.id);
    });
    let subjects = subjects(project);
    if session.to == ExportTo::Blender {
        ui.horizontal(|ui| {
            let label = ui.label(if project.family == Family::Plen2 { words.subjects[1] } else { words.subjects[0] });
            let shown =
                subjects.iter().find(|(id, _)| Some(*id) == session.subject).map_or("—", |(_, name)| name.as_str());
            egui::ComboBox::from_id_salt("export-subject")
                .selected_text(shown)
                .show_ui(ui, |ui| {
                    for (id, name) in &subjects {
                        ui.selectable_value(&mut session.subject, Some(*id), name);
                    }
                })
                .response
                .labelled_by(label.id);
            let label = ui.label(words.fps);
            ui.add(egui::DragValue::new(&mut session.fps).range(1.0..=1000.0)).labelled_by(label.id);
        });
    }
    let problem = match (session.to, project.family) {
        (ExportTo::Maestro, family) if family != Family::Servo => Some(words.maestro_servo_only),
        (ExportTo::Blender, _) if subjects.is_empty() => Some(words.nothing),
        _ => None,
    };
    if let Some(problem) = problem {
        ui.colored_label(ui.visuals().warn_fg_color, problem);
    }
    ui.horizontal(|ui| {
        if ui.add_enabled(problem.is_none(), egui::Button::new(words.export)).clicked() {
            let (kind, extension) = match session.to {
                ExportTo::Maestro => (words.formats[0], "xml"),
                ExportTo::Blender => (words.formats[1], "json"),
            };
            let mut request = Export::json(offered(session, project, path.map(PathBuf::as_path)), kind, |path| {
                Action::Import(ImportAction::Export(path))
            });
            request.extension = extension;
            actions.push(Action::AskFile(FileRequest::Export(request)));
        }
        if ui.button(words.close).clicked() {
            actions.push(Action::Import(ImportAction::CloseExport));
        }
    });
}
