//! The rig table of the servo settings: each servo placed in a skeleton (or
//! not) — the servo it is mounted on (or the body), where its joint sits
//! there in mm, the axis it turns about, its sign, and the angle at which its
//! link is straight. The 3D preview is built from it; `check` validates it.

use std::sync::Arc;

use crate::project::{Edit, LinkMesh, RigAxis, RigJoint, Servo, ServoProject};
use crate::ui::action::{Action, FileRequest, Pick};
use crate::ui::i18n::Strings;
use crate::ui::rows;
use crate::ui::servo::action::ServoAction;
use crate::ui::servo::captions::ServoWords;

/// A new servo in the rig: on the body, turning about y (a pitch).
fn placed() -> RigJoint {
    RigJoint {
        parent: None,
        offset_mm: [0, 0, 0],
        axis: RigAxis::Y,
        reversed: false,
        straight_deg: 0,
        mirror: None,
        end: None,
    }
}

fn axis_name(axis: RigAxis) -> &'static str {
    match axis {
        RigAxis::X => "x (roll)",
        RigAxis::Y => "y (pitch)",
        RigAxis::Z => "z (yaw)",
    }
}

/// The parts of the servo settings: each a table with the servo's id first
/// and a heading over every field, narrow enough for the pane at 1280×800.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Part {
    /// Calibration, limits, home.
    #[default]
    Limits,
    /// Where each servo sits in the skeleton.
    Rig,
    /// Which links are hands and feet.
    Ends,
    /// The meshes links are drawn with.
    Meshes,
}

/// The widest the id column gets (a long caption is cut, its whole in a hover).
const ID_COLUMN: f32 = 120.0;

/// The rig table, `height` points high at most. A drag of one value is one undo step.
pub fn table(ui: &mut egui::Ui, project: &ServoProject, height: f32, words: &Strings, actions: &mut Vec<Action>) {
    let heading = [
        words.servo_id,
        words.servo().in_rig,
        words.servo().mounted_on,
        words.servo().offset_mm,
        words.axis,
        words.reversed,
        words.servo().straight_at,
        words.servo().twin,
    ];
    rows::table_with_id(ui, "servo-rig", &heading, ID_COLUMN, project.servos.len(), height, |row, index| {
        rig_row(row, project, index, words, actions);
    });
}

/// The hands-and-feet table: for each rigged servo, whether its link is a
/// hand or a foot, the servo its chain starts at, and its tip (mm).
pub fn ends_table(ui: &mut egui::Ui, project: &ServoProject, height: f32, words: &Strings, actions: &mut Vec<Action>) {
    let [end, from, tip] = words.servo().end_columns;
    let heading = [words.servo_id, end, from, tip];
    rows::table_with_id(ui, "servo-ends", &heading, ID_COLUMN, project.servos.len(), height, |row, index| {
        let servo = &project.servos[index];
        let row_id = id_cell(row, servo);
        let Some(rig) = servo.rig else {
            row.col(|ui| {
                ui.weak(words.servo().not_rigged);
            });
            return;
        };
        end_cells(row, project, (servo, rig), (row_id, words), actions);
    });
}

/// The meshes table: for each servo, the mesh its link is drawn with, and its placing.
pub fn meshes_table(
    ui: &mut egui::Ui,
    project: &ServoProject,
    height: f32,
    words: &Strings,
    actions: &mut Vec<Action>,
) {
    let [file, offset, turn, scale] = words.servo().mesh_columns;
    let heading = [words.servo_id, file, offset, turn, scale, ""];
    rows::table_with_id(ui, "servo-meshes", &heading, ID_COLUMN, project.servos.len(), height, |row, index| {
        let servo = &project.servos[index];
        let row_id = id_cell(row, servo);
        mesh_cells(row, project, (servo.id, row_id), words, actions);
    });
}

/// The row's first cell: the servo's id and caption (cut to the column, whole
/// in a hover); its id labels every field of the row.
fn id_cell(row: &mut egui_extras::TableRow<'_, '_>, servo: &Servo) -> egui::Id {
    let mut row_id = egui::Id::NULL;
    row.col(|ui| {
        let text = format!("{} {}", servo.id, servo.caption);
        row_id = ui.add(egui::Label::new(&text).truncate()).on_hover_text(&text).id;
    });
    row_id
}

/// One servo's row of the rig: in the rig, mounted on, offset, axis, reversed, straight at, twin.
fn rig_row(
    row: &mut egui_extras::TableRow<'_, '_>,
    project: &ServoProject,
    index: usize,
    words: &Strings,
    actions: &mut Vec<Action>,
) {
    let servo = &project.servos[index];
    let set = |rig: Option<RigJoint>, field: &str| Action::Edit {
        edit: Edit::SetServo { index, servo: Servo { rig, ..servo.clone() } },
        coalesce: Some(format!("servo {} rig {field}", servo.id)),
    };
    let row_id = id_cell(row, servo);
    row.col(|ui| {
        let mut rigged = servo.rig.is_some();
        if ui.checkbox(&mut rigged, "").labelled_by(row_id).changed() {
            actions.push(set(rigged.then(placed), "in"));
        }
    });
    let Some(rig) = servo.rig else { return };
    row.col(|ui| {
        let mut parent = rig.parent;
        other_servo(ui, ("rig-parent", servo.id), (project, servo.id), &mut parent, words.body).labelled_by(row_id);
        if parent != rig.parent {
            actions.push(set(Some(RigJoint { parent, ..rig }), "parent"));
        }
    });
    row.col(|ui| {
        let mut offset = rig.offset_mm;
        for value in &mut offset {
            ui.add(egui::DragValue::new(value).range(-2000..=2000)).labelled_by(row_id);
        }
        if offset != rig.offset_mm {
            actions.push(set(Some(RigJoint { offset_mm: offset, ..rig }), "offset"));
        }
    });
    row.col(|ui| {
        let mut axis = rig.axis;
        egui::ComboBox::from_id_salt(("rig-axis", servo.id))
            .selected_text(axis_name(axis))
            .width(80.0)
            .show_ui(ui, |ui| {
                for option in RigAxis::ALL {
                    ui.selectable_value(&mut axis, option, axis_name(option));
                }
            })
            .response
            .labelled_by(row_id);
        if axis != rig.axis {
            actions.push(set(Some(RigJoint { axis, ..rig }), "axis"));
        }
    });
    row.col(|ui| {
        let mut reversed = rig.reversed;
        if ui.checkbox(&mut reversed, "").labelled_by(row_id).changed() {
            actions.push(set(Some(RigJoint { reversed, ..rig }), "reversed"));
        }
    });
    row.col(|ui| {
        let mut straight = rig.straight_deg;
        let drag = egui::DragValue::new(&mut straight).range(-360..=360).suffix("°");
        if ui.add(drag).labelled_by(row_id).changed() {
            actions.push(set(Some(RigJoint { straight_deg: straight, ..rig }), "straight"));
        }
    });
    row.col(|ui| {
        let mut mirror = rig.mirror;
        other_servo(ui, ("rig-twin", servo.id), (project, servo.id), &mut mirror, "—").labelled_by(row_id);
        if mirror != rig.mirror {
            actions.push(set(Some(RigJoint { mirror, ..rig }), "mirror"));
        }
    });
}

/// Whether a link is a hand or a foot (a box), and when it is, the servo its
/// chain starts at and its tip (mm), a cell each.
fn end_cells(
    row: &mut egui_extras::TableRow<'_, '_>,
    project: &ServoProject,
    (servo, rig): (&Servo, RigJoint),
    (row_id, words): (egui::Id, &Strings),
    actions: &mut Vec<Action>,
) {
    let mut end = rig.end.is_some();
    row.col(|ui| {
        ui.checkbox(&mut end, "").labelled_by(row_id).on_hover_text(words.servo().end_hint);
    });
    let mut now = if end { Some(rig.end.unwrap_or_default()) } else { None };
    if let Some(chain) = &mut now {
        row.col(|ui| {
            other_servo(ui, ("rig-root", servo.id), (project, servo.id), &mut chain.root, words.body)
                .labelled_by(row_id);
        });
        row.col(|ui| {
            for value in &mut chain.tip_mm {
                ui.add(egui::DragValue::new(value).range(-2000..=2000)).labelled_by(row_id);
            }
        });
    }
    if now != rig.end {
        let index = project.servos.iter().position(|s| s.id == servo.id).unwrap_or(0);
        actions.push(Action::Edit {
            edit: Edit::SetServo { index, servo: Servo { rig: Some(RigJoint { end: now, ..rig }), ..servo.clone() } },
            coalesce: Some(format!("servo {} rig end", servo.id)),
        });
    }
}

/// A link's mesh, a cell each: the file (a button that picks another), its
/// offset (mm), its turn (°), its scale, and × — each field under its heading.
fn mesh_cells(
    row: &mut egui_extras::TableRow<'_, '_>,
    project: &ServoProject,
    (servo_id, row_id): (u8, egui::Id),
    words: &Strings,
    actions: &mut Vec<Action>,
) {
    let index = project.meshes.iter().position(|mesh| mesh.servo_id == Some(servo_id));
    let name = index.map_or(words.servo().choose_mesh.to_string(), |i| project.meshes[i].path.clone());
    row.col(|ui| {
        let button = egui::Button::new(&name).truncate();
        if ui.add(button).labelled_by(row_id).on_hover_text(format!("{name}\n{}", words.servo().mesh_hint)).clicked() {
            actions.push(Action::AskFile(FileRequest::Pick(Pick {
                kind: words.servo().mesh_kind,
                extensions: &["stl", "obj", "STL", "OBJ"],
                then: Arc::new(move |path| Action::family(ServoAction::SetMesh { servo_id, path })),
            })));
        }
    });
    let Some(index) = index else { return };
    let mut mesh = project.meshes[index].clone();
    row.col(|ui| {
        for value in mesh.offset_mm.iter_mut() {
            ui.add(egui::DragValue::new(value).range(-2000..=2000)).labelled_by(row_id);
        }
    });
    row.col(|ui| {
        for value in mesh.rotation_deg.iter_mut() {
            ui.add(egui::DragValue::new(value).range(-180..=180).suffix("°")).labelled_by(row_id);
        }
    });
    row.col(|ui| {
        ui.add(
            egui::DragValue::new(&mut mesh.scale_milli)
                .range(1..=1_000_000)
                .prefix("×")
                .custom_formatter(|v, _| format!("{:.3}", v / 1000.0))
                .custom_parser(|text| text.trim_start_matches('×').parse::<f64>().ok().map(|v| v * 1000.0)),
        )
        .labelled_by(row_id);
    });
    let mut removed = false;
    row.col(|ui| removed = ui.small_button("×").on_hover_text(words.remove).clicked());
    if removed || mesh != project.meshes[index] {
        let mut changed = project.clone();
        if removed {
            changed.meshes.remove(index);
        } else {
            changed.meshes[index] = mesh;
        }
        let coalesce = (!removed).then(|| format!("servo {servo_id} mesh"));
        actions.push(Action::Edit { edit: Edit::ReplaceAll(Box::new(changed)), coalesce });
    }
}

/// The project with `servo_id`'s link drawn by the mesh in `path` (kept as
/// given when no folder is known, else relative to `folder` where it can be).
pub fn with_mesh(
    project: &ServoProject,
    servo_id: u8,
    path: &std::path::Path,
    folder: Option<&std::path::Path>,
) -> ServoProject {
    let relative = folder.and_then(|folder| path.strip_prefix(folder).ok()).unwrap_or(path);
    let written = relative.components().map(|part| part.as_os_str().to_string_lossy()).collect::<Vec<_>>().join("/");
    let written = if relative.is_absolute() { path.to_string_lossy().into_owned() } else { written };
    let mut changed = project.clone();
    let mesh = LinkMesh {
        servo_id: Some(servo_id),
        path: written,
        offset_mm: [0; 3],
        rotation_deg: [0; 3],
        scale_milli: 1000,
    };
    match changed.meshes.iter_mut().find(|m| m.servo_id == Some(servo_id)) {
        Some(existing) => existing.path = mesh.path,
        None => changed.meshes.push(mesh),
    }
    changed
}

/// A choice of another servo of the project than `own` (or `none`).
fn other_servo(
    ui: &mut egui::Ui,
    id_salt: (&str, u8),
    (project, own): (&ServoProject, u8),
    value: &mut Option<u8>,
    none: &str,
) -> egui::Response {
    let name = |id: Option<u8>| match id.and_then(|id| project.servo(id)) {
        None => none.to_string(),
        Some(servo) => format!("{} {}", servo.id, servo.caption),
    };
    egui::ComboBox::from_id_salt(id_salt)
        .selected_text(name(*value))
        .width(110.0)
        .truncate()
        .show_ui(ui, |ui| {
            ui.selectable_value(value, None, none);
            for other in project.servos.iter().filter(|other| other.id != own) {
                ui.selectable_value(value, Some(other.id), name(Some(other.id)));
            }
        })
        .response
}

#[cfg(test)]
mod tests {
    use egui::accesskit::Role;
    use egui_kittest::Harness;
    use egui_kittest::kittest::Queryable;

    use super::*;
    use crate::ui::i18n::Language;

    fn rig_table(project: ServoProject) -> Harness<'static, (ServoProject, Vec<Action>)> {
        Harness::builder()
            .with_size(egui::vec2(1200.0, 400.0))
            .with_context_setup(crate::ui::fonts::install)
            .build_ui_state(
                |ui, (project, actions): &mut (ServoProject, Vec<Action>)| {
                    table(ui, project, 300.0, Language::English.strings(), actions);
                },
                (project, Vec::new()),
            )
    }

    fn robot() -> ServoProject {
        let hip = Servo::new(1, "hip");
        let knee = Servo { rig: Some(RigJoint { parent: Some(1), ..placed() }), ..Servo::new(2, "knee") };
        ServoProject { servos: vec![hip, knee], ..ServoProject::default() }
    }

    /// The servo the last action set, and its undo key.
    fn set(harness: &Harness<'static, (ServoProject, Vec<Action>)>) -> (usize, Servo, String) {
        match harness.state().1.last() {
            Some(Action::Edit { edit: Edit::SetServo { index, servo }, coalesce: Some(key) }) => {
                (*index, servo.clone(), key.clone())
            }
            other => panic!("a servo set, not {other:?}"),
        }
    }

    #[test]
    fn a_servo_joins_the_rig_on_the_body_turning_about_y() {
        let mut harness = rig_table(robot());
        harness.run();
        let hip = harness.get_all_by_role_and_label(Role::CheckBox, "1 hip").count();
        assert_eq!(hip, 1, "a servo out of the rig has only its in-the-rig box");
        harness.get_by_role_and_label(Role::CheckBox, "1 hip").click();
        harness.run();
        let (index, servo, key) = set(&harness);
        assert_eq!((index, servo.rig, key.as_str()), (0, Some(placed()), "servo 1 rig in"));
    }

    #[test]
    fn a_rigged_servo_names_its_parent_and_is_reversed_in_one_step_of_its_own() {
        let mut harness = rig_table(robot());
        harness.run();
        assert!(
            harness.query(egui_kittest::kittest::By::new().role(Role::ComboBox).value("1 hip")).is_some(),
            "mounted on the hip"
        );
        let boxes: Vec<_> = harness.get_all_by_role_and_label(Role::CheckBox, "2 knee").collect();
        assert_eq!(boxes.len(), 2, "in the rig, reversed (hand or foot has a table of its own)");
        boxes[1].click();
        harness.run();
        let (index, servo, key) = set(&harness);
        let reversed = RigJoint { parent: Some(1), reversed: true, ..placed() };
        assert_eq!((index, servo.rig, key.as_str()), (1, Some(reversed), "servo 2 rig reversed"));
    }

    #[test]
    fn a_picked_mesh_is_stored_relative_to_the_project_and_replaces_the_links_old_one() {
        let folder = std::path::Path::new("/home/me/robot");
        let project = with_mesh(&robot(), 2, &folder.join("parts").join("shin.stl"), Some(folder));
        assert_eq!(project.meshes.len(), 1);
        assert_eq!((project.meshes[0].servo_id, project.meshes[0].path.as_str()), (Some(2), "parts/shin.stl"));
        let again = with_mesh(&project, 2, std::path::Path::new("/elsewhere/knee.obj"), Some(folder));
        assert_eq!(again.meshes.len(), 1, "one mesh a link");
        assert_eq!(again.meshes[0].path, "/elsewhere/knee.obj", "outside the folder: kept whole");
        let unsaved = with_mesh(&robot(), 1, std::path::Path::new("/tmp/hip.stl"), None);
        assert_eq!(unsaved.meshes[0].path, "/tmp/hip.stl");
    }
}
