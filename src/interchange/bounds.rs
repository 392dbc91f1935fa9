//! What another tool's file may ask for, checked once it is read and before
//! anything is made of it: a time, a rate or a count that no board (and no
//! tool) can mean is refused, naming the motion, the key and the value —
//! never expanded into memory or work. The bounds, beyond what any real file
//! of these tools holds (docs/import-export.md):
//!
//! - channels: at most [`MAX_CHANNELS`] (Dynamixel ids are 0–253; a Maestro
//!   has 24 channels);
//! - keys of every kind, and a step's values: at most [`MAX_KEYS`] and
//!   [`MAX_CHANNELS`], counted while the file is read, before they are built
//!   (a reader's memory stays within a few times its file);
//! - a key's move, hold or frame: at most [`MAX_CLIP_MS`];
//! - one pass of a motion at its speed: at most [`MAX_CLIP_MS`];
//! - speed rates: [`SPEED_RATES`];
//! - how often a motion or a flow's step is played: at most [`MAX_PLAYS`];
//! - sampled animations: a value per channel in every frame, and at most
//!   [`MAX_SAMPLED_POSITIONS`] positions once brought to the boards' 10 ms.

use super::format::ReadError;
use super::source::{Body, Clip, Source, Timing};

/// The most channels a file may drive.
pub const MAX_CHANNELS: usize = 256;
/// The most keys (frames, steps, pages, a flow's units) one file holds,
/// counted as it is read: a RoboPlus file holds at most 255 pages of 7 steps,
/// a Maestro's script room a few hundred frames.
pub const MAX_KEYS: usize = 100_000;
/// Why a file with more keys is refused.
pub const TOO_MANY_KEYS: &str = "no tool writes as many (is the file damaged?)";
/// The longest key, and the longest pass of one motion, ms: an hour.
pub const MAX_CLIP_MS: f64 = 3_600_000.0;
/// The speed rates a motion or a flow's step may play at (RoboPlus' speed
/// rate, R+ Motion's main and exit speeds: 1 = as authored).
pub const SPEED_RATES: std::ops::RangeInclusive<f64> = 0.01..=100.0;
/// The most times a motion or a flow's step is played (a board's loop count is 16-bit).
pub const MAX_PLAYS: u32 = 32_767;
/// The most positions a sampled animation is fitted from, once brought to
/// the boards' 10 ms updates (channels × updates): 18 joints for 30 minutes.
pub const MAX_SAMPLED_POSITIONS: f64 = 3_240_000.0 * 10.0;

/// A number as a person reads it: plainly, or in scientific notation when far
/// from 1 (1e-300 is not printed as 300 zeros).
fn shown(value: f64) -> String {
    if value != 0.0 && !(1e-3..1e9).contains(&value.abs()) {
        // Four figures at most: 9.766e11, 1e12.
        let figures = format!("{value:.3e}");
        let (mantissa, exponent) = figures.split_once('e').unwrap_or((&figures, "0"));
        format!("{}e{exponent}", mantissa.trim_end_matches('0').trim_end_matches('.'))
    } else {
        format!("{value}")
    }
}

/// An error about `clip`'s content (no line: the file has been read whole).
fn in_clip(clip: &Clip, message: &str) -> ReadError {
    let name = match clip.number {
        Some(number) => format!("page {number} {:?}", clip.name),
        None => format!("{:?}", clip.name),
    };
    ReadError { line: None, element: None, message: format!("{name}: {message}") }
}

/// Whether `source` asks only for what a board can mean (see the module).
pub fn check(source: &Source) -> Result<(), ReadError> {
    if source.channels.len() > MAX_CHANNELS {
        return Err(ReadError {
            line: None,
            element: None,
            message: format!(
                "the file drives {} channels: a board has at most {MAX_CHANNELS} (is the file damaged?)",
                source.channels.len()
            ),
        });
    }
    for clip in &source.clips {
        check_clip(source, clip)?;
    }
    Ok(())
}

/// Whether a time in ms is outside 0 to an hour.
fn beyond_an_hour(ms: f64) -> bool {
    !(0.0..=MAX_CLIP_MS).contains(&ms)
}

/// A clip's keys, samples or chain, each within what a board can mean.
fn check_body(source: &Source, clip: &Clip) -> Result<(), ReadError> {
    match &clip.body {
        Body::Keys(keys) => {
            for (index, key) in keys.iter().enumerate() {
                let (what, ms) = match key.timing {
                    Timing::Move { move_ms, .. } if beyond_an_hour(move_ms) => ("a move", move_ms),
                    Timing::Move { hold_ms, .. } if beyond_an_hour(hold_ms) => ("a hold", hold_ms),
                    Timing::Frame { duration_ms } if beyond_an_hour(duration_ms) => ("a frame", duration_ms),
                    _ => continue,
                };
                return Err(in_clip(
                    clip,
                    &format!(
                        "key {} ({:?}): {what} of {} ms: a key lasts at most an hour (3,600,000 ms)",
                        index + 1,
                        key.name,
                        shown(ms)
                    ),
                ));
            }
        }
        Body::Samples { rows, .. } => {
            if let Some((frame, row)) = rows.iter().enumerate().find(|(_, row)| row.len() != source.channels.len()) {
                return Err(in_clip(
                    clip,
                    &format!("frame {frame} holds {} values for {} channels", row.len(), source.channels.len()),
                ));
            }
        }
        Body::Chain(links) => {
            for (index, link) in links.iter().enumerate() {
                if !SPEED_RATES.contains(&link.speed) || link.plays > MAX_PLAYS {
                    return Err(in_clip(
                        clip,
                        &format!(
                            "step {} plays {} times at a speed of {}: a board plays at most {MAX_PLAYS} times at 0.01 to 100",
                            index + 1,
                            link.plays,
                            shown(link.speed)
                        ),
                    ));
                }
            }
        }
    }
    Ok(())
}

fn check_clip(source: &Source, clip: &Clip) -> Result<(), ReadError> {
    if !SPEED_RATES.contains(&clip.speed) {
        return Err(in_clip(
            clip,
            &format!("a speed rate of {} is not one a board plays (0.01 to 100)", shown(clip.speed)),
        ));
    }
    if clip.repeat > MAX_PLAYS {
        return Err(in_clip(
            clip,
            &format!("played {} times: a board plays a motion at most {MAX_PLAYS} times", clip.repeat),
        ));
    }
    check_body(source, clip)?;
    let pass_ms = clip.duration_ms();
    if beyond_an_hour(pass_ms) {
        return Err(in_clip(
            clip,
            &format!("one pass lasts {:.0} s at its speed: a motion lasts at most an hour", pass_ms / 1000.0),
        ));
    }
    if matches!(clip.body, Body::Samples { .. }) {
        // Channel counts are small (checked above).
        #[allow(clippy::cast_precision_loss)]
        let positions = clip.duration_ms() / 10.0 * source.channels.len() as f64;
        if positions > MAX_SAMPLED_POSITIONS {
            return Err(in_clip(
                clip,
                &format!(
                    "{} channels for {:.0} s make {} positions at the boards' 10 ms: at most {} are fitted (fewer channels, or a shorter animation)",
                    source.channels.len(),
                    clip.duration_ms() / 1000.0,
                    shown(positions.round()),
                    shown(MAX_SAMPLED_POSITIONS)
                ),
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::interchange::format::Format;
    use crate::interchange::source::{Channel, Key, Link, Unit};

    fn source(clip: Clip) -> Source {
        Source {
            format: Format::Mtn,
            channels: vec![Channel::new("1", Unit::DEGREES)],
            clips: vec![clip],
            dropped: Vec::new(),
            notes: Vec::new(),
        }
    }

    fn key(timing: Timing) -> Key {
        Key { values: vec![Some(0.0)], timing, name: "k".into() }
    }

    #[test]
    fn times_speeds_plays_and_counts_no_board_can_mean_are_refused_naming_them() {
        let long = Clip::new("walk", Body::Keys(vec![key(Timing::Move { move_ms: 1e12, hold_ms: 0.0 })]));
        let said = check(&source(long)).unwrap_err().to_string();
        assert!(said.contains("\"walk\"") && said.contains("key 1") && said.contains("1e12 ms"), "{said}");

        let mut slow = Clip::new("bow", Body::Keys(vec![key(Timing::Frame { duration_ms: 100.0 })]));
        slow.speed = 1e-300;
        assert!(check(&source(slow)).unwrap_err().to_string().contains("speed rate of 1e-300"));

        let sampled = Clip::new("wave", Body::Samples { fps: 1.0, rows: vec![vec![0.0]; 1_000_000] });
        assert!(check(&source(sampled)).unwrap_err().to_string().contains("at most an hour"));

        let ragged = Clip::new("nod", Body::Samples { fps: 30.0, rows: vec![vec![0.0], vec![]] });
        assert!(check(&source(ragged)).unwrap_err().to_string().contains("frame 1 holds 0 values for 1 channels"));

        let flow = Clip::new("flow", Body::Chain(vec![Link { clip: 0, plays: 100_000, speed: 1.0 }]));
        assert!(check(&source(flow)).unwrap_err().to_string().contains("step 1 plays 100000 times"));

        let mut wide = source(Clip::new("x", Body::Keys(Vec::new())));
        wide.channels = (0..1_000_000).map(|i| Channel::new(i.to_string(), Unit::DEGREES)).collect();
        assert!(check(&wide).unwrap_err().to_string().contains("1000000 channels"));

        // 256 channels for 40 minutes: 61 million positions at 10 ms.
        let mut many = source(Clip::new("crowd", Body::Samples { fps: 1.0, rows: vec![vec![0.0; 256]; 2401] }));
        many.channels = (0..256).map(|i| Channel::new(i.to_string(), Unit::DEGREES)).collect();
        assert!(
            check(&many)
                .unwrap_err()
                .to_string()
                .contains("256 channels for 2400 s make 61440000 positions at the boards' 10 ms: at most 32400000")
        );

        let fine = Clip::new("ok", Body::Keys(vec![key(Timing::Move { move_ms: 500.0, hold_ms: 3_000_000.0 })]));
        assert_eq!(check(&source(fine)), Ok(()));
    }
}
