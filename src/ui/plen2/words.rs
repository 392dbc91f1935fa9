//! The PLEN2's operations in words: why one failed, what the robot panel
//! says after one — in the interface's language.

use crate::device::plen2::{Plen2Item, Plen2OpError, ReplyError, SlotResult};
use crate::say;
use crate::ui::i18n::{Language, Worded};

use super::{Plen2Failure, Plen2Result};
use crate::ui::plen2::captions::Plen2Words;

impl Plen2Failure {
    /// Why a PLEN2 operation failed, in `language`.
    pub fn words(&self, language: Language) -> String {
        match self {
            Self::Op(error) => error.worded(language),
            Self::Upload(failure) => {
                language.upload_failure(failure, |error| error.worded(language), |item| item.worded(language))
            }
            Self::Reply(error) => error.worded(language),
            Self::BackupFolder { folder, error } => language.backup_folder_failed(folder, error),
            Self::Thread(error) => language.no_worker(error),
        }
    }
}

impl Plen2Result {
    /// What the robot panel says after an operation, in `language`, and whether it is an error.
    pub fn words(&self, language: Language) -> (String, bool) {
        let words = language.strings();
        match self {
            Plen2Result::Read(count) => (format!("{} {count}", words.plen2().robot_read), false),
            Plen2Result::Uploaded(report) => {
                let verified = report.slots.iter().filter(|(_, r)| *r == SlotResult::Verified).count();
                let mut text = format!("{} {verified}/{}", words.uploaded_items, report.slots.len());
                let differing: Vec<String> = report
                    .slots
                    .iter()
                    .filter(|(_, r)| *r == SlotResult::Differs)
                    .map(|(slot, _)| slot.to_string())
                    .collect();
                if !differing.is_empty() {
                    text.push_str(&format!("\n{} {}", words.plen2().slots_differ, differing.join(", ")));
                }
                if let Some(backup) = &report.backup {
                    text.push_str(&format!("\n{} {}", words.backup_at, backup.display()));
                }
                (text, !differing.is_empty())
            }
            Plen2Result::JointsWritten(count) => (format!("{}: {count}", words.plen2().write_joints), false),
            Plen2Result::Invalid(problems) => {
                (Plen2OpError::Invalid { problems: problems.clone() }.worded(language), true)
            }
            Plen2Result::ReadIntoProject => (words.read_done.to_string(), false),
            Plen2Result::Exported(path) => (format!("{} {}", words.saved_board_to, path.display()), false),
            Plen2Result::ExportFailed(text) => (text.clone(), true),
            Plen2Result::Failed(failure) => (failure.words(language), true),
            Plen2Result::Cancelled => (words.cancelled.to_string(), false),
        }
    }
}

/// The PLEN2's adaptive pacing widened its margins, in this language.
impl Worded for crate::device::plen2::Widened {
    fn worded(&self, language: Language) -> String {
        let widened = self;
        use crate::device::plen2::{RING_WINDOW_BYTES, WidenReason};
        if language == Language::English {
            return widened.to_string();
        }
        let ms = |d: std::time::Duration| d.as_secs_f64() * 1000.0;
        let (window, bytes) = (ms(widened.window), RING_WINDOW_BYTES);
        match widened.reason {
            WidenReason::Bursts { gap } => say!(language, "widened.bursts", gap = ms(gap), window, bytes),
            WidenReason::Slow { bytes_per_s } => say!(language, "widened.slow", bytes_per_s),
            WidenReason::Late { delay } => say!(language, "widened.late", delay = ms(delay), window, bytes),
            WidenReason::ReadBackDiffered => say!(language, "widened.read_back_differed", window, bytes),
            WidenReason::Events { interval } => {
                say!(language, "widened.events", interval = ms(interval), window, bytes)
            }
        }
    }
}

/// A PLEN2 pacing mode's name.
pub(crate) fn pacing_name(language: Language, mode: crate::device::plen2::PacingMode) -> &'static str {
    use crate::device::plen2::PacingMode as P;
    match mode {
        P::Fast => language.word("pacing.fast"),
        P::Adaptive => language.word("pacing.adaptive"),
        P::Safe => language.word("pacing.safe"),
    }
}

/// What a PLEN2 operation step works on, in this language.
impl Worded for Plen2Item {
    fn worded(&self, language: Language) -> String {
        let item = self;
        if language == Language::English {
            return item.to_string();
        }
        match item {
            Plen2Item::Version => say!(language, "plen2_item.version"),
            Plen2Item::JointSettings => say!(language, "plen2_item.joint_settings"),
            Plen2Item::Joint(joint) => say!(language, "plen2_item.joint", joint = joint.name()),
            Plen2Item::Slot { slot, name } if name.is_empty() => say!(language, "plen2_item.slot", slot),
            Plen2Item::Slot { slot, name } => say!(language, "plen2_item.named_slot", slot, name = format!("{name:?}")),
            Plen2Item::Link => say!(language, "plen2_item.link"),
            Plen2Item::Erased { slot, remaining } => {
                let mut text = say!(language, "plen2_item.erased", slot);
                if let Some(left) = remaining {
                    text.push_str(&say!(language, "plen2_item.erased_left", seconds = left.as_secs().max(1)));
                }
                text
            }
            Plen2Item::Pacing => say!(language, "plen2_item.pacing"),
            Plen2Item::FactoryReset => say!(language, "plen2_item.factory_reset"),
            Plen2Item::Done => say!(language, "plen2_item.done"),
        }
    }
}

/// Why a PLEN2 did not answer, in this language, with what to try.
impl Worded for ReplyError {
    fn worded(&self, language: Language) -> String {
        let error = self;
        match (language, error) {
            (Language::English, _) => error.to_string(),
            (_, ReplyError::Timeout { timeout_ms }) => say!(language, "reply.timeout", timeout_ms),
            (_, ReplyError::NotThisProtocol { bytes }) => say!(language, "reply.not_this_protocol", bytes),
            (_, ReplyError::Garbage { bytes }) => say!(language, "reply.garbage", bytes),
            (_, ReplyError::Disconnected) => say!(language, "reply.disconnected"),
            (_, ReplyError::Stopped) => say!(language, "reply.stopped"),
        }
    }
}

/// Why a PLEN2 operation step failed, in this language.
impl Worded for Plen2OpError {
    fn worded(&self, language: Language) -> String {
        let error = self;
        if language == Language::English {
            return error.to_string();
        }
        match error {
            Plen2OpError::Reply { item, source } => {
                say!(language, "op.request", item = item.worded(language), source = source.worded(language))
            }
            Plen2OpError::Unreadable { item } => say!(language, "plen2_op.unreadable", item = item.worded(language)),
            Plen2OpError::Invalid { problems } => {
                let list = language.problem_lines(problems).join("\n");
                say!(language, "plen2_op.invalid", errors = problems.errors(), list)
            }
            Plen2OpError::Backup(error) => say!(language, "op.backup", error = language.save_error(error)),
            Plen2OpError::Unstorable(error) => {
                use crate::device::plen2::NotStorable;
                let why = match error.why {
                    NotStorable::Frames(count) => say!(language, "plen2_op.frames", count),
                    NotStorable::Slot => say!(language, "plen2_op.slot"),
                    NotStorable::Name => say!(language, "plen2_op.name"),
                };
                let (slot, name) = (error.slot, format!("{:?}", error.name));
                say!(language, "plen2_op.unstorable", slot, name, why)
            }
            Plen2OpError::Cancelled => say!(language, "op.cancelled"),
        }
    }
}

// A PLEN2 says its version; it reads the same in every language.
inventory::submit! {
    crate::ui::i18n::SaidWords(|identity, _| identity.said::<crate::device::plen2::Said>().map(ToString::to_string))
}
