//! Sound to the speakers, through the system's sound server: PulseAudio,
//! or PipeWire, which serves the same protocol. The client is the
//! `pulseaudio` crate, pure Rust (no system package to build). A stream is
//! made corked with a short buffer (30 ms), filled from a decoding thread,
//! then started; when its first sample is heard is read back from the
//! server's own clock (how far it has played, less the sink's latency), so
//! a motion or a board can be started on the sound's time.
//!
//! With no sound server (none running, or another system) `Speakers::connect`
//! says so once, and callers play the motion on the same clock without sound.

use std::path::Path;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use crossbeam_channel::{Receiver, TryRecvError};

use super::{AudioError, Reader};

/// A PulseAudio cookie's length.
#[cfg(unix)]
const COOKIE_BYTES: usize = 256;

/// How much sound the server holds ahead of the speakers.
pub const BUFFER: Duration = Duration::from_millis(30);

/// Why sound cannot be played.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    /// No sound server to talk to.
    #[error("no sound output ({0})")]
    NoServer(String),
    /// The server refused the stream, or went away.
    #[error("the sound server refused to play: {0}")]
    Stream(String),
    /// The sound could not be read.
    #[error(transparent)]
    Sound(#[from] AudioError),
}

#[cfg(unix)]
type Client = pulseaudio::Client;
#[cfg(not(unix))]
type Client = ();

/// A connection to the sound server (a copy shares it).
#[derive(Clone)]
pub struct Speakers {
    client: Client,
}

impl std::fmt::Debug for Speakers {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Speakers").finish_non_exhaustive()
    }
}

/// A sound being played; dropping it stops it.
pub struct Playing {
    #[cfg(unix)]
    stream: Option<pulseaudio::PlaybackStream>,
    stop: Arc<AtomicBool>,
    /// The whole sound (or grain) has gone to the server.
    ended: Arc<AtomicBool>,
    rate: u32,
    frame_bytes: u64,
    /// The sound's time at the stream's first frame, s (before 0: silence first).
    from_s: f64,
}

impl std::fmt::Debug for Playing {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Playing").field("rate", &self.rate).finish_non_exhaustive()
    }
}

/// Interleaved samples from a decoding thread: at most this many chunks ahead (about a second or two).
const AHEAD_CHUNKS: usize = 48;

/// The decoded sound on its way to the server: at most two channels a chunk, at most `left` samples.
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

/// Decodes `path` from `from_s` (silence first for a start before 0), each
/// chunk in at most two channels: the first half second before it returns
/// (so the server never asks before there is sound to give), the rest on a
/// thread of its own, a second or two ahead.
fn decoding(
    path: &Path,
    from_s: f64,
    only: Option<Duration>,
    stop: Arc<AtomicBool>,
) -> Result<(Receiver<Vec<f32>>, u32, usize), AudioError> {
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
    Ok((receiver, rate, channels))
}

/// Bytes for the server from the decoded chunks, little-endian f32; 0 at the end of the sound.
fn filler(chunks: Receiver<Vec<f32>>, ended: Arc<AtomicBool>) -> impl FnMut(&mut [u8]) -> usize + Send + 'static {
    let mut pending: Vec<u8> = Vec::new();
    let mut at = 0;
    move |buffer: &mut [u8]| {
        let mut written = 0;
        while written < buffer.len() {
            if at == pending.len() {
                match chunks.try_recv() {
                    Ok(chunk) => {
                        pending = chunk.iter().flat_map(|sample| sample.to_le_bytes()).collect();
                        at = 0;
                    }
                    // The decoder is behind (it seldom is: it runs far faster than
                    // the sound, and the first half second was decoded before the
                    // stream began): silence, rather than an end the server would
                    // take for the sound's.
                    Err(TryRecvError::Empty) => {
                        buffer[written..].fill(0);
                        return buffer.len();
                    }
                    Err(TryRecvError::Disconnected) => {
                        ended.store(written == 0, Ordering::Relaxed);
                        break;
                    }
                }
            }
            let take = (pending.len() - at).min(buffer.len() - written);
            buffer[written..written + take].copy_from_slice(&pending[at..at + take]);
            (at, written) = (at + take, written + take);
        }
        written
    }
}

#[cfg(unix)]
impl Speakers {
    /// Connects to the sound server the environment names (`PULSE_SERVER`,
    /// or the user's runtime folder), as every PulseAudio client does.
    pub fn connect() -> Result<Self, OutputError> {
        let socket = pulseaudio::socket_path_from_env()
            .ok_or_else(|| OutputError::NoServer("no sound server is running for this user".into()))?;
        Self::connect_to(&socket)
    }

    /// Connects to the sound server listening on `socket`. The cookie is the
    /// user's (`PULSE_COOKIE`, `~/.config/pulse/cookie`); without one, the
    /// server's anonymous access is asked for (the server still wants a
    /// cookie's 256 bytes).
    pub fn connect_to(socket: &Path) -> Result<Self, OutputError> {
        let no_server = |error: &dyn std::fmt::Display| OutputError::NoServer(format!("{}: {error}", socket.display()));
        let cookie = pulseaudio::cookie_path_from_env()
            .and_then(|path| std::fs::read(path).ok())
            .filter(|cookie| cookie.len() == COOKIE_BYTES)
            .unwrap_or_else(|| vec![0; COOKIE_BYTES]);
        let stream = std::os::unix::net::UnixStream::connect(socket).map_err(|error| no_server(&error))?;
        let client =
            pulseaudio::Client::new_unix(c"Servo Studio", stream, Some(cookie)).map_err(|error| no_server(&error))?;
        pollster::block_on(client.server_info()).map_err(|error| no_server(&error))?;
        Ok(Self { client })
    }

    /// Plays `path` from `from_s` (before 0: silence first) as soon as it can.
    pub fn play(&self, path: &Path, from_s: f64) -> Result<Playing, OutputError> {
        self.play_for(path, from_s, None)
    }

    /// Plays `path` from `from_s` for `only` at most (a scrubbing grain), or to its end.
    pub fn play_for(&self, path: &Path, from_s: f64, only: Option<Duration>) -> Result<Playing, OutputError> {
        use pulseaudio::AsPlaybackSource;
        use pulseaudio::protocol::{self, stream::BufferAttr, stream::StreamFlags};
        let stop = Arc::new(AtomicBool::new(false));
        let (chunks, rate, channels) = decoding(path, from_s, only, Arc::clone(&stop))?;
        let ended = Arc::new(AtomicBool::new(false));
        let frame_bytes = 4 * channels as u64;
        let bytes_for = |duration: Duration| {
            u32::try_from(u128::from(rate) * u128::from(frame_bytes) * duration.as_micros() / 1_000_000)
                .unwrap_or(u32::MAX)
        };
        let params = protocol::PlaybackStreamParams {
            sample_spec: protocol::SampleSpec {
                format: protocol::SampleFormat::Float32Le,
                channels: u8::try_from(channels).unwrap_or(2),
                sample_rate: rate,
            },
            channel_map: if channels == 1 { protocol::ChannelMap::mono() } else { protocol::ChannelMap::stereo() },
            cvolume: Some(protocol::ChannelVolume::norm(u8::try_from(channels).unwrap_or(2))),
            sink_name: Some(protocol::DEFAULT_SINK.to_owned()),
            buffer_attr: BufferAttr {
                target_length: bytes_for(BUFFER),
                minimum_request_length: bytes_for(BUFFER / 3),
                pre_buffering: 0,
                ..BufferAttr::default()
            },
            flags: StreamFlags { start_corked: true, adjust_latency: true, ..StreamFlags::default() },
            ..Default::default()
        };
        let failed = |error: pulseaudio::ClientError| OutputError::Stream(error.to_string());
        let stream = pollster::block_on(
            self.client.create_playback_stream(params, filler(chunks, Arc::clone(&ended)).as_playback_source()),
        )
        .map_err(failed)?;
        pollster::block_on(stream.uncork()).map_err(failed)?;
        Ok(Playing { stream: Some(stream), stop, ended, rate, frame_bytes, from_s })
    }
}

#[cfg(not(unix))]
impl Speakers {
    /// No sound server client on this system yet.
    pub fn connect() -> Result<Self, OutputError> {
        Err(OutputError::NoServer("this system has no sound server client in Servo Studio yet".into()))
    }

    /// Never reached: there are no speakers to play on.
    pub fn play(&self, _path: &Path, _from_s: f64) -> Result<Playing, OutputError> {
        Err(OutputError::NoServer("no speakers".into()))
    }

    /// Never reached: there are no speakers to play on.
    pub fn play_for(&self, _path: &Path, _from_s: f64, _only: Option<Duration>) -> Result<Playing, OutputError> {
        Err(OutputError::NoServer("no speakers".into()))
    }
}

impl Playing {
    /// When the sound's `sound_s` (seconds from its start) is heard, read off
    /// the server's clock: the frames it has played less the sink's latency,
    /// against the midpoint of the question's round trip. Asked a few times;
    /// the answer with the shortest round trip is taken.
    #[cfg(unix)]
    pub fn heard_at(&self, sound_s: f64) -> Result<Instant, OutputError> {
        let stream = self.stream.as_ref().ok_or_else(|| OutputError::Stream("stopped".into()))?;
        let mut best: Option<(Duration, Instant)> = None;
        let mut answers = 0;
        let deadline = Instant::now() + Duration::from_secs(2);
        while answers < 8 && Instant::now() < deadline {
            let asked = Instant::now();
            let timing =
                pollster::block_on(stream.timing_info()).map_err(|error| OutputError::Stream(error.to_string()))?;
            let answered = Instant::now();
            let played = u64::try_from(timing.read_offset.max(0)).unwrap_or(0) / self.frame_bytes.max(1);
            let latency_frames = timing.sink_usec * u64::from(self.rate) / 1_000_000;
            if played <= latency_frames {
                // Nothing heard yet: the server has not begun.
                std::thread::yield_now();
                continue;
            }
            answers += 1;
            let round_trip = answered - asked;
            // The stream's first frame (the sound's `from_s`) was heard `heard` before the midpoint.
            #[allow(clippy::cast_precision_loss)]
            let heard = Duration::from_secs_f64((played - latency_frames) as f64 / f64::from(self.rate));
            if let Some(first) = (asked + round_trip / 2).checked_sub(heard)
                && best.is_none_or(|(shortest, _)| round_trip < shortest)
            {
                best = Some((round_trip, first));
            }
        }
        let (_, first) = best.ok_or_else(|| OutputError::Stream("the sound server never began playing".into()))?;
        let after = sound_s - self.from_s;
        let at = if after >= 0.0 {
            first.checked_add(Duration::from_secs_f64(after))
        } else {
            first.checked_sub(Duration::from_secs_f64(-after))
        };
        at.ok_or_else(|| OutputError::Stream("the sound's clock is out of range".into()))
    }

    /// Never reached without a sound server.
    #[cfg(not(unix))]
    pub fn heard_at(&self, _sound_s: f64) -> Result<Instant, OutputError> {
        Err(OutputError::NoServer("no speakers".into()))
    }

    /// Whether it is still sending sound (it ends at the sound's or grain's end).
    pub fn is_playing(&self) -> bool {
        !self.ended.load(Ordering::Relaxed)
    }

    /// Stops the sound now.
    pub fn stop(mut self) {
        self.halt();
    }

    fn halt(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
        #[cfg(unix)]
        if let Some(stream) = self.stream.take() {
            let _ = pollster::block_on(stream.delete());
        }
    }
}

impl Drop for Playing {
    fn drop(&mut self) {
        self.halt();
    }
}

#[cfg(all(test, unix))]
mod tests {
    use super::*;

    #[test]
    fn without_a_sound_server_it_says_no_sound_output_naming_where_it_looked() {
        let dir = tempfile::tempdir().unwrap();
        let socket = dir.path().join("native");
        let said = Speakers::connect_to(&socket).unwrap_err().to_string();
        assert!(said.starts_with("no sound output") && said.contains("native"), "{said}");
    }

    #[test]
    fn half_a_second_is_decoded_before_the_server_can_ask_so_a_stream_never_starts_empty() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("tone.wav");
        let tone: Vec<f32> = (0..16_000).map(|i| (f32::from(u16::try_from(i % 100).unwrap()) / 100.0) - 0.5).collect();
        std::fs::write(&path, crate::audio::pcm16_wav(&tone, 8_000, 2)).unwrap();
        let stop = Arc::new(AtomicBool::new(true));
        // Stopped at once: only what was decoded before `decoding` returned is there.
        let (chunks, rate, channels) = decoding(&path, -0.25, None, stop).unwrap();
        assert_eq!((rate, channels), (8_000, 2));
        let queued: usize = chunks.try_iter().map(|chunk| chunk.len() / 2).sum();
        assert!(queued >= 4_000, "{queued} frames (a quarter second of silence, then the sound)");
    }

    #[test]
    fn the_filler_hands_out_every_sample_in_order_then_ends() {
        let (sender, receiver) = crossbeam_channel::unbounded();
        sender.send(vec![0.5f32, -0.25]).unwrap();
        sender.send(vec![1.0f32]).unwrap();
        drop(sender);
        let ended = Arc::new(AtomicBool::new(false));
        let mut fill = filler(receiver, Arc::clone(&ended));
        let mut first = [0u8; 8];
        assert_eq!(fill(&mut first), 8);
        let mut rest = [0u8; 8];
        assert_eq!(fill(&mut rest), 4, "what is left, then the end");
        assert!(!ended.load(Ordering::Relaxed));
        assert_eq!(fill(&mut rest), 0);
        assert!(ended.load(Ordering::Relaxed), "the end is known");
        let bytes: Vec<u8> = [0.5f32, -0.25, 1.0].iter().flat_map(|s| s.to_le_bytes()).collect();
        assert_eq!([&first[..], &rest[..4]].concat(), bytes);
    }
}
