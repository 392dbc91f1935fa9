//! What an action or a macro does, as meant and as the board plays it: the
//! plot draws each servo as meant (a curve, point by point) and, where a
//! curve is baked into straight sub-steps for the board, what the board plays
//! beside it; the preview plays what the board plays. And what baking the
//! project's curves costs on the board (its steps and bytes).

use super::preview::Timed;
use crate::authoring::bake_servo::{self, BakedServo, DEFAULT_TOLERANCE_DEG};
use crate::device::servo::ServoImage;
use crate::project::{Follower, Run, ServoProject, Trajectories, action_trajectories, macro_trajectories};
use crate::ui::plot;

fn traced(project: &ServoProject, run: Run) -> (Trajectories, f64) {
    match run {
        Run::Macro { macro_id } => macro_trajectories(project, macro_id),
        Run::Action { action_id } => action_trajectories(project, action_id),
        Run::Delay { delay_ms } => (Trajectories::new(), f64::from(delay_ms.max(0))),
    }
}

/// The preview's timing and the plot's series for `run`: each servo as meant
/// ("id caption") and, where the board plays it otherwise, as the board does
/// ("id caption (`board`)"); those pairs first.
pub fn played(project: &ServoProject, run: Run, board: &str) -> (Timed, plot::Series) {
    let (meant, meant_end) = traced(project, run);
    let name = |servo_id: u8| {
        let caption = project.servo(servo_id).map_or("", |servo| servo.caption.as_str());
        format!("{servo_id} {caption}")
    };
    let points = |points: &[(f64, f64)]| points.iter().map(|&(t, angle)| [t, angle]).collect::<Vec<_>>();
    if !bake_servo::has_curves(project) {
        let series = meant.iter().map(|(&id, line)| (name(id), points(line))).collect();
        return (Timed::new(meant, meant_end), series);
    }
    let (stored, stored_run) = bake_servo::stored_run(project, run);
    let (plays, plays_end) = traced(&stored, stored_run);
    // A servo the board plays otherwise than meant: both lines, first (the plot shows the first few).
    let (mut pairs, mut single) = (plot::Series::new(), plot::Series::new());
    for (id, line) in &meant {
        let apart = plays.get(id).filter(|played| {
            // At every update (read in time order): a straight step split with a curve's pieces stays on its line.
            let (mut meant_at, mut played_at) = (Follower::new(line), Follower::new(played));
            (0..=crate::project::sample_count(plays_end.max(meant_end))).any(|k| {
                // Update counts are small.
                #[allow(clippy::cast_precision_loss)]
                let t = k as f64 * crate::project::SAMPLE_MS;
                // Before the board moves it, a servo holds where it starts.
                let held = played_at.at(t).or_else(|| line.first().map(|&(_, start)| start));
                meant_at.at(t).zip(held).is_none_or(|(a, b)| (a - b).abs() > 0.05)
            })
        });
        match apart {
            Some(played) => {
                pairs.push((name(*id), points(line)));
                pairs.push((format!("{} ({board})", name(*id)), points(played)));
            }
            None => single.push((name(*id), points(line))),
        }
    }
    pairs.extend(single);
    let series = pairs;
    (Timed::new(plays, plays_end), series)
}

/// What the project's curves cost on the board: every step it stores, those
/// added for curves, its bytes, and the bake (the tolerance widened when the
/// board's `total_bytes`, if known, are short). None without curves.
#[derive(Clone, Debug, PartialEq)]
pub struct Budget {
    /// The bake.
    pub baked: BakedServo,
    /// Bytes the board needs for the baked project (none: it cannot be encoded).
    pub bytes: Option<usize>,
    /// The board's memory, if known.
    pub total_bytes: Option<i64>,
}

impl Budget {
    /// The budget of `project` on a board of `total_bytes`.
    pub fn of(project: &ServoProject, total_bytes: Option<i64>) -> Option<Self> {
        if !bake_servo::has_curves(project) {
            return None;
        }
        let (image, baked) = ServoImage::within(project, total_bytes).ok()?;
        let bytes = image.footprint_bytes().ok();
        Some(Self { baked, bytes, total_bytes })
    }

    /// True when the tolerance had to be widened to fit the board.
    pub fn widened(&self) -> bool {
        self.baked.widened(DEFAULT_TOLERANCE_DEG)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::project::{Action, Command, Easing, Macro, Servo, Step};

    fn eased() -> ServoProject {
        let mut step = Step::new(1, 60, 80);
        step.easing = Easing::EaseOut;
        ServoProject {
            servos: vec![Servo::new(1, "arm"), Servo::new(2, "wrist")],
            actions: vec![Action { id: 3, caption: "reach".into(), steps: vec![step, Step::new(2, 10, 20)] }],
            macros: vec![Macro {
                id: 1,
                caption: "m".into(),
                commands: vec![Command::once(Run::Action { action_id: 3 })],
            }],
            ..ServoProject::default()
        }
    }

    #[test]
    fn a_curved_servo_is_plotted_as_meant_and_as_the_board_plays_it_a_straight_one_once() {
        let (_, series) = played(&eased(), Run::Action { action_id: 3 }, "board");
        let names: Vec<&str> = series.iter().map(|(name, _)| name.as_str()).collect();
        // The wrist's straight step, split with the arm's pieces into whole degrees, is drawn too when that shows.
        assert_eq!(names[..2], ["1 arm", "1 arm (board)"], "the curve and the board's line first");
        assert!(names.contains(&"2 wrist"));
        // Meant: a point per update; the board: a few straight pieces, never more than 1° away.
        assert_eq!(series[0].1.len(), 81);
        assert!(series[1].1.len() < 20, "{}", series[1].1.len());
        let mut straight = eased();
        straight.actions[0].steps[0].easing = Easing::Linear;
        let (_, series) = played(&straight, Run::Macro { macro_id: 1 }, "board");
        assert_eq!(series.len(), 2, "nothing baked, nothing drawn twice");
    }

    #[test]
    fn the_budget_widens_when_the_board_is_short_and_says_so() {
        let roomy = Budget::of(&eased(), None).expect("curves cost something");
        assert!(!roomy.widened() && roomy.baked.added_actions > 1);
        let bytes = roomy.bytes.unwrap();
        let short = Budget::of(&eased(), Some(i64::try_from(bytes).unwrap() - 1)).unwrap();
        assert!(short.widened(), "{short:?}");
        assert!(short.bytes.unwrap() < bytes);
        assert!(Budget::of(&ServoProject::default(), None).is_none());
    }
}
