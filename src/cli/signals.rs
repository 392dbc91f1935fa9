//! Signals that end the command line (Ctrl-C, `kill`, a closed terminal),
//! delivered as messages, so that a command driving a base stops it, sets its
//! brake and says so before it exits, instead of dying mid-drive.

use crossbeam_channel::Receiver;

/// A signal that asks the command to end.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Interrupt {
    /// Its name, e.g. `SIGINT`.
    pub name: &'static str,
    /// The exit status a shell gives a command it ended (128 + the signal's number).
    pub exit_code: u8,
}

impl std::fmt::Display for Interrupt {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name)
    }
}

/// From now on SIGINT, SIGTERM and SIGHUP no longer end the process: each
/// arrives on the returned channel instead.
#[cfg(unix)]
pub fn listen() -> std::io::Result<Receiver<Interrupt>> {
    use signal_hook::consts::signal::{SIGHUP, SIGINT, SIGTERM};
    let mut signals = signal_hook::iterator::Signals::new([SIGINT, SIGTERM, SIGHUP])?;
    let (sender, interrupts) = crossbeam_channel::unbounded();
    std::thread::Builder::new().name("signals".into()).spawn(move || {
        for signal in signals.forever() {
            let name = match signal {
                SIGINT => "SIGINT",
                SIGTERM => "SIGTERM",
                _ => "SIGHUP",
            };
            let exit_code = u8::try_from(128 + signal).unwrap_or(1);
            if sender.send(Interrupt { name, exit_code }).is_err() {
                return;
            }
        }
    })?;
    Ok(interrupts)
}

/// From now on Ctrl-C and termination requests arrive on the returned channel.
#[cfg(not(unix))]
pub fn listen() -> std::io::Result<Receiver<Interrupt>> {
    use std::sync::Arc;
    use std::sync::atomic::{AtomicBool, Ordering};
    let flag = Arc::new(AtomicBool::new(false));
    for signal in [signal_hook::consts::SIGINT, signal_hook::consts::SIGTERM] {
        signal_hook::flag::register(signal, Arc::clone(&flag))?;
    }
    let (sender, interrupts) = crossbeam_channel::unbounded();
    std::thread::Builder::new().name("signals".into()).spawn(move || {
        // Windows has no signal iterator: look at the flag ten times a second.
        loop {
            std::thread::sleep(std::time::Duration::from_millis(100));
            if flag.swap(false, Ordering::SeqCst) && sender.send(Interrupt { name: "Ctrl-C", exit_code: 130 }).is_err()
            {
                return;
            }
        }
    })?;
    Ok(interrupts)
}

/// The first signal that asked the command to end, once one has.
#[derive(Clone, Debug, Default)]
pub struct Caught(std::sync::Arc<std::sync::OnceLock<Interrupt>>);

impl Caught {
    /// Remembers `interrupt` if it is the first.
    pub fn set(&self, interrupt: Interrupt) {
        let _ = self.0.set(interrupt);
    }

    /// The first signal caught, if any.
    pub fn get(&self) -> Option<Interrupt> {
        self.0.get().copied()
    }
}

/// From now on SIGINT, SIGTERM and SIGHUP cancel the returned token instead
/// of ending the process: an operation stops at its next safe point (never
/// mid-packet) and the command says what it left. Which signal it was is in
/// the returned [`Caught`].
pub fn cancel_on_signal(what: &'static str) -> std::io::Result<(crate::device::Cancel, Caught)> {
    let interrupts = listen()?;
    let (trigger, cancel) = crate::device::Cancel::new();
    let caught = Caught::default();
    let seen = caught.clone();
    std::thread::Builder::new().name("cancel on signal".into()).spawn(move || {
        for interrupt in interrupts {
            if seen.get().is_none() {
                super::out::say!("\n{interrupt}: stopping {what} at the next safe point…");
            }
            seen.set(interrupt);
            let _ = trigger.try_send(());
        }
    })?;
    Ok((cancel, caught))
}
