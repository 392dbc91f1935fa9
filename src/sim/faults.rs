//! Fault injection for the emulated boards (the servo board's faults, the rFLEX
//! base's line noise): deterministic, counted faults, so a test that injects one
//! knows exactly where it lands.

use std::str::FromStr;

/// Which faults the emulated board injects. Counts are of responses sent
/// (or frames received, for `disconnect_after`), from 1.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Faults {
    /// Before every n-th response, send a burst of garbage bytes (including a
    /// partial magic).
    pub garbage_every: Option<u32>,
    /// Corrupt the checksum of every n-th response.
    pub corrupt_every: Option<u32>,
    /// Drop every n-th response (never send it).
    pub drop_every: Option<u32>,
    /// While subscribed, send a button event before every n-th response, so it
    /// arrives between a request and its response.
    pub button_every: Option<u32>,
    /// Close the link after receiving this many frames.
    pub disconnect_after: Option<u64>,
    /// Answer `result = 0` to adds (actions, macros, tables) with these ids.
    pub refuse_add: Vec<i32>,
}

/// A fault list could not be read.
#[derive(Debug, PartialEq, Eq, thiserror::Error)]
#[error(
    "cannot read fault {item:?}: expected a comma-separated list of garbage-every=N, corrupt-every=N, drop-every=N, button-every=N, disconnect-after=N, refuse-add=ID"
)]
pub struct FaultsError {
    /// The item that could not be read.
    pub item: String,
}

impl FromStr for Faults {
    type Err = FaultsError;

    fn from_str(text: &str) -> Result<Self, Self::Err> {
        let mut faults = Self::default();
        for item in text.split(',').map(str::trim).filter(|item| !item.is_empty()) {
            let error = || FaultsError { item: item.to_string() };
            let (key, value) = item.split_once('=').ok_or_else(error)?;
            let every = || value.parse::<u32>().ok().filter(|n| *n > 0).ok_or_else(error);
            match key {
                "garbage-every" => faults.garbage_every = Some(every()?),
                "corrupt-every" => faults.corrupt_every = Some(every()?),
                "drop-every" => faults.drop_every = Some(every()?),
                "button-every" => faults.button_every = Some(every()?),
                "disconnect-after" => {
                    faults.disconnect_after = Some(value.parse().map_err(|_| error())?);
                }
                "refuse-add" => faults.refuse_add.push(value.parse().map_err(|_| error())?),
                _ => return Err(error()),
            }
        }
        Ok(faults)
    }
}

/// Line noise on the base's output, counted over frames sent, from 1.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct LineNoise {
    /// Send a burst of garbage before every n-th frame.
    pub garbage_every: Option<u32>,
    /// Corrupt a data byte (so the checksum fails) of every n-th frame.
    pub corrupt_every: Option<u32>,
    /// Cut every n-th frame short (only its first half is sent).
    pub cut_every: Option<u32>,
}

/// A noise list could not be read.
#[derive(Debug, PartialEq, Eq, thiserror::Error)]
#[error("cannot read noise {item:?}: expected a comma-separated list of garbage-every=N, corrupt-every=N, cut-every=N")]
pub struct LineNoiseError {
    /// The item that could not be read.
    pub item: String,
}

impl FromStr for LineNoise {
    type Err = LineNoiseError;

    fn from_str(text: &str) -> Result<Self, Self::Err> {
        let mut noise = Self::default();
        for item in text.split(',').map(str::trim).filter(|item| !item.is_empty()) {
            let error = || LineNoiseError { item: item.to_string() };
            let (key, value) = item.split_once('=').ok_or_else(error)?;
            let every = Some(value.parse::<u32>().ok().filter(|n| *n > 0).ok_or_else(error)?);
            match key {
                "garbage-every" => noise.garbage_every = every,
                "corrupt-every" => noise.corrupt_every = every,
                "cut-every" => noise.cut_every = every,
                _ => return Err(error()),
            }
        }
        Ok(noise)
    }
}

/// Whether the `count`-th event falls on an `every` fault.
pub(crate) fn hits(every: Option<u32>, count: u64) -> bool {
    every.is_some_and(|every| count.is_multiple_of(u64::from(every)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn noise_lists_parse() {
        let noise: LineNoise = "garbage-every=3, cut-every=5".parse().unwrap();
        assert_eq!(noise, LineNoise { garbage_every: Some(3), corrupt_every: None, cut_every: Some(5) });
        assert!("nope=1".parse::<LineNoise>().is_err());
        assert!("cut-every=0".parse::<LineNoise>().is_err());
    }

    #[test]
    fn fault_lists_parse() {
        let faults: Faults =
            "garbage-every=3, drop-every=7,disconnect-after=40,refuse-add=42,refuse-add=-1".parse().unwrap();
        assert_eq!(
            faults,
            Faults {
                garbage_every: Some(3),
                drop_every: Some(7),
                disconnect_after: Some(40),
                refuse_add: vec![42, -1],
                ..Faults::default()
            }
        );
        assert_eq!("".parse::<Faults>().unwrap(), Faults::default());
        for bad in ["drop-every", "drop-every=0", "drop-every=x", "explode=1"] {
            assert!(bad.parse::<Faults>().is_err(), "{bad}");
        }
    }

    #[test]
    fn every_nth() {
        assert!(!hits(None, 3));
        assert!(hits(Some(3), 3));
        assert!(hits(Some(3), 6));
        assert!(!hits(Some(3), 4));
    }
}
