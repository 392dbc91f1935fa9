//! A fit turned into what a project stores: PLEN2 frames, or servo-board
//! actions and the macro that runs them in order.

use super::fit::Fit;
use crate::project::plen2::{Frame, JOINTS, Pose};
use crate::project::{Action, Command, Macro, Run, Step};
use crate::protocol::plen2::playback::CYCLE_US;

/// A PLEN2 cycle, ms.
// 32768 µs: exact in f64.
#[allow(clippy::cast_precision_loss)]
pub const PLEN2_UPDATE_MS: f64 = CYCLE_US as f64 / 1000.0;

/// A servo-board update (the step interval's unit), ms.
pub const SERVO_UPDATE_MS: f64 = 10.0;

/// The transition a frame of `cycles` cycles is stored with: `cycles × 32` ms
/// (the firmware gives `(ms / 32) & 0xFF` cycles back).
pub fn transition_ms(cycles: usize) -> u16 {
    u16::try_from(cycles.min(255) * 32).unwrap_or(u16::MAX)
}

/// PLEN2 frames from a fit whose channels are the joints in `Joint::ALL` order.
pub fn plen2_frames(fit: &Fit) -> Vec<Frame> {
    fit.moves
        .iter()
        .map(|step| {
            let mut values = [0i16; JOINTS];
            for (value, &fitted) in values.iter_mut().zip(&step.values) {
                *value = i16::try_from(fitted).unwrap_or(0);
            }
            Frame::new(transition_ms(step.updates), Pose(values))
        })
        .collect()
}

/// Servo-board actions from a fit whose channels are `servo_ids` (one action
/// per move, every servo in it with its own interval: the move's, or
/// shorter for a servo that arrives early and holds), ids from
/// `first_id`, captioned `caption` and their number (cut to 32 bytes).
pub fn servo_actions(fit: &Fit, servo_ids: &[u8], first_id: i32, caption: &str) -> Vec<Action> {
    fit.moves
        .iter()
        .zip(first_id..)
        .enumerate()
        .map(|(index, (step, id))| Action {
            id,
            caption: caption_within(&format!("{caption} {}", index + 1), 32),
            steps: servo_ids
                .iter()
                .zip(step.values.iter().zip(&step.arrivals))
                .map(|(&servo_id, (&degree, &arrival))| {
                    Step::new(servo_id, i16::try_from(degree).unwrap_or(0), i16::try_from(arrival).unwrap_or(i16::MAX))
                })
                .collect(),
        })
        .collect()
}

/// A macro running `actions` once each, in order.
pub fn macro_running(id: i32, caption: &str, actions: &[Action]) -> Macro {
    Macro {
        id,
        caption: caption_within(caption, 32),
        commands: actions.iter().map(|action| Command::once(Run::Action { action_id: action.id })).collect(),
    }
}

/// `text` cut to at most `bytes` UTF-8 bytes, on a character boundary.
pub fn caption_within(text: &str, bytes: usize) -> String {
    let mut end = text.len().min(bytes);
    while !text.is_char_boundary(end) {
        end -= 1;
    }
    text[..end].to_string()
}
