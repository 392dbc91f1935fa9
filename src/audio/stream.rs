//! A sound decoded as it streams, one packet's samples at a time
//! (interleaved, as the file holds them), from the start or from any time:
//! what the analyses read and what playback sends to the speakers.

use std::path::{Path, PathBuf};

use symphonia::core::audio::SampleBuffer;
use symphonia::core::codecs::{CODEC_TYPE_MP3, CODEC_TYPE_NULL, Decoder, DecoderOptions};
use symphonia::core::errors::Error as DecodeError;
use symphonia::core::formats::{FormatOptions, FormatReader, SeekMode, SeekTo};
use symphonia::core::io::MediaSourceStream;
use symphonia::core::meta::MetadataOptions;
use symphonia::core::probe::Hint;
use symphonia::core::units::Time;

use super::{AudioError, MAX_CHANNELS, MAX_SOUND_BYTES, MAX_SOUND_SECONDS, SAMPLE_RATES};

/// Runs a call into the decoders, which can still panic on a file damaged
/// in a way they do not check (everything this module can check is checked
/// before): a panic is the file's damage, named, never the program's end.
fn contained<T>(path: &Path, what: &str, call: impl FnOnce() -> T) -> Result<T, AudioError> {
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(call))
        .map_err(|_| AudioError::Damaged { path: path.to_path_buf(), what: what.to_string() })
}

/// The sample rate a WAV's `fmt ` chunk or a FLAC's STREAMINFO says, from the
/// file's first bytes; `None` for other files (or one too short to say).
fn header_rate(head: &[u8]) -> Option<u64> {
    let u32_at = |at: usize| head.get(at..at + 4).map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]));
    if head.starts_with(b"RIFF") && head.get(8..12) == Some(b"WAVE") {
        // Chunks after the 12-byte header: id, size, body (padded to even).
        let mut at = 12usize;
        while let (Some(id), Some(size)) = (head.get(at..at + 4), u32_at(at + 4)) {
            if id == b"fmt " {
                return u32_at(at + 12).map(u64::from);
            }
            at = at.checked_add(8)?.checked_add(usize::try_from(size).ok()?.next_multiple_of(2))?;
        }
        return None;
    }
    if head.starts_with(b"fLaC") {
        // The first metadata block is STREAMINFO: its rate is 20 bits at byte 10 of the block.
        let b = head.get(18..21)?;
        return Some((u64::from(b[0]) << 12) | (u64::from(b[1]) << 4) | (u64::from(b[2]) >> 4));
    }
    None
}

/// Samples an MP3 without a gapless note is taken to start late by (LAME's
/// encoder delay, 576, and the decoder's, 529).
const MP3_DELAY: usize = 1105;

/// A sound being read.
pub struct Reader {
    path: PathBuf,
    format: Box<dyn FormatReader>,
    decoder: Box<dyn Decoder>,
    track_id: u32,
    rate: u32,
    channels: u16,
    expected: Option<u64>,
    /// Frames still to drop before the first one handed out.
    skip: usize,
    /// An MP3 without a gapless note: every time is late by [`MP3_DELAY`].
    late_mp3: bool,
    buffer: Option<SampleBuffer<f32>>,
}

impl std::fmt::Debug for Reader {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Reader").field("path", &self.path).field("rate", &self.rate).finish_non_exhaustive()
    }
}

impl Reader {
    /// Opens the sound in `path`, at its start.
    /// Only a regular file within [`MAX_SOUND_BYTES`] is read; a sample
    /// rate, channel count or length outside what is read is refused before
    /// anything is decoded.
    pub fn open(path: &Path) -> Result<Self, AudioError> {
        let (mut file, _) = crate::project::input::open_regular(path, MAX_SOUND_BYTES)?;
        let io = |source| AudioError::Open { path: path.to_path_buf(), source };
        let mut head = Vec::new();
        std::io::Read::read_to_end(&mut std::io::Read::take(&mut file, 64 * 1024), &mut head).map_err(io)?;
        if let Some(rate) = header_rate(&head).filter(|rate| !SAMPLE_RATES.contains(&u32::try_from(*rate).unwrap_or(0)))
        {
            return Err(AudioError::Rate { path: path.to_path_buf(), rate });
        }
        std::io::Seek::rewind(&mut file).map_err(io)?;
        let format_error =
            |error: DecodeError| AudioError::Format { path: path.to_path_buf(), reason: error.to_string() };
        let stream = MediaSourceStream::new(Box::new(file), Default::default());
        let mut hint = Hint::new();
        if let Some(extension) = path.extension().and_then(|e| e.to_str()) {
            hint.with_extension(extension);
        }
        // Gapless: an MP3's encoder delay and padding are cut, so times are the sound's own.
        let options = FormatOptions { enable_gapless: true, ..FormatOptions::default() };
        let probed = contained(path, "reading its header", || {
            symphonia::default::get_probe().format(&hint, stream, &options, &MetadataOptions::default())
        })?
        .map_err(format_error)?;
        let format = probed.format;
        let track = format
            .tracks()
            .iter()
            .find(|track| track.codec_params.codec != CODEC_TYPE_NULL && track.codec_params.sample_rate.is_some())
            .ok_or_else(|| AudioError::NoTrack { path: path.to_path_buf() })?;
        let (track_id, params) = (track.id, track.codec_params.clone());
        let rate = params.sample_rate.unwrap_or(0);
        if !SAMPLE_RATES.contains(&rate) {
            return Err(AudioError::Rate { path: path.to_path_buf(), rate: u64::from(rate) });
        }
        if let Some(channels) = params.channels.map(|c| c.count()).filter(|count| *count > MAX_CHANNELS) {
            return Err(AudioError::Channels { path: path.to_path_buf(), channels });
        }
        if let Some(seconds) = params.n_frames.map(|frames| frames / u64::from(rate)).filter(|s| *s > MAX_SOUND_SECONDS)
        {
            return Err(AudioError::TooLong { path: path.to_path_buf(), seconds });
        }
        let decoder = contained(path, "starting its decoder", || {
            symphonia::default::get_codecs().make(&params, &DecoderOptions::default())
        })?
        .map_err(format_error)?;
        // An MP3 without the encoder's gapless note starts with the encoder's and
        // the decoder's delay: LAME's 576 + 529 samples, which nearly every MP3 has.
        let late_mp3 = params.codec == CODEC_TYPE_MP3 && params.delay.is_none();
        Ok(Self {
            path: path.to_path_buf(),
            format,
            decoder,
            track_id,
            rate,
            channels: params.channels.map_or(0, |c| u16::try_from(c.count()).unwrap_or(u16::MAX)),
            expected: params.n_frames,
            skip: if late_mp3 { MP3_DELAY } else { 0 },
            late_mp3,
            buffer: None,
        })
    }

    /// Samples a second.
    pub fn rate(&self) -> u32 {
        self.rate
    }

    /// Channels (known once the first packet is decoded, for a file that does not say).
    pub fn channels(&self) -> u16 {
        self.channels
    }

    /// Samples per channel, when the file says.
    pub fn expected_frames(&self) -> Option<u64> {
        self.expected
    }

    /// Goes to `seconds` from the start: the next chunk starts there (to the sample).
    pub fn seek(&mut self, seconds: f64) -> Result<(), AudioError> {
        let seconds = seconds.max(0.0);
        let delay_s = if self.late_mp3 { MP3_DELAY as f64 / f64::from(self.rate) } else { 0.0 };
        let target = seconds + delay_s;
        // Whole seconds and a fraction, as symphonia takes a time.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let time = Time::new(target.trunc() as u64, target.fract());
        let (format, track_id) = (&mut self.format, self.track_id);
        let seeked = contained(&self.path, "seeking", || {
            format.seek(SeekMode::Accurate, SeekTo::Time { time, track_id: Some(track_id) })
        })?
        .map_err(|error| AudioError::Format { path: self.path.clone(), reason: error.to_string() })?;
        self.decoder.reset();
        self.skip = usize::try_from(seeked.required_ts.saturating_sub(seeked.actual_ts)).unwrap_or(0);
        Ok(())
    }

    /// The next packet's samples, interleaved, and how many channels they
    /// interleave; `None` at the end.
    pub fn next_chunk(&mut self) -> Result<Option<(&[f32], usize)>, AudioError> {
        let Some(first) = self.decode_next()? else { return Ok(None) };
        let count = usize::from(self.channels.max(1));
        Ok(self.buffer.as_ref().map(|samples| (&samples.samples()[first * count..], count)))
    }

    /// Decodes the next packet with something left after the skip; the first frame to hand out.
    fn decode_next(&mut self) -> Result<Option<usize>, AudioError> {
        let path = self.path.clone();
        let format_error = |error: DecodeError| AudioError::Format { path: path.clone(), reason: error.to_string() };
        loop {
            let format = &mut self.format;
            let packet = match contained(&path, "reading a packet", || format.next_packet())? {
                Ok(packet) => packet,
                // The end of the stream.
                Err(DecodeError::IoError(error)) if error.kind() == std::io::ErrorKind::UnexpectedEof => {
                    return Ok(None);
                }
                Err(DecodeError::ResetRequired) => return Ok(None),
                Err(error) => return Err(format_error(error)),
            };
            if packet.track_id() != self.track_id {
                continue;
            }
            let decoder = &mut self.decoder;
            let decoded = match contained(&path, "decoding a packet", || decoder.decode(&packet))? {
                Ok(decoded) => decoded,
                // A damaged packet is skipped, as players do.
                Err(DecodeError::DecodeError(_)) => continue,
                Err(error) => return Err(format_error(error)),
            };
            let spec = *decoded.spec();
            let count = spec.channels.count().max(1);
            self.channels = u16::try_from(count).unwrap_or(u16::MAX);
            let samples = self.buffer.get_or_insert_with(|| SampleBuffer::new(decoded.capacity() as u64, spec));
            if samples.capacity() < decoded.capacity() * count {
                *samples = SampleBuffer::new(decoded.capacity() as u64, spec);
            }
            samples.copy_interleaved_ref(decoded);
            let frames = samples.samples().len() / count;
            let skipped = self.skip.min(frames);
            self.skip -= skipped;
            if skipped < frames {
                return Ok(Some(skipped));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reading_from_a_time_starts_there_to_the_sample() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("ramp.wav");
        // A ramp: sample i is i / 50,000, so a value says where it is.
        let rate = 8_000;
        let samples: Vec<f32> = (0..24_000).map(|i| f32::from(i16::try_from(i).unwrap()) / 50_000.0).collect();
        std::fs::write(&path, crate::audio::pcm16_wav(&samples, rate, 2)).unwrap();
        let mut reader = Reader::open(&path).unwrap();
        reader.seek(1.25).unwrap();
        let (chunk, _) = reader.next_chunk().unwrap().unwrap();
        // Written as 16-bit (×32,000), read back over 32,768.
        let at = 10_000.0 / 50_000.0 * 32_000.0 / 32_768.0;
        assert!((chunk[0] - at).abs() < 1e-4 && (chunk[1] - at).abs() < 1e-4, "{} {}", chunk[0], at);
        let mut frames = chunk.len() / 2;
        while let Some((chunk, _)) = reader.next_chunk().unwrap() {
            frames += chunk.len() / 2;
        }
        assert_eq!(frames, 14_000, "the rest of the sound, to its end");
    }
}
