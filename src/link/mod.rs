//! Transports and the one I/O thread. A link moves bytes; it does not know
//! which protocol reads them (the [`Driver`] it runs does).

pub mod by_id;
mod connection;
mod driver;
mod io_thread;
mod opening;
mod output;
mod port;

pub use connection::Connection;
pub use driver::Driver;
pub use io_thread::{DisconnectReason, LinkEvent, LinkHandle, Owner, Waker, idle, no_waker, run, spawn};
pub use opening::{Opener, Opening, system_opener};
pub(crate) use port::READ_WAKE;
pub use port::{LineSettings, LinkError, PortInfo, PortName, list_ports, open};
