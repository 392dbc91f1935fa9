//! The app shell's PLEN2 side: live joints, playing on the robot (stored
//! motions, play lists, or a motion streamed from any frame), captured frames,
//! and the robot operations run as jobs.

use super::*;
use crate::project::plen2::{Frame, Joint, Motion, Pose};
use crate::ui::action::Plen2Intent;
use crate::ui::plen2_job::{Plen2Job, Plen2JobKind, Plen2Outcome};
use crate::ui::plen2_joints::limits;

/// A motion played from one of its frames by streaming its poses live.
#[derive(Debug)]
pub struct Stream {
    motion: Motion,
    frame: usize,
    started: Instant,
    from: [i16; 18],
}

impl StudioApp {
    fn homes(&self) -> [i16; 18] {
        Joint::ALL.map(|joint| limits(&self.document.project.plen2, joint).home_tenths_deg)
    }

    /// Sends every joint's angle (coalesced and paced by the driver).
    fn send_pose(&mut self) {
        let moves: Vec<(u8, i16)> = Joint::ALL.iter().map(|j| (j.device_id(), self.plen2_pose[j.index()])).collect();
        if let Some(robot) = self.link.as_mut().and_then(BoardLink::plen2_mut) {
            robot.move_joints(moves);
        }
    }

    pub(super) fn set_joint(&mut self, joint: Joint, tenths: i16) {
        let setting = limits(&self.document.project.plen2, joint);
        let low = setting.min_tenths_deg.min(setting.max_tenths_deg);
        let high = setting.max_tenths_deg.max(setting.min_tenths_deg);
        // The limits clamp every move the app sends.
        let tenths = tenths.clamp(low, high);
        self.plen2_pose[joint.index()] = tenths;
        self.plen2_stream = None;
        if let Some(robot) = self.link.as_mut().and_then(BoardLink::plen2_mut) {
            robot.move_joints(vec![(joint.device_id(), tenths)]);
        }
    }

    pub(super) fn plen2_home(&mut self) {
        self.plen2_pose = self.homes();
        self.plen2_stream = None;
        if let Some(robot) = self.link.as_ref().and_then(BoardLink::plen2) {
            robot.home();
        }
    }

    pub(super) fn capture_frame(&mut self, slot: u8) {
        let homes = self.homes();
        let mut pose = Pose::default();
        for joint in Joint::ALL {
            pose.set(joint, self.plen2_pose[joint.index()].saturating_sub(homes[joint.index()]));
        }
        let mut plen2 = self.document.project.plen2.clone();
        let Some(motion) = plen2.motions.iter_mut().find(|m| m.slot == slot) else { return };
        if motion.frames.len() >= crate::project::plen2::MAX_FRAMES {
            self.report(
                self.language.problem(&crate::project::ProblemKind::OutOfRange {
                    field: "frames",
                    value: 21,
                    min: 1,
                    max: 20,
                }),
                true,
            );
            return;
        }
        motion.frames.push(Frame { transition_ms: 500, values_tenths_deg: pose });
        self.document.apply(Edit::SetPlen2(Box::new(plen2)), None);
    }

    pub(super) fn play_from(&mut self, slot: u8, frame: usize) {
        let Some(motion) = self.document.project.plen2.motions.iter().find(|m| m.slot == slot).cloned() else { return };
        self.plen2_stream = Some(Stream { motion, frame, started: Instant::now(), from: self.plen2_pose });
    }

    pub(super) fn play_list(&mut self, index: usize) {
        let Some(list) = self.document.project.plen2.play_lists.get(index) else { return };
        let entries: Vec<(u8, u8)> = list.entries.iter().map(|e| (e.slot, e.plays)).collect();
        if let Some(robot) = self.link.as_mut().and_then(BoardLink::plen2_mut) {
            robot.play_list(&entries);
        }
    }

    pub(super) fn play_motion(&mut self, slot: u8) {
        if let Some(robot) = self.link.as_mut().and_then(BoardLink::plen2_mut) {
            robot.play(slot);
        }
    }

    /// Moves the streamed motion on to `now`.
    pub(super) fn advance_stream(&mut self, now: Instant) {
        let Some(stream) = &self.plen2_stream else { return };
        let homes = self.homes();
        let elapsed = now.saturating_duration_since(stream.started).as_secs_f64() * 1000.0;
        let mut from = stream.from;
        let mut t = 0.0;
        let mut pose = None;
        for frame in stream.motion.frames.iter().skip(stream.frame) {
            let target: [i16; 18] = Joint::ALL.map(|j| homes[j.index()].saturating_add(frame.values_tenths_deg.get(j)));
            let span = f64::from(frame.transition_ms);
            if elapsed < t + span {
                let share = (elapsed - t) / span.max(1.0);
                #[allow(clippy::cast_possible_truncation)]
                let at = std::array::from_fn(|i| {
                    (f64::from(from[i]) + (f64::from(target[i]) - f64::from(from[i])) * share).round() as i16
                });
                pose = Some(at);
                break;
            }
            t += span;
            from = target;
        }
        match pose {
            Some(pose) => self.plen2_pose = pose,
            None => {
                self.plen2_pose = from;
                self.plen2_stream = None;
            }
        }
        self.send_pose();
    }

    /// Whether a motion is being streamed.
    pub fn streaming(&self) -> bool {
        self.plen2_stream.is_some()
    }

    pub(super) fn plen2_board(&mut self, intent: Plen2Intent) {
        let start = |app: &mut Self, kind: Plen2JobKind| {
            let Some(robot) = app.link.as_ref().and_then(BoardLink::plen2) else {
                app.report(app.words().msg_connect_first, true);
                return;
            };
            app.plen2_result = None;
            let backups = app.data_dir.join("backups");
            app.plen2_job = Some(Plen2Job::start(kind, robot.requester(), backups, app.waker.clone()));
        };
        match intent {
            Plen2Intent::Read => start(self, Plen2JobKind::Read),
            Plen2Intent::Upload => {
                let plen2 = self.document.project.plen2.clone();
                let document = Project { family: Family::Plen2, plen2: plen2.clone(), ..Project::default() };
                let errors: Vec<_> = crate::project::validate(&document)
                    .into_iter()
                    .filter(|p| p.severity == crate::project::Severity::Error)
                    .map(|p| format!("{}: {}", self.language.location(&p.location), self.language.problem(&p.kind)))
                    .collect();
                if errors.is_empty() {
                    start(self, Plen2JobKind::Upload(Box::new(plen2)));
                } else {
                    self.plen2_result = Some(errors.join("\n"));
                }
            }
            Plen2Intent::WriteJoints => {
                start(self, Plen2JobKind::WriteJoints(Box::new(self.document.project.plen2.clone())));
            }
            Plen2Intent::FactoryReset => start(self, Plen2JobKind::FactoryReset),
            Plen2Intent::ReadIntoProject => {
                if let Some(robot) = self.plen2_robot.clone() {
                    let mut plen2 = robot;
                    plen2.play_lists = self.document.project.plen2.play_lists.clone();
                    self.document.apply(Edit::SetPlen2(Box::new(plen2)), None);
                    self.report(self.words().read_done, false);
                }
            }
            Plen2Intent::ExportToFile(path) => {
                if let Some(robot) = self.plen2_robot.clone() {
                    let document = Project { family: Family::Plen2, plen2: robot, ..Project::default() };
                    match crate::project::save(&path, &document) {
                        Ok(()) => self.report(format!("{} {}", self.words().saved_board_to, path.display()), false),
                        Err(error) => self.report(self.language.save_error(&error), true),
                    }
                }
            }
        }
    }

    pub(super) fn poll_plen2_job(&mut self) {
        let Some(job) = &mut self.plen2_job else { return };
        let Some(outcome) = job.poll() else { return };
        self.plen2_job = None;
        self.plen2_result = Some(match outcome {
            Plen2Outcome::Read(robot) => {
                let text = format!("{} {}", self.words().robot_read, robot.motions.len());
                self.plen2_robot = Some(*robot);
                self.plen2_robot_reads += 1;
                text
            }
            Plen2Outcome::Uploaded(report) => {
                let verified =
                    report.slots.iter().filter(|(_, r)| *r == crate::device::plen2::SlotResult::Verified).count();
                let mut text = format!("{} {verified}/{}", self.words().uploaded_items, report.slots.len());
                let differing: Vec<String> = report
                    .slots
                    .iter()
                    .filter(|(_, r)| *r == crate::device::plen2::SlotResult::Differs)
                    .map(|(slot, _)| slot.to_string())
                    .collect();
                if !differing.is_empty() {
                    text.push_str(&format!("\n{} {}", self.words().slots_differ, differing.join(", ")));
                }
                if let Some(backup) = &report.backup {
                    text.push_str(&format!("\n{} {}", self.words().backup_at, backup.display()));
                }
                text
            }
            Plen2Outcome::JointsWritten(count) => format!("{}: {count}", self.words().write_joints),
            Plen2Outcome::Failed(error) => error,
            Plen2Outcome::Cancelled => self.words().cancelled.to_string(),
        });
    }
}
