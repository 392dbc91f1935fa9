//! Tests that need a system service or program beside the Rust toolchain: a
//! real PulseAudio server with a null sink for speakers (Debian's
//! `pulseaudio`), espeak-ng's voice. On a machine without them each skips
//! with a one-line notice saying what to install; under `CI` (or
//! `SERVO_STUDIO_REQUIRE_SERVICES=1`) each fails instead, and `.ci/run`
//! installs them and runs this module (and `ui::sound::`, whose sound-server
//! tests skip the same way) on their own, with the `cpal` feature.

mod show_sync;
mod sound_sync;
mod speech;
