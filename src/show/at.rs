//! What a device of a show is at a moment of it — the show window's scrub
//! and its stage view, a record pass followed on the boards — in the shapes
//! every family's lane (`timeline::Lane`) answers in: servos' angles, joints'
//! values, a place on the floor, a drive. A family added later answers in one
//! of these (the echo board's one servo is `Posed::Servos`).

use std::collections::BTreeMap;

use super::Place;
use crate::device::plen2::playback::DEVICE_IDS;

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

/// What a device is doing at a moment of the show, as its board is told
/// to follow it: where its servos or joints are, or the drive a base is on.
#[derive(Clone, Debug, PartialEq)]
pub enum Now {
    /// A servo board's servos or a PLEN2's joints, where they are.
    Posed(Posed),
    /// A base's drive now: speed (m/s) and turn rate (°/s); None: at rest.
    Driving(Option<(f64, f64)>),
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
