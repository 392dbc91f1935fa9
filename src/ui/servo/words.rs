//! The servo board's errors in words, in the interface's language: worded
//! here, beside the family that meets them, through [`Worded`].

use crate::say;
use crate::ui::i18n::{Language, Worded};

/// What an operation step is about, in this language.
impl Worded for crate::device::servo::Item {
    fn worded(&self, language: Language) -> String {
        let item = self;
        use crate::device::servo::Item as I;
        if language == Language::English {
            return item.to_string();
        }
        match item {
            I::ProjectId => say!(language, "servo_item.project_id"),
            I::ServoParameters => say!(language, "servo_item.servo_parameters"),
            I::ActionList => say!(language, "servo_item.action_list"),
            I::Action { id, caption } => say!(language, "servo_item.action", id, caption = format!("{caption:?}")),
            I::MacroList => say!(language, "servo_item.macro_list"),
            I::Macro { id, caption } => say!(language, "servo_item.macro", id, caption = format!("{caption:?}")),
            I::TableList => say!(language, "servo_item.table_list"),
            I::Table { id, caption } => say!(language, "servo_item.table", id, caption = format!("{caption:?}")),
            I::ActiveTable => say!(language, "servo_item.active_table"),
            I::MemorySize => say!(language, "servo_item.memory_size"),
            I::ClearAll => say!(language, "servo_item.clear_all"),
            I::WriteProjectId(id) => say!(language, "servo_item.write_project_id", id),
            I::AddServoParameters(count) => say!(language, "servo_item.add_servo_parameters", count),
            I::SetActiveTable(id) => say!(language, "servo_item.set_active_table", id),
            I::MoveServos => say!(language, "servo_item.move_servos"),
            I::RunAction(id) => say!(language, "servo_item.run_action", id),
            I::RunMacro(id) => say!(language, "servo_item.run_macro", id),
            I::ServoSwitches(id) => say!(language, "servo_item.servo_switches", id),
            I::AngleUnit(id) => say!(language, "servo_item.angle_unit", id),
            I::ServoState(id) => say!(language, "servo_item.servo_state", id),
            I::Battery => say!(language, "servo_item.battery"),
            I::ButtonEvents => say!(language, "servo_item.button_events"),
        }
    }
}

/// A difference between project and board, in this language.
impl Worded for crate::device::servo::Difference {
    fn worded(&self, language: Language) -> String {
        let difference = self;
        use crate::device::servo::{Difference as D, RecordKind as K};
        if language == Language::English {
            return difference.to_string();
        }
        let kind = |kind: &K| match kind {
            K::Servo => language.word("item.servo"),
            K::Action => language.word("item.action"),
            K::Macro => language.word("item.macro"),
            K::Table => language.word("item.table"),
        };
        match difference {
            D::ProjectId { expected, actual } => say!(language, "difference.project_id", expected, actual),
            D::Missing { kind: k, id } => say!(language, "difference.missing", kind = kind(k), id),
            D::Differs { kind: k, id } => say!(language, "difference.differs", kind = kind(k), id),
            D::Extra { kind: k, id } => say!(language, "difference.extra", kind = kind(k), id),
            D::Order { kind: k } => say!(language, "difference.order", kind = kind(k)),
            D::ActiveTable { expected, actual } => say!(language, "difference.active_table", expected, actual),
        }
    }
}

/// Why a request failed, in this language, with what to try.
impl Worded for crate::device::servo::RequestError {
    fn worded(&self, language: Language) -> String {
        let error = self;
        use crate::device::servo::RequestError as R;
        match (language, error) {
            (Language::English, _) => error.to_string(),
            (_, R::Timeout { request, attempts, timeout_ms }) => {
                say!(language, "request.timeout", request, attempts, timeout_ms)
            }
            (_, R::Incomplete { request, received, expected, timeout_ms, .. }) => {
                say!(language, "request.incomplete", request, received, expected, timeout_ms)
            }
            (_, R::NotThisProtocol { request, bytes }) => say!(language, "request.not_this_protocol", request, bytes),
            (_, R::Malformed { request, .. }) => say!(language, "request.malformed", request),
            (_, R::Encode(_)) => say!(language, "request.encode"),
            (_, R::Disconnected { .. }) => say!(language, "request.disconnected"),
            (_, R::Stopped { request }) => say!(language, "request.stopped", request),
        }
    }
}

/// Why a board operation failed, in this language, with what to try.
impl Worded for crate::device::servo::OpError {
    fn worded(&self, language: Language) -> String {
        let error = self;
        use crate::device::servo::OpError as O;
        if language == Language::English {
            return error.to_string();
        }
        match error {
            O::Request { item, source } => {
                say!(language, "op.request", item = item.worded(language), source = source.worded(language))
            }
            O::Refused { item } => say!(language, "op.refused", item = item.worded(language)),
            O::ReadFailed { item } => say!(language, "op.read_failed", item = item.worded(language)),
            O::Invalid { problems } => {
                let list = language.problem_lines(problems).join("\n");
                say!(language, "op.invalid", errors = problems.errors(), list)
            }
            O::DoesNotFit { needed_bytes, total_bytes } => say!(language, "op.does_not_fit", needed_bytes, total_bytes),
            O::Image(crate::device::servo::ImageError::CaptionTooLong { item, bytes }) => {
                say!(language, "op.caption_too_long", item, bytes)
            }
            O::Encode(error) => say!(language, "op.encode", error),
            O::Backup(error) => say!(language, "op.backup", error),
            O::Verify { differences } => {
                let list: Vec<String> = differences.iter().map(|d| d.worded(language)).collect();
                say!(language, "op.verify", list = list.join("\n"))
            }
            O::Cancelled => say!(language, "op.cancelled"),
            O::Unexpected { item, response } => say!(language, "op.unexpected", item = item.worded(language), response),
        }
    }
}

/// Why a run time cannot be computed.
impl Worded for crate::project::TimingError {
    fn worded(&self, language: Language) -> String {
        let error = self;
        use crate::project::TimingError as T;
        match (language, error) {
            (Language::English, _) => error.to_string(),
            (_, T::MissingAction(action_id)) => say!(language, "problem.missing_action", action_id),
            (_, T::MissingMacro(macro_id)) => say!(language, "problem.missing_macro", macro_id),
            (_, T::Cycle(id)) => say!(language, "timing.cycle", id),
            (_, T::ZeroRatio) => say!(language, "timing.zero_ratio"),
        }
    }
}

/// Why a message cannot be put into a frame (too many entries, too long).
impl Worded for crate::device::servo::EncodeError {
    fn worded(&self, language: Language) -> String {
        let error = self;
        use crate::device::servo::EncodeError as E;
        match (language, error) {
            (Language::English, _) => error.to_string(),
            (_, E::TooMany { message, field, max, actual }) => {
                say!(language, "encode.too_many", message, field, max, actual)
            }
            (_, E::ContentTooLong { packet_id, max_bytes, actual_bytes }) => {
                say!(language, "encode.content_too_long", packet_id, max_bytes, actual_bytes)
            }
        }
    }
}

/// Something could not be sent.
pub(crate) fn send_failed(language: Language, error: &crate::device::servo::EncodeError) -> String {
    say!(language, "encode.send_failed", error = error.worded(language))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A message that cannot be encoded used to reach the Chinese interface in
    /// English; a lost link is one phrase.
    #[test]
    fn send_and_request_errors_keep_their_detail_in_chinese() {
        let zh = Language::TraditionalChinese;
        let error = crate::device::servo::EncodeError::TooMany {
            message: "ExecuteActionRequest",
            field: "servoCount",
            max: 255,
            actual: 300,
        };
        assert_eq!(send_failed(zh, &error), "無法傳送：ExecuteActionRequest 的 `servoCount` 最多 255 筆，但有 300 筆");
        assert!(send_failed(Language::English, &error).contains("at most 255 entries, but 300"));
        let lost = crate::device::servo::RequestError::Disconnected { reason: "the link is closed".into() };
        assert_eq!(lost.worded(zh), "與控制板的連線已中斷");
    }
}

/// What a servo board said of itself, in this language.
impl Worded for crate::device::servo::Said {
    fn worded(&self, language: Language) -> String {
        if language == Language::English {
            return self.to_string();
        }
        let mut text = say!(language, "servo_said.board");
        match self.project_id {
            Some(0) => text.push_str(&say!(language, "servo_said.no_project")),
            Some(id) => text.push_str(&say!(language, "servo_said.project", id)),
            None => {}
        }
        match self.memory {
            Some((free, Some(total))) => text.push_str(&say!(language, "servo_said.free_of", free, total)),
            Some((free, None)) => text.push_str(&say!(language, "servo_said.free", free)),
            None => {}
        }
        text
    }
}

inventory::submit! {
    crate::ui::i18n::SaidWords(|identity, language| {
        identity.said::<crate::device::servo::Said>().map(|said| said.worded(language))
    })
}
