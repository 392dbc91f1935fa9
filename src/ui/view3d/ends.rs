//! Ends to pose the figure by (a hand, a foot, the pelvis): each a ring the
//! pointer grabs. A drag carries the end's goal across the screen in the
//! plane that faces the camera through where it was grabbed, so the goal
//! stays under the pointer whichever way the camera looks. Where the limb
//! could not follow, a red line runs from where it stopped to its goal.

use egui::{Color32, Pos2, Shape as Paint, Stroke, pos2};

use super::{Projector, Scene};
use crate::figure::Vec3;

/// An end the user can drag.
#[derive(Clone, Debug, PartialEq)]
pub struct End {
    /// Where it is.
    pub at: Vec3,
    /// What hovering it says (its name and the joints of its chain).
    pub reading: String,
    /// Held where it is (a planted foot): drawn as a pin, not dragged.
    pub held: bool,
}

/// A goal the limb did not reach: from where the end stopped to the goal.
#[derive(Clone, Debug, PartialEq)]
pub struct Gap {
    /// Where the end stopped.
    pub from: Vec3,
    /// Where it was asked to go.
    pub to: Vec3,
    /// How far, in words (e.g. "12.5 mm out of reach").
    pub words: String,
}

/// An end held by a drag.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Reach {
    pub end: usize,
    /// Where the end was when grabbed.
    start: Vec3,
    /// Where the pointer was then.
    origin: Pos2,
}

/// How near (screen pixels) the pointer must come to an end to grab it.
pub(super) const GRAB_RADIUS: f32 = 12.0;

const RING: Color32 = Color32::from_rgb(255, 170, 40);
const PIN: Color32 = Color32::from_rgb(60, 130, 220);
const GAP: Color32 = Color32::from_rgb(225, 50, 50);

impl Reach {
    pub(super) fn new(end: usize, start: Vec3, origin: Pos2) -> Self {
        Self { end, start, origin }
    }

    /// The goal under `pointer`: the grabbed point moved in the plane facing the camera.
    pub(super) fn goal(&self, projector: &Projector, pointer: Pos2) -> Vec3 {
        let depth = (self.start - projector.eye).dot(projector.forward).max(1.0);
        let moved = pointer - self.origin;
        let per_pixel = depth / projector.focal;
        self.start + (projector.right * moved.x - projector.up * moved.y) * per_pixel
    }
}

/// The end nearest `at`, within the grab radius (held ends too: hovering names them).
pub(super) fn nearest(scene: &Scene, projector: &Projector, at: Pos2) -> Option<usize> {
    scene
        .ends
        .iter()
        .enumerate()
        .filter_map(|(index, end)| Some((index, projector.point(end.at)?.0.distance(at))))
        .filter(|(_, distance)| *distance <= GRAB_RADIUS)
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(index, _)| index)
}

/// The rings (hovered or held: filled), the pins, and the gap, drawn over the figure.
pub(super) fn paint(scene: &Scene, projector: &Projector, hovered: Option<usize>) -> Vec<Paint> {
    let mut paints = Vec::new();
    if let Some(gap) = &scene.gap
        && let (Some((from, _)), Some((to, _))) = (projector.point(gap.from), projector.point(gap.to))
    {
        paints.extend(Paint::dashed_line(&[from, to], Stroke::new(2.0, GAP), 6.0, 4.0));
        paints.push(Paint::circle_stroke(to, 6.0, Stroke::new(2.0, GAP)));
        paints.push(Paint::line_segment([to + egui::vec2(-4.0, -4.0), to + egui::vec2(4.0, 4.0)], (2.0, GAP)));
        paints.push(Paint::line_segment([to + egui::vec2(-4.0, 4.0), to + egui::vec2(4.0, -4.0)], (2.0, GAP)));
    }
    for (index, end) in scene.ends.iter().enumerate() {
        let Some((at, _)) = projector.point(end.at) else { continue };
        let lit = hovered == Some(index);
        if end.held {
            let pin = egui::Rect::from_center_size(at, egui::vec2(10.0, 10.0));
            paints.push(Paint::rect_filled(pin, 2.0, PIN));
            paints.push(Paint::line_segment([at, pos2(at.x, at.y + 12.0)], (2.0, PIN)));
        } else {
            let fill = if lit { RING } else { Color32::from_rgba_unmultiplied(255, 170, 40, 60) };
            paints.push(Paint::circle_filled(at, 7.0, fill));
            paints.push(Paint::circle_stroke(at, 7.0, Stroke::new(2.0, RING)));
        }
    }
    paints
}

#[cfg(test)]
mod tests {
    use egui::{Rect, vec2};

    use super::*;
    use crate::ui::view3d::Camera;

    #[test]
    fn a_dragged_end_stays_under_the_pointer_and_only_a_near_one_is_grabbed() {
        let camera = Camera { yaw: 0.7, pitch: 0.3, distance: 900.0, target: Vec3::new(0.0, 0.0, 200.0) };
        let projector = Projector::new(&camera, Rect::from_min_size(Pos2::ZERO, vec2(640.0, 480.0)));
        let start = Vec3::new(30.0, 60.0, 120.0);
        let scene =
            Scene { ends: vec![End { at: start, reading: "left foot".into(), held: false }], ..Scene::default() };
        let (origin, _) = projector.point(start).unwrap();
        assert_eq!(nearest(&scene, &projector, origin + vec2(5.0, 5.0)), Some(0));
        assert_eq!(nearest(&scene, &projector, origin + vec2(20.0, 0.0)), None);
        let reach = Reach::new(0, start, origin);
        let pointer = origin + vec2(-37.0, 52.0);
        let goal = reach.goal(&projector, pointer);
        let (drawn, depth) = projector.point(goal).unwrap();
        assert!(drawn.distance(pointer) < 0.01, "{drawn:?} vs {pointer:?}");
        let (_, start_depth) = projector.point(start).unwrap();
        assert!((depth - start_depth).abs() < 1e-2, "in the plane facing the camera");
    }
}
