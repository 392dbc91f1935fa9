//! What a conversion made, added to the project open in the editor: servos it
//! lacks, actions and macros under ids it does not use yet (references
//! renumbered with them), PLEN2 motions in its free slots (jumps and play
//! lists following them).

use std::collections::HashMap;

use crate::project::plen2::{Plen2Project, SLOTS};
use crate::project::{Run, ServoProject, next_free_id};

/// `built` added to `into`; the notes say what was kept or renumbered.
pub fn servo(into: &ServoProject, built: &ServoProject) -> (ServoProject, Vec<String>) {
    let mut merged = into.clone();
    let mut notes = Vec::new();
    let mut kept = Vec::new();
    for servo in &built.servos {
        if merged.servo(servo.id).is_some() {
            kept.push(servo.id.to_string());
        } else {
            merged.servos.push(servo.clone());
        }
    }
    if !kept.is_empty() {
        notes.push(format!("servos already in the project keep their settings: {}", kept.join(", ")));
    }
    merged.servos.sort_by_key(|servo| servo.id);
    let mut action_ids = HashMap::new();
    for action in &built.actions {
        let id = next_free_id(merged.actions.iter().map(|a| a.id));
        action_ids.insert(action.id, id);
        let mut action = action.clone();
        action.id = id;
        merged.actions.push(action);
    }
    let mut macro_ids = HashMap::new();
    let mut used: Vec<i32> = merged.macros.iter().map(|m| m.id).collect();
    for item in &built.macros {
        let id = next_free_id(used.iter().copied());
        used.push(id);
        macro_ids.insert(item.id, id);
    }
    for item in &built.macros {
        let mut item = item.clone();
        item.id = macro_ids[&item.id];
        for command in &mut item.commands {
            match &mut command.run {
                Run::Action { action_id } => *action_id = action_ids.get(action_id).copied().unwrap_or(*action_id),
                Run::Macro { macro_id } => *macro_id = macro_ids.get(macro_id).copied().unwrap_or(*macro_id),
                Run::Delay { .. } => {}
            }
        }
        merged.macros.push(item);
    }
    if action_ids.iter().any(|(from, to)| from != to) || macro_ids.iter().any(|(from, to)| from != to) {
        notes.push("actions and macros take ids the project does not use yet".into());
    }
    (merged, notes)
}

/// `built`'s motions in `into`'s free slots, in order; refused when they do not fit.
pub fn plen2(into: &Plen2Project, built: &Plen2Project) -> Result<(Plen2Project, Vec<String>), String> {
    let free: Vec<u8> = (0..SLOTS).filter(|slot| into.motions.iter().all(|m| m.slot != *slot)).collect();
    if free.len() < built.motions.len() {
        return Err(format!(
            "the import needs {} motion slots and the project has {} free: remove motions, or import fewer (choose one)",
            built.motions.len(),
            free.len()
        ));
    }
    let slots: HashMap<u8, u8> = built.motions.iter().map(|m| m.slot).zip(free).collect();
    let mut merged = into.clone();
    for motion in &built.motions {
        let mut motion = motion.clone();
        motion.slot = slots[&motion.slot];
        motion.jump_slot = motion.jump_slot.map(|slot| slots.get(&slot).copied().unwrap_or(slot));
        merged.motions.push(motion);
    }
    merged.motions.sort_by_key(|m| m.slot);
    for list in &built.play_lists {
        let mut list = list.clone();
        for entry in &mut list.entries {
            entry.slot = slots.get(&entry.slot).copied().unwrap_or(entry.slot);
        }
        merged.play_lists.push(list);
    }
    let moved = slots.iter().any(|(from, to)| from != to);
    let notes = if moved { vec!["motions take the project's free slots".to_string()] } else { Vec::new() };
    Ok((merged, notes))
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use crate::project::plen2::{Frame, Motion, PlayEntry, PlayList, Pose};
    use crate::project::{Action, Command, Macro, Servo, Step};

    #[test]
    fn servo_imports_take_free_ids_and_keep_their_references() {
        let mut into = ServoProject::default();
        into.servos.push(Servo::new(1, "mine"));
        into.actions.push(Action { id: 1, caption: "old".into(), steps: vec![Step::new(1, 5, 10)] });
        into.macros.push(Macro { id: 1, caption: "old".into(), commands: Vec::new() });
        let mut built = ServoProject::default();
        built.servos.extend([Servo::new(1, "theirs"), Servo::new(2, "new")]);
        built.actions.push(Action { id: 1, caption: "a".into(), steps: vec![Step::new(2, 30, 50)] });
        built.macros.push(Macro {
            id: 1,
            caption: "body".into(),
            commands: vec![Command::once(Run::Action { action_id: 1 })],
        });
        built.macros.push(Macro {
            id: 2,
            caption: "play".into(),
            commands: vec![Command::once(Run::Macro { macro_id: 1 })],
        });
        let (merged, notes) = servo(&into, &built);
        assert_eq!(merged.servo(1).unwrap().caption, "mine");
        assert_eq!(merged.servo(2).unwrap().caption, "new");
        assert_eq!(merged.macros[1].commands[0].run, Run::Action { action_id: 2 });
        assert_eq!(merged.macros[2].commands[0].run, Run::Macro { macro_id: 2 });
        assert!(notes.iter().any(|n| n.ends_with("keep their settings: 1")), "{notes:?}");
    }

    #[test]
    fn plen2_imports_take_free_slots_and_follow_their_jumps() {
        let motion = |slot, jump| Motion {
            slot,
            name: "m".into(),
            frames: vec![Frame::new(320, Pose::default())],
            loop_range: None,
            jump_slot: jump,
        };
        let into = Plen2Project { motions: vec![motion(0, None)], ..Default::default() };
        let built = Plen2Project {
            motions: vec![motion(0, Some(1)), motion(1, None)],
            play_lists: vec![PlayList { name: "p".into(), entries: vec![PlayEntry { slot: 1, plays: 2 }] }],
            ..Default::default()
        };
        let (merged, _) = plen2(&into, &built).unwrap();
        assert_eq!(
            merged.motions.iter().map(|m| (m.slot, m.jump_slot)).collect::<Vec<_>>(),
            [(0, None), (1, Some(2)), (2, None)]
        );
        assert_eq!(merged.play_lists[0].entries[0].slot, 2);
        let full = Plen2Project { motions: (0..90).map(|slot| motion(slot, None)).collect(), ..Default::default() };
        assert!(plen2(&full, &built).unwrap_err().contains("0 free"));
    }
}
