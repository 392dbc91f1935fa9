//! Emulated boards, with fault injection, and the runners that serve any of
//! them (in-process, pseudo-terminal, TCP): the servo board, the PLEN2 humanoid
//! and the rFLEX base.

pub mod dynamixel;
mod faults;
mod log;
mod plen2;
mod rflex;
mod runner;
mod servo;

pub use faults::{Faults, FaultsError, LineNoise, LineNoiseError};
pub use log::{Logged, MonotonicClock, Received};
pub use plen2::{Bridge, JointLimits, LinkKind, Plen2Sim, Plen2SimCommand, Plen2SimEvent, Plen2State, Plen2Timing};
pub use rflex::{BaseState, RflexSim, RflexSimCommand, RflexSimConfig, RflexSimEvent};
pub use runner::{InMemory, SimHandle, spawn_in_memory, spawn_pty, spawn_tcp};

/// A loopback address on a port the system picks (an emulated board served to this machine only).
pub const LOOPBACK_ANY: std::net::SocketAddr =
    std::net::SocketAddr::new(std::net::IpAddr::V4(std::net::Ipv4Addr::LOCALHOST), 0);
pub use servo::{ServoSim, SimCommand, SimConfig, SimEvent};
