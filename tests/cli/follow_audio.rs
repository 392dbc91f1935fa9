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

#[test]
fn follow_audio_says_what_is_wrong_before_writing_anything() {
    let dir = tempfile::tempdir().unwrap();
    let sound = dir.path().join("beat.wav");
    std::fs::write(&sound, servo_studio::audio::pcm16_wav(&bursts(1.0, &[(0.2, 0.5)]), RATE, 1)).unwrap();
    let out = dir.path().join("out.json");
    let (sound, out_text) = (sound.to_str().unwrap(), out.to_str().unwrap());
    let cases: [(&[&str], &str); 4] = [
        (&["--protocol", "plen2", "--joint", "jaw", "--closed", "0", "--open", "10"], "is not a PLEN2 joint"),
        (&["--protocol", "servo", "--joint", "left_shoulder_pitch", "--closed", "0", "--open", "10"], "--servo N"),
        (&["--protocol", "servo", "--servo", "1", "--closed", "0", "--open", "10", "--attack-ms", "0"], "0.1..=10000"),
        (&["--protocol", "servo", "--closed", "0", "--open", "10"], "--servo"),
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
