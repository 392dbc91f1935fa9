//! Soak: what runs with nobody watching, run for a long time under abuse.
//!
//! - `serve` on three emulated boards (a servo board, a PLEN2, a base) while
//!   hostile clients never let up: a flood of requests on keep-alive
//!   connections, bodies announced and stalled, clients that pipeline and
//!   never read, hundreds of idle connections, 16 MiB header lines and 10 MB
//!   bodies, OSC garbage and bundles nested to the limit of a datagram,
//!   status streams that read and streams that never do. Meanwhile a remote
//!   drives the base on heartbeats at 5 Hz (pausing now and then, so the
//!   dead-man must stop it) and a STOP is sent every second on a new connection.
//! - `play --loop` of a show whose PLEN2's cable is pulled and put back, and
//!   whose base goes silent for a while (both played on without), beside a
//!   servo board on a direct link.
//!
//! Printed: STOPs sent, answered and their latency (median, 99th percentile,
//! largest: the target is every one answered within 100 ms), heartbeats and
//! what the dead-man did, both processes' memory over the run (first, largest,
//! last), runs played and devices connected again, and whether the base was
//! left braked. `SOAK_SECONDS` (default 600) sets the length.
//!
//! `cargo bench --bench soak`.

#![allow(clippy::expect_used, clippy::unwrap_used, clippy::cast_precision_loss, clippy::cast_possible_truncation)]

#[path = "../tests/common/proxy.rs"]
mod proxy;

use std::io::{BufRead, BufReader, Read, Write};
use std::net::{TcpStream, UdpSocket};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use servo_studio::project::plen2::{Frame, Motion, Plen2Project, Pose};
use servo_studio::project::{
    self, Action, Command as MacroCommand, Family, Macro, Project, Run, Servo, ServoProject, Step,
};
use servo_studio::show::{Cue, Device, Place, Show, Start};

const EXE: &str = env!("CARGO_BIN_EXE_servo-studio");

fn swinging(swings: i32) -> Project {
    let actions: Vec<Action> = (1..=swings)
        .map(|id| Action {
            id,
            caption: format!("swing {id}"),
            steps: vec![Step::new(1, if id % 2 == 0 { 30 } else { -30 }, 50)],
        })
        .collect();
    let commands = actions.iter().map(|a| MacroCommand::once(Run::Action { action_id: a.id })).collect();
    Project::servo(ServoProject {
        servos: vec![Servo::new(1, "arm")],
        actions,
        macros: vec![Macro { id: 1, caption: "show".into(), commands }],
        ..ServoProject::default()
    })
}

fn waving() -> Project {
    let motion = Motion {
        slot: 2,
        name: "wave".into(),
        frames: vec![Frame::new(320, Pose::default()); 5],
        loop_range: None,
        jump_slot: None,
    };
    let mut project = Project::empty(Family::Plen2);
    project.plen2 = Plen2Project { motions: vec![motion], ..Plen2Project::default() };
    project
}

fn device(name: &str, project: Project, play_on_without: bool) -> Device {
    Device { name: name.into(), port: None, place: Place::default(), project, play_on_without }
}

/// A `servo-studio` process, killed when dropped.
struct Process(Child);

impl Drop for Process {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// An emulator on TCP, logging; its port.
fn sim(dir: &Path, name: &str, project: &Project) -> (Process, String, PathBuf) {
    let state = dir.join(format!("{name}.json"));
    project::save(&state, project).unwrap();
    let log = dir.join(format!("{name}.log"));
    let mut args =
        vec!["sim", "--protocol", project.family.tag(), "--log", log.to_str().unwrap(), "--tcp", "127.0.0.1:0"];
    if project.family != Family::Rflex {
        args.extend(["--state", state.to_str().unwrap()]);
    }
    let mut child = Command::new(EXE).args(&args).stdout(Stdio::piped()).stderr(Stdio::null()).spawn().unwrap();
    let mut line = String::new();
    BufReader::new(child.stdout.take().unwrap()).read_line(&mut line).unwrap();
    (Process(child), line.trim().to_string(), log)
}

fn rss_kib(pid: u32) -> Option<u64> {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).ok()?;
    status.lines().find(|line| line.starts_with("VmRSS:"))?.split_whitespace().nth(1)?.parse().ok()
}

/// A status code from a raw request on a new connection (0: no answer).
fn request(address: &str, raw: &[u8]) -> u16 {
    let Ok(mut stream) = TcpStream::connect(address) else { return 0 };
    let _ = stream.set_read_timeout(Some(Duration::from_secs(10)));
    if stream.write_all(raw).is_err() {
        return 0;
    }
    let mut line = Vec::new();
    let mut byte = [0; 1];
    while !line.ends_with(b"\r\n") && matches!(stream.read(&mut byte), Ok(1)) {
        line.push(byte[0]);
    }
    String::from_utf8_lossy(&line).split_whitespace().nth(1).and_then(|code| code.parse().ok()).unwrap_or(0)
}

/// A JSON answer on a new connection: its code and body.
fn json(address: &str, method: &str, path: &str, body: &str) -> (u16, String) {
    let Ok(mut stream) = TcpStream::connect(address) else { return (0, String::new()) };
    let _ = stream.set_read_timeout(Some(Duration::from_secs(10)));
    let raw = format!(
        "{method} {path} HTTP/1.1\r\nHost: robot\r\nConnection: close\r\nContent-Type: application/json\r\nContent-Length: {}\r\n\r\n{body}",
        body.len()
    );
    if stream.write_all(raw.as_bytes()).is_err() {
        return (0, String::new());
    }
    let mut text = String::new();
    let _ = stream.read_to_string(&mut text);
    let code = text.split_whitespace().nth(1).and_then(|code| code.parse().ok()).unwrap_or(0);
    (code, text.split("\r\n\r\n").nth(1).unwrap_or_default().to_string())
}

fn percentile(sorted: &[f64], p: f64) -> f64 {
    if sorted.is_empty() {
        return 0.0;
    }
    sorted[((sorted.len() - 1) as f64 * p).round() as usize]
}

/// Memory samples of a process: first, largest, last, KiB.
#[derive(Default)]
struct Memory(Vec<u64>);

impl Memory {
    /// First, after the first minute (the load under way), largest, last; one sample each 10 s.
    fn said(&self, what: &str) -> String {
        let mib = |kib: u64| kib as f64 / 1024.0;
        let (first, last) = (self.0.first().copied().unwrap_or(0), self.0.last().copied().unwrap_or(0));
        let settled = self.0.get(6).copied().unwrap_or(last);
        let most = self.0.iter().copied().max().unwrap_or(0);
        format!(
            "{what} memory: first {:.1} MiB, after a minute {:.1} MiB, largest {:.1} MiB, last {:.1} MiB ({} samples, one each 10 s)",
            mib(first),
            mib(settled),
            mib(most),
            mib(last),
            self.0.len()
        )
    }
}

fn main() {
    let seconds: u64 = std::env::var("SOAK_SECONDS").ok().and_then(|s| s.parse().ok()).unwrap_or(600);
    let length = Duration::from_secs(seconds);
    println!("soak: {seconds} s of serve under hostile load and play --loop over bad links");
    let dir = tempfile::tempdir().unwrap();
    let done = Arc::new(AtomicBool::new(false));

    // ---- serve -------------------------------------------------------------
    let (_skull_sim, skull_port, skull_log) = sim(dir.path(), "skull", &swinging(400));
    let (_plen_sim, plen_port, _) = sim(dir.path(), "plen", &waving());
    let (_base_sim, base_port, base_log) = sim(dir.path(), "base", &Project::empty(Family::Rflex));
    let show = Show {
        devices: vec![
            device("skull", swinging(400), false),
            device("plen", waving(), false),
            device("base", Project::empty(Family::Rflex), false),
        ],
        sound: None,
        cues: vec![Cue { device: "skull".into(), at_ms: 0, start: Start::Macro(1) }],
    };
    let show_file = dir.path().join("serve.json");
    std::fs::write(&show_file, show.to_json()).unwrap();
    let mut serve = Command::new(EXE)
        .args(["serve", show_file.to_str().unwrap(), "--listen", "127.0.0.1:0", "--osc", "0"])
        .args(["--device", &format!("skull={skull_port}"), "--device", &format!("plen={plen_port}")])
        .args(["--device", &format!("base={base_port}")])
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let mut lines = BufReader::new(serve.stdout.take().unwrap()).lines();
    let (mut http, mut osc) = (String::new(), String::new());
    while http.is_empty() || osc.is_empty() {
        let line = lines.next().unwrap().unwrap();
        if let Some(rest) = line.strip_prefix("listening on http://") {
            http = rest.split_whitespace().next().unwrap().to_string();
        }
        if let Some(rest) = line.strip_prefix("OSC on udp://") {
            osc = rest.trim().to_string();
        }
    }
    std::thread::spawn(move || lines.for_each(drop));
    let serve = Process(serve);
    let serve_pid = serve.0.id();

    let mut load = Vec::new();
    let hostile = |load: &mut Vec<std::thread::JoinHandle<()>>, work: Box<dyn Fn(&str) + Send>| {
        let (done, http) = (Arc::clone(&done), http.clone());
        load.push(std::thread::spawn(move || {
            while !done.load(Ordering::SeqCst) {
                work(&http);
            }
        }));
    };
    // A flood on keep-alive connections, four of them.
    for _ in 0..4 {
        hostile(
            &mut load,
            Box::new(|http| {
                let Ok(mut stream) = TcpStream::connect(http) else { return };
                let _ = stream.set_read_timeout(Some(Duration::from_secs(5)));
                let mut reader = BufReader::new(stream.try_clone().unwrap());
                for _ in 0..500 {
                    if stream.write_all(b"GET /status HTTP/1.1\r\nHost: robot\r\n\r\n").is_err() {
                        return;
                    }
                    let mut length = 0;
                    loop {
                        let mut line = String::new();
                        if reader.read_line(&mut line).unwrap_or(0) == 0 {
                            return;
                        }
                        if let Some(value) = line.to_ascii_lowercase().strip_prefix("content-length:") {
                            length = value.trim().parse().unwrap_or(0);
                        }
                        if line == "\r\n" {
                            break;
                        }
                    }
                    let mut body = vec![0; length];
                    if reader.read_exact(&mut body).is_err() {
                        return;
                    }
                }
            }),
        );
    }
    // Stalled bodies, pipeliners that never read, idle and half-sent connections: held, renewed.
    hostile(
        &mut load,
        Box::new(|http| {
            let mut held = Vec::new();
            for _ in 0..4 {
                if let Ok(mut stream) = TcpStream::connect(http) {
                    let _ = stream.write_all(b"POST /devices/skull/play HTTP/1.1\r\nHost: robot\r\nContent-Type: application/json\r\nContent-Length: 1000\r\n\r\n{\"wh");
                    held.push(stream);
                }
            }
            if let Ok(mut stream) = TcpStream::connect(http) {
                let _ = stream.set_write_timeout(Some(Duration::from_secs(1)));
                let _ = stream.write_all(&b"GET /status HTTP/1.1\r\nHost: robot\r\n\r\n".repeat(2_000));
                held.push(stream);
            }
            for _ in 0..100 {
                if let Ok(mut stream) = TcpStream::connect(http) {
                    let _ = stream.write_all(b"GET /sta");
                    held.push(stream);
                }
            }
            std::thread::sleep(Duration::from_secs(3));
        }),
    );
    hostile(
        &mut load,
        Box::new(|http| {
            let idle: Vec<TcpStream> = (0..300).filter_map(|_| TcpStream::connect(http).ok()).collect();
            std::thread::sleep(Duration::from_secs(12));
            drop(idle);
        }),
    );
    // Oversized: a 16 MiB header line, a 10 MB body, a Content-Length of 2^64 − 1.
    hostile(
        &mut load,
        Box::new(|http| {
            let mut header = b"GET /status HTTP/1.1\r\nHost: robot\r\nX-Big: ".to_vec();
            header.resize(header.len() + (16 << 20), b'a');
            header.extend_from_slice(b"\r\n\r\n");
            let _ = request(http, &header);
            let mut body = b"POST /devices/skull/play HTTP/1.1\r\nHost: robot\r\nContent-Type: application/json\r\nContent-Length: 10000000\r\n\r\n".to_vec();
            body.resize(body.len() + 10_000_000, b'x');
            let _ = request(http, &body);
            let _ =
                request(http, b"POST /stop HTTP/1.1\r\nHost: robot\r\nContent-Length: 18446744073709551615\r\n\r\n");
            std::thread::sleep(Duration::from_secs(2));
        }),
    );
    // Status streams: eight that read, and eight more that never do.
    hostile(
        &mut load,
        Box::new(|http| {
            let mut streams = Vec::new();
            for _ in 0..16 {
                if let Ok(mut stream) = TcpStream::connect(http) {
                    let _ = stream.write_all(b"GET /events HTTP/1.1\r\nHost: robot\r\n\r\n");
                    streams.push(stream);
                }
            }
            let readers: Vec<_> = streams
                .drain(..8)
                .map(|mut stream| {
                    std::thread::spawn(move || {
                        let _ = stream.set_read_timeout(Some(Duration::from_secs(1)));
                        let mut buffer = [0; 4096];
                        let until = Instant::now() + Duration::from_secs(20);
                        while Instant::now() < until && !matches!(stream.read(&mut buffer), Ok(0)) {}
                    })
                })
                .collect();
            for reader in readers {
                let _ = reader.join();
            }
            drop(streams);
        }),
    );
    // OSC: garbage, and bundles nested to fill a datagram.
    {
        let (done, osc) = (Arc::clone(&done), osc.clone());
        load.push(std::thread::spawn(move || {
            let socket = UdpSocket::bind("127.0.0.1:0").unwrap();
            let mut deep = b"/stop\0\0\0,\0\0\0".to_vec();
            for _ in 0..3_200 {
                let mut outer = b"#bundle\0\0\0\0\0\0\0\0\x01".to_vec();
                outer.extend_from_slice(&i32::try_from(deep.len()).unwrap().to_be_bytes());
                outer.extend_from_slice(&deep);
                deep = outer;
            }
            let mut noise = 0x9e37_79b9_u32;
            while !done.load(Ordering::SeqCst) {
                let _ = socket.send_to(&deep, &osc);
                let garbage: Vec<u8> = (0..64)
                    .map(|_| {
                        noise ^= noise << 13;
                        noise ^= noise >> 17;
                        noise ^= noise << 5;
                        noise as u8
                    })
                    .collect();
                let _ = socket.send_to(&garbage, &osc);
                std::thread::sleep(Duration::from_millis(10));
            }
        }));
    }

    // The base, driven on heartbeats at 5 Hz, pausing 1 s every 30 s (the dead-man must stop it).
    let (beats, refused_beats, dead_man_stops, drives) = (
        Arc::new(AtomicU64::new(0)),
        Arc::new(AtomicU64::new(0)),
        Arc::new(AtomicU64::new(0)),
        Arc::new(AtomicU64::new(0)),
    );
    let refusals = Arc::new(Mutex::new(std::collections::BTreeMap::<u16, (u64, String)>::new()));
    let driver = {
        let (done, http) = (Arc::clone(&done), http.clone());
        let (beats, refused_beats, dead_man_stops, drives) =
            (Arc::clone(&beats), Arc::clone(&refused_beats), Arc::clone(&dead_man_stops), Arc::clone(&drives));
        let base_log = base_log.clone();
        let refusals = Arc::clone(&refusals);
        std::thread::spawn(move || {
            let began = Instant::now();
            let mut paused_at = 30;
            let mut driving = false;
            while !done.load(Ordering::SeqCst) {
                if began.elapsed().as_secs() >= paused_at {
                    paused_at += 30;
                    let braked = std::fs::read_to_string(&base_log).unwrap_or_default().matches("BrakeSet").count();
                    std::thread::sleep(Duration::from_secs(1));
                    let after = std::fs::read_to_string(&base_log).unwrap_or_default().matches("BrakeSet").count();
                    if after > braked {
                        dead_man_stops.fetch_add(1, Ordering::SeqCst);
                    }
                    driving = false;
                }
                let (code, said) = if driving {
                    beats.fetch_add(1, Ordering::SeqCst);
                    json(&http, "POST", "/devices/base/heartbeat", "")
                } else {
                    drives.fetch_add(1, Ordering::SeqCst);
                    json(&http, "POST", "/devices/base/drive", r#"{"speed_m_s": 0.1}"#)
                };
                if code != 200 {
                    if driving {
                        refused_beats.fetch_add(1, Ordering::SeqCst);
                    }
                    let mut refusals = refusals.lock().unwrap();
                    let seen = refusals.entry(code).or_insert((0, said));
                    seen.0 += 1;
                }
                driving = code == 200;
                std::thread::sleep(Duration::from_millis(200));
            }
        })
    };

    // ---- play --loop -------------------------------------------------------
    let (_arm_sim, arm_port, arm_log) = sim(dir.path(), "arm", &swinging(8));
    let (_pplen_sim, pplen_port, _) = sim(dir.path(), "pplen", &waving());
    let (_pbase_sim, pbase_port, pbase_log) = sim(dir.path(), "pbase", &Project::empty(Family::Rflex));
    let plen_link = proxy::Proxy::new(&pplen_port, Duration::ZERO);
    let base_link = proxy::Proxy::new(&pbase_port, Duration::ZERO);
    let played = Show {
        devices: vec![
            device("arm", swinging(8), false),
            device("pplen", waving(), true),
            device("pbase", Project::empty(Family::Rflex), true),
        ],
        sound: None,
        cues: vec![
            Cue { device: "arm".into(), at_ms: 0, start: Start::Macro(1) },
            Cue { device: "pplen".into(), at_ms: 0, start: Start::Slot(2) },
            Cue {
                device: "pbase".into(),
                at_ms: 0,
                start: Start::Drive { speed_m_s: 0.1, turn_deg_s: 0.0, for_ms: 3_000 },
            },
        ],
    };
    let played_file = dir.path().join("play.json");
    std::fs::write(&played_file, played.to_json()).unwrap();
    let mut player = Command::new(EXE)
        .args(["play", played_file.to_str().unwrap(), "--loop", "1000000"])
        .args(["--device", &format!("arm={arm_port}"), "--device", &format!("pplen={}", plen_link.port)])
        .args(["--device", &format!("pbase={}", base_link.port)])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let runs = Arc::new(AtomicU64::new(0));
    let said = Arc::new(Mutex::new(Vec::<String>::new()));
    {
        let (runs, out) = (Arc::clone(&runs), player.stdout.take().unwrap());
        std::thread::spawn(move || {
            for line in BufReader::new(out).lines().map_while(Result::ok) {
                if line.contains(": ended after") {
                    runs.fetch_add(1, Ordering::SeqCst);
                }
            }
        });
        let (said, err) = (Arc::clone(&said), player.stderr.take().unwrap());
        std::thread::spawn(move || {
            for line in BufReader::new(err).lines().map_while(Result::ok) {
                said.lock().unwrap().push(line);
            }
        });
    }
    let player = Process(player);
    let player_pid = player.0.id();

    // ---- the watch: STOP every second, memory every ten, links cut and silenced ----
    let began = Instant::now();
    let (mut stops, mut stop_failures, mut latencies) = (0u64, 0u64, Vec::new());
    let (mut serve_memory, mut play_memory) = (Memory::default(), Memory::default());
    let mut tick = 0u64;
    while began.elapsed() < length {
        tick += 1;
        let asked = Instant::now();
        let code = request(&http, b"POST /devices/skull/stop HTTP/1.1\r\nHost: robot\r\nContent-Length: 0\r\n\r\n");
        latencies.push(asked.elapsed().as_secs_f64() * 1000.0);
        stops += 1;
        if code != 200 {
            stop_failures += 1;
        }
        if tick % 10 == 1 {
            serve_memory.0.extend(rss_kib(serve_pid));
            play_memory.0.extend(rss_kib(player_pid));
        }
        match tick % 40 {
            10 => plen_link.cut(),
            15 => plen_link.restore(),
            25 => base_link.silence(true),
            35 => base_link.silence(false),
            _ => {}
        }
        std::thread::sleep(Duration::from_secs(1).saturating_sub(asked.elapsed()));
    }
    done.store(true, Ordering::SeqCst);
    let _ = driver.join();
    let serve_alive = rss_kib(serve_pid).is_some();
    let play_alive = rss_kib(player_pid).is_some();
    drop(load);
    // SIGTERM: every device stopped, the base braked, before serve exits.
    let braked = std::fs::read_to_string(&base_log).unwrap_or_default().matches("BrakeSet").count();
    let _ = Command::new("kill").args(["-TERM", &serve_pid.to_string()]).status();
    let mut serve = serve;
    let ended = serve.0.wait().unwrap();
    let braked_at_end = std::fs::read_to_string(&base_log).unwrap_or_default().matches("BrakeSet").count() > braked;
    let _ = Command::new("kill").args(["-TERM", &player_pid.to_string()]).status();
    let mut player = player;
    let played_ended = player.0.wait().unwrap();
    let pbase_last = std::fs::read_to_string(&pbase_log).unwrap_or_default();
    let pbase_braked = pbase_last
        .lines()
        .rev()
        .find(|line| line.contains("BrakeSet") || line.contains("BrakeRelease"))
        .is_some_and(|line| line.contains("BrakeSet"));
    let arm_runs = std::fs::read_to_string(&arm_log).unwrap_or_default().matches("ExecuteMacroRequest").count();
    let reconnected =
        said.lock().unwrap().iter().filter(|line| line.starts_with("pplen (PLEN2) answered")).count().saturating_sub(1);
    let base_back = said
        .lock()
        .unwrap()
        .iter()
        .filter(|line| line.starts_with("pbase (rFLEX base) answered"))
        .count()
        .saturating_sub(1);

    let skull_stops = std::fs::read_to_string(&skull_log).unwrap_or_default().matches("is_start: false").count();
    latencies.sort_by(f64::total_cmp);
    println!("serve, {} s under hostile load (alive at the end: {serve_alive}):", began.elapsed().as_secs());
    println!(
        "  STOP: {stops} sent, {} answered 200, {stop_failures} not; latency median {:.1} ms, 99th percentile {:.1} ms, largest {:.1} ms (target: within 100 ms)",
        stops - stop_failures,
        percentile(&latencies, 0.5),
        percentile(&latencies, 0.99),
        latencies.last().copied().unwrap_or(0.0)
    );
    println!("  the skull's board took {skull_stops} stops in (one per STOP, and one at SIGTERM)");
    println!(
        "  base on heartbeats: {} heartbeats, {} refused (after a pause or a STOP); {} drives; the dead-man stopped it in {} of {} pauses",
        beats.load(Ordering::SeqCst),
        refused_beats.load(Ordering::SeqCst),
        drives.load(Ordering::SeqCst),
        dead_man_stops.load(Ordering::SeqCst),
        began.elapsed().as_secs() / 30
    );
    for (code, (times, said)) in refusals.lock().unwrap().iter() {
        println!("  the drive or heartbeat answered {code} {times} times, e.g. {}", said.trim());
    }
    println!("  {}", serve_memory.said("serve"));
    println!("  SIGTERM: exit {:?}; the base braked before it exited: {braked_at_end}", ended.code());
    println!("play --loop, the same {} s (alive at the end: {play_alive}):", began.elapsed().as_secs());
    println!(
        "  {} runs ended ({} started on the arm); the PLEN2's cable pulled {} times, connected again {reconnected} times; the base silenced {} times, back {base_back} times",
        runs.load(Ordering::SeqCst),
        arm_runs,
        tick / 40 + u64::from(tick % 40 >= 10),
        tick / 40 + u64::from(tick % 40 >= 25),
    );
    println!("  {}", play_memory.said("play"));
    println!("  SIGTERM: exit {:?}; the base's last brake command was a set: {pbase_braked}", played_ended.code());
    if !play_alive {
        println!("  play ended early; it said last:");
        for line in said.lock().unwrap().iter().rev().take(5).rev() {
            println!("    {line}");
        }
    }
}
