//! rFLEX framing (`rflex.md` §2): `1B 02 | PORT | ID | OPCODE | LEN | DATA | CHK | 1B 03`,
//! with CHK the XOR of PORT, ID, OPCODE, LEN and DATA; optional byte stuffing.

/// Start of a frame.
pub const STX: [u8; 2] = [0x1b, 0x02];
/// End of a frame.
pub const ETX: [u8; 2] = [0x1b, 0x03];
/// Bytes around the data: STX, PORT, ID, OPCODE, LEN, CHK, ETX.
pub const OVERHEAD_LEN: usize = 9;
/// Most data bytes a frame carries (LEN is one byte).
pub const MAX_DATA_LEN: usize = 255;

/// A module of the base (`PORT`).
pub mod port {
    /// System module: status, LCD.
    pub const SYSTEM: u8 = 1;
    /// Motion: axes, brake, odometry reports.
    pub const MOTION: u8 = 2;
    /// Joystick.
    pub const JOYSTICK: u8 = 3;
    /// Sonar ring.
    pub const SONAR: u8 = 4;
    /// Digital I/O (bump panels).
    pub const DIO: u8 = 5;
    /// Infrared.
    pub const IR: u8 = 6;
}

/// One frame, as on the wire after unstuffing.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Frame {
    /// `PORT`: which module.
    pub port: u8,
    /// `ID`: 0 from a client (4 for sonar commands); a running number from the base.
    pub id: u8,
    /// `OPCODE`.
    pub opcode: u8,
    /// `DATA`, at most 255 bytes.
    pub data: Vec<u8>,
}

/// XOR of PORT, ID, OPCODE, LEN and every DATA byte.
pub fn checksum(port: u8, id: u8, opcode: u8, data: &[u8]) -> u8 {
    // LEN is one byte: a longer data slice is never framed (see `Frame::to_bytes`).
    let len = u8::try_from(data.len()).unwrap_or(u8::MAX);
    data.iter().fold(port ^ id ^ opcode ^ len, |acc, byte| acc ^ byte)
}

/// A frame too large for its LEN byte.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("rFLEX frame data is {actual_bytes} bytes; LEN holds at most {MAX_DATA_LEN}")]
pub struct TooLong {
    /// The data's length.
    pub actual_bytes: usize,
}

impl Frame {
    /// The unstuffed bytes, as every reference driver sends them.
    pub fn to_bytes(&self) -> Result<Vec<u8>, TooLong> {
        let len = u8::try_from(self.data.len()).map_err(|_| TooLong { actual_bytes: self.data.len() })?;
        let mut out = Vec::with_capacity(self.data.len() + OVERHEAD_LEN);
        out.extend_from_slice(&STX);
        out.extend_from_slice(&[self.port, self.id, self.opcode, len]);
        out.extend_from_slice(&self.data);
        out.push(checksum(self.port, self.id, self.opcode, &self.data));
        out.extend_from_slice(&ETX);
        Ok(out)
    }

    /// The stuffed bytes: between STX and ETX, `1B` → `1B 00` and `7C` → `7C 1B 01`;
    /// LEN and CHK are those of the unstuffed frame.
    pub fn to_stuffed_bytes(&self) -> Result<Vec<u8>, TooLong> {
        let plain = self.to_bytes()?;
        let body = &plain[2..plain.len() - 2];
        let mut out = Vec::with_capacity(plain.len() + 8);
        out.extend_from_slice(&STX);
        for &byte in body {
            match byte {
                0x1b => out.extend_from_slice(&[0x1b, 0x00]),
                0x7c => out.extend_from_slice(&[0x7c, 0x1b, 0x01]),
                other => out.push(other),
            }
        }
        out.extend_from_slice(&ETX);
        Ok(out)
    }
}
