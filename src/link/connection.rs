//! An open byte stream to a board, split into a reading and a writing half.

use std::io::{self, Read, Write};
use std::net::{Shutdown, TcpStream};

use crossbeam_channel::{Receiver, Sender, select};

/// An open link to a board: serial port, TCP stream, or in-memory pipe.
pub struct Connection {
    /// What it is connected to, for messages (e.g. `/dev/ttyUSB0`).
    pub description: String,
    pub(crate) reader: Box<dyn Read + Send>,
    pub(crate) writer: Box<dyn Write + Send>,
    /// Wakes a reader blocked in `read` so that the link can close promptly.
    pub(crate) shutdown: Option<Box<dyn FnOnce() + Send>>,
    /// Ends the writing half only (TCP: a FIN after every byte written), so
    /// that the owner's close can wait for the peer to have read it all.
    pub(crate) half_close: Option<Box<dyn FnOnce() + Send>>,
    /// Whatever must stay open as long as the connection does.
    pub(crate) keep: Vec<Box<dyn Send>>,
    /// Least time between two writes (zero: none).
    pub(crate) min_write_gap: std::time::Duration,
}

impl std::fmt::Debug for Connection {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Connection").field("description", &self.description).finish_non_exhaustive()
    }
}

impl Connection {
    /// A connection over an open serial port (its read timeout bounds how long
    /// closing takes).
    pub fn from_serial(port: Box<dyn serialport::SerialPort>, description: String) -> io::Result<Self> {
        let reader = port.try_clone().map_err(|error| io::Error::other(error.description))?;
        Ok(Self {
            description,
            reader: Box::new(reader),
            writer: Box::new(port),
            shutdown: None,
            half_close: None,
            keep: Vec::new(),
            min_write_gap: std::time::Duration::ZERO,
        })
    }

    /// A connection over a TCP stream.
    pub fn from_tcp(stream: TcpStream, description: String) -> io::Result<Self> {
        stream.set_nodelay(true)?;
        let reader = stream.try_clone()?;
        let closer = stream.try_clone()?;
        let half_closer = stream.try_clone()?;
        Ok(Self {
            description,
            reader: Box::new(reader),
            writer: Box::new(stream),
            shutdown: Some(Box::new(move || {
                // Already closed by the peer is fine: the reader is awake either way.
                let _ = closer.shutdown(Shutdown::Both);
            })),
            half_close: Some(Box::new(move || {
                let _ = half_closer.shutdown(Shutdown::Write);
            })),
            keep: Vec::new(),
            min_write_gap: std::time::Duration::ZERO,
        })
    }

    /// Two connections wired to each other in memory: what one writes, the
    /// other reads. Used for the in-process demo board and for tests.
    pub fn memory_pair() -> (Self, Self) {
        let (a_to_b, b_from_a) = crossbeam_channel::unbounded();
        let (b_to_a, a_from_b) = crossbeam_channel::unbounded();
        (Self::memory_end("memory:a", a_to_b, a_from_b), Self::memory_end("memory:b", b_to_a, b_from_a))
    }

    fn memory_end(description: &str, to_peer: Sender<Vec<u8>>, from_peer: Receiver<Vec<u8>>) -> Self {
        let (wake, woken) = crossbeam_channel::bounded::<()>(0);
        Self {
            description: description.to_string(),
            reader: Box::new(MemoryReader { from_peer, woken, leftover: Vec::new() }),
            writer: Box::new(MemoryWriter { to_peer }),
            shutdown: Some(Box::new(move || drop(wake))),
            half_close: None,
            keep: Vec::new(),
            min_write_gap: std::time::Duration::ZERO,
        }
    }

    /// The least time between two writes.
    pub fn min_write_gap(&self) -> std::time::Duration {
        self.min_write_gap
    }

    /// Spaces writes at least `gap` apart (the I/O thread holds bytes back until then).
    pub fn with_min_write_gap(mut self, gap: std::time::Duration) -> Self {
        self.min_write_gap = gap;
        self
    }

    #[cfg(any(test, feature = "test-api"))]
    /// The reading half (for tests and tools that play the other end).
    pub fn reader_mut(&mut self) -> &mut (dyn Read + Send) {
        &mut *self.reader
    }

    #[cfg(any(test, feature = "test-api"))]
    /// The writing half.
    pub fn writer_mut(&mut self) -> &mut (dyn Write + Send) {
        &mut *self.writer
    }

    /// Keeps `resource` open for as long as this connection lives.
    pub fn keep_alive(&mut self, resource: Box<dyn Send>) {
        self.keep.push(resource);
    }
}

struct MemoryWriter {
    to_peer: Sender<Vec<u8>>,
}

impl Write for MemoryWriter {
    fn write(&mut self, bytes: &[u8]) -> io::Result<usize> {
        self.to_peer
            .send(bytes.to_vec())
            .map_err(|_| io::Error::new(io::ErrorKind::BrokenPipe, "the other end closed"))?;
        Ok(bytes.len())
    }

    fn flush(&mut self) -> io::Result<()> {
        Ok(())
    }
}

struct MemoryReader {
    from_peer: Receiver<Vec<u8>>,
    /// Disconnected when this end shuts down.
    woken: Receiver<()>,
    leftover: Vec<u8>,
}

impl Read for MemoryReader {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        if self.leftover.is_empty() {
            select! {
                recv(self.from_peer) -> bytes => match bytes {
                    Ok(bytes) => self.leftover = bytes,
                    Err(_) => return Ok(0), // the peer closed: end of stream
                },
                recv(self.woken) -> _ => return Ok(0), // this end is closing
            }
        }
        let len = buf.len().min(self.leftover.len());
        buf[..len].copy_from_slice(&self.leftover[..len]);
        self.leftover.drain(..len);
        Ok(len)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn memory_pair_carries_bytes_both_ways_and_ends_when_a_side_drops() {
        let (mut a, mut b) = Connection::memory_pair();
        a.writer.write_all(b"hello").unwrap();
        let mut buf = [0u8; 3];
        assert_eq!(b.reader.read(&mut buf).unwrap(), 3);
        assert_eq!(&buf, b"hel");
        let mut rest = [0u8; 8];
        assert_eq!(b.reader.read(&mut rest).unwrap(), 2);
        b.writer.write_all(b"!").unwrap();
        assert_eq!(a.reader.read(&mut rest).unwrap(), 1);
        drop(a);
        assert_eq!(b.reader.read(&mut rest).unwrap(), 0);
        assert!(b.writer.write_all(b"x").is_err());
    }
}
