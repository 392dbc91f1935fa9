//! Servo-board servos, actions and macros: a key is an action (every driven
//! servo in one step) and, when it holds, a delay; a clip is a macro running
//! them; repeats, next pages and flows are macros running macros.

use super::{BuildError, CUT_SHORT, Input, JUMP, LIVE_DEG_PER_S, Start, flow_keys, frame_move, timing};
use crate::authoring::fit::{self, Board, Budget, FitError, ServoBoard};
use crate::authoring::fitted::{self, SERVO_UPDATE_MS, caption_within};
use crate::authoring::recording::Recording;
use crate::interchange::map::Target;
use crate::interchange::report::{Report, count};
use crate::interchange::source::{Body, Clip, Key};
use crate::project::{Action, Command, MAX_LIST_LEN, Macro, Run, Servo, ServoProject, Step};

const CAPTION_BYTES: usize = 32;
/// The most keys a flow is played out in: an action each (and a delay where
/// it holds), far within a list's 32,767 and a board's memory for its actions.
const MOST_PLAYED_OUT: usize = 1_000;

pub(super) fn build(
    input: &Input<'_>,
    report: &mut Report,
    starts: &mut Vec<(usize, Start)>,
) -> Result<ServoProject, BuildError> {
    let servos = servos(input, report);
    let mut made = Made { servos, actions: Vec::new(), macros: Vec::new(), worst_ms: 0.0 };
    // Macro ids: each clip's body, then (when it repeats or leads on) the macro that plays it.
    let next = acyclic_next(input, report);
    let mut ids = Ids::default();
    for &clip_index in &input.clips {
        let clip = input.clip(clip_index);
        let body = ids.take();
        let play = if clip.repeat > 1 || next[clip_index].is_some() { ids.take() } else { body };
        ids.clips.push((clip_index, body, play));
    }
    for &(clip_index, body, play) in &ids.clips.clone() {
        let clip = input.clip(clip_index);
        let commands = match &clip.body {
            Body::Keys(keys) => made.keys(input, clip, keys, report),
            Body::Samples { fps, rows } => made.samples(input, clip, *fps, rows, report)?,
            Body::Chain(links) => match flow_keys(input, clip, links, MOST_PLAYED_OUT) {
                Some(keys) => {
                    report.converted(format!(
                        "{:?}: its pages played out in one macro, on one clock (every key within half an update, the whole within one)",
                        clip.name
                    ));
                    made.keys(input, clip, &keys, report)
                }
                None => links
                    .iter()
                    .filter_map(|link| {
                        let macro_id = ids.play_of(link.clip)?;
                        Some(chained(Run::Macro { macro_id }, link.plays, link.speed, report))
                    })
                    .collect(),
            },
        };
        let caption = if play == body { clip.name.clone() } else { format!("{} steps", clip.name) };
        made.macros.push(Macro { id: body, caption: caption_within(&caption, CAPTION_BYTES), commands });
        if play != body {
            let mut commands = vec![chained(Run::Macro { macro_id: body }, clip.repeat, 1.0, report)];
            if let Some(macro_id) = next[clip_index].and_then(|n| ids.play_of(n)) {
                commands.push(Command::once(Run::Macro { macro_id }));
            }
            made.macros.push(Macro { id: play, caption: caption_within(&clip.name, CAPTION_BYTES), commands });
        }
    }
    for &(clip_index, _, play) in &ids.clips.clone() {
        let clip = input.clip(clip_index);
        let Some(exit) = clip.exit.and_then(|exit| ids.play_of(exit)) else { continue };
        report.approximated(
            "exit pages: a macro \"… then exit\" plays the page, then its exit page (a board has no stop-then-exit)",
        );
        let commands = vec![Command::once(Run::Macro { macro_id: play }), Command::once(Run::Macro { macro_id: exit })];
        let caption = caption_within(&format!("{} then exit", clip.name), CAPTION_BYTES);
        made.macros.push(Macro { id: ids.take(), caption, commands });
    }
    if made.worst_ms >= 0.5 {
        report.approximated(format!(
            "times kept on the board's {SERVO_UPDATE_MS} ms updates: every key within {:.1} ms of the file's time, rounding never adding up",
            made.worst_ms
        ));
    }
    starts.extend(ids.clips.iter().map(|&(clip, _, play)| (clip, Start::Macro(play))));
    made.macros.sort_by_key(|m| m.id);
    report.converted(format!(
        "{}, {}, {}",
        count(made.servos.len(), "servo", "servos"),
        count(made.actions.len(), "action", "actions"),
        count(made.macros.len(), "macro", "macros")
    ));
    Ok(ServoProject { servos: made.servos, actions: made.actions, macros: made.macros, ..ServoProject::default() })
}

#[derive(Clone, Default)]
struct Ids {
    last: i32,
    /// `(clip, body macro, play macro)`.
    clips: Vec<(usize, i32, i32)>,
}

impl Ids {
    fn take(&mut self) -> i32 {
        self.last += 1;
        self.last
    }

    fn play_of(&self, clip: usize) -> Option<i32> {
        self.clips.iter().find(|(index, ..)| *index == clip).map(|(_, _, play)| *play)
    }
}

/// A macro command played `plays` times at `speed` (a board's ratio is 1..=100 %).
fn chained(run: Run, plays: u32, speed: f64, report: &mut Report) -> Command {
    let mut command = Command::once(run);
    if plays == 0 {
        report.approximated("played until stopped: the macro plays it once (a macro's loop count is at least 1)");
    }
    command.loop_count = i16::try_from(plays.max(1)).unwrap_or(i16::MAX);
    if (speed - 1.0).abs() > 1e-9 {
        if speed > 1.0 {
            report.approximated("played faster than authored: a macro plays at most at 100 %");
        }
        // Within 1..=100 first.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let percent = (speed * 100.0).round().clamp(1.0, 100.0) as u8;
        command.ratio_percent = percent;
    }
    command
}

/// Each clip's next clip, with one link of every loop of next pages cut (a
/// board's macros cannot call themselves).
fn acyclic_next(input: &Input<'_>, report: &mut Report) -> Vec<Option<usize>> {
    let mut next: Vec<Option<usize>> = vec![None; input.source.clips.len()];
    for &index in &input.clips {
        let Some(target) = input.clip(index).next else { continue };
        let mut at = Some(target);
        let mut steps = 0;
        while let Some(clip) = at {
            if clip == index || steps > next.len() {
                break;
            }
            at = next[clip];
            steps += 1;
        }
        if at == Some(index) {
            report.approximated(
                "next pages that loop forever: the macros play the loop once through (a macro cannot call itself)",
            );
        } else {
            next[index] = Some(target);
        }
    }
    next
}

fn servos(input: &Input<'_>, report: &mut Report) -> Vec<Servo> {
    let mut servos: Vec<Servo> = Vec::new();
    for (index, target, channel) in input.targets() {
        let Target::Servo(id) = target else { continue };
        let Some(entry) = input.mapped[index] else { continue };
        let mut servo = Servo::new(id, caption_within(&channel.name, CAPTION_BYTES));
        if let Some((low, high)) = channel.limits {
            let (a, b) = (entry.degrees(low), entry.degrees(high));
            // Rounded inward: the servo never goes past what the tool allowed.
            #[allow(clippy::cast_possible_truncation)]
            let (min, max) =
                (a.min(b).ceil().clamp(-180.0, 180.0) as i16, a.max(b).floor().clamp(-180.0, 180.0) as i16);
            (servo.min_deg, servo.max_deg) = (min, max.max(min));
        }
        if let Some(home) = channel.home {
            servo.home_deg = servo.clamp(whole(entry.degrees(home)));
        } else {
            servo.home_deg = servo.clamp(0);
        }
        servos.push(servo);
    }
    servos.sort_by_key(|servo| servo.id);
    if servos.len() < input.targets().count() {
        report.dropped("channels mapped to PLEN2 joints (this is a servo board)");
    }
    servos
}

/// Degrees as a board's whole degree.
fn whole(degrees: f64) -> i16 {
    // Rounded and clamped first.
    #[allow(clippy::cast_possible_truncation)]
    let value = degrees.round().clamp(f64::from(i16::MIN), f64::from(i16::MAX)) as i16;
    value
}

struct Made {
    servos: Vec<Servo>,
    actions: Vec<Action>,
    macros: Vec<Macro>,
    /// The farthest any clip's key was from the file's time, ms (said once, for all of them).
    worst_ms: f64,
}

impl Made {
    fn servo_id(input: &Input<'_>, channel: usize) -> Option<u8> {
        match input.mapped[channel]?.target? {
            Target::Servo(id) => Some(id),
            Target::Joint(_) => None,
        }
    }

    /// Where every channel starts: its servo's home.
    fn homes(&self, input: &Input<'_>) -> Vec<Option<f64>> {
        (0..input.mapped.len())
            .map(|channel| {
                let id = Self::servo_id(input, channel)?;
                self.servos.iter().find(|servo| servo.id == id).map(|servo| f64::from(servo.home_deg))
            })
            .collect()
    }

    fn next_action_id(&self) -> i32 {
        self.actions.last().map_or(1, |action| action.id + 1)
    }

    /// A clip's keys as actions and delays. Times are kept on the board's
    /// clock, not rounded key by key: each move takes the whole updates that
    /// end it nearest the file's time since the clip began, each hold the
    /// milliseconds that end it at the file's time, so rounding never adds up.
    fn keys(&mut self, input: &Input<'_>, clip: &Clip, keys: &[Key], report: &mut Report) -> Vec<Command> {
        let mut at = self.homes(input);
        let mut commands = Vec::new();
        let mut clock = Clock::default();
        for key in keys {
            let (move_ms, hold_ms, is_frame) = timing(clip, key.timing);
            let (end, updates) = if is_frame {
                let moved = frame_move(input, &at, &key.values, move_ms);
                if moved.cut_short {
                    report.approximated(CUT_SHORT);
                }
                (moved.end, moved.updates)
            } else {
                let wanted = input.degrees(&key.values);
                let farthest = wanted
                    .iter()
                    .zip(&at)
                    .filter_map(|(w, a)| Some((w.as_ref()? - a.unwrap_or(*w.as_ref()?)).abs()))
                    .fold(0.0, f64::max);
                let updates = if move_ms < SERVO_UPDATE_MS / 2.0 && farthest > 0.0 {
                    report.approximated(JUMP);
                    (farthest / LIVE_DEG_PER_S * 100.0).ceil().max(1.0)
                } else {
                    clock.updates_to(move_ms)
                };
                // Small and non-negative.
                #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
                let updates = updates.min(f64::from(u32::MAX)) as u32;
                let merged: Vec<Option<f64>> = wanted.iter().zip(&at).map(|(w, a)| w.or(*a)).collect();
                (merged, vec![updates; key.values.len()])
            };
            let steps = self.steps(input, &key.values, &end, &updates, report);
            let moved_ms = steps.iter().map(|step| f64::from(step.interval_10ms) * 10.0).fold(0.0, f64::max);
            if !steps.is_empty() {
                let id = self.next_action_id();
                let caption = caption_within(&format!("{} {}", clip.name, self.actions.len() + 1), CAPTION_BYTES);
                self.actions.push(Action { id, caption, steps });
                commands.push(Command::once(Run::Action { action_id: id }));
            }
            let (arrive_ms, wait_ms) = if is_frame { (0.0, move_ms) } else { (move_ms, hold_ms) };
            clock.moved(arrive_ms, moved_ms);
            if let Some(delay_ms) = clock.hold(wait_ms) {
                commands.push(Command::once(Run::Delay { delay_ms }));
            }
            at = end;
        }
        self.worst_ms = self.worst_ms.max(clock.worst_ms);
        commands
    }

    /// One step per driven servo of a key.
    fn steps(
        &self,
        input: &Input<'_>,
        raw: &[Option<f64>],
        end: &[Option<f64>],
        updates: &[u32],
        report: &mut Report,
    ) -> Vec<Step> {
        let mut steps = Vec::new();
        for channel in 0..raw.len() {
            let (Some(_), Some(degrees), Some(id)) = (raw[channel], end[channel], Self::servo_id(input, channel))
            else {
                continue;
            };
            let Some(servo) = self.servos.iter().find(|servo| servo.id == id) else { continue };
            let degree = servo.clamp(whole(degrees));
            if f64::from(degree) != degrees.round() {
                report.approximated("positions beyond a servo's limits are held at the limit");
            }
            let interval = i16::try_from(updates[channel].max(1)).unwrap_or_else(|_| {
                report.approximated("a move over 327 s is cut to 327 s (a step's longest)");
                i16::MAX
            });
            steps.push(Step::new(id, degree, interval));
        }
        steps
    }

    fn samples(
        &mut self,
        input: &Input<'_>,
        clip: &Clip,
        fps: f64,
        rows: &[Vec<f64>],
        report: &mut Report,
    ) -> Result<Vec<Command>, BuildError> {
        let channels: Vec<(usize, u8)> =
            (0..input.mapped.len()).filter_map(|channel| Some((channel, Self::servo_id(input, channel)?))).collect();
        let degrees: Vec<Vec<f64>> = rows
            .iter()
            .map(|row| {
                channels
                    .iter()
                    .map(|&(channel, _)| input.mapped[channel].map_or(0.0, |e| e.degrees(row[channel])))
                    .collect()
            })
            .collect();
        // Frame numbers far below 2^52.
        #[allow(clippy::cast_precision_loss)]
        let times_ms = (0..rows.len()).map(|frame| frame as f64 * 1000.0 / (fps * clip.speed)).collect();
        let recording =
            Recording { names: channels.iter().map(|(_, id)| id.to_string()).collect(), times_ms, rows: degrees };
        let resampled = recording.resample(SERVO_UPDATE_MS);
        let Some((first, rest)) = resampled.split_first() else { return Ok(Vec::new()) };
        let start: Vec<i32> = first.iter().map(|value| ServoBoard.store(*value)).collect();
        for (&(_, id), &home) in channels.iter().zip(&start) {
            if let Some(servo) = self.servos.iter_mut().find(|servo| servo.id == id) {
                servo.home_deg = servo.clamp(i16::try_from(home).unwrap_or(0));
            }
        }
        let budget = Budget { tolerance: input.tolerance_deg, allowed: MAX_LIST_LEN, resolution: 0.1 };
        let fitted = fit::fit_within(&ServoBoard, &start, rest, budget)
            .map_err(|error| BuildError::Fit(fit_said(&error, 1.0, "steps")))?;
        report.converted(format!(
            "{:?}: {} samples at {fps} fps fitted into {} steps within {:.2}° (asked {}°)",
            clip.name,
            rows.len(),
            fitted.moves.len(),
            fitted.max_error,
            input.tolerance_deg
        ));
        report.approximated("the servos start the animation from its first frame: their home is set there");
        let ids: Vec<u8> = channels.iter().map(|(_, id)| *id).collect();
        let actions = fitted::servo_actions(&fitted, &ids, self.next_action_id(), &clip.name);
        let commands = actions.iter().map(|action| Command::once(Run::Action { action_id: action.id })).collect();
        self.actions.extend(actions);
        Ok(commands)
    }
}

/// The file's time and the board's, through one clip, ms from its start.
#[derive(Default)]
struct Clock {
    /// Where the file says the clip is.
    file_ms: f64,
    /// Where the board is (whole updates and whole-ms delays).
    board_ms: f64,
    /// The farthest the board has been from the file at a key's end.
    worst_ms: f64,
}

impl Clock {
    /// The whole updates (at least 1) that end a move of `move_ms` nearest the file's time.
    fn updates_to(&self, move_ms: f64) -> f64 {
        ((self.file_ms + move_ms - self.board_ms) / SERVO_UPDATE_MS).round().max(1.0)
    }

    /// The file moves on `file_ms` (0: a Maestro frame's move, or a jump, which keep no time of their own), the board `board_ms`.
    fn moved(&mut self, file_ms: f64, board_ms: f64) {
        self.file_ms += file_ms;
        self.board_ms += board_ms;
        if file_ms > 0.0 {
            self.key_ends();
        }
    }

    /// The delay (whole ms) that ends a wait of `wait_ms` at the file's time, if any.
    fn hold(&mut self, wait_ms: f64) -> Option<i32> {
        if wait_ms <= 0.0 {
            return None;
        }
        self.file_ms += wait_ms;
        let delay = (self.file_ms - self.board_ms).round();
        let delay_ms = if delay >= 1.0 {
            // Under i32::MAX ms of any real file: clamped first.
            #[allow(clippy::cast_possible_truncation)]
            let delay_ms = delay.min(f64::from(i32::MAX)) as i32;
            self.board_ms += f64::from(delay_ms);
            Some(delay_ms)
        } else {
            None
        };
        self.key_ends();
        delay_ms
    }

    fn key_ends(&mut self) {
        self.worst_ms = self.worst_ms.max((self.board_ms - self.file_ms).abs());
    }
}

/// A fit's failure in degrees, to 0.1° (`per_degree` board units a
/// degree), in the board's word for a move (`steps`, `frames`).
pub(super) fn fit_said(error: &FitError, per_degree: f64, moves: &str) -> String {
    let tenths = |value: f64| format!("{}", (value / per_degree * 10.0).round() / 10.0);
    match error {
        FitError::Tolerance { needed, allowed, tolerance, smallest } => format!(
            "{needed} {moves} are needed to stay within {}° and at most {allowed} fit: the smallest tolerance that fits is --tolerance-deg {}. Nothing was written",
            tenths(*tolerance),
            tenths(*smallest)
        ),
        FitError::TooLong { updates, needed, allowed, .. } => format!(
            "the animation lasts {updates} board updates: that takes at least {needed} {moves} at any tolerance, and at most {allowed} fit. Nothing was written"
        ),
    }
}
