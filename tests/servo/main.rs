//! The servo board: codec, link, live moves, gaps on the line: one test binary (each binary links the whole crate, egui
//! included, so the suites share one).

#[path = "../common/mod.rs"]
mod common;

mod codec;
mod codec_props;
mod link;
mod link_gap;
mod live;
