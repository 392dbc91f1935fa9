//! The sound track in the editor: a click track added through the file
//! dialog is stored relative to the project with its length and hash, drawn
//! as a lane under the preview's cursor with its onsets, moved by dragging
//! the lane (one undo step); a missing or changed file opens the project and
//! says which, with Locate and Remove; Play plays the sound through a real
//! PulseAudio server (null sink) and Pause stops it; without a sound server
//! "no sound output" is said once and the motion plays on; Run on the board
//! starts the sound with the macro.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::cast_possible_truncation, clippy::cast_sign_loss)]

use crate::common;
use crate::common::pulse::Pulse;

use std::path::{Path, PathBuf};
use std::time::Duration;

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use servo_studio::link::{LinkEvent, Waker, no_waker};
use servo_studio::project::{Project, SoundTrack};
use servo_studio::sim::SimEvent;
use servo_studio::ui::{
    Action, FileRequest, Picker, Plen2BoardLink as _, ServoBoardLink as _, SoundAction, SoundDesk, StudioApp, Tab,
};

/// Clicks at these times (s) in a 3 s track.
const CLICKS: [f64; 4] = [0.3, 0.9, 1.6, 2.2];

fn click_track(path: &Path) {
    let rate = 22_050u32;
    let mut samples = vec![0.0f32; 3 * rate as usize];
    for at in CLICKS {
        let start = (at * f64::from(rate)) as usize;
        for (i, sample) in samples[start..start + 300].iter_mut().enumerate() {
            *sample = (i as f32 * 0.9).sin() * (-(i as f32) / 60.0).exp() * 0.9;
        }
    }
    std::fs::write(path, servo_studio::audio::pcm16_wav(&samples, rate, 1)).unwrap();
}

/// A file dialog that answers each request with the next of `answers`.
fn picker(answers: Vec<PathBuf>) -> Picker {
    let answers = std::sync::Mutex::new(answers.into_iter());
    std::sync::Arc::new(move |_: &FileRequest, waker: Waker| {
        let (tx, rx) = crossbeam_channel::bounded(1);
        tx.send(answers.lock().unwrap().next()).unwrap();
        waker();
        rx
    })
}

/// The sample robot saved in `dir`, opened from there in the Actions tab.
fn saved_editor(dir: &Path, project: Project, answers: Vec<PathBuf>) -> Harness<'static, StudioApp> {
    let path = dir.join("show.json");
    servo_studio::project::save(&path, &project).unwrap();
    let data = tempfile::tempdir().unwrap().keep();
    let app = StudioApp::new(project, Some(path), no_waker()).with_data_dir(data).with_picker(picker(answers));
    common::ui::showing(app, Tab::Actions, (1300.0, 900.0))
}

fn track(harness: &Harness<'static, StudioApp>) -> Option<SoundTrack> {
    harness.state().document.project.sound.clone()
}

#[test]
fn an_added_sound_is_kept_relative_with_its_hash_drawn_with_its_onsets_and_moved_by_dragging_the_lane() {
    let dir = tempfile::tempdir().unwrap();
    let sound = dir.path().join("clicks.wav");
    click_track(&sound);
    let mut harness = saved_editor(dir.path(), servo_studio::ui::sample_project(), vec![sound.clone()]);
    harness.get_by_label_contains("Add a sound…").click();
    common::ui::run_until(&mut harness, "the sound read", |app| {
        app.document.project.sound.as_ref().is_some_and(|track| !track.sha256.is_empty())
    });
    let added = track(&harness).unwrap();
    assert_eq!(added.path, "clicks.wav", "relative to the project's folder");
    assert_eq!(added.duration_ms, 3000);
    let hash = servo_studio::ui::sound::sha256_of(&sound).unwrap();
    assert_eq!(added.sha256, hash);
    assert!(harness.query_by_label_contains("Sound: clicks.wav").is_some(), "the lane names the file");
    // The onsets, on the motion's time: every click within 10 ms.
    let view = harness.state().desks.sound.view(&harness.state().document.project);
    let onsets = view.onsets_ms();
    assert_eq!(onsets.len(), CLICKS.len(), "{onsets:?}");
    for (onset, click) in onsets.iter().zip(CLICKS) {
        assert!((onset - click * 1000.0).abs() <= 10.0, "{onset} ms for a click at {click} s");
    }
    // Dragging the waveform to the right moves the sound later; one undo puts it back.
    let lane = harness.get_by_label_contains("Click: cursor here").rect();
    let from = lane.center();
    harness.drag_at(from);
    harness.step();
    for part in 1..=6 {
        harness.hover_at(from + egui::vec2(10.0 * part as f32, 0.0));
        harness.step();
    }
    harness.drop_at(from + egui::vec2(60.0, 0.0));
    harness.run_steps(3);
    let moved = track(&harness).unwrap().offset_ms;
    assert!(moved > 50, "the sound starts later: {moved} ms");
    let onsets = harness.state().desks.sound.view(&harness.state().document.project).onsets_ms();
    assert!((onsets[0] - (300.0 + moved as f64)).abs() <= 10.0, "the onsets move with it");
    harness.state_mut().apply(Action::Undo);
    harness.run_steps(2);
    assert_eq!(track(&harness).unwrap().offset_ms, 0, "one drag, one undo step");
}

#[test]
fn a_missing_or_changed_sound_opens_the_project_and_says_what_to_do() {
    let dir = tempfile::tempdir().unwrap();
    let here = dir.path().join("found.wav");
    click_track(&here);
    let mut project = servo_studio::ui::sample_project();
    let gone = SoundTrack {
        path: "songs/gone.wav".into(),
        duration_ms: 3000,
        sha256: "00".repeat(32),
        offset_ms: 120,
        sensitivity_percent: 70,
    };
    project.sound = Some(gone);
    let mut harness = saved_editor(dir.path(), project.clone(), vec![here.clone()]);
    common::ui::run_until(&mut harness, "the missing file said", |app| {
        app.desks.sound.view(&app.document.project).problem.is_some()
    });
    assert!(harness.query_by_label_contains("gone.wav is missing").is_some(), "names the file and what to do");
    assert_eq!(harness.state().document.project.servo, project.servo, "the project opened whole");
    harness.get_by_label("Locate…").click();
    common::ui::run_until(&mut harness, "the located file read", |app| {
        app.document.project.sound.as_ref().is_some_and(|track| track.path == "found.wav")
    });
    let located = track(&harness).unwrap();
    assert_eq!((located.offset_ms, located.sensitivity_percent), (120, 70), "the timing is kept");
    assert!(harness.query_by_label_contains("is missing").is_none());

    // The file changes under the project: said, and kept as it is now when asked.
    let shorter: Vec<f32> = vec![0.0; 22_050];
    std::fs::write(&here, servo_studio::audio::pcm16_wav(&shorter, 22_050, 1)).unwrap();
    let project = harness.state().document.project.clone();
    let mut harness = saved_editor(dir.path(), project, Vec::new());
    common::ui::run_until(&mut harness, "the change said", |app| {
        app.desks.sound.view(&app.document.project).problem.is_some()
    });
    assert!(harness.query_by_label_contains("has changed since the show was timed to it").is_some());
    harness.get_by_label("Keep it as it is now").click();
    harness.run_steps(3);
    assert_eq!(track(&harness).unwrap().duration_ms, 1000);
    assert!(harness.query_by_label_contains("has changed").is_none());
}

/// The sample robot with `clicks.wav` as its sound, in `dir`.
fn with_sound(dir: &Path) -> Project {
    let sound = dir.join("clicks.wav");
    click_track(&sound);
    let mut project = servo_studio::ui::sample_project();
    project.sound = Some(SoundTrack {
        path: "clicks.wav".into(),
        duration_ms: 3000,
        sha256: servo_studio::ui::sound::sha256_of(&sound).unwrap(),
        offset_ms: 0,
        sensitivity_percent: 50,
    });
    project
}

#[test]
fn play_plays_the_sound_through_the_sound_server_and_pause_stops_it() {
    let Some(pulse) = Pulse::start() else { return };
    let dir = tempfile::tempdir().unwrap();
    let mut harness = saved_editor(dir.path(), with_sound(dir.path()), Vec::new());
    harness.state_mut().desks.sound = SoundDesk::with_server(pulse.socket.clone());
    common::ui::run_until(&mut harness, "the sound read", |app| {
        app.desks.sound.view(&app.document.project).read.is_some()
    });
    harness.get_by_label("Play").click();
    common::ui::run_until(&mut harness, "the sound playing", |app| app.desks.sound.is_playing());
    harness.get_by_label("Pause").click();
    common::ui::run_until(&mut harness, "the sound stopped", |app| !app.desks.sound.is_playing());
    assert!(harness.state().status.as_ref().is_none_or(|status| !status.text.contains("no sound output")));
}

#[test]
fn without_a_sound_server_no_sound_output_is_said_once_and_the_motion_plays_on() {
    let dir = tempfile::tempdir().unwrap();
    let mut harness = saved_editor(dir.path(), with_sound(dir.path()), Vec::new());
    harness.state_mut().desks.sound = SoundDesk::with_server(dir.path().join("no-server"));
    common::ui::run_until(&mut harness, "the sound read", |app| {
        app.desks.sound.view(&app.document.project).read.is_some()
    });
    harness.get_by_label("Play").click();
    // The output is asked off the frame: its answer comes when it comes.
    common::ui::run_until(&mut harness, "no sound output said", |app| app.status.is_some());
    let said = harness.state().status.clone().expect("said");
    assert!(said.text.starts_with("no sound output: the motion plays without sound"), "{}", said.text);
    harness.state_mut().status = None;
    harness.get_by_label("Pause").click();
    harness.run_steps(2);
    harness.get_by_label("Play").click();
    harness.run_steps(3);
    assert!(harness.state().status.is_none(), "said once");
    assert!(common::ui::servo_ui(harness.state()).figure.transport.is_playing(), "the motion plays on");
}

/// A sound server that accepts every connection and never answers (a hung
/// PipeWire, a stale socket): Play and Run on board go on; the editor keeps
/// drawing every frame, STOP works at once, and within 2 s more "the server
/// at … did not answer in 2 s: the motion plays on without sound" is said and the board's
/// start goes out without the sound.
#[test]
fn a_sound_server_that_never_answers_freezes_nothing_and_stop_works() {
    let dir = tempfile::tempdir().unwrap();
    let socket = dir.path().join("hung");
    let listener = std::os::unix::net::UnixListener::bind(&socket).unwrap();
    // Accepted and held, never read or answered.
    let held = std::thread::spawn(move || listener.incoming().take(4).filter_map(Result::ok).collect::<Vec<_>>());
    let project = with_sound(dir.path());
    let macro_id = project.servo.macros[0].id;
    let (drawn, frames) = crossbeam_channel::unbounded::<&'static str>();
    let root = dir.path().to_path_buf();
    // The editor runs on a thread of its own: should a frame block, this test fails instead of hanging.
    std::thread::spawn(move || {
        let mut harness = saved_editor(&root, project, Vec::new());
        harness.state_mut().desks.sound = SoundDesk::with_server(socket);
        harness.state_mut().apply(Action::ConnectDemo);
        common::ui::run_until(&mut harness, "the sound read", |app| {
            app.desks.sound.view(&app.document.project).read.is_some()
        });
        common::ui::run_until(&mut harness, "the demo board", |app| {
            app.link.as_ref().is_some_and(|link| link.demo_board().is_some())
        });
        let events = harness.state().link.as_ref().unwrap().demo_board().unwrap().events().clone();
        harness.get_by_label("Play").click();
        harness.step();
        drawn.send("played").unwrap();
        harness.state_mut().apply(Action::Stop);
        harness.step();
        assert!(!harness.state().desks.sound.is_playing(), "STOP stopped the sound at once");
        drawn.send("stopped").unwrap();
        // STOP holds the servos until Resume; the preview (which plays on its
        // own) is paused, so its end does not silence the next sound.
        harness.state_mut().apply(Action::Resume);
        if let Some(pause) = harness.query_by_label("Pause") {
            pause.click();
        }
        harness.run_steps(3);
        harness.state_mut().apply(Action::family(servo_studio::ui::ServoAction::RunMacro(macro_id)));
        let deadline = std::time::Instant::now() + Duration::from_secs(30);
        let said = loop {
            harness.step();
            drawn.send("frame").unwrap();
            assert!(
                harness.state().status.as_ref().is_none_or(|s| !s.text.contains("did not answer"))
                    || std::time::Instant::now() < deadline,
                "said in time"
            );
            if let Some(status) = harness.state().status.as_ref().filter(|s| s.text.contains("did not answer in 2 s")) {
                break status.text.clone();
            }
            assert!(std::time::Instant::now() < deadline, "never said the server did not answer");
        };
        // Said once: the server named, and that the motion plays on without its sound.
        assert!(said.starts_with("the server at ") && said.contains("hung"), "{said}");
        assert_eq!(said.matches("without sound").count(), 1, "{said}");
        // The board's start, held for the sound, went out when the output was given up.
        let ran = loop {
            harness.step();
            drawn.send("frame").unwrap();
            match events.recv_timeout(Duration::from_millis(100)) {
                Ok(LinkEvent::Driver(SimEvent::MacroSteps { macro_id: ran, .. })) => break ran,
                _ => assert!(std::time::Instant::now() < deadline, "the board never ran the macro"),
            }
        };
        assert_eq!(ran, macro_id);
        // The window's end does not wait on the sound output either.
        let closing = std::time::Instant::now();
        harness.state_mut().close_within(servo_studio::ui::EXIT_WITHIN);
        assert!(closing.elapsed() < Duration::from_secs(20), "closed ({:?})", closing.elapsed());
        drawn.send("done").unwrap();
    });
    // Every frame comes within a second, however long the server keeps silent.
    loop {
        match frames.recv_timeout(Duration::from_secs(5)) {
            Ok("done") => break,
            Ok(_) => {}
            Err(error) => panic!("the editor stopped drawing ({error}): a frame waits on the sound server"),
        }
    }
    drop(held);
}

/// Plays through `pulse`, connects the demo board of the project's family, and waits for the sound to be read.
fn on_the_demo_with_sound(harness: &mut Harness<'static, StudioApp>, pulse: &Pulse) {
    harness.state_mut().desks.sound = SoundDesk::with_server(pulse.socket.clone());
    harness.state_mut().apply(Action::ConnectDemo);
    common::ui::run_until(harness, "the sound read", |app| app.desks.sound.view(&app.document.project).read.is_some());
}

#[test]
fn running_a_macro_on_the_board_starts_the_sound_with_it() {
    let Some(pulse) = Pulse::start() else { return };
    let dir = tempfile::tempdir().unwrap();
    let project = with_sound(dir.path());
    let macro_id = project.servo.macros[0].id;
    let mut harness = saved_editor(dir.path(), project, Vec::new());
    on_the_demo_with_sound(&mut harness, &pulse);
    common::ui::run_until(&mut harness, "the demo board", |app| {
        app.link.as_ref().is_some_and(|link| link.demo_board().is_some())
    });
    let events = harness.state().link.as_ref().unwrap().demo_board().unwrap().events().clone();
    harness.state_mut().apply(Action::family(servo_studio::ui::ServoAction::RunMacro(macro_id)));
    common::ui::run_until(&mut harness, "the sound playing", |app| app.desks.sound.is_playing());
    let deadline = std::time::Instant::now() + Duration::from_secs(10);
    loop {
        match events.recv_deadline(deadline) {
            Ok(LinkEvent::Driver(SimEvent::MacroSteps { macro_id: ran, .. })) if ran == macro_id => break,
            Ok(_) => {}
            Err(error) => panic!("the board never ran the macro: {error}"),
        }
    }
    harness.state_mut().apply(Action::Sound(SoundAction::Silence));
}

#[test]
fn follow_the_sound_adds_a_servos_steps_and_a_macro_timed_to_it_in_one_undo_step() {
    let dir = tempfile::tempdir().unwrap();
    let project = with_sound(dir.path());
    let before = project.servo.clone();
    let mut harness = saved_editor(dir.path(), project, Vec::new());
    common::ui::run_until(&mut harness, "the sound read", |app| {
        app.desks.sound.view(&app.document.project).read.is_some()
    });
    harness.get_by_label("Follow the sound…").click();
    harness.run_steps(3);
    harness.get_by_label("Make the motion").click();
    harness.run_steps(3);
    let after = harness.state().document.project.servo.clone();
    assert_eq!(after.macros.len(), before.macros.len() + 1, "a macro running the steps");
    let made = after.macros.last().unwrap();
    let added = &after.actions[before.actions.len()..];
    assert_eq!(made.commands.len(), added.len());
    assert!(added.len() >= 2, "the clicks open and close: {} steps", added.len());
    let servo_id = before.servos[0].id;
    assert!(added.iter().all(|action| action.steps.iter().all(|step| step.servo_id == servo_id)));
    // Steps run end to end from the macro's start: they last as long as the sound.
    let total_ms: i64 = added.iter().map(|action| i64::from(action.steps[0].interval_10ms) * 10).sum();
    assert!((total_ms - 3000).abs() <= 20, "{total_ms} ms of steps for 3 s of sound");
    assert!(harness.query_by_label_contains("steps, run by macro").is_some(), "it says what it made");
    // Said again in the language chosen while it shows.
    harness.state_mut().apply(Action::SetLanguage(servo_studio::ui::Language::Japanese));
    harness.run_steps(2);
    assert!(harness.query_by_label_contains("steps, run by macro").is_none(), "no English left");
    let said = format!("{} ステップ、マクロで実行", added.len());
    assert!(harness.query_by_label_contains(&said).is_some(), "said in Japanese: {said}");
    harness.state_mut().apply(Action::SetLanguage(servo_studio::ui::Language::English));
    harness.state_mut().apply(Action::Undo);
    harness.run_steps(2);
    assert_eq!(harness.state().document.project.servo, before, "one undo step");
}

#[test]
fn stop_before_the_boards_start_goes_out_stops_the_sound_and_the_start_never_goes_out() {
    let Some(pulse) = Pulse::start() else { return };
    let dir = tempfile::tempdir().unwrap();
    let project = with_sound(dir.path());
    let mut harness = saved_editor(dir.path(), project.clone(), Vec::new());
    harness.state_mut().desks.sound = SoundDesk::with_server(pulse.socket.clone());
    common::ui::run_until(&mut harness, "the sound read", |app| {
        app.desks.sound.view(&app.document.project).read.is_some()
    });
    let (sent, went_out) = crossbeam_channel::bounded(1);
    let start = move || sent.send(()).unwrap();
    let waiting = harness.state_mut().desks.sound.play_with_board(&project, 0.0, (Duration::ZERO, no_waker()), start);
    assert!(waiting, "the board's start waits for the sound");
    // STOP at once: the start is due only once the sound has played its 300 ms lead.
    harness.state_mut().apply(Action::Stop);
    // The start is dropped unsent when the sound-and-board thread ends: its channel closes.
    assert_eq!(
        went_out.recv_timeout(Duration::from_secs(30)),
        Err(crossbeam_channel::RecvTimeoutError::Disconnected),
        "the board's start never went out"
    );
    harness.run_steps(2);
    assert!(!harness.state().desks.sound.is_playing(), "the sound stopped with the board");
}

#[test]
fn playing_a_play_list_on_the_robot_queues_it_then_starts_it_with_the_sound() {
    use servo_studio::project::Family;
    use servo_studio::project::plen2::{PlayEntry, PlayList};
    use servo_studio::protocol::plen2::Command;
    use servo_studio::sim::Plen2SimEvent;
    let Some(pulse) = Pulse::start() else { return };
    let dir = tempfile::tempdir().unwrap();
    let mut project = Project::empty(Family::Plen2);
    project.sound = with_sound(dir.path()).sound;
    let entries = vec![PlayEntry { slot: 3, plays: 2 }, PlayEntry { slot: 5, plays: 1 }];
    project.plen2.play_lists = vec![PlayList { name: "show".into(), entries }];
    let path = dir.path().join("show.json");
    servo_studio::project::save(&path, &project).unwrap();
    let data = tempfile::tempdir().unwrap().keep();
    let app = StudioApp::new(project, Some(path), no_waker()).with_data_dir(data);
    let mut harness = common::ui::showing(app, Tab::PlayLists, (1300.0, 900.0));
    on_the_demo_with_sound(&mut harness, &pulse);
    common::ui::run_until(&mut harness, "the demo robot", |app| {
        app.link.as_ref().is_some_and(|link| link.demo_plen2().is_some())
    });
    let events = harness.state().link.as_ref().unwrap().demo_plen2().unwrap().events().clone();
    harness.state_mut().apply(Action::family(servo_studio::ui::Plen2Action::PlayList(0)));
    // The sound plays once the thread starting both has sent `#PO`.
    common::ui::run_until(&mut harness, "the sound playing", |app| app.desks.sound.is_playing());
    let deadline = std::time::Instant::now() + Duration::from_secs(10);
    let mut executed = Vec::new();
    while executed.last() != Some(&Command::Pop) {
        match events.recv_deadline(deadline) {
            Ok(LinkEvent::Driver(Plen2SimEvent::Executed(command))) => executed.push(command),
            Ok(_) => {}
            Err(error) => panic!("the robot never started the list ({executed:?}): {error}"),
        }
    }
    let queued = [Command::Push { slot: 3, plays: 2 }, Command::Push { slot: 5, plays: 1 }, Command::Pop];
    assert!(executed.ends_with(&queued), "the list queued, then started: {executed:?}");
    assert_eq!(executed.iter().filter(|command| **command == Command::Pop).count(), 1, "{executed:?}");
    harness.state_mut().apply(Action::Sound(SoundAction::Silence));
}

/// A sound longer than the motion: the play bar, the sound lane and the
/// graph share one time axis — the longer of the two — so at any time the
/// bar's cursor and the lane's are at the same x (they were ~180 px apart
/// at 0.92 s when the bar spanned the motion and the lane the sound).
#[test]
fn the_play_bar_and_the_sound_lane_share_one_time_axis() {
    let dir = tempfile::tempdir().unwrap();
    let mut harness = saved_editor(dir.path(), with_sound(dir.path()), Vec::new());
    common::ui::run_until(&mut harness, "the sound read", |app| {
        app.desks.sound.view(&app.document.project).read.is_some()
    });
    let span = common::ui::servo_ui(harness.state()).figure.transport.span_ms().unwrap();
    assert!((span - 3000.0).abs() < 1.0, "the span is the sound's 3 s, longer than the action: {span}");
    for t_ms in [0.0, 920.0, 2200.0, 3000.0] {
        let figure = &common::ui::servo_ui(harness.state()).figure;
        let (bar, lane) = (figure.transport.x_of(t_ms).unwrap(), figure.lane.x_of(t_ms).unwrap());
        assert!((bar - lane).abs() < 1.0, "at {t_ms} ms: the bar's x {bar}, the lane's {lane}");
    }
}
