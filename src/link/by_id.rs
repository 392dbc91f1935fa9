//! A port found by the USB device behind it rather than by its name: a show
//! that names `usb:1a86:7523:A50285BI` finds that adapter wherever the system
//! put it today (`/dev/ttyUSB0` yesterday, `/dev/ttyUSB3` after a reboot, a
//! different `COM` on Windows) — what `/dev/serial/by-id` does, on every OS.
//! Written `usb:VID:PID` (hex) or `usb:VID:PID:SERIAL`; anything else is a
//! port's own name.

use std::fmt;

/// A USB serial device, by its vendor and product ids and, when it has one, its serial number.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UsbId {
    /// Vendor id.
    pub vid: u16,
    /// Product id.
    pub pid: u16,
    /// Its serial number (`None`: any device with these ids).
    pub serial: Option<String>,
}

/// A USB serial device attached now: the port it has and its ids.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Attached {
    /// The name to open it by today.
    pub port: String,
    /// Its ids, serial number included when it reports one.
    pub id: UsbId,
    /// Its product and maker, as it names itself.
    pub description: String,
}

/// Why a device named by id could not be found.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum FindError {
    /// `usb:` followed by something that is not ids.
    #[error("{0:?} is not a USB id: write usb:VID:PID or usb:VID:PID:SERIAL, the ids in hex (e.g. usb:1a86:7523)")]
    Malformed(String),
    /// No attached device has these ids.
    #[error("no USB serial device {id} is attached{}", attached_list(.attached))]
    Missing {
        /// What was looked for.
        id: UsbId,
        /// What is attached (ids and ports).
        attached: Vec<String>,
    },
    /// Several attached devices have these ids and no serial number tells them apart.
    #[error("{} devices are {id} ({}): add the serial number (usb:VID:PID:SERIAL) or name the port", .ports.len(), .ports.join(", "))]
    Ambiguous {
        /// What was looked for.
        id: UsbId,
        /// The ports of the devices that match.
        ports: Vec<String>,
    },
}

fn attached_list(attached: &[String]) -> String {
    if attached.is_empty() {
        " (no USB serial device is attached: is it plugged in?)".into()
    } else {
        format!(" (attached: {})", attached.join(", "))
    }
}

impl fmt::Display for UsbId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "usb:{:04x}:{:04x}", self.vid, self.pid)?;
        match &self.serial {
            Some(serial) => write!(f, ":{serial}"),
            None => Ok(()),
        }
    }
}

impl UsbId {
    /// `text` as a USB id: `None` when it does not start with `usb:` (a port's own name).
    pub fn parse(text: &str) -> Option<Result<Self, FindError>> {
        let rest = text.trim().strip_prefix("usb:")?;
        let mut parts = rest.splitn(3, ':');
        let hex = |part: Option<&str>| {
            part.filter(|p| (1..=4).contains(&p.len())).and_then(|p| u16::from_str_radix(p, 16).ok())
        };
        let (vid, pid) = (hex(parts.next()), hex(parts.next()));
        let serial = parts.next().map(str::to_string);
        Some(match (vid, pid) {
            (Some(vid), Some(pid)) if serial.as_ref().is_none_or(|s| !s.is_empty()) => Ok(Self { vid, pid, serial }),
            _ => Err(FindError::Malformed(text.trim().to_string())),
        })
    }

    /// Whether `other` (an attached device's ids) is this device.
    fn matches(&self, other: &Self) -> bool {
        self.vid == other.vid
            && self.pid == other.pid
            && self.serial.as_ref().is_none_or(|serial| other.serial.as_ref() == Some(serial))
    }
}

/// The port of the one device of `attached` that `id` names.
pub fn find(id: &UsbId, attached: &[Attached]) -> Result<String, FindError> {
    let matching: Vec<&Attached> = attached.iter().filter(|device| id.matches(&device.id)).collect();
    match matching.as_slice() {
        [one] => Ok(one.port.clone()),
        [] => Err(FindError::Missing {
            id: id.clone(),
            attached: attached.iter().map(|device| format!("{} on {}", device.id, device.port)).collect(),
        }),
        several => {
            Err(FindError::Ambiguous { id: id.clone(), ports: several.iter().map(|d| d.port.clone()).collect() })
        }
    }
}

/// The USB serial devices attached now (none where the system cannot list them).
pub fn attached() -> Vec<Attached> {
    let Ok(ports) = serialport::available_ports() else { return Vec::new() };
    ports
        .into_iter()
        .filter_map(|port| match port.port_type {
            serialport::SerialPortType::UsbPort(usb) => {
                let description = [usb.product, usb.manufacturer].into_iter().flatten().collect::<Vec<_>>().join(" · ");
                let id = UsbId { vid: usb.vid, pid: usb.pid, serial: usb.serial_number.filter(|s| !s.is_empty()) };
                Some(Attached { port: port.port_name, id, description })
            }
            _ => None,
        })
        .collect()
}

/// `text` as a port to open: a USB id found among the devices attached now,
/// or the port's own name as written.
pub fn resolve(text: &str) -> Result<String, FindError> {
    match UsbId::parse(text) {
        None => Ok(text.trim().to_string()),
        Some(id) => find(&id?, &attached()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn device(port: &str, vid: u16, pid: u16, serial: Option<&str>) -> Attached {
        Attached {
            port: port.into(),
            id: UsbId { vid, pid, serial: serial.map(str::to_string) },
            description: String::new(),
        }
    }

    #[test]
    fn ids_parse_and_print_as_written() {
        let id = UsbId::parse("usb:1a86:7523:A50285BI").unwrap().unwrap();
        assert_eq!(id, UsbId { vid: 0x1a86, pid: 0x7523, serial: Some("A50285BI".into()) });
        assert_eq!(id.to_string(), "usb:1a86:7523:A50285BI");
        assert_eq!(UsbId::parse(" usb:403:6001 ").unwrap().unwrap().to_string(), "usb:0403:6001");
        // A serial number may hold colons.
        assert_eq!(UsbId::parse("usb:0403:6001:AB:CD").unwrap().unwrap().serial.as_deref(), Some("AB:CD"));
        assert!(UsbId::parse("/dev/ttyUSB0").is_none());
        assert!(UsbId::parse("tcp://127.0.0.1:5000").is_none());
        for bad in ["usb:", "usb:1a86", "usb:xyz:7523", "usb:1a86:75230", "usb:1a86:7523:"] {
            assert!(matches!(UsbId::parse(bad), Some(Err(FindError::Malformed(_)))), "{bad}");
        }
    }

    #[test]
    fn a_device_is_found_wherever_it_is_and_a_missing_or_ambiguous_one_is_said() {
        let attached = [
            device("/dev/ttyUSB3", 0x1a86, 0x7523, Some("A1")),
            device("/dev/ttyUSB0", 0x1a86, 0x7523, Some("B2")),
            device("/dev/ttyACM0", 0x2341, 0x0043, None),
        ];
        let id = |text: &str| UsbId::parse(text).unwrap().unwrap();
        assert_eq!(find(&id("usb:1a86:7523:A1"), &attached).unwrap(), "/dev/ttyUSB3");
        assert_eq!(find(&id("usb:1a86:7523:B2"), &attached).unwrap(), "/dev/ttyUSB0");
        assert_eq!(find(&id("usb:2341:0043"), &attached).unwrap(), "/dev/ttyACM0");
        let ambiguous = find(&id("usb:1a86:7523"), &attached).unwrap_err();
        assert_eq!(
            ambiguous.to_string(),
            "2 devices are usb:1a86:7523 (/dev/ttyUSB3, /dev/ttyUSB0): add the serial number (usb:VID:PID:SERIAL) or name the port"
        );
        let missing = find(&id("usb:0403:6001"), &attached).unwrap_err().to_string();
        assert!(
            missing.starts_with(
                "no USB serial device usb:0403:6001 is attached (attached: usb:1a86:7523:A1 on /dev/ttyUSB3"
            ),
            "{missing}"
        );
        let none = find(&id("usb:0403:6001"), &[]).unwrap_err().to_string();
        assert!(none.ends_with("(no USB serial device is attached: is it plugged in?)"), "{none}");
        // A port's own name passes through.
        assert_eq!(resolve(" /dev/ttyUSB9 ").unwrap(), "/dev/ttyUSB9");
    }
}
