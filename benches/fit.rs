//! The fitter (prints figures; run with `cargo bench --bench fit`):
//! 1. A 60 s recording of 18 joints fitted into PLEN2 frames, and of 18
//!    servos into servo-board steps, at 1°: median time of 21 runs (target:
//!    under 100 ms).
//! 2. For the set of recordings (`authoring::fit::samples`) and the official
//!    PLEN2 motions, at 1° and 0.5°: the moves the fit takes, the earlier
//!    fit's (ending every move on a sample), and the lower bound no fit can
//!    go under (`lower_bound`): fitted / bound must stay ≤ 1.2, which keeps
//!    the fit within 20 % of the true minimum.
//! 3. Baking a servo project's curves for the board (what an upload, the
//!    budget meter and the plots do, the latter two off the frame): 32
//!    servos, 40 actions of 32 eased 2 s steps, 20 macros running them in
//!    turn; and the same with the board's memory short (the tolerance widened
//!    by halving).

#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::cast_precision_loss,
    clippy::cast_possible_truncation,
    clippy::cast_sign_loss,
    missing_docs
)]

use std::time::{Duration, Instant};

use servo_studio::authoring::fit::{Board, Plen2Board, ServoBoard, fit, fit_on_samples, lower_bound, play, samples};
use servo_studio::protocol::plen2::DEVICE_IDS;

fn time_fit(what: &str, board: &impl Board, rows: &[Vec<f64>], tolerance: f64) {
    let start = vec![0; rows[0].len()];
    let mut times: Vec<Duration> = (0..21)
        .map(|_| {
            let begun = Instant::now();
            let fitted = fit(board, &start, rows, tolerance);
            let took = begun.elapsed();
            assert!(fitted.max_error <= tolerance);
            took
        })
        .collect();
    times.sort();
    let fitted = fit(board, &start, rows, tolerance);
    let played = play(board, &start, &fitted.moves);
    let worst =
        played.iter().zip(rows).flat_map(|(a, b)| a.iter().zip(b).map(|(a, b)| (a - b).abs())).fold(0.0, f64::max);
    println!(
        "{what}: {} updates × {} channels → {} moves, largest error {worst:.2} (tolerance {tolerance}); median {:.1} ms, slowest {:.1} ms (target < 100 ms)",
        rows.len(),
        rows[0].len(),
        fitted.moves.len(),
        times[times.len() / 2].as_secs_f64() * 1000.0,
        times[times.len() - 1].as_secs_f64() * 1000.0,
    );
}

/// One row of the table: fitted, the earlier fit, the bound, the ratio.
fn against_bound(what: &str, board: &impl Board, start: &[i32], rows: &[Vec<f64>], tolerance: f64) -> f64 {
    let fitted = fit(board, start, rows, tolerance);
    let earlier = fit_on_samples(board, start, rows, tolerance).moves.len();
    let bound = lower_bound(board, start, rows, tolerance);
    let ratio = fitted.moves.len() as f64 / bound.max(1) as f64;
    println!(
        "  {what:<44} {:>6} {:>8} {:>6} {:>6.2}{}",
        fitted.moves.len(),
        earlier,
        bound,
        ratio,
        if fitted.max_error <= tolerance { "" } else { "  (over the tolerance!)" }
    );
    ratio
}

/// The official PLEN2 motions' playback (30 s at most each), if `../shared` is there.
fn official_motions() -> Vec<(String, Vec<Vec<f64>>)> {
    use servo_studio::device::plen2::playback::{self, StoredMotions};
    use servo_studio::project::plen2::Plen2Project;
    let folder = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/plen2/motions");
    let Ok(motions) = servo_studio::project::motion_json::load_motions(&folder) else {
        println!("  (the official motions are not beside the clone: ../shared/plen2/motions)");
        return Vec::new();
    };
    let project = Plen2Project { motions, ..Plen2Project::default() };
    let stored = StoredMotions::new(&project);
    project
        .motions
        .iter()
        .map(|motion| {
            let played = playback::play(&stored, motion.slot, [0; DEVICE_IDS], 916);
            let rows = played.cycles.iter().map(|values| values.iter().map(|&v| f64::from(v)).collect()).collect();
            (format!("{} {}", motion.slot, motion.name), rows)
        })
        .collect()
}

fn main() {
    println!("fitting a 60 s recording at 1°:");
    time_fit("  PLEN2, 32.768 ms cycles", &Plen2Board, &samples::sines(60.0, 32.768, 18, 400.0), 10.0);
    time_fit("  servo board, 10 ms updates", &ServoBoard, &samples::sines(60.0, 10.0, 18, 40.0), 1.0);

    println!("moves against the lower bound (fitted / bound ≤ 1.20 keeps the fit within 20 % of the minimum):");
    println!("  {:<44} {:>6} {:>8} {:>6} {:>6}", "recording", "fitted", "earlier", "bound", "ratio");
    let mut worst: f64 = 0.0;
    for (tolerance_deg, label) in [(1.0, "1°"), (0.5, "0.5°")] {
        for (name, rows) in samples::recordings(32.768, 400.0) {
            let start = vec![0; rows[0].len()];
            let what = format!("PLEN2 {name}, {label}");
            worst = worst.max(against_bound(&what, &Plen2Board, &start, &rows, tolerance_deg * 10.0));
        }
        for (name, rows) in samples::recordings(10.0, 40.0) {
            let start = vec![0; rows[0].len()];
            let what = format!("servo {name}, {label}");
            worst = worst.max(against_bound(&what, &ServoBoard, &start, &rows, tolerance_deg));
        }
    }
    let official = official_motions();
    for (tolerance, label) in [(10.0, "1°"), (5.0, "0.5°")] {
        let mut totals = (0, 0, 0);
        let mut official_worst: f64 = 0.0;
        for (_, rows) in official.iter().filter(|(_, rows)| !rows.is_empty()) {
            let start = [0; DEVICE_IDS];
            let fitted = fit(&Plen2Board, &start, rows, tolerance).moves.len();
            let bound = lower_bound(&Plen2Board, &start, rows, tolerance);
            totals.0 += fitted;
            totals.1 += fit_on_samples(&Plen2Board, &start, rows, tolerance).moves.len();
            totals.2 += bound;
            official_worst = official_worst.max(fitted as f64 / bound.max(1) as f64);
        }
        if !official.is_empty() {
            println!(
                "  {:<44} {:>6} {:>8} {:>6} {:>6.2} (worst motion {official_worst:.2})",
                format!("the {} official PLEN2 motions, {label}", official.len()),
                totals.0,
                totals.1,
                totals.2,
                totals.0 as f64 / totals.2.max(1) as f64
            );
            worst = worst.max(official_worst);
        }
    }
    println!("largest ratio fitted / bound: {worst:.2} (target ≤ 1.20)");
    bake_figures();
}

/// Figure 3: baking a project of curves.
fn bake_figures() {
    use servo_studio::authoring::bake_servo::{DEFAULT_TOLERANCE_DEG, bake_servo};
    use servo_studio::project::{Action, Command, Easing, Macro, Run, Servo, ServoProject, Step};
    let servos: Vec<Servo> = (1..=32).map(|id| Servo::new(id, format!("s{id}"))).collect();
    let curves = [Easing::EaseIn, Easing::EaseOut, Easing::EaseInOut];
    let actions: Vec<Action> = (1..=40)
        .map(|id: i32| Action {
            id,
            caption: format!("a{id}"),
            steps: (1..=32u8)
                .map(|servo| {
                    let mut step = Step::new(servo, ((id * 17 + i32::from(servo) * 7) % 120 - 60) as i16, 200);
                    step.easing = curves[(id as usize + usize::from(servo)) % 3];
                    step
                })
                .collect(),
        })
        .collect();
    let macros: Vec<Macro> = (1..=20)
        .map(|id: i32| Macro {
            id,
            caption: format!("m{id}"),
            commands: (0..4).map(|k| Command::once(Run::Action { action_id: (id * 3 + k) % 40 + 1 })).collect(),
        })
        .collect();
    let project = ServoProject { servos, actions, macros, ..ServoProject::default() };
    let mut runs = Vec::new();
    let mut baked = None;
    for _ in 0..5 {
        let start = Instant::now();
        baked = Some(bake_servo(&project, DEFAULT_TOLERANCE_DEG, |_| true));
        runs.push(start.elapsed());
    }
    runs.sort();
    let baked = baked.unwrap();
    println!(
        "baking 80 curved action runs (32 servos × 2 s) at 1°: median {:.1} ms; {} sub-actions, {} steps, largest deviation {:.2}°",
        runs[2].as_secs_f64() * 1000.0,
        baked.added_actions,
        baked.steps(),
        baked.max_error_deg
    );
    let allowed = baked.steps() * 2 / 3;
    let start = Instant::now();
    let short = bake_servo(&project, DEFAULT_TOLERANCE_DEG, |stored| {
        stored.actions.iter().map(|a| a.steps.len()).sum::<usize>() <= allowed
    });
    println!(
        "  the same, the board holding two thirds of those steps: {:.1} ms, widened to {:.1}° ({} steps)",
        start.elapsed().as_secs_f64() * 1000.0,
        short.tolerance_deg,
        short.steps()
    );
}
