//! Properties of the rFLEX receiver: any chunking and interleaved line noise
//! never lose a valid frame, stuffed or not; random bytes never panic and
//! never make it hold more than a frame's worth.

#![allow(clippy::unwrap_used)]

use proptest::prelude::*;
use servo_studio::protocol::rflex::{DecoderEvent, Frame, FrameDecoder};

fn frame() -> impl Strategy<Value = Frame> {
    (1u8..=6, any::<u8>(), any::<u8>(), prop::collection::vec(any::<u8>(), 0..40))
        .prop_map(|(port, id, opcode, data)| Frame { port, id, opcode, data })
}

/// Line noise: any byte but the escape byte `1B`, which noise cannot fake a frame without.
fn noise() -> impl Strategy<Value = Vec<u8>> {
    prop::collection::vec(any::<u8>().prop_filter("not 1B", |b| *b != 0x1b), 0..12)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn chunking_and_noise_never_lose_a_valid_frame(
        items in prop::collection::vec((noise(), frame(), any::<bool>()), 1..8),
        trailing in noise(),
        chunk in 1usize..17,
    ) {
        let mut stream = Vec::new();
        for (garbage, frame, stuffed) in &items {
            stream.extend(garbage);
            let bytes = if *stuffed { frame.to_stuffed_bytes() } else { frame.to_bytes() };
            stream.extend(bytes.unwrap());
        }
        stream.extend(&trailing);
        let mut decoder = FrameDecoder::new();
        let mut got = Vec::new();
        for piece in stream.chunks(chunk) {
            decoder.push(piece);
            while let Some(event) = decoder.poll() {
                if let DecoderEvent::Frame { frame, .. } = event {
                    got.push(frame);
                }
            }
        }
        let expected: Vec<Frame> = items.into_iter().map(|(_, frame, _)| frame).collect();
        prop_assert_eq!(got, expected);
    }

    #[test]
    fn random_bytes_never_panic_and_memory_stays_bounded(
        bytes in prop::collection::vec(any::<u8>(), 0..4000),
        chunk in 1usize..64,
    ) {
        let mut decoder = FrameDecoder::new();
        for piece in bytes.chunks(chunk) {
            decoder.push(piece);
            while decoder.poll().is_some() {}
            prop_assert!(decoder.pending() <= 800 + chunk, "holds {} bytes", decoder.pending());
        }
    }

    #[test]
    fn escape_heavy_frames_round_trip(data in prop::collection::vec(prop_oneof![Just(0x1bu8), Just(0x7c), Just(0x02), Just(0x03), Just(0x00), Just(0x01)], 0..60), stuffed in any::<bool>()) {
        let frame = Frame { port: 2, id: 0, opcode: 33, data };
        let bytes = if stuffed { frame.to_stuffed_bytes() } else { frame.to_bytes() }.unwrap();
        let mut decoder = FrameDecoder::new();
        decoder.push(&bytes);
        let got: Vec<Frame> = std::iter::from_fn(|| decoder.poll())
            .map(|event| match event {
                DecoderEvent::Frame { frame, .. } => Ok(frame),
                skipped @ DecoderEvent::Skipped { .. } => Err(skipped),
            })
            .collect::<Result<_, _>>()
            .map_err(|skipped| TestCaseError::fail(format!("{skipped:?}")))?;
        prop_assert_eq!(got, vec![frame]);
    }
}
