//! What a conversion made, what it had to approximate and what it left out,
//! each said once.

/// The account of one conversion.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Report {
    /// What was made ("3 actions", "motion 0 \"wave\" (5 frames)").
    pub converted: Vec<String>,
    /// What plays differently from the source, and how.
    pub approximated: Vec<String>,
    /// What the source held that nothing here plays.
    pub dropped: Vec<String>,
    /// What reading the file found that is neither (a checksum, the robot it declares).
    pub notes: Vec<String>,
}

/// `n` things in English: "1 servo", "3 servos" (`one` and `many`: the word for each).
pub fn count(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

/// The English nouns conversions count, for [`count`] and for reading a
/// note back by its pattern (which names the plural): "1 servo" is "1 servos".
pub const COUNTED: [&str; 7] = ["servo", "action", "macro", "frame", "step", "sample", "joystick table"];

impl Report {
    /// Notes something made.
    pub fn converted(&mut self, note: impl Into<String>) {
        self.converted.push(note.into());
    }

    /// Notes an approximation, once however often it happens.
    pub fn approximated(&mut self, note: impl Into<String>) {
        let note = note.into();
        if !self.approximated.contains(&note) {
            self.approximated.push(note);
        }
    }

    /// Notes something left out, once however often it happens.
    pub fn dropped(&mut self, note: impl Into<String>) {
        let note = note.into();
        if !self.dropped.contains(&note) {
            self.dropped.push(note);
        }
    }

    /// Notes what reading the file found, once.
    pub fn noted(&mut self, note: impl Into<String>) {
        let note = note.into();
        if !self.notes.contains(&note) {
            self.notes.push(note);
        }
    }

    /// The report as lines for a terminal: what was converted, then
    /// "approximated: …" and "dropped: …" lines.
    pub fn lines(&self) -> Vec<String> {
        let mut lines: Vec<String> = self.converted.iter().map(|note| format!("converted: {note}")).collect();
        lines.extend(self.approximated.iter().map(|note| format!("approximated: {note}")));
        lines.extend(self.dropped.iter().map(|note| format!("dropped: {note}")));
        lines.extend(self.notes.iter().map(|note| format!("note: {note}")));
        lines
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_note_is_said_once() {
        let mut report = Report::default();
        report.converted("2 actions");
        report.approximated("a");
        report.approximated("a");
        report.dropped("b");
        report.dropped("b");
        assert_eq!(report.lines(), ["converted: 2 actions", "approximated: a", "dropped: b"]);
    }
}
