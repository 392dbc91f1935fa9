//! Naming, opening and listing ports: a serial device path (`/dev/ttyUSB0`,
//! `/dev/pts/3`, `COM3`) or a serial-over-network bridge (`tcp://HOST:PORT`).

use std::fmt;
use std::io;
use std::net::{TcpStream, ToSocketAddrs};
use std::time::Duration;

use super::connection::Connection;

/// How a line is set up: each board family has its own (see `device::line_settings`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LineSettings {
    /// Line rate of a serial port (up to 2,000,000).
    pub baud: u32,
    /// Assert DTR on open (a PLEN2 drops its replies while DTR is low).
    pub assert_dtr: bool,
    /// Assert RTS on open.
    pub assert_rts: bool,
    /// Least time between two writes (an rFLEX base ignores commands sent too
    /// rapidly); zero for none.
    pub min_write_gap: Duration,
    /// How long a TCP connect may take before it is given up.
    pub connect_timeout: Duration,
}

impl LineSettings {
    /// Line rate `baud`, DTR and RTS asserted, no gap, a 3 s TCP connect timeout.
    pub fn new(baud: u32) -> Self {
        Self {
            baud,
            assert_dtr: true,
            assert_rts: true,
            min_write_gap: Duration::ZERO,
            connect_timeout: Duration::from_secs(3),
        }
    }
}

/// Where a board is attached.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum PortName {
    /// A serial device path or name.
    Serial(String),
    /// A TCP bridge, as `host:port`.
    Tcp(String),
}

impl PortName {
    /// Parses a port as a user types it: `tcp://HOST:PORT` or a serial device.
    pub fn parse(text: &str) -> Result<Self, LinkError> {
        let text = text.trim();
        if let Some(address) = text.strip_prefix("tcp://") {
            if address.rsplit_once(':').is_none_or(|(host, port)| host.is_empty() || port.parse::<u16>().is_err()) {
                return Err(LinkError::BadPortName {
                    name: text.to_string(),
                    hint: "a network port is written tcp://HOST:PORT, e.g. tcp://127.0.0.1:5000",
                });
            }
            return Ok(Self::Tcp(address.to_string()));
        }
        if text.is_empty() {
            return Err(LinkError::BadPortName {
                name: String::new(),
                hint: "name a serial port (e.g. /dev/ttyUSB0 or COM3) or tcp://HOST:PORT",
            });
        }
        Ok(Self::Serial(text.to_string()))
    }
}

impl fmt::Display for PortName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Serial(path) => write!(f, "{path}"),
            Self::Tcp(address) => write!(f, "tcp://{address}"),
        }
    }
}

/// A port could not be used. Each variant says what to try.
#[derive(Debug, thiserror::Error)]
pub enum LinkError {
    /// The port name cannot be understood.
    #[error("cannot understand port name {name:?}: {hint}")]
    BadPortName {
        /// What was given.
        name: String,
        /// How to write it.
        hint: &'static str,
    },
    /// The device does not exist.
    #[error("{port}: no such port. Is the board plugged in? `servo-studio ports` lists the ports this computer sees")]
    NotFound {
        /// The port.
        port: String,
    },
    /// The operating system refused access.
    #[error(
        "{port}: permission denied. On Linux, add yourself to the `dialout` group (sudo usermod -aG dialout $USER) and log in again"
    )]
    PermissionDenied {
        /// The port.
        port: String,
    },
    /// Another program holds the port.
    #[error(
        "{port}: the port is busy. Close other programs using it (another Servo Studio, a serial monitor) and retry"
    )]
    Busy {
        /// The port.
        port: String,
    },
    /// The TCP connection was not accepted in time.
    #[error(
        "{port}: no answer within {timeout_ms} ms. Is the address right, the bridge switched on and on this network?"
    )]
    TimedOut {
        /// The port.
        port: String,
        /// How long was waited, ms.
        timeout_ms: u128,
    },
    /// Nothing accepted the TCP connection.
    #[error("{port}: connection refused. Is the bridge (or `servo-studio sim --tcp`) running on that address?")]
    Refused {
        /// The port.
        port: String,
    },
    /// The name is not of a serial port (a regular file, a folder, /dev/null).
    #[error(
        "{port} is {what}, not a serial port: give the port the board is on (`servo-studio ports` lists them, or tcp://HOST:PORT)"
    )]
    NotAPort {
        /// The port.
        port: String,
        /// What it is instead.
        what: &'static str,
    },
    /// Any other failure to open.
    #[error("{port}: cannot open: {source}")]
    Open {
        /// The port.
        port: String,
        /// The cause.
        source: io::Error,
    },
}

impl LinkError {
    fn from_io(port: &PortName, error: io::Error) -> Self {
        let port = port.to_string();
        match error.kind() {
            io::ErrorKind::NotFound => Self::NotFound { port },
            io::ErrorKind::PermissionDenied => Self::PermissionDenied { port },
            io::ErrorKind::ConnectionRefused => Self::Refused { port },
            io::ErrorKind::ResourceBusy => Self::Busy { port },
            _ => match error.raw_os_error() {
                // EBUSY: a serial port held exclusively by another program.
                Some(16) => Self::Busy { port },
                _ => Self::Open { port, source: error },
            },
        }
    }

    fn from_serial(port: &PortName, error: serialport::Error) -> Self {
        // ENOTTY: a device, but one that takes no line settings (/dev/null, a disk).
        if ["Not a typewriter", "Inappropriate ioctl"].iter().any(|text| error.description.contains(text)) {
            return Self::NotAPort { port: port.to_string(), what: "a device that is not a terminal" };
        }
        match error.kind() {
            serialport::ErrorKind::NoDevice => {
                // serialport reports a busy (exclusively held) device as NoDevice too.
                let path = port.to_string();
                if std::path::Path::new(&path).exists() {
                    Self::Busy { port: path }
                } else {
                    Self::NotFound { port: path }
                }
            }
            serialport::ErrorKind::Io(kind) => Self::from_io(port, io::Error::new(kind, error.description)),
            _ => Self::Open { port: port.to_string(), source: io::Error::other(error.description) },
        }
    }
}

/// How long a blocked read waits before checking whether the link is closing.
pub(crate) const READ_WAKE: Duration = Duration::from_millis(50);

/// Opens a port with the given line settings. Blocks (a TCP connect for at
/// most `settings.connect_timeout`): call it off the UI thread, e.g. through
/// [`super::Opening`].
pub fn open(port: &PortName, settings: &LineSettings) -> Result<Connection, LinkError> {
    let mut connection = match port {
        PortName::Serial(path) => {
            not_a_port(port, path)?;
            let mut serial = serialport::new(path, settings.baud)
                .timeout(READ_WAKE)
                .open()
                .map_err(|error| LinkError::from_serial(port, error))?;
            // Some USB serial chips do not implement the lines; the port still works.
            if settings.assert_dtr {
                let _ = serial.write_data_terminal_ready(true);
            }
            if settings.assert_rts {
                let _ = serial.write_request_to_send(true);
            }
            Connection::from_serial(serial, port.to_string()).map_err(|error| LinkError::from_io(port, error))?
        }
        PortName::Tcp(address) => {
            let stream = connect_tcp(port, address, settings.connect_timeout)?;
            Connection::from_tcp(stream, port.to_string()).map_err(|error| LinkError::from_io(port, error))?
        }
    };
    connection.min_write_gap = settings.min_write_gap;
    Ok(connection)
}

/// Refuses, before opening it, a path that names something other than a
/// device (a project file given as `--port`, a folder): opening it would
/// fail with a word for an ioctl, or worse, succeed.
fn not_a_port(port: &PortName, path: &str) -> Result<(), LinkError> {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        let Ok(metadata) = std::fs::metadata(path) else { return Ok(()) };
        let kind = metadata.file_type();
        let what = if kind.is_char_device() {
            return Ok(());
        } else if kind.is_file() {
            "a regular file"
        } else if kind.is_dir() {
            "a folder"
        } else if kind.is_fifo() {
            "a named pipe (FIFO)"
        } else if kind.is_socket() {
            "a socket"
        } else {
            "a block device"
        };
        Err(LinkError::NotAPort { port: port.to_string(), what })
    }
    #[cfg(not(unix))]
    {
        let _ = (port, path);
        Ok(())
    }
}

/// Tries each address `address` resolves to, each for at most `timeout`.
fn connect_tcp(port: &PortName, address: &str, timeout: Duration) -> Result<TcpStream, LinkError> {
    let addresses = address.to_socket_addrs().map_err(|error| LinkError::from_io(port, error))?;
    let mut last = io::Error::new(io::ErrorKind::NotFound, "the host name has no address");
    for candidate in addresses {
        match TcpStream::connect_timeout(&candidate, timeout) {
            Ok(stream) => return Ok(stream),
            Err(error) => last = error,
        }
    }
    if matches!(last.kind(), io::ErrorKind::TimedOut | io::ErrorKind::WouldBlock) {
        return Err(LinkError::TimedOut { port: port.to_string(), timeout_ms: timeout.as_millis() });
    }
    Err(LinkError::from_io(port, last))
}

/// A serial port this computer sees.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PortInfo {
    /// The name to open it by.
    pub name: String,
    /// What it is: "USB 1a86:7523 USB Serial (QinHeng)", "PCI", "Bluetooth", …
    pub description: String,
}

/// The serial ports this computer sees, with USB vendor / product ids and strings.
pub fn list_ports() -> Result<Vec<PortInfo>, LinkError> {
    let ports = serialport::available_ports()
        .map_err(|error| LinkError::Open { port: "(port list)".into(), source: io::Error::other(error.description) })?;
    Ok(ports
        .into_iter()
        .map(|port| {
            let description = match port.port_type {
                serialport::SerialPortType::UsbPort(usb) => {
                    let mut text = format!("USB {:04x}:{:04x}", usb.vid, usb.pid);
                    if let Some(product) = usb.product {
                        text.push_str(&format!(" {product}"));
                    }
                    if let Some(maker) = usb.manufacturer {
                        text.push_str(&format!(" ({maker})"));
                    }
                    if let Some(serial) = usb.serial_number {
                        text.push_str(&format!(" serial {serial}"));
                    }
                    text
                }
                serialport::SerialPortType::PciPort => "PCI".into(),
                serialport::SerialPortType::BluetoothPort => "Bluetooth".into(),
                serialport::SerialPortType::Unknown => "serial".into(),
            };
            PortInfo { name: port.port_name, description }
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn port_names_parse() {
        assert_eq!(PortName::parse("/dev/ttyUSB0").unwrap(), PortName::Serial("/dev/ttyUSB0".into()));
        assert_eq!(PortName::parse(" COM3 ").unwrap(), PortName::Serial("COM3".into()));
        assert_eq!(PortName::parse("tcp://127.0.0.1:5000").unwrap(), PortName::Tcp("127.0.0.1:5000".into()));
        assert_eq!(PortName::parse("tcp://[::1]:7").unwrap().to_string(), "tcp://[::1]:7");
        for bad in ["", "tcp://", "tcp://host", "tcp://:80", "tcp://host:99999"] {
            assert!(matches!(PortName::parse(bad), Err(LinkError::BadPortName { .. })), "{bad:?}");
        }
    }

    #[test]
    fn open_errors_say_what_to_try() {
        let missing =
            open(&PortName::Serial("/dev/does-not-exist-servo".into()), &LineSettings::new(115_200)).unwrap_err();
        assert!(matches!(missing, LinkError::NotFound { .. }), "{missing:?}");
        assert!(missing.to_string().contains("servo-studio ports"));

        // A port nobody listens on: bind one, then close it.
        let listener = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
        let address = listener.local_addr().unwrap();
        drop(listener);
        let refused = open(&PortName::Tcp(address.to_string()), &LineSettings::new(115_200)).unwrap_err();
        assert!(matches!(refused, LinkError::Refused { .. }), "{refused:?}");
        assert!(refused.to_string().contains("sim --tcp"));
    }

    #[cfg(unix)]
    #[test]
    fn a_file_or_a_device_that_is_no_terminal_is_not_a_port() {
        let folder = std::env::temp_dir().join(format!("not-a-port-{}", std::process::id()));
        std::fs::create_dir_all(&folder).unwrap();
        let file = folder.join("robot.json");
        std::fs::write(&file, "{}").unwrap();
        for (path, what) in [
            (file.display().to_string(), "a regular file"),
            (folder.display().to_string(), "a folder"),
            ("/dev/null".to_string(), "a device that is not a terminal"),
        ] {
            let error = open(&PortName::Serial(path.clone()), &LineSettings::new(115_200)).unwrap_err();
            assert!(matches!(&error, LinkError::NotAPort { what: got, .. } if *got == what), "{path}: {error:?}");
            let text = error.to_string();
            assert!(text.contains("not a serial port") && !text.contains("typewriter"), "{text}");
        }
        std::fs::remove_dir_all(&folder).unwrap();
    }

    #[cfg(unix)]
    #[test]
    fn a_port_held_by_another_program_is_busy() {
        let (_master, slave) = serialport::TTYPort::pair().unwrap();
        let name = serialport::SerialPort::name(&slave).unwrap();
        let first = open(&PortName::Serial(name.clone()), &LineSettings::new(115_200)).unwrap();
        let second = open(&PortName::Serial(name), &LineSettings::new(115_200));
        assert!(matches!(second, Err(LinkError::Busy { .. })), "{second:?}");
        drop(first);
    }
}
