//! A curve that follows a sound (how open, 0–1, each millisecond, from
//! `audio::follow`) fitted into what a board stores: a servo's steps (one
//! action each, and a macro running them) or a PLEN2 motion's frames. The
//! editor's follow-sound dialog builds on this; the command line's
//! `follow-audio` fits the same curve through `fit`.

use super::fit::{self, Board as _, Budget, Fit, FitError, Plen2Board, ServoBoard};
use super::fitted::{self, PLEN2_UPDATE_MS, SERVO_UPDATE_MS};
use crate::project::plen2::{Frame, JOINTS, Joint, MAX_FRAMES, Motion, Plen2Project};
use crate::project::{Action, MAX_LIST_LEN, Macro};

/// What follows, between which angles, within which tolerance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Follower {
    /// The angle in silence, degrees (PLEN2: from home).
    pub closed_deg: f64,
    /// The angle at the loudest, degrees.
    pub open_deg: f64,
    /// How far the board may stray from the curve, degrees.
    pub tolerance_deg: f64,
}

/// The curve at every `update_ms` (the board's update), from one value a millisecond.
fn at_updates(open: &[f64], update_ms: f64, closed: f64, opened: f64) -> Vec<f64> {
    // Milliseconds of at most an hour: exact.
    #[allow(clippy::cast_precision_loss)]
    let last = open.len().saturating_sub(1) as f64;
    let mut values = Vec::new();
    let mut t = 0.0;
    while t <= last {
        // Within the curve: a whole millisecond index below its length.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let (below, along) = (t.floor() as usize, t.fract());
        let a = open[below];
        let b = open.get(below + 1).copied().unwrap_or(a);
        values.push(closed + (opened - closed) * (a + (b - a) * along));
        t += update_ms;
    }
    values
}

/// A servo following the curve: one action per fitted step (ids from
/// `first_action_id`), and a macro `macro_id` running them; the servo's
/// angle at the start (where the macro begins).
pub fn servo(
    open: &[f64],
    servo_id: u8,
    follower: Follower,
    (first_action_id, macro_id, name): (i32, i32, &str),
) -> Result<(Vec<Action>, Macro, i32), FitError> {
    let values = at_updates(open, SERVO_UPDATE_MS, follower.closed_deg, follower.open_deg);
    let start = ServoBoard.store(values.first().copied().unwrap_or(follower.closed_deg));
    let rows: Vec<Vec<f64>> = values.iter().skip(1).map(|value| vec![*value]).collect();
    let budget = Budget { tolerance: follower.tolerance_deg, allowed: MAX_LIST_LEN, resolution: 0.1 };
    let fit: Fit = fit::fit_within(&ServoBoard, &[start], &rows, budget)?;
    let actions = fitted::servo_actions(&fit, &[servo_id], first_action_id, name);
    let running = fitted::macro_running(macro_id, name, &actions);
    Ok((actions, running, start))
}

/// What a PLEN2 joint's follow became: a chain of motions the robot plays as one.
#[derive(Clone, Debug, PartialEq)]
pub struct Chain {
    /// Each motion's frames (at most 20), in the order the chain plays them.
    pub motions: Vec<Vec<Frame>>,
    /// How much later than the sound the robot plays the curve, ms (negative:
    /// earlier): 0, or the least shift within half a cycle with which the
    /// motions allowed hold it ([`MOST_SHIFT_MS`]).
    pub shift_ms: i32,
    /// The largest distance from the curve, tenths of a degree.
    pub max_error_tenths: f64,
    /// The robot's cycles the curve lasts.
    pub cycles: usize,
}

impl Chain {
    /// Every frame of the chain.
    pub fn frames(&self) -> usize {
        self.motions.iter().map(Vec::len).sum()
    }
}

/// The most a follow may be shifted against its sound to fit, ms: under half
/// a PLEN2 cycle (32.768 ms). The robot starts a motion at its next cycle,
/// so where a cycle falls against the sound is never known closer than
/// that; the same curve needs from 18 to 21 frames as the cycles fall
/// (three bursts in 4.2 s at 1°), so the phase that fits is as true as any.
pub const MOST_SHIFT_MS: i32 = 16;

/// A PLEN2 joint following the curve (every other joint at home), in at
/// most `motions` motions of at most 20 frames each. Played as a chain —
/// each motion jumping to the next — the robot plays them as one (plen2.md
/// §6: a jump loads the next slot's frame 0 as it would load the next
/// frame, its steps from the last frame's exact values), so the whole is
/// fitted at once and cut every 20 frames. When the frames needed are a
/// few more than the motions hold, the curve is tried shifted by up to
/// [`MOST_SHIFT_MS`] either way, the least shift first.
pub fn plen2(open: &[f64], joint: Joint, follower: Follower, motions: usize) -> Result<Chain, FitError> {
    plen2_within(open, joint, follower, MAX_FRAMES.saturating_mul(motions))
}

/// [`plen2`] in at most `allowed` frames in all.
pub fn plen2_within(open: &[f64], joint: Joint, follower: Follower, allowed: usize) -> Result<Chain, FitError> {
    let unshifted = plen2_shifted(open, joint, follower, allowed, 0);
    let Err(FitError::Tolerance { needed, .. }) = unshifted else { return unshifted };
    // A shift changes the count by a few frames, not by a fifth.
    if needed > allowed + allowed / 5 + 2 {
        return unshifted;
    }
    (1..=MOST_SHIFT_MS)
        .flat_map(|ms| [ms, -ms])
        .find_map(|shift| plen2_shifted(open, joint, follower, allowed, shift).ok())
        .map_or(unshifted, Ok)
}

/// [`plen2`] with the curve played `shift_ms` later than the sound.
fn plen2_shifted(
    open: &[f64],
    joint: Joint,
    follower: Follower,
    allowed: usize,
    shift_ms: i32,
) -> Result<Chain, FitError> {
    let skip = usize::try_from(-shift_ms).unwrap_or(0).min(open.len().saturating_sub(2));
    let held = usize::try_from(shift_ms).unwrap_or(0);
    let first = open.first().copied().unwrap_or(0.0);
    let shifted: Vec<f64> = std::iter::repeat_n(first, held).chain(open[skip..].iter().copied()).collect();
    let values = at_updates(&shifted, PLEN2_UPDATE_MS, follower.closed_deg * 10.0, follower.open_deg * 10.0);
    let rows: Vec<Vec<f64>> = values
        .iter()
        .map(|value| {
            let mut row = vec![0.0; JOINTS];
            row[joint.index()] = *value;
            row
        })
        .collect();
    // `$PM` from power-up: every joint's frame buffer at 0 (plen2.md §6).
    let budget = Budget { tolerance: follower.tolerance_deg * 10.0, allowed, resolution: 1.0 };
    let fit = fit::fit_within(&Plen2Board, &[0; JOINTS], &rows, budget)?;
    Ok(Chain {
        motions: fitted::plen2_frames(&fit).chunks(MAX_FRAMES).map(<[Frame]>::to_vec).collect(),
        shift_ms,
        max_error_tenths: fit.max_error,
        cycles: rows.len(),
    })
}

/// `plen2` with `chain` written in `slots` (in order), each motion named
/// `name` and jumping to the next, replacing what those slots held; and the
/// slots it replaced, with their motions' names.
pub fn placed(plen2: &Plen2Project, slots: &[u8], chain: &Chain, name: &str) -> (Plen2Project, Vec<(u8, String)>) {
    let used = &slots[..chain.motions.len().min(slots.len())];
    let mut made = plen2.clone();
    let replaced = made
        .motions
        .iter()
        .filter(|motion| used.contains(&motion.slot))
        .map(|motion| (motion.slot, motion.name.clone()))
        .collect();
    made.motions.retain(|motion| !used.contains(&motion.slot));
    for (part, (frames, &slot)) in chain.motions.iter().zip(used).enumerate() {
        let jump_slot = used.get(part + 1).copied();
        made.motions.push(Motion { slot, name: name.to_string(), frames: frames.clone(), loop_range: None, jump_slot });
    }
    made.motions.sort_by_key(|motion| motion.slot);
    (made, replaced)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Open from 200 to 500 ms of a second, closed otherwise.
    fn burst() -> Vec<f64> {
        (0..1000).map(|ms| if (200..500).contains(&ms) { 1.0 } else { 0.0 }).collect()
    }

    #[test]
    fn a_servo_follows_a_burst_in_a_few_steps_within_the_tolerance() {
        let follower = Follower { closed_deg: 0.0, open_deg: 40.0, tolerance_deg: 1.0 };
        let (actions, running, start) = servo(&burst(), 7, follower, (10, 3, "jaw")).unwrap();
        assert_eq!(start, 0);
        assert!((2..=8).contains(&actions.len()), "{} steps", actions.len());
        assert_eq!(actions[0].id, 10);
        assert_eq!(running.id, 3);
        assert_eq!(running.commands.len(), actions.len());
        assert!(actions.iter().any(|action| action.steps[0].degree == 40), "it opens");
        assert_eq!(actions.last().unwrap().steps[0].degree, 0, "and closes");
    }

    #[test]
    fn a_plen2_joint_follows_a_burst_in_frames_of_that_joint_alone() {
        let follower = Follower { closed_deg: 0.0, open_deg: -20.0, tolerance_deg: 1.0 };
        let chain = plen2(&burst(), Joint::ALL[3], follower, 1).unwrap();
        assert_eq!((chain.motions.len(), chain.shift_ms), (1, 0), "a second fits one motion, as it falls");
        let motions = chain.motions;
        let frames = &motions[0];
        assert!((2..=MAX_FRAMES).contains(&frames.len()), "{} frames", frames.len());
        assert!(frames.iter().any(|frame| frame.values_tenths_deg.0[3] == -200), "it opens");
        assert!(
            frames.iter().all(|frame| frame.values_tenths_deg.0.iter().enumerate().all(|(j, v)| j == 3 || *v == 0))
        );
    }

    /// Four bursts in 4.2 s (loud from the first ms to the second of each), as
    /// `audio::follow` opens the axis for them: 21 frames at 1° as the
    /// robot's cycles fall from the sound's start, 20 when they fall 1 ms later.
    #[test]
    fn a_follow_a_frame_or_two_over_a_motion_fits_it_shifted_under_half_a_cycle() {
        use crate::device::plen2::playback::{self, StoredMotions};
        let mut db = vec![-60.0f32; 4200];
        for (from, to) in [(352, 862), (1032, 1372), (1484, 1638), (1865, 2392)] {
            db[from..to].fill(-3.0);
        }
        let open = crate::audio::follow::openness(&db, &crate::audio::follow::Follow::default());
        let follower = Follower { closed_deg: 0.0, open_deg: -30.0, tolerance_deg: 1.0 };
        let joint = Joint::ALL[5];
        let unshifted = plen2_shifted(&open, joint, follower, MAX_FRAMES, 0);
        assert!(matches!(unshifted, Err(FitError::Tolerance { needed: 21.., .. })), "{unshifted:?}");
        let chain = plen2(&open, joint, follower, 1).unwrap();
        assert!(chain.shift_ms != 0 && chain.shift_ms.abs() <= MOST_SHIFT_MS, "{}", chain.shift_ms);
        assert_eq!(chain.motions.len(), 1);
        let (project, _) = placed(&Plen2Project::default(), &[7], &chain, "talk");
        // The robot's playback, cycle by cycle, against the curve shifted as said.
        let played = playback::play(&StoredMotions::new(&project), 7, [0; playback::DEVICE_IDS], 20 * 256);
        let shifted: Vec<f64> = (0..open.len())
            .map(|ms| open[usize::try_from(ms as i64 - i64::from(chain.shift_ms)).unwrap_or(0).min(open.len() - 1)])
            .collect();
        let wanted = at_updates(&shifted, PLEN2_UPDATE_MS, 0.0, -300.0);
        let device = usize::from(joint.device_id());
        let worst =
            played.cycles.iter().zip(&wanted).map(|(values, wanted)| (f64::from(values[device]) - wanted).abs());
        assert!(worst.fold(0.0, f64::max) <= 10.0 + 1.0, "within 1° (and the board's whole tenths)");
        // A sound far past what the motions hold is not shifted about: said at once.
        let long: Vec<f64> = (0..40).flat_map(|_| open.iter().copied()).collect();
        assert!(matches!(plen2(&long, joint, follower, 1), Err(FitError::Tolerance { .. } | FitError::TooLong { .. })));
    }

    /// 20 s of a talker: bursts of 150–400 ms, 80–300 ms apart.
    fn talk() -> Vec<f64> {
        let mut open = Vec::new();
        let mut walk = 7_u32;
        while open.len() < 20_000 {
            walk = walk.wrapping_mul(1_103_515_245).wrapping_add(12_345);
            let (on, off) = (150 + (walk >> 8) % 250, 80 + (walk >> 20) % 220);
            open.extend((0..on).map(|ms| (f64::from(ms) / 30.0).min(1.0)));
            open.extend((0..off).map(|ms| (1.0 - f64::from(ms) / 60.0).max(0.0)));
        }
        open
    }

    #[test]
    fn a_long_sound_is_followed_by_a_chain_of_motions_the_robot_plays_as_one_within_the_tolerance() {
        use crate::device::plen2::playback::{self, StoredMotions};
        let follower = Follower { closed_deg: 0.0, open_deg: 30.0, tolerance_deg: 1.5 };
        let joint = Joint::ALL[2];
        let open = talk();
        // One motion cannot hold it, and says so in frames (the editor words it in degrees).
        assert!(plen2(&open, joint, follower, 1).is_err(), "20 s of talk in 20 frames");
        let chain = plen2(&open, joint, follower, 90).unwrap();
        assert!(chain.motions.len() >= 3, "{} motions", chain.motions.len());
        assert!(chain.motions.iter().all(|frames| !frames.is_empty() && frames.len() <= MAX_FRAMES));
        // In slots 40, 41, …, each jumping to the next.
        let mut before = Plen2Project::default();
        before.motions.push(Motion {
            slot: 41,
            name: "wave".into(),
            frames: chain.motions[0].clone(),
            loop_range: None,
            jump_slot: None,
        });
        let slots: Vec<u8> = (40..90).collect();
        let (project, replaced) = placed(&before, &slots, &chain, "follow");
        assert_eq!(replaced, [(41, "wave".to_string())]);
        assert_eq!(project.motions.len(), chain.motions.len());
        // The robot's playback from slot 40, cycle by cycle, against the curve at each cycle.
        let played = playback::play(&StoredMotions::new(&project), 40, [0; playback::DEVICE_IDS], 20 * 256 * 90);
        assert!(played.ended, "the chain ends");
        let wanted = at_updates(&open, PLEN2_UPDATE_MS, 0.0, 300.0);
        let device = usize::from(joint.device_id());
        let total_ms = played.cycles.len() as f64 * PLEN2_UPDATE_MS;
        assert!((total_ms - open.len() as f64).abs() <= 2.0 * PLEN2_UPDATE_MS, "{total_ms} ms for {} ms", open.len());
        let worst = played
            .cycles
            .iter()
            .zip(&wanted)
            .map(|(values, wanted)| (f64::from(values[device]) - wanted).abs())
            .fold(0.0, f64::max);
        // Within the tolerance (tenths), and the board's whole-tenth rounding.
        assert!(worst <= 15.0 + 1.0, "off the curve by {worst} tenths at worst");
    }
}
