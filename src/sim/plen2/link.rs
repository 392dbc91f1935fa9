//! The line between a host and the emulated PLEN2, as real links behave: a
//! clean USB line, a Bluetooth LE serial bridge that delivers in bursts at its
//! connection events, a host whose writes leave late, a slow line. The
//! emulator times every byte by when this model delivers it (never by how
//! promptly its own thread runs), so in virtual time its verdict on lost
//! bytes is exact. Deterministic: the late link's holds come from a fixed seed.

use std::time::Duration;
use std::time::Instant;

pub use super::bridge::Bridge;
use super::bridge::Carried;

/// Bytes a USB full-speed packet carries: replies cross a clean line in these.
pub const USB_PACKET: usize = 64;
/// Host → robot bytes a Bluetooth LE bridge delivers per connection event:
/// four 20-byte writes (the default ATT payload).
pub const BLE_BYTES_PER_EVENT: usize = 4 * 20;
/// Robot → host bytes a Bluetooth LE bridge delivers per connection event:
/// six 244-byte notifications (a BLE 4.2 link with data length extension).
pub const BLE_REPLY_BYTES_PER_EVENT: usize = 6 * 244;

/// How the line behaves.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LinkKind {
    /// USB CDC at 2,000,000 baud: a byte every 5 µs to the robot, replies at
    /// full-speed USB (1 µs a byte) in 64-byte packets.
    Clean,
    /// A Bluetooth LE serial bridge: what the host writes waits for the next
    /// connection event, which carries at most 80 bytes to the robot (at the
    /// line rate from there); replies wait for an event too, which carries at
    /// most 1,464 bytes to the host at once — or, with `whole`, the bridge
    /// buffers a reply until the robot has printed it all and hands it over
    /// whole at the next event (replies that look clean, only late).
    Bursty {
        /// The connection interval (BLE: 7.5–30 ms).
        interval: Duration,
        /// Replies arrive whole at the event after the robot printed them.
        whole: bool,
    },
    /// Writes, both ways, leave late: every other write, at random, is held
    /// back a random time up to `max_hold` (uniform; FIFO: nothing overtakes a
    /// held write, so what follows arrives with it), as when the host's thread
    /// is descheduled or a loaded USB stack holds a transfer.
    Late {
        /// The longest hold.
        max_hold: Duration,
    },
    /// A Bluetooth LE bridge modelled apart from `Bursty`, with what its
    /// description leaves open chosen otherwise (phases, notifications, late writes).
    Bridge(Bridge),
    /// A slower line, both ways (10 bits a byte).
    Slow {
        /// Its rate.
        baud: u32,
    },
}

impl std::str::FromStr for LinkKind {
    type Err = String;

    /// `clean`, `bursty` (15 ms), `bursty=MS`, either with `,whole`, `late=MS`, `slow=BAUD`.
    fn from_str(text: &str) -> Result<Self, String> {
        if text.trim().starts_with("bridge=") {
            return text.parse().map(Self::Bridge);
        }
        let bad = || format!("{text:?} is not a link: use clean, bursty[=MS][,whole], late=MS or slow=BAUD");
        if let Some(bursty) = text.trim().strip_suffix(",whole") {
            return match bursty.parse::<Self>()? {
                Self::Bursty { interval, .. } => Ok(Self::Bursty { interval, whole: true }),
                _ => Err(format!("{text:?}: only a bursty link delivers replies whole")),
            };
        }
        let number = |value: &str| value.trim().parse::<f64>().ok().filter(|n| n.is_finite() && *n > 0.0);
        match text.trim().split_once('=') {
            None if text.trim() == "clean" => Ok(Self::Clean),
            None if text.trim() == "bursty" => Ok(Self::Bursty { interval: Duration::from_millis(15), whole: false }),
            Some(("bursty", ms)) => {
                let ms = number(ms)
                    .filter(|ms| (7.5..=30.0).contains(ms))
                    .ok_or_else(|| format!("{text:?}: a Bluetooth LE connection interval is 7.5 to 30 ms"))?;
                Ok(Self::Bursty { interval: Duration::from_secs_f64(ms / 1000.0), whole: false })
            }
            Some(("late", ms)) => {
                let ms = number(ms)
                    .filter(|ms| *ms <= 1000.0)
                    .ok_or_else(|| format!("{text:?}: writes are held back up to late=MS, 0 to 1000 ms"))?;
                Ok(Self::Late { max_hold: Duration::from_secs_f64(ms / 1000.0) })
            }
            Some(("slow", baud)) => {
                let baud = baud
                    .trim()
                    .parse::<u32>()
                    .ok()
                    .filter(|baud| (300..=4_000_000).contains(baud))
                    .ok_or_else(|| format!("{text:?}: a line rate is slow=BAUD, 300 to 4000000"))?;
                Ok(Self::Slow { baud })
            }
            _ => Err(bad()),
        }
    }
}

impl std::fmt::Display for LinkKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Clean => write!(f, "clean"),
            Self::Bursty { interval, whole } => {
                write!(f, "bursty={}{}", interval.as_secs_f64() * 1000.0, if *whole { ",whole" } else { "" })
            }
            Self::Late { max_hold } => write!(f, "late={}", max_hold.as_millis()),
            Self::Slow { baud } => write!(f, "slow={baud}"),
            Self::Bridge(bridge) => write!(f, "{bridge}"),
        }
    }
}

/// The line's state: where each direction's bytes are, and the next event.
#[derive(Debug)]
pub struct Link {
    kind: LinkKind,
    /// Clean line: a byte to the robot, a byte of a reply.
    line_byte: Duration,
    reply_byte: Duration,
    /// Connection events are counted from the first write.
    started: Option<Instant>,
    /// When the last byte towards the robot arrives / towards the host.
    to_robot_free: Option<Instant>,
    to_host_free: Option<Instant>,
    /// Bursty: the event the next byte to the robot can ride, and how full it is.
    robot_event: (u64, usize),
    host_event: (u64, usize),
    /// A modelled bridge's two directions.
    carried: Carried,
    seed: u32,
}

impl Link {
    /// A line of `kind`; a clean line carries a byte to the robot in
    /// `line_byte` and a reply byte in `reply_byte`.
    pub fn new(kind: LinkKind, line_byte: Duration, reply_byte: Duration) -> Self {
        Self {
            kind,
            line_byte,
            reply_byte,
            started: None,
            to_robot_free: None,
            to_host_free: None,
            robot_event: (0, 0),
            host_event: (0, 0),
            carried: Carried::default(),
            seed: 0x9e37_79b9,
        }
    }

    /// The next pseudo-random number (xorshift; deterministic from the seed).
    fn random(&mut self) -> u32 {
        self.seed ^= self.seed << 13;
        self.seed ^= self.seed >> 17;
        self.seed ^= self.seed << 5;
        self.seed
    }

    /// Half the writes are held, each for a time in `0..=max`.
    fn hold(&mut self, max: Duration) -> Duration {
        if self.random() & 1 == 0 {
            return Duration::ZERO;
        }
        max.mul_f64(f64::from(self.random()) / f64::from(u32::MAX))
    }

    fn byte_time(&self, baud: u32) -> Duration {
        Duration::from_secs_f64(10.0 / f64::from(baud.max(1)))
    }

    /// The time of connection event `index`.
    fn event(&self, start: Instant, interval: Duration, index: u64) -> Instant {
        start + interval.mul_f64(index as f64)
    }

    /// The first event at or after `at`.
    fn event_at_or_after(start: Instant, interval: Duration, at: Instant) -> u64 {
        let since = at.saturating_duration_since(start).as_secs_f64();
        // Events are a few per second, for hours at most: well inside u64.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let index = (since / interval.as_secs_f64()).ceil() as u64;
        index
    }

    /// When each byte of a write the host made at `now` reaches the robot's ring.
    pub fn carry_to_robot(&mut self, now: Instant, bytes: usize) -> Vec<Instant> {
        let start = *self.started.get_or_insert(now);
        let mut arrivals = Vec::with_capacity(bytes);
        match self.kind {
            LinkKind::Clean | LinkKind::Slow { .. } | LinkKind::Late { .. } => {
                let byte = match self.kind {
                    LinkKind::Slow { baud } => self.byte_time(baud),
                    _ => self.line_byte,
                };
                let held = match self.kind {
                    LinkKind::Late { max_hold } => self.hold(max_hold),
                    _ => Duration::ZERO,
                };
                let mut at = self.to_robot_free.map_or(now + held, |free| free.max(now + held));
                for _ in 0..bytes {
                    at += byte;
                    arrivals.push(at);
                }
                self.to_robot_free = Some(at);
            }
            LinkKind::Bursty { interval, .. } => {
                let (mut index, mut used) = self.robot_event;
                // The next event: one under way at this very instant has its packets already.
                let first = Self::event_at_or_after(start, interval, now + Duration::from_nanos(1));
                if first > index {
                    (index, used) = (first, 0);
                }
                for _ in 0..bytes {
                    if used == BLE_BYTES_PER_EVENT {
                        (index, used) = (index + 1, 0);
                    }
                    // From the module to the robot at the USB line's rate.
                    used += 1;
                    arrivals
                        .push(self.event(start, interval, index) + self.line_byte * u32::try_from(used).unwrap_or(0));
                }
                self.robot_event = (index, used);
            }
            LinkKind::Bridge(bridge) => {
                let held = self.hold(bridge.hold);
                return bridge.carry_to_robot(&mut self.carried, start, now, held, self.line_byte, bytes);
            }
        }
        arrivals
    }

    /// When the pieces of a reply the robot begins to print at `at` reach
    /// the host, and when the robot has printed it all (it prints as fast as
    /// the line takes it).
    pub fn carry_to_host(&mut self, at: Instant, bytes: &[u8]) -> (Vec<(Instant, Vec<u8>)>, Instant) {
        let start = *self.started.get_or_insert(at);
        let mut pieces = Vec::new();
        let mut printed = at;
        match self.kind {
            LinkKind::Clean | LinkKind::Late { .. } | LinkKind::Slow { .. } => {
                let byte = match self.kind {
                    LinkKind::Slow { baud } => self.byte_time(baud),
                    _ => self.reply_byte,
                };
                for piece in bytes.chunks(USB_PACKET) {
                    let held = match self.kind {
                        LinkKind::Late { max_hold } => self.hold(max_hold),
                        _ => Duration::ZERO,
                    };
                    let began = self.to_host_free.map_or(printed, |free| free.max(printed));
                    let on_line = began + byte * u32::try_from(piece.len()).unwrap_or(u32::MAX);
                    printed = on_line;
                    let arrives = on_line + held;
                    // Nothing overtakes a held piece.
                    let arrives = pieces.last().map_or(arrives, |(last, _): &(Instant, Vec<u8>)| arrives.max(*last));
                    self.to_host_free = Some(on_line);
                    pieces.push((arrives, piece.to_vec()));
                }
            }
            LinkKind::Bursty { interval, whole: true } => {
                // Buffered until printed, then handed over whole at the next event.
                printed += self.reply_byte * u32::try_from(bytes.len()).unwrap_or(u32::MAX);
                let index = Self::event_at_or_after(start, interval, printed).max(self.host_event.0 + 1);
                self.host_event = (index, bytes.len());
                pieces.push((self.event(start, interval, index), bytes.to_vec()));
            }
            LinkKind::Bursty { interval, whole: false } => {
                let (mut index, mut used) = self.host_event;
                for &value in bytes {
                    printed += self.reply_byte;
                    let first = Self::event_at_or_after(start, interval, printed);
                    if first > index {
                        (index, used) = (first, 0);
                    }
                    if used == BLE_REPLY_BYTES_PER_EVENT {
                        (index, used) = (index + 1, 0);
                    }
                    used += 1;
                    let event = self.event(start, interval, index);
                    match pieces.last_mut() {
                        Some((when, piece)) if *when == event => piece.push(value),
                        _ => pieces.push((event, vec![value])),
                    }
                }
                self.host_event = (index, used);
            }
            LinkKind::Bridge(bridge) => {
                return bridge.carry_to_host(&mut self.carried, start, at, self.reply_byte, bytes);
            }
        }
        (pieces, printed)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn link(kind: LinkKind) -> Link {
        Link::new(kind, Duration::from_micros(5), Duration::from_micros(1))
    }

    #[test]
    fn links_parse_as_the_command_line_writes_them() {
        assert_eq!("clean".parse(), Ok(LinkKind::Clean));
        assert_eq!("bursty".parse(), Ok(LinkKind::Bursty { interval: Duration::from_millis(15), whole: false }));
        assert_eq!("bursty=7.5".parse(), Ok(LinkKind::Bursty { interval: Duration::from_micros(7_500), whole: false }));
        let whole = LinkKind::Bursty { interval: Duration::from_millis(30), whole: true };
        assert_eq!("bursty=30,whole".parse(), Ok(whole));
        assert_eq!(whole.to_string().parse(), Ok(whole), "{whole}");
        assert_eq!("bursty,whole".parse::<LinkKind>().map(|link| link.to_string()), Ok("bursty=15,whole".into()));
        assert!("slow=9600,whole".parse::<LinkKind>().unwrap_err().contains("only a bursty link"));
        assert_eq!("late=20".parse(), Ok(LinkKind::Late { max_hold: Duration::from_millis(20) }));
        assert_eq!("slow=115200".parse(), Ok(LinkKind::Slow { baud: 115_200 }));
        assert!("bursty=40".parse::<LinkKind>().unwrap_err().contains("7.5 to 30 ms"));
        assert!("fast".parse::<LinkKind>().is_err());
    }

    #[test]
    fn a_bluetooth_bridge_delivers_80_bytes_per_connection_event() {
        let t0 = Instant::now();
        let mut bursty = link(LinkKind::Bursty { interval: Duration::from_millis(15), whole: false });
        // 100 bytes written at once, as the link starts (an event): they wait
        // for the next one, which takes 80; the next one after, 20.
        let arrivals = bursty.carry_to_robot(t0, 100);
        assert_eq!(arrivals[0], t0 + Duration::from_millis(15) + Duration::from_micros(5));
        assert_eq!(arrivals[79], t0 + Duration::from_millis(15) + Duration::from_micros(400));
        assert_eq!(arrivals[80], t0 + Duration::from_millis(30) + Duration::from_micros(5));
        // A write 1 ms later waits for the event after the one already full.
        let later = bursty.carry_to_robot(t0 + Duration::from_millis(1), 1);
        assert_eq!(later[0], t0 + Duration::from_millis(30) + Duration::from_micros(105));
        // Replies come at events too, 1,464 bytes at most each.
        let (pieces, _) = bursty.carry_to_host(t0 + Duration::from_millis(16), &[b'x'; 2000]);
        let sizes: Vec<usize> = pieces.iter().map(|(_, piece)| piece.len()).collect();
        assert_eq!(sizes, [1464, 536]);
        assert_eq!(pieces[0].0, t0 + Duration::from_millis(30));
        assert_eq!(pieces[1].0, t0 + Duration::from_millis(45));
    }

    /// A bridge that buffers replies hands each one over whole, at the first
    /// connection event after the robot printed its last byte (and never two
    /// replies at one event).
    #[test]
    fn a_whole_reply_bridge_delivers_each_reply_in_one_piece_at_the_next_event() {
        let t0 = Instant::now();
        let mut bridge = link(LinkKind::Bursty { interval: Duration::from_millis(15), whole: true });
        let _ = bridge.carry_to_robot(t0, 3);
        let (pieces, printed) = bridge.carry_to_host(t0 + Duration::from_millis(16), &[b'x'; 2000]);
        assert_eq!(printed, t0 + Duration::from_millis(16) + Duration::from_micros(2000));
        assert_eq!(pieces.len(), 1);
        assert_eq!((pieces[0].0, pieces[0].1.len()), (t0 + Duration::from_millis(30), 2000));
        // The next reply, printed within the same interval, waits for the event after.
        let (next, _) = bridge.carry_to_host(t0 + Duration::from_millis(20), b"{}");
        assert_eq!(next[0].0, t0 + Duration::from_millis(45));
    }

    #[test]
    fn a_late_link_holds_writes_up_to_its_limit_and_nothing_overtakes() {
        let t0 = Instant::now();
        let mut late = link(LinkKind::Late { max_hold: Duration::from_millis(20) });
        let mut last = t0;
        let mut longest = Duration::ZERO;
        for step in 0..200u32 {
            let now = t0 + Duration::from_millis(2) * step;
            let arrivals = late.carry_to_robot(now, 8);
            assert!(arrivals[0] >= last, "in order");
            longest = longest.max(arrivals[0].saturating_duration_since(now));
            assert!(arrivals[0] <= now + Duration::from_millis(20) + Duration::from_micros(45), "{step}");
            last = arrivals[7];
        }
        assert!(longest > Duration::from_millis(15), "holds reach towards the limit: {longest:?}");
    }

    #[test]
    fn a_slow_line_carries_ten_bits_a_byte_both_ways() {
        let t0 = Instant::now();
        let mut slow = link(LinkKind::Slow { baud: 115_200 });
        let arrivals = slow.carry_to_robot(t0, 2);
        let byte = Duration::from_secs_f64(10.0 / 115_200.0);
        assert_eq!(arrivals[1] - t0, byte * 2);
        let (pieces, printed) = slow.carry_to_host(t0, &[b'x'; 128]);
        assert_eq!(pieces.len(), 2);
        assert_eq!(printed - t0, byte * 128);
    }
}
