//! Validation: every problem of a project, each with where it is.

use std::fmt;

pub use location::Location;

use super::document::Project;
use super::family::Family;
use crate::protocol::servo::STR32_LEN;

mod gamepad;
mod location;
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
    /// What a family that keeps its own section says is wrong with it, in its words.
    Section {
        /// The family's words.
        message: String,
    },
}

impl fmt::Display for ProblemKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.board_fmt(f) {
            Some(written) => written,
            None => self.other_fmt(f),
        }
    }
}

impl ProblemKind {
    /// A servo board's problem (captions, ids, limits, steps, commands, tables), written; None: another's.
    fn board_fmt(&self, f: &mut fmt::Formatter<'_>) -> Option<fmt::Result> {
        Some(match self {
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
            _ => return None,
        })
    }

    /// A rig's, a gamepad binding's, a PLEN2's or any section's problem, written.
    fn other_fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
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
            Self::Section { message } => write!(f, "{message}"),
            // Written by `board_fmt`.
            _ => Ok(()),
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

/// Every problem of the document's own family's typed section, in document order
/// (the first thousand of each severity kept, all counted), then of its
/// gamepad bindings.
pub fn validate(project: &Project) -> Problems {
    let mut problems = match project.family {
        Family::Servo => validate_servo(&project.servo),
        Family::Plen2 => validate_plen2(&project.plen2),
        Family::Rflex => rflex::validate_rflex(&project.rflex),
        // A family whose project has no section of its own has nothing to check.
        _ => Problems::default(),
    };
    problems.extend(gamepad::gamepad(project));
    problems
}

/// Whether any problem is an error.
pub fn has_errors(problems: &[Problem]) -> bool {
    problems.iter().any(|problem| problem.severity == Severity::Error)
}
