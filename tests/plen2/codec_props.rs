//! Property tests of the PLEN2 codec: any motion encoded, read by the
//! emulated firmware and read back decodes to the same motion; the reply
//! reader takes any bytes without panicking; garbage replies of any length
//! are drained in bounded memory.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::time::{Duration, Instant};

use proptest::prelude::*;
use servo_studio::device::plen2::{motion_commands, motion_from_reply};
use servo_studio::link::Driver;
use servo_studio::project::plen2::{Frame, Joint, LoopRange, Motion, Pose};
use servo_studio::protocol::plen2::{
    Command, MAX_FRAMES, MAX_REPLY_BYTES, MAX_TRANSITION_MS, MIN_TRANSITION_MS, ReplyEvent, ReplyKind, ReplyReader,
    SLOTS, decode_joint_settings, decode_motion, decode_version, parse_commands,
};
use servo_studio::sim::{Plen2Sim, Plen2Timing};

fn pose() -> impl Strategy<Value = Pose> {
    proptest::collection::vec(-900i16..=900, Joint::ALL.len()).prop_map(|values| {
        let mut pose = Pose::default();
        for (joint, value) in Joint::ALL.into_iter().zip(values) {
            pose.set(joint, value);
        }
        pose
    })
}

fn motion() -> impl Strategy<Value = Motion> {
    let frames = proptest::collection::vec(
        (MIN_TRANSITION_MS..=MAX_TRANSITION_MS, pose())
            .prop_map(|(transition_ms, values_tenths_deg)| Frame::new(transition_ms, values_tenths_deg)),
        1..=MAX_FRAMES,
    );
    (0..SLOTS, "[A-Za-z0-9][A-Za-z0-9 ()!-]{0,18}[A-Za-z0-9]", frames, any::<(u8, u8, u8)>(), any::<bool>(), 0..SLOTS)
        .prop_map(|(slot, name, frames, (a, b, count), looped, jump)| {
            let last = u8::try_from(frames.len() - 1).unwrap();
            let (begin, end) = (a % (last + 1), b % (last + 1));
            let loop_range =
                looped.then(|| LoopRange { begin_frame: begin.min(end), end_frame: begin.max(end), count });
            Motion { slot, name, frames, loop_range, jump_slot: looped.then_some(jump).filter(|j| j % 2 == 0) }
        })
}

/// Feeds `bytes` to the emulated firmware at `at`, lets it read them all.
fn feed(sim: &mut Plen2Sim, at: Instant, bytes: &[u8]) {
    sim.handle_input(at, bytes);
    let limit = at + Duration::from_secs(2);
    while let Some(deadline) = sim.poll_timeout().filter(|d| *d <= limit) {
        sim.handle_timeout(deadline);
        while sim.poll_transmit(deadline).is_some() {}
    }
}

/// Sends a getter and reads the reply the way the driver does.
fn ask(sim: &mut Plen2Sim, at: Instant, getter: &Command, kind: ReplyKind) -> Vec<u8> {
    let mut reader = ReplyReader::new();
    reader.expect(kind);
    sim.handle_input(at, getter.to_ascii().as_bytes());
    let limit = at + Duration::from_secs(5);
    while let Some(deadline) = sim.poll_timeout().filter(|d| *d <= limit) {
        sim.handle_timeout(deadline);
        while let Some(bytes) = sim.poll_transmit(deadline) {
            reader.push(&bytes);
        }
        while let Some(event) = reader.poll() {
            if let ReplyEvent::Complete { bytes, .. } = event {
                return bytes;
            }
        }
    }
    panic!("no reply to {getter:?}");
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    #[test]
    fn a_motion_encoded_read_by_the_firmware_and_read_back_is_the_same(motion in motion(), noise in "[\r\n x]{0,4}") {
        let commands = motion_commands(&motion);
        // What the firmware reads is exactly what was encoded, noise between commands ignored.
        let mut bytes = Vec::new();
        for command in &commands {
            bytes.extend_from_slice(command.to_ascii().as_bytes());
            bytes.extend_from_slice(noise.as_bytes());
        }
        let parsed: Vec<Command> = parse_commands(&bytes).into_iter().map(Result::unwrap).collect();
        prop_assert_eq!(&parsed, &commands);

        // Through the emulated robot, 24 bytes a millisecond (its ring holds 64),
        // each command given time for its EEPROM write.
        let mut sim = Plen2Sim::new(Plen2Timing::default());
        let mut at = Instant::now();
        for command in &commands {
            for chunk in format!("{}{noise}", command.to_ascii()).as_bytes().chunks(24) {
                feed(&mut sim, at, chunk);
                at += Duration::from_millis(1);
            }
            at += Duration::from_millis(20);
        }
        prop_assert_eq!(sim.state().lost_bytes, 0);
        let reply = ask(&mut sim, at, &Command::GetMotion { slot: motion.slot }, ReplyKind::Motion);
        let decoded = decode_motion(&reply).expect("a written slot decodes");
        prop_assert_eq!(motion_from_reply(&decoded), motion);
    }

    #[test]
    fn random_bytes_never_panic_the_reader_or_the_decoders(
        chunks in proptest::collection::vec(proptest::collection::vec(any::<u8>(), 0..200), 0..20),
        kind in prop_oneof![Just(ReplyKind::Version), Just(ReplyKind::JointSettings), Just(ReplyKind::Motion)],
    ) {
        let mut reader = ReplyReader::new();
        reader.expect(kind);
        for chunk in &chunks {
            reader.push(chunk);
            prop_assert!(reader.held() <= MAX_REPLY_BYTES);
            while let Some(event) = reader.poll() {
                if let ReplyEvent::Complete { bytes, .. } = event {
                    let _ = (decode_motion(&bytes), decode_joint_settings(&bytes), decode_version(&bytes));
                }
            }
        }
        let all: Vec<u8> = chunks.concat();
        let _ = (decode_motion(&all), decode_joint_settings(&all), decode_version(&all));
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 6, ..ProptestConfig::default() })]

    #[test]
    fn garbage_of_any_length_is_drained_in_bounded_memory(length in 0usize..3_000_000, seed in any::<u64>()) {
        let mut reader = ReplyReader::new();
        reader.expect(ReplyKind::Motion);
        reader.push(b"{\r\n\t\"slot\": 7,\r\n\t\"name\": \"");
        // Bytes that are not UTF-8 and never close the object (no quotes, no brackets).
        let mut state = seed | 1;
        let mut chunk = Vec::with_capacity(4096);
        let mut sent = 0;
        while sent < length {
            chunk.clear();
            for _ in 0..4096.min(length - sent) {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                let byte = state.to_le_bytes()[0] | 0x80;
                chunk.push(byte);
            }
            sent += chunk.len();
            reader.push(&chunk);
            prop_assert!(reader.held() <= MAX_REPLY_BYTES, "{} bytes held", reader.held());
        }
        // The end of it: the string and the object close.
        reader.push(b"\"}");
        let mut ended = false;
        while let Some(event) = reader.poll() {
            match event {
                ReplyEvent::Complete { bytes, .. } => {
                    prop_assert!(bytes.len() <= MAX_REPLY_BYTES);
                    prop_assert!(decode_motion(&bytes).is_none_or(|m| m.frames.is_empty()));
                    ended = true;
                }
                ReplyEvent::Oversized { bytes, .. } => {
                    prop_assert!(bytes > MAX_REPLY_BYTES);
                    ended = true;
                }
                ReplyEvent::Ignored { .. } => {}
            }
        }
        prop_assert!(ended, "the reply ended when its brackets balanced");
        prop_assert_eq!(reader.held(), 0);
    }
}
