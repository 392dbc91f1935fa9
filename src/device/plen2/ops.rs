//! Operations on a PLEN2 over its paced driver: read it (version, joint
//! settings, motions in their slots), upload motions (backup of the slots
//! about to be overwritten first, then written paced so the robot loses no
//! byte, then verified by reading every written slot back), and joint settings.

use std::path::PathBuf;

use super::Plen2Requester;
use super::convert::{motion_commands, motion_from_reply};
use super::driver::ReplyError;
use crate::device::{Cancel, UploadFailure};
use crate::project::plen2::{JointSetting, Motion, Plen2Project};
use crate::project::{self, Problems, Project};
use crate::protocol::plen2::{
    Command, FACTORY_LIMIT_TENTHS_DEG, Joint, SLOTS, decode_joint_settings, decode_motion, decode_version,
};

pub use crate::device::Phase as Plen2Phase;

/// What a PLEN2 operation works on, as data (the interface words it in its
/// own language); `Display` gives English.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Plen2Item {
    /// The firmware's version (`<VI`).
    Version,
    /// The joint settings (`<JS`, `>HO`/`>MA`/`>MI`).
    JointSettings,
    /// One joint's settings.
    Joint(Joint),
    /// A slot, with its motion's name when known.
    Slot {
        /// The slot.
        slot: u8,
        /// The motion's name ("" when not known).
        name: String,
    },
    /// Reading a reply to see how the link delivers.
    Link,
    /// A slot found never written while it is read: the robot prints its
    /// erased memory before it reads anything else, which takes long on a slow link.
    Erased {
        /// The slot.
        slot: u8,
        /// How much longer that takes, once the rate it comes at tells.
        remaining: Option<std::time::Duration>,
    },
    /// Telling the pacing a read-back differed.
    Pacing,
    /// The factory reset of the joint settings (`>JS`).
    FactoryReset,
    /// The end of the operation.
    Done,
}

impl std::fmt::Display for Plen2Item {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Version => write!(f, "version"),
            Self::JointSettings => write!(f, "joint settings"),
            Self::Joint(joint) => write!(f, "joint {}", joint.name()),
            Self::Slot { slot, name } if name.is_empty() => write!(f, "slot {slot}"),
            Self::Slot { slot, name } => write!(f, "slot {slot} {name:?}"),
            Self::Link => write!(f, "the link"),
            Self::Erased { slot, remaining } => {
                write!(
                    f,
                    "slot {slot} was never written: the robot prints all of its erased memory (about 300 KB) before it reads anything else"
                )?;
                match remaining {
                    Some(left) => write!(f, "; about {} s more on this link", left.as_secs().max(1)),
                    None => Ok(()),
                }
            }
            Self::Pacing => write!(f, "pacing"),
            Self::FactoryReset => write!(f, "factory joint settings"),
            Self::Done => write!(f, "done"),
        }
    }
}

/// How far a PLEN2 operation has come.
pub type Plen2Progress = crate::device::Progress<Plen2Item>;

/// An operation failed; each message says what failed and what to try.
#[derive(Debug, thiserror::Error)]
pub enum Plen2OpError {
    /// The robot did not answer (or the link ended).
    #[error("{item}: {source}")]
    Reply {
        /// What was being done.
        item: Plen2Item,
        /// Why.
        source: ReplyError,
    },
    /// The robot's answer could not be read.
    #[error("{item}: the device answers, but not in the PLEN2's protocol: is it a PLEN2 with firmware 1.4.x?")]
    Unreadable {
        /// What was being read.
        item: Plen2Item,
    },
    /// The project has errors; nothing was written.
    #[error(
        "the project has {} error(s); nothing was written:\n{}\nFix them, or write it as it is with --force",
        .problems.errors(),
        .problems.listed(20)
    )]
    Invalid {
        /// The errors.
        problems: Problems,
    },
    /// The backup could not be saved; nothing was written.
    #[error("backup failed, so nothing was written: {0}")]
    Backup(project::SaveError),
    /// A motion the robot cannot store, even with --force; nothing was written.
    #[error("{0}; nothing was written")]
    Unstorable(#[from] super::Unstorable),
    /// The owner cancelled.
    #[error("cancelled")]
    Cancelled,
}

fn check(cancel: &Cancel) -> Result<(), Plen2OpError> {
    if cancel.is_requested() { Err(Plen2OpError::Cancelled) } else { Ok(()) }
}

fn slot_item(slot: u8, name: &str) -> Plen2Item {
    Plen2Item::Slot { slot, name: name.to_string() }
}

/// Reads one slot: `None` when it was never written (its garbage is drained).
pub fn read_slot(requester: &Plen2Requester, slot: u8) -> Result<Option<Motion>, Plen2OpError> {
    read_slot_noting(requester, slot, &mut |_| {})
}

/// Reads one slot as [`read_slot`] does; when its reply shows the slot was
/// never written, `erased` is told (and told again with how long the rest
/// takes, once that is known).
pub fn read_slot_noting(
    requester: &Plen2Requester,
    slot: u8,
    erased: &mut dyn FnMut(Option<std::time::Duration>),
) -> Result<Option<Motion>, Plen2OpError> {
    let mut news = |news: super::ReplyNews| match news {
        super::ReplyNews::Erased { remaining } => erased(remaining),
    };
    match requester.get_noting(Command::GetMotion { slot }, &mut news) {
        Ok(bytes) => Ok(decode_motion(&bytes).map(|reply| motion_from_reply(&reply))),
        Err(ReplyError::Garbage { .. }) => Ok(None),
        Err(source) => Err(Plen2OpError::Reply { item: slot_item(slot, ""), source }),
    }
}

/// Reads the joint settings of the 18 joints.
pub fn read_joint_settings(requester: &Plen2Requester) -> Result<Vec<JointSetting>, Plen2OpError> {
    let item = Plen2Item::JointSettings;
    let bytes = requester
        .get(Command::GetJointSettings)
        .map_err(|source| Plen2OpError::Reply { item: item.clone(), source })?;
    let entries = decode_joint_settings(&bytes).ok_or(Plen2OpError::Unreadable { item })?;
    Ok(Joint::ALL
        .iter()
        .filter_map(|joint| {
            let entry = entries.iter().find(|e| e.device == joint.device_id())?;
            Some(JointSetting {
                joint: *joint,
                min_tenths_deg: entry.min,
                max_tenths_deg: entry.max,
                home_tenths_deg: entry.home,
            })
        })
        .collect())
}

/// The robot at a glance.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Plen2Info {
    /// "PLEN2 Cytisus 1.4.2".
    pub version: String,
    /// The joint settings.
    pub joints: Vec<JointSetting>,
}

/// Reads the version and the joint settings.
pub fn info(requester: &Plen2Requester) -> Result<Plen2Info, Plen2OpError> {
    let item = Plen2Item::Version;
    let bytes =
        requester.get(Command::GetVersion).map_err(|source| Plen2OpError::Reply { item: item.clone(), source })?;
    let version = decode_version(&bytes).ok_or(Plen2OpError::Unreadable { item })?;
    Ok(Plen2Info {
        version: format!("{} {} {}", version.device, version.codename, version.version),
        joints: read_joint_settings(requester)?,
    })
}

/// Reads the version, the joint settings and `slots` into a project (unwritten slots skipped).
pub fn export(
    requester: &Plen2Requester,
    slots: &[u8],
    progress: &mut dyn FnMut(&Plen2Progress),
    cancel: &Cancel,
) -> Result<Plen2Project, Plen2OpError> {
    let total = slots.len() + 1;
    let mut step =
        |done: usize, item: Plen2Item| progress(&Plen2Progress { phase: Plen2Phase::Read, done, total, item });
    step(0, Plen2Item::JointSettings);
    let joints = info(requester)?.joints;
    let mut motions = Vec::new();
    for (index, &slot) in slots.iter().enumerate() {
        check(cancel)?;
        step(index + 1, slot_item(slot, ""));
        let mut erased = |remaining| step(index + 1, Plen2Item::Erased { slot, remaining });
        if let Some(motion) = read_slot_noting(requester, slot, &mut erased)? {
            motions.push(motion);
        }
    }
    step(total, Plen2Item::Done);
    Ok(Plen2Project { joints, motions, play_lists: Vec::new() })
}

/// How to import.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Plen2ImportOptions {
    /// Where to save the slots about to be overwritten; `None` = no backup.
    pub backup_dir: Option<PathBuf>,
    /// Read every written slot back and compare.
    pub verify: bool,
    /// Write despite validation errors (what cannot be encoded is still refused).
    pub force: bool,
}

/// One slot's outcome.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum SlotResult {
    /// Written and read back identical.
    Verified,
    /// Written (not verified).
    Written,
    /// Read back different: the robot holds something else.
    Differs,
}

/// What an import did.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Plen2ImportReport {
    /// Where the overwritten slots were saved.
    pub backup: Option<PathBuf>,
    /// Each motion's slot and outcome, in order.
    pub slots: Vec<(u8, SlotResult)>,
    /// Joint settings written (device, what).
    pub joint_writes: usize,
    /// Slot writes repeated because a read-back differed (each repeat counted).
    pub rewritten: usize,
}

impl Plen2ImportReport {
    /// Whether every slot verified (or was written, without verification).
    pub fn all_good(&self) -> bool {
        self.slots.iter().all(|(_, result)| *result != SlotResult::Differs)
    }
}

/// What to import: motions always; joint settings only when the project holds them.
pub type Plen2Import = Plen2Project;

/// Writes joint settings that differ from the robot's (max and min before home,
/// so home never falls outside them); returns how many commands were sent.
pub fn write_joint_settings(
    requester: &Plen2Requester,
    wanted: &[JointSetting],
    current: &[JointSetting],
) -> Result<usize, Plen2OpError> {
    let mut writes = 0;
    for setting in wanted {
        let device = setting.joint.device_id();
        let now = current.iter().find(|c| c.joint == setting.joint);
        let differs = |pick: fn(&JointSetting) -> i16| now.is_none_or(|now| pick(now) != pick(setting));
        let mut commands = Vec::new();
        let set_max =
            differs(|s| s.max_tenths_deg).then_some(Command::SetMax { device, angle: setting.max_tenths_deg });
        let set_min =
            differs(|s| s.min_tenths_deg).then_some(Command::SetMin { device, angle: setting.min_tenths_deg });
        // The robot refuses a max at or below its current min (and a min at or above its
        // max, plen2.md §3): a range moved wholly below the current one sets its min first.
        let current_min = now.map_or(-FACTORY_LIMIT_TENTHS_DEG, |now| now.min_tenths_deg);
        if setting.max_tenths_deg > current_min {
            commands.extend(set_max.into_iter().chain(set_min));
        } else {
            commands.extend(set_min.into_iter().chain(set_max));
        }
        if differs(|s| s.home_tenths_deg) {
            commands.push(Command::SetHome { device, angle: setting.home_tenths_deg });
        }
        for command in commands {
            requester
                .send(command)
                .map_err(|source| Plen2OpError::Reply { item: Plen2Item::Joint(setting.joint), source })?;
            writes += 1;
        }
    }
    Ok(writes)
}

/// The file a PLEN2 backup gets: `plen2-backup-YYYYMMDD-HHMMSS.json` (local time), with a
/// counter if that name is taken.
pub fn plen2_backup_path(folder: &std::path::Path) -> PathBuf {
    crate::device::backup_path(folder, "plen2-backup", "")
}

/// How many times a slot that read back different is written again.
pub const REWRITE_ROUNDS: usize = 3;

/// A failed upload: the error, and what it left on the robot.
pub type Plen2ImportFailure = UploadFailure<Plen2OpError, Plen2Item>;

/// Uploads `project`'s motions (and its joint settings, if it holds them and they differ):
/// validates, backs up the slots about to be overwritten, writes paced, verifies.
/// A failure says what it left: nothing written, what reached the robot, or everything.
pub fn import(
    requester: &Plen2Requester,
    project: &Plen2Project,
    options: &Plen2ImportOptions,
    progress: &mut dyn FnMut(&Plen2Progress),
    cancel: &Cancel,
) -> Result<Plen2ImportReport, Box<Plen2ImportFailure>> {
    let steps = Upload {
        requester,
        project,
        options,
        progress,
        cancel,
        current_joints: Vec::new(),
        results: Vec::new(),
        joint_writes: 0,
        rewritten: 0,
    };
    crate::device::upload(steps)
}

/// A PLEN2's upload, step by step (run by [`crate::device::upload`]).
struct Upload<'a> {
    requester: &'a Plen2Requester,
    project: &'a Plen2Project,
    options: &'a Plen2ImportOptions,
    progress: &'a mut dyn FnMut(&Plen2Progress),
    cancel: &'a Cancel,
    /// The robot's joint settings before the upload (read by the check or the backup).
    current_joints: Vec<JointSetting>,
    results: Vec<(u8, SlotResult)>,
    joint_writes: usize,
    rewritten: usize,
}

impl Upload<'_> {
    fn slots(&self) -> Vec<u8> {
        self.project.motions.iter().map(|m| m.slot).filter(|slot| *slot < SLOTS).collect()
    }
}

impl crate::device::UploadSteps for Upload<'_> {
    type Error = Plen2OpError;
    type Item = Plen2Item;
    type Report = Plen2ImportReport;

    fn check(&mut self) -> Result<(), Plen2OpError> {
        super::storable(self.project)?;
        let document = Project { family: project::Family::Plen2, plen2: self.project.clone(), ..Project::default() };
        let problems = project::validate(&document).errors_only();
        if problems.has_errors() && !self.options.force {
            return Err(Plen2OpError::Invalid { problems });
        }
        // Something is read before anything is written: once a session, when
        // the adaptive pacing has not learned the link yet, a probe (short
        // getters' round trips, the joint settings); then the backup, or the
        // joint settings when the project holds some. Replies show how the
        // link delivers before the first byte of the upload.
        let item = Plen2Item::Link;
        self.requester.probe().map_err(|source| Plen2OpError::Reply { item, source })?;
        if self.options.backup_dir.is_none() && !self.project.joints.is_empty() {
            self.current_joints = read_joint_settings(self.requester)?;
        }
        Ok(())
    }

    fn back_up(&mut self) -> Result<Option<PathBuf>, Plen2OpError> {
        let Some(folder) = &self.options.backup_dir else { return Ok(None) };
        let mut saved = export(self.requester, &self.slots(), &mut *self.progress, self.cancel)?;
        saved.play_lists.clear();
        self.current_joints = saved.joints.clone();
        let path = plen2_backup_path(folder);
        let document = Project { family: project::Family::Plen2, plen2: saved, ..Project::default() };
        project::save(&path, &document).map_err(Plen2OpError::Backup)?;
        Ok(Some(path))
    }

    fn write(&mut self, reached: &mut Vec<Plen2Item>) -> Result<(), Plen2OpError> {
        let (requester, project, current) = (self.requester, self.project, &self.current_joints);
        let results = &mut self.results;
        self.joint_writes = write_all(requester, project, current, reached, results, &mut *self.progress, self.cancel)?;
        Ok(())
    }

    fn total(&self) -> usize {
        self.project.motions.len() + usize::from(!self.project.joints.is_empty())
    }

    fn verify(&mut self) -> Result<(), Plen2OpError> {
        if !self.options.verify {
            return Ok(());
        }
        let (requester, motions) = (self.requester, &self.project.motions);
        verify(requester, motions, &mut self.results, &mut *self.progress, self.cancel)?;
        rewrite(requester, motions, &mut self.results, &mut self.rewritten, &mut *self.progress, self.cancel)
    }

    fn report(self, backup: Option<PathBuf>) -> Plen2ImportReport {
        Plen2ImportReport { backup, slots: self.results, joint_writes: self.joint_writes, rewritten: self.rewritten }
    }
}

/// Writes the joint settings (where they differ) and every motion; `reached`
/// names each part the robot was sent whole. Returns the joint writes.
fn write_all(
    requester: &Plen2Requester,
    project: &Plen2Project,
    current_joints: &[JointSetting],
    reached: &mut Vec<Plen2Item>,
    results: &mut Vec<(u8, SlotResult)>,
    progress: &mut dyn FnMut(&Plen2Progress),
    cancel: &Cancel,
) -> Result<usize, Plen2OpError> {
    let mut joint_writes = 0;
    if !project.joints.is_empty() {
        check(cancel)?;
        joint_writes = write_joint_settings(requester, &project.joints, current_joints)?;
        reached.push(Plen2Item::JointSettings);
    }
    // Each motion is queued while the robot still writes the one before (no
    // gap between them on the line); it counts as reached once the robot
    // should have finished it. A cancel stops after the motion under way.
    let total = project.motions.len();
    let mut under_way: Option<(usize, super::Finished)> = None;
    for (index, motion) in project.motions.iter().enumerate() {
        if let Err(cancelled) = check(cancel) {
            motion_reached(project, under_way.take(), reached, results, progress)?;
            return Err(cancelled);
        }
        let finished = queue_motion(requester, motion, index, total, progress)?;
        motion_reached(project, under_way.replace((index, finished)), reached, results, progress)?;
    }
    motion_reached(project, under_way, reached, results, progress)?;
    Ok(joint_writes)
}

/// Waits until the robot should have finished writing `under_way` (a motion's
/// index and its last command), then counts it reached and written.
fn motion_reached(
    project: &Plen2Project,
    under_way: Option<(usize, super::Finished)>,
    reached: &mut Vec<Plen2Item>,
    results: &mut Vec<(u8, SlotResult)>,
    progress: &mut dyn FnMut(&Plen2Progress),
) -> Result<(), Plen2OpError> {
    let Some((index, finished)) = under_way else { return Ok(()) };
    let motion = &project.motions[index];
    let item = slot_item(motion.slot, &motion.name);
    finished.wait().map_err(|source| Plen2OpError::Reply { item: item.clone(), source })?;
    reached.push(item.clone());
    results.push((motion.slot, SlotResult::Written));
    let total = project.motions.len();
    progress(&Plen2Progress { phase: Plen2Phase::Write, done: index + 1, total, item });
    Ok(())
}

/// A slot that reads back different is written again (a byte lost on a busy
/// USB line, or a host too loaded to keep the pace), up to
/// [`REWRITE_ROUNDS`] times, each checked again; what still differs is reported.
fn rewrite(
    requester: &Plen2Requester,
    motions: &[Motion],
    results: &mut [(u8, SlotResult)],
    rewritten: &mut usize,
    progress: &mut dyn FnMut(&Plen2Progress),
    cancel: &Cancel,
) -> Result<(), Plen2OpError> {
    let total = motions.len();
    for _ in 0..REWRITE_ROUNDS {
        let differing: Vec<usize> =
            (0..results.len()).filter(|index| results[*index].1 == SlotResult::Differs).collect();
        if !differing.is_empty() {
            // Bytes were lost on the way: write again with wider margins.
            requester.read_back_differed().map_err(|source| Plen2OpError::Reply { item: Plen2Item::Pacing, source })?;
        }
        for index in differing {
            check(cancel)?;
            write_motion(requester, &motions[index], index, total, progress)?;
            *rewritten += 1;
            let back = read_slot(requester, motions[index].slot)?;
            results[index].1 =
                if back.as_ref() == Some(&motions[index]) { SlotResult::Verified } else { SlotResult::Differs };
        }
    }
    Ok(())
}

/// Writes one motion and waits until the robot should have finished it.
fn write_motion(
    requester: &Plen2Requester,
    motion: &Motion,
    index: usize,
    total: usize,
    progress: &mut dyn FnMut(&Plen2Progress),
) -> Result<(), Plen2OpError> {
    let item = slot_item(motion.slot, &motion.name);
    let finished = queue_motion(requester, motion, index, total, progress)?;
    finished.wait().map_err(|source| Plen2OpError::Reply { item: item.clone(), source })?;
    progress(&Plen2Progress { phase: Plen2Phase::Write, done: index + 1, total, item });
    Ok(())
}

/// Queues one motion's commands; the answer tells when the robot should have
/// finished its last.
fn queue_motion(
    requester: &Plen2Requester,
    motion: &Motion,
    index: usize,
    total: usize,
    progress: &mut dyn FnMut(&Plen2Progress),
) -> Result<super::Finished, Plen2OpError> {
    let item = slot_item(motion.slot, &motion.name);
    progress(&Plen2Progress { phase: Plen2Phase::Write, done: index, total, item: item.clone() });
    let failed = |source| Plen2OpError::Reply { item: item.clone(), source };
    let mut commands = motion_commands(motion);
    let Some(last) = commands.pop() else { return Err(Plen2OpError::Unreadable { item }) };
    for command in commands {
        requester.send(command).map_err(failed)?;
    }
    requester.send_then_finished(last).map_err(failed)
}

fn verify(
    requester: &Plen2Requester,
    motions: &[Motion],
    results: &mut [(u8, SlotResult)],
    progress: &mut dyn FnMut(&Plen2Progress),
    cancel: &Cancel,
) -> Result<(), Plen2OpError> {
    let total = motions.len();
    for (index, motion) in motions.iter().enumerate() {
        check(cancel)?;
        let item = slot_item(motion.slot, &motion.name);
        progress(&Plen2Progress { phase: Plen2Phase::Verify, done: index, total, item: item.clone() });
        let back = read_slot(requester, motion.slot)?;
        let stored = super::convert::stored_motion(motion);
        results[index].1 = if back.as_ref() == Some(&stored) { SlotResult::Verified } else { SlotResult::Differs };
        progress(&Plen2Progress { phase: Plen2Phase::Verify, done: index + 1, total, item });
    }
    Ok(())
}
