//! The PLEN2's actions: what its panels ask for, applied by its own ui.

use std::path::PathBuf;

use crate::project::Family;
use crate::ui::action::ActionOf;

/// A PLEN2 robot operation.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Plen2Intent {
    /// Read every slot, the joint settings and the version.
    Read,
    /// Upload the project's motions (backup of the overwritten slots first, then verify).
    Upload,
    /// Replace the project's PLEN2 section with what was read.
    ReadIntoProject,
    /// Save what was read to a file.
    ExportToFile(PathBuf),
    /// Write the project's joint settings where they differ.
    WriteJoints,
    /// Factory joint settings (`>JS`).
    FactoryReset,
}

/// A PLEN2 panel's request.
#[derive(Clone, Debug, PartialEq)]
pub enum Plen2Action {
    /// A joint to an absolute angle (tenths of a degree), live.
    SetJoint {
        /// The joint.
        joint: crate::project::plen2::Joint,
        /// Tenths of a degree.
        tenths: i16,
    },
    /// Select a joint (its slider row and its link in the 3D view), or none.
    SelectJoint(Option<crate::project::plen2::Joint>),
    /// A joint turned in the 3D view: to where it was when the drag began, plus this (live).
    TurnJoint {
        /// The joint.
        joint: crate::project::plen2::Joint,
        /// Tenths of a degree from where the drag began.
        by_tenths: i32,
    },
    /// Every joint to an absolute angle at once (tenths of a degree, by joint
    /// index), live: a limb posed by its end in the 3D view.
    Pose([i16; 18]),
    /// The drag turning a joint (or posing a limb) let go: the turn is one undo step.
    TurnDone,
    /// Every joint to home.
    Home,
    /// Play a motion stored on the robot (`$PM`).
    PlayMotion(u8),
    /// Play the project's motion from a frame by streaming its poses live.
    PlayFrom {
        /// The motion's slot.
        slot: u8,
        /// The first frame, from 0.
        frame: usize,
    },
    /// Play a play list of the project on the robot.
    PlayList(usize),
    /// Start recording the live pose into a motion (after a count-in), to be
    /// fitted into frames inserted after the motion's selected frame.
    Record {
        /// The motion's slot.
        slot: u8,
    },
    /// Stop recording: fit what was recorded and insert it (one undo step).
    StopRecording,
    /// Append the current joint pose to a motion as a frame.
    CaptureFrame {
        /// The motion's slot.
        slot: u8,
    },
    /// A robot operation.
    Robot(Plen2Intent),
    /// Save a motion of the project as the official editor's motion.json.
    SaveMotionJson {
        /// The motion's slot.
        slot: u8,
        /// Where.
        path: PathBuf,
    },
    /// How the robot is paced from the next connection on.
    SetPacing(crate::device::plen2::PacingMode),
}

impl ActionOf for Plen2Action {
    const FAMILY: Family = Family::Plen2;

    fn moves_robot(&self) -> bool {
        matches!(
            self,
            Self::SetJoint { .. }
                | Self::TurnJoint { .. }
                | Self::Pose(_)
                | Self::Home
                | Self::PlayMotion(_)
                | Self::PlayFrom { .. }
                | Self::PlayList(_)
        )
    }
}
