//! Data derived from the document — validation, timing, trajectories, the
//! board footprint — computed once per document revision and, when that takes
//! long (a large project), off the frame path on a worker thread. The panel
//! shows the last result meanwhile, so a drag on a 500-action project costs a
//! frame what it costs on a small one; the result follows a few milliseconds
//! later.
//!
//! Where a computation runs is decided by what the last one cost, measured on
//! the wall clock — unless the context carries a [`Costing`] (tests): then
//! every computation is taken to cost that, so a test decides where they run
//! and no verdict depends on how fast the machine is.

use std::time::{Duration, Instant};

use crossbeam_channel::{Receiver, TryRecvError};

/// A computation that took less than this runs in the frame (its result shows
/// at once); one that took longer runs on a worker thread from then on.
pub const IN_FRAME_BUDGET: Duration = Duration::from_millis(1);

/// What every computation is taken to cost in one context, instead of the
/// wall clock's measure: [`Costing::IN_FRAME`] runs each in the frame (its
/// result shows at once), [`Costing::OFF_FRAME`] each on a worker.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Costing(pub Duration);

impl Costing {
    /// Every computation cheap: computed in the frame.
    pub const IN_FRAME: Self = Self(Duration::ZERO);
    /// Every computation costly: computed on a worker thread.
    pub const OFF_FRAME: Self = Self(Duration::from_secs(1));

    /// Makes every computation in `ctx` cost this from now on.
    pub fn install(self, ctx: &egui::Context) {
        ctx.data_mut(|data| data.insert_temp(Self::id(), self));
    }

    fn of(ctx: &egui::Context) -> Option<Self> {
        ctx.data(|data| data.get_temp::<Self>(Self::id()))
    }

    fn id() -> egui::Id {
        egui::Id::NULL.with("servo-studio derive costing")
    }
}

/// A value derived from the document, for a key (the revision, and whatever
/// else it depends on, such as the selected item).
#[derive(Debug)]
pub struct Derived<K, T> {
    shown: Option<(K, T)>,
    running: Option<(K, Receiver<(T, Duration)>)>,
    last_cost: Duration,
}

impl<K, T> Default for Derived<K, T> {
    fn default() -> Self {
        Self { shown: None, running: None, last_cost: Duration::ZERO }
    }
}

impl<K: Clone + PartialEq, T: Send + 'static> Derived<K, T> {
    /// The value for `key` if it is ready, else the last one computed (for an
    /// earlier key), with the key it is for; `None` before the first. When the value for `key` is
    /// missing and nothing is running, `prepare` is called (in the frame: it
    /// takes the snapshot the job needs) and the job it returns is run — in
    /// the frame if the last one was cheap, else on a worker thread that asks
    /// for a repaint when done. At most one job runs at a time: edits made
    /// meanwhile are folded into the next.
    pub fn get<J>(&mut self, ctx: &egui::Context, key: K, prepare: impl FnOnce() -> J) -> Option<(&K, &T)>
    where
        J: FnOnce() -> T + Send + 'static,
    {
        if let Some((running_key, results)) = &self.running {
            match results.try_recv() {
                Ok((value, cost)) => {
                    self.shown = Some((running_key.clone(), value));
                    self.last_cost = cost;
                    self.running = None;
                }
                Err(TryRecvError::Disconnected) => self.running = None,
                Err(TryRecvError::Empty) => {}
            }
        }
        let current = self.shown.as_ref().is_some_and(|(shown_key, _)| *shown_key == key);
        if !current && self.running.is_none() {
            let job = prepare();
            let costing = Costing::of(ctx);
            if costing.map_or(self.last_cost, |Costing(cost)| cost) < IN_FRAME_BUDGET {
                self.shown = Some((key, self.timed(job)));
            } else {
                self.spawn(ctx, key, job);
            }
        }
        self.shown.as_ref().map(|(key, value)| (key, value))
    }

    /// Whether the value shown is the one for `key`.
    #[cfg(test)]
    fn is_current(&self, key: &K) -> bool {
        self.shown.as_ref().is_some_and(|(shown_key, _)| shown_key == key)
    }

    fn timed(&mut self, job: impl FnOnce() -> T) -> T {
        let began = Instant::now();
        let value = job();
        self.last_cost = began.elapsed();
        value
    }

    fn spawn<J>(&mut self, ctx: &egui::Context, key: K, job: J)
    where
        J: FnOnce() -> T + Send + 'static,
    {
        let (results, receiver) = crossbeam_channel::bounded(1);
        let ctx = ctx.clone();
        // The job moves into the thread; if no thread can be started it is lost,
        // and the next frame computes in the frame instead.
        let started = std::thread::Builder::new().name("derive".into()).spawn(move || {
            let began = Instant::now();
            let value = job();
            // The panel may be gone (window closed): nothing to tell then.
            let _ = results.send((value, began.elapsed()));
            ctx.request_repaint();
        });
        match started {
            Ok(_) => self.running = Some((key, receiver)),
            Err(_) => self.last_cost = Duration::ZERO,
        }
    }
}

impl<T: Send + 'static> Derived<(u64, usize), T> {
    /// The value for the selected item at `revision` ([`Self::get`] with the key
    /// `(revision, selected)`), or the last one for the same item while the new
    /// one is computed; never another item's.
    pub fn for_selected<J>(
        &mut self,
        ctx: &egui::Context,
        revision: u64,
        selected: usize,
        prepare: impl FnOnce() -> J,
    ) -> Option<&T>
    where
        J: FnOnce() -> T + Send + 'static,
    {
        match self.get(ctx, (revision, selected), prepare) {
            Some(((_, of), value)) if *of == selected => Some(value),
            _ => None,
        }
    }
}

/// A revision key that changes with the interface's language too (for what
/// is derived with words in it): each revision and language its own key.
pub fn with_language(revision: u64, language: crate::ui::i18n::Language) -> u64 {
    let languages = crate::ui::i18n::Language::ALL;
    let index = languages.iter().position(|option| *option == language).unwrap_or_default();
    revision.wrapping_mul(languages.len() as u64) + index as u64
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_cheap_value_is_computed_in_the_frame_once_per_key() {
        let ctx = egui::Context::default();
        let mut derived: Derived<u64, u64> = Derived::default();
        let mut computed = 0;
        for _ in 0..3 {
            let value = derived.get(&ctx, 1, || {
                computed += 1;
                || 10
            });
            assert_eq!(value, Some((&1, &10)));
        }
        assert_eq!(computed, 1, "once per key");
        assert_eq!(derived.get(&ctx, 2, || || 20), Some((&2, &20)), "a new key: at once");
    }

    #[test]
    fn a_costing_decides_where_every_computation_runs_whatever_the_clock_says() {
        let ctx = egui::Context::default();
        Costing::IN_FRAME.install(&ctx);
        let mut derived: Derived<u64, u64> = Derived::default();
        // However long it takes, the next one is computed in the frame too.
        assert_eq!(derived.get(&ctx, 1, || costly(10)), Some((&1, &10)));
        assert_eq!(derived.get(&ctx, 2, || || 20), Some((&2, &20)), "in the frame: at once");
        Costing::OFF_FRAME.install(&ctx);
        let (release, hold) = crossbeam_channel::bounded::<()>(1);
        let value = derived.get(&ctx, 3, move || {
            move || {
                hold.recv().ok();
                30
            }
        });
        assert_eq!(value, Some((&2, &20)), "off the frame, however cheap the last one was");
        release.send(()).unwrap();
        wait_current(&ctx, &mut derived, 3);
    }

    /// A job that costs more than the frame's budget on any machine.
    fn costly(value: u64) -> impl FnOnce() -> u64 {
        move || {
            let began = Instant::now();
            while began.elapsed() < IN_FRAME_BUDGET * 3 {
                std::hint::spin_loop();
            }
            value
        }
    }

    /// Asks for `key` as frames would until its value is shown (the worker answers on its own thread).
    fn wait_current(ctx: &egui::Context, derived: &mut Derived<u64, u64>, key: u64) {
        let deadline = Instant::now() + Duration::from_secs(10);
        while !derived.is_current(&key) {
            assert!(Instant::now() < deadline, "the worker never answered");
            derived.get(ctx, key, || -> fn() -> u64 { panic!("key {key} is running") });
            std::thread::yield_now();
        }
    }

    #[test]
    fn a_costly_value_is_computed_off_the_frame_and_the_last_one_shown_meanwhile() {
        let ctx = egui::Context::default();
        let mut derived: Derived<u64, u64> = Derived::default();
        // The first computation runs in the frame and turns out costly.
        let value = derived.get(&ctx, 1, || costly(10));
        assert_eq!(value, Some((&1, &10)));
        // The next goes to a worker, held until the test lets it finish.
        let (release, hold) = crossbeam_channel::bounded::<()>(1);
        let value = derived.get(&ctx, 2, move || {
            move || {
                hold.recv().ok();
                20
            }
        });
        assert_eq!(value, Some((&1, &10)), "the last value, while the new one is computed");
        assert!(!derived.is_current(&2));
        // Another edit meanwhile starts nothing: one job at a time.
        assert_eq!(derived.get(&ctx, 3, || -> fn() -> u64 { panic!("a second job while one runs") }), Some((&1, &10)));
        release.send(()).unwrap();
        wait_current(&ctx, &mut derived, 2);
        assert_eq!(derived.get(&ctx, 2, || -> fn() -> u64 { panic!("key 2 is ready") }), Some((&2, &20)));
    }
}
