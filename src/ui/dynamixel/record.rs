//! A performance recorded from the servos' present positions (one sample a
//! round of readings, 50 a second) and fitted into the fewest linear steps
//! that play it back within a tolerance (the fit every family uses), checked
//! at every frame the stream plays.

use std::collections::BTreeMap;
use std::time::Instant;

use crate::authoring::fit::{Board, LinearBand, ServoBoard, fit};
use crate::project::Easing;
use crate::project::dynamixel::Step;

use super::state::{Bus, FRAME, degrees, units};

/// The tolerance a recording is fitted within unless the user set one, degrees.
pub const TOLERANCE_DEG: f64 = 1.0;

/// How the stream plays a step, frame by frame: each servo straight from
/// where it was, all arriving at the step's end; values in tenths of a degree.
#[derive(Clone, Copy, Debug, Default)]
struct Stream;

impl Board for Stream {
    fn max_updates(&self) -> usize {
        // A minute of frames.
        3000
    }

    fn store(&self, value: f64) -> i32 {
        // Tenths of a degree: within ±3600.
        #[allow(clippy::cast_possible_truncation)]
        let stored = value.round().clamp(-36_000.0, 36_000.0) as i32;
        stored
    }

    fn output(&self, from: i32, to: i32, updates: usize, k: usize) -> f64 {
        // Straight from start to end, as a servo board's servo moves over its step.
        ServoBoard.output(from, to, updates, k)
    }

    type Band = LinearBand;

    fn band(&self, from: i32, tolerance: f64) -> LinearBand {
        LinearBand::new(from, tolerance)
    }

    fn below_line(&self) -> f64 {
        0.0
    }
}

/// A recording under way. It keeps each servo's model from when it began,
/// so that a recording whose cable was pulled still fits what it holds.
#[derive(Debug)]
pub struct Recording {
    /// Where the servos were when it started.
    start: BTreeMap<u8, u32>,
    /// Each servo's model number, by ID.
    models: BTreeMap<u8, u16>,
    /// Each servo's readings, with when they came.
    heard: BTreeMap<u8, Vec<(Instant, u32)>>,
}

impl Recording {
    /// A recording of the servos on `bus`, from where they are.
    pub fn new(bus: &Bus) -> Self {
        let models = bus.servos.values().map(|servo| (servo.found.id, servo.found.model_number)).collect();
        Self { start: bus.present(), models, heard: BTreeMap::new() }
    }

    /// Servo `id` said it is at `position`.
    pub fn heard(&mut self, id: u8, position: u32, at: Instant) {
        self.heard.entry(id).or_default().push((at, position));
    }

    /// How many samples it holds (the most of any servo).
    pub fn samples(&self) -> usize {
        self.heard.values().map(Vec::len).max().unwrap_or(0)
    }

    /// The fewest steps that play it back within `tolerance_deg` at every
    /// frame (none: it holds less than two frames).
    pub fn fit(&self, tolerance_deg: f64) -> Option<Vec<Step>> {
        let ids: Vec<u8> = self.heard.keys().copied().filter(|id| self.models.contains_key(id)).collect();
        let first = self.heard.values().filter_map(|samples| samples.first().map(|(at, _)| *at)).min()?;
        let last = self.heard.values().filter_map(|samples| samples.last().map(|(at, _)| *at)).max()?;
        // Frames to the last sample, the last one at it (the hand's last place is kept).
        let frames = (last - first).as_micros().div_ceil(FRAME.as_micros());
        if frames < 2 || ids.is_empty() {
            return None;
        }
        let model = |id: u8| self.models[&id];
        // Each frame: every servo's position then, in tenths of a degree (the latest reading at or before it).
        let rows: Vec<Vec<f64>> = (1..=frames)
            .map(|k| {
                let at = (first + FRAME * u32::try_from(k).unwrap_or(u32::MAX)).min(last);
                ids.iter()
                    .map(|id| {
                        let samples = &self.heard[id];
                        let upto = samples.partition_point(|(when, _)| *when <= at);
                        let position = samples[upto.saturating_sub(1)].1;
                        degrees(model(*id), position) * 10.0
                    })
                    .collect()
            })
            .collect();
        let start: Vec<i32> = ids
            .iter()
            .map(|id| {
                let position = self.start.get(id).copied().unwrap_or(self.heard[id][0].1);
                Stream.store(degrees(model(*id), position) * 10.0)
            })
            .collect();
        // Each step's end is a whole position of its servo: half of one is kept out of the tolerance.
        let rounding = ids.iter().map(|id| (degrees(model(*id), 1) - degrees(model(*id), 0)) * 5.0).fold(0.0, f64::max);
        let fitted = fit(&Stream, &start, &rows, (tolerance_deg * 10.0 - rounding).max(0.5));
        let frame_ms = u32::try_from(FRAME.as_millis()).unwrap_or(20);
        Some(
            fitted
                .moves
                .iter()
                .map(|step| Step {
                    duration_ms: u32::try_from(step.updates).unwrap_or(u32::MAX) * frame_ms,
                    easing: Easing::Linear,
                    positions: ids
                        .iter()
                        .zip(&step.values)
                        .map(|(id, tenths)| (*id, units(model(*id), f64::from(*tenths) / 10.0)))
                        .collect(),
                })
                .collect(),
        )
    }
}
