//! The getters' replies as the firmware prints them: `<VI`, `<JS`, and `<MO`
//! (tab indentation, CRLF, no end marker; a never-written slot prints the
//! erased EEPROM's garbage).

use std::fmt::Write as _;

use super::{JointLimits, Slot};
use crate::protocol::plen2::{DEVICE_IDS, MotionHeader};

/// `<VI`: the firmware's version.
pub(super) const VERSION_REPLY: &[u8] =
    b"{\r\n\t\"device\": \"PLEN2\",\r\n\t\"codename\": \"Cytisus\",\r\n\t\"version\": \"1.4.2\"\r\n}\r\n";

/// `<JS`: every joint's limits and home, as the firmware prints them.
pub(super) fn joint_settings_json(joints: &[JointLimits; DEVICE_IDS]) -> String {
    let mut text = String::from("[\r\n");
    for (device, joint) in joints.iter().enumerate() {
        let comma = if device + 1 < DEVICE_IDS { "," } else { "" };
        let _ = write!(
            text,
            "\t{{\r\n\t\t\"@device\": {device},\r\n\t\t\"max\": {},\r\n\t\t\"min\": {},\r\n\t\t\"home\": {}\r\n\t}}{comma}\r\n",
            joint.max, joint.min, joint.home
        );
    }
    text.push_str("]\r\n");
    text
}

/// A slot's header as a never-written EEPROM page reads: every byte 0xff,
/// so its own slot field says 255 (plen2.md §3).
pub(super) fn garbage_header() -> MotionHeader {
    MotionHeader {
        slot: 0xff,
        name: [0xff; 20],
        loop_on: true,
        loop_begin: 0xff,
        loop_end: 0xff,
        loop_count: 0xff,
        jump_on: true,
        jump_slot: 0xff,
        frame_count: 0xff,
    }
}

/// `<MO` in the firmware's layout. A never-written slot prints its garbage:
/// frame length 255, a name that is not UTF-8, 255 frames of 24 outputs.
pub(super) fn motion_json(stored: Option<&Slot>) -> Vec<u8> {
    let garbage = garbage_header();
    let header = stored.map_or(&garbage, |s| &s.header);
    let mut out = Vec::new();
    // The header's own slot byte: the slot asked for, or 255 read from erased EEPROM.
    out.extend_from_slice(format!("{{\r\n\t\"slot\": {},\r\n\t\"name\": \"", header.slot).as_bytes());
    out.extend_from_slice(&header.name);
    let frames = usize::from(header.frame_count);
    let mut text = format!("\",\r\n\t\"@frame_length\": {frames},\r\n\t\"codes\": [");
    let mut codes = Vec::new();
    if header.loop_on {
        codes.push(format!(
            "\r\n\t\t{{\r\n\t\t\t\"method\": \"loop\",\r\n\t\t\t\"arguments\": [{}, {}, {}]\r\n\t\t}}",
            header.loop_begin, header.loop_end, header.loop_count
        ));
    }
    if header.jump_on {
        codes.push(format!(
            "\r\n\t\t{{\r\n\t\t\t\"method\": \"jump\",\r\n\t\t\t\"arguments\": [{}]\r\n\t\t}}",
            header.jump_slot
        ));
    }
    text.push_str(&codes.join(","));
    // No code at all still prints the list's line break and indent: `[`, CRLF, a tab, `],`.
    text.push_str("\r\n\t],\r\n\t\"frames\": [");
    for index in 0..frames {
        let frame = stored.and_then(|s| s.frames.get(index).cloned().flatten());
        // An unwritten frame reads erased EEPROM: 0xffff everywhere.
        let (transition, values) = frame.map_or((0xffff, [-1; DEVICE_IDS]), |f| (f.transition_ms, f.values));
        let _ = write!(
            text,
            "\r\n\t\t{{\r\n\t\t\t\"@index\": {index},\r\n\t\t\t\"transition_time_ms\": {transition},\r\n\t\t\t\"outputs\": ["
        );
        for (device, value) in values.iter().enumerate() {
            let comma = if device + 1 < DEVICE_IDS { "," } else { "" };
            let _ = write!(
                text,
                "\r\n\t\t\t\t{{\r\n\t\t\t\t\t\"device\": {device},\r\n\t\t\t\t\t\"value\": {value}\r\n\t\t\t\t}}{comma}"
            );
        }
        text.push_str("\r\n\t\t\t]\r\n\t\t}");
        if index + 1 < frames {
            text.push(',');
        }
    }
    text.push_str(if frames == 0 { "]\r\n}\r\n" } else { "\r\n\t]\r\n}\r\n" });
    out.extend_from_slice(text.as_bytes());
    out
}
