//! Property: any v2 project, of any family, survives save → load unchanged.

#![allow(clippy::unwrap_used)]

use proptest::prelude::*;
use servo_studio::project::gamepad::{
    AxisBinding, AxisMode, AxisTarget, ButtonBinding, Fire, GamepadMappings, Mapping,
};
use servo_studio::project::plen2::{
    Frame, Joint, JointSetting, LoopRange, Motion, PlayEntry, PlayList, Plen2Project, Pose,
};
use servo_studio::project::rflex::{DriveSettings, RflexProject, Robot};
use servo_studio::project::{
    self, Action, Button, Command, Family, JoystickTable, Macro, Project, RigAxis, RigJoint, Run, Servo, ServoProject,
    Step,
};

fn text() -> impl Strategy<Value = String> {
    // ASCII, CJK and the characters JSON must escape.
    proptest::string::string_regex("[a-zA-Z0-9 \"\\\\/\\n\\t揮手動作遙控器左右]{0,12}").unwrap()
}

fn rig() -> impl Strategy<Value = Option<RigJoint>> {
    proptest::option::of(
        (proptest::option::of(any::<u8>()), any::<[i16; 3]>(), 0..3usize, any::<bool>(), any::<i16>()).prop_map(
            |(parent, offset_mm, axis, reversed, straight_deg)| RigJoint {
                parent,
                offset_mm,
                axis: RigAxis::ALL[axis],
                reversed,
                straight_deg,
                mirror: None,
                end: None,
            },
        ),
    )
}

fn servo() -> impl Strategy<Value = Servo> {
    (any::<u8>(), text(), any::<i16>(), any::<i16>(), any::<i16>(), any::<i16>(), rig()).prop_map(
        |(id, caption, calibration_offset_deg, min_deg, max_deg, home_deg, rig)| Servo {
            id,
            caption,
            calibration_offset_deg,
            min_deg,
            max_deg,
            home_deg,
            rig,
        },
    )
}

fn command() -> impl Strategy<Value = Command> {
    let run = prop_oneof![
        any::<i32>().prop_map(|action_id| Run::Action { action_id }),
        any::<i32>().prop_map(|delay_ms| Run::Delay { delay_ms }),
        any::<i32>().prop_map(|macro_id| Run::Macro { macro_id }),
    ];
    (run, any::<u8>(), any::<i16>(), any::<Option<i32>>()).prop_map(
        |(run, ratio_percent, loop_count, stored_total_ms)| Command { run, ratio_percent, loop_count, stored_total_ms },
    )
}

fn servo_section() -> impl Strategy<Value = ServoProject> {
    let step = (any::<u8>(), any::<i16>(), any::<i16>())
        .prop_map(|(servo_id, degree, interval_10ms)| Step::new(servo_id, degree, interval_10ms));
    let action = (any::<i32>(), text(), prop::collection::vec(step, 0..4)).prop_map(|(id, caption, steps)| Action {
        id,
        caption,
        steps,
    });
    let item = (any::<i32>(), text(), prop::collection::vec(command(), 0..4))
        .prop_map(|(id, caption, commands)| Macro { id, caption, commands });
    let button =
        (any::<u32>(), text(), any::<Option<i32>>(), any::<Option<i32>>(), any::<Option<i32>>(), any::<bool>())
            .prop_map(|(id, caption, press_macro, long_press_macro, release_macro, uninterruptible)| Button {
                id,
                caption,
                press_macro,
                long_press_macro,
                release_macro,
                uninterruptible,
            });
    let table = (any::<i32>(), text(), prop::collection::vec(button, 0..3))
        .prop_map(|(id, caption, buttons)| JoystickTable { id, caption, buttons });
    (
        any::<i32>(),
        prop::collection::vec(servo(), 0..4),
        prop::collection::vec(action, 0..3),
        prop::collection::vec(item, 0..3),
        prop::collection::vec(table, 0..2),
        any::<Option<i32>>(),
    )
        .prop_map(|(project_id, servos, actions, macros, joystick_tables, active_table)| ServoProject {
            project_id,
            servos,
            actions,
            macros,
            joystick_tables,
            active_table,
            meshes: Vec::new(),
        })
}

fn plen2_section() -> impl Strategy<Value = Plen2Project> {
    let joint = prop::sample::select(Joint::ALL.to_vec());
    let setting = (joint, any::<i16>(), any::<i16>(), any::<i16>()).prop_map(
        |(joint, min_tenths_deg, max_tenths_deg, home_tenths_deg)| JointSetting {
            joint,
            min_tenths_deg,
            max_tenths_deg,
            home_tenths_deg,
        },
    );
    let frame =
        (any::<u16>(), any::<[i16; 18]>()).prop_map(|(transition_ms, values)| Frame::new(transition_ms, Pose(values)));
    let range = (any::<u8>(), any::<u8>(), any::<u8>()).prop_map(|(begin_frame, end_frame, count)| LoopRange {
        begin_frame,
        end_frame,
        count,
    });
    let motion =
        (any::<u8>(), text(), prop::collection::vec(frame, 0..3), proptest::option::of(range), any::<Option<u8>>())
            .prop_map(|(slot, name, frames, loop_range, jump_slot)| Motion {
                slot,
                name,
                frames,
                loop_range,
                jump_slot,
            });
    let entry = (any::<u8>(), any::<u8>()).prop_map(|(slot, plays)| PlayEntry { slot, plays });
    let list = (text(), prop::collection::vec(entry, 0..3)).prop_map(|(name, entries)| PlayList { name, entries });
    (prop::collection::vec(setting, 0..3), prop::collection::vec(motion, 0..3), prop::collection::vec(list, 0..2))
        .prop_map(|(joints, motions, play_lists)| Plen2Project { joints, motions, play_lists })
}

fn rflex_section() -> impl Strategy<Value = RflexProject> {
    let finite = || -1e9f64..1e9f64;
    let robot = prop_oneof![
        Just(Robot::B21r),
        Just(Robot::AtrvJr),
        Just(Robot::Magellan),
        (finite(), finite(), finite()).prop_map(|(distance_units_per_m, angle_units_per_rad, power_offset_volts)| {
            Robot::Custom { distance_units_per_m, angle_units_per_rad, power_offset_volts }
        }),
    ];
    let drive = (finite(), finite(), finite(), any::<bool>()).prop_map(
        |(max_speed_m_per_s, max_turn_rad_per_s, accel_m_per_s2, sonar_on_connect)| DriveSettings {
            max_speed_m_per_s,
            max_turn_rad_per_s,
            accel_m_per_s2,
            sonar_on_connect,
        },
    );
    (robot, drive).prop_map(|(robot, drive)| RflexProject { robot, drive })
}

/// Gamepad bindings of every kind, for any family.
fn mapping() -> impl Strategy<Value = Mapping> {
    let finite = || -1e9f64..1e9f64;
    let target = prop_oneof![
        any::<u8>().prop_map(AxisTarget::Servo),
        prop::sample::select(Joint::ALL.to_vec()).prop_map(AxisTarget::Joint),
    ];
    let mode = prop_oneof![Just(AxisMode::Absolute), finite().prop_map(|deg_per_s| AxisMode::Rate { deg_per_s })];
    let axis = (any::<u16>(), target, finite(), finite(), finite(), any::<bool>(), mode).prop_map(
        |(axis, target, min_deg, max_deg, dead_zone, invert, mode)| AxisBinding {
            axis,
            target,
            min_deg,
            max_deg,
            dead_zone,
            invert,
            mode,
        },
    );
    let fire = prop_oneof![
        any::<i32>().prop_map(Fire::Action),
        any::<i32>().prop_map(Fire::Macro),
        any::<u8>().prop_map(Fire::Motion),
        (0usize..100).prop_map(Fire::PlayList),
        Just(Fire::Stop),
        Just(Fire::Brake),
    ];
    let button = (any::<u16>(), fire).prop_map(|(button, fire)| ButtonBinding { button, fire });
    (prop::collection::vec(axis, 0..4), prop::collection::vec(button, 0..4))
        .prop_map(|(axes, buttons)| Mapping { axes, buttons })
}

fn project_strategy() -> impl Strategy<Value = Project> {
    let family = prop::sample::select(Family::all().to_vec());
    let gamepad =
        (mapping(), mapping(), mapping()).prop_map(|(servo, plen2, rflex)| GamepadMappings { servo, plen2, rflex });
    (family, servo_section(), plen2_section(), rflex_section(), gamepad).prop_map(
        |(family, servo, plen2, rflex, gamepad)| Project { family, servo, plen2, rflex, gamepad, ..Project::default() },
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn any_v2_project_round_trips_through_its_file(document in project_strategy()) {
        let text = project::to_json(&document);
        prop_assert!(text.contains("\"version\": 2"));
        prop_assert_eq!(project::from_json(&text).unwrap(), document);
    }
}
