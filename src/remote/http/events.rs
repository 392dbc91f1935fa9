//! `GET /events`: the status as Server-Sent Events, to at most
//! [`MOST_STREAMS`] clients at once. One thread waits for the status to
//! change and hands each stream the event through a queue of
//! [`QUEUE_EVENTS`]; a stream whose queue is full (its client does not read)
//! is dropped and its connection closed, and a stream whose client went frees
//! its slot as soon as the connection ends.

use std::convert::Infallible;
use std::pin::Pin;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, Weak};
use std::task::{Context, Poll};
use std::time::{Duration, Instant};

use hyper::body::{Bytes, Frame};
use serde_json::json;
use tokio::sync::mpsc;

use super::conns::Conn;
use crate::remote::Remote;

/// How many status streams may be open at once (the next is answered 503).
pub const MOST_STREAMS: usize = 8;
/// How many events wait for a stream's client before it is dropped.
pub const QUEUE_EVENTS: usize = 16;
/// How often a quiet stream says it is still there.
pub const KEEP_ALIVE: Duration = Duration::from_secs(15);
/// How long the broadcaster waits for a change before it looks again.
const LOOK_EVERY: Duration = Duration::from_millis(500);

struct Slot {
    id: u64,
    queue: mpsc::Sender<Bytes>,
    conn: Conn,
}

/// The open streams.
#[derive(Default)]
pub struct Streams {
    slots: Mutex<(u64, Vec<Slot>)>,
}

impl std::fmt::Debug for Streams {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Streams").field("open", &self.open()).finish()
    }
}

/// A stream's body: the events its queue holds, until the queue ends.
pub struct EventBody {
    events: mpsc::Receiver<Bytes>,
    _slot: SlotHeld,
}

/// A stream's slot, freed when its body goes (the connection ended).
struct SlotHeld {
    id: u64,
    conn: Conn,
    streams: Weak<Streams>,
}

impl Drop for SlotHeld {
    fn drop(&mut self) {
        self.conn.streams.fetch_sub(1, Ordering::SeqCst);
        if let Some(streams) = self.streams.upgrade()
            && let Ok(mut slots) = streams.slots.lock()
        {
            slots.1.retain(|slot| slot.id != self.id);
        }
    }
}

impl hyper::body::Body for EventBody {
    type Data = Bytes;
    type Error = Infallible;

    fn poll_frame(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<Option<Result<Frame<Bytes>, Infallible>>> {
        self.events.poll_recv(cx).map(|event| event.map(|bytes| Ok(Frame::data(bytes))))
    }
}

/// The event a status is sent as.
fn status_event(remote: &Remote) -> Option<(u64, Bytes)> {
    let status = remote.boards()?.status();
    Some((status.revision, Bytes::from(format!("event: status\ndata: {}\n\n", json!(status)))))
}

impl Streams {
    /// How many are open.
    pub fn open(&self) -> usize {
        self.slots.lock().map_or(0, |slots| slots.1.len())
    }

    /// A new stream on `conn`, starting with the status now; `None` when
    /// [`MOST_STREAMS`] are open (or the boards are gone).
    pub fn start(self: &Arc<Self>, remote: &Remote, conn: &Conn) -> Option<EventBody> {
        let mut slots = self.slots.lock().ok()?;
        if slots.1.len() >= MOST_STREAMS {
            return None;
        }
        let (queue, events) = mpsc::channel(QUEUE_EVENTS);
        let (_, first) = status_event(remote)?;
        queue.try_send(first).ok()?;
        slots.0 += 1;
        let id = slots.0;
        conn.streams.fetch_add(1, Ordering::SeqCst);
        slots.1.push(Slot { id, queue, conn: conn.clone() });
        Some(EventBody { events, _slot: SlotHeld { id, conn: conn.clone(), streams: Arc::downgrade(self) } })
    }

    /// Hands `event` to every stream; one whose queue is full is dropped and its connection closed.
    fn broadcast(&self, event: &Bytes) {
        let Ok(mut slots) = self.slots.lock() else { return };
        slots.1.retain(|slot| match slot.queue.try_send(event.clone()) {
            Ok(()) => true,
            Err(mpsc::error::TrySendError::Full(_)) => {
                // Its client does not read: the slot goes to someone who will.
                slot.conn.kill.notify_one();
                false
            }
            Err(mpsc::error::TrySendError::Closed(_)) => false,
        });
    }

    /// Ends every stream (the boards were let go).
    fn end_all(&self) {
        if let Ok(mut slots) = self.slots.lock() {
            slots.1.clear();
        }
    }
}

/// Follows the status for the streams until `done` or the boards are let go:
/// an event at each change, a comment after a quiet [`KEEP_ALIVE`].
pub fn broadcast(streams: &Streams, remote: &Remote, done: &AtomicBool) {
    let mut seen = status_event(remote).map(|(revision, _)| revision);
    let mut last_said = Instant::now();
    while !done.load(Ordering::SeqCst) {
        let Some(boards) = remote.boards() else { break };
        let status = match seen {
            Some(seen) => boards.status_after(seen, LOOK_EVERY),
            None => boards.status(),
        };
        drop(boards);
        if seen != Some(status.revision) {
            seen = Some(status.revision);
            streams.broadcast(&Bytes::from(format!("event: status\ndata: {}\n\n", json!(status))));
            last_said = Instant::now();
        } else if last_said.elapsed() >= KEEP_ALIVE {
            streams.broadcast(&Bytes::from_static(b": still here\n\n"));
            last_said = Instant::now();
        }
    }
    streams.end_all();
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::remote::http::conns::Conns;

    fn remote_with_boards() -> (Arc<Remote>, Arc<crate::show::boards::Boards>) {
        let show = crate::show::Show { devices: Vec::new(), sound: None, cues: Vec::new() };
        let boards = Arc::new(crate::show::boards::Boards::connect(&show, crate::link::no_waker()).unwrap());
        (Arc::new(Remote::new(show, Arc::downgrade(&boards), false)), boards)
    }

    #[test]
    fn a_stream_whose_client_does_not_read_is_dropped_once_its_queue_fills_and_its_slot_freed() {
        let (remote, _boards) = remote_with_boards();
        let streams = Arc::new(Streams::default());
        let conns = Conns::default();
        let conn = conns.admit();
        let body = streams.start(&remote, &conn).unwrap();
        assert_eq!(conn.streams.load(Ordering::SeqCst), 1);
        // The first event is queued; QUEUE_EVENTS − 1 more fit, the next does not.
        for _ in 1..QUEUE_EVENTS {
            streams.broadcast(&Bytes::from_static(b": x\n\n"));
        }
        assert_eq!(streams.open(), 1);
        streams.broadcast(&Bytes::from_static(b": x\n\n"));
        assert_eq!(streams.open(), 0, "dropped once its queue was full");
        drop(body);
        assert_eq!(conn.streams.load(Ordering::SeqCst), 0, "its connection streams no more");
    }

    #[test]
    fn at_most_eight_streams_and_a_slot_is_free_the_moment_its_body_goes() {
        let (remote, _boards) = remote_with_boards();
        let streams = Arc::new(Streams::default());
        let conns = Conns::default();
        let bodies: Vec<EventBody> =
            (0..MOST_STREAMS).map(|_| streams.start(&remote, &conns.admit()).unwrap()).collect();
        assert!(streams.start(&remote, &conns.admit()).is_none(), "the ninth is refused");
        drop(bodies.into_iter().next());
        assert!(streams.start(&remote, &conns.admit()).is_some(), "a slot freed at once");
    }
}
