//! PLEN2 motions and play lists: a key is a frame (and a held frame when it
//! pauses), timed in whole firmware cycles so that every key ends within half
//! a cycle of the source's time; a clip longer than 20 frames continues in
//! the next slot (`jump_slot`); repeats are loops, next pages jumps, flows
//! and exit pages play lists.

use super::servo::fit_said;
use super::{BuildError, CUT_SHORT, Input, JUMP, LIVE_DEG_PER_S, Start, frame_move, timing};
use crate::authoring::fit::{self, Budget, Plen2Board};
use crate::authoring::fitted::{self, PLEN2_UPDATE_MS};
use crate::authoring::recording::Recording;
use crate::interchange::map::Target;
use crate::interchange::report::Report;
use crate::interchange::source::{Body, Clip, Key};
use crate::project::plen2::{
    Frame, JOINTS, Joint, LoopRange, MAX_FRAMES, Motion, PlayEntry, PlayList, Plen2Project, Pose, SLOTS,
};
use crate::protocol::plen2::ANGLE_LIMIT_TENTHS_DEG;

/// A firmware cycle, ms.
const CYCLE_MS: f64 = PLEN2_UPDATE_MS;
/// The most cycles one frame lasts.
const MAX_CYCLES: u32 = 255;
/// How far a frame may turn a joint from its home, tenths.
const FRAME_LIMIT: f64 = 2.0 * ANGLE_LIMIT_TENTHS_DEG as f64;
/// A play list's longest queue.
const MAX_QUEUE: usize = 31;
/// A motion name's longest.
const NAME_CHARS: usize = 20;

pub(super) fn build(
    input: &Input<'_>,
    report: &mut Report,
    starts: &mut Vec<(usize, Start)>,
) -> Result<Plen2Project, BuildError> {
    let joints: Vec<Option<Joint>> = input
        .mapped
        .iter()
        .map(|entry| match entry.and_then(|e| e.target) {
            Some(Target::Joint(joint)) => Some(joint),
            _ => None,
        })
        .collect();
    // Each clip's frames first, then slots for them. A clip another jumps
    // to plays on from where that one ended, on the same cycle clock (plen2.md §6).
    let mut framed: Vec<(usize, Vec<Frame>)> = Vec::new();
    let mut clock = Clock::default();
    let mut ends: Vec<(usize, End)> = Vec::new();
    // Repeated clips whose passes fit one motion, played out on one clock (no loop).
    let mut unrolled: Vec<usize> = Vec::new();
    for &index in &input.clips {
        let clip = input.clip(index);
        let before = input.clips.iter().copied().find(|&other| other != index && input.clip(other).next == Some(index));
        let start = before.map(|other| match ends.iter().find(|(clip, _)| *clip == other) {
            // Played once, or its passes played out: on the same clock, rounding carried over.
            Some((_, end)) if input.clip(other).repeat <= 1 || unrolled.contains(&other) => *end,
            // Repeated, or made later: from its end, on a clock of its own.
            found => End {
                pose: found.map_or([0.0; JOINTS], |(_, end)| end.pose),
                source_ms: 0.0,
                cycles: 0,
                first_cycle: 0,
            },
        });
        let frames = match &clip.body {
            Body::Keys(keys) => {
                if let Some((frames, end)) = played_out(input, &joints, (clip, keys, start), &mut clock, report) {
                    unrolled.push(index);
                    ends.push((index, end));
                    framed.push((index, frames));
                    continue;
                }
                let (frames, end) = keyed(input, &joints, (clip, keys, start), &mut clock, report);
                ends.push((index, end));
                frames
            }
            Body::Samples { fps, rows } => sampled(input, &joints, clip, *fps, rows, report)?,
            Body::Chain(_) => Vec::new(),
        };
        framed.push((index, frames));
    }
    clock.said(report);
    let needed: usize = framed.iter().map(|(_, frames)| frames.len().div_ceil(MAX_FRAMES)).sum();
    if needed > usize::from(SLOTS) {
        return Err(BuildError::TooBig(format!(
            "the motions need {needed} slots and a PLEN2 holds {SLOTS}: convert fewer at once (--page, --sequence)"
        )));
    }
    let mut project = Plen2Project::default();
    let first_slot = place(input, &framed, &mut project, report);
    let slot_of = |clip: usize| first_slot.iter().find(|(index, ..)| *index == clip).map(|(_, slot, _)| *slot);
    link(input, (&first_slot, &unrolled), &mut project, report);
    starts.extend(first_slot.iter().map(|&(clip, slot, _)| (clip, Start::Slot(slot))));
    flows(input, &slot_of, &mut project, report, starts);
    Ok(project)
}

/// The clips' frames as motions from slot 0, 20 frames a slot (a longer one
/// jumping on to its next part): each clip's (index, first slot, slots).
fn place(
    input: &Input<'_>,
    framed: &[(usize, Vec<Frame>)],
    project: &mut Plen2Project,
    report: &mut Report,
) -> Vec<(usize, u8, u8)> {
    // (clip, its first slot, how many slots it takes).
    let mut first_slot: Vec<(usize, u8, u8)> = Vec::new();
    let mut slot = 0u8;
    for (index, frames) in framed {
        if frames.is_empty() {
            continue;
        }
        let clip = input.clip(*index);
        let chunks: Vec<&[Frame]> = frames.chunks(MAX_FRAMES).collect();
        first_slot.push((*index, slot, u8::try_from(chunks.len()).unwrap_or(u8::MAX)));
        for (part, chunk) in chunks.iter().enumerate() {
            let name = motion_name(&clip.name, part, report);
            let jump_slot = (part + 1 < chunks.len()).then_some(slot + 1);
            project.motions.push(Motion { slot, name, frames: chunk.to_vec(), loop_range: None, jump_slot });
            slot += 1;
        }
        let first = slot - u8::try_from(chunks.len()).unwrap_or(0);
        let frames = crate::interchange::count(frames.len(), "frame", "frames");
        report.converted(format!("{:?}: motion in slot {first} ({frames})", clip.name));
    }
    first_slot
}

/// A repeated clip's passes played out one after another on one cycle clock,
/// when they fit one motion (20 frames): every pass's keys then keep their
/// time as the first pass's do, where a loop's passes each end a cycle later.
fn played_out(
    input: &Input<'_>,
    joints: &[Option<Joint>],
    (clip, keys, start): (&Clip, &[Key], Option<End>),
    clock: &mut Clock,
    report: &mut Report,
) -> Option<(Vec<Frame>, End)> {
    let passes = usize::try_from(clip.repeat).ok().filter(|passes| *passes > 1)?;
    if keys.len().saturating_mul(passes) > MAX_FRAMES {
        return None;
    }
    let (mut tried_clock, mut tried_report) = (clock.clone(), report.clone());
    let all: Vec<Key> = (0..passes).flat_map(|_| keys.iter().cloned()).collect();
    let (frames, end) = keyed(input, joints, (clip, &all, start), &mut tried_clock, &mut tried_report);
    if frames.len() > MAX_FRAMES {
        return None;
    }
    (*clock, *report) = (tried_clock, tried_report);
    report.converted(format!(
        "{:?}: its {passes} passes played out in one motion, on one clock (every pass's keys keep their time)",
        clip.name
    ));
    Some((frames, end))
}

/// Repeats as loops (unless played out), next pages as jumps, exit pages as play lists.
fn link(
    input: &Input<'_>,
    (first_slot, unrolled): (&[(usize, u8, u8)], &[usize]),
    project: &mut Plen2Project,
    report: &mut Report,
) {
    let slot_of = |clip: usize| first_slot.iter().find(|(index, ..)| *index == clip).map(|(_, slot, _)| *slot);
    for &(index, first, parts) in first_slot {
        let clip = input.clip(index);
        // Motions are pushed in slot order from slot 0.
        let last = usize::from(first + parts - 1);
        if clip.repeat > 1 && !unrolled.contains(&index) {
            if parts == 1 {
                let motion = &mut project.motions[last];
                let count = u8::try_from((clip.repeat - 1).min(254)).unwrap_or(254);
                let end_frame = u8::try_from(motion.frames.len() - 1).unwrap_or(0);
                motion.loop_range = Some(LoopRange { begin_frame: 0, end_frame, count });
                report.approximated(format!(
                    "a repeated motion loops its frames: each pass after the first ends one {CYCLE_MS} ms cycle later than the file's (the first pass's first cycle is output as it starts, a loop's is not)"
                ));
            } else {
                report.approximated(
                    "a repeated motion over 20 frames: a play list repeats it (a loop stays within one motion)",
                );
                let plays = u8::try_from(clip.repeat.min(255)).unwrap_or(255);
                project
                    .play_lists
                    .push(PlayList { name: clip.name.clone(), entries: vec![PlayEntry { slot: first, plays }] });
            }
        }
        if let Some(next) = clip.next.and_then(slot_of) {
            project.motions[last].jump_slot = Some(next);
        }
        if let Some(exit) = clip.exit.and_then(slot_of) {
            report.approximated("exit pages: a play list \"… then exit\" plays the page, then its exit page");
            let entries = vec![PlayEntry { slot: first, plays: 1 }, PlayEntry { slot: exit, plays: 1 }];
            project.play_lists.push(PlayList { name: format!("{} then exit", clip.name), entries });
        }
    }
}

/// Flows as play lists.
fn flows(
    input: &Input<'_>,
    slot_of: &dyn Fn(usize) -> Option<u8>,
    project: &mut Plen2Project,
    report: &mut Report,
    starts: &mut Vec<(usize, Start)>,
) {
    let mut farthest: Option<(f64, String)> = None;
    for &index in &input.clips {
        let clip = input.clip(index);
        let Body::Chain(links) = &clip.body else { continue };
        // Each motion of the list lasts whole cycles: how far the flow's end is from the file's.
        let off: f64 = links
            .iter()
            .filter_map(|link| {
                let page = input.clip(link.clip);
                let first = slot_of(link.clip)?;
                let cycles: u32 = project
                    .motions
                    .iter()
                    .skip_while(|motion| motion.slot != first)
                    .scan(true, |more, motion| {
                        let this = (*more).then_some(motion);
                        *more = motion.jump_slot == Some(motion.slot + 1);
                        this
                    })
                    .flat_map(|motion| &motion.frames)
                    .map(|frame| u32::from(frame.transition_ms) / 32)
                    .sum();
                let plays = f64::from(link.plays.max(1));
                Some(plays * (f64::from(cycles) * CYCLE_MS - page.duration_ms() / link.speed))
            })
            .sum();
        if off.abs() >= 0.5 && farthest.as_ref().is_none_or(|(ms, _)| off.abs() > ms.abs()) {
            farthest = Some((off, clip.name.clone()));
        }
        let mut entries: Vec<PlayEntry> = links
            .iter()
            .filter_map(|link| {
                if (link.speed - 1.0).abs() > 1e-9 {
                    report.approximated("a flow's unit speeds: a play list plays each motion at its own speed");
                }
                Some(PlayEntry { slot: slot_of(link.clip)?, plays: u8::try_from(link.plays.min(255)).unwrap_or(255) })
            })
            .collect();
        if entries.len() > MAX_QUEUE {
            report.approximated(format!("a flow of over {MAX_QUEUE} units: its play list keeps the first {MAX_QUEUE}"));
            entries.truncate(MAX_QUEUE);
        }
        starts.push((index, Start::PlayList(project.play_lists.len())));
        project.play_lists.push(PlayList { name: clip.name.clone(), entries });
    }
    if let Some((ms, name)) = farthest {
        report.approximated(format!(
            "a flow's play list plays each motion in whole {CYCLE_MS} ms cycles: {name:?} ends {ms:+.1} ms from the file's time (a queued motion starts on a cycle of its own, and each motion's cycles are rounded)"
        ));
    }
}

/// A name a PLEN2 stores: at most 20 ASCII characters (a part after the first numbered).
fn motion_name(name: &str, part: usize, report: &mut Report) -> String {
    let mut ascii: String = name.chars().map(|c| if c.is_ascii() && !c.is_ascii_control() { c } else { '_' }).collect();
    let suffix = if part == 0 { String::new() } else { format!(" {}", part + 1) };
    if ascii.len() + suffix.len() > NAME_CHARS || ascii != name {
        report.approximated("motion names cut to a PLEN2's 20 ASCII characters");
    }
    ascii.truncate(NAME_CHARS - suffix.len());
    ascii + &suffix
}

/// Tenths of a degree as a frame stores them.
fn tenths(degrees: f64, report: &mut Report) -> i16 {
    let wanted = (degrees * 10.0).round();
    if wanted.abs() > FRAME_LIMIT {
        report.approximated("joint angles beyond ±180° from home are held at ±180°");
    }
    // Clamped into ±1800 first.
    #[allow(clippy::cast_possible_truncation)]
    let value = wanted.clamp(-FRAME_LIMIT, FRAME_LIMIT) as i16;
    value
}

/// How far the cycles kept from the file's time, over every clip.
#[derive(Clone, Default)]
struct Clock {
    /// The farthest a key's end was from the file's time, ms.
    worst_ms: f64,
    /// The latest a step shorter than a cycle made its key, ms.
    short_ms: f64,
    /// Clips played on from a jump.
    jumps: usize,
}

impl Clock {
    fn said(&self, report: &mut Report) {
        if self.short_ms > 0.0 {
            report.approximated(format!(
                "steps shorter than a {CYCLE_MS} ms cycle take a whole cycle (a PLEN2 does no less): the key after one is up to {:.1} ms late, the keys after it keep their time",
                self.short_ms
            ));
        }
        if self.worst_ms >= 0.5 {
            report.approximated(format!(
                "times kept on the PLEN2's {CYCLE_MS} ms cycles: every key within {:.1} ms of the file's time, rounding never adding up",
                self.worst_ms
            ));
        }
        if self.jumps > 0 {
            report.converted(
                "next pages: the jumped-to motion plays on the same cycles as the one before, so the robot plays the chain as one",
            );
        }
    }
}

/// Frames timed in cycles: `cycles` to reach `pose` (split when over 255).
struct Timeline<'r> {
    frames: Vec<Frame>,
    /// Source time reached, ms.
    source_ms: f64,
    /// Cycles played.
    cycles: i64,
    /// 1 from `$PM` (cycle 0 is output as it starts), 0 played on from a jump
    /// (the jumped-to frame's first cycle follows the last one's).
    first_cycle: i64,
    pose: [f64; JOINTS],
    clock: &'r mut Clock,
    report: &'r mut Report,
}

impl Timeline<'_> {
    /// Moves to `to` so that it ends `after_ms` of source time later, at least `least` cycles.
    fn go(&mut self, to: [f64; JOINTS], after_ms: f64, least: i64) {
        self.source_ms += after_ms;
        // Cycle k is output at k × 32.768 ms (cycle 0 as `$PM` starts, as
        // `trajectory` and the fitter count): a frame ending at source time T
        // ends with cycle round(T / cycle), the cycle count so far one more
        // (played on from a jump: the count so far is round(T / cycle)).
        // Cycle counts of any real file are far below 2^52.
        #[allow(clippy::cast_possible_truncation)]
        let end = (self.source_ms / CYCLE_MS).round() as i64 + self.first_cycle;
        let mut cycles = end - self.cycles;
        if cycles < least {
            if least == 1 {
                // Counts of a few hundred cycles.
                #[allow(clippy::cast_precision_loss)]
                let late = (least - cycles) as f64 * CYCLE_MS;
                self.clock.short_ms = self.clock.short_ms.max(late);
            }
            cycles = least;
        }
        if cycles < 1 {
            return;
        }
        let from = self.pose;
        let mut done = 0;
        while done < cycles {
            let part = (cycles - done).min(i64::from(MAX_CYCLES));
            done += part;
            // Fractions of a whole move.
            #[allow(clippy::cast_precision_loss)]
            let share = done as f64 / cycles as f64;
            let mut values = [0i16; JOINTS];
            for joint in 0..JOINTS {
                values[joint] = tenths(from[joint] + (to[joint] - from[joint]) * share, self.report);
            }
            let transition_ms = u16::try_from(part * 32).unwrap_or(u16::MAX);
            self.frames.push(Frame::new(transition_ms, Pose(values)));
        }
        self.cycles += cycles;
        self.pose = to;
        if least <= 1 {
            // Counts of a few thousand cycles.
            #[allow(clippy::cast_precision_loss)]
            let board_ms = (self.cycles - self.first_cycle) as f64 * CYCLE_MS;
            self.clock.worst_ms = self.clock.worst_ms.max((board_ms - self.source_ms).abs());
        }
    }
}

/// Where a clip of keys ended: its pose, and its clock (source time, cycles).
#[derive(Clone, Copy)]
struct End {
    pose: [f64; JOINTS],
    source_ms: f64,
    cycles: i64,
    first_cycle: i64,
}

/// A clip of keys as frames, from power-up (`start` None) or played on from
/// a jump where the motion before ended.
fn keyed(
    input: &Input<'_>,
    joints: &[Option<Joint>],
    (clip, keys, start): (&Clip, &[Key], Option<End>),
    clock: &mut Clock,
    report: &mut Report,
) -> (Vec<Frame>, End) {
    let mut at: Vec<Option<f64>> = vec![Some(0.0); joints.len()];
    clock.jumps += usize::from(start.is_some());
    let from = start.unwrap_or(End { pose: [0.0; JOINTS], source_ms: 0.0, cycles: 0, first_cycle: 1 });
    let mut timeline = Timeline {
        frames: Vec::new(),
        source_ms: from.source_ms,
        cycles: from.cycles,
        first_cycle: from.first_cycle,
        pose: from.pose,
        clock,
        report,
    };
    if start.is_some() {
        for (channel, joint) in joints.iter().enumerate() {
            if let Some(joint) = joint {
                at[channel] = Some(from.pose[joint.index()]);
            }
        }
    }
    for key in keys {
        let (move_ms, hold_ms, is_frame) = timing(clip, key.timing);
        let (end, move_ms, hold_ms) = if is_frame {
            let moved = frame_move(input, &at, &key.values, move_ms);
            if moved.cut_short {
                timeline.report.approximated(CUT_SHORT);
            }
            let took = f64::from(moved.updates.iter().copied().max().unwrap_or(0)) * 10.0;
            (moved.end, took.min(move_ms), (move_ms - took).max(0.0))
        } else {
            let wanted = input.degrees(&key.values);
            (wanted.iter().zip(&at).map(|(w, a)| w.or(*a)).collect(), move_ms, hold_ms)
        };
        let mut pose = timeline.pose;
        for (channel, joint) in joints.iter().enumerate() {
            if let (Some(joint), Some(degrees)) = (joint, end[channel]) {
                pose[joint.index()] = degrees;
            }
        }
        let farthest = pose.iter().zip(&timeline.pose).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
        // A timed move keeps its time; a jump (under half a cycle) takes what
        // the live speed limit needs, so that no joint slams.
        let least = if move_ms < CYCLE_MS / 2.0 && farthest > 0.0 {
            timeline.report.approximated(JUMP);
            // A few hundred cycles at most.
            #[allow(clippy::cast_possible_truncation)]
            let cycles = (farthest / LIVE_DEG_PER_S * 1000.0 / CYCLE_MS).ceil().max(1.0) as i64;
            cycles
        } else {
            1
        };
        timeline.go(pose, move_ms, least);
        if hold_ms > 0.0 {
            timeline.go(pose, hold_ms, 0);
        }
        at = end;
    }
    let end = End {
        pose: timeline.pose,
        source_ms: timeline.source_ms,
        cycles: timeline.cycles,
        first_cycle: timeline.first_cycle,
    };
    (timeline.frames, end)
}

fn sampled(
    input: &Input<'_>,
    joints: &[Option<Joint>],
    clip: &Clip,
    fps: f64,
    rows: &[Vec<f64>],
    report: &mut Report,
) -> Result<Vec<Frame>, BuildError> {
    let tenths_rows: Vec<Vec<f64>> = rows
        .iter()
        .map(|row| {
            let mut values = vec![0.0; JOINTS];
            for (channel, joint) in joints.iter().enumerate() {
                if let (Some(joint), Some(entry)) = (joint, input.mapped[channel]) {
                    values[joint.index()] = entry.degrees(row[channel]) * 10.0;
                }
            }
            values
        })
        .collect();
    // Frame numbers far below 2^52.
    #[allow(clippy::cast_precision_loss)]
    let times_ms = (0..rows.len()).map(|frame| frame as f64 * 1000.0 / (fps * clip.speed)).collect();
    let names = Joint::ALL.iter().map(|joint| joint.name().to_string()).collect();
    let resampled = Recording { names, times_ms, rows: tenths_rows }.resample(PLEN2_UPDATE_MS);
    let budget =
        Budget { tolerance: input.tolerance_deg * 10.0, allowed: MAX_FRAMES * usize::from(SLOTS), resolution: 1.0 };
    // `$PM` from power-up: every joint's frame buffer at 0 (plen2.md §6).
    let fitted = fit::fit_within(&Plen2Board, &[0; JOINTS], &resampled, budget)
        .map_err(|error| BuildError::Fit(fit_said(&error, 10.0, "frames")))?;
    report.converted(format!(
        "{:?}: {} samples at {fps} fps fitted into {} frames within {:.2}° (asked {}°)",
        clip.name,
        rows.len(),
        fitted.moves.len(),
        fitted.max_error / 10.0,
        input.tolerance_deg
    ));
    Ok(fitted::plen2_frames(&fitted))
}
