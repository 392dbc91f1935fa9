//! The project document: what a user saves and what a board stores, plus the
//! client-side safety settings the board protocol does not carry.
//! Field by field in `docs/project-format.md`.

use serde::{Deserialize, Serialize};

/// The servo section of a project: servos, actions, macros and joystick tables.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct ServoProject {
    /// The project id written to the board (30120); 0 means none.
    #[serde(default)]
    pub project_id: i32,
    /// The servos, in display order.
    #[serde(default, deserialize_with = "super::bounded::list")]
    pub servos: Vec<Servo>,
    /// The actions (poses), in display order.
    #[serde(default, deserialize_with = "super::bounded::list")]
    pub actions: Vec<Action>,
    /// The macros (sequences of actions and delays), in display order.
    #[serde(default, deserialize_with = "super::bounded::list")]
    pub macros: Vec<Macro>,
    /// The remote-control button tables, in display order.
    #[serde(default, deserialize_with = "super::bounded::list")]
    pub joystick_tables: Vec<JoystickTable>,
    /// The table the board uses, if any.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub active_table: Option<i32>,
    /// What the figure's links look like: a mesh file each (client-side only).
    #[serde(default, skip_serializing_if = "Vec::is_empty", deserialize_with = "super::bounded::list")]
    pub meshes: Vec<LinkMesh>,
}

/// A mesh (STL or OBJ) a link of the figure is drawn with, placed in the
/// link's frame (client-side only: the board never sees it).
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct LinkMesh {
    /// The servo whose link carries it; none: the robot's body.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub servo_id: Option<u8>,
    /// The file, relative to the project file's folder ('/' between folders).
    pub path: String,
    /// Where the file's origin sits in the link's frame, mm.
    #[serde(default)]
    pub offset_mm: [i16; 3],
    /// How the file is turned in the link's frame: about x, then y, then z, °.
    #[serde(default)]
    pub rotation_deg: [i16; 3],
    /// Millimetres per unit of the file, in thousandths (1000: the file is in mm).
    #[serde(default = "LinkMesh::default_scale")]
    pub scale_milli: u32,
}

impl LinkMesh {
    fn default_scale() -> u32 {
        1000
    }
}

/// One servo: its board parameters and its client-side limits.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Servo {
    /// `servoID` on the board (0..=254; 255 addresses all servos).
    pub id: u8,
    /// `servoCaption`, at most 32 UTF-8 bytes.
    #[serde(default)]
    pub caption: String,
    /// `adjustedDegree`: the calibration offset the board stores for this servo.
    #[serde(default)]
    pub calibration_offset_deg: i16,
    /// Lowest angle the app will ever send to this servo (client-side only).
    #[serde(default = "Servo::default_min_deg")]
    pub min_deg: i16,
    /// Highest angle the app will ever send to this servo (client-side only).
    #[serde(default = "Servo::default_max_deg")]
    pub max_deg: i16,
    /// The rest angle, between `min_deg` and `max_deg` (client-side only).
    #[serde(default)]
    pub home_deg: i16,
    /// Where it sits in the robot's skeleton, for the 3D preview (client-side
    /// only; a servo without one is shown as a bar beside the figure).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rig: Option<RigJoint>,
}

/// A servo's place in the robot's skeleton: the link it turns, mounted on its
/// parent's link. Frames: x forward, y left, z up (mm), each link's own frame
/// the parent's turned by the parent's joint.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct RigJoint {
    /// The servo whose link it is mounted on; none: the robot's body.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub parent: Option<u8>,
    /// Where its joint sits in the parent's frame, mm.
    #[serde(default)]
    pub offset_mm: [i16; 3],
    /// The axis it turns about.
    pub axis: RigAxis,
    /// A larger angle turns the other way round the axis.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub reversed: bool,
    /// The servo angle at which its link is straight (as the offsets of the
    /// servos mounted on it are given), °.
    #[serde(default)]
    pub straight_deg: i16,
    /// Its twin on the other side (Mirror L/R hands a move to it, the angle
    /// reflected about their homes); either twin may name the other.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mirror: Option<u8>,
    /// Its link is a hand or a foot: posed by dragging its end in the 3D view.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub end: Option<RigEnd>,
}

/// A link posed by its end: the chain that moves it runs from `root` down to it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct RigEnd {
    /// The first servo of the chain (an ancestor, or itself); none: every
    /// servo from the body down.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub root: Option<u8>,
    /// The point held, in its link's frame, mm (a sole's middle, a fingertip).
    #[serde(default)]
    pub tip_mm: [i16; 3],
}

/// An axis of a link's frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum RigAxis {
    /// Forward: a roll.
    X,
    /// Left: a pitch.
    #[default]
    Y,
    /// Up: a yaw.
    Z,
}

impl RigAxis {
    /// Every axis, in order.
    pub const ALL: [Self; 3] = [Self::X, Self::Y, Self::Z];
}

impl Servo {
    fn default_min_deg() -> i16 {
        -180
    }

    fn default_max_deg() -> i16 {
        180
    }

    /// A servo with the given id and caption, full ±180° range, home at 0.
    pub fn new(id: u8, caption: impl Into<String>) -> Self {
        Self {
            id,
            caption: caption.into(),
            calibration_offset_deg: 0,
            min_deg: Self::default_min_deg(),
            max_deg: Self::default_max_deg(),
            home_deg: 0,
            rig: None,
        }
    }

    /// The limit farther from `degree`: where a servo whose position is not
    /// known is taken to be, so a move timed from there can never be too fast.
    pub fn farther_limit(&self, degree: f64) -> f64 {
        let (low, high) = (f64::from(self.min_deg.min(self.max_deg)), f64::from(self.max_deg.max(self.min_deg)));
        if (degree - low).abs() > (degree - high).abs() { low } else { high }
    }

    /// `degree` clamped into this servo's limits.
    pub fn clamp(&self, degree: i16) -> i16 {
        degree.clamp(self.min_deg.min(self.max_deg), self.max_deg.max(self.min_deg))
    }
}

/// A pose: servos moving together. All steps start at once; the action lasts
/// as long as its longest step.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Action {
    /// `actionID` (1..=2147483647).
    pub id: i32,
    /// `actionCaption`, at most 32 UTF-8 bytes.
    #[serde(default)]
    pub caption: String,
    /// One step per servo.
    #[serde(default, deserialize_with = "super::bounded::list")]
    pub steps: Vec<Step>,
}

/// One servo's part of an action.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Step {
    /// The servo that moves.
    pub servo_id: u8,
    /// The angle it moves to.
    pub degree: i16,
    /// How long the move takes, in units of 10 ms.
    pub interval_10ms: i16,
    /// The curve of the move (the board moves straight: a curve is baked into
    /// straight sub-steps for it, `authoring::bake_servo`); absent in files when linear.
    #[serde(default, skip_serializing_if = "super::Easing::is_linear")]
    pub easing: super::Easing,
}

impl Step {
    /// A straight step.
    pub fn new(servo_id: u8, degree: i16, interval_10ms: i16) -> Self {
        Self { servo_id, degree, interval_10ms, easing: super::Easing::Linear }
    }
}

/// A sequence of commands run one after another.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Macro {
    /// `macroID` (1..=2147483647).
    pub id: i32,
    /// `macroCaption`, at most 32 UTF-8 bytes.
    #[serde(default)]
    pub caption: String,
    /// The commands, in order.
    #[serde(default, deserialize_with = "super::bounded::list")]
    pub commands: Vec<Command>,
}

/// One command of a macro. Its total run time is derived (see
/// [`crate::project::Timing`]), except that a total read from a board is kept
/// and written back as it was until the command is edited.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Command {
    /// What the command runs.
    #[serde(flatten)]
    pub run: Run,
    /// Speed in percent, 1..=100 (100 = as authored).
    #[serde(default = "Command::default_ratio_percent")]
    pub ratio_percent: u8,
    /// Repetitions, 1 or more.
    #[serde(default = "Command::default_loop_count")]
    pub loop_count: i16,
    /// `totalInterval` as a board stored it, in ms; `None` once edited (then derived).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stored_total_ms: Option<i32>,
}

impl Command {
    fn default_ratio_percent() -> u8 {
        100
    }

    fn default_loop_count() -> i16 {
        1
    }

    /// A command run once at full speed.
    pub fn once(run: Run) -> Self {
        Self { run, ratio_percent: 100, loop_count: 1, stored_total_ms: None }
    }
}

/// What a macro command runs (wire `type` 0, 1, 2).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Run {
    /// Run an action.
    Action {
        /// The action's id.
        action_id: i32,
    },
    /// Wait.
    Delay {
        /// How long, in milliseconds.
        delay_ms: i32,
    },
    /// Run another macro.
    Macro {
        /// The macro's id.
        macro_id: i32,
    },
}

/// A remote-control mapping: which macros each button runs.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct JoystickTable {
    /// `tableID` (1..=2147483647).
    pub id: i32,
    /// `tableCaption`, at most 32 UTF-8 bytes.
    #[serde(default)]
    pub caption: String,
    /// The buttons.
    #[serde(default, deserialize_with = "super::bounded::list")]
    pub buttons: Vec<Button>,
}

/// One button of a joystick table.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Button {
    /// `buttonID` as the remote reports it (any 32-bit value).
    pub id: u32,
    /// `buttonCaption`, at most 32 UTF-8 bytes.
    #[serde(default)]
    pub caption: String,
    /// Macro run when the button goes down.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub press_macro: Option<i32>,
    /// Macro run when the button is held long.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub long_press_macro: Option<i32>,
    /// Macro run when the button comes up.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub release_macro: Option<i32>,
    /// After a long press is released, let the long-press macro finish instead
    /// of cutting it short with the release macro.
    #[serde(default)]
    pub uninterruptible: bool,
}

impl ServoProject {
    /// The servo with this id.
    pub fn servo(&self, servo_id: u8) -> Option<&Servo> {
        self.servos.iter().find(|servo| servo.id == servo_id)
    }

    /// The servo's twin on the other side, as either one's rig names it.
    pub fn twin(&self, servo_id: u8) -> Option<&Servo> {
        let named = self.servo(servo_id)?.rig.and_then(|rig| rig.mirror);
        let naming = || self.servos.iter().find(|other| other.rig.and_then(|rig| rig.mirror) == Some(servo_id));
        named.and_then(|id| self.servo(id)).filter(|twin| twin.id != servo_id).or_else(naming)
    }

    /// Steps mirrored left↔right: a servo with a twin hands its move to it,
    /// turned as the mirror image of its own link (a pitch — about the
    /// left-pointing y axis — keeps its sense, a roll or a yaw turns the other
    /// way; each side's `reversed` and `straight_deg` applied), within the
    /// twin's limits. A servo without a twin (or a rig) keeps its step.
    pub fn mirrored(&self, steps: &[Step]) -> Vec<Step> {
        let sense = |rig: &RigJoint| if rig.reversed { -1 } else { 1 };
        steps
            .iter()
            .map(|step| {
                let own = self.servo(step.servo_id).and_then(|servo| servo.rig);
                let twin = self.twin(step.servo_id);
                let (Some(own), Some((twin, other))) = (own, twin.and_then(|twin| Some((twin, twin.rig?)))) else {
                    return *step;
                };
                let reflect = if own.axis == RigAxis::Y { 1 } else { -1 };
                let turned = sense(&own) * (i32::from(step.degree) - i32::from(own.straight_deg));
                let angle = i32::from(other.straight_deg) + sense(&other) * reflect * turned;
                let angle = i16::try_from(angle.clamp(i32::from(i16::MIN), i32::from(i16::MAX))).unwrap_or(0);
                Step { servo_id: twin.id, degree: twin.clamp(angle), ..*step }
            })
            .collect()
    }

    /// The actions and macros by id, for looking many up (validation,
    /// timing, traces): each lookup then costs the same however many there are.
    pub fn index(&self) -> ServoIndex<'_> {
        let mut index = ServoIndex::default();
        // The first of a duplicated id wins, as `action` and `macro_by_id` find it.
        for action in &self.actions {
            index.actions.entry(action.id).or_insert(action);
        }
        for item in &self.macros {
            index.macros.entry(item.id).or_insert(item);
        }
        index
    }

    /// The action with this id.
    pub fn action(&self, action_id: i32) -> Option<&Action> {
        self.actions.iter().find(|action| action.id == action_id)
    }

    /// The macro with this id.
    pub fn macro_by_id(&self, macro_id: i32) -> Option<&Macro> {
        self.macros.iter().find(|item| item.id == macro_id)
    }

    /// The joystick table with this id.
    pub fn table(&self, table_id: i32) -> Option<&JoystickTable> {
        self.joystick_tables.iter().find(|table| table.id == table_id)
    }
}

// The registry of families: servo controller boards, where their section of the project lives.
inventory::submit! {
    super::family::Registered { family: super::family::Family::Servo, rank: 0 }
}

/// A servo project's actions and macros by id ([`ServoProject::index`]).
#[derive(Clone, Debug, Default)]
pub struct ServoIndex<'a> {
    actions: std::collections::HashMap<i32, &'a Action>,
    macros: std::collections::HashMap<i32, &'a Macro>,
}

impl<'a> ServoIndex<'a> {
    /// The action with this id.
    pub fn action(&self, action_id: i32) -> Option<&'a Action> {
        self.actions.get(&action_id).copied()
    }

    /// The macro with this id.
    pub fn macro_by_id(&self, macro_id: i32) -> Option<&'a Macro> {
        self.macros.get(&macro_id).copied()
    }
}
