//! Reading PLEN2 replies (`plen2.md` §3): JSON with tab indentation and CRLF,
//! no end marker — read until the brackets balance (strings respected). A
//! never-written slot answers EEPROM garbage (frame length 255, bytes that are
//! not UTF-8, hundreds of kilobytes): the reader drains it without keeping it,
//! and the motion decoder calls it empty. Never a panic.

use serde::Deserialize;

use super::joint::{DEVICE_IDS, MAX_FRAMES, SLOTS};

/// Most bytes of one reply kept in memory (a full 20-frame motion is about 30 KB).
pub const MAX_REPLY_BYTES: usize = 96 * 1024;

/// Which getter a reply answers.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ReplyKind {
    /// `<VI`.
    Version,
    /// `<JS`.
    JointSettings,
    /// `<MO`.
    Motion,
}

/// What the reader found.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ReplyEvent {
    /// A whole reply: its text, brackets balanced.
    Complete {
        /// The getter.
        kind: ReplyKind,
        /// The reply's bytes (not necessarily UTF-8).
        bytes: Vec<u8>,
    },
    /// A reply too large to be anything but garbage, drained to its end.
    Oversized {
        /// The getter.
        kind: ReplyKind,
        /// How many bytes it had.
        bytes: usize,
    },
    /// Bytes outside any reply (nothing was asked for, or before the reply
    /// began), blanks and line ends not counted.
    Ignored {
        /// How many.
        bytes: usize,
    },
}

/// The streaming reader: tell it what was asked, push bytes, poll events.
#[derive(Debug, Default)]
pub struct ReplyReader {
    expecting: Option<ReplyKind>,
    kept: Vec<u8>,
    length: usize,
    depth: u32,
    in_string: bool,
    escaped: bool,
    started: bool,
    events: std::collections::VecDeque<ReplyEvent>,
    ignored: usize,
}

impl ReplyReader {
    /// A reader expecting nothing.
    pub fn new() -> Self {
        Self::default()
    }

    /// A getter was sent: the next JSON value answers it.
    pub fn expect(&mut self, kind: ReplyKind) {
        self.reset();
        self.expecting = Some(kind);
    }

    /// Whether a reply is awaited or being read.
    pub fn busy(&self) -> bool {
        self.expecting.is_some()
    }

    /// How many bytes of the reply being read are held in memory (never more
    /// than [`MAX_REPLY_BYTES`], however long the reply).
    pub fn held(&self) -> usize {
        self.kept.len()
    }

    /// Whether a reply has begun (some of it arrived).
    pub fn started(&self) -> bool {
        self.started
    }

    /// Whether the reply being read is recognisably the one asked for: its
    /// first key has arrived (`{"device"` for `<VI`, `[{"@device"` for `<JS`,
    /// `{"slot"` for `<MO`, blanks aside). A stray `{` on a noisy line is not.
    pub fn recognised(&self) -> bool {
        let Some(kind) = self.expecting.filter(|_| self.started) else { return false };
        let start: &[u8] = match kind {
            ReplyKind::Version => b"{\"device\"",
            ReplyKind::JointSettings => b"[{\"@device\"",
            ReplyKind::Motion => b"{\"slot\"",
        };
        let mut seen = self.kept.iter().filter(|byte| !byte.is_ascii_whitespace());
        start.iter().all(|wanted| seen.next() == Some(wanted))
    }

    /// Whether the `<MO` reply being read is a never-written slot's garbage,
    /// known from its first bytes: its `"slot"` field prints a number no slot
    /// has (255 from erased EEPROM, `plen2.md` §3). `None` until that field
    /// has arrived whole (or for another reply).
    pub fn erased_slot(&self) -> Option<bool> {
        if self.expecting != Some(ReplyKind::Motion) || !self.started {
            return None;
        }
        // `{`, CRLF, a tab, `"slot": 255,` — well within the first 32 bytes.
        let head = &self.kept[..self.kept.len().min(32)];
        let at = head.windows(7).position(|window| window == b"\"slot\":")? + 7;
        let rest = &head[at..];
        let digits: Vec<u8> = rest.iter().copied().skip_while(u8::is_ascii_whitespace).collect();
        let number: Vec<u8> = digits.iter().copied().take_while(u8::is_ascii_digit).collect();
        // The number is whole only once something follows it.
        if number.is_empty() || number.len() == digits.len() {
            return None;
        }
        let slot: u32 = std::str::from_utf8(&number).ok()?.parse().ok()?;
        Some(slot >= u32::from(SLOTS))
    }

    /// Gives up the awaited reply (its timeout ran out); returns what was awaited.
    pub fn abandon(&mut self) -> Option<ReplyKind> {
        let kind = self.expecting.take();
        self.reset();
        kind
    }

    fn reset(&mut self) {
        self.kept.clear();
        self.length = 0;
        self.depth = 0;
        self.in_string = false;
        self.escaped = false;
        self.started = false;
    }

    /// Takes bytes as they arrived.
    pub fn push(&mut self, bytes: &[u8]) {
        for &byte in bytes {
            self.byte(byte);
        }
        if self.ignored > 0 {
            self.events.push_back(ReplyEvent::Ignored { bytes: self.ignored });
            self.ignored = 0;
        }
    }

    fn byte(&mut self, byte: u8) {
        let Some(kind) = self.expecting.filter(|_| self.started || byte == b'{' || byte == b'[') else {
            // The CRLF after a reply and blanks around one are layout, not stray bytes.
            if !byte.is_ascii_whitespace() {
                self.ignored += 1;
            }
            return;
        };
        self.started = true;
        self.length += 1;
        if self.kept.len() < MAX_REPLY_BYTES {
            self.kept.push(byte);
        }
        if self.in_string {
            match (self.escaped, byte) {
                (true, _) => self.escaped = false,
                (false, b'\\') => self.escaped = true,
                (false, b'"') => self.in_string = false,
                _ => {}
            }
            return;
        }
        match byte {
            b'"' => self.in_string = true,
            b'{' | b'[' => self.depth += 1,
            b'}' | b']' => self.depth = self.depth.saturating_sub(1),
            _ => {}
        }
        if self.depth == 0 {
            let event = if self.length > MAX_REPLY_BYTES {
                ReplyEvent::Oversized { kind, bytes: self.length }
            } else {
                ReplyEvent::Complete { kind, bytes: std::mem::take(&mut self.kept) }
            };
            self.events.push_back(event);
            self.expecting = None;
            self.reset();
        }
    }

    /// The next event.
    pub fn poll(&mut self) -> Option<ReplyEvent> {
        self.events.pop_front()
    }
}

/// `<VI`.
#[derive(Clone, Debug, PartialEq, Eq, Deserialize)]
pub struct VersionReply {
    /// "PLEN2".
    pub device: String,
    /// "Cytisus".
    pub codename: String,
    /// "1.4.2".
    pub version: String,
}

/// One device's entry of `<JS`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
pub struct JointSettingsReply {
    /// The device id.
    #[serde(rename = "@device")]
    pub device: u8,
    /// Max, tenths of a degree.
    pub max: i16,
    /// Min.
    pub min: i16,
    /// Home.
    pub home: i16,
}

/// `<MO`, read: a stored motion.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MotionReply {
    /// The slot.
    pub slot: u8,
    /// The name, its padding trimmed.
    pub name: String,
    /// (begin, end, count) when the loop is on.
    pub loop_range: Option<(u8, u8, u8)>,
    /// The jump slot when the jump is on.
    pub jump_slot: Option<u8>,
    /// (transition ms, 24 values) per frame.
    pub frames: Vec<(u16, [i16; DEVICE_IDS])>,
}

#[derive(Deserialize)]
struct RawCode {
    method: String,
    arguments: Vec<i64>,
}

#[derive(Deserialize)]
struct RawOutput {
    device: u8,
    value: i16,
}

#[derive(Deserialize)]
struct RawFrame {
    transition_time_ms: u16,
    outputs: Vec<RawOutput>,
}

#[derive(Deserialize)]
struct RawMotion {
    slot: u8,
    name: String,
    #[serde(rename = "@frame_length")]
    frame_length: usize,
    #[serde(default)]
    codes: Vec<RawCode>,
    #[serde(default)]
    frames: Vec<RawFrame>,
}

/// A `<MO` reply as a motion; `None` for a slot that was never written (or
/// holds anything that is not a whole motion).
pub fn decode_motion(bytes: &[u8]) -> Option<MotionReply> {
    let raw: RawMotion = serde_json::from_slice(bytes).ok()?;
    if !(1..=MAX_FRAMES).contains(&raw.frame_length) || raw.frames.len() != raw.frame_length {
        return None;
    }
    let mut loop_range = None;
    let mut jump_slot = None;
    for code in &raw.codes {
        let args: Vec<u8> = code.arguments.iter().filter_map(|a| u8::try_from(*a).ok()).collect();
        match (code.method.as_str(), args.as_slice()) {
            ("loop", [begin, end, count]) => loop_range = Some((*begin, *end, *count)),
            ("jump", [slot]) => jump_slot = Some(*slot),
            _ => return None,
        }
    }
    let mut frames = Vec::with_capacity(raw.frames.len());
    for frame in raw.frames {
        let mut values = [0i16; DEVICE_IDS];
        for output in frame.outputs {
            *values.get_mut(usize::from(output.device))? = output.value;
        }
        frames.push((frame.transition_time_ms, values));
    }
    Some(MotionReply { slot: raw.slot, name: raw.name.trim_end().to_string(), loop_range, jump_slot, frames })
}

/// A `<JS` reply, `None` if it is not 24 entries.
pub fn decode_joint_settings(bytes: &[u8]) -> Option<Vec<JointSettingsReply>> {
    let entries: Vec<JointSettingsReply> = serde_json::from_slice(bytes).ok()?;
    (entries.len() == DEVICE_IDS).then_some(entries)
}

/// A `<VI` reply.
pub fn decode_version(bytes: &[u8]) -> Option<VersionReply> {
    serde_json::from_slice(bytes).ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(kind: ReplyKind, chunks: &[&[u8]]) -> Vec<ReplyEvent> {
        let mut reader = ReplyReader::new();
        reader.expect(kind);
        let mut out = Vec::new();
        for chunk in chunks {
            reader.push(chunk);
            out.extend(std::iter::from_fn(|| reader.poll()));
        }
        out
    }

    #[test]
    fn a_reply_ends_when_its_brackets_balance_strings_included() {
        let text =
            b"\r\n{\r\n\t\"device\": \"PL{EN2\",\r\n\t\"codename\": \"Cyt]isus\",\r\n\t\"version\": \"1.4.2\"\r\n}\r\n";
        let events = read(ReplyKind::Version, &[&text[..20], &text[20..]]);
        let complete = events.iter().find_map(|e| match e {
            ReplyEvent::Complete { bytes, .. } => Some(bytes.clone()),
            _ => None,
        });
        let version = decode_version(&complete.unwrap()).unwrap();
        assert_eq!(version.codename, "Cyt]isus");
        // The line ends around the reply are its layout, not stray bytes.
        assert!(!events.iter().any(|e| matches!(e, ReplyEvent::Ignored { .. })), "{events:?}");
        // Bytes that are not layout are counted.
        let mut reader = ReplyReader::new();
        reader.push(b"\r\nok\r\n");
        assert_eq!(reader.poll(), Some(ReplyEvent::Ignored { bytes: 2 }));
    }

    /// A reply is recognised by its first key, however it is laid out; a
    /// stray bracket is not a reply.
    #[test]
    fn a_reply_is_recognised_by_its_first_key() {
        for (kind, text) in [
            (ReplyKind::Version, &b"{\r\n\t\"device\": \"PLEN2\""[..]),
            (ReplyKind::JointSettings, b"[\r\n\t{\r\n\t\t\"@device\": 0"),
            (ReplyKind::Motion, b"{\"slot\": 3"),
        ] {
            let mut reader = ReplyReader::new();
            reader.expect(kind);
            // The key's closing quote: the second quote in the text.
            let key_end = text.iter().enumerate().filter(|(_, b)| **b == b'"').nth(1).unwrap().0;
            for (cut, byte) in text.iter().enumerate() {
                reader.push(&[*byte]);
                assert_eq!(reader.recognised(), cut >= key_end, "{kind:?} after {} bytes", cut + 1);
            }
        }
        let mut noise = ReplyReader::new();
        noise.expect(ReplyKind::Motion);
        noise.push(b"{\x07\x93\"slot\"");
        assert!(!noise.recognised());
    }

    /// An erased slot is known from its first bytes, long before its 300 KB end.
    #[test]
    fn an_erased_slot_is_known_from_its_first_bytes() {
        let mut reader = ReplyReader::new();
        reader.expect(ReplyKind::Motion);
        let erased = b"{\r\n\t\"slot\": 255,\r\n\t\"name\": \"\xff\xff";
        for (cut, _) in erased.iter().enumerate() {
            let mut reader = ReplyReader::new();
            reader.expect(ReplyKind::Motion);
            reader.push(&erased[..cut]);
            // "slot": 2 could still become 25 or 255: undecided until a byte follows the number.
            let whole = cut > erased.iter().position(|b| *b == b',').unwrap();
            assert_eq!(reader.erased_slot(), whole.then_some(true), "after {cut} bytes");
        }
        reader.push(b"{\r\n\t\"slot\": 7,\r\n");
        assert_eq!(reader.erased_slot(), Some(false), "a written slot prints its own number");
        reader.expect(ReplyKind::Version);
        reader.push(b"{\"slot\": 255,");
        assert_eq!(reader.erased_slot(), None, "only <MO has slots");
    }

    #[test]
    fn garbage_of_any_size_is_drained_and_never_kept() {
        let mut reader = ReplyReader::new();
        reader.expect(ReplyKind::Motion);
        reader.push(b"{\"slot\": 3, \"name\": \"\xff\xfe\xfa\", \"@frame_length\": 255, \"frames\": [");
        for _ in 0..20_000 {
            reader.push(b"{\"outputs\": [{\"device\": 0, \"value\": 0}]},");
            assert!(reader.kept.len() <= MAX_REPLY_BYTES);
        }
        reader.push(b"{}]}");
        let events: Vec<_> = std::iter::from_fn(|| reader.poll()).collect();
        assert!(
            events.iter().any(|e| matches!(e, ReplyEvent::Oversized { kind: ReplyKind::Motion, .. })),
            "{:?}",
            events.len()
        );
        // A garbage slot that fits is read and called empty.
        let small = b"{\"slot\": 3, \"name\": \"\xff\xfe\", \"@frame_length\": 255, \"codes\": [], \"frames\": []}";
        assert_eq!(decode_motion(small), None);
    }
}
