//! Sound through the system's own audio with `cpal`: WASAPI on Windows,
//! Core Audio on macOS (nothing to install on either), ALSA on Linux (the
//! `cpal` feature: ALSA's headers are a system package there). The default
//! output device is opened at its own rate and channels; the sound is
//! brought to them (linear interpolation, mono to every channel). When the
//! stream's first frame is heard is read off each callback's timestamps:
//! when its first frame will be played, less the frames handed out before it.

use std::collections::VecDeque;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Condvar, Mutex};
use std::time::{Duration, Instant};

use cpal::traits::{DeviceTrait, HostTrait, StreamTrait};

use super::feed::{Decoded, Pull};
use super::{BUFFER, OutputError};

/// Consecutive callbacks whose reckonings of when the first frame is heard must agree.
const SETTLED_CALLBACKS: usize = 8;
/// Within this of each other.
const AGREE: Duration = Duration::from_millis(3);
/// What to do when the device will not play.
const TO_DO: &str = "plug in speakers or headphones, or choose another default output in the system's sound settings";
/// How long a device may take to settle.
const SETTLE_WITHIN: Duration = Duration::from_secs(5);

/// The system's default output device (a copy shares it).
#[derive(Clone)]
pub(super) struct Device {
    device: cpal::Device,
    config: cpal::SupportedStreamConfig,
}

/// A stream on the device; dropping it stops the sound.
pub(super) struct Stream {
    _stream: cpal::Stream,
    clock: Arc<Timing>,
}

/// The clock, and a bell rung at each callback.
#[derive(Default)]
struct Timing {
    clock: Mutex<Clock>,
    rung: Condvar,
}

/// When the stream's first frame is heard, from the callbacks' timestamps.
#[derive(Default)]
struct Clock {
    /// The last few reckonings, newest last.
    recent: VecDeque<Instant>,
}

impl Device {
    /// The default host's default output device, and its own configuration.
    pub fn connect() -> Result<Self, OutputError> {
        let host = cpal::default_host();
        let device = host
            .default_output_device()
            .ok_or_else(|| OutputError::NoServer(format!("{} has no output device: {TO_DO}", host.id().name())))?;
        let config = device
            .default_output_config()
            .map_err(|error| OutputError::NoServer(format!("{}: {error}: {TO_DO}", host.id().name())))?;
        Ok(Self { device, config })
    }

    /// Starts the decoded sound.
    pub fn play(&self, decoded: Decoded, ended: Arc<AtomicBool>) -> Result<Stream, OutputError> {
        use cpal::SampleFormat as F;
        let clock = Arc::new(Timing::default());
        let stream = match self.config.sample_format() {
            F::F32 => self.build::<f32>(decoded, Arc::clone(&clock), ended),
            F::I16 => self.build::<i16>(decoded, Arc::clone(&clock), ended),
            F::I32 => self.build::<i32>(decoded, Arc::clone(&clock), ended),
            F::U16 => self.build::<u16>(decoded, Arc::clone(&clock), ended),
            F::F64 => self.build::<f64>(decoded, Arc::clone(&clock), ended),
            other => Err(OutputError::Stream(format!("the output device wants {other} samples: {TO_DO}"))),
        }?;
        stream.play().map_err(|error| OutputError::Stream(error.to_string()))?;
        Ok(Stream { _stream: stream, clock })
    }

    fn build<T: cpal::SizedSample + cpal::FromSample<f32>>(
        &self,
        decoded: Decoded,
        clock: Arc<Timing>,
        ended: Arc<AtomicBool>,
    ) -> Result<cpal::Stream, OutputError> {
        let rate = self.config.sample_rate();
        let mut config = self.config.config();
        // A short buffer, as with the sound server, where the device allows one.
        if let cpal::SupportedBufferSize::Range { min, max } = *self.config.buffer_size() {
            let frames = u32::try_from(u64::from(rate) * u64::try_from(BUFFER.as_millis()).unwrap_or(30) / 1000)
                .unwrap_or(u32::MAX);
            config.buffer_size = cpal::BufferSize::Fixed(frames.clamp(min, max));
        }
        let channels = usize::from(config.channels.max(1));
        let mut convert = Convert::new(decoded, rate);
        let mut handed_out: u64 = 0;
        let mut frame = Vec::new();
        let data = move |out: &mut [T], info: &cpal::OutputCallbackInfo| {
            let now = Instant::now();
            let stamp = info.timestamp();
            let ahead = stamp.playback.saturating_duration_since(stamp.callback);
            #[allow(clippy::cast_precision_loss)]
            let before = Duration::from_secs_f64(handed_out as f64 / f64::from(rate));
            // Never wait in the callback: a reckoning missed is one of many.
            if let Ok(mut reckoned) = clock.clock.try_lock() {
                reckoned.note((now + ahead).checked_sub(before));
                clock.rung.notify_all();
            }
            for samples in out.chunks_mut(channels) {
                frame.resize(channels, 0.0);
                convert.next(&mut frame);
                for (sample, value) in samples.iter_mut().zip(&frame) {
                    *sample = T::from_sample(*value);
                }
            }
            handed_out += (out.len() / channels) as u64;
        };
        let gone = move |error: cpal::Error| {
            if ends_the_sound(error.kind()) {
                ended.store(true, Ordering::Relaxed);
            }
        };
        self.device
            .build_output_stream::<T, _, _>(config, data, gone, Some(Duration::from_secs(2)))
            .map_err(|error| OutputError::Stream(error.to_string()))
    }
}

/// Whether a stream's error ends the sound: the device went away (unplugged)
/// or failed. A glitch, a new route for the default device or a refused
/// real-time priority leave it playing.
fn ends_the_sound(kind: cpal::ErrorKind) -> bool {
    use cpal::ErrorKind as K;
    !matches!(kind, K::Xrun | K::DeviceChanged | K::RealtimeDenied)
}

impl Clock {
    fn note(&mut self, first_heard: Option<Instant>) {
        if let Some(first_heard) = first_heard {
            if self.recent.len() == SETTLED_CALLBACKS {
                self.recent.pop_front();
            }
            self.recent.push_back(first_heard);
        }
    }

    /// The earliest of the last few reckonings (a late-running callback only
    /// ever reckons later), once they agree: until the device is running,
    /// callbacks fill its buffer ahead and reckon nothing true.
    fn settled(&self) -> Option<Instant> {
        let earliest = *self.recent.iter().min()?;
        let latest = *self.recent.iter().max()?;
        (self.recent.len() == SETTLED_CALLBACKS && latest - earliest <= AGREE).then_some(earliest)
    }

    /// The newest reckoning, settled or not.
    fn latest(&self) -> Option<Instant> {
        self.recent.back().copied()
    }
}

impl Stream {
    /// When the stream's first frame was (or will be) heard: the earliest
    /// reckoning of the first callbacks (waiting up to two seconds for them).
    pub fn first_heard(&self) -> Result<Instant, OutputError> {
        let deadline = Instant::now() + SETTLE_WITHIN;
        let stopped = || OutputError::Stream("the output stopped".into());
        let mut clock = self.clock.clock.lock().map_err(|_| stopped())?;
        loop {
            let now = Instant::now();
            if let Some(first) = clock.settled() {
                return Ok(first);
            }
            if now >= deadline {
                return clock
                    .latest()
                    .ok_or_else(|| OutputError::Stream(format!("the output device never began playing: {TO_DO}")));
            }
            clock = self.clock.rung.wait_timeout(clock, deadline - now).map_err(|_| stopped())?.0;
        }
    }
}

/// The sound brought to the device's rate and channels.
struct Convert {
    pull: Pull,
    /// The source's channels (one or two).
    source: usize,
    /// The source frames either side of the output's time.
    from: [f32; 2],
    to: [f32; 2],
    /// Where the output's time falls between `from` (0) and `to` (1).
    phase: f64,
    /// Source frames per output frame.
    step: f64,
}

impl Convert {
    fn new(decoded: Decoded, rate: u32) -> Self {
        let Decoded { pull, rate: source_rate, channels: source } = decoded;
        // The first output frame is the first source frame: two frames are read in first.
        Self {
            pull,
            source,
            from: [0.0; 2],
            to: [0.0; 2],
            phase: 2.0,
            step: f64::from(source_rate) / f64::from(rate.max(1)),
        }
    }

    /// The next source frame, in two channels (silence after the end).
    fn read(&mut self) -> [f32; 2] {
        let mut frame = [0.0; 2];
        let read = self.pull.fill(&mut frame[..self.source]);
        match (read, self.source) {
            (0, _) => [0.0; 2],
            (_, 1) => [frame[0], frame[0]],
            _ => frame,
        }
    }

    /// The next output frame into `out` (the device's channels).
    fn next(&mut self, out: &mut [f32]) {
        while self.phase >= 1.0 {
            self.from = self.to;
            self.to = self.read();
            self.phase -= 1.0;
        }
        #[allow(clippy::cast_possible_truncation)]
        let phase = self.phase as f32;
        let [left, right] = [0, 1].map(|side| self.from[side] + (self.to[side] - self.from[side]) * phase);
        self.phase += self.step;
        match out {
            [mono] => *mono = 0.5 * (left + right),
            [first, second, rest @ ..] => {
                *first = left;
                *second = right;
                // A mono sound on every speaker; a stereo one on the first two.
                rest.fill(if self.source == 1 { left } else { 0.0 });
            }
            [] => {}
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn decoded(samples: Vec<f32>, rate: u32, channels: usize) -> Decoded {
        let (sender, chunks) = crossbeam_channel::unbounded();
        sender.send(samples).unwrap();
        Decoded { pull: Pull::new(chunks, Arc::default()), rate, channels }
    }

    fn converted(convert: &mut Convert, frames: usize, channels: usize) -> Vec<f32> {
        let mut out = vec![0.0; frames * channels];
        for frame in out.chunks_mut(channels) {
            convert.next(frame);
        }
        out
    }

    #[test]
    fn at_the_same_rate_every_frame_passes_unchanged_mono_on_every_channel() {
        let mut convert = Convert::new(decoded(vec![0.1, 0.2, 0.3], 48_000, 1), 48_000);
        let out = converted(&mut convert, 4, 4);
        assert_eq!(out, [[0.1; 4], [0.2; 4], [0.3; 4], [0.0; 4]].concat());
    }

    #[test]
    fn a_lower_rate_is_interpolated_on_the_same_time_axis() {
        // 24 kHz stereo to 48 kHz stereo: every other output frame is halfway.
        let mut convert = Convert::new(decoded(vec![0.0, 1.0, 1.0, 0.0, 0.5, 0.5], 24_000, 2), 48_000);
        let out = converted(&mut convert, 5, 2);
        let expected = [0.0, 1.0, 0.5, 0.5, 1.0, 0.0, 0.75, 0.25, 0.5, 0.5];
        for (got, want) in out.iter().zip(expected) {
            assert!((got - want).abs() < 1e-6, "{out:?}");
        }
    }

    #[test]
    fn a_higher_rate_keeps_time_stereo_to_a_mono_device_is_averaged() {
        // 96 kHz to 48 kHz: every other source frame.
        let samples: Vec<f32> = (0..8).flat_map(|i| [i as f32, -(i as f32)]).collect();
        let mut convert = Convert::new(decoded(samples, 96_000, 2), 48_000);
        assert_eq!(converted(&mut convert, 4, 1), [0.0; 4], "left and right cancel");
        let samples: Vec<f32> = (0..8).flat_map(|i| [i as f32, i as f32]).collect();
        let mut convert = Convert::new(decoded(samples, 96_000, 2), 48_000);
        assert_eq!(converted(&mut convert, 4, 2), [0.0, 0.0, 2.0, 2.0, 4.0, 4.0, 6.0, 6.0]);
    }

    #[test]
    fn an_unplugged_device_ends_the_sound_a_glitch_or_a_new_route_does_not() {
        use cpal::ErrorKind as K;
        assert!(ends_the_sound(K::DeviceNotAvailable));
        assert!(ends_the_sound(K::StreamInvalidated));
        assert!(ends_the_sound(K::BackendError));
        assert!(!ends_the_sound(K::Xrun));
        assert!(!ends_the_sound(K::DeviceChanged));
        assert!(!ends_the_sound(K::RealtimeDenied));
    }

    #[test]
    fn the_earliest_of_the_last_reckonings_counts_once_they_agree() {
        let start = Instant::now();
        let ms = |ms| start + Duration::from_millis(ms);
        let mut clock = Clock::default();
        // Filling the buffer before the device runs: reckonings far too early.
        clock.note(Some(start));
        clock.note(Some(start));
        assert_eq!(clock.settled(), None);
        for late in [2000, 2001, 2003, 2000, 2002, 2001, 2002] {
            clock.note(Some(ms(late)));
            assert_eq!(clock.settled(), None, "the early ones are still among the last {SETTLED_CALLBACKS}");
        }
        clock.note(Some(ms(2001)));
        assert_eq!(clock.settled(), Some(ms(2000)));
        clock.note(Some(ms(2009)));
        assert_eq!(clock.settled(), None, "9 ms apart do not agree");
        assert_eq!(clock.latest(), Some(ms(2009)));
    }
}
