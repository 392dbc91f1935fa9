//! rFLEX codec against the bytes and rules of `rflex.md`.

#![allow(clippy::unwrap_used)]

use servo_studio::protocol::rflex::{
    Axis, B21R, Command, DecoderEvent, Frame, FrameDecoder, MAGELLAN, Report, SkipReason, SonarReading,
    avoid_escape_bytes, normalise,
};

fn hex(text: &str) -> Vec<u8> {
    text.split_whitespace().map(|b| u8::from_str_radix(b, 16).unwrap()).collect()
}

fn decode_all(bytes: &[u8]) -> Vec<DecoderEvent> {
    let mut decoder = FrameDecoder::new();
    decoder.push(bytes);
    std::iter::from_fn(|| decoder.poll()).collect()
}

fn frames(events: &[DecoderEvent]) -> Vec<Frame> {
    events
        .iter()
        .filter_map(|event| match event {
            DecoderEvent::Frame { frame, .. } => Some(frame.clone()),
            DecoderEvent::Skipped { .. } => None,
        })
        .collect()
}

#[test]
fn golden_frames_from_rflex_md() {
    let odometry_on = Command::OdometryReports { period_us: 100_000, axis_mask: 3 };
    assert_eq!(odometry_on.to_frame().to_bytes().unwrap(), hex("1b 02 02 00 22 08 00 01 86 a0 00 00 00 03 0c 1b 03"));
    assert_eq!(Command::MotionDefaults.to_frame().to_bytes().unwrap(), hex("1b 02 02 00 0a 00 08 1b 03"));
    assert_eq!(Command::BrakeRelease.to_frame().to_bytes().unwrap(), hex("1b 02 02 00 0c 00 0e 1b 03"));
    // And back, as a base reads them.
    for command in [odometry_on, Command::MotionDefaults, Command::BrakeRelease] {
        let events = decode_all(&command.to_frame().to_bytes().unwrap());
        assert_eq!(Command::from_frame(&frames(&events)[0]).unwrap(), command);
    }
}

#[test]
fn the_0x1b_rule_on_both_bytes() {
    assert_eq!(avoid_escape_bytes(0x1B40), 0x1AFF);
    assert_eq!(avoid_escape_bytes(0x1B90), 0x1C00);
    assert_eq!(avoid_escape_bytes(0x1B90_1234), 0x1C90_1234);
    assert_eq!(avoid_escape_bytes(0x1B40_1234), 0x1AFF_1234);
    assert_eq!(avoid_escape_bytes(0x1234), 0x1234, "other speeds are untouched");
    // Bits 8–15 first, then bits 24–31.
    assert_eq!(avoid_escape_bytes(0x1B40_1B40), 0x1AFF_1AFF);
}

#[test]
fn a_drive_command_is_translation_then_rotation_with_the_reference_constants() {
    let [translation, rotation] = B21R.drive(0.5, -0.1, 0.3);
    assert_eq!(
        translation,
        Command::AxisSetDir { axis: 0, speed: 51_500, acceleration: 30_900, torque: 30_000, direction: 1 }
    );
    assert_eq!(
        rotation,
        Command::AxisSetDir { axis: 1, speed: 3_500, acceleration: 100_000, torque: 35_000, direction: 0 }
    );
    // 0.2 rad/s is 7000 = 0x1B58 angle units: bits 8–15 are 0x1B, so 0x1AFF is sent.
    let [_, rotation] = B21R.drive(0.0, 0.2, 0.3);
    assert!(matches!(rotation, Command::AxisSetDir { speed: 0x1AFF, .. }), "{rotation:?}");
    // Translation speeds are never adjusted: 0x1B58 distance units go as they are.
    let metres = f64::from(0x1B58u32) / B21R.distance_units_per_m + 1e-9;
    assert!(matches!(B21R.drive(metres, 0.0, 0.0)[0], Command::AxisSetDir { speed: 0x1B58, .. }));
    let [translation, rotation] = B21R.stop(0.3);
    assert!(matches!(translation, Command::AxisSetDir { speed: 0, direction: 1, .. }));
    assert!(matches!(rotation, Command::AxisSetDir { speed: 0, direction: 1, .. }));
    // Truncated toward zero: 0.00001 m/s on a Magellan is 0.31 units.
    assert!(matches!(MAGELLAN.drive(0.00001, 0.0, 0.0)[0], Command::AxisSetDir { speed: 0, .. }));
}

#[test]
fn reports_are_read_at_the_documented_offsets() {
    // MOT_SYSTEM_REPORT, LEN 25: @6 unknown, @10 timestamp, @14 axis, @15 position, @19 velocity…
    let mut data = vec![0, 0, 0, 9, 0, 0, 0x12, 0x34, 1];
    data.extend((-35_000i32).to_be_bytes());
    data.extend(700i32.to_be_bytes());
    data.extend(100_000u32.to_be_bytes());
    data.extend(35_000u32.to_be_bytes());
    let frame = Frame { port: 2, id: 7, opcode: 33, data };
    let bytes = frame.to_bytes().unwrap();
    assert_eq!(bytes[14], 1, "axis at offset 14");
    assert_eq!(&bytes[15..19], &(-35_000i32).to_be_bytes(), "position at offset 15");
    let report = Report::from_frame(&frames(&decode_all(&bytes))[0]).unwrap();
    assert_eq!(
        report,
        Report::Odometry {
            unknown: 9,
            timestamp: 0x1234,
            axis: 1,
            position: -35_000,
            velocity: 700,
            acceleration: 100_000,
            torque: 35_000
        }
    );
    // SYS_STATUS: @6 timestamp, @10 voltage, @14 brake.
    let status = Report::Status { timestamp: 5, voltage_raw: 2_650, brake: 1 };
    let bytes = status.to_frame(1).to_bytes().unwrap();
    assert_eq!(&bytes[10..14], &2_650u32.to_be_bytes());
    assert_eq!(bytes[14], 1);
    assert!((B21R.volts(2_650) - 27.7).abs() < 1e-9, "raw / 100 + 1.2 V");
    // SONAR_REPORT: (id u8, range u16) pairs after 8 bytes.
    let sonar = Report::Sonar {
        unknown: 0,
        timestamp: 1,
        readings: vec![SonarReading { sonar_id: 17, range: 1476 }, SonarReading { sonar_id: 18, range: 3001 }],
    };
    let bytes = sonar.to_frame(2).to_bytes().unwrap();
    assert_eq!(&bytes[14..17], &[17, 0x05, 0xc4]);
    assert_eq!(Report::from_frame(&frames(&decode_all(&bytes))[0]).unwrap(), sonar);
    assert_eq!(B21R.layout.range_m(1476), Some(1.0));
    assert_eq!(MAGELLAN.layout.range_m(1474), Some(1.0), "the Magellan's own scale");
    assert_eq!(B21R.layout.range_m(3001), None, "above 3000 is no echo");
    // DIO_REPORT: @10 address, @11 data u16.
    let dio = Report::Dio { timestamp: 3, address: 0x41, data: 0x0005 };
    let bytes = dio.to_frame(3).to_bytes().unwrap();
    assert_eq!(&bytes[10..13], &[0x41, 0x00, 0x05]);
    // JSTK reply: @10 x, @14 y, @18 buttons.
    let stick = Report::Joystick { timestamp: 4, x: -20, y: 30, buttons: 0b101 };
    let bytes = stick.to_frame(4).to_bytes().unwrap();
    assert_eq!(bytes[18], 0b101);
    assert_eq!(Report::from_frame(&frames(&decode_all(&bytes))[0]).unwrap(), stick);
}

#[test]
fn stuffed_and_unstuffed_frames_both_decode() {
    // Data holding 1B and 7C: stuffed as 1B 00 and 7C 1B 01, LEN and CHK over the plain bytes.
    let frame = Frame { port: 2, id: 0, opcode: 7, data: vec![1, 0x1b, 0x03, 0x7c, 0x1b, 0x02, 9] };
    let stuffed = frame.to_stuffed_bytes().unwrap();
    let plain = frame.to_bytes().unwrap();
    assert_eq!(&stuffed[..8], &[0x1b, 0x02, 0x02, 0x00, 0x07, 0x07, 0x01, 0x1b]);
    assert_eq!(&stuffed[8..14], &[0x00, 0x03, 0x7c, 0x1b, 0x01, 0x1b]);
    for (bytes, was_stuffed) in [(stuffed, true), (plain, false)] {
        let events = decode_all(&bytes);
        assert_eq!(events, [DecoderEvent::Frame { frame: frame.clone(), stuffed: was_stuffed }], "{bytes:02x?}");
    }
}

#[test]
fn garbage_corruption_and_cut_frames_are_skipped_and_the_stream_resynchronises() {
    let good = Report::Status { timestamp: 1, voltage_raw: 2_500, brake: 0 }.to_frame(9).to_bytes().unwrap();
    let mut corrupt = good.clone();
    corrupt[8] ^= 0x40; // a data byte: the checksum no longer matches
    let cut = &good[..7];
    let mut stream = hex("00 ff 55");
    stream.extend(&corrupt);
    stream.extend(cut);
    stream.extend(&good);
    let events = decode_all(&stream);
    assert_eq!(events[0], DecoderEvent::Skipped { bytes: 3, reason: SkipReason::Garbage });
    assert!(events.iter().any(|e| matches!(e, DecoderEvent::Skipped { reason: SkipReason::BadFrame, .. })));
    assert_eq!(frames(&events).len(), 1, "only the good frame: {events:?}");
    assert_eq!(
        Report::from_frame(&frames(&events)[0]).unwrap(),
        Report::Status { timestamp: 1, voltage_raw: 2_500, brake: 0 }
    );
    let skipped: usize = events
        .iter()
        .map(|e| match e {
            DecoderEvent::Skipped { bytes, .. } => *bytes,
            DecoderEvent::Frame { .. } => 0,
        })
        .sum();
    assert_eq!(skipped, 3 + corrupt.len() + cut.len(), "every byte is accounted for");

    // A frame cut short whose LEN promises more than will come: given up as soon
    // as a whole frame follows, not after 255 more bytes.
    let mut stream = hex("1b 02 01 09 01 ff 00 00");
    stream.extend(&good);
    let mut decoder = FrameDecoder::new();
    decoder.push(&stream);
    let events: Vec<_> = std::iter::from_fn(|| decoder.poll()).collect();
    assert_eq!(events[0], DecoderEvent::Skipped { bytes: 8, reason: SkipReason::Truncated });
    assert_eq!(frames(&events).len(), 1);
    assert_eq!(decoder.pending(), 0);
}

#[test]
fn a_frame_split_anywhere_waits_for_its_end() {
    let bytes = B21R.drive(0.25, 0.1, 0.5)[0].to_frame().to_bytes().unwrap();
    for split in 0..bytes.len() {
        let mut decoder = FrameDecoder::new();
        decoder.push(&bytes[..split]);
        assert!(
            std::iter::from_fn(|| decoder.poll()).all(|e| !matches!(e, DecoderEvent::Frame { .. })),
            "nothing before the end (split {split})"
        );
        decoder.push(&bytes[split..]);
        let events: Vec<_> = std::iter::from_fn(|| decoder.poll()).collect();
        assert_eq!(frames(&events).len(), 1, "split {split}: {events:?}");
    }
}

#[test]
fn odometry_integrates_from_the_first_report() {
    let mut pose = servo_studio::protocol::rflex::Odometry::default();
    pose.update(&B21R, Axis::Translation, 1_000_000);
    pose.update(&B21R, Axis::Rotation, -5_000);
    assert_eq!((pose.x_m, pose.y_m, pose.theta_rad), (0.0, 0.0, 0.0), "the first report is the origin");
    pose.update(&B21R, Axis::Translation, 1_103_000); // 1 m straight ahead
    pose.update(&B21R, Axis::Rotation, -5_000 + 54_978); // a quarter turn left (π/2 × 35000)
    pose.update(&B21R, Axis::Translation, 1_154_500); // 0.5 m north
    assert!((pose.x_m - 1.0).abs() < 1e-5 && (pose.y_m - 0.5).abs() < 1e-5, "{pose:?}");
    assert!((pose.theta_rad - std::f64::consts::FRAC_PI_2).abs() < 1e-4);
    assert!((normalise(3.0 * std::f64::consts::PI).abs() - std::f64::consts::PI).abs() < 1e-12, "±π");
    assert!((normalise(-3.5 * std::f64::consts::PI) - 0.5 * std::f64::consts::PI).abs() < 1e-12);
}
