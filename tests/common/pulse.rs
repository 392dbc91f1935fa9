//! A real PulseAudio server with a null sink standing in for speakers
//! (Debian's `pulseaudio`, which `.ci/run` installs), started and stopped
//! here, and a recorder of the null sink's monitor that says when each
//! sample came out. Shared by the sync test and the sync bench.

#![allow(
    dead_code,
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::cast_possible_truncation,
    clippy::cast_sign_loss,
    clippy::cast_precision_loss
)]

use std::io::{BufRead, BufReader};
use std::path::PathBuf;
use std::process::{Child, Command, Stdio};
use std::sync::{Arc, Condvar, Mutex};
use std::time::{Duration, Instant};

use servo_studio::audio::output::Speakers;
use servo_studio::audio::together;
use servo_studio::device::servo::{DEFAULT_BAUD, ServoBoard, ServoImage, SessionConfig};
use servo_studio::link::{LinkEvent, PortName, no_waker};
use servo_studio::project::{Action, Macro, Servo, ServoProject, Step};
use servo_studio::protocol::servo::Message;
use servo_studio::sim::{ServoSim, SimConfig, SimEvent, spawn_pty};

use pulseaudio::protocol;

/// The null sink's name.
pub const SINK: &str = "show";
/// The null sink's rate.
pub const RATE: u32 = 48_000;
/// Names the server's socket to a test run in its own process.
const SOCKET_VAR: &str = "SERVO_STUDIO_TEST_PULSE_SOCKET";

/// A running server in a folder of its own; stopped when dropped.
pub struct Pulse {
    /// The server, when this process started it.
    child: Option<Child>,
    _dir: Option<tempfile::TempDir>,
    /// Its socket.
    pub socket: PathBuf,
}

impl Pulse {
    /// Starts a server, waiting for it to say it is up. `None` (the caller
    /// skips, saying so) when `pulseaudio` is not installed, except where
    /// services are required (CI: `.ci/run` installs it), where its absence fails.
    pub fn start() -> Option<Pulse> {
        let dir = tempfile::tempdir().unwrap();
        let socket = dir.path().join("native");
        let spawned = Command::new("pulseaudio")
            .args([
                "-n",
                "--daemonize=no",
                "--exit-idle-time=-1",
                "--use-pid-file=no",
                "--disable-shm=yes",
                "--log-target=stderr",
                "-v",
            ])
            .arg(format!("--load=module-native-protocol-unix socket={} auth-anonymous=1", socket.display()))
            .arg(format!("--load=module-null-sink sink_name={SINK} rate={RATE}"))
            .env("HOME", dir.path())
            .env("XDG_RUNTIME_DIR", dir.path())
            .env("XDG_CONFIG_HOME", dir.path())
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn();
        let mut child = match spawned {
            Ok(child) => child,
            Err(error) => {
                super::without_service(
                    &format!("this test needs a PulseAudio server and `pulseaudio` cannot be started ({error})"),
                    "apt-get install pulseaudio",
                );
                return None;
            }
        };
        // Its log, line by line, until it is up (or ends).
        let stderr = child.stderr.take().unwrap();
        let (up_tx, up_rx) = crossbeam_channel::bounded(1);
        std::thread::spawn(move || {
            let mut said = Vec::new();
            for line in BufReader::new(stderr).lines().map_while(Result::ok) {
                if line.contains("Daemon startup complete") {
                    let _ = up_tx.send(Ok(()));
                }
                said.push(line);
            }
            let _ = up_tx.send(Err(said.join("\n")));
        });
        match up_rx.recv_timeout(Duration::from_secs(30)) {
            Ok(Ok(())) => Some(Pulse { child: Some(child), _dir: Some(dir), socket }),
            Ok(Err(log)) => panic!("pulseaudio ended before it was up:\n{log}"),
            Err(_) => panic!("pulseaudio was not up within 30 s"),
        }
    }

    /// The server of the process that ran this one (`in_own_process`).
    pub fn of_parent() -> Pulse {
        let socket = std::env::var_os(SOCKET_VAR).expect("run by `in_own_process`, which names the server");
        Pulse { child: None, _dir: None, socket: PathBuf::from(socket) }
    }

    /// Runs this program again with `args`, in a process whose environment
    /// names this server, as a user's does (`PULSE_SERVER`), for what finds
    /// the server only there (ALSA's PulseAudio plugin). Fails with what it
    /// said when it fails; returns what it said.
    pub fn in_own_process(&self, args: &[&str]) -> String {
        let folder = self.socket.parent().unwrap();
        let output = Command::new(std::env::current_exe().unwrap())
            .args(args)
            .env("PULSE_SERVER", format!("unix:{}", self.socket.display()))
            .env(SOCKET_VAR, &self.socket)
            .env("HOME", folder)
            .env("XDG_RUNTIME_DIR", folder)
            .env("XDG_CONFIG_HOME", folder)
            .stdin(Stdio::null())
            .output()
            .unwrap();
        let said = format!("{}{}", String::from_utf8_lossy(&output.stdout), String::from_utf8_lossy(&output.stderr));
        assert!(output.status.success(), "{args:?} failed in its own process:\n{said}");
        said
    }

    /// A client of this server.
    pub fn client(&self) -> pulseaudio::Client {
        let stream = std::os::unix::net::UnixStream::connect(&self.socket).unwrap();
        // Anonymous access: the server still wants a cookie's 256 bytes.
        pulseaudio::Client::new_unix(c"servo-studio tests", stream, Some(vec![0u8; 256])).unwrap()
    }
}

impl Drop for Pulse {
    fn drop(&mut self) {
        if let Some(child) = &mut self.child {
            let _ = child.kill();
            let _ = child.wait();
        }
    }
}

/// What the monitor heard, and when each packet of it arrived.
#[derive(Default)]
struct Heard {
    samples: Vec<f32>,
    /// Each packet's arrival and the samples held after it.
    arrivals: Vec<(Instant, usize)>,
    /// When sample 0 was played, by each of the server's timing answers,
    /// with the answer's round trip (the shorter, the surer).
    zeros: Vec<(Duration, Instant)>,
    /// How far the samples have been scanned for clicks, the last loud
    /// sample, and each click's first sample (see [`Recorder::clicks`]).
    scanned: usize,
    last_loud: Option<usize>,
    rises: Vec<usize>,
}

impl Heard {
    /// Sample 0's time: the median of the answers with the shortest round
    /// trips (a quarter of them; a loaded machine delays some answers).
    fn zero(&self) -> Option<Instant> {
        let mut zeros = self.zeros.clone();
        zeros.sort();
        zeros.truncate(zeros.len().div_ceil(4));
        let mut tightest: Vec<Instant> = zeros.into_iter().map(|(_, zero)| zero).collect();
        tightest.sort();
        tightest.get(tightest.len() / 2).copied()
    }

    /// Scans what came in since the last scan for sounds rising past
    /// `CLICK_LEVEL` after `CLICK_QUIET_S` of quiet.
    fn scan(&mut self) {
        let quiet = (CLICK_QUIET_S * f64::from(RATE)) as usize;
        for index in self.scanned..self.samples.len() {
            if self.samples[index].abs() >= CLICK_LEVEL {
                if self.last_loud.is_none_or(|last| index - last > quiet) {
                    self.rises.push(index);
                }
                self.last_loud = Some(index);
            }
        }
        self.scanned = self.samples.len();
    }
}

/// A click is a sound rising past this level…
const CLICK_LEVEL: f32 = 0.5;
/// …after this long of quiet, s.
const CLICK_QUIET_S: f64 = 0.2;

/// A sample's offset from sample 0 (not a rounded duration per sample, times a count: that drifts 16 µs a second).
fn after(samples: usize) -> Duration {
    Duration::from_secs_f64(samples as f64 / f64::from(RATE))
}

/// Records the null sink's monitor (mono, f32) in packets of about 2 ms.
pub struct Recorder {
    _client: pulseaudio::Client,
    heard: Arc<(Mutex<Heard>, Condvar)>,
    /// Dropping it ends the timing thread, which holds the stream.
    _stop: crossbeam_channel::Sender<()>,
}

impl Recorder {
    /// Starts recording.
    pub fn start(pulse: &Pulse) -> Recorder {
        let client = pulse.client();
        let heard = Arc::new((Mutex::new(Heard::default()), Condvar::new()));
        let into = Arc::clone(&heard);
        let sink = move |data: &[u8]| {
            let now = Instant::now();
            let mut heard = into.0.lock().unwrap();
            heard.samples.extend(data.chunks_exact(4).map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]])));
            let held = heard.samples.len();
            heard.arrivals.push((now, held));
            into.1.notify_all();
        };
        let fragment = u32::try_from(RATE as usize * 4 * 2 / 1000).unwrap();
        let params = protocol::RecordStreamParams {
            sample_spec: protocol::SampleSpec {
                format: protocol::SampleFormat::Float32Le,
                channels: 1,
                sample_rate: RATE,
            },
            channel_map: protocol::ChannelMap::mono(),
            source_name: Some(std::ffi::CString::new(format!("{SINK}.monitor")).unwrap()),
            buffer_attr: protocol::stream::BufferAttr { fragment_size: fragment, ..Default::default() },
            flags: protocol::stream::StreamFlags { adjust_latency: true, ..Default::default() },
            ..Default::default()
        };
        let stream = pollster::block_on(client.create_record_stream(params, sink)).unwrap();
        // The server's timing, every 100 ms: where the stream is at each answer,
        // as PulseAudio's own library reckons a monitor's time (what has come
        // in, plus what the source still holds, less what the monitored sink
        // has yet to play).
        let (stop, stopped) = crossbeam_channel::bounded::<()>(0);
        let timing = Arc::clone(&heard);
        std::thread::spawn(move || {
            while let Err(crossbeam_channel::RecvTimeoutError::Timeout) =
                stopped.recv_timeout(Duration::from_millis(100))
            {
                let asked = Instant::now();
                let Ok(answer) = pollster::block_on(stream.timing_info()) else { return };
                let answered = Instant::now();
                let midpoint = asked + (answered - asked) / 2;
                let written = answer.write_offset.max(0) as f64 / 4.0 / f64::from(RATE);
                let position = written + answer.source_usec as f64 / 1e6 - answer.sink_usec as f64 / 1e6;
                if position > 0.0
                    && let Some(zero) = midpoint.checked_sub(Duration::from_secs_f64(position))
                {
                    timing.0.lock().unwrap().zeros.push((answered - asked, zero));
                }
            }
        });
        Recorder { _client: client, heard, _stop: stop }
    }

    /// Waits until `count` clicks have been heard and what was played until
    /// 0.3 s after the last of them (and after `last`) has been recorded,
    /// then says when the last `count` were played, on this process's clock:
    /// sample 0's time by the server's timing answers, and one sample every
    /// 1/48,000 s after. A click is a sound rising past half of full scale
    /// after 0.2 s of quiet; the clicks before the last `count` are not the
    /// show's (an output slower to start than the sound's lead is started
    /// again with a longer one: what it played the first time). Waits by
    /// what was recorded, never by the clock alone, so a loaded machine that
    /// delays the sound, the board or the recording is waited for; panics
    /// after `within`, saying what was heard.
    pub fn clicks(&self, count: usize, last: Instant, within: Duration) -> Vec<Instant> {
        let deadline = Instant::now() + within;
        let (heard, more) = &*self.heard;
        let mut heard = heard.lock().unwrap();
        loop {
            heard.scan();
            if let Some(zero) = heard.zero()
                && heard.rises.len() >= count
            {
                let clicks: Vec<Instant> =
                    heard.rises[heard.rises.len() - count..].iter().map(|rise| zero + after(*rise)).collect();
                let recorded = zero + after(heard.samples.len());
                if recorded >= clicks[count - 1].max(last) + Duration::from_millis(300) {
                    let loudest = heard.samples.iter().fold(0.0f32, |loudest, sample| loudest.max(sample.abs()));
                    eprintln!(
                        "recorded {:.2} s, loudest {loudest:.3}, {} timing answers, {} rises",
                        heard.samples.len() as f64 / f64::from(RATE),
                        heard.zeros.len(),
                        heard.rises.len()
                    );
                    return clicks;
                }
            }
            let now = Instant::now();
            assert!(
                now < deadline,
                "{count} clicks were not heard within {within:?}: recorded {:.2} s, clicks at samples {:?}, {} timing answers",
                heard.samples.len() as f64 / f64::from(RATE),
                heard.rises,
                heard.zeros.len()
            );
            heard = more.wait_timeout(heard, (deadline - now).min(Duration::from_millis(100))).unwrap().0;
        }
    }
}

/// A click track at the null sink's rate: a 1 ms full-scale burst at each of `at_s`, silence between.
pub fn clicks(at_s: &[f64], seconds: f64) -> Vec<f32> {
    let mut samples = vec![0.0f32; (seconds * f64::from(RATE)) as usize];
    for at in at_s {
        let start = (at * f64::from(RATE)).round() as usize;
        for (i, sample) in samples.iter_mut().skip(start).take(RATE as usize / 1000).enumerate() {
            *sample = if i % 2 == 0 { 0.9 } else { -0.9 };
        }
    }
    samples
}

/// A PLEN2 motion of `frames` frames of `transition_ms` each (the left
/// shoulder swinging), a click where each frame starts (as the firmware's
/// playback places it, in whole 32.768 ms cycles), played on the emulated
/// PLEN2 over a pty with the sound started together; measured.
pub fn measure_plen2(pulse: &Pulse, frames: usize, transition_ms: u16) -> Measured {
    use servo_studio::device::plen2::playback::{self, DEVICE_IDS, StoredMotions};
    use servo_studio::device::plen2::{Command, Plen2Handle, Plen2Options, play_motion_delay, store_commands};
    use servo_studio::project::plen2::{Frame, Joint, Motion, Plen2Project, Pose};
    use servo_studio::sim::{Plen2Sim, Plen2SimEvent, Plen2Timing};

    let frames: Vec<Frame> = (0..frames)
        .map(|k| {
            let mut pose = Pose::default();
            pose.set(Joint::ALL[0], if k % 2 == 0 { 300 } else { -300 });
            Frame::new(transition_ms, pose)
        })
        .collect();
    let motion = Motion { slot: 0, name: "show".into(), frames, loop_range: None, jump_slot: None };
    let plen2 = Plen2Project { motions: vec![motion], ..Plen2Project::default() };
    let played = playback::play(&StoredMotions::new(&plen2), 0, [0; DEVICE_IDS], 100_000);
    let starts: Vec<usize> = (0..played.frames.len())
        .filter(|&cycle| cycle == 0 || played.frames[cycle] != played.frames[cycle - 1])
        .collect();
    let cycle_s = playback::Playback::CYCLE_MS / 1000.0;
    let at: Vec<f64> = starts.iter().map(|cycle| *cycle as f64 * cycle_s).collect();
    let dir = tempfile::tempdir().unwrap();
    let sound = dir.path().join("clicks.wav");
    let seconds = played.frames.len() as f64 * cycle_s + 0.5;
    std::fs::write(&sound, servo_studio::audio::pcm16_wav(&clicks(&at, seconds), RATE, 1)).unwrap();

    let mut robot = Plen2Sim::new(Plen2Timing::default());
    robot.preload(&store_commands(&plen2));
    let sim = spawn_pty(robot, no_waker()).unwrap();
    let port = PortName::parse(&sim.port_name).unwrap();
    let settings = servo_studio::device::line_settings(servo_studio::project::Family::Plen2);
    let handle =
        Plen2Handle::over(servo_studio::link::open(&port, &settings).unwrap(), Plen2Options::default(), no_waker())
            .unwrap();
    let requester = handle.requester();
    let recorder = Recorder::start(pulse);
    let speakers = Speakers::connect_to(&pulse.socket).unwrap();
    let started = together::start(&speakers, &sound, 0.0, play_motion_delay(0, Duration::ZERO), || {
        requester.send(Command::PlayMotion { slot: 0 }).unwrap();
    })
    .unwrap();
    let deadline = Instant::now() + Duration::from_secs(30);
    let first_cycle = loop {
        match sim.events().recv_deadline(deadline) {
            Ok(LinkEvent::Driver(Plen2SimEvent::MotionStarted { first_cycle, .. })) => break first_cycle,
            Ok(_) => {}
            Err(error) => panic!("the robot never started the motion: {error}"),
        }
    };
    let steps: Vec<Instant> = at.iter().map(|s| first_cycle + Duration::from_secs_f64(*s)).collect();
    heard(&recorder, &steps, &started, seconds)
}

/// The clicks `recorder` heard, each beside its step, once every step's
/// click has been heard (waiting the show's `seconds` and a generous minute more).
fn heard(recorder: &Recorder, steps: &[Instant], started: &together::Together, seconds: f64) -> Measured {
    let last = steps[steps.len() - 1];
    let clicks = recorder.clicks(steps.len(), last, Duration::from_secs_f64(seconds + 60.0));
    let mut measured = offsets(&clicks, steps);
    measured.lead = started.moving_at - started.due_at;
    measured.sent_late = started.sent_at - started.due_at;
    measured
}

/// `later` − `earlier`, ms (negative when `later` is earlier).
fn since_ms(later: Instant, earlier: Instant) -> f64 {
    if later >= earlier { (later - earlier).as_secs_f64() * 1e3 } else { -((earlier - later).as_secs_f64() * 1e3) }
}

/// Each click's offset from its step, ms (positive: the sound late), and
/// from its place in the show (as far from the first click as its step is
/// from the first step).
fn offsets(clicks: &[Instant], steps: &[Instant]) -> Measured {
    assert_eq!(clicks.len(), steps.len(), "every click heard once: {clicks:?}");
    let offsets_ms = clicks.iter().zip(steps).map(|(click, step)| since_ms(*click, *step)).collect();
    let placed_ms =
        clicks.iter().zip(steps).map(|(click, step)| since_ms(*click, clicks[0]) - since_ms(*step, steps[0])).collect();
    Measured { offsets_ms, placed_ms, lead: Duration::ZERO, sent_late: Duration::ZERO }
}

/// What one run measured.
pub struct Measured {
    /// Each click's offset from its step's start, ms (positive: the sound late).
    pub offsets_ms: Vec<f64>,
    /// Each click's offset from its place in the show: its time from the
    /// first click less its step's from the first step, ms. An emulator
    /// starved by a loaded machine starts late, but plays its steps on
    /// their own schedule from there.
    pub placed_ms: Vec<f64>,
    /// How long before the sound's point the board's start was due (the link's delay).
    pub lead: Duration,
    /// How long after it was due the start went out.
    pub sent_late: Duration,
}

/// Plays `steps` one-second steps with a click on each, and measures.
pub fn measure_servo(pulse: &Pulse, steps: usize) -> Measured {
    measure_servo_through(pulse, steps, &Speakers::connect_to(&pulse.socket).unwrap())
}

/// Plays `steps` one-second steps with a click on each through `speakers`
/// (which must play into `pulse`), and measures.
pub fn measure_servo_through(pulse: &Pulse, steps: usize, speakers: &Speakers) -> Measured {
    let dir = tempfile::tempdir().unwrap();
    let sound = dir.path().join("clicks.wav");
    let at: Vec<f64> = (0..steps).map(|step| step as f64).collect();
    let samples = clicks(&at, steps as f64 + 0.5);
    std::fs::write(&sound, servo_studio::audio::pcm16_wav(&samples, RATE, 1)).unwrap();

    // Servo 1 swings every second, one action a step, macro 1 running them.
    let actions: Vec<Action> = (0..steps)
        .map(|step| Action {
            id: i32::try_from(step).unwrap() + 1,
            caption: format!("swing {step}"),
            steps: vec![Step::new(1, if step % 2 == 0 { 30 } else { -30 }, 100)],
        })
        .collect();
    let macros = vec![Macro {
        id: 1,
        caption: "show".into(),
        commands: actions
            .iter()
            .map(|action| {
                servo_studio::project::Command::once(servo_studio::project::Run::Action { action_id: action.id })
            })
            .collect(),
    }];
    let project = ServoProject { servos: vec![Servo::new(1, "arm")], actions, macros, ..ServoProject::default() };
    let board = ServoSim::new(SimConfig::default(), ServoImage::from_project(&project).unwrap());
    let sim = spawn_pty(board, no_waker()).unwrap();
    let client = ServoBoard::connect(
        &PortName::parse(&sim.port_name).unwrap(),
        DEFAULT_BAUD,
        // A loaded machine may answer late: the test waits for the answer, the bench times it.
        SessionConfig { response_timeout: Duration::from_secs(30), ..SessionConfig::default() },
        no_waker(),
    )
    .unwrap();
    let requester = client.requester();

    let recorder = Recorder::start(pulse);
    let command = Message::ExecuteMacroRequest { macro_id: 1 }.encode().unwrap();
    let delay = together::link_delay(command.len(), DEFAULT_BAUD, Duration::ZERO);
    let mut reply = None;
    let started = together::start(speakers, &sound, 0.0, delay, || {
        reply = Some(requester.request_async(Message::ExecuteMacroRequest { macro_id: 1 }).unwrap());
    })
    .unwrap();

    // The board's steps, on its own clock.
    let deadline = Instant::now() + Duration::from_secs(30);
    let board_steps = loop {
        match sim.events().recv_deadline(deadline) {
            Ok(LinkEvent::Driver(SimEvent::MacroSteps { steps, .. })) => break steps,
            Ok(_) => {}
            Err(error) => panic!("the board never started the macro: {error}"),
        }
    };
    assert_eq!(board_steps.len(), steps);
    let answered = reply.expect("the start was sent").recv_timeout(Duration::from_secs(30)).unwrap().unwrap();
    assert_eq!(answered, Message::ExecuteMacroResponse { ok: true });
    let since = since_ms;
    eprintln!(
        "sent {:.2} ms before the sound's point; the board started {:.2} ms after it was sent",
        since(started.moving_at, started.sent_at),
        since(board_steps[0], started.sent_at)
    );
    let measured = heard(&recorder, &board_steps, &started, steps as f64 + 0.5);
    eprintln!(
        "the first click came {:.2} ms after the sound said it would",
        since(board_steps[0], started.moving_at) + measured.offsets_ms[0]
    );
    measured
}

/// Clicks a second apart, one a servo board step.
pub const SERVO_STEPS: usize = 10;

/// The servo board's start was due the link's delay before the sound's point
/// and every click fell on its own step; the worst offset, ms.
pub fn the_servo_board_started_with_the_sound(measured: &Measured) -> f64 {
    let command = Message::ExecuteMacroRequest { macro_id: 1 }.encode().unwrap();
    assert_eq!(measured.lead, together::link_delay(command.len(), DEFAULT_BAUD, Duration::ZERO), "the lead");
    every_click_on_its_step(measured, 1000.0)
}

/// Each click at its step's place in the show, nearer it than the next
/// step's or the one before (`spacing_ms` apart); the worst offset from its step, ms.
pub fn every_click_on_its_step(measured: &Measured, spacing_ms: f64) -> f64 {
    for (step, placed) in measured.placed_ms.iter().enumerate() {
        assert!(
            placed.abs() < spacing_ms / 2.0,
            "step {step}: the click is {placed:.2} ms from its step's place in the show (all: {:?})",
            measured.placed_ms
        );
    }
    let worst = measured.offsets_ms.iter().fold(0.0f64, |worst, offset| worst.max(offset.abs()));
    eprintln!(
        "sync over {} steps: worst {worst:.2} ms; the start went out {:.2} ms after it was due",
        measured.offsets_ms.len(),
        measured.sent_late.as_secs_f64() * 1e3
    );
    worst
}
