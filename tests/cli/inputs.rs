//! The newer inputs — sounds, meshes, other tools' files — as a careless or
//! hostile file presents them: named pipes, devices and links to them,
//! sparse giants, headers that declare what the file cannot hold, times and
//! rates no board can mean. Each is refused before it is read, naming what
//! is wrong, with status 1 (never 101, never a hang, never gigabytes); a
//! failed command writes nothing; an output that names an input is refused
//! before anything is read.

#![cfg(unix)]
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::cast_possible_truncation)]

use std::path::Path;
use std::time::Duration;

use crate::common;

/// Runs `servo-studio ARGS` in `cwd` with a watchdog; (exit code, stdout, stderr).
fn run_in(cwd: &Path, args: &[&str]) -> (Option<i32>, String, String) {
    let (code, stdout, stderr, _) = common::run_in(cwd, args, Duration::from_secs(60));
    (code, stdout, stderr)
}

/// `follow-audio SOUND` on servo 1 (0° closed, 30° open) `--out OUT`, in `cwd`.
fn follow(cwd: &Path, sound: &str, out: &str) -> (Option<i32>, String, String) {
    let args = ["--protocol", "servo", "--servo", "1", "--closed", "0", "--open", "30", "--out", out];
    run_in(cwd, &[&["follow-audio", sound][..], &args[..]].concat())
}

fn mkfifo(path: &Path) {
    assert!(std::process::Command::new("mkfifo").arg(path).status().unwrap().success());
}

/// A WAV header saying `rate` and `channels`, with `data` bytes of silence.
fn wav_saying(rate: u32, channels: u16, data: usize) -> Vec<u8> {
    let mut out = Vec::new();
    out.extend(b"RIFF");
    out.extend(u32::try_from(36 + data).unwrap().to_le_bytes());
    out.extend(b"WAVEfmt ");
    out.extend(16u32.to_le_bytes());
    out.extend(1u16.to_le_bytes());
    out.extend(channels.to_le_bytes());
    out.extend(rate.to_le_bytes());
    out.extend(rate.wrapping_mul(2 * u32::from(channels)).to_le_bytes());
    out.extend((2 * channels).to_le_bytes());
    out.extend(16u16.to_le_bytes());
    out.extend(b"data");
    out.extend(u32::try_from(data).unwrap().to_le_bytes());
    out.resize(out.len() + data, 0);
    out
}

#[test]
fn sounds_that_are_pipes_devices_or_links_to_them_are_refused_before_reading() {
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("p.wav");
    mkfifo(&fifo);
    let zero = dir.path().join("zero.wav");
    std::os::unix::fs::symlink("/dev/zero", &zero).unwrap();
    for (path, what) in [(&fifo, "a named pipe (FIFO), not a file"), (&zero, "a device, not a file")] {
        let (code, _, stderr) = run_in(dir.path(), &["audio-info", path.to_str().unwrap()]);
        assert_eq!(code, Some(1), "{stderr}");
        assert!(stderr.contains(what) && stderr.contains(path.to_str().unwrap()), "{stderr}");
    }
    // The editor's reader (the hash of the project's sound) refuses them the same way.
    for path in [&fifo, &zero] {
        let error = servo_studio::ui::sound::sha256_of(path).unwrap_err().to_string();
        assert!(error.contains("not a file"), "{error}");
    }
}

#[test]
fn a_sound_declaring_a_rate_no_file_is_sampled_at_is_refused_naming_it_and_nothing_panics() {
    let dir = tempfile::tempdir().unwrap();
    for (rate, said) in [(0, "sampled at 0 Hz"), (4_294_967_295, "sampled at 4294967295 Hz"), (50, "sampled at 50 Hz")]
    {
        let path = dir.path().join(format!("r{rate}.wav"));
        std::fs::write(&path, wav_saying(rate, 2, 16_000)).unwrap();
        let (code, _, stderr) = run_in(dir.path(), &["audio-info", path.to_str().unwrap()]);
        assert_eq!(code, Some(1), "{rate} Hz: {stderr}");
        assert!(stderr.contains(said) && stderr.contains("100 Hz to 768 kHz"), "{rate} Hz: {stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
        let (code, _, stderr) = follow(dir.path(), path.to_str().unwrap(), "f.json");
        assert_eq!(code, Some(1), "{rate} Hz: {stderr}");
        assert!(stderr.contains(said), "{stderr}");
        assert!(!dir.path().join("f.json").exists(), "a failure writes nothing");
    }
}

#[test]
fn meshes_that_are_pipes_devices_links_or_giants_are_refused_before_reading() {
    use servo_studio::figure::mesh::Mesh;
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("arm.stl");
    mkfifo(&fifo);
    let error = Mesh::load(&fifo).unwrap_err().to_string();
    assert!(error.contains("a named pipe (FIFO), not a file"), "{error}");
    let zero = dir.path().join("zero.obj");
    std::os::unix::fs::symlink("/dev/zero", &zero).unwrap();
    assert!(Mesh::load(&zero).unwrap_err().to_string().contains("a device, not a file"));
    // 1.5 GB, sparse: refused by its size, never read.
    let sparse = dir.path().join("huge.stl");
    std::fs::File::create(&sparse).unwrap().set_len(1_500_000_000).unwrap();
    let error = Mesh::load(&sparse).unwrap_err().to_string();
    assert!(error.contains("1500 MB") && error.contains("over 134 MB"), "{error}");
    // A binary STL whose header says four billion triangles in 134 bytes.
    let mut lying = vec![0u8; 80];
    lying.extend(u32::MAX.to_le_bytes());
    lying.extend([0u8; 50]);
    let path = dir.path().join("lying.stl");
    std::fs::write(&path, lying).unwrap();
    let error = Mesh::load(&path).unwrap_err().to_string();
    assert!(error.contains("says 4294967295 triangles, but the file holds only 1"), "{error}");
}

/// Other tools' files asking for times, rates and counts no board can mean:
/// refused, naming the motion, the key and the value, in bounded time and memory.
#[test]
fn other_tools_files_asking_for_what_no_board_can_mean_are_refused_naming_it() {
    let dir = tempfile::tempdir().unwrap();
    // A RoboPlus step: a value per id (0 a placeholder), then pause and time in seconds.
    let mtn = "type=motion\nversion=1.01\nenable=0 1\nmotor_type=0\npage_begin\nname=walk\nplay_param=0 0 1 1.0 32\nstep=0 512 0.000 1000000000\npage_end\n";
    let maestro = r#"<UscSettings version="1"><Channels><Channel name="jaw" mode="Servo" min="3968" max="8000" homemode="Goto" home="6000" speed="0" acceleration="0"/></Channels><Sequences><Sequence name="talk"><Frame name="open" duration="1000000000000">6400</Frame></Sequence></Sequences></UscSettings>"#;
    let slow = mtn.replace("play_param=0 0 1 1.0", "play_param=0 0 1 1e-300").replace("1000000000", "1.0");
    let blender = format!(
        "{{\"fps\": 1, \"frames\": {}, \"servos\": {{\"1\": {{\"positions\": [{}]}}}}}}",
        1_000_000,
        vec!["90"; 1_000_000].join(",")
    );
    for (name, text, to, said) in [
        // 10^9 s: 1.25e11 units of 8 ms, played as ticks of 7.8125 ms.
        ("walk.mtn", mtn.to_string(), "plen2", "a move of 9.766e11 ms"),
        ("talk.xml", maestro.to_string(), "servo", "a frame of 1e12 ms"),
        ("slow.mtn", slow, "servo", "a speed rate of 1e-300"),
        ("wave.json", blender, "servo", "at most an hour"),
    ] {
        let path = dir.path().join(name);
        std::fs::write(&path, text).unwrap();
        let (code, _, stderr) =
            run_in(dir.path(), &["convert", name, "--to", to, "--out", "out.json", "--save-map", "map.json"]);
        assert_eq!(code, Some(1), "{name}: {stderr}");
        assert!(stderr.contains(said), "{name}: {stderr}");
        for written in ["out.json", "map.json"] {
            assert!(!dir.path().join(written).exists(), "{name}: a failure writes nothing ({written})");
        }
        let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().file_name()).collect();
        assert!(left.iter().all(|f| !f.to_string_lossy().ends_with(".tmp")), "no temporary file: {left:?}");
    }
}

/// `--save-map` with a conversion that fails writes no map (it used to, and
/// say "nothing was written"); one that succeeds writes both.
#[test]
fn the_map_is_written_with_the_output_or_not_at_all() {
    let dir = tempfile::tempdir().unwrap();
    let fixture = crate::interchange::maestro::SETTINGS;
    std::fs::write(dir.path().join("m.xml"), fixture).unwrap();
    // A map naming no servo: nothing converts.
    std::fs::write(dir.path().join("none.json"), r#"{"entries": []}"#).unwrap();
    let (code, _, stderr) = run_in(
        dir.path(),
        &["convert", "m.xml", "--to", "plen2", "--map", "none.json", "--out", "o.json", "--save-map", "saved.json"],
    );
    assert_eq!(code, Some(1), "{stderr}");
    assert!(!dir.path().join("saved.json").exists() && !dir.path().join("o.json").exists(), "{stderr}");
    let (code, stdout, stderr) =
        run_in(dir.path(), &["convert", "m.xml", "--to", "servo", "--out", "o.json", "--save-map", "saved.json"]);
    assert_eq!(code, Some(0), "{stderr}");
    assert!(dir.path().join("saved.json").exists() && dir.path().join("o.json").exists(), "{stdout}");
}

/// An output that is an input — by name, through a link or a hard link —
/// is refused before anything is read: the input is never replaced.
#[test]
fn an_output_that_names_an_input_is_refused_and_the_input_kept() {
    let dir = tempfile::tempdir().unwrap();
    let fixture = crate::interchange::maestro::SETTINGS;
    std::fs::write(dir.path().join("m.xml"), fixture).unwrap();
    std::os::unix::fs::symlink("m.xml", dir.path().join("link.xml")).unwrap();
    std::fs::hard_link(dir.path().join("m.xml"), dir.path().join("hard.xml")).unwrap();
    for out in ["m.xml", "link.xml", "hard.xml", "./m.xml"] {
        let (code, _, stderr) = run_in(dir.path(), &["convert", "m.xml", "--to", "maestro", "--out", out]);
        assert_eq!(code, Some(1), "{out}: {stderr}");
        assert!(stderr.contains("which this command reads"), "{out}: {stderr}");
        assert_eq!(std::fs::read_to_string(dir.path().join("m.xml")).unwrap(), fixture, "{out}");
    }
    let (code, _, stderr) =
        run_in(dir.path(), &["convert", "m.xml", "--to", "servo", "--out", "o.json", "--save-map", "m.xml"]);
    assert_eq!(code, Some(1), "{stderr}");
    assert_eq!(std::fs::read_to_string(dir.path().join("m.xml")).unwrap(), fixture);

    let rate = 8_000;
    let sound = dir.path().join("s.wav");
    let wav = servo_studio::audio::pcm16_wav(&vec![0.1; rate], u32::try_from(rate).unwrap(), 1);
    std::fs::write(&sound, &wav).unwrap();
    let (code, _, stderr) = follow(dir.path(), "s.wav", "s.wav");
    assert_eq!(code, Some(1), "{stderr}");
    assert!(stderr.contains("which this command reads"), "{stderr}");
    assert_eq!(std::fs::read(&sound).unwrap(), wav);
}
