//! What every device of a show does at a moment of it — the show window's
//! scrub and its stage view: a servo board's servos where the macro its
//! latest cue started has them (its trace, `project::trajectory`), a PLEN2's
//! joints where the firmware's playback of its latest cue's motion has them
//! (plen2.md §6), a base where its drives have taken it from its place.
//! Before a device's first cue it is at home (a base at its place).

use std::collections::BTreeMap;

use super::{Place, Show, Start};
use crate::device::plen2::playback::DEVICE_IDS;
use crate::project::{ServoProject, Trajectories, angle_at, angle_at_sorted};

/// What a pass moves.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Axis {
    /// A servo board's servo, by id.
    Servo(u8),
    /// A PLEN2 joint, by device id (0..18).
    Joint(u8),
}

/// A device's state at a moment of the show.
#[derive(Clone, Debug, PartialEq)]
pub enum Posed {
    /// Each servo's angle, degrees, by servo id.
    Servos(BTreeMap<u8, f64>),
    /// Each PLEN2 joint's value, tenths of a degree from home, by device id.
    Joints([i16; DEVICE_IDS]),
    /// Where a base is on the floor.
    Base(Place),
}

/// Every servo of `servo` where `trajectories` have it `since_ms` into them
/// (its home before they move it); `sorted`: their times never go back.
pub(super) fn trace_pose(
    servo: &ServoProject,
    (trajectories, sorted): (&Trajectories, bool),
    since_ms: f64,
) -> BTreeMap<u8, f64> {
    let angle_at = if sorted { angle_at_sorted } else { angle_at };
    servo
        .servos
        .iter()
        .map(|s| {
            let angle = trajectories.get(&s.id).and_then(|points| angle_at(points, since_ms));
            (s.id, angle.unwrap_or(f64::from(s.home_deg)))
        })
        .collect()
}

/// What a device is doing at a moment of the show, as its board is told
/// to follow it: where its servos or joints are, or the drive a base is on.
#[derive(Clone, Debug, PartialEq)]
pub enum Now {
    /// A servo board's servos or a PLEN2's joints, where they are.
    Posed(Posed),
    /// A base's drive now: speed (m/s) and turn rate (°/s); None: at rest.
    Driving(Option<(f64, f64)>),
}

/// The drive `device`'s cues have it on at `t_ms` (a later cue ends an earlier one); None: at rest.
pub(super) fn driving_at(show: &Show, device: &str, t_ms: u64) -> Option<(f64, f64)> {
    let latest =
        show.cues.iter().filter(|cue| cue.device == device && cue.at_ms <= t_ms).max_by_key(|cue| cue.at_ms)?;
    match latest.start {
        Start::Drive { speed_m_s, turn_deg_s, for_ms } if t_ms < latest.at_ms + for_ms => Some((speed_m_s, turn_deg_s)),
        _ => None,
    }
}

/// `posed` with `axis` at `value` degrees (the pass being recorded).
pub fn hold(posed: &mut Posed, axis: Axis, value: f64) {
    match (posed, axis) {
        (Posed::Servos(degrees), Axis::Servo(id)) => {
            degrees.insert(id, value);
        }
        (Posed::Joints(values), Axis::Joint(joint)) => {
            if let Some(slot) = values.get_mut(usize::from(joint)) {
                // Tenths of a degree within ±180°.
                #[allow(clippy::cast_possible_truncation)]
                let tenths = (value * 10.0).round().clamp(-1800.0, 1800.0) as i16;
                *slot = tenths;
            }
        }
        _ => {}
    }
}

/// The value of `axis` in `posed`, as [`hold`] takes it (degrees); none
/// where the pose has no such axis.
pub fn axis_value(posed: &Posed, axis: Axis) -> Option<f64> {
    match (posed, axis) {
        (Posed::Servos(degrees), Axis::Servo(id)) => degrees.get(&id).copied(),
        (Posed::Joints(values), Axis::Joint(joint)) => {
            values.get(usize::from(joint)).map(|&tenths| f64::from(tenths) / 10.0)
        }
        _ => None,
    }
}

/// Where `seconds` at `speed_m_s` turning `turn_deg_s` take a base from `from`.
pub(super) fn arc(from: Place, speed_m_s: f64, turn_deg_s: f64, seconds: f64) -> Place {
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
