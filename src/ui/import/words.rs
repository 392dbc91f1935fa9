//! The import window's own captions, in English and Traditional Chinese.

use crate::interchange::map::Target;
use crate::project::Family;
use crate::project::plen2::Joint;
use crate::ui::i18n::{Language, fill};

crate::words! {
    /// The import window's captions.
    #[derive(Debug)]
    pub struct ImportWords in "import" {
        /// The language these words are in.
        pub lang: Language,
        /// The File menu's entry and the window's title.
        pub title: &'static str,
        /// "Reading".
        pub reading: &'static str,
        /// "Motion".
        pub motion: &'static str,
        /// "All".
        pub all: &'static str,
        /// "For".
        pub for_board: &'static str,
        /// "Tolerance for fitted animations (°)".
        pub tolerance: &'static str,
        /// Column heads.
        pub channel: &'static str,
        /// "Name".
        pub name: &'static str,
        /// "Drives".
        pub drives: &'static str,
        /// "Zero".
        pub zero: &'static str,
        /// "Units per °".
        pub per_degree: &'static str,
        /// "Reversed".
        pub reversed: &'static str,
        /// "Offset °".
        pub offset: &'static str,
        /// "Now °".
        pub now: &'static str,
        /// "— not imported".
        pub not_imported: &'static str,
        /// "Time".
        pub time: &'static str,
        /// "Play".
        pub play: &'static str,
        /// "Pause".
        pub pause: &'static str,
        /// "Load map…".
        pub load_map: &'static str,
        /// "Save map…".
        pub save_map: &'static str,
        /// "Create".
        pub create: &'static str,
        /// "Cancel".
        pub cancel: &'static str,
        /// "Close".
        pub close: &'static str,
        /// "Not taken from the file".
        pub left_out: &'static str,
        /// "No rig: the Now column shows each servo's angle".
        pub no_rig: &'static str,
        /// "A base stores no motions".
        pub rflex: &'static str,
        /// "Imported".
        pub imported: &'static str,
        /// "Converted", "Approximated", "Dropped", "Notes".
        pub report_heads: [&'static str; 4],
        /// "Joint map".
        pub joint_map: &'static str,
        /// The File menu's export entry and its window's title.
        pub export_title: &'static str,
        /// "Format".
        pub format: &'static str,
        /// The two formats written.
        pub formats: [&'static str; 2],
        /// "Macro", "Motion".
        pub subjects: [&'static str; 2],
        /// "Frames per second".
        pub fps: &'static str,
        /// "Export…".
        pub export: &'static str,
        /// "Nothing to export: the project holds no macro or motion".
        pub nothing: &'static str,
        /// "A Maestro takes a servo board's project".
        pub maestro_servo_only: &'static str,
        /// "Exported".
        pub exported: &'static str,
        /// "Working out what the board plays…".
        pub checking: &'static str,
        /// "The board cannot play this:".
        pub board_cannot: &'static str,
        /// "The board plays this as the file says (within 0.1°)."
        pub same_as_file: &'static str,
        /// Where the board plays farthest from the file: channel, what it drives, degrees, seconds, whether at a limit.
        pub differs: &'static str,
        /// Why: held at its limit.
        pub held_at_limit: &'static str,
        /// Why: see Approximated.
        pub see_approximated: &'static str,
        /// "servo {id}".
        pub servo: &'static str,
        /// A family's name: servo board, PLEN2, rFLEX base.
        pub families: [(&'static str, &'static str); 3],
        /// The formats read, by their command-line word.
        pub read_formats: [(&'static str, &'static str); 4],
        /// A PLEN2 joint's name from its parts: side, part, axis.
        pub joint: &'static str,
        /// The sides of a joint (left, right).
        pub sides: [&'static str; 2],
        /// The parts of a joint: shoulder, elbow, thigh, knee, foot.
        pub parts: [&'static str; 5],
        /// The axes of a joint: pitch, roll, yaw.
        pub axes: [&'static str; 3],
        /// The notes of a conversion in this language: (English pattern, this language's), `{}` a hole.
        pub notes: &'static [(&'static str, &'static str)],
        /// "The servo {id} is already in this project: …" — a map entry landing on a servo in use.
        pub in_use: &'static str,
        /// "Two channels drive {target}: …".
        pub twice: &'static str,
    }
}

/// A PLEN2 joint in these words: its side, part and axis (or its own name).
pub fn joint(joint: Joint, words: &ImportWords) -> String {
    let name = joint.name();
    let side = if name.starts_with("left") { words.sides[0] } else { words.sides[1] };
    let parts = ["shoulder", "elbow", "thigh", "knee", "foot"];
    let part = parts.iter().zip(words.parts).find(|(word, _)| name.contains(*word)).map_or("", |(_, part)| part);
    let axis = ["pitch", "roll", "yaw"].iter().zip(words.axes).find(|(word, _)| name.ends_with(*word));
    let axis = axis.map_or("", |(_, axis)| axis);
    fill(words.joint, &[("name", &name), ("side", &side), ("part", &part), ("axis", &axis)])
}

/// The board plays a channel other than the file says.
pub fn differs(words: &ImportWords, channel: &str, target: &str, degrees: f64, seconds: f64, limited: bool) -> String {
    let why = if limited { words.held_at_limit } else { words.see_approximated };
    let args: [(&str, &dyn std::fmt::Display); 5] =
        [("channel", &channel), ("target", &target), ("degrees", &degrees), ("seconds", &seconds), ("why", &why)];
    fill(words.differs, &args)
}

/// A family's name in these words.
pub fn family(family: Family, words: &ImportWords) -> &'static str {
    words.families.iter().find(|(tag, _)| *tag == family.tag()).map_or_else(|| family.name(), |(_, name)| name)
}

/// A format's name in these words.
pub fn format(format: crate::interchange::Format, words: &ImportWords) -> &'static str {
    words.read_formats.iter().find(|(tag, _)| *tag == format.tag()).map_or_else(|| format.name(), |(_, name)| name)
}

/// What a map entry drives, in these words.
pub fn target(target: Target, words: &ImportWords) -> String {
    match target {
        Target::Servo(id) => fill(words.servo, &[("id", &id)]),
        Target::Joint(joint) => self::joint(joint, words),
    }
}

/// A conversion's note or error in these words: the first pattern it fits,
/// its holes carried over; as it is when none fits (English).
pub fn note(text: &str, words: &ImportWords) -> String {
    let find = |text: &str| words.notes.iter().find_map(|(english, ours)| refill(text, english, ours));
    if words.lang == Language::English {
        // The conversion's own English, its counts' words right.
        return text.to_string();
    }
    find(text).or_else(|| find(&counted_as_many(text))).unwrap_or_else(|| text.to_string())
}

/// `text` with "1 servo" read as "1 servos": the patterns name the plural
/// (a language without one says a count the same way for every number).
fn counted_as_many(text: &str) -> String {
    let mut out = text.to_string();
    for noun in crate::interchange::COUNTED {
        let one = format!("1 {noun}");
        let mut from = 0;
        while let Some(found) = out[from..].find(&one).map(|at| at + from) {
            let end = found + one.len();
            let before = out[..found].chars().next_back();
            let after = out[end..].chars().next();
            if before.is_none_or(|c| !c.is_ascii_digit() && c != '.') && after.is_none_or(|c| !c.is_alphanumeric()) {
                out.insert(end, 's');
            }
            from = end;
        }
    }
    out
}

/// `text` read by `pattern` (`{}` a hole: as little as reaches the next
/// literal part, the last hole up to the pattern's end) and written by `into`.
fn refill(text: &str, pattern: &str, into: &str) -> Option<String> {
    let parts: Vec<&str> = pattern.split("{}").collect();
    let (first, rest) = parts.split_first()?;
    let mut left = text.strip_prefix(first)?;
    let mut holes = Vec::new();
    for (index, part) in rest.iter().enumerate() {
        let end = if index + 1 == rest.len() {
            if !left.ends_with(part) {
                return None;
            }
            left.len() - part.len()
        } else if part.is_empty() {
            0
        } else {
            left.find(part)?
        };
        holes.push(&left[..end]);
        left = &left[end + part.len()..];
    }
    if !left.is_empty() && rest.is_empty() {
        return None;
    }
    Some(fill_holes(into, &holes))
}

/// `into` with its holes filled: `{}` by the next hole in turn, `{N}` by hole
/// N (a language whose order differs), a hole that is not there by nothing.
fn fill_holes(into: &str, holes: &[&str]) -> String {
    // `{}` numbered in turn, so the template is one `fill` reads (`{0}`, `{1}`…).
    let mut numbered = String::with_capacity(into.len() + 8);
    for (index, part) in into.split("{}").enumerate() {
        if index > 0 {
            numbered.push_str(&format!("{{{}}}", index - 1));
        }
        numbered.push_str(part);
    }
    let names: Vec<String> = (0..holes.len()).map(|index| index.to_string()).collect();
    let args: Vec<(&str, &dyn std::fmt::Display)> =
        names.iter().zip(holes).map(|(name, hole)| (name.as_str(), hole as &dyn std::fmt::Display)).collect();
    fill(&numbered, &args)
}

/// The captions in `language`.
pub fn words(language: Language) -> &'static ImportWords {
    ImportWords::of(language)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A note is read by its English and written in the language, holes carried
    /// over in turn (`{}`) or by number (`{1}` before `{0}`, as Japanese words it).
    /// A count of one is said in the singular in English and, in a language
    /// with one form, read by the same pattern as any other count.
    #[test]
    fn a_count_of_one_is_singular_in_english_and_translated_in_the_others() {
        let made = format!(
            "{}, {}, {}",
            crate::interchange::count(1, "servo", "servos"),
            crate::interchange::count(10, "action", "actions"),
            crate::interchange::count(1, "macro", "macros")
        );
        assert_eq!(made, "1 servo, 10 actions, 1 macro");
        assert_eq!(note(&made, words(Language::English)), made);
        for language in [Language::Japanese, Language::Korean, Language::TraditionalChinese] {
            let said = note(&made, words(language));
            assert!(!said.contains("servo") && !said.contains("macro"), "{language:?}: {said}");
            assert!(said.contains('1') && said.contains("10"), "{language:?}: {said}");
        }
        // "11 servo" is not one servo; a word that only begins with the noun is not it.
        assert_eq!(counted_as_many("11 servo, 1 servomotor, 1 step."), "11 servo, 1 servomotor, 1 steps.");
    }

    #[test]
    fn a_note_keeps_its_holes_in_the_languages_order() {
        let japanese = words(Language::Japanese);
        let said = "90 steps are needed to stay within 0.5° and at most 64 fit: the smallest tolerance that fits is --tolerance-deg 1.2. Nothing was written";
        assert_eq!(
            note(said, japanese),
            "0.5° 以内に収めるには 90 ステップ必要ですが、入るのは最大 64 です：入る最小の許容誤差は --tolerance-deg 1.2 です。何も書き込んでいません"
        );
        assert_eq!(note("channel 7: not mapped", words(Language::Korean)), "채널 7: 대응 없음");
        assert_eq!(note("not a note at all", japanese), "not a note at all");
    }
}
