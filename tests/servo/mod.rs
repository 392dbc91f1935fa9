//! The servo board: codec, link, live moves, gaps on the line.

mod codec;
mod codec_props;
mod link;
mod link_gap;
mod live;
