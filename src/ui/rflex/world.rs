//! The base seen from above, in the world its odometry describes: the
//! footprint at its pose with its heading, the bump panels lit on its edge,
//! each sonar's cone and echo where they are, the echoes heard so far as a
//! fading map, and the driven path. Drag to pan, wheel to zoom, double-click
//! to centre on the base again; following keeps the base in the middle.

// Screen coordinates are f32: drawing an f64 quantity loses nothing visible.
#![allow(clippy::cast_possible_truncation)]

use egui::{Color32, Pos2, Rect, Sense, Shape, Stroke, pos2, vec2};

use crate::device::rflex::{
    Bumps, ECHO_CELL_M, EchoMap, FORGET_AFTER_S, Layout, Odometry, SONAR_REACH_M, Telemetry, echo_point, mount_point,
};
use crate::ui::action::Action;
use crate::ui::i18n::Strings;
use crate::ui::plot;
use crate::ui::rflex::action::RflexAction;
use crate::ui::rflex::captions::RflexWords;

/// Metres a point stands for at the start (6 m across a 600-point view).
const START_SCALE: f64 = 0.01;
/// Half the angle a sonar's cone covers, radians (a B21r ring's 15° spacing).
const CONE_HALF_RAD: f64 = std::f64::consts::PI / 24.0;
/// The body drawn before the robot's layout is known, metres.
const DEFAULT_RADIUS_M: f64 = 0.26;

const ECHO: Color32 = Color32::from_rgb(40, 170, 220);
const PRESSED: Color32 = Color32::from_rgb(230, 50, 40);

/// The view's camera.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WorldView {
    /// The world point at the view's centre, metres.
    pub center: [f64; 2],
    /// Metres a point stands for.
    pub metres_per_point: f64,
    /// Whether the view keeps the base in its middle.
    pub follow: bool,
}

impl Default for WorldView {
    fn default() -> Self {
        Self { center: [0.0, 0.0], metres_per_point: START_SCALE, follow: true }
    }
}

/// From world metres to the screen, for one frame.
#[derive(Clone, Copy, Debug)]
struct Frame {
    rect: Rect,
    center: [f64; 2],
    metres_per_point: f64,
}

impl Frame {
    fn screen(&self, [x, y]: [f64; 2]) -> Pos2 {
        let c = self.rect.center();
        pos2(
            c.x + ((x - self.center[0]) / self.metres_per_point) as f32,
            c.y - ((y - self.center[1]) / self.metres_per_point) as f32,
        )
    }

    fn points(&self, metres: f64) -> f32 {
        (metres / self.metres_per_point) as f32
    }

    /// The world's visible box, metres: (min, max).
    fn visible(&self) -> ([f64; 2], [f64; 2]) {
        let half = [
            f64::from(self.rect.width()) / 2.0 * self.metres_per_point,
            f64::from(self.rect.height()) / 2.0 * self.metres_per_point,
        ];
        ([self.center[0] - half[0], self.center[1] - half[1]], [self.center[0] + half[0], self.center[1] + half[1]])
    }
}

/// A point `reach` metres from `pose` along `bearing` (relative to its heading).
fn around(pose: &Odometry, bearing: f64, reach: f64) -> [f64; 2] {
    let angle = pose.theta_rad + bearing;
    [pose.x_m + reach * angle.cos(), pose.y_m + reach * angle.sin()]
}

impl WorldView {
    /// Draws the world in `rect`; `label` names it for screen readers.
    pub fn show(&mut self, ui: &mut egui::Ui, rect: Rect, telemetry: &Telemetry, label: &str) -> egui::Response {
        let response = ui.allocate_rect(rect, Sense::click_and_drag());
        response.widget_info(|| egui::WidgetInfo::labeled(egui::Role::Image, true, label));
        if response.double_clicked() {
            *self = Self::default();
        }
        if response.dragged() {
            let delta = response.drag_delta();
            self.center[0] -= f64::from(delta.x) * self.metres_per_point;
            self.center[1] += f64::from(delta.y) * self.metres_per_point;
            self.follow = false;
        }
        if response.hovered() {
            let scroll = ui.input(|input| input.smooth_scroll_delta.y);
            if scroll != 0.0 {
                self.metres_per_point = (self.metres_per_point * f64::from((-scroll / 200.0).exp())).clamp(0.001, 0.2);
            }
        }
        let pose = telemetry.pose;
        if self.follow {
            self.center = [pose.x_m, pose.y_m];
        }
        let frame = Frame { rect, center: self.center, metres_per_point: self.metres_per_point };
        let painter = ui.painter_at(rect);
        let visuals = ui.visuals();
        painter.rect_filled(rect, 0.0, visuals.extreme_bg_color);
        grid(&painter, &frame, visuals.widgets.noninteractive.bg_stroke.color);
        echoes(&painter, &frame, &telemetry.echoes);
        // The driven path, a point per pixel at most.
        let path = plot::thin_path(telemetry.path.iter(), [self.metres_per_point; 2]);
        let path: Vec<Pos2> = path.into_iter().map(|point| frame.screen(point)).collect();
        if path.len() > 1 {
            painter.add(Shape::line(path, Stroke::new(1.5, visuals.weak_text_color())));
        }
        sonar(&painter, &frame, telemetry);
        base(&painter, &frame, telemetry, visuals);
        scale_bar(&painter, &frame, visuals.text_color());
        response
    }
}

/// The world view with its controls above it, filling what is left of `ui`.
pub fn panel(
    ui: &mut egui::Ui,
    view: &mut WorldView,
    telemetry: Option<&Telemetry>,
    words: &Strings,
    actions: &mut Vec<Action>,
) {
    ui.horizontal(|ui| {
        ui.heading(words.rflex().world_view);
        ui.checkbox(&mut view.follow, words.rflex().follow);
        if ui.add_enabled(telemetry.is_some(), egui::Button::new(words.rflex().clear_map)).clicked() {
            actions.push(Action::family(RflexAction::ClearMap));
        }
    });
    ui.label(egui::RichText::new(words.rflex().world_hint).weak());
    match telemetry {
        Some(telemetry) => {
            let rect = ui.available_rect_before_wrap();
            view.show(ui, rect, telemetry, words.rflex().world_view);
        }
        None => {
            ui.label(words.not_connected);
        }
    }
}

/// Lines every metre (every 0.5 m when zoomed in, every 5 m far out).
fn grid(painter: &egui::Painter, frame: &Frame, color: Color32) {
    let step = [0.5, 1.0, 5.0, 10.0].into_iter().find(|step| frame.points(*step) >= 24.0).unwrap_or(10.0);
    let (min, max) = frame.visible();
    let stroke = Stroke::new(1.0, color.gamma_multiply(0.6));
    let mut x = (min[0] / step).ceil() * step;
    while x <= max[0] {
        let top = frame.screen([x, max[1]]);
        painter.line_segment([top, pos2(top.x, frame.rect.bottom())], stroke);
        x += step;
    }
    let mut y = (min[1] / step).ceil() * step;
    while y <= max[1] {
        let left = frame.screen([min[0], y]);
        painter.line_segment([left, pos2(frame.rect.right(), left.y)], stroke);
        y += step;
    }
}

/// The map: a square per cell, fading with age — one mesh for them all (a
/// shape per cell would cost its own tessellation, thousands a frame).
fn echoes(painter: &egui::Painter, frame: &Frame, map: &EchoMap) {
    let side = frame.points(ECHO_CELL_M).max(2.0);
    let half = vec2(side, side) / 2.0;
    let area = frame.rect.expand(side);
    let mut mesh = egui::Mesh::default();
    for (point, age) in map.points() {
        let centre = frame.screen(point);
        if !area.contains(centre) {
            continue;
        }
        let alpha = (1.0 - age / FORGET_AFTER_S).clamp(0.15, 1.0) as f32;
        mesh.add_colored_rect(Rect::from_min_max(centre - half, centre + half), ECHO.gamma_multiply(alpha * 0.8));
    }
    painter.add(Shape::mesh(mesh));
}

/// Each sonar's cone from its transducer's mount to its echo (faint to its
/// reach when it hears nothing), along the transducer's own bearing: both
/// rings of a B21r, an ATRV-Jr's four sides, a Magellan's ring.
fn sonar(painter: &egui::Painter, frame: &Frame, telemetry: &Telemetry) {
    let Some(layout) = telemetry.layout() else { return };
    let pose = &telemetry.pose;
    for (&id, &range) in &telemetry.sonar_m {
        let Some(transducer) = layout.transducer(id) else { continue };
        let (reach, fill) = match range {
            Some(metres) => (metres, ECHO.gamma_multiply(0.18)),
            None => (SONAR_REACH_M, ECHO.gamma_multiply(0.05)),
        };
        let mount = mount_point(pose, &transducer);
        let mut points = vec![frame.screen(mount)];
        for step in 0..=4 {
            let offset = -CONE_HALF_RAD + f64::from(step) * CONE_HALF_RAD / 2.0;
            let angle = pose.theta_rad + transducer.bearing_rad + offset;
            points.push(frame.screen([mount[0] + reach * angle.cos(), mount[1] + reach * angle.sin()]));
        }
        painter.add(Shape::convex_polygon(points, fill, Stroke::NONE));
        if let Some(metres) = range {
            painter.circle_filled(frame.screen(echo_point(pose, &transducer, metres)), 3.0, ECHO);
        }
    }
}

/// Where each bumper is drawn: (its DIO address, the bits that say it is pressed,
/// its middle bearing, the ring it sits on as a multiple of the body's radius).
/// Choice (rflex.md §6 gives addresses, not places): a B21r's six body panels
/// round the body from ahead, clockwise, and its eight base panels round a
/// ring outside them; a Magellan's sixteen bumpers round its body from ahead.
fn bumper_arcs(layout: &Layout) -> Vec<(u16, u16, f64, f64)> {
    let around = |index: u16, of: u16| -f64::from(index) * std::f64::consts::TAU / f64::from(of.max(1));
    match layout.bumps {
        Bumps::Panels { first, count } => {
            let body = count.min(6);
            (0..count)
                .map(|k| {
                    let (index, of, ring) = if k < body { (k, body, 1.0) } else { (k - body, count - body, 1.25) };
                    (first + k, 0x0f, around(index, of), ring)
                })
                .collect()
        }
        Bumps::Bits { first, bytes } => {
            let count = bytes * 8;
            (0..count).map(|k| (first + k / 8, 1 << (k % 8), around(k, count), 1.0)).collect()
        }
        Bumps::None => Vec::new(),
    }
}

/// The footprint, its heading and its bumpers, lit when pressed.
fn base(painter: &egui::Painter, frame: &Frame, telemetry: &Telemetry, visuals: &egui::Visuals) {
    let pose = &telemetry.pose;
    let body_m = telemetry.layout().map_or(DEFAULT_RADIUS_M, |layout| layout.body_radius_m);
    let centre = frame.screen([pose.x_m, pose.y_m]);
    let radius = frame.points(body_m).max(4.0);
    painter.circle(centre, radius, visuals.widgets.inactive.bg_fill, Stroke::new(1.0, visuals.text_color()));
    let nose = frame.screen(around(pose, 0.0, body_m * 0.9));
    painter.arrow(centre, nose - centre, Stroke::new(2.5, visuals.text_color()));
    let Some(layout) = telemetry.layout() else { return };
    let arcs = bumper_arcs(layout);
    // Each arc covers 85 % of its share of the ring.
    #[allow(clippy::cast_precision_loss)]
    let half_span = std::f64::consts::PI / (arcs.len().max(1) as f64).min(8.0) * 0.85;
    for (address, bits, middle, ring) in arcs {
        let pressed = telemetry.bumpers.get(&address).is_some_and(|data| data & bits != 0);
        let arc: Vec<Pos2> = (0..=8)
            .map(|step| {
                let bearing = middle - half_span / 2.0 + f64::from(step) * half_span / 8.0;
                frame.screen(around(pose, bearing, body_m * ring + frame.metres_per_point * 4.0))
            })
            .collect();
        let stroke = if pressed {
            Stroke::new(5.0, PRESSED)
        } else {
            Stroke::new(3.0, visuals.widgets.noninteractive.bg_stroke.color)
        };
        painter.add(Shape::line(arc, stroke));
    }
}

/// A bar one metre long (or the nearest round length that fits) in the lower left corner.
fn scale_bar(painter: &egui::Painter, frame: &Frame, color: Color32) {
    let metres = [0.25, 0.5, 1.0, 2.0, 5.0, 10.0].into_iter().find(|m| frame.points(*m) >= 60.0).unwrap_or(10.0);
    let start = frame.rect.left_bottom() + vec2(12.0, -14.0);
    let end = start + vec2(frame.points(metres), 0.0);
    let stroke = Stroke::new(2.0, color);
    painter.line_segment([start, end], stroke);
    painter.line_segment([start, start - vec2(0.0, 5.0)], stroke);
    painter.line_segment([end, end - vec2(0.0, 5.0)], stroke);
    painter.text(
        end + vec2(6.0, 0.0),
        egui::Align2::LEFT_CENTER,
        format!("{metres} m"),
        egui::FontId::default(),
        color,
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_frame_puts_north_up_and_the_centre_in_the_middle() {
        let frame = Frame {
            rect: Rect::from_min_size(Pos2::ZERO, vec2(600.0, 400.0)),
            center: [1.0, 1.0],
            metres_per_point: 0.01,
        };
        assert_eq!(frame.screen([1.0, 1.0]), pos2(300.0, 200.0));
        // A metre east is 100 points right; a metre north, 100 points up.
        assert_eq!(frame.screen([2.0, 2.0]), pos2(400.0, 100.0));
        let (min, max) = frame.visible();
        assert!((min[0] + 2.0).abs() < 1e-9 && (max[1] - 3.0).abs() < 1e-9, "{min:?} {max:?}");
    }
}
