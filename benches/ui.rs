//! Editor benchmarks (prints figures; run with `cargo bench --bench ui`):
//! 1. Median CPU time per frame of each panel on a large project (64 servos,
//!    500 actions × 64 steps, 200 macros × 50 commands, 8 tables × 64
//!    buttons) in a headless egui_kittest harness.
//! 2. The time from the last slider change of a drag to the emulated board
//!    holding that angle, over a link throttled to 115200 baud.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::cast_possible_truncation, missing_docs)]

use std::time::{Duration, Instant};

use egui_kittest::Harness;
use servo_studio::link::{LinkEvent, no_waker};
use servo_studio::project::{Action, Button, Command, JoystickTable, Macro, Project, Run, Servo, ServoProject, Step};
use servo_studio::protocol::servo::Message;
use servo_studio::sim::{SimConfig, SimEvent};
use servo_studio::ui::{Action as UiAction, BoardLink, StudioApp, Tab};

fn large_project() -> ServoProject {
    let servos: Vec<Servo> = (0..64u8).map(|id| Servo::new(id, format!("關節{id}"))).collect();
    let actions = (1..=500)
        .map(|id| Action {
            id,
            caption: format!("動作{id}"),
            steps: (0..64u8)
                .map(|servo_id| Step {
                    servo_id,
                    degree: ((id * 7 + i32::from(servo_id)) % 180 - 90) as i16,
                    interval_10ms: 50,
                })
                .collect(),
        })
        .collect();
    let macros = (1..=200)
        .map(|id| Macro {
            id,
            caption: format!("巨集{id}"),
            commands: (0..50)
                .map(|n| match n % 3 {
                    0 => Command::once(Run::Action { action_id: 1 + (id * 50 + n) % 500 }),
                    1 => Command::once(Run::Delay { delay_ms: 100 }),
                    // Only earlier macros: no cycles.
                    _ if id > 1 => Command::once(Run::Macro { macro_id: id - 1 }),
                    _ => Command::once(Run::Delay { delay_ms: 50 }),
                })
                .collect(),
        })
        .collect();
    let joystick_tables = (1..=8)
        .map(|id| JoystickTable {
            id,
            caption: format!("表{id}"),
            buttons: (0..64u32)
                .map(|button| Button {
                    id: 0x8000_0000 | button,
                    caption: format!("鍵{button}"),
                    press_macro: Some(1 + (button as i32 % 200)),
                    long_press_macro: None,
                    release_macro: None,
                    uninterruptible: false,
                })
                .collect(),
        })
        .collect();
    ServoProject { project_id: 1, servos, actions, macros, joystick_tables, active_table: Some(1) }
}

fn frame_times() {
    let project = large_project();
    println!(
        "large project: {} servos, {} actions × 64 steps, {} macros × 50 commands, {} tables × 64 buttons",
        project.servos.len(),
        project.actions.len(),
        project.macros.len(),
        project.joystick_tables.len()
    );
    for tab in [Tab::Servos, Tab::Actions, Tab::Macros, Tab::Joystick, Tab::Board, Tab::Log] {
        let data = std::env::temp_dir().join("servo-studio-bench");
        let mut app = StudioApp::new(project.clone(), None, no_waker()).with_data_dir(data);
        app.apply(UiAction::ConnectDemo);
        app.apply(UiAction::ShowTab(tab));
        let mut harness = Harness::builder()
            .with_size(egui::vec2(1400.0, 900.0))
            .with_context_setup(servo_studio::ui::fonts::install)
            .with_accessibility_check(false)
            .build_ui_state(|ui, app: &mut StudioApp| app.show(ui), app);
        for _ in 0..10 {
            harness.step();
        }
        let mut times: Vec<Duration> = (0..60)
            .map(|_| {
                let began = Instant::now();
                harness.step();
                began.elapsed()
            })
            .collect();
        times.sort_unstable();
        println!(
            "frame time {tab:?}: median {:.2} ms, p90 {:.2} ms, max {:.2} ms",
            times[30].as_secs_f64() * 1e3,
            times[54].as_secs_f64() * 1e3,
            times[59].as_secs_f64() * 1e3
        );
    }
}

fn slider_latency() {
    let project = ServoProject { servos: vec![Servo::new(1, "左肩")], ..ServoProject::default() };
    let mut app = StudioApp::new(project.clone(), None, no_waker());
    let config = SimConfig { baud: Some(115_200), ..SimConfig::default() };
    app.link = Some(BoardLink::demo_with(&Project::servo(project.clone()), config, no_waker()).unwrap());
    let mut latencies = Vec::new();
    for drag in 0..20 {
        // A drag: a new angle every frame (60 Hz), then the user lets go.
        let target = if drag % 2 == 0 { 90 } else { -90 };
        let mut last_change = Instant::now();
        for step in 0..=30 {
            if step > 0 {
                std::thread::sleep(Duration::from_millis(16));
            }
            let degree = (-target) + (2 * target * step / 30);
            app.apply(UiAction::SetPose { servo_id: 1, degree: degree as i16 });
            last_change = Instant::now();
        }
        // The board holds the angle once it has handled the move that carries it.
        let events = app.link.as_ref().unwrap().demo_board().unwrap().events().clone();
        let arrived = loop {
            match events.recv_timeout(Duration::from_secs(5)).unwrap() {
                LinkEvent::Driver(SimEvent::Handled(Message::ExecuteActionRequest { moves }))
                    if moves.iter().any(|m| m.servo_id == 1 && m.degree == target as i16) =>
                {
                    break Instant::now();
                }
                _ => {}
            }
        };
        latencies.push(arrived.saturating_duration_since(last_change));
    }
    latencies.sort_unstable();
    let packet_ms = 15.0 * 10.0 / 115_200.0 * 1e3;
    println!(
        "slider latency at 115200 baud (last change → board handled it), 20 drags: median {:.2} ms, max {:.2} ms; one packet {packet_ms:.2} ms + one 60 Hz frame 16.67 ms = {:.2} ms; the servo then takes its 20 ms live-move interval to get there",
        latencies[10].as_secs_f64() * 1e3,
        latencies[19].as_secs_f64() * 1e3,
        packet_ms + 16.67
    );
}

fn main() {
    frame_times();
    slider_latency();
}
