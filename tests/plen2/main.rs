//! The PLEN2: codec, figure, link, official motions, pacing, playback: one test binary (each binary links the whole crate, egui
//! included, so the suites share one).

#[path = "../common/mod.rs"]
mod common;

mod codec_props;
mod figure;
mod link;
mod official;
mod pacing;
mod playback;
