//! Servo trajectories over time: what a macro or an action does to each servo,
//! as (time ms, angle) points joined by straight lines — the board moves each
//! servo linearly over its step's interval. A step with a curve is traced as
//! meant, a point per 10 ms update; what the board plays is the trace of the
//! project baked for it (`authoring::bake_servo`).

use std::collections::BTreeMap;

use super::servo::{Run, ServoIndex, ServoProject};

/// Points per servo: (time in ms, angle), in time order.
pub type Trajectories = BTreeMap<u8, Vec<(f64, f64)>>;

/// How much a trace may do (loop iterations and points together) before it
/// stops: a macro of nested 32767-fold loops would otherwise take years and
/// all memory. A real macro needs a few thousand.
pub const MAX_TRACE_WORK: u64 = 4_000_000;

/// Why a trajectory cannot be traced whole.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum TraceError {
    /// The macro reaches a macro that calls itself: it never ends.
    #[error("macro {} never ends: it runs itself again ({})", .0.first().copied().unwrap_or_default(), cycle_text(.0))]
    Cycle(Vec<i32>),
    /// Tracing it takes more than [`MAX_TRACE_WORK`] steps and loop turns.
    #[error(
        "it takes more than {MAX_TRACE_WORK} steps and loop turns to trace (loops inside loops): lower the loop counts of the macros it runs, or ask for fewer seconds"
    )]
    TooMuch,
}

fn cycle_text(path: &[i32]) -> String {
    let hops: Vec<String> = path.iter().map(|id| format!("macro {id}")).collect();
    hops.join(" → ")
}

struct Tracer<'a> {
    project: ServoIndex<'a>,
    angles: BTreeMap<u8, f64>,
    points: Trajectories,
    /// Nothing starting after this is traced, ms.
    until_ms: f64,
    /// The macros being run, outermost first (a macro on it is not entered again).
    running: Vec<i32>,
    work: u64,
}

impl Tracer<'_> {
    /// Counts `amount` of work; false once the budget is spent.
    fn spend(&mut self, amount: u64) -> bool {
        self.work = self.work.saturating_add(amount);
        self.work <= MAX_TRACE_WORK
    }

    fn run_action(&mut self, start_ms: f64, action_id: i32, speed: f64) -> f64 {
        let Some(action) = self.project.action(action_id) else { return start_ms };
        if !self.spend(2 * action.steps.len() as u64) {
            return start_ms;
        }
        let mut end_ms = start_ms;
        for step in &action.steps {
            let duration = f64::from(step.interval_10ms.max(0)) * 10.0 / speed;
            let from = self.angles.get(&step.servo_id).copied().unwrap_or(0.0);
            let to = f64::from(step.degree);
            let points = self.points.entry(step.servo_id).or_default();
            points.push((start_ms, from));
            if !step.easing.is_linear() && step.interval_10ms > 1 {
                // The curve meant, a point per board update (the board plays it baked into straight pieces).
                let updates = step.interval_10ms;
                self.work = self.work.saturating_add(updates.unsigned_abs().into());
                for k in 1..updates {
                    let along = f64::from(k) / f64::from(updates);
                    points.push((start_ms + duration * along, from + (to - from) * step.easing.at(along)));
                }
            }
            points.push((start_ms + duration, to));
            self.angles.insert(step.servo_id, to);
            end_ms = end_ms.max(start_ms + duration);
        }
        end_ms
    }

    fn run_macro(&mut self, start_ms: f64, macro_id: i32, speed: f64) -> f64 {
        let Some(item) = self.project.macro_by_id(macro_id) else { return start_ms };
        if self.running.contains(&macro_id) {
            // A cycle: the editor plots what comes before it; `trace` refuses it.
            return start_ms;
        }
        self.running.push(macro_id);
        let mut at = start_ms;
        'commands: for command in &item.commands {
            let command_speed = speed * f64::from(command.ratio_percent.max(1)) / 100.0;
            for _ in 0..command.loop_count.max(0) {
                if at > self.until_ms || !self.spend(1) {
                    break 'commands;
                }
                at = match command.run {
                    Run::Action { action_id } => self.run_action(at, action_id, command_speed),
                    Run::Delay { delay_ms } => at + f64::from(delay_ms.max(0)),
                    Run::Macro { macro_id } => self.run_macro(at, macro_id, command_speed),
                };
            }
        }
        self.running.pop();
        at
    }

    fn spent(&self) -> bool {
        self.work > MAX_TRACE_WORK
    }
}

fn tracer(project: &ServoProject, until_ms: f64) -> Tracer<'_> {
    let angles = project.servos.iter().map(|servo| (servo.id, f64::from(servo.home_deg))).collect();
    Tracer { project: project.index(), angles, points: Trajectories::new(), until_ms, running: Vec::new(), work: 0 }
}

/// The trajectories of one action, starting from each servo's home angle.
pub fn action_trajectories(project: &ServoProject, action_id: i32) -> (Trajectories, f64) {
    let mut tracer = tracer(project, f64::INFINITY);
    let end = tracer.run_action(0.0, action_id, 1.0);
    (tracer.points, end)
}

/// The trajectories of a whole macro, starting from each servo's home angle,
/// and when it ends (ms), for the editor's plot: a macro that calls itself is
/// plotted up to the call, one too long to trace up to where tracing stopped.
pub fn macro_trajectories(project: &ServoProject, macro_id: i32) -> (Trajectories, f64) {
    let mut tracer = tracer(project, f64::INFINITY);
    let end = tracer.run_macro(0.0, macro_id, 1.0);
    (tracer.points, end)
}

/// The first cycle reachable from `macro_id`, as the macros it passes,
/// starting and ending with the same one; `None` when the macro ends.
pub fn macro_cycle(project: &ServoProject, macro_id: i32) -> Option<Vec<i32>> {
    // Depth-first without recursion (a chain of 32767 macros must not overflow the stack).
    let project = project.index();
    let mut path: Vec<(i32, usize)> = vec![(macro_id, 0)];
    let mut done = std::collections::HashSet::new();
    while let Some((id, next)) = path.last().copied() {
        let calls = project.macro_by_id(id).map_or(&[][..], |item| &item.commands[..]);
        let Some(command) = calls.get(next) else {
            done.insert(id);
            path.pop();
            continue;
        };
        if let Some(top) = path.last_mut() {
            top.1 += 1;
        }
        let Run::Macro { macro_id: inner } = command.run else { continue };
        if command.loop_count <= 0 || done.contains(&inner) || project.macro_by_id(inner).is_none() {
            continue;
        }
        if let Some(from) = path.iter().position(|&(on_path, _)| on_path == inner) {
            let mut cycle: Vec<i32> = path[from..].iter().map(|&(id, _)| id).collect();
            cycle.push(inner);
            return Some(cycle);
        }
        path.push((inner, 0));
    }
    None
}

/// The trajectories of an action or a macro up to `until_ms` (what starts
/// later is not traced) and when it ends or stops being traced, ms; refuses
/// a macro that never ends and one too large to trace.
pub fn trace(project: &ServoProject, run: Run, until_ms: f64) -> Result<(Trajectories, f64), TraceError> {
    let mut tracer = tracer(project, until_ms);
    let end = match run {
        Run::Action { action_id } => tracer.run_action(0.0, action_id, 1.0),
        Run::Macro { macro_id } => {
            if let Some(cycle) = macro_cycle(project, macro_id) {
                return Err(TraceError::Cycle(cycle));
            }
            tracer.run_macro(0.0, macro_id, 1.0)
        }
        Run::Delay { delay_ms } => f64::from(delay_ms.max(0)),
    };
    if tracer.spent() {
        return Err(TraceError::TooMuch);
    }
    Ok((tracer.points, end))
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
    let mut rows = Vec::new();
    let mut samples = Samples::new(project, trajectories);
    for index in 0..sample_count(end_ms) {
        // Exact for the sample counts in use.
        #[allow(clippy::cast_precision_loss)]
        rows.push(samples.at(index as f64 * SAMPLE_MS).to_vec());
    }
    rows
}

/// How many samples [`sample`] takes from 0 to `end_ms` inclusive.
pub fn sample_count(end_ms: f64) -> usize {
    // Sample counts are bounded by the caller's end and non-negative.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let count = (end_ms.max(0.0) / SAMPLE_MS).ceil() as usize;
    count.saturating_add(1)
}

/// Every servo's angle at times that only grow, one row at a time, in time
/// proportional to the points passed (a trajectory file is written as it is
/// sampled, never held whole).
pub struct Samples<'a> {
    servos: Vec<(Option<Follower<'a>>, f64)>,
    row: Vec<f64>,
}

impl<'a> Samples<'a> {
    /// Samples `trajectories` for the servos of `project`, in order.
    pub fn new(project: &ServoProject, trajectories: &'a Trajectories) -> Self {
        let servos: Vec<_> = project
            .servos
            .iter()
            .map(|servo| (trajectories.get(&servo.id).map(|points| Follower::new(points)), f64::from(servo.home_deg)))
            .collect();
        let row = vec![0.0; servos.len()];
        Self { servos, row }
    }

    /// The angles at `time_ms` (not before the last time asked), as [`pose_at`] gives them.
    pub fn at(&mut self, time_ms: f64) -> &[f64] {
        for ((follower, home), angle) in self.servos.iter_mut().zip(&mut self.row) {
            *angle = follower.as_mut().and_then(|follower| follower.at(time_ms)).unwrap_or(*home);
        }
        &self.row
    }
}

/// One trajectory read at times that only grow, each angle exactly as
/// [`angle_at`] gives it.
pub struct Follower<'a> {
    points: &'a [(f64, f64)],
    /// Segments before this one ended (both ends) at or before the last time asked.
    next: usize,
    /// The angle they leave.
    held: f64,
    /// From this point on, times never decrease (so nothing later can matter once a segment starts after the time asked).
    sorted_from: usize,
}

impl<'a> Follower<'a> {
    /// Follows `points`.
    pub fn new(points: &'a [(f64, f64)]) -> Self {
        let mut sorted_from = points.len().saturating_sub(1);
        while sorted_from > 0 && points[sorted_from - 1].0 <= points[sorted_from].0 {
            sorted_from -= 1;
        }
        Self { points, next: 0, held: points.first().map_or(0.0, |point| point.1), sorted_from }
    }

    /// The angle at `time_ms`; `None` before the first point.
    pub fn at(&mut self, time_ms: f64) -> Option<f64> {
        let first = self.points.first()?;
        if time_ms < first.0 {
            return None;
        }
        let points = self.points;
        while self.next + 1 < points.len() && points[self.next].0 <= time_ms && points[self.next + 1].0 <= time_ms {
            self.held = points[self.next + 1].1;
            self.next += 1;
        }
        let mut angle = self.held;
        for (index, pair) in points[self.next..].windows(2).enumerate() {
            let ((t0, _), (t1, a1)) = (pair[0], pair[1]);
            if time_ms >= t1 {
                angle = a1;
            } else if time_ms >= t0 {
                angle = along(pair[0], pair[1], time_ms);
                break;
            } else if self.next + index >= self.sorted_from {
                // Every later segment starts later still.
                break;
            }
        }
        Some(angle)
    }
}

/// The angle at `time_ms` on a trajectory: linear between points, held after
/// the last one; `None` before the first point.
pub fn angle_at(points: &[(f64, f64)], time_ms: f64) -> Option<f64> {
    Follower::new(points).at(time_ms)
}

/// [`angle_at`] for points whose times never go back (a trace's usual
/// shape: check once with [`times_sorted`]), found by halving: as fast an
/// hour in as at the start.
pub fn angle_at_sorted(points: &[(f64, f64)], time_ms: f64) -> Option<f64> {
    let first = points.first()?;
    if time_ms < first.0 {
        return None;
    }
    // The first point later than the time asked: the move from the one before it is under way.
    let next = points.partition_point(|point| point.0 <= time_ms);
    Some(match points.get(next) {
        Some(&later) => along(points[next - 1], later, time_ms),
        None => points[points.len() - 1].1,
    })
}

/// Whether every trajectory's times never go back (so [`angle_at_sorted`] reads them).
pub fn times_sorted(trajectories: &Trajectories) -> bool {
    trajectories.values().all(|points| points.is_sorted_by(|a, b| a.0 <= b.0))
}

/// The angle at `time_ms` on the straight move from `(t0, a0)` to `(t1, a1)`
/// (a move that takes no time is already there).
fn along((t0, a0): (f64, f64), (t1, a1): (f64, f64), time_ms: f64) -> f64 {
    if t1 > t0 { a0 + (a1 - a0) * (time_ms - t0) / (t1 - t0) } else { a1 }
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
                Action { id: 1, caption: String::new(), steps: vec![Step::new(1, 90, 100)] },
                Action { id: 2, caption: String::new(), steps: vec![Step::new(1, -90, 50)] },
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
        assert_eq!(trace(&project(), Run::Macro { macro_id: 6 }, 1e9), Err(TraceError::Cycle(vec![6, 6])));
    }

    #[test]
    fn a_cycle_through_two_macros_is_named_from_where_it_is_reached() {
        let mut project = project();
        project.macros.push(Macro {
            id: 7,
            caption: String::new(),
            commands: vec![Command::once(Run::Macro { macro_id: 8 })],
        });
        project.macros.push(Macro {
            id: 8,
            caption: String::new(),
            commands: vec![Command::once(Run::Macro { macro_id: 9 })],
        });
        project.macros.push(Macro {
            id: 9,
            caption: String::new(),
            commands: vec![Command::once(Run::Macro { macro_id: 8 })],
        });
        assert_eq!(macro_cycle(&project, 7), Some(vec![8, 9, 8]));
        let error = trace(&project, Run::Macro { macro_id: 7 }, 1e9).unwrap_err();
        assert_eq!(error.to_string(), "macro 8 never ends: it runs itself again (macro 8 → macro 9 → macro 8)");
        assert_eq!(macro_cycle(&project, 5), None);
    }

    #[test]
    fn a_long_chain_of_macros_is_followed_without_recursion_limits() {
        let mut project = project();
        let chain = 30_000;
        for id in 100..100 + chain {
            project.macros.push(Macro {
                id,
                caption: String::new(),
                commands: vec![Command::once(Run::Macro { macro_id: id + 1 })],
            });
        }
        assert_eq!(macro_cycle(&project, 100), None);
        project.macros.last_mut().unwrap().commands = vec![Command::once(Run::Macro { macro_id: 100 })];
        assert_eq!(macro_cycle(&project, 100).map(|cycle| cycle.len()), Some(usize::try_from(chain).unwrap() + 1));
    }

    #[test]
    fn loops_inside_loops_stop_at_the_work_budget_or_the_time_asked() {
        let mut project = project();
        let looped = |run| Command { run, ratio_percent: 100, loop_count: 32_767, stored_total_ms: None };
        project.macros.push(Macro {
            id: 20,
            caption: String::new(),
            commands: vec![looped(Run::Delay { delay_ms: 0 })],
        });
        project.macros.push(Macro {
            id: 21,
            caption: String::new(),
            commands: vec![looped(Run::Macro { macro_id: 20 })],
        });
        project.macros.push(Macro {
            id: 22,
            caption: String::new(),
            commands: vec![looped(Run::Macro { macro_id: 21 })],
        });
        assert_eq!(trace(&project, Run::Macro { macro_id: 22 }, 1e9), Err(TraceError::TooMuch));
        // Time that runs: stops at the time asked for.
        project.macros.push(Macro {
            id: 23,
            caption: String::new(),
            commands: vec![looped(Run::Action { action_id: 1 })],
        });
        let (points, end) = trace(&project, Run::Macro { macro_id: 23 }, 5_000.0).unwrap();
        assert!(end > 5_000.0 && end <= 7_000.0, "{end}");
        assert!(points[&1].len() <= 14);
    }

    /// The plain reading of a trajectory the follower must agree with: every
    /// segment in order, the last one reached wins, a segment under way interpolates.
    fn reference_angle_at(points: &[(f64, f64)], time_ms: f64) -> Option<f64> {
        let first = points.first()?;
        if time_ms < first.0 {
            return None;
        }
        let mut angle = first.1;
        for pair in points.windows(2) {
            let ((t0, _), (t1, a1)) = (pair[0], pair[1]);
            if time_ms >= t1 {
                angle = a1;
            } else if time_ms >= t0 {
                angle = along(pair[0], pair[1], time_ms);
                break;
            }
        }
        Some(angle)
    }

    #[test]
    fn a_follower_agrees_with_angle_at_on_any_points() {
        // Times in and out of order (an action moving one servo twice), ties, and a point at the end.
        let sets: [&[(f64, f64)]; 4] = [
            &[(0.0, 10.0), (1000.0, 90.0), (1200.0, 90.0), (2200.0, -90.0)],
            &[(0.0, 0.0), (500.0, 30.0), (0.0, 30.0), (300.0, -20.0), (300.0, 5.0), (900.0, 45.0)],
            &[(100.0, 1.0), (100.0, 2.0), (100.0, 3.0)],
            &[(50.0, 7.0)],
        ];
        for points in sets {
            let mut follower = Follower::new(points);
            for step in 0..=300 {
                let time = f64::from(step) * 10.0 - 100.0;
                assert_eq!(follower.at(time), reference_angle_at(points, time), "{points:?} at {time}");
            }
        }
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
