//! The view's orbit camera and how it puts the world on the screen: the
//! painter's projector and the same camera as OpenGL matrices for the card.

use egui::{Pos2, Rect, pos2};

use crate::figure::Vec3;

/// An orbit camera: it looks at `target` from `distance` away, turned `yaw`
/// about the vertical and raised `pitch` (radians).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// Turn about the vertical: 0 looks at the figure's front from ahead.
    pub yaw: f32,
    /// Height angle: positive looks down.
    pub pitch: f32,
    /// From the target.
    pub distance: f32,
    /// What it looks at.
    pub target: Vec3,
}

/// The vertical field of view.
pub(super) const FOV: f32 = 0.6;
/// Where the light comes from (up, front, left).
pub(super) const LIGHT: Vec3 = Vec3::new(0.45, 0.35, 0.82);

impl Camera {
    /// The camera that shows a scene whole in `rect`, from the front-left, a little above.
    pub(super) fn fit(points: &[Vec3], rect: Rect) -> Self {
        Self { yaw: 0.6, pitch: 0.25, distance: 1000.0, target: Vec3::ZERO }.framing(points, rect)
    }

    /// This camera looking from where it looks, moved to show `points` whole
    /// in `rect` with a margin: aimed at the middle of their box and as near
    /// as the farthest-out point allows, across and up.
    pub(super) fn framing(self, points: &[Vec3], rect: Rect) -> Self {
        if points.is_empty() {
            return self;
        }
        let (low, high) =
            points.iter().fold((Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)), |(l, h), p| (l.min(*p), h.max(*p)));
        let target = (low + high) / 2.0;
        let (_, right, up, forward) = Self { target, ..self }.frame();
        let tan_up = (FOV / 2.0).tan() * 0.85;
        let tan_across = tan_up * (rect.width() / rect.height().max(1.0)).clamp(0.05, 20.0);
        let distance = points
            .iter()
            .map(|p| {
                let d = *p - target;
                let toward = d.dot(forward);
                (d.dot(right).abs() / tan_across - toward).max(d.dot(up).abs() / tan_up - toward)
            })
            .fold(1.0_f32, f32::max);
        Self { distance, target, ..self }
    }

    pub(super) fn eye(&self) -> Vec3 {
        let (sy, cy) = self.yaw.sin_cos();
        let (sp, cp) = self.pitch.sin_cos();
        self.target + Vec3::new(cp * cy, cp * sy, sp) * self.distance
    }

    /// The camera's frame: eye, right, up, forward.
    pub(super) fn frame(&self) -> (Vec3, Vec3, Vec3, Vec3) {
        let eye = self.eye();
        let forward = (self.target - eye).normalize_or(Vec3::X);
        let right = forward.cross(Vec3::Z).normalize_or(Vec3::Y);
        let up = right.cross(forward);
        (eye, right, up, forward)
    }
}

/// Points of the world on the screen, for one frame.
pub(super) struct Projector {
    pub(super) eye: Vec3,
    pub(super) right: Vec3,
    pub(super) up: Vec3,
    pub(super) forward: Vec3,
    pub(super) focal: f32,
    center: Pos2,
}

impl Projector {
    pub(super) fn new(camera: &Camera, rect: Rect) -> Self {
        let (eye, right, up, forward) = camera.frame();
        Self { eye, right, up, forward, focal: rect.height() / 2.0 / (FOV / 2.0).tan(), center: rect.center() }
    }

    /// A point on the screen and its depth; none behind the camera.
    pub(super) fn point(&self, p: Vec3) -> Option<(Pos2, f32)> {
        let d = p - self.eye;
        let depth = d.dot(self.forward);
        if depth < 1.0 {
            return None;
        }
        let scale = self.focal / depth;
        Some((pos2(self.center.x + d.dot(self.right) * scale, self.center.y - d.dot(self.up) * scale), depth))
    }

    /// A length at a depth, on the screen.
    pub(super) fn size(&self, length: f32, depth: f32) -> f32 {
        length * self.focal / depth
    }
}

/// The projector's own camera as OpenGL matrices: the same eye, axes and field of view.
pub(super) fn view_projection(camera: &Camera, rect: Rect) -> glam::Mat4 {
    use glam::{Mat4, Vec4};
    let (eye, right, up, forward) = camera.frame();
    let view = Mat4::from_cols(
        Vec4::new(right.x, up.x, -forward.x, 0.0),
        Vec4::new(right.y, up.y, -forward.y, 0.0),
        Vec4::new(right.z, up.z, -forward.z, 0.0),
        Vec4::new(-right.dot(eye), -up.dot(eye), forward.dot(eye), 1.0),
    );
    let aspect = rect.width() / rect.height().max(1.0);
    let (near, far) = (1.0, (camera.distance * 20.0).max(1000.0));
    let f = 1.0 / (FOV / 2.0).tan();
    let projection = Mat4::from_cols(
        Vec4::new(f / aspect, 0.0, 0.0, 0.0),
        Vec4::new(0.0, f, 0.0, 0.0),
        Vec4::new(0.0, 0.0, (far + near) / (near - far), -1.0),
        Vec4::new(0.0, 0.0, 2.0 * far * near / (near - far), 0.0),
    );
    projection * view
}
