//! An OSC datagram's shape, read before it is decoded: bundles nested at
//! most [`MOST_NESTING`] deep, arrays in a message's type tags at most
//! [`MOST_NESTING`] deep, at most [`MOST_MESSAGES`] messages — so that no
//! datagram (at most 64 KB, however built) can make the decoder recurse
//! deeply or the server answer it at length. Walked with a list, never by
//! recursion.

/// The deepest bundles (or arrays) may nest.
pub const MOST_NESTING: usize = 8;
/// The most messages one datagram may carry.
pub const MOST_MESSAGES: usize = 32;

/// Why a datagram is refused before it is decoded.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum Misshapen {
    /// Bundles nested too deep.
    #[error("bundles nested deeper than {MOST_NESTING}")]
    BundlesTooDeep,
    /// Arrays nested too deep in a message's type tags.
    #[error("arrays nested deeper than {MOST_NESTING} in a message's type tags")]
    ArraysTooDeep,
    /// Too many messages in one datagram.
    #[error("more than {MOST_MESSAGES} messages in one datagram")]
    TooManyMessages,
    /// Not OSC's framing at this byte.
    #[error("not an OSC packet (byte {at}: {what})")]
    NotOsc {
        /// The offset into the datagram.
        at: usize,
        /// What was wrong there.
        what: &'static str,
    },
}

const BUNDLE_TAG: &[u8] = b"#bundle\0";

/// How many messages `packet` carries, or why it is refused.
pub fn check(packet: &[u8]) -> Result<usize, Misshapen> {
    // (offset, length, depth) of each element still to look at.
    let mut pending = vec![(0usize, packet.len(), 0usize)];
    let mut messages = 0;
    while let Some((at, length, depth)) = pending.pop() {
        let element = &packet[at..at + length];
        if element.starts_with(BUNDLE_TAG) {
            if depth >= MOST_NESTING {
                return Err(Misshapen::BundlesTooDeep);
            }
            let mut offset = at + BUNDLE_TAG.len() + 8;
            let end = at + length;
            if offset > end {
                return Err(Misshapen::NotOsc { at, what: "a bundle without its time tag" });
            }
            while offset < end {
                let size = packet
                    .get(offset..offset + 4)
                    .and_then(|bytes| <[u8; 4]>::try_from(bytes).ok())
                    .map(i32::from_be_bytes)
                    .ok_or(Misshapen::NotOsc { at: offset, what: "a bundle element's size is cut off" })?;
                let size = usize::try_from(size)
                    .ok()
                    .filter(|size| *size > 0 && size.is_multiple_of(4) && offset + 4 + size <= end)
                    .ok_or(Misshapen::NotOsc { at: offset, what: "a bundle element's size does not fit" })?;
                pending.push((offset + 4, size, depth + 1));
                offset += 4 + size;
            }
        } else if element.first() == Some(&b'/') {
            messages += 1;
            if messages > MOST_MESSAGES {
                return Err(Misshapen::TooManyMessages);
            }
            if arrays_depth(element).ok_or(Misshapen::NotOsc { at, what: "a message's strings are cut off" })?
                > MOST_NESTING
            {
                return Err(Misshapen::ArraysTooDeep);
            }
        } else {
            return Err(Misshapen::NotOsc { at, what: "neither a message (/…) nor a bundle (#bundle)" });
        }
    }
    Ok(messages)
}

/// The deepest `[` nesting of a message's type tags (0 without tags); `None` when its strings are cut off.
fn arrays_depth(message: &[u8]) -> Option<usize> {
    let address_end = message.iter().position(|byte| *byte == 0)?;
    let tags_at = (address_end + 4) & !3;
    let Some(tags) = message.get(tags_at..) else { return Some(0) };
    if tags.first() != Some(&b',') {
        return Some(0);
    }
    let (mut depth, mut deepest) = (0usize, 0usize);
    for byte in tags.iter().take_while(|byte| **byte != 0) {
        match byte {
            b'[' => {
                depth += 1;
                deepest = deepest.max(depth);
            }
            b']' => depth = depth.saturating_sub(1),
            _ => {}
        }
    }
    Some(deepest)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rosc::{OscArray, OscBundle, OscMessage, OscPacket, OscTime, OscType};

    fn message(addr: &str, args: Vec<OscType>) -> OscPacket {
        OscPacket::Message(OscMessage { addr: addr.into(), args })
    }

    fn bundled(content: Vec<OscPacket>) -> OscPacket {
        OscPacket::Bundle(OscBundle { timetag: OscTime { seconds: 0, fractional: 1 }, content })
    }

    /// A bundle holding a bundle … `depth` deep, a message at the bottom — built as bytes (the encoder recurses).
    fn nested_bundles(depth: usize) -> Vec<u8> {
        let mut bytes = rosc::encoder::encode(&message("/stop", vec![])).unwrap();
        for _ in 0..depth {
            let mut outer = BUNDLE_TAG.to_vec();
            outer.extend_from_slice(&[0, 0, 0, 0, 0, 0, 0, 1]);
            outer.extend_from_slice(&i32::try_from(bytes.len()).unwrap().to_be_bytes());
            outer.extend_from_slice(&bytes);
            bytes = outer;
        }
        bytes
    }

    /// `/pose/a/b` with arrays nested `depth` deep, built as bytes.
    fn nested_arrays(depth: usize) -> Vec<u8> {
        let mut bytes = b"/pose/a/b\0\0\0".to_vec();
        let mut tags = b",".to_vec();
        tags.extend(std::iter::repeat_n(b'[', depth));
        tags.extend(std::iter::repeat_n(b']', depth));
        tags.push(0);
        while !tags.len().is_multiple_of(4) {
            tags.push(0);
        }
        bytes.extend(tags);
        bytes
    }

    #[test]
    fn what_qlab_sends_passes_with_its_count_of_messages() {
        let one = rosc::encoder::encode(&message("/pose/skull/jaw", vec![OscType::Float(20.0)])).unwrap();
        assert_eq!(check(&one), Ok(1));
        let two = bundled(vec![message("/stop", vec![]), bundled(vec![message("/show/play", vec![])])]);
        assert_eq!(check(&rosc::encoder::encode(&two).unwrap()), Ok(2));
        let array = message("/x", vec![OscType::Array(OscArray { content: vec![OscType::Int(1)] })]);
        assert_eq!(check(&rosc::encoder::encode(&array).unwrap()), Ok(1));
    }

    #[test]
    fn nesting_and_counts_over_the_bounds_are_refused_before_decoding() {
        assert_eq!(check(&nested_bundles(MOST_NESTING)), Ok(1));
        assert_eq!(check(&nested_bundles(MOST_NESTING + 1)), Err(Misshapen::BundlesTooDeep));
        // A datagram of nearly 64 KB that is bundles all the way down (one of
        // about 2,150 overflowed the decoder's stack).
        let deep = nested_bundles(3_200);
        assert!(deep.len() > 64_000);
        assert_eq!(check(&deep), Err(Misshapen::BundlesTooDeep));
        assert_eq!(check(&nested_arrays(MOST_NESTING)), Ok(1));
        assert_eq!(check(&nested_arrays(16_000)), Err(Misshapen::ArraysTooDeep));
        let many = bundled((0..=MOST_MESSAGES).map(|_| message("/stop", vec![])).collect());
        assert_eq!(check(&rosc::encoder::encode(&many).unwrap()), Err(Misshapen::TooManyMessages));
    }

    #[test]
    fn framing_that_lies_is_refused_where_it_lies() {
        assert!(matches!(check(b"garbage!"), Err(Misshapen::NotOsc { at: 0, .. })));
        let mut lying = nested_bundles(1);
        lying[16..20].copy_from_slice(&10_000i32.to_be_bytes());
        assert!(matches!(check(&lying), Err(Misshapen::NotOsc { at: 16, .. })));
        assert!(matches!(check(b"#bundle\0"), Err(Misshapen::NotOsc { .. })));
        assert!(matches!(check(b"/no-end"), Err(Misshapen::NotOsc { .. })));
    }

    proptest::proptest! {
        /// Any bytes are checked without a panic.
        #[test]
        fn any_bytes_are_checked_without_a_panic(bytes in proptest::collection::vec(proptest::prelude::any::<u8>(), 0..300)) {
            let _ = check(&bytes);
        }
    }
}
