//! What every device of a show does at a moment of it — the show window's
//! scrub and its stage view: a servo board's servos where the macro its
//! latest cue started has them (its trace, `project::trajectory`), a PLEN2's
//! joints where the firmware's playback of its latest cue's motion has them
//! (plen2.md §6), a base where its drives have taken it from its place.
//! Before a device's first cue it is at home (a base at its place).

use super::passes::Axis;
use super::{Cue, Device, Place, Show, Start};
use crate::device::plen2::playback::{self, DEVICE_IDS, StoredMotions};
use crate::project::{Family, Run};

/// A device's state at a moment of the show.
#[derive(Clone, Debug, PartialEq)]
pub enum Posed {
    /// Each servo's angle, degrees, by servo id.
    Servos(std::collections::BTreeMap<u8, f64>),
    /// Each PLEN2 joint's value, tenths of a degree from home, by device id.
    Joints([i16; DEVICE_IDS]),
    /// Where a base is on the floor.
    Base(Place),
}

/// The longest a cue's playback is followed, ms (as the show's lanes: an hour).
const LONGEST_MS: f64 = 3_600_000.0;

/// The device at `index` at `t_ms` of the show (`None`: no such device).
pub fn posed_at(show: &Show, index: usize, t_ms: u64) -> Option<Posed> {
    let device = show.devices.get(index)?;
    let mut cues: Vec<&Cue> = show.cues.iter().filter(|cue| cue.device == device.name && cue.at_ms <= t_ms).collect();
    cues.sort_by_key(|cue| cue.at_ms);
    let family = device.project.family;
    if family == Family::Rflex {
        return Some(Posed::Base(driven(device.place, &cues, t_ms)));
    }
    let latest = cues.last();
    if family == Family::Plen2 {
        let mut values = [0; DEVICE_IDS];
        if let Some(&&Cue { at_ms, start: Start::Slot(slot), .. }) = latest {
            values = joints_at(device, slot, t_ms - at_ms);
        }
        return Some(Posed::Joints(values));
    }
    let servo = &device.project.servo;
    let mut angles: std::collections::BTreeMap<u8, f64> =
        servo.servos.iter().map(|s| (s.id, f64::from(s.home_deg))).collect();
    if let Some(&&Cue { at_ms, start: Start::Macro(macro_id), .. }) = latest
        && let Ok((trajectories, _)) = crate::project::trace(servo, Run::Macro { macro_id }, LONGEST_MS)
    {
        // Whole ms of a show: exact in f64.
        #[allow(clippy::cast_precision_loss)]
        let since = (t_ms - at_ms) as f64;
        let pose = crate::project::pose_at(servo, &trajectories, since);
        angles = servo.servos.iter().map(|s| s.id).zip(pose).collect();
    }
    Some(Posed::Servos(angles))
}

/// A PLEN2's joints `since_ms` after its motion in `slot` started (held at its end).
fn joints_at(device: &Device, slot: u8, since_ms: u64) -> [i16; DEVICE_IDS] {
    let stored = StoredMotions::new(&device.project.plen2);
    // Whole ms and cycle counts of at most an hour.
    #[allow(clippy::cast_precision_loss, clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let done = (since_ms as f64 / playback::Playback::CYCLE_MS) as usize;
    if done == 0 {
        return [0; DEVICE_IDS];
    }
    // After `done` whole cycles, `done` steps were output (cycles[k] is step k + 1's).
    let played = playback::play(&stored, slot, [0; DEVICE_IDS], done);
    played.cycles.get(done - 1).or(played.cycles.last()).copied().unwrap_or(played.from)
}

/// Where a base is at `t_ms`: from its place, each drive cue in turn (a
/// later cue ends an earlier one), each an arc at its speed and turn rate.
fn driven(place: Place, cues: &[&Cue], t_ms: u64) -> Place {
    let mut at = place;
    for (index, cue) in cues.iter().enumerate() {
        let Start::Drive { speed_m_s, turn_deg_s, for_ms } = cue.start else { continue };
        let next = cues.get(index + 1).map_or(u64::MAX, |later| later.at_ms);
        let until = (cue.at_ms + for_ms).min(next).min(t_ms);
        // Whole ms of a show: exact in f64.
        #[allow(clippy::cast_precision_loss)]
        let seconds = until.saturating_sub(cue.at_ms) as f64 / 1000.0;
        at = arc(at, speed_m_s, turn_deg_s, seconds);
    }
    at
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

/// The device at `index` at `t_ms`, as its board follows it; `held`: an
/// axis of it held at a value (degrees), the pass being recorded.
pub fn now_at(show: &Show, index: usize, t_ms: u64, held: Option<(Axis, f64)>) -> Option<Now> {
    let device = show.devices.get(index)?;
    if device.project.family == Family::Rflex {
        return Some(Now::Driving(driving_at(show, &device.name, t_ms)));
    }
    let mut posed = posed_at(show, index, t_ms)?;
    if let Some((axis, value)) = held {
        hold(&mut posed, axis, value);
    }
    Some(Now::Posed(posed))
}

/// The drive `device`'s cues have it on at `t_ms` (a later cue ends an earlier one); None: at rest.
fn driving_at(show: &Show, device: &str, t_ms: u64) -> Option<(f64, f64)> {
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
    #![allow(clippy::unwrap_used)]
    use super::*;
    use crate::project::plen2::{Frame, Motion, Plen2Project, Pose};
    use crate::project::{Action, Command, Macro, Project, Servo, ServoProject, Step};

    fn show() -> Show {
        let action = Action { id: 1, caption: "up".into(), steps: vec![Step::new(1, 90, 100)] };
        let macros =
            vec![Macro { id: 1, caption: "m".into(), commands: vec![Command::once(Run::Action { action_id: 1 })] }];
        let servo = Project::servo(ServoProject {
            servos: vec![Servo::new(1, "jaw")],
            actions: vec![action],
            macros,
            ..ServoProject::default()
        });
        let mut pose = Pose::default();
        pose.0[0] = 320;
        let motion = Motion {
            slot: 2,
            name: "lift".into(),
            frames: vec![Frame::new(32 * 10, pose)],
            loop_range: None,
            jump_slot: None,
        };
        let mut plen = Project::empty(Family::Plen2);
        plen.plen2 = Plen2Project { motions: vec![motion], ..Plen2Project::default() };
        let mut show = Show::of_one("skull", servo);
        show.add_device("plen", plen);
        show.add_device("base", Project::empty(Family::Rflex));
        show.devices[2].place = Place { x_m: 1.0, y_m: 0.0, heading_deg: 90.0 };
        show.cues = vec![
            Cue { device: "skull".into(), at_ms: 1000, start: Start::Macro(1) },
            Cue { device: "plen".into(), at_ms: 0, start: Start::Slot(2) },
            Cue {
                device: "base".into(),
                at_ms: 0,
                start: Start::Drive { speed_m_s: 0.5, turn_deg_s: 0.0, for_ms: 2000 },
            },
            Cue {
                device: "base".into(),
                at_ms: 3000,
                start: Start::Drive { speed_m_s: 0.0, turn_deg_s: 90.0, for_ms: 1000 },
            },
        ];
        show
    }

    #[test]
    fn a_servo_board_is_home_before_its_cue_then_follows_its_macro() {
        let show = show();
        let angle = |t| match posed_at(&show, 0, t).unwrap() {
            Posed::Servos(angles) => angles[&1],
            other => panic!("{other:?}"),
        };
        assert!((angle(500) - 0.0).abs() < 1e-9, "home before its cue");
        assert!((angle(1500) - 45.0).abs() < 1e-6, "half way through the 1 s step: {}", angle(1500));
        assert!((angle(5000) - 90.0).abs() < 1e-9, "held at the end");
    }

    #[test]
    fn a_plen2_follows_the_firmware_s_cycles_and_a_base_its_drives() {
        let show = show();
        let Posed::Joints(values) = posed_at(&show, 1, 5 * 32 + 20).unwrap() else { panic!() };
        assert_eq!(values[0], 160, "half of 32.0° after 5 of 10 cycles");
        let Posed::Joints(values) = posed_at(&show, 1, 60_000).unwrap() else { panic!() };
        assert_eq!(values[0], 320, "held at its last frame");
        let place = |t| match posed_at(&show, 2, t).unwrap() {
            Posed::Base(place) => place,
            other => panic!("{other:?}"),
        };
        // Heading 90°: 0.5 m/s along +y for 2 s, then still, then a quarter turn in place.
        let at = place(1000);
        assert!((at.x_m - 1.0).abs() < 1e-9 && (at.y_m - 0.5).abs() < 1e-9, "{at:?}");
        let at = place(2500);
        assert!((at.y_m - 1.0).abs() < 1e-9, "stopped after its 2 s: {at:?}");
        let at = place(9000);
        assert!((at.heading_deg - 180.0).abs() < 1e-9 && (at.y_m - 1.0).abs() < 1e-9, "{at:?}");
        assert!(posed_at(&show, 3, 0).is_none());
    }

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
}
