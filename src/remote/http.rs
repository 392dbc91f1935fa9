//! The HTTP + JSON side of remote control (`docs/remote-openapi.yaml`):
//! a few threads taking requests, each checked by the [`Guard`] (token,
//! `Origin`, rate), bounded (64 KB), read into a [`Verb`] and carried out by
//! the [`Remote`]; `GET /events` streams the status as Server-Sent Events.

use std::io::{Read, Write};
use std::net::SocketAddr;
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Duration;

use serde_json::json;

use super::guard::Guard;
use super::{Remote, Reply, verbs};

/// The largest request body taken.
pub const MOST_BODY: usize = 64 * 1024;
/// How many threads take requests.
const THREADS: usize = 4;
/// How many status streams may be open at once.
const MOST_STREAMS: usize = 8;
/// How often a quiet status stream says it is still there.
const KEEP_ALIVE: Duration = Duration::from_secs(15);

/// A server taking requests until dropped.
pub struct HttpServer {
    server: Arc<tiny_http::Server>,
    threads: Vec<std::thread::JoinHandle<()>>,
    addr: SocketAddr,
}

impl std::fmt::Debug for HttpServer {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("HttpServer").field("addr", &self.addr).finish_non_exhaustive()
    }
}

impl HttpServer {
    /// Listens on `listen` (port 0: any free one) and serves `remote` under `guard`.
    pub fn start(listen: SocketAddr, remote: &Arc<Remote>, guard: &Arc<Guard>) -> std::io::Result<Self> {
        let server = Arc::new(tiny_http::Server::http(listen).map_err(std::io::Error::other)?);
        let addr = server.server_addr().to_ip().ok_or_else(|| std::io::Error::other("not an IP address"))?;
        let streams = Arc::new(AtomicUsize::new(0));
        let mut threads = Vec::new();
        for index in 0..THREADS {
            let (server, remote, guard, streams) =
                (Arc::clone(&server), Arc::clone(remote), Arc::clone(guard), Arc::clone(&streams));
            threads.push(std::thread::Builder::new().name(format!("remote http {index}")).spawn(move || {
                while let Ok(request) = server.recv() {
                    take(request, &remote, &guard, &streams);
                }
            })?);
        }
        Ok(Self { server, threads, addr })
    }

    /// Where it listens.
    pub fn addr(&self) -> SocketAddr {
        self.addr
    }
}

impl Drop for HttpServer {
    fn drop(&mut self) {
        for _ in &self.threads {
            self.server.unblock();
        }
        for thread in self.threads.drain(..) {
            let _ = thread.join();
        }
    }
}

/// A header's value.
fn header<'a>(request: &'a tiny_http::Request, name: &str) -> Option<&'a str> {
    request.headers().iter().find(|h| h.field.as_str().as_str().eq_ignore_ascii_case(name)).map(|h| h.value.as_str())
}

/// Answers one request.
fn take(mut request: tiny_http::Request, remote: &Arc<Remote>, guard: &Guard, streams: &Arc<AtomicUsize>) {
    let bearer = header(&request, "Authorization").and_then(|value| value.strip_prefix("Bearer ")).map(str::trim);
    if !guard.token_ok(bearer) {
        let reply = Reply::error(401, "a bearer token is needed: Authorization: Bearer <the token file's secret>");
        return answer(request, &reply);
    }
    if !guard.origin_ok(header(&request, "Origin")) {
        return answer(request, &Reply::error(403, "a page of another site may not drive the robot"));
    }
    let method = request.method().as_str().to_ascii_uppercase();
    let url = request.url().to_string();
    let path = url.split('?').next().unwrap_or_default();
    if method == "GET" && path.trim_end_matches('/') == "/events" {
        return stream(request, remote, streams);
    }
    let body = match body(&mut request) {
        Ok(body) => body,
        Err(reply) => return answer(request, &reply),
    };
    let reply = match verbs::from_http(&method, path, &body) {
        Err(bad) => Reply::error(bad.code, bad.said),
        Ok(verb) if !guard.admit(verb.stops()) => Reply::error(
            429,
            format!("more than {} requests a second: slow down (STOP is always served)", super::guard::RATE_PER_S),
        ),
        Ok(verb) => remote.act(&verb),
    };
    answer(request, &reply);
}

/// The request's body: at most [`MOST_BODY`], JSON when there is one.
fn body(request: &mut tiny_http::Request) -> Result<Vec<u8>, Reply> {
    if request.body_length().is_some_and(|length| length > MOST_BODY) {
        return Err(Reply::error(413, format!("the body is over {} KB", MOST_BODY / 1024)));
    }
    let json = header(request, "Content-Type").is_some_and(|kind| {
        kind.split(';').next().is_some_and(|kind| kind.trim().eq_ignore_ascii_case("application/json"))
    });
    let mut body = Vec::new();
    let read = request.as_reader().take(MOST_BODY as u64 + 1).read_to_end(&mut body);
    if read.is_err() {
        return Err(Reply::error(400, "the body could not be read"));
    }
    if body.len() > MOST_BODY {
        return Err(Reply::error(413, format!("the body is over {} KB", MOST_BODY / 1024)));
    }
    if !body.is_empty() && !json {
        return Err(Reply::error(415, "a body must be JSON: Content-Type: application/json"));
    }
    Ok(body)
}

fn answer(request: tiny_http::Request, reply: &Reply) {
    let mut response = tiny_http::Response::from_string(reply.body.to_string()).with_status_code(reply.code);
    for (name, value) in [("Content-Type", "application/json"), ("Cache-Control", "no-store")] {
        if let Ok(header) = tiny_http::Header::from_bytes(name, value) {
            response.add_header(header);
        }
    }
    if reply.code == 401
        && let Ok(header) = tiny_http::Header::from_bytes("WWW-Authenticate", "Bearer")
    {
        response.add_header(header);
    }
    let _ = request.respond(response);
}

/// `GET /events`: the status each time it changes (and a comment every
/// [`KEEP_ALIVE`]), on a thread of its own, until the client goes.
fn stream(request: tiny_http::Request, remote: &Arc<Remote>, streams: &Arc<AtomicUsize>) {
    if streams.fetch_add(1, Ordering::SeqCst) >= MOST_STREAMS {
        streams.fetch_sub(1, Ordering::SeqCst);
        return answer(request, &Reply::error(503, format!("at most {MOST_STREAMS} status streams at once")));
    }
    let remote = Arc::clone(remote);
    let open = Arc::clone(streams);
    let spawned = std::thread::Builder::new().name("remote events".into()).spawn(move || {
        // Written straight to the connection, each event flushed as it comes
        // (a response body would be held back in chunks); it ends with the connection.
        let mut writer = request.into_writer();
        let head = "HTTP/1.1 200 OK\r\nContent-Type: text/event-stream\r\nCache-Control: no-store\r\nConnection: close\r\n\r\n";
        let mut events = Events { remote, seen: None };
        let mut next = Some(head.as_bytes().to_vec());
        while let Some(bytes) = next {
            if writer.write_all(&bytes).and_then(|()| writer.flush()).is_err() {
                break;
            }
            next = events.next();
        }
        open.fetch_sub(1, Ordering::SeqCst);
    });
    if spawned.is_err() {
        // No thread: the stream never began (its request went with the closure).
        streams.fetch_sub(1, Ordering::SeqCst);
    }
}

/// The status as a stream of events.
struct Events {
    remote: Arc<Remote>,
    seen: Option<u64>,
}

impl Iterator for Events {
    type Item = Vec<u8>;

    /// The next event: the status when it changed, or a comment after a quiet
    /// [`KEEP_ALIVE`]; none once the boards are let go.
    fn next(&mut self) -> Option<Vec<u8>> {
        let mut quiet = Duration::ZERO;
        loop {
            // The boards are held only a second at a time: letting them go ends the stream soon.
            let boards = self.remote.boards()?;
            let status = match self.seen {
                None => boards.status(),
                Some(seen) => boards.status_after(seen, Duration::from_secs(1)),
            };
            if self.seen != Some(status.revision) {
                self.seen = Some(status.revision);
                return Some(format!("event: status\ndata: {}\n\n", json!(status)).into_bytes());
            }
            quiet += Duration::from_secs(1);
            if quiet >= KEEP_ALIVE {
                return Some(b": still here\n\n".to_vec());
            }
        }
    }
}
