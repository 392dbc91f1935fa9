//! `servo-studio follow-audio`: a sound of noise bursts at hand-picked times,
//! followed by a servo (servo board) and a joint (PLEN2). What the board then
//! plays is read back through `trajectory` and checked against times worked
//! by hand: open through each burst once the attack has passed, closed
//! between once the release has.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::cast_possible_truncation, clippy::cast_sign_loss)]

use std::path::Path;
use std::process::Command;

const EXE: &str = env!("CARGO_BIN_EXE_servo-studio");
const RATE: u32 = 44_100;

/// `seconds` of faint hiss with loud noise over each `(from, to)` burst (seconds).
fn bursts(seconds: f64, bursts_s: &[(f64, f64)]) -> Vec<f32> {
    let mut walk = 0x2545_f491_u32;
    let len = (seconds * f64::from(RATE)) as usize;
    (0..len)
        .map(|i| {
            walk ^= walk << 13;
            walk ^= walk >> 17;
            walk ^= walk << 5;
            let noise = f64::from(walk) / f64::from(u32::MAX) * 2.0 - 1.0;
            let t = i as f64 / f64::from(RATE);
            let loud = bursts_s.iter().any(|(from, to)| (*from..*to).contains(&t));
            (noise * if loud { 0.6 } else { 0.001 }) as f32
        })
        .collect()
}

fn run(args: &[&str]) -> (bool, String, String) {
    let output = Command::new(EXE).args(args).output().unwrap();
    let text = |bytes: &[u8]| String::from_utf8_lossy(bytes).into_owned();
    (output.status.success(), text(&output.stdout), text(&output.stderr))
}

/// `trajectory`'s CSV: each row's time (ms) and its value in `column`.
fn played(csv: &Path, column: &str) -> Vec<(f64, f64)> {
    let text = std::fs::read_to_string(csv).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let at = header.iter().position(|name| *name == column).unwrap_or_else(|| panic!("{column} in {header:?}"));
    lines
        .map(|line| {
            let fields: Vec<f64> = line.split(',').map(|field| field.parse().unwrap()).collect();
            (fields[0], fields[at])
        })
        .collect()
}

/// Every row from `from` ms to `to` ms satisfies `ok`.
fn check(rows: &[(f64, f64)], from: f64, to: f64, what: &str, ok: impl Fn(f64) -> bool) {
    let within: Vec<&(f64, f64)> = rows.iter().filter(|(t, _)| (from..to).contains(t)).collect();
    assert!(within.len() > 3, "rows from {from} to {to} ms");
    for (t, value) in within {
        assert!(ok(*value), "{what} at {t} ms, but the board plays {value}");
    }
}

#[test]
fn a_servo_follows_noise_bursts_open_during_each_and_closed_between() {
    let dir = tempfile::tempdir().unwrap();
    let sound = dir.path().join("talk.wav");
    let spoken = [(0.30, 0.70), (1.20, 1.50), (2.10, 2.80)];
    std::fs::write(&sound, servo_studio::audio::pcm16_wav(&bursts(3.4, &spoken), RATE, 1)).unwrap();
    let project = dir.path().join("jaw.json");
    let (ok, stdout, stderr) = run(&[
        "follow-audio",
        sound.to_str().unwrap(),
        "--protocol",
        "servo",
        "--servo",
        "3",
        "--closed",
        "10",
        "--open",
        "50",
        "--attack-ms",
        "10",
        "--release-ms",
        "40",
        "--out",
        project.to_str().unwrap(),
    ]);
    assert!(ok, "{stderr}");
    assert!(stdout.contains("steps") && stdout.contains(project.to_str().unwrap()), "{stdout}");
    let csv = dir.path().join("jaw.csv");
    let (ok, _, stderr) =
        run(&["trajectory", project.to_str().unwrap(), "--macro", "1", "--out", csv.to_str().unwrap()]);
    assert!(ok, "{stderr}");
    let rows = played(&csv, "servo 3");
    // Worked by hand: the level is the last 10 ms, the attack is 10 ms (open
    // within 1 % after five of them), the release 40 ms (closed within 1 %
    // after five); the fit may stray 1° more, and the board holds whole degrees.
    for (from, to) in spoken {
        let (from_ms, to_ms) = (from * 1000.0, to * 1000.0);
        check(&rows, from_ms + 10.0 + 50.0, to_ms, "open (50°)", |deg| deg >= 48.5);
    }
    let quiet = [(0.0, 0.30), (0.70, 1.20), (1.50, 2.10), (2.80, 3.4)];
    for (i, (from, to)) in quiet.into_iter().enumerate() {
        let settled = if i == 0 { 0.0 } else { from * 1000.0 + 10.0 + 200.0 };
        check(&rows, settled, to * 1000.0, "closed (10°)", |deg| deg <= 11.5);
    }
}

#[test]
fn a_plen2_joint_nods_to_two_beats_within_a_motions_twenty_frames() {
    let dir = tempfile::tempdir().unwrap();
    let sound = dir.path().join("beat.wav");
    let beats = [(0.40, 0.80), (1.40, 1.80)];
    std::fs::write(&sound, servo_studio::audio::pcm16_wav(&bursts(2.4, &beats), RATE, 1)).unwrap();
    let motion = dir.path().join("nod.json");
    let (ok, stdout, stderr) = run(&[
        "follow-audio",
        sound.to_str().unwrap(),
        "--protocol",
        "plen2",
        "--joint",
        "left_shoulder_pitch",
        "--closed",
        "0",
        "--open",
        "-30",
        "--release-ms",
        "40",
        "--tolerance-deg",
        "2",
        "--out",
        motion.to_str().unwrap(),
    ]);
    assert!(ok, "{stderr}");
    assert!(stdout.contains("frames"), "{stdout}");
    let csv = dir.path().join("nod.csv");
    let (ok, _, stderr) = run(&["trajectory", motion.to_str().unwrap(), "--slot", "0", "--out", csv.to_str().unwrap()]);
    assert!(ok, "{stderr}");
    // Tenths of a degree from home; one PLEN2 update is 32.768 ms, and the fit may stray 2°.
    let rows = played(&csv, "left_shoulder_pitch");
    for (from, to) in beats {
        check(&rows, from * 1000.0 + 60.0 + 33.0, to * 1000.0, "open (−30°)", |tenths| tenths <= -270.0);
    }
    for (from, to) in [(0.0, 0.40), (0.80, 1.40), (1.80, 2.4)] {
        let settled = if from == 0.0 { 0.0 } else { from * 1000.0 + 210.0 + 33.0 };
        check(&rows, settled, to * 1000.0, "closed (0°)", |tenths| tenths.abs() <= 25.0);
    }
}

/// `follow-audio` of `spoken` bursts in `seconds` by a PLEN2's left shoulder
/// (0° closed, −30° open) with `extra` arguments: what it printed, and the
/// robot's playback from `slot` (tenths of a degree from home at each cycle).
fn plen2_follow(
    dir: &Path,
    seconds: f64,
    spoken: &[(f64, f64)],
    extra: &[&str],
    slot: &str,
) -> (String, Vec<(f64, f64)>) {
    let sound = dir.join("talk.wav");
    std::fs::write(&sound, servo_studio::audio::pcm16_wav(&bursts(seconds, spoken), RATE, 1)).unwrap();
    let out = dir.join(if extra.contains(&"--from-slot") { "robot.json" } else { "talk.json" });
    let mut args = vec!["follow-audio", sound.to_str().unwrap(), "--protocol", "plen2"];
    args.extend_from_slice(&["--joint", "left_shoulder_pitch", "--closed", "0", "--open", "-30"]);
    args.extend_from_slice(extra);
    args.extend_from_slice(&["--out", out.to_str().unwrap()]);
    let (ok, stdout, stderr) = run(&args);
    assert!(ok, "{spoken:?}: {stderr}");
    let csv = dir.join("played.csv");
    let (ok, _, stderr) = run(&["trajectory", out.to_str().unwrap(), "--slot", slot, "--out", csv.to_str().unwrap()]);
    assert!(ok, "{stderr}");
    (stdout, played(&csv, "left_shoulder_pitch"))
}

/// The frames a `follow-audio` line says it made ("20 frames …").
fn frames_said(said: &str) -> usize {
    said.split_whitespace().next().and_then(|count| count.parse().ok()).unwrap_or_else(|| panic!("{said}"))
}

/// Open through each burst once the level (10 ms), the attack (five of
/// 10 ms) and a cycle have passed, and a shift of up to 16 ms; closed before
/// the first.
fn opened_through(rows: &[(f64, f64)], spoken: &[(f64, f64)], tolerance_tenths: f64) {
    for (from, to) in spoken {
        check(rows, from * 1000.0 + 60.0 + 33.0 + 16.0, to * 1000.0, "open (−30°)", |tenths| {
            tenths <= -300.0 + tolerance_tenths + 1.0
        });
    }
    check(rows, 0.0, spoken[0].0 * 1000.0 - 16.0, "closed (0°)", |tenths| tenths.abs() <= tolerance_tenths + 1.0);
}

/// Three bursts in 4.2 s at 1° fit one motion (20 frames), as they did
/// before follow-audio read a sound's milliseconds exactly: the same curve
/// needs 18 to 21 frames as the robot's cycles fall against it, and where a
/// phase within half a cycle fits, it is taken and said.
#[test]
fn a_plen2_joint_follows_three_bursts_at_one_degree_in_one_motion() {
    let dir = tempfile::tempdir().unwrap();
    let sounds = [
        [(0.72, 1.20), (1.62, 1.91), (2.51, 3.13)],
        [(0.40, 0.80), (1.60, 2.00), (2.90, 3.40)],
        [(0.37, 0.99), (1.47, 1.80), (2.15, 2.57)],
    ];
    for spoken in sounds {
        let (said, rows) = plen2_follow(dir.path(), 4.2, &spoken, &[], "0");
        assert!(frames_said(&said) <= 20 && said.contains("largest error"), "{spoken:?}: {said}");
        opened_through(&rows, &spoken, 10.0);
    }
}

/// `--from-slot N`: a sound too long for one motion becomes a chain of
/// motions in slots N, N+1, … (each jumping to the next) in a project the
/// robot plays as one; given the same project again it replaces the slots
/// it takes and says which; another file at --out is never replaced (and a
/// servo board's follow takes no slot: `follow_audio_says_what_is_wrong…`).
#[test]
fn from_slot_chains_motions_into_a_plen2_project_as_the_editor_does() {
    let dir = tempfile::tempdir().unwrap();
    let spoken: Vec<(f64, f64)> = (0..9).map(|k| (0.5 + 1.3 * f64::from(k), 0.9 + 1.3 * f64::from(k))).collect();
    let (said, rows) = plen2_follow(dir.path(), 12.4, &spoken, &["--from-slot", "40"], "40");
    assert!(said.contains("from slot 40 (slots 40, 41") && said.contains("each jumping to the next"), "{said}");
    assert!(frames_said(&said) > 20, "{said}");
    assert!(rows.last().unwrap().0 >= 12_000.0, "the chain plays the whole sound: {} ms", rows.last().unwrap().0);
    opened_through(&rows, &spoken, 10.0);
    let robot = dir.path().join("robot.json");
    let (ok, stdout, _) = run(&["check", robot.to_str().unwrap()]);
    assert!(ok && stdout.contains("0 error(s)"), "{stdout}");
    // Again from slot 41, into the same project: slot 40 kept, 41 on replaced.
    let (said, _) = plen2_follow(dir.path(), 12.4, &spoken, &["--from-slot", "41"], "40");
    assert!(said.contains("replaced: 41 talk"), "{said}");
    let project = servo_studio::project::from_json(&std::fs::read_to_string(&robot).unwrap()).unwrap();
    assert!(project.plen2.motions.iter().any(|motion| motion.slot == 40 && motion.name == "talk"));
    // A servo project at --out is refused and left as it was; --from-slot is a PLEN2's.
    let servo = dir.path().join("servo.json");
    let kept = servo_studio::project::to_json(&servo_studio::project::Project::servo(Default::default()));
    std::fs::write(&servo, &kept).unwrap();
    let sound = dir.path().join("talk.wav");
    let (sound, servo_text) = (sound.to_str().unwrap(), servo.to_str().unwrap());
    let plen2 = ["--protocol", "plen2", "--joint", "left_shoulder_pitch", "--closed", "0", "--open", "-30"];
    let mut args = vec!["follow-audio", sound];
    args.extend_from_slice(&plen2);
    args.extend_from_slice(&["--from-slot", "3", "--out", servo_text]);
    let (ok, _, stderr) = run(&args);
    assert!(!ok && stderr.contains("adds motions to a PLEN2 project"), "{stderr}");
    assert_eq!(std::fs::read_to_string(&servo).unwrap(), kept);
}

#[test]
fn follow_audio_says_what_is_wrong_before_writing_anything() {
    let dir = tempfile::tempdir().unwrap();
    let sound = dir.path().join("beat.wav");
    std::fs::write(&sound, servo_studio::audio::pcm16_wav(&bursts(1.0, &[(0.2, 0.5)]), RATE, 1)).unwrap();
    let out = dir.path().join("out.json");
    let (sound, out_text) = (sound.to_str().unwrap(), out.to_str().unwrap());
    let cases: [(&[&str], &str); 5] = [
        (&["--protocol", "plen2", "--joint", "jaw", "--closed", "0", "--open", "10"], "is not a PLEN2 joint"),
        (&["--protocol", "servo", "--joint", "left_shoulder_pitch", "--closed", "0", "--open", "10"], "--servo N"),
        (&["--protocol", "servo", "--servo", "1", "--closed", "0", "--open", "10", "--attack-ms", "0"], "0.1..=10000"),
        (&["--protocol", "servo", "--closed", "0", "--open", "10"], "--servo"),
        (
            &["--protocol", "servo", "--servo", "1", "--closed", "0", "--open", "10", "--from-slot", "3"],
            "is for a PLEN2",
        ),
    ];
    for (args, said) in cases {
        let mut full = vec!["follow-audio", sound];
        full.extend_from_slice(args);
        full.extend_from_slice(&["--out", out_text]);
        let (ok, _, stderr) = run(&full);
        assert!(!ok && stderr.contains(said), "{args:?}: {stderr}");
        assert!(!out.exists(), "{args:?} wrote {out_text}");
    }
    let not_sound = Path::new(out_text).with_extension("txt");
    std::fs::write(&not_sound, "no sound").unwrap();
    let (ok, _, stderr) = run(&[
        "follow-audio",
        not_sound.to_str().unwrap(),
        "--protocol",
        "servo",
        "--servo",
        "1",
        "--closed",
        "0",
        "--open",
        "10",
        "--out",
        out_text,
    ]);
    assert!(!ok && stderr.contains("out.txt") && stderr.contains("WAV, FLAC, MP3"), "{stderr}");
    assert!(!out.exists());
}
