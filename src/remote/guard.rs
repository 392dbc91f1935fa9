//! Who may drive the robot, and how much: a remote listens on the loopback
//! address unless told otherwise, and then only with a token (a bearer
//! token, compared in constant time); a browser page of another site is
//! turned away by its `Origin`; requests beyond a steady rate are refused
//! (429), STOP never: each client (an HTTP connection, an OSC sender) has a
//! [`Rate`] of its own, so a flood slows only its sender, and every client
//! together shares a larger one.

use std::net::SocketAddr;
use std::path::Path;
use std::sync::Mutex;
use std::time::Instant;

use subtle::ConstantTimeEq;

/// Requests a second one client may send, on average.
pub const RATE_PER_S: f64 = 100.0;
/// How many it may send at once above that.
pub const BURST: f64 = 50.0;
/// Requests a second every client together may send, on average.
pub const ALL_RATE_PER_S: f64 = 500.0;
/// How many they may send at once above that.
pub const ALL_BURST: f64 = 250.0;

/// A token bucket: requests let through at a steady rate, with bursts.
#[derive(Clone, Copy, Debug)]
pub struct Rate {
    per_s: f64,
    burst: f64,
    /// Tokens left, and when they were counted.
    left: f64,
    counted: Instant,
}

impl Rate {
    /// One client's: [`RATE_PER_S`], bursts of [`BURST`].
    pub fn client() -> Self {
        Self::new(RATE_PER_S, BURST)
    }

    fn new(per_s: f64, burst: f64) -> Self {
        Self { per_s, burst, left: burst, counted: Instant::now() }
    }

    /// Whether one more is let through at `now` (taking its token).
    pub fn take(&mut self, now: Instant) -> bool {
        self.left =
            (self.left + now.saturating_duration_since(self.counted).as_secs_f64() * self.per_s).min(self.burst);
        self.counted = now;
        if self.left >= 1.0 {
            self.left -= 1.0;
            true
        } else {
            false
        }
    }
}
/// The shortest token a file may hold.
pub const SHORTEST_TOKEN: usize = 16;

/// The rules a server applies to every request.
#[derive(Debug)]
pub struct Guard {
    token: Option<Vec<u8>>,
    /// The origins of the server's own pages (`http://127.0.0.1:8765`, …).
    own_origins: Vec<String>,
    /// Every client's requests together.
    all: Mutex<Rate>,
}

impl Guard {
    /// The rules for a server on `listen` with `token` (from `--token-file`):
    /// an address other than loopback needs a token.
    pub fn new(listen: SocketAddr, token: Option<String>) -> Result<Self, ServeError> {
        if !listen.ip().is_loopback() && token.is_none() {
            return Err(ServeError::NoToken { listen });
        }
        let port = listen.port();
        let own_origins =
            ["127.0.0.1", "localhost", "[::1]"].iter().map(|host| format!("http://{host}:{port}")).collect();
        Ok(Self {
            token: token.map(String::into_bytes),
            own_origins,
            all: Mutex::new(Rate::new(ALL_RATE_PER_S, ALL_BURST)),
        })
    }

    /// The rules for a server on `listen`, its token read from `token_file` (see [`read_token`]).
    pub fn from_file(listen: SocketAddr, token_file: Option<&Path>) -> Result<Self, ServeError> {
        let token = token_file.map(read_token).transpose()?;
        Self::new(listen, token)
    }

    /// Whether a token is needed.
    pub fn needs_token(&self) -> bool {
        self.token.is_some()
    }

    /// Whether `given` is the token (anything, when none is needed); compared in constant time.
    pub fn token_ok(&self, given: Option<&str>) -> bool {
        let Some(token) = &self.token else { return true };
        let given = given.unwrap_or_default().as_bytes();
        // The length is no secret; the bytes are compared without an early end.
        given.len() == token.len() && bool::from(given.ct_eq(token))
    }

    /// Whether a request with this `Origin` header may act: none (not a
    /// browser), or the server's own page; another site's page may not.
    pub fn origin_ok(&self, origin: Option<&str>) -> bool {
        origin.is_none_or(|origin| self.own_origins.iter().any(|own| own == origin))
    }

    /// Whether a request from the client whose rate is `client` is let
    /// through now: STOP always; others while the client's rate allows
    /// ([`RATE_PER_S`], bursts of [`BURST`]), and those that reach the
    /// boards (`to_boards`) while every client's together does too
    /// ([`ALL_RATE_PER_S`], bursts of [`ALL_BURST`]): a flood of status
    /// questions takes nothing from a show controller's plays and drives.
    pub fn admit(&self, client: &mut Rate, stops: bool, to_boards: bool) -> bool {
        if stops {
            return true;
        }
        let now = Instant::now();
        client.take(now) && (!to_boards || self.all.lock().is_ok_and(|mut all| all.take(now)))
    }
}

/// The largest token file read, bytes (a token is a line of a few dozen characters).
pub const MOST_TOKEN_FILE: u64 = 4096;

/// The token in `path`: its first line, trimmed. Only a regular file of at
/// most [`MOST_TOKEN_FILE`] bytes is read (a named pipe or a device is
/// refused without waiting on it); one too short, too large, not text or
/// unreadable is an error.
pub fn read_token(path: &Path) -> Result<String, ServeError> {
    let unreadable = |why: String| ServeError::TokenUnreadable { path: path.to_path_buf(), why };
    let bytes =
        crate::project::input::read_bytes(path, MOST_TOKEN_FILE).map_err(|error| unreadable(error.to_string()))?;
    let text = String::from_utf8(bytes).map_err(|_| unreadable("it is not text".into()))?;
    let token = text.lines().next().unwrap_or_default().trim().to_string();
    if token.chars().count() < SHORTEST_TOKEN {
        return Err(ServeError::TokenTooShort { path: path.to_path_buf() });
    }
    Ok(token)
}

/// Why remote control could not start.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ServeError {
    /// An address other than loopback, and no token.
    #[error(
        "listening on {listen} lets other machines in: give --token-file FILE (a secret of at least {SHORTEST_TOKEN} characters), or listen on 127.0.0.1"
    )]
    NoToken {
        /// Where it was to listen.
        listen: SocketAddr,
    },
    /// The token file cannot be read.
    #[error("cannot read the token {}: {why}", .path.display())]
    TokenUnreadable {
        /// The file.
        path: std::path::PathBuf,
        /// What the system said.
        why: String,
    },
    /// The token is too short to be a secret.
    #[error("the token in {} is shorter than {SHORTEST_TOKEN} characters: make a longer secret", .path.display())]
    TokenTooShort {
        /// The file.
        path: std::path::PathBuf,
    },
    /// The HTTP port is taken.
    #[error("cannot listen on {at} ({why}): another program may be listening there: pick another port")]
    HttpTaken {
        /// The address.
        at: SocketAddr,
        /// What the system said.
        why: String,
    },
    /// The OSC port is taken.
    #[error("cannot take OSC on udp {at} ({why}): another program may be listening there: pick another port")]
    OscTaken {
        /// The address.
        at: SocketAddr,
        /// What the system said.
        why: String,
    },
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn another_machine_needs_a_token_and_only_the_right_one_gets_in() {
        let anywhere: SocketAddr = "0.0.0.0:8765".parse().unwrap();
        assert!(Guard::new(anywhere, None).unwrap_err().to_string().contains("--token-file"));
        let guard = Guard::new(anywhere, Some("a-secret-of-24-letters!!".into())).unwrap();
        assert!(guard.token_ok(Some("a-secret-of-24-letters!!")));
        assert!(!guard.token_ok(Some("a-secret-of-24-letters!?")));
        assert!(!guard.token_ok(Some("a-secret")) && !guard.token_ok(None));
        let local = Guard::new("127.0.0.1:8765".parse().unwrap(), None).unwrap();
        assert!(local.token_ok(None) && !local.needs_token());
    }

    #[test]
    fn only_the_servers_own_page_or_no_browser_may_act() {
        let guard = Guard::new("127.0.0.1:8765".parse().unwrap(), None).unwrap();
        assert!(guard.origin_ok(None));
        assert!(guard.origin_ok(Some("http://localhost:8765")));
        assert!(!guard.origin_ok(Some("https://evil.example")));
        assert!(!guard.origin_ok(Some("http://127.0.0.1:9999")));
    }

    #[test]
    fn a_flood_is_refused_beyond_its_clients_burst_and_stop_never_is() {
        let guard = Guard::new("127.0.0.1:8765".parse().unwrap(), None).unwrap();
        let (mut flooder, mut other) = (Rate::client(), Rate::client());
        // Counted at once: a burst's worth, then a few more as the clock moves on.
        let admitted = (0..1000).filter(|_| guard.admit(&mut flooder, false, true)).count();
        assert!((50..1000).contains(&admitted), "{admitted}");
        assert!((0..100).all(|_| guard.admit(&mut flooder, true, true)), "STOP is always let through");
        assert!(guard.admit(&mut other, false, true), "the flood slowed only its sender");
    }

    #[test]
    fn many_clients_together_are_held_to_the_shared_rate() {
        let guard = Guard::new("127.0.0.1:8765".parse().unwrap(), None).unwrap();
        let mut clients = vec![Rate::client(); 20];
        let admitted: usize =
            clients.iter_mut().map(|client| (0..50).filter(|_| guard.admit(client, false, true)).count()).sum();
        assert!((250..1000).contains(&admitted), "{admitted} of 1000 at once");
    }

    #[test]
    fn a_rate_refills_at_its_pace() {
        let t0 = Instant::now();
        let mut rate = Rate::new(100.0, 2.0);
        rate.counted = t0;
        assert!(rate.take(t0) && rate.take(t0) && !rate.take(t0));
        assert!(!rate.take(t0 + std::time::Duration::from_millis(5)), "half a token");
        assert!(rate.take(t0 + std::time::Duration::from_millis(10)), "a whole one");
    }
}
