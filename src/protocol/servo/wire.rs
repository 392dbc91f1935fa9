//! Field-level reading and writing of message content: little-endian integers
//! (decision D1) and fixed 32-byte strings (decision D3).

use super::error::{ContentError, EncodeError};

/// Width of every caption field on the board.
pub const STR32_LEN: usize = 32;

/// Reads one message's fields in table order, naming the message in every error.
pub(crate) struct Reader<'a> {
    message: &'static str,
    bytes: &'a [u8],
    pos: usize,
}

impl<'a> Reader<'a> {
    pub(crate) fn new(message: &'static str, bytes: &'a [u8]) -> Self {
        Self { message, bytes, pos: 0 }
    }

    pub(crate) fn remaining(&self) -> usize {
        self.bytes.len() - self.pos
    }

    fn take(&mut self, field: &'static str, len: usize) -> Result<&'a [u8], ContentError> {
        if self.remaining() < len {
            return Err(ContentError::TooShort {
                message: self.message,
                field,
                expected_bytes: len,
                actual_bytes: self.remaining(),
            });
        }
        let slice = &self.bytes[self.pos..self.pos + len];
        self.pos += len;
        Ok(slice)
    }

    fn array<const N: usize>(&mut self, field: &'static str) -> Result<[u8; N], ContentError> {
        let mut out = [0u8; N];
        out.copy_from_slice(self.take(field, N)?);
        Ok(out)
    }

    pub(crate) fn u8(&mut self, field: &'static str) -> Result<u8, ContentError> {
        Ok(self.array::<1>(field)?[0])
    }

    /// A one-byte flag: 0 is false, anything else true (a lenient reading of "0 / 1").
    pub(crate) fn flag(&mut self, field: &'static str) -> Result<bool, ContentError> {
        Ok(self.u8(field)? != 0)
    }

    pub(crate) fn i16(&mut self, field: &'static str) -> Result<i16, ContentError> {
        Ok(i16::from_le_bytes(self.array(field)?))
    }

    pub(crate) fn i32(&mut self, field: &'static str) -> Result<i32, ContentError> {
        Ok(i32::from_le_bytes(self.array(field)?))
    }

    pub(crate) fn u32(&mut self, field: &'static str) -> Result<u32, ContentError> {
        Ok(u32::from_le_bytes(self.array(field)?))
    }

    /// A fixed 32-byte string: up to the first NUL, invalid UTF-8 replaced.
    pub(crate) fn str32(&mut self, field: &'static str) -> Result<String, ContentError> {
        let raw = self.take(field, STR32_LEN)?;
        let end = raw.iter().position(|&b| b == 0).unwrap_or(raw.len());
        Ok(String::from_utf8_lossy(&raw[..end]).into_owned())
    }

    /// Everything that is left, as raw bytes.
    pub(crate) fn rest(&mut self) -> Vec<u8> {
        let rest = self.bytes[self.pos..].to_vec();
        self.pos = self.bytes.len();
        rest
    }

    /// Reads `count` entries of `entry_len` bytes each with `read_one`, checking
    /// first that the bytes are there so that no count allocates unchecked.
    pub(crate) fn group<T>(
        &mut self,
        field: &'static str,
        count: usize,
        entry_len: usize,
        mut read_one: impl FnMut(&mut Self) -> Result<T, ContentError>,
    ) -> Result<Vec<T>, ContentError> {
        let needed = count.saturating_mul(entry_len);
        if self.remaining() < needed {
            return Err(ContentError::TooShort {
                message: self.message,
                field,
                expected_bytes: needed,
                actual_bytes: self.remaining(),
            });
        }
        (0..count).map(|_| read_one(self)).collect()
    }

    /// A signed 16-bit repetition count, which must not be negative (decision D2).
    pub(crate) fn count_i16(&mut self, field: &'static str) -> Result<usize, ContentError> {
        let value = self.i16(field)?;
        usize::try_from(value).map_err(|_| ContentError::NegativeCount { message: self.message, field, actual: value })
    }

    /// Ends the read: the content must hold nothing more.
    pub(crate) fn finish(self) -> Result<(), ContentError> {
        if self.pos == self.bytes.len() {
            Ok(())
        } else {
            Err(ContentError::TrailingBytes {
                message: self.message,
                expected_len: self.pos,
                actual_len: self.bytes.len(),
            })
        }
    }

    pub(crate) fn invalid(&self, field: &'static str, expected: &'static str, actual: i64) -> ContentError {
        ContentError::InvalidValue { message: self.message, field, expected, actual }
    }
}

/// Writes one message's fields in table order.
pub(crate) struct Writer {
    message: &'static str,
    out: Vec<u8>,
}

impl Writer {
    pub(crate) fn new(message: &'static str) -> Self {
        Self { message, out: Vec::new() }
    }

    pub(crate) fn u8(&mut self, value: u8) -> &mut Self {
        self.out.push(value);
        self
    }

    pub(crate) fn flag(&mut self, value: bool) -> &mut Self {
        self.u8(u8::from(value))
    }

    pub(crate) fn i16(&mut self, value: i16) -> &mut Self {
        self.out.extend_from_slice(&value.to_le_bytes());
        self
    }

    pub(crate) fn i32(&mut self, value: i32) -> &mut Self {
        self.out.extend_from_slice(&value.to_le_bytes());
        self
    }

    pub(crate) fn u32(&mut self, value: u32) -> &mut Self {
        self.out.extend_from_slice(&value.to_le_bytes());
        self
    }

    pub(crate) fn bytes(&mut self, value: &[u8]) -> &mut Self {
        self.out.extend_from_slice(value);
        self
    }

    pub(crate) fn str32(&mut self, value: &str) -> &mut Self {
        let fitted = truncate_utf8(value, STR32_LEN);
        self.out.extend_from_slice(fitted.as_bytes());
        self.out.resize(self.out.len() + STR32_LEN - fitted.len(), 0);
        self
    }

    /// Writes an 8-bit count for a group of `len` entries.
    pub(crate) fn count_u8(&mut self, field: &'static str, len: usize) -> Result<&mut Self, EncodeError> {
        let count = u8::try_from(len).map_err(|_| self.too_many(field, usize::from(u8::MAX), len))?;
        Ok(self.u8(count))
    }

    /// Writes a signed 16-bit count for a group of `len` entries.
    pub(crate) fn count_i16(&mut self, field: &'static str, len: usize) -> Result<&mut Self, EncodeError> {
        let max = usize::try_from(i16::MAX).unwrap_or(usize::MAX);
        let count = i16::try_from(len).map_err(|_| self.too_many(field, max, len))?;
        Ok(self.i16(count))
    }

    fn too_many(&self, field: &'static str, max: usize, actual: usize) -> EncodeError {
        EncodeError::TooMany { message: self.message, field, max, actual }
    }

    pub(crate) fn finish(&mut self) -> Vec<u8> {
        std::mem::take(&mut self.out)
    }
}

/// The longest prefix of `text` that fits in `max_bytes` without splitting a character.
pub fn truncate_utf8(text: &str, max_bytes: usize) -> &str {
    if text.len() <= max_bytes {
        return text;
    }
    let mut end = max_bytes;
    while !text.is_char_boundary(end) {
        end -= 1;
    }
    &text[..end]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn str32_pads_with_nul() {
        let bytes = Writer::new("t").str32("ab").finish();
        assert_eq!(bytes.len(), 32);
        assert_eq!(&bytes[..3], b"ab\0");
        assert!(bytes[2..].iter().all(|&b| b == 0));
    }

    #[test]
    fn str32_truncates_on_a_character_boundary() {
        // 11 CJK characters are 33 bytes: only 10 (30 bytes) fit, then 2 NULs.
        let caption = "動作一二三四五六七八九";
        let bytes = Writer::new("t").str32(caption).finish();
        assert_eq!(bytes.len(), 32);
        assert_eq!(&bytes[..30], "動作一二三四五六七八".as_bytes());
        assert_eq!(&bytes[30..], [0, 0]);
        let decoded = Reader::new("t", &bytes).str32("caption").unwrap();
        assert_eq!(decoded, "動作一二三四五六七八");
    }

    #[test]
    fn str32_reads_up_to_first_nul_and_replaces_invalid_utf8() {
        let mut raw = [0u8; 32];
        raw[..3].copy_from_slice(&[b'a', 0xff, b'b']);
        raw[4] = b'z'; // after the NUL at 3: ignored
        assert_eq!(Reader::new("t", &raw).str32("caption").unwrap(), "a\u{fffd}b");
    }

    #[test]
    fn truncate_utf8_table() {
        assert_eq!(truncate_utf8("abc", 2), "ab");
        assert_eq!(truncate_utf8("é", 1), "");
        assert_eq!(truncate_utf8("aé", 2), "a");
        assert_eq!(truncate_utf8("", 0), "");
    }

    #[test]
    fn group_refuses_a_count_larger_than_the_content() {
        let mut reader = Reader::new("QueryActionListResponse", &[1, 2, 3]);
        let err = reader.group("actionCount", 30_000, 36, |r| r.u8("x")).unwrap_err();
        assert_eq!(
            err,
            ContentError::TooShort {
                message: "QueryActionListResponse",
                field: "actionCount",
                expected_bytes: 30_000 * 36,
                actual_bytes: 3,
            }
        );
    }
}
