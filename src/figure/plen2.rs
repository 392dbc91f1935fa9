//! The PLEN2 as a figure: its 18 joints with the link offsets, axes and signs
//! of the official PLEN Motion Editor's 3D model (plen-MotionEditor,
//! `plen2_3dmodel.json`, MIT, 2016), in that model's units (its figure is
//! 540 units tall; the robot about 24 cm). Derived once by walking the
//! model's matrices at home (its Y-up frame turned to x forward, y left, z
//! up); the table is in docs/plen2.md. Each joint turns about its axis by its
//! value (home + value, clamped to the joint's settings, minus home: what the
//! servo really does), right-hand rule. The right side is the left mirrored
//! (y negated): the model's two sides agree to 0.1 unit, and so the figure of
//! a mirrored frame is exactly the mirror image.

use super::ik::Limb;
use super::{Chain, Link, Shape, Solid, Vec3};
use crate::protocol::plen2::{DEVICE_IDS, Joint};

/// The body's height above the ground at home: its feet's soles at z = 0.
pub const BODY_HEIGHT: f32 = 369.0;

/// Millimetres per unit of the model (540 units; the robot 24 cm tall).
pub const MM_PER_UNIT: f32 = 240.0 / 540.0;

/// A sole's middle, in its foot-roll link's frame (the left; the right's y negated).
const SOLE: Vec3 = Vec3::new(11.6, 24.7, -37.8);
/// A hand's tip, in its elbow link's frame.
const HAND: Vec3 = Vec3::new(0.0, 0.0, -123.8);

const SHELL: [u8; 3] = [236, 236, 230];
const FRAME: [u8; 3] = [170, 172, 178];
const SOLE_COLOR: [u8; 3] = [70, 72, 78];
const EYE: [u8; 3] = [40, 170, 235];

/// A left joint: its parent (a left joint, or the body), its offset there, its axis.
struct Left {
    joint: Joint,
    parent: Option<Joint>,
    offset: [f32; 3],
    axis: [f32; 3],
    /// Boxes: centre and half extents, in the joint's frame.
    boxes: &'static [([f32; 3], [f32; 3], [u8; 3])],
}

/// The left half, from the model (the right is its mirror image).
const LEFT: [Left; 9] = [
    Left {
        joint: Joint::LeftShoulderPitch,
        parent: None,
        offset: [35.0, 75.0, 60.0],
        axis: [0.0, -1.0, 0.0],
        boxes: &[
            ([5.8, 12.6, 0.0], [52.0, 4.2, 14.9], FRAME),
            ([51.9, 31.5, 0.0], [5.8, 14.7, 14.9], FRAME),
            ([-40.5, 31.5, 0.0], [5.8, 14.7, 14.9], FRAME),
        ],
    },
    Left {
        joint: Joint::LeftShoulderRoll,
        parent: Some(Joint::LeftShoulderPitch),
        offset: [5.7, 37.8, 0.0],
        axis: [-1.0, 0.0, 0.0],
        boxes: &[([0.0, 10.8, -63.1], [43.4, 22.9, 75.3], SHELL)],
    },
    Left {
        joint: Joint::LeftElbowRoll,
        parent: Some(Joint::LeftShoulderRoll),
        offset: [0.1, 20.9, -121.3],
        axis: [1.0, 0.0, 0.0],
        boxes: &[([0.0, 0.0, -49.5], [49.2, 10.6, 74.3], SHELL)],
    },
    Left {
        joint: Joint::LeftThighYaw,
        parent: None,
        offset: [35.1, 49.5, -75.0],
        axis: [0.0, 0.0, 1.0],
        boxes: &[
            ([0.0, -5.0, -12.6], [54.9, 19.8, 4.2], FRAME),
            ([49.1, -5.0, -31.5], [5.8, 19.8, 14.7], FRAME),
            ([-49.1, -5.0, -31.5], [5.8, 19.8, 14.7], FRAME),
        ],
    },
    Left {
        joint: Joint::LeftThighRoll,
        parent: Some(Joint::LeftThighYaw),
        offset: [0.0, -9.9, -42.0],
        axis: [-1.0, 0.0, 0.0],
        boxes: &[([0.0, 9.9, -12.6], [43.3, 37.1, 26.3], SHELL)],
    },
    Left {
        joint: Joint::LeftThighPitch,
        parent: Some(Joint::LeftThighRoll),
        offset: [0.0, 9.9, -29.4],
        axis: [0.0, -1.0, 0.0],
        boxes: &[
            ([17.3, 39.6, -21.0], [21.7, 2.5, 37.8], FRAME),
            ([17.3, -39.6, -21.0], [21.7, 2.5, 37.8], FRAME),
            ([17.3, 0.0, -42.0], [21.7, 37.1, 14.7], SHELL),
            ([34.6, 0.0, -71.4], [43.4, 37.2, 14.7], SHELL),
        ],
    },
    Left {
        joint: Joint::LeftKneePitch,
        parent: Some(Joint::LeftThighPitch),
        offset: [17.2, 0.0, -71.4],
        axis: [0.0, -1.0, 0.0],
        boxes: &[
            ([0.0, 39.6, -50.4], [43.4, 2.5, 52.5], FRAME),
            ([-0.1, -39.6, -50.4], [43.4, 2.5, 52.5], FRAME),
            ([28.8, 0.0, -42.0], [14.5, 37.1, 10.5], SHELL),
        ],
    },
    Left {
        joint: Joint::LeftFootPitch,
        parent: Some(Joint::LeftKneePitch),
        offset: [-0.1, 0.0, -84.0],
        axis: [0.0, 1.0, 0.0],
        boxes: &[([-17.3, 0.0, -16.8], [43.4, 37.2, 26.3], SHELL)],
    },
    Left {
        joint: Joint::LeftFootRoll,
        parent: Some(Joint::LeftFootPitch),
        offset: [-5.9, -14.8, -29.4],
        axis: [1.0, 0.0, 0.0],
        boxes: &[([11.6, 24.7, -33.6], [101.2, 54.6, 4.2], SOLE_COLOR)],
    },
];

fn boxes(list: &[([f32; 3], [f32; 3], [u8; 3])], mirrored: bool) -> Vec<Solid> {
    let side = if mirrored { -1.0 } else { 1.0 };
    list.iter()
        .map(|&(at, half, color)| Solid {
            at: Vec3::new(at[0], side * at[1], at[2]),
            shape: Shape::Box { half: Vec3::from(half) },
            color,
        })
        .collect()
}

/// The PLEN2's chain: the body (link 0, fixed), then the 18 joints.
pub fn chain() -> Chain {
    let mut links = vec![Link {
        name: "body".into(),
        parent: None,
        offset: Vec3::new(0.0, 0.0, BODY_HEIGHT),
        axis: Vec3::ZERO,
        solids: vec![
            Solid { at: Vec3::ZERO, shape: Shape::Box { half: Vec3::new(87.6, 75.0, 75.1) }, color: SHELL },
            Solid {
                at: Vec3::new(29.6, 0.0, 127.5),
                shape: Shape::Box { half: Vec3::new(49.9, 49.5, 43.5) },
                color: SHELL,
            },
            Solid { at: Vec3::new(74.5, 24.8, 127.6), shape: Shape::Ball { radius: 14.0 }, color: EYE },
            Solid { at: Vec3::new(74.5, -24.8, 127.6), shape: Shape::Ball { radius: 14.0 }, color: EYE },
        ],
    }];
    for mirrored in [false, true] {
        let side = if mirrored { -1.0 } else { 1.0 };
        for left in &LEFT {
            let joint = if mirrored { twin(left.joint) } else { left.joint };
            let parent = match left.parent {
                None => 0,
                Some(parent) => {
                    let parent = if mirrored { twin(parent) } else { parent };
                    links.iter().position(|link| link.name == parent.name()).unwrap_or(0)
                }
            };
            links.push(Link {
                name: joint.name().into(),
                parent: Some(parent),
                offset: Vec3::new(left.offset[0], side * left.offset[1], left.offset[2]),
                // A mirror keeps an axis along y's sign flipped: the twin turns the mirrored way
                // for the negated value (plen2.md: the right homes are the left ones negated).
                axis: Vec3::new(left.axis[0], side * left.axis[1], left.axis[2]),
                solids: boxes(left.boxes, mirrored),
            });
        }
    }
    Chain { links }
}

/// The four limbs posed by their ends: left foot, right foot, left hand, right hand.
pub fn limbs(chain: &Chain) -> Vec<Limb> {
    let links = |joints: &[Joint]| joints.iter().filter_map(|joint| chain.link(joint.name())).collect::<Vec<_>>();
    let leg = [
        Joint::LeftThighYaw,
        Joint::LeftThighRoll,
        Joint::LeftThighPitch,
        Joint::LeftKneePitch,
        Joint::LeftFootPitch,
        Joint::LeftFootRoll,
    ];
    let arm = [Joint::LeftShoulderPitch, Joint::LeftShoulderRoll, Joint::LeftElbowRoll];
    let right = |joints: &[Joint]| joints.iter().map(|joint| twin(*joint)).collect::<Vec<_>>();
    let flip = |p: Vec3| Vec3::new(p.x, -p.y, p.z);
    vec![
        Limb { name: "left foot".into(), joints: links(&leg), tip: SOLE },
        Limb { name: "right foot".into(), joints: links(&right(&leg)), tip: flip(SOLE) },
        Limb { name: "left hand".into(), joints: links(&arm), tip: HAND },
        Limb { name: "right hand".into(), joints: links(&right(&arm)), tip: flip(HAND) },
    ]
}

/// Each link's limits (radians, relative to home) from the joint settings
/// (home, min, max in tenths of a degree, by device id); the body's none.
pub fn limits(chain: &Chain, settings: &[(i16, i16, i16); DEVICE_IDS]) -> Vec<(f32, f32)> {
    chain
        .links
        .iter()
        .map(|link| {
            Joint::ALL.iter().find(|joint| joint.name() == link.name).map_or((0.0, 0.0), |joint| {
                let (home, min, max) = settings[usize::from(joint.device_id())];
                let radians = |tenths: i16| (f32::from(tenths) / 10.0).to_radians();
                (radians(min.saturating_sub(home)), radians(max.saturating_sub(home)))
            })
        })
        .collect()
}

/// Joint values relative to home (tenths of a degree, by device id) for
/// each link's angle: [`angles`] the other way round.
pub fn values(chain: &Chain, angles: &[f32]) -> [i16; DEVICE_IDS] {
    let mut out = [0; DEVICE_IDS];
    for (link, angle) in chain.links.iter().zip(angles) {
        if let Some(joint) = Joint::ALL.iter().find(|joint| joint.name() == link.name) {
            // Within a turn: a few thousand tenths.
            #[allow(clippy::cast_possible_truncation)]
            let tenths = (angle.to_degrees() * 10.0).round() as i16;
            out[usize::from(joint.device_id())] = tenths;
        }
    }
    out
}

/// The joint on the other side.
pub fn twin(joint: Joint) -> Joint {
    let index = Joint::ALL.iter().position(|j| *j == joint).unwrap_or(0);
    Joint::ALL[(index + 9) % 18]
}

/// Each link's angle (radians) for joint values relative to home (tenths of a
/// degree, by device id, already clamped to the joint settings).
pub fn angles(chain: &Chain, values: &[i16; DEVICE_IDS]) -> Vec<f32> {
    chain
        .links
        .iter()
        .map(|link| {
            Joint::ALL
                .iter()
                .find(|joint| joint.name() == link.name)
                .map_or(0.0, |joint| (f32::from(values[usize::from(joint.device_id())]) / 10.0).to_radians())
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::figure::Placed;

    fn joint_position(chain: &Chain, placed: &[Placed], joint: Joint) -> Vec3 {
        placed[chain.link(joint.name()).unwrap()].position
    }

    fn pose(values: &[(Joint, i16)]) -> [i16; DEVICE_IDS] {
        let mut out = [0; DEVICE_IDS];
        for &(joint, value) in values {
            out[usize::from(joint.device_id())] = value;
        }
        out
    }

    /// The lowest corner of a link's first box, in the world.
    fn sole(chain: &Chain, placed: &[Placed], joint: Joint) -> f32 {
        let link = chain.link(joint.name()).unwrap();
        let solids = chain.dress(placed, false);
        let owned: Vec<_> = chain.links[..link].iter().map(|l| l.solids.len()).collect();
        let solid = solids[owned.iter().sum::<usize>()];
        let Shape::Box { half } = solid.shape else { panic!() };
        let mut lowest = f32::MAX;
        for corner in 0..8 {
            let sign = |bit: u32| if corner & (1 << bit) == 0 { -1.0 } else { 1.0 };
            let local = Vec3::new(sign(0) * half.x, sign(1) * half.y, sign(2) * half.z);
            lowest = lowest.min((solid.at + solid.rotation * local).z);
        }
        lowest
    }

    #[test]
    fn at_home_the_feet_are_level_on_the_ground_and_the_figure_is_symmetric() {
        let chain = chain();
        let placed = chain.pose(&angles(&chain, &[0; DEVICE_IDS]));
        for side in [Joint::LeftFootRoll, Joint::RightFootRoll] {
            assert!(sole(&chain, &placed, side).abs() < 0.05, "{side:?} sole at {}", sole(&chain, &placed, side));
            let link = chain.link(side.name()).unwrap();
            // Level: the foot's frame is the world's.
            assert!((placed[link].rotation.z_axis - Vec3::Z).length() < 1e-6);
        }
        for (index, left) in Joint::ALL[..9].iter().enumerate() {
            let right = Joint::ALL[index + 9];
            let (l, r) = (joint_position(&chain, &placed, *left), joint_position(&chain, &placed, right));
            assert!((l - Vec3::new(r.x, -r.y, r.z)).length() < 1e-3, "{left:?} {l} vs {right:?} {r}");
        }
        // The model's own home positions (its Y-up frame turned), for a few joints.
        let knee = joint_position(&chain, &placed, Joint::LeftKneePitch);
        assert!((knee - Vec3::new(52.3, 49.5, -137.8 + 289.0)).length() < 0.2, "{knee}");
    }

    #[test]
    fn a_mirrored_frame_is_the_mirror_image_of_the_figure() {
        let chain = chain();
        // Any frame: every joint a different value; mirrored as Mirror L/R does it.
        let mut values = crate::project::plen2::Pose::default();
        for (i, joint) in Joint::ALL.iter().enumerate() {
            values.set(*joint, (i16::try_from(i).unwrap_or(0) * 97 % 700) - 350);
        }
        let device = |pose: &crate::project::plen2::Pose| {
            let mut out = [0; DEVICE_IDS];
            for joint in Joint::ALL {
                out[usize::from(joint.device_id())] = pose.get(joint);
            }
            out
        };
        let (frame, mirror) = (device(&values), device(&values.mirrored()));
        let placed = chain.pose(&angles(&chain, &frame));
        let reflected = chain.pose(&angles(&chain, &mirror));
        for joint in Joint::ALL {
            let a = joint_position(&chain, &placed, joint);
            let b = joint_position(&chain, &reflected, twin(joint));
            assert!((a - Vec3::new(b.x, -b.y, b.z)).length() < 1e-2, "{joint:?}: {a} vs {b}");
        }
        // And the solids too (the feet's soles).
        let (a, b) = (chain.dress(&placed, false), chain.dress(&reflected, false));
        let centre = |solids: &[crate::figure::WorldSolid]| solids.iter().map(|s| s.at).fold(Vec3::ZERO, |s, p| s + p);
        let (ca, cb) = (centre(&a), centre(&b));
        assert!((ca - Vec3::new(cb.x, -cb.y, cb.z)).length() < 0.5, "{ca} vs {cb}");
    }

    #[test]
    fn the_official_bow_bends_the_hips_forward_and_the_knees_as_a_knee_bends() {
        // The official "Bow" (slot 4), frame 3: left thigh pitch +607, left knee −129.
        // With the body held still, a bow swings the legs forward of the body (the
        // body tips forward over them); a knee flexes by swinging the shin back and up.
        let chain = chain();
        let home = chain.pose(&angles(&chain, &[0; DEVICE_IDS]));
        let hips = chain.pose(&angles(&chain, &pose(&[(Joint::LeftThighPitch, 607), (Joint::RightThighPitch, -607)])));
        for knee in [Joint::LeftKneePitch, Joint::RightKneePitch] {
            let (from, to) = (joint_position(&chain, &home, knee), joint_position(&chain, &hips, knee));
            assert!(to.x > from.x + 40.0, "{knee:?}: {from} → {to}");
        }
        let flexed = chain.pose(&angles(&chain, &pose(&[(Joint::LeftKneePitch, -300)])));
        let foot = |placed: &[Placed]| joint_position(&chain, placed, Joint::LeftFootPitch);
        assert!(foot(&flexed).x < foot(&home).x - 30.0, "{} vs {}", foot(&flexed), foot(&home));
        assert!(foot(&flexed).z > foot(&home).z, "the foot rises");
    }

    /// A fixed pseudo-random walk (xorshift): the same targets every run.
    struct Walk(u64);

    impl Walk {
        fn unit(&mut self) -> f32 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            // 24 bits of it, as a fraction.
            #[allow(clippy::cast_precision_loss)]
            let fraction = (self.0 >> 40) as f32 / (1u64 << 24) as f32;
            fraction
        }
    }

    fn factory() -> [(i16, i16, i16); DEVICE_IDS] {
        let mut settings = [(0, -900, 900); DEVICE_IDS];
        for joint in Joint::ALL {
            settings[usize::from(joint.device_id())].0 = joint.factory_home_tenths_deg();
        }
        settings
    }

    /// Where a limb's end is for joint values (tenths, as the robot gets them), in mm and radians apart.
    fn apart(chain: &Chain, limb: &Limb, values: &[i16; DEVICE_IDS], goal: &Placed) -> (f32, f32) {
        let reach = limb.reach(&chain.pose(&angles(chain, values))).unwrap();
        let turn = goal.rotation * reach.rotation.transpose();
        let (_, angle) = glam::Quat::from_mat3(&turn).normalize().to_axis_angle();
        let angle = if angle > std::f32::consts::PI { std::f32::consts::TAU - angle } else { angle };
        ((reach.position - goal.position).length() * MM_PER_UNIT, angle)
    }

    #[test]
    fn two_hundred_reachable_foot_targets_are_reached_within_a_millimetre_and_half_a_degree() {
        use crate::figure::ik::{Goal, solve};
        let chain = chain();
        let limits = limits(&chain, &factory());
        let limbs = limbs(&chain);
        let mut walk = Walk(0x9e37_79b9_7f4a_7c15);
        let mut worst = (0.0_f32, 0.0_f32);
        for target in 0..200 {
            let limb = &limbs[target % 2];
            // A pose within the limits, its foot by forward kinematics: the target.
            let mut random = vec![0.0; chain.links.len()];
            for &link in &limb.joints {
                let (low, high) = limits[link];
                random[link] = low + (high - low) * walk.unit();
            }
            let goal = limb.reach(&chain.pose(&random)).unwrap();
            let solved = solve(&chain, Placed::ORIGIN, &[0.0; 19], limb, Goal::Hold(goal), &limits);
            // What the robot gets: whole tenths, within each joint's settings.
            let sent = values(&chain, &solved.angles);
            for &link in &limb.joints {
                let angle = solved.angles[link];
                assert!(angle >= limits[link].0 - 1e-6 && angle <= limits[link].1 + 1e-6, "a joint past its limit");
            }
            let (mm, radians) = apart(&chain, limb, &sent, &goal);
            assert!(
                mm < 1.0 && radians.to_degrees() < 0.5,
                "target {target} ({}): {mm} mm, {}° apart",
                limb.name,
                radians.to_degrees()
            );
            worst = (worst.0.max(mm), worst.1.max(radians.to_degrees()));
        }
        println!("200 foot targets: worst {:.3} mm, {:.3}°", worst.0, worst.1);
    }

    #[test]
    fn a_target_out_of_reach_stops_at_the_nearest_pose_and_says_how_far() {
        use crate::figure::ik::{Goal, solve};
        let chain = chain();
        let limits = limits(&chain, &factory());
        let foot = &limbs(&chain)[0];
        let home = foot.reach(&chain.pose(&[0.0; 19])).unwrap().position;
        // A metre below: the leg stretches straight down as far as it goes.
        let far = home - Vec3::new(0.0, 0.0, 1000.0 / MM_PER_UNIT);
        let solved = solve(&chain, Placed::ORIGIN, &[0.0; 19], foot, Goal::Reach(far), &limits);
        let reached = foot.reach(&chain.pose(&solved.angles)).unwrap().position;
        assert!(!solved.reached(1.0, 0.01));
        assert!((solved.gap - (far - reached).length()).abs() < 1e-2, "the gap is the distance left");
        assert!(reached.z < home.z, "it went toward the target");
        assert!(solved.gap * MM_PER_UNIT > 990.0 && solved.gap * MM_PER_UNIT < 1000.0, "{}", solved.gap);
    }

    #[test]
    fn dragging_the_pelvis_three_centimetres_keeps_the_planted_feet_within_a_millimetre() {
        use crate::figure::ik::{keep_planted, plant};
        let chain = chain();
        let limits = limits(&chain, &factory());
        let limbs = limbs(&chain);
        let feet = |angles: &[f32], base: Placed| {
            let placed = chain.pose_from(base, angles);
            [limbs[0].reach(&placed).unwrap(), limbs[1].reach(&placed).unwrap()]
        };
        // As a drag does it: a millimetre a frame, toward the pelvis's goal.
        let drag = |angles: &mut Vec<f32>, base: &mut Placed, by: Vec3, planted: &[(&Limb, Placed)]| {
            for _ in 0..30 {
                let next = Placed { position: base.position + by / 30.0 / MM_PER_UNIT, ..*base };
                let kept = keep_planted(&chain, next, angles, planted, &limits);
                assert!(kept.reached(0.2, 0.002), "the feet held: {kept:?}");
                (*angles, *base) = (kept.angles, next);
            }
        };
        let home = vec![0.0; chain.links.len()];
        let held = plant(&chain, Placed::ORIGIN, &home, &[&limbs[0], &limbs[1]]);
        let planted: Vec<(&Limb, Placed)> = vec![(&limbs[0], held[0]), (&limbs[1], held[1])];
        // The legs straighten at home: first a crouch, the pelvis 3 cm down.
        let (mut crouched, mut base) = (home.clone(), Placed::ORIGIN);
        drag(&mut crouched, &mut base, Vec3::new(0.0, 0.0, -30.0), &planted);
        let crouch = base;
        for direction in [Vec3::X, -Vec3::X, Vec3::Y, Vec3::new(0.6, -0.6, 0.0), Vec3::new(0.0, 0.6, -0.8)] {
            let (mut angles, mut base) = (crouched.clone(), crouch);
            drag(&mut angles, &mut base, direction.normalize() * 30.0, &planted);
            let sent = super::angles(&chain, &values(&chain, &angles));
            let after = feet(&sent, base);
            assert!(((base.position - crouch.position).length() * MM_PER_UNIT - 30.0).abs() < 1e-2);
            for ((_, a), b) in planted.iter().zip(&after) {
                let mm = (a.position - b.position).length() * MM_PER_UNIT;
                let (_, turn) = glam::Quat::from_mat3(&(a.rotation * b.rotation.transpose())).to_axis_angle();
                assert!(mm < 1.0, "{direction}: a planted foot moved {mm} mm");
                assert!(
                    turn.min(std::f32::consts::TAU - turn).to_degrees() < 0.5,
                    "{direction}: a planted foot turned"
                );
            }
        }
    }

    #[test]
    fn the_twin_of_a_mirrored_goal_reaches_the_mirror_image() {
        use crate::figure::ik::{Goal, mirrored, solve};
        let chain = chain();
        let limits = limits(&chain, &factory());
        let limbs = limbs(&chain);
        let home = chain.pose(&[0.0; 19]);
        let goal = limbs[2].reach(&home).unwrap().position + Vec3::new(60.0, 30.0, 80.0);
        let left = solve(&chain, Placed::ORIGIN, &[0.0; 19], &limbs[2], Goal::Reach(goal), &limits);
        let both = solve(&chain, Placed::ORIGIN, &left.angles, &limbs[3], mirrored(Goal::Reach(goal)), &limits);
        let placed = chain.pose(&both.angles);
        let (l, r) = (limbs[2].reach(&placed).unwrap().position, limbs[3].reach(&placed).unwrap().position);
        assert!((l - goal).length() * MM_PER_UNIT < 0.1, "{l} vs {goal}");
        assert!((l - Vec3::new(r.x, -r.y, r.z)).length() * MM_PER_UNIT < 0.1, "{l} vs {r}");
    }
}
