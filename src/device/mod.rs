//! Drivers, one per board family, over a link: sessions and high-level
//! operations that speak typed events. Today: [`board`], the servo board.

pub mod board;
