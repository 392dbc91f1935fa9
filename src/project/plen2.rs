//! The PLEN2 section of a project: joint settings as the robot holds them,
//! motions in slots 0..=89, and play lists for the interpreter queue.

use serde::{Deserialize, Serialize};

use super::Easing;

pub use crate::protocol::plen2::{
    FACTORY_LIMIT_TENTHS_DEG, JOINTS, Joint, MAX_FRAMES, MAX_TRANSITION_MS, MIN_TRANSITION_MS, SLOTS,
};

/// Everything a PLEN2 project holds.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Plen2Project {
    /// Joint settings as held by the robot (`<JS`); empty when the project does
    /// not hold them (then an upload never touches them).
    #[serde(default, deserialize_with = "super::bounded::list", skip_serializing_if = "Vec::is_empty")]
    pub joints: Vec<JointSetting>,
    /// Motions, each in its slot.
    #[serde(default, deserialize_with = "super::bounded::list")]
    pub motions: Vec<Motion>,
    /// Motions queued with a number of plays (`#PU` … `#PO`).
    #[serde(default, deserialize_with = "super::bounded::list", skip_serializing_if = "Vec::is_empty")]
    pub play_lists: Vec<PlayList>,
}

impl Plen2Project {
    /// The motions `motion` plays on into, each jumping to the next
    /// (plen2.md §6): none when it loops for ever first; ending at a slot
    /// with no motion or at one already played (a chain that comes back
    /// replays for ever), or after a motion that loops for ever.
    pub fn chained(&self, motion: &Motion) -> Vec<&Motion> {
        let forever = |m: &Motion| m.loop_range.is_some_and(|range| matches!(range.count, 0 | 255));
        let mut chain: Vec<&Motion> = Vec::new();
        let mut seen = vec![motion.slot];
        let mut at = motion;
        while !forever(at)
            && let Some(next) = at.jump_slot.and_then(|slot| self.motions.iter().find(|m| m.slot == slot))
            && !seen.contains(&next.slot)
        {
            seen.push(next.slot);
            chain.push(next);
            at = next;
        }
        chain
    }
}

/// One joint's limits and home, in tenths of a degree (`>MI` / `>MA` / `>HO`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct JointSetting {
    /// The joint.
    pub joint: Joint,
    /// Lowest angle the robot moves it to.
    pub min_tenths_deg: i16,
    /// Highest angle.
    pub max_tenths_deg: i16,
    /// Home: frames are relative to it.
    pub home_tenths_deg: i16,
}

/// A stored motion (`>MH` + `>MF`).
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Motion {
    /// Slot 0..=89.
    pub slot: u8,
    /// At most 20 ASCII characters.
    #[serde(default)]
    pub name: String,
    /// 1..=20 frames.
    #[serde(default, deserialize_with = "super::bounded::list")]
    pub frames: Vec<Frame>,
    /// Frames played again after the first pass, if any.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub loop_range: Option<LoopRange>,
    /// The slot played after this motion ends, if any.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub jump_slot: Option<u8>,
}

/// A motion's loop: frames `begin_frame..=end_frame` (from 0), run `count + 1` times.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct LoopRange {
    /// First looped frame, from 0.
    pub begin_frame: u8,
    /// Last looped frame, from 0.
    pub end_frame: u8,
    /// Extra passes; 255 = forever.
    pub count: u8,
}

/// One frame: every joint's angle relative to its home, reached in `transition_ms`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Frame {
    /// How long the move to this frame takes, 32..=8191 ms.
    pub transition_ms: u16,
    /// Each joint's angle relative to home, tenths of a degree.
    pub values_tenths_deg: Pose,
    /// The curve of the move to it (the robot plays it baked into straight frames).
    #[serde(default, skip_serializing_if = "Easing::is_linear")]
    pub easing: Easing,
}

impl Frame {
    /// A frame reached at constant speed.
    pub fn new(transition_ms: u16, values_tenths_deg: Pose) -> Self {
        Self { transition_ms, values_tenths_deg, easing: Easing::Linear }
    }
}

/// One value per joint, in device-map order; written in files as an object
/// keyed by joint name (a missing joint is 0).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Pose(pub [i16; JOINTS]);

impl Pose {
    /// The pose mirrored left↔right (the official editor's Mirror L/R): each
    /// left joint takes its right twin's value and the reverse, negated (the
    /// twins' axes are mirror images: the factory homes of ids 12..20 are those
    /// of 0..8 negated).
    pub fn mirrored(&self) -> Self {
        let mut out = Self::default();
        for left in 0..9 {
            let (l, r) = (Joint::ALL[left], Joint::ALL[left + 9]);
            out.set(l, self.get(r).saturating_neg());
            out.set(r, self.get(l).saturating_neg());
        }
        out
    }

    /// The value of `joint`.
    pub fn get(&self, joint: Joint) -> i16 {
        self.0[joint.index()]
    }

    /// Sets the value of `joint`.
    pub fn set(&mut self, joint: Joint, value: i16) {
        self.0[joint.index()] = value;
    }
}

impl Serialize for Pose {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let mut map = serializer.serialize_map(Some(JOINTS))?;
        for joint in Joint::ALL {
            map.serialize_entry(joint.name(), &self.get(joint))?;
        }
        map.end()
    }
}

impl<'de> Deserialize<'de> for Pose {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct PoseVisitor;
        impl<'de> serde::de::Visitor<'de> for PoseVisitor {
            type Value = Pose;

            fn expecting(&self, formatter: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                formatter.write_str("an object of joint names and values, each joint once")
            }

            fn visit_map<A: serde::de::MapAccess<'de>>(self, mut map: A) -> Result<Pose, A::Error> {
                let mut pose = Pose::default();
                let mut seen = [false; JOINTS];
                while let Some((joint, value)) = map.next_entry::<Joint, i16>()? {
                    // Which of two values was meant cannot be guessed.
                    if std::mem::replace(&mut seen[joint.index()], true) {
                        return Err(serde::de::Error::custom(format_args!("{} is listed twice", joint.name())));
                    }
                    pose.set(joint, value);
                }
                Ok(pose)
            }
        }
        deserializer.deserialize_map(PoseVisitor)
    }
}

/// Motions played one after another by the interpreter.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct PlayList {
    /// What the user calls it.
    #[serde(default)]
    pub name: String,
    /// The queue, in order (at most 31).
    #[serde(default, deserialize_with = "super::bounded::list")]
    pub entries: Vec<PlayEntry>,
}

/// One queued motion (`#PU`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct PlayEntry {
    /// The motion's slot.
    pub slot: u8,
    /// Total plays, 1..=255; 0 = forever.
    pub plays: u8,
}

// The registry of families: the PLEN2, where their section of the project lives.
inventory::submit! {
    super::family::Registered { family: super::family::Family::Plen2, rank: 1 }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn motion(slot: u8, jump_slot: Option<u8>, loop_count: Option<u8>) -> Motion {
        Motion {
            slot,
            name: format!("m{slot}"),
            frames: vec![],
            loop_range: loop_count.map(|count| LoopRange { begin_frame: 0, end_frame: 0, count }),
            jump_slot,
        }
    }

    fn slots(project: &Plen2Project, slot: u8) -> Vec<u8> {
        let first = project.motions.iter().find(|m| m.slot == slot).unwrap();
        project.chained(first).iter().map(|m| m.slot).collect()
    }

    #[test]
    fn a_chain_runs_through_its_jumps_and_stops_where_the_robot_would_not_go_on() {
        let project = Plen2Project {
            motions: vec![
                motion(1, Some(2), None),
                motion(2, Some(7), Some(3)),
                motion(7, None, None),
                // Back to where it came from: replays for ever.
                motion(10, Some(11), None),
                motion(11, Some(10), None),
                // On to an empty slot.
                motion(20, Some(21), None),
                // A loop for ever (stored 0 wraps to 255) never reaches its jump.
                motion(30, Some(31), Some(0)),
                motion(31, None, None),
                motion(40, Some(41), None),
                motion(41, Some(42), Some(255)),
                motion(42, None, None),
            ],
            ..Plen2Project::default()
        };
        assert_eq!(slots(&project, 1), vec![2, 7], "a finite loop plays on");
        assert_eq!(slots(&project, 10), vec![11]);
        assert_eq!(slots(&project, 20), Vec::<u8>::new());
        assert_eq!(slots(&project, 30), Vec::<u8>::new());
        assert_eq!(slots(&project, 40), vec![41], "it reaches the motion that loops for ever, not past it");
    }
}
