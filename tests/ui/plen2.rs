//! The PLEN2 panels against the in-process emulated robot: joint sliders move
//! joints live, STOP sends `#RI` then `$HP`, a play list queues its motions,
//! a captured pose becomes a frame, and the robot panel uploads and reads back.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common;

use std::time::{Duration, Instant};

use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT, Queryable, by};
use servo_studio::link::{LinkEvent, no_waker};
use servo_studio::project::plen2::{Frame, Joint, Motion, PlayEntry, PlayList, Plen2Project, Pose};
use servo_studio::project::{Family, Project};
use servo_studio::protocol::plen2::Command;
use servo_studio::sim::{Plen2SimCommand, Plen2SimEvent, Plen2State};
use servo_studio::ui::{Action, Plen2BoardLink as _, Plen2Intent, StudioApp, Tab};

fn project() -> Project {
    let mut pose = Pose::default();
    pose.set(Joint::LeftShoulderPitch, 300);
    let motion = Motion {
        slot: 3,
        name: "Wave".into(),
        frames: vec![Frame::new(200, pose), Frame::new(300, Pose::default())],
        loop_range: None,
        jump_slot: None,
    };
    let list = PlayList { name: "Show".into(), entries: vec![PlayEntry { slot: 3, plays: 2 }] };
    Project {
        family: Family::Plen2,
        plen2: Plen2Project { motions: vec![motion], play_lists: vec![list], ..Default::default() },
        ..Project::default()
    }
}

fn harness(tab: Tab) -> Harness<'static, StudioApp> {
    let mut app = common::ui::editor(project());
    app.apply(Action::ConnectDemo);
    assert!(app.link.as_ref().is_some_and(|link| link.plen2().is_some()), "{:?}", app.status);
    assert!(app.status.as_ref().unwrap().text.contains("factory-fresh"), "{:?}", app.status);
    common::ui::showing(app, tab, (1200.0, 800.0))
}

fn inspect(harness: &Harness<'static, StudioApp>) -> Plen2State {
    let (reply, state) = crossbeam_channel::bounded(1);
    harness.state().link.as_ref().unwrap().demo_plen2().unwrap().command(Plen2SimCommand::Inspect(reply));
    state.recv_timeout(Duration::from_secs(10)).unwrap()
}

/// Waits (on the robot's own events) until it executes a command matching `wanted`.
fn executed(harness: &Harness<'static, StudioApp>, what: &str, wanted: impl Fn(&Command) -> bool) {
    let events = harness.state().link.as_ref().unwrap().demo_plen2().unwrap().events().clone();
    let deadline = Instant::now() + Duration::from_secs(10);
    loop {
        match events.recv_deadline(deadline) {
            Ok(LinkEvent::Driver(Plen2SimEvent::Executed(command))) if wanted(&command) => return,
            Ok(_) => {}
            Err(_) => panic!("the robot never executed {what}"),
        }
    }
}

/// Runs frames (a joint is walked a step per cycle at the live speed limit)
/// until the robot executes a command matching `wanted`.
fn walked(harness: &mut Harness<'static, StudioApp>, what: &str, wanted: impl Fn(&Command) -> bool) {
    let events = harness.state().link.as_ref().unwrap().demo_plen2().unwrap().events().clone();
    let deadline = Instant::now() + Duration::from_secs(10);
    loop {
        assert!(Instant::now() < deadline, "the robot never executed {what}");
        harness.step();
        common::ui::wait_for_news();
        while let Ok(event) = events.try_recv() {
            if let LinkEvent::Driver(Plen2SimEvent::Executed(command)) = event
                && wanted(&command)
            {
                return;
            }
        }
    }
}

#[test]
fn a_joint_moves_live_within_its_limits_and_stop_sends_ri_then_hp() {
    let mut harness = harness(Tab::Joints);
    assert!(harness.query_all_by_label_contains("left_knee_pitch #6").next().is_some());
    harness
        .state_mut()
        .apply(Action::family(servo_studio::ui::Plen2Action::SetJoint { joint: Joint::LeftKneePitch, tenths: 2000 }));
    harness.step();
    // Clamped to the factory max of 90.0°.
    assert_eq!(common::ui::plen2_ui(harness.state()).pose[Joint::LeftKneePitch.index()], 900);
    // Walked there from home (50.0°) at the live speed limit, 180°/s: a step per
    // firmware cycle at most, the first at once, never the whole 40° in one go.
    let events = harness.state().link.as_ref().unwrap().demo_plen2().unwrap().events().clone();
    let deadline = Instant::now() + Duration::from_secs(10);
    let mut angles = vec![500];
    while angles.last() != Some(&900) {
        assert!(Instant::now() < deadline, "the knee never reached 90°: {angles:?}");
        harness.step();
        common::ui::wait_for_news();
        while let Ok(event) = events.try_recv() {
            if let LinkEvent::Driver(Plen2SimEvent::Executed(Command::SetAngle { device: 6, angle })) = event {
                angles.push(angle);
            }
        }
    }
    assert!(angles.len() >= 3, "walked, not sent at once: {angles:?}");
    assert!(angles[1] - angles[0] <= 58, "the first step is one cycle's worth (5.8°): {angles:?}");
    assert!(angles.windows(2).all(|pair| pair[0] < pair[1]), "{angles:?}");
    assert_eq!(inspect(&harness).angles[6], 900);

    harness.get_all_by_label_contains("STOP").next().unwrap().click();
    harness.step();
    executed(&harness, "#RI", |c| *c == Command::ResetInterpreter);
    executed(&harness, "$HP", |c| *c == Command::HomePosition);
    assert_eq!(inspect(&harness).angles[6], 500, "home");
    assert!(harness.state().status.as_ref().unwrap().text.starts_with("STOP"));
}

#[test]
fn a_captured_pose_becomes_a_frame_relative_to_home() {
    let mut harness = harness(Tab::Joints);
    harness
        .state_mut()
        .apply(Action::family(servo_studio::ui::Plen2Action::SetJoint { joint: Joint::RightKneePitch, tenths: -400 }));
    harness.get_by_label_contains("Capture into frame").click();
    harness.step();
    let motion = &harness.state().document.project.plen2.motions[0];
    assert_eq!(motion.frames.len(), 3);
    // Right knee home is −50.0°, so −40.0° is +100 relative to home.
    assert_eq!(motion.frames[2].values_tenths_deg.get(Joint::RightKneePitch), 100);
}

/// The robot panel's last result, as it words it.
fn shown_result(app: &StudioApp) -> String {
    common::ui::plen2_ui(app).result.as_ref().expect("a result").words(app.language).0
}

#[test]
fn the_robot_panel_uploads_verifies_and_a_play_list_queues_its_motions() {
    let mut harness = harness(Tab::Board);
    harness.get_by_label("Upload motions").click();
    let deadline = Instant::now() + Duration::from_secs(20);
    while harness.state().operation.is_some() || common::ui::plen2_ui(harness.state()).result.is_none() {
        assert!(Instant::now() < deadline, "the upload never ended");
        harness.step();
        common::ui::wait_for_news();
    }
    let result = shown_result(harness.state());
    assert!(result.contains("Uploaded and verified, items: 1/1"), "{result}");
    // The status line follows: the robot is no longer the factory-fresh one it connected to.
    // (A reply that came late on this machine's clock may have widened the pacing just
    // after; its note is the newest line then, and the result stays in the panel.)
    let status = harness.state().status.clone().unwrap();
    let widened = status.text.starts_with("pacing widened: ");
    assert!(
        (status.text.starts_with("Uploaded and verified, items: 1/1") || widened) && !status.is_error,
        "{status:?}"
    );
    assert!(
        harness.query_all_by_label_contains("Uploaded and verified, items: 1/1").count() >= if widened { 1 } else { 2 },
        "the panel and the status line"
    );
    assert!(result.contains("plen2-backup-"), "{result}");
    assert_eq!(inspect(&harness).written_slots, [3]);

    harness.state_mut().apply(Action::family(servo_studio::ui::Plen2Action::PlayList(0)));
    executed(&harness, "#PU slot 3, two plays", |c| *c == Command::Push { slot: 3, plays: 2 });
    executed(&harness, "#PO", |c| *c == Command::Pop);
    harness.state_mut().apply(Action::ShowTab(Tab::PlayLists));
    harness.run_steps(2);
    assert!(harness.query_by_label("Play on robot").is_some(), "the play list is shown");

    harness.state_mut().apply(Action::family(servo_studio::ui::Plen2Action::Robot(Plen2Intent::Read)));
    let deadline = Instant::now() + Duration::from_secs(60);
    while harness.state().operation.is_some() {
        assert!(Instant::now() < deadline, "the read never ended");
        harness.step();
        common::ui::wait_for_news();
    }
    let robot = common::ui::plen2_ui(harness.state()).robot.clone().unwrap();
    assert_eq!(robot.motions, harness.state().document.project.plen2.motions);
    let result = shown_result(harness.state());
    assert_eq!(result, "Read the robot; motions it holds: 1", "reading does not replace the project");
}

#[test]
fn keyboard_nudges_the_focused_joint_by_1_and_10_degrees_within_its_limits() {
    let mut harness = harness(Tab::Joints);
    let knee = Joint::LeftKneePitch;
    let before = common::ui::plen2_ui(harness.state()).pose;
    let start = before[knee.index()];
    harness.get_all_by_role(Role::Slider).nth(knee.index()).unwrap().focus();
    harness.run_steps(2);
    harness.key_press(egui::Key::ArrowRight);
    harness.run_steps(2);
    assert_eq!(common::ui::plen2_ui(harness.state()).pose[knee.index()], start + 10, "1° is 10 tenths");
    harness.key_press_modifiers(egui::Modifiers::SHIFT, egui::Key::ArrowLeft);
    harness.run_steps(2);
    assert_eq!(common::ui::plen2_ui(harness.state()).pose[knee.index()], start - 90);
    walked(&mut harness, "$AN for the nudged knee", |c| *c == Command::SetAngle { device: 6, angle: start - 90 });
    for _ in 0..200 {
        harness.key_press(egui::Key::PageUp);
        harness.step();
    }
    harness.run_steps(2);
    assert_eq!(common::ui::plen2_ui(harness.state()).pose[knee.index()], 900, "the factory max holds");
    let others = Joint::ALL.into_iter().filter(|&j| j != knee);
    assert!(
        others.into_iter().all(|j| common::ui::plen2_ui(harness.state()).pose[j.index()] == before[j.index()]),
        "no other joint moved"
    );
}

/// A file with values the editor would not author (a 20 ms transition, a joint
/// setting beyond the factory range) is shown as it is: drawing the panels
/// never edits the document.
#[test]
fn showing_out_of_range_values_does_not_change_them() {
    let mut document = project();
    document.plen2.motions[0].frames[1].transition_ms = 20;
    document.plen2.joints.push(servo_studio::project::plen2::JointSetting {
        joint: Joint::LeftKneePitch,
        min_tenths_deg: -1200,
        max_tenths_deg: 900,
        home_tenths_deg: 0,
    });
    let app = common::ui::editor(document.clone());
    let mut harness = common::ui::window(app, (1200.0, 800.0));
    for tab in [Tab::Motions, Tab::Joints] {
        harness.state_mut().apply(Action::ShowTab(tab));
        harness.run_steps(3);
    }
    harness.get_by_label_contains("Joint settings").click();
    harness.run_steps(3);
    assert!(!harness.state().document.can_undo(), "nothing was edited");
    assert_eq!(harness.state().document.project.plen2, document.plen2);
}

#[test]
fn the_pacing_is_chosen_in_the_connection_settings_and_used_at_the_next_connection() {
    use servo_studio::device::plen2::PacingMode;
    let data = tempfile::tempdir().unwrap();
    let app = StudioApp::new(project(), None, no_waker()).with_data_dir(data.path().to_path_buf());
    let mut harness = common::ui::window(app, (1200.0, 800.0));
    harness.run();
    assert_eq!(common::ui::plen2_ui(harness.state()).pacing, PacingMode::Adaptive, "adaptive by default");
    harness.get_by_label("Pacing").click();
    harness.run();
    harness.get_by_label("Safe (official)").click();
    harness.run();
    assert_eq!(common::ui::plen2_ui(harness.state()).pacing, PacingMode::Safe);
    harness.get_by_label("Demo board").click();
    harness.run();
    let link = harness.state().link.as_ref().expect("connected");
    assert_eq!(link.plen2().unwrap().pacing(), PacingMode::Safe);
    // Remembered between runs.
    assert_eq!(harness.state().remembered().plen2_pacing, PacingMode::Safe);
}

/// plen2.md §6 in the editor: a loop of count 0 is said to run forever (in
/// the preview and as a warning), a first frame under 32 ms as undefined.
#[test]
fn the_motion_editor_says_what_the_robot_really_does_with_an_edge_motion() {
    let mut document = project();
    document.plen2.motions[0].loop_range =
        Some(servo_studio::project::plen2::LoopRange { begin_frame: 0, end_frame: 1, count: 0 });
    document.plen2.motions[0].frames[0].transition_ms = 20;
    let app = common::ui::editor(document);
    let mut harness = common::ui::window(app, (1200.0, 800.0));
    harness.state_mut().apply(Action::ShowTab(Tab::Motions));
    harness.run_steps(3);
    assert!(harness.query_by_label_contains("This motion never ends on the robot").is_some());
    assert!(harness.query_by_label_contains("the robot divides by zero there").is_some());
    let problems: Vec<String> =
        servo_studio::project::validate(&harness.state().document.project).iter().map(ToString::to_string).collect();
    assert!(problems.iter().any(|p| p.contains("loop count 0 runs forever")), "{problems:?}");
}

/// motion.json… asks the shell where (the dialog is answered here), and the
/// motion is written there off the frame, in the official editor's format.
#[test]
fn a_motion_is_saved_as_motion_json_where_the_user_chose() {
    use servo_studio::ui::{FileRequest, Picker};
    let data = tempfile::tempdir().unwrap();
    let chosen = data.path().join("wave.json");
    let answer = chosen.clone();
    let offered = std::sync::Arc::new(std::sync::Mutex::new(None));
    let seen = offered.clone();
    let picker: Picker = std::sync::Arc::new(move |request: &FileRequest, waker: servo_studio::link::Waker| {
        if let FileRequest::Export(export) = request {
            *seen.lock().unwrap() = Some(export.name.clone());
        }
        let (tx, rx) = crossbeam_channel::bounded(1);
        tx.send(Some(answer.clone())).unwrap();
        waker();
        rx
    });
    let app = common::ui::editor(project()).with_picker(picker);
    let mut harness = common::ui::showing(app, Tab::Motions, (1200.0, 800.0));
    harness.get_by_label("motion.json…").click();
    common::ui::run_until(&mut harness, "the motion.json", |_| chosen.exists());
    assert_eq!(offered.lock().unwrap().as_deref(), Some("03_Wave.json"), "the name the official editor gives it");
    let written = servo_studio::project::motion_json::load_motions(&chosen).map(|mut motions| motions.remove(0));
    assert_eq!(written.unwrap(), project().plen2.motions[0]);
    common::ui::run_until(&mut harness, "the status line", |app| {
        app.status.as_ref().is_some_and(|status| status.text == format!("saved {}", chosen.display()))
    });
}

#[test]
fn a_curve_picked_for_a_frame_is_one_undo_step_and_the_meter_shows_what_it_costs() {
    let mut harness = harness(Tab::Motions);
    assert!(harness.query_by_label_contains("On the robot").is_none(), "no curve, no meter");
    // The first frame's curve (its name is its hover text).
    harness.query_all(by().role(Role::ComboBox).value("Linear")).next().unwrap().click();
    harness.run();
    harness.get_by_label("Ease in-out").click();
    harness.run();
    let motion = &harness.state().document.project.plen2.motions[0];
    assert_eq!(motion.frames[0].easing, servo_studio::project::Easing::EaseInOut);
    assert_eq!(motion.frames[1].easing, servo_studio::project::Easing::Linear);
    // What the robot will store: the eased frame baked, the other as it is.
    let stored = servo_studio::device::plen2::stored_motion(motion);
    assert!(stored.frames.len() > 2, "{} frames", stored.frames.len());
    let meter = harness.get_by_label_contains("On the robot").accesskit_node().label().unwrap_or_default();
    assert!(meter.contains(&format!("On the robot: {} frames of 20", stored.frames.len())), "{meter}");
    assert!(meter.contains("largest deviation from the curves"), "{meter}");
    // The graph draws what the robot plays against the curve.
    assert!(harness.query_all(by().value("dashed: what the board plays")).next().is_some());
    harness.state_mut().apply(Action::Undo);
    harness.run();
    assert_eq!(
        harness.state().document.project.plen2.motions[0].frames[0].easing,
        servo_studio::project::Easing::Linear
    );
    assert!(harness.query_by_label_contains("On the robot").is_none());
}

#[test]
fn frames_are_retimed_twice_as_slow_or_to_a_total_each_one_undo_step() {
    let mut harness = harness(Tab::Motions);
    let times = |harness: &Harness<'static, StudioApp>| -> Vec<u16> {
        harness.state().document.project.plen2.motions[0].frames.iter().map(|frame| frame.transition_ms).collect()
    };
    assert_eq!(times(&harness), vec![200, 300]);
    harness.get_by_label("×2").click();
    harness.run();
    assert_eq!(times(&harness), vec![400, 600]);
    // The total shows 1 s; typed as 1.5 s, each frame keeps its share.
    let total = || by().role(Role::SpinButton).label("total");
    assert_eq!(harness.get(total()).value().as_deref(), Some("1000 ms"));
    harness.get(total()).click();
    harness.run();
    harness.get(total()).type_text("1500");
    harness.run();
    harness.key_press(egui::Key::Enter);
    harness.run();
    assert_eq!(times(&harness), vec![600, 900]);
    assert_eq!(harness.get(total()).value().as_deref(), Some("1500 ms"));
    harness.state_mut().apply(Action::Undo);
    harness.run();
    assert_eq!(times(&harness), vec![400, 600], "one undo step each");
    harness.state_mut().apply(Action::Undo);
    harness.run();
    assert_eq!(times(&harness), vec![200, 300]);
}

/// Recording a scripted sequence of joint moves: after the 3 s count-in the
/// knee ramps 32° in 2 s and holds 1 s; Stop fits it into the fewest frames
/// the robot plays within 1°, inserted after the selected frame, one undo step.
#[test]
fn recording_joint_moves_fits_them_into_frames_after_the_selected_one() {
    use servo_studio::ui::Plen2Action;
    let app = common::ui::editor(project());
    let mut harness = common::ui::showing(app, Tab::Joints, (1200.0, 800.0));
    let knee = Joint::LeftKneePitch;
    let home = common::ui::plen2_ui(harness.state()).pose[knee.index()];
    let set = |harness: &mut Harness<'static, StudioApp>, relative: i16| {
        harness.state_mut().apply(Action::family(Plen2Action::SetJoint { joint: knee, tenths: home + relative }));
    };
    common::ui::record_through_count_in(&mut harness);
    for k in 0..=8 {
        set(&mut harness, 40 * k);
        harness.step();
    }
    assert!(harness.query_by_label_contains("REC 2.0 s").is_some());
    for _ in 0..4 {
        harness.step();
    }
    harness.get_by_label("■ Stop recording").click();
    harness.step();
    harness.step();
    let frames = &harness.state().document.project.plen2.motions[0].frames;
    let knees: Vec<i16> = frames.iter().map(|frame| frame.values_tenths_deg.get(knee)).collect();
    let times: Vec<u16> = frames.iter().map(|frame| frame.transition_ms).collect();
    // Frame 0 (shoulder at 30°) stays; the recording starts with the shoulder at home:
    // one cycle takes it there, one frame ramps the knee, one holds; then the old frame 1.
    assert_eq!(frames.len(), 5, "{times:?} {knees:?}");
    assert_eq!(frames[1].values_tenths_deg.get(Joint::LeftShoulderPitch), 0);
    assert_eq!(times[1], 32, "{times:?}");
    assert!((i32::from(knees[2]) - 320).abs() <= 10, "{knees:?}");
    assert!((i32::from(times[2]) - 2000).abs() <= 100, "{times:?}");
    assert_eq!(knees[3], knees[2], "{knees:?}");
    assert_eq!(times[4], 300, "the motion's own frame 1 follows");
    let status = harness.state().status.as_ref().unwrap().text.clone();
    assert!(status.starts_with("Recorded and fitted: "), "{status}");
    assert!(status.contains(" s → 3 frames inserted after frame 0 · largest error "), "{status}");
    harness.state_mut().apply(Action::Undo);
    harness.step();
    assert_eq!(harness.state().document.project.plen2.motions[0].frames.len(), 2, "one undo step");
}

/// The robot reports no angles: after a motion played on it, the joints are
/// where its last frame leaves them (the firmware's playback of the project's
/// motion), so a joint moved next is walked from there, never jumped from
/// where the sliders were.
#[test]
fn after_a_motion_played_on_the_robot_a_joint_is_walked_from_where_the_motion_left_it() {
    let mut document = project();
    let mut bent = Pose::default();
    bent.set(Joint::LeftKneePitch, -300);
    document.plen2.motions.push(Motion {
        slot: 4,
        name: "Crouch".into(),
        frames: vec![Frame::new(300, bent)],
        loop_range: None,
        jump_slot: None,
    });
    let mut app = common::ui::editor(document);
    app.apply(Action::ConnectDemo);
    let mut harness = common::ui::showing(app, Tab::Joints, (1200.0, 800.0));
    let knee = Joint::LeftKneePitch;
    let home = common::ui::plen2_ui(harness.state()).pose[knee.index()];
    harness.state_mut().apply(Action::family(servo_studio::ui::Plen2Action::PlayMotion(4)));
    harness.step();
    assert_eq!(
        common::ui::plen2_ui(harness.state()).pose[knee.index()],
        home - 300,
        "the sliders show where the motion ends"
    );
    // A nudge up from there: the robot gets 1° above the crouch, not 1° above home.
    harness
        .state_mut()
        .apply(Action::family(servo_studio::ui::Plen2Action::SetJoint { joint: knee, tenths: home - 290 }));
    let device = knee.device_id();
    let first = std::cell::Cell::new(None);
    walked(&mut harness, "$AN for the knee", |c| match c {
        Command::SetAngle { device: d, angle } if *d == device => {
            first.set(Some(*angle));
            true
        }
        _ => false,
    });
    assert_eq!(first.get(), Some(home - 290), "one step from the crouch, not a walk from home");
}
