//! Posing the PLEN2 by its hands and feet, as a user does it: hovering a ring
//! names the limb and its joints; dragging a foot's ring moves the foot (flat
//! stays flat) with the leg's joints solved, sent to the robot and undone in
//! one step; symmetric mirrors the twin; standing on a foot, the pelvis ring
//! shifts the weight while both feet stay planted. Where the foot ends up is
//! computed here by forward kinematics over the joint values the editor
//! holds, not by the solver.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common;

use std::time::{Duration, Instant};

use egui::Pos2;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use servo_studio::figure::{self, Placed, Vec3};
use servo_studio::link::LinkEvent;
use servo_studio::project::plen2::{Joint, Plen2Project};
use servo_studio::project::{Family, Project};
use servo_studio::protocol::plen2::Command;
use servo_studio::sim::Plen2SimEvent;
use servo_studio::ui::{Action, Plen2BoardLink as _, StudioApp, Tab};

const LEFT_FOOT: usize = 0;
const RIGHT_FOOT: usize = 1;
const LEFT_HAND: usize = 2;
const RIGHT_HAND: usize = 3;
const PELVIS: usize = 4;

fn harness() -> Harness<'static, StudioApp> {
    let project = Project { family: Family::Plen2, plen2: Plen2Project::default(), ..Project::default() };
    let mut app = common::ui::editor(project);
    app.apply(Action::ConnectDemo);
    common::ui::showing(app, Tab::Joints, (1200.0, 800.0))
}

fn pose(harness: &Harness<'static, StudioApp>) -> [i16; 18] {
    common::ui::plen2_ui(harness.state()).pose
}

fn ring(harness: &Harness<'static, StudioApp>, end: usize) -> Pos2 {
    common::ui::plen2_ui(harness.state()).preview.end_on_screen(end).expect("the ring is drawn")
}

/// Presses at `from`, moves the pointer `by` in eight frames, and (when `release`) lets go.
fn drag(harness: &mut Harness<'static, StudioApp>, from: Pos2, by: egui::Vec2, release: bool) {
    harness.drag_at(from);
    harness.step();
    for part in 1..=8u8 {
        harness.hover_at(from + by * f32::from(part) / 8.0);
        harness.step();
    }
    if release {
        harness.drop_at(from + by);
        harness.run_steps(2);
    }
}

/// Every link placed for the editor's joint angles (absolute tenths), the body fixed.
fn placed(angles: &[i16; 18]) -> Vec<Placed> {
    let chain = figure::plen2::chain();
    let mut values = [0; 24];
    for joint in Joint::ALL {
        values[usize::from(joint.device_id())] = angles[joint.index()] - joint.factory_home_tenths_deg();
    }
    chain.pose(&figure::plen2::angles(&chain, &values))
}

/// Where a limb's end is, and how it is turned, for the editor's angles.
fn end(angles: &[i16; 18], limb: usize) -> Placed {
    let chain = figure::plen2::chain();
    figure::plen2::limbs(&chain)[limb].reach(&placed(angles)).unwrap()
}

fn degrees_apart(a: &Placed, b: &Placed) -> f32 {
    let (_, angle) = glam::Quat::from_mat3(&(a.rotation * b.rotation.transpose())).normalize().to_axis_angle();
    angle.min(std::f32::consts::TAU - angle).to_degrees()
}

fn mm(a: Vec3, b: Vec3) -> f32 {
    (a - b).length() * figure::plen2::MM_PER_UNIT
}

fn undo(harness: &mut Harness<'static, StudioApp>) {
    harness.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Z);
    harness.run_steps(2);
}

/// Runs frames until the robot has executed `$AN` putting `joint` at `angle`.
fn robot_reaches(harness: &mut Harness<'static, StudioApp>, joint: Joint, angle: i16) {
    let events = harness.state().link.as_ref().unwrap().demo_plen2().unwrap().events().clone();
    let deadline = Instant::now() + Duration::from_secs(10);
    loop {
        assert!(Instant::now() < deadline, "the robot never turned {joint:?} to {angle}");
        harness.step();
        common::ui::wait_for_news();
        while let Ok(event) = events.try_recv() {
            if let LinkEvent::Driver(Plen2SimEvent::Executed(Command::SetAngle { device, angle: a })) = event
                && device == joint.device_id()
                && a == angle
            {
                return;
            }
        }
    }
}

#[test]
fn a_foot_dragged_by_its_ring_rises_flat_its_leg_alone_solved_sent_and_undone_in_one_step() {
    let mut harness = harness();
    let before = pose(&harness);
    let at = ring(&harness, LEFT_FOOT);
    harness.hover_at(at);
    harness.run_steps(8);
    assert!(
        harness.query_by_label_contains("left foot: left_thigh_yaw → left_thigh_roll").is_some(),
        "hovering the ring names the limb and its chain"
    );

    drag(&mut harness, at, egui::vec2(0.0, -60.0), true);
    let after = pose(&harness);
    let (from, to) = (end(&before, LEFT_FOOT), end(&after, LEFT_FOOT));
    assert!(to.position.z - from.position.z > 10.0, "the foot rose: {} → {}", from.position, to.position);
    assert!(degrees_apart(&from, &to) < 0.5, "flat stays flat: {}°", degrees_apart(&from, &to));
    let leg = [
        Joint::LeftThighYaw,
        Joint::LeftThighRoll,
        Joint::LeftThighPitch,
        Joint::LeftKneePitch,
        Joint::LeftFootPitch,
        Joint::LeftFootRoll,
    ];
    for joint in Joint::ALL.into_iter().filter(|joint| !leg.contains(joint)) {
        assert_eq!(after[joint.index()], before[joint.index()], "{joint:?} is not in the left leg and did not move");
    }
    assert_ne!(after[Joint::LeftKneePitch.index()], before[Joint::LeftKneePitch.index()], "the knee bent");
    robot_reaches(&mut harness, Joint::LeftKneePitch, after[Joint::LeftKneePitch.index()]);

    undo(&mut harness);
    assert_eq!(pose(&harness), before, "one undo brings the whole drag back");
    assert!(!harness.state().document.can_undo(), "the drag was one step");
}

#[test]
fn with_symmetric_on_the_twin_hand_follows_as_the_mirror_image() {
    let mut harness = harness();
    harness.get_by_label("Symmetric").click();
    harness.run_steps(2);
    let before = pose(&harness);
    let at = ring(&harness, LEFT_HAND);
    drag(&mut harness, at, egui::vec2(-30.0, -50.0), true);
    let after = pose(&harness);
    let (left, right) = (end(&after, LEFT_HAND).position, end(&after, RIGHT_HAND).position);
    assert!(mm(left, end(&before, LEFT_HAND).position) > 5.0, "the hand moved");
    assert!(mm(left, Vec3::new(right.x, -right.y, right.z)) < 1.0, "mirrored: {left} vs {right}");
    undo(&mut harness);
    assert_eq!(pose(&harness), before, "both hands in one undo step");
}

#[test]
fn standing_on_a_foot_the_pelvis_shifts_the_weight_and_both_feet_stay_planted() {
    let mut harness = harness();
    // Stand on the left foot: the pelvis gets its ring.
    harness.get_by_label("Stand on").click();
    harness.run_steps(2);
    harness.get_by_label("left foot").click();
    harness.run_steps(3);
    let before = pose(&harness);
    // First down, then across: the legs straighten at home.
    for by in [egui::vec2(0.0, 40.0), egui::vec2(30.0, 0.0)] {
        let at = ring(&harness, PELVIS);
        drag(&mut harness, at, by, true);
    }
    let after = pose(&harness);
    assert_ne!(after, before, "the pelvis moved the legs");
    // The body against the feet: it moved, the feet kept their places and turns to each other.
    let (l0, r0, l1, r1) =
        (end(&before, LEFT_FOOT), end(&before, RIGHT_FOOT), end(&after, LEFT_FOOT), end(&after, RIGHT_FOOT));
    let between = |l: &Placed, r: &Placed| r.relative_to(l);
    let (b0, b1) = (between(&l0, &r0), between(&l1, &r1));
    assert!(
        mm(b0.position, b1.position) < 1.0,
        "the feet stayed where they were planted: {} mm",
        mm(b0.position, b1.position)
    );
    assert!(degrees_apart(&b0, &b1) < 0.5);
    let body = |l: &Placed, angles: &[i16; 18]| placed(angles)[0].relative_to(l).position;
    assert!(mm(body(&l0, &before), body(&l1, &after)) > 10.0, "the pelvis moved over the feet");
    assert!(degrees_apart(&l0, &l1) < 0.5, "the planted foot stayed flat");
}

#[test]
fn a_foot_pulled_out_of_reach_stops_short_and_shows_the_gap_until_let_go() {
    let mut harness = harness();
    let at = ring(&harness, RIGHT_FOOT);
    drag(&mut harness, at, egui::vec2(0.0, 400.0), false);
    let gap = common::ui::plen2_ui(harness.state()).preview.posing.gap().expect("the gap is shown");
    assert!(gap.words.contains("mm out of reach"), "{}", gap.words);
    assert!(mm(gap.from, gap.to) > 20.0);
    let still = pose(&harness);
    let foot = end(&still, RIGHT_FOOT).position;
    assert!(mm(foot, gap.from) < 1.0, "the line starts where the foot stopped");
    harness.drop_at(at + egui::vec2(0.0, 400.0));
    harness.run_steps(2);
    assert!(common::ui::plen2_ui(harness.state()).preview.posing.gap().is_none(), "let go, the gap goes");
}

#[test]
fn the_sliders_and_the_view_share_the_width_without_an_empty_band() {
    use egui::accesskit::Role;
    use egui_kittest::kittest::NodeT as _;
    for (family, tab) in [(Family::Plen2, Tab::Joints), (Family::Servo, Tab::Servos)] {
        for size in [(1600.0, 1000.0), (1100.0, 720.0)] {
            let project = if family == Family::Servo {
                servo_studio::ui::sample_project()
            } else {
                Project { family, ..Project::default() }
            };
            let harness = common::ui::showing(common::ui::editor(project), tab, size);
            let slider = harness.get_all_by_role(Role::Slider).next().unwrap().rect();
            let view = harness
                .get_all_by_role(Role::Image)
                .find(|node| node.accesskit_node().label().is_some_and(|l| l.contains("Robot preview")))
                .expect("the 3D view")
                .rect();
            let band = view.min.x - slider.max.x;
            // Between them: the row's value and home (PLEN2) or hold (servo) columns, ~140 px;
            // sliders capped at 420 px left a band of ~480 px at 1600 wide.
            assert!(band < 200.0, "{family:?} at {size:?}: {band} px between the sliders' end and the view");
        }
    }
}

/// A drag that starts on a link and passes over a ring (the right thigh
/// dragged up and left, across the right hand's ring): the joint turns for
/// the whole drag — the camera does not take over — and the drag is one
/// undo step; Ctrl+Z takes back exactly it, not the edit before.
#[test]
fn a_drag_on_a_link_across_a_ring_is_one_undo_step() {
    let mut harness = harness();
    // An edit before the drag (a sound track, as a user saw it), which one undo must leave alone.
    let track = servo_studio::project::SoundTrack {
        path: "song.wav".into(),
        duration_ms: 3000,
        sha256: String::new(),
        offset_ms: 0,
        sensitivity_percent: 50,
    };
    harness.state_mut().document.apply(servo_studio::project::Edit::SetSound(Some(track)), None);
    harness.state_mut().document.seal();
    harness.run_steps(3);
    let with_motion = harness.state().document.project.clone();
    let before = pose(&harness);
    let camera = common::ui::plen2_ui(harness.state()).preview.joints_camera();
    let thigh = common::ui::plen2_ui(harness.state()).preview.joint_on_screen(Joint::RightThighPitch).unwrap();
    let hand = ring(&harness, RIGHT_HAND);
    // Through the ring and on past it.
    drag(&mut harness, thigh, (hand - thigh) * 1.5, true);
    let after = pose(&harness);
    assert_ne!(after[Joint::RightThighPitch.index()], before[Joint::RightThighPitch.index()], "the thigh turned");
    assert_eq!(common::ui::plen2_ui(harness.state()).preview.joints_camera(), camera, "the camera did not orbit");
    harness.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Z);
    harness.run_steps(2);
    assert_eq!(pose(&harness), before, "one undo takes the whole drag back");
    assert_eq!(harness.state().document.project, with_motion, "and only the drag");
}
