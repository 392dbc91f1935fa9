//! Servo actions and macros on the graph pane. An action: a channel per
//! step, its servo from home (as the action alone plays) to the step's key at
//! its interval (10 ms updates), within the servo's limits, with what the
//! board plays when a curve is baked. A macro: each servo as its commands
//! move it, drawn (its keys are its actions' steps, edited in the action).

use crate::project::{Action, ServoProject};
use crate::ui::graph::{Channel, GraphEdit, Key};
use crate::ui::plot;

/// The board's update, ms.
pub const UPDATE_MS: f64 = 10.0;

/// A servo's name on the graph, as the plot series call it.
fn name(project: &ServoProject, servo_id: u8) -> String {
    let caption = project.servo(servo_id).map_or("", |servo| servo.caption.as_str());
    format!("{servo_id} {caption}")
}

/// The line the series hold for `name` as the board plays it, if it differs.
fn board_line(series: &plot::Series, name: &str, board: &str) -> Option<Vec<[f64; 2]>> {
    let wanted = format!("{name} ({board})");
    series.iter().find(|(series_name, _)| *series_name == wanted).map(|(_, points)| points.clone())
}

/// The action's steps as the graph draws them; `series` are its plot's
/// (meant and, where baked, as the board plays it under "(`board`)").
pub fn action_curves(project: &ServoProject, action: &Action, series: &plot::Series, board: &str) -> Vec<Channel> {
    action
        .steps
        .iter()
        .map(|step| {
            let servo = project.servo(step.servo_id);
            let name = name(project, step.servo_id);
            let home = servo.map_or(0.0, |servo| f64::from(servo.home_deg));
            let limits = servo.map_or([-90.0, 90.0], |servo| [f64::from(servo.min_deg), f64::from(servo.max_deg)]);
            Channel {
                baked: board_line(series, &name, board),
                name,
                start: [0.0, home],
                keys: vec![Key {
                    t_ms: f64::from(step.interval_10ms.max(0)) * UPDATE_MS,
                    value: f64::from(step.degree),
                    easing: step.easing,
                }],
                limits,
            }
        })
        .collect()
}

/// A macro's servos as the graph draws them (no keys: each line is its
/// points), what the board plays beside them where it differs.
pub fn played_curves(series: &plot::Series, board: &str) -> Vec<Channel> {
    let suffix = format!(" ({board})");
    series
        .iter()
        .filter(|(name, _)| !name.ends_with(&suffix))
        .map(|(name, points)| Channel {
            name: name.clone(),
            start: points.first().copied().unwrap_or_default(),
            keys: points
                .iter()
                .skip(1)
                .map(|&[t_ms, value]| Key { t_ms, value, easing: crate::project::Easing::Linear })
                .collect(),
            limits: [f64::MIN, f64::MAX],
            baked: board_line(series, name, board),
        })
        .collect()
}

/// `action` with the graph's edit applied: a key moved in time changes its
/// step's interval (whole 10 ms updates, at least one), in value its angle
/// (within the servo's limits); a shaped move is its step's curve.
pub fn apply(project: &ServoProject, action: &Action, edit: &GraphEdit) -> Action {
    let mut changed = action.clone();
    match edit {
        GraphEdit::Shape { keys, easing } => {
            for &(c, _) in keys {
                if let Some(step) = changed.steps.get_mut(c) {
                    step.easing = *easing;
                }
            }
        }
        GraphEdit::Move { keys, dt_ms, dv_deg } => {
            // Whole updates and degrees, clamped to an i16's range below.
            #[allow(clippy::cast_possible_truncation)]
            let (updates, degrees) = ((dt_ms / UPDATE_MS).round() as i32, dv_deg.round() as i32);
            for &(c, _) in keys {
                let Some(step) = changed.steps.get_mut(c) else { continue };
                let interval = (i32::from(step.interval_10ms) + updates).clamp(1, i32::from(i16::MAX));
                step.interval_10ms = i16::try_from(interval).unwrap_or(i16::MAX);
                let (low, high) =
                    project.servo(step.servo_id).map_or((-90, 90), |servo| (servo.min_deg, servo.max_deg));
                let degree = (i32::from(step.degree) + degrees).clamp(i32::from(low), i32::from(high));
                step.degree = i16::try_from(degree).unwrap_or(step.degree);
            }
        }
    }
    changed
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::project::{Easing, Handles, Step};

    fn project() -> ServoProject {
        let mut servo = crate::project::Servo::new(1, "arm");
        servo.home_deg = 10;
        ServoProject {
            servos: vec![servo],
            actions: vec![Action { id: 7, caption: "wave".into(), steps: vec![Step::new(1, 30, 50)] }],
            ..ServoProject::default()
        }
    }

    #[test]
    fn a_steps_key_moves_its_interval_by_whole_updates_and_its_angle_within_the_limits() {
        let project = project();
        let servo = project.servo(1).unwrap();
        let edit = GraphEdit::Move { keys: vec![(0, 0)], dt_ms: 123.0, dv_deg: 1000.0 };
        let moved = apply(&project, &project.actions[0], &edit);
        assert_eq!(moved.steps[0].interval_10ms, 62);
        assert_eq!(moved.steps[0].degree, servo.max_deg);
        let back = GraphEdit::Move { keys: vec![(0, 0)], dt_ms: -10_000.0, dv_deg: 0.0 };
        assert_eq!(apply(&project, &project.actions[0], &back).steps[0].interval_10ms, 1, "at least one update");
        let channels = action_curves(&project, &project.actions[0], &Vec::new(), "board");
        assert_eq!(channels[0].keys[0].t_ms, 500.0);
        assert_eq!(channels[0].start, [0.0, f64::from(servo.home_deg)]);
    }

    #[test]
    fn a_shaped_move_is_its_steps_curve() {
        let project = project();
        let shaped = Easing::Shaped(Handles::new([0, 500], [500, 1000]));
        let edit = GraphEdit::Shape { keys: vec![(0, 0)], easing: shaped };
        assert_eq!(apply(&project, &project.actions[0], &edit).steps[0].easing, shaped);
    }
}
