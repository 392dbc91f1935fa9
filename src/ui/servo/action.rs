//! The servo board's actions: what its panels ask for, applied by its own ui.

use std::path::PathBuf;

use crate::project::Family;
use crate::ui::action::ActionOf;

/// What happens after a board comparison is confirmed.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum BoardIntent {
    /// Write the project onto the board.
    Upload,
    /// Write the project onto the board although validation found errors
    /// (restoring a backup of content Servo Studio would not author).
    UploadAnyway,
    /// Replace the project with the board's contents.
    ReadIntoProject,
    /// Save the board's contents to a file.
    ExportToFile(PathBuf),
}

/// A servo board panel's request.
#[derive(Clone, Debug, PartialEq)]
pub enum ServoAction {
    /// A slider moved: set the pose of one servo (sent live when connected).
    SetPose {
        /// The servo.
        servo_id: u8,
        /// The angle asked for (clamped to the servo's limits).
        degree: i16,
    },
    /// Select a servo (its slider row and its link in the 3D view), or none.
    SelectServo(Option<u8>),
    /// A servo turned in the 3D view: to where it was when the drag began, plus this (live).
    TurnServo {
        /// The servo.
        servo_id: u8,
        /// Degrees from where the drag began.
        by_deg: i32,
    },
    /// Draw a servo's link with the mesh in this file (picked in the rig table).
    SetMesh {
        /// The servo.
        servo_id: u8,
        /// The file chosen.
        path: PathBuf,
    },
    /// Several servos to these angles at once (°), live: a limb posed by its end in the 3D view.
    Pose(std::collections::BTreeMap<u8, i16>),
    /// The drag turning a servo (or posing a limb) let go: the turn is one undo step.
    TurnDone,
    /// Hold or release one servo's torque.
    SetHold {
        /// The servo.
        servo_id: u8,
        /// Hold (true) or release (false).
        hold: bool,
    },
    /// Start recording the sliders (after a count-in), to be fitted into
    /// actions and a macro running them.
    Record,
    /// Stop recording: fit what was recorded and add it (one undo step).
    StopRecording,
    /// Turn the current pose into a new action.
    CapturePose {
        /// Use the angles read back from the board instead of the sliders.
        from_board: bool,
    },
    /// Read servo angles from the board continuously.
    SetPolling(bool),
    /// Read the board and show what differs, before doing `intent`.
    BoardCompare(BoardIntent),
    /// Go ahead with the compared intent.
    BoardConfirm,
    /// Drop the compared intent.
    BoardDismiss,
    /// Run a stored macro on the board.
    RunMacro(i32),
    /// Move the servos through an action of the project now (live).
    PlayAction(i32),
    /// Play a macro of the project live from one of its commands (its actions
    /// sent one after another, curves as their sub-steps).
    PlayMacroFrom {
        /// The macro.
        macro_id: i32,
        /// The first command played, from 0.
        command: usize,
    },
    /// Play an action on the sliders, without a board.
    PreviewAction(i32),
    /// Start (with the table to pick into) or stop picking a button by pressing it on the remote.
    PickButton {
        /// The table a pressed button is selected in (or added to); `None` stops picking.
        table_index: Option<usize>,
    },
}

impl ActionOf for ServoAction {
    const FAMILY: Family = Family::Servo;

    fn moves_robot(&self) -> bool {
        matches!(
            self,
            Self::SetPose { .. }
                | Self::TurnServo { .. }
                | Self::Pose(_)
                | Self::RunMacro(_)
                | Self::PlayAction(_)
                | Self::PlayMacroFrom { .. }
        )
    }
}
