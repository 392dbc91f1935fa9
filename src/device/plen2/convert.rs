//! A project's motion as the commands that store it, and a `<MO` reply as a motion.

use crate::authoring::bake::{DEFAULT_TOLERANCE_TENTHS, bake_plen2};
use crate::project::plen2::{Frame, LoopRange, Motion, Plen2Project, Pose};
use crate::protocol::plen2::{
    Command, DEVICE_IDS, Joint, MAX_FRAMES, MotionFrame, MotionHeader, MotionReply, NAME_LEN, SLOTS,
};

/// A motion the robot cannot store at all, whatever `--force` says: its
/// header or frames cannot be encoded (`plen2.md` §2: a header with a frame
/// count outside 1..=20 is dropped; slots are 0..=89; the name is 20 bytes of
/// printable ASCII, where `$ # > <` would start a command).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("motion {slot} {name:?} {why}")]
pub struct Unstorable {
    /// Its slot.
    pub slot: u8,
    /// Its name.
    pub name: String,
    /// What cannot be stored.
    pub why: NotStorable,
}

/// What of a motion cannot be stored.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub enum NotStorable {
    /// A frame count outside 1..=20.
    #[error("holds {0} frames; a PLEN2 motion holds 1 to {MAX_FRAMES}")]
    Frames(usize),
    /// A slot of 90 or more.
    #[error("is in a slot a PLEN2 does not have (it has 0 to {})", SLOTS - 1)]
    Slot,
    /// A name longer than 20 bytes or not printable ASCII.
    #[error("has a name a PLEN2 cannot store (at most {NAME_LEN} printable ASCII characters)")]
    Name,
}

/// Whether every motion of `project` can be stored on a robot.
pub fn storable(project: &Plen2Project) -> Result<(), Unstorable> {
    for motion in &project.motions {
        let frames = motion.frames.len();
        let why = if !(1..=MAX_FRAMES).contains(&frames) {
            NotStorable::Frames(frames)
        } else if motion.slot >= SLOTS {
            NotStorable::Slot
        } else if motion.name.len() > NAME_LEN || !motion.name.bytes().all(|byte| (0x20..0x7f).contains(&byte)) {
            NotStorable::Name
        } else {
            continue;
        };
        return Err(Unstorable { slot: motion.slot, name: motion.name.clone(), why });
    }
    Ok(())
}

/// A pose as the 24 device values of a `>MF` (unused ids 0).
pub fn device_values(pose: &Pose) -> [i16; DEVICE_IDS] {
    let mut values = [0; DEVICE_IDS];
    for joint in Joint::ALL {
        values[usize::from(joint.device_id())] = pose.get(joint);
    }
    values
}

/// `motion` as the robot stores it: its eased frames baked into straight
/// ones (`authoring::bake`, at 1°, widened when 20 frames are short); a
/// motion without curves is itself. Upload, verify, motion.json, the preview
/// and `trajectory` all use this form.
pub fn stored_motion(motion: &Motion) -> Motion {
    bake_plen2(motion, DEFAULT_TOLERANCE_TENTHS).motion
}

/// The `>MH` and every `>MF` that store `motion` (baked: [`stored_motion`])
/// in its slot. The name is space-padded to 20 bytes (validation keeps it
/// printable ASCII).
pub fn motion_commands(motion: &Motion) -> Vec<Command> {
    let stored = stored_motion(motion);
    let motion = &stored;
    let mut name = [b' '; NAME_LEN];
    for (slot, byte) in name.iter_mut().zip(motion.name.bytes()) {
        *slot = byte;
    }
    let range = motion.loop_range;
    let header = MotionHeader {
        slot: motion.slot,
        name,
        loop_on: range.is_some(),
        loop_begin: range.map_or(0, |r| r.begin_frame),
        loop_end: range.map_or(0, |r| r.end_frame),
        loop_count: range.map_or(0, |r| r.count),
        jump_on: motion.jump_slot.is_some(),
        jump_slot: motion.jump_slot.unwrap_or(0),
        frame_count: u8::try_from(motion.frames.len()).unwrap_or(u8::MAX),
    };
    let mut commands = vec![Command::Header(header)];
    // Frame indices are a byte: past 255 frames (never valid, but a file may hold them) nothing more is sent.
    for (index, frame) in (0..=u8::MAX).zip(&motion.frames) {
        commands.push(Command::Frame(Box::new(MotionFrame {
            slot: motion.slot,
            index,
            transition_ms: frame.transition_ms,
            values: device_values(&frame.values_tenths_deg),
        })));
    }
    commands
}

/// Everything that stores `project` on a robot: each joint's `>MA`, `>MI`,
/// `>HO` (max first, so a new min never exceeds an old max), then every
/// motion's `>MH` and `>MF`s. Preloads an emulated robot.
pub fn store_commands(project: &Plen2Project) -> Vec<Command> {
    let mut commands = Vec::new();
    for setting in &project.joints {
        let device = setting.joint.device_id();
        commands.push(Command::SetMax { device, angle: setting.max_tenths_deg });
        commands.push(Command::SetMin { device, angle: setting.min_tenths_deg });
        commands.push(Command::SetHome { device, angle: setting.home_tenths_deg });
    }
    for motion in &project.motions {
        commands.extend(motion_commands(motion));
    }
    commands
}

/// The frames of a reply as project frames (the unused device ids dropped).
pub fn frames_of(reply: &MotionReply) -> Vec<Frame> {
    reply
        .frames
        .iter()
        .map(|(transition_ms, values)| {
            let mut pose = Pose::default();
            for joint in Joint::ALL {
                pose.set(joint, values[usize::from(joint.device_id())]);
            }
            Frame::new(*transition_ms, pose)
        })
        .collect()
}

/// A `<MO` reply as a project motion.
pub fn motion_from_reply(reply: &MotionReply) -> Motion {
    Motion {
        slot: reply.slot,
        name: reply.name.clone(),
        frames: frames_of(reply),
        loop_range: reply.loop_range.map(|(begin_frame, end_frame, count)| LoopRange { begin_frame, end_frame, count }),
        jump_slot: reply.jump_slot,
    }
}
