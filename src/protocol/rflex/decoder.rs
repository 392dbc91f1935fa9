//! The streaming rFLEX receiver: push bytes as they arrive, poll frames and
//! skip reports. It undoes stuffing (`1B 00` → `1B`, `1B 01` dropped), checks
//! LEN and CHK, falls back to reading the raw bytes by length (a base that does
//! not stuff sends `1B` inside data as is), and resynchronises on `1B 02`
//! (`rflex.md` §2). Same contract as the servo decoder: corrupt input is an
//! event, never an error that stops the stream; memory stays bounded.

use std::collections::VecDeque;

use super::frame::{ETX, Frame, MAX_DATA_LEN, OVERHEAD_LEN, STX, checksum};

/// The most bytes a stuffed frame can take (every body byte doubled or tripled).
const MAX_STUFFED_LEN: usize = 2 + 3 * (MAX_DATA_LEN + 5) + 2;

/// Why bytes were skipped.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SkipReason {
    /// Bytes before a `1B 02`.
    Garbage,
    /// A frame whose checksum or length does not add up, read either way.
    BadFrame,
    /// A frame cut short: another frame started before it ended.
    Truncated,
}

impl std::fmt::Display for SkipReason {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Self::Garbage => "not a frame",
            Self::BadFrame => "bad checksum or length",
            Self::Truncated => "cut short",
        })
    }
}

/// What the decoder found.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum DecoderEvent {
    /// A frame whose length and checksum are right.
    Frame {
        /// The frame.
        frame: Frame,
        /// Whether it arrived stuffed.
        stuffed: bool,
    },
    /// Bytes dropped while resynchronising.
    Skipped {
        /// How many.
        bytes: usize,
        /// Why.
        reason: SkipReason,
    },
}

enum Attempt {
    Complete { frame: Frame, consumed: usize, stuffed: bool },
    NeedMore,
    Invalid,
}

/// The receiver.
#[derive(Debug, Default)]
pub struct FrameDecoder {
    buffer: VecDeque<u8>,
}

fn at(buffer: &VecDeque<u8>, index: usize) -> Option<u8> {
    buffer.get(index).copied()
}

fn validated(body: &[u8]) -> Option<Frame> {
    let [port, id, opcode, len, rest @ ..] = body else { return None };
    let (data, chk) = rest.split_at(rest.len().checked_sub(1)?);
    if usize::from(*len) != data.len() || chk != [checksum(*port, *id, *opcode, data)] {
        return None;
    }
    Some(Frame { port: *port, id: *id, opcode: *opcode, data: data.to_vec() })
}

/// Reads a stuffed frame starting at `start` (a `1B 02`).
fn stuffed_at(buffer: &VecDeque<u8>, start: usize) -> Attempt {
    let mut body = Vec::new();
    let mut index = start + 2;
    loop {
        let Some(byte) = at(buffer, index) else { return Attempt::NeedMore };
        if byte != 0x1b {
            body.push(byte);
            index += 1;
            if body.len() > MAX_DATA_LEN + 5 {
                return Attempt::Invalid;
            }
            continue;
        }
        let Some(next) = at(buffer, index + 1) else { return Attempt::NeedMore };
        match next {
            0x00 => body.push(0x1b),
            0x01 => {}
            0x03 => {
                return match validated(&body) {
                    Some(frame) => Attempt::Complete { frame, consumed: index + 2 - start, stuffed: true },
                    None => Attempt::Invalid,
                };
            }
            // `1B 02` (a new frame) or an escape the rule does not know.
            _ => return Attempt::Invalid,
        }
        index += 2;
    }
}

/// Reads an unstuffed frame starting at `start`, by its LEN.
fn raw_at(buffer: &VecDeque<u8>, start: usize) -> Attempt {
    let Some(len) = at(buffer, start + 5) else { return Attempt::NeedMore };
    let total = usize::from(len) + OVERHEAD_LEN;
    if buffer.len() < start + total {
        return Attempt::NeedMore;
    }
    let body: Vec<u8> = buffer.range(start + 2..start + total - 2).copied().collect();
    let end = [at(buffer, start + total - 2), at(buffer, start + total - 1)];
    if end != [Some(ETX[0]), Some(ETX[1])] {
        return Attempt::Invalid;
    }
    match validated(&body) {
        Some(frame) => Attempt::Complete { frame, consumed: total, stuffed: false },
        None => Attempt::Invalid,
    }
}

fn attempt(buffer: &VecDeque<u8>, start: usize) -> Attempt {
    match stuffed_at(buffer, start) {
        complete @ Attempt::Complete { .. } => complete,
        stuffed => match raw_at(buffer, start) {
            complete @ Attempt::Complete { .. } => complete,
            Attempt::NeedMore => Attempt::NeedMore,
            Attempt::Invalid if matches!(stuffed, Attempt::NeedMore) => Attempt::NeedMore,
            Attempt::Invalid => Attempt::Invalid,
        },
    }
}

fn find_stx(buffer: &VecDeque<u8>, from: usize) -> Option<usize> {
    (from..buffer.len().saturating_sub(1)).find(|&i| at(buffer, i) == Some(STX[0]) && at(buffer, i + 1) == Some(STX[1]))
}

impl FrameDecoder {
    /// An empty receiver.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds bytes as they arrived.
    pub fn push(&mut self, bytes: &[u8]) {
        self.buffer.extend(bytes);
    }

    /// Bytes held, waiting for the rest of a frame.
    pub fn pending(&self) -> usize {
        self.buffer.len()
    }

    fn skip(&mut self, bytes: usize, reason: SkipReason) -> DecoderEvent {
        self.buffer.drain(..bytes);
        DecoderEvent::Skipped { bytes, reason }
    }

    /// The next frame or skip report, if the bytes so far decide one.
    pub fn poll(&mut self) -> Option<DecoderEvent> {
        let Some(start) = find_stx(&self.buffer, 0) else {
            // Keep a trailing `1B`: it may be the first half of a `1B 02`.
            let keep = usize::from(self.buffer.back() == Some(&STX[0]));
            let garbage = self.buffer.len() - keep;
            return (garbage > 0).then(|| self.skip(garbage, SkipReason::Garbage));
        };
        if start > 0 {
            return Some(self.skip(start, SkipReason::Garbage));
        }
        match attempt(&self.buffer, 0) {
            Attempt::Complete { frame, consumed, stuffed } => {
                self.buffer.drain(..consumed);
                Some(DecoderEvent::Frame { frame, stuffed })
            }
            Attempt::Invalid => Some(self.skip(2, SkipReason::BadFrame)),
            Attempt::NeedMore => {
                // A frame cut short never completes: give it up when a whole
                // frame starts after it, or when it has grown past any frame.
                let mut from = 2;
                while let Some(next) = find_stx(&self.buffer, from) {
                    if matches!(attempt(&self.buffer, next), Attempt::Complete { .. }) {
                        return Some(self.skip(next, SkipReason::Truncated));
                    }
                    from = next + 2;
                }
                if self.buffer.len() > MAX_STUFFED_LEN {
                    return Some(self.skip(2, SkipReason::Truncated));
                }
                None
            }
        }
    }
}
