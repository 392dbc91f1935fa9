//! Touching the figure: which link is under the pointer (the nearest solid
//! there, ghosts aside), and how far a grabbed joint turns as the pointer
//! drags. The turn follows the grabbed point: each frame the pointer's move
//! is measured along the way that point goes on the screen when the joint
//! turns, so dragging a point on an arm carries the arm with the pointer
//! whichever way the camera looks.

use egui::{Pos2, Vec2};

use super::{Projector, Scene, corners, hull};
use crate::figure::{Mat3, Shape, Vec3};

/// A link the user can touch: what hovering it says and, when it turns, its joint.
#[derive(Clone, Debug, PartialEq)]
pub struct Handle {
    /// What hovering it shows (the joint and its angle).
    pub reading: String,
    /// Its joint's position and the axis it turns about (world, unit); none: it does not turn.
    pub joint: Option<(Vec3, Vec3)>,
}

/// What the pointer did to the figure this frame.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Touch {
    /// The link under the pointer, if it has a handle.
    pub hovered: Option<usize>,
    /// The link clicked, if it has a handle.
    pub clicked: Option<usize>,
    /// A joint being turned by a drag: its link and the turn since it was grabbed (radians).
    pub turned: Option<(usize, f32)>,
    /// The drag turning this link let go.
    pub let_go: Option<usize>,
    /// The end under the pointer (or held by a drag).
    pub hovered_end: Option<usize>,
    /// An end dragged: which, and its goal (world).
    pub reached: Option<(usize, Vec3)>,
    /// The drag holding this end let go.
    pub released: Option<usize>,
}

impl Touch {
    /// A new turn of the held joint, in whole `units` (per degree), when it
    /// differs from `last` (the one sent before, cleared when the drag lets go):
    /// the link and the turn since it was grabbed.
    pub fn new_turn(&self, last: &mut Option<i32>, units_per_degree: f64) -> Option<(usize, i32)> {
        let turned = self.turned.and_then(|(link, radians)| {
            // Turns are a few radians at most.
            #[allow(clippy::cast_possible_truncation)]
            let by = (f64::from(radians).to_degrees() * units_per_degree).round() as i32;
            (*last != Some(by)).then(|| {
                *last = Some(by);
                (link, by)
            })
        });
        if self.let_go.is_some() {
            *last = None;
        }
        turned
    }
}

/// A joint held by a drag.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Grab {
    pub link: usize,
    pivot: Vec3,
    axis: Vec3,
    /// The point grabbed, where it was when grabbed.
    point: Vec3,
    /// The turn so far.
    pub total: f32,
    /// Where the pointer was last frame.
    pointer: Pos2,
}

/// Fewer screen pixels per radian than this and the pointer's move is taken
/// at this rate (a point grabbed near the axis would otherwise spin).
const LEAST_PIXELS_PER_RADIAN: f32 = 60.0;
/// The most a joint turns in one frame, however fast the pointer goes.
const MOST_PER_FRAME: f32 = 0.5;

/// Whether `at` is within a convex outline.
fn inside(outline: &[Pos2], at: Pos2) -> bool {
    let cross = |a: Pos2, b: Pos2| (b.x - a.x) * (at.y - a.y) - (b.y - a.y) * (at.x - a.x);
    let n = outline.len();
    n >= 3 && {
        let sides: Vec<f32> = (0..n).map(|i| cross(outline[i], outline[(i + 1) % n])).collect();
        sides.iter().all(|s| *s >= 0.0) || sides.iter().all(|s| *s <= 0.0)
    }
}

/// The nearest solid under `at` (its link and the point of it there, roughly),
/// faint ghosts aside.
pub(super) fn pick(scene: &Scene, projector: &Projector, at: Pos2) -> Option<(usize, Vec3)> {
    let mut nearest: Option<(f32, usize, Vec3)> = None;
    for solid in scene.solids.iter().filter(|solid| !solid.faint) {
        let hit = match solid.shape {
            Shape::Box { half } => {
                let points: Option<Vec<Pos2>> =
                    corners(solid, half).iter().map(|&p| projector.point(p).map(|(p, _)| p)).collect();
                let depth = projector.point(solid.at).map(|(_, depth)| depth);
                points.filter(|points| inside(&hull(points.clone()), at)).and(depth).map(|depth| (depth, solid.at))
            }
            Shape::Ball { radius } => projector
                .point(solid.at)
                .filter(|(center, depth)| center.distance(at) <= projector.size(radius, *depth))
                .map(|(_, depth)| (depth, solid.at)),
            Shape::Capsule { to, radius } => {
                let (Some((a, da)), Some((b, db))) = (projector.point(solid.at), projector.point(to)) else { continue };
                let ab = b - a;
                let u = if ab.length_sq() < 1e-6 { 0.0 } else { ((at - a).dot(ab) / ab.length_sq()).clamp(0.0, 1.0) };
                let depth = da + (db - da) * u;
                let near = a + ab * u;
                (near.distance(at) <= projector.size(radius, depth)).then(|| (depth, solid.at.lerp(to, u)))
            }
        };
        if let Some((depth, point)) = hit
            && nearest.is_none_or(|(best, ..)| depth < best)
        {
            nearest = Some((depth, solid.link, point));
        }
    }
    nearest.map(|(_, link, point)| (link, point))
}

impl Grab {
    /// Holds `link`'s joint (at `pivot`, turning about `axis`) by `point`, the pointer at `pointer`.
    pub(super) fn new(link: usize, (pivot, axis): (Vec3, Vec3), point: Vec3, pointer: Pos2) -> Self {
        Self { link, pivot, axis: axis.normalize_or(Vec3::Z), point, total: 0.0, pointer }
    }

    /// Turns by the pointer's move to `pointer`, seen through `projector`.
    pub(super) fn drag(&mut self, projector: &Projector, pointer: Pos2) {
        let moved = pointer - self.pointer;
        self.pointer = pointer;
        if moved == Vec2::ZERO {
            return;
        }
        let now = self.pivot + Mat3::from_axis_angle(self.axis, self.total) * (self.point - self.pivot);
        // Where the point goes on the screen per radian of turn.
        let along = self.axis.cross(now - self.pivot);
        let step = 0.01;
        let way = match (projector.point(now), projector.point(now + along * step)) {
            (Some((a, _)), Some((b, _))) => (b - a) / step,
            _ => Vec2::ZERO,
        };
        let turn = if way.length() < 1e-3 {
            // The point moves straight at the camera: left and right turn it.
            moved.x / LEAST_PIXELS_PER_RADIAN
        } else {
            moved.dot(way) / way.length_sq().max(LEAST_PIXELS_PER_RADIAN * LEAST_PIXELS_PER_RADIAN)
        };
        self.total += turn.clamp(-MOST_PER_FRAME, MOST_PER_FRAME);
    }
}

#[cfg(test)]
mod tests {
    use egui::{Rect, pos2, vec2};

    use super::*;
    use crate::figure::WorldSolid;
    use crate::ui::view3d::Camera;

    fn projector() -> Projector {
        // Looking from +x at the origin: +y is to the right on the screen, +z up.
        let camera = Camera { yaw: 0.0, pitch: 0.0, distance: 1000.0, target: Vec3::ZERO };
        Projector::new(&camera, Rect::from_min_size(Pos2::ZERO, vec2(600.0, 600.0)))
    }

    fn ball(link: usize, at: Vec3, faint: bool) -> WorldSolid {
        WorldSolid {
            at,
            rotation: Mat3::IDENTITY,
            shape: Shape::Ball { radius: 20.0 },
            color: [200, 200, 200],
            faint,
            link,
        }
    }

    #[test]
    fn the_nearest_solid_under_the_pointer_is_picked_and_ghosts_are_not() {
        let projector = projector();
        let scene = Scene {
            solids: vec![
                ball(0, Vec3::new(-100.0, 0.0, 0.0), false),
                ball(1, Vec3::new(100.0, 0.0, 0.0), false),
                ball(2, Vec3::new(200.0, 0.0, 0.0), true),
                ball(3, Vec3::new(0.0, 200.0, 0.0), false),
            ],
            ..Scene::default()
        };
        let middle = pos2(300.0, 300.0);
        assert_eq!(pick(&scene, &projector, middle).map(|(link, _)| link), Some(1), "the nearer of two");
        let (right, _) = projector.point(Vec3::new(0.0, 200.0, 0.0)).unwrap();
        assert_eq!(pick(&scene, &projector, right).map(|(link, _)| link), Some(3));
        assert_eq!(pick(&scene, &projector, pos2(10.0, 10.0)), None);
    }

    #[test]
    fn dragging_a_point_turns_its_joint_the_way_the_pointer_goes() {
        let projector = projector();
        // A joint at the origin turning about x (straight at the camera), an arm out along +y.
        let point = Vec3::new(0.0, 100.0, 0.0);
        let (start, _) = projector.point(point).unwrap();
        let mut grab = Grab::new(0, (Vec3::ZERO, Vec3::X), point, start);
        // Turning about +x takes +y toward +z: up on the screen.
        let (up, _) = projector.point(Mat3::from_axis_angle(Vec3::X, 0.3) * point).unwrap();
        grab.drag(&projector, up);
        assert!((grab.total - 0.3).abs() < 0.03, "{}", grab.total);
        // Back down past the start: the other way.
        grab.drag(&projector, start + vec2(0.0, 40.0));
        assert!(grab.total < 0.0, "{}", grab.total);
        // A pointer that flies off turns at most so far a frame.
        let before = grab.total;
        grab.drag(&projector, start + vec2(0.0, -5000.0));
        assert!((grab.total - before - MOST_PER_FRAME).abs() < 1e-6);
    }
}
