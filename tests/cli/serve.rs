//! `servo-studio serve`: remote control of a show's devices (a servo board,
//! a PLEN2 and an rFLEX base on three emulators, each logging what it
//! receives) through a real HTTP client (`ureq`) and real OSC datagrams
//! (`rosc`): every verb reaches its board; bad requests are answered with
//! where they went wrong; the token rules off loopback; a base stops and
//! brakes once its heartbeats stop; a flood is refused while STOP is served;
//! a signal stops every device and exits 143.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::io::{BufRead, BufReader};
use std::net::UdpSocket;
use std::process::{Child, Command as Process, Stdio};
use std::time::Duration;

use rosc::{OscMessage, OscPacket, OscType};
use serde_json::Value;
use servo_studio::project::{Family, Project};
use servo_studio::show::{Show, Start};

use super::play::{Stage, device, logged_until, swinging, waving};
use crate::common;

const EXE: &str = env!("CARGO_BIN_EXE_servo-studio");
const LONG: Duration = Duration::from_secs(30);

/// A skull swinging (servo 1 limited to ±60°), a PLEN2 waving in slot 2, a base.
pub(super) fn three_devices() -> Show {
    let mut skull = swinging(400);
    skull.servo.servos[0].min_deg = -60;
    skull.servo.servos[0].max_deg = 60;
    Show {
        devices: vec![device("skull", skull), device("plen", waving()), device("base", Project::empty(Family::Rflex))],
        sound: None,
        cues: vec![servo_studio::show::Cue { device: "skull".into(), at_ms: 0, start: Start::Macro(1) }],
    }
}

pub(super) struct Served {
    pub(super) child: Child,
    pub(super) url: String,
    pub(super) osc: Option<String>,
}

impl Drop for Served {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// `serve` on the stage's emulators with `more` options; its URL once it listens.
pub(super) fn serve(stage: &Stage, more: &[&str]) -> Served {
    let mut args = vec!["serve".to_string(), stage.dir.path().join("show.json").to_str().unwrap().to_string()];
    args.extend(stage.device_args());
    args.extend(more.iter().map(ToString::to_string));
    let mut child = Process::new(EXE)
        .args(&args)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut lines = BufReader::new(child.stdout.take().unwrap()).lines();
    let (mut url, mut osc) = (None, None);
    while url.is_none() || (more.contains(&"--osc") && osc.is_none()) {
        let line = lines.next().expect("serve printed where it listens").unwrap();
        if let Some(rest) = line.strip_prefix("listening on ") {
            url = Some(rest.split_whitespace().next().unwrap().to_string());
        }
        if let Some(rest) = line.strip_prefix("OSC on udp://") {
            osc = Some(rest.trim().to_string());
        }
    }
    // What it says from now on is not read: it is drained so that it never blocks.
    std::thread::spawn(move || lines.for_each(drop));
    Served { child, url: url.unwrap(), osc }
}

fn agent() -> ureq::Agent {
    ureq::Agent::config_builder().http_status_as_error(false).build().into()
}

/// A request's status and JSON body.
pub(super) fn ask(method: &str, url: &str, body: Option<&str>, headers: &[(&str, &str)]) -> (u16, Value) {
    let agent = agent();
    let mut response = if method == "GET" {
        let mut request = agent.get(url);
        for (name, value) in headers {
            request = request.header(*name, *value);
        }
        request.call().unwrap()
    } else {
        let mut request = agent.post(url);
        for (name, value) in headers {
            request = request.header(*name, *value);
        }
        match body {
            Some(body) => request.header("Content-Type", "application/json").send(body).unwrap(),
            None => request.send_empty().unwrap(),
        }
    };
    let status = response.status().as_u16();
    let text = response.body_mut().read_to_string().unwrap();
    (status, serde_json::from_str(&text).unwrap_or(Value::String(text)))
}

pub(super) fn post(served: &Served, path: &str, body: Option<&str>) -> (u16, Value) {
    ask("POST", &format!("{}{path}", served.url), body, &[])
}

#[test]
fn every_verb_reaches_its_board_over_http_and_bad_requests_say_where() {
    let stage = Stage::new(&three_devices(), &[]);
    let served = serve(&stage, &["--listen", "127.0.0.1:0"]);
    let (code, listed) = ask("GET", &format!("{}/devices", served.url), None, &[]);
    assert_eq!(code, 200);
    let names: Vec<&str> = listed["devices"].as_array().unwrap().iter().map(|d| d["name"].as_str().unwrap()).collect();
    assert_eq!(names, ["skull", "plen", "base"]);
    assert_eq!(listed["devices"][1]["motions"][0]["name"], "wave");
    // Play: a macro by caption, a motion by name; a second play on a busy device is refused.
    assert_eq!(post(&served, "/devices/skull/play", Some(r#"{"what": "show"}"#)).0, 200);
    logged_until(stage.log("skull"), "ExecuteMacroRequest", LONG);
    let (code, said) = post(&served, "/devices/skull/play", Some(r#"{"what": "1"}"#));
    assert_eq!(code, 409, "{said}");
    assert_eq!(post(&served, "/devices/plen/play", Some(r#"{"what": "wave"}"#)).0, 200);
    logged_until(stage.log("plen"), "$PM", LONG);
    // A pose beyond the servo's limit takes the limit, at the live speed.
    let (code, posed) = post(&served, "/devices/skull/pose", Some(r#"{"axis": "1", "value": 500}"#));
    assert_eq!((code, posed["value"].as_f64()), (200, Some(60.0)), "{posed}");
    logged_until(stage.log("skull"), "degree: 60", LONG);
    let (code, posed) = post(&served, "/devices/plen/pose", Some(r#"{"axis": "left_shoulder_pitch", "value": 15}"#));
    assert_eq!((code, posed["value"].as_f64()), (200, Some(15.0)), "{posed}");
    logged_until(stage.log("plen"), "$AN", LONG);
    // The status says what plays; its stream says it as events.
    let (_, status) = ask("GET", &format!("{}/status", served.url), None, &[]);
    assert!(status["devices"][0]["playing"].as_str().unwrap().contains("macro 1"), "{status}");
    let mut events = agent().get(&format!("{}/events", served.url)).call().unwrap();
    let mut first = String::new();
    BufReader::new(events.body_mut().as_reader()).read_line(&mut first).unwrap();
    assert_eq!(first.trim(), "event: status");
    // Bad requests: where they went wrong.
    let (code, said) = post(&served, "/devices/skull/pose", Some(r#"{"axis": "1", "value": }"#));
    assert!(code == 400 && said["error"].as_str().unwrap().contains("line 1 column"), "{said}");
    assert_eq!(post(&served, "/devices/nobody/stop", None).0, 404);
    assert_eq!(post(&served, "/devices/skull/play", Some(r#"{"what": "nothing"}"#)).0, 404);
    let (code, _) = ask("POST", &format!("{}/stop", served.url), None, &[("Origin", "https://evil.example")]);
    assert_eq!(code, 403, "another site's page may not drive the robot");
    let plain = agent().post(&format!("{}/devices/skull/play", served.url)).header("Content-Type", "text/plain");
    assert_eq!(plain.send("what=show").unwrap().status().as_u16(), 415);
    let huge = format!(r#"{{"what": "{}"}}"#, "x".repeat(70_000));
    assert_eq!(post(&served, "/devices/skull/play", Some(&huge)).0, 413);
    // STOP: every device.
    assert_eq!(post(&served, "/stop", None).0, 200);
    logged_until(stage.log("skull"), "is_start: false", LONG);
    logged_until(stage.log("plen"), "#RI", LONG);
    logged_until(stage.log("base"), "BrakeSet", LONG);
}

#[test]
fn a_driven_base_stops_and_brakes_once_its_heartbeats_stop() {
    let stage = Stage::new(&three_devices(), &[]);
    let served = serve(&stage, &["--listen", "127.0.0.1:0"]);
    let braked_before = count(&stage, "base", "BrakeSet");
    assert_eq!(post(&served, "/devices/base/heartbeat", None).0, 422, "nothing to keep driving yet");
    assert_eq!(post(&served, "/devices/base/drive", Some(r#"{"speed_m_s": 0.1, "turn_deg_s": 5}"#)).0, 200);
    let driving = logged_until(stage.log("base"), "AxisSetDir { axis: 0, speed: 1", LONG);
    let started = driving.iter().rev().find(|(_, line)| line.contains("BrakeRelease")).map(|(ns, _)| *ns);
    assert!(started.is_some(), "the brake was let go: {driving:?}");
    // No more heartbeats: it stops and brakes on its own.
    let stopped = logged_more(&stage, "base", "BrakeSet", braked_before);
    let (_, status) = ask("GET", &format!("{}/status", served.url), None, &[]);
    assert_eq!(status["devices"][2]["driven"], false, "{status}");
    let braked = stopped.iter().rfind(|(_, line)| line.contains("BrakeSet")).unwrap().0;
    eprintln!("the base braked {:.0} ms after its drive", (braked - started.unwrap()) as f64 / 1e6);
    assert_eq!(post(&served, "/devices/skull/drive", Some(r#"{"speed_m_s": 0.1}"#)).0, 422, "only a base is driven");
}

pub(super) fn count(stage: &Stage, name: &str, wanted: &str) -> usize {
    std::fs::read_to_string(stage.log(name)).unwrap_or_default().lines().filter(|l| l.contains(wanted)).count()
}

/// The log once more than `seen` lines contain `wanted`.
pub(super) fn logged_more(stage: &Stage, name: &str, wanted: &str, seen: usize) -> Vec<(u128, String)> {
    let deadline = std::time::Instant::now() + LONG;
    while count(stage, name, wanted) <= seen {
        assert!(std::time::Instant::now() < deadline, "{name} never logged {wanted:?} again");
        std::thread::yield_now();
    }
    logged_until(stage.log(name), wanted, LONG)
}

#[test]
fn off_loopback_every_request_needs_the_token_and_a_flood_still_lets_stop_through() {
    let stage = Stage::new(&three_devices(), &[]);
    let refused = Process::new(EXE)
        .args(["serve", stage.dir.path().join("show.json").to_str().unwrap(), "--listen", "0.0.0.0:0"])
        .output()
        .unwrap();
    assert!(!refused.status.success());
    assert!(String::from_utf8_lossy(&refused.stderr).contains("--token-file"));
    let token_file = stage.dir.path().join("token");
    std::fs::write(&token_file, "correct-horse-battery-staple\n").unwrap();
    let served = serve(&stage, &["--listen", "0.0.0.0:0", "--token-file", token_file.to_str().unwrap(), "--osc", "0"]);
    let url = served.url.replace("0.0.0.0", "127.0.0.1");
    let bearer = [("Authorization", "Bearer correct-horse-battery-staple")];
    assert_eq!(ask("POST", &format!("{url}/stop"), None, &[]).0, 401, "STOP too needs the token");
    assert_eq!(ask("GET", &format!("{url}/devices"), None, &[("Authorization", "Bearer wrong")]).0, 401);
    assert_eq!(ask("GET", &format!("{url}/devices"), None, &bearer).0, 200);
    // OSC: the token first, or 401.
    let osc = served.osc.clone().unwrap().replace("0.0.0.0", "127.0.0.1");
    assert_eq!(osc_ask(&osc, "/play/skull/show", vec![]).0, 401);
    let token = OscType::String("correct-horse-battery-staple".into());
    assert_eq!(osc_ask(&osc, "/play/skull/show", vec![token.clone()]).0, 200);
    // A flood from four clients, each on a keep-alive connection, each asking
    // until it is refused with 429 (its own 100 a second), while a STOP in its midst is served.
    let flood: Vec<_> = (0..4)
        .map(|_| {
            let url = url.clone();
            std::thread::spawn(move || {
                let agent = agent();
                (0..10_000)
                    .map(|_| {
                        let request = agent.get(&format!("{url}/status"));
                        let mut response =
                            request.header("Authorization", "Bearer correct-horse-battery-staple").call().unwrap();
                        let _ = response.body_mut().read_to_string();
                        response.status().as_u16()
                    })
                    .find(|code| *code == 429)
                    .is_some()
            })
        })
        .collect();
    let stops = count(&stage, "skull", "is_start: false");
    assert_eq!(ask("POST", &format!("{url}/stop"), None, &bearer).0, 200, "STOP is never refused");
    let refused = flood.into_iter().map(|thread| thread.join().unwrap()).filter(|refused| *refused).count();
    assert_eq!(refused, 4, "each flooding client was refused once past its rate");
    logged_more(&stage, "skull", "is_start: false", stops);
    // A signal: every device stopped, 143.
    let braked = count(&stage, "base", "BrakeSet");
    let mut served = served;
    Process::new("kill").args(["-TERM", &served.child.id().to_string()]).status().unwrap();
    let child = std::mem::replace(&mut served.child, Process::new("true").spawn().unwrap());
    let (code, stderr) = common::ended(child, LONG);
    assert_eq!(code, Some(143), "{stderr}");
    assert!(count(&stage, "base", "BrakeSet") > braked, "the base braked before the exit");
}

/// Sends one OSC message and takes its `/reply i s`: the code and what it said.
pub(super) fn osc_ask(to: &str, addr: &str, args: Vec<OscType>) -> (i32, String) {
    let socket = UdpSocket::bind("127.0.0.1:0").unwrap();
    socket.set_read_timeout(Some(LONG)).unwrap();
    let packet = rosc::encoder::encode(&OscPacket::Message(OscMessage { addr: addr.into(), args })).unwrap();
    socket.send_to(&packet, to).unwrap();
    osc_reply(&socket)
}

pub(super) fn osc_reply(socket: &UdpSocket) -> (i32, String) {
    let mut buffer = [0; 65_536];
    let (length, _) = socket.recv_from(&mut buffer).unwrap();
    let (_, packet) = rosc::decoder::decode_udp(&buffer[..length]).unwrap();
    let OscPacket::Message(message) = packet else { panic!("a bundle came back") };
    match message.args.as_slice() {
        [OscType::Int(code), OscType::String(said)] => (*code, said.clone()),
        other => panic!("not a reply: {other:?}"),
    }
}

#[test]
fn osc_plays_poses_and_stops_as_qlab_sends_it_and_garbage_is_answered_400() {
    let stage = Stage::new(&three_devices(), &[]);
    let served = serve(&stage, &["--listen", "127.0.0.1:0", "--osc", "0"]);
    let osc = served.osc.clone().unwrap();
    assert_eq!(osc_ask(&osc, "/play/plen/wave", vec![]).0, 200);
    logged_until(stage.log("plen"), "$PM", LONG);
    let (code, said) = osc_ask(&osc, "/pose/skull/arm", vec![OscType::Float(-20.0)]);
    assert_eq!(code, 200, "{said}");
    logged_until(stage.log("skull"), "degree: -20", LONG);
    assert_eq!(osc_ask(&osc, "/pose/skull/arm", vec![OscType::String("up".into())]).0, 400);
    assert_eq!(osc_ask(&osc, "/dance", vec![]).0, 404);
    let socket = UdpSocket::bind("127.0.0.1:0").unwrap();
    socket.set_read_timeout(Some(LONG)).unwrap();
    socket.send_to(b"\x00\x01garbage", &osc).unwrap();
    assert_eq!(osc_reply(&socket).0, 400);
    assert_eq!(osc_ask(&osc, "/stop", vec![]).0, 200);
    logged_until(stage.log("skull"), "is_start: false", LONG);
    drop(served);
}

#[test]
fn with_queue_a_second_play_waits_its_turn_and_the_whole_show_plays_once_at_a_time() {
    let stage = Stage::new(&three_devices(), &[]);
    let served = serve(&stage, &["--listen", "127.0.0.1:0", "--queue"]);
    assert_eq!(post(&served, "/devices/skull/play", Some(r#"{"what": "show"}"#)).1["as"], "started");
    let (code, queued) = post(&served, "/devices/skull/play", Some(r#"{"what": "show"}"#));
    assert_eq!((code, queued["as"].as_str()), (200, Some("queued")), "{queued}");
    let (_, status) = ask("GET", &format!("{}/status", served.url), None, &[]);
    assert_eq!(status["devices"][0]["queued"][0], "macro 1 show", "{status}");
    assert_eq!(post(&served, "/stop", None).0, 200);
    logged_until(stage.log("skull"), "is_start: false", LONG);
    // The whole show, on its boards; asked again while it plays: 409.
    let starts = count(&stage, "skull", "ExecuteMacroRequest");
    assert_eq!(post(&served, "/show/play", None).0, 200);
    let deadline = std::time::Instant::now() + LONG;
    // (Asked as fast as it answers: a 429 now and then is not a "no".)
    while ask("GET", &format!("{}/status", served.url), None, &[]).1["show_playing"].as_bool() != Some(true) {
        assert!(std::time::Instant::now() < deadline, "the show never began");
        std::thread::yield_now();
    }
    assert_eq!(post(&served, "/show/play", None).0, 409, "one show at a time");
    let (code, said) = post(&served, "/devices/plen/play", Some(r#"{"what": "wave"}"#));
    assert!(code == 409 && said["error"].as_str().unwrap().contains("the show is playing"), "{said}");
    logged_more(&stage, "skull", "ExecuteMacroRequest", starts);
    assert_eq!(post(&served, "/stop", None).0, 200, "STOP ends the show too");
}
