//! What the replies showed of a PLEN2's link — the connection doctor's
//! figures, measured as the adaptive pacing measures it (`super::pacer`).

use std::time::Duration;

/// A gap inside a reply longer than this, before a clump, shows a link that
/// holds bytes back (a clean USB line carries a reply in 64-byte packets well
/// under a millisecond apart; a thread's hiccup seldom lasts this long).
pub const CLUMP_GAP: Duration = Duration::from_millis(5);

/// What the replies so far showed of the link (the connection doctor's
/// figures; the adaptive pacing acts on the same measurements).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LinkReport {
    /// Replies measured.
    pub replies: u32,
    /// The shortest delay from when the robot began printing a reply to its
    /// first byte's arrival (what every reply costs on this link).
    pub latency: Option<Duration>,
    /// The longest such delay beyond the time the first bytes need: how late
    /// the link may hold bytes back (a bridge's connection events).
    pub late: Duration,
    /// The longest gap before a clump inside a reply (zero: none).
    pub clump_gap: Duration,
    /// A long reply arrived in one piece (a bridge that hands replies over whole).
    pub whole: bool,
    /// The delivery rate a reply of at least a kilobyte arrived at, bytes a second.
    pub bytes_per_s: Option<u32>,
}

impl std::fmt::Display for LinkReport {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let ms = |d: Duration| d.as_secs_f64() * 1000.0;
        let Some(latency) = self.latency else { return write!(f, "not measured") };
        write!(f, "first byte after {:.1} ms", ms(latency))?;
        if self.late > CLUMP_GAP {
            write!(f, ", up to {:.1} ms late", ms(self.late))?;
        }
        if !self.clump_gap.is_zero() {
            write!(f, ", in clumps up to {:.1} ms apart", ms(self.clump_gap))?;
        } else if self.whole {
            write!(f, ", replies whole")?;
        } else {
            write!(f, ", smooth")?;
        }
        if let Some(rate) = self.bytes_per_s {
            write!(f, ", {rate} bytes/s")?;
        }
        Ok(())
    }
}
