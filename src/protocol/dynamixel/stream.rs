//! Packets read back out of a byte stream, in either protocol, however the
//! bytes arrive: in pieces, run together, with noise between them. A packet
//! whose checksum fails is said and skipped, and reading goes on at the next header.

use super::{Kind, Packet, Protocol, checksum_one, instruction, unstuff};

/// The longest packet taken (a 2.0 packet's LEN may say up to 65535: a
/// garbled LEN must not make the reader wait for that much).
const LONGEST: usize = 1024;

/// What the reader found.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Read {
    /// A whole packet, checked.
    Packet(Packet),
    /// Bytes that were no packet (noise, a failed checksum), skipped, and why.
    Skipped {
        /// How many bytes.
        bytes: usize,
        /// Why.
        why: &'static str,
    },
}

/// A byte stream's packets. In Protocol 1.0 nothing in a packet says whether
/// it is an instruction or a status, so a reader reads one side of the bus.
#[derive(Debug)]
pub struct Packets {
    buffer: Vec<u8>,
    statuses: bool,
}

impl Packets {
    /// Reads the instructions a controller sends (an emulated servo's side).
    pub fn instructions() -> Self {
        Self { buffer: Vec::new(), statuses: false }
    }

    /// Reads the status packets servos send (the controller's side).
    pub fn statuses() -> Self {
        Self { buffer: Vec::new(), statuses: true }
    }

    /// Takes `bytes` in; what they completed.
    pub fn push(&mut self, bytes: &[u8]) -> Vec<Read> {
        self.buffer.extend_from_slice(bytes);
        let mut found = Vec::new();
        while let Some(read) = self.next() {
            found.push(read);
        }
        found
    }

    /// The next whole packet or skipped run, if the buffer holds one.
    fn next(&mut self) -> Option<Read> {
        let start = self.buffer.windows(2).position(|pair| pair == [0xFF, 0xFF]);
        let Some(start) = start else {
            // No header: all but a last FF (the first half of one) is noise.
            let keep = usize::from(self.buffer.last() == Some(&0xFF));
            let noise = self.buffer.len() - keep;
            self.buffer.drain(..noise);
            return (noise > 0).then_some(Read::Skipped { bytes: noise, why: "no header" });
        };
        if start > 0 {
            self.buffer.drain(..start);
            return Some(Read::Skipped { bytes: start, why: "no header" });
        }
        let two = self.buffer.get(2..4).map(|next| next == [0xFD, 0x00]);
        match two? {
            true => self.two(),
            // `FF FF FF…`: the first FF is noise before a header.
            false if self.buffer[2] == 0xFF => {
                self.buffer.drain(..1);
                Some(Read::Skipped { bytes: 1, why: "no header" })
            }
            false => self.one(),
        }
    }

    fn two(&mut self) -> Option<Read> {
        let len = usize::from(u16::from_le_bytes([*self.buffer.get(5)?, *self.buffer.get(6)?]));
        if len < 3 || 7 + len > LONGEST {
            return Some(self.skip("a 2.0 length no packet has"));
        }
        let whole = 7 + len;
        if self.buffer.len() < whole {
            return None;
        }
        let crc = u16::from_le_bytes([self.buffer[whole - 2], self.buffer[whole - 1]]);
        if dynamixel2::checksum::calculate_checksum(0, &self.buffer[..whole - 2]) != crc {
            return Some(self.skip("a 2.0 packet whose CRC fails"));
        }
        let id = self.buffer[4];
        let body = unstuff(&self.buffer[7..whole - 2]);
        self.buffer.drain(..whole);
        let packet = match body.as_slice() {
            [instruction::STATUS, error, params @ ..] => Packet::status(Protocol::Two, id, *error, params.to_vec()),
            [code, params @ ..] if *code != instruction::STATUS => {
                Packet::instruction(Protocol::Two, id, *code, params.to_vec())
            }
            _ => return Some(Read::Skipped { bytes: whole, why: "a 2.0 status packet without its error byte" }),
        };
        Some(Read::Packet(packet))
    }

    fn one(&mut self) -> Option<Read> {
        let len = usize::from(*self.buffer.get(3)?);
        if len < 2 {
            return Some(self.skip("a 1.0 length no packet has"));
        }
        let whole = 4 + len;
        if self.buffer.len() < whole {
            return None;
        }
        if checksum_one(&self.buffer[2..whole - 1]) != self.buffer[whole - 1] {
            return Some(self.skip("a 1.0 packet whose checksum fails"));
        }
        let (id, code) = (self.buffer[2], self.buffer[4]);
        let params = self.buffer[5..whole - 1].to_vec();
        self.buffer.drain(..whole);
        let kind = if self.statuses { Kind::Status(code) } else { Kind::Instruction(code) };
        Some(Read::Packet(Packet { protocol: Protocol::One, id, kind, params }))
    }

    /// The header's first byte, skipped: reading goes on from the next.
    fn skip(&mut self, why: &'static str) -> Read {
        self.buffer.drain(..1);
        Read::Skipped { bytes: 1, why }
    }
}
