//! The OSC side of remote control: UDP messages as QLab, TouchDesigner and
//! Companion send them — `/play/<device>/<what>`, `/stop`, `/stop/<device>`,
//! `/pose/<device>/<axis> f`, `/drive/<device> f f`, `/heartbeat/<device>`,
//! `/show/play` — each answered to its sender with `/reply i s` (the HTTP
//! status code and the JSON said). With a token (needed off loopback) the
//! token is every message's first argument. Bundles are taken message by
//! message; a packet that is not OSC is answered 400.

use std::net::{SocketAddr, UdpSocket};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use rosc::{OscMessage, OscPacket, OscType};

use super::guard::Guard;
use super::verbs::{self, Arg};
use super::{Remote, Reply};

/// The largest datagram taken.
const MOST_PACKET: usize = 64 * 1024;
/// How often the listener looks whether it should end.
const LOOK_EVERY: Duration = Duration::from_millis(100);

/// An OSC listener, until dropped.
pub struct OscServer {
    addr: SocketAddr,
    done: Arc<AtomicBool>,
    thread: Option<std::thread::JoinHandle<()>>,
}

impl std::fmt::Debug for OscServer {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("OscServer").field("addr", &self.addr).finish_non_exhaustive()
    }
}

impl OscServer {
    /// Listens on `listen` (UDP; port 0: any free one) and serves `remote` under `guard`.
    pub fn start(listen: SocketAddr, remote: &Arc<Remote>, guard: &Arc<Guard>) -> std::io::Result<Self> {
        let socket = UdpSocket::bind(listen)?;
        socket.set_read_timeout(Some(LOOK_EVERY))?;
        let addr = socket.local_addr()?;
        let done = Arc::new(AtomicBool::new(false));
        let ended = Arc::clone(&done);
        let (remote, guard) = (Arc::clone(remote), Arc::clone(guard));
        let thread = std::thread::Builder::new().name("remote osc".into()).spawn(move || {
            let mut buffer = vec![0; MOST_PACKET];
            while !ended.load(Ordering::SeqCst) {
                let Ok((length, from)) = socket.recv_from(&mut buffer) else { continue };
                for reply in take(&buffer[..length], &remote, &guard) {
                    let _ = socket.send_to(&encoded(&reply), from);
                }
            }
        })?;
        Ok(Self { addr, done, thread: Some(thread) })
    }

    /// Where it listens.
    pub fn addr(&self) -> SocketAddr {
        self.addr
    }
}

impl Drop for OscServer {
    fn drop(&mut self) {
        self.done.store(true, Ordering::SeqCst);
        if let Some(thread) = self.thread.take() {
            let _ = thread.join();
        }
    }
}

/// A reply as `/reply i s`.
fn encoded(reply: &Reply) -> Vec<u8> {
    let message = OscMessage {
        addr: "/reply".into(),
        args: vec![OscType::Int(i32::from(reply.code)), OscType::String(reply.body.to_string())],
    };
    rosc::encoder::encode(&OscPacket::Message(message)).unwrap_or_default()
}

/// Every reply to one datagram (a bundle: one per message).
pub fn take(packet: &[u8], remote: &Remote, guard: &Guard) -> Vec<Reply> {
    match rosc::decoder::decode_udp(packet) {
        Ok((_, packet)) => {
            let mut messages = Vec::new();
            flatten(packet, &mut messages, 0);
            messages.iter().map(|message| one(message, remote, guard)).collect()
        }
        Err(error) => vec![Reply::error(400, format!("not an OSC packet: {error}"))],
    }
}

/// The messages of a packet, bundles opened (nested at most 8 deep).
fn flatten(packet: OscPacket, into: &mut Vec<OscMessage>, depth: usize) {
    match packet {
        OscPacket::Message(message) => into.push(message),
        OscPacket::Bundle(bundle) if depth < 8 => {
            for inner in bundle.content {
                flatten(inner, into, depth + 1);
            }
        }
        OscPacket::Bundle(_) => {}
    }
}

fn one(message: &OscMessage, remote: &Remote, guard: &Guard) -> Reply {
    let mut args: &[OscType] = &message.args;
    if guard.needs_token() {
        let given = match args.first() {
            Some(OscType::String(token)) => Some(token.as_str()),
            _ => None,
        };
        if !guard.token_ok(given) {
            return Reply::error(401, format!("{}: the token must be the first argument", message.addr));
        }
        args = &args[1..];
    }
    let args: Vec<Arg> = args
        .iter()
        .map(|arg| match arg {
            OscType::Int(value) => Arg::Number(f64::from(*value)),
            OscType::Float(value) => Arg::Number(f64::from(*value)),
            OscType::Double(value) => Arg::Number(*value),
            // An OSC long: a number of a few digits here.
            #[allow(clippy::cast_precision_loss)]
            OscType::Long(value) => Arg::Number(*value as f64),
            OscType::String(text) => Arg::Text(text.clone()),
            other => Arg::Text(format!("{other:?}")),
        })
        .collect();
    match verbs::from_osc(&message.addr, &args) {
        Err(bad) => Reply::error(bad.code, bad.said),
        Ok(verb) if !guard.admit(verb.stops()) => Reply::error(429, "too many messages a second: slow down"),
        Ok(verb) => remote.act(&verb),
    }
}
