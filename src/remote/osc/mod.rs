//! The OSC side of remote control: UDP messages as QLab, TouchDesigner and
//! Companion send them — `/play/<device>/<what>`, `/stop`, `/stop/<device>`,
//! `/pose/<device>/<axis> f`, `/drive/<device> f f`, `/heartbeat/<device>`,
//! `/show/play` — each answered to its sender with `/reply i s` (the HTTP
//! status code and the JSON said). With a token (needed off loopback) the
//! token is every message's first argument, and it is checked before
//! anything else is done with the message. Bundles are taken message by
//! message, in order.
//!
//! A datagram's shape is bounded before it is decoded (`shape`: nesting,
//! message count), the decoder runs contained (a panic in it is a 400, never
//! the server's end), and each datagram is taken on a task of its own:
//! STOP is carried out at once, what waits for the boards' worker shares the
//! HTTP side's bound.

mod shape;

use rosc::{OscMessage, OscPacket, OscType};
use std::net::SocketAddr;
use std::sync::Arc;
use tokio::sync::Semaphore;

pub use self::shape::{MOST_MESSAGES, MOST_NESTING, Misshapen};
use super::guard::{Guard, Rate};
use super::running::{Running, WAITING_FOR_BOARDS};
use super::verbs::{self, Arg, Verb};
use super::{Remote, Reply};

/// The largest datagram taken (UDP's own limit is just under it).
const MOST_PACKET: usize = 64 * 1024;

/// An OSC listener, until dropped.
pub struct OscServer {
    addr: SocketAddr,
    _running: Running,
}

impl std::fmt::Debug for OscServer {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("OscServer").field("addr", &self.addr).finish_non_exhaustive()
    }
}

impl OscServer {
    /// Listens on `listen` (UDP; port 0: any free one) and serves `remote` under `guard`.
    pub fn start(listen: SocketAddr, remote: &Arc<Remote>, guard: &Arc<Guard>) -> std::io::Result<Self> {
        let socket = std::net::UdpSocket::bind(listen)?;
        socket.set_nonblocking(true)?;
        let addr = socket.local_addr()?;
        let runtime = super::running::runtime("remote osc")?;
        let socket = {
            let _entered = runtime.enter();
            Arc::new(tokio::net::UdpSocket::from_std(socket)?)
        };
        let running = Running::spawn("remote osc", runtime, listen_on(socket, Arc::clone(remote), Arc::clone(guard)))?;
        Ok(Self { addr, _running: running })
    }

    /// Where it listens.
    pub fn addr(&self) -> SocketAddr {
        self.addr
    }
}

/// Takes datagrams until the server ends, each on a task of its own.
async fn listen_on(socket: Arc<tokio::net::UdpSocket>, remote: Arc<Remote>, guard: Arc<Guard>) {
    let waiting = Arc::new(Semaphore::new(WAITING_FOR_BOARDS));
    let mut senders = Senders::default();
    let mut buffer = vec![0; MOST_PACKET];
    loop {
        let Ok((length, from)) = socket.recv_from(&mut buffer).await else { continue };
        let messages = match read(&buffer[..length], &guard, senders.rate(from)) {
            Ok(messages) => messages,
            Err(reply) => {
                let _ = socket.send_to(&encoded(&reply), from).await;
                continue;
            }
        };
        let (socket, remote, waiting) = (Arc::clone(&socket), Arc::clone(&remote), Arc::clone(&waiting));
        tokio::spawn(async move {
            for message in messages {
                let reply = match message {
                    Ok(verb) => super::http::carried(&remote, &waiting, verb).await,
                    Err(reply) => reply,
                };
                let _ = socket.send_to(&encoded(&reply), from).await;
            }
        });
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

/// The most senders whose rates are remembered (the one heard from longest ago goes).
const MOST_SENDERS: usize = 1024;

/// Each sender's rate, the newest [`MOST_SENDERS`] of them.
#[derive(Default)]
struct Senders {
    rates: std::collections::HashMap<SocketAddr, (Rate, u64)>,
    heard: u64,
}

impl Senders {
    /// The rate of `from`, remembered from now (a new sender starts with a full burst).
    fn rate(&mut self, from: SocketAddr) -> &mut Rate {
        self.heard += 1;
        if self.rates.len() >= MOST_SENDERS && !self.rates.contains_key(&from) {
            let oldest = self.rates.iter().min_by_key(|(_, (_, heard))| *heard).map(|(sender, _)| *sender);
            if let Some(oldest) = oldest {
                self.rates.remove(&oldest);
            }
        }
        let (rate, heard) = self.rates.entry(from).or_insert_with(|| (Rate::client(), 0));
        *heard = self.heard;
        rate
    }
}

/// A datagram read: each message's verb (or why it is refused), in order;
/// or one refusal for the whole datagram (not OSC, misshapen).
fn read(packet: &[u8], guard: &Guard, rate: &mut Rate) -> Result<Vec<Result<Verb, Reply>>, Reply> {
    shape::check(packet).map_err(|misshapen| Reply::error(400, misshapen.to_string()))?;
    // Bounded by its shape; a panic inside the decoder all the same is a refusal, not the server's end.
    let decoded = std::panic::catch_unwind(|| rosc::decoder::decode_udp(packet))
        .map_err(|_| Reply::error(400, "not an OSC packet: the decoder could not read it"))?;
    let (_, packet) = decoded.map_err(|error| Reply::error(400, format!("not an OSC packet: {error}")))?;
    let mut messages = Vec::new();
    flatten(packet, &mut messages);
    Ok(messages.iter().map(|message| verb(message, guard, rate)).collect())
}

/// Every reply to one datagram (a bundle: one per message), carried out here and now.
#[cfg(test)]
pub(super) fn take(packet: &[u8], remote: &Remote, guard: &Guard) -> Vec<Reply> {
    match read(packet, guard, &mut Rate::client()) {
        Ok(messages) => {
            messages.into_iter().map(|message| message.map_or_else(|reply| reply, |verb| remote.act(&verb))).collect()
        }
        Err(reply) => vec![reply],
    }
}

/// The messages of a packet, bundles opened in order (their depth is bounded by `shape`).
fn flatten(packet: OscPacket, into: &mut Vec<OscMessage>) {
    let mut pending = vec![packet];
    while let Some(packet) = pending.pop() {
        match packet {
            OscPacket::Message(message) => into.push(message),
            OscPacket::Bundle(bundle) => pending.extend(bundle.content.into_iter().rev()),
        }
    }
}

/// One message as a verb: the token first (401 without it), then its address and arguments, then the rate.
fn verb(message: &OscMessage, guard: &Guard, rate: &mut Rate) -> Result<Verb, Reply> {
    let mut args: &[OscType] = &message.args;
    if guard.needs_token() {
        let given = match args.first() {
            Some(OscType::String(token)) => Some(token.as_str()),
            _ => None,
        };
        if !guard.token_ok(given) {
            return Err(Reply::error(401, "the token must be the first argument"));
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
        Err(bad) => Err(Reply::error(bad.code, bad.said)),
        Ok(verb) if !guard.admit(rate, verb.stops(), verb.reaches_the_boards()) => {
            Err(Reply::error(429, "too many messages a second: slow down"))
        }
        Ok(verb) => Ok(verb),
    }
}
