//! Validation: every problem of a project, each with where it is.

use std::fmt;

use super::document::{Family, Project};
use crate::protocol::servo::STR32_LEN;

mod plen2;
mod problems;
mod rflex;
mod servo;

pub use plen2::validate_plen2;
pub use problems::Problems;

pub use servo::validate_servo;

/// How serious a problem is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Severity {
    /// Worth a look; the project can still be uploaded.
    Warning,
    /// The project cannot be uploaded until this is fixed.
    Error,
}

/// Where in a project a problem is. Indices are 1-based, as a person counts.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Location {
    /// The project as a whole.
    Project,
    /// A servo.
    Servo {
        /// Its id.
        servo_id: u8,
        /// Its caption.
        caption: String,
    },
    /// An action.
    Action {
        /// Its id.
        action_id: i32,
        /// Its caption.
        caption: String,
    },
    /// One step of an action.
    Step {
        /// The action's id.
        action_id: i32,
        /// The action's caption.
        caption: String,
        /// The step's position, from 1.
        step: usize,
    },
    /// A macro.
    Macro {
        /// Its id.
        macro_id: i32,
        /// Its caption.
        caption: String,
    },
    /// One command of a macro.
    Command {
        /// The macro's id.
        macro_id: i32,
        /// The macro's caption.
        caption: String,
        /// The command's position, from 1.
        command: usize,
    },
    /// A joystick table.
    Table {
        /// Its id.
        table_id: i32,
        /// Its caption.
        caption: String,
    },
    /// A button of a joystick table.
    Button {
        /// The table's id.
        table_id: i32,
        /// The table's caption.
        table_caption: String,
        /// The button's id.
        button_id: u32,
        /// The button's caption.
        caption: String,
    },
    /// A PLEN2 joint's settings.
    Joint {
        /// The device map's name, e.g. `left_knee_pitch`.
        joint: &'static str,
    },
    /// A PLEN2 motion.
    Motion {
        /// Its slot (0..=89).
        slot: u8,
        /// Its name.
        name: String,
    },
    /// One frame of a PLEN2 motion.
    Frame {
        /// The motion's slot.
        slot: u8,
        /// The motion's name.
        name: String,
        /// The frame's position, from 1.
        frame: usize,
    },
    /// A PLEN2 play list.
    PlayList {
        /// Its position, from 1.
        index: usize,
        /// Its name.
        name: String,
    },
    /// The rFLEX robot settings.
    Robot,
    /// A gamepad button's binding.
    GamepadButton {
        /// Its code (`BTN_SOUTH` = 0x130, …).
        button: u16,
    },
    /// A gamepad axis's binding.
    GamepadAxis {
        /// Its code (`ABS_X` = 0, …).
        axis: u16,
    },
    /// A key of the file, by its path (`servo.servos[3].min_degs`).
    Key {
        /// Where it is, from the top of the file.
        path: String,
    },
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let q = |text| Shortened { text, quoted: true };
        match self {
            Self::Project => write!(f, "project"),
            Self::Servo { servo_id, caption } => write!(f, "servo {servo_id} {}", q(caption)),
            Self::Action { action_id, caption } => write!(f, "action {action_id} {}", q(caption)),
            Self::Step { action_id, caption, step } => write!(f, "action {action_id} {}, step {step}", q(caption)),
            Self::Macro { macro_id, caption } => write!(f, "macro {macro_id} {}", q(caption)),
            Self::Command { macro_id, caption, command } => {
                write!(f, "macro {macro_id} {}, command {command}", q(caption))
            }
            Self::Table { table_id, caption } => write!(f, "joystick table {table_id} {}", q(caption)),
            Self::Button { table_id, table_caption, button_id, caption } => {
                write!(f, "joystick table {table_id} {}, button 0x{button_id:08x} {}", q(table_caption), q(caption))
            }
            Self::Joint { joint } => write!(f, "joint {joint}"),
            Self::Motion { slot, name } => write!(f, "motion {slot} {}", q(name)),
            Self::Frame { slot, name, frame } => write!(f, "motion {slot} {}, frame {frame}", q(name)),
            Self::PlayList { index, name } => write!(f, "play list {index} {}", q(name)),
            Self::Robot => write!(f, "robot"),
            Self::GamepadButton { button } => write!(f, "gamepad button 0x{button:03x}"),
            Self::GamepadAxis { axis } => write!(f, "gamepad axis {axis}"),
            Self::Key { path } => write!(f, "{}", Shortened { text: path, quoted: false }),
        }
    }
}

/// At most this many characters of a caption or a key are shown in a
/// location; the rest is "…" (a 100,000-character caption is not echoed).
pub const SHOWN_CHARS: usize = 40;

/// Text cut to [`SHOWN_CHARS`] characters, in quotes (with escapes) when `quoted`.
struct Shortened<'a> {
    text: &'a str,
    quoted: bool,
}

impl fmt::Display for Shortened<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let cut = self.text.char_indices().nth(SHOWN_CHARS).map(|(at, _)| at);
        let shown = cut.map_or(self.text, |at| &self.text[..at]);
        let more = if cut.is_some() { "…" } else { "" };
        if self.quoted { write!(f, "{shown:?}{more}") } else { write!(f, "{shown}{more}") }
    }
}

/// What kind of item an id belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ItemKind {
    /// A servo.
    Servo,
    /// An action.
    Action,
    /// A macro.
    Macro,
    /// A joystick table.
    Table,
}

impl ItemKind {
    /// The English word.
    pub fn word(self) -> &'static str {
        match self {
            Self::Servo => "servo",
            Self::Action => "action",
            Self::Macro => "macro",
            Self::Table => "joystick table",
        }
    }
}

/// Which button event a binding is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ButtonSlot {
    /// The press macro.
    Press,
    /// The long-press macro.
    LongPress,
    /// The release macro.
    Release,
}

/// What is wrong, as data, so that an interface can say it in its own language.
/// `Display` gives the English text.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum ProblemKind {
    /// A caption longer than the board's 32 bytes.
    CaptionTooLong {
        /// Its UTF-8 length.
        bytes: usize,
    },
    /// An id below 1 (0 is the board's "none").
    IdNotPositive {
        /// Of what.
        kind: ItemKind,
        /// The id.
        id: i32,
    },
    /// An id used twice.
    DuplicateId {
        /// Of what.
        kind: ItemKind,
        /// The id, as text.
        id: String,
    },
    /// Servo id 255, which addresses all servos.
    ReservedServoId,
    /// A servo's min above its max.
    MinAboveMax {
        /// Min, °.
        min_deg: i16,
        /// Max, °.
        max_deg: i16,
    },
    /// A servo's home outside its limits.
    HomeOutsideLimits {
        /// Home, °.
        home_deg: i16,
        /// Min, °.
        min_deg: i16,
        /// Max, °.
        max_deg: i16,
    },
    /// An action without steps.
    NoSteps,
    /// A servo with two steps in one action.
    ServoTwiceInAction {
        /// The servo.
        servo_id: u8,
    },
    /// A negative step interval.
    NegativeInterval {
        /// The interval, × 10 ms.
        interval_10ms: i16,
    },
    /// A step naming a servo the project lacks.
    MissingServo {
        /// The servo.
        servo_id: u8,
    },
    /// A step angle outside its servo's limits.
    StepOutsideLimits {
        /// The angle, °.
        degree: i16,
        /// The servo.
        servo_id: u8,
        /// Min, °.
        min_deg: i16,
        /// Max, °.
        max_deg: i16,
    },
    /// A macro without commands.
    NoCommands,
    /// More commands than one board frame holds.
    TooManyCommands {
        /// How many.
        count: usize,
        /// The most a frame holds.
        max: usize,
    },
    /// A ratio outside 1..=100.
    RatioOutOfRange {
        /// The ratio, %.
        ratio_percent: u8,
    },
    /// A loop count below 1.
    LoopBelowOne {
        /// The loop count.
        loop_count: i16,
    },
    /// A command naming a missing action.
    MissingAction {
        /// The action.
        action_id: i32,
    },
    /// A command naming a missing macro.
    MissingMacro {
        /// The macro.
        macro_id: i32,
    },
    /// A negative delay.
    NegativeDelay {
        /// The delay, ms.
        delay_ms: i32,
    },
    /// A run time the board's 32-bit field cannot hold.
    TotalTooLong {
        /// The run time, ms.
        total_ms: i64,
    },
    /// A rigged servo mounted on a servo the project lacks (or one without a rig).
    RigUnknownParent {
        /// The parent named.
        parent: u8,
    },
    /// A rigged servo whose Mirror L/R twin is not another rigged servo.
    RigUnknownTwin {
        /// The twin named.
        twin: u8,
    },
    /// A gamepad binding that is also made by another (a button twice, a
    /// servo or joint moved by two axes), or a button another use holds.
    BoundTwice,
    /// A gamepad button that plays a play list the project lacks.
    MissingPlayList {
        /// The play list's position, from 1.
        index: usize,
    },
    /// Rigged servos mounted on each other in a ring.
    RigCycle {
        /// The servo ids along the ring, first repeated at the end.
        path: Vec<u8>,
    },
    /// A macro that reaches itself.
    MacroCycle {
        /// The macro ids along the cycle, first repeated at the end.
        path: Vec<i32>,
    },
    /// More buttons than one board frame holds.
    TooManyButtons {
        /// How many.
        count: usize,
        /// The most a frame holds.
        max: usize,
    },
    /// A button id used twice in one table.
    DuplicateButton {
        /// The button.
        button_id: u32,
    },
    /// A button bound to a missing macro.
    MissingButtonMacro {
        /// Which binding.
        slot: ButtonSlot,
        /// The macro.
        macro_id: i32,
    },
    /// A button that runs no macro.
    ButtonRunsNothing,
    /// The active table does not exist.
    MissingActiveTable {
        /// The table.
        table_id: i32,
    },
    /// A macro command's total as stored on the board differs from the one derived from the project.
    StoredTotalDiffers {
        /// The stored total, ms (written back unless the command is edited).
        stored_ms: i32,
        /// The derived total, ms.
        derived_ms: i64,
    },
    /// A number outside the range the hardware takes.
    OutOfRange {
        /// The field, as the protocol names it (e.g. `transition_ms`).
        field: &'static str,
        /// The value.
        value: i64,
        /// Lowest allowed.
        min: i64,
        /// Highest allowed.
        max: i64,
    },
    /// A slot used by two motions.
    DuplicateSlot {
        /// The slot.
        slot: u8,
    },
    /// A joint listed twice in the joint settings.
    DuplicateJoint,
    /// A name longer than the hardware stores.
    NameTooLong {
        /// Its length in bytes.
        bytes: usize,
        /// The most stored.
        max: usize,
    },
    /// A name with characters that are not printable ASCII.
    NameNotAscii,
    /// A motion without frames.
    NoFrames,
    /// A loop range that is not inside the motion's frames.
    BadLoopRange {
        /// First looped frame, from 0.
        begin_frame: u8,
        /// Last looped frame, from 0.
        end_frame: u8,
        /// The motion's frame count.
        frames: usize,
    },
    /// A play list or jump naming a slot the project has no motion in.
    MissingMotion {
        /// The slot.
        slot: u8,
    },
    /// A loop count of 0: the robot decrements it to 255 and loops forever (plen2.md §6).
    LoopRunsForever,
    /// A jump to a slot the robot does not have: it replays this motion forever.
    JumpBeyondSlots {
        /// The slot jumped to.
        slot: u8,
    },
    /// The first frame lasts 0 cycles: the robot divides by zero there.
    FirstFrameZeroCycles {
        /// Its transition.
        transition_ms: u16,
    },
    /// A later frame lasts 0 cycles: the robot skips it (its values are
    /// never output; the next frame starts from them).
    FrameSkipped {
        /// Its transition.
        transition_ms: u16,
    },
    /// A conversion constant that is not a positive number.
    NotPositive {
        /// The field.
        field: &'static str,
    },
    /// A key Servo Studio does not know: ignored (a misspelt name?).
    UnknownKey,
}

impl fmt::Display for ProblemKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::CaptionTooLong { bytes } => {
                write!(f, "caption is {bytes} UTF-8 bytes; the board stores at most {STR32_LEN}")
            }
            Self::IdNotPositive { kind, id } => {
                write!(f, "{} id must be 1 or more (0 means \"none\" on the board), not {id}", kind.word())
            }
            Self::DuplicateId { kind, id } => write!(f, "duplicate {} id {id}", kind.word()),
            Self::ReservedServoId => write!(f, "servo id 255 is reserved (it addresses all servos); use 0..=254"),
            Self::MinAboveMax { min_deg, max_deg } => write!(f, "min {min_deg}° is above max {max_deg}°"),
            Self::HomeOutsideLimits { home_deg, min_deg, max_deg } => {
                write!(f, "home {home_deg}° is outside the limits {min_deg}°..{max_deg}°")
            }
            Self::NoSteps => write!(f, "has no steps: running it does nothing"),
            Self::ServoTwiceInAction { servo_id } => write!(f, "servo {servo_id} already has a step in this action"),
            Self::NegativeInterval { interval_10ms } => write!(f, "interval {interval_10ms} × 10 ms is negative"),
            Self::MissingServo { servo_id } => write!(f, "servo {servo_id} does not exist"),
            Self::StepOutsideLimits { degree, servo_id, min_deg, max_deg } => {
                write!(f, "{degree}° is outside servo {servo_id}'s limits {min_deg}°..{max_deg}°")
            }
            Self::NoCommands => write!(f, "has no commands: running it does nothing"),
            Self::TooManyCommands { count, max } => {
                write!(f, "has {count} commands; one board frame holds at most {max}")
            }
            Self::RatioOutOfRange { ratio_percent } => write!(f, "ratio {ratio_percent} % is outside 1..=100"),
            Self::LoopBelowOne { loop_count } => write!(f, "loop count {loop_count} must be 1 or more"),
            Self::MissingAction { action_id } => write!(f, "action {action_id} does not exist"),
            Self::MissingMacro { macro_id } => write!(f, "macro {macro_id} does not exist"),
            Self::NegativeDelay { delay_ms } => write!(f, "delay {delay_ms} ms is negative"),
            Self::TotalTooLong { total_ms } => {
                write!(f, "runs for {total_ms} ms, more than the board can count ({} ms)", i32::MAX)
            }
            Self::MacroCycle { path } => {
                let names: Vec<String> = path.iter().map(ToString::to_string).collect();
                write!(f, "macro cycle {}: a macro must not reach itself", names.join(" → "))
            }
            Self::RigUnknownParent { parent } => {
                write!(
                    f,
                    "its rig is mounted on servo {parent}, which is not in the rig: rig that servo or pick another parent"
                )
            }
            Self::RigCycle { path } => {
                let names: Vec<String> = path.iter().map(ToString::to_string).collect();
                write!(f, "rig cycle {}: a servo cannot be mounted on itself", names.join(" → "))
            }
            Self::RigUnknownTwin { twin } => write!(
                f,
                "its Mirror L/R twin is servo {twin}, which is not another servo of the rig: Mirror L/R keeps its steps; name a rigged servo on the other side"
            ),
            Self::BoundTwice => {
                write!(f, "is bound twice (or held by another use): only one of its bindings works; remove the others")
            }
            Self::MissingPlayList { index } => write!(f, "play list {index} does not exist"),
            Self::TooManyButtons { count, max } => {
                write!(f, "has {count} buttons; one board frame holds at most {max}")
            }
            Self::DuplicateButton { button_id } => write!(f, "duplicate button id 0x{button_id:08x} in this table"),
            Self::MissingButtonMacro { slot, macro_id } => {
                let event = match slot {
                    ButtonSlot::Press => "press",
                    ButtonSlot::LongPress => "long-press",
                    ButtonSlot::Release => "release",
                };
                write!(f, "{event} macro {macro_id} does not exist")
            }
            Self::ButtonRunsNothing => write!(f, "runs no macro"),
            Self::MissingActiveTable { table_id } => write!(f, "active joystick table {table_id} does not exist"),
            Self::StoredTotalDiffers { stored_ms, derived_ms } => write!(
                f,
                "the board stored a total of {stored_ms} ms, the project derives {derived_ms} ms; the stored one is kept until you edit this command"
            ),
            Self::OutOfRange { field, value, min, max } => write!(f, "{field} {value} is outside {min}..={max}"),
            Self::DuplicateSlot { slot } => write!(f, "slot {slot} holds another motion already"),
            Self::DuplicateJoint => write!(f, "listed twice"),
            Self::NameTooLong { bytes, max } => write!(f, "name is {bytes} bytes; the robot stores at most {max}"),
            Self::NameNotAscii => write!(f, "name must be printable ASCII (the robot stores bytes, not text)"),
            Self::NoFrames => write!(f, "has no frames"),
            Self::BadLoopRange { begin_frame, end_frame, frames } => {
                write!(f, "loop from frame {begin_frame} to {end_frame} is not inside its {frames} frame(s)")
            }
            Self::MissingMotion { slot } => write!(f, "no motion in slot {slot}"),
            Self::LoopRunsForever => write!(
                f,
                "loop count 0 runs forever: the robot counts it down to 255 (give 1 for two passes, 255 to say forever)"
            ),
            Self::JumpBeyondSlots { slot } => {
                write!(f, "jump to slot {slot}: the robot has slots 0..=89, so it replays this motion forever instead")
            }
            Self::FirstFrameZeroCycles { transition_ms } => write!(
                f,
                "transition_ms {transition_ms} is 0 cycles of 32 ms: as the first frame the robot divides by zero (what it does is undefined); give 32..=8191"
            ),
            Self::FrameSkipped { transition_ms } => write!(
                f,
                "transition_ms {transition_ms} is 0 cycles of 32 ms: the robot skips this frame (its pose is never shown, the next frame starts from it)"
            ),
            Self::NotPositive { field } => write!(f, "{field} must be a positive number"),
            Self::UnknownKey => write!(f, "unknown key, ignored (is it misspelt?)"),
        }
    }
}

/// One problem found in a project.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Problem {
    /// How serious it is.
    pub severity: Severity,
    /// Where it is.
    pub location: Location,
    /// What is wrong.
    pub kind: ProblemKind,
}

impl fmt::Display for Problem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let severity = match self.severity {
            Severity::Error => "error",
            Severity::Warning => "warning",
        };
        write!(f, "{severity}: {}: {}", self.location, self.kind)
    }
}

/// Every problem of the document's own family's section, in document order
/// (the first thousand of each severity kept, all counted), then of its
/// gamepad bindings.
pub fn validate(project: &Project) -> Problems {
    let mut problems = match project.family {
        Family::Servo => validate_servo(&project.servo),
        Family::Plen2 => validate_plen2(&project.plen2),
        Family::Rflex => rflex::validate_rflex(&project.rflex),
    };
    problems.extend(gamepad(project));
    problems
}

/// The family's gamepad bindings: what they fire or move exists, and nothing
/// is bound twice (warnings: the bindings are the editor's, not the robot's;
/// a PLEN2 motion may be on the robot without being in the project).
fn gamepad(project: &Project) -> Vec<Problem> {
    use super::gamepad::{AxisTarget, Conflict, Fire};
    let mapping = match project.family {
        Family::Servo => &project.gamepad.servo,
        Family::Plen2 => &project.gamepad.plen2,
        Family::Rflex => &project.gamepad.rflex,
    };
    let warning = |location, kind| Problem { severity: Severity::Warning, location, kind };
    let mut problems = Vec::new();
    for binding in &mapping.buttons {
        let missing = match binding.fire {
            Fire::Action(action_id) if project.servo.action(action_id).is_none() => {
                Some(ProblemKind::MissingAction { action_id })
            }
            Fire::Macro(macro_id) if project.servo.macro_by_id(macro_id).is_none() => {
                Some(ProblemKind::MissingMacro { macro_id })
            }
            Fire::PlayList(index) if index >= project.plen2.play_lists.len() => {
                Some(ProblemKind::MissingPlayList { index: index + 1 })
            }
            _ => None,
        };
        problems.extend(missing.map(|kind| warning(Location::GamepadButton { button: binding.button }, kind)));
    }
    for binding in &mapping.axes {
        if let AxisTarget::Servo(servo_id) = binding.target
            && project.servo.servo(servo_id).is_none()
        {
            problems
                .push(warning(Location::GamepadAxis { axis: binding.axis }, ProblemKind::MissingServo { servo_id }));
        }
    }
    // The rFLEX dead-man is the base's own: `ui` reserves it; here only twice-bound is said.
    for conflict in mapping.conflicts(&[]) {
        let location = match conflict {
            Conflict::Button(button) | Conflict::Reserved(button) => Location::GamepadButton { button },
            Conflict::Target(target) => {
                let axis =
                    mapping.axes.iter().find(|binding| binding.target == target).map_or(0, |binding| binding.axis);
                Location::GamepadAxis { axis }
            }
        };
        problems.push(warning(location, ProblemKind::BoundTwice));
    }
    problems
}

/// Whether any problem is an error.
pub fn has_errors(problems: &[Problem]) -> bool {
    problems.iter().any(|problem| problem.severity == Severity::Error)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_twin_outside_the_rig_and_gamepad_bindings_to_nothing_or_twice_are_warned_about() {
        use crate::project::gamepad::{AxisBinding, AxisTarget, ButtonBinding, Fire};
        use crate::project::{RigAxis, RigJoint, Servo, ServoProject};
        let rig = |mirror| RigJoint {
            parent: None,
            offset_mm: [0; 3],
            axis: RigAxis::Y,
            reversed: false,
            straight_deg: 0,
            mirror,
        };
        let mut servos = vec![Servo::new(1, "L"), Servo::new(2, "R"), Servo::new(3, "head")];
        servos[0].rig = Some(rig(Some(2)));
        servos[1].rig = Some(rig(Some(9)));
        servos[2].rig = Some(rig(Some(3)));
        let mut project = Project::servo(ServoProject { servos, ..ServoProject::default() });
        let button = |button, fire| ButtonBinding { button, fire };
        project.gamepad.servo.buttons =
            vec![button(0x130, Fire::Action(7)), button(0x131, Fire::Macro(8)), button(0x131, Fire::Stop)];
        project.gamepad.servo.axes = vec![AxisBinding::absolute(0, AxisTarget::Servo(42), (-90.0, 90.0))];
        let said: Vec<String> = validate(&project).iter().map(ToString::to_string).collect();
        assert_eq!(
            said,
            [
                "warning: servo 2 \"R\": its Mirror L/R twin is servo 9, which is not another servo of the rig: Mirror L/R keeps its steps; name a rigged servo on the other side",
                "warning: servo 3 \"head\": its Mirror L/R twin is servo 3, which is not another servo of the rig: Mirror L/R keeps its steps; name a rigged servo on the other side",
                "warning: gamepad button 0x130: action 7 does not exist",
                "warning: gamepad button 0x131: macro 8 does not exist",
                "warning: gamepad axis 0: servo 42 does not exist",
                "warning: gamepad button 0x131: is bound twice (or held by another use): only one of its bindings works; remove the others",
            ]
        );
        assert!(!validate(&project).has_errors(), "the bindings and twins are the editor's: nothing is refused");
    }

    #[test]
    fn a_long_caption_is_cut_where_a_location_is_shown() {
        let caption = "揮手".repeat(50_000);
        let shown = Location::Action { action_id: 3, caption }.to_string();
        assert_eq!(shown, format!("action 3 {:?}…", "揮手".repeat(20)));
        assert_eq!(Location::Servo { servo_id: 1, caption: "頭".into() }.to_string(), "servo 1 \"頭\"");
        let key = Location::Key { path: format!("servos[0].{}", "k".repeat(100)) }.to_string();
        assert_eq!(key, format!("servos[0].{}…", "k".repeat(30)));
    }
}
