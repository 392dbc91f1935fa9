//! The PLEN community's 90 official motion files (read where shared/ keeps them):
//! each opens, uploads to the emulated robot over a pseudo-terminal through the
//! command line, exports back, and saves as motion.json with the same content.

#![cfg(unix)]
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::print_stderr)]

use std::path::PathBuf;
use std::process::{Command, Stdio};

use common::Sim;
use servo_studio::project::{self, motion_json};

use crate::common;

const EXE: &str = env!("CARGO_BIN_EXE_servo-studio");

fn motions_folder() -> Option<PathBuf> {
    common::shared("plen2/motions")
}

fn sim_with(extra: &[&str]) -> Sim {
    let mut args = vec!["--protocol", "plen2", "--pty"];
    args.extend_from_slice(extra);
    common::sim(&args)
}

/// A motion.json's content: everything but the editor's `@metadata`, which no
/// robot stores, with each frame's outputs in device order (some official
/// files list them in another order; the values per device are the content).
fn content(text: &str) -> serde_json::Value {
    let mut value: serde_json::Value = serde_json::from_str(text).unwrap();
    value.as_object_mut().unwrap().remove("@metadata");
    for frame in value["frames"].as_array_mut().unwrap() {
        let outputs = frame["outputs"].as_array_mut().unwrap();
        outputs.sort_by(|a, b| a["device"].as_str().cmp(&b["device"].as_str()));
    }
    value
}

#[test]
fn every_official_motion_opens_and_survives_upload_and_export_unchanged() {
    let Some(folder) = motions_folder() else { return };
    let originals = motion_json::load_motions(&folder).unwrap();
    assert_eq!(originals.len(), 90);
    // Each opens as a valid PLEN2 motion.
    let document = project::Project {
        family: project::Family::Plen2,
        plen2: project::plen2::Plen2Project { motions: originals, ..Default::default() },
        ..project::Project::default()
    };
    assert_eq!(project::validate(&document), [], "the official motions are valid");

    let robot = sim_with(&[]);
    let import = Command::new(EXE)
        .args([
            "import",
            "--protocol",
            "plen2",
            "--port",
            &robot.port,
            "--in",
            folder.to_str().unwrap(),
            "--yes",
            "--no-backup",
        ])
        .stdin(Stdio::null())
        .output()
        .unwrap();
    let log = String::from_utf8_lossy(&import.stderr);
    assert!(import.status.success(), "{log}");
    assert_eq!(log.matches("written and verified").count(), 90, "{log}");

    let out = tempfile::tempdir().unwrap();
    let exported_path = out.path().join("robot.json");
    let export = Command::new(EXE)
        .args(["export", "--protocol", "plen2", "--port", &robot.port, "--out", exported_path.to_str().unwrap()])
        .stdin(Stdio::null())
        .output()
        .unwrap();
    assert!(export.status.success(), "{}", String::from_utf8_lossy(&export.stderr));
    let exported = project::load(&exported_path).unwrap();
    assert_eq!(exported.family, project::Family::Plen2);
    assert_eq!(exported.plen2.motions.len(), 90);

    let mut files: Vec<PathBuf> = std::fs::read_dir(&folder).unwrap().map(|e| e.unwrap().path()).collect();
    files.sort();
    for file in files {
        let original = std::fs::read_to_string(&file).unwrap();
        let slot = content(&original)["slot"].as_u64().unwrap();
        let motion = exported.plen2.motions.iter().find(|m| u64::from(m.slot) == slot).unwrap();
        assert_eq!(content(&motion_json::motion_to_json(motion)), content(&original), "{}", file.display());
    }
}

/// `sim --protocol plen2 --state FILE` starts with the file's joint settings
/// and motions in its slots, as `export` then finds them (needs no shared/).
#[test]
fn sim_state_preloads_the_robot() {
    use project::plen2::{Frame, Joint, JointSetting, LoopRange, Motion, Plen2Project, Pose};
    let mut pose = Pose::default();
    pose.set(Joint::LeftKneePitch, 321);
    pose.set(Joint::RightFootRoll, -123);
    let frames = vec![Frame::new(300, pose), Frame::new(500, Pose::default())];
    let plen2 = Plen2Project {
        joints: vec![JointSetting {
            joint: Joint::LeftKneePitch,
            min_tenths_deg: -500,
            max_tenths_deg: 800,
            home_tenths_deg: 450,
        }],
        motions: vec![
            Motion { slot: 3, name: "Nod".into(), frames: frames.clone(), loop_range: None, jump_slot: Some(45) },
            Motion {
                slot: 45,
                name: "Nod loop".into(),
                frames,
                loop_range: Some(LoopRange { begin_frame: 0, end_frame: 1, count: 4 }),
                jump_slot: None,
            },
        ],
        play_lists: Vec::new(),
    };
    let folder = tempfile::tempdir().unwrap();
    let state = folder.path().join("state.json");
    let document =
        project::Project { family: project::Family::Plen2, plen2: plen2.clone(), ..project::Project::default() };
    project::save(&state, &document).unwrap();

    let robot = sim_with(&["--state", state.to_str().unwrap()]);
    let exported_path = folder.path().join("robot.json");
    let export = Command::new(EXE)
        .args(["export", "--protocol", "plen2", "--port", &robot.port, "--out", exported_path.to_str().unwrap()])
        .args(["--slots", "0-5,44-46"])
        .stdin(Stdio::null())
        .output()
        .unwrap();
    assert!(export.status.success(), "{}", String::from_utf8_lossy(&export.stderr));
    let exported = project::load(&exported_path).unwrap();
    assert_eq!(exported.plen2.motions, plen2.motions);
    assert!(exported.plen2.joints.contains(&plen2.joints[0]), "{:?}", exported.plen2.joints);
}
