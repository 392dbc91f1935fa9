//! An rFLEX base on the show's timeline: at its place before its first cue;
//! each drive runs until its time is up or the next cue starts, along an arc
//! of its speed and turn. Where it is as each cue starts is worked out once;
//! a moment after is the latest drive's arc from there. Its board follows
//! the drive it is on, not a pose.

use crate::project::{Family, Project};
use crate::show::at::{Now, Posed};
use crate::show::timeline::{FamilyTimeline, Lane, latest};
use crate::show::{Device, Place, Start};

inventory::submit! {
    FamilyTimeline { family: Family::Rflex, lane: || Box::<BaseLane>::default() }
}

/// One base's places as each of its cues starts, worked out once.
#[derive(Debug, Default)]
struct BaseLane {
    places: Option<Vec<Place>>,
}

impl Lane for BaseLane {
    fn length_ms(&mut self, _project: &Project, start: &Start) -> u64 {
        let Start::Drive { for_ms, .. } = *start else { return 0 };
        for_ms
    }

    fn posed_at(&mut self, device: &Device, cues: &[(u64, Start)], t_ms: u64) -> Posed {
        let places = self.places.get_or_insert_with(|| {
            let mut places = Vec::with_capacity(cues.len());
            let mut at = device.place;
            for (k, &(start_ms, start)) in cues.iter().enumerate() {
                places.push(at);
                let next = cues.get(k + 1).map_or(u64::MAX, |&(later, _)| later);
                at = drive_to(at, start, start_ms, next);
            }
            places
        });
        let started = cues.partition_point(|&(at, _)| at <= t_ms);
        let Some(latest) = started.checked_sub(1) else { return Posed::Base(device.place) };
        let (start_ms, start) = cues[latest];
        Posed::Base(drive_to(places[latest], start, start_ms, t_ms))
    }

    fn now_at(&mut self, _device: &Device, cues: &[(u64, Start)], t_ms: u64) -> Now {
        // A later cue ends an earlier one.
        Now::Driving(match latest(cues, t_ms) {
            Some((at_ms, Start::Drive { speed_m_s, turn_deg_s, for_ms })) if t_ms < at_ms + for_ms => {
                Some((speed_m_s, turn_deg_s))
            }
            _ => None,
        })
    }
}

/// Where `start` (a drive begun at `at_ms`) takes a base from `from` by
/// `until_ms` (or by its end, if sooner); not a drive: where it is.
fn drive_to(from: Place, start: Start, at_ms: u64, until_ms: u64) -> Place {
    let Start::Drive { speed_m_s, turn_deg_s, for_ms } = start else { return from };
    let until = (at_ms + for_ms).min(until_ms);
    // Whole ms of a show: exact in f64.
    #[allow(clippy::cast_precision_loss)]
    let seconds = until.saturating_sub(at_ms) as f64 / 1000.0;
    arc(from, speed_m_s, turn_deg_s, seconds)
}

/// Where `seconds` at `speed_m_s` turning `turn_deg_s` take a base from `from`.
fn arc(from: Place, speed_m_s: f64, turn_deg_s: f64, seconds: f64) -> Place {
    let heading = from.heading_deg.to_radians();
    let turned = turn_deg_s.to_radians() * seconds;
    let distance = speed_m_s * seconds;
    let (dx, dy) = if turned.abs() < 1e-9 {
        (distance * heading.cos(), distance * heading.sin())
    } else {
        let radius = distance / turned;
        (radius * ((heading + turned).sin() - heading.sin()), radius * (heading.cos() - (heading + turned).cos()))
    };
    Place { x_m: from.x_m + dx, y_m: from.y_m + dy, heading_deg: from.heading_deg + turned.to_degrees() }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::show::Show;

    #[test]
    fn an_arc_ends_where_a_circle_says() {
        // A quarter circle of radius 1 m from the origin heading +x, turning left.
        let quarter = std::f64::consts::FRAC_PI_2;
        let end = arc(Place::default(), quarter, 90.0, 1.0);
        assert!(
            (end.x_m - 1.0).abs() < 1e-9 && (end.y_m - 1.0).abs() < 1e-9 && (end.heading_deg - 90.0).abs() < 1e-9,
            "{end:?}"
        );
    }

    /// Where a base is, worked out from every cue again.
    fn driven_again(device: &Device, cues: &[(u64, Start)], t_ms: u64) -> Place {
        let started: Vec<&(u64, Start)> = cues.iter().filter(|(at, _)| *at <= t_ms).collect();
        let mut at = device.place;
        for (k, (at_ms, start)) in started.iter().enumerate() {
            let next = started.get(k + 1).map_or(u64::MAX, |later| later.0);
            at = drive_to(at, *start, *at_ms, next.min(t_ms));
        }
        at
    }

    /// An hour of drives, turning every other one, scrubbed back and forth
    /// on one kept lane: each place is the one every drive worked out again gives.
    #[test]
    fn a_base_kept_on_the_timeline_is_where_its_drives_take_it_worked_out_again() {
        let mut show = Show::of_one("base", Project::empty(Family::Rflex));
        show.devices[0].place = Place { x_m: 1.0, y_m: -0.5, heading_deg: 30.0 };
        let cues: Vec<(u64, Start)> = (0..3_600_000u64)
            .step_by(5000)
            .enumerate()
            .map(|(k, at_ms)| {
                let turn = if k % 2 == 0 { 0.0 } else { 45.0 };
                (at_ms, Start::Drive { speed_m_s: 0.2, turn_deg_s: turn, for_ms: 3000 + (k as u64 % 3) * 1500 })
            })
            .collect();
        let mut kept = BaseLane::default();
        let device = &show.devices[0];
        for t in [0, 250, 90_000, 61_000, 3_599_000, 1_234_567, 500, 2_000_000, 60_532, 3_600_000] {
            let Posed::Base(place) = kept.posed_at(device, &cues, t) else { panic!() };
            let again = driven_again(device, &cues, t);
            assert!((place.x_m - again.x_m).abs() < 1e-9 && (place.y_m - again.y_m).abs() < 1e-9, "{t}");
            assert!((place.heading_deg - again.heading_deg).abs() < 1e-9, "{t}");
        }
    }
}
