//! Where a source's channels are at a time, through a joint map: what the
//! import window's 3D figure shows before anything is created. Keys are
//! joined straight (a Maestro frame over the time its slowest channel needs
//! at its speed limit), samples taken as they are, a chain played in turn.

use super::map::JointMap;
use super::source::{Body, Clip, Key, Link, Source, Timing};

/// How deep chains of chains are followed.
const MAX_DEPTH: usize = 8;

/// How long `clip` plays once through, ms (a chain: its links in turn, a link
/// played forever counted once).
pub fn length_ms(source: &Source, clip: &Clip) -> f64 {
    length(source, clip, 0)
}

fn length(source: &Source, clip: &Clip, depth: usize) -> f64 {
    match &clip.body {
        Body::Chain(links) if depth < MAX_DEPTH => links
            .iter()
            .filter_map(|link| {
                Some(
                    length(source, source.clips.get(link.clip)?, depth + 1) * f64::from(link.plays.max(1)) / link.speed,
                )
            })
            .sum(),
        Body::Chain(_) => 0.0,
        _ => clip.duration_ms() * f64::from(clip.repeat.max(1)),
    }
}

/// Each channel's degrees `time_ms` into `clip` (`None`: not mapped or not
/// driven yet).
pub fn degrees_at(source: &Source, clip: &Clip, map: &JointMap, time_ms: f64) -> Vec<Option<f64>> {
    let raw = raw_at(source, clip, time_ms.max(0.0), 0);
    source.channels.iter().zip(raw).map(|(channel, raw)| Some(map.entry(&channel.key)?.degrees(raw?))).collect()
}

fn raw_at(source: &Source, clip: &Clip, time_ms: f64, depth: usize) -> Vec<Option<f64>> {
    match &clip.body {
        Body::Chain(links) => chain_at(source, links, time_ms, depth),
        Body::Samples { fps, rows } => samples_at(source, clip, (*fps, rows), time_ms),
        Body::Keys(keys) => keys_at(source, clip, keys, time_ms),
    }
}

/// A chain of clips `time_ms` in: the clip playing then, or where the last one ended.
fn chain_at(source: &Source, links: &[Link], time_ms: f64, depth: usize) -> Vec<Option<f64>> {
    let width = source.channels.len();
    let mut left = time_ms;
    let mut last = vec![None; width];
    for link in links {
        let Some(inner) = source.clips.get(link.clip) else { continue };
        if depth >= MAX_DEPTH {
            break;
        }
        let once = length(source, inner, depth + 1) / link.speed;
        let whole = once * f64::from(link.plays.max(1));
        if left <= whole || link.plays == 0 {
            let into = if once > 0.0 { left % once } else { 0.0 };
            return raw_at(source, inner, into * link.speed, depth + 1);
        }
        left -= whole;
        last = raw_at(source, inner, once * link.speed, depth + 1);
    }
    last
}

/// Sampled rows `time_ms` into `clip`, straight between two samples.
fn samples_at(source: &Source, clip: &Clip, (fps, rows): (f64, &[Vec<f64>]), time_ms: f64) -> Vec<Option<f64>> {
    let width = source.channels.len();
    let one = clip.duration_ms();
    let at = if one > 0.0 { (time_ms % (one * f64::from(clip.repeat.max(1)) + 1e-9)).min(one) } else { 0.0 };
    // Between two samples the file moves straight from one to the next,
    // as the conversion reads it (`Recording::resample`).
    let along = (at * clip.speed * fps / 1000.0).max(0.0);
    // Frame indices of any real animation are far below 2^52.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let frame = (along.floor() as usize).min(rows.len().saturating_sub(1));
    let next = (frame + 1).min(rows.len().saturating_sub(1));
    #[allow(clippy::cast_precision_loss)]
    let part = (along - frame as f64).clamp(0.0, 1.0);
    match (rows.get(frame), rows.get(next)) {
        (Some(row), Some(after)) => row.iter().zip(after).map(|(a, b)| Some(a + (b - a) * part)).collect(),
        _ => vec![None; width],
    }
}

/// Keys `time_ms` into `clip`: each moving from the one before, then holding.
fn keys_at(source: &Source, clip: &Clip, keys: &[Key], time_ms: f64) -> Vec<Option<f64>> {
    let one = clip.duration_ms();
    let mut left =
        if one > 0.0 && time_ms < one * f64::from(clip.repeat.max(1)) { time_ms % one } else { time_ms.min(one) };
    left *= clip.speed;
    // From where the tool puts each channel at power-up, when it says.
    let mut at: Vec<Option<f64>> = source.channels.iter().map(|channel| channel.home).collect();
    for key in keys {
        let (moving, total) = match key.timing {
            Timing::Move { move_ms, hold_ms } => (move_ms, move_ms + hold_ms),
            Timing::Frame { duration_ms } => (frame_move_ms(source, &at, &key.values).min(duration_ms), duration_ms),
        };
        if left < moving {
            let share = left / moving;
            return at
                .iter()
                .zip(&key.values)
                .map(|(from, to)| match (from, to) {
                    (Some(from), Some(to)) => Some(from + (to - from) * share),
                    (None, to) => *to,
                    (from, None) => *from,
                })
                .collect();
        }
        for (value, target) in at.iter_mut().zip(&key.values) {
            if target.is_some() {
                *value = *target;
            }
        }
        if left < total {
            return at;
        }
        left -= total;
    }
    at
}

/// How long a Maestro frame's slowest channel moves at its speed limit (0:
/// as fast as the servo goes, drawn as no time), ms.
fn frame_move_ms(source: &Source, from: &[Option<f64>], to: &[Option<f64>]) -> f64 {
    source
        .channels
        .iter()
        .zip(from.iter().zip(to))
        .filter_map(|(channel, (from, to))| {
            let speed = channel.speed.filter(|s| *s > 0.0)?;
            Some(((to.as_ref()? - from.as_ref()?).abs() / speed).ceil() * 10.0)
        })
        .fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::float_cmp)]
    use super::*;
    use crate::interchange::source::{Channel, Key, Link, Unit};
    use crate::interchange::{Format, JointMap};
    use crate::project::Family;

    fn source() -> Source {
        let key = |value, move_ms, hold_ms| Key {
            values: vec![Some(value)],
            timing: Timing::Move { move_ms, hold_ms },
            name: String::new(),
        };
        let wave =
            Clip::new("wave", Body::Keys(vec![key(0.0, 0.0, 0.0), key(100.0, 1000.0, 500.0), key(0.0, 500.0, 0.0)]));
        let chain = Clip::new("flow", Body::Chain(vec![Link { clip: 0, plays: 2, speed: 1.0 }]));
        Source {
            format: Format::Mtnx,
            channels: vec![Channel::new("1", Unit::DEGREES)],
            clips: vec![wave, chain],
            dropped: Vec::new(),
            notes: Vec::new(),
        }
    }

    #[test]
    fn keys_are_joined_straight_and_chains_play_in_turn() {
        let source = source();
        let map = JointMap::for_source(&source, Family::Servo, None);
        let at = |clip: usize, ms: f64| degrees_at(&source, &source.clips[clip], &map, ms)[0].unwrap();
        assert_eq!(at(0, 500.0), 50.0);
        assert_eq!(at(0, 1200.0), 100.0, "held");
        assert_eq!(at(0, 1750.0), 50.0);
        assert_eq!(length_ms(&source, &source.clips[1]), 4000.0);
        assert_eq!(at(1, 2000.0 + 500.0), 50.0, "the second play");
    }
}
