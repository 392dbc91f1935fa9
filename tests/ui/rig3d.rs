//! A servo robot's rig posed by its hands and feet, and dressed in the user's
//! own meshes: the sample biped's foot dragged by its ring moves its leg's
//! servos alone (the foot kept flat, computed here by forward kinematics over
//! the angles the editor holds), sent to the board and undone in one step; a
//! project naming an STL that reads and one that does not opens, draws the
//! first and says which file failed and what to do.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common;

use std::collections::BTreeMap;

use egui::Pos2;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use servo_studio::figure::{self, Placed};
use servo_studio::project::{LinkMesh, Project};
use servo_studio::ui::{Action, StudioApp, Tab};

/// The sample biped's limbs, in its servos' order: left hand, right hand, left foot, right foot.
const LEFT_FOOT: usize = 2;

fn pose(harness: &Harness<'static, StudioApp>) -> BTreeMap<u8, i16> {
    common::ui::servo_ui(harness.state()).pose.clone()
}

fn ring(harness: &Harness<'static, StudioApp>, end: usize) -> Pos2 {
    common::ui::servo_ui(harness.state()).figure.end_on_screen(end).expect("the ring is drawn")
}

/// The sample biped's left foot (its sole's middle and turn) for servo angles, by forward kinematics.
fn left_foot(project: &Project, degrees: &BTreeMap<u8, i16>) -> Placed {
    let project = &project.servo;
    let (chain, links) = figure::rig::chain(project);
    let degrees: BTreeMap<u8, f64> = degrees.iter().map(|(id, d)| (*id, f64::from(*d))).collect();
    let placed = chain.pose(&figure::rig::angles(project, &links, &degrees, chain.links.len()));
    let (limbs, _) = figure::rig::limbs(project, &chain, &links);
    limbs[LEFT_FOOT].reach(&placed).unwrap()
}

#[test]
fn the_sample_bipeds_foot_dragged_by_its_ring_moves_its_leg_alone_flat_and_undoes_in_one_step() {
    let project = servo_studio::ui::sample_project();
    let mut app = common::ui::editor(project.clone());
    app.apply(Action::ConnectDemo);
    let mut harness = common::ui::showing(app, Tab::Servos, (1200.0, 800.0));
    let before = pose(&harness);
    let at = ring(&harness, LEFT_FOOT);
    harness.hover_at(at);
    harness.run_steps(8);
    assert!(
        harness.query_by_label_contains("L hip roll 左髖側擺 → L hip pitch").is_some(),
        "hovering the ring names the chain"
    );
    harness.drag_at(at);
    harness.step();
    for part in 1..=8u8 {
        harness.hover_at(at + egui::vec2(0.0, -40.0) * f32::from(part) / 8.0);
        harness.step();
    }
    harness.drop_at(at + egui::vec2(0.0, -40.0));
    harness.run_steps(2);
    let after = pose(&harness);
    let (from, to) = (left_foot(&project, &before), left_foot(&project, &after));
    assert!(to.position.z - from.position.z > 10.0, "the foot rose: {} → {}", from.position, to.position);
    let (_, turn) = glam::Quat::from_mat3(&(from.rotation * to.rotation.transpose())).normalize().to_axis_angle();
    // Whole degrees at each of five servos: flat within a few degrees.
    assert!(turn.min(std::f32::consts::TAU - turn).to_degrees() < 3.0, "the foot stayed flat: {turn} rad");
    for (id, degree) in &after {
        if !(7..=11).contains(id) {
            assert_eq!(Some(degree), before.get(id), "servo {id} is not in the left leg and did not move");
        }
    }
    harness.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Z);
    harness.run_steps(2);
    assert_eq!(pose(&harness), before, "one undo brings the drag back");
    assert!(!harness.state().document.can_undo(), "the drag was one step");
}

#[test]
fn a_mesh_that_reads_is_drawn_and_one_that_does_not_is_named_with_what_to_do() {
    let dir = tempfile::tempdir().unwrap();
    // A binary STL: 80 bytes of header, a count, one triangle of 50 bytes.
    let mut stl = vec![0u8; 80];
    stl.extend(1u32.to_le_bytes());
    for value in [0.0f32, 0.0, 1.0, 0.0, 0.0, 0.0, 30.0, 0.0, 0.0, 0.0, 30.0, 0.0] {
        stl.extend(value.to_le_bytes());
    }
    stl.extend([0, 0]);
    std::fs::create_dir(dir.path().join("parts")).unwrap();
    std::fs::write(dir.path().join("parts/shin.stl"), &stl).unwrap();
    std::fs::write(dir.path().join("parts/bad.stl"), b"solid nothing\nfacet normal oops\n").unwrap();
    let mut project = servo_studio::ui::sample_project();
    let mesh = |servo_id, path: &str| LinkMesh {
        servo_id,
        path: path.into(),
        offset_mm: [0, 0, 0],
        rotation_deg: [0, 0, 0],
        scale_milli: 1000,
    };
    project.servo.meshes = vec![mesh(Some(9), "parts/shin.stl"), mesh(Some(14), "parts/bad.stl")];
    let path = dir.path().join("robot.json");
    std::fs::write(&path, servo_studio::project::to_json(&project)).unwrap();
    let opened = servo_studio::project::from_json(&std::fs::read_to_string(&path).unwrap()).unwrap();
    assert_eq!(opened.servo.meshes, project.servo.meshes, "meshes are stored as written, relative to the project");
    let data = tempfile::tempdir().unwrap().keep();
    let app = StudioApp::new(opened, Some(path), servo_studio::link::no_waker()).with_data_dir(data);
    let mut harness = common::ui::showing(app, Tab::Servos, (1200.0, 800.0));
    common::ui::run_until(&mut harness, "the mesh files read", |app| {
        common::ui::servo_ui(app).figure.mesh_files.settled()
    });
    harness.run_steps(2);
    assert_eq!(common::ui::servo_ui(harness.state()).figure.meshes_drawn(), 1, "the shin is drawn by its mesh");
    let error = harness.query_by_label_contains("bad.stl").expect("the failed file is named");
    let text = format!("{error:?}");
    assert!(text.contains("STL") && text.contains("Servo settings → Meshes"), "what went wrong and what to do: {text}");
    assert_eq!(harness.state().document.project.servo.servos.len(), 16, "the project opened");
}
