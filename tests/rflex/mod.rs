//! The rFLEX base: codec, layout, link, live driving, teleop.

mod codec;
mod codec_props;
mod layout;
mod link;
mod live;
mod teleop;
