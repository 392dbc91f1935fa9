//! Board operations from the board panel: compare first, then upload (or
//! upload anyway), read into the project, or export to a file, on a worker thread.

use super::*;

impl StudioApp {
    pub(super) fn start_job(&mut self, kind: JobKind) {
        let Some(link) = self.link.as_ref().and_then(BoardLink::servo) else {
            self.report(self.words().msg_connect_first, true);
            return;
        };
        self.board_result = None;
        let backups = self.data_dir.join("backups");
        self.job = Some(Job::start(
            kind,
            link.requester(),
            self.document.project.servo.clone(),
            backups,
            self.language,
            self.waker.clone(),
        ));
    }

    pub(super) fn board_compare(&mut self, intent: BoardIntent) {
        if self.job.is_some() {
            return;
        }
        if intent == BoardIntent::Upload {
            let problems = validate_servo(&self.document.project.servo);
            if has_errors(&problems) {
                let errors: Vec<_> =
                    problems.into_iter().filter(|p| p.severity == crate::project::Severity::Error).collect();
                let error = self.language.op_error(&crate::device::servo::OpError::Invalid { problems: errors });
                self.board_result = Some(BoardResult::Invalid { error });
                return;
            }
        }
        self.compare_intent = Some(intent);
        self.start_job(JobKind::Compare);
    }

    pub(super) fn board_confirm(&mut self) {
        let Some(pending) = self.pending.take() else { return };
        let board = self.compared_board.take().unwrap_or_default();
        match pending.intent {
            BoardIntent::Upload => self.start_job(JobKind::Upload { force: false }),
            BoardIntent::UploadAnyway => self.start_job(JobKind::Upload { force: true }),
            BoardIntent::ReadIntoProject => {
                // The board does not store the client-side safety limits: keep the
                // project's for servos it already knows.
                let mut board = board;
                for servo in &mut board.servos {
                    if let Some(known) = self.document.project.servo.servo(servo.id) {
                        servo.min_deg = known.min_deg;
                        servo.max_deg = known.max_deg;
                        servo.home_deg = known.home_deg;
                    }
                }
                self.pose = board.servos.iter().map(|servo| (servo.id, servo.home_deg)).collect();
                self.document.apply(Edit::ReplaceAll(Box::new(board)), None);
                self.board_result = Some(BoardResult::ReadIntoProject);
            }
            BoardIntent::ExportToFile(path) => {
                self.board_result = Some(match crate::project::save(&path, &Project::servo(board)) {
                    Ok(()) => BoardResult::Exported(path),
                    Err(error) => BoardResult::Failed { items: Vec::new(), error: error.to_string() },
                });
            }
        }
    }

    pub(super) fn poll_job(&mut self) {
        let Some(job) = &mut self.job else { return };
        let Some(outcome) = job.poll() else { return };
        let written: Vec<String> = job
            .done_items
            .iter()
            .filter(|(phase, _)| *phase == Phase::Write)
            .map(|(_, item)| self.language.item(item))
            .collect();
        self.job = None;
        match outcome {
            JobOutcome::Compared { differences, board } => {
                if let Some(intent) = self.compare_intent.take() {
                    self.pending = Some(PendingConfirm { intent, differences });
                    self.compared_board = Some(*board);
                }
            }
            JobOutcome::Uploaded(report) => {
                self.board_result = Some(BoardResult::Uploaded { items: written, backup: report.backup });
            }
            JobOutcome::Read(board) => {
                self.compared_board = Some(*board);
            }
            JobOutcome::Failed(error) => self.board_result = Some(BoardResult::Failed { items: written, error }),
            JobOutcome::Cancelled => self.board_result = Some(BoardResult::Cancelled),
        }
    }
}
