//! A PLEN2 joint follows the sound: a chain of motions — each up to 20
//! frames, jumping to the next, so a sentence fits — in the free slots or
//! from a slot the user picks, replacing what it holds (the follow dialog,
//! `ui::sound::follow`, asks for them).

use crate::authoring::fit::FitError;
use crate::authoring::fitted::PLEN2_UPDATE_MS;
use crate::authoring::follow;
use crate::project::plen2::{Joint, Plen2Project, SLOTS};
use crate::project::{Edit, Project};
use crate::ui::i18n::Said;
use crate::ui::sound::follow::{Follower, SoundFollower, Target, Words, fit_error, said_by};

/// A PLEN2's side of following the sound.
pub struct Plen2Follower;

impl SoundFollower for Plen2Follower {
    fn axes(&self, _project: &Project) -> Vec<(usize, String)> {
        Joint::ALL.iter().enumerate().map(|(index, joint)| (index, joint.name().to_string())).collect()
    }

    fn axis_word(&self, words: &Words) -> &'static str {
        words.joint
    }

    /// "Write to": the free slots, or a slot and those after it (saying
    /// what it holds: that is what is replaced first).
    fn options(&self, ui: &mut egui::Ui, project: &Project, target: &mut Target, words: &Words) -> bool {
        let before = *target;
        ui.horizontal(|ui| {
            ui.label(words.write_to);
            ui.radio_value(target, Target::FreeSlots, words.free_slots);
            let first = match *target {
                Target::From(slot) => slot,
                Target::FreeSlots => 0,
            };
            let from = ui.radio_value(target, Target::From(first), words.from_slot);
            let mut slot = first;
            let field = ui
                .add_enabled(matches!(*target, Target::From(_)), egui::DragValue::new(&mut slot).range(0..=SLOTS - 1));
            if field.labelled_by(from.id).changed() {
                *target = Target::From(slot);
            }
            if let Target::From(slot) = *target
                && let Some(held) = project.plen2.motions.iter().find(|m| m.slot == slot)
            {
                ui.weak(format!("{} {slot} {}", words.replaces, held.name));
            }
        });
        *target != before
    }

    fn make(
        &self,
        project: &Project,
        axis: usize,
        open: &[f64],
        (follower, target): (Follower, Target),
        _words: &Words,
    ) -> Result<(Vec<Edit>, Said), Said> {
        let joint = *Joint::ALL.get(axis).ok_or_else(|| said_by(|words| words.no_axis.to_string()))?;
        let (plen2, said) = chain(&project.plen2, joint, open, (follower, target))?;
        Ok((vec![Edit::SetPlen2(Box::new(plen2))], said))
    }
}

/// Which slots the follow may take, in the order its chain takes them.
fn slots(target: Target, plen2: &Plen2Project) -> Vec<u8> {
    match target {
        Target::FreeSlots => (0..SLOTS).filter(|slot| !plen2.motions.iter().any(|m| m.slot == *slot)).collect(),
        Target::From(first) => (first..SLOTS).collect(),
    }
}

/// The project with `joint` following the sound — a chain of motions in
/// the slots [`slots`] gives, each jumping to the next — and what to say;
/// or why not, in the interface's words (every language's).
fn chain(
    plen2: &Plen2Project,
    joint: Joint,
    open: &[f64],
    (follower, target): (Follower, Target),
) -> Result<(Plen2Project, Said), Said> {
    let slots = slots(target, plen2);
    if slots.is_empty() {
        return Err(said_by(|words| words.no_slot.to_string()));
    }
    let chain = follow::plen2(open, joint, follower, slots.len()).map_err(|error| {
        said_by(|words| {
            let said = fit_error(&error, (0.1, PLEN2_UPDATE_MS), words.frames, words);
            // Too long for the slots it may take: more slots hold more.
            if matches!(error, FitError::TooLong { .. }) { format!("{said}{}", words.more_slots) } else { said }
        })
    })?;
    let (made, replaced) = follow::placed(plen2, &slots, &chain, "follow");
    let replaced: Vec<String> = replaced.iter().map(|(slot, name)| format!("{slot} {name}")).collect();
    let used = &slots[..chain.motions.len()];
    let frames = chain.frames();
    let listed = used.iter().map(u8::to_string).collect::<Vec<String>>().join(", ");
    let motions = used.len();
    let shift_ms = chain.shift_ms;
    let said = said_by(|words| {
        let mut made = words
            .made_chain
            .replace("{frames}", &frames.to_string())
            .replace("{motions}", &motions.to_string())
            .replace("{slots}", &listed);
        if shift_ms != 0 {
            made.push_str(&words.shifted.replace("{ms}", &format!("{shift_ms:+}")));
        }
        if replaced.is_empty() { made } else { format!("{made}{}{}", words.replaced, replaced.join(", ")) }
    });
    Ok((made, said))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::project::plen2::Motion;
    use crate::ui::i18n::Language;
    use crate::ui::sound::follow::words;

    /// 200 s of sound from slot 89: one motion of 20 frames of at most 255
    /// cycles cannot hold it, and the dialog says what to do.
    #[test]
    fn a_chain_too_short_for_the_sound_says_what_to_do() {
        let open = vec![0.5; 200_000];
        let follower = Follower { closed_deg: 0.0, open_deg: 30.0, tolerance_deg: 1.0 };
        let words = words(Language::TraditionalChinese);
        let plen2 = Plen2Project::default();
        let said = chain(&plen2, Joint::ALL[0], &open, (follower, Target::From(89))).unwrap_err();
        let said = said.in_(Language::TraditionalChinese);
        assert!(said.starts_with("聲音太長") && said.contains("8356 ms"), "{said}");
        assert!(said.ends_with(words.more_slots), "says what to do: {said}");
    }

    #[test]
    fn a_follow_fills_the_free_slots_in_order_and_replaces_from_a_picked_slot() {
        let mut plen2 = Plen2Project::default();
        plen2.motions.push(Motion {
            slot: 0,
            name: "wave".into(),
            frames: Vec::new(),
            loop_range: None,
            jump_slot: None,
        });
        assert_eq!(slots(Target::FreeSlots, &plen2)[..2], [1, 2], "slot 0 is taken");
        assert_eq!(slots(Target::From(0), &plen2)[..2], [0, 1], "a picked slot is taken whatever it holds");
        let open: Vec<f64> = (0..2_000).map(|ms| f64::from(ms / 250 % 2)).collect();
        let follower = Follower { closed_deg: 0.0, open_deg: 30.0, tolerance_deg: 1.0 };
        let (made, said) = chain(&plen2, Joint::ALL[0], &open, (follower, Target::From(0))).unwrap();
        let said = said.in_(Language::English);
        assert!(said.contains("replaced: 0 wave"), "{said}");
        assert_eq!(made.motions[0].name, "follow");
    }
}
