//! The fitter (prints figures; run with `cargo bench --bench fit`):
//! 1. A 60 s recording of 18 joints fitted into PLEN2 frames, and of 18
//!    servos into servo-board steps, at 1°: median time of 21 runs (target:
//!    under 100 ms).
//! 2. For a set of smooth curves, the frames the fit takes against the fewest
//!    possible (`fewest_moves`, an exhaustive search over the same moves):
//!    the fit must stay within 20 % of it.
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

use servo_studio::authoring::fit::{Board, Plen2Board, ServoBoard, fewest_moves, fit, play};

/// `channels` smooth movements: each a sum of two sines of its own
/// frequencies (0.1..0.6 Hz) and amplitude `amplitude`, sampled every `update_ms`.
fn smooth(seconds: f64, update_ms: f64, channels: usize, amplitude: f64) -> Vec<Vec<f64>> {
    let count = (seconds * 1000.0 / update_ms) as usize;
    (1..=count)
        .map(|k| {
            let t = k as f64 * update_ms / 1000.0;
            (0..channels)
                .map(|c| {
                    let f1 = 0.1 + 0.02 * c as f64;
                    let f2 = 0.25 + 0.02 * c as f64;
                    let tau = std::f64::consts::TAU;
                    amplitude
                        * (0.7 * (tau * f1 * t).sin() + 0.3 * (tau * f2 * t + c as f64).sin() - 0.3 * (c as f64).sin())
                })
                .collect()
        })
        .collect()
}

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

fn against_minimum(what: &str, board: &impl Board, rows: &[Vec<f64>], tolerance: f64) -> (usize, usize) {
    let start = vec![0; rows[0].len()];
    let fitted = fit(board, &start, rows, tolerance).moves.len();
    let minimum = fewest_moves(board, &start, rows, tolerance).expect("wide enough");
    println!(
        "  {what}: {fitted} moves, fewest possible {minimum} ({:+.0} %)",
        (fitted as f64 / minimum as f64 - 1.0) * 100.0
    );
    (fitted, minimum)
}

fn main() {
    println!("fitting a 60 s recording at 1°:");
    time_fit("  PLEN2, 32.768 ms cycles", &Plen2Board, &smooth(60.0, 32.768, 18, 400.0), 10.0);
    time_fit("  servo board, 10 ms updates", &ServoBoard, &smooth(60.0, 10.0, 18, 40.0), 1.0);

    println!("frames against the fewest possible:");
    let mut worst: f64 = 0.0;
    for (seconds, channels, amplitude, tolerance) in
        [(8.0, 18, 400.0, 10.0), (8.0, 3, 600.0, 5.0), (6.0, 1, 900.0, 10.0), (8.0, 18, 200.0, 20.0)]
    {
        let (fitted, minimum) = against_minimum(
            &format!("PLEN2 {seconds} s × {channels} joints, ±{}°, within {}°", amplitude / 10.0, tolerance / 10.0),
            &Plen2Board,
            &smooth(seconds, 32.768, channels, amplitude),
            tolerance,
        );
        worst = worst.max(fitted as f64 / minimum as f64);
    }
    for (seconds, channels, amplitude, tolerance) in [(3.0, 4, 60.0, 1.0), (3.0, 1, 90.0, 0.5)] {
        let (fitted, minimum) = against_minimum(
            &format!("servo {seconds} s × {channels} servos, ±{amplitude}°, within {tolerance}°"),
            &ServoBoard,
            &smooth(seconds, 10.0, channels, amplitude),
            tolerance,
        );
        worst = worst.max(fitted as f64 / minimum as f64);
    }
    println!("largest ratio fitted / fewest: {worst:.2} (target ≤ 1.20)");
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
