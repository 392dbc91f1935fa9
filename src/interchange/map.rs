//! The joint map: which source channel drives which servo or PLEN2 joint, and
//! how its raw value becomes degrees — `degrees = direction × (raw − zero) /
//! per_degree + offset_deg`. Guessed from ids and names, edited in a table,
//! saved as a small JSON file and given again with `--map`.

use serde::{Deserialize, Serialize};

use super::format::Format;
use super::source::{Channel, Source};
use crate::project::Family;
use crate::project::plen2::Joint;

/// What a map file says it is.
pub const MAP_FORMAT: &str = "servo-studio joint map";

/// Where a channel goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Target {
    /// A servo-board servo, by id.
    Servo(u8),
    /// A PLEN2 joint.
    Joint(Joint),
}

impl Target {
    /// As written in a map file and shown in the table: `servo 3`, `left_knee_pitch`.
    pub fn word(self) -> String {
        match self {
            Self::Servo(id) => format!("servo {id}"),
            Self::Joint(joint) => joint.name().to_string(),
        }
    }

    /// The target a word names.
    pub fn from_word(word: &str) -> Option<Self> {
        if let Some(id) = word.trim().strip_prefix("servo ") {
            return id.trim().parse::<u8>().ok().filter(|id| *id != 255).map(Self::Servo);
        }
        Joint::ALL.into_iter().find(|joint| joint.name() == word.trim()).map(Self::Joint)
    }

    /// The family it belongs to.
    pub fn family(self) -> Family {
        match self {
            Self::Servo(_) => Family::Servo,
            Self::Joint(_) => Family::Plen2,
        }
    }
}

impl Serialize for Target {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(&self.word())
    }
}

impl<'de> Deserialize<'de> for Target {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let word = String::deserialize(deserializer)?;
        Self::from_word(&word).ok_or_else(|| {
            serde::de::Error::custom(format!("{word:?} is neither `servo N` (0..=254) nor a PLEN2 joint name"))
        })
    }
}

/// One channel's line of the map.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MapEntry {
    /// The source channel's key (its id, channel number or bone).
    pub source: String,
    /// Its name in the source, for people reading the file.
    #[serde(default)]
    pub name: String,
    /// Where it goes; `null`: not imported.
    #[serde(rename = "to")]
    pub target: Option<Target>,
    /// The raw value at 0°.
    pub zero: f64,
    /// Raw units per degree.
    pub per_degree: f64,
    /// 1, or -1 when the target turns the other way.
    #[serde(default = "MapEntry::forward")]
    pub direction: i8,
    /// Degrees added after scaling.
    #[serde(default)]
    pub offset_deg: f64,
}

impl MapEntry {
    fn forward() -> i8 {
        1
    }

    /// The degrees a raw value stands for.
    pub fn degrees(&self, raw: f64) -> f64 {
        f64::from(self.direction.signum()) * (raw - self.zero) / self.per_degree + self.offset_deg
    }

    /// The raw value that stands for `degrees` (the inverse of [`Self::degrees`]).
    pub fn raw(&self, degrees: f64) -> f64 {
        self.zero + self.per_degree * f64::from(self.direction.signum()) * (degrees - self.offset_deg)
    }
}

/// A whole map.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct JointMap {
    /// [`MAP_FORMAT`].
    #[serde(default)]
    pub format: String,
    /// One entry per source channel.
    pub entries: Vec<MapEntry>,
}

/// A map file that cannot be used.
#[derive(Debug, thiserror::Error)]
pub enum MapError {
    /// Not a map file.
    #[error("not a joint map: {0}")]
    Json(#[from] serde_json::Error),
    /// An entry that cannot be used.
    #[error("entry for {channel:?}: {problem}")]
    Entry {
        /// The entry's source channel.
        channel: String,
        /// What is wrong.
        problem: String,
    },
}

impl JointMap {
    /// Reads a map file's text, checking every entry.
    pub fn from_json(text: &str) -> Result<Self, MapError> {
        let map: Self = serde_json::from_str(text)?;
        map.check()?;
        Ok(map)
    }

    /// The map as a file's text.
    pub fn to_json(&self) -> String {
        let mut map = self.clone();
        map.format = MAP_FORMAT.to_string();
        serde_json::to_string_pretty(&map).unwrap_or_default() + "\n"
    }

    /// Every entry usable, no target driven twice.
    pub fn check(&self) -> Result<(), MapError> {
        let mut seen = std::collections::HashMap::new();
        for entry in &self.entries {
            let problem = |problem: String| MapError::Entry { channel: entry.source.clone(), problem };
            if !(entry.per_degree.is_finite() && entry.per_degree != 0.0) {
                return Err(problem(format!("per_degree {} must be a number other than 0", entry.per_degree)));
            }
            if !(entry.zero.is_finite() && entry.offset_deg.is_finite()) {
                return Err(problem("zero and offset_deg must be numbers".into()));
            }
            if entry.direction.abs() != 1 {
                return Err(problem(format!("direction {} must be 1 or -1", entry.direction)));
            }
            if let Some(target) = entry.target
                && let Some(other) = seen.insert(target, entry.source.clone())
            {
                return Err(problem(format!("{} is driven by {other:?} already", target.word())));
            }
        }
        Ok(())
    }

    /// The entry for a source channel.
    pub fn entry(&self, key: &str) -> Option<&MapEntry> {
        self.entries.iter().find(|entry| entry.source == key)
    }

    /// A map for `source` on a `family` board: `given`'s entries where it has
    /// them, a guess for every other channel (by id, then by name).
    pub fn for_source(source: &Source, family: Family, given: Option<&Self>) -> Self {
        let mut taken: Vec<Target> =
            given.map(|map| map.entries.iter().filter_map(|entry| entry.target).collect()).unwrap_or_default();
        let mut entries = Vec::new();
        for (index, channel) in source.channels.iter().enumerate() {
            if let Some(entry) = given.and_then(|map| map.entry(&channel.key)) {
                entries.push(entry.clone());
                continue;
            }
            let target = guess(source.format, channel, index, family).filter(|target| !taken.contains(target));
            taken.extend(target);
            entries.push(MapEntry {
                source: channel.key.clone(),
                name: channel.name.clone(),
                target,
                zero: channel.unit.zero,
                per_degree: channel.unit.per_degree,
                direction: 1,
                offset_deg: 0.0,
            });
        }
        Self { format: MAP_FORMAT.to_string(), entries }
    }
}

impl std::hash::Hash for Target {
    fn hash<H: std::hash::Hasher>(&self, state: &mut H) {
        self.word().hash(state);
    }
}

/// A Bioloid-class humanoid's ids (the ROBOTIS Premium type A layout, ids
/// 1..=18: right before left, arms then legs) as PLEN2 joints.
const BIOLOID: [&str; 18] = [
    "right_shoulder_pitch",
    "left_shoulder_pitch",
    "right_shoulder_roll",
    "left_shoulder_roll",
    "right_elbow_roll",
    "left_elbow_roll",
    "right_thigh_yaw",
    "left_thigh_yaw",
    "right_thigh_roll",
    "left_thigh_roll",
    "right_thigh_pitch",
    "left_thigh_pitch",
    "right_knee_pitch",
    "left_knee_pitch",
    "right_foot_pitch",
    "left_foot_pitch",
    "right_foot_roll",
    "left_foot_roll",
];

/// The PLEN2 joint a Bioloid humanoid's Dynamixel id drives.
pub(super) fn bioloid_joint(id: &str) -> Option<&'static str> {
    let id: usize = id.parse().ok()?;
    BIOLOID.get(id.checked_sub(1)?).copied()
}

fn guess(format: Format, channel: &Channel, index: usize, family: Family) -> Option<Target> {
    match family {
        Family::Servo => channel
            .key
            .parse::<u8>()
            .ok()
            .filter(|id| *id != 255)
            .or_else(|| u8::try_from(index + 1).ok())
            .map(Target::Servo),
        // An R+ file's reader names the joints of a robot it declares as a
        // Bioloid humanoid; a RoboPlus file's ids are a Bioloid's.
        Family::Plen2 => joint_by_name(&channel.name).map(Target::Joint).or_else(|| {
            if format != Format::Mtn {
                return None;
            }
            Target::from_word(bioloid_joint(&channel.key)?)
        }),
        // A base, or any other family: nothing of another tool's file drives it.
        _ => None,
    }
}

/// The PLEN2 joint a channel's name describes ("L knee", "right_hip_pitch", "左肩 pitch").
pub fn joint_by_name(name: &str) -> Option<Joint> {
    let lower = name.to_lowercase();
    let words: Vec<&str> = lower.split(|c: char| !c.is_alphanumeric()).filter(|w| !w.is_empty()).collect();
    let has = |options: &[&str]| {
        words.iter().any(|word| options.contains(word))
            || options.iter().any(|o| o.chars().count() == 1 && !o.is_ascii() && lower.contains(o))
    };
    let side = if has(&["left", "l", "左"]) {
        "left"
    } else if has(&["right", "r", "右"]) {
        "right"
    } else {
        return None;
    };
    let (part, axis) = if has(&["shoulder", "肩"]) {
        ("shoulder", if has(&["roll", "lateral", "side"]) { "roll" } else { "pitch" })
    } else if has(&["elbow", "肘"]) {
        ("elbow", "roll")
    } else if has(&["hip", "thigh", "股"]) {
        (
            "thigh",
            if has(&["yaw", "twist"]) {
                "yaw"
            } else if has(&["roll", "lateral"]) {
                "roll"
            } else {
                "pitch"
            },
        )
    } else if has(&["knee", "膝"]) {
        ("knee", "pitch")
    } else if has(&["ankle", "foot", "足", "腳"]) {
        ("foot", if has(&["roll", "lateral"]) { "roll" } else { "pitch" })
    } else {
        return None;
    };
    let wanted = format!("{side}_{part}_{axis}");
    Joint::ALL.into_iter().find(|joint| joint.name() == wanted)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::float_cmp)]
    use super::*;
    use crate::interchange::source::Unit;

    #[test]
    fn names_and_bioloid_ids_are_guessed_as_plen2_joints() {
        assert_eq!(joint_by_name("L knee"), Some(Joint::LeftKneePitch));
        assert_eq!(joint_by_name("r_hip_twist"), Some(Joint::RightThighYaw));
        assert_eq!(joint_by_name("right ankle lateral"), Some(Joint::RightFootRoll));
        assert_eq!(joint_by_name("左肩"), Some(Joint::LeftShoulderPitch));
        assert_eq!(joint_by_name("jaw"), None);
        let source = Source {
            format: Format::Mtn,
            channels: vec![Channel::new("13", Unit::DEGREES), Channel::new("30", Unit::DEGREES)],
            clips: Vec::new(),
            dropped: Vec::new(),
            notes: Vec::new(),
        };
        let map = JointMap::for_source(&source, Family::Plen2, None);
        assert_eq!(map.entries[0].target, Some(Target::Joint(Joint::RightKneePitch)));
        assert_eq!(map.entries[1].target, None);
        let servo = JointMap::for_source(&source, Family::Servo, None);
        assert_eq!(servo.entries[1].target, Some(Target::Servo(30)));
    }

    #[test]
    fn a_map_file_round_trips_and_wins_over_the_guess() {
        let source = Source {
            format: Format::Maestro,
            channels: vec![Channel::new("0", Unit { zero: 6000.0, per_degree: 40.0, label: "" })],
            clips: Vec::new(),
            dropped: Vec::new(),
            notes: Vec::new(),
        };
        let mut map = JointMap::for_source(&source, Family::Servo, None);
        assert_eq!(map.entries[0].target, Some(Target::Servo(0)));
        map.entries[0].target = Some(Target::Servo(7));
        map.entries[0].direction = -1;
        let again = JointMap::from_json(&map.to_json()).unwrap();
        let used = JointMap::for_source(&source, Family::Servo, Some(&again));
        assert_eq!(used.entries[0].target, Some(Target::Servo(7)));
        assert_eq!(used.entries[0].degrees(6400.0), -10.0);
        assert_eq!(used.entries[0].raw(-10.0), 6400.0);
        let twice = map.to_json().replace(
            "\"entries\": [",
            "\"entries\": [{\"source\": \"9\", \"to\": \"servo 7\", \"zero\": 0, \"per_degree\": 1},",
        );
        assert!(JointMap::from_json(&twice).unwrap_err().to_string().contains("driven by"));
        assert!(
            JointMap::from_json(
                "{\"entries\": [{\"source\": \"1\", \"to\": \"elbow\", \"zero\": 0, \"per_degree\": 1}]}"
            )
            .is_err()
        );
    }
}
