//! A file's bytes as the text its tool meant: a UTF-8 or UTF-16 byte-order
//! mark, RoboPlus's 2-byte checksum after the last page (the ones' complement
//! of the 16-bit sum of every byte before it, high byte first), and names
//! saved in a legacy code page, each said in a note rather than refused.

use super::format::ReadError;

/// A file's text and what was done to read it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Decoded {
    /// The text, without its byte-order mark or checksum.
    pub text: String,
    /// What reading it took, for the report ("a RoboPlus checksum … matches").
    pub notes: Vec<String>,
}

/// `bytes` as text; only UTF-16 that is not UTF-16 is refused (with its line).
/// Bytes given whole (a `Vec`) become the text in place, not copied: a large
/// file is held once.
pub fn decode(bytes: impl Into<Vec<u8>>) -> Result<Decoded, ReadError> {
    let mut bytes = bytes.into();
    let mut notes = Vec::new();
    if let Some(units) = utf16_units(&bytes) {
        let text = char::decode_utf16(units?).collect::<Result<String, _>>().map_err(|_| ReadError {
            line: None,
            element: None,
            message: "UTF-16 text with a broken character: save it again as UTF-8".into(),
        })?;
        notes.push("read as UTF-16 (its byte-order mark says so)".into());
        return Ok(Decoded { text, notes });
    }
    let end = checksum_trailer(&bytes, &mut notes).len();
    bytes.truncate(end);
    if bytes.starts_with(b"\xef\xbb\xbf") {
        bytes.drain(..3);
    }
    let text = match String::from_utf8(bytes) {
        Ok(text) => text,
        Err(error) => {
            let body = error.as_bytes();
            let valid = error.utf8_error().valid_up_to();
            let line = body[..valid].iter().filter(|b| **b == b'\n').count() + 1;
            notes.push(format!(
                "bytes that are not UTF-8 (the first on line {line}) are shown as \u{fffd}: a name saved in another code page; save the file as UTF-8 to keep it"
            ));
            String::from_utf8_lossy(body).into_owned()
        }
    };
    Ok(Decoded { text, notes })
}

/// UTF-16 code units when the bytes start with a UTF-16 byte-order mark.
fn utf16_units(bytes: &[u8]) -> Option<Result<Vec<u16>, ReadError>> {
    let little = match bytes {
        [0xff, 0xfe, ..] => true,
        [0xfe, 0xff, ..] => false,
        _ => return None,
    };
    let rest = &bytes[2..];
    if !rest.len().is_multiple_of(2) {
        return Some(Err(ReadError {
            line: None,
            element: None,
            message: "UTF-16 text of an odd number of bytes: the file is cut short".into(),
        }));
    }
    let pair = |chunk: &[u8]| {
        if little { u16::from_le_bytes([chunk[0], chunk[1]]) } else { u16::from_be_bytes([chunk[0], chunk[1]]) }
    };
    Some(Ok(rest.chunks_exact(2).map(pair).collect()))
}

/// The bytes before a RoboPlus checksum, when the file ends with one after
/// its last `page_end`; a note says whether it matches.
fn checksum_trailer<'a>(bytes: &'a [u8], notes: &mut Vec<String>) -> &'a [u8] {
    const END: &[u8] = b"page_end";
    let Some(at) = bytes.windows(END.len()).rposition(|window| window == END) else { return bytes };
    let mut body_end = at + END.len();
    if bytes[body_end..].starts_with(b"\r\n") {
        body_end += 2;
    } else if bytes[body_end..].starts_with(b"\n") {
        body_end += 1;
    }
    let written = match &bytes[body_end..] {
        [high, low] | [high, low, b'\n'] | [high, low, b'\r', b'\n'] => [*high, *low],
        _ => return bytes,
    };
    let sum = bytes[..body_end].iter().fold(0u16, |sum, byte| sum.wrapping_add(u16::from(*byte)));
    let expected = !sum;
    let found = u16::from_be_bytes(written);
    notes.push(if found == expected {
        "RoboPlus's checksum after the last page matches: the file is as RoboPlus saved it".into()
    } else {
        format!(
            "RoboPlus's checksum after the last page is {found:04X}, the content's is {expected:04X}: the file was edited outside RoboPlus (it is read all the same)"
        )
    });
    &bytes[..body_end]
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    /// A RoboPlus file's bytes as RoboPlus saves them: a BOM, the text, its checksum.
    fn saved(text: &str) -> Vec<u8> {
        let mut bytes = b"\xef\xbb\xbf".to_vec();
        bytes.extend_from_slice(text.as_bytes());
        let sum = bytes.iter().fold(0u16, |sum, byte| sum.wrapping_add(u16::from(*byte)));
        bytes.extend_from_slice(&(!sum).to_be_bytes());
        bytes
    }

    #[test]
    fn a_roboplus_file_loses_its_mark_and_checksum() {
        let text = "type=motion\npage_begin\npage_end\n";
        let read = decode(saved(text)).unwrap();
        assert_eq!(read.text, text);
        assert!(read.notes[0].contains("matches"), "{:?}", read.notes);
        let mut edited = saved(text);
        edited[5] = b'X';
        edited.push(b'\n');
        let read = decode(edited.as_slice()).unwrap();
        assert!(read.notes[0].contains("edited outside RoboPlus"), "{:?}", read.notes);
        assert!(read.text.ends_with("page_end\n"));
    }

    #[test]
    fn utf16_and_legacy_code_pages_are_read() {
        let mut utf16 = vec![0xff, 0xfe];
        for unit in "name=舞".encode_utf16() {
            utf16.extend_from_slice(&unit.to_le_bytes());
        }
        assert_eq!(decode(utf16.as_slice()).unwrap().text, "name=舞");
        assert!(decode(&utf16[..utf16.len() - 1]).is_err());
        let latin1 = b"type=motion\nname=Se\xf1or\n";
        let read = decode(latin1).unwrap();
        assert_eq!(read.text, "type=motion\nname=Se\u{fffd}or\n");
        assert!(read.notes[0].contains("line 2"), "{:?}", read.notes);
    }

    #[test]
    fn plain_text_is_untouched() {
        let read = decode(b"<UscSettings>page_end in a comment</UscSettings>").unwrap();
        assert_eq!((read.text.as_str(), read.notes.len()), ("<UscSettings>page_end in a comment</UscSettings>", 0));
    }
}
