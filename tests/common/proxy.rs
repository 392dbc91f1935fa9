//! A TCP proxy between a client and an emulated board, standing in for a
//! bad link: every byte held back a fixed delay each way (a Bluetooth or
//! Wi-Fi bridge), the link cut and restored (a pulled cable), or the board's
//! answers swallowed while what is sent to it still arrives (a board that
//! went silent: it hears, never answers). A listener that accepts and never
//! answers at all is [`Silent`].
#![allow(dead_code, clippy::unwrap_used, clippy::expect_used)]

use std::io::{Read, Write};
use std::net::{Shutdown, TcpListener, TcpStream};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// What the proxy does to the link now.
#[derive(Default)]
struct Faults {
    /// Refuse new connections and close the open ones.
    cut: AtomicBool,
    /// Swallow what the board sends.
    silent: AtomicBool,
    /// Bytes the board sent that were swallowed.
    swallowed: AtomicU64,
}

/// A proxy on 127.0.0.1 to `upstream` (`tcp://HOST:PORT`).
pub struct Proxy {
    /// Where clients connect: `tcp://127.0.0.1:PORT`.
    pub port: String,
    faults: Arc<Faults>,
    open: Arc<Mutex<Vec<TcpStream>>>,
}

impl Proxy {
    /// Forwards to `upstream`, each byte `delay` late in each direction.
    pub fn new(upstream: &str, delay: Duration) -> Self {
        let listener = TcpListener::bind("127.0.0.1:0").unwrap();
        let port = format!("tcp://{}", listener.local_addr().unwrap());
        let upstream = upstream.trim_start_matches("tcp://").to_string();
        let faults = Arc::new(Faults::default());
        let open = Arc::new(Mutex::new(Vec::new()));
        let (theirs, kept) = (Arc::clone(&faults), Arc::clone(&open));
        std::thread::spawn(move || {
            for client in listener.incoming() {
                let Ok(client) = client else { continue };
                if theirs.cut.load(Ordering::SeqCst) {
                    let _ = client.shutdown(Shutdown::Both);
                    continue;
                }
                let Ok(board) = TcpStream::connect(&upstream) else {
                    let _ = client.shutdown(Shutdown::Both);
                    continue;
                };
                let _ = (client.set_nodelay(true), board.set_nodelay(true));
                kept.lock().unwrap().extend([client.try_clone().unwrap(), board.try_clone().unwrap()]);
                let both = (client.try_clone().unwrap(), board.try_clone().unwrap());
                pipe(client, board, delay, None);
                pipe(both.1, both.0, delay, Some(Arc::clone(&theirs)));
            }
        });
        Self { port, faults, open }
    }

    /// Closes every connection and refuses new ones (a pulled cable).
    pub fn cut(&self) {
        self.faults.cut.store(true, Ordering::SeqCst);
        for stream in self.open.lock().unwrap().drain(..) {
            let _ = stream.shutdown(Shutdown::Both);
        }
    }

    /// Takes connections again (the cable back in).
    pub fn restore(&self) {
        self.faults.cut.store(false, Ordering::SeqCst);
    }

    /// The board's answers are swallowed from now on (`true`), or pass again.
    pub fn silence(&self, silent: bool) {
        self.faults.silent.store(silent, Ordering::SeqCst);
    }

    /// Bytes the board sent that were swallowed.
    pub fn swallowed(&self) -> u64 {
        self.faults.swallowed.load(Ordering::SeqCst)
    }
}

/// Copies `from` to `to`, each chunk held back `delay` from when it arrived
/// (order kept); with `faults`, the board's side: swallowed while silent.
fn pipe(mut from: TcpStream, mut to: TcpStream, delay: Duration, faults: Option<Arc<Faults>>) {
    let (chunks, delivered) = crossbeam_channel::unbounded::<(Instant, Vec<u8>)>();
    let closer = to.try_clone().unwrap();
    std::thread::spawn(move || {
        let mut buffer = vec![0; 16 * 1024];
        loop {
            let length = match from.read(&mut buffer) {
                Ok(0) | Err(_) => break,
                Ok(length) => length,
            };
            if let Some(faults) = &faults
                && faults.silent.load(Ordering::SeqCst)
            {
                faults.swallowed.fetch_add(length as u64, Ordering::SeqCst);
                continue;
            }
            if chunks.send((Instant::now() + delay, buffer[..length].to_vec())).is_err() {
                break;
            }
        }
        drop(chunks);
        let _ = from.shutdown(Shutdown::Both);
    });
    std::thread::spawn(move || {
        for (due, bytes) in delivered {
            // The link's own delay: the model of a slow bridge, not a wait for something.
            std::thread::sleep(due.saturating_duration_since(Instant::now()));
            if to.write_all(&bytes).is_err() {
                break;
            }
        }
        let _ = closer.shutdown(Shutdown::Both);
    });
}

/// A port that accepts connections, reads everything sent and never answers.
pub struct Silent {
    /// `tcp://127.0.0.1:PORT`.
    pub port: String,
    /// Bytes received so far.
    pub received: Arc<AtomicU64>,
}

impl Silent {
    /// Listening on 127.0.0.1.
    pub fn new() -> Self {
        let listener = TcpListener::bind("127.0.0.1:0").unwrap();
        let port = format!("tcp://{}", listener.local_addr().unwrap());
        let received = Arc::new(AtomicU64::new(0));
        let counted = Arc::clone(&received);
        std::thread::spawn(move || {
            for client in listener.incoming() {
                let Ok(mut client) = client else { continue };
                let counted = Arc::clone(&counted);
                std::thread::spawn(move || {
                    let mut buffer = [0; 4096];
                    while let Ok(length) = client.read(&mut buffer) {
                        if length == 0 {
                            break;
                        }
                        counted.fetch_add(length as u64, Ordering::SeqCst);
                    }
                });
            }
        });
        Self { port, received }
    }
}
