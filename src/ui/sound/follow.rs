//! Follow the sound: pick a servo (or a PLEN2 joint), a closed and an open
//! angle, attack and release; the sound's loudness becomes that axis's
//! motion, fitted into the board's steps or frames within the tolerance
//! (a talking skull's jaw, a PLEN2 nodding to a beat). The motion is timed
//! to the sound as the lane places it (its offset), and added to the
//! project in one undo step. The dialog is the same for every family: it
//! asks the open family's [`SoundFollower`] for its axes and its motion (a
//! servo's actions and a macro running them, `ui::servo::follow`; a PLEN2
//! chain of motions, `ui::plen2::follow`).

use crate::audio::follow::{self as loudness, Follow};
use crate::authoring::fit::FitError;
pub use crate::authoring::follow::Follower;
use crate::project::{Edit, Project};
use crate::ui::action::Action;
use crate::ui::i18n::{Language, Said};

/// The dialog's widest, points.
const DIALOG_WIDTH: f32 = 560.0;

/// The dialog's fields.
#[derive(Clone, Debug, PartialEq)]
pub struct FollowForm {
    /// The axis that follows (a servo's id, a joint's index), as its family keys it.
    axis: Option<usize>,
    closed_deg: f64,
    open_deg: f64,
    attack_ms: f64,
    release_ms: f64,
    threshold_db: f64,
    tolerance_deg: f64,
    /// Where a PLEN2's motions are written.
    target: Target,
    /// What the last try said (in every language).
    said: Option<Said>,
}

/// Where a follow that takes slots (a PLEN2's) is written: a chain of motions (each up to 20
/// frames, jumping to the next) when the sound is longer than one holds.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Target {
    /// The free slots, in order.
    #[default]
    FreeSlots,
    /// This slot and the ones after it, replacing what they hold.
    From(u8),
}

impl Default for FollowForm {
    fn default() -> Self {
        let follow = Follow::default();
        Self {
            axis: None,
            closed_deg: 0.0,
            open_deg: 30.0,
            attack_ms: follow.attack_ms,
            release_ms: follow.release_ms,
            threshold_db: follow.threshold_db,
            tolerance_deg: 1.0,
            target: Target::FreeSlots,
            said: None,
        }
    }
}

crate::words! {
    /// The dialog's words (a family's follower says what it made in them).
    #[allow(missing_docs)]
    pub struct Words in "follow" {
        pub lang: Language,
        pub title: &'static str,
        pub servo: &'static str,
        pub joint: &'static str,
        pub closed: &'static str,
        pub open: &'static str,
        pub attack: &'static str,
        pub release: &'static str,
        pub threshold: &'static str,
        pub tolerance: &'static str,
        pub make: &'static str,
        pub close: &'static str,
        pub no_servo: &'static str,
        pub write_to: &'static str,
        pub free_slots: &'static str,
        pub from_slot: &'static str,
        pub replaces: &'static str,
        pub made_chain: &'static str,
        pub replaced: &'static str,
        /// A chain fitted with the curve shifted (`{ms}`, signed) within half a cycle.
        pub shifted: &'static str,
        pub no_slot: &'static str,
        pub frames: &'static str,
        pub steps: &'static str,
        pub tolerance_error: &'static str,
        pub too_long: &'static str,
        /// What to do when a PLEN2's slots are too few for the sound.
        pub more_slots: &'static str,
        /// The open board has no axis the sound can move.
        pub no_axis: &'static str,
    }
}

/// The dialog's words in `language`.
pub fn words(language: Language) -> &'static Words {
    Words::of(language)
}

/// A family whose axis can follow the sound's loudness (a servo, a PLEN2
/// joint): the dialog asks it for its axes and for the motion, never which
/// family it is. A family with none (a base) offers no follower.
pub trait SoundFollower {
    /// The axes that may follow, each a key and a name, in order.
    fn axes(&self, project: &Project) -> Vec<(usize, String)>;

    /// What one of its axes is called.
    fn axis_word(&self, words: &Words) -> &'static str;

    /// Rows of its own under the axis (a PLEN2's "Write to"); `target` is
    /// where the motion goes. Whether `target` changed.
    fn options(&self, _ui: &mut egui::Ui, _project: &Project, _target: &mut Target, _words: &Words) -> bool {
        false
    }

    /// The motion of `axis` following `open` (0 closed … 1 open, a value a
    /// millisecond on the motion's time): the project's edits (one undo step)
    /// and what to say; or why not, in the interface's words.
    fn make(
        &self,
        project: &Project,
        axis: usize,
        open: &[f64],
        how: (Follower, Target),
        words: &Words,
    ) -> Result<(Vec<Edit>, Said), Said>;
}

/// Something the dialog says, worded from its words in every language.
pub fn said_by(word: impl Fn(&Words) -> String) -> Said {
    Said::new(|language| word(words(language)))
}

impl FollowForm {
    /// The dialog; `open` is cleared by its Close. `loudness_db` is the
    /// sound's, one value a millisecond; `offset_ms` where it starts on the
    /// motion's time; `family` the open family's follower (None: it has no
    /// axis to follow with, and the dialog says so).
    pub fn window(
        &mut self,
        ctx: &egui::Context,
        (project, loudness_db, offset_ms): (&Project, &[f32], i64),
        (family, language): (Option<&dyn SoundFollower>, Language),
        open: &mut bool,
        actions: &mut Vec<Action>,
    ) {
        let words = words(language);
        let mut keep = true;
        let middle = ctx.content_rect().center();
        let window = egui::Window::new(words.title).collapsible(false).resizable(false);
        window.pivot(egui::Align2::CENTER_CENTER).default_pos(middle).show(ctx, |ui| {
            // What it says wraps: a long message does not widen the dialog.
            ui.set_max_width(DIALOG_WIDTH);
            let Some(family) = family else {
                ui.label(words.no_axis);
                keep = !ui.button(words.close).clicked();
                return;
            };
            self.axis(ui, project, family, words);
            if family.options(ui, project, &mut self.target, words) {
                // What the last try said was of the target before.
                self.said = None;
            }
            egui::Grid::new("follow-sound").num_columns(2).show(ui, |ui| {
                let row = |ui: &mut egui::Ui, label: &str, value: &mut f64, range, suffix: &str| {
                    let label = ui.label(label);
                    ui.add(egui::DragValue::new(value).range(range).suffix(suffix)).labelled_by(label.id);
                    ui.end_row();
                };
                row(ui, words.closed, &mut self.closed_deg, -180.0..=180.0, "°");
                row(ui, words.open, &mut self.open_deg, -180.0..=180.0, "°");
                row(ui, words.attack, &mut self.attack_ms, 0.1..=10_000.0, " ms");
                row(ui, words.release, &mut self.release_ms, 0.1..=10_000.0, " ms");
                row(ui, words.threshold, &mut self.threshold_db, -120.0..=0.0, " dB");
                row(ui, words.tolerance, &mut self.tolerance_deg, 0.1..=90.0, "°");
            });
            if let Some(said) = &self.said {
                ui.label(said.in_(words.lang));
            }
            ui.horizontal(|ui| {
                if ui.button(words.make).clicked() {
                    self.make(project, family, (loudness_db, offset_ms), words, actions);
                }
                keep = !ui.button(words.close).clicked();
            });
        });
        *open &= keep;
    }

    /// The axis that follows, among those the family offers.
    fn axis(&mut self, ui: &mut egui::Ui, project: &Project, family: &dyn SoundFollower, words: &Words) {
        let axes = family.axes(project);
        if self.axis.is_none_or(|key| !axes.iter().any(|(axis, _)| *axis == key)) {
            self.axis = axes.first().map(|(axis, _)| *axis);
        }
        ui.horizontal(|ui| {
            let label = ui.label(family.axis_word(words));
            let Some(selected) = self.axis else {
                ui.label(words.no_servo);
                return;
            };
            let name = |key: usize| axes.iter().find(|(axis, _)| *axis == key).map_or("", |(_, name)| name.as_str());
            egui::ComboBox::from_id_salt("follow-axis")
                .selected_text(name(selected))
                .show_ui(ui, |ui| {
                    for (key, name) in &axes {
                        ui.selectable_value(&mut self.axis, Some(*key), name);
                    }
                })
                .response
                .labelled_by(label.id);
        });
    }

    /// Follows, fits and adds the motion to the project (one undo step).
    fn make(
        &mut self,
        project: &Project,
        family: &dyn SoundFollower,
        (loudness_db, offset_ms): (&[f32], i64),
        words: &Words,
        actions: &mut Vec<Action>,
    ) {
        let Some(axis) = self.axis else { return };
        let settings =
            Follow { attack_ms: self.attack_ms, release_ms: self.release_ms, threshold_db: self.threshold_db };
        let mut open = loudness::openness(loudness_db, &settings);
        // On the motion's time: closed until the sound starts, or the sound's start cut.
        match usize::try_from(offset_ms) {
            Ok(late) => open.splice(0..0, std::iter::repeat_n(0.0, late)).for_each(drop),
            Err(_) => open
                .drain(..usize::try_from(offset_ms.unsigned_abs()).unwrap_or(usize::MAX).min(open.len()))
                .for_each(drop),
        }
        let follower =
            Follower { closed_deg: self.closed_deg, open_deg: self.open_deg, tolerance_deg: self.tolerance_deg };
        self.said = Some(match family.make(project, axis, &open, (follower, self.target), words) {
            Ok((edits, said)) => {
                let key = Some("follow the sound".to_string());
                actions.extend(edits.into_iter().map(|edit| Action::Edit { edit, coalesce: key.clone() }));
                said
            }
            Err(said) => said,
        });
    }
}

/// A fit that failed, in the interface's words: tolerances in degrees
/// (`degrees` a board unit: a PLEN2's tenth, a servo's degree), lengths in
/// ms (`update_ms` a board update), `moves` the board's frames or steps.
pub fn fit_error(error: &FitError, (degrees, update_ms): (f64, f64), moves: &str, words: &Words) -> String {
    let deg = |units: f64| format!("{:.1}°", units * degrees);
    match *error {
        FitError::Tolerance { needed, allowed, tolerance, smallest } => words
            .tolerance_error
            .replace("{needed}", &needed.to_string())
            .replace("{moves}", moves)
            .replace("{tolerance}", &deg(tolerance))
            .replace("{allowed}", &allowed.to_string())
            .replace("{smallest}", &deg(smallest)),
        FitError::TooLong { needed, longest, allowed, .. } => {
            // Updates in one move: at most a few hundred.
            #[allow(clippy::cast_precision_loss)]
            let longest_ms = format!("{:.0} ms", longest as f64 * update_ms);
            words
                .too_long
                .replace("{needed}", &needed.to_string())
                .replace("{moves}", moves)
                .replace("{longest}", &longest_ms)
                .replace("{allowed}", &allowed.to_string())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_fit_that_cannot_be_made_is_said_in_degrees_and_ms() {
        let tolerance = FitError::Tolerance { needed: 36, allowed: 20, tolerance: 10.0, smallest: 29.0 };
        let english = Words::of(Language::English);
        let said = fit_error(&tolerance, (0.1, 32.768), english.frames, english);
        assert_eq!(
            said,
            "36 frames are needed within 1.0° and at most 20 fit; the smallest tolerance that fits is 2.9°"
        );
        let too_long = FitError::TooLong { updates: 9000, needed: 30, longest: 255, allowed: 20 };
        let chinese = Words::of(Language::TraditionalChinese);
        let said = fit_error(&too_long, (1.0, 10.0), chinese.steps, chinese);
        assert!(said.starts_with("聲音太長") && said.contains("2550 ms"), "{said}");
    }
}
