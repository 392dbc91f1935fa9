//! A servo board on the show's timeline: before its first cue its servos are
//! at home; from a cue on, where the macro the cue started has them, traced as
//! the board plays it (`project::trajectory`, at most an hour), each trace
//! worked out once while the show is unchanged.

use std::collections::{BTreeMap, HashMap};

use crate::project::{Family, Project, Run, ServoProject, Trajectories, angle_at, angle_at_sorted, times_sorted};
use crate::show::at::Posed;
use crate::show::timeline::{FamilyTimeline, Lane, latest, whole_ms};
use crate::show::{Device, Start};

/// The longest a servo macro is traced, ms: an hour.
const LONGEST_CUE_MS: f64 = 3_600_000.0;

inventory::submit! {
    FamilyTimeline { family: Family::Servo, lane: || Box::<ServoLane>::default() }
}

/// A macro's trace, when it ends, and whether its times never go back.
type Traced = (Trajectories, f64, bool);

/// One servo board's macros, traced as they are asked for.
#[derive(Debug, Default)]
struct ServoLane {
    /// Each macro's trace (none: it does not trace).
    traces: HashMap<i32, Option<Traced>>,
}

impl ServoLane {
    fn trace(&mut self, project: &Project, macro_id: i32) -> Option<&Traced> {
        let entry = self.traces.entry(macro_id).or_insert_with(|| {
            let (trajectories, end) =
                crate::project::trace(&project.servo, Run::Macro { macro_id }, LONGEST_CUE_MS).ok()?;
            let sorted = times_sorted(&trajectories);
            Some((trajectories, end, sorted))
        });
        entry.as_ref()
    }
}

impl Lane for ServoLane {
    fn length_ms(&mut self, project: &Project, start: &Start) -> u64 {
        let Start::Macro(macro_id) = *start else { return 0 };
        whole_ms(self.trace(project, macro_id).map_or(0.0, |(_, end, _)| *end))
    }

    fn posed_at(&mut self, device: &Device, cues: &[(u64, Start)], t_ms: u64) -> Posed {
        let servo = &device.project.servo;
        let mut angles = servo.servos.iter().map(|s| (s.id, f64::from(s.home_deg))).collect();
        if let Some((at_ms, Start::Macro(macro_id))) = latest(cues, t_ms)
            && let Some((trajectories, _, sorted)) = self.trace(&device.project, macro_id)
        {
            // Whole ms of a show: exact in f64.
            #[allow(clippy::cast_precision_loss)]
            let since = (t_ms - at_ms) as f64;
            angles = trace_pose(servo, (trajectories, *sorted), since);
        }
        Posed::Servos(angles)
    }
}

/// Every servo of `servo` where `trajectories` have it `since_ms` into them
/// (its home before they move it); `sorted`: their times never go back.
fn trace_pose(servo: &ServoProject, (trajectories, sorted): (&Trajectories, bool), since_ms: f64) -> BTreeMap<u8, f64> {
    let angle_at = if sorted { angle_at_sorted } else { angle_at };
    servo
        .servos
        .iter()
        .map(|s| {
            let angle = trajectories.get(&s.id).and_then(|points| angle_at(points, since_ms));
            (s.id, angle.unwrap_or(f64::from(s.home_deg)))
        })
        .collect()
}
