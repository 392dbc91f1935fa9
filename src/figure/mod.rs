//! A robot as a posed figure: a kinematic chain of links, each turning about
//! one axis at its joint, dressed in simple solids (boxes, balls, capsules).
//! The PLEN2's chain comes from the official Motion Editor's model
//! ([`plen2`]); a servo board robot's from the rig its project gives
//! ([`rig`]). Pure geometry: the editor draws what [`Chain::dress`] returns,
//! tests compare its points. Frames: x forward, y left, z up.

pub mod ik;
pub mod mesh;
pub mod plen2;
pub mod rig;

pub use glam::{Mat3, Vec3};

/// A solid's shape, in its link's frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shape {
    /// A box of these half extents, axis-aligned in the link's frame.
    Box {
        /// Half its size along x, y, z.
        half: Vec3,
    },
    /// A ball.
    Ball {
        /// Its radius.
        radius: f32,
    },
    /// A rod with round ends, from the solid's centre to `to`.
    Capsule {
        /// The other end, in the link's frame.
        to: Vec3,
        /// Its radius.
        radius: f32,
    },
}

/// A solid fixed to a link.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Solid {
    /// Its centre (a capsule's first end), in the link's frame.
    pub at: Vec3,
    /// Its shape.
    pub shape: Shape,
    /// Its colour (linear-ish sRGB, shaded when drawn).
    pub color: [u8; 3],
}

/// One link: where its joint sits on its parent, and the axis it turns about.
#[derive(Clone, Debug, PartialEq)]
pub struct Link {
    /// Its name (a PLEN2 joint's, a servo's caption).
    pub name: String,
    /// The link it is mounted on (earlier in the chain); none: the root.
    pub parent: Option<usize>,
    /// Its joint's place in the parent's frame.
    pub offset: Vec3,
    /// The axis it turns about, in its own frame (zero: it does not turn).
    pub axis: Vec3,
    /// What it looks like.
    pub solids: Vec<Solid>,
}

/// A link's place in the world: its joint's position and its frame's rotation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placed {
    /// The joint's position.
    pub position: Vec3,
    /// The link's frame.
    pub rotation: Mat3,
}

/// A solid placed in the world.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WorldSolid {
    /// Its centre (a capsule's first end).
    pub at: Vec3,
    /// Its frame (a box's axes).
    pub rotation: Mat3,
    /// Its shape (a capsule's `to` in world coordinates).
    pub shape: Shape,
    /// Its colour.
    pub color: [u8; 3],
    /// Drawn faint: a ghost of another pose.
    pub faint: bool,
    /// The link it is fixed to (its index in the chain).
    pub link: usize,
}

/// Links, each after its parent.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Chain {
    /// The links; a parent always comes before its children.
    pub links: Vec<Link>,
}

impl Placed {
    /// At the origin, turned as the world.
    pub const ORIGIN: Self = Self { position: Vec3::ZERO, rotation: Mat3::IDENTITY };

    /// This frame seen from `frame` (`frame` ∘ result = self).
    pub fn relative_to(&self, frame: &Self) -> Self {
        let back = frame.rotation.transpose();
        Self { position: back * (self.position - frame.position), rotation: back * self.rotation }
    }

    /// A frame given in this one, in the world.
    pub fn then(&self, inner: &Self) -> Self {
        Self { position: self.position + self.rotation * inner.position, rotation: self.rotation * inner.rotation }
    }
}

impl Chain {
    /// Every link placed for `angles` (radians, one per link, missing ones 0).
    pub fn pose(&self, angles: &[f32]) -> Vec<Placed> {
        self.pose_from(Placed::ORIGIN, angles)
    }

    /// Every link placed for `angles`, the root's parent frame at `base` (a
    /// figure standing on a planted foot, a pelvis dragged).
    pub fn pose_from(&self, base: Placed, angles: &[f32]) -> Vec<Placed> {
        let mut placed: Vec<Placed> = Vec::with_capacity(self.links.len());
        for (index, link) in self.links.iter().enumerate() {
            let parent = link.parent.and_then(|parent| placed.get(parent)).copied();
            let base = parent.unwrap_or(base);
            let angle = angles.get(index).copied().unwrap_or(0.0);
            let turn = if link.axis == Vec3::ZERO || angle == 0.0 {
                Mat3::IDENTITY
            } else {
                Mat3::from_axis_angle(link.axis.normalize(), angle)
            };
            placed
                .push(Placed { position: base.position + base.rotation * link.offset, rotation: base.rotation * turn });
        }
        placed
    }

    /// The solids of every link, placed.
    pub fn dress(&self, placed: &[Placed], faint: bool) -> Vec<WorldSolid> {
        let mut solids = Vec::new();
        for (index, (link, place)) in self.links.iter().zip(placed).enumerate() {
            for solid in &link.solids {
                let at = place.position + place.rotation * solid.at;
                let shape = match solid.shape {
                    Shape::Capsule { to, radius } => {
                        Shape::Capsule { to: place.position + place.rotation * to, radius }
                    }
                    shape => shape,
                };
                solids.push(WorldSolid { at, rotation: place.rotation, shape, color: solid.color, faint, link: index });
            }
        }
        solids
    }

    /// Where `link`'s joint is and the axis it turns about (world, unit), in
    /// the pose `placed`; none for a link that does not turn.
    pub fn joint(&self, placed: &[Placed], link: usize) -> Option<(Vec3, Vec3)> {
        let axis = self.links.get(link)?.axis;
        let place = placed.get(link)?;
        (axis != Vec3::ZERO).then(|| (place.position, (place.rotation * axis).normalize()))
    }

    /// The index of the link named `name`.
    pub fn link(&self, name: &str) -> Option<usize> {
        self.links.iter().position(|link| link.name == name)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_joint_turns_its_link_and_everything_mounted_on_it() {
        // An arm along x: shoulder at the origin turning about z, elbow 100 along x.
        let chain = Chain {
            links: vec![
                Link { name: "shoulder".into(), parent: None, offset: Vec3::ZERO, axis: Vec3::Z, solids: Vec::new() },
                Link {
                    name: "elbow".into(),
                    parent: Some(0),
                    offset: Vec3::new(100.0, 0.0, 0.0),
                    axis: Vec3::Z,
                    solids: vec![Solid {
                        at: Vec3::ZERO,
                        shape: Shape::Capsule { to: Vec3::new(50.0, 0.0, 0.0), radius: 5.0 },
                        color: [200, 200, 200],
                    }],
                },
            ],
        };
        let quarter = std::f32::consts::FRAC_PI_2;
        let placed = chain.pose(&[quarter, quarter]);
        assert!((placed[1].position - Vec3::new(0.0, 100.0, 0.0)).length() < 1e-4);
        let solids = chain.dress(&placed, false);
        let Shape::Capsule { to, .. } = solids[0].shape else { panic!() };
        assert!((to - Vec3::new(-50.0, 100.0, 0.0)).length() < 1e-4, "{to}");
    }
}
