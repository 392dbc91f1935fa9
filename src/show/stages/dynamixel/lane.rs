//! A DYNAMIXEL bus on the show's timeline: before its first cue each servo
//! is at its centre; from a cue on, where the cue's motion has it, played
//! from where the cue before left it — the poses the stream sends.

use std::collections::BTreeMap;

use crate::project::dynamixel::{DynamixelSection, Motion, degrees, units};
use crate::project::{Family, Project};
use crate::show::at::Posed;
use crate::show::timeline::{FamilyTimeline, Lane};
use crate::show::{Device, Start};

inventory::submit! {
    FamilyTimeline { family: Family::Dynamixel, lane: || Box::new(DynamixelLane) }
}

/// The bus on the timeline: it works out each pose as asked.
#[derive(Debug)]
struct DynamixelLane;

/// The motion a cue plays, if the project holds it.
fn motion(section: &DynamixelSection, start: &Start) -> Option<Motion> {
    let Start::Family(cue) = start else { return None };
    if cue.kind != super::MOTION || cue.value < 1.0 || cue.value.fract() != 0.0 {
        return None;
    }
    // A whole number of at least 1.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    section.motions.get(cue.value as usize - 1).cloned()
}

impl Lane for DynamixelLane {
    fn length_ms(&mut self, project: &Project, start: &Start) -> u64 {
        motion(&DynamixelSection::of(project), start).map_or(0, |motion| motion.duration_ms())
    }

    fn posed_at(&mut self, device: &Device, cues: &[(u64, Start)], t_ms: u64) -> Posed {
        let section = DynamixelSection::of(&device.project);
        let mut pose: BTreeMap<u8, u32> =
            section.servos.iter().map(|servo| (servo.id, units(servo.model_number, 0.0))).collect();
        for (at_ms, start) in cues.iter().filter(|(at_ms, _)| *at_ms <= t_ms) {
            if let Some(motion) = motion(&section, start) {
                // Milliseconds of a show: exact in f64.
                #[allow(clippy::cast_precision_loss)]
                let into = (t_ms - at_ms) as f64;
                pose = motion.pose_at(&pose, into);
            }
        }
        let model = |id: u8| section.servo(id).map_or(0, |servo| servo.model_number);
        Posed::Servos(pose.into_iter().map(|(id, position)| (id, degrees(model(id), position))).collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::project::Easing;
    use crate::project::dynamixel::{ServoSetup, Step};
    use crate::show::family::FamilyCue;

    #[test]
    fn a_cue_plays_its_motion_from_where_the_cue_before_left_the_servos() {
        let section = DynamixelSection {
            servos: vec![ServoSetup { id: 1, name: "臂".into(), model_number: 1060, profile: None }],
            motions: vec![Motion {
                name: "lift".into(),
                steps: vec![Step { duration_ms: 1000, easing: Easing::Linear, positions: [(1, 3072)].into() }],
            }],
        };
        let mut project = Project::empty(Family::Dynamixel);
        project.sections.set(Family::Dynamixel, section.kept());
        let device = Device {
            name: "arm".into(),
            port: None,
            place: crate::show::Place::default(),
            project: project.clone(),
            play_on_without: false,
        };
        let cue = Start::Family(FamilyCue::named(super::super::MOTION, 1.0).unwrap());
        let mut lane = DynamixelLane;
        assert_eq!(lane.length_ms(&project, &cue), 1000);
        let cues = [(2000, cue)];
        assert_eq!(lane.posed_at(&device, &cues, 0), Posed::Servos([(1, 0.0)].into()), "at its centre before");
        assert_eq!(lane.posed_at(&device, &cues, 2500), Posed::Servos([(1, 45.0)].into()), "half way");
        assert_eq!(lane.posed_at(&device, &cues, 9000), Posed::Servos([(1, 90.0)].into()));
    }
}
