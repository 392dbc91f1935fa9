//! Files asking for more than any board or tool holds (a settings file of a
//! million channels, an animation of two million frames) are refused where
//! they pass the bound, before the rest is built: `convert` runs with its
//! data limited to three times the file and 64 MiB (`ulimit -d`), which the
//! readers that built the whole file first (up to 13 times its size) could
//! not keep to.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::fmt::Write as _;
use std::path::Path;
use std::process::Command;

const EXE: &str = env!("CARGO_BIN_EXE_servo-studio");

/// The line (from 1) of the `nth` (from 1) occurrence of `mark` in `text`.
fn line_of(text: &str, mark: &str, nth: usize) -> usize {
    let (at, _) = text.match_indices(mark).nth(nth - 1).expect("so many in the file");
    text[..at].matches('\n').count() + 1
}

/// `convert` of `text` (as `name`) with its data limited to three times the
/// file and 64 MiB: refused, saying `message` at `line`, nothing written.
fn refused_within_three_times_its_size(name: &str, text: &str, message: &str, line: usize) {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join(name);
    std::fs::write(&input, text).unwrap();
    let limit_kib = 3 * text.len() / 1024 + 64 * 1024;
    let output = Command::new("sh")
        .arg("-c")
        .arg(format!("ulimit -d {limit_kib} && exec \"$0\" convert \"$1\" --to servo --out \"$2\""))
        .arg(EXE)
        .arg(&input)
        .arg(dir.path().join("out.json"))
        .output()
        .unwrap();
    let said = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{name} ({} MB): refused, not killed: {said}", text.len() >> 20);
    assert!(
        said.contains(message) && said.contains(&format!("line {line}:")),
        "{name}: {message} at line {line}: {said}"
    );
    assert!(!Path::new(&dir.path().join("out.json")).exists(), "{name}: nothing written");
}

const CHANNEL: &str = r#"    <Channel name="" mode="Servo" min="3968" max="8000" homemode="Off" home="3968" speed="0" acceleration="0" neutral="6000" range="1905" />"#;

fn maestro(channels: usize, frames: usize) -> String {
    let mut text = String::from(
        "<!--Pololu Maestro servo controller settings file-->\n<UscSettings version=\"1\">\n  <Channels ServosAvailable=\"6\" ServoPeriod=\"156\">\n",
    );
    for _ in 0..channels {
        text.push_str(CHANNEL);
        text.push('\n');
    }
    text.push_str("  </Channels>\n  <Sequences>\n    <Sequence name=\"s\">\n");
    for frame in 0..frames {
        writeln!(text, "      <Frame name=\"Frame {frame}\" duration=\"20\">6000 6000 6000 6000 6000 6000</Frame>")
            .unwrap();
    }
    text.push_str("    </Sequence>\n  </Sequences>\n</UscSettings>\n");
    text
}

#[test]
fn a_maestro_file_of_more_channels_or_frames_than_a_board_holds_is_refused_as_it_is_read() {
    let channels = maestro(150_000, 0);
    let line = line_of(&channels, "<Channel ", 257);
    refused_within_three_times_its_size("channels.xml", &channels, "more than 256 <Channel>", line);
    let frames = maestro(6, 400_000);
    let line = line_of(&frames, "<Frame ", 100_001);
    refused_within_three_times_its_size("frames.xml", &frames, "more than 100000 <Frame>", line);
}

#[test]
fn roboplus_files_of_more_steps_or_values_than_any_tool_writes_are_refused_as_they_are_read() {
    let mut mtn = String::from("type=motion\nversion=1.01\npage_begin\nname=long\n");
    for _ in 0..200_000 {
        mtn.push_str("step=512 512 512 512 512 512 512 512 512 512 512 512 512 512 0.000 0.096\n");
    }
    mtn.push_str("page_end\n");
    refused_within_three_times_its_size("long.mtn", &mtn, "more than 100000 steps", line_of(&mtn, "step=", 100_001));
    let wide = format!("type=motion\npage_begin\nstep={} 0 0.1\npage_end\n", "512 ".repeat(3_000_000));
    refused_within_three_times_its_size("wide.mtn", &wide, "more than 258 values", 3);
    let mut mtnx = String::from(
        "<?xml version=\"1.0\"?>\n<Root name=\"R+Motion\" version=\"2.0.0\">\n<PageRoot>\n<Page name=\"p\">\n<steps>\n",
    );
    for step in 0..300_000 {
        writeln!(mtnx, "<step frame=\"{step}\" pose=\"0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0\" />").unwrap();
    }
    mtnx.push_str("</steps>\n</Page>\n</PageRoot>\n</Root>\n");
    refused_within_three_times_its_size(
        "long.mtnx",
        &mtnx,
        "more than 100000 <step>",
        line_of(&mtnx, "<step ", 100_001),
    );
}

#[test]
fn a_blender_export_of_more_servos_or_frames_than_an_animation_holds_is_refused_as_it_is_read() {
    let mut servos = String::from("{\"fps\": 30, \"frames\": 2, \"servos\": {\n");
    for id in 0..200_000 {
        writeln!(servos, "\"{id}\": {{\"name\": \"bone{id}\", \"positions\": [375, 400]}},").unwrap();
    }
    servos.push_str("\"last\": {\"positions\": [375, 400]}}}\n");
    let said = "<servos.256>: more than 256 servos";
    refused_within_three_times_its_size("servos.json", &servos, said, line_of(&servos, "\"name\"", 257));
    let frames = format!(
        "{{\"fps\": 30, \"servos\": {{\"0\": {{\"name\": \"jaw\", \"positions\": [\n{}375]}}}}}}\n",
        "375,\n".repeat(2_000_000)
    );
    let said = "<servos.0.positions[108001]>: more than 108001 frames at 30 fps";
    refused_within_three_times_its_size("frames.json", &frames, said, 108_003);
}
