//! Blender servo-animation add-on JSON: one position per animation frame at
//! `fps`. In: fitted into the fewest frames / steps whose playback on the
//! board stays within the tolerance of the animation at every update. Out:
//! a motion sampled at a frame rate, read back to what the board plays.
//! The official PLEN2 motions go out and back in.

#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::float_cmp,
    clippy::cast_precision_loss,
    clippy::cast_possible_truncation
)]

use servo_studio::device::plen2::playback::{self, Playback, StoredMotions};
use servo_studio::interchange::build::{self, Options};
use servo_studio::interchange::{self, Body, Format, JointMap, export};
use servo_studio::project::plen2::Joint;
use servo_studio::project::{self, Family, Run};
use servo_studio::protocol::plen2::DEVICE_IDS;

/// Two servos over 3 s at 30 fps, in µs: a sine on servo 3 (±40°), a ramp on servo 7.
fn animation() -> (String, Vec<Vec<f64>>) {
    let per_degree = 2000.0 / 180.0;
    let degrees: Vec<Vec<f64>> = (0..=90)
        .map(|frame| {
            let t = f64::from(frame) / 30.0;
            vec![40.0 * (t * std::f64::consts::PI).sin(), -20.0 + 10.0 * t]
        })
        .collect();
    let column = |servo: usize| {
        let positions: Vec<String> =
            degrees.iter().map(|row| format!("{:.2}", 1500.0 + row[servo] * per_degree)).collect();
        positions.join(", ")
    };
    let text = format!(
        r#"{{"description": "Blender Servo Animation Positions", "fps": 30, "frames": 91, "seconds": 3, "bones": 2, "armature": "Armature", "file": "head.blend", "scene": "Scene",
"servos": {{"3": {{"name": "Jaw", "positions": [{}]}}, "7": {{"name": "Neck", "positions": [{}]}}}}}}"#,
        column(0),
        column(1)
    );
    // The angles as the file holds them (positions written to a hundredth of a µs):
    // a fit within the tolerance of the file is within it of these.
    let written = degrees
        .iter()
        .map(|row| {
            row.iter()
                .map(|angle| (((1500.0 + angle * per_degree) * 100.0).round() / 100.0 - 1500.0) / per_degree)
                .collect()
        })
        .collect();
    (text, written)
}

/// The animation's angle (degrees) at `ms`, joined straight between frames.
fn wanted(degrees: &[Vec<f64>], servo: usize, ms: f64) -> f64 {
    let at = (ms * 30.0 / 1000.0).min((degrees.len() - 1) as f64);
    let (frame, share) = (at.floor() as usize, at.fract());
    let next = (frame + 1).min(degrees.len() - 1);
    degrees[frame][servo] + (degrees[next][servo] - degrees[frame][servo]) * share
}

#[test]
fn an_animation_is_fitted_for_a_servo_board_within_the_tolerance_at_every_update() {
    let (text, degrees) = animation();
    for tolerance in [1.0, 0.5] {
        let source = interchange::read(Format::Blender, &text).unwrap();
        assert_eq!(source.channels[0].name, "Jaw");
        let map = JointMap::for_source(&source, Family::Servo, None);
        let options = Options { tolerance_deg: tolerance, ..Options::new(Family::Servo) };
        let built = build::build(&source, &map, &options).unwrap();
        let servo = &built.project.servo;
        let (trajectories, end_ms) =
            project::trace(servo, Run::Macro { macro_id: servo.macros[0].id }, 60_000.0).unwrap();
        assert_eq!(end_ms, 3000.0);
        let mut worst: f64 = 0.0;
        for update in 0..=300 {
            let ms = f64::from(update) * 10.0;
            for (index, id) in [3u8, 7].into_iter().enumerate() {
                let got =
                    project::angle_at(&trajectories[&id], ms).unwrap_or(f64::from(servo.servo(id).unwrap().home_deg));
                worst = worst.max((got - wanted(&degrees, index, ms)).abs());
            }
        }
        assert!(worst <= tolerance + 1e-9, "{worst}° from the animation at {tolerance}°");
        assert!(servo.actions.len() < 300 / 2, "fewer steps than samples: {}", servo.actions.len());
    }
}

#[test]
fn an_animation_is_fitted_for_a_plen2_within_the_tolerance_at_every_cycle() {
    let (text, degrees) = animation();
    // Servo 3 drives the left knee, servo 7 the right elbow (a map file says so).
    let map = JointMap::from_json(
        r#"{"entries": [
            {"source": "3", "to": "left_knee_pitch", "zero": 1500, "per_degree": 11.111111111111111},
            {"source": "7", "to": "right_elbow_roll", "zero": 1500, "per_degree": 11.111111111111111, "direction": -1}]}"#,
    )
    .unwrap();
    let source = interchange::read(Format::Blender, &text).unwrap();
    let built =
        build::build(&source, &JointMap::for_source(&source, Family::Plen2, Some(&map)), &Options::new(Family::Plen2))
            .unwrap();
    let plen2 = &built.project.plen2;
    let play = playback::play(&StoredMotions::new(plen2), plen2.motions[0].slot, [0; DEVICE_IDS], 200);
    let knee = usize::from(Joint::LeftKneePitch.device_id());
    let elbow = usize::from(Joint::RightElbowRoll.device_id());
    for (cycle, values) in play.cycles.iter().enumerate() {
        // Cycle k at k × 32.768 ms, as `trajectory` writes it.
        let ms = cycle as f64 * Playback::CYCLE_MS;
        if ms > 3000.0 {
            break;
        }
        assert!((f64::from(values[knee]) / 10.0 - wanted(&degrees, 0, ms)).abs() <= 1.0 + 1e-9, "knee at {ms} ms");
        assert!(
            (f64::from(values[elbow]) / 10.0 + wanted(&degrees, 1, ms)).abs() <= 1.0 + 1e-9,
            "elbow (reversed) at {ms} ms"
        );
    }
}

#[test]
fn a_macro_goes_out_as_an_animation_that_reads_back_to_what_the_board_plays() {
    let (text, _) = animation();
    let source = interchange::read(Format::Blender, &text).unwrap();
    let built =
        build::build(&source, &JointMap::for_source(&source, Family::Servo, None), &Options::new(Family::Servo))
            .unwrap();
    let servo = &built.project.servo;
    let (out, report) = export::blender_servo(servo, servo.macros[0].id, 50.0, None).unwrap();
    assert!(report.converted[0].contains("151 frames at 50 fps"), "{report:?}");
    let again = interchange::read(Format::Blender, &out).unwrap();
    let Body::Samples { fps, rows } = &again.clips[0].body else { panic!("samples") };
    assert_eq!(*fps, 50.0);
    let (trajectories, _) = project::trace(servo, Run::Macro { macro_id: servo.macros[0].id }, 60_000.0).unwrap();
    let map = JointMap::for_source(&again, Family::Servo, None);
    for (frame, row) in rows.iter().enumerate() {
        let ms = frame as f64 * 20.0;
        for (channel, value) in again.channels.iter().zip(row) {
            let id: u8 = channel.key.parse().unwrap();
            let board =
                project::angle_at(&trajectories[&id], ms).unwrap_or(f64::from(servo.servo(id).unwrap().home_deg));
            let back = map.entry(&channel.key).unwrap().degrees(*value);
            assert!((back - board).abs() < 0.01, "servo {id} at {ms} ms: {back} written, {board} played");
        }
    }
}

#[test]
fn the_official_motions_go_out_and_back_within_the_tolerance() {
    let Some(files) = crate::common::official_motion_files() else { return };
    let fps = 1000.0 / Playback::CYCLE_MS;
    let mut checked = 0;
    for file in &files {
        let (motion, _) = project::motion_json::read_motion_file(file).unwrap();
        let mut original = project::Project::empty(Family::Plen2);
        original.plen2.motions.push(motion.clone());
        let before = playback::play(&StoredMotions::new(&original.plen2), motion.slot, [0; DEVICE_IDS], 3000);
        if !before.ended {
            continue;
        }
        let (out, _) = export::blender_plen2(&original.plen2, motion.slot, fps, None).unwrap();
        let source = interchange::read(Format::Blender, &out).unwrap();
        let map = JointMap::for_source(&source, Family::Plen2, None);
        assert_eq!(
            map.entries.iter().filter(|e| e.target.is_some()).count(),
            18,
            "{}: every joint by its name",
            file.display()
        );
        let built = build::build(&source, &map, &Options::new(Family::Plen2)).unwrap();
        let plen2 = &built.project.plen2;
        let after = playback::play(&StoredMotions::new(plen2), plen2.motions[0].slot, [0; DEVICE_IDS], 3000);
        for (cycle, (was, now)) in before.cycles.iter().zip(&after.cycles).enumerate() {
            for device in 0..DEVICE_IDS {
                assert!(
                    (was[device] - now[device]).abs() <= 10,
                    "{}: device {device} at cycle {cycle}: {} then {}",
                    file.display(),
                    was[device],
                    now[device]
                );
            }
        }
        checked += 1;
    }
    assert!(checked >= files.len() / 2, "{checked} of {} official motions end and were checked", files.len());
}

#[test]
fn malformed_animations_say_where() {
    let read = |text: &str| interchange::read(Format::Blender, text).unwrap_err().to_string();
    let (text, _) = animation();
    let cut = read(&text[..text.len() / 2]);
    assert!(cut.starts_with("line 2: <servos.3.positions[") && cut.contains("not JSON"), "{cut}");
    let word = read(&text.replacen("\"Jaw\", \"positions\": [", "\"Jaw\", \"positions\": [\"x\", ", 1));
    assert!(word.starts_with("line 2: <servos.3.positions[0]>: \"x\" is not a number"), "{word}");
    let bare = read(&text.replacen("\"Jaw\", \"positions\": [", "\"Jaw\", \"positions\": [x, ", 1));
    assert!(bare.starts_with("line 2: <servos.3.positions[0]>: not JSON"), "{bare}");
    assert!(read(r#"{"servos": {}}"#).contains("fps"));
    assert!(
        read(r#"{"fps": 30, "servos": {"1": {"positions": [1, 2]}, "2": {"positions": [1]}}}"#)
            .contains("1 positions where the first servo has 2")
    );
}
