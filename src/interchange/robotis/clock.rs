//! How a ROBOTIS controller plays a RoboPlus page in time: the Action engine
//! the CM-5/CM-510 firmware and the DARWIN-OP framework share (ROBOTIS's
//! `Action.cpp`), on the controller's clock of 128 ticks a second.
//!
//! - A step's play time and pause are whole units, which RoboPlus shows as
//!   8 ms each ("0.096") and the controller plays as one tick (7.8125 ms).
//! - A step takes its play time and three ticks more: the tick that sets it
//!   up, and the two that pass from its ease-in to its straight part and on
//!   to its ease-out (each a tick with no output). It reaches its pose one
//!   tick after its play time; the two ticks after, it stands.
//! - A pause adds its own ticks and one more (the tick that ends the ease-out).
//! - A play time of 0 plays as 1; with an ease (the page's inertial force)
//!   a step of one or two units cannot ease and jumps (0 ticks).
//!
//! So a page of a 1.976 s step and a 0.008 s pause (1.984 s as RoboPlus
//! shows it) ends after 252 ticks: 1,968.75 ms.

/// One tick of the controller's clock, ms.
pub const TICK_MS: f64 = 1000.0 / 128.0;
/// One unit of a step's time as a `.mtn` writes it, s.
const UNIT_S: f64 = 0.008;

/// Whole units of `seconds` (as RoboPlus stored them: the text rounds them to 8 ms).
fn units(seconds: f64) -> f64 {
    (seconds / UNIT_S).round().max(0.0)
}

/// A step as the controller plays it, in ticks: from the tick that sets it
/// up to the tick it reaches its pose, then the ticks it stands before the
/// next step is set up. `ease` is the page's inertial force (its ease-in
/// and ease-out, in ticks).
pub fn step_ticks(time_s: f64, pause_s: f64, ease: f64) -> (f64, f64) {
    let mut time = units(time_s).max(1.0);
    let mut ease = ease.max(0.0).floor();
    if time <= 2.0 * ease {
        ease = ((time - 1.0) / 2.0).floor();
        if ease == 0.0 {
            time = 0.0;
        }
    }
    // Reached as the straight part ends (no ease), on the ease-out's last
    // tick but one (the engine writes the pose itself there), or its only one.
    let reach = if time == 0.0 {
        1.0
    } else if ease == 1.0 {
        time + 2.0
    } else {
        time + 1.0
    };
    let pause = units(pause_s);
    (reach, time + 3.0 - reach + if pause > 0.0 { pause + 1.0 } else { 0.0 })
}

/// How far a step eased in and out over `ease` ticks (a trapezoid of
/// speed, as the controller moves it) strays from a straight move of the
/// same length and time, at most: a share of the move's distance. (Within
/// the ease-in, the eased move is at D·t² / (2a(T − a)), the straight one at
/// D·t / T; they are farthest apart at t = a(T − a) / T.)
pub fn eased_share(time_s: f64, ease: f64) -> f64 {
    let time = units(time_s).max(1.0);
    let ease = ease.max(0.0).floor();
    if time <= 2.0 * ease {
        // Too short for its ease: eased over under half its time (a jump: not at all).
        let less = ((time - 1.0) / 2.0).floor();
        return if less == 0.0 { 0.0 } else { eased_share(time_s, less) };
    }
    ease * (time - ease) / (2.0 * time * time)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::float_cmp)]
    use super::*;

    #[test]
    fn a_step_plays_its_units_as_ticks_and_three_more() {
        // 1.976 s: 247 units, reached at tick 248, standing to tick 250, a
        // pause of one unit to tick 252: 1.984 s as RoboPlus shows it, 1,968.75 ms played.
        assert_eq!(step_ticks(1.976, 0.008, 0.0), (248.0, 4.0));
        let (reach, stand) = step_ticks(1.976, 0.008, 0.0);
        assert_eq!((reach + stand) * TICK_MS, 1_968.75);
        // A pause of 0.016 s: two ticks and the one that ends the ease-out.
        assert_eq!(step_ticks(0.096, 0.016, 32.0), (13.0, 5.0));
        // No time: one unit; eased, a step of one or two units jumps.
        assert_eq!(step_ticks(0.0, 0.0, 0.0), (2.0, 2.0));
        assert_eq!(step_ticks(0.016, 0.0, 5.0), (1.0, 2.0));
        assert_eq!(step_ticks(0.024, 0.0, 5.0), (5.0, 1.0), "three units ease one tick each way");
    }

    #[test]
    fn an_eased_step_strays_from_a_straight_one_by_a_share_of_its_distance() {
        // 1.000 s (125 units) eased over 32 ticks: 23° of move strays up to
        // 2.19° (at tick 23.8); 1.9° as its ease-in ends (250 ms: straight 5.9°, eased 4.0°).
        let share = eased_share(1.0, 32.0);
        assert!((share * 23.0 - 2.19).abs() < 0.01, "{}", share * 23.0);
        // A triangle (ease of half the time) strays an eighth of its distance.
        assert!((eased_share(0.8, 50.0) - 0.125).abs() < 1e-3, "{}", eased_share(0.8, 50.0));
        assert_eq!(eased_share(1.0, 0.0), 0.0, "no ease: straight");
        assert_eq!(eased_share(0.016, 5.0), 0.0, "a step that jumps");
    }
}
