//! File → Show…: a show's devices with their ports, its cues in a lane per
//! device under the sound's, Play on the boards (every emulated board is
//! started on its cue by the same player as `servo-studio play`), and the
//! window's STOP stopping every board of a show that plays.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::time::Duration;

use egui_kittest::kittest::Queryable;
use servo_studio::show::{Cue, Show, Start};
use servo_studio::ui::show::ShowAction;
use servo_studio::ui::{Action, Language, Tab};

use crate::cli::play::{Stage, device, logged_until, swinging};
use crate::common;

fn two_boards(swings: i32) -> Show {
    Show {
        devices: vec![device("skull", swinging(swings)), device("arms", swinging(swings))],
        sound: None,
        cues: vec![
            Cue { device: "skull".into(), at_ms: 0, start: Start::Macro(1) },
            Cue { device: "arms".into(), at_ms: 500, start: Start::Macro(1) },
        ],
    }
}

fn opened(stage: &Stage) -> egui_kittest::Harness<'static, servo_studio::ui::StudioApp> {
    let mut app = common::ui::editor(servo_studio::project::Project::servo(common::sample_biped()));
    app.apply(Action::Show(ShowAction::Open(stage.dir.path().join("show.json"))));
    let session = app.desks.show.session.as_mut().expect("the show opened");
    let ports: Vec<String> =
        stage.device_args().chunks(2).map(|pair| pair[1].split_once('=').unwrap().1.to_string()).collect();
    session.ports = ports;
    common::ui::showing(app, Tab::Servos, (1280.0, 1400.0))
}

#[test]
fn the_show_window_lays_out_each_device_s_cues_and_plays_them_on_the_boards() {
    let stage = Stage::new(&two_boards(2), &[]);
    let mut harness = opened(&stage);
    // A lane per device, each cue said with its time.
    assert!(
        harness.query_all_by_label("skull").next().is_some() && harness.query_all_by_label("arms").next().is_some()
    );
    assert!(harness.query_by_label("skull macro 1 show 0.00–1.00 s").is_some());
    assert!(harness.query_by_label("arms macro 1 show 0.50–1.50 s").is_some());
    harness.get_by_label("Play on the boards").click();
    common::ui::run_until(&mut harness, "the show ended", |app| {
        !app.desks.show.playing() && common::ui::show_log(app).iter().any(|l| l.starts_with("ended after"))
    });
    let said = common::ui::show_log(harness.state()).join("\n");
    assert!(said.contains("skull answered on") && said.contains("arms answered on"), "{said}");
    logged_until(stage.log("skull"), "ExecuteMacroRequest", Duration::from_secs(10));
    logged_until(stage.log("arms"), "ExecuteMacroRequest", Duration::from_secs(10));
}

#[test]
fn stop_stops_every_board_of_a_show_that_plays() {
    let stage = Stage::new(&two_boards(200), &[]);
    let mut harness = opened(&stage);
    harness.get_by_label("Play on the boards").click();
    harness.run_steps(2);
    logged_until(stage.log("arms"), "ExecuteMacroRequest", Duration::from_secs(30));
    harness.get_by_label("■ STOP").click();
    common::ui::run_until(&mut harness, "the show stopped", |app| !app.desks.show.playing());
    let said = common::ui::show_log(harness.state()).join("\n");
    assert!(said.contains("STOP stopped every device"), "{said}");
    for name in ["skull", "arms"] {
        let log = logged_until(stage.log(name), "SetServoParameterRequest", Duration::from_secs(10));
        assert!(log.iter().any(|(_, line)| line.contains("is_start: false")), "{name}: {log:?}");
    }
}

#[test]
fn a_cue_is_added_changed_and_the_show_saved_as_version_3() {
    use egui::accesskit::Role;
    use egui_kittest::kittest::by;
    let stage = Stage::new(&two_boards(2), &[]);
    let saved = stage.dir.path().join("saved.json");
    let answer = saved.clone();
    let picker: servo_studio::ui::Picker =
        std::sync::Arc::new(move |_: &servo_studio::ui::FileRequest, waker: servo_studio::link::Waker| {
            let (tx, rx) = crossbeam_channel::bounded(1);
            tx.send(Some(answer.clone())).unwrap();
            waker();
            rx
        });
    let mut app = common::ui::editor(servo_studio::project::Project::servo(common::sample_biped())).with_picker(picker);
    app.apply(Action::Show(ShowAction::Open(stage.dir.path().join("show.json"))));
    // Tall enough that the cues are not scrolled out of the show window (it scrolls at 800).
    let mut harness = common::ui::showing(app, Tab::Servos, (1280.0, 1400.0));
    harness.get_by_label("+ Cue").click();
    harness.run();
    // The new cue: the first device's first macro, at 0; moved to the other board in its row.
    assert_eq!(harness.state().desks.show.session.as_ref().unwrap().show.cues.len(), 3);
    assert_eq!(
        harness.query_all(by().label("skull macro 1 show 0.00–1.00 s")).count(),
        2,
        "the first cue and the new one"
    );
    let rows: Vec<_> = harness.query_all(by().role(Role::ComboBox).value("skull")).collect();
    rows.last().unwrap().click();
    harness.run();
    harness.query_all(by().label("arms")).last().unwrap().click();
    harness.run();
    assert_eq!(harness.state().desks.show.session.as_ref().unwrap().show.cues[2].device, "arms");
    // A cue at a time the show cannot hold is said, and Play waits for it to be right.
    harness.state_mut().desks.show.session.as_mut().unwrap().show.cues[2].device = "nobody".into();
    harness.run();
    assert!(harness.query_by_label_contains("\"nobody\", which is not a device").is_some());
    harness.state_mut().desks.show.session.as_mut().unwrap().show.cues[2].device = "arms".into();
    harness.run();
    harness.get_by_label("Save show…").click();
    common::ui::run_until(&mut harness, "the show saved", |_| saved.exists());
    let again = Show::open(&saved).unwrap();
    assert_eq!(again.cues.len(), 3);
    assert_eq!((again.cues[2].device.as_str(), again.cues[2].at_ms, again.cues[2].start), ("arms", 0, Start::Macro(1)));
}

#[test]
fn each_device_says_whether_the_show_plays_on_without_it() {
    let stage = Stage::new(&two_boards(2), &[]);
    let mut harness = opened(&stage);
    let boxes: Vec<_> = harness.query_all_by_label("play on without it").collect();
    assert_eq!(boxes.len(), 2, "a box per device");
    boxes[1].click();
    harness.run();
    let show = &harness.state().desks.show.session.as_ref().unwrap().show;
    assert_eq!(show.devices.iter().map(|d| d.play_on_without).collect::<Vec<_>>(), [false, true]);
    assert!(show.to_json().contains("\"play_on_without\": true"), "saved with the show");
}

/// "+ Device" adds a new PLEN2 under a name of its own; a device's Remove
/// takes it away with its cues (said); Find by id lists the USB serial
/// devices attached (none on this machine: it says so).
#[test]
fn devices_are_added_and_removed_and_a_port_is_found_by_id() {
    let stage = Stage::new(&two_boards(2), &[]);
    let mut harness = opened(&stage);
    harness.get_by_label("+ Device").click();
    harness.run();
    harness.get_by_label("New PLEN2").click();
    harness.run();
    let names = |harness: &egui_kittest::Harness<'static, servo_studio::ui::StudioApp>| -> Vec<String> {
        let session = harness.state().desks.show.session.as_ref().unwrap();
        assert_eq!(session.ports.len(), session.show.devices.len(), "a port per device");
        session.show.devices.iter().map(|d| d.name.clone()).collect()
    };
    assert_eq!(names(&harness), ["skull", "arms", "plen2"]);
    assert!(harness.query_all_by_label("play on without it").count() == 3, "its row is shown");
    // The stage shows every device; a click on the timeline shows that time there.
    harness.get_by_label("Stage: every device at the time shown");
    assert_eq!(harness.state().desks.show.stage.scrub_ms, 0);
    harness.get_by_label("Timeline: click to show that time").click();
    harness.run();
    let scrub = harness.state().desks.show.stage.scrub_ms;
    assert!((100..1500).contains(&scrub), "a click mid-timeline (1.5 s shown) shows its middle: {scrub} ms");
    // The devices' Remove buttons come first, then the cues'.
    harness.query_all_by_label("Remove").next().unwrap().click();
    harness.run();
    assert_eq!(names(&harness), ["arms", "plen2"]);
    let session = harness.state().desks.show.session.as_ref().unwrap();
    assert_eq!(session.show.cues.iter().map(|c| c.device.as_str()).collect::<Vec<_>>(), ["arms"]);
    assert!(
        session.log(Language::English).contains(&"skull: 1 cue went with it"),
        "{:?}",
        session.log(Language::English)
    );
    // Listed off the frame: once they are, the menu shows them.
    common::ui::run_until(&mut harness, "the adapters listed", |app| app.desks.show.adapters_listed());
    harness.query_all_by_label("Find by id").next().unwrap().click();
    harness.run();
    let attached = servo_studio::link::by_id::attached();
    if attached.is_empty() {
        harness.get_by_label("No USB serial device is attached: plug it in, or type its port");
    } else {
        assert!(harness.query_all_by_label_contains(&attached[0].id.to_string()).next().is_some());
    }
}

/// Preview runs the time shown with the clock (every figure on the stage
/// moving with it) until the show's end; Stop preview and the window's
/// STOP stop it where it is.
#[test]
fn the_stage_previews_the_show_and_stop_stops_it() {
    let stage = Stage::new(&two_boards(2), &[]);
    let mut harness = opened(&stage);
    harness.get_by_label("Preview").click();
    common::ui::run_until(&mut harness, "the preview moving", |app| app.desks.show.stage.scrub_ms > 0);
    assert!(harness.state().desks.show.stage.previewing());
    harness.get_by_label("Stop preview").click();
    harness.run();
    let stopped_at = harness.state().desks.show.stage.scrub_ms;
    assert!(!harness.state().desks.show.stage.previewing());
    harness.run();
    assert_eq!(harness.state().desks.show.stage.scrub_ms, stopped_at, "it stays where it was stopped");
    harness.get_by_label("Preview").click();
    common::ui::run_until(&mut harness, "the preview again", |app| app.desks.show.stage.scrub_ms > stopped_at);
    harness.get_by_label("■ STOP").click();
    harness.run();
    assert!(!harness.state().desks.show.stage.previewing(), "the window's STOP stops the preview");
    // Said where it was stopped, in the show's log.
    let at = harness.state().desks.show.stage.scrub_ms as f64 / 1000.0;
    let said = format!("STOP stopped the preview at {at:.2} s");
    assert!(common::ui::show_log(harness.state()).contains(&said), "{:?}", common::ui::show_log(harness.state()));
    // To its end: it stops there by itself.
    harness.get_by_label("Preview").click();
    harness.step();
    assert!(harness.state().desks.show.stage.previewing());
    common::ui::run_until(&mut harness, "the preview's end", |app| !app.desks.show.stage.previewing());
    assert_eq!(harness.state().desks.show.stage.scrub_ms, 1500, "the show's span: the last cue's end");
}

/// A record pass: servo 1 of the skull picked, ● Record pass previews the
/// show from 0 while its slider is moved (here, set each frame as a hand
/// would), the figure following it; ■ Stop pass (a show with no sound
/// records until stopped) joins it into one macro cued at its start, said
/// with its steps; Undo pass takes it back.
#[test]
fn a_record_pass_joins_into_the_show_and_is_undone_on_its_own() {
    use servo_studio::show::passes::Axis;
    let stage = Stage::new(&two_boards(2), &[]);
    let mut harness = opened(&stage);
    let macros_before = harness.state().desks.show.session.as_ref().unwrap().show.devices[0].project.servo.macros.len();
    harness.state_mut().desks.show.passes.pick("skull", Axis::Servo(1));
    harness.run();
    harness.get_by_label("● Record pass").click();
    harness.step();
    assert!(harness.state().desks.show.passes.recording.is_some() && harness.state().desks.show.stage.previewing());
    // The show has no sound: the pass records until it is stopped, here after the last cue's end.
    while harness.state().desks.show.stage.scrub_ms < 1800 {
        let t = harness.state().desks.show.stage.scrub_ms as f64 / 1000.0;
        harness.state_mut().desks.show.passes.value = 40.0 * t;
        harness.step();
        common::ui::wait_for_news();
    }
    assert!(harness.state().desks.show.passes.recording.is_some(), "still recording past the show's 1.5 s");
    harness.get_by_label("■ Stop pass").click();
    harness.run();
    assert!(harness.state().desks.show.passes.recording.is_none());
    let show = &harness.state().desks.show.session.as_ref().unwrap().show;
    let skull = &show.devices[0].project.servo;
    assert_eq!(skull.macros.len(), macros_before + 1, "the pass became a macro");
    let made = skull.macros.last().unwrap();
    assert_eq!(made.caption, "Recorded passes");
    assert!(show.cues.iter().any(|cue| cue.device == "skull" && cue.start == Start::Macro(made.id)), "cued");
    let said = common::ui::show_log(harness.state()).join("\n");
    assert!(said.contains("skull: 1 pass joined → ") && said.contains(" step"), "{said}");
    harness.get_by_label("Undo pass").click();
    harness.run();
    let show = &harness.state().desks.show.session.as_ref().unwrap().show;
    assert_eq!(show.devices[0].project.servo.macros.len(), macros_before, "undone");
    assert_eq!(show.cues.len(), 2, "the show's own cues are back");
}

/// A pass moved by a gamepad axis: the stick's travel spans the servo's
/// range, and what is recorded is where the stick was at each time shown.
#[test]
fn a_record_pass_follows_a_gamepad_axis() {
    use servo_studio::gamepad::{ABS_X, EV_ABS, EV_SYN, PadState, RawEvent, SYN_REPORT};
    use servo_studio::show::passes::Axis;
    let stage = Stage::new(&two_boards(2), &[]);
    let mut harness = opened(&stage);
    let stick = |value: i32| {
        let mut state = PadState::new((-100, 100));
        state.apply(RawEvent { kind: EV_ABS, code: ABS_X, value });
        state.apply(RawEvent { kind: EV_SYN, code: SYN_REPORT, value: 0 });
        state
    };
    harness.state_mut().desks.pad.state = Some(stick(-100));
    harness.state_mut().desks.show.passes.pick("arms", Axis::Servo(1));
    harness.state_mut().desks.show.passes.pad_axis = Some(ABS_X);
    harness.run();
    harness.get_by_label("● Record pass").click();
    harness.step();
    while harness.state().desks.show.stage.scrub_ms < 1500 {
        // The stick pushed from one end to the other over 1.5 s.
        let t = i32::try_from(harness.state().desks.show.stage.scrub_ms).unwrap();
        harness.state_mut().desks.pad.state = Some(stick(-100 + t * 200 / 1500));
        harness.step();
        common::ui::wait_for_news();
    }
    harness.state_mut().desks.pad.state = Some(stick(100));
    harness.step();
    harness.get_by_label("■ Stop pass").click();
    harness.run();
    let pass = harness.state().desks.show.passes.recorded.last().expect("a pass kept").clone();
    assert_eq!((pass.device.as_str(), pass.axis), ("arms", Axis::Servo(1)));
    let servo = &harness.state().desks.show.session.as_ref().unwrap().show.devices[1].project.servo.servos[0];
    let (low, high) = (f64::from(servo.min_deg), f64::from(servo.max_deg));
    assert!(pass.samples.iter().all(|&(_, v)| (low..=high).contains(&v)), "{:?}", pass.samples);
    let (first, last) = (pass.samples.first().unwrap().1, pass.samples.last().unwrap().1);
    assert!(
        first < low + (high - low) * 0.2 && last > low + (high - low) * 0.8,
        "from near {low} to near {high}: {first} … {last}"
    );
}

/// Collapsed, the show window parks at the bottom edge, above the status
/// line: its title bar covers no tab or panel heading; opened again, it is
/// whole, back where it stood.
#[test]
fn a_collapsed_show_window_parks_at_the_bottom_edge() {
    let mut app = common::ui::editor(servo_studio::ui::sample_project());
    app.apply(Action::Show(ShowAction::OpenProject));
    let mut harness = common::ui::showing(app, Tab::Servos, (1280.0, 800.0));
    let id = egui::Id::unique("show-window");
    let area = |harness: &egui_kittest::Harness<'static, servo_studio::ui::StudioApp>| {
        harness.ctx.memory(|memory| memory.area_rect(id)).expect("the show window's area")
    };
    assert!(area(&harness).top() < 200.0, "open, it stands near the top: {:?}", area(&harness));
    let collapse = |harness: &mut egui_kittest::Harness<'static, servo_studio::ui::StudioApp>, open: bool| {
        let mut state =
            egui::collapsing_header::CollapsingState::load_with_default_open(&harness.ctx, id.with("collapsing"), true);
        state.set_open(open);
        state.store(&harness.ctx);
        harness.run_steps(4);
    };
    collapse(&mut harness, false);
    let parked = area(&harness);
    assert!(parked.top() >= 800.0 - servo_studio::ui::PARKED_ABOVE_BOTTOM - 1.0, "{parked:?}");
    assert!(parked.bottom() <= 800.0, "within the window: {parked:?}");
    // Nothing of the tab bar or the panels' headings is under it.
    for tab in harness.query_all_by_label("Servos").map(|node| node.rect()) {
        assert!(!parked.intersects(tab), "{parked:?} over {tab:?}");
    }
    collapse(&mut harness, true);
    let open = area(&harness);
    assert!(open.height() > 300.0 && open.bottom() <= 800.0 + 1.0, "opened again, whole: {open:?}");
    assert!(open.top() < 200.0, "back where it stood before it was parked: {open:?}");
}
