//! Authoring motions as they are meant: a sampled movement fitted into the
//! fewest moves a board plays ([`fit`]), recordings read from CSV
//! ([`recording`]). Uses the protocol's playback arithmetic and the project
//! model; nothing of link, device, sim or ui.

pub mod bake;
pub mod bake_servo;
pub mod fit;
pub mod fitted;
pub mod follow;
pub mod recording;
pub mod retime;
