//! Project format version 3, the show: a version 1 or 2 project file opens
//! as a show of one device whose project is that file, byte for byte (every
//! project fixture, and each official PLEN2 motion as a project), and a show
//! reads back exactly as it was written.

#![allow(clippy::unwrap_used)]

use std::path::Path;

use servo_studio::project::{self, Family, Project};
use servo_studio::show::{Cue, Device, Place, Show, Start};

fn fixtures() -> Vec<std::path::PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    vec![
        root.join("tests/fixtures/project-v1.json"),
        root.join("tests/fixtures/project-v2.json"),
        root.join("assets/sample-biped.json"),
    ]
}

#[test]
fn every_project_fixture_opens_as_a_one_device_show_byte_for_byte() {
    for path in fixtures() {
        let original = project::load(&path).unwrap();
        let show = Show::open(&path).unwrap();
        assert_eq!(show.devices.len(), 1, "{}", path.display());
        assert_eq!(show.devices[0].name, path.file_stem().unwrap().to_string_lossy());
        let mut again = show.devices[0].project.clone();
        again.sound.clone_from(&show.sound);
        assert_eq!(project::to_json(&again), project::to_json(&original), "{}", path.display());
        // And as a show file, version 3, it reads back the same.
        let reread = Show::from_text(&show.to_json(), "x").unwrap();
        assert_eq!(reread, show, "{}", path.display());
    }
}

#[test]
fn official_motions_as_projects_open_as_one_device_shows_byte_for_byte() {
    let Some(files) = crate::common::official_motion_files() else { return };
    let dir = tempfile::tempdir().unwrap();
    for file in files.iter().take(90) {
        let (motion, _) = project::motion_json::read_motion(&std::fs::read_to_string(file).unwrap()).unwrap();
        let mut original = Project::empty(Family::Plen2);
        original.plen2.motions.push(motion);
        let path = dir.path().join("one.json");
        project::save(&path, &original).unwrap();
        let show = Show::open(&path).unwrap();
        let (again, saved) = (project::to_json(&show.devices[0].project), std::fs::read_to_string(&path).unwrap());
        assert!(
            again.trim_end() == saved.trim_end(),
            "{}: the one device's project is not the file, byte for byte",
            file.display()
        );
    }
}

#[test]
fn a_three_device_show_reads_back_as_written_and_a_newer_version_is_refused() {
    let sample = project::load(&fixtures()[2]).unwrap();
    let show = Show {
        devices: vec![
            Device {
                name: "skull".into(),
                port: Some("/dev/ttyUSB0".into()),
                place: Place { x_m: -1.0, y_m: 0.5, heading_deg: 90.0 },
                project: sample,
                play_on_without: false,
            },
            Device {
                name: "plen".into(),
                port: None,
                place: Place::default(),
                project: Project::empty(Family::Plen2),
                play_on_without: true,
            },
            Device {
                name: "base".into(),
                port: Some("tcp://127.0.0.1:5000".into()),
                place: Place::default(),
                project: Project::empty(Family::Rflex),
                play_on_without: false,
            },
        ],
        sound: None,
        cues: vec![Cue {
            device: "base".into(),
            at_ms: 1500,
            start: Start::Drive { speed_m_s: 0.3, turn_deg_s: -10.0, for_ms: 2000 },
        }],
    };
    show.check().unwrap();
    let text = show.to_json();
    assert!(text.contains("\"version\": 3") && text.contains("\"format\": \"servo-studio-show\""), "{text}");
    assert_eq!(Show::from_text(&text, "x").unwrap(), show);
    let newer = text.replace("\"version\": 3", "\"version\": 4");
    assert!(Show::from_text(&newer, "x").unwrap_err().to_string().contains("update Servo Studio"));
    let unknown = text.replace("\"device\": \"base\"", "\"device\": \"ghost\"");
    assert!(Show::from_text(&unknown, "x").unwrap_err().to_string().contains("\"ghost\", which is not a device"));
}
