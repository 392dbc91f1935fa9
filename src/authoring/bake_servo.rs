//! Eased servo-board steps baked into the straight steps the board plays. The
//! board moves each servo of an action linearly over its step's interval, in
//! 10 ms updates; an action with a curved step becomes a run of sub-actions
//! (every servo of the action in each, all of one sub-action's steps lasting
//! as long) that keeps the board's output within the tolerance of the curve
//! at every update, and a macro running them. A macro command that runs such
//! an action runs that macro instead, at the same speed; a command that runs
//! it more than once runs the action itself for the other turns (the servos
//! are at its angles then: it moves nothing, only takes its time, as before).
//!
//! Where a curve starts: the board moves a servo from wherever it is, so a
//! curve is baked for where its macro has put the servo, counting from every
//! servo at home when the macro starts (as the macro's plot and `trajectory`
//! count). The same action reached from different angles is baked once per
//! start. When the baked project would not fit the board's memory, the
//! tolerance is widened (in tenths of a degree) until it does.

use std::collections::{BTreeMap, HashMap};

use super::fit::{self, Board, ServoBoard};
use super::fitted;
use crate::project::{Action, Command, Run, ServoProject};

/// The tolerance a curve is baked to unless the board's memory is short, °.
pub const DEFAULT_TOLERANCE_DEG: f64 = 1.0;

/// A project as the board will store it, and what baking cost.
#[derive(Clone, Debug, PartialEq)]
pub struct BakedServo {
    /// Only straight steps: the sub-actions and the macros running them added.
    pub project: ServoProject,
    /// The tolerance used, ° (above the one asked when the memory was short).
    pub tolerance_deg: f64,
    /// The largest distance between a curve and the board's output at any update, °.
    pub max_error_deg: f64,
    /// Sub-actions added.
    pub added_actions: usize,
    /// Macros added.
    pub added_macros: usize,
}

impl BakedServo {
    /// True when the tolerance had to be widened to fit the board.
    pub fn widened(&self, asked_deg: f64) -> bool {
        self.tolerance_deg > asked_deg
    }

    /// Every step the board stores.
    pub fn steps(&self) -> usize {
        self.project.actions.iter().map(|action| action.steps.len()).sum()
    }
}

/// True when the action has a step with a curve that takes more than one update.
pub fn is_curved(action: &Action) -> bool {
    action.steps.iter().any(|step| !step.easing.is_linear() && step.interval_10ms > 1)
}

/// True when any action of the project has a curve.
pub fn has_curves(project: &ServoProject) -> bool {
    project.actions.iter().any(is_curved)
}

/// What every servo of `action` should be at each 10 ms update, starting
/// `from` (°, by servo; a servo not there from 0): a curved step along its
/// curve, a straight one as the board moves it, each holding once done.
pub fn action_rows(action: &Action, from: &BTreeMap<u8, f64>) -> (Vec<i32>, Vec<Vec<f64>>) {
    let start: Vec<i32> =
        action.steps.iter().map(|step| ServoBoard.store(from.get(&step.servo_id).copied().unwrap_or(0.0))).collect();
    let updates = action.steps.iter().map(|step| usize::from(step.interval_10ms.max(0).unsigned_abs())).max();
    let rows = (1..=updates.unwrap_or(0))
        .map(|k| {
            action
                .steps
                .iter()
                .zip(&start)
                .map(|(step, &begin)| {
                    let n = usize::from(step.interval_10ms.max(0).unsigned_abs());
                    let to = i32::from(step.degree);
                    if k >= n {
                        f64::from(to)
                    } else if step.easing.is_linear() {
                        ServoBoard.output(begin, to, n, k)
                    } else {
                        // Update counts are at most 32767: exact.
                        #[allow(clippy::cast_precision_loss)]
                        let along = step.easing.at(k as f64 / n as f64);
                        f64::from(begin) + f64::from(to - begin) * along
                    }
                })
                .collect()
        })
        .collect();
    (start, rows)
}

/// `action` played from `from`, baked into straight sub-actions with ids from
/// `first_id` (for the caller to replace when it stores them), and the largest deviation from its curves, °.
pub fn bake_action(action: &Action, from: &BTreeMap<u8, f64>, tolerance: f64, first_id: i32) -> (Vec<Action>, f64) {
    let (start, rows) = action_rows(action, from);
    let fitted = fit::fit_on_samples(&ServoBoard, &start, &rows, tolerance);
    let ids: Vec<u8> = action.steps.iter().map(|step| step.servo_id).collect();
    let mut subs = fitted::servo_actions(&fitted, &ids, first_id, &format!("{} ~", action.caption));
    // A servo that stays where the last sub-action left it needs no step (every move of a
    // sub-action ends with it, so none is under way): the board leaves it be. A sub-action
    // where nothing moves keeps one step, for its time.
    let mut at = start;
    for sub in &mut subs {
        let before = at.clone();
        for (place, step) in at.iter_mut().zip(&sub.steps) {
            *place = i32::from(step.degree);
        }
        let keep: Vec<bool> = sub.steps.iter().zip(&before).map(|(step, &was)| i32::from(step.degree) != was).collect();
        if keep.iter().any(|&moves| moves) {
            let mut flags = keep.into_iter();
            sub.steps.retain(|_| flags.next().unwrap_or(true));
        } else {
            sub.steps.truncate(1);
        }
    }
    (subs, fitted.max_error)
}

/// Ids not used yet: above the highest in use, then from 1 again (a project
/// using ids up to 2147483647 still gets fresh ones, never a taken one).
struct FreshIds {
    used: std::collections::BTreeSet<i32>,
    next: i32,
}

impl FreshIds {
    fn new(used: impl IntoIterator<Item = i32>) -> Self {
        let used: std::collections::BTreeSet<i32> = used.into_iter().filter(|id| *id > 0).collect();
        let next = used.last().map_or(1, |highest| highest.checked_add(1).unwrap_or(1));
        Self { used, next }
    }

    fn take(&mut self) -> i32 {
        loop {
            let id = self.next;
            self.next = id.checked_add(1).unwrap_or(1);
            if self.used.insert(id) {
                return id;
            }
        }
    }

    /// `subs` given fresh ids, and a macro (fresh id) running them.
    fn wrap(&mut self, caption: &str, mut subs: Vec<Action>) -> (crate::project::Macro, Vec<Action>) {
        for sub in &mut subs {
            sub.id = self.take();
        }
        (fitted::macro_running(0, caption, &subs), subs)
    }
}

/// `project` baked at `tolerance` (°), widened until `fits` holds for it (in
/// tenths of a degree, up to the widest, a straight line per step).
pub fn bake_servo(project: &ServoProject, tolerance: f64, fits: impl Fn(&ServoProject) -> bool) -> BakedServo {
    let baked = bake_at(project, tolerance);
    if !has_curves(project) || fits(&baked.project) {
        return baked;
    }
    // A wider tolerance never takes more steps.
    let (mut low, mut high) = (0u32, 3600u32);
    let at = |tenths: u32| bake_at(project, tolerance + f64::from(tenths) / 10.0);
    let mut best = at(high);
    if !fits(&best.project) {
        return best;
    }
    while high - low > 1 {
        let middle = low + (high - low) / 2;
        let tried = at(middle);
        if fits(&tried.project) {
            high = middle;
            best = tried;
        } else {
            low = middle;
        }
    }
    best
}

/// What the board plays for `run` (an action alone starts with every servo
/// at home, as its plot does): the project as stored, and what to run in it
/// (a curved action alone: the macro running its sub-actions).
pub fn stored_run(project: &ServoProject, run: Run) -> (ServoProject, Run) {
    let mut stored = bake_servo(project, DEFAULT_TOLERANCE_DEG, |_| true).project;
    let curved = match run {
        Run::Action { action_id } => project.action(action_id).filter(|action| is_curved(action)),
        _ => None,
    };
    let Some(action) = curved else { return (stored, run) };
    let homes: BTreeMap<u8, f64> = project.servos.iter().map(|servo| (servo.id, f64::from(servo.home_deg))).collect();
    let (subs, _) = bake_action(action, &homes, DEFAULT_TOLERANCE_DEG, 1);
    let (mut wrapper, subs) = FreshIds::new(stored.actions.iter().map(|a| a.id)).wrap(&action.caption, subs);
    wrapper.id = FreshIds::new(stored.macros.iter().map(|m| m.id)).take();
    let macro_id = wrapper.id;
    stored.macros.push(wrapper);
    stored.actions.extend(subs);
    (stored, Run::Macro { macro_id })
}

/// Every servo's angle once `command` has run from `angles` (a macro already
/// being run, a loop on the way, is not entered again; every turn of a loop
/// ends where the first did).
fn run_through(project: &ServoProject, command: &Command, angles: &mut BTreeMap<u8, f64>, running: &mut Vec<i32>) {
    if command.loop_count <= 0 {
        return;
    }
    match command.run {
        Run::Action { action_id } => {
            for step in project.action(action_id).map_or(&[][..], |action| &action.steps[..]) {
                angles.insert(step.servo_id, f64::from(step.degree));
            }
        }
        Run::Macro { macro_id } => {
            let Some(item) = project.macro_by_id(macro_id).filter(|_| !running.contains(&macro_id)) else { return };
            running.push(macro_id);
            for inner in &item.commands {
                run_through(project, inner, angles, running);
            }
            running.pop();
        }
        Run::Delay { .. } => {}
    }
}

fn bake_at(project: &ServoProject, tolerance: f64) -> BakedServo {
    let mut out = project.clone();
    if !has_curves(project) {
        return BakedServo {
            project: out,
            tolerance_deg: tolerance,
            max_error_deg: 0.0,
            added_actions: 0,
            added_macros: 0,
        };
    }
    let mut action_ids = FreshIds::new(project.actions.iter().map(|action| action.id));
    let mut macro_ids = FreshIds::new(project.macros.iter().map(|item| item.id));
    let homes: BTreeMap<u8, f64> = project.servos.iter().map(|servo| (servo.id, f64::from(servo.home_deg))).collect();
    // (action, where its servos start) → the macro running its sub-actions.
    let mut baked: HashMap<(i32, Vec<i32>), i32> = HashMap::new();
    let (mut max_error, mut added_actions) = (0.0_f64, 0);
    for (index, item) in project.macros.iter().enumerate() {
        let mut angles = homes.clone();
        let mut commands = Vec::with_capacity(item.commands.len());
        for command in &item.commands {
            let curved = match command.run {
                Run::Action { action_id } => project.action(action_id).filter(|action| is_curved(action)),
                _ => None,
            };
            match curved {
                Some(action) if command.loop_count > 0 => {
                    let start: Vec<i32> = action_rows(action, &angles).0;
                    let wrapper = *baked.entry((action.id, start)).or_insert_with(|| {
                        let (subs, error) = bake_action(action, &angles, tolerance, 1);
                        max_error = max_error.max(error);
                        added_actions += subs.len();
                        let (mut wrapper, subs) = action_ids.wrap(&format!("{} ~", action.caption), subs);
                        wrapper.id = macro_ids.take();
                        let id = wrapper.id;
                        out.macros.push(wrapper);
                        out.actions.extend(subs);
                        id
                    });
                    let speed = |run, loop_count| Command { run, loop_count, stored_total_ms: None, ..*command };
                    commands.push(speed(Run::Macro { macro_id: wrapper }, 1));
                    if command.loop_count > 1 {
                        commands.push(speed(command.run, command.loop_count - 1));
                    }
                }
                _ => commands.push(*command),
            }
            run_through(project, command, &mut angles, &mut vec![item.id]);
        }
        out.macros[index].commands = commands;
    }
    // The board stores no curves: the authored actions stay, straight (a loop's later turns run them).
    for step in out.actions.iter_mut().flat_map(|action| action.steps.iter_mut()) {
        step.easing = crate::project::Easing::Linear;
    }
    let added_macros = out.macros.len() - project.macros.len();
    BakedServo { project: out, tolerance_deg: tolerance, max_error_deg: max_error, added_actions, added_macros }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::project::{self, Easing, Macro, Servo, Step};

    /// Servo 1 eased from 0 to 90° over a second, servo 2 straight to -30° in half of it, run by macro 1.
    fn project(easing: Easing, command: Command) -> ServoProject {
        let mut curved = Step::new(1, 90, 100);
        curved.easing = easing;
        ServoProject {
            servos: vec![Servo::new(1, "arm"), Servo::new(2, "wrist")],
            actions: vec![Action { id: 4, caption: "Wave 揮手".into(), steps: vec![curved, Step::new(2, -30, 50)] }],
            macros: vec![Macro { id: 1, caption: "show".into(), commands: vec![command] }],
            ..ServoProject::default()
        }
    }

    fn run_wave(ratio_percent: u8, loop_count: i16) -> Command {
        Command { ratio_percent, loop_count, ..Command::once(Run::Action { action_id: 4 }) }
    }

    /// The largest distance, at every 10 ms update, between what `meant` and
    /// `stored` do to each servo running macro 1, and their ends (ms).
    fn deviation(meant: &ServoProject, stored: &ServoProject) -> (f64, f64, f64) {
        let run = Run::Macro { macro_id: 1 };
        let (want, want_end) = project::trace(meant, run, f64::INFINITY).unwrap();
        let (got, got_end) = project::trace(stored, run, f64::INFINITY).unwrap();
        let mut worst = 0.0_f64;
        for (servo, points) in &want {
            let mut t = 0.0;
            while t <= want_end.max(got_end) {
                let a = project::angle_at(points, t).unwrap_or(0.0);
                let b = project::angle_at(&got[servo], t).unwrap_or(0.0);
                worst = worst.max((a - b).abs());
                t += 10.0;
            }
        }
        (worst, want_end, got_end)
    }

    #[test]
    fn each_curve_is_baked_into_straight_steps_within_a_degree_at_every_update() {
        for easing in Easing::ALL {
            let authored = project(easing, run_wave(100, 1));
            let baked = bake_servo(&authored, DEFAULT_TOLERANCE_DEG, |_| true);
            assert!(baked.project.actions.iter().flat_map(|a| &a.steps).all(|s| s.easing.is_linear()));
            let (worst, want_end, got_end) = deviation(&authored, &baked.project);
            assert!(worst <= DEFAULT_TOLERANCE_DEG, "{easing:?}: {worst}°");
            assert!(baked.max_error_deg <= DEFAULT_TOLERANCE_DEG);
            assert!((want_end - got_end).abs() < 1e-9, "{easing:?}: {want_end} vs {got_end}");
            if easing.is_linear() {
                assert_eq!(baked.project, authored, "a straight project is stored as it is");
            } else {
                assert!(baked.added_actions >= 2, "{easing:?}: {}", baked.added_actions);
                // The wrist is done at 500 ms: the sub-actions after that hold only the arm's step.
                let added: usize = baked.project.actions[1..].iter().map(|a| a.steps.len()).sum();
                assert!(added < 2 * baked.added_actions, "{easing:?}: {added} steps in {}", baked.added_actions);
                assert_eq!(baked.added_macros, 1);
                // The authored action is still there, straight, for a loop's later turns.
                let straight: Vec<(u8, i16, i16)> =
                    authored.actions[0].steps.iter().map(|s| (s.servo_id, s.degree, s.interval_10ms)).collect();
                let stored = &baked.project.actions[0];
                assert_eq!(
                    stored.steps.iter().map(|s| (s.servo_id, s.degree, s.interval_10ms)).collect::<Vec<_>>(),
                    straight
                );
            }
        }
    }

    #[test]
    fn a_curved_action_alone_is_played_from_home_as_its_sub_actions() {
        let authored = project(Easing::EaseIn, run_wave(100, 1));
        let (stored, run) = stored_run(&authored, Run::Action { action_id: 4 });
        let Run::Macro { macro_id } = run else { panic!("{run:?}") };
        let (want, want_end) = project::trace(&authored, Run::Action { action_id: 4 }, f64::INFINITY).unwrap();
        let (got, got_end) = project::trace(&stored, Run::Macro { macro_id }, f64::INFINITY).unwrap();
        assert!((want_end - got_end).abs() < 1e-9);
        for k in 0..=100 {
            let t = f64::from(k) * 10.0;
            let (a, b) = (project::angle_at(&want[&1], t).unwrap(), project::angle_at(&got[&1], t).unwrap());
            assert!((a - b).abs() <= DEFAULT_TOLERANCE_DEG, "at {t} ms: {a} vs {b}");
        }
        assert!(project::angle_at(&got[&1], 500.0).unwrap() < 30.0, "eased in: a quarter of the way at half the time");
    }

    #[test]
    fn ids_at_the_top_of_the_range_give_fresh_ids_never_a_taken_one() {
        let mut authored = project(Easing::EaseOut, run_wave(100, 1));
        authored.actions[0].id = i32::MAX;
        authored.macros[0].id = i32::MAX;
        authored.macros[0].commands[0].run = Run::Action { action_id: i32::MAX };
        authored.actions.push(Action { id: 1, caption: "one".into(), steps: vec![Step::new(2, 5, 10)] });
        let baked = bake_servo(&authored, DEFAULT_TOLERANCE_DEG, |_| true);
        let mut ids: Vec<i32> = baked.project.actions.iter().map(|a| a.id).collect();
        ids.sort_unstable();
        let count = ids.len();
        ids.dedup();
        assert_eq!(ids.len(), count, "no id twice: {ids:?}");
        assert!(ids.iter().all(|id| *id > 0));
        assert_eq!(baked.project.macros.len(), 2);
        assert_ne!(baked.project.macros[0].id, baked.project.macros[1].id);
        assert!(deviation(&authored, &baked.project).0 <= DEFAULT_TOLERANCE_DEG);
        let (stored, run) = stored_run(&authored, Run::Action { action_id: i32::MAX });
        assert!(matches!(run, Run::Macro { macro_id } if stored.macro_by_id(macro_id).is_some()));
    }

    #[test]
    fn a_looped_command_at_half_speed_plays_the_curve_once_then_holds_as_before() {
        let authored = project(Easing::EaseInOut, run_wave(50, 3));
        let baked = bake_servo(&authored, DEFAULT_TOLERANCE_DEG, |_| true);
        let commands = &baked.project.macro_by_id(1).unwrap().commands;
        assert_eq!(commands.len(), 2);
        assert!(matches!(commands[0].run, Run::Macro { .. }) && commands[0].loop_count == 1);
        assert_eq!((commands[1].run, commands[1].loop_count), (Run::Action { action_id: 4 }, 2));
        assert!(commands.iter().all(|c| c.ratio_percent == 50));
        let (worst, want_end, got_end) = deviation(&authored, &baked.project);
        assert!(worst <= DEFAULT_TOLERANCE_DEG, "{worst}°");
        assert!((want_end - 6000.0).abs() < 1e-9 && (got_end - want_end).abs() < 1e-9, "{got_end}");
    }

    #[test]
    fn an_action_reached_from_another_angle_is_baked_again_and_from_the_same_one_shared() {
        let mut authored = project(Easing::EaseOut, run_wave(100, 1));
        authored.actions.push(Action { id: 9, caption: "down".into(), steps: vec![Step::new(1, -45, 20)] });
        let commands = &mut authored.macros[0].commands;
        commands.push(Command::once(Run::Action { action_id: 9 }));
        commands.push(run_wave(100, 1));
        authored.macros.push(Macro { id: 2, caption: "again".into(), commands: vec![run_wave(100, 1)] });
        let baked = bake_servo(&authored, DEFAULT_TOLERANCE_DEG, |_| true);
        // From home (macros 1 and 2 share it) and from -45°.
        assert_eq!(baked.added_macros, 2);
        let wrapper = |id: i32, at: usize| baked.project.macro_by_id(id).unwrap().commands[at].run;
        assert_eq!(wrapper(1, 0), wrapper(2, 0));
        assert_ne!(wrapper(1, 0), wrapper(1, 2));
        assert!(deviation(&authored, &baked.project).0 <= DEFAULT_TOLERANCE_DEG);
    }

    #[test]
    fn a_board_too_small_widens_the_tolerance_to_the_smallest_that_fits() {
        let authored = project(Easing::EaseInOut, run_wave(100, 1));
        let tight = bake_servo(&authored, DEFAULT_TOLERANCE_DEG, |_| true);
        let allowed = tight.steps() - 4;
        let fits = |stored: &ServoProject| stored.actions.iter().map(|a| a.steps.len()).sum::<usize>() <= allowed;
        let baked = bake_servo(&authored, DEFAULT_TOLERANCE_DEG, fits);
        assert!(baked.widened(DEFAULT_TOLERANCE_DEG) && baked.steps() <= allowed);
        assert!(!fits(&bake_at(&authored, baked.tolerance_deg - 0.1).project), "the smallest that fits");
        assert!(deviation(&authored, &baked.project).0 <= baked.tolerance_deg);
    }
}
