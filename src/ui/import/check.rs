//! What the board will play of the open import, worked out off the frame
//! whenever the choices change (the conversion Create would make, traced as
//! the board plays it), said under the preview; and where the map lands on
//! a servo or joint already taken, said before Create.

use super::played::Played;
use super::{ImportDesk, ImportWords, Session, note, words};
use crate::interchange::build::{self, Built, Options, Selection};
use crate::interchange::map::Target;
use crate::project::{Family, Project};
use crate::ui::files::FileWork;
use crate::ui::i18n::fill;

/// The conversion Create would make and what the board plays of the previewed clip.
pub(super) type Checked = Result<(Box<Built>, Option<Played>), String>;

/// What the board's playback depends on: the map, the clip, the tolerance and the board.
pub(super) fn choices(session: &Session) -> u64 {
    use std::hash::{Hash, Hasher};
    let mut hasher = std::collections::hash_map::DefaultHasher::new();
    session.map.to_json().hash(&mut hasher);
    session.clip.hash(&mut hasher);
    session.tolerance_deg.to_bits().hash(&mut hasher);
    session.family.tag().hash(&mut hasher);
    hasher.finish()
}

impl ImportDesk {
    /// Starts working out what the board plays when the choices changed and nothing runs.
    pub(super) fn check(&mut self, session: &Session, project: &Project, files: &FileWork) {
        let key = choices(session);
        if self.checking.is_some() || self.checked.as_ref().is_some_and(|(done, _)| *done == key) {
            return;
        }
        let (source, map, clip) = (session.source.clone(), session.map.clone(), session.clip);
        let selection = clip.map_or(Selection::All, |clip| Selection::Named(source.clips[clip].name.clone()));
        let options = Options { family: project.family, selection, tolerance_deg: session.tolerance_deg };
        let project = project.clone();
        self.checking = Some((
            key,
            files.run(move |_| {
                let built = build::build(&source, &map, &options).map_err(|error| error.to_string())?;
                let played = Played::new(&source, &map, clip.unwrap_or(0), &built, &project);
                Ok((Box::new(built), played))
            }),
        ));
    }

    #[cfg(any(test, feature = "test-api"))]
    /// Whether what the board plays of the open session, as it stands, is worked out.
    pub fn board_known(&self) -> bool {
        self.session.as_ref().is_some_and(|session| self.board(session).is_some())
    }

    /// The board's playback of the session as it stands, when worked out.
    pub(super) fn board(&self, session: &Session) -> Option<&Checked> {
        self.checked.as_ref().filter(|(key, _)| *key == choices(session)).map(|(_, checked)| checked)
    }

    /// Whether the board plays what the file says, and where not: the line
    /// under the preview. Returns what the conversion approximates.
    pub(super) fn board_ui(&self, ui: &mut egui::Ui, session: &Session, words: &ImportWords) -> Vec<String> {
        let warn = ui.visuals().warn_fg_color;
        match self.board(session) {
            None => {
                // Still: the worker wakes the window when it is done (no spinner repainting every frame).
                ui.label(words.checking);
                Vec::new()
            }
            Some(Err(error)) => {
                ui.colored_label(warn, format!("{} {}", words.board_cannot, note(error, words)));
                Vec::new()
            }
            Some(Ok((built, played))) => {
                match played.as_ref().and_then(|played| played.differs.as_ref()) {
                    Some(differs) => {
                        let channel = &session.source.channels[differs.channel];
                        let target = session.map.entry(&channel.key).and_then(|e| e.target);
                        let said = words::differs(
                            words,
                            &channel.key,
                            &target.map_or_else(String::new, |t| words::target(t, words)),
                            differs.degrees,
                            differs.at_ms / 1000.0,
                            differs.limited,
                        );
                        ui.colored_label(warn, said);
                    }
                    None if played.is_some() => {
                        ui.label(words.same_as_file);
                    }
                    None => {}
                }
                built.report.approximated.clone()
            }
        }
    }
}

/// Where the map lands on something already taken, before Create: a servo
/// the project already has (its settings are kept), or a servo or joint
/// that two channels drive.
pub(super) fn landings(session: &Session, project: &Project, words: &ImportWords) -> Landings {
    let mut said = Landings::default();
    let mut by_target: Vec<(Target, Vec<&str>)> = Vec::new();
    for entry in &session.map.entries {
        let Some(target) = entry.target else { continue };
        if let Target::Servo(id) = target
            && project.family == Family::Servo
            && project.servo.servo(id).is_some()
        {
            said.in_use.push((entry.source.clone(), words::target(target, words)));
        }
        match by_target.iter_mut().find(|(t, _)| *t == target) {
            Some((_, channels)) => channels.push(&entry.source),
            None => by_target.push((target, vec![&entry.source])),
        }
    }
    for (target, channels) in by_target.iter().filter(|(_, channels)| channels.len() > 1) {
        let (channels, target) = (channels.join(", "), words::target(*target, words));
        said.twice.push(fill(words.twice, &[("channels", &channels), ("target", &target)]));
    }
    said
}

/// Where the map lands on something already taken.
#[derive(Debug, Default)]
pub(super) struct Landings {
    /// Each channel driving a servo the project already has, and that servo, in these words.
    pub in_use: Vec<(String, String)>,
    /// Each servo or joint more than one channel drives, said.
    pub twice: Vec<String>,
}

impl Landings {
    /// The warnings, a line each; channels landing on servos the project has
    /// are one line with their count when there are several, the list under it on demand.
    pub fn ui(&self, ui: &mut egui::Ui, words: &ImportWords) {
        let warn = ui.visuals().warn_fg_color;
        match self.in_use.as_slice() {
            [] => {}
            [(channel, target)] => {
                ui.colored_label(warn, fill(words.in_use, &[("channel", channel), ("target", target)]));
            }
            many => {
                let count = many.len();
                ui.colored_label(warn, crate::say!(words.lang, "import.in_use_many", count));
                egui::CollapsingHeader::new(crate::say!(words.lang, "import.which_channels", count))
                    .id_salt("import-in-use")
                    .show(ui, |ui| {
                        for (channel, target) in many {
                            ui.label(format!("{channel} → {target}"));
                        }
                    });
            }
        }
        for line in &self.twice {
            ui.colored_label(warn, line);
        }
    }
}
