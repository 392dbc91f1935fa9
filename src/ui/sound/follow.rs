//! Follow the sound: pick a servo (or a PLEN2 joint), a closed and an open
//! angle, attack and release; the sound's loudness becomes that axis's
//! motion, fitted into the board's steps or frames within the tolerance
//! (a talking skull's jaw, a PLEN2 nodding to a beat). The motion is timed
//! to the sound as the lane places it (its offset), and added to the
//! project in one undo step: a servo's actions and a macro running them, or
//! a PLEN2 motion in the first free slot.

use crate::audio::follow::{self as loudness, Follow};
use crate::authoring::follow::{self, Follower};
use crate::project::plen2::{Joint, Motion, SLOTS};
use crate::project::{Edit, Family, Project, next_free_id};
use crate::ui::action::Action;
use crate::ui::i18n::Language;

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
    /// What the last try said.
    said: Option<String>,
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
    made_frames: &'static str,
    no_slot: &'static str,
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
    made_frames: "frames, in slot",
    no_slot: "every PLEN2 slot is taken",
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
    made_frames: "個影格，位於槽位",
    no_slot: "PLEN2 的槽位都已使用",
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
            self.axis(ui, project, words);
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
                egui::ComboBox::from_id_salt("follow-joint").selected_text(names[self.joint]).show_ui(ui, |ui| {
                    for (index, name) in names.iter().enumerate() {
                        ui.selectable_value(&mut self.joint, index, *name);
                    }
                });
                let _ = label;
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
            let Some(slot) = (0..SLOTS).find(|slot| !project.plen2.motions.iter().any(|m| m.slot == *slot)) else {
                self.said = Some(words.no_slot.to_string());
                return;
            };
            match follow::plen2(&open, Joint::ALL[self.joint], follower) {
                Ok(frames) => {
                    self.said = Some(format!("{} {} {slot}", frames.len(), words.made_frames));
                    let mut plen2 = project.plen2.clone();
                    plen2.motions.push(Motion {
                        slot,
                        name: "follow".into(),
                        frames,
                        loop_range: None,
                        jump_slot: None,
                    });
                    plen2.motions.sort_by_key(|motion| motion.slot);
                    actions.push(edit(Edit::SetPlen2(Box::new(plen2))));
                }
                Err(error) => self.said = Some(error.to_string()),
            }
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
            Err(error) => self.said = Some(error.to_string()),
        }
    }
}
