//! The show's boards held connected by the window (**Connect the boards**):
//! each device says whether it answered; while they are connected the
//! preview and record passes play on every board as on the stage, Play on
//! the boards uses these links, and STOP, a lost link the show needs,
//! Disconnect or closing the window stops them all.

use crate::ui::i18n::{Said, Worded};
use std::time::Duration;

use crate::link::Waker;
use crate::show::Show;
use crate::show::alive::Loss;
use crate::show::boards::{Boards, Heard, Held};

use super::ShowWords;

/// What a device's link is doing.
#[derive(Clone, Debug, PartialEq)]
pub enum LinkState {
    /// Being connected.
    Asking,
    /// It answered: how long a command takes to reach it.
    Answered(Duration),
    /// It did not answer: why.
    Silent(Said),
    /// Its link was lost: why.
    Lost(Loss),
}

/// The boards, connected, and what each device's link is doing.
#[derive(Debug)]
pub struct Linked {
    boards: std::sync::Arc<Boards>,
    /// A state per device, in the show's order.
    pub states: Vec<LinkState>,
    /// Whether the boards follow a preview now.
    following: bool,
    /// Whether the show plays on them now.
    pub playing: bool,
}

/// What the window does with what the boards said.
#[derive(Debug, Default, PartialEq)]
pub struct Taken {
    /// Lines for the user.
    pub said: Vec<Said>,
    /// Every device was stopped (a lost link the show needs): the preview stops too.
    pub all_stopped: bool,
}

impl Linked {
    /// Connects every device of `show` (ports as given), off the frame.
    pub fn connect(show: &Show, waker: Waker) -> std::io::Result<Self> {
        let boards = std::sync::Arc::new(Boards::connect(show, waker)?);
        Ok(Self { boards, states: vec![LinkState::Asking; show.devices.len()], following: false, playing: false })
    }

    /// Takes in what the boards said.
    pub fn poll(&mut self, show: &Show) -> Taken {
        let mut taken = Taken::default();
        let name = |index: usize| show.devices.get(index).map_or("?", |device| device.name.as_str()).to_string();
        for heard in self.boards.heard() {
            match heard {
                Heard::Linked(index, answered) => {
                    let state = match answered {
                        Ok(delay) => LinkState::Answered(delay),
                        Err(unlinked) => {
                            let why = Said::new(|language| unlinked.worded(language));
                            let device = name(index);
                            taken.said.push(super::said_by(|words| {
                                format!("{device} {}: {}", words.silent, why.in_(words.lang))
                            }));
                            LinkState::Silent(why)
                        }
                    };
                    if let Some(slot) = self.states.get_mut(index) {
                        *slot = state;
                    }
                }
                Heard::Lost { device, why, all_stopped } => {
                    let named = name(device);
                    taken.said.push(super::said_by(|words| {
                        let then = if all_stopped { words.all_stopped } else { "" };
                        format!("{named} {} ({}){then}", words.lost, why.worded(words.lang))
                    }));
                    taken.all_stopped |= all_stopped;
                    if let Some(slot) = self.states.get_mut(device) {
                        *slot = LinkState::Lost(why);
                    }
                }
                Heard::Silent(why) => taken.said.extend(super::said::told(&crate::show::boards::Told::Silent(why))),
                Heard::Played(played) => {
                    self.playing = false;
                    match played {
                        Ok(ran) => taken.said.extend(super::said::ran(&ran)),
                        Err(stopped) => taken.said.push(Said::new(|language| stopped.worded(language))),
                    }
                }
            }
        }
        if taken.all_stopped {
            self.following = false;
        }
        taken
    }

    #[cfg(any(test, feature = "test-api"))]
    /// Whether every device answered (none asking, silent or lost).
    pub fn all_answered(&self) -> bool {
        self.states.iter().all(|state| matches!(state, LinkState::Answered(_)))
    }

    /// The preview's state this frame: while it runs every board follows it
    /// at `t_ms` (`held`: the pass's device index, axis and value); once it
    /// ends they rest (bases stop, servos hold).
    pub fn follow(&mut self, show: &Show, previewing: bool, t_ms: u64, held: Option<Held>) {
        if self.playing {
            return;
        }
        match (previewing, self.following) {
            (true, false) => {
                self.boards.follow(show);
                self.boards.at(t_ms, held);
            }
            (true, true) => self.boards.at(t_ms, held),
            (false, true) => self.boards.rest(),
            (false, false) => {}
        }
        self.following = previewing;
    }

    /// Plays `show` on these boards with its sound.
    pub fn play(&mut self, show: &Show, sound: Option<std::path::PathBuf>) {
        self.playing = true;
        self.following = false;
        self.boards.play(show, sound);
    }

    /// The boards, for a remote to reach while they are held (never to keep them).
    pub fn shared(&self) -> std::sync::Weak<Boards> {
        std::sync::Arc::downgrade(&self.boards)
    }

    /// How fast a remote's pose may move a servo or a joint.
    pub fn set_speed(&self, speed: crate::device::speed::LiveSpeed) {
        self.boards.set_speed(speed);
    }

    /// Stops every device at once.
    pub fn stop(&mut self) {
        self.following = false;
        self.boards.stop();
    }
}

/// A device's link said in a word or two, and whether it is well.
pub fn state_words(state: &LinkState, words: &ShowWords) -> (String, bool) {
    match state {
        LinkState::Asking => (words.asking.to_string(), true),
        LinkState::Answered(delay) => (format!("● {} ({:.1} ms)", words.answered, delay.as_secs_f64() * 1000.0), true),
        LinkState::Silent(why) => (format!("{}: {}", words.silent, why.in_(words.lang)), false),
        LinkState::Lost(why) => (format!("{}: {}", words.lost, why.worded(words.lang)), false),
    }
}
