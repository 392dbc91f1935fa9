//! What panels ask for. Panels never change state themselves: they push
//! actions, and the app shell applies them in one place — the shell's own,
//! and each family's, which it hands to the family that owns them.

use std::path::PathBuf;

use crate::project::{Edit, Family};
use crate::ui::i18n::Language;

/// One of the editor's tabs: the packet log every family shares
/// ([`Tab::Log`]), or one of a family's own panels. Families name their
/// tabs themselves (`Tab::Servos`, `Tab::Drive`… are declared in their
/// folders); the name is what is remembered between runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Tab(&'static str);

#[allow(non_upper_case_globals)]
impl Tab {
    /// Every frame sent and received.
    pub const Log: Self = Self("Log");
    /// The gamepad: which, its live state, the family's bindings.
    pub const Gamepad: Self = Self("Gamepad");

    /// A family's tab called `name` (unique among all families' tabs).
    pub const fn named(name: &'static str) -> Self {
        Self(name)
    }

    /// Its name, as remembered between runs.
    pub fn name(self) -> &'static str {
        self.0
    }
}

impl std::fmt::Display for Tab {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.0)
    }
}

/// What the Gamepad tab binds by pressing or moving it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Bind {
    /// The next button pressed.
    Button,
    /// The next axis moved.
    Axis,
}

/// A file the user is asked for (the shell opens the dialog, off the frame).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum FileRequest {
    /// A project (or motion.json, or folder of them) to open.
    Open,
    /// Where to save the project.
    SaveAs,
    /// Where to save the project before going on with what waits on the unsaved question.
    SaveAsThenContinue,
    /// Where a family writes something of its own (an export).
    Export(Export),
    /// A file to read (an import, a joint map).
    Pick(Pick),
}

/// A request for a file to read: the kind of file, the names it may end in,
/// and the action the chosen path becomes.
#[derive(Clone)]
pub struct Pick {
    /// The kind of file, as the dialog's filter names it.
    pub kind: &'static str,
    /// The endings the filter offers.
    pub extensions: &'static [&'static str],
    /// The action the chosen path becomes.
    pub then: std::sync::Arc<dyn Fn(PathBuf) -> Action + Send + Sync>,
}

impl std::fmt::Debug for Pick {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Pick").field("kind", &self.kind).field("extensions", &self.extensions).finish_non_exhaustive()
    }
}

/// Two requests are the same when they ask for the same kind for the same answer.
impl PartialEq for Pick {
    fn eq(&self, other: &Self) -> bool {
        self.kind == other.kind && std::sync::Arc::ptr_eq(&self.then, &other.then)
    }
}

impl Eq for Pick {}

/// What the file dialogs call a project file.
pub const PROJECT_FILE: &str = "Servo Studio project";

/// A family's request for a place to write a file: the name offered, the kind
/// of file, and the action the chosen path becomes.
#[derive(Clone)]
pub struct Export {
    /// The file name offered.
    pub name: String,
    /// The kind of file, as the dialog's filter names it.
    pub kind: &'static str,
    /// The ending the filter offers (`json`, `xml`).
    pub extension: &'static str,
    /// The action the chosen path becomes.
    pub then: std::sync::Arc<dyn Fn(PathBuf) -> Action + Send + Sync>,
}

impl Export {
    /// Asks where to write a JSON file called `name` (offered) of `kind`; `then` makes the action.
    pub fn json(
        name: impl Into<String>,
        kind: &'static str,
        then: impl Fn(PathBuf) -> Action + Send + Sync + 'static,
    ) -> Self {
        Self { name: name.into(), kind, extension: "json", then: std::sync::Arc::new(then) }
    }
}

impl std::fmt::Debug for Export {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Export").field("name", &self.name).field("kind", &self.kind).finish_non_exhaustive()
    }
}

/// Two requests are the same when they offer the same file for the same answer.
impl PartialEq for Export {
    fn eq(&self, other: &Self) -> bool {
        self.name == other.name && self.kind == other.kind && std::sync::Arc::ptr_eq(&self.then, &other.then)
    }
}

impl Eq for Export {}

/// What the import window asks of the shell.
#[derive(Clone, Debug, PartialEq)]
pub enum ImportAction {
    /// Read this file (off the frame) and open the window on it.
    Read(PathBuf),
    /// Use the joint map in this file.
    LoadMap(PathBuf),
    /// Write the joint map to this file.
    SaveMap(PathBuf),
    /// Make what the window shows and add it to the project.
    Create,
    /// Close the window.
    Close,
    /// Open the window that exports for another tool.
    OpenExport,
    /// Write the export chosen in that window to this file.
    Export(PathBuf),
    /// Close that window.
    CloseExport,
}

/// One request from a panel to the app shell.
#[derive(Clone, Debug, PartialEq)]
pub enum Action {
    /// Change the project; edits sharing `coalesce` form one undo step.
    Edit {
        /// The change.
        edit: Edit,
        /// Undo coalescing key (e.g. `"servo 3 limits"`), if any.
        coalesce: Option<String>,
    },
    /// Undo the last step.
    Undo,
    /// Redo the last undone step.
    Redo,
    /// Open a port.
    Connect {
        /// As typed: `/dev/ttyUSB0`, `COM3`, `tcp://host:port`.
        port: String,
        /// Line rate.
        baud: u32,
    },
    /// Stop opening the port.
    CancelConnect,
    /// Ask the board on `port` which family it is (the connection doctor);
    /// with `connect`, connect to it as that family (Hardware = Auto).
    FindBoard {
        /// As typed.
        port: String,
        /// Connect once it is known.
        connect: bool,
    },
    /// Ask every port the computer lists which board is on it.
    FindEveryBoard,
    /// Connect to what the doctor found: its family (the document's becomes it) at its line rate.
    ConnectFound {
        /// The port.
        port: String,
        /// The family that answered.
        family: Family,
        /// The line rate it answered at.
        baud: u32,
    },
    /// Switch the document's board family (servo, PLEN2, rFLEX).
    SetFamily(Family),
    /// Start the in-process emulated board and connect to it.
    ConnectDemo,
    /// Close the link.
    Disconnect,
    /// STOP, the family's way: every servo held where it is; a PLEN2's motion
    /// stopped and every joint home; a base stopped at once.
    Stop,
    /// Switch the interface language.
    SetLanguage(Language),
    /// Set the live speed limit, °/s.
    SetLiveSpeed(f64),
    /// Show a tab.
    ShowTab(Tab),
    /// Read the gamepad at this path (an event device or a pipe of input events); None: let it go.
    UseGamepad(Option<PathBuf>),
    /// Test mode on or off: buttons light up, nothing fires or moves.
    PadTestMode(bool),
    /// Wait for the next button pressed or axis moved, to bind it; None: stop waiting.
    BindPad(Option<Bind>),
    /// Show or hide the robot's preview (the world view for a base) beside the panels.
    ShowView(bool),
    /// Ask the user for a file (the answer comes back as the matching action).
    AskFile(FileRequest),
    /// Stop the running board operation after its current step.
    CancelOperation,
    /// Start an empty project (asks first if there are unsaved changes).
    NewProject,
    /// Open a project file (asks first if there are unsaved changes).
    Open(PathBuf),
    /// Save to the document's file (or ask where, if it has none).
    Save,
    /// Save to this file.
    SaveAs(PathBuf),
    /// Answer to "unsaved changes": save first, then go on.
    UnsavedSave,
    /// Answer to "unsaved changes": drop them and go on.
    UnsavedDiscard,
    /// Answer to "unsaved changes": do nothing.
    UnsavedCancel,
    /// Take the autosaved project offered at start.
    Recover,
    /// Decline the autosaved project offered at start.
    DeclineRecovery,
    /// Write the recovery file now if there are unsaved changes.
    Autosave,
    /// The process is asked to end (a signal): stop the board, keep the work
    /// in the recovery file, close.
    Terminate,
    /// What the import window asks for.
    Import(ImportAction),
    /// What the servo board's panels ask for.
    Servo(ServoAction),
    /// What the PLEN2's panels ask for.
    Plen2(Plen2Action),
    /// What the rFLEX base's panels ask for.
    Rflex(RflexAction),
}

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
    /// The drag turning a servo let go: the turn is one undo step.
    TurnDone,
    /// Hold or release one servo's torque.
    SetHold {
        /// The servo.
        servo_id: u8,
        /// Hold (true) or release (false).
        hold: bool,
    },
    /// Let servos move again after a STOP.
    Resume,
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
    /// The drag turning a joint let go: the turn is one undo step.
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

/// An rFLEX panel's request.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RflexAction {
    /// Drive the base at this velocity (held until changed; 0, 0 stops).
    Drive {
        /// m/s, forward positive.
        speed_m_per_s: f64,
        /// rad/s, left positive.
        turn_rad_per_s: f64,
    },
    /// Choose the robot preset.
    SetRobot(crate::project::rflex::Robot),
    /// Set or release the brake.
    SetBrake(bool),
    /// Turn the sonar ring on or off.
    SetSonar(bool),
    /// Forget the echoes heard so far.
    ClearMap,
}

/// What was asked for when the document had unsaved changes.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum AfterUnsaved {
    /// Start an empty project.
    New,
    /// Open this file.
    Open(PathBuf),
    /// Close the window.
    Quit,
}
