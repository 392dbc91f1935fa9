//! `servo-studio audio-info SOUND`: one JSON object with the sound's length,
//! rate, channels and onsets, checked against a click track the test writes
//! (clicks at hand-picked times) and against a file that is no sound.

#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::cast_possible_truncation,
    clippy::cast_sign_loss,
    clippy::cast_precision_loss
)]

use std::process::Command;

const EXE: &str = env!("CARGO_BIN_EXE_servo-studio");

/// `seconds` of silence at `rate` with a short ringing click (louder first,
/// `length` samples) at each of `clicks_s`.
fn click_track(rate: u32, seconds: f64, clicks_s: &[f64], length: usize) -> Vec<f32> {
    let mut samples = vec![0.0f32; (seconds * f64::from(rate)) as usize];
    for at in clicks_s {
        let start = (at * f64::from(rate)) as usize;
        let ring = length as f32 / 5.0;
        for (i, sample) in samples[start..start + length].iter_mut().enumerate() {
            *sample = (i as f32 * 0.8).sin() * (-(i as f32) / ring).exp() * 0.9;
        }
    }
    samples
}

#[test]
fn audio_info_prints_the_length_rate_channels_and_every_click_within_10_ms() {
    let dir = tempfile::tempdir().unwrap();
    let rate = 22_050u32;
    let clicks_s = [0.4, 1.15, 1.3, 2.72];
    let path = dir.path().join("clicks.wav");
    std::fs::write(&path, servo_studio::audio::pcm16_wav(&click_track(rate, 3.0, &clicks_s, 200), rate, 2)).unwrap();
    let output = Command::new(EXE).arg("audio-info").arg(&path).output().unwrap();
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let info: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    assert_eq!(info["sample_rate"], 22_050);
    assert_eq!(info["channels"], 2);
    assert!((info["duration_s"].as_f64().unwrap() - 3.0).abs() < 1e-3);
    let onsets: Vec<f64> = info["onsets_s"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect();
    assert_eq!(onsets.len(), clicks_s.len(), "{onsets:?}");
    for (found, click) in onsets.iter().zip(clicks_s) {
        assert!((found - click).abs() < 0.010, "a click at {click} s found at {found} s");
    }

    let bad = dir.path().join("notes.wav");
    std::fs::write(&bad, "not a sound").unwrap();
    let output = Command::new(EXE).arg("audio-info").arg(&bad).output().unwrap();
    assert_eq!(output.status.code(), Some(1));
    let said = String::from_utf8_lossy(&output.stderr);
    assert!(said.contains("notes.wav") && said.contains("WAV, FLAC, MP3, OGG"), "{said}");
}

/// One click track in every format: written here as WAV, and kept as FLAC,
/// MP3 and OGG/Vorbis made once by real encoders (`tests/fixtures/sound`,
/// with their recipe): the same length, rate and clicks from each.
#[test]
fn every_format_decodes_to_the_same_sound_and_clicks() {
    let fixtures = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/sound");
    let dir = tempfile::tempdir().unwrap();
    let rate = 22_050u32;
    let clicks_s = [0.3, 0.95, 1.6, 2.2];
    let wav = dir.path().join("clicks.wav");
    std::fs::write(&wav, servo_studio::audio::pcm16_wav(&click_track(rate, 2.5, &clicks_s, 400), rate, 2)).unwrap();
    for extension in ["wav", "flac", "mp3", "ogg"] {
        let path = if extension == "wav" { wav.clone() } else { fixtures.join(format!("clicks.{extension}")) };
        let analysis = servo_studio::audio::analyse(&path, 0.5, |_| {}).unwrap();
        assert_eq!((analysis.sample_rate, analysis.channels), (rate, 2), "{extension}");
        // MP3 and Vorbis come in blocks (1,152 samples; up to 2,048): the end may be padded to whole ones.
        let slack = if matches!(extension, "mp3" | "ogg") { 0.1 } else { 0.001 };
        assert!((analysis.duration_s() - 2.5).abs() < slack, "{extension}: {} s", analysis.duration_s());
        assert_eq!(analysis.onsets_s.len(), clicks_s.len(), "{extension}: {:?}", analysis.onsets_s);
        for (found, click) in analysis.onsets_s.iter().zip(clicks_s) {
            assert!((found - click).abs() < 0.010, "{extension}: a click at {click} s found at {found} s");
        }
    }
}
