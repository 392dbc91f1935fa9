//! The robot previews as a user works them: the time cursor scrubbed to a
//! time shows the pose the robot has then (read from the view's model, and
//! worked out by hand from plen2.md §6 or the board's linear steps), Space
//! plays and stops the preview, the 3D views and the base's world view
//! render headless, and the world view's echoes land on the emulated room's walls.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common;

use std::time::{Duration, Instant};

use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use servo_studio::project::plen2::{Frame, Joint, JointSetting, Motion, Plen2Project, Pose};
use servo_studio::project::{self, Family, Project};
use servo_studio::sim::{BaseState, RflexSimCommand};
use servo_studio::ui::{Action, RflexBoardLink as _, StudioApp, Tab};

fn harness(project: Project, tab: Tab) -> Harness<'static, StudioApp> {
    common::ui::showing(common::ui::editor(project), tab, (1400.0, 900.0))
}

/// Drags the time cursor to `fraction` of its length and lets go there.
fn scrub(harness: &mut Harness<'static, StudioApp>, fraction: f32) {
    let rect = harness.get_by_label("Time cursor").rect();
    let at = egui::pos2(rect.left() + rect.width() * fraction, rect.center().y);
    harness.drag_at(egui::pos2(rect.left() + 2.0, rect.center().y));
    harness.step();
    harness.hover_at(at);
    harness.step();
    harness.drop_at(at);
    harness.run_steps(2);
}

/// A motion whose left shoulder rises to 30° in 200 ms, then comes back in 300 ms.
fn plen2_project() -> Project {
    let mut raised = Pose::default();
    raised.set(Joint::LeftShoulderPitch, 300);
    let motion = Motion {
        slot: 3,
        name: "Raise 舉手".into(),
        frames: vec![Frame::new(200, raised), Frame::new(300, Pose::default())],
        loop_range: None,
        jump_slot: None,
    };
    Project {
        family: Family::Plen2,
        plen2: Plen2Project { motions: vec![motion], ..Default::default() },
        ..Project::default()
    }
}

fn shoulder(harness: &Harness<'static, StudioApp>) -> i16 {
    let shown = common::ui::plen2_ui(harness.state()).preview.shown.expect("the view shows a pose");
    shown[usize::from(Joint::LeftShoulderPitch.device_id())]
}

#[test]
fn scrubbing_a_plen2_motion_shows_the_firmwares_cycle_at_that_time() {
    let mut harness = harness(plen2_project(), Tab::Motions);
    assert_eq!(harness.query_all_by_role_and_label(Role::Image, "Robot preview").count(), 1);
    // By hand (plen2.md §6): 200 ms is 200 / 32 = 6 cycles of 32.768 ms, each
    // adding 300 / 6 = 50; then 300 / 32 = 9 cycles back. 15 cycles = 491.52 ms.
    // A quarter of the way is 122.9 ms: cycle 3, the fourth step, 200.
    scrub(&mut harness, 0.25);
    let t = common::ui::plen2_ui(harness.state()).preview.transport.t_ms;
    let cycle = (t / 32.768).floor();
    assert_eq!(cycle, 3.0, "t = {t} ms");
    assert_eq!(shoulder(&harness), 200);
    // The sixth cycle (t in 163.8–196.6 ms) reaches the frame: 300.
    scrub(&mut harness, 0.37);
    let t = common::ui::plen2_ui(harness.state()).preview.transport.t_ms;
    assert_eq!((t / 32.768).floor(), 5.0, "t = {t} ms");
    assert_eq!(shoulder(&harness), 300);
    // Past the end the last cycle holds: home again.
    scrub(&mut harness, 1.0);
    assert_eq!(shoulder(&harness), 0);
}

#[test]
fn space_plays_the_preview_at_real_speed_and_stops_it() {
    let mut harness = harness(plen2_project(), Tab::Motions);
    scrub(&mut harness, 0.0);
    let start = common::ui::plen2_ui(harness.state()).preview.transport.t_ms;
    assert!(!common::ui::plen2_ui(harness.state()).preview.transport.is_playing());
    harness.key_press(egui::Key::Space);
    harness.step();
    assert!(common::ui::plen2_ui(harness.state()).preview.transport.is_playing(), "Space plays");
    // The harness's clock moves 250 ms a frame: the cursor follows, looping over 491.52 ms.
    let before = common::ui::plen2_ui(harness.state()).preview.transport.t_ms;
    harness.step();
    let after = common::ui::plen2_ui(harness.state()).preview.transport.t_ms;
    let moved = (after - before).rem_euclid(491.52);
    assert!((moved - 250.0).abs() < 1e-6, "moved {moved} ms (from {start})");
    harness.get_by_label("Pause").click();
    harness.step();
    assert!(!common::ui::plen2_ui(harness.state()).preview.transport.is_playing(), "the button pauses");
    harness.key_press(egui::Key::Space);
    harness.step();
    assert!(common::ui::plen2_ui(harness.state()).preview.transport.is_playing(), "Space plays again");
    harness.key_press(egui::Key::Space);
    harness.step();
    let stopped = common::ui::plen2_ui(harness.state()).preview.transport.t_ms;
    harness.run_steps(3);
    assert!(!common::ui::plen2_ui(harness.state()).preview.transport.is_playing(), "Space stops");
    assert_eq!(common::ui::plen2_ui(harness.state()).preview.transport.t_ms, stopped, "stopped where it was");
}

#[test]
fn the_plen2_joints_tab_shows_the_live_pose_clamped_as_the_firmware_outputs_it() {
    let mut project = plen2_project();
    // The elbow homes at 10° and may go from −30° to 40°.
    let elbow =
        JointSetting { joint: Joint::LeftElbowRoll, min_tenths_deg: -300, max_tenths_deg: 400, home_tenths_deg: 100 };
    project.plen2.joints = vec![elbow];
    let mut harness = harness(project, Tab::Joints);
    assert!(harness.query_by_role_and_label(Role::Image, "Robot preview").is_some());
    let elbow_shown = |harness: &Harness<'static, StudioApp>| {
        common::ui::plen2_ui(harness.state()).preview.shown.expect("the view shows a pose")
            [usize::from(Joint::LeftElbowRoll.device_id())]
    };
    // At home: nothing bent.
    assert_eq!(elbow_shown(&harness), 0);
    let set = |harness: &mut Harness<'static, StudioApp>, tenths: i16| {
        harness
            .state_mut()
            .apply(Action::family(servo_studio::ui::Plen2Action::SetJoint { joint: Joint::LeftElbowRoll, tenths }));
        harness.run_steps(2);
    };
    set(&mut harness, 250);
    assert_eq!(elbow_shown(&harness), 150, "25° is 15° from home");
    // Asked far past the limit, the joint stops at its maximum: 40° − 10°.
    set(&mut harness, 3_000);
    assert_eq!(elbow_shown(&harness), 300);
}

#[test]
fn scrubbing_a_servo_action_shows_the_boards_linear_step_at_that_time() {
    let mut harness = harness(servo_studio::ui::sample_project(), Tab::Actions);
    harness.get_by_label("2 Wave up 揮手舉起").click();
    harness.run_steps(2);
    // "Wave up": every servo moves to its angle in 40 × 10 ms; the right
    // shoulder pitch (servo 4) from 0° to −80°, so −40° at 200 ms.
    scrub(&mut harness, 0.5);
    let t = common::ui::servo_ui(harness.state()).figure.transport.t_ms;
    assert!((t - 200.0).abs() < 5.0, "t = {t}");
    let shown = common::ui::servo_ui(harness.state()).figure.shown.clone().expect("the view shows a pose");
    assert!((shown[&4] + 40.0).abs() <= 1.0, "servo 4 at {}", shown[&4]);
    assert!((shown[&5] - 30.0).abs() <= 1.0, "servo 5 at {}", shown[&5]);
    // And exactly the trajectory the plot draws, at the board's 10 ms step.
    let servo = &harness.state().document.project.servo;
    let (trajectories, _) = project::action_trajectories(servo, 2);
    let step = (t / project::SAMPLE_MS).round() * project::SAMPLE_MS;
    for (id, points) in &trajectories {
        let expected = project::angle_at(points, step).unwrap();
        assert!((shown[id] - expected).abs() < 1e-9, "servo {id}: {} vs {expected}", shown[id]);
    }
    // Every rigged servo is in the figure; the view renders headless.
    assert!(harness.query_by_role_and_label(Role::Image, "Robot preview").is_some());
    // A step's number puts the cursor where its servo arrives: step 4, 40 × 10 ms.
    harness.get_by_role_and_label(Role::Button, "4").click();
    harness.run_steps(2);
    assert_eq!(common::ui::servo_ui(harness.state()).figure.transport.t_ms, 400.0);
    assert_eq!(common::ui::servo_ui(harness.state()).figure.shown.as_ref().unwrap()[&4], -80.0);
}

#[test]
fn the_view_toggle_hides_and_shows_the_preview() {
    let mut harness = harness(servo_studio::ui::sample_project(), Tab::Servos);
    let previews = |harness: &Harness<'static, StudioApp>| {
        harness.query_all_by_role_and_label(Role::Image, "Robot preview").count()
    };
    assert_eq!(previews(&harness), 1);
    harness.get_by_label("3D view").click();
    harness.run_steps(2);
    assert_eq!(previews(&harness), 0);
    assert!(!common::ui::servo_ui(harness.state()).layout.view_open);
    harness.get_by_label("3D view").click();
    harness.run_steps(2);
    assert_eq!(previews(&harness), 1);
}

fn inspect(harness: &Harness<'static, StudioApp>) -> BaseState {
    let (reply, state) = crossbeam_channel::bounded(1);
    harness.state().link.as_ref().unwrap().demo_base().unwrap().command(RflexSimCommand::Inspect(reply));
    state.recv_timeout(Duration::from_secs(10)).unwrap()
}

/// Steps the window until `done` holds (the link's reports arrive on their own thread).
fn step_until(
    harness: &mut Harness<'static, StudioApp>,
    what: &str,
    done: impl Fn(&Harness<'static, StudioApp>) -> bool,
) {
    let deadline = Instant::now() + Duration::from_secs(10);
    while !done(harness) {
        assert!(Instant::now() < deadline, "never: {what}");
        harness.step();
        common::ui::wait_for_news();
    }
}

/// Whether every echo of the map lies on a wall of the emulated 4.2 × 2.8 m
/// room (the base started in its middle facing +x), within `slack` metres.
fn on_the_walls(harness: &Harness<'static, StudioApp>, slack: f64) -> Result<usize, String> {
    let telemetry = &harness.state().link.as_ref().unwrap().rflex().unwrap().telemetry;
    let mut count = 0;
    for ([x, y], _) in telemetry.echoes.points() {
        let off = ((x.abs() - 2.1).abs()).min((y.abs() - 1.4).abs());
        if off > slack {
            return Err(format!("an echo at ({x:.3}, {y:.3}) is {off:.3} m off the walls"));
        }
        count += 1;
    }
    Ok(count)
}

#[test]
fn the_world_view_maps_the_rooms_walls_as_the_base_drives() {
    let mut app = common::ui::editor(Project::empty(Family::Rflex));
    app.apply(Action::ConnectDemo);
    app.apply(Action::ShowTab(Tab::Drive));
    let mut harness = common::ui::window(app, (1400.0, 900.0));
    harness.run_steps(2);
    assert!(harness.query_by_role_and_label(Role::Image, "World view").is_some());
    step_until(&mut harness, "a full sonar sweep", |h| {
        h.state().link.as_ref().unwrap().rflex().unwrap().telemetry.full_sonar_sweep()
    });
    // At rest in the middle: each sonar's echo sits on a wall, to the map's 5 cm cell.
    let at_rest = on_the_walls(&harness, 0.05).unwrap();
    assert!(at_rest >= 16, "{at_rest} echoes");

    harness.get_by_label("Brake").click();
    harness.run_steps(2);
    step_until(&mut harness, "the brake released", |h| !inspect(h).braked);
    harness.key_down(egui::Key::ArrowUp);
    step_until(&mut harness, "the base driving 0.6 m", |h| inspect(h).x_m > 0.6);
    harness.key_up(egui::Key::ArrowUp);
    harness.run_steps(2);
    let telemetry = &harness.state().link.as_ref().unwrap().rflex().unwrap().telemetry;
    assert!(telemetry.path.iter().count() > 3, "the driven path is kept");
    // Seen from many places, the side walls fill in; every echo still on a wall
    // (odometry reports every 100 ms: up to 5 cm of pose behind the sonar, plus the cell).
    let driven = on_the_walls(&harness, 0.12).unwrap();
    assert!(driven > at_rest + 10, "{driven} echoes after driving, {at_rest} at rest");

    harness.get_by_label("Clear the map").click();
    harness.step();
    let left = harness.state().link.as_ref().unwrap().rflex().unwrap().telemetry.echoes.len();
    assert!(left <= 24, "at most one sweep heard since the map was cleared: {left}");
}

#[test]
fn the_rig_is_edited_in_servo_settings_and_the_preview_follows() {
    let mut harness = harness(servo_studio::ui::sample_project(), Tab::Servos);
    common::ui::servo_ui_mut(harness.state_mut()).layout.settings_open = true;
    harness.run_steps(2);
    harness.get_by_label("Rig").click();
    harness.run_steps(2);
    assert!(harness.query_by_label("Not in the rig").is_none(), "the demo biped is rigged throughout");
    // Servo 3 (the left elbow) taken out of the rig: a bar beside the figure.
    // Its row's first box is "In rig" (the second, "Reversed").
    harness.query_all_by_role_and_label(Role::CheckBox, "3 L elbow 左手肘").next().unwrap().click();
    harness.run_steps(2);
    let servo = harness.state().document.project.servo.servo(3).unwrap().clone();
    assert_eq!(servo.rig, None);
    assert!(harness.query_by_label("Not in the rig").is_some(), "the servo outside the rig shows as a bar");
    // Undo puts it back where it was.
    harness.state_mut().apply(Action::Undo);
    harness.run_steps(2);
    let rig = harness.state().document.project.servo.servo(3).unwrap().rig.expect("back in the rig");
    assert_eq!(rig.parent, Some(2));
}

#[test]
fn a_motion_played_after_another_starts_from_its_last_frame_and_the_snap_is_said() {
    let mut project = plen2_project();
    let mut held = Pose::default();
    held.set(Joint::LeftShoulderPitch, 500);
    project.plen2.motions.push(Motion {
        slot: 4,
        name: "Hold 舉高".into(),
        frames: vec![Frame::new(100, held)],
        loop_range: None,
        jump_slot: None,
    });
    let mut harness = harness(project, Tab::Motions);
    let snap = "The joint sliders' pose is not where this motion starts: the robot will snap there at the first cycle.";
    // From power-up the motion starts at home, where the sliders are: nothing to say.
    assert!(harness.query_by_label(snap).is_none());
    harness.get_by_label("Played after").click();
    harness.run_steps(2);
    harness.get_by_label("4 Hold 舉高").click();
    harness.run_steps(2);
    assert_eq!(common::ui::plen2_ui(harness.state()).preview.after, Some(4));
    assert!(harness.query_by_label(snap).is_some(), "the sliders stand at home, the motion starts at 50°");
    scrub(&mut harness, 0.0);
    // By hand: cycle 0 steps from 500 towards 300 over 6 cycles: (−200 << 16) / 6 truncated,
    // added to 500 << 16, floored: 466.
    assert_eq!(shoulder(&harness), 466);
}

#[test]
fn the_world_view_pans_zooms_and_goes_back_to_following_the_base() {
    let mut harness = harness(Project::empty(Family::Rflex), Tab::Drive);
    harness.state_mut().apply(Action::ConnectDemo);
    harness.run_steps(2);
    assert!(common::ui::rflex_ui(harness.state()).world.follow);
    let rect = harness.get_by_role_and_label(Role::Image, "World view").rect();
    harness.drag_at(rect.center());
    harness.step();
    harness.hover_at(rect.center() + egui::vec2(100.0, 50.0));
    harness.step();
    harness.drop_at(rect.center() + egui::vec2(100.0, 50.0));
    harness.run_steps(2);
    let world = common::ui::rflex_ui(harness.state()).world;
    assert!(!world.follow, "panning lets go of the base");
    // Dragged right and down: the view's centre moved left and up (north) in the world.
    assert!(world.center[0] < -0.5 && world.center[1] > 0.2, "{:?}", world.center);
    harness.hover_at(rect.center());
    harness.step();
    harness.event(egui::Event::MouseWheel {
        unit: egui::MouseWheelUnit::Point,
        delta: egui::vec2(0.0, -100.0),
        phase: egui::TouchPhase::Move,
        source: egui::MouseWheelSource::Wheel,
        modifiers: egui::Modifiers::NONE,
    });
    harness.run_steps(4);
    assert!(
        common::ui::rflex_ui(harness.state()).world.metres_per_point > world.metres_per_point,
        "the wheel zooms out"
    );
    // A double-click: two presses and releases within one frame.
    let at = rect.center();
    for pressed in [true, false, true, false] {
        let button = egui::Event::PointerButton {
            pos: at,
            button: egui::PointerButton::Primary,
            pressed,
            modifiers: egui::Modifiers::NONE,
        };
        harness.input_mut().events.push(button);
    }
    harness.run_steps(2);
    assert!(common::ui::rflex_ui(harness.state()).world.follow, "a double-click centres on the base again");
}

/// A frame with a curve is stored as several: selecting the authored frame
/// after it still puts the cursor where that frame is reached, and the view
/// shows the curve (eased in: slower than the line at first).
#[test]
fn a_curve_shows_in_the_preview_and_selecting_a_frame_after_it_finds_its_cycle() {
    let mut project = plen2_project();
    let frames = &mut project.plen2.motions[0].frames;
    frames[0].transition_ms = 640;
    frames[0].easing = project::Easing::EaseIn;
    let mut harness = harness(project, Tab::Motions);
    // 640 ms is 20 cycles eased in to 30°, then 9 cycles back: 29 cycles.
    harness.get_by_label("#1").click();
    harness.run();
    let t = common::ui::plen2_ui(harness.state()).preview.transport.t_ms;
    assert_eq!((t / 32.768).floor(), 28.0, "the last cycle of frame #1: t = {t} ms");
    assert_eq!(shoulder(&harness), 0);
    harness.get_by_label("#0").click();
    harness.run();
    let t = common::ui::plen2_ui(harness.state()).preview.transport.t_ms;
    assert_eq!((t / 32.768).floor(), 19.0, "the last cycle of frame #0: t = {t} ms");
    assert_eq!(shoulder(&harness), 300);
    // Halfway through the curve (cycle 9 of 20) an ease-in is a quarter of the way: within 1° of 7.5°.
    scrub(&mut harness, 9.5 / 29.0);
    let t = common::ui::plen2_ui(harness.state()).preview.transport.t_ms;
    assert_eq!((t / 32.768).floor(), 9.0, "t = {t} ms");
    let eased = 300.0 * (10.0_f64 / 20.0).powi(2);
    assert!((f64::from(shoulder(&harness)) - eased).abs() <= 10.0, "{} for {eased}", shoulder(&harness));
}
