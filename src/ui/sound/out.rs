//! The sound output, driven off the frame. Every call that can wait on the
//! sound server — connecting, making, starting and deleting a stream,
//! decoding the first half second, seeking — runs on one thread of its own;
//! the frame sends it a request and reads its answer when it comes. A
//! request the output does not answer within [`ANSWER_WITHIN`] (beyond the
//! time it may take by design) marks the output gone: "no sound output (the
//! server at … did not answer in 2 s)" is said once and the motion plays on;
//! a board start that waited for the sound goes out then. STOP never waits:
//! it cancels a start still waiting and asks the thread to stop the sound.

use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use crossbeam_channel::{Receiver, Sender};

use crate::audio::output::{OutputError, Playing, Speakers};
use crate::link::Waker;

/// How long the output may take to answer beyond what a request takes by design.
pub const ANSWER_WITHIN: Duration = Duration::from_secs(2);

/// A board's start, run once: by the thread when the sound's point is due,
/// or by the frame when the output did not answer (or there is none).
pub type BoardStart = Arc<Mutex<Option<Box<dyn FnOnce() + Send>>>>;

/// A board's start carried by a request, and its cancel flag.
type Carried = (BoardStart, Arc<AtomicBool>);

/// Runs a board's start unless it ran already or was cancelled.
fn start_once(start: &BoardStart, cancelled: &AtomicBool) {
    let taken = start.lock().ok().and_then(|mut start| start.take());
    if let Some(start) = taken
        && !cancelled.load(Ordering::SeqCst)
    {
        start();
    }
}

/// What the frame asks of the output.
enum Request {
    /// Play `file` from `from_s` (for `only` at most).
    Play { file: PathBuf, from_s: f64, only: Option<Duration> },
    /// Play `file` so that `sound_s` is heard as the board starts, the start
    /// going out `link_delay` before (see `audio::together`).
    WithBoard { file: PathBuf, sound_s: f64, link_delay: Duration, start: BoardStart, cancelled: Arc<AtomicBool> },
    /// Stop what plays.
    Silence,
}

/// What the output answers.
enum Answer {
    /// The output was reached (what was asked is under way).
    Connected,
    /// Playing: this flag is set when the sound (or grain) has ended.
    Playing(Arc<AtomicBool>),
    /// It could not play: why, in words (no output, a stream refused).
    Failed { why: String, no_output: bool },
}

/// Whether the output has been reached.
#[derive(Clone, Debug, PartialEq, Eq)]
enum Reach {
    /// Not yet asked (it is connected on the first sound).
    Unasked,
    /// Connected.
    Ready,
    /// None, or it stopped answering: the motion plays on without sound.
    Gone,
}

/// The output as the frame holds it.
pub struct SoundOut {
    requests: Sender<Request>,
    answers: Receiver<Answer>,
    reach: Reach,
    /// A request sent and not yet answered: since when, how long it may take
    /// by design, and the board start it carries (run here if it times out).
    waiting: Option<(Instant, Duration, Option<Carried>)>,
    /// The sound playing: set when it has ended (None: nothing plays).
    ended: Option<Arc<AtomicBool>>,
    /// Asked to play and not yet answered (the cursor plays meanwhile).
    asked: bool,
    /// Where the sound server is, when not the environment's (tests).
    server: Option<PathBuf>,
}

impl std::fmt::Debug for SoundOut {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SoundOut").field("reach", &self.reach).finish_non_exhaustive()
    }
}

impl SoundOut {
    /// An output on the environment's sound server, or on the one at `server`.
    pub fn new(server: Option<PathBuf>, waker: Waker) -> Self {
        let (requests, asked) = crossbeam_channel::unbounded();
        let (answer, answers) = crossbeam_channel::unbounded();
        let to = server.clone();
        let spawned = std::thread::Builder::new()
            .name("sound output".into())
            .spawn(move || Worker { server: to, speakers: None, playing: None }.run(&asked, &answer, &waker));
        let reach = if spawned.is_ok() { Reach::Unasked } else { Reach::Gone };
        Self { requests, answers, reach, waiting: None, ended: None, asked: false, server }
    }

    /// Whether sound may play (not known gone).
    pub fn available(&self) -> bool {
        self.reach != Reach::Gone
    }

    /// Whether sound plays now (or was asked to and has not been refused).
    pub fn is_playing(&self) -> bool {
        self.asked || self.ended.as_ref().is_some_and(|ended| !ended.load(Ordering::Relaxed))
    }

    fn send(&mut self, request: Request, takes: Duration, start: Option<Carried>) {
        if self.requests.send(request).is_err() {
            self.reach = Reach::Gone;
            return;
        }
        // The first answer counts from the oldest request not yet answered.
        let since = self.waiting.as_ref().map_or_else(Instant::now, |(since, ..)| *since);
        let carried = start.or_else(|| self.waiting.take().and_then(|(_, _, start)| start));
        self.waiting = Some((since, takes, carried));
    }

    /// Plays `file` from `from_s` (for `only` at most).
    pub fn play(&mut self, file: PathBuf, from_s: f64, only: Option<Duration>) {
        if self.reach == Reach::Gone {
            return;
        }
        self.ended = None;
        self.asked = true;
        self.send(Request::Play { file, from_s, only }, Duration::ZERO, None);
    }

    /// Plays `file` with the board (see [`Request::WithBoard`]); false when
    /// there is no output (the caller starts the board alone).
    pub fn with_board(
        &mut self,
        file: PathBuf,
        (sound_s, link_delay): (f64, Duration),
        start: BoardStart,
        cancelled: Arc<AtomicBool>,
    ) -> bool {
        if self.reach == Reach::Gone {
            return false;
        }
        self.ended = None;
        self.asked = true;
        // By design it takes the sound's lead, and up to the longest lead for an output slow to start.
        let takes = crate::audio::together::LONGEST_PREROLL;
        let carried = Some((Arc::clone(&start), Arc::clone(&cancelled)));
        self.send(Request::WithBoard { file, sound_s, link_delay, start, cancelled }, takes, carried);
        true
    }

    /// Stops what plays (never waits).
    pub fn silence(&mut self) {
        self.asked = false;
        self.ended = None;
        if self.reach != Reach::Gone {
            let _ = self.requests.send(Request::Silence);
        }
    }

    /// Takes the output's answers; says (once) when it has none or stopped
    /// answering. Returns what to say on the status line.
    pub fn poll(&mut self, now: Instant) -> Option<super::Said> {
        let mut said = None;
        while let Ok(answer) = self.answers.try_recv() {
            if !matches!(answer, Answer::Connected) {
                self.waiting = None;
            }
            match answer {
                Answer::Connected => {
                    // What was asked may take its designed time from here.
                    self.reach = Reach::Ready;
                    if let Some((since, ..)) = &mut self.waiting {
                        *since = now;
                    }
                    continue;
                }
                Answer::Playing(ended) => {
                    self.reach = Reach::Ready;
                    if self.asked {
                        self.ended = Some(ended);
                    }
                    self.asked = false;
                }
                Answer::Failed { why, no_output } => {
                    self.asked = false;
                    if no_output {
                        self.reach = Reach::Gone;
                        said = Some(super::Said::NoOutput(why));
                    } else {
                        said = Some(super::Said::Line(why));
                    }
                }
            }
        }
        if let Some(deadline) = self.next_deadline()
            && now > deadline
            && let Some((_, _, start)) = &self.waiting
        {
            if let Some((start, cancelled)) = start {
                start_once(start, cancelled);
            }
            self.waiting = None;
            self.asked = false;
            self.ended = None;
            self.reach = Reach::Gone;
            // Named, the user's default server too: where it stalled is what to look at.
            let server = self.server.clone().or_else(crate::audio::output::default_server);
            let server = server.map(|server| server.display().to_string());
            said = Some(super::Said::Stalled { server, after_s: ANSWER_WITHIN.as_secs() });
        }
        said
    }

    /// When [`SoundOut::poll`] next has something to decide without an
    /// answer (a deadline): reaching the output must take at most
    /// [`ANSWER_WITHIN`]; once reached, what was asked its designed time more.
    pub fn next_deadline(&self) -> Option<Instant> {
        let (since, takes, _) = self.waiting.as_ref()?;
        let designed = if self.reach == Reach::Ready { *takes } else { Duration::ZERO };
        Some(*since + designed + ANSWER_WITHIN)
    }
}

/// The thread's side.
struct Worker {
    server: Option<PathBuf>,
    speakers: Option<Speakers>,
    playing: Option<Playing>,
}

impl Worker {
    fn run(mut self, asked: &Receiver<Request>, answer: &Sender<Answer>, waker: &Waker) {
        let connected = |answer: &Sender<Answer>| {
            let _ = answer.send(Answer::Connected);
            waker();
        };
        while let Ok(first) = asked.recv() {
            // Only the newest of what waits is worth doing (a scrub sends grains faster than they start).
            let mut request = first;
            while let Ok(newer) = asked.try_recv() {
                if let Request::WithBoard { start, cancelled, .. } = &request {
                    // Superseded: its board start is not the sound's any more; it never goes out.
                    cancelled.store(true, Ordering::SeqCst);
                    drop(start.lock().ok().and_then(|mut start| start.take()));
                }
                request = newer;
            }
            if let Some(reply) = self.handle(request, &|| connected(answer)) {
                if answer.send(reply).is_err() {
                    return;
                }
                waker();
            }
        }
    }

    /// The speakers, connecting the first time (`reached` is told when it did).
    fn speakers(&mut self, reached: &dyn Fn()) -> Result<&Speakers, OutputError> {
        if self.speakers.is_none() {
            let connected = match &self.server {
                Some(socket) => Speakers::connect_to(socket),
                None => Speakers::connect(),
            };
            self.speakers = Some(connected?);
            reached();
        }
        self.speakers.as_ref().ok_or_else(|| OutputError::NoServer(String::new()))
    }

    fn handle(&mut self, request: Request, reached: &dyn Fn()) -> Option<Answer> {
        // Whatever played stops first (deleting its stream waits on the server).
        drop(self.playing.take());
        let failed = |error: OutputError| match error {
            OutputError::NoServer(why) => Answer::Failed { why, no_output: true },
            other => Answer::Failed { why: other.to_string(), no_output: false },
        };
        match request {
            Request::Silence => None,
            Request::Play { file, from_s, only } => {
                let played = self.speakers(reached).and_then(|speakers| speakers.play_for(&file, from_s, only));
                Some(match played {
                    Ok(playing) => {
                        let ended = playing.ended();
                        self.playing = Some(playing);
                        Answer::Playing(ended)
                    }
                    Err(error) => failed(error),
                })
            }
            Request::WithBoard { file, sound_s, link_delay, start, cancelled } => {
                let speakers = match self.speakers(reached) {
                    Ok(speakers) => speakers.clone(),
                    Err(error) => {
                        // No sound: the board starts at once, on its own.
                        start_once(&start, &cancelled);
                        return Some(failed(error));
                    }
                };
                let begin = || start_once(&start, &cancelled);
                let together = crate::audio::together::start(&speakers, &file, sound_s, link_delay, begin);
                Some(match together {
                    Ok(together) => {
                        let ended = together.playing.ended();
                        self.playing = Some(together.playing);
                        Answer::Playing(ended)
                    }
                    Err(error) => {
                        start_once(&start, &cancelled);
                        failed(error)
                    }
                })
            }
        }
    }
}
