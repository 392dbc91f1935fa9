//! `servo-studio convert` run as a user runs it: the format told from the
//! content, a report of what was converted, approximated and dropped (each
//! once), nothing written unless all of it converted, and a result `check`
//! passes.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::Path;
use std::process::Command;

const EXE: &str = env!("CARGO_BIN_EXE_servo-studio");

fn convert(dir: &Path, args: &[&str]) -> (bool, String, String) {
    let output = Command::new(EXE).current_dir(dir).arg("convert").args(args).output().unwrap();
    (
        output.status.success(),
        String::from_utf8_lossy(&output.stdout).into_owned(),
        String::from_utf8_lossy(&output.stderr).into_owned(),
    )
}

fn checked(dir: &Path, file: &str) {
    let output = Command::new(EXE).current_dir(dir).args(["check", file]).output().unwrap();
    let said = String::from_utf8_lossy(&output.stdout);
    assert!(output.status.success() && said.contains("0 error(s)"), "check {file}: {said}");
}

#[test]
fn a_maestro_file_goes_to_a_project_and_back_through_the_map_it_saved() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("skull.xml"), super::maestro::SETTINGS).unwrap();
    let (ok, said, err) =
        convert(dir.path(), &["skull.xml", "--to", "servo", "--out", "skull.json", "--save-map", "map.json"]);
    assert!(ok, "{err}");
    assert!(said.starts_with("converted: 3 servos, 5 actions, 2 macros\n"), "{said}");
    assert_eq!(said.matches("a target of 0").count(), 1, "each note once: {said}");
    assert!(said.ends_with("wrote the joint map to map.json\nwrote skull.json\n"), "{said}");
    checked(dir.path(), "skull.json");
    let (ok, said, err) =
        convert(dir.path(), &["skull.json", "--to", "maestro", "--map", "map.json", "--out", "back.xml"]);
    assert!(ok, "{err}");
    assert!(said.contains("converted: 3 channels, 2 sequences, 5 frames"), "{said}");
    let back = std::fs::read_to_string(dir.path().join("back.xml")).unwrap();
    assert!(back.contains(r#"<Frame name="Frame 2" duration="1000">7200 0 6800 6000 0 0</Frame>"#), "{back}");
}

#[test]
fn every_format_is_told_from_its_content_and_converts_to_a_project_check_passes() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("a.txt"), super::robotis::mtn("1.0")).unwrap();
    std::fs::write(dir.path().join("b.xml"), super::robotis::MTNX).unwrap();
    for (input, to) in [("a.txt", "plen2"), ("a.txt", "servo"), ("b.xml", "plen2"), ("b.xml", "servo")] {
        let out = format!("{input}.{to}.json");
        let (ok, said, err) = convert(dir.path(), &[input, "--to", to, "--out", &out]);
        assert!(ok, "{input} → {to}: {err}");
        assert!(said.contains("converted: "), "{said}");
        checked(dir.path(), &out);
    }
    let (ok, _, err) = convert(dir.path(), &["a.txt", "--to", "plen2", "--page", "2", "--out", "walk.json"]);
    assert!(ok, "{err}");
    let (ok, said, err) = convert(dir.path(), &["walk.json", "--to", "blender", "--out", "walk.anim.json"]);
    assert!(ok, "{err}");
    assert!(said.contains("converted: \"Walk\": 18 servos"), "{said}");
}

#[test]
fn bad_input_is_said_with_where_and_nothing_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let broken = super::maestro::SETTINGS.replace("duration=\"250\"", "duration=\"soon\"");
    std::fs::write(dir.path().join("broken.xml"), broken).unwrap();
    std::fs::write(dir.path().join("kept.json"), "what was here").unwrap();
    let (ok, _, err) = convert(dir.path(), &["broken.xml", "--to", "servo", "--out", "kept.json"]);
    assert!(!ok);
    assert!(
        err.contains(
            "broken.xml is not a Maestro settings file (maestro); nothing was written (correct line 16 in a text editor, or save the file again from Maestro Control Center): line 16: <Frame>: duration \"soon\" is not a number"
        ),
        "{err}"
    );
    assert_eq!(std::fs::read_to_string(dir.path().join("kept.json")).unwrap(), "what was here", "nothing half-written");
    std::fs::write(dir.path().join("notes.txt"), "shopping list\n").unwrap();
    let (ok, _, err) = convert(dir.path(), &["notes.txt", "--to", "servo", "--out", "x.json"]);
    assert!(
        !ok && err.contains("cannot tell what notes.txt is")
            && err.contains(": give --from maestro, mtn, mtnx or blender"),
        "{err}"
    );
    assert!(!dir.path().join("x.json").exists());
    std::fs::write(dir.path().join("skull.xml"), super::maestro::SETTINGS).unwrap();
    let (ok, _, err) = convert(dir.path(), &["skull.xml", "--from", "mtnx", "--to", "servo", "--out", "x.json"]);
    assert!(!ok && err.contains("is not a R+ Motion .mtnx (mtnx)"), "{err}");
    std::fs::write(
        dir.path().join("bad.map.json"),
        r#"{"entries": [{"source": "0", "to": "servo 1", "zero": 6000, "per_degree": 0}]}"#,
    )
    .unwrap();
    let (ok, _, err) = convert(dir.path(), &["skull.xml", "--to", "servo", "--map", "bad.map.json", "--out", "x.json"]);
    assert!(!ok && err.contains("entry for \"0\": per_degree 0 must be a number other than 0"), "{err}");
    let (ok, _, err) = convert(dir.path(), &["skull.xml", "--to", "plen2", "--out", "x.json"]);
    assert!(!ok && err.contains("no channel drives a PLEN2: give a joint map (--map)"), "{err}");
    assert!(!dir.path().join("x.json").exists());
}
