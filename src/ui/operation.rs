//! One runner for every family's long board operation, on a worker thread so
//! the window never freezes: progress and the outcome come back over
//! channels, a cancel message stops it between two steps. Outcomes are typed
//! (the family's own), and turned into words only when shown.

use crossbeam_channel::{Receiver, Sender};

use crate::device::{Cancel, Phase, Progress};
use crate::link::Waker;

/// How far an operation has come; `I` is what a step works on (the family's item).
pub type Step<I> = Progress<I>;

/// A running operation; `K` is what it does, `O` its outcome and `I` what
/// each step works on — all the family's own.
#[derive(Debug)]
pub struct Operation<K, O, I> {
    /// What it does (the family says).
    pub kind: K,
    /// The latest progress.
    pub progress: Option<Step<I>>,
    /// Every item finished so far, in order, with the phase it belonged to.
    pub done_items: Vec<(Phase, I)>,
    progress_rx: Receiver<Step<I>>,
    outcome_rx: Receiver<O>,
    cancel: Sender<()>,
}

impl<K, O: Send + 'static, I: Clone + Send + 'static> Operation<K, O, I> {
    /// Runs `work` on a worker thread; `waker` is called after each step and at the end.
    /// `failed` is the outcome when no thread can be started.
    pub fn start(
        kind: K,
        waker: Waker,
        work: impl FnOnce(&mut dyn FnMut(Step<I>), &Cancel) -> O + Send + 'static,
        failed: impl FnOnce(std::io::Error) -> O,
    ) -> Self {
        let (progress_tx, progress_rx) = crossbeam_channel::unbounded();
        let (outcome_tx, outcome_rx) = crossbeam_channel::bounded(1);
        let (cancel, token) = Cancel::new();
        let spawned = std::thread::Builder::new().name("board operation".into()).spawn(move || {
            let mut report = |step: Step<I>| {
                let _ = progress_tx.send(step);
                waker();
            };
            let outcome = work(&mut report, &token);
            let _ = outcome_tx.send(outcome);
            waker();
        });
        let outcome_rx = match spawned {
            Ok(_) => outcome_rx,
            Err(error) => {
                // No thread: that is the operation's outcome.
                let (tx, rx) = crossbeam_channel::bounded(1);
                let _ = tx.send(failed(error));
                rx
            }
        };
        Self { kind, progress: None, done_items: Vec::new(), progress_rx, outcome_rx, cancel }
    }

    /// Asks the operation to stop after its current step.
    pub fn cancel(&self) {
        let _ = self.cancel.try_send(());
    }

    /// Takes in progress; returns the outcome once the operation has ended.
    pub fn poll(&mut self) -> Option<O> {
        for step in self.progress_rx.try_iter() {
            let finished_one =
                self.progress.as_ref().is_none_or(|last| step.done > last.done || step.phase != last.phase);
            if finished_one && step.done > 0 {
                self.done_items.push((step.phase, step.item.clone()));
            }
            self.progress = Some(step);
        }
        self.outcome_rx.try_recv().ok()
    }

    /// Like [`poll`](Self::poll), waiting up to `timeout` for the outcome
    /// (only when the editor ends: a frame never waits).
    pub fn wait(&mut self, timeout: std::time::Duration) -> Option<O> {
        if let Some(outcome) = self.poll() {
            return Some(outcome);
        }
        let outcome = self.outcome_rx.recv_timeout(timeout).ok();
        let _ = self.poll();
        outcome
    }

    /// The fraction done of the part running, for a progress bar.
    pub fn fraction(&self) -> f32 {
        self.progress.as_ref().map_or(0.0, |step| {
            // Step counts are small: exact in f32.
            #[allow(clippy::cast_precision_loss)]
            let fraction = if step.total == 0 { 0.0 } else { step.done as f32 / step.total as f32 };
            fraction
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::device::servo::Item;

    #[test]
    fn progress_and_the_outcome_come_back_and_cancel_reaches_the_work() {
        let (go, gate) = crossbeam_channel::bounded::<()>(0);
        let mut operation = Operation::start(
            "count",
            crate::link::no_waker(),
            move |report, cancel| {
                for done in 1..=3 {
                    report(Step { phase: Phase::Write, done, total: 3, item: Item::ProjectId });
                }
                // Wait for the test to cancel, then say whether it was seen.
                let _ = gate.recv();
                cancel.is_requested()
            },
            |_| false,
        );
        operation.cancel();
        go.send(()).unwrap();
        let outcome = operation.outcome_rx.recv_timeout(std::time::Duration::from_secs(5)).unwrap();
        assert_eq!(operation.poll(), None, "the outcome is taken once");
        assert!(outcome, "the work saw the cancel");
        assert_eq!(operation.done_items.len(), 3);
        assert!((operation.fraction() - 1.0).abs() < f32::EPSILON);
    }
}
