//! `servo-studio serve` against hostile and careless clients, through raw
//! sockets and raw UDP, on three emulators logging what they receive: huge
//! announced bodies, oversized headers, stalled bodies, a client that
//! pipelines and never reads, hundreds of idle and half-sent connections,
//! bursts of keep-alive STOPs, OSC datagrams built to exhaust the decoder, a
//! token file that is a pipe or a device, a drive far past the base's
//! limits, heartbeats at exactly 5 Hz, and status streams that vanish or
//! never read. Every case ends with STOP served and reaching the boards.
//! How fast STOP is answered under such load is a figure (printed here, and
//! by `benches/soak.rs`), not a verdict: the verdict is that it is answered
//! while the hostile clients still hold their connections.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::io::{BufRead, BufReader, ErrorKind, Read, Write};
use std::net::{TcpStream, UdpSocket};
use std::process::Command as Process;
use std::time::{Duration, Instant};

use super::play::{Stage, logged_until};
use super::serve::{Served, ask, count, logged_more, osc_ask, osc_reply, post, serve, three_devices};
use crate::common;

const EXE: &str = env!("CARGO_BIN_EXE_servo-studio");
const LONG: Duration = Duration::from_secs(30);

fn address(served: &Served) -> String {
    served.url.trim_start_matches("http://").to_string()
}

fn connect(served: &Served) -> TcpStream {
    let stream = TcpStream::connect(address(served)).unwrap();
    stream.set_read_timeout(Some(LONG)).unwrap();
    stream.set_write_timeout(Some(LONG)).unwrap();
    stream
}

/// The status code of the next answer on `stream`: its status line, read a
/// byte at a time so that nothing after it is taken from the stream.
fn status(mut stream: &TcpStream) -> u16 {
    let mut line = Vec::new();
    let mut byte = [0; 1];
    while !line.ends_with(b"\r\n") && stream.read(&mut byte).unwrap() == 1 {
        line.push(byte[0]);
    }
    let line = String::from_utf8_lossy(&line);
    line.split_whitespace().nth(1).and_then(|code| code.parse().ok()).unwrap_or_else(|| panic!("no status: {line:?}"))
}

/// A whole answer: its head and body, read until the server closes.
fn whole(mut stream: &TcpStream) -> String {
    let mut text = Vec::new();
    let _ = stream.read_to_end(&mut text);
    String::from_utf8_lossy(&text).into_owned()
}

/// `POST /stop` on a new connection: its status code and how long the answer took.
fn stop(served: &Served) -> (u16, Duration) {
    let began = Instant::now();
    let mut stream = connect(served);
    stream.write_all(b"POST /stop HTTP/1.1\r\nHost: robot\r\nContent-Length: 0\r\n\r\n").unwrap();
    (status(&stream), began.elapsed())
}

/// The resident memory of a process, KiB.
fn rss_kib(pid: u32) -> u64 {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).unwrap();
    let line = status.lines().find(|line| line.starts_with("VmRSS:")).unwrap();
    line.split_whitespace().nth(1).unwrap().parse().unwrap()
}

/// Whether the server still holds `stream` open without having answered on it.
fn held_unanswered(stream: &TcpStream) -> bool {
    stream.set_nonblocking(true).unwrap();
    let mut byte = [0; 1];
    let held = matches!(stream.peek(&mut byte), Err(error) if error.kind() == ErrorKind::WouldBlock);
    stream.set_nonblocking(false).unwrap();
    held
}

#[test]
fn stop_is_served_while_clients_stall_pipeline_idle_and_burst() {
    let stage = Stage::new(&three_devices(), &[]);
    let served = serve(&stage, &["--listen", "127.0.0.1:0"]);
    // Three hundred idle connections and fifty that sent half a header, first (the quietest).
    let idle: Vec<TcpStream> = (0..300).map(|_| connect(&served)).collect();
    let half: Vec<TcpStream> = (0..50)
        .map(|_| {
            let mut stream = connect(&served);
            stream.write_all(b"POST /stop HTTP/1.1\r\nHo").unwrap();
            stream
        })
        .collect();
    // Four bodies announced and never sent whole (the four request threads of old).
    let stalled: Vec<TcpStream> = (0..4)
        .map(|_| {
            let mut stream = connect(&served);
            stream
                .write_all(b"POST /devices/skull/play HTTP/1.1\r\nHost: robot\r\nContent-Type: application/json\r\nContent-Length: 1000\r\n\r\n{\"wh")
                .unwrap();
            stream
        })
        .collect();
    // One client that pipelines requests and never reads an answer.
    let mut pipeliner = connect(&served);
    pipeliner.set_write_timeout(Some(Duration::from_secs(2))).unwrap();
    let requests = b"GET /status HTTP/1.1\r\nHost: robot\r\n\r\n".repeat(4_000);
    let _ = pipeliner.write_all(&requests);
    let before = count(&stage, "skull", "is_start: false");
    let (code, took) = stop(&served);
    assert_eq!(code, 200, "STOP is answered whatever the others do");
    let still_held = stalled.iter().filter(|stream| held_unanswered(stream)).count();
    eprintln!(
        "figure: STOP answered in {:.1} ms beside 300 idle, 50 half-sent, 4 stalled bodies ({still_held} still held) and a pipeliner",
        took.as_secs_f64() * 1000.0
    );
    if took < Duration::from_secs(4) {
        assert_eq!(still_held, 4, "STOP did not wait for the stalled bodies to be let go");
    }
    logged_more(&stage, "skull", "is_start: false", before);
    // Twenty keep-alive connections, two STOPs each, all at once: every one answered.
    let burst: Vec<_> = (0..20)
        .map(|_| {
            let mut stream = connect(&served);
            std::thread::spawn(move || {
                let mut reader = BufReader::new(stream.try_clone().unwrap());
                let mut answered = 0;
                for _ in 0..2 {
                    stream.write_all(b"POST /stop HTTP/1.1\r\nHost: robot\r\nContent-Length: 0\r\n\r\n").unwrap();
                    let mut head = String::new();
                    let mut length = 0;
                    loop {
                        let mut line = String::new();
                        reader.read_line(&mut line).unwrap();
                        if let Some(value) = line.to_ascii_lowercase().strip_prefix("content-length:") {
                            length = value.trim().parse().unwrap();
                        }
                        if line == "\r\n" {
                            break;
                        }
                        head.push_str(&line);
                    }
                    let mut body = vec![0; length];
                    reader.read_exact(&mut body).unwrap();
                    answered += usize::from(head.starts_with("HTTP/1.1 200"));
                }
                answered
            })
        })
        .collect();
    let answered: usize = burst.into_iter().map(|thread| thread.join().unwrap()).sum();
    assert_eq!(answered, 40, "every keep-alive STOP of the burst was answered");
    // The stalled bodies are answered 408 and closed once their time is up; the server is still there.
    for stream in &stalled {
        let said = whole(stream);
        assert!(said.is_empty() || said.starts_with("HTTP/1.1 408"), "{said}");
    }
    assert_eq!(stop(&served).0, 200, "still up");
    drop((idle, half, pipeliner));
}

#[test]
fn a_body_or_header_too_large_is_refused_unread_and_nothing_brings_the_server_down() {
    let stage = Stage::new(&three_devices(), &[]);
    let served = serve(&stage, &["--listen", "127.0.0.1:0"]);
    let pid = served.child.id();
    assert_eq!(stop(&served).0, 200);
    let before_kib = rss_kib(pid);
    // A body announced at 99,999,999,999,999 bytes: refused from its header alone, and the connection closed.
    let mut huge = connect(&served);
    huge.write_all(
        b"POST /devices/skull/play HTTP/1.1\r\nHost: robot\r\nContent-Type: application/json\r\nContent-Length: 99999999999999\r\n\r\n",
    )
    .unwrap();
    let said = whole(&huge);
    assert!(said.starts_with("HTTP/1.1 413") && said.contains("64 KB"), "{said}");
    assert!(said.to_ascii_lowercase().contains("connection: close"), "{said}");
    // 2^64 − 1, four times (once one per request thread): refused, never a panic.
    for _ in 0..4 {
        let mut most = connect(&served);
        most.write_all(b"POST /stop HTTP/1.1\r\nHost: robot\r\nContent-Length: 18446744073709551615\r\n\r\n").unwrap();
        // hyper refuses a length it cannot hold as a header too large.
        let code = status(&most);
        assert!(matches!(code, 400 | 413 | 431), "{code}");
    }
    assert_eq!(stop(&served).0, 200, "still up");
    // A 10 MB body really sent: answered 413 before it is read, and not kept.
    let mut sent = connect(&served);
    sent.write_all(
        b"POST /devices/skull/play HTTP/1.1\r\nHost: robot\r\nContent-Type: application/json\r\nContent-Length: 10000000\r\n\r\n",
    )
    .unwrap();
    let mut writer = sent.try_clone().unwrap();
    let writing = std::thread::spawn(move || {
        let chunk = vec![b'x'; 64 * 1024];
        let mut written = 0usize;
        while written < 10_000_000 && writer.write_all(&chunk).is_ok() {
            written += chunk.len();
        }
        written
    });
    assert_eq!(status(&sent), 413);
    let written = writing.join().unwrap();
    // A header line of 16 MiB, and one of 100 KB: 431, the connection closed.
    for size in [16 << 20, 100_000] {
        let mut big = connect(&served);
        let mut request = b"GET /status HTTP/1.1\r\nHost: robot\r\nX-Big: ".to_vec();
        request.resize(request.len() + size, b'a');
        request.extend_from_slice(b"\r\n\r\n");
        let mut writer = big.try_clone().unwrap();
        let writing = std::thread::spawn(move || writer.write_all(&request).is_ok());
        let said = whole(&big);
        assert!(said.starts_with("HTTP/1.1 431"), "a {size}-byte header line: {said:?}");
        let _ = (writing.join(), big.flush());
    }
    let after_kib = rss_kib(pid);
    eprintln!(
        "figure: serve's memory {before_kib} KiB → {after_kib} KiB after a 10 MB body ({} KB of it written before the server closed) and a 16 MiB header",
        written / 1000
    );
    assert!(after_kib < before_kib + 4 * 1024, "{before_kib} KiB → {after_kib} KiB: something was buffered");
    let (code, status) = ask("GET", &format!("{}/status", served.url), None, &[]);
    assert_eq!(code, 200, "{status}");
}

/// A bundle holding a bundle … `depth` deep, `/stop` at the bottom.
fn nested_bundles(depth: usize) -> Vec<u8> {
    let mut bytes = b"/stop\0\0\0,\0\0\0".to_vec();
    for _ in 0..depth {
        let mut outer = b"#bundle\0\0\0\0\0\0\0\0\x01".to_vec();
        outer.extend_from_slice(&i32::try_from(bytes.len()).unwrap().to_be_bytes());
        outer.extend_from_slice(&bytes);
        bytes = outer;
    }
    bytes
}

#[test]
fn osc_datagrams_built_to_exhaust_the_decoder_are_refused_and_stop_is_still_served() {
    let stage = Stage::new(&three_devices(), &[]);
    let served = serve(&stage, &["--listen", "127.0.0.1:0", "--osc", "0"]);
    let osc = served.osc.clone().unwrap();
    let socket = UdpSocket::bind("127.0.0.1:0").unwrap();
    socket.set_read_timeout(Some(LONG)).unwrap();
    let deep = nested_bundles(3_200);
    assert!(deep.len() > 64_000 && deep.len() < 65_507, "{}", deep.len());
    socket.send_to(&deep, &osc).unwrap();
    let (code, said) = osc_reply(&socket);
    assert!(code == 400 && said.contains("bundles nested deeper than 8"), "{code} {said}");
    // Arrays nested 16,000 deep in a message's type tags (no token needed here).
    let mut arrays = b"/pose/skull/arm\0,".to_vec();
    arrays.extend(std::iter::repeat_n(b'[', 16_000));
    arrays.extend(std::iter::repeat_n(b']', 16_000));
    arrays.push(0);
    arrays.resize(arrays.len().next_multiple_of(4), 0);
    socket.send_to(&arrays, &osc).unwrap();
    let (code, said) = osc_reply(&socket);
    assert!(code == 400 && said.contains("arrays nested deeper than 8"), "{code} {said}");
    // The server is there: STOP by OSC reaches the boards.
    let before = count(&stage, "skull", "is_start: false");
    assert_eq!(osc_ask(&osc, "/stop", vec![]).0, 200);
    logged_more(&stage, "skull", "is_start: false", before);
    assert_eq!(post(&served, "/stop", None).0, 200);
}

#[test]
fn a_token_file_that_is_a_pipe_a_device_or_too_large_is_refused_at_once() {
    let stage = Stage::new(&three_devices(), &[]);
    let show = stage.dir.path().join("show.json");
    let fifo = stage.dir.path().join("token.fifo");
    assert!(Process::new("mkfifo").arg(&fifo).status().unwrap().success());
    let large = stage.dir.path().join("token.large");
    std::fs::write(&large, "x".repeat(10_000)).unwrap();
    for (token, said) in
        [(fifo.to_str().unwrap(), "named pipe"), ("/dev/zero", "a device"), (large.to_str().unwrap(), "MB")]
    {
        let child = Process::new(EXE)
            .args(["serve", show.to_str().unwrap(), "--listen", "0.0.0.0:0", "--token-file", token])
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap();
        let (code, stderr) = common::ended(child, LONG);
        assert_eq!(code, Some(1), "{token}: {stderr}");
        assert!(stderr.contains("cannot read the token") && stderr.contains(said), "{token}: {stderr}");
    }
}

#[test]
fn a_drive_is_held_within_the_bases_limits_and_a_base_is_not_posed() {
    let stage = Stage::new(&three_devices(), &[]);
    let served = serve(&stage, &["--listen", "127.0.0.1:0"]);
    // 50 m/s, and 1e308: the project's 0.5 m/s (a B21r allows 1.0), said in the answer.
    for asked in ["50", "1e308"] {
        let (code, drove) = post(&served, "/devices/base/drive", Some(&format!(r#"{{"speed_m_s": {asked}}}"#)));
        assert_eq!(code, 200, "{drove}");
        assert_eq!(drove["drives"][0].as_f64(), Some(0.5), "{drove}");
        let clamped = drove["clamped"].as_str().unwrap_or_default();
        assert!(clamped.contains("at most 0.5 m/s") && clamped.contains("b21r"), "{drove}");
        assert_eq!(post(&served, "/stop", None).0, 200);
    }
    // On the wire: 0.5 m/s × 103,000 units a metre, never more.
    let lines = logged_until(stage.log("base"), "speed: 51500", LONG);
    let fastest = lines
        .iter()
        .filter_map(|(_, line)| line.split("axis: 0, speed: ").nth(1)?.split(',').next()?.parse::<u64>().ok())
        .max();
    assert_eq!(fastest, Some(51_500));
    // Within the limits: as asked, and nothing said.
    let (_, drove) = post(&served, "/devices/base/drive", Some(r#"{"speed_m_s": -0.2, "turn_deg_s": 10}"#));
    assert!(drove["clamped"].is_null() && drove["drives"][0].as_f64() == Some(-0.2), "{drove}");
    assert_eq!(post(&served, "/stop", None).0, 200);
    let (code, said) = post(&served, "/devices/base/pose", Some(r#"{"axis": "1", "value": 10}"#));
    assert!(code == 422 && said["error"].as_str().unwrap().contains("drive it"), "{said}");
}

#[test]
fn heartbeats_at_exactly_5_hz_keep_a_base_driving_and_a_late_one_is_told_what_to_send() {
    let stage = Stage::new(&three_devices(), &[]);
    let served = serve(&stage, &["--listen", "127.0.0.1:0"]);
    let (code, drove) = post(&served, "/devices/base/drive", Some(r#"{"speed_m_s": 0.1}"#));
    assert_eq!((code, drove["most_gap_ms"].as_u64()), (200, Some(300)), "{drove}");
    logged_until(stage.log("base"), "BrakeRelease", LONG);
    let braked = count(&stage, "base", "BrakeSet");
    // Fifteen heartbeats, one every 200 ms as a 5 Hz sender sends them (this pacing is the sender under test).
    let mut gaps = Vec::new();
    for _ in 0..15 {
        std::thread::sleep(Duration::from_millis(200));
        let (code, beat) = post(&served, "/devices/base/heartbeat", None);
        let gap = beat["gap_ms"].as_f64();
        match code {
            200 => gaps.push(gap.unwrap()),
            // A machine so loaded that a beat came more than 300 ms after the last: stopped, and said why.
            409 => {
                assert!(beat["error"].as_str().unwrap().contains("dead-man stopped it"), "{beat}");
                break;
            }
            _ => panic!("{code}: {beat}"),
        }
    }
    assert!(gaps.iter().all(|gap| *gap <= 300.0), "{gaps:?}");
    if gaps.len() == 15 {
        assert_eq!(count(&stage, "base", "BrakeSet"), braked, "kept driving at 5 Hz: gaps {gaps:?}");
    }
    eprintln!("figure: heartbeat gaps as the server took them in: {gaps:?} ms");
    // No more heartbeats: it stops and brakes, and a late heartbeat says what happened and what to send.
    logged_more(&stage, "base", "BrakeSet", braked);
    let (code, late) = post(&served, "/devices/base/heartbeat", None);
    let said = late["error"].as_str().unwrap_or_default();
    assert!(code == 409 && said.contains("at most 300 ms") && said.contains("until a drive is sent"), "{late}");
    let (_, status) = ask("GET", &format!("{}/status", served.url), None, &[]);
    assert_eq!(status["devices"][2]["driven"], false, "{status}");
}

/// Opens `GET /events` on a new connection: its status code (and the stream).
fn open_events(served: &Served) -> (u16, TcpStream) {
    let mut stream = connect(served);
    stream.write_all(b"GET /events HTTP/1.1\r\nHost: robot\r\nConnection: close\r\n\r\n").unwrap();
    (status(&stream), stream)
}

#[test]
fn status_streams_are_bounded_said_and_freed_as_soon_as_a_client_goes() {
    let stage = Stage::new(&three_devices(), &[]);
    let served = serve(&stage, &["--listen", "127.0.0.1:0"]);
    let mut streams: Vec<TcpStream> = (0..8)
        .map(|_| open_events(&served))
        .map(|(code, stream)| {
            assert_eq!(code, 200);
            stream
        })
        .collect();
    let (code, refused) = open_events(&served);
    assert_eq!(code, 503);
    let said = whole(&refused);
    assert!(said.contains("at most 8 status streams") && said.to_ascii_lowercase().contains("retry-after"), "{said}");
    // A client goes without a word: its slot is free the moment the server sees the connection end.
    drop(streams.remove(0));
    let deadline = Instant::now() + LONG;
    loop {
        let (code, stream) = open_events(&served);
        if code == 200 {
            streams.push(stream);
            break;
        }
        assert!(Instant::now() < deadline, "the slot was never freed");
    }
    // The streams still carry the status: a STOP is seen by a client that reads.
    assert_eq!(post(&served, "/devices/skull/play", Some(r#"{"what": "show"}"#)).0, 200);
    let mut reader = BufReader::new(streams.pop().unwrap());
    let mut seen = String::new();
    while !seen.contains("macro 1") {
        let mut line = String::new();
        reader.read_line(&mut line).unwrap();
        seen.push_str(&line);
    }
    assert_eq!(post(&served, "/stop", None).0, 200);
}
