//! The rFLEX base: codec, layout, link, live driving, teleop: one test binary (each binary links the whole crate, egui
//! included, so the suites share one).

#[path = "../common/mod.rs"]
mod common;

mod codec;
mod codec_props;
mod layout;
mod link;
mod live;
mod teleop;
