//! The emulated servo board playing what it stores, on its own clock: live and
//! stored moves start each servo's linear move; a macro's actions are laid out
//! in time (ratio and loops applied) and started when they fall due.

use std::time::{Duration, Instant};

use super::ServoSim;
use crate::protocol::servo::{ALL_SERVOS, CommandType, ServoMove};

/// The most loop turns one macro run is laid out for.
pub const MOST_TURNS: u64 = 1_000_000;
/// How far ahead one macro run is laid out.
pub const HORIZON: Duration = Duration::from_secs(24 * 3600);

/// What is left of one macro run's lay-out.
struct Plan {
    turns_left: u64,
    until: Instant,
}

impl ServoSim {
    pub(super) fn start_moves(&mut self, now: Instant, moves: &[ServoMove], speed_percent: u8) {
        for servo_move in moves {
            let targets: Vec<usize> = self
                .servos
                .iter()
                .enumerate()
                .filter(|(_, s)| {
                    (servo_move.servo_id == ALL_SERVOS || s.servo_id == servo_move.servo_id) && s.switches.is_start
                })
                .map(|(index, _)| index)
                .collect();
            let interval_ms = u64::try_from(servo_move.interval_10ms.max(0)).unwrap_or(0) * 10 * 100
                / u64::from(speed_percent.max(1));
            for index in targets {
                let state = &mut self.servos[index];
                state.from = state.angle(now);
                state.to = servo_move.degree;
                state.start = now;
                state.end = now + Duration::from_millis(interval_ms);
            }
        }
    }

    /// Lays out a macro's moves in time; returns when it ends. Nested macros
    /// beyond a small depth are ignored (the client validates against cycles).
    /// A macro of loops inside loops is laid out for its first
    /// [`MOST_TURNS`] loop turns and [`HORIZON`] at most: the emulator stays
    /// responsive where a real board would play for years.
    pub(super) fn schedule_macro(&mut self, start: Instant, macro_id: i32, speed_percent: u32, depth: u8) -> Instant {
        let mut plan = Plan { turns_left: MOST_TURNS, until: start.checked_add(HORIZON).unwrap_or(start) };
        self.schedule_within(start, macro_id, speed_percent, depth, &mut plan)
    }

    fn schedule_within(
        &mut self,
        start: Instant,
        macro_id: i32,
        speed_percent: u32,
        depth: u8,
        plan: &mut Plan,
    ) -> Instant {
        let Some(record) = self.image.macros.iter().find(|m| m.macro_id == macro_id).cloned() else {
            return start;
        };
        if depth > 8 {
            return start;
        }
        let mut at = start;
        for command in &record.commands {
            let ratio = u32::from(command.ratio_percent.max(1)) * speed_percent / 100;
            for _ in 0..command.loop_count.max(0) {
                if plan.turns_left == 0 || at > plan.until {
                    return at;
                }
                plan.turns_left -= 1;
                match command.command_type {
                    CommandType::RunAction => {
                        let Some(action) = self.image.actions.iter().find(|a| a.action_id == command.command_id) else {
                            break;
                        };
                        let scaled: Vec<ServoMove> = action.steps.clone();
                        let longest_ms = scaled
                            .iter()
                            .map(|s| u64::try_from(s.interval_10ms.max(0)).unwrap_or(0) * 10)
                            .max()
                            .unwrap_or(0);
                        self.schedule.push((at, scale_moves(&scaled, ratio.max(1))));
                        at += Duration::from_millis(longest_ms * 100 / u64::from(ratio.max(1)));
                    }
                    CommandType::Delay => {
                        at += Duration::from_millis(u64::try_from(command.command_id.max(0)).unwrap_or(0));
                    }
                    CommandType::RunMacro => {
                        at = self.schedule_within(at, command.command_id, ratio.max(1), depth + 1, plan);
                    }
                }
            }
        }
        at
    }

    pub(super) fn apply_schedule(&mut self, now: Instant) {
        let (due, later): (Vec<_>, Vec<_>) =
            std::mem::take(&mut self.schedule).into_iter().partition(|(at, _)| *at <= now);
        self.schedule = later;
        for (at, moves) in due {
            self.start_moves(at, &moves, 100);
        }
    }
}

fn scale_moves(moves: &[ServoMove], ratio_percent: u32) -> Vec<ServoMove> {
    moves
        .iter()
        .map(|m| ServoMove {
            interval_10ms: i16::try_from(i64::from(m.interval_10ms) * 100 / i64::from(ratio_percent.max(1)))
                .unwrap_or(i16::MAX),
            ..*m
        })
        .collect()
}
