//! Servo trajectories over time: what a macro or an action does to each servo,
//! as (time ms, angle) points joined by straight lines — the board moves each
//! servo linearly over its step's interval.

use std::collections::BTreeMap;

use super::servo::{Run, ServoProject};

/// Points per servo: (time in ms, angle), in time order.
pub type Trajectories = BTreeMap<u8, Vec<(f64, f64)>>;

/// How deep nested macros are followed (a cycle stops here instead of looping).
const MAX_DEPTH: u8 = 8;

struct Tracer<'a> {
    project: &'a ServoProject,
    angles: BTreeMap<u8, f64>,
    points: Trajectories,
}

impl Tracer<'_> {
    fn run_action(&mut self, start_ms: f64, action_id: i32, speed: f64) -> f64 {
        let Some(action) = self.project.action(action_id) else { return start_ms };
        let mut end_ms = start_ms;
        for step in &action.steps {
            let duration = f64::from(step.interval_10ms.max(0)) * 10.0 / speed;
            let from = self.angles.get(&step.servo_id).copied().unwrap_or(0.0);
            let to = f64::from(step.degree);
            let points = self.points.entry(step.servo_id).or_default();
            points.push((start_ms, from));
            points.push((start_ms + duration, to));
            self.angles.insert(step.servo_id, to);
            end_ms = end_ms.max(start_ms + duration);
        }
        end_ms
    }

    fn run_macro(&mut self, start_ms: f64, macro_id: i32, speed: f64, depth: u8) -> f64 {
        let Some(item) = self.project.macro_by_id(macro_id) else { return start_ms };
        if depth > MAX_DEPTH {
            return start_ms;
        }
        let mut at = start_ms;
        for command in &item.commands {
            let command_speed = speed * f64::from(command.ratio_percent.max(1)) / 100.0;
            for _ in 0..command.loop_count.max(0) {
                at = match command.run {
                    Run::Action { action_id } => self.run_action(at, action_id, command_speed),
                    Run::Delay { delay_ms } => at + f64::from(delay_ms.max(0)),
                    Run::Macro { macro_id } => self.run_macro(at, macro_id, command_speed, depth + 1),
                };
            }
        }
        at
    }
}

fn tracer(project: &ServoProject) -> Tracer<'_> {
    let angles = project.servos.iter().map(|servo| (servo.id, f64::from(servo.home_deg))).collect();
    Tracer { project, angles, points: Trajectories::new() }
}

/// The trajectories of one action, starting from each servo's home angle.
pub fn action_trajectories(project: &ServoProject, action_id: i32) -> (Trajectories, f64) {
    let mut tracer = tracer(project);
    let end = tracer.run_action(0.0, action_id, 1.0);
    (tracer.points, end)
}

/// The trajectories of a whole macro, starting from each servo's home angle,
/// and when it ends (ms).
pub fn macro_trajectories(project: &ServoProject, macro_id: i32) -> (Trajectories, f64) {
    let mut tracer = tracer(project);
    let end = tracer.run_macro(0.0, macro_id, 1.0, 0);
    (tracer.points, end)
}

/// How often the board's servos are sampled for a preview or a trajectory
/// file, ms (intervals are counted in 10 ms).
pub const SAMPLE_MS: f64 = 10.0;

/// Every servo's angle at `time_ms` (a servo not moved yet holds its home), the project's servos in order.
pub fn pose_at(project: &ServoProject, trajectories: &Trajectories, time_ms: f64) -> Vec<f64> {
    project
        .servos
        .iter()
        .map(|servo| {
            trajectories
                .get(&servo.id)
                .and_then(|points| angle_at(points, time_ms))
                .unwrap_or(f64::from(servo.home_deg))
        })
        .collect()
}

/// Every servo's angle every [`SAMPLE_MS`] from 0 to `end_ms` (inclusive): a
/// servo not moved yet holds its home. Rows of the project's servos, in order.
pub fn sample(project: &ServoProject, trajectories: &Trajectories, end_ms: f64) -> Vec<Vec<f64>> {
    // Sample counts are small and non-negative.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let samples = (end_ms.max(0.0) / SAMPLE_MS).ceil() as usize + 1;
    // Exact for the sample counts in use.
    #[allow(clippy::cast_precision_loss)]
    (0..samples).map(|index| pose_at(project, trajectories, index as f64 * SAMPLE_MS)).collect()
}

/// The angle at `time_ms` on a trajectory: linear between points, held after
/// the last one; `None` before the first point.
pub fn angle_at(points: &[(f64, f64)], time_ms: f64) -> Option<f64> {
    let first = points.first()?;
    if time_ms < first.0 {
        return None;
    }
    let mut angle = first.1;
    for pair in points.windows(2) {
        let ((t0, a0), (t1, a1)) = (pair[0], pair[1]);
        if time_ms >= t1 {
            angle = a1;
        } else if time_ms >= t0 {
            angle = if t1 > t0 { a0 + (a1 - a0) * (time_ms - t0) / (t1 - t0) } else { a1 };
            break;
        }
    }
    Some(angle)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::project::{Action, Command, Macro, Servo, Step, Timing};

    fn project() -> ServoProject {
        let mut servo = Servo::new(1, "a");
        servo.home_deg = 10;
        ServoProject {
            servos: vec![servo],
            actions: vec![
                Action {
                    id: 1,
                    caption: String::new(),
                    steps: vec![Step { servo_id: 1, degree: 90, interval_10ms: 100 }],
                },
                Action {
                    id: 2,
                    caption: String::new(),
                    steps: vec![Step { servo_id: 1, degree: -90, interval_10ms: 50 }],
                },
            ],
            macros: vec![
                Macro {
                    id: 5,
                    caption: String::new(),
                    commands: vec![
                        Command::once(Run::Action { action_id: 1 }),
                        Command::once(Run::Delay { delay_ms: 200 }),
                        Command {
                            run: Run::Action { action_id: 2 },
                            ratio_percent: 50,
                            loop_count: 1,
                            stored_total_ms: None,
                        },
                    ],
                },
                Macro { id: 6, caption: String::new(), commands: vec![Command::once(Run::Macro { macro_id: 6 })] },
            ],
            ..ServoProject::default()
        }
    }

    #[test]
    fn a_macro_traces_each_servo_from_home_and_ends_when_timing_says() {
        let project = project();
        let (points, end) = macro_trajectories(&project, 5);
        assert_eq!(points[&1], [(0.0, 10.0), (1000.0, 90.0), (1200.0, 90.0), (2200.0, -90.0)]);
        // The plot agrees with the derived totals.
        assert_eq!(end, Timing::new(&project).macro_total_ms(5).unwrap() as f64);
    }

    #[test]
    fn a_cyclic_macro_stops_instead_of_looping_forever() {
        let (points, end) = macro_trajectories(&project(), 6);
        assert!(points.is_empty());
        assert_eq!(end, 0.0);
    }

    #[test]
    fn angles_are_interpolated_and_held() {
        let points = [(0.0, 10.0), (1000.0, 90.0), (1200.0, 90.0), (2200.0, -90.0)];
        assert_eq!(angle_at(&points, -1.0), None);
        assert_eq!(angle_at(&points, 500.0), Some(50.0));
        assert_eq!(angle_at(&points, 1100.0), Some(90.0));
        assert_eq!(angle_at(&points, 1700.0), Some(0.0));
        assert_eq!(angle_at(&points, 9999.0), Some(-90.0));
    }

    #[test]
    fn an_action_alone() {
        let (points, end) = action_trajectories(&project(), 2);
        assert_eq!(points[&1], [(0.0, 10.0), (500.0, -90.0)]);
        assert_eq!(end, 500.0);
    }
}
