//! Nothing cut at 1280×800, in every language of the interface: the panels users
//! found cut — the PLEN2 frames table ("Play from here" was cut to "P"), the
//! servo macro rows (their ↓ and × were cut off), the servo settings' rig,
//! hands-and-feet and meshes tables (which needed a sideways scroll that took
//! the Id column away) — are drawn with no widget straddling the edge of the
//! pane it is in (the 3D view's left edge) or the window's, and every field
//! of the settings tables is labelled (by its row's servo).

#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common;

use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT as _, Queryable};
use servo_studio::project::{Family, Project};
use servo_studio::ui::Language;
use servo_studio::ui::{Action, StudioApp, Tab};

const SIZE: (f32, f32) = (1280.0, 800.0);

/// The widgets that straddle the 3D view's left edge or the window's right
/// edge: each as its role, label and horizontal extent.
fn cut(harness: &Harness<'static, StudioApp>, language: Language) -> Vec<String> {
    let preview = language.word("strings.robot_preview");
    let view = harness
        .get_all_by_role(Role::Image)
        .find(|node| node.accesskit_node().label().is_some_and(|l| l.contains(preview)))
        .expect("the 3D view")
        .rect();
    let mut cut = vec![];
    for role in [Role::Button, Role::ComboBox, Role::CheckBox, Role::SpinButton, Role::Slider, Role::TextInput] {
        for node in harness.get_all_by_role(role) {
            let rect = node.rect();
            // Beside the view (not above it, as the toolbar is) and across its left edge.
            let beside = rect.max.y > view.min.y && rect.min.y < view.max.y;
            let straddles = beside && rect.min.x < view.min.x && rect.max.x > view.min.x + 1.0;
            if straddles || rect.max.x > SIZE.0 + 1.0 {
                let label = node.accesskit_node().label().unwrap_or_default();
                cut.push(format!(
                    "{role:?} {label:?} {:.0}..{:.0} (the view from {:.0})",
                    rect.min.x, rect.max.x, view.min.x
                ));
            }
        }
    }
    cut
}

fn editor(project: Project, language: Language, tab: Tab) -> Harness<'static, StudioApp> {
    let mut app = common::ui::editor(project);
    app.apply(Action::SetLanguage(language));
    app.apply(Action::ConnectDemo);
    common::ui::showing(app, tab, SIZE)
}

#[test]
fn the_plen2_frames_table_is_not_cut() {
    let Some(files) = common::official_motion_files() else { return };
    let motions: Vec<_> = files
        .iter()
        .take(10)
        .map(|file| servo_studio::project::motion_json::read_motion_file(file).unwrap().0)
        .collect();
    for language in Language::ALL {
        let mut project = Project::empty(Family::Plen2);
        project.plen2.motions.clone_from(&motions);
        let harness = editor(project, language, Tab::Motions);
        let play_here = language.word("plen2.play_from_here");
        assert!(harness.query_all_by_label(play_here).count() >= 3, "{language:?}: the rows' {play_here} are drawn");
        assert_eq!(cut(&harness, language), Vec::<String>::new(), "{language:?}");
    }
}

#[test]
fn the_servo_macro_rows_are_not_cut() {
    for language in Language::ALL {
        let harness = editor(servo_studio::ui::sample_project(), language, Tab::Macros);
        assert!(harness.query_all_by_label("×").count() >= 3, "the rows' × are drawn");
        assert_eq!(cut(&harness, language), Vec::<String>::new(), "{language:?}");
    }
}

#[test]
fn the_servo_settings_tables_are_not_cut_and_every_field_is_labelled() {
    for language in Language::ALL {
        let mut project = servo_studio::ui::sample_project();
        project.servo.meshes = vec![servo_studio::project::LinkMesh {
            servo_id: Some(9),
            path: "parts/shin.stl".into(),
            offset_mm: [0; 3],
            rotation_deg: [0; 3],
            scale_milli: 1000,
        }];
        let mut harness = editor(project, language, Tab::Servos);
        let settings = language.word("servo.servo_settings");
        let parts = ["strings.rig", "servo.ends_tab", "servo.meshes_tab"].map(|key| language.word(key));
        harness.get_by_label(settings).click();
        harness.run_steps(3);
        for part in parts {
            harness.get_by_label(part).click();
            harness.run_steps(3);
            assert_eq!(cut(&harness, language), Vec::<String>::new(), "{language:?}, {part}");
            // The id column stays: the first servo's row is there, and every field is labelled by it.
            let unlabelled: Vec<String> = [Role::ComboBox, Role::CheckBox, Role::SpinButton]
                .into_iter()
                .flat_map(|role| harness.get_all_by_role(role).collect::<Vec<_>>())
                .filter(|node| node.rect().min.y > harness.get_by_label(part).rect().max.y)
                .filter(|node| node.accesskit_node().label().is_none_or(|label| label.is_empty()))
                .map(|node| format!("{:?} at {:?}", node.accesskit_node().role(), node.rect().min))
                .collect();
            assert_eq!(unlabelled, Vec::<String>::new(), "{language:?}, {part}: fields with no label");
            assert!(
                harness.query_all_by_label_contains("1 L shoulder").count() > 0,
                "{language:?}, {part}: the Id column"
            );
        }
    }
}

#[test]
fn the_servo_action_steps_are_not_cut() {
    for language in Language::ALL {
        let harness = editor(servo_studio::ui::sample_project(), language, Tab::Actions);
        assert!(harness.query_all_by_label("×").count() >= 3, "the steps' × are drawn");
        assert_eq!(cut(&harness, language), Vec::<String>::new(), "{language:?}");
    }
}
