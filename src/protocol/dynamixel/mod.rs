//! DYNAMIXEL packets, both protocols, sans IO: an instruction or a status
//! packet to bytes, and a byte stream back into packets — both protocols on
//! one bus, as a U2D2 carries them (an AX-12 of a Bioloid beside an XL430).
//!
//! Protocol 2.0 (ROBOTIS e-Manual, "DYNAMIXEL Protocol 2.0"):
//! `FF FF FD 00 | ID | LEN_L LEN_H | INST | PARAM… | CRC_L CRC_H`. LEN counts
//! the instruction, the parameters as stuffed and the CRC; a status packet's
//! INST is `0x55`, followed by its error byte. Wherever `FF FF FD` occurs from
//! the instruction on, a `FD` is stuffed after it; the CRC-16 (polynomial
//! 0x8005, `dynamixel2::checksum`) covers the packet as sent.
//!
//! Protocol 1.0 ("DYNAMIXEL Protocol 1.0"): `FF FF | ID | LEN | INST | PARAM… | CHK`,
//! LEN = parameters + 2, CHK = the low byte of `!(ID + LEN + INST + Σ PARAM)`;
//! a status packet carries its error byte where the instruction was.

mod stream;
pub mod table;

pub use stream::{Packets, Read};

/// Which protocol a packet is in.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Protocol {
    /// Protocol 1.0: AX-12/AX-18, MX with its 1.0 firmware (Bioloid).
    One,
    /// Protocol 2.0: X-series, MX 2.0, XL330/XL430…
    Two,
}

/// The ID every servo takes a packet for (none of them answers it, but for a ping in Protocol 2.0).
pub const BROADCAST: u8 = 0xFE;

/// Instructions (the same numbers in both protocols where both have them).
pub mod instruction {
    /// Asks a servo whether it is there (2.0: its model number and firmware).
    pub const PING: u8 = 0x01;
    /// Reads a span of the control table.
    pub const READ: u8 = 0x02;
    /// Writes a span of the control table.
    pub const WRITE: u8 = 0x03;
    /// Writes a span to be carried out at the next ACTION.
    pub const REG_WRITE: u8 = 0x04;
    /// Carries out what REG_WRITE registered.
    pub const ACTION: u8 = 0x05;
    /// Puts the control table back to the factory's values.
    pub const FACTORY_RESET: u8 = 0x06;
    /// Restarts the servo.
    pub const REBOOT: u8 = 0x08;
    /// 2.0: the status packet's instruction byte.
    pub const STATUS: u8 = 0x55;
    /// 2.0: the same span read from several servos, each answering in turn.
    pub const SYNC_READ: u8 = 0x82;
    /// The same span written to several servos in one packet.
    pub const SYNC_WRITE: u8 = 0x83;
}

/// A packet as it travels: who it is for or from, and what it carries.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Packet {
    /// Its protocol.
    pub protocol: Protocol,
    /// The servo's ID (or [`BROADCAST`]).
    pub id: u8,
    /// What it is.
    pub kind: Kind,
    /// Its parameters, unstuffed.
    pub params: Vec<u8>,
}

/// An instruction, or a status with its error byte.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// An instruction from the controller.
    Instruction(u8),
    /// A servo's answer, with its error byte (2.0: bit 7 an alert, bits 0–6 a
    /// result number; 1.0: a bit for each kind of error).
    Status(u8),
}

impl Packet {
    /// An instruction packet.
    pub fn instruction(protocol: Protocol, id: u8, instruction: u8, params: Vec<u8>) -> Self {
        Self { protocol, id, kind: Kind::Instruction(instruction), params }
    }

    /// A status packet.
    pub fn status(protocol: Protocol, id: u8, error: u8, params: Vec<u8>) -> Self {
        Self { protocol, id, kind: Kind::Status(error), params }
    }

    /// The packet's bytes as sent.
    pub fn to_bytes(&self) -> Vec<u8> {
        match self.protocol {
            Protocol::One => self.one(),
            Protocol::Two => self.two(),
        }
    }

    fn one(&self) -> Vec<u8> {
        let code = match self.kind {
            Kind::Instruction(code) | Kind::Status(code) => code,
        };
        // A 1.0 packet holds at most 253 parameters (LEN is one byte).
        let len = u8::try_from(self.params.len() + 2).unwrap_or(u8::MAX);
        let mut bytes = vec![0xFF, 0xFF, self.id, len, code];
        bytes.extend(&self.params[..usize::from(len) - 2]);
        bytes.push(checksum_one(&bytes[2..]));
        bytes
    }

    fn two(&self) -> Vec<u8> {
        let mut body = match self.kind {
            Kind::Instruction(code) => vec![code],
            Kind::Status(error) => vec![instruction::STATUS, error],
        };
        body.extend(&self.params);
        let body = stuff(&body);
        // LEN: the body and the CRC.
        let len = u16::try_from(body.len() + 2).unwrap_or(u16::MAX);
        let mut bytes = vec![0xFF, 0xFF, 0xFD, 0x00, self.id];
        bytes.extend(len.to_le_bytes());
        bytes.extend(body);
        let crc = dynamixel2::checksum::calculate_checksum(0, &bytes);
        bytes.extend(crc.to_le_bytes());
        bytes
    }
}

/// Protocol 1.0's checksum of `ID, LEN, INST, PARAM…`.
pub fn checksum_one(bytes: &[u8]) -> u8 {
    !bytes.iter().fold(0u8, |sum, byte| sum.wrapping_add(*byte))
}

/// `body` with an `FD` stuffed after every `FF FF FD`.
fn stuff(body: &[u8]) -> Vec<u8> {
    let mut stuffed = Vec::with_capacity(body.len() + 4);
    for &byte in body {
        stuffed.push(byte);
        if stuffed.ends_with(&[0xFF, 0xFF, 0xFD]) {
            stuffed.push(0xFD);
        }
    }
    stuffed
}

/// `body` with the `FD` after every `FF FF FD` taken out again.
fn unstuff(body: &[u8]) -> Vec<u8> {
    let mut plain = Vec::with_capacity(body.len());
    let mut at = 0;
    while at < body.len() {
        plain.push(body[at]);
        if plain.ends_with(&[0xFF, 0xFF, 0xFD]) && body.get(at + 1) == Some(&0xFD) {
            at += 1;
        }
        at += 1;
    }
    plain
}

#[cfg(test)]
mod tests;
