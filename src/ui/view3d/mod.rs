//! A 3D view of a posed figure, drawn with egui's painter so it runs wherever
//! eframe runs and in headless tests: an orbit camera of our own (drag to
//! orbit, wheel to zoom, double-click to reset), flat-shaded boxes, balls and
//! capsules sorted back to front, a ground grid and the figure's shadow. A
//! ghost (another pose, drawn faint) can share the scene. A scene whose links
//! have handles can be posed: hovering a link names it, a click selects it,
//! and a drag that starts on a joint turns that joint (the `touch` module).
//! A scene with ends (a hand, a foot) can be posed by them: a drag that starts
//! on an end's ring carries its goal (the `ends` module), and the family
//! solves the limb. The camera frames the whole figure at every size: "frame
//! all" (the F key over the view, or [`View::frame_all`]) and a resize fit it
//! again, keeping the way it looks from.

mod ends;
mod gpu;
mod mesh_files;
pub mod posing;
mod touch;

use egui::{Color32, Pos2, Rect, Sense, Shape as Paint, Stroke, pos2};

use std::sync::{Arc, Mutex};

use crate::figure::mesh::Mesh;
use crate::figure::{Placed, Shape, Vec3, WorldSolid};
pub use ends::{End, Gap};
pub use mesh_files::MeshFiles;
pub use touch::{Handle, Touch};

/// What the view draws: solids over a ground at `ground_z`.
#[derive(Clone, Debug, Default)]
pub struct Scene {
    /// The solids, already placed.
    pub solids: Vec<WorldSolid>,
    /// The ground's height.
    pub ground_z: f32,
    /// Each link's handle, by link index (none: the link cannot be touched;
    /// empty: nothing can, the view only orbits).
    pub handles: Vec<Option<Handle>>,
    /// The link drawn as selected.
    pub selected: Option<usize>,
    /// Ends to pose the figure by (empty: none).
    pub ends: Vec<End>,
    /// The goal an end did not reach.
    pub gap: Option<Gap>,
    /// Meshes the links are drawn with (a link with one shows it instead of its solids).
    pub meshes: Vec<SceneMesh>,
}

/// A mesh placed in the world on a link.
#[derive(Clone, Debug)]
pub struct SceneMesh {
    /// The link it is fixed to.
    pub link: usize,
    /// Its triangles, in its own units.
    pub mesh: Arc<Mesh>,
    /// Where its origin is and how it is turned, in the world.
    pub place: Placed,
    /// World units per unit of the mesh.
    pub scale: f32,
    /// Its colour.
    pub color: [u8; 3],
}

impl SceneMesh {
    /// From the mesh's units to the world.
    fn model(&self) -> glam::Mat4 {
        glam::Mat4::from_translation(self.place.position)
            * glam::Mat4::from_mat3(self.place.rotation)
            * glam::Mat4::from_scale(Vec3::splat(self.scale))
    }

    /// The corners of its box, in the world.
    fn corners(&self) -> [Vec3; 8] {
        let (low, high) = self.mesh.bounds();
        std::array::from_fn(|corner| {
            let pick = |bit: usize, l: f32, h: f32| if corner & (1 << bit) == 0 { l } else { h };
            let local = Vec3::new(pick(0, low.x, high.x), pick(1, low.y, high.y), pick(2, low.z, high.z));
            self.place.position + self.place.rotation * (local * self.scale)
        })
    }
}

impl Scene {
    /// Points around everything solid the scene holds (the corners of boxes,
    /// the extremes of balls and rods): what the camera frames.
    fn outline(&self) -> Vec<Vec3> {
        let mut points = Vec::with_capacity(self.solids.len() * 8 + self.meshes.len() * 8);
        for mesh in self.meshes.iter().filter(|mesh| !mesh.mesh.positions.is_empty()) {
            points.extend(mesh.corners());
        }
        let around = |points: &mut Vec<Vec3>, at: Vec3, radius: f32| {
            for axis in [Vec3::X, Vec3::Y, Vec3::Z] {
                points.push(at + axis * radius);
                points.push(at - axis * radius);
            }
        };
        for solid in self.solids.iter().filter(|solid| !solid.faint && !self.meshed(solid.link)) {
            match solid.shape {
                Shape::Box { half } => points.extend(corners(solid, half)),
                Shape::Ball { radius } => around(&mut points, solid.at, radius),
                Shape::Capsule { to, radius } => {
                    around(&mut points, solid.at, radius);
                    around(&mut points, to, radius);
                }
            }
        }
        points
    }

    /// Whether a link is drawn by its mesh (its solids are only touched, not drawn).
    fn meshed(&self, link: usize) -> bool {
        self.meshes.iter().any(|mesh| mesh.link == link)
    }

    /// The centre and radius of what the scene holds (for the camera).
    fn bounds(&self) -> (Vec3, f32) {
        let mut low = Vec3::splat(f32::MAX);
        let mut high = Vec3::splat(f32::MIN);
        for solid in &self.solids {
            let reach = match solid.shape {
                Shape::Box { half } => half.length(),
                Shape::Ball { radius } => radius,
                Shape::Capsule { to, radius } => {
                    low = low.min(to - Vec3::splat(radius));
                    high = high.max(to + Vec3::splat(radius));
                    radius
                }
            };
            low = low.min(solid.at - Vec3::splat(reach));
            high = high.max(solid.at + Vec3::splat(reach));
        }
        if low.x > high.x {
            return (Vec3::ZERO, 100.0);
        }
        let low = low.min(Vec3::new(low.x, low.y, self.ground_z));
        ((low + high) / 2.0, ((high - low).length() / 2.0).max(10.0))
    }
}

/// A point of `link`'s solids to hold it by: of their centres (a rod's
/// middle), the one farthest from its joint's axis.
pub fn grip(scene: &Scene, link: usize) -> Option<Vec3> {
    let (pivot, axis) = scene.handles.get(link)?.as_ref()?.joint?;
    scene
        .solids
        .iter()
        .filter(|solid| solid.link == link && !solid.faint)
        .map(|solid| match solid.shape {
            Shape::Capsule { to, .. } => solid.at.lerp(to, 0.5),
            _ => solid.at,
        })
        .max_by(|a, b| (*a - pivot).cross(axis).length().total_cmp(&(*b - pivot).cross(axis).length()))
}

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
const FOV: f32 = 0.6;
/// Where the light comes from (up, front, left).
const LIGHT: Vec3 = Vec3::new(0.45, 0.35, 0.82);

impl Camera {
    /// The camera that shows a scene whole in `rect`, from the front-left, a little above.
    fn fit(points: &[Vec3], rect: Rect) -> Self {
        Self { yaw: 0.6, pitch: 0.25, distance: 1000.0, target: Vec3::ZERO }.framing(points, rect)
    }

    /// This camera looking from where it looks, moved to show `points` whole
    /// in `rect` with a margin: aimed at the middle of their box and as near
    /// as the farthest-out point allows, across and up.
    fn framing(self, points: &[Vec3], rect: Rect) -> Self {
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

    fn eye(&self) -> Vec3 {
        let (sy, cy) = self.yaw.sin_cos();
        let (sp, cp) = self.pitch.sin_cos();
        self.target + Vec3::new(cp * cy, cp * sy, sp) * self.distance
    }

    /// The camera's frame: eye, right, up, forward.
    fn frame(&self) -> (Vec3, Vec3, Vec3, Vec3) {
        let eye = self.eye();
        let forward = (self.target - eye).normalize_or(Vec3::X);
        let right = forward.cross(Vec3::Z).normalize_or(Vec3::Y);
        let up = right.cross(forward);
        (eye, right, up, forward)
    }
}

/// Points of the world on the screen, for one frame.
struct Projector {
    eye: Vec3,
    right: Vec3,
    up: Vec3,
    forward: Vec3,
    focal: f32,
    center: Pos2,
}

impl Projector {
    fn new(camera: &Camera, rect: Rect) -> Self {
        let (eye, right, up, forward) = camera.frame();
        Self { eye, right, up, forward, focal: rect.height() / 2.0 / (FOV / 2.0).tan(), center: rect.center() }
    }

    /// A point on the screen and its depth; none behind the camera.
    fn point(&self, p: Vec3) -> Option<(Pos2, f32)> {
        let d = p - self.eye;
        let depth = d.dot(self.forward);
        if depth < 1.0 {
            return None;
        }
        let scale = self.focal / depth;
        Some((pos2(self.center.x + d.dot(self.right) * scale, self.center.y - d.dot(self.up) * scale), depth))
    }

    /// A length at a depth, on the screen.
    fn size(&self, length: f32, depth: f32) -> f32 {
        length * self.focal / depth
    }
}

fn shade(color: [u8; 3], normal: Vec3, faint: bool) -> Color32 {
    let light = 0.35 + 0.65 * normal.dot(LIGHT.normalize()).max(0.0);
    // Channels stay within 0..=255.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let channel = |c: u8| (f32::from(c) * light).round().clamp(0.0, 255.0) as u8;
    let [r, g, b] = color.map(channel);
    if faint { Color32::from_rgba_unmultiplied(r, g, b, 70) } else { Color32::from_rgb(r, g, b) }
}

/// A shape to paint, and how far it is.
struct Piece {
    depth: f32,
    paint: Paint,
}

/// The corners of a box solid.
fn corners(solid: &WorldSolid, half: Vec3) -> [Vec3; 8] {
    std::array::from_fn(|corner| {
        let sign = |bit: usize| if corner & (1 << bit) == 0 { -1.0 } else { 1.0 };
        solid.at + solid.rotation * Vec3::new(sign(0) * half.x, sign(1) * half.y, sign(2) * half.z)
    })
}

/// The box's faces: corner indices (counter-clockwise seen from outside) and the local normal.
const FACES: [([usize; 4], Vec3); 6] = [
    ([0, 2, 6, 4], Vec3::NEG_X),
    ([1, 5, 7, 3], Vec3::X),
    ([0, 4, 5, 1], Vec3::NEG_Y),
    ([2, 3, 7, 6], Vec3::Y),
    ([0, 1, 3, 2], Vec3::NEG_Z),
    ([4, 6, 7, 5], Vec3::Z),
];

/// The convex hull of screen points (Andrew's monotone chain), counter-clockwise.
fn hull(mut points: Vec<Pos2>) -> Vec<Pos2> {
    points.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    let cross = |o: Pos2, a: Pos2, b: Pos2| (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
    let mut lower: Vec<Pos2> = Vec::new();
    for &p in &points {
        while lower.len() >= 2 && cross(lower[lower.len() - 2], lower[lower.len() - 1], p) <= 0.0 {
            lower.pop();
        }
        lower.push(p);
    }
    let mut upper: Vec<Pos2> = Vec::new();
    for &p in points.iter().rev() {
        while upper.len() >= 2 && cross(upper[upper.len() - 2], upper[upper.len() - 1], p) <= 0.0 {
            upper.pop();
        }
        upper.push(p);
    }
    lower.pop();
    upper.pop();
    lower.extend(upper);
    lower
}

/// The projector's own camera as OpenGL matrices: the same eye, axes and field of view.
fn view_projection(camera: &Camera, rect: Rect) -> glam::Mat4 {
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

/// The colour of a selected (or hovered, `strength` less) link: toward amber.
fn tinted(color: [u8; 3], strength: f32) -> [u8; 3] {
    const AMBER: [f32; 3] = [255.0, 170.0, 40.0];
    // Channels stay within 0..=255.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let mix = |index: usize| (f32::from(color[index]) * (1.0 - strength) + AMBER[index] * strength).round() as u8;
    [mix(0), mix(1), mix(2)]
}

fn solid_pieces(solid: &WorldSolid, projector: &Projector, pieces: &mut Vec<Piece>) {
    match solid.shape {
        Shape::Box { half } => {
            let corners = corners(solid, half);
            for (indices, local_normal) in FACES {
                let normal = solid.rotation * local_normal;
                let center = indices.iter().map(|&i| corners[i]).fold(Vec3::ZERO, |s, p| s + p) / 4.0;
                if normal.dot(projector.eye - center) <= 0.0 {
                    continue;
                }
                let points: Option<Vec<Pos2>> =
                    indices.iter().map(|&i| projector.point(corners[i]).map(|(p, _)| p)).collect();
                let (Some(points), Some((_, depth))) = (points, projector.point(center)) else { continue };
                let fill = shade(solid.color, normal, solid.faint);
                pieces.push(Piece { depth, paint: Paint::convex_polygon(points, fill, Stroke::NONE) });
            }
        }
        Shape::Ball { radius } => {
            if let Some((center, depth)) = projector.point(solid.at) {
                let r = projector.size(radius, depth);
                let fill = shade(solid.color, (projector.eye - solid.at).normalize_or(Vec3::Z), solid.faint);
                pieces.push(Piece { depth, paint: Paint::circle_filled(center, r, fill) });
            }
        }
        Shape::Capsule { to, radius } => {
            let (Some((a, da)), Some((b, db))) = (projector.point(solid.at), projector.point(to)) else { return };
            let depth = (da + db) / 2.0;
            let width = projector.size(radius, depth) * 2.0;
            // Lit by how much its side faces the light.
            let along = (to - solid.at).normalize_or(Vec3::Z);
            let side = (LIGHT - along * along.dot(LIGHT)).normalize_or(Vec3::Z);
            let fill = shade(solid.color, side, solid.faint);
            pieces.push(Piece {
                depth,
                paint: Paint::Vec(vec![
                    Paint::line_segment([a, b], Stroke::new(width, fill)),
                    Paint::circle_filled(a, width / 2.0, fill),
                    Paint::circle_filled(b, width / 2.0, fill),
                ]),
            });
        }
    }
}

/// The solid's shadow on the ground (light from straight above), on the screen.
fn shadow(solid: &WorldSolid, ground: f32, projector: &Projector) -> Option<Paint> {
    let color = Color32::from_black_alpha(70);
    let flat = |p: Vec3| projector.point(Vec3::new(p.x, p.y, ground)).map(|(p, _)| p);
    match solid.shape {
        Shape::Box { half } => {
            let points: Option<Vec<Pos2>> = corners(solid, half).iter().map(|&p| flat(p)).collect();
            Some(Paint::convex_polygon(hull(points?), color, Stroke::NONE))
        }
        Shape::Ball { radius } => {
            let (center, depth) = projector.point(Vec3::new(solid.at.x, solid.at.y, ground))?;
            Some(Paint::circle_filled(center, projector.size(radius, depth), color))
        }
        Shape::Capsule { to, radius } => {
            let (a, da) = projector.point(Vec3::new(solid.at.x, solid.at.y, ground))?;
            let b = flat(to)?;
            Some(Paint::line_segment([a, b], Stroke::new(projector.size(radius, da) * 2.0, color)))
        }
    }
}

/// Ground grid lines around `center`, `radius` out, a line every `step`.
fn grid(center: Vec3, radius: f32, ground: f32, projector: &Projector, color: Color32) -> Vec<Paint> {
    let step = nice_step(radius / 4.0);
    let reach = (radius * 1.5 / step).ceil() * step;
    let (cx, cy) = ((center.x / step).round() * step, (center.y / step).round() * step);
    let mut lines = Vec::new();
    let mut offset = -reach;
    while offset <= reach + step / 2.0 {
        for (a, b) in [
            (Vec3::new(cx + offset, cy - reach, ground), Vec3::new(cx + offset, cy + reach, ground)),
            (Vec3::new(cx - reach, cy + offset, ground), Vec3::new(cx + reach, cy + offset, ground)),
        ] {
            if let (Some((a, _)), Some((b, _))) = (projector.point(a), projector.point(b)) {
                lines.push(Paint::line_segment([a, b], Stroke::new(1.0, color)));
            }
        }
        offset += step;
    }
    lines
}

/// 1, 2 or 5 times a power of ten, near `raw`.
fn nice_step(raw: f32) -> f32 {
    let power = 10f32.powf(raw.max(1e-3).log10().floor());
    let fraction = raw / power;
    let nice = if fraction < 1.5 {
        1.0
    } else if fraction < 3.5 {
        2.0
    } else if fraction < 7.5 {
        5.0
    } else {
        10.0
    };
    nice * power
}

/// The view's own state: its camera (none until it has seen a scene), the
/// joint a drag holds, where it drew last, and the meshes on the card.
#[derive(Clone, Debug, Default)]
pub struct View {
    camera: Option<Camera>,
    grab: Option<touch::Grab>,
    reach: Option<ends::Reach>,
    drawn: Option<(Camera, Rect)>,
    /// Frame the figure on the next draw.
    reframe: bool,
    /// The meshes uploaded to the graphics card (shared with the paint callback).
    card: Arc<Mutex<gpu::Card>>,
}

impl View {
    /// Where a point of the world was on the screen when last drawn.
    pub fn on_screen(&self, point: Vec3) -> Option<Pos2> {
        let (camera, rect) = self.drawn?;
        Projector::new(&camera, rect).point(point).map(|(at, _)| at)
    }

    /// The meshes, drawn by the card with a depth buffer (tinted as solids are when selected or hovered).
    fn meshes(&self, scene: &Scene, (camera, rect): (&Camera, Rect), touch: &Touch) -> egui::PaintCallback {
        let view_projection = view_projection(camera, rect);

        let items = scene
            .meshes
            .iter()
            .map(|mesh| {
                let strength = match Some(mesh.link) {
                    link if link == scene.selected => 0.55,
                    link if link == touch.hovered => 0.3,
                    _ => 0.0,
                };
                let color = tinted(mesh.color, strength).map(|c| f32::from(c) / 255.0);
                gpu::Item { mesh: Arc::clone(&mesh.mesh), model: mesh.model(), color }
            })
            .collect();
        gpu::callback(rect, view_projection, LIGHT, items, Arc::clone(&self.card))
    }

    /// Frames the whole figure on the next draw, keeping the way the camera looks from.
    pub fn frame_all(&mut self) {
        self.reframe = true;
    }

    /// Where the view was drawn last (its camera and rectangle).
    pub fn drawn(&self) -> Option<(Camera, Rect)> {
        self.drawn
    }

    /// A drag that starts on an end's ring carries its goal (ends come before links).
    fn touch_ends(&mut self, ui: &egui::Ui, response: &egui::Response, scene: &Scene, projector: &Projector) -> Touch {
        let mut touch = Touch::default();
        if scene.ends.is_empty() {
            self.reach = None;
            return touch;
        }
        touch.hovered_end = response.hover_pos().and_then(|at| ends::nearest(scene, projector, at));
        if response.drag_started()
            && let Some(origin) = ui.input(|input| input.pointer.press_origin())
            && let Some(end) = ends::nearest(scene, projector, origin).filter(|&end| !scene.ends[end].held)
        {
            self.reach = Some(ends::Reach::new(end, scene.ends[end].at, origin));
        }
        if let Some(reach) = self.reach {
            if let Some(pointer) = ui.input(|input| input.pointer.latest_pos()) {
                touch.reached = Some((reach.end, reach.goal(projector, pointer)));
            }
            touch.hovered_end = Some(reach.end);
            if !response.dragged() {
                touch.released = Some(reach.end);
                self.reach = None;
            }
        }
        touch
    }

    /// What the pointer does to a posable scene: hover, click, and a drag
    /// that started on a joint turns it (any other drag orbits).
    fn touch(&mut self, ui: &egui::Ui, response: &egui::Response, scene: &Scene, projector: &Projector) -> Touch {
        let handle = |link: usize| scene.handles.get(link).and_then(Option::as_ref);
        let under = |at: Pos2| touch::pick(scene, projector, at).filter(|(link, _)| handle(*link).is_some());
        let mut touch = self.touch_ends(ui, response, scene, projector);
        if scene.handles.is_empty() || touch.hovered_end.is_some() {
            self.grab = None;
            return touch;
        }
        touch.hovered = response.hover_pos().and_then(under).map(|(link, _)| link);
        if response.clicked() {
            touch.clicked = response.interact_pointer_pos().and_then(under).map(|(link, _)| link);
        }
        if response.drag_started()
            && let Some(origin) = ui.input(|input| input.pointer.press_origin())
            && let Some((link, point)) = under(origin)
            && let Some(joint) = handle(link).and_then(|handle| handle.joint)
        {
            self.grab = Some(touch::Grab::new(link, joint, point, origin));
        }
        if let Some(grab) = &mut self.grab {
            if let Some(pointer) = ui.input(|input| input.pointer.latest_pos()) {
                grab.drag(projector, pointer);
            }
            touch.turned = Some((grab.link, grab.total));
            touch.hovered = Some(grab.link);
            if !response.dragged() {
                touch.let_go = Some(grab.link);
                self.grab = None;
            }
        }
        touch
    }

    /// Draws `scene` filling `rect`; dragging orbits (or turns a joint of a
    /// posable scene), the wheel zooms, a double-click puts the camera back.
    /// Hovering a link with a handle names it.
    pub fn show(&mut self, ui: &mut egui::Ui, rect: Rect, scene: &Scene, label: &str) -> (egui::Response, Touch) {
        let response = ui.allocate_rect(rect, Sense::click_and_drag());
        response.widget_info(|| egui::WidgetInfo::labeled(egui::Role::Image, true, label));
        let (center, radius) = scene.bounds();
        let mut camera = self.camera.unwrap_or_else(|| Camera::fit(&scene.outline(), rect));
        let resized = self.drawn.is_some_and(|(_, drawn)| drawn.size() != rect.size());
        let frame_key = response.hovered() && ui.input(|input| input.key_pressed(egui::Key::F));
        if response.double_clicked() {
            camera = Camera::fit(&scene.outline(), rect);
        } else if self.reframe || resized || frame_key {
            camera = camera.framing(&scene.outline(), rect);
        }
        self.reframe = false;
        let touch = self.touch(ui, &response, scene, &Projector::new(&camera, rect));
        if response.dragged() && touch.turned.is_none() && touch.reached.is_none() {
            let delta = response.drag_delta();
            camera.yaw -= delta.x * 0.01;
            camera.pitch = (camera.pitch + delta.y * 0.01).clamp(-1.2, 1.45);
        }
        if response.hovered() {
            let scroll = ui.input(|input| input.smooth_scroll_delta.y);
            if scroll != 0.0 {
                camera.distance = (camera.distance * (-scroll * 0.002).exp()).clamp(radius * 0.3, radius * 40.0);
            }
        }
        self.camera = Some(camera);
        self.drawn = Some((camera, rect));
        let painter = ui.painter_at(rect);
        let visuals = ui.visuals();
        painter.rect_filled(rect, 4.0, visuals.extreme_bg_color);
        let projector = Projector::new(&camera, rect);
        painter.extend(grid(
            center,
            radius,
            scene.ground_z,
            &projector,
            visuals.widgets.noninteractive.bg_stroke.color,
        ));
        painter.extend(
            scene
                .solids
                .iter()
                .filter(|solid| !solid.faint && !scene.meshed(solid.link))
                .filter_map(|s| shadow(s, scene.ground_z, &projector)),
        );
        let mut pieces = Vec::with_capacity(scene.solids.len() * 3);
        for solid in scene.solids.iter().filter(|solid| solid.faint || !scene.meshed(solid.link)) {
            let strength = match Some(solid.link) {
                _ if solid.faint => 0.0,
                link if link == scene.selected => 0.55,
                link if link == touch.hovered => 0.3,
                _ => 0.0,
            };
            if strength > 0.0 {
                let solid = WorldSolid { color: tinted(solid.color, strength), ..*solid };
                solid_pieces(&solid, &projector, &mut pieces);
            } else {
                solid_pieces(solid, &projector, &mut pieces);
            }
        }
        // Far first: the near ones cover them (the painter's algorithm).
        pieces.sort_by(|a, b| b.depth.total_cmp(&a.depth));
        painter.extend(pieces.into_iter().map(|piece| piece.paint));
        if !scene.meshes.is_empty() {
            painter.add(self.meshes(scene, (&camera, rect), &touch));
        }
        painter.extend(ends::paint(scene, &projector, touch.hovered_end));
        if let Some(gap) = &scene.gap
            && let Some((at, _)) = projector.point(gap.to)
        {
            let color = Color32::from_rgb(225, 50, 50);
            painter.text(
                at + egui::vec2(10.0, -10.0),
                egui::Align2::LEFT_BOTTOM,
                &gap.words,
                egui::FontId::proportional(13.0),
                color,
            );
        }
        let reading = match touch.hovered_end {
            Some(end) => scene.ends.get(end).map(|end| end.reading.clone()),
            None => touch.hovered.and_then(|link| scene.handles.get(link)?.as_ref()).map(|h| h.reading.clone()),
        };
        let response = match reading {
            Some(reading) => response.on_hover_text_at_pointer(reading),
            None => response,
        };
        (response, touch)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::figure::Mat3;

    #[test]
    fn the_camera_sees_the_target_in_the_middle_and_nearer_is_bigger() {
        let camera = Camera { yaw: 0.0, pitch: 0.0, distance: 1000.0, target: Vec3::ZERO };
        let rect = Rect::from_min_size(Pos2::ZERO, egui::vec2(600.0, 600.0));
        let projector = Projector::new(&camera, rect);
        let (center, depth) = projector.point(Vec3::ZERO).unwrap();
        assert!((center - rect.center()).length() < 1e-3);
        assert!((depth - 1000.0).abs() < 1e-3);
        // Looking from +x: +y (left of the figure) is to the right on the screen, +z up.
        let (left, _) = projector.point(Vec3::new(0.0, 100.0, 0.0)).unwrap();
        let (up, _) = projector.point(Vec3::new(0.0, 0.0, 100.0)).unwrap();
        assert!(left.x > center.x && up.y < center.y);
        let near = projector.size(10.0, 500.0);
        assert!(near > projector.size(10.0, 1000.0));
        assert!(projector.point(Vec3::new(2000.0, 0.0, 0.0)).is_none(), "behind the camera");
    }

    #[test]
    fn a_box_shows_at_most_three_faces_and_the_hull_of_its_shadow_is_convex() {
        let camera = Camera { yaw: 0.6, pitch: 0.4, distance: 500.0, target: Vec3::ZERO };
        let rect = Rect::from_min_size(Pos2::ZERO, egui::vec2(400.0, 400.0));
        let projector = Projector::new(&camera, rect);
        let solid = WorldSolid {
            at: Vec3::ZERO,
            rotation: Mat3::IDENTITY,
            shape: Shape::Box { half: Vec3::splat(20.0) },
            color: [200, 200, 200],
            faint: false,
            link: 0,
        };
        let mut pieces = Vec::new();
        solid_pieces(&solid, &projector, &mut pieces);
        assert_eq!(pieces.len(), 3);
        let points: Vec<Pos2> =
            corners(&solid, Vec3::splat(20.0)).iter().map(|&p| projector.point(p).unwrap().0).collect();
        let outline = hull(points);
        assert!((4..=6).contains(&outline.len()), "{}", outline.len());
        assert_eq!(nice_step(37.0), 50.0);
        assert_eq!(nice_step(0.18), 0.2);
    }

    #[test]
    fn the_card_sees_a_mesh_where_the_painter_draws_the_solids() {
        // The matrices handed to OpenGL put a point on the same pixel as the projector does.
        let camera = Camera { yaw: 0.8, pitch: 0.35, distance: 700.0, target: Vec3::new(10.0, -20.0, 150.0) };
        let rect = Rect::from_min_size(pos2(40.0, 30.0), egui::vec2(500.0, 320.0));
        let projector = Projector::new(&camera, rect);
        let view = View::default();
        let scene = Scene {
            meshes: vec![SceneMesh {
                link: 0,
                mesh: Arc::new(Mesh::default()),
                place: Placed::ORIGIN,
                scale: 1.0,
                color: [0; 3],
            }],
            ..Scene::default()
        };
        let callback = view.meshes(&scene, (&camera, rect), &Touch::default());
        assert_eq!(callback.rect, rect);
        let view_projection = view_projection(&camera, rect);
        for point in [Vec3::ZERO, Vec3::new(100.0, 50.0, 300.0), Vec3::new(-80.0, 120.0, 20.0)] {
            let clip = view_projection * point.extend(1.0);
            let ndc = clip.truncate() / clip.w;
            let pixel =
                pos2(rect.center().x + ndc.x * rect.width() / 2.0, rect.center().y - ndc.y * rect.height() / 2.0);
            let (drawn, depth) = projector.point(point).unwrap();
            assert!(pixel.distance(drawn) < 0.05, "{point}: {pixel:?} vs {drawn:?}");
            assert!(ndc.z > -1.0 && ndc.z < 1.0 && (clip.w - depth).abs() < 1e-2);
        }
    }
}
