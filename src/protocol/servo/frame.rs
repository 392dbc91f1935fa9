//! The servo board's frame: magic, packet id, length, content, checksum
//! (`board.md` §1).
//!
//! ```text
//! offset  size  field
//! 0       4     magic        0x13 0x4C 0x05 0x1D
//! 4       2     packet id    u16, little-endian
//! 6       2     length N     u16, little-endian (content bytes only)
//! 8       N     content
//! 8+N     1     checksum     (sum of bytes 0 .. 8+N-1) mod 256
//! ```

use super::error::EncodeError;

/// The four bytes that open every frame.
pub const MAGIC: [u8; 4] = [0x13, 0x4C, 0x05, 0x1D];
/// Bytes before the content: magic, packet id, length.
pub const HEADER_LEN: usize = 8;
/// Bytes a frame adds around its content: the header and the checksum byte.
pub const OVERHEAD_LEN: usize = HEADER_LEN + 1;
/// The largest content a frame can carry (its length field is a `u16`).
pub const MAX_CONTENT_LEN: usize = u16::MAX as usize;

/// One frame as it travels: a packet id and its raw content.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Frame {
    /// The message number, e.g. 30010 (`board.md` §2).
    pub packet_id: u16,
    /// The content bytes, the message's fields in table order.
    pub content: Vec<u8>,
}

impl Frame {
    /// A frame with the given id and content.
    pub fn new(packet_id: u16, content: Vec<u8>) -> Self {
        Self { packet_id, content }
    }

    /// Number of bytes this frame occupies on the wire (`N + 9`).
    pub fn wire_len(&self) -> usize {
        self.content.len() + OVERHEAD_LEN
    }

    /// The frame's bytes: header, content and checksum.
    pub fn to_bytes(&self) -> Result<Vec<u8>, EncodeError> {
        let mut out = Vec::with_capacity(self.wire_len());
        self.write_to(&mut out)?;
        Ok(out)
    }

    /// Appends the frame's bytes to `out`.
    pub fn write_to(&self, out: &mut Vec<u8>) -> Result<(), EncodeError> {
        let length = u16::try_from(self.content.len()).map_err(|_| EncodeError::ContentTooLong {
            packet_id: self.packet_id,
            max_bytes: MAX_CONTENT_LEN,
            actual_bytes: self.content.len(),
        })?;
        let begin = out.len();
        out.extend_from_slice(&MAGIC);
        out.extend_from_slice(&self.packet_id.to_le_bytes());
        out.extend_from_slice(&length.to_le_bytes());
        out.extend_from_slice(&self.content);
        let sum = checksum(&out[begin..]);
        out.push(sum);
        Ok(())
    }
}

/// The checksum of a frame's header and content: the byte sum modulo 256.
pub fn checksum(bytes: &[u8]) -> u8 {
    bytes.iter().fold(0u8, |sum, byte| sum.wrapping_add(*byte))
}

/// Position of the first complete magic in `bytes`, if any.
pub fn find_magic(bytes: &[u8]) -> Option<usize> {
    bytes.windows(MAGIC.len()).position(|window| window == MAGIC)
}

/// Length of the longest suffix of `bytes` that is a proper prefix of the magic:
/// those bytes may still become a frame once more bytes arrive.
pub fn magic_prefix_suffix_len(bytes: &[u8]) -> usize {
    (1..MAGIC.len()).rev().find(|&len| bytes.len() >= len && bytes[bytes.len() - len..] == MAGIC[..len]).unwrap_or(0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn empty_request_frame_matches_the_page() {
        // QueryActionListRequest (30010) from the issue's golden bytes.
        let bytes = Frame::new(30010, vec![]).to_bytes().unwrap();
        assert_eq!(bytes, [0x13, 0x4c, 0x05, 0x1d, 0x3a, 0x75, 0x00, 0x00, 0x30]);
    }

    #[test]
    fn oversized_content_is_an_error_not_a_truncation() {
        let err = Frame::new(10050, vec![0; MAX_CONTENT_LEN + 1]).to_bytes().unwrap_err();
        assert_eq!(err, EncodeError::ContentTooLong { packet_id: 10050, max_bytes: 65535, actual_bytes: 65536 });
    }

    #[test]
    fn find_magic_table() {
        let cases: &[(&[u8], Option<usize>)] = &[
            (&[], None),
            (&[0x13, 0x4c, 0x05], None),
            (&[0x13, 0x4c, 0x05, 0x1d], Some(0)),
            (&[0x00, 0x13, 0x13, 0x4c, 0x05, 0x1d, 0x13], Some(2)),
            (&[0x1d, 0x05, 0x4c, 0x13], None),
        ];
        for (bytes, expected) in cases {
            assert_eq!(find_magic(bytes), *expected, "{bytes:02x?}");
        }
    }

    #[test]
    fn magic_prefix_suffix_table() {
        let cases: &[(&[u8], usize)] = &[
            (&[], 0),
            (&[0x00], 0),
            (&[0x13], 1),
            (&[0x00, 0x13, 0x4c], 2),
            (&[0x13, 0x4c, 0x05], 3),
            (&[0x13, 0x4c, 0x05, 0x1d], 0),
            (&[0x4c, 0x05], 0),
        ];
        for (bytes, expected) in cases {
            assert_eq!(magic_prefix_suffix_len(bytes), *expected, "{bytes:02x?}");
        }
    }
}
