//! Editor benchmarks (prints figures; run with `cargo bench --bench ui`):
//! 1. Median CPU time per frame of every panel of every family, in a
//!    1600 × 1000 and an 1100 × 720 window, on a small and a large project in
//!    the same run taking turns frame by frame, laid out and tessellated as
//!    eframe does it (no GPU); then one `ratio <family>/<panel> @WxH: large ÷
//!    small` line per panel and window size, with the large project's median
//!    beside it (the ratio is the figure that travels between machines: a
//!    panel whose cost does not grow with the project stays smooth on a slow
//!    laptop too). The small project fills the window — every list has more
//!    rows than fit, so both draw full lists and the ratio shows what the
//!    project's size adds: 48 servos, 40 actions × 40 steps, 40 macros × 40
//!    commands, 40 tables × 40 buttons; 40 PLEN2 slots × 40 frames with 40 play
//!    lists × 40 entries; ten minutes of rFLEX telemetry (its bounded history
//!    full). Large: 64 servos, 500 actions × 64 steps, 200 macros × 50
//!    commands, 8 tables × 64 buttons; 90 PLEN2 slots × 20 frames with 10 play
//!    lists × 30 entries; an hour of rFLEX telemetry at the report rate. The
//!    packet log holds 100 entries (small) or its bound (large).
//! 2. Cold start to the first frame with each large project (a fresh process
//!    that reads the project file, installs the fonts and lays out one frame),
//!    and the resident memory once every panel has been drawn.
//! 3. The robot's preview alone in a 600 × 600 view, per family: the PLEN2
//!    and the demo biped posed with a ghost (as the motion and action editors
//!    draw them), the base's world view after ten minutes of driving (path and
//!    echo map full) — posing, drawing and tessellating, per frame.
//! 4. The time from the last slider change of a drag to the emulated board
//!    holding that angle, over a link throttled to 115200 baud.
//! 5. The show window at 1280 × 800 on a show of four devices (two servo
//!    boards, a PLEN2, a base) cued every few seconds, one minute long and
//!    one hour long, the two taking turns frame by frame, the scrub moved
//!    every frame (as a preview or a drag moves it): median frame time of
//!    each and `ratio show hour ÷ minute` (`UI_BENCH_SHOW=1` runs only this).

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::cast_possible_truncation, missing_docs)]

use std::io::BufRead;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use servo_studio::device::rflex::Telemetry;
use servo_studio::device::{Direction, LogEntry};
use servo_studio::link::{LinkEvent, no_waker};
use servo_studio::project::plen2::{Frame, Joint, Motion, PlayEntry, PlayList, Plen2Project, Pose};
use servo_studio::project::{
    Action, Button, Command, Edit, Family, JoystickTable, Macro, Project, Run, Servo, ServoProject, Step,
};
use servo_studio::protocol::rflex::{B21R, Report, SonarReading};
use servo_studio::protocol::servo::Message;
use servo_studio::sim::{SimConfig, SimEvent};
use servo_studio::ui::packet_log::MAX_ENTRIES;
use servo_studio::ui::{Action as UiAction, RflexBoardLink as _, ServoBoardLink as _, StudioApp, Tab, servo_demo_link};

/// Frames measured per panel (`UI_BENCH_FRAMES` for more, when profiling).
fn measured_frames() -> usize {
    std::env::var("UI_BENCH_FRAMES").ok().and_then(|n| n.parse().ok()).unwrap_or(200).max(10)
}

/// A servo project of `servos` servos, `actions` actions of `steps` steps,
/// `macros` macros of `commands` commands and `tables` tables of `buttons` buttons.
fn servo_project(
    servos: u8,
    (actions, steps): (i32, u8),
    (macros, commands): (i32, i32),
    (tables, buttons): (i32, u32),
) -> ServoProject {
    let servo_list: Vec<Servo> = (0..servos).map(|id| Servo::new(id, format!("關節{id}"))).collect();
    let action_list = (1..=actions)
        .map(|id| Action {
            id,
            caption: format!("動作{id}"),
            steps: (0..steps)
                .map(|servo_id| Step::new(servo_id % servos, ((id * 7 + i32::from(servo_id)) % 180 - 90) as i16, 50))
                .collect(),
        })
        .collect();
    let macro_list = (1..=macros)
        .map(|id| Macro {
            id,
            caption: format!("巨集{id}"),
            commands: (0..commands)
                .map(|n| match n % 3 {
                    0 => Command::once(Run::Action { action_id: 1 + (id * 50 + n) % actions }),
                    1 => Command::once(Run::Delay { delay_ms: 100 }),
                    // Only earlier macros: no cycles.
                    _ if id > 1 => Command::once(Run::Macro { macro_id: id - 1 }),
                    _ => Command::once(Run::Delay { delay_ms: 50 }),
                })
                .collect(),
        })
        .collect();
    let joystick_tables = (1..=tables)
        .map(|id| JoystickTable {
            id,
            caption: format!("表{id}"),
            buttons: (0..buttons)
                .map(|button| Button {
                    id: 0x8000_0000 | button,
                    caption: format!("鍵{button}"),
                    press_macro: Some(1 + (button as i32 % macros)),
                    long_press_macro: None,
                    release_macro: None,
                    uninterruptible: false,
                })
                .collect(),
        })
        .collect();
    ServoProject {
        meshes: Vec::new(),
        project_id: 1,
        servos: servo_list,
        actions: action_list,
        macros: macro_list,
        joystick_tables,
        active_table: Some(1),
    }
}

fn large_project() -> ServoProject {
    servo_project(64, (500, 64), (200, 50), (8, 64))
}

/// A servo project whose every list has more rows than a 1600 × 1000 window shows.
fn small_servo() -> Project {
    Project::servo(servo_project(48, (40, 40), (40, 40), (40, 40)))
}

fn motion(slot: u8, frames: usize) -> Motion {
    Motion {
        slot,
        name: format!("Motion {slot}"),
        frames: (0..frames)
            .map(|f| {
                let mut pose = Pose::default();
                for (j, joint) in Joint::ALL.into_iter().enumerate() {
                    pose.set(joint, ((f * 37 + j * 11 + usize::from(slot)) % 600) as i16 - 300);
                }
                Frame::new(100 + (f as u16 % 5) * 50, pose)
            })
            .collect(),
        loop_range: None,
        jump_slot: None,
    }
}

fn plen2(slots: u8, frames: usize, lists: usize, entries: usize) -> Project {
    let motions = (0..slots).map(|slot| motion(slot, frames)).collect();
    let play_lists = (0..lists)
        .map(|l| PlayList {
            name: format!("Show {l}"),
            entries: (0..entries).map(|e| PlayEntry { slot: ((l + e) % usize::from(slots)) as u8, plays: 1 }).collect(),
        })
        .collect();
    Project {
        family: Family::Plen2,
        plen2: Plen2Project { motions, play_lists, ..Default::default() },
        ..Project::default()
    }
}

/// `seconds` of a base driving circles, at the rates the driver asks for:
/// odometry per axis every 100 ms, status every 500 ms, a sonar bank every 50 ms.
fn telemetry(seconds: u32) -> Telemetry {
    let mut telemetry = Telemetry::default();
    let conversion = B21R;
    for tick in 0..seconds * 20 {
        let t = f64::from(tick) * 0.05;
        let timestamp = tick * 50;
        if tick.is_multiple_of(2) {
            let distance = (t * 0.3 * conversion.distance_units_per_m) as i32;
            let bearing = (t * 0.2 * conversion.angle_units_per_rad) as i32;
            for (axis, position) in [(0u8, distance), (1, bearing)] {
                let report = Report::Odometry {
                    unknown: 0,
                    timestamp,
                    axis,
                    position,
                    velocity: 1000,
                    acceleration: 0,
                    torque: 0,
                };
                telemetry.record(&conversion, t, report);
            }
        }
        if tick.is_multiple_of(10) {
            let voltage_raw = 2520 - tick / 100;
            telemetry.record(&conversion, t, Report::Status { timestamp, voltage_raw, brake: 0 });
            telemetry.record(&conversion, t, Report::Dio { timestamp, address: 0x40 + (tick / 10 % 4) as u8, data: 0 });
        }
        // The B21r's own banks in turn (six of four, eight of three: rflex.md §6).
        let layout = conversion.layout;
        let bank = (tick % u32::from(layout.bank_count())) as u8;
        let readings = layout
            .bank_ids(bank)
            .map(|id| SonarReading { sonar_id: id, range: 1000 + u16::from(id % 16) * 50 })
            .collect();
        telemetry.record(&conversion, t, Report::Sonar { unknown: 0, timestamp, readings });
    }
    telemetry
}

/// One scenario: a project, a size, and what the link is given to show.
struct Scenario {
    family: Family,
    size: &'static str,
    project: Project,
    telemetry_seconds: u32,
    log_entries: usize,
}

fn scenarios(family: Family) -> [Scenario; 2] {
    match family {
        Family::Servo => [
            Scenario { family, size: "small", project: small_servo(), telemetry_seconds: 0, log_entries: 100 },
            Scenario {
                family,
                size: "large",
                project: Project::servo(large_project()),
                telemetry_seconds: 0,
                log_entries: MAX_ENTRIES,
            },
        ],
        Family::Plen2 => [
            Scenario { family, size: "small", project: plen2(40, 40, 40, 40), telemetry_seconds: 0, log_entries: 100 },
            Scenario {
                family,
                size: "large",
                project: plen2(90, 20, 10, 30),
                telemetry_seconds: 0,
                log_entries: MAX_ENTRIES,
            },
        ],
        // The base, and any other family: an empty project of its own.
        _ => {
            let project = Project { family, ..Project::default() };
            [
                // Ten minutes fill the telemetry's bounded history (its recent points
                // and its thinned past), as the small lists fill the window.
                Scenario { family, size: "small", project: project.clone(), telemetry_seconds: 600, log_entries: 100 },
                Scenario { family, size: "large", project, telemetry_seconds: 3600, log_entries: MAX_ENTRIES },
            ]
        }
    }
}

fn log_entry(index: usize) -> LogEntry {
    LogEntry {
        seconds: index as f64 * 0.05,
        direction: if index.is_multiple_of(2) { Direction::Sent } else { Direction::Received },
        name: "MOT_SYSTEM_REPORT".into(),
        fields: format!("axis {} position {index}", index % 2),
        hex: "1b 02 02 21 00 00 00 00 00 1b 03".into(),
    }
}

/// An app showing `scenario` on the emulated board of its family, on `tab`.
fn app(scenario: &Scenario, tab: Tab) -> StudioApp {
    let data = std::env::temp_dir().join("servo-studio-bench");
    let mut app = StudioApp::new(scenario.project.clone(), None, no_waker()).with_data_dir(data);
    app.apply(UiAction::ConnectDemo);
    let link = app.link.as_mut().expect("the demo board connects");
    for index in 0..scenario.log_entries.saturating_sub(link.log.len()) {
        link.log.record(log_entry(index));
    }
    if let Some(base) = link.rflex_mut() {
        base.telemetry = telemetry(scenario.telemetry_seconds);
    }
    app.apply(UiAction::ShowTab(tab));
    app
}

/// The editor in an egui context of its own, run as eframe runs it: lay out
/// the frame, then tessellate it (no GPU; AccessKit off, as it is until a
/// screen reader asks).
struct Window {
    ctx: egui::Context,
    app: StudioApp,
    size: egui::Vec2,
}

/// The window sizes measured: a large desktop window, and the editor's default.
const SIZES: [(f32, f32); 2] = [(1600.0, 1000.0), (1100.0, 720.0)];

impl Window {
    fn new(app: StudioApp, (width, height): (f32, f32)) -> Self {
        let ctx = egui::Context::default();
        servo_studio::ui::fonts::install(&ctx);
        Self { ctx, app, size: egui::vec2(width, height) }
    }

    fn step(&mut self) {
        let input = egui::RawInput {
            screen_rect: Some(egui::Rect::from_min_size(egui::Pos2::ZERO, self.size)),
            ..Default::default()
        };
        let output = self.ctx.run_ui(input, |ui| self.app.show(ui));
        let primitives = self.ctx.tessellate(output.shapes, output.pixels_per_point);
        std::hint::black_box(primitives);
    }

    fn run_steps(&mut self, steps: usize) {
        for _ in 0..steps {
            self.step();
        }
    }
}

/// Median frame time of one panel on the small and the large project, ms,
/// in a window of `size`. The two windows take turns frame by frame, so that
/// a change of clock speed or a busy neighbour weighs on both alike.
fn frame_times_of(small: &Scenario, large: &Scenario, tab: Tab, size: (f32, f32)) -> (f64, f64) {
    let mut windows = [Window::new(app(small, tab), size), Window::new(app(large, tab), size)];
    for window in &mut windows {
        window.run_steps(10);
    }
    let frames = measured_frames();
    let mut times = [Vec::with_capacity(frames), Vec::with_capacity(frames)];
    for _ in 0..frames {
        for (window, times) in windows.iter_mut().zip(&mut times) {
            let began = Instant::now();
            window.step();
            times.push(began.elapsed());
        }
    }
    let mut medians = [0.0; 2];
    for ((scenario, times), median) in [small, large].into_iter().zip(&mut times).zip(&mut medians) {
        times.sort_unstable();
        *median = times[frames / 2].as_secs_f64() * 1e3;
        println!(
            "frame time {}/{tab} @{}x{} {}: median {:.3} ms, p90 {:.3} ms, max {:.3} ms",
            scenario.family.tag(),
            size.0,
            size.1,
            scenario.size,
            *median,
            times[frames * 9 / 10].as_secs_f64() * 1e3,
            times[frames - 1].as_secs_f64() * 1e3
        );
    }
    (medians[0], medians[1])
}

fn frame_times() {
    let servo = large_project();
    println!(
        "large servo project: {} servos, {} actions × 64 steps, {} macros × 50 commands, {} tables × 64 buttons",
        servo.servos.len(),
        servo.actions.len(),
        servo.macros.len(),
        servo.joystick_tables.len()
    );
    // `UI_BENCH_ONLY=servo/Servos` measures one panel (for profiling).
    let only = std::env::var("UI_BENCH_ONLY").ok();
    let mut ratios = Vec::new();
    for size in SIZES {
        for family in [Family::Servo, Family::Plen2, Family::Rflex] {
            let [small, large] = scenarios(family);
            for tab in family_tabs(family) {
                if only.as_ref().is_some_and(|only| *only != format!("{}/{tab}", family.tag())) {
                    continue;
                }
                let (small_ms, large_ms) = frame_times_of(&small, &large, tab, size);
                ratios.push((size, family, tab, large_ms / small_ms, large_ms));
            }
        }
    }
    for (size, family, tab, ratio, large_ms) in ratios {
        println!(
            "ratio {}/{tab} @{}x{}: large ÷ small = {ratio:.2} (large: median {large_ms:.2} ms a frame)",
            family.tag(),
            size.0,
            size.1
        );
    }
}

/// The edit a drag makes each frame, given the project and the dragged value.
type EditEveryFrame = fn(&ServoProject, i16) -> UiAction;

/// Median frame time while the user drags a value on the large project: every
/// frame is a new document revision, so what is derived per revision is
/// derived every frame.
fn editing_frame_times() {
    let large = &scenarios(Family::Servo)[1];
    let edits: [(Tab, EditEveryFrame); 3] = [
        (Tab::Actions, |project, degree| {
            let mut action = project.actions[0].clone();
            action.steps[0].degree = degree;
            UiAction::Edit { edit: Edit::SetAction { index: 0, action }, coalesce: Some("bench".into()) }
        }),
        (Tab::Macros, |project, delay| {
            let mut item = project.macros[0].clone();
            item.commands[1].run = Run::Delay { delay_ms: 100 + i32::from(delay) };
            UiAction::Edit { edit: Edit::SetMacro { index: 0, item }, coalesce: Some("bench".into()) }
        }),
        (Tab::Board, |project, degree| {
            let mut servo = project.servos[0].clone();
            servo.home_deg = degree;
            UiAction::Edit { edit: Edit::SetServo { index: 0, servo }, coalesce: Some("bench".into()) }
        }),
    ];
    for (tab, edit) in edits {
        let mut window = Window::new(app(large, tab), SIZES[0]);
        window.run_steps(10);
        let frames = measured_frames() / 4;
        let mut times: Vec<Duration> = (0..frames)
            .map(|frame| {
                let degree = i16::try_from(frame % 60).unwrap_or(0) - 30;
                let began = Instant::now();
                let action = edit(&window.app.document.project.servo, degree);
                window.app.apply(action);
                window.step();
                began.elapsed()
            })
            .collect();
        times.sort_unstable();
        println!(
            "frame time while editing servo/{tab} large (an edit every frame): median {:.2} ms, p90 {:.2} ms, max {:.2} ms",
            times[frames / 2].as_secs_f64() * 1e3,
            times[frames * 9 / 10].as_secs_f64() * 1e3,
            times[frames - 1].as_secs_f64() * 1e3
        );
    }
}

/// Resident memory of this process, MB (Linux; `None` elsewhere).
fn resident_mb() -> Option<(f64, f64)> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let field = |name: &str| {
        status
            .lines()
            .find(|line| line.starts_with(name))?
            .split_whitespace()
            .nth(1)?
            .parse::<f64>()
            .ok()
            .map(|kb| kb / 1024.0)
    };
    Some((field("VmRSS:")?, field("VmHWM:")?))
}

/// In a fresh process: read the project, lay out the first frame, say so; then
/// draw every panel and report the resident memory.
fn cold_start_child(family: Family, path: &Path) {
    let project = servo_studio::project::load(path).unwrap();
    let scenario = Scenario { family, size: "large", project, telemetry_seconds: 0, log_entries: 0 };
    let data = std::env::temp_dir().join("servo-studio-bench");
    let mut window =
        Window::new(StudioApp::new(scenario.project.clone(), None, no_waker()).with_data_dir(data), SIZES[0]);
    window.step();
    println!("first-frame");
    let large = &scenarios(family)[1];
    for tab in family_tabs(family) {
        Window::new(app(large, tab), SIZES[0]).run_steps(3);
    }
    let (rss, peak) = resident_mb().unwrap_or((f64::NAN, f64::NAN));
    println!("resident {rss:.1} {peak:.1}");
}

fn cold_starts() {
    for family in [Family::Servo, Family::Plen2, Family::Rflex] {
        let large = &scenarios(family)[1];
        let path: PathBuf = std::env::temp_dir().join(format!("servo-studio-bench-{}.json", family.tag()));
        servo_studio::project::save(&path, &large.project).unwrap();
        let mut child = std::process::Command::new(std::env::current_exe().unwrap())
            .args(["--cold-start", family.tag()])
            .arg(&path)
            .stdout(std::process::Stdio::piped())
            .spawn()
            .unwrap();
        let began = Instant::now();
        let mut lines = std::io::BufReader::new(child.stdout.take().unwrap()).lines();
        let mut first_frame = None;
        let mut resident = None;
        for line in lines.by_ref() {
            let line = line.unwrap();
            if line == "first-frame" {
                first_frame = Some(began.elapsed());
            } else if let Some(figures) = line.strip_prefix("resident ") {
                resident = Some(figures.to_string());
            }
        }
        child.wait().unwrap();
        let first_frame = first_frame.expect("the child drew a frame");
        let (rss, peak) = resident.as_deref().and_then(|f| f.split_once(' ')).unwrap_or(("?", "?"));
        println!(
            "cold start {} large project ({} KB file): first frame {:.0} ms; resident memory with every panel drawn {rss} MB (peak {peak} MB)",
            family.tag(),
            std::fs::metadata(&path).map_or(0, |m| m.len() / 1024),
            first_frame.as_secs_f64() * 1e3
        );
    }
}

fn slider_latency() {
    let project = ServoProject { servos: vec![Servo::new(1, "左肩")], ..ServoProject::default() };
    let mut app = StudioApp::new(project.clone(), None, no_waker());
    let config = SimConfig { baud: Some(115_200), ..SimConfig::default() };
    app.link = Some(servo_demo_link(&Project::servo(project.clone()), config, no_waker()).unwrap());
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
            app.apply(UiAction::family(servo_studio::ui::ServoAction::SetPose { servo_id: 1, degree: degree as i16 }));
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

/// Median ms of `frames` frames of a 600 × 600 window drawing only `draw`.
fn view_median(mut draw: impl FnMut(&mut egui::Ui, egui::Rect)) -> f64 {
    let ctx = egui::Context::default();
    servo_studio::ui::fonts::install(&ctx);
    let size = egui::vec2(600.0, 600.0);
    let mut step = || {
        let input = egui::RawInput {
            screen_rect: Some(egui::Rect::from_min_size(egui::Pos2::ZERO, size)),
            ..Default::default()
        };
        let output = ctx.run_ui(input, |ui| draw(ui, egui::Rect::from_min_size(egui::Pos2::ZERO, size)));
        std::hint::black_box(ctx.tessellate(output.shapes, output.pixels_per_point));
    };
    for _ in 0..10 {
        step();
    }
    let frames = measured_frames();
    let mut times: Vec<Duration> = (0..frames)
        .map(|_| {
            let began = Instant::now();
            step();
            began.elapsed()
        })
        .collect();
    times.sort_unstable();
    times[frames / 2].as_secs_f64() * 1e3
}

/// What drawing the robot's preview costs a frame, per family, at 600 × 600.
fn view_costs() {
    use servo_studio::figure;
    use servo_studio::ui::view3d::{Scene, View};
    let empty = view_median(|ui, rect| {
        ui.allocate_rect(rect, egui::Sense::hover());
    });
    println!("view (an empty 600x600 frame, for reference): median {empty:.3} ms");

    // The PLEN2 mid-"bow", with the next frame as a ghost.
    let chain = figure::plen2::chain();
    let mut pose = [0i16; 24];
    let mut ghost = [0i16; 24];
    for joint in [Joint::LeftThighPitch, Joint::RightThighPitch] {
        pose[usize::from(joint.device_id())] = -300;
        ghost[usize::from(joint.device_id())] = -600;
    }
    let mut view = View::default();
    let plen2 = view_median(|ui, rect| {
        let mut solids = chain.dress(&chain.pose(&figure::plen2::angles(&chain, &ghost)), true);
        solids.extend(chain.dress(&chain.pose(&figure::plen2::angles(&chain, &pose)), false));
        view.show(ui, rect, &Scene { solids, ground_z: 0.0, ..Scene::default() }, "PLEN2");
    });

    // The demo biped mid-"Wave up", with where it goes as a ghost.
    let project = servo_studio::ui::sample_project().servo;
    let (chain, links) = figure::rig::chain(&project);
    let degrees = |scale: f64| -> std::collections::BTreeMap<u8, f64> {
        [(4u8, -80.0), (5, 60.0), (6, -45.0)].into_iter().map(|(id, d)| (id, d * scale)).collect()
    };
    let (now, next) = (degrees(0.5), degrees(1.0));
    let mut view = View::default();
    let servo = view_median(|ui, rect| {
        let links_len = chain.links.len();
        let mut solids = chain.dress(&chain.pose(&figure::rig::angles(&project, &links, &next, links_len)), true);
        solids.extend(chain.dress(&chain.pose(&figure::rig::angles(&project, &links, &now, links_len)), false));
        view.show(ui, rect, &Scene { solids, ground_z: -400.0, ..Scene::default() }, "biped");
    });

    // The same biped dressed in meshes of 100k triangles in all (a body and a
    // rod per link, as a user's CAD parts would be): the card draws them, so the
    // frame's cost is the figure's solids, the rings and one paint callback.
    let meshes = biped_meshes(&chain, 100_000);
    let triangles: usize = meshes.iter().map(|m| m.mesh.triangles.len()).sum();
    let mut view = View::default();
    let meshed = view_median(|ui, rect| {
        let links_len = chain.links.len();
        let placed = chain.pose(&figure::rig::angles(&project, &links, &now, links_len));
        let solids = chain.dress(&placed, false);
        let meshes =
            meshes.iter().map(|m| servo_studio::ui::view3d::SceneMesh { place: placed[m.link], ..m.clone() }).collect();
        view.show(ui, rect, &Scene { solids, ground_z: -400.0, meshes, ..Scene::default() }, "biped");
    });
    println!(
        "view servo with meshes ({triangles} triangles on {} links) @600x600: median {meshed:.3} ms a frame (over the empty frame: {:.3} ms; the figure's draw, target ≤ 0.5 ms)",
        meshes.len(),
        meshed - empty
    );

    // The base after ten minutes of driving circles: path and echo map full.
    let telemetry = telemetry(600);
    let mut world = servo_studio::ui::WorldView::default();
    let rflex = view_median(|ui, rect| {
        world.show(ui, rect, &telemetry, "world");
    });
    println!("  (world view: {} echo cells, {} path points)", telemetry.echoes.len(), telemetry.path.iter().count());
    for (family, ms) in [("servo", servo), ("plen2", plen2), ("rflex", rflex)] {
        println!("view {family} @600x600: median {ms:.3} ms a frame (over the empty frame: {:.3} ms)", ms - empty);
    }
}

/// A mesh on every link of `chain` but the body, `total` triangles in all:
/// each a tube of as many rings as it takes.
fn biped_meshes(chain: &servo_studio::figure::Chain, total: usize) -> Vec<servo_studio::ui::view3d::SceneMesh> {
    use servo_studio::figure::mesh::Mesh;
    use servo_studio::figure::{Placed, Vec3};
    let links: Vec<usize> = (1..chain.links.len()).collect();
    let per = total.div_ceil(links.len());
    let segments = 64usize;
    let rings = per.div_ceil(segments * 2);
    let mut mesh = Mesh::default();
    for ring in 0..=rings {
        let z = -(ring as f32) / rings as f32 * 80.0;
        for segment in 0..segments {
            let angle = segment as f32 / segments as f32 * std::f32::consts::TAU;
            mesh.positions.push(Vec3::new(12.0 * angle.cos(), 12.0 * angle.sin(), z));
        }
    }
    for ring in 0..rings as u32 {
        for segment in 0..segments as u32 {
            let at = |r: u32, s: u32| r * segments as u32 + s % segments as u32;
            let (a, b, c, d) =
                (at(ring, segment), at(ring, segment + 1), at(ring + 1, segment + 1), at(ring + 1, segment));
            for triangle in [[a, d, c], [a, c, b]] {
                let [p, q, r] = triangle.map(|i| mesh.positions[i as usize]);
                mesh.normals.push((q - p).cross(r - p).normalize_or_zero());
                mesh.triangles.push(triangle);
            }
        }
    }
    let mesh = std::sync::Arc::new(mesh);
    links
        .into_iter()
        .map(|link| servo_studio::ui::view3d::SceneMesh {
            link,
            mesh: std::sync::Arc::clone(&mesh),
            place: Placed::ORIGIN,
            scale: 1.0,
            color: [200, 200, 200],
        })
        .collect()
}

/// A show of `minutes`: two servo boards, a PLEN2 and a base, each cued every few seconds.
fn show_of(minutes: u64) -> servo_studio::show::Show {
    use servo_studio::show::{Cue, Show, Start};
    let steps = |degree: i16| vec![Step::new(1, degree, 40), Step::new(2, -degree, 60)];
    let actions: Vec<Action> = (1..=4)
        .map(|id| Action { id, caption: format!("動作{id}"), steps: steps(20 * i16::try_from(id).unwrap()) })
        .collect();
    let commands = actions.iter().map(|a| Command::once(Run::Action { action_id: a.id })).collect();
    let macros = vec![Macro { id: 1, caption: "Wave 揮手".into(), commands }];
    let servos = vec![Servo::new(1, "jaw"), Servo::new(2, "neck")];
    let servo = Project::servo(ServoProject { servos, actions, macros, ..ServoProject::default() });
    let plen = plen2(2, 12, 0, 0);
    let mut show = Show::of_one("skull", servo.clone());
    show.add_device("arms", servo);
    show.add_device("plen", plen);
    show.add_device("base", Project::empty(Family::Rflex));
    for at_ms in (0..minutes * 60_000).step_by(3000) {
        show.cues.push(Cue { device: "skull".into(), at_ms, start: Start::Macro(1) });
        show.cues.push(Cue { device: "arms".into(), at_ms: at_ms + 1500, start: Start::Macro(1) });
    }
    for (k, at_ms) in (0..minutes * 60_000).step_by(4000).enumerate() {
        show.cues.push(Cue { device: "plen".into(), at_ms, start: Start::Slot(u8::try_from(k % 2).unwrap()) });
        let turn = if k % 2 == 0 { 0.0 } else { 30.0 };
        show.cues.push(Cue {
            device: "base".into(),
            at_ms,
            start: Start::Drive { speed_m_s: 0.2, turn_deg_s: turn, for_ms: 2500 },
        });
    }
    show
}

/// The show window's frame time on a minute's show and an hour's, the scrub moved every frame.
fn show_frame_times() {
    let dir = tempfile::tempdir().unwrap();
    let mut windows: Vec<(String, u64, Window)> = [1, 60]
        .into_iter()
        .map(|minutes| {
            let show = show_of(minutes);
            let path = dir.path().join(format!("{minutes}.json"));
            std::fs::write(&path, show.to_json()).unwrap();
            let mut app = StudioApp::new(Project::default(), None, no_waker());
            app.apply(UiAction::Show(servo_studio::ui::show::ShowAction::Open(path)));
            let label = format!("{} min, {} cues", minutes, show.cues.len());
            (label, minutes * 60_000, Window::new(app, (1280.0, 800.0)))
        })
        .collect();
    for (_, _, window) in &mut windows {
        window.run_steps(10);
    }
    let frames = measured_frames();
    let mut times = vec![Vec::with_capacity(frames); windows.len()];
    for frame in 0..frames {
        for ((_, length_ms, window), times) in windows.iter_mut().zip(&mut times) {
            // The scrub a step on each frame, across the whole show (a preview, a drag).
            window.app.desks.show.stage.scrub_ms = (frame as u64 * 7919) % *length_ms;
            let began = Instant::now();
            window.step();
            times.push(began.elapsed());
        }
    }
    let mut medians = Vec::new();
    for ((label, _, _), times) in windows.iter().zip(&mut times) {
        times.sort_unstable();
        let median = times[frames / 2].as_secs_f64() * 1e3;
        println!(
            "frame time show window @1280x800, {label}: median {median:.3} ms, p90 {:.3} ms, max {:.3} ms",
            times[frames * 9 / 10].as_secs_f64() * 1e3,
            times[frames - 1].as_secs_f64() * 1e3
        );
        medians.push(median);
    }
    println!("ratio show hour ÷ minute = {:.2} (hour: median {:.2} ms a frame)", medians[1] / medians[0], medians[1]);
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if std::env::var_os("UI_BENCH_SHOW").is_some() {
        show_frame_times();
        return;
    }
    if let Some(at) = args.iter().position(|arg| arg == "--cold-start") {
        let family = Family::all().iter().copied().find(|f| f.tag() == args[at + 1]).unwrap();
        cold_start_child(family, Path::new(&args[at + 2]));
        return;
    }
    if std::env::var_os("UI_BENCH_EDITING").is_some() {
        editing_frame_times();
        return;
    }
    if std::env::var_os("UI_BENCH_VIEWS").is_some() {
        view_costs();
        return;
    }
    frame_times();
    if std::env::var_os("UI_BENCH_ONLY").is_none() {
        show_frame_times();
        view_costs();
        editing_frame_times();
        cold_starts();
        slider_latency();
    }
}

/// The tabs the editor shows for `family`.
fn family_tabs(family: Family) -> Vec<Tab> {
    StudioApp::new(Project::default(), None, no_waker()).tabs(family)
}
