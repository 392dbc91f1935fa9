//! The decoded sound on its way to an output: decoded on a thread of its own
//! a second or two ahead, at most two channels a frame, handed out in order
//! as the output asks for it.

use std::path::Path;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use crossbeam_channel::{Receiver, TryRecvError};

use crate::audio::{AudioError, Reader};

/// Interleaved samples from a decoding thread: at most this many chunks ahead (about a second or two).
const AHEAD_CHUNKS: usize = 48;

/// The decoded sound on its way to the output: at most two channels a chunk, at most `left` samples.
struct Feed {
    reader: Reader,
    sender: crossbeam_channel::Sender<Vec<f32>>,
    left: usize,
    queued_frames: usize,
}

impl Feed {
    /// Sends `samples` (interleaved, `count` channels); false when nothing more is to go.
    fn send(&mut self, samples: &[f32], count: usize) -> bool {
        let mut shaped = if count <= 2 {
            samples.to_vec()
        } else {
            // Channel counts are small.
            #[allow(clippy::cast_precision_loss)]
            let scale = 1.0 / count as f32;
            samples.chunks_exact(count).map(|frame| frame.iter().sum::<f32>() * scale).collect()
        };
        shaped.truncate(self.left);
        self.left -= shaped.len();
        self.queued_frames += shaped.len() / count.clamp(1, 2);
        !shaped.is_empty() && self.sender.send(shaped).is_ok()
    }

    /// Decodes and sends the next packet; false at the end.
    fn next(&mut self) -> bool {
        match self.reader.next_chunk() {
            Ok(Some((chunk, count))) => {
                let chunk = chunk.to_vec();
                self.send(&chunk, count)
            }
            Ok(None) | Err(_) => false,
        }
    }
}

/// A sound being decoded for an output.
pub(super) struct Decoded {
    /// What to hand the output.
    pub pull: Pull,
    /// The sound's rate.
    pub rate: u32,
    /// One or two.
    pub channels: usize,
}

/// Decodes `path` from `from_s` (silence first for a start before 0), each
/// chunk in at most two channels: the first half second before it returns
/// (so the output never asks before there is sound to give), the rest on a
/// thread of its own, a second or two ahead. `ended` is set once the whole
/// sound (or `only` of it) has been handed out; `stop` ends the decoding.
pub(super) fn decoding(
    path: &Path,
    from_s: f64,
    only: Option<Duration>,
    stop: Arc<AtomicBool>,
    ended: Arc<AtomicBool>,
) -> Result<Decoded, AudioError> {
    let mut reader = Reader::open(path)?;
    let rate = reader.rate();
    if from_s > 0.0 {
        reader.seek(from_s)?;
    }
    // Whole frames of silence before 0: a start a little before the sound.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let lead_frames = ((-from_s).max(0.0) * f64::from(rate)).round() as usize;
    let first = reader.next_chunk()?.map(|(chunk, count)| (chunk.to_vec(), count));
    let channels = first.as_ref().map_or(1, |(_, count)| (*count).min(2));
    // At most this many samples (interleaved), for a grain.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let left = only.map_or(usize::MAX, |only| (only.as_secs_f64() * f64::from(rate)) as usize * channels);
    let (sender, receiver) = crossbeam_channel::bounded(AHEAD_CHUNKS);
    let mut feed = Feed { reader, sender, left, queued_frames: 0 };
    let mut going = (lead_frames == 0 || feed.send(&vec![0.0; lead_frames * channels], channels))
        && first.is_none_or(|(chunk, count)| feed.send(&chunk, count));
    let half_second = rate as usize / 2;
    while going && feed.queued_frames < half_second && receiver.len() + 1 < AHEAD_CHUNKS {
        going = feed.next();
    }
    if going {
        std::thread::Builder::new()
            .name("sound decoding".into())
            .spawn(move || while !stop.load(Ordering::Relaxed) && feed.next() {})
            .map_err(|source| AudioError::Open { path: path.to_path_buf(), source })?;
    }
    Ok(Decoded { pull: Pull::new(receiver, ended), rate, channels })
}

/// The decoded samples as the output asks for them.
pub(super) struct Pull {
    chunks: Receiver<Vec<f32>>,
    pending: Vec<f32>,
    at: usize,
    ended: Arc<AtomicBool>,
}

impl Pull {
    /// Hands out `chunks` in order; `ended` is set once they are all out.
    pub fn new(chunks: Receiver<Vec<f32>>, ended: Arc<AtomicBool>) -> Self {
        Self { chunks, pending: Vec::new(), at: 0, ended }
    }

    /// Fills `out` with the next samples (interleaved) and says how many it
    /// filled: all of them (silence where the decoder is behind), fewer only
    /// at the sound's end, 0 (and `ended` set) once it is over.
    pub fn fill(&mut self, out: &mut [f32]) -> usize {
        let mut written = 0;
        while written < out.len() {
            if self.at == self.pending.len() {
                match self.chunks.try_recv() {
                    Ok(chunk) => (self.pending, self.at) = (chunk, 0),
                    // The decoder is behind (it seldom is: it runs far faster than
                    // the sound, and the first half second was decoded before the
                    // stream began): silence, rather than an end an output would
                    // take for the sound's.
                    Err(TryRecvError::Empty) => {
                        out[written..].fill(0.0);
                        return out.len();
                    }
                    Err(TryRecvError::Disconnected) => {
                        self.ended.store(written == 0, Ordering::Relaxed);
                        break;
                    }
                }
            }
            let take = (self.pending.len() - self.at).min(out.len() - written);
            out[written..written + take].copy_from_slice(&self.pending[self.at..self.at + take]);
            (self.at, written) = (self.at + take, written + take);
        }
        written
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn half_a_second_is_decoded_before_the_output_can_ask_so_a_stream_never_starts_empty() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("tone.wav");
        let tone: Vec<f32> = (0..16_000).map(|i| (f32::from(u16::try_from(i % 100).unwrap()) / 100.0) - 0.5).collect();
        std::fs::write(&path, crate::audio::pcm16_wav(&tone, 8_000, 2)).unwrap();
        let stop = Arc::new(AtomicBool::new(true));
        // Stopped at once: only what was decoded before `decoding` returned is there.
        let decoded = decoding(&path, -0.25, None, stop, Arc::default()).unwrap();
        assert_eq!((decoded.rate, decoded.channels), (8_000, 2));
        let queued: usize = decoded.pull.chunks.try_iter().map(|chunk| chunk.len() / 2).sum();
        assert!(queued >= 4_000, "{queued} frames (a quarter second of silence, then the sound)");
    }

    #[test]
    fn the_pull_hands_out_every_sample_in_order_then_ends() {
        let (sender, chunks) = crossbeam_channel::unbounded();
        sender.send(vec![0.5f32, -0.25]).unwrap();
        sender.send(vec![1.0f32]).unwrap();
        drop(sender);
        let ended = Arc::new(AtomicBool::new(false));
        let mut pull = Pull::new(chunks, Arc::clone(&ended));
        let mut first = [0f32; 2];
        assert_eq!(pull.fill(&mut first), 2);
        let mut rest = [9f32; 2];
        assert_eq!(pull.fill(&mut rest), 1, "what is left, then the end");
        assert!(!ended.load(Ordering::Relaxed));
        assert_eq!(pull.fill(&mut rest), 0);
        assert!(ended.load(Ordering::Relaxed), "the end is known");
        assert_eq!([first[0], first[1], rest[0]], [0.5, -0.25, 1.0]);
    }

    #[test]
    fn a_decoder_behind_gives_silence_never_an_end() {
        let (sender, chunks) = crossbeam_channel::unbounded::<Vec<f32>>();
        let ended = Arc::new(AtomicBool::new(false));
        let mut pull = Pull::new(chunks, Arc::clone(&ended));
        let mut out = [7f32; 4];
        assert_eq!(pull.fill(&mut out), 4);
        assert_eq!(out, [0.0; 4]);
        assert!(!ended.load(Ordering::Relaxed));
        drop(sender);
    }
}
