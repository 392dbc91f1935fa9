//! Sans-IO protocol codecs, one folder per board family. Nothing here does I/O
//! or knows about the UI: bytes in, typed values out, and back.
//!
//! [`servo`]: the servo controller board (all 60 messages, streaming decoder).
//! [`plen2`]: the PLEN2 humanoid (device map and field limits so far).
//! [`dynamixel`]: DYNAMIXEL servos' packets, Protocol 1.0 and 2.0.
//! [`rflex`]: rFLEX mobile bases (robot presets so far). See `docs/ARCHITECTURE.md`.

pub mod dynamixel;
pub mod plen2;
pub mod rflex;
pub mod servo;
