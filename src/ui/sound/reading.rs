//! A sound file read off the frame: its SHA-256 (is it the file the project
//! was timed to?) and its analysis (peaks, onsets, loudness), with the share
//! done so far for a progress bar.

use std::io::Read as _;
use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicU32, Ordering};

use crossbeam_channel::Receiver;
use sha2::{Digest, Sha256};

use super::Problem;
use crate::audio::Analysis;
use crate::link::Waker;

/// A sound read.
#[derive(Debug)]
pub struct Read {
    /// What it holds.
    pub analysis: Analysis,
    /// Its bytes' SHA-256, hex.
    pub sha256: String,
}

impl Read {
    /// How long it plays, ms.
    pub fn duration_ms(&self) -> u64 {
        // An hour's milliseconds: far inside u64.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let ms = (self.analysis.duration_s() * 1000.0).round() as u64;
        ms
    }
}

/// A reading under way.
#[derive(Debug)]
pub struct Reading {
    /// Done so far, thousandths (hashing is the first tenth, decoding the rest).
    share: Arc<AtomicU32>,
    done: Receiver<Result<Read, Problem>>,
}

/// The file's SHA-256, hex, read in 64 KiB pieces; only a regular file
/// within the sounds' size cap is read (never a pipe or a device).
pub fn sha256(file: &std::path::Path) -> std::io::Result<String> {
    let (reader, _) = crate::project::input::open_regular(file, crate::audio::MAX_SOUND_BYTES)
        .map_err(|error| std::io::Error::new(std::io::ErrorKind::InvalidInput, error.to_string()))?;
    let mut reader = reader.take(crate::audio::MAX_SOUND_BYTES);
    let mut hasher = Sha256::new();
    let mut buffer = vec![0u8; 1 << 16];
    loop {
        let read = reader.read(&mut buffer)?;
        if read == 0 {
            break;
        }
        hasher.update(&buffer[..read]);
    }
    Ok(hasher.finalize().iter().map(|byte| format!("{byte:02x}")).collect())
}

impl Reading {
    /// Starts reading `file` on a thread of its own; `waker` is called as it goes and when it ends.
    pub fn start(file: PathBuf, waker: Waker) -> Self {
        let share = Arc::new(AtomicU32::new(0));
        let (sender, done) = crossbeam_channel::bounded(1);
        let progress = Arc::clone(&share);
        let failed = sender.clone();
        let spawned = std::thread::Builder::new().name("sound reading".into()).spawn(move || {
            let result = read(&file, &progress, &waker);
            let _ = sender.send(result);
            waker();
        });
        if let Err(error) = spawned {
            let _ = failed.send(Err(Problem::Unreadable(format!("cannot start reading the sound: {error}"))));
        }
        Self { share, done }
    }

    /// How far it is, 0–1.
    pub fn progress(&self) -> f32 {
        // Thousandths: exact in f32.
        #[allow(clippy::cast_precision_loss)]
        let share = self.share.load(Ordering::Relaxed) as f32 / 1000.0;
        share
    }

    /// The result, once it has ended.
    pub fn done(&mut self) -> Option<Result<Read, Problem>> {
        self.done.try_recv().ok()
    }
}

fn read(file: &std::path::Path, progress: &AtomicU32, waker: &Waker) -> Result<Read, Problem> {
    if !file.exists() {
        return Err(Problem::Missing(file.to_path_buf()));
    }
    let sha256 = sha256(file).map_err(|error| Problem::Unreadable(format!("{}: {error}", file.display())))?;
    progress.store(100, Ordering::Relaxed);
    let mut last = 100;
    let analysis = crate::audio::analyse(file, f32::from(super::READ_AT_PERCENT) / 100.0, |share| {
        // A share in thousandths.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let now = 100 + (share * 900.0) as u32;
        if now >= last + 10 {
            last = now;
            progress.store(now, Ordering::Relaxed);
            waker();
        }
    })
    .map_err(|error| Problem::Unreadable(error.to_string()))?;
    Ok(Read { analysis, sha256 })
}
