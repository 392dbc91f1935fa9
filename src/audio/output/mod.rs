//! Sound to the speakers, and when each part of it is heard, so a motion or
//! a board can be started on the sound's time.
//!
//! - On Linux and the other Unix systems: the system's sound server
//!   (PulseAudio, or PipeWire, which serves the same protocol), in pure
//!   Rust (`server.rs`).
//! - On Windows and macOS: the system's own audio through `cpal` (WASAPI,
//!   Core Audio: `device.rs`). On Linux the `cpal` feature adds it behind the
//!   server (ALSA's default device, when no server answers); the tests build
//!   with it and play through it.
//!
//! With no sound output at all `Speakers::connect` says so once, and callers
//! play the motion on the same clock without sound.

#[cfg(any(feature = "cpal", windows, target_os = "macos"))]
mod device;
mod feed;
#[cfg(not(any(windows, target_os = "macos")))]
mod server;

use std::path::Path;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use super::AudioError;

/// How much sound the output holds ahead of the speakers.
pub const BUFFER: Duration = Duration::from_millis(30);

/// Why sound cannot be played.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    /// No sound server or output device to play on.
    #[error("no sound output ({0})")]
    NoServer(String),
    /// The output refused the stream, or went away.
    #[error("the sound output refused to play: {0}")]
    Stream(String),
    /// The sound could not be read.
    #[error(transparent)]
    Sound(#[from] AudioError),
}

impl OutputError {
    /// Why, without the "no sound output" (for a list of places looked in).
    fn why(self) -> String {
        match self {
            Self::NoServer(why) => why,
            other => other.to_string(),
        }
    }
}

/// Where the sound goes.
#[derive(Clone)]
enum Backend {
    #[cfg(not(any(windows, target_os = "macos")))]
    Server(server::Server),
    #[cfg(any(feature = "cpal", windows, target_os = "macos"))]
    Device(device::Device),
}

/// A connection to the sound output (a copy shares it).
#[derive(Clone)]
pub struct Speakers {
    backend: Backend,
}

impl std::fmt::Debug for Speakers {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Speakers").finish_non_exhaustive()
    }
}

/// A sound being played; dropping it stops it.
pub struct Playing {
    sink: Option<Sink>,
    stop: Arc<AtomicBool>,
    /// The whole sound (or grain) has gone to the output.
    ended: Arc<AtomicBool>,
    /// The sound's time at the stream's first frame, s (before 0: silence first).
    from_s: f64,
}

/// The stream a sound plays on.
enum Sink {
    #[cfg(not(any(windows, target_os = "macos")))]
    Server(server::Stream),
    #[cfg(any(feature = "cpal", windows, target_os = "macos"))]
    Device(device::Stream),
}

impl std::fmt::Debug for Playing {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Playing").field("from_s", &self.from_s).finish_non_exhaustive()
    }
}

/// Where the sound server this user's programs reach listens (`PULSE_SERVER`,
/// or the user's runtime folder), when one is named: what a stalled output names.
pub fn default_server() -> Option<std::path::PathBuf> {
    #[cfg(not(any(windows, target_os = "macos")))]
    return pulseaudio::socket_path_from_env();
    #[cfg(any(windows, target_os = "macos"))]
    None
}

impl Speakers {
    /// The system's sound output: the sound server the environment names
    /// (`PULSE_SERVER`, or the user's runtime folder), as every PulseAudio
    /// client does; on Windows and macOS (or with the `cpal` feature, when
    /// no server answers) the default output device.
    pub fn connect() -> Result<Self, OutputError> {
        let mut looked = Vec::new();
        #[cfg(not(any(windows, target_os = "macos")))]
        match server::Server::connect() {
            Ok(server) => return Ok(Self { backend: Backend::Server(server) }),
            Err(error) => looked.push(error.why()),
        }
        #[cfg(any(feature = "cpal", windows, target_os = "macos"))]
        match device::Device::connect() {
            Ok(device) => return Ok(Self { backend: Backend::Device(device) }),
            Err(error) => looked.push(error.why()),
        }
        Err(OutputError::NoServer(looked.join("; ")))
    }

    /// The sound server listening on `socket`. The cookie is the user's
    /// (`PULSE_COOKIE`, `~/.config/pulse/cookie`); without one, the server's
    /// anonymous access is asked for.
    pub fn connect_to(socket: &Path) -> Result<Self, OutputError> {
        #[cfg(not(any(windows, target_os = "macos")))]
        return server::Server::connect_to(socket).map(|server| Self { backend: Backend::Server(server) });
        #[cfg(any(windows, target_os = "macos"))]
        Err(OutputError::NoServer(format!("{}: this system has no sound server client", socket.display())))
    }

    /// The system's default output device through `cpal` (WASAPI, Core
    /// Audio; ALSA on Linux), whatever server is running.
    #[cfg(any(feature = "cpal", windows, target_os = "macos"))]
    pub fn connect_device() -> Result<Self, OutputError> {
        device::Device::connect().map(|device| Self { backend: Backend::Device(device) })
    }

    /// Plays `path` from `from_s` (before 0: silence first) as soon as it can.
    pub fn play(&self, path: &Path, from_s: f64) -> Result<Playing, OutputError> {
        self.play_for(path, from_s, None)
    }

    /// Plays `path` from `from_s` for `only` at most (a scrubbing grain), or to its end.
    pub fn play_for(&self, path: &Path, from_s: f64, only: Option<Duration>) -> Result<Playing, OutputError> {
        let stop = Arc::new(AtomicBool::new(false));
        let ended = Arc::new(AtomicBool::new(false));
        let decoded = feed::decoding(path, from_s, only, Arc::clone(&stop), Arc::clone(&ended))?;
        let sink = match &self.backend {
            #[cfg(not(any(windows, target_os = "macos")))]
            Backend::Server(server) => Sink::Server(server.play(decoded)?),
            #[cfg(any(feature = "cpal", windows, target_os = "macos"))]
            Backend::Device(device) => Sink::Device(device.play(decoded, Arc::clone(&ended))?),
        };
        Ok(Playing { sink: Some(sink), stop, ended, from_s })
    }
}

impl Playing {
    /// When the sound's `sound_s` (seconds from its start) is heard, read
    /// off the output's own clock (the server's, or the device's timestamps).
    pub fn heard_at(&self, sound_s: f64) -> Result<Instant, OutputError> {
        let first = match self.sink.as_ref().ok_or_else(|| OutputError::Stream("stopped".into()))? {
            #[cfg(not(any(windows, target_os = "macos")))]
            Sink::Server(stream) => stream.first_heard()?,
            #[cfg(any(feature = "cpal", windows, target_os = "macos"))]
            Sink::Device(stream) => stream.first_heard()?,
        };
        let after = sound_s - self.from_s;
        let at = if after >= 0.0 {
            first.checked_add(Duration::from_secs_f64(after))
        } else {
            first.checked_sub(Duration::from_secs_f64(-after))
        };
        at.ok_or_else(|| OutputError::Stream("the sound's clock is out of range".into()))
    }

    /// Whether it is still sending sound (it ends at the sound's or grain's end).
    pub fn is_playing(&self) -> bool {
        !self.ended.load(Ordering::Relaxed)
    }

    /// A flag set once the whole sound (or grain) has gone to the output,
    /// for whoever watches it from another thread.
    pub fn ended(&self) -> Arc<AtomicBool> {
        Arc::clone(&self.ended)
    }

    /// Stops the sound now.
    pub fn stop(mut self) {
        self.halt();
    }

    fn halt(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
        match self.sink.take() {
            #[cfg(not(any(windows, target_os = "macos")))]
            Some(Sink::Server(stream)) => stream.delete(),
            #[cfg(any(feature = "cpal", windows, target_os = "macos"))]
            Some(Sink::Device(stream)) => drop(stream),
            None => {}
        }
    }
}

impl Drop for Playing {
    fn drop(&mut self) {
        self.halt();
    }
}
