//! What panels ask for. Panels never change state themselves: they push
//! actions, and the app shell applies them in one place — the shell's own,
//! and each family's, which it hands to the family that owns them.

use std::any::Any;
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
    /// stopped and every joint home; a base stopped at once — and the editor's
    /// own previews and sound; nothing that moves a robot goes out until [`Action::Resume`].
    Stop,
    /// After STOP: moves may go out again.
    Resume,
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
    /// What the show window asks for.
    Show(ShowAction),
    /// The project's sound track: add, locate, offset, play in step with a preview.
    Sound(SoundAction),
    /// What a family's panels ask for (its own action type, which only that
    /// family's ui takes back).
    Family(Box<dyn FamilyAction>),
}

impl Action {
    /// A family's own action.
    pub fn family(action: impl FamilyAction) -> Self {
        Self::Family(Box::new(action))
    }

    #[cfg(test)]
    /// The family action this is, if it is a `T`.
    pub fn family_action<T: Any>(&self) -> Option<&T> {
        let Self::Family(action) = self else { return None };
        let action: &dyn Any = &**action;
        action.downcast_ref()
    }
}

/// A family's own action type names its family.
pub trait ActionOf {
    /// The family whose ui applies it.
    const FAMILY: Family;

    /// Whether it moves a robot (a servo, a joint, a motion, a drive): after
    /// STOP, refused until Resume.
    fn moves_robot(&self) -> bool {
        false
    }
}

/// A family's action as the shell carries it, whatever its type.
pub trait FamilyAction: Any + std::fmt::Debug {
    /// The family whose ui applies it.
    fn owner(&self) -> Family;
    /// A copy.
    fn boxed_clone(&self) -> Box<dyn FamilyAction>;
    /// Whether it is the same action as `other`.
    fn same_as(&self, other: &dyn FamilyAction) -> bool;
    /// Whether it moves a robot (see [`ActionOf::moves_robot`]).
    fn moves_robot(&self) -> bool;
    /// Itself, for its family to take back.
    fn into_any(self: Box<Self>) -> Box<dyn Any>;
}

impl<T: ActionOf + Any + Clone + PartialEq + std::fmt::Debug> FamilyAction for T {
    fn owner(&self) -> Family {
        T::FAMILY
    }
    fn boxed_clone(&self) -> Box<dyn FamilyAction> {
        Box::new(self.clone())
    }
    fn same_as(&self, other: &dyn FamilyAction) -> bool {
        let other: &dyn Any = other;
        other.downcast_ref::<T>() == Some(self)
    }
    fn moves_robot(&self) -> bool {
        ActionOf::moves_robot(self)
    }
    fn into_any(self: Box<Self>) -> Box<dyn Any> {
        self
    }
}

impl Clone for Box<dyn FamilyAction> {
    fn clone(&self) -> Self {
        self.boxed_clone()
    }
}

impl PartialEq for Box<dyn FamilyAction> {
    fn eq(&self, other: &Self) -> bool {
        self.same_as(&**other)
    }
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

/// What the show window asks for.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ShowAction {
    /// Open this show (or project) file.
    Open(PathBuf),
    /// The open project as a show of one device.
    OpenProject,
    /// Add the open project to the show as a device.
    AddOpenProject,
    /// Add a project file (one device) or a show file's devices to the show.
    AddFromFile(PathBuf),
    /// Connect every device and hold the links while the window is open (`true`), or let them go.
    Boards(bool),
    /// Serve remote control on the show's boards (`true`), or stop.
    Remote(bool),
    /// Open the remote control window (Settings → Remote control…).
    RemoteWindow,
    /// Connect every device and play the show.
    Play,
    /// Stop every device.
    StopAll,
    /// Play the show on the stage from the time shown, with its sound (`true`), or stop that.
    Preview(bool),
    /// Record a pass of the axis picked while the show previews (`true`), or end it and join it.
    RecordPass(bool),
    /// Take the last pass back.
    UndoPass,
    /// Write the show (version 3) to this file.
    Save(PathBuf),
    /// Close the window (stopping a show that plays).
    Close,
}

impl ShowAction {
    /// Whether it moves the show's boards: playing the show on them (a preview
    /// or a pass followed on held boards is stopped by STOP and started again by hand).
    pub fn moves_robots(&self) -> bool {
        matches!(self, Self::Play)
    }
}

/// What a sound action asks.
#[derive(Clone, Debug, PartialEq)]
pub enum SoundAction {
    /// Add this file as the project's sound track (replacing any).
    Add(PathBuf),
    /// The project's sound is now this file (keeping the offset and sensitivity).
    Locate(PathBuf),
    /// Keep the changed file, as it is now.
    AcceptChanged,
    /// No sound track.
    Remove,
    /// Where the sound starts on the motion's time, ms.
    SetOffset(i64),
    /// Onset sensitivity, percent.
    SetSensitivity(u8),
    /// Open the follow-the-sound dialog.
    OpenFollow,
    /// Play the sound from the motion's `from_ms` (the preview started, or went on from elsewhere).
    Play {
        /// The motion's time, ms.
        from_ms: f64,
    },
    /// Stop the sound.
    Silence,
    /// A short grain at the motion's `at_ms` (scrubbing).
    Grain {
        /// The motion's time, ms.
        at_ms: f64,
    },
}
