//! DYNAMIXEL servos' side of the connection doctor: a Protocol 2.0
//! broadcast ping (every 2.0 servo answers with its model and firmware) and
//! a Protocol 1.0 ping of ID 1 (a Bioloid's first servo), sent together —
//! pings change nothing on any servo — and what the first servo to answer said.

use std::fmt;

use crate::device::family::{Heard, Identity, Recogniser, Said as SaidTrait};
use crate::project::Family;
use crate::protocol::dynamixel::table::known;
use crate::protocol::dynamixel::{BROADCAST, Kind, Packet, Packets, Protocol, Read, instruction};

/// What a servo on the bus said of itself.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Said {
    /// Its ID.
    pub id: u8,
    /// The protocol it answered in.
    pub protocol: Protocol,
    /// Its model number and firmware (a 2.0 ping says them; a 1.0 ping does not).
    pub model: Option<(u16, u8)>,
}

impl SaidTrait for Said {
    fn family(&self) -> Family {
        Family::Dynamixel
    }
}

impl Said {
    /// Its model's name, or its number, when it said one.
    pub fn model_name(&self) -> Option<String> {
        let (number, _) = self.model?;
        Some(known(number).map_or_else(|| format!("model {number}"), |model| model.name.to_string()))
    }

    /// "2.0" or "1.0".
    pub fn protocol_name(&self) -> &'static str {
        if self.protocol == Protocol::Two { "2.0" } else { "1.0" }
    }
}

impl fmt::Display for Said {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match (self.model_name(), self.model) {
            (Some(name), Some((_, firmware))) => {
                write!(f, "DYNAMIXEL {name}, ID {}, Protocol {}, firmware {firmware}", self.id, self.protocol_name())
            }
            _ => write!(f, "DYNAMIXEL servo, ID {}, Protocol {}", self.id, self.protocol_name()),
        }
    }
}

/// Reads status packets out of whatever comes: the first servo to answer
/// speaks for the bus (a broadcast is answered by each servo in turn, the
/// lowest ID first); later statuses are answers with nothing more to tell.
#[derive(Debug)]
struct Doctor {
    packets: Packets,
    answered: bool,
}

/// A fresh reader, as the doctor registry wants it.
pub(super) fn recogniser() -> Box<dyn Recogniser> {
    Box::new(Doctor { packets: Packets::statuses(), answered: false })
}

impl Recogniser for Doctor {
    /// One request of both pings (the doctor asks a family's next request only
    /// once the one before was answered): a 2.0 servo hears only the first, a
    /// 1.0 servo only the second.
    fn requests(&self) -> Vec<Vec<u8>> {
        let two = Packet::instruction(Protocol::Two, BROADCAST, instruction::PING, Vec::new()).to_bytes();
        let one = Packet::instruction(Protocol::One, 1, instruction::PING, Vec::new()).to_bytes();
        vec![[two, one].concat()]
    }

    fn read(&mut self, bytes: &[u8]) -> Vec<Heard> {
        let reads = self.packets.push(bytes);
        reads
            .into_iter()
            .filter_map(|read| {
                let Read::Packet(packet) = read else { return None };
                let Kind::Status(_) = packet.kind else { return None };
                if self.answered {
                    return Some(Heard::Answered);
                }
                let model = match (packet.protocol, packet.params.as_slice()) {
                    (Protocol::Two, [low, high, firmware]) => Some((u16::from_le_bytes([*low, *high]), *firmware)),
                    (Protocol::Two, _) => return None,
                    (Protocol::One, _) => None,
                };
                self.answered = true;
                Some(Heard::Said(Identity::new(Said { id: packet.id, protocol: packet.protocol, model })))
            })
            .collect()
    }

    fn abandon(&mut self) {
        self.packets = Packets::statuses();
        self.answered = false;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 2.0 servo's answer to the broadcast names its model; the requests are the pings as printed.
    #[test]
    fn a_ping_answer_is_a_servo_saying_its_model() {
        let mut doctor = Doctor { packets: Packets::statuses(), answered: false };
        assert_eq!(
            doctor.requests(),
            [vec![0xFF, 0xFF, 0xFD, 0x00, 0xFE, 0x03, 0x00, 0x01, 0x31, 0x42, 0xFF, 0xFF, 0x01, 0x02, 0x01, 0xFB]],
            "the e-Manual's broadcast ping, then 1.0's ping of ID 1"
        );
        let answer = Packet::status(Protocol::Two, 1, 0, vec![0x24, 0x04, 46]).to_bytes();
        let heard = doctor.read(&[b"noise".as_slice(), &answer].concat());
        let [Heard::Said(identity)] = heard.as_slice() else { panic!("{heard:?}") };
        let said = identity.said::<Said>().unwrap();
        assert_eq!(said.to_string(), "DYNAMIXEL XL430-W250, ID 1, Protocol 2.0, firmware 46");
        let second = Packet::status(Protocol::Two, 2, 0, vec![0xFC, 0x03, 46]).to_bytes();
        let heard = doctor.read(&second);
        assert!(matches!(heard.as_slice(), [Heard::Answered]), "the first servo speaks for the bus: {heard:?}");
        let mut doctor = Doctor { packets: Packets::statuses(), answered: false };
        let one = Packet::status(Protocol::One, 1, 0, Vec::new()).to_bytes();
        let heard = doctor.read(&one);
        let [Heard::Said(identity)] = heard.as_slice() else { panic!("{heard:?}") };
        assert_eq!(identity.said::<Said>().unwrap().to_string(), "DYNAMIXEL servo, ID 1, Protocol 1.0");
    }
}
