//! A servo board robot as a figure: the rig its project gives (each servo's
//! parent, offset in mm, axis, sign and straight angle). Servos without a rig
//! are not in the figure (the editor shows them as bars beside it). A rig
//! with a cycle or an unknown parent is refused by validation; here its
//! servos are left out rather than looped over.

use std::collections::BTreeMap;

use super::ik::Limb;
use super::{Chain, Link, Shape, Solid, Vec3};
use crate::project::{RigAxis, ServoProject};

const BONE: [u8; 3] = [220, 222, 226];
const JOINT: [u8; 3] = [90, 150, 220];
const BODY: [u8; 3] = [200, 202, 206];
const HEAD: [u8; 3] = [214, 216, 222];
const EYE: [u8; 3] = [40, 170, 235];
const SOLE: [u8; 3] = [70, 72, 78];

/// A servo board robot's chain: the body (link 0), then every rigged servo
/// after its parent. Also each servo id's link.
pub fn chain(project: &ServoProject) -> (Chain, BTreeMap<u8, usize>) {
    let rigged: BTreeMap<u8, &crate::project::RigJoint> =
        project.servos.iter().filter_map(|servo| servo.rig.as_ref().map(|rig| (servo.id, rig))).collect();
    let mut links =
        vec![Link { name: "body".into(), parent: None, offset: Vec3::ZERO, axis: Vec3::ZERO, solids: Vec::new() }];
    let mut index_of: BTreeMap<u8, usize> = BTreeMap::new();
    // Parents first: add what can be added until nothing more can (a cycle or an
    // unknown parent stays out).
    loop {
        let mut added = false;
        for servo in &project.servos {
            let Some(rig) = rigged.get(&servo.id) else { continue };
            if index_of.contains_key(&servo.id) {
                continue;
            }
            let parent = match rig.parent {
                None => 0,
                Some(parent) => match index_of.get(&parent) {
                    Some(index) => *index,
                    None => continue,
                },
            };
            let sign = if rig.reversed { -1.0 } else { 1.0 };
            let axis = match rig.axis {
                RigAxis::X => Vec3::X,
                RigAxis::Y => Vec3::Y,
                RigAxis::Z => Vec3::Z,
            } * sign;
            let name = if servo.caption.is_empty() { format!("servo {}", servo.id) } else { servo.caption.clone() };
            links.push(Link {
                name,
                parent: Some(parent),
                offset: Vec3::new(
                    f32::from(rig.offset_mm[0]),
                    f32::from(rig.offset_mm[1]),
                    f32::from(rig.offset_mm[2]),
                ),
                axis,
                solids: Vec::new(),
            });
            index_of.insert(servo.id, links.len() - 1);
            added = true;
        }
        if !added {
            break;
        }
    }
    dress(&mut links);
    (Chain { links }, index_of)
}

/// Bones from each joint to its children's joints, a ball at each joint, a
/// body between the body's children with a head on it, and on each link
/// nothing is mounted on a foot (a flat sole, when it hangs below the body's
/// lowest mount) or else a hand.
fn dress(links: &mut [Link]) {
    let children: Vec<Vec<Vec3>> = (0..links.len())
        .map(|index| links.iter().filter(|link| link.parent == Some(index)).map(|link| link.offset).collect())
        .collect();
    // Where each joint is with every servo straight (to tell hands from feet).
    let placed = Chain { links: links.to_vec() }.pose(&[]);
    // How thick the bones are: a tenth of the longest, at least 4 mm.
    let longest = links.iter().map(|link| link.offset.length()).fold(0.0_f32, f32::max);
    let radius = (longest / 10.0).clamp(4.0, 25.0);
    // Below the body's lowest mount (the hips): a foot; else a hand.
    let mut hips = f32::MIN;
    if let (Some(body), Some(ends)) = (links.first_mut(), children.first())
        && !ends.is_empty()
    {
        // The body: a box around where its children are mounted, a head on top.
        let (low, high) =
            ends.iter().fold((Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)), |(l, h), p| (l.min(*p), h.max(*p)));
        let half = ((high - low) / 2.0).max(Vec3::splat(radius));
        let centre = (low + high) / 2.0;
        hips = low.z;
        body.solids.push(Solid { at: centre, shape: Shape::Box { half }, color: BODY });
        let size = half.y.min(half.z).max(radius * 2.0) * 0.42;
        let head = centre + Vec3::new(0.0, 0.0, half.z + size * 1.1);
        body.solids.push(Solid { at: head, shape: Shape::Box { half: Vec3::splat(size) }, color: HEAD });
        for side in [-1.0, 1.0] {
            let eye = head + Vec3::new(size, side * size * 0.45, size * 0.2);
            body.solids.push(Solid { at: eye, shape: Shape::Ball { radius: size * 0.18 }, color: EYE });
        }
    }
    for (index, link) in links.iter_mut().enumerate().skip(1) {
        let ends = &children[index];
        link.solids.push(Solid { at: Vec3::ZERO, shape: Shape::Ball { radius: radius * 1.3 }, color: JOINT });
        for end in ends {
            link.solids.push(Solid { at: Vec3::ZERO, shape: Shape::Capsule { to: *end, radius }, color: BONE });
        }
        if ends.is_empty() {
            // A hand or a foot: a stub along the way the link came, a third as long.
            let along = if link.offset.length() > 0.0 { link.offset / 3.0 } else { Vec3::new(0.0, 0.0, -radius * 3.0) };
            link.solids.push(Solid { at: Vec3::ZERO, shape: Shape::Capsule { to: along, radius }, color: BONE });
            let below = placed.get(index).is_some_and(|at| at.position.z < hips);
            link.solids.push(if below {
                // A sole, flat under the stub's end, longer forward.
                let half = Vec3::new(radius * 3.2, radius * 1.8, radius * 0.5);
                Solid {
                    at: along + Vec3::new(radius * 0.8, 0.0, -radius * 1.2),
                    shape: Shape::Box { half },
                    color: SOLE,
                }
            } else {
                Solid { at: along * 1.4, shape: Shape::Box { half: Vec3::splat(radius * 1.2) }, color: BONE }
            });
        }
    }
}

/// The limbs posed by their ends: each servo whose rig marks an end, with the
/// chain from its root (or the body) down to it; and each limb's twin (the
/// limb whose end is its end's mirror twin).
pub fn limbs(project: &ServoProject, chain: &Chain, index_of: &BTreeMap<u8, usize>) -> (Vec<Limb>, Vec<Option<usize>>) {
    let servo_of = |link: usize| index_of.iter().find(|(_, index)| **index == link).map(|(id, _)| *id);
    let mut limbs = Vec::new();
    let mut ends = Vec::new();
    for servo in &project.servos {
        let (Some(rig), Some(&link)) = (servo.rig.as_ref(), index_of.get(&servo.id)) else { continue };
        let Some(end) = rig.end else { continue };
        let mut joints = vec![link];
        let mut at = link;
        while servo_of(at) != end.root
            && let Some(parent) = chain.links.get(at).and_then(|l| l.parent).filter(|&parent| parent != 0)
        {
            joints.push(parent);
            at = parent;
        }
        joints.reverse();
        let [x, y, z] = end.tip_mm.map(f32::from);
        limbs.push(Limb { name: chain.links[link].name.clone(), joints, tip: Vec3::new(x, y, z) });
        ends.push(servo.id);
    }
    let twins = ends
        .iter()
        .map(|&id| {
            let twin = project.twin(id)?.id;
            ends.iter().position(|&other| other == twin)
        })
        .collect();
    (limbs, twins)
}

/// Each link's limits (radians): its servo's min and max less its straight angle.
pub fn limits(project: &ServoProject, index_of: &BTreeMap<u8, usize>, links: usize) -> Vec<(f32, f32)> {
    let mut limits = vec![(0.0, 0.0); links];
    for servo in &project.servos {
        let (Some(rig), Some(&index)) = (servo.rig.as_ref(), index_of.get(&servo.id)) else { continue };
        let radians = |degree: i16| f32::from(degree.saturating_sub(rig.straight_deg)).to_radians();
        limits[index] = (radians(servo.min_deg.min(servo.max_deg)), radians(servo.max_deg.max(servo.min_deg)));
    }
    limits
}

/// The servos' angles (whole degrees) for each link's angle: [`angles`] the other way round.
pub fn degrees(project: &ServoProject, index_of: &BTreeMap<u8, usize>, angles: &[f32]) -> BTreeMap<u8, i16> {
    let mut out = BTreeMap::new();
    for servo in &project.servos {
        let (Some(rig), Some(&index)) = (servo.rig.as_ref(), index_of.get(&servo.id)) else { continue };
        let Some(angle) = angles.get(index) else { continue };
        // Within a turn or two: a few hundred degrees.
        #[allow(clippy::cast_possible_truncation)]
        let degree = (angle.to_degrees() + f32::from(rig.straight_deg)).round() as i16;
        out.insert(servo.id, servo.clamp(degree));
    }
    out
}

/// Each link's angle (radians) for the servos' angles (degrees, by servo id):
/// the angle minus the servo's straight angle.
pub fn angles(
    project: &ServoProject,
    index_of: &BTreeMap<u8, usize>,
    degrees: &BTreeMap<u8, f64>,
    links: usize,
) -> Vec<f32> {
    let mut angles = vec![0.0; links];
    for servo in &project.servos {
        let (Some(rig), Some(index)) = (servo.rig.as_ref(), index_of.get(&servo.id)) else { continue };
        let degree = degrees.get(&servo.id).copied().unwrap_or(f64::from(servo.home_deg));
        // Angles are a few hundred degrees at most: f32 is plenty.
        #[allow(clippy::cast_possible_truncation)]
        let turn = (degree - f64::from(rig.straight_deg)).to_radians() as f32;
        angles[*index] = turn;
    }
    angles
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::project::{RigJoint, Servo};

    fn rigged(id: u8, parent: Option<u8>, offset_mm: [i16; 3], axis: RigAxis) -> Servo {
        let mut servo = Servo::new(id, format!("s{id}"));
        servo.rig =
            Some(RigJoint { parent, offset_mm, axis, reversed: false, straight_deg: 0, mirror: None, end: None });
        servo
    }

    #[test]
    fn a_rigged_arm_turns_at_each_servo_and_a_cycle_is_left_out() {
        // Shoulder (yaw) at the body, elbow 100 mm forward of it; servo 3 and 4 form a loop.
        let project = ServoProject {
            servos: vec![
                rigged(2, Some(1), [100, 0, 0], RigAxis::Z),
                rigged(1, None, [0, 0, 200], RigAxis::Z),
                rigged(3, Some(4), [10, 0, 0], RigAxis::Y),
                rigged(4, Some(3), [10, 0, 0], RigAxis::Y),
                Servo::new(5, "unrigged"),
            ],
            ..ServoProject::default()
        };
        let (chain, index_of) = chain(&project);
        assert_eq!(chain.links.len(), 3, "body, 1, 2: the loop and the unrigged servo stay out");
        assert!(index_of[&1] < index_of[&2], "a parent before its child");
        let degrees = BTreeMap::from([(1, 90.0), (2, 0.0)]);
        let placed = chain.pose(&angles(&project, &index_of, &degrees, chain.links.len()));
        let elbow = placed[index_of[&2]].position;
        assert!((elbow - Vec3::new(0.0, 100.0, 200.0)).length() < 1e-3, "{elbow}");
    }
}
