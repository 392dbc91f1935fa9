//! What the painter draws of a figure: flat-shaded boxes (their visible
//! faces), balls and rods as pieces sorted far to near, their shadows on the
//! ground, and the ground's grid.

use egui::{Color32, Pos2, Shape as Paint, Stroke};

use super::camera::{LIGHT, Projector};
use crate::figure::{Shape, Vec3, WorldSolid};

pub(super) fn shade(color: [u8; 3], normal: Vec3, faint: bool) -> Color32 {
    let light = 0.35 + 0.65 * normal.dot(LIGHT.normalize()).max(0.0);
    // Channels stay within 0..=255.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let channel = |c: u8| (f32::from(c) * light).round().clamp(0.0, 255.0) as u8;
    let [r, g, b] = color.map(channel);
    if faint { Color32::from_rgba_unmultiplied(r, g, b, 70) } else { Color32::from_rgb(r, g, b) }
}

/// A shape to paint, and how far it is.
pub(super) struct Piece {
    pub(super) depth: f32,
    pub(super) paint: Paint,
}

/// The corners of a box solid.
pub(super) fn corners(solid: &WorldSolid, half: Vec3) -> [Vec3; 8] {
    std::array::from_fn(|corner| {
        let sign = |bit: usize| if corner & (1 << bit) == 0 { -1.0 } else { 1.0 };
        solid.at + solid.rotation * Vec3::new(sign(0) * half.x, sign(1) * half.y, sign(2) * half.z)
    })
}

/// The box's faces: corner indices (counter-clockwise seen from outside) and the local normal.
pub(super) const FACES: [([usize; 4], Vec3); 6] = [
    ([0, 2, 6, 4], Vec3::NEG_X),
    ([1, 5, 7, 3], Vec3::X),
    ([0, 4, 5, 1], Vec3::NEG_Y),
    ([2, 3, 7, 6], Vec3::Y),
    ([0, 1, 3, 2], Vec3::NEG_Z),
    ([4, 6, 7, 5], Vec3::Z),
];

/// The convex hull of screen points (Andrew's monotone chain), counter-clockwise.
pub(super) fn hull(mut points: Vec<Pos2>) -> Vec<Pos2> {
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

/// The colour of a selected (or hovered, `strength` less) link: toward amber.
pub(super) fn tinted(color: [u8; 3], strength: f32) -> [u8; 3] {
    const AMBER: [f32; 3] = [255.0, 170.0, 40.0];
    // Channels stay within 0..=255.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let mix = |index: usize| (f32::from(color[index]) * (1.0 - strength) + AMBER[index] * strength).round() as u8;
    [mix(0), mix(1), mix(2)]
}

pub(super) fn solid_pieces(solid: &WorldSolid, projector: &Projector, pieces: &mut Vec<Piece>) {
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
pub(super) fn shadow(solid: &WorldSolid, ground: f32, projector: &Projector) -> Option<Paint> {
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
pub(super) fn grid(center: Vec3, radius: f32, ground: f32, projector: &Projector, color: Color32) -> Vec<Paint> {
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
pub(super) fn nice_step(raw: f32) -> f32 {
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
