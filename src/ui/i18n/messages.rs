//! Whole sentences in each language: link and request errors, validation
//! problems, operation errors, status lines.

use super::Language;
use crate::say;

impl Language {
    /// A link error in this language, with what to try.
    pub fn link_error(self, error: &crate::link::LinkError) -> String {
        use crate::link::LinkError as E;
        match error {
            _ if self == Self::English => error.to_string(),
            E::BadPortName { name, .. } => say!(self, "link.bad_port_name", name = format!("{name:?}")),
            E::NotFound { port } => say!(self, "link.not_found", port),
            E::PermissionDenied { port } => say!(self, "link.permission_denied", port),
            E::Busy { port } => say!(self, "link.busy", port),
            E::TimedOut { port, timeout_ms } => say!(self, "link.timed_out", port, timeout_ms),
            E::Refused { port } => say!(self, "link.refused", port),
            E::NotAPort { port, what } => {
                let what = match *what {
                    "a regular file" => self.word("link.a_regular_file"),
                    "a folder" => self.word("link.a_folder"),
                    "a named pipe (FIFO)" => self.word("link.a_named_pipe"),
                    "a socket" => self.word("link.a_socket"),
                    "a block device" => self.word("link.a_block_device"),
                    _ => self.word("link.a_device"),
                };
                say!(self, "link.not_a_port", port, what)
            }
            E::Open { port, source } => say!(self, "link.open", port, source),
        }
    }

    /// A validation problem in this language.
    pub fn problem(self, kind: &crate::project::ProblemKind) -> String {
        if self == Self::English {
            return kind.to_string();
        }
        self.board_problem(kind).or_else(|| self.other_problem(kind)).unwrap_or_else(|| kind.to_string())
    }

    /// What a project's item is called ("servo", "action", "macro", "table").
    fn item(self, kind: &crate::project::ItemKind) -> &'static str {
        use crate::project::ItemKind;
        match kind {
            ItemKind::Servo => self.word("item.servo"),
            ItemKind::Action => self.word("item.action"),
            ItemKind::Macro => self.word("item.macro"),
            ItemKind::Table => self.word("item.table"),
        }
    }

    /// A servo board's problem (captions, ids, limits, steps, commands, tables).
    fn board_problem(self, kind: &crate::project::ProblemKind) -> Option<String> {
        use crate::project::ProblemKind as P;
        let text = match kind {
            P::CaptionTooLong { bytes } => say!(self, "problem.caption_too_long", bytes),
            P::IdNotPositive { kind, id } => say!(self, "problem.id_not_positive", item = self.item(kind), id),
            P::DuplicateId { kind, id } => say!(self, "problem.duplicate_id", item = self.item(kind), id),
            P::ReservedServoId => say!(self, "problem.reserved_servo_id"),
            P::MinAboveMax { min_deg, max_deg } => say!(self, "problem.min_above_max", min_deg, max_deg),
            P::HomeOutsideLimits { home_deg, min_deg, max_deg } => {
                say!(self, "problem.home_outside_limits", home_deg, min_deg, max_deg)
            }
            P::NoSteps => say!(self, "problem.no_steps"),
            P::ServoTwiceInAction { servo_id } => say!(self, "problem.servo_twice_in_action", servo_id),
            P::NegativeInterval { interval_10ms } => say!(self, "problem.negative_interval", interval_10ms),
            P::MissingServo { servo_id } => say!(self, "problem.missing_servo", servo_id),
            P::StepOutsideLimits { degree, servo_id, min_deg, max_deg } => {
                say!(self, "problem.step_outside_limits", degree, servo_id, min_deg, max_deg)
            }
            P::NoCommands => say!(self, "problem.no_commands"),
            P::TooManyCommands { count, max } => say!(self, "problem.too_many_commands", count, max),
            P::RatioOutOfRange { ratio_percent } => say!(self, "problem.ratio_out_of_range", ratio_percent),
            P::LoopBelowOne { loop_count } => say!(self, "problem.loop_below_one", loop_count),
            P::MissingAction { action_id } => say!(self, "problem.missing_action", action_id),
            P::MissingMacro { macro_id } => say!(self, "problem.missing_macro", macro_id),
            P::NegativeDelay { delay_ms } => say!(self, "problem.negative_delay", delay_ms),
            P::TotalTooLong { total_ms } => say!(self, "problem.total_too_long", total_ms, max_ms = i32::MAX),
            P::MacroCycle { path } => say!(self, "problem.macro_cycle", path = arrows(path)),
            _ => return None,
        };
        Some(text)
    }

    /// A rig's, a gamepad binding's, a PLEN2's or any section's problem.
    fn other_problem(self, kind: &crate::project::ProblemKind) -> Option<String> {
        use crate::project::{ButtonSlot, ProblemKind as P};
        let text = match kind {
            P::RigUnknownParent { parent } => say!(self, "problem.rig_unknown_parent", parent),
            P::RigCycle { path } => say!(self, "problem.rig_cycle", path = arrows(path)),
            P::RigUnknownTwin { twin } => say!(self, "problem.rig_unknown_twin", twin),
            P::BoundTwice => say!(self, "problem.bound_twice"),
            P::MissingPlayList { index } => say!(self, "problem.missing_play_list", index),
            P::TooManyButtons { count, max } => say!(self, "problem.too_many_buttons", count, max),
            P::DuplicateButton { button_id } => {
                say!(self, "problem.duplicate_button", button_id = format!("0x{button_id:08x}"))
            }
            P::MissingButtonMacro { slot, macro_id } => {
                let event = match slot {
                    ButtonSlot::Press => self.word("problem.press"),
                    ButtonSlot::LongPress => self.word("problem.long_press"),
                    ButtonSlot::Release => self.word("problem.release"),
                };
                say!(self, "problem.missing_button_macro", event, macro_id)
            }
            P::ButtonRunsNothing => say!(self, "problem.button_runs_nothing"),
            P::MissingActiveTable { table_id } => say!(self, "problem.missing_active_table", table_id),
            P::StoredTotalDiffers { stored_ms, derived_ms } => {
                say!(self, "problem.stored_total_differs", stored_ms, derived_ms)
            }
            P::OutOfRange { field, value, min, max } => say!(self, "problem.out_of_range", field, value, min, max),
            P::DuplicateSlot { slot } => say!(self, "problem.duplicate_slot", slot),
            P::DuplicateJoint => say!(self, "problem.duplicate_joint"),
            P::NameTooLong { bytes, max } => say!(self, "problem.name_too_long", bytes, max),
            P::NameNotAscii => say!(self, "problem.name_not_ascii"),
            P::NoFrames => say!(self, "problem.no_frames"),
            P::BadLoopRange { begin_frame, end_frame, frames } => {
                say!(self, "problem.bad_loop_range", begin_frame, end_frame, frames)
            }
            P::MissingMotion { slot } => say!(self, "problem.missing_motion", slot),
            P::LoopRunsForever => say!(self, "problem.loop_runs_forever"),
            P::JumpBeyondSlots { slot } => say!(self, "problem.jump_beyond_slots", slot),
            P::FirstFrameZeroCycles { transition_ms } => say!(self, "problem.first_frame_zero_cycles", transition_ms),
            P::FrameSkipped { transition_ms } => say!(self, "problem.frame_skipped", transition_ms),
            P::NotPositive { field } => say!(self, "problem.not_positive", field),
            P::UnknownKey => say!(self, "problem.unknown_key"),
            _ => return None,
        };
        Some(text)
    }

    /// A project's problems as lines ("where：what", in this language): the
    /// first twenty, then how many more there are (an upload refused says them).
    pub fn problem_lines(self, problems: &crate::project::Problems) -> Vec<String> {
        let mut list: Vec<String> = problems
            .iter()
            .take(20)
            .map(|p| say!(self, "location.at", location = self.location(&p.location), problem = self.problem(&p.kind)))
            .collect();
        let more = problems.errors() + problems.warnings() - list.len();
        if more > 0 {
            list.push(say!(self, "status.more_problems", more));
        }
        list
    }

    /// Where a problem is, in this language.
    pub fn location(self, location: &crate::project::Location) -> String {
        use crate::project::Location as L;
        if self == Self::English {
            return location.to_string();
        }
        let q = |caption: &str| format!("{caption:?}");
        match location {
            L::Project => say!(self, "location.project"),
            L::Servo { servo_id, caption } => say!(self, "location.servo", servo_id, caption = q(caption)),
            L::Action { action_id, caption } => say!(self, "location.action", action_id, caption = q(caption)),
            L::Step { action_id, caption, step } => say!(self, "location.step", action_id, caption = q(caption), step),
            L::Macro { macro_id, caption } => say!(self, "location.macro", macro_id, caption = q(caption)),
            L::Command { macro_id, caption, command } => {
                say!(self, "location.command", macro_id, caption = q(caption), command)
            }
            L::Table { table_id, caption } => say!(self, "location.table", table_id, caption = q(caption)),
            L::Button { table_id, table_caption, button_id, caption } => say!(
                self,
                "location.button",
                table_id,
                table_caption = q(table_caption),
                button_id = format!("0x{button_id:08x}"),
                caption = q(caption)
            ),
            L::Joint { joint } => say!(self, "location.joint", joint),
            L::Motion { slot, name } => say!(self, "location.motion", slot, name = q(name)),
            L::Frame { slot, name, frame } => say!(self, "location.frame", slot, name = q(name), frame),
            L::PlayList { index, name } => say!(self, "location.play_list", index, name = q(name)),
            L::Robot => say!(self, "location.robot"),
            L::GamepadButton { button } => say!(self, "location.gamepad_button", button = format!("0x{button:03x}")),
            L::GamepadAxis { axis } => say!(self, "location.gamepad_axis", axis),
            L::Key { path } => path.clone(),
        }
    }

    /// A family's name.
    pub fn family(self, family: crate::project::Family) -> &'static str {
        super::Catalogue::of(self).find(&format!("family.{}", family.tag())).unwrap_or_else(|| family.name())
    }

    /// "connecting to PORT…".
    pub fn connecting_to(self, port: &str) -> String {
        say!(self, "status.connecting_to", port)
    }

    /// The user stopped a connection attempt.
    pub fn connect_cancelled(self, port: &str) -> String {
        say!(self, "status.connect_cancelled", port)
    }

    /// Why a link ended, as a phrase.
    pub fn disconnect_reason(self, reason: &crate::link::DisconnectReason) -> String {
        use crate::link::DisconnectReason as D;
        match reason {
            _ if self == Self::English => reason.to_string(),
            D::Closed => say!(self, "link.closed"),
            D::ClosedByDriver => say!(self, "link.closed_by_driver"),
            D::ClosedByPeer => say!(self, "link.closed_by_peer"),
            D::ReadFailed(_) => say!(self, "link.read_failed"),
            D::WriteFailed(_) => say!(self, "link.write_failed"),
            D::ThreadFailed(_) => say!(self, "link.thread_failed"),
        }
    }

    /// The status line when the link ends: one sentence, the reason once.
    pub fn link_ended(self, reason: &crate::link::DisconnectReason) -> String {
        say!(self, "status.link_ended", why = self.disconnect_reason(reason))
    }

    /// The backup folder could not be made, so nothing was written.
    pub fn backup_folder_failed(self, folder: &std::path::Path, error: &std::io::Error) -> String {
        say!(self, "file.backup_folder_failed", folder = folder.display(), error = self.io_error(error))
    }

    /// A file opened, but with keys Servo Studio does not know (ignored).
    /// `keys` are the first unknown keys by name, `count` how many there were.
    pub fn opened_with_unknown_keys(self, path: &std::path::Path, keys: &[String], count: usize) -> String {
        let shown: Vec<&str> = keys.iter().take(3).map(String::as_str).collect();
        let more = if count > shown.len() { self.word("file.and_more") } else { "" };
        let keys = shown.join(self.word("file.list_comma"));
        say!(self, "file.opened_with_unknown_keys", file = path.display(), count, keys, more)
    }

    /// A file that could not be read at all, in one sentence.
    pub fn read_error(self, error: &crate::project::input::ReadError) -> String {
        use crate::project::input::ReadError as E;
        match error {
            _ if self == Self::English => error.to_string(),
            E::Io { path, source } => say!(self, "file.io", file = path.display(), why = self.io_words(source.kind())),
            E::NotAFile { path, .. } => say!(self, "file.not_a_file", file = path.display()),
            E::TooLarge { path, bytes, max } => {
                say!(self, "file.too_large", file = path.display(), mb = bytes / 1_000_000, max_mb = max / 1_000_000)
            }
            E::NotText { path, .. } => say!(self, "file.not_text", file = path.display()),
        }
    }

    /// A project file that could not be opened, in one sentence.
    pub fn load_error(self, path: &std::path::Path, error: &crate::project::LoadError) -> String {
        use crate::project::LoadError as E;
        let file = path.display();
        match (self, error) {
            (_, E::Read(error)) => self.read_error(error),
            (Self::English, _) => format!("cannot open {file}: {error}"),
            (_, E::Syntax { line, column, .. }) => say!(self, "file.syntax", file, line, column),
            (_, E::WrongFormat { .. }) => say!(self, "file.wrong_format", file),
            (_, E::NewerVersion { found, .. }) => say!(self, "file.newer_version", file, found),
        }
    }

    /// What the user asked to open (a project, a motion.json, a folder of
    /// them) that could not be opened, in one sentence with its detail.
    pub fn open_error(self, path: &std::path::Path, error: &crate::project::input::OpenError) -> String {
        use crate::project::input::OpenError as E;
        use crate::project::motion_json::MotionJsonError as M;
        match (self, error) {
            (_, E::Read(error)) => self.read_error(error),
            (_, E::Project { source, .. }) => self.load_error(path, source),
            (Self::English, _) => error.to_string(),
            (_, E::Motion(M::Io { path, source })) => {
                say!(self, "file.motion_io", file = path.display(), why = self.io_words(source.kind()))
            }
            (_, E::Motion(M::NotAMotion { path, reason })) => {
                say!(self, "file.not_a_motion", file = path.display(), reason)
            }
            (_, E::Motion(M::Empty { path })) => say!(self, "file.no_motions", folder = path.display()),
            (_, E::Entry { folder, skipped }) => say!(self, "file.folder_entry", folder = folder.display(), skipped),
        }
    }

    /// A project file that could not be saved; the previous file is intact.
    pub fn save_error(self, error: &crate::project::SaveError) -> String {
        if self == Self::English {
            return error.to_string();
        }
        let kept = if error.existed { self.word("file.previous_kept") } else { self.word("file.nothing_written") };
        say!(self, "file.save_error", file = error.path.display(), why = self.io_words(error.source.kind()), kept)
    }

    /// The recovery file could not be written.
    pub fn autosave_failed(self, error: &std::io::Error) -> String {
        say!(self, "file.autosave_failed", error = self.io_error(error))
    }

    /// An I/O error: as the system says it in English, else in words.
    fn io_error(self, error: &std::io::Error) -> String {
        match self {
            Self::English => error.to_string(),
            _ => self.io_words(error.kind()).to_string(),
        }
    }

    /// What went wrong with a file.
    fn io_words(self, kind: std::io::ErrorKind) -> &'static str {
        use std::io::ErrorKind as K;
        match kind {
            K::NotFound => self.word("file.not_found"),
            K::PermissionDenied => self.word("file.permission_denied"),
            K::StorageFull => self.word("file.storage_full"),
            K::ReadOnlyFilesystem => self.word("file.read_only"),
            K::InvalidData => self.word("file.invalid_data"),
            _ => self.word("file.io_failed"),
        }
    }
}

/// A path of ids joined by arrows ("1 → 2 → 1").
fn arrows(path: &[impl ToString]) -> String {
    path.iter().map(ToString::to_string).collect::<Vec<_>>().join(" → ")
}
