//! Sans-IO protocol codecs, one folder per board family. Nothing here does I/O
//! or knows about the UI: bytes in, typed values out, and back.
//!
//! Today: [`board`], the servo controller board. The PLEN2 humanoid (ASCII
//! commands, JSON replies) and rFLEX mobile bases (stuffed, XOR-checked frames)
//! will sit beside it as `plen2` and `rflex`, each with its own decoder and
//! message types; see `docs/ARCHITECTURE.md`.

pub mod board;
