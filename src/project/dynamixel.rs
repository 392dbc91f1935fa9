//! A DYNAMIXEL project's section (`"dynamixel"` in the project file, kept in
//! `Project::sections`): the servos on the bus, by ID, with their captions,
//! and the motions, each a list of steps — a pose of every servo it names, in
//! the servo's own units (X and MX: 4096 a turn; AX: 1024 over 300°), reached
//! in the step's time along its curve. A DYNAMIXEL stores nothing, so the
//! project is all there is: the editor streams a motion from it.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use super::easing::Easing;
use super::{Family, Project};

#[allow(non_upper_case_globals)]
impl Family {
    /// ROBOTIS DYNAMIXEL servos on one bus (Protocol 1.0 and 2.0, `docs/dynamixel.md`).
    pub const Dynamixel: Self = Self::named("dynamixel", "DYNAMIXEL");
}

inventory::submit! {
    super::Registered { family: Family::Dynamixel, rank: 3 }
}
inventory::submit! {
    super::Section { family: Family::Dynamixel, check: DynamixelSection::check, fresh: || DynamixelSection::default().kept() }
}

/// The longest step (a minute).
pub const LONGEST_STEP_MS: u32 = 60_000;

/// What a DYNAMIXEL project keeps.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DynamixelSection {
    /// The servos on the bus, by ID.
    #[serde(default)]
    pub servos: Vec<ServoSetup>,
    /// The motions.
    #[serde(default)]
    pub motions: Vec<Motion>,
}

/// One servo on the bus.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ServoSetup {
    /// Its ID (0..=252).
    pub id: u8,
    /// Its caption (any script: 左肩, shoulder).
    #[serde(default)]
    pub name: String,
    /// Its model number, as its table says (0: not known yet).
    #[serde(default)]
    pub model_number: u16,
    /// How it moves to a goal set live (none: [`Profile::LIVE`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub profile: Option<Profile>,
}

/// A servo's own profile: how fast and how sharply it moves to a goal (its
/// Profile Velocity and Profile Acceleration; an AX: its Moving Speed).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Profile {
    /// Profile Velocity (X: 0.229 rev/min a unit; AX Moving Speed: 0.111 rev/min); 0 is as fast as it can.
    pub velocity: u32,
    /// Profile Acceleration (X: 214.577 rev/min² a unit); 0 is at once. An AX has none.
    #[serde(default)]
    pub acceleration: u32,
}

impl Profile {
    /// What a servo is given for live moves unless its project says: about
    /// 137°/s on an X-series (67°/s on an AX), never a slam to a far goal.
    pub const LIVE: Self = Self { velocity: 100, acceleration: 20 };
}

impl ServoSetup {
    /// Its profile for live moves.
    pub fn live_profile(&self) -> Profile {
        self.profile.unwrap_or(Profile::LIVE)
    }
}

/// A motion: steps played one after another.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Motion {
    /// Its caption.
    #[serde(default)]
    pub name: String,
    /// Its steps.
    #[serde(default)]
    pub steps: Vec<Step>,
}

/// One step: where each servo it names goes, in how long, along which curve.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Step {
    /// How long the move to this pose takes, ms.
    pub duration_ms: u32,
    /// The curve of the move.
    #[serde(default)]
    pub easing: Easing,
    /// Each servo's position, in its own units, by ID.
    pub positions: BTreeMap<u8, u32>,
}

impl DynamixelSection {
    /// What is wrong with a kept section.
    fn check(kept: &serde_json::Value) -> Vec<String> {
        let section = match Self::deserialize(kept) {
            Ok(section) => section,
            // No section yet: an empty bus.
            Err(_) if kept.is_null() => return Vec::new(),
            Err(error) => return vec![format!("the DYNAMIXEL section cannot be read: {error}")],
        };
        let mut problems = Vec::new();
        let mut seen = std::collections::BTreeSet::new();
        for servo in &section.servos {
            if servo.id > 252 {
                problems.push(format!("servo ID {} is outside 0..=252", servo.id));
            }
            if !seen.insert(servo.id) {
                problems.push(format!("servo ID {} is listed twice", servo.id));
            }
        }
        for (m, motion) in section.motions.iter().enumerate() {
            for (s, step) in motion.steps.iter().enumerate() {
                if step.duration_ms == 0 || step.duration_ms > LONGEST_STEP_MS {
                    problems.push(format!(
                        "motion {} step {}: {} ms is outside 1..={LONGEST_STEP_MS} ms",
                        m + 1,
                        s + 1,
                        step.duration_ms
                    ));
                }
                for id in step.positions.keys().filter(|id| !seen.contains(id)) {
                    problems.push(format!("motion {} step {}: servo {id} is not on the bus", m + 1, s + 1));
                }
            }
        }
        problems
    }

    /// The project's section, or an empty one.
    pub fn of(project: &Project) -> Self {
        project.sections.read(Family::Dynamixel).ok().flatten().unwrap_or_default()
    }

    /// The section as the project keeps it.
    pub fn kept(&self) -> serde_json::Value {
        serde_json::to_value(self).unwrap_or_default()
    }

    /// The servo with ID `id`.
    pub fn servo(&self, id: u8) -> Option<&ServoSetup> {
        self.servos.iter().find(|servo| servo.id == id)
    }
}

impl Motion {
    /// How long it plays, ms.
    pub fn duration_ms(&self) -> u64 {
        self.steps.iter().map(|step| u64::from(step.duration_ms)).sum()
    }

    /// Where each servo is `at_ms` into the motion, starting from `from`
    /// (where the servos were): each step's move along its curve, a servo a
    /// step does not name staying where it was.
    pub fn pose_at(&self, from: &BTreeMap<u8, u32>, at_ms: f64) -> BTreeMap<u8, u32> {
        let mut pose = from.clone();
        let mut start_ms = 0.0;
        for step in &self.steps {
            let end_ms = start_ms + f64::from(step.duration_ms);
            if at_ms >= end_ms {
                pose.extend(step.positions.iter().map(|(id, position)| (*id, *position)));
                start_ms = end_ms;
                continue;
            }
            let t = ((at_ms - start_ms) / f64::from(step.duration_ms.max(1))).clamp(0.0, 1.0);
            let way = step.easing.at(t);
            for (id, to) in &step.positions {
                let from = f64::from(pose.get(id).copied().unwrap_or(*to));
                let at = from + (f64::from(*to) - from) * way;
                // Between two positions of the servo's own range.
                #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
                pose.insert(*id, at.round().max(0.0) as u32);
            }
            break;
        }
        pose
    }
}

impl Motion {
    /// The motion sampled every `every_ms` from `from` (where the servos
    /// were): the pose at each frame after the start, to its end — what is
    /// streamed, the same poses a plot of it draws.
    pub fn frames(&self, from: &BTreeMap<u8, u32>, every_ms: f64) -> Vec<BTreeMap<u8, u32>> {
        // A motion lasts at most a minute a step: its frames count fits.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss, clippy::cast_precision_loss)]
        let count = (self.duration_ms() as f64 / every_ms.max(1.0)).ceil() as usize;
        #[allow(clippy::cast_precision_loss)]
        (1..=count).map(|k| self.pose_at(from, k as f64 * every_ms)).collect()
    }
}

/// Position units a turn and the centre, for model number `model_number`
/// (X and MX: 4096 a turn, centred on 2048; AX: 1024 over 300°, on 512).
fn scale(model_number: u16) -> (f64, f64) {
    crate::protocol::dynamixel::table::known(model_number)
        .map_or((4096.0, 2048.0), |model| (model.layout.units_per_turn, f64::from(model.layout.top_position + 1) / 2.0))
}

/// A position of a servo of `model_number` in degrees from its centre.
pub fn degrees(model_number: u16, position: u32) -> f64 {
    let (per_turn, centre) = scale(model_number);
    (f64::from(position) - centre) * 360.0 / per_turn
}

/// Degrees from the centre as a position of a servo of `model_number` (never below 0).
pub fn units(model_number: u16, deg: f64) -> u32 {
    let (per_turn, centre) = scale(model_number);
    // Rounded and kept at or above 0: a position.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let units = (centre + deg * per_turn / 360.0).round().max(0.0) as u32;
    units
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn degrees_and_units_agree_for_each_kind_of_servo() {
        assert!((degrees(1060, 3072) - 90.0).abs() < 1e-9, "X: 4096 a turn, centred on 2048");
        assert!((degrees(12, 1023) - 149.707).abs() < 1e-3, "AX: 1024 over 300°, centred on 512");
        assert_eq!(units(12, -150.0), 0);
        assert_eq!(units(1020, -45.0), 1536);
        for model in [12, 29, 1060] {
            for position in [0, 100, 512, 1000] {
                assert_eq!(units(model, degrees(model, position)), position);
            }
        }
    }

    fn step(duration_ms: u32, easing: Easing, positions: &[(u8, u32)]) -> Step {
        Step { duration_ms, easing, positions: positions.iter().copied().collect() }
    }

    #[test]
    fn a_motion_moves_each_servo_along_its_steps_curve() {
        let motion = Motion {
            name: "wave 揮手".into(),
            steps: vec![step(1000, Easing::Linear, &[(1, 3048)]), step(1000, Easing::EaseIn, &[(1, 2048), (3, 812)])],
        };
        let from: BTreeMap<u8, u32> = [(1, 2048), (3, 512)].into();
        assert_eq!(motion.duration_ms(), 2000);
        assert_eq!(motion.pose_at(&from, 0.0)[&1], 2048);
        assert_eq!(motion.pose_at(&from, 500.0)[&1], 2548, "linear: half way at half time");
        assert_eq!(motion.pose_at(&from, 1000.0)[&1], 3048);
        assert_eq!(motion.pose_at(&from, 1000.0)[&3], 512, "not named by the first step: it stays");
        // Ease in: a quarter of the way at half the time.
        assert_eq!(motion.pose_at(&from, 1500.0)[&1], 3048 - 250);
        assert_eq!(motion.pose_at(&from, 1500.0)[&3], 512 + 75);
        assert_eq!(motion.pose_at(&from, 5000.0), [(1, 2048), (3, 812)].into());
    }

    #[test]
    fn a_section_is_checked_in_its_own_words() {
        let section = DynamixelSection {
            servos: vec![ServoSetup { id: 1, name: "肩".into(), model_number: 1060, profile: None }],
            motions: vec![Motion { name: String::new(), steps: vec![step(0, Easing::Linear, &[(1, 0), (9, 0)])] }],
        };
        assert_eq!(
            DynamixelSection::check(&section.kept()),
            ["motion 1 step 1: 0 ms is outside 1..=60000 ms", "motion 1 step 1: servo 9 is not on the bus"]
        );
        assert!(DynamixelSection::check(&serde_json::Value::Null).is_empty(), "no section yet is an empty one");
        let unknown = serde_json::json!({ "servos": [], "speed": 3 });
        assert!(DynamixelSection::check(&unknown)[0].starts_with("the DYNAMIXEL section cannot be read"));
    }
}
