//! Shared test fixtures.
#![allow(dead_code, clippy::unwrap_used, clippy::expect_used)]

use std::io::{BufRead, BufReader, Read, Write};
use std::process::{Child, Stdio};
use std::time::Duration;

pub mod proxy;
pub mod pulse;
pub mod ui;

use servo_studio::project::{Action, Button, Command, JoystickTable, Macro, Run, Servo, ServoProject, Step};

/// A `servo-studio sim` process, killed when dropped.
pub struct Sim {
    /// The process.
    pub child: Child,
    /// The port it printed on its first line.
    pub port: String,
}

impl Drop for Sim {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// Whether the environment variable `name` is set to something other than empty, `0` or `false`.
fn set(name: &str) -> bool {
    std::env::var(name).is_ok_and(|value| !value.is_empty() && value != "0" && value != "false")
}

/// Whether a test that needs `../shared` must fail without it: in CI (`CI`
/// set, as CI sets it) or when `SERVO_STUDIO_REQUIRE_SHARED=1`.
pub fn shared_required() -> bool {
    set("CI") || set("SERVO_STUDIO_REQUIRE_SHARED")
}

/// Whether a test that needs a system service or program (a PulseAudio
/// server, espeak-ng) must fail without it: in CI or when
/// `SERVO_STUDIO_REQUIRE_SERVICES=1`.
pub fn services_required() -> bool {
    set("CI") || set("SERVO_STUDIO_REQUIRE_SERVICES")
}

/// A test cannot have `what` here: it skips with a one-line notice saying
/// what to install, or fails saying so where services are required.
pub fn without_service(what: &str, install: &str) {
    assert!(!services_required(), "{what} (CI / SERVO_STUDIO_REQUIRE_SERVICES require it): {install}");
    eprintln!("skipped: {what}; to run it: {install}");
}

/// `../shared/<relative>` (the workplace's shared folder beside the clone):
/// `None` with a notice on stderr when it is absent, or a failure naming
/// what is missing where it is required ([`shared_required`]).
pub fn shared(relative: &str) -> Option<std::path::PathBuf> {
    shared_in(&std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared"), relative, shared_required())
}

/// [`shared`] under `root`, failing when `required` and it is absent.
pub fn shared_in(root: &std::path::Path, relative: &str, required: bool) -> Option<std::path::PathBuf> {
    let path = root.join(relative);
    if path.exists() {
        return Some(path);
    }
    assert!(
        !required,
        "{} is missing: this test needs the shared folder beside the clone (CI / SERVO_STUDIO_REQUIRE_SHARED require it)",
        path.display()
    );
    eprintln!("skipped: {} is absent (a clone without ../shared)", path.display());
    None
}

/// The 90 official PLEN2 motion files (`../shared/plen2/motions`), in name order; see [`shared`].
pub fn official_motion_files() -> Option<Vec<std::path::PathBuf>> {
    let folder = shared("plen2/motions")?;
    let mut files: Vec<std::path::PathBuf> =
        std::fs::read_dir(&folder).unwrap().map(|entry| entry.unwrap().path()).collect();
    files.sort();
    Some(files)
}

/// The sample robot shipped in `assets/` (a rigged biped, its twins named), its servo section.
pub fn sample_biped() -> ServoProject {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/sample-biped.json");
    servo_studio::project::load(&path).expect("the sample loads").servo
}

/// Starts `servo-studio sim ARGS` and waits for the port it prints.
pub fn sim(args: &[&str]) -> Sim {
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_servo-studio"))
        .arg("sim")
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let stdout = child.stdout.take().unwrap();
    let (line_tx, line_rx) = crossbeam_channel::bounded(1);
    std::thread::spawn(move || {
        let mut line = String::new();
        let _ = BufReader::new(stdout).read_line(&mut line);
        let _ = line_tx.send(line);
    });
    let port = line_rx.recv_timeout(Duration::from_secs(30)).expect("the sim printed its port").trim().to_string();
    assert!(!port.is_empty(), "sim printed no port");
    Sim { child, port }
}

/// A project that exercises the whole protocol: CJK captions, negative angles,
/// button ids with the high bit set, an action with 60 steps, ids up to i32::MAX.
pub fn rich_project() -> ServoProject {
    let servos: Vec<Servo> = (0..60u8)
        .map(|id| Servo { calibration_offset_deg: i16::from(id) - 30, ..Servo::new(id, format!("關節{id}號")) })
        .collect();
    let big_step = |id: u8| Step::new(id, -180 + 6 * i16::from(id), 10 + i16::from(id));
    ServoProject {
        project_id: i32::MAX,
        servos,
        meshes: Vec::new(),
        actions: vec![
            Action { id: 1, caption: "六十步的大動作".into(), steps: (0..60).map(big_step).collect() },
            Action { id: 42, caption: "揮手".into(), steps: vec![Step::new(3, -90, 50), Step::new(4, 45, 100)] },
            Action { id: i32::MAX, caption: "最後".into(), steps: vec![Step::new(59, -1, 0)] },
        ],
        macros: vec![
            Macro {
                id: 100,
                caption: "巨集1".into(),
                commands: vec![
                    Command {
                        run: Run::Action { action_id: 42 },
                        ratio_percent: 50,
                        loop_count: 3,
                        stored_total_ms: None,
                    },
                    Command::once(Run::Delay { delay_ms: 250 }),
                    Command::once(Run::Action { action_id: i32::MAX }),
                ],
            },
            Macro {
                id: i32::MAX,
                caption: "打招呼".into(),
                commands: vec![Command {
                    run: Run::Macro { macro_id: 100 },
                    ratio_percent: 100,
                    loop_count: 2,
                    stored_total_ms: None,
                }],
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
    }
}

/// `project` as an export of a board it was written to returns it: each macro
/// command carries the total the board stored, which for a project Servo
/// Studio wrote is the derived one.
pub fn exported(mut project: ServoProject) -> ServoProject {
    let totals: Vec<Vec<Option<i32>>> = {
        let timing = servo_studio::project::Timing::new(&project);
        project
            .macros
            .iter()
            .map(|item| {
                item.commands
                    .iter()
                    .map(|command| i32::try_from(timing.command_total_ms(command).unwrap()).ok())
                    .collect()
            })
            .collect()
    };
    for (item, totals) in project.macros.iter_mut().zip(totals) {
        for (command, total) in item.commands.iter_mut().zip(totals) {
            command.stored_total_ms = total;
        }
    }
    project
}

/// What a board can hold that Servo Studio would never author: a servo twice
/// in one action, a step for a servo without parameters, macros calling a
/// macro that is not there, stored totals unlike the derived ones, a macro
/// whose derived total overflows the board's 32-bit counter, a button bound
/// to a missing macro.
pub fn unauthorable_image() -> servo_studio::device::servo::ServoImage {
    use servo_studio::device::servo::{ServoImage, ServoMove};
    use servo_studio::protocol::servo::{
        ActionRecord, ButtonRecord, CommandType, JoystickTableRecord, MacroCommandRecord, MacroRecord, ServoParameter,
    };
    let command = |command_type, command_id, ratio_percent, loop_count, total_interval_ms| MacroCommandRecord {
        command_id,
        command_type,
        ratio_percent,
        loop_count,
        total_interval_ms,
    };
    ServoImage {
        project_id: 31,
        servos: vec![
            ServoParameter { servo_id: 1, adjusted_degree: -4, caption: "左臂".into() },
            ServoParameter { servo_id: 2, adjusted_degree: 3, caption: "右臂".into() },
        ],
        actions: vec![
            ActionRecord {
                action_id: 1,
                caption: "重複".into(),
                steps: vec![
                    ServoMove { servo_id: 1, degree: 10, interval_10ms: 20 },
                    ServoMove { servo_id: 1, degree: 20, interval_10ms: 40 },
                    ServoMove { servo_id: 9, degree: 5, interval_10ms: 10 },
                ],
            },
            ActionRecord {
                action_id: 2,
                caption: "很長".into(),
                steps: vec![ServoMove { servo_id: 2, degree: 30, interval_10ms: 30_000 }],
            },
        ],
        macros: vec![
            MacroRecord {
                macro_id: 10,
                caption: "懸空".into(),
                commands: vec![
                    command(CommandType::RunMacro, 999, 100, 1, 1234),
                    command(CommandType::RunAction, 1, 100, 1, 777),
                ],
            },
            MacroRecord {
                macro_id: 11,
                caption: "溢位".into(),
                commands: vec![command(CommandType::RunAction, 2, 1, i16::MAX, i32::MAX)],
            },
        ],
        tables: vec![JoystickTableRecord {
            table_id: 3,
            caption: "遙控".into(),
            buttons: vec![ButtonRecord {
                button_id: 0x8000_0010,
                caption: "A".into(),
                press_macro: 55,
                long_press_macro: 0,
                up_macro: 10,
                uninterruptible: false,
            }],
        }],
        active_table: 3,
    }
}

/// The encoded add requests a board image is written with, in order: equal
/// when two images hold the same records byte for byte.
pub fn record_bytes(image: &servo_studio::device::servo::ServoImage) -> Vec<Vec<u8>> {
    use servo_studio::protocol::servo::Message;
    let mut out = vec![Message::WriteProjectIdRequest { project_id: image.project_id }.encode().unwrap()];
    out.push(Message::AddServoParameterRequest { servos: image.servos.clone() }.encode().unwrap());
    out.extend(image.actions.iter().map(|a| Message::AddActionRequest(a.clone()).encode().unwrap()));
    out.extend(image.macros.iter().map(|m| Message::AddMacroRequest(m.clone()).encode().unwrap()));
    out.extend(image.tables.iter().map(|t| Message::AddJoystickTableRequest(t.clone()).encode().unwrap()));
    out.push(Message::SetActiveJoystickTableRequest { table_id: image.active_table }.encode().unwrap());
    out
}

/// `servo-studio ARGS` with no input and both outputs piped.
fn piped(args: &[&str]) -> std::process::Command {
    let mut command = std::process::Command::new(env!("CARGO_BIN_EXE_servo-studio"));
    command.args(args).stdin(Stdio::null()).stdout(Stdio::piped()).stderr(Stdio::piped());
    command
}

/// Runs `servo-studio ARGS` in `cwd` with a watchdog; (exit code, stdout, stderr, how long).
pub fn run_in(cwd: &std::path::Path, args: &[&str], within: Duration) -> (Option<i32>, String, String, Duration) {
    let began = std::time::Instant::now();
    let mut child = piped(args).current_dir(cwd).spawn().unwrap();
    let stdout = child.stdout.take().unwrap();
    let reader = std::thread::spawn(move || std::io::read_to_string(stdout).unwrap_or_default());
    let (code, stderr) = ended(child, within);
    (code, reader.join().unwrap(), stderr, began.elapsed())
}

/// Runs `servo-studio ARGS` with its stdout's reader gone before the first
/// line (`| head -0`); its exit code and stderr, with a watchdog.
pub fn with_stdout_closed(args: &[&str]) -> (Option<i32>, String) {
    let mut child = piped(args).spawn().unwrap();
    drop(child.stdout.take());
    ended(child, Duration::from_secs(20))
}

/// Starts `servo-studio ARGS` with its stderr kept (for [`ended`]) and its stdout dropped.
pub fn spawn_quiet(args: &[&str]) -> Child {
    std::process::Command::new(env!("CARGO_BIN_EXE_servo-studio"))
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap()
}

/// Waits for the child with a watchdog; returns its exit code and stderr.
pub fn ended(mut child: Child, within: Duration) -> (Option<i32>, String) {
    let mut stderr = child.stderr.take().unwrap();
    let (exited_tx, exited) = crossbeam_channel::bounded(1);
    let pid = child.id();
    std::thread::spawn(move || {
        let _ = exited_tx.send(child.wait().unwrap());
    });
    let Ok(status) = exited.recv_timeout(within) else {
        let _ = std::process::Command::new("kill").args(["-9", &pid.to_string()]).status();
        panic!("the command did not end within {within:?}");
    };
    let mut text = String::new();
    stderr.read_to_string(&mut text).unwrap();
    (status.code(), text)
}

/// What a misbehaving peer on a pseudo-terminal says.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Chatter {
    /// Nothing at all.
    Silent,
    /// Random bytes, as fast as they are read.
    Garbage,
    /// One byte every 500 ms.
    Drip,
    /// To every servo-board request, the header of its response (claiming
    /// 200 content bytes), then a byte every 100 ms: a line too slow for its traffic.
    Begins,
}

/// A pseudo-terminal whose other end the test holds, saying `chatter` until dropped.
#[cfg(unix)]
pub struct Peer {
    _master: serialport::TTYPort,
    // The slave end stays open here too, so the pty lives between clients.
    _slave: serialport::TTYPort,
    /// The port a client opens.
    pub port: String,
    _stop: Option<crossbeam_channel::Sender<()>>,
}

/// A peer saying `chatter` on a fresh pseudo-terminal.
#[cfg(unix)]
pub fn peer(chatter: Chatter) -> Peer {
    use serialport::SerialPort;
    let (mut master, slave) = serialport::TTYPort::pair().unwrap();
    let port = slave.name().unwrap();
    if chatter == Chatter::Begins {
        let stop = begins(master.try_clone_native().unwrap());
        master.set_timeout(Duration::from_millis(10)).unwrap();
        return Peer { _master: master, _slave: slave, port, _stop: Some(stop) };
    }
    let stop = (chatter != Chatter::Silent).then(|| {
        let (stop, stopped) = crossbeam_channel::bounded::<()>(0);
        let mut writer = master.try_clone_native().unwrap();
        std::thread::spawn(move || {
            let mut seed = 0x2545_f491_u32;
            let (size, pause) = match chatter {
                Chatter::Drip => (1, Duration::from_millis(500)),
                _ => (32, Duration::from_millis(2)),
            };
            loop {
                let bytes: Vec<u8> = (0..size)
                    .map(|_| {
                        seed ^= seed << 13;
                        seed ^= seed >> 17;
                        seed ^= seed << 5;
                        seed.to_le_bytes()[0]
                    })
                    .collect();
                match writer.write_all(&bytes) {
                    // Nobody reads between clients: the line stays full a while.
                    Err(error) if error.kind() == std::io::ErrorKind::TimedOut => {}
                    Err(_) => return,
                    Ok(()) => {}
                }
                // Until dropped: the wait is also the pace.
                if !matches!(stopped.recv_timeout(pause), Err(crossbeam_channel::RecvTimeoutError::Timeout)) {
                    return;
                }
            }
        });
        stop
    });
    master.set_timeout(Duration::from_millis(10)).unwrap();
    Peer { _master: master, _slave: slave, port, _stop: stop }
}

/// [`Chatter::Begins`] on the master end `line`, until the returned sender is dropped.
#[cfg(unix)]
fn begins(mut line: serialport::TTYPort) -> crossbeam_channel::Sender<()> {
    use serialport::SerialPort;
    let (stop, stopped) = crossbeam_channel::bounded::<()>(0);
    line.set_timeout(Duration::from_millis(10)).unwrap();
    std::thread::spawn(move || {
        const MAGIC: [u8; 4] = [0x13, 0x4c, 0x05, 0x1d];
        let mut heard = Vec::new();
        let mut buffer = [0u8; 256];
        let mut next_drip = std::time::Instant::now();
        loop {
            match line.read(&mut buffer) {
                Ok(count) => heard.extend_from_slice(&buffer[..count]),
                Err(error) if error.kind() == std::io::ErrorKind::TimedOut => {}
                Err(_) => return,
            }
            // Each request's header: answer with its response's header (packet id + 1).
            while let Some(at) = heard.windows(4).position(|window| window == MAGIC) {
                if heard.len() < at + 8 {
                    break;
                }
                let id = u16::from_le_bytes([heard[at + 4], heard[at + 5]]).wrapping_add(1);
                let mut header = MAGIC.to_vec();
                header.extend_from_slice(&id.to_le_bytes());
                header.extend_from_slice(&200u16.to_le_bytes());
                let _ = line.write_all(&header);
                heard.drain(..at + 8);
            }
            if std::time::Instant::now() >= next_drip {
                let _ = line.write_all(&[0]);
                next_drip += Duration::from_millis(100);
            }
            if !matches!(stopped.try_recv(), Err(crossbeam_channel::TryRecvError::Empty)) {
                return;
            }
        }
    });
    stop
}
