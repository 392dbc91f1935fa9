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

mod camera;
mod ends;
mod gpu;
mod mesh_files;
mod paint;
pub mod posing;
mod touch;

use egui::{Color32, Pos2, Rect, Sense};

use std::sync::{Arc, Mutex};

use crate::figure::mesh::Mesh;
use crate::figure::{Placed, Shape, Vec3, WorldSolid};
pub use camera::Camera;
use camera::{LIGHT, Projector, view_projection};
pub use ends::{End, Gap};
pub use mesh_files::MeshFiles;
use paint::{corners, grid, hull, shadow, solid_pieces, tinted};
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

    /// This frame's camera: framed when first drawn, asked to (F, the button)
    /// or resized, put back by a double-click; turned by a drag that holds no
    /// joint or end, zoomed by the wheel. What the pointer did to the figure too.
    fn camera(
        &mut self,
        ui: &egui::Ui,
        (response, rect): (&egui::Response, Rect),
        scene: &Scene,
        radius: f32,
    ) -> (Camera, Touch) {
        let mut camera = self.camera.unwrap_or_else(|| Camera::fit(&scene.outline(), rect));
        let resized = self.drawn.is_some_and(|(_, drawn)| drawn.size() != rect.size());
        let frame_key = response.hovered() && ui.input(|input| input.key_pressed(egui::Key::F));
        if response.double_clicked() {
            camera = Camera::fit(&scene.outline(), rect);
        } else if self.reframe || resized || frame_key {
            camera = camera.framing(&scene.outline(), rect);
        }
        self.reframe = false;
        let touch = self.touch(ui, response, scene, &Projector::new(&camera, rect));
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
        (camera, touch)
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
        if scene.handles.is_empty() {
            self.grab = None;
            return touch;
        }
        if self.grab.is_some() {
            // A drag that holds a joint holds it to the end, whatever it
            // passes over (a ring, another link, the empty view): one drag,
            // one turn, one undo step.
            touch.hovered_end = None;
        } else if touch.hovered_end.is_some() {
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
        let (camera, touch) = self.camera(ui, (&response, rect), scene, radius);
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
    use egui::pos2;

    use super::paint::nice_step;
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

    #[test]
    fn frame_all_fits_every_corner_of_the_figure_in_the_view_at_any_shape_keeping_the_orbit() {
        let chain = crate::figure::plen2::chain();
        let solids = chain.dress(&chain.pose(&[0.0; 19]), false);
        let scene = Scene { solids, ..Scene::default() };
        let outline = scene.outline();
        for (w, h) in [(380.0, 640.0), (900.0, 300.0), (300.0, 300.0), (1200.0, 900.0)] {
            let rect = Rect::from_min_size(pos2(10.0, 20.0), egui::vec2(w, h));
            let turned = Camera { yaw: -2.1, pitch: 0.7, distance: 5.0, target: Vec3::ZERO };
            for camera in [Camera::fit(&outline, rect), turned.framing(&outline, rect)] {
                let projector = Projector::new(&camera, rect);
                let mut touches = 0;
                for point in &outline {
                    let (at, _) = projector.point(*point).expect("in front of the camera");
                    assert!(rect.contains(at), "{w}x{h}: {point} at {at:?} outside {rect:?}");
                    let near_edge = (at.x - rect.left()).min(rect.right() - at.x) < 0.1 * w
                        || (at.y - rect.top()).min(rect.bottom() - at.y) < 0.1 * h;
                    touches += usize::from(near_edge);
                }
                assert!(touches > 0, "{w}x{h}: framed, not lost in the middle");
            }
            let framed = turned.framing(&outline, rect);
            assert_eq!((framed.yaw, framed.pitch), (turned.yaw, turned.pitch), "the orbit is kept");
        }
    }
}
