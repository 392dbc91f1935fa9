//! PLEN2 facts (`plen2.md`): the device map, the factory joint settings and
//! the field limits of the motion commands.

use serde::{Deserialize, Serialize};

/// Stored motion slots: `>MH` / `<MO` take a slot below 90.
pub const SLOTS: u8 = 90;
/// Frames per motion (`>MH` frame count 1..=20).
pub const MAX_FRAMES: usize = 20;
/// Bytes of a motion name (`>MH`, space-padded ASCII).
pub const NAME_LEN: usize = 20;
/// Shortest transition the firmware handles: below 32 ms its 32.768 ms tick divides by zero.
pub const MIN_TRANSITION_MS: u16 = 32;
/// Longest transition: the tick count is 8 bits, so 8192 ms and up wraps.
pub const MAX_TRANSITION_MS: u16 = 8191;
/// Firmware 1.4.2 clamps every joint to ±900 tenths of a degree.
pub const ANGLE_LIMIT_TENTHS_DEG: i16 = 900;
/// Device ids in a `>MF` frame (18 joints, ids 9–11 and 21–23 unused).
pub const DEVICE_IDS: usize = 24;
/// Tenths of a degree firmware 1.4.2 clamps every joint to (the factory min / max).
pub const FACTORY_LIMIT_TENTHS_DEG: i16 = 900;
/// Motions the interpreter queue (`#PU`) holds.
pub const QUEUE_LEN: usize = 31;
/// `>MH` loop count meaning "forever".
pub const LOOP_FOREVER: u8 = 0xff;

/// The 18 joints of the device map, in device-id order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
#[allow(missing_docs)] // the names are the device map's own
pub enum Joint {
    LeftShoulderPitch,
    LeftThighYaw,
    LeftShoulderRoll,
    LeftElbowRoll,
    LeftThighRoll,
    LeftThighPitch,
    LeftKneePitch,
    LeftFootPitch,
    LeftFootRoll,
    RightShoulderPitch,
    RightThighYaw,
    RightShoulderRoll,
    RightElbowRoll,
    RightThighRoll,
    RightThighPitch,
    RightKneePitch,
    RightFootPitch,
    RightFootRoll,
}

/// Number of real joints.
pub const JOINTS: usize = 18;

impl Joint {
    /// Every joint, in device-id order.
    pub const ALL: [Self; JOINTS] = [
        Self::LeftShoulderPitch,
        Self::LeftThighYaw,
        Self::LeftShoulderRoll,
        Self::LeftElbowRoll,
        Self::LeftThighRoll,
        Self::LeftThighPitch,
        Self::LeftKneePitch,
        Self::LeftFootPitch,
        Self::LeftFootRoll,
        Self::RightShoulderPitch,
        Self::RightThighYaw,
        Self::RightShoulderRoll,
        Self::RightElbowRoll,
        Self::RightThighRoll,
        Self::RightThighPitch,
        Self::RightKneePitch,
        Self::RightFootPitch,
        Self::RightFootRoll,
    ];

    /// Position in [`Joint::ALL`] (0..18).
    pub fn index(self) -> usize {
        self as usize
    }

    /// The firmware's device id: 0..=8 on the left, 12..=20 on the right.
    pub fn device_id(self) -> u8 {
        let index = self as u8;
        if index < 9 { index } else { index + 3 }
    }

    /// The joint with this device id, if it is one of the 18.
    pub fn from_device_id(device_id: u8) -> Option<Self> {
        match device_id {
            0..=8 => Some(Self::ALL[usize::from(device_id)]),
            12..=20 => Some(Self::ALL[usize::from(device_id - 3)]),
            _ => None,
        }
    }

    /// The device map's name, e.g. `left_shoulder_pitch`.
    pub fn name(self) -> &'static str {
        const NAMES: [&str; JOINTS] = [
            "left_shoulder_pitch",
            "left_thigh_yaw",
            "left_shoulder_roll",
            "left_elbow_roll",
            "left_thigh_roll",
            "left_thigh_pitch",
            "left_knee_pitch",
            "left_foot_pitch",
            "left_foot_roll",
            "right_shoulder_pitch",
            "right_thigh_yaw",
            "right_shoulder_roll",
            "right_elbow_roll",
            "right_thigh_roll",
            "right_thigh_pitch",
            "right_knee_pitch",
            "right_foot_pitch",
            "right_foot_roll",
        ];
        NAMES[self.index()]
    }

    /// The factory home of fw 1.4.2, in tenths of a degree.
    pub fn factory_home_tenths_deg(self) -> i16 {
        const LEFT: [i16; 9] = [-200, 50, 375, 250, -470, -220, 500, 200, 220];
        let index = self.index();
        if index < 9 { LEFT[index] } else { -LEFT[index - 9] }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn device_map_matches_plen2_md() {
        assert_eq!(Joint::LeftShoulderPitch.device_id(), 0);
        assert_eq!(Joint::LeftFootRoll.device_id(), 8);
        assert_eq!(Joint::RightShoulderPitch.device_id(), 12);
        assert_eq!(Joint::RightFootRoll.device_id(), 20);
        assert_eq!(Joint::RightKneePitch.name(), "right_knee_pitch");
        for unused in [9, 10, 11, 21, 22, 23] {
            assert_eq!(Joint::from_device_id(unused), None);
        }
        for joint in Joint::ALL {
            assert_eq!(Joint::from_device_id(joint.device_id()), Some(joint));
        }
        // Factory homes, ids 12..20 per plen2.md.
        let right: Vec<i16> = Joint::ALL[9..].iter().map(|j| j.factory_home_tenths_deg()).collect();
        assert_eq!(right, [200, -50, -375, -250, 470, 220, -500, -200, -220]);
        assert_eq!(Joint::LeftKneePitch.factory_home_tenths_deg(), 500);
    }
}
