//! Bluetooth LE serial bridges modelled from their description alone — bytes
//! wait for the next connection event; at most 80 bytes reach the robot per
//! event; replies leave in bursts — with what a description leaves open
//! varied: where in the event each direction's bytes come out (the phases),
//! how replies are cut into notifications and spaced, and a host whose writes
//! leave late. The pacing must hold on every one of them, not on one reading
//! ([`super::link::LinkKind::Bursty`] is the first, kept as it was).

use std::time::{Duration, Instant};

/// One bridge: its connection events and how it fills them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Bridge {
    /// The connection interval (BLE: 7.5–30 ms).
    pub interval: Duration,
    /// Host → robot bytes per event.
    pub to_robot: usize,
    /// After its event, when the module begins passing bytes to the robot.
    pub robot_phase: Duration,
    /// After its event, when a notification reaches the host's port (a
    /// dongle's and its driver's latency).
    pub host_phase: Duration,
    /// Bytes a notification carries.
    pub notification: usize,
    /// Notifications an event carries.
    pub per_event: usize,
    /// How far apart the notifications of one event reach the host.
    pub spacing: Duration,
    /// Half the host's writes leave late, by up to this (uniform; in order).
    pub hold: Duration,
    /// Replies buffered until the robot printed them whole, then sent.
    pub whole: bool,
}

impl Bridge {
    /// The description's own bridge at `interval`: each direction at the
    /// event, six 244-byte notifications at once.
    pub fn plain(interval: Duration) -> Self {
        Self {
            interval,
            to_robot: 80,
            robot_phase: Duration::ZERO,
            host_phase: Duration::ZERO,
            notification: 244,
            per_event: 6,
            spacing: Duration::ZERO,
            hold: Duration::ZERO,
            whole: false,
        }
    }

    /// The models every pacing test and the benchmark run, at `interval`: the
    /// plain one; one whose directions come out at other phases of the event
    /// (the robot's 40 % in, the host's 70 %) and whose notifications reach the
    /// host 1.25 ms apart; one of 20-byte notifications, 64 an event, 0.1 ms
    /// apart; one that buffers whole replies, a third of an event late; and
    /// the plain one behind a host whose writes leave up to 6 ms late.
    pub fn models(interval: Duration) -> [(&'static str, Self); 5] {
        let plain = Self::plain(interval);
        [
            ("plain", plain),
            (
                "phased",
                Self {
                    robot_phase: interval.mul_f64(0.4),
                    host_phase: interval.mul_f64(0.7),
                    spacing: Duration::from_micros(1250),
                    ..plain
                },
            ),
            (
                "small notifications",
                Self { notification: 20, per_event: 64, spacing: Duration::from_micros(100), ..plain },
            ),
            ("whole replies", Self { whole: true, host_phase: interval / 3, ..plain }),
            ("late writes", Self { hold: Duration::from_millis(6), ..plain }),
        ]
    }
}

impl std::fmt::Display for Bridge {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let ms = |d: Duration| d.as_secs_f64() * 1000.0;
        write!(f, "bridge={}", ms(self.interval))?;
        if !self.robot_phase.is_zero() || !self.host_phase.is_zero() {
            write!(f, ",phase={}/{}", ms(self.robot_phase), ms(self.host_phase))?;
        }
        if (self.notification, self.per_event) != (244, 6) || !self.spacing.is_zero() {
            write!(f, ",notify={}x{}/{}", self.notification, self.per_event, ms(self.spacing))?;
        }
        if !self.hold.is_zero() {
            write!(f, ",hold={}", ms(self.hold))?;
        }
        if self.whole {
            write!(f, ",whole")?;
        }
        Ok(())
    }
}

impl std::str::FromStr for Bridge {
    type Err = String;

    /// `bridge=MS` then any of `,phase=ROBOT/HOST`, `,notify=BYTESxCOUNT/SPACING`, `,hold=MS`, `,whole` (times in ms).
    fn from_str(text: &str) -> Result<Self, String> {
        let bad =
            |why: &str| format!("{text:?}: {why} (bridge=MS[,phase=MS/MS][,notify=BYTESxN/MS][,hold=MS][,whole])");
        let ms = |value: &str| {
            value
                .trim()
                .parse::<f64>()
                .ok()
                .filter(|ms| ms.is_finite() && (0.0..=1000.0).contains(ms))
                .map(|ms| Duration::from_secs_f64(ms / 1000.0))
        };
        let mut parts = text.trim().split(',');
        let interval = parts
            .next()
            .and_then(|first| first.strip_prefix("bridge="))
            .and_then(ms)
            .filter(|interval| (Duration::from_micros(7500)..=Duration::from_millis(30)).contains(interval))
            .ok_or_else(|| bad("a connection interval of 7.5 to 30 ms first"))?;
        let mut bridge = Self::plain(interval);
        for part in parts {
            let (key, value) = part.split_once('=').unwrap_or((part, ""));
            match key.trim() {
                "whole" => bridge.whole = true,
                "hold" => bridge.hold = ms(value).ok_or_else(|| bad("hold=MS"))?,
                "phase" => {
                    let (robot, host) = value.split_once('/').ok_or_else(|| bad("phase=ROBOT/HOST"))?;
                    bridge.robot_phase = ms(robot).ok_or_else(|| bad("phase=ROBOT/HOST"))?;
                    bridge.host_phase = ms(host).ok_or_else(|| bad("phase=ROBOT/HOST"))?;
                }
                "notify" => {
                    let (size, spacing) = value.split_once('/').ok_or_else(|| bad("notify=BYTESxN/MS"))?;
                    let (bytes, per_event) = size.split_once('x').ok_or_else(|| bad("notify=BYTESxN/MS"))?;
                    let number = |text: &str| text.trim().parse::<usize>().ok().filter(|n| (1..=4096).contains(n));
                    bridge.notification = number(bytes).ok_or_else(|| bad("notify=BYTESxN/MS"))?;
                    bridge.per_event = number(per_event).ok_or_else(|| bad("notify=BYTESxN/MS"))?;
                    bridge.spacing = ms(spacing).ok_or_else(|| bad("notify=BYTESxN/MS"))?;
                }
                _ => return Err(bad("unknown option")),
            }
        }
        Ok(bridge)
    }
}

/// Where a bridge's two directions stand.
#[derive(Debug, Default)]
pub(super) struct Carried {
    /// When the host's last write reached the bridge (nothing overtakes it).
    reached: Option<Instant>,
    /// The event the next byte to the robot can ride, and how full it is.
    robot_event: (u64, usize),
    /// The event the next notification can ride, and how many it carries.
    host_event: (u64, usize),
    /// When the last notification reached the host.
    last_arrival: Option<Instant>,
}

impl Bridge {
    fn event(&self, start: Instant, index: u64) -> Instant {
        start + self.interval.mul_f64(index as f64)
    }

    /// The first event after `at`: what reaches the bridge while an event is
    /// under way waits for the next (its packets are scheduled at its start).
    fn event_after(&self, start: Instant, at: Instant) -> u64 {
        let since = at.saturating_duration_since(start).as_secs_f64();
        // As below.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let index = (since / self.interval.as_secs_f64()).floor() as u64 + 1;
        index
    }

    /// The first event at or after `at`.
    fn first_event(&self, start: Instant, at: Instant) -> u64 {
        let since = at.saturating_duration_since(start).as_secs_f64();
        // Events are a few hundred a second, for hours at most: well inside u64.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let index = (since / self.interval.as_secs_f64()).ceil() as u64;
        index
    }

    /// When each byte of a write the host made at `now` (held back `held`)
    /// reaches the robot, which the module feeds a byte every `line_byte`.
    pub(super) fn carry_to_robot(
        &self,
        carried: &mut Carried,
        start: Instant,
        now: Instant,
        held: Duration,
        line_byte: Duration,
        bytes: usize,
    ) -> Vec<Instant> {
        let reached = carried.reached.map_or(now + held, |last| last.max(now + held));
        carried.reached = Some(reached);
        let (mut index, mut used) = carried.robot_event;
        let first = self.event_after(start, reached);
        if first > index {
            (index, used) = (first, 0);
        }
        let mut arrivals = Vec::with_capacity(bytes);
        for _ in 0..bytes {
            if used == self.to_robot {
                (index, used) = (index + 1, 0);
            }
            used += 1;
            let fed = line_byte * u32::try_from(used).unwrap_or(u32::MAX);
            arrivals.push(self.event(start, index) + self.robot_phase + fed);
        }
        carried.robot_event = (index, used);
        arrivals
    }

    /// When the pieces of a reply the robot begins to print at `at` (a byte
    /// every `reply_byte`) reach the host, and when the robot has printed it all.
    pub(super) fn carry_to_host(
        &self,
        carried: &mut Carried,
        start: Instant,
        at: Instant,
        reply_byte: Duration,
        bytes: &[u8],
    ) -> (Vec<(Instant, Vec<u8>)>, Instant) {
        let printed = at + reply_byte * u32::try_from(bytes.len()).unwrap_or(u32::MAX);
        if self.whole {
            let index = self.first_event(start, printed).max(carried.host_event.0 + 1);
            carried.host_event = (index, self.per_event);
            let arrives = self.event(start, index) + self.host_phase;
            let arrives = carried.last_arrival.map_or(arrives, |last| arrives.max(last));
            carried.last_arrival = Some(arrives);
            return (vec![(arrives, bytes.to_vec())], printed);
        }
        let mut pieces = Vec::new();
        let mut on_module = at;
        let (mut index, mut sent) = carried.host_event;
        for piece in bytes.chunks(self.notification) {
            on_module += reply_byte * u32::try_from(piece.len()).unwrap_or(u32::MAX);
            let first = self.first_event(start, on_module);
            if first > index {
                (index, sent) = (first, 0);
            }
            if sent == self.per_event {
                (index, sent) = (index + 1, 0);
            }
            let spaced = self.spacing * u32::try_from(sent).unwrap_or(u32::MAX);
            sent += 1;
            let arrives = self.event(start, index) + self.host_phase + spaced;
            let arrives = carried.last_arrival.map_or(arrives, |last| arrives.max(last));
            carried.last_arrival = Some(arrives);
            pieces.push((arrives, piece.to_vec()));
        }
        carried.host_event = (index, sent);
        (pieces, printed)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const LINE: Duration = Duration::from_micros(5);
    const PRINT: Duration = Duration::from_micros(1);

    #[test]
    fn bridges_parse_as_they_print() {
        for (name, bridge) in Bridge::models(Duration::from_millis(15)) {
            assert_eq!(bridge.to_string().parse(), Ok(bridge), "{name}: {bridge}");
        }
        assert!("bridge=40".parse::<Bridge>().unwrap_err().contains("7.5 to 30 ms"));
        assert!("bridge=15,fast".parse::<Bridge>().unwrap_err().contains("unknown option"));
    }

    /// Each direction comes out at its own phase of the event; the robot gets
    /// 80 bytes an event, the host its notifications spaced as they come.
    #[test]
    fn a_phased_bridge_delivers_each_direction_at_its_phase() {
        let interval = Duration::from_millis(15);
        let [_, (_, phased), ..] = Bridge::models(interval);
        let (t0, mut carried) = (Instant::now(), Carried::default());
        let arrivals =
            phased.carry_to_robot(&mut carried, t0, t0 + Duration::from_millis(1), Duration::ZERO, LINE, 100);
        assert_eq!(arrivals[0], t0 + interval + Duration::from_millis(6) + LINE);
        assert_eq!(arrivals[80], t0 + interval * 2 + Duration::from_millis(6) + LINE);
        let (pieces, printed) =
            phased.carry_to_host(&mut carried, t0, t0 + Duration::from_millis(17), PRINT, &[b'x'; 2000]);
        assert_eq!(printed, t0 + Duration::from_millis(19));
        let times: Vec<Duration> = pieces.iter().map(|(at, _)| *at - t0).collect();
        let event =
            |index: u32, nth: u32| interval * index + Duration::from_micros(10_500) + Duration::from_micros(1250) * nth;
        // Six notifications ride the event at 30 ms, the rest (two) the next.
        let expected: Vec<Duration> = (0..6).map(|nth| event(2, nth)).chain((0..3).map(|nth| event(3, nth))).collect();
        assert_eq!(times, expected);
    }

    #[test]
    fn a_held_write_takes_what_follows_with_it() {
        let bridge = Bridge { hold: Duration::from_millis(6), ..Bridge::plain(Duration::from_millis(15)) };
        let (t0, mut carried) = (Instant::now(), Carried::default());
        let held =
            bridge.carry_to_robot(&mut carried, t0, t0 + Duration::from_millis(13), Duration::from_millis(5), LINE, 1);
        let next = bridge.carry_to_robot(&mut carried, t0, t0 + Duration::from_millis(14), Duration::ZERO, LINE, 1);
        // Both reach the bridge at 18 ms: the event at 30 ms carries them.
        assert_eq!(
            (held[0], next[0]),
            (t0 + Duration::from_millis(30) + LINE, t0 + Duration::from_millis(30) + LINE * 2)
        );
    }
}
