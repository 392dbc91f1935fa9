//! The port's writing half as the I/O thread drives it: writes spaced at
//! least a gap apart, and a port that is full for a while held, not lost.

use std::io::{self, Write};
use std::time::Instant;

use super::driver::Driver;

/// How long the port may take no byte at all before the link is called lost
/// (a port whose reader is slow — a busy machine, a board busy elsewhere —
/// takes bytes again; one that takes none for this long is stuck or gone).
pub const WRITE_STALL: std::time::Duration = std::time::Duration::from_secs(10);

/// The port's writing half, spacing writes at least `min_gap` apart.
pub(super) struct Output<'a> {
    writer: &'a mut dyn Write,
    min_gap: std::time::Duration,
    last_write: Option<Instant>,
    /// Bytes taken from the driver that wait for the gap to pass, or for the
    /// port to take them (the rest of a chunk it took part of), with the
    /// chunk's whole length.
    held: Option<(Vec<u8>, usize)>,
    /// Since when the port has taken no byte of what is held (its write timed out).
    stalled_since: Option<Instant>,
}

impl<'a> Output<'a> {
    /// Writing to `writer`, at least `min_gap` between writes.
    pub(super) fn new(writer: &'a mut dyn Write, min_gap: std::time::Duration) -> Self {
        Self { writer, min_gap, last_write: None, held: None, stalled_since: None }
    }

    /// When held bytes may go out, if the gap holds any back; at once when
    /// the port was full (each attempt waits for it up to its write timeout).
    pub(super) fn ready_at(&self) -> Option<Instant> {
        self.held.as_ref()?;
        if self.stalled_since.is_some() {
            return Some(Instant::now());
        }
        self.last_write.map(|last| last + self.min_gap)
    }

    /// Writes what the driver has, as far as the gap allows and the port
    /// takes. A port that is full (its write timed out) is not a lost link:
    /// the rest is held and tried again, unless it took nothing for
    /// [`WRITE_STALL`].
    pub(super) fn flush_from<D: Driver>(&mut self, driver: &mut D, now: Instant) -> io::Result<()> {
        loop {
            if self.held.is_none() {
                self.held = driver.poll_transmit(now).map(|bytes| {
                    let len = bytes.len();
                    (bytes, len)
                });
            }
            let Some((bytes, total)) = self.held.take() else { return Ok(()) };
            let partial = bytes.len() < total;
            if !partial
                && !self.min_gap.is_zero()
                && self.last_write.is_some_and(|last| Instant::now() < last + self.min_gap)
            {
                self.held = Some((bytes, total));
                return Ok(());
            }
            let taken = match self.writer.write(&bytes) {
                Ok(0) => return Err(io::Error::new(io::ErrorKind::WriteZero, "the port took no bytes")),
                Ok(taken) => taken,
                Err(error)
                    if matches!(
                        error.kind(),
                        io::ErrorKind::TimedOut | io::ErrorKind::WouldBlock | io::ErrorKind::Interrupted
                    ) =>
                {
                    let since = *self.stalled_since.get_or_insert(now);
                    self.held = Some((bytes, total));
                    if Instant::now().saturating_duration_since(since) >= WRITE_STALL {
                        return Err(io::Error::new(
                            io::ErrorKind::TimedOut,
                            format!("the port took no byte for {} s", WRITE_STALL.as_secs()),
                        ));
                    }
                    return Ok(());
                }
                Err(error) => return Err(error),
            };
            self.stalled_since = None;
            if taken < bytes.len() {
                self.held = Some((bytes[taken..].to_vec(), total));
                continue;
            }
            self.writer.flush()?;
            let written = Instant::now();
            self.last_write = Some(written);
            driver.handle_written(written, total);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::VecDeque;
    use std::time::Duration;

    /// A port whose reader is slow: its first writes time out (its buffer is
    /// full), then it takes at most 7 bytes a write.
    struct SlowPort {
        full_for: usize,
        took: Vec<u8>,
    }

    impl Write for SlowPort {
        fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
            if self.full_for > 0 {
                self.full_for -= 1;
                return Err(io::ErrorKind::TimedOut.into());
            }
            let taken = buf.len().min(7);
            self.took.extend_from_slice(&buf[..taken]);
            Ok(taken)
        }

        fn flush(&mut self) -> io::Result<()> {
            Ok(())
        }
    }

    /// A driver with chunks to send, noting what it is told has left.
    struct Chunks {
        out: VecDeque<Vec<u8>>,
        left: Vec<usize>,
    }

    impl Driver for Chunks {
        type Command = ();
        type Event = ();
        fn handle_command(&mut self, _: Instant, (): ()) {}
        fn handle_input(&mut self, _: Instant, _: &[u8]) {}
        fn handle_timeout(&mut self, _: Instant) {}
        fn handle_disconnect(&mut self, _: &str) {}
        fn poll_transmit(&mut self, _: Instant) -> Option<Vec<u8>> {
            self.out.pop_front()
        }
        fn handle_written(&mut self, _: Instant, bytes: usize) {
            self.left.push(bytes);
        }
        fn poll_event(&mut self) -> Option<()> {
            None
        }
        fn poll_timeout(&self) -> Option<Instant> {
            None
        }
    }

    /// A port that is full for a while is not a lost link: what it did not
    /// take is held and written when it takes bytes again, in order, and the
    /// driver is told each chunk left once all of it did.
    #[test]
    fn a_full_port_holds_the_bytes_until_it_takes_them_again() {
        let mut port = SlowPort { full_for: 3, took: Vec::new() };
        let mut driver =
            Chunks { out: VecDeque::from([b"0123456789abcdef".to_vec(), b"XYZ".to_vec()]), left: Vec::new() };
        let mut output =
            Output { writer: &mut port, min_gap: Duration::ZERO, last_write: None, held: None, stalled_since: None };
        let now = Instant::now();
        for attempt in 0..3 {
            output.flush_from(&mut driver, now).expect("a full port is not an error");
            assert!(output.ready_at().is_some(), "attempt {attempt}: tried again at once");
        }
        output.flush_from(&mut driver, now).unwrap();
        assert_eq!(output.ready_at(), None, "nothing held once it took everything");
        assert_eq!(driver.left, [16, 3], "each chunk told whole");
        drop(output);
        assert_eq!(port.took, b"0123456789abcdefXYZ");
    }

    /// A port that takes nothing for [`WRITE_STALL`] is lost.
    #[test]
    fn a_port_that_takes_nothing_for_the_stall_limit_is_lost() {
        let mut port = SlowPort { full_for: usize::MAX, took: Vec::new() };
        let mut driver = Chunks { out: VecDeque::from([b"abc".to_vec()]), left: Vec::new() };
        let long_ago = Instant::now().checked_sub(WRITE_STALL).expect("the clock reaches back 10 s");
        let mut output = Output {
            writer: &mut port,
            min_gap: Duration::ZERO,
            last_write: None,
            held: None,
            stalled_since: Some(long_ago),
        };
        let error = output.flush_from(&mut driver, Instant::now()).unwrap_err();
        assert_eq!(error.kind(), io::ErrorKind::TimedOut);
        assert!(error.to_string().contains("took no byte for 10 s"), "{error}");
    }
}
