//! Onsets picked again off the frame when the sensitivity changes: on an
//! hour's sound a pick takes about a tenth of a second (measured: 111–118 ms
//! in release), which a dragged sensitivity would otherwise stall the editor
//! for at every step. One worker per sound read; asks coalesce, so a drag
//! costs one pick per answer, and the newest sensitivity is always the one
//! answered last. The lane keeps the onsets it has until the new ones come.

use std::sync::Arc;

use crossbeam_channel::{Receiver, Sender};

use crate::audio::Found;
use crate::link::Waker;

/// Onsets at a sensitivity (percent), s from the sound's start.
pub type Picked = (u8, Vec<f64>);

/// The worker picking a read sound's onsets.
#[derive(Debug)]
pub struct Picking {
    ask: Sender<u8>,
    answers: Receiver<Picked>,
    /// The sensitivity asked last (none yet).
    asked: Option<u8>,
    /// No thread could be had: picked on the frame, as before there was one.
    inline: Option<(Arc<Found>, Option<Picked>)>,
}

impl Picking {
    /// A worker for `found`; it wakes the frame with each answer and ends
    /// when this is dropped.
    pub fn start(found: Arc<Found>, waker: Waker) -> Self {
        let (ask, asks) = crossbeam_channel::unbounded::<u8>();
        let (answer, answers) = crossbeam_channel::unbounded();
        let kept = Arc::clone(&found);
        let spawned = std::thread::Builder::new().name("onsets".into()).spawn(move || {
            while let Ok(mut percent) = asks.recv() {
                // Only the newest ask matters.
                while let Ok(newer) = asks.try_recv() {
                    percent = newer;
                }
                let onsets = found.onsets(f32::from(percent.min(100)) / 100.0);
                if answer.send((percent, onsets)).is_err() {
                    break;
                }
                waker();
            }
        });
        let inline = spawned.is_err().then_some((kept, None));
        Self { ask, answers, asked: None, inline }
    }

    /// The onsets at `percent` are already had (picked as the sound was read).
    #[must_use]
    pub fn holding(mut self, percent: u8) -> Self {
        self.asked = Some(percent);
        self
    }

    /// Asks for the onsets at `percent`, unless that was the last ask.
    pub fn ask(&mut self, percent: u8) {
        if self.asked != Some(percent) {
            self.asked = Some(percent);
            if let Some((found, ready)) = &mut self.inline {
                *ready = Some((percent, found.onsets(f32::from(percent.min(100)) / 100.0)));
            }
            // A worker that is gone (or never was) has nothing more to answer.
            let _ = self.ask.send(percent);
        }
    }

    /// The newest answer that came, if any.
    pub fn answer(&mut self) -> Option<Picked> {
        match &mut self.inline {
            Some((_, ready)) => ready.take(),
            None => self.answers.try_iter().last(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_newest_sensitivity_asked_is_answered_last_and_wakes_the_frame() {
        let rate = 8_000;
        let samples = crate::audio::tests::clicks(&[0.2, 0.5, 0.9], 1.2, rate);
        let mut onsets = crate::audio::Onsets::new(rate);
        onsets.push(&samples);
        let found = Arc::new(onsets.finish());
        let (woke, wakes) = crossbeam_channel::unbounded();
        let waker: Waker = Arc::new(move || {
            let _ = woke.send(());
        });
        let mut picking = Picking::start(Arc::clone(&found), waker);
        for percent in [10, 30, 50, 50, 70] {
            picking.ask(percent);
        }
        let mut last = None;
        while last.as_ref().is_none_or(|(percent, _): &Picked| *percent != 70) {
            wakes.recv_timeout(std::time::Duration::from_secs(30)).expect("an answer wakes the frame");
            if let Some(answer) = picking.answer() {
                last = Some(answer);
            }
        }
        assert_eq!(last, Some((70, found.onsets(0.7))), "the newest ask, picked as on the frame");
    }
}
