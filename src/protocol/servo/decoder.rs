//! A streaming frame decoder: bytes in, frames and skip reports out
//! (`board.md` §1, decisions D4 and D6).
//!
//! Feed it chunks of any size with [`FrameDecoder::push`], then drain
//! [`FrameDecoder::poll`] until it returns `None`. Corrupt input is an event,
//! never an error: the decoder drops bytes up to the next magic and goes on.
//! When the line goes quiet with a frame still incomplete (its length claimed
//! more bytes than the stream delivered), call [`FrameDecoder::abandon_partial`]
//! so the bytes held for it are skipped and re-scanned.

use super::frame::Frame;
use super::frame::{HEADER_LEN, MAX_CONTENT_LEN, OVERHEAD_LEN, checksum, find_magic, magic_prefix_suffix_len};

/// Why the decoder skipped bytes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SkipReason {
    /// Bytes that do not start with the magic.
    Garbage,
    /// A frame whose checksum byte does not match its bytes.
    BadChecksum {
        /// The checksum computed from the header and content.
        expected: u8,
        /// The checksum byte that came.
        actual: u8,
    },
    /// A header whose length exceeds what this decoder accepts.
    LengthTooLong {
        /// The length the header claims.
        length: usize,
        /// The largest length accepted.
        max: usize,
    },
    /// A frame the stream stopped short of: its length asked for more bytes
    /// than arrived before the line went quiet.
    Truncated {
        /// Bytes the frame needed (header, content and checksum).
        expected_len: usize,
        /// Bytes that arrived.
        actual_len: usize,
    },
}

impl std::fmt::Display for SkipReason {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Garbage => write!(f, "not a frame"),
            Self::BadChecksum { expected, actual } => {
                write!(f, "bad checksum: expected 0x{expected:02x}, got 0x{actual:02x}")
            }
            Self::LengthTooLong { length, max } => write!(f, "length {length} is over the limit of {max}"),
            Self::Truncated { expected_len, actual_len } => {
                write!(f, "cut short: {actual_len} of {expected_len} bytes arrived")
            }
        }
    }
}

/// What the decoder found in the stream.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum DecoderEvent {
    /// A complete frame with a valid checksum.
    Frame(Frame),
    /// Bytes dropped while resynchronising.
    Skipped {
        /// How many bytes were dropped.
        bytes: usize,
        /// Why.
        reason: SkipReason,
    },
}

/// Splits a byte stream into frames (see the module documentation).
#[derive(Debug)]
pub struct FrameDecoder {
    buffer: Vec<u8>,
    /// Bytes of `buffer` before this index are consumed.
    start: usize,
    max_content_len: usize,
    abandon: bool,
}

impl Default for FrameDecoder {
    fn default() -> Self {
        Self::new()
    }
}

impl FrameDecoder {
    /// A decoder that accepts any length the frame format can express.
    pub fn new() -> Self {
        Self::with_max_content_len(MAX_CONTENT_LEN)
    }

    /// A decoder that treats a header claiming more than `max_content_len`
    /// content bytes as corrupt, without waiting for those bytes.
    pub fn with_max_content_len(max_content_len: usize) -> Self {
        Self { buffer: Vec::new(), start: 0, max_content_len, abandon: false }
    }

    /// Adds received bytes.
    pub fn push(&mut self, bytes: &[u8]) {
        if self.start == self.buffer.len() {
            self.buffer.clear();
            self.start = 0;
        } else if self.start > 4096 && self.start * 2 > self.buffer.len() {
            self.buffer.drain(..self.start);
            self.start = 0;
        }
        self.buffer.extend_from_slice(bytes);
        self.abandon = false;
    }

    /// Bytes held, waiting for the rest of a frame.
    pub fn pending_len(&self) -> usize {
        self.buffer.len() - self.start
    }

    /// The packet id and whole length (header, content and checksum) of the
    /// frame the held bytes begin, once its header has arrived: how many more
    /// bytes the frame still needs is then known, not guessed.
    pub fn pending_header(&self) -> Option<(u16, usize)> {
        let available = &self.buffer[self.start..];
        if available.len() < HEADER_LEN || find_magic(available) != Some(0) {
            return None;
        }
        let packet_id = u16::from_le_bytes([available[4], available[5]]);
        let length = usize::from(u16::from_le_bytes([available[6], available[7]]));
        (length <= self.max_content_len).then_some((packet_id, length + OVERHEAD_LEN))
    }

    /// Gives up on the frame the held bytes began: the next [`poll`](Self::poll)s
    /// report them as skipped and decode whatever complete frames they hide.
    pub fn abandon_partial(&mut self) {
        self.abandon = true;
    }

    /// The next frame or skip report, or `None` when more bytes are needed.
    pub fn poll(&mut self) -> Option<DecoderEvent> {
        let available = &self.buffer[self.start..];
        if available.is_empty() {
            self.abandon = false;
            return None;
        }
        match find_magic(available) {
            Some(0) => {}
            Some(offset) => return Some(self.skip(offset, SkipReason::Garbage)),
            None => {
                let keep = magic_prefix_suffix_len(available);
                let garbage = available.len() - keep;
                if garbage > 0 {
                    return Some(self.skip(garbage, SkipReason::Garbage));
                }
                return self.give_up_if_abandoned(available.len(), HEADER_LEN);
            }
        }
        if available.len() < HEADER_LEN {
            return self.give_up_if_abandoned(available.len(), HEADER_LEN);
        }
        let length = usize::from(u16::from_le_bytes([available[6], available[7]]));
        if length > self.max_content_len {
            return Some(self.skip_candidate(SkipReason::LengthTooLong { length, max: self.max_content_len }));
        }
        let frame_len = length + OVERHEAD_LEN;
        if available.len() < frame_len {
            return self.give_up_if_abandoned(available.len(), frame_len);
        }
        let expected = checksum(&available[..frame_len - 1]);
        let actual = available[frame_len - 1];
        if expected != actual {
            return Some(self.skip_candidate(SkipReason::BadChecksum { expected, actual }));
        }
        let packet_id = u16::from_le_bytes([available[4], available[5]]);
        let content = available[HEADER_LEN..frame_len - 1].to_vec();
        self.start += frame_len;
        Some(DecoderEvent::Frame(Frame { packet_id, content }))
    }

    fn give_up_if_abandoned(&mut self, actual_len: usize, expected_len: usize) -> Option<DecoderEvent> {
        if !self.abandon {
            return None;
        }
        Some(self.skip_candidate(SkipReason::Truncated { expected_len, actual_len }))
    }

    /// Drops the candidate frame at the front: its first byte, and everything
    /// up to the next magic (which may sit inside the candidate's body).
    fn skip_candidate(&mut self, reason: SkipReason) -> DecoderEvent {
        let rest = &self.buffer[self.start + 1..];
        let skip = match find_magic(rest) {
            Some(offset) => 1 + offset,
            // With nothing more to wait for, nothing can still become a frame.
            None if self.abandon => 1 + rest.len(),
            None => 1 + rest.len() - magic_prefix_suffix_len(rest),
        };
        self.skip(skip, reason)
    }

    fn skip(&mut self, bytes: usize, reason: SkipReason) -> DecoderEvent {
        self.start += bytes;
        DecoderEvent::Skipped { bytes, reason }
    }
}

#[cfg(test)]
mod tests {
    use super::super::frame::MAGIC;
    use super::*;

    fn frame_bytes(packet_id: u16, content: &[u8]) -> Vec<u8> {
        Frame::new(packet_id, content.to_vec()).to_bytes().unwrap()
    }

    fn drain(decoder: &mut FrameDecoder) -> Vec<DecoderEvent> {
        std::iter::from_fn(|| decoder.poll()).collect()
    }

    #[test]
    fn leading_garbage_is_reported_then_the_frame_decodes() {
        let mut decoder = FrameDecoder::new();
        decoder.push(&[0xaa, 0xbb, 0x13]);
        decoder.push(&frame_bytes(30010, &[]));
        assert_eq!(
            drain(&mut decoder),
            [
                DecoderEvent::Skipped { bytes: 3, reason: SkipReason::Garbage },
                DecoderEvent::Frame(Frame::new(30010, vec![])),
            ]
        );
        assert_eq!(decoder.pending_len(), 0);
    }

    #[test]
    fn partial_magic_is_held_until_more_bytes_come() {
        let mut decoder = FrameDecoder::new();
        let bytes = frame_bytes(30131, &[7, 0, 0, 0]);
        decoder.push(&bytes[..2]);
        assert_eq!(drain(&mut decoder), []);
        decoder.push(&bytes[2..]);
        assert_eq!(drain(&mut decoder), [DecoderEvent::Frame(Frame::new(30131, vec![7, 0, 0, 0]))]);
    }

    #[test]
    fn bad_checksum_resynchronises_on_a_magic_inside_the_body() {
        // A dummy-data frame whose body is itself a valid frame; then the outer
        // checksum is corrupted. The inner frame must come out.
        let inner = frame_bytes(30131, &[1, 2, 3, 4]);
        let mut outer = frame_bytes(10050, &inner);
        let last = outer.len() - 1;
        outer[last] = outer[last].wrapping_add(1);
        let mut decoder = FrameDecoder::new();
        decoder.push(&outer);
        let events = drain(&mut decoder);
        assert_eq!(
            events[0],
            DecoderEvent::Skipped {
                bytes: HEADER_LEN,
                reason: SkipReason::BadChecksum { expected: outer[last].wrapping_sub(1), actual: outer[last] }
            }
        );
        assert_eq!(events[1], DecoderEvent::Frame(Frame::new(30131, vec![1, 2, 3, 4])));
        assert_eq!(events[2], DecoderEvent::Skipped { bytes: 1, reason: SkipReason::Garbage });
        assert_eq!(events.len(), 3);
    }

    #[test]
    fn overlong_length_is_skipped_without_waiting() {
        let mut decoder = FrameDecoder::with_max_content_len(100);
        let mut bogus = MAGIC.to_vec();
        bogus.extend_from_slice(&[0x3a, 0x75, 0xff, 0x7f]); // claims 32767 bytes
        decoder.push(&bogus);
        decoder.push(&frame_bytes(30010, &[]));
        assert_eq!(
            drain(&mut decoder),
            [
                DecoderEvent::Skipped { bytes: 8, reason: SkipReason::LengthTooLong { length: 32767, max: 100 } },
                DecoderEvent::Frame(Frame::new(30010, vec![])),
            ]
        );
    }

    #[test]
    fn truncated_frame_is_given_up_when_the_line_goes_quiet() {
        // A header claiming 1000 bytes, followed by one complete frame: the
        // decoder waits, then, told the line is quiet, finds the frame inside.
        let mut decoder = FrameDecoder::new();
        let mut bytes = MAGIC.to_vec();
        bytes.extend_from_slice(&[0x3a, 0x75, 0xe8, 0x03]);
        let good = frame_bytes(30131, &[9, 0, 0, 0]);
        bytes.extend_from_slice(&good);
        decoder.push(&bytes);
        assert_eq!(drain(&mut decoder), []);
        decoder.abandon_partial();
        assert_eq!(
            drain(&mut decoder),
            [
                DecoderEvent::Skipped {
                    bytes: 8,
                    reason: SkipReason::Truncated { expected_len: 1009, actual_len: bytes.len() }
                },
                DecoderEvent::Frame(Frame::new(30131, vec![9, 0, 0, 0])),
            ]
        );
        assert_eq!(decoder.pending_len(), 0);
    }

    #[test]
    fn abandoning_a_lone_partial_magic_empties_the_buffer() {
        let mut decoder = FrameDecoder::new();
        decoder.push(&[0x13, 0x4c]);
        assert_eq!(drain(&mut decoder), []);
        decoder.abandon_partial();
        assert_eq!(
            drain(&mut decoder),
            [DecoderEvent::Skipped { bytes: 2, reason: SkipReason::Truncated { expected_len: 8, actual_len: 2 } }]
        );
        assert_eq!(decoder.pending_len(), 0);
    }

    #[test]
    fn buffer_is_compacted_on_a_long_stream() {
        let mut decoder = FrameDecoder::new();
        let bytes = frame_bytes(30010, &[]);
        for _ in 0..10_000 {
            decoder.push(&bytes);
            assert!(matches!(decoder.poll(), Some(DecoderEvent::Frame(_))));
            assert_eq!(decoder.poll(), None);
        }
        decoder.push(&bytes[..3]);
        assert!(decoder.buffer.len() < 8192, "buffer grew to {}", decoder.buffer.len());
    }
}
