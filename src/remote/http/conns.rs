//! The connections a remote holds open, bounded: at most
//! [`MOST_CONNECTIONS`] at once (the next one takes the place of the one
//! quiet longest), each closed once no byte has moved for [`IDLE`] (a status
//! stream is exempt: its own queue bounds it), and each watched at the TCP
//! level so that a peer that vanished is found within seconds.

use std::collections::BTreeMap;
use std::io;
use std::pin::Pin;
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::task::{Context, Poll};
use std::time::{Duration, Instant};

use tokio::io::{AsyncRead, AsyncWrite, ReadBuf};
use tokio::net::TcpStream;
use tokio::sync::Notify;

use crate::remote::guard::Rate;

/// The most connections held open at once; the next takes the place of the quietest.
pub const MOST_CONNECTIONS: usize = 256;
/// A connection on which no byte moved for this long is closed (a stalled
/// body, a client that sends requests and never reads the answers, an idle keep-alive).
pub const IDLE: Duration = Duration::from_secs(10);
/// Data the peer has not acknowledged for this long ends the connection (a peer that vanished).
pub const UNACKNOWLEDGED: Duration = Duration::from_secs(10);

/// One open connection, as the registry and its task see it.
#[derive(Clone, Debug)]
pub struct Conn {
    id: u64,
    /// Milliseconds since the registry began, when a byte last moved.
    active_ms: Arc<AtomicU64>,
    /// Status streams open on it (while any is, it is not idle).
    pub streams: Arc<AtomicUsize>,
    /// Notified when the connection must close now (evicted, or its stream fell behind).
    pub kill: Arc<Notify>,
    /// Its requests' rate (a flood on it slows it alone).
    pub rate: Arc<Mutex<Rate>>,
}

/// Every connection open.
#[derive(Debug)]
pub struct Conns {
    began: Instant,
    open: Mutex<(u64, BTreeMap<u64, Conn>)>,
}

impl Default for Conns {
    fn default() -> Self {
        Self { began: Instant::now(), open: Mutex::new((0, BTreeMap::new())) }
    }
}

impl Conns {
    fn ms(&self, at: Instant) -> u64 {
        u64::try_from(at.saturating_duration_since(self.began).as_millis()).unwrap_or(u64::MAX)
    }

    /// A new connection; at the cap, the one quiet longest (not streaming) is told to close.
    pub fn admit(&self) -> Conn {
        let now = self.ms(Instant::now());
        let Ok(mut open) = self.open.lock() else {
            // A poisoned registry still admits: the connection is only not counted.
            return Conn::new(u64::MAX, now);
        };
        if open.1.len() >= MOST_CONNECTIONS {
            let quietest = open
                .1
                .values()
                .filter(|conn| conn.streams.load(Ordering::SeqCst) == 0)
                .min_by_key(|conn| conn.active_ms.load(Ordering::SeqCst))
                .map(|conn| conn.id);
            if let Some(conn) = quietest.and_then(|id| open.1.remove(&id)) {
                conn.kill.notify_one();
            }
        }
        open.0 += 1;
        let conn = Conn::new(open.0, now);
        open.1.insert(conn.id, conn.clone());
        conn
    }

    /// The connection has closed.
    pub fn gone(&self, conn: &Conn) {
        if let Ok(mut open) = self.open.lock() {
            open.1.remove(&conn.id);
        }
    }

    /// How many are open.
    pub fn count(&self) -> usize {
        self.open.lock().map_or(0, |open| open.1.len())
    }

    /// Whether `conn` has been idle for [`IDLE`] at `now` (never while it streams).
    pub fn idle(&self, conn: &Conn, now: Instant) -> bool {
        conn.streams.load(Ordering::SeqCst) == 0
            && self.ms(now).saturating_sub(conn.active_ms.load(Ordering::SeqCst)) >= millis(IDLE)
    }

    /// `stream` wrapped so that every byte moved marks `conn` active.
    pub fn watched(self: &Arc<Self>, stream: TcpStream, conn: &Conn) -> Watched {
        Watched { stream, active_ms: Arc::clone(&conn.active_ms), conns: Arc::clone(self) }
    }
}

fn millis(duration: Duration) -> u64 {
    u64::try_from(duration.as_millis()).unwrap_or(u64::MAX)
}

impl Conn {
    fn new(id: u64, now_ms: u64) -> Self {
        Self {
            id,
            active_ms: Arc::new(AtomicU64::new(now_ms)),
            streams: Arc::new(AtomicUsize::new(0)),
            kill: Arc::new(Notify::new()),
            rate: Arc::new(Mutex::new(Rate::client())),
        }
    }
}

/// The TCP options every accepted connection gets: no Nagle delay (an
/// answer goes at once), keep-alive probes and a bound on unacknowledged
/// data, so that a peer gone without a word is found.
pub fn tune(stream: &TcpStream) {
    let socket = socket2::SockRef::from(stream);
    let _ = socket.set_tcp_nodelay(true);
    let keepalive =
        socket2::TcpKeepalive::new().with_time(Duration::from_secs(5)).with_interval(Duration::from_secs(2));
    let _ = socket.set_tcp_keepalive(&keepalive);
    #[cfg(any(target_os = "linux", target_os = "android"))]
    let _ = socket.set_tcp_user_timeout(Some(UNACKNOWLEDGED));
}

/// A connection's stream that notes when bytes last moved.
#[derive(Debug)]
pub struct Watched {
    stream: TcpStream,
    active_ms: Arc<AtomicU64>,
    conns: Arc<Conns>,
}

impl Watched {
    fn moved(&self) {
        self.active_ms.store(self.conns.ms(Instant::now()), Ordering::SeqCst);
    }
}

impl AsyncRead for Watched {
    fn poll_read(mut self: Pin<&mut Self>, cx: &mut Context<'_>, buf: &mut ReadBuf<'_>) -> Poll<io::Result<()>> {
        let before = buf.filled().len();
        let polled = Pin::new(&mut self.stream).poll_read(cx, buf);
        if matches!(polled, Poll::Ready(Ok(()))) && buf.filled().len() > before {
            self.moved();
        }
        polled
    }
}

impl AsyncWrite for Watched {
    fn poll_write(mut self: Pin<&mut Self>, cx: &mut Context<'_>, bytes: &[u8]) -> Poll<io::Result<usize>> {
        let polled = Pin::new(&mut self.stream).poll_write(cx, bytes);
        if matches!(polled, Poll::Ready(Ok(written)) if written > 0) {
            self.moved();
        }
        polled
    }

    fn poll_flush(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<io::Result<()>> {
        Pin::new(&mut self.stream).poll_flush(cx)
    }

    fn poll_shutdown(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<io::Result<()>> {
        Pin::new(&mut self.stream).poll_shutdown(cx)
    }

    fn poll_write_vectored(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        bufs: &[io::IoSlice<'_>],
    ) -> Poll<io::Result<usize>> {
        let polled = Pin::new(&mut self.stream).poll_write_vectored(cx, bufs);
        if matches!(polled, Poll::Ready(Ok(written)) if written > 0) {
            self.moved();
        }
        polled
    }

    fn is_write_vectored(&self) -> bool {
        self.stream.is_write_vectored()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn at_the_cap_the_quietest_connection_not_streaming_makes_room() {
        let conns = Conns::default();
        let first = conns.admit();
        let streaming = conns.admit();
        streaming.streams.fetch_add(1, Ordering::SeqCst);
        // The streaming one is the quietest of all, and still kept.
        first.active_ms.store(5, Ordering::SeqCst);
        streaming.active_ms.store(0, Ordering::SeqCst);
        let rest: Vec<Conn> = (2..MOST_CONNECTIONS).map(|_| conns.admit()).collect();
        for conn in &rest {
            conn.active_ms.store(1_000, Ordering::SeqCst);
        }
        assert_eq!(conns.count(), MOST_CONNECTIONS);
        let _newest = conns.admit();
        assert_eq!(conns.count(), MOST_CONNECTIONS, "one made room");
        let open = conns.open.lock().unwrap();
        assert!(!open.1.contains_key(&first.id), "the quietest went");
        assert!(open.1.contains_key(&streaming.id), "a stream is never evicted for quiet");
    }

    #[test]
    fn a_connection_is_idle_only_after_the_limit_and_never_while_it_streams() {
        let conns = Conns::default();
        let conn = conns.admit();
        let began = conns.began;
        conn.active_ms.store(0, Ordering::SeqCst);
        assert!(!conns.idle(&conn, began + IDLE - Duration::from_millis(1)));
        assert!(conns.idle(&conn, began + IDLE));
        conn.streams.fetch_add(1, Ordering::SeqCst);
        assert!(!conns.idle(&conn, began + IDLE * 10));
    }
}
