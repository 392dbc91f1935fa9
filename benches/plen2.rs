//! PLEN2 upload figures, over a pseudo-terminal against the emulated robot at
//! its modelled firmware speed, for each kind of line: clean USB, a Bluetooth
//! LE bridge (15 and 30 ms connection intervals), writes held back up to
//! 20 ms, a 115200-baud line. For each: upload + verify of a 20-frame motion
//! with the default (adaptive) pacing, beside the official tool's pacing
//! (32 bytes, then 50 ms; no verification) for the same bytes and beside the
//! floor (what the robot and the line themselves need); bytes the robot lost
//! and slots written again. A fresh session per line: the pacing learns each.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::print_stdout, clippy::cast_precision_loss)]

use std::time::{Duration, Instant};

use servo_studio::device::Cancel;
use servo_studio::device::plen2::{
    Plen2Handle, Plen2ImportOptions, Plen2Notice, Plen2Options, SlotResult, import, motion_commands,
};
use servo_studio::link::{PortName, no_waker};
use servo_studio::project::Family;
use servo_studio::project::plen2::{Frame, Joint, Motion, Plen2Project, Pose};
use servo_studio::sim::{LinkKind, Plen2Sim, Plen2SimCommand, Plen2Timing, spawn_pty};

fn motion(slot: u8) -> Motion {
    let frames = (0..20)
        .map(|i: i16| {
            let mut pose = Pose::default();
            for (j, joint) in (0i16..).zip(Joint::ALL) {
                pose.set(joint, (i * 53 + j * 29) % 600 - 300);
            }
            Frame::new(100 + 20 * u16::try_from(i).unwrap(), pose)
        })
        .collect();
    Motion { slot, name: "Bench Walk".into(), frames, loop_range: None, jump_slot: None }
}

/// What the line alone needs to carry `bytes` to the robot and `reply` back.
fn line_floor(link: LinkKind, timing: &Plen2Timing, bytes: u32, reply: u32) -> Duration {
    match link {
        LinkKind::Clean | LinkKind::Late { .. } => timing.line_byte * bytes + timing.reply_byte * reply,
        LinkKind::Slow { baud } => Duration::from_secs_f64(f64::from(bytes + reply) * 10.0 / f64::from(baud)),
        LinkKind::Bursty { interval, whole: false } => interval * (bytes.div_ceil(80) + reply.div_ceil(1464)),
        // Each reply whole at one event (this bench reads back one reply).
        LinkKind::Bursty { interval, whole: true } => interval * (bytes.div_ceil(80) + u32::from(reply > 0)),
        LinkKind::Bridge(bridge) => {
            let per_event = u32::try_from(bridge.notification * bridge.per_event).unwrap();
            let replies = if bridge.whole { u32::from(reply > 0) } else { reply.div_ceil(per_event) };
            bridge.interval * (bytes.div_ceil(u32::try_from(bridge.to_robot).unwrap()) + replies)
        }
    }
}

struct Figures {
    median: Duration,
    best: Duration,
    worst: Duration,
    lost: u64,
    dropped: u64,
    rewritten: usize,
    widened: Vec<String>,
    /// The read-back's size, bytes.
    reply_bytes: u32,
}

fn measure(link: LinkKind, rounds: u8) -> Figures {
    let timing = Plen2Timing::default();
    let robot = spawn_pty(Plen2Sim::new(timing).with_link(link), no_waker()).unwrap();
    let port = PortName::parse(&robot.port_name).unwrap();
    let settings = servo_studio::device::line_settings(Family::Plen2);
    // The line rate is not told: on a slower line the pacing learns it.
    let connection = servo_studio::link::open(&port, &settings).unwrap();
    let mut handle = Plen2Handle::over(connection, Plen2Options::default(), no_waker()).unwrap();
    let requester = handle.requester();
    let options = Plen2ImportOptions { backup_dir: None, verify: true, force: false };
    let mut times = Vec::new();
    let mut rewritten = 0;
    for round in 0..rounds {
        let project = Plen2Project { motions: vec![motion(round)], ..Plen2Project::default() };
        let began = Instant::now();
        let report = import(&requester, &project, &options, &mut |_| {}, &Cancel::never()).unwrap();
        times.push(began.elapsed());
        assert!(report.slots.iter().all(|(_, r)| *r == SlotResult::Verified), "{report:?}");
        rewritten += report.rewritten;
    }
    let read_back = requester.get(servo_studio::device::plen2::Command::GetMotion { slot: 0 }).unwrap();
    let widened = handle
        .pump(Instant::now())
        .into_iter()
        .filter_map(|notice| match notice {
            Plen2Notice::Widened(widened) => Some(widened.to_string()),
            _ => None,
        })
        .collect();
    let (reply, state) = crossbeam_channel::bounded(1);
    robot.command(Plen2SimCommand::Inspect(reply));
    let state = state.recv_timeout(Duration::from_secs(5)).unwrap();
    times.sort();
    Figures {
        median: times[times.len() / 2],
        best: times[0],
        worst: times[times.len() - 1],
        lost: state.lost_bytes,
        dropped: state.dropped,
        rewritten,
        widened,
        reply_bytes: u32::try_from(read_back.len()).unwrap(),
    }
}

/// The first ten official motions (`../shared/plen2/motions`, 00 to 09: 1 to
/// 20 frames each), a user's real upload.
fn official_ten() -> Option<Plen2Project> {
    let folder = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/plen2/motions");
    let mut files: Vec<_> = std::fs::read_dir(folder).ok()?.map(|entry| entry.unwrap().path()).collect();
    files.sort();
    let motions = files
        .iter()
        .take(10)
        .map(|file| servo_studio::project::motion_json::read_motion_file(file).unwrap().0)
        .collect();
    Some(Plen2Project { motions, ..Plen2Project::default() })
}

/// What one upload in a fresh session took and showed.
struct Run {
    took: Duration,
    /// Until the last motion was written (the rest: verification).
    written: Duration,
    lost: u64,
    rewritten: usize,
    widened: Vec<String>,
}

/// One upload + verify of `project` in a fresh session (the pacing learns
/// the link anew, as at each of a user's connections).
fn upload_in_a_fresh_session(link: LinkKind, project: &Plen2Project) -> Run {
    let robot = spawn_pty(Plen2Sim::new(Plen2Timing::default()).with_link(link), no_waker()).unwrap();
    let port = PortName::parse(&robot.port_name).unwrap();
    let connection = servo_studio::link::open(&port, &servo_studio::device::line_settings(Family::Plen2)).unwrap();
    let mut handle = Plen2Handle::over(connection, Plen2Options::default(), no_waker()).unwrap();
    let options = Plen2ImportOptions { backup_dir: None, verify: true, force: false };
    let began = Instant::now();
    let mut written = Duration::ZERO;
    let mut progress = |progress: &servo_studio::device::plen2::Plen2Progress| {
        if progress.phase == servo_studio::device::plen2::Plen2Phase::Write && progress.done == progress.total {
            written = began.elapsed();
        }
    };
    let report = import(&handle.requester(), project, &options, &mut progress, &Cancel::never()).unwrap();
    let took = began.elapsed();
    assert!(report.slots.iter().all(|(_, r)| *r == SlotResult::Verified), "{report:?}");
    let widened = handle
        .pump(Instant::now())
        .into_iter()
        .filter_map(|notice| match notice {
            Plen2Notice::Widened(widened) => Some(widened.to_string()),
            _ => None,
        })
        .collect();
    let (reply, state) = crossbeam_channel::bounded(1);
    robot.command(Plen2SimCommand::Inspect(reply));
    let state = state.recv_timeout(Duration::from_secs(5)).unwrap();
    Run { took, written, lost: state.lost_bytes, rewritten: report.rewritten, widened }
}

/// Import of one motion into a factory-fresh robot with a backup first: the
/// backup drains the slot's erased memory (plen2.md §3), then the motion is
/// written and verified. Returns the time, bytes lost, slots written again,
/// and whether the progress said why the slot was slow (with the time left).
fn backup_of_a_fresh_robot(link: LinkKind) -> (Duration, u64, usize, bool) {
    let robot = spawn_pty(Plen2Sim::new(Plen2Timing::default()).with_link(link), no_waker()).unwrap();
    let port = PortName::parse(&robot.port_name).unwrap();
    let connection = servo_studio::link::open(&port, &servo_studio::device::line_settings(Family::Plen2)).unwrap();
    let handle = Plen2Handle::over(connection, Plen2Options::default(), no_waker()).unwrap();
    let folder = tempfile::tempdir().unwrap();
    let options = Plen2ImportOptions { backup_dir: Some(folder.path().to_path_buf()), verify: true, force: false };
    let project = Plen2Project { motions: vec![motion(3)], ..Plen2Project::default() };
    let mut said = false;
    let mut progress = |progress: &servo_studio::device::plen2::Plen2Progress| {
        said |= matches!(progress.item, servo_studio::device::plen2::Plen2Item::Erased { remaining: Some(_), .. });
    };
    let began = Instant::now();
    let report = import(&handle.requester(), &project, &options, &mut progress, &Cancel::never()).unwrap();
    let took = began.elapsed();
    assert!(report.slots.iter().all(|(_, r)| *r == SlotResult::Verified), "{report:?}");
    let (reply, state) = crossbeam_channel::bounded(1);
    robot.command(Plen2SimCommand::Inspect(reply));
    let state = state.recv_timeout(Duration::from_secs(5)).unwrap();
    (took, state.lost_bytes, report.rewritten, said)
}

/// Runs of a user's upload — the first ten official motions, written and
/// verified, each run a fresh connection — behind every model of a Bluetooth
/// LE bridge at 15 and 30 ms, against the official tool's pacing for the same
/// bytes: the spread between runs (and models) is what a user feels from one
/// upload to the next.
fn spread() {
    const RUNS: usize = 3;
    let Some(project) = official_ten() else {
        println!("spread: skipped (../shared/plen2/motions is absent)");
        return;
    };
    let bytes: u32 = project
        .motions
        .iter()
        .flat_map(motion_commands)
        .map(|command| u32::try_from(command.to_ascii().len()).unwrap())
        .sum();
    // The official tool writes motion by motion: 32 bytes, then 50 ms.
    let official: Duration = project
        .motions
        .iter()
        .map(|motion| {
            let bytes: u32 = motion_commands(motion).iter().map(|c| u32::try_from(c.to_ascii().len()).unwrap()).sum();
            Duration::from_millis(50) * bytes.div_ceil(32)
        })
        .sum();
    println!(
        "the first ten official motions ({bytes} bytes), upload + verify in a fresh session, {RUNS} runs each; the official pacing writes them in {:.1} s:",
        official.as_secs_f64()
    );
    // The first model of a bridge, and five more read from its description
    // alone (other phases, other notifications, whole replies, late writes):
    // a pacing that holds on one model only is tuned to it.
    let mut links: Vec<(String, LinkKind, f64)> = Vec::new();
    for (interval, target) in [(Duration::from_millis(15), 2.5), (Duration::from_millis(30), 1.5)] {
        for whole in [false, true] {
            links.push(("first model".into(), LinkKind::Bursty { interval, whole }, target));
        }
        for (name, bridge) in servo_studio::sim::Bridge::models(interval) {
            links.push((name.into(), LinkKind::Bridge(bridge), target));
        }
    }
    // `-- spread NAME`: only the models whose name or link holds NAME.
    let only: Option<String> =
        std::env::args().skip_while(|arg| arg != "spread").skip(1).find(|arg| !arg.starts_with("--"));
    for (name, link, target) in links {
        if only.as_ref().is_some_and(|only| !name.contains(only.as_str()) && !link.to_string().contains(only.as_str()))
        {
            continue;
        }
        let runs: Vec<Run> = (0..RUNS).map(|_| upload_in_a_fresh_session(link, &project)).collect();
        let faster: Vec<f64> = runs.iter().map(|run| official.as_secs_f64() / run.took.as_secs_f64()).collect();
        let slowest = faster.iter().copied().fold(f64::MAX, f64::min);
        let fastest = faster.iter().copied().fold(0.0, f64::max);
        println!(
            "  {name:<20} {link}: runs {} s (written by {} s) — {slowest:.2}× to {fastest:.2}× the official (target ≥ {target}× in every run: {}); bytes lost {}, slots written again {}",
            runs.iter().map(|run| format!("{:.2}", run.took.as_secs_f64())).collect::<Vec<_>>().join(", "),
            runs.iter().map(|run| format!("{:.2}", run.written.as_secs_f64())).collect::<Vec<_>>().join(", "),
            if slowest >= target { "met" } else { "NOT met" },
            runs.iter().map(|run| run.lost).sum::<u64>(),
            runs.iter().map(|run| run.rewritten).sum::<usize>(),
        );
        for (number, run) in runs.iter().enumerate() {
            // What the pacing learned of the bridge's events, else its last word.
            let learned = run.widened.iter().rev().find(|said| said.contains("connection events"));
            let said = learned.or(run.widened.last()).map_or("not widened", String::as_str);
            println!("               run {}: {said}", number + 1);
        }
    }
}

fn main() {
    let timing = Plen2Timing::default();
    let bytes: u32 = motion_commands(&motion(0)).iter().map(|c| u32::try_from(c.to_ascii().len()).unwrap()).sum();
    let official = Duration::from_millis(50) * bytes.div_ceil(32);
    let eeprom = timing.header_write + timing.frame_write * 20;
    let ms = |d: Duration| d.as_secs_f64() * 1e3;
    // `cargo bench --bench plen2 -- spread`: only the runs of a user's upload.
    if std::env::args().any(|arg| arg == "spread") {
        spread();
        return;
    }
    println!(
        "20-frame motion: {bytes} bytes written; official pacing (32 bytes, then 50 ms; no verification): {:.0} ms",
        ms(official)
    );
    let links = [
        (LinkKind::Clean, None, 10),
        (LinkKind::Bursty { interval: Duration::from_millis(15), whole: false }, Some(2.5), 5),
        (LinkKind::Bursty { interval: Duration::from_millis(30), whole: false }, Some(1.5), 5),
        (LinkKind::Bursty { interval: Duration::from_millis(15), whole: true }, Some(2.5), 5),
        (LinkKind::Bursty { interval: Duration::from_millis(30), whole: true }, Some(1.5), 5),
        (LinkKind::Late { max_hold: Duration::from_millis(20) }, Some(3.0), 5),
        (LinkKind::Slow { baud: 115_200 }, Some(1.2), 5),
    ];
    spread();
    for (link, faster_target, rounds) in links {
        let figures = measure(link, rounds);
        // The robot reads every byte and writes every page; the line carries both ways.
        let robot_floor = timing.byte_read * bytes + eeprom;
        let reply = figures.reply_bytes;
        let floor = robot_floor.max(line_floor(link, &timing, bytes, 0)) + line_floor(link, &timing, 0, reply);
        let faster = official.as_secs_f64() / figures.median.as_secs_f64();
        let target = match faster_target {
            Some(target) => format!("target ≥ {target}×"),
            None => format!("target ≤ 1.3× the floor: {:.2}×", figures.median.as_secs_f64() / floor.as_secs_f64()),
        };
        println!(
            "  {link:<12} upload + verify median {:.1} ms (best {:.1}, worst {:.1} of {rounds}) — {faster:.1}× faster than official ({target}); floor {:.1} ms ({:.2}×); bytes lost {}, commands dropped {}, slots written again {}",
            ms(figures.median),
            ms(figures.best),
            ms(figures.worst),
            ms(floor),
            figures.median.as_secs_f64() / floor.as_secs_f64(),
            figures.lost,
            figures.dropped,
            figures.rewritten,
        );
        for widened in figures.widened {
            println!("               {widened}");
        }
    }
    println!(
        "backup of a factory-fresh robot's slot (its erased memory, {} KB, drained whole), then upload + verify of one motion:",
        servo_studio::device::plen2::ERASED_REPLY_BYTES / 1024
    );
    for link in [
        LinkKind::Clean,
        LinkKind::Bursty { interval: Duration::from_millis(15), whole: false },
        LinkKind::Bursty { interval: Duration::from_millis(15), whole: true },
        LinkKind::Late { max_hold: Duration::from_millis(20) },
        LinkKind::Slow { baud: 115_200 },
    ] {
        let (took, lost, rewritten, said) = backup_of_a_fresh_robot(link);
        println!(
            "  {link:<16} {:.2} s; bytes lost {lost}, slots written again {rewritten}; the progress said why and how long: {}",
            took.as_secs_f64(),
            if said { "yes" } else { "no (the reply came whole: nothing to say before it was there)" }
        );
    }
}
