//! The HTTP + JSON side of remote control (`docs/remote-openapi.yaml`), on
//! hyper over tokio, built to stay up and keep STOP in reach whatever
//! clients do (`docs/remote.md`, "Hostile clients"):
//! - a request's header section is at most [`MOST_HEADERS`] (else 431) and
//!   must arrive within [`HEADERS_WITHIN`]; a body over [`MOST_BODY`] is
//!   refused (413) from its `Content-Length` before a byte of it is read, and
//!   a body must arrive within [`BODY_WITHIN`] (else 408); either closes the
//!   connection;
//! - every connection is one task, none of them holds another: at most
//!   [`conns::MOST_CONNECTIONS`] are open (the next takes the place of the
//!   quietest) and one on which nothing moved for [`conns::IDLE`] is closed;
//! - STOP is carried out where it is read, never behind a queue; requests
//!   that wait for the boards' worker are at most [`WAITING_FOR_BOARDS`] at
//!   once (the next is answered 503 at once);
//! - each request is checked by the [`Guard`] (token, `Origin`, rate) and
//!   read into a [`Verb`](super::Verb) for the [`Remote`]; `GET /events`
//!   streams the status (`events`).

pub mod conns;
mod events;

use std::convert::Infallible;
use std::net::SocketAddr;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use http_body_util::{BodyExt, Either, Full, Limited};
use hyper::body::{Body as _, Bytes, Incoming};
use hyper::header::{self, HeaderMap, HeaderValue};
use hyper::{Request, Response, StatusCode};
use hyper_util::rt::{TokioIo, TokioTimer};
use tokio::sync::Semaphore;

use self::conns::{Conn, Conns};
use self::events::{EventBody, Streams};
pub use self::events::{KEEP_ALIVE, MOST_STREAMS, QUEUE_EVENTS};
use super::guard::Guard;
use super::running::Running;
pub use super::running::WAITING_FOR_BOARDS;
use super::{Remote, Reply, Verb, verbs};

/// The largest request body taken.
pub const MOST_BODY: usize = 64 * 1024;
/// The largest header section (request line and headers) taken; more is answered 431.
pub const MOST_HEADERS: usize = 16 * 1024;
/// How long a client has to send a request's headers.
pub const HEADERS_WITHIN: Duration = Duration::from_secs(5);
/// How long a client has to send a request's body once its headers came.
pub const BODY_WITHIN: Duration = Duration::from_secs(5);
/// The most bytes a connection buffers while it reads (a header section, a body's chunk).
const READ_BUFFER: usize = 32 * 1024;
/// How often each connection looks whether it has been idle too long.
const LOOK_EVERY: Duration = Duration::from_millis(500);

/// An answer's body: JSON, or a status stream.
type Body = Either<Full<Bytes>, EventBody>;

/// What every connection's task shares.
struct Served {
    remote: Arc<Remote>,
    guard: Arc<Guard>,
    conns: Arc<Conns>,
    streams: Arc<Streams>,
    waiting: Arc<Semaphore>,
}

/// A server taking requests until dropped.
pub struct HttpServer {
    addr: SocketAddr,
    /// The connections open, counted for the tests.
    #[cfg(any(test, feature = "test-api"))]
    conns: Arc<Conns>,
    streams: Arc<Streams>,
    running: Option<Running>,
    ending: Arc<AtomicBool>,
    broadcaster: Option<std::thread::JoinHandle<()>>,
}

impl std::fmt::Debug for HttpServer {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("HttpServer").field("addr", &self.addr).finish_non_exhaustive()
    }
}

impl HttpServer {
    /// Listens on `listen` (port 0: any free one) and serves `remote` under `guard`.
    pub fn start(listen: SocketAddr, remote: &Arc<Remote>, guard: &Arc<Guard>) -> std::io::Result<Self> {
        let listener = std::net::TcpListener::bind(listen)?;
        listener.set_nonblocking(true)?;
        let addr = listener.local_addr()?;
        let runtime = super::running::runtime("remote http")?;
        let listener = {
            let _entered = runtime.enter();
            tokio::net::TcpListener::from_std(listener)?
        };
        let served = Arc::new(Served {
            remote: Arc::clone(remote),
            guard: Arc::clone(guard),
            conns: Arc::new(Conns::default()),
            streams: Arc::new(Streams::default()),
            waiting: Arc::new(Semaphore::new(WAITING_FOR_BOARDS)),
        });
        #[cfg(any(test, feature = "test-api"))]
        let conns = Arc::clone(&served.conns);
        let streams = Arc::clone(&served.streams);
        let running = Running::spawn("remote http", runtime, accept(listener, served))?;
        let ending = Arc::new(AtomicBool::new(false));
        let (streaming, remote, ended) = (Arc::clone(&streams), Arc::clone(remote), Arc::clone(&ending));
        let broadcaster = std::thread::Builder::new()
            .name("remote events".into())
            .spawn(move || events::broadcast(&streaming, &remote, &ended))?;
        Ok(Self {
            addr,
            #[cfg(any(test, feature = "test-api"))]
            conns,
            streams,
            running: Some(running),
            ending,
            broadcaster: Some(broadcaster),
        })
    }

    /// Where it listens.
    pub fn addr(&self) -> SocketAddr {
        self.addr
    }

    #[cfg(any(test, feature = "test-api"))]
    /// How many connections are open now.
    pub fn connections(&self) -> usize {
        self.conns.count()
    }

    /// How many status streams are open now.
    pub fn streams(&self) -> usize {
        self.streams.open()
    }
}

impl Drop for HttpServer {
    fn drop(&mut self) {
        self.ending.store(true, Ordering::SeqCst);
        drop(self.running.take());
        if let Some(thread) = self.broadcaster.take() {
            let _ = thread.join();
        }
    }
}

/// Takes connections until the server ends, each on a task of its own.
async fn accept(listener: tokio::net::TcpListener, served: Arc<Served>) {
    let mut http = hyper::server::conn::http1::Builder::new();
    http.timer(TokioTimer::new())
        .header_read_timeout(HEADERS_WITHIN)
        .max_header_size(MOST_HEADERS)
        .max_buf_size(READ_BUFFER)
        .keep_alive(true)
        .half_close(false);
    loop {
        match listener.accept().await {
            Ok((stream, _)) => {
                conns::tune(&stream);
                let conn = served.conns.admit();
                tokio::spawn(serve(stream, conn, http.clone(), Arc::clone(&served)));
            }
            // Out of file descriptors (or a connection reset before it was
            // taken): the quietest connection is let go and the loop goes on.
            Err(_) => {
                drop(served.conns.admit());
                tokio::time::sleep(Duration::from_millis(10)).await;
            }
        }
    }
}

/// Serves one connection until it ends, is told to close, or stays idle too long.
async fn serve(
    stream: tokio::net::TcpStream,
    conn: Conn,
    http: hyper::server::conn::http1::Builder,
    served: Arc<Served>,
) {
    let io = TokioIo::new(served.conns.watched(stream, &conn));
    let (theirs, mine) = (Arc::clone(&served), conn.clone());
    let service = hyper::service::service_fn(move |request| {
        let (served, conn) = (Arc::clone(&theirs), mine.clone());
        async move { Ok::<_, Infallible>(answer(request, &served, &conn).await) }
    });
    let connection = http.serve_connection(io, service);
    tokio::pin!(connection);
    let mut look = tokio::time::interval(LOOK_EVERY);
    loop {
        tokio::select! {
            _ = connection.as_mut() => break,
            () = conn.kill.notified() => break,
            _ = look.tick() => if served.conns.idle(&conn, Instant::now()) { break },
        }
    }
    served.conns.gone(&conn);
}

/// A header's value, as text.
fn header(headers: &HeaderMap, name: header::HeaderName) -> Option<&str> {
    headers.get(name).and_then(|value| value.to_str().ok())
}

/// Answers one request.
async fn answer(request: Request<Incoming>, served: &Served, conn: &Conn) -> Response<Body> {
    // A body that is not read is never taken as the next request: the connection closes after the answer.
    let unread = !request.body().is_end_stream();
    let headers = request.headers();
    let bearer = header(headers, header::AUTHORIZATION).and_then(|value| value.strip_prefix("Bearer ")).map(str::trim);
    if !served.guard.token_ok(bearer) {
        let said = "a bearer token is needed: Authorization: Bearer <the token file's secret>";
        return respond(&Reply::error(401, said), unread);
    }
    if !served.guard.origin_ok(header(headers, header::ORIGIN)) {
        return respond(&Reply::error(403, "a page of another site may not drive the robot"), unread);
    }
    let method = request.method().as_str().to_ascii_uppercase();
    let path = request.uri().path().to_string();
    if method == "GET" && path.trim_end_matches('/') == "/events" {
        return stream(served, conn);
    }
    if request.body().size_hint().lower() > MOST_BODY as u64 {
        return respond(&Reply::error(413, format!("the body is over {} KB", MOST_BODY / 1024)), true);
    }
    let json = header(headers, header::CONTENT_TYPE).is_some_and(|kind| {
        kind.split(';').next().is_some_and(|kind| kind.trim().eq_ignore_ascii_case("application/json"))
    });
    if unread && !json {
        return respond(&Reply::error(415, "a body must be JSON: Content-Type: application/json"), true);
    }
    let body = match body(request.into_body()).await {
        Ok(body) => body,
        Err(reply) => return respond(&reply, true),
    };
    let reply = match verbs::from_http(&method, &path, &body) {
        Err(bad) => Reply::error(bad.code, bad.said),
        Ok(verb) if !admitted(served, conn, &verb) => Reply::error(
            429,
            format!("more than {} requests a second: slow down (STOP is always served)", super::guard::RATE_PER_S),
        ),
        Ok(verb) => carried(&served.remote, &served.waiting, verb).await,
    };
    respond(&reply, false)
}

/// Whether `verb` is let through now on `conn` (STOP always).
fn admitted(served: &Served, conn: &Conn, verb: &Verb) -> bool {
    let Ok(mut rate) = conn.rate.lock() else { return verb.stops() };
    served.guard.admit(&mut rate, verb.stops(), verb.reaches_the_boards())
}

/// Carries `verb` out on `remote`: at once when it does not wait for the
/// boards' worker, else on a blocking thread if one of `waiting` is free
/// (503 at once if not).
pub(super) async fn carried(remote: &Arc<Remote>, waiting: &Arc<Semaphore>, verb: Verb) -> Reply {
    if !verb.waits_for_the_boards() {
        return remote.act(&verb);
    }
    let Ok(permit) = Arc::clone(waiting).try_acquire_owned() else {
        return Reply::error(
            503,
            format!(
                "busy: {WAITING_FOR_BOARDS} requests already wait for the boards; try again (STOP is always taken)"
            ),
        );
    };
    let remote = Arc::clone(remote);
    let done = tokio::task::spawn_blocking(move || {
        let reply = remote.act(&verb);
        drop(permit);
        reply
    });
    done.await.unwrap_or_else(|_| Reply::error(500, "the request failed inside the server: try again"))
}

/// The request's body: at most [`MOST_BODY`], within [`BODY_WITHIN`].
async fn body(body: Incoming) -> Result<Bytes, Reply> {
    match tokio::time::timeout(BODY_WITHIN, Limited::new(body, MOST_BODY).collect()).await {
        Err(_) => Err(Reply::error(408, format!("the body did not arrive within {} s", BODY_WITHIN.as_secs()))),
        Ok(Err(error)) if error.downcast_ref::<http_body_util::LengthLimitError>().is_some() => {
            Err(Reply::error(413, format!("the body is over {} KB", MOST_BODY / 1024)))
        }
        Ok(Err(_)) => Err(Reply::error(400, "the body could not be read")),
        Ok(Ok(collected)) => Ok(collected.to_bytes()),
    }
}

/// `reply` as an HTTP answer; `close`: the connection closes after it.
fn respond(reply: &Reply, close: bool) -> Response<Body> {
    let mut response = Response::new(Either::Left(Full::new(Bytes::from(reply.body.to_string()))));
    *response.status_mut() = StatusCode::from_u16(reply.code).unwrap_or(StatusCode::INTERNAL_SERVER_ERROR);
    let headers = response.headers_mut();
    headers.insert(header::CONTENT_TYPE, HeaderValue::from_static("application/json"));
    headers.insert(header::CACHE_CONTROL, HeaderValue::from_static("no-store"));
    match reply.code {
        401 => drop(headers.insert(header::WWW_AUTHENTICATE, HeaderValue::from_static("Bearer"))),
        429 => drop(headers.insert(header::RETRY_AFTER, HeaderValue::from_static("1"))),
        503 => drop(headers.insert(header::RETRY_AFTER, HeaderValue::from_static("5"))),
        _ => {}
    }
    if close {
        headers.insert(header::CONNECTION, HeaderValue::from_static("close"));
    }
    response
}

/// `GET /events`: the status each time it changes, until the client goes; 503 when [`MOST_STREAMS`] are open.
fn stream(served: &Served, conn: &Conn) -> Response<Body> {
    if served.remote.boards().is_none() {
        return respond(&Reply::error(503, "the show's boards are not connected"), false);
    }
    let Some(events) = served.streams.start(&served.remote, conn) else {
        let said = format!(
            "at most {MOST_STREAMS} status streams at once: try again shortly, or ask GET /status (a slot frees as soon as a stream's client goes)"
        );
        return respond(&Reply::error(503, said), false);
    };
    let mut response = Response::new(Either::Right(events));
    let headers = response.headers_mut();
    headers.insert(header::CONTENT_TYPE, HeaderValue::from_static("text/event-stream"));
    headers.insert(header::CACHE_CONTROL, HeaderValue::from_static("no-store"));
    response
}
