//! Follow the sound: pick a servo (or a PLEN2 joint), a closed and an open
//! angle, attack and release; the sound's loudness becomes that axis's
//! motion, fitted into the board's steps or frames within the tolerance
//! (a talking skull's jaw, a PLEN2 nodding to a beat). The motion is timed
//! to the sound as the lane places it (its offset), and added to the
//! project in one undo step: a servo's actions and a macro running them, or
//! a PLEN2 chain of motions — each up to 20 frames, jumping to the next, so
//! a sentence fits — in the free slots or from a slot the user picks
//! (replacing what it holds).

use crate::audio::follow::{self as loudness, Follow};
use crate::authoring::fit::FitError;
use crate::authoring::fitted::{PLEN2_UPDATE_MS, SERVO_UPDATE_MS};
use crate::authoring::follow::{self, Follower};
use crate::project::plen2::{Joint, Motion, Plen2Project, SLOTS};
use crate::project::{Edit, Family, Project, next_free_id};
use crate::ui::action::Action;
use crate::ui::i18n::Language;

/// The dialog's widest, points.
const DIALOG_WIDTH: f32 = 560.0;

/// The dialog's fields.
#[derive(Clone, Debug, PartialEq)]
pub struct FollowForm {
    servo_id: Option<u8>,
    joint: usize,
    closed_deg: f64,
    open_deg: f64,
    attack_ms: f64,
    release_ms: f64,
    threshold_db: f64,
    tolerance_deg: f64,
    /// Where a PLEN2's motions are written.
    target: Target,
    /// What the last try said.
    said: Option<String>,
}

/// Where a PLEN2's follow is written: a chain of motions (each up to 20
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
            servo_id: None,
            joint: 0,
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

/// The dialog's words.
struct Words {
    title: &'static str,
    servo: &'static str,
    joint: &'static str,
    closed: &'static str,
    open: &'static str,
    attack: &'static str,
    release: &'static str,
    threshold: &'static str,
    tolerance: &'static str,
    make: &'static str,
    close: &'static str,
    no_servo: &'static str,
    made_steps: &'static str,
    write_to: &'static str,
    free_slots: &'static str,
    from_slot: &'static str,
    replaces: &'static str,
    made_chain: &'static str,
    replaced: &'static str,
    no_slot: &'static str,
    frames: &'static str,
    steps: &'static str,
    tolerance_error: &'static str,
    too_long: &'static str,
    /// What to do when a PLEN2's slots are too few for the sound.
    more_slots: &'static str,
}

const ENGLISH: Words = Words {
    title: "Follow the sound",
    servo: "Servo",
    joint: "Joint",
    closed: "Closed (silence)",
    open: "Open (loudest)",
    attack: "Attack",
    release: "Release",
    threshold: "Quieter than this stays closed",
    tolerance: "Tolerance",
    make: "Make the motion",
    close: "Close",
    no_servo: "Add a servo first",
    made_steps: "steps, run by macro",
    write_to: "Write to",
    free_slots: "the free slots",
    from_slot: "from slot",
    replaces: "replaces",
    made_chain: "{frames} frames in {motions} motions, slots {slots}, played as one (each jumps to the next)",
    replaced: "; replaced: ",
    no_slot: "every PLEN2 slot is taken: pick the slot to write to under Write to (what it holds is replaced; Undo brings it back)",
    frames: "frames",
    steps: "steps",
    tolerance_error: "{needed} {moves} are needed within {tolerance} and at most {allowed} fit; the smallest tolerance that fits is {smallest}",
    too_long: "the sound is too long: it needs at least {needed} {moves} of at most {longest} each, and at most {allowed} fit",
    more_slots: ": write from an earlier slot (its chain may take the slots after it), or use a shorter sound",
};

const TRADITIONAL_CHINESE: Words = Words {
    title: "跟隨聲音",
    servo: "伺服機",
    joint: "關節",
    closed: "閉合（安靜時）",
    open: "張開（最大聲時）",
    attack: "起音時間",
    release: "釋放時間",
    threshold: "低於此音量保持閉合",
    tolerance: "容許誤差",
    make: "產生動作",
    close: "關閉",
    no_servo: "請先加入伺服機",
    made_steps: "個步驟，由巨集執行：",
    write_to: "寫入",
    free_slots: "空的位置",
    from_slot: "從位置",
    replaces: "取代",
    made_chain: "{frames} 個影格，共 {motions} 個動作，位於位置 {slots}，連續播放（每個動作接著跳到下一個）",
    replaced: "；已取代：",
    no_slot: "PLEN2 的位置都已使用：請在「寫入」選擇要寫入的位置（原有內容會被取代；可用復原找回）",
    frames: "影格",
    steps: "步驟",
    tolerance_error: "在 {tolerance} 內需要 {needed} 個{moves}，最多只能放 {allowed} 個；可行的最小容許誤差為 {smallest}",
    too_long: "聲音太長：至少需要 {needed} 個{moves}（每個最長 {longest}），最多只能放 {allowed} 個",
    more_slots: "：請從較前面的位置寫入（動作串可使用其後的位置），或改用較短的聲音",
};

fn words(language: Language) -> &'static Words {
    match language {
        Language::English => &ENGLISH,
        Language::TraditionalChinese => &TRADITIONAL_CHINESE,
    }
}

impl FollowForm {
    /// The dialog; `open` is cleared by its Close. `loudness_db` is the
    /// sound's, one value a millisecond; `offset_ms` where it starts on the motion's time.
    pub fn window(
        &mut self,
        ctx: &egui::Context,
        (project, loudness_db, offset_ms): (&Project, &[f32], i64),
        language: Language,
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
            self.axis(ui, project, words);
            if project.family == Family::Plen2 {
                self.target_row(ui, project, words);
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
                ui.label(said);
            }
            ui.horizontal(|ui| {
                if ui.button(words.make).clicked() {
                    self.make(project, (loudness_db, offset_ms), words, actions);
                }
                keep = !ui.button(words.close).clicked();
            });
        });
        *open &= keep;
    }

    /// The servo or the joint that follows.
    fn axis(&mut self, ui: &mut egui::Ui, project: &Project, words: &Words) {
        ui.horizontal(|ui| {
            if project.family == Family::Plen2 {
                let label = ui.label(words.joint);
                let names: Vec<&str> = Joint::ALL.iter().map(|joint| joint.name()).collect();
                egui::ComboBox::from_id_salt("follow-joint")
                    .selected_text(names[self.joint])
                    .show_ui(ui, |ui| {
                        for (index, name) in names.iter().enumerate() {
                            ui.selectable_value(&mut self.joint, index, *name);
                        }
                    })
                    .response
                    .labelled_by(label.id);
                return;
            }
            let servos = &project.servo.servos;
            if self.servo_id.is_none_or(|id| !servos.iter().any(|servo| servo.id == id)) {
                self.servo_id = servos.first().map(|servo| servo.id);
            }
            ui.label(words.servo);
            let Some(selected) = self.servo_id else {
                ui.label(words.no_servo);
                return;
            };
            let name = |id: u8| {
                servos.iter().find(|s| s.id == id).map_or(String::new(), |s| format!("{} {}", s.id, s.caption))
            };
            egui::ComboBox::from_id_salt("follow-servo").selected_text(name(selected)).show_ui(ui, |ui| {
                for servo in servos {
                    ui.selectable_value(&mut self.servo_id, Some(servo.id), name(servo.id));
                }
            });
        });
    }

    /// Follows, fits and adds the motion to the project (one undo step).
    fn make(
        &mut self,
        project: &Project,
        (loudness_db, offset_ms): (&[f32], i64),
        words: &Words,
        actions: &mut Vec<Action>,
    ) {
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
        let key = Some("follow the sound".to_string());
        let edit = |edit: Edit| Action::Edit { edit, coalesce: key.clone() };
        if project.family == Family::Plen2 {
            self.said = Some(match self.follow_plen2(&project.plen2, &open, follower, words) {
                Ok((plen2, said)) => {
                    actions.push(edit(Edit::SetPlen2(Box::new(plen2))));
                    said
                }
                Err(said) => said,
            });
            return;
        }
        let Some(servo_id) = self.servo_id else { return };
        let servo = &project.servo;
        // Ids after every one in use: the fitted actions take the next ones in a row.
        let first = servo.actions.iter().map(|action| action.id).max().unwrap_or(0).saturating_add(1);
        let macro_id = next_free_id(servo.macros.iter().map(|item| item.id));
        match follow::servo(&open, servo_id, follower, (first, macro_id, "follow the sound")) {
            Ok((made, running, _)) => {
                self.said = Some(format!("{} {} {macro_id}", made.len(), words.made_steps));
                actions.extend(made.into_iter().map(|action| edit(Edit::AddAction(action))));
                actions.push(edit(Edit::AddMacro(running)));
            }
            Err(error) => self.said = Some(fit_error(&error, (1.0, SERVO_UPDATE_MS), words.steps, words)),
        }
    }

    /// Which slots a PLEN2's follow may take, in the order its chain takes them.
    fn slots(&self, plen2: &Plen2Project) -> Vec<u8> {
        match self.target {
            Target::FreeSlots => (0..SLOTS).filter(|slot| !plen2.motions.iter().any(|m| m.slot == *slot)).collect(),
            Target::From(first) => (first..SLOTS).collect(),
        }
    }

    /// "Write to": the free slots, or a slot and those after it (saying
    /// what it holds: that is what is replaced first).
    fn target_row(&mut self, ui: &mut egui::Ui, project: &Project, words: &Words) {
        let before = self.target;
        ui.horizontal(|ui| {
            ui.label(words.write_to);
            ui.radio_value(&mut self.target, Target::FreeSlots, words.free_slots);
            let first = match self.target {
                Target::From(slot) => slot,
                Target::FreeSlots => 0,
            };
            let from = ui.radio_value(&mut self.target, Target::From(first), words.from_slot);
            let mut slot = first;
            let field = ui.add_enabled(
                matches!(self.target, Target::From(_)),
                egui::DragValue::new(&mut slot).range(0..=SLOTS - 1),
            );
            if field.labelled_by(from.id).changed() {
                self.target = Target::From(slot);
            }
            if let Target::From(slot) = self.target
                && let Some(held) = project.plen2.motions.iter().find(|m| m.slot == slot)
            {
                ui.weak(format!("{} {slot} {}", words.replaces, held.name));
            }
        });
        if self.target != before {
            // What the last try said was of the slots before.
            self.said = None;
        }
    }

    /// The project with a PLEN2 joint following the sound — a chain of
    /// motions in the slots [`Self::slots`] gives, each jumping to the next —
    /// and what to say; or why not, in the interface's words.
    fn follow_plen2(
        &self,
        plen2: &Plen2Project,
        open: &[f64],
        follower: Follower,
        words: &Words,
    ) -> Result<(Plen2Project, String), String> {
        let slots = self.slots(plen2);
        if slots.is_empty() {
            return Err(words.no_slot.to_string());
        }
        let chain = follow::plen2(open, Joint::ALL[self.joint], follower, slots.len()).map_err(|error| {
            let said = fit_error(&error, (0.1, PLEN2_UPDATE_MS), words.frames, words);
            // Too long for the slots it may take: more slots hold more.
            if matches!(error, FitError::TooLong { .. }) { format!("{said}{}", words.more_slots) } else { said }
        })?;
        let used = &slots[..chain.len()];
        let mut made = plen2.clone();
        let replaced: Vec<String> = made
            .motions
            .iter()
            .filter(|motion| used.contains(&motion.slot))
            .map(|motion| format!("{} {}", motion.slot, motion.name))
            .collect();
        made.motions.retain(|motion| !used.contains(&motion.slot));
        let frames: usize = chain.iter().map(Vec::len).sum();
        for (part, (frames, &slot)) in chain.into_iter().zip(used).enumerate() {
            let jump_slot = used.get(part + 1).copied();
            made.motions.push(Motion { slot, name: "follow".into(), frames, loop_range: None, jump_slot });
        }
        made.motions.sort_by_key(|motion| motion.slot);
        let listed: Vec<String> = used.iter().map(u8::to_string).collect();
        let mut said = words
            .made_chain
            .replace("{frames}", &frames.to_string())
            .replace("{motions}", &used.len().to_string())
            .replace("{slots}", &listed.join(", "));
        if !replaced.is_empty() {
            said = format!("{said}{}{}", words.replaced, replaced.join(", "));
        }
        Ok((made, said))
    }
}

/// A fit that failed, in the interface's words: tolerances in degrees
/// (`degrees` a board unit: a PLEN2's tenth, a servo's degree), lengths in
/// ms (`update_ms` a board update), `moves` the board's frames or steps.
fn fit_error(error: &FitError, (degrees, update_ms): (f64, f64), moves: &str, words: &Words) -> String {
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
    fn a_fit_that_cannot_be_made_is_said_in_degrees_and_ms_and_a_short_chain_says_what_to_do() {
        let tolerance = FitError::Tolerance { needed: 36, allowed: 20, tolerance: 10.0, smallest: 29.0 };
        let said = fit_error(&tolerance, (0.1, PLEN2_UPDATE_MS), ENGLISH.frames, &ENGLISH);
        assert_eq!(
            said,
            "36 frames are needed within 1.0° and at most 20 fit; the smallest tolerance that fits is 2.9°"
        );
        // 200 s of sound from slot 89: one motion of 20 frames of at most 255 cycles cannot hold it.
        let form = FollowForm { target: Target::From(89), ..FollowForm::default() };
        let open = vec![0.5; 200_000];
        let follower = Follower { closed_deg: 0.0, open_deg: 30.0, tolerance_deg: 1.0 };
        let said = form.follow_plen2(&Plen2Project::default(), &open, follower, &TRADITIONAL_CHINESE).unwrap_err();
        assert!(said.starts_with("聲音太長") && said.contains("8356 ms"), "{said}");
        assert!(said.ends_with(TRADITIONAL_CHINESE.more_slots), "says what to do: {said}");
    }
}
