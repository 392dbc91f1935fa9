//! The packets of the ROBOTIS e-Manual's own examples, byte for byte
//! ("DYNAMIXEL Protocol 2.0": Ping, Read and Write examples, ID 1;
//! "DYNAMIXEL Protocol 1.0" / the RX-28 and AX-12 manuals: Ping and Read
//! examples). Each example's checksum was checked against the bytes printed
//! there, so a misreading here would show as a failed CRC.

use super::*;

fn hex(text: &str) -> Vec<u8> {
    text.split_whitespace().map(|byte| u8::from_str_radix(byte, 16).unwrap()).collect()
}

/// Each packet written as `printed`, and read back from it by a reader of its side of the bus.
fn written_and_read_as_printed<const N: usize>(examples: [(Packet, &str); N]) {
    for (packet, printed) in examples {
        assert_eq!(packet.to_bytes(), hex(printed), "{packet:?}");
        let mut reader =
            if matches!(packet.kind, Kind::Status(_)) { Packets::statuses() } else { Packets::instructions() };
        assert_eq!(reader.push(&hex(printed)), [Read::Packet(packet)]);
    }
}

/// Protocol 2.0's examples: each written as the manual prints it, and each read back.
#[test]
fn the_manual_s_protocol_2_examples_are_written_and_read_byte_for_byte() {
    let examples = [
        // Ping ID 1; its status: model number 1030 (0x0406), firmware 0x26.
        (Packet::instruction(Protocol::Two, 1, instruction::PING, vec![]), "FF FF FD 00 01 03 00 01 19 4E"),
        (Packet::status(Protocol::Two, 1, 0, vec![0x06, 0x04, 0x26]), "FF FF FD 00 01 07 00 55 00 06 04 26 65 5D"),
        // Read 4 bytes at 132 (Present Position); its status: 166.
        (
            Packet::instruction(Protocol::Two, 1, instruction::READ, vec![0x84, 0x00, 0x04, 0x00]),
            "FF FF FD 00 01 07 00 02 84 00 04 00 1D 15",
        ),
        (Packet::status(Protocol::Two, 1, 0, vec![0xA6, 0, 0, 0]), "FF FF FD 00 01 08 00 55 00 A6 00 00 00 8C C0"),
        // Write 512 at 116 (Goal Position); its status.
        (
            Packet::instruction(Protocol::Two, 1, instruction::WRITE, vec![0x74, 0x00, 0x00, 0x02, 0x00, 0x00]),
            "FF FF FD 00 01 09 00 03 74 00 00 02 00 00 CA 89",
        ),
        (Packet::status(Protocol::Two, 1, 0, vec![]), "FF FF FD 00 01 04 00 55 00 A1 0C"),
    ];
    written_and_read_as_printed(examples);
}

/// Protocol 1.0's examples: a ping of ID 1 and its status; a read of the
/// temperature (1 byte at 43) and its status, 32 °C.
#[test]
fn the_manual_s_protocol_1_examples_are_written_and_read_byte_for_byte() {
    let examples = [
        (Packet::instruction(Protocol::One, 1, instruction::PING, vec![]), "FF FF 01 02 01 FB"),
        (Packet::status(Protocol::One, 1, 0, vec![]), "FF FF 01 02 00 FC"),
        (Packet::instruction(Protocol::One, 1, instruction::READ, vec![0x2B, 0x01]), "FF FF 01 04 02 2B 01 CC"),
        (Packet::status(Protocol::One, 1, 0, vec![0x20]), "FF FF 01 03 00 20 DB"),
    ];
    written_and_read_as_printed(examples);
}

/// `FF FF FD` inside a 2.0 packet is stuffed as it is sent (LEN and CRC
/// counting the stuffed bytes) and unstuffed as it is read.
#[test]
fn a_header_inside_a_protocol_2_packet_is_stuffed_and_read_back_whole() {
    let packet = Packet::instruction(Protocol::Two, 3, instruction::WRITE, vec![0x74, 0x00, 0xFF, 0xFF, 0xFD, 0x01]);
    let bytes = packet.to_bytes();
    assert_eq!(&bytes[7..15], [0x03, 0x74, 0x00, 0xFF, 0xFF, 0xFD, 0xFD, 0x01], "{bytes:02X?}");
    assert_eq!(u16::from_le_bytes([bytes[5], bytes[6]]), 10, "the instruction, 7 parameters as stuffed, the CRC");
    assert_eq!(Packets::instructions().push(&bytes), [Read::Packet(packet)]);
}

/// Both protocols on one bus, in pieces, with noise and a packet whose
/// checksum fails between them: every good packet is read, in order, the
/// rest skipped and said.
#[test]
fn packets_of_both_protocols_are_read_through_pieces_noise_and_a_failed_checksum() {
    let mut bytes = vec![0x00, 0x13];
    bytes.extend(hex("FF FF FD 00 01 03 00 01 19 4E"));
    let mut broken = hex("FF FF 01 04 02 2B 01 CC");
    broken[5] = 0x2C;
    bytes.extend(broken);
    bytes.extend(hex("FF FF 01 04 02 2B 01 CC"));
    bytes.push(0xFF);
    bytes.extend(hex("FF FF FD 00 01 07 00 02 84 00 04 00 1D 15"));
    let mut reader = Packets::instructions();
    let read: Vec<Read> = bytes.chunks(3).flat_map(|piece| reader.push(piece)).collect();
    let packets: Vec<(Protocol, u8)> = read
        .iter()
        .filter_map(|read| match read {
            Read::Packet(Packet { protocol, kind: Kind::Instruction(code), .. }) => Some((*protocol, *code)),
            _ => None,
        })
        .collect();
    assert_eq!(packets, [(Protocol::Two, 1), (Protocol::One, 2), (Protocol::Two, 2)], "{read:?}");
    assert!(read.contains(&Read::Skipped { bytes: 1, why: "a 1.0 packet whose checksum fails" }), "{read:?}");
}
