//! The devices a show plays on, connected: a servo board, a PLEN2 or an
//! rFLEX base behind its port, each a [`Stage`] the player starts and stops.
//! At connect each family's link delay is measured from several real round
//! trips ([`LinkDelay`]); while held, each is asked whether it is still there
//! (`alive`) and called lost once it stops answering, link open or not.

mod dynamixel;
mod plen2;
mod rflex;
mod servo;

use std::time::{Duration, Instant};

use super::play::Stage;

/// How many round trips a link's delay is measured from at connect.
pub const ROUND_TRIPS: usize = 5;

/// A link's delay, as well as it can be known from round trips: half the
/// shortest (one way), and half their spread (how far a start may be off).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LinkDelay {
    /// Half the shortest round trip.
    pub one_way: Duration,
    /// Half the difference between the longest and the shortest.
    pub spread: Duration,
}

impl LinkDelay {
    /// From round trips; zero when there are none.
    pub fn from_round_trips(round_trips: &[Duration]) -> Self {
        let (Some(shortest), Some(longest)) = (round_trips.iter().min(), round_trips.iter().max()) else {
            return Self::default();
        };
        Self { one_way: *shortest / 2, spread: (*longest - *shortest) / 2 }
    }

    /// Asks `ask` (which returns once its answer came) [`ROUND_TRIPS`] times, timing each.
    fn measured(mut ask: impl FnMut() -> Result<(), String>) -> anyhow::Result<Self> {
        let mut round_trips = Vec::with_capacity(ROUND_TRIPS);
        for _ in 0..ROUND_TRIPS {
            let asked = Instant::now();
            ask().map_err(|error| anyhow::anyhow!(error))?;
            round_trips.push(asked.elapsed());
        }
        Ok(Self::from_round_trips(&round_trips))
    }
}

/// A device connected for a show.
pub struct Linked {
    /// What the player drives.
    pub stage: Box<dyn Stage>,
    /// How long its first kind of cue takes from being written to the device starting.
    pub start_delay: Duration,
    /// Its link's measured delay.
    pub link: LinkDelay,
}

impl std::fmt::Debug for Linked {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Linked").field("start_delay", &self.start_delay).field("link", &self.link).finish()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_link_delay_is_half_the_shortest_round_trip_and_its_spread_half_the_range() {
        let ms = Duration::from_millis;
        let delay = LinkDelay::from_round_trips(&[ms(90), ms(82), ms(120), ms(85)]);
        assert_eq!(delay, LinkDelay { one_way: ms(41), spread: ms(19) });
        assert_eq!(LinkDelay::from_round_trips(&[]), LinkDelay::default());
    }
}
