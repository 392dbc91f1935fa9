//! Motions taken back to the tools they came from: a servo project's macros as
//! a Maestro settings file's sequences, and any motion as the Blender add-on's
//! JSON (sampled at a frame rate), each through the joint map when one is given.

use std::fmt::Write as _;

use super::blender::{self, MICROSECONDS, Written};
use super::maestro::QUARTER_US;
use super::map::{JointMap, MapEntry, Target};
use super::report::Report;
use crate::device::plen2::playback::{self as plen2_playback, Playback, StoredMotions};
use crate::project::plen2::{Joint, Plen2Project};
use crate::project::{self, Easing, Macro, Run, ServoProject};
use crate::protocol::plen2::DEVICE_IDS;

/// The most frames one Maestro sequence is given (a macro's repeats are played out).
const MAX_SEQUENCE_FRAMES: usize = 10_000;
/// How deep macros running macros are followed.
const MAX_DEPTH: usize = 16;
/// The most PLEN2 cycles written (ten minutes).
const MAX_CYCLES: usize = 18_311;
/// Maestro pulse widths from 64 to 4080 µs, in quarter-µs; min and max in 64-unit steps.
const MAESTRO_RANGE: (f64, f64) = (256.0, 16320.0);

/// A motion that cannot be exported.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ExportError {
    /// Nothing to export.
    #[error("{0}")]
    Nothing(String),
    /// A servo with no Maestro channel.
    #[error("servo {servo_id}: a Maestro has channels 0..=23; give a joint map (--map) that puts it on one")]
    NoChannel {
        /// The servo.
        servo_id: u8,
    },
    /// A motion that cannot be played out.
    #[error("{0}")]
    Play(String),
}

/// How a target's degrees are written: through its map entry, or `default`
/// with the target's own number as the channel.
fn entry_for(map: Option<&JointMap>, target: Target, default_key: String, default: super::Unit) -> MapEntry {
    map.and_then(|map| map.entries.iter().find(|entry| entry.target == Some(target))).cloned().unwrap_or(MapEntry {
        source: default_key,
        name: String::new(),
        target: Some(target),
        zero: default.zero,
        per_degree: default.per_degree,
        direction: 1,
        offset_deg: 0.0,
    })
}

/// One Maestro frame being built.
struct Frame {
    duration_ms: f64,
    targets: Vec<f64>,
}

/// A servo project as a Maestro settings file: a channel per servo (its
/// limits, home and the speed its fastest step needs), a sequence per macro
/// (a frame per action, delays lengthening the frame before them).
pub fn maestro(servo: &ServoProject, map: Option<&JointMap>) -> Result<(String, Report), ExportError> {
    if servo.servos.is_empty() {
        return Err(ExportError::Nothing("the project has no servos to put on Maestro channels".into()));
    }
    let mut report = Report::default();
    let mut entries: Vec<(usize, MapEntry)> = Vec::new();
    for item in &servo.servos {
        let entry = entry_for(map, Target::Servo(item.id), item.id.to_string(), QUARTER_US);
        let channel = entry
            .source
            .parse::<usize>()
            .ok()
            .filter(|c| *c < 24)
            .ok_or(ExportError::NoChannel { servo_id: item.id })?;
        entries.push((channel, entry));
    }
    let count = [6, 12, 18, 24].into_iter().find(|n| entries.iter().all(|(c, _)| c < n)).unwrap_or(24);
    let homes: Vec<f64> = (0..count)
        .map(|channel| {
            entries
                .iter()
                .zip(&servo.servos)
                .find(|((c, _), _)| *c == channel)
                .map_or(0.0, |((_, entry), item)| entry.raw(f64::from(item.home_deg)))
        })
        .collect();
    let mut speeds = vec![0.0f64; count];
    let mut walk = |from: Option<&Macro>, report: &mut Report| {
        let mut walk =
            Walk { servo, entries: &entries, targets: homes.clone(), frames: Vec::new(), speeds: &mut speeds, report };
        match from {
            Some(item) => walk.run_macro(item, 1.0, 0),
            None => servo.actions.iter().for_each(|action| walk.action(action.id, 1.0)),
        }
        walk.frames
    };
    let mut sequences: Vec<(String, Vec<Frame>)> =
        servo.macros.iter().map(|item| (item.caption.clone(), walk(Some(item), &mut report))).collect();
    if servo.macros.is_empty() && !servo.actions.is_empty() {
        sequences.push(("actions".to_string(), walk(None, &mut report)));
        report.approximated("no macros: the actions are one sequence, a frame each, in id order");
    }
    let channels = Channels { servo, entries: &entries, homes: &homes, speeds: &speeds };
    let text = settings_xml(&channels, count, &sequences, &mut report);
    let frames: usize = sequences.iter().map(|(_, frames)| frames.len()).sum();
    report.converted(format!("{} channels, {} sequences, {frames} frames", entries.len(), sequences.len()));
    Ok((text, report))
}

/// What a settings file's channels are made from.
struct Channels<'a> {
    servo: &'a ServoProject,
    entries: &'a [(usize, MapEntry)],
    homes: &'a [f64],
    speeds: &'a [f64],
}

/// The settings file's text.
fn settings_xml(
    channels: &Channels<'_>,
    count: usize,
    sequences: &[(String, Vec<Frame>)],
    report: &mut Report,
) -> String {
    let mut text = String::from(
        "<!--Pololu Maestro servo controller settings file, http://www.pololu.com/catalog/product/1350-->\n",
    );
    text.push_str("<!--Written by Servo Studio-->\n<UscSettings version=\"1\">\n  <NeverSuspend>false</NeverSuspend>\n  <SerialMode>UART_DETECT_BAUD_RATE</SerialMode>\n  <FixedBaudRate>9600</FixedBaudRate>\n  <SerialTimeout>0</SerialTimeout>\n  <EnableCrc>false</EnableCrc>\n  <SerialDeviceNumber>12</SerialDeviceNumber>\n  <SerialMiniSscOffset>0</SerialMiniSscOffset>\n");
    let _ = writeln!(text, "  <Channels ServosAvailable=\"{count}\" ServoPeriod=\"156\">");
    for channel in 0..count {
        let _ = writeln!(text, "    <!--Channel {channel}-->");
        let found = channels.entries.iter().zip(&channels.servo.servos).find(|((c, _), _)| *c == channel);
        let Some(((_, entry), item)) = found else {
            text.push_str("    <Channel name=\"\" mode=\"Servo\" min=\"3968\" max=\"8000\" homemode=\"Off\" home=\"3968\" speed=\"0\" acceleration=\"0\" neutral=\"6000\" range=\"1905\" />\n");
            continue;
        };
        let (a, b) = (entry.raw(f64::from(item.min_deg)), entry.raw(f64::from(item.max_deg)));
        let min = ((a.min(b).max(MAESTRO_RANGE.0) / 64.0).ceil() * 64.0).min(MAESTRO_RANGE.1);
        let max = ((a.max(b).min(MAESTRO_RANGE.1) / 64.0).floor() * 64.0).max(min);
        if min != a.min(b) || max != a.max(b) {
            report.approximated("channel limits rounded inward to the Maestro's 16 µs steps (64 µs..4080 µs)");
        }
        let _ = writeln!(
            text,
            "    <Channel name=\"{}\" mode=\"Servo\" min=\"{min:.0}\" max=\"{max:.0}\" homemode=\"Goto\" home=\"{:.0}\" speed=\"{:.0}\" acceleration=\"0\" neutral=\"6000\" range=\"1905\" />",
            escape(&item.caption),
            channels.homes[channel].round(),
            channels.speeds[channel].ceil()
        );
    }
    text.push_str("  </Channels>\n  <Sequences>\n");
    for (name, frames) in sequences {
        let _ = writeln!(text, "    <Sequence name=\"{}\">", escape(name));
        for (index, frame) in frames.iter().enumerate() {
            let targets: Vec<String> = frame.targets.iter().map(|t| format!("{:.0}", t.round())).collect();
            let duration = frame.duration_ms.round();
            let _ = writeln!(
                text,
                "      <Frame name=\"Frame {index}\" duration=\"{duration:.0}\">{}</Frame>",
                targets.join(" ")
            );
        }
        text.push_str("    </Sequence>\n");
    }
    text.push_str("  </Sequences>\n  <Script ScriptDone=\"true\" />\n</UscSettings>\n");
    text
}

fn escape(text: &str) -> String {
    text.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

/// Macros played out into frames.
struct Walk<'a> {
    servo: &'a ServoProject,
    entries: &'a [(usize, MapEntry)],
    targets: Vec<f64>,
    frames: Vec<Frame>,
    speeds: &'a mut [f64],
    report: &'a mut Report,
}

impl Walk<'_> {
    fn run_macro(&mut self, item: &Macro, rate: f64, depth: usize) {
        if depth > MAX_DEPTH {
            self.report.dropped(format!("macros nested over {MAX_DEPTH} deep"));
            return;
        }
        for command in &item.commands {
            let rate = rate * f64::from(command.ratio_percent.clamp(1, 100)) / 100.0;
            for _ in 0..command.loop_count.max(1) {
                if self.frames.len() >= MAX_SEQUENCE_FRAMES {
                    self.report.dropped(format!("frames past {MAX_SEQUENCE_FRAMES} in one sequence"));
                    return;
                }
                match command.run {
                    Run::Action { action_id } => self.action(action_id, rate),
                    Run::Delay { delay_ms } => self.delay(f64::from(delay_ms.max(0)) / rate),
                    Run::Macro { macro_id } => {
                        if let Some(inner) = self.servo.macro_by_id(macro_id) {
                            self.run_macro(inner, rate, depth + 1);
                        }
                    }
                }
            }
        }
    }

    fn delay(&mut self, ms: f64) {
        match self.frames.last_mut() {
            Some(frame) => frame.duration_ms += ms,
            None => self.frames.push(Frame { duration_ms: ms, targets: self.targets.clone() }),
        }
    }

    fn action(&mut self, action_id: i32, rate: f64) {
        let Some(action) = self.servo.action(action_id) else { return };
        let longest = action.steps.iter().map(|step| step.interval_10ms.max(1)).max().unwrap_or(1);
        for step in &action.steps {
            let Some((channel, entry)) =
                self.entries.iter().find(|(_, e)| e.target == Some(Target::Servo(step.servo_id)))
            else {
                continue;
            };
            if step.interval_10ms.max(1) != longest {
                self.report.approximated("an action's steps of different lengths: its frame lasts the longest, each channel paced by its speed limit");
            }
            if step.easing != Easing::Linear {
                self.report.approximated("eased steps: a Maestro moves at its speed limit (the curve is not kept)");
            }
            let target = entry.raw(f64::from(step.degree));
            let updates = f64::from(step.interval_10ms.max(1)) / rate;
            let speed = (target - self.targets[*channel]).abs() / updates;
            self.speeds[*channel] = self.speeds[*channel].max(speed);
            self.targets[*channel] = target;
        }
        let duration_ms = f64::from(longest) * 10.0 / rate;
        self.frames.push(Frame { duration_ms, targets: self.targets.clone() });
    }
}

/// A servo macro as add-on JSON at `fps`: each servo's angle every frame.
pub fn blender_servo(
    servo: &ServoProject,
    macro_id: i32,
    fps: f64,
    map: Option<&JointMap>,
) -> Result<(String, Report), ExportError> {
    let Some(item) = servo.macro_by_id(macro_id) else {
        return Err(ExportError::Nothing(format!("there is no macro {macro_id}")));
    };
    // As the board plays it: curves baked into straight steps.
    let (stored, run) = crate::authoring::bake_servo::stored_run(servo, Run::Macro { macro_id });
    let (trajectories, end_ms) = project::trace(&stored, run, 3_600_000.0)
        .map_err(|error| ExportError::Play(format!("macro {macro_id}: {error}")))?;
    let frames = frame_count(end_ms, fps);
    let mut samples = project::Samples::new(&stored, &trajectories);
    let mut columns: Vec<Vec<f64>> = vec![Vec::with_capacity(frames); stored.servos.len()];
    for frame in 0..frames {
        // Frame numbers far below 2^52.
        #[allow(clippy::cast_precision_loss)]
        let pose = samples.at(frame as f64 * 1000.0 / fps);
        for (column, angle) in columns.iter_mut().zip(pose) {
            column.push(*angle);
        }
    }
    let targets = stored.servos.iter().map(|s| (Target::Servo(s.id), s.id.to_string(), s.caption.clone()));
    Ok(written(fps, &item.caption, &targets.collect::<Vec<_>>(), columns, map))
}

/// A PLEN2 motion (from power-up, as the robot plays it) as add-on JSON at `fps`.
pub fn blender_plen2(
    plen2: &Plen2Project,
    slot: u8,
    fps: f64,
    map: Option<&JointMap>,
) -> Result<(String, Report), ExportError> {
    let Some(motion) = plen2.motions.iter().find(|motion| motion.slot == slot) else {
        return Err(ExportError::Nothing(format!("there is no motion in slot {slot}")));
    };
    crate::device::plen2::storable(plen2)
        .map_err(|error| ExportError::Play(format!("{error}; it cannot be played")))?;
    let stored = StoredMotions::new(plen2);
    // Ten minutes of cycles at most: a motion that loops forever is cut there.
    let Playback { cycles, ended, .. } = plen2_playback::play(&stored, slot, [0; DEVICE_IDS], MAX_CYCLES);
    // Cycle counts far below 2^52.
    #[allow(clippy::cast_precision_loss)]
    let end_ms = Playback::CYCLE_MS * cycles.len().saturating_sub(1) as f64;
    let frames = frame_count(end_ms, fps);
    let mut columns: Vec<Vec<f64>> = vec![Vec::with_capacity(frames); Joint::ALL.len()];
    for frame in 0..frames {
        #[allow(clippy::cast_precision_loss, clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let cycle = ((frame as f64 * 1000.0 / fps) / Playback::CYCLE_MS + 1e-9).floor() as usize;
        // Cycle k at k × 32.768 ms, as `trajectory` writes it.
        let values = cycles.get(cycle.min(cycles.len().saturating_sub(1))).copied().unwrap_or([0; DEVICE_IDS]);
        for (column, joint) in columns.iter_mut().zip(Joint::ALL) {
            column.push(f64::from(values[usize::from(joint.device_id())]) / 10.0);
        }
    }
    let targets = Joint::ALL
        .iter()
        .map(|&joint| (Target::Joint(joint), (joint.index() + 1).to_string(), joint.name().to_string()));
    let (text, mut report) = written(fps, &motion.name, &targets.collect::<Vec<_>>(), columns, map);
    if !ended {
        report
            .approximated("a motion that never ends (a loop forever, a jump back): its first ten minutes are written");
    }
    Ok((text, report))
}

fn frame_count(end_ms: f64, fps: f64) -> usize {
    // An hour at 1000 fps at most: small and non-negative.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    // The last frame at or past the end: the final pose is always written.
    let frames = (end_ms.max(0.0) * fps / 1000.0 - 1e-9).ceil().max(0.0) as usize + 1;
    frames
}

fn written(
    fps: f64,
    name: &str,
    targets: &[(Target, String, String)],
    columns: Vec<Vec<f64>>,
    map: Option<&JointMap>,
) -> (String, Report) {
    let mut report = Report::default();
    let entries: Vec<MapEntry> =
        targets.iter().map(|(target, key, _)| entry_for(map, *target, key.clone(), MICROSECONDS)).collect();
    // One unit for the file: the first entry's (a map with mixed units is written in the first's, said once).
    let unit =
        entries.first().map_or(MICROSECONDS, |e| super::Unit { zero: e.zero, per_degree: e.per_degree, label: "" });
    if entries
        .iter()
        .any(|e| e.zero != unit.zero || e.per_degree != unit.per_degree || e.direction != 1 || e.offset_deg != 0.0)
    {
        report.approximated("the joint map's per-servo units: the file says one unit for all, so each servo's positions are written in its own and the file's unit is the first servo's");
    }
    let servos: Vec<Written<'_>> = targets
        .iter()
        .zip(&entries)
        .zip(columns)
        .map(|(((_, _, caption), entry), column)| Written {
            id: entry.source.clone(),
            name: caption,
            positions: column.iter().map(|d| entry.raw(*d)).collect(),
        })
        .collect();
    let frames = servos.first().map_or(0, |s| s.positions.len());
    report.converted(format!("{name:?}: {} servos, {frames} frames at {fps} fps", servos.len()));
    (blender::write(fps, name, unit, &servos), report)
}
