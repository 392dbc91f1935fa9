//! Posing a limb by its end (inverse kinematics): a hand or a foot is put
//! where the user drags it, and the limb's joints turn to reach it, each
//! within its limits.
//!
//! The method is damped least squares in its Levenberg–Marquardt form: each
//! step solves `(J Jᵀ + λ² I) y = e`, turns by `Jᵀ y`, clamps every joint to
//! its limits, and keeps the step only if the error fell (else λ grows). It
//! was chosen over FABRIK because the limbs are chains of single-axis servos
//! with hard limits and (the PLEN2's legs) six joints that must hold the
//! foot's orientation too: the Jacobian speaks of axes and orientation
//! directly, FABRIK of points and ball joints, which would need projecting
//! back onto each axis and its limits after every pass. Damping keeps a
//! straight knee (a singular pose) from throwing the leg about.
//!
//! From the current pose first (a drag moves a little each frame, so the
//! limb follows without jumping); only if that stalls, from home and a few
//! fixed spreads of the limits. What it cannot reach it comes nearest to,
//! and says how far off it stayed.

use super::{Chain, Mat3, Placed, Vec3};

/// A limb: the joints from its root to its end, and the point of its end held.
#[derive(Clone, Debug, PartialEq)]
pub struct Limb {
    /// What it is called (a hand, a foot; hover names it and its joints).
    pub name: String,
    /// The links whose joints move it, root first; the last is the end.
    pub joints: Vec<usize>,
    /// The point held, in the end link's frame (a sole's middle, a hand's tip).
    pub tip: Vec3,
}

impl Limb {
    /// The end link.
    pub fn end(&self) -> Option<usize> {
        self.joints.last().copied()
    }

    /// Where its tip is and how its end is turned, in the pose `placed`.
    pub fn reach(&self, placed: &[Placed]) -> Option<Placed> {
        let end = placed.get(self.end()?)?;
        Some(Placed { position: end.position + end.rotation * self.tip, rotation: end.rotation })
    }
}

/// Where to put a limb's end.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Goal {
    /// The tip at this point, the end turned however it must.
    Reach(Vec3),
    /// The tip at this point and the end turned so (a foot kept flat).
    Hold(Placed),
}

impl Goal {
    fn position(&self) -> Vec3 {
        match self {
            Self::Reach(at) => *at,
            Self::Hold(placed) => placed.position,
        }
    }
}

/// What solving came to.
#[derive(Clone, Debug, PartialEq)]
pub struct Solution {
    /// Every link's angle (radians): the limb's solved, the others as they were.
    pub angles: Vec<f32>,
    /// How far the tip stayed from the goal (the chain's units).
    pub gap: f32,
    /// How far the end stayed turned from the goal's (radians; 0 for a reach).
    pub twist: f32,
}

impl Solution {
    /// Whether the goal was met within `gap` (units) and `twist` (radians).
    pub fn reached(&self, gap: f32, twist: f32) -> bool {
        self.gap <= gap && self.twist <= twist
    }
}

/// A joint's limits (radians), by link index; a link not listed turns freely.
pub type Limits = [(f32, f32)];

/// How many units a radian of twist weighs against a unit of distance.
const TWIST_WEIGHT: f32 = 100.0;
/// Steps per start.
const STEPS: usize = 100;
/// Starts besides the current pose, when that one stalls.
const SEEDS: usize = 48;
/// Closer than this (units, radians) is there.
const CLOSE: (f32, f32) = (0.05, 0.000_5);

/// The angles that put `limb`'s end at `goal`, starting from `angles`, with
/// the chain's root placed at `base`.
pub fn solve(chain: &Chain, base: Placed, angles: &[f32], limb: &Limb, goal: Goal, limits: &Limits) -> Solution {
    let start: Vec<f32> =
        (0..chain.links.len()).map(|i| clamp(angles.get(i).copied().unwrap_or(0.0), limits, i)).collect();
    let mut best = descend(chain, base, start.clone(), limb, goal, limits);
    if best.reached(CLOSE.0 * 4.0, CLOSE.1 * 4.0) {
        return best;
    }
    if beyond_reach(chain, base, &start, limb, goal) {
        return best;
    }
    // Stalled (a limit, a fold the wrong way): from home, then from spreads of the limits.
    let mut walk = 0x2545_f491_4f6c_dd1d_u64;
    for seed in 0..SEEDS {
        let mut from = start.clone();
        for &link in &limb.joints {
            let (low, high) = limits.get(link).copied().unwrap_or((-std::f32::consts::PI, std::f32::consts::PI));
            from[link] = if seed == 0 { 0.0_f32.clamp(low, high) } else { low + (high - low) * next_unit(&mut walk) };
        }
        let tried = descend(chain, base, from, limb, goal, limits);
        if error(&tried) < error(&best) {
            best = tried;
        }
        if best.reached(CLOSE.0 * 4.0, CLOSE.1 * 4.0) {
            break;
        }
    }
    best
}

#[cfg(test)]
/// Where each of `limbs`' ends is in the pose `angles` with the root at
/// `base`: what planting them holds.
pub fn plant(chain: &Chain, base: Placed, angles: &[f32], limbs: &[&Limb]) -> Vec<Placed> {
    let placed = chain.pose_from(base, angles);
    limbs.iter().filter_map(|limb| limb.reach(&placed)).collect()
}

/// Keeps planted ends where they were planted while the root is at `base`
/// (the pelvis dragged over planted feet): the angles that do, from `angles`.
pub fn keep_planted(
    chain: &Chain,
    base: Placed,
    angles: &[f32],
    planted: &[(&Limb, Placed)],
    limits: &Limits,
) -> Solution {
    let mut solution = Solution { angles: angles.to_vec(), gap: 0.0, twist: 0.0 };
    for (limb, held) in planted {
        let solved = solve(chain, base, &solution.angles, limb, Goal::Hold(*held), limits);
        solution.gap = solution.gap.max(solved.gap);
        solution.twist = solution.twist.max(solved.twist);
        solution.angles = solved.angles;
    }
    solution
}

/// The goal as seen in a mirror across the body's middle (y negated): the
/// twin limb's goal when posing symmetrically.
pub fn mirrored(goal: Goal) -> Goal {
    let flip = Mat3::from_diagonal(Vec3::new(1.0, -1.0, 1.0));
    let point = |p: Vec3| Vec3::new(p.x, -p.y, p.z);
    match goal {
        Goal::Reach(at) => Goal::Reach(point(at)),
        Goal::Hold(placed) => {
            Goal::Hold(Placed { position: point(placed.position), rotation: flip * placed.rotation * flip })
        }
    }
}

/// A fixed pseudo-random walk (xorshift): a fraction in 0..1, the same every run.
fn next_unit(state: &mut u64) -> f32 {
    *state ^= *state << 13;
    *state ^= *state >> 7;
    *state ^= *state << 17;
    // 24 bits, as a fraction.
    #[allow(clippy::cast_precision_loss)]
    let fraction = (*state >> 40) as f32 / (1u64 << 24) as f32;
    fraction
}

/// Whether the goal lies farther from the limb's first joint than the limb
/// is long: no start would reach it.
fn beyond_reach(chain: &Chain, base: Placed, angles: &[f32], limb: &Limb, goal: Goal) -> bool {
    let placed = chain.pose_from(base, angles);
    let (Some(&first), Some(reach)) = (limb.joints.first(), limb.reach(&placed)) else { return true };
    let Some(root) = placed.get(first) else { return true };
    let mut length = 0.0;
    let mut previous = root.position;
    for &link in &limb.joints[1..] {
        length += (placed[link].position - previous).length();
        previous = placed[link].position;
    }
    length += (reach.position - previous).length();
    (goal.position() - root.position).length() > length + CLOSE.0
}

fn clamp(angle: f32, limits: &Limits, link: usize) -> f32 {
    limits.get(link).map_or(angle, |&(low, high)| angle.clamp(low, high))
}

fn error(solution: &Solution) -> f32 {
    solution.gap + solution.twist * TWIST_WEIGHT
}

/// The goal's error at the pose `angles`: position (3) and, held, twist (3, weighed).
fn residual(chain: &Chain, base: Placed, angles: &[f32], limb: &Limb, goal: Goal) -> ([f32; 6], usize, Vec<Placed>) {
    let placed = chain.pose_from(base, angles);
    let Some(reach) = limb.reach(&placed) else { return ([0.0; 6], 3, placed) };
    let d = goal.position() - reach.position;
    match goal {
        Goal::Reach(_) => ([d.x, d.y, d.z, 0.0, 0.0, 0.0], 3, placed),
        Goal::Hold(held) => {
            let turn = twist(held.rotation * reach.rotation.transpose()) * TWIST_WEIGHT;
            ([d.x, d.y, d.z, turn.x, turn.y, turn.z], 6, placed)
        }
    }
}

/// The rotation vector (axis × angle) of a rotation matrix.
fn twist(rotation: Mat3) -> Vec3 {
    let (axis, angle) = glam::Quat::from_mat3(&rotation).normalize().to_axis_angle();
    let angle = if angle > std::f32::consts::PI { angle - std::f32::consts::TAU } else { angle };
    axis * angle
}

fn measured(angles: Vec<f32>, e: &[f32; 6]) -> Solution {
    let gap = Vec3::new(e[0], e[1], e[2]).length();
    let twist = Vec3::new(e[3], e[4], e[5]).length() / TWIST_WEIGHT;
    Solution { angles, gap, twist }
}

/// Levenberg–Marquardt from `angles`.
fn descend(chain: &Chain, base: Placed, mut angles: Vec<f32>, limb: &Limb, goal: Goal, limits: &Limits) -> Solution {
    let (mut e, rows, mut placed) = residual(chain, base, &angles, limb, goal);
    let mut damping = 1.0_f64;
    let norm = |e: &[f32; 6]| e.iter().map(|v| f64::from(*v).powi(2)).sum::<f64>();
    for _ in 0..STEPS {
        let now = measured(Vec::new(), &e);
        if now.reached(CLOSE.0, CLOSE.1) {
            break;
        }
        let mut jacobian = columns(chain, &placed, limb, rows == 6);
        let mut improved = false;
        for _ in 0..6 {
            let step = free_step(&mut jacobian, &e[..rows], damping, |k, by| {
                let link = limb.joints[k];
                let (low, high) = limits.get(link).copied().unwrap_or((f32::MIN, f32::MAX));
                (by < 0.0 && angles[link] <= low + 1e-6) || (by > 0.0 && angles[link] >= high - 1e-6)
            });
            let mut tried = angles.clone();
            for (&link, by) in limb.joints.iter().zip(&step) {
                // Steps are small angles.
                #[allow(clippy::cast_possible_truncation)]
                let by = by.clamp(-0.3, 0.3) as f32;
                tried[link] = clamp(tried[link] + by, limits, link);
            }
            let (next, _, next_placed) = residual(chain, base, &tried, limb, goal);
            if norm(&next) < norm(&e) {
                (angles, e, placed) = (tried, next, next_placed);
                damping = (damping / 3.0).max(1e-3);
                improved = true;
                break;
            }
            damping *= 4.0;
        }
        if !improved {
            break;
        }
    }
    measured(angles, &e)
}

/// Each joint's column of the Jacobian: how the tip (and, held, the end's
/// turn, weighed) moves per radian of the joint.
fn columns(chain: &Chain, placed: &[Placed], limb: &Limb, held: bool) -> Vec<[f64; 6]> {
    let tip = limb.reach(placed).map_or(Vec3::ZERO, |reach| reach.position);
    limb.joints
        .iter()
        .map(|&link| match chain.joint(placed, link) {
            Some((at, axis)) => {
                let moves = axis.cross(tip - at);
                let turns = if held { axis * TWIST_WEIGHT } else { Vec3::ZERO };
                [moves.x, moves.y, moves.z, turns.x, turns.y, turns.z].map(f64::from)
            }
            None => [0.0; 6],
        })
        .collect()
}

/// The damped step with the joints that sit at a limit and would be pushed
/// past it held still (their columns dropped and the step solved again), so
/// that the others do the work instead of the step stalling against the limit.
fn free_step(jacobian: &mut [[f64; 6]], e: &[f32], damping: f64, blocked: impl Fn(usize, f64) -> bool) -> Vec<f64> {
    let mut step = damped_step(jacobian, e, damping);
    for _ in 0..jacobian.len() {
        let stuck: Vec<usize> = (0..step.len()).filter(|&k| step[k] != 0.0 && blocked(k, step[k])).collect();
        if stuck.is_empty() {
            break;
        }
        for k in stuck {
            jacobian[k] = [0.0; 6];
        }
        step = damped_step(jacobian, e, damping);
    }
    step
}

/// `Jᵀ (J Jᵀ + λ² I)⁻¹ e`, for `rows` of the error.
fn damped_step(jacobian: &[[f64; 6]], e: &[f32], damping: f64) -> Vec<f64> {
    let rows = e.len();
    let mut a = [[0.0_f64; 7]; 6];
    for r in 0..rows {
        for c in 0..rows {
            a[r][c] = jacobian.iter().map(|column| column[r] * column[c]).sum::<f64>();
        }
        a[r][r] += damping * damping;
        a[r][6] = f64::from(e[r]);
    }
    let y = gauss(&mut a, rows);
    jacobian.iter().map(|column| (0..rows).map(|r| column[r] * y[r]).sum()).collect()
}

/// Solves the `n`×`n` system in `a` (its right side in column 6), partial pivoting.
fn gauss(a: &mut [[f64; 7]; 6], n: usize) -> [f64; 6] {
    for col in 0..n {
        let pivot = (col..n).max_by(|&x, &y| a[x][col].abs().total_cmp(&a[y][col].abs())).unwrap_or(col);
        a.swap(col, pivot);
        if a[col][col].abs() < 1e-12 {
            continue;
        }
        let pivot_row = a[col];
        for row in a.iter_mut().take(n).skip(col + 1) {
            let factor = row[col] / pivot_row[col];
            for (value, above) in row.iter_mut().zip(pivot_row).skip(col) {
                *value -= factor * above;
            }
        }
    }
    let mut y = [0.0; 6];
    for row in (0..n).rev() {
        let known: f64 = (row + 1..n).map(|k| a[row][k] * y[k]).sum();
        y[row] = if a[row][row].abs() < 1e-12 { 0.0 } else { (a[row][6] - known) / a[row][row] };
    }
    y
}
