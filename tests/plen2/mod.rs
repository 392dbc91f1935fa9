//! The PLEN2: codec, figure, link, official motions, pacing, playback.

mod codec_props;
mod figure;
mod link;
mod official;
mod pacing;
mod playback;
