//! Errors of the board codec: each carries what was expected and what came.

/// A frame's content does not match its message's layout (`board.md` §2).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ContentError {
    /// The content ended before a field was complete.
    #[error("{message}: field `{field}` needs {expected_bytes} more byte(s), but only {actual_bytes} remain")]
    TooShort {
        /// The message being decoded, e.g. `QueryActionResponse`.
        message: &'static str,
        /// The field that did not fit.
        field: &'static str,
        /// Bytes the field (or repeated group) needs.
        expected_bytes: usize,
        /// Bytes that were left.
        actual_bytes: usize,
    },
    /// The content carries bytes after the message's last field.
    #[error("{message}: content should be {expected_len} byte(s) long, but is {actual_len}")]
    TrailingBytes {
        /// The message being decoded.
        message: &'static str,
        /// The length its fields account for.
        expected_len: usize,
        /// The content's real length.
        actual_len: usize,
    },
    /// A repetition count is negative (decision D2).
    #[error("{message}: count `{field}` must be 0 or more, but is {actual}")]
    NegativeCount {
        /// The message being decoded.
        message: &'static str,
        /// The count field.
        field: &'static str,
        /// The negative value that came.
        actual: i16,
    },
    /// A field holds a value its message does not define.
    #[error("{message}: field `{field}` must be {expected}, but is {actual}")]
    InvalidValue {
        /// The message being decoded.
        message: &'static str,
        /// The field.
        field: &'static str,
        /// The values the page allows, in words.
        expected: &'static str,
        /// The value that came.
        actual: i64,
    },
}

/// A message cannot be put into a frame.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum EncodeError {
    /// A repeated group has more entries than its count field can express.
    #[error("{message}: `{field}` can hold at most {max} entries, but {actual} were given")]
    TooMany {
        /// The message being encoded.
        message: &'static str,
        /// The count field.
        field: &'static str,
        /// The largest count the field can carry.
        max: usize,
        /// The number of entries given.
        actual: usize,
    },
    /// The content does not fit the frame's 16-bit length field.
    #[error("packet {packet_id}: content is {actual_bytes} bytes, but a frame carries at most {max_bytes}")]
    ContentTooLong {
        /// The packet id.
        packet_id: u16,
        /// The largest content a frame can carry.
        max_bytes: usize,
        /// The content's length.
        actual_bytes: usize,
    },
}
