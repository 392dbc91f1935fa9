//! Shared test fixtures.
#![allow(dead_code, clippy::unwrap_used)]

use servo_studio::project::{Action, Button, Command, JoystickTable, Macro, Project, Run, Servo, Step};

/// A project that exercises the whole protocol: CJK captions, negative angles,
/// button ids with the high bit set, an action with 60 steps, ids up to i32::MAX.
pub fn rich_project() -> Project {
    let servos: Vec<Servo> = (0..60u8)
        .map(|id| Servo { calibration_offset_deg: i16::from(id) - 30, ..Servo::new(id, format!("關節{id}號")) })
        .collect();
    let big_step = |id: u8| Step { servo_id: id, degree: -180 + 6 * i16::from(id), interval_10ms: 10 + i16::from(id) };
    Project {
        project_id: i32::MAX,
        servos,
        actions: vec![
            Action { id: 1, caption: "六十步的大動作".into(), steps: (0..60).map(big_step).collect() },
            Action {
                id: 42,
                caption: "揮手".into(),
                steps: vec![
                    Step { servo_id: 3, degree: -90, interval_10ms: 50 },
                    Step { servo_id: 4, degree: 45, interval_10ms: 100 },
                ],
            },
            Action {
                id: i32::MAX,
                caption: "最後".into(),
                steps: vec![Step { servo_id: 59, degree: -1, interval_10ms: 0 }],
            },
        ],
        macros: vec![
            Macro {
                id: 100,
                caption: "巨集1".into(),
                commands: vec![
                    Command { run: Run::Action { action_id: 42 }, ratio_percent: 50, loop_count: 3 },
                    Command::once(Run::Delay { delay_ms: 250 }),
                    Command::once(Run::Action { action_id: i32::MAX }),
                ],
            },
            Macro {
                id: i32::MAX,
                caption: "打招呼".into(),
                commands: vec![Command { run: Run::Macro { macro_id: 100 }, ratio_percent: 100, loop_count: 2 }],
            },
        ],
        joystick_tables: vec![
            JoystickTable {
                id: 7,
                caption: "遙控器".into(),
                buttons: vec![
                    Button {
                        id: 0x8000_0001,
                        caption: "Ａ鍵".into(),
                        press_macro: Some(100),
                        long_press_macro: Some(i32::MAX),
                        release_macro: None,
                        uninterruptible: true,
                    },
                    Button {
                        id: u32::MAX,
                        caption: "停".into(),
                        press_macro: None,
                        long_press_macro: None,
                        release_macro: Some(100),
                        uninterruptible: false,
                    },
                ],
            },
            JoystickTable { id: i32::MAX, caption: "備用".into(), buttons: vec![] },
        ],
        active_table: Some(7),
        ..Project::default()
    }
}
