//! Sound through the system's sound server: PulseAudio, or PipeWire, which
//! serves the same protocol. The client is the `pulseaudio` crate, pure Rust
//! (no system package to build). A stream is made corked with a short buffer
//! (30 ms), filled from the decoding thread, then started; when its first
//! sample is heard is read back from the server's own clock (how far it has
//! played, less the sink's latency).

use std::path::Path;
use std::time::{Duration, Instant};

use super::feed::{Decoded, Pull};
use super::{BUFFER, OutputError};

/// A PulseAudio cookie's length.
const COOKIE_BYTES: usize = 256;

/// A connection to the sound server (a copy shares it).
#[derive(Clone)]
pub(super) struct Server {
    client: pulseaudio::Client,
}

/// A stream on the server.
pub(super) struct Stream {
    stream: pulseaudio::PlaybackStream,
    rate: u32,
    frame_bytes: u64,
}

/// Bytes for the server from the decoded samples, little-endian f32; 0 at the end of the sound.
fn bytes(mut pull: Pull) -> impl FnMut(&mut [u8]) -> usize + Send + 'static {
    let mut samples = Vec::new();
    move |buffer: &mut [u8]| {
        samples.resize(buffer.len() / 4, 0.0);
        let filled = pull.fill(&mut samples);
        for (bytes, sample) in buffer.chunks_exact_mut(4).zip(&samples[..filled]) {
            bytes.copy_from_slice(&sample.to_le_bytes());
        }
        filled * 4
    }
}

impl Server {
    /// Connects to the sound server the environment names (`PULSE_SERVER`,
    /// or the user's runtime folder), as every PulseAudio client does.
    pub fn connect() -> Result<Self, OutputError> {
        let socket = pulseaudio::socket_path_from_env().ok_or_else(|| {
            OutputError::NoServer(
                "no sound server is running for this user: start PulseAudio or PipeWire (with its pulse service)"
                    .into(),
            )
        })?;
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

    /// Starts the decoded sound on the default sink.
    pub fn play(&self, decoded: Decoded) -> Result<Stream, OutputError> {
        use pulseaudio::AsPlaybackSource;
        use pulseaudio::protocol::{self, stream::BufferAttr, stream::StreamFlags};
        let Decoded { pull, rate, channels } = decoded;
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
        let stream = pollster::block_on(self.client.create_playback_stream(params, bytes(pull).as_playback_source()))
            .map_err(failed)?;
        pollster::block_on(stream.uncork()).map_err(failed)?;
        Ok(Stream { stream, rate, frame_bytes })
    }
}

impl Stream {
    /// When the stream's first frame was (or will be) heard, read off the
    /// server's clock: the frames it has played less the sink's latency,
    /// against the midpoint of the question's round trip. Asked a few times;
    /// the answer with the shortest round trip is taken.
    pub fn first_heard(&self) -> Result<Instant, OutputError> {
        let mut best: Option<(Duration, Instant)> = None;
        let mut answers = 0;
        let deadline = Instant::now() + Duration::from_secs(2);
        while answers < 8 && Instant::now() < deadline {
            let asked = Instant::now();
            let timing = pollster::block_on(self.stream.timing_info())
                .map_err(|error| OutputError::Stream(error.to_string()))?;
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
            // The stream's first frame was heard `heard` before the midpoint.
            #[allow(clippy::cast_precision_loss)]
            let heard = Duration::from_secs_f64((played - latency_frames) as f64 / f64::from(self.rate));
            if let Some(first) = (asked + round_trip / 2).checked_sub(heard)
                && best.is_none_or(|(shortest, _)| round_trip < shortest)
            {
                best = Some((round_trip, first));
            }
        }
        best.map(|(_, first)| first).ok_or_else(|| OutputError::Stream("the sound server never began playing".into()))
    }

    /// Takes the stream off the server.
    pub fn delete(self) {
        let _ = pollster::block_on(self.stream.delete());
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn without_a_sound_server_it_says_no_sound_output_naming_where_it_looked() {
        let dir = tempfile::tempdir().unwrap();
        let socket = dir.path().join("native");
        let said = Server::connect_to(&socket).err().unwrap().to_string();
        assert!(said.starts_with("no sound output") && said.contains("native"), "{said}");
    }
}
