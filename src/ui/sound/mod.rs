//! The project's sound track in the editor: read off the frame with
//! progress (hashed and analysed in one pass each), checked against what the
//! project recorded of it (a missing or changed file is said, with what to
//! do), played in step with a preview's time cursor, scrubbed in short
//! grains, and started together with the board. The lane under each
//! preview's cursor is [`lane`].

pub mod follow;
pub mod lane;
mod out;
pub use out::SoundOut;
mod picking;
mod reading;

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use crate::link::Waker;
use crate::project::{Edit, Project, SoundTrack};
use reading::{Read, Reading};

pub use crate::ui::action::SoundAction;
pub use lane::SoundLane;
pub use out::ANSWER_WITHIN;
pub use reading::sha256 as sha256_of;

/// What the sound says on the status line (the shell words it in the interface's language).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Said {
    /// There is no sound output: why, as the output said it.
    NoOutput(String),
    /// The sound server stopped answering: the motion plays on without sound.
    Stalled {
        /// The server, as its address reads (none: the system's).
        server: Option<String>,
        /// How long it was given, s.
        after_s: u64,
    },
    /// Anything else (a file that is no sound), as it was said.
    Line(String),
}

/// A grain played while scrubbing, s.
pub const GRAIN_S: f64 = 0.06;

/// The sensitivity a sound is read at (percent): its onsets come with it.
const READ_AT_PERCENT: u8 = 50;

/// What is wrong with the project's sound file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Problem {
    /// The file is not where the project says.
    Missing(PathBuf),
    /// It is there but cannot be read as a sound.
    Unreadable(String),
    /// It reads, but is not the file the project was timed to (its content changed).
    Changed(PathBuf),
}

/// The editor's sound: the file read, the speakers, what plays.
pub struct SoundDesk {
    reading: Option<Reading>,
    read: Option<Read>,
    problem: Option<Problem>,
    /// The file the reading or the read is of.
    file: Option<PathBuf>,
    /// The sound output, off the frame (made on the first frame).
    out: Option<SoundOut>,
    /// Where the sound server is, when not the environment's (tests).
    server: Option<PathBuf>,
    /// Onsets at the track's sensitivity, s (and that sensitivity): the
    /// newest the picker answered.
    onsets: (u8, Vec<f64>),
    /// Picks the read sound's onsets again, off the frame, as the sensitivity changes.
    picking: Option<picking::Picking>,
    /// A line for the status bar, once.
    said: Option<Said>,
    /// An edit the project needs (a sound added or located, once read).
    edit: Option<(Edit, &'static str)>,
    /// The file being added or located, and the track it becomes.
    adding: Option<SoundTrack>,
    /// The follow-the-sound dialog, while open.
    follow: Option<follow::FollowForm>,
    /// The link's first-byte latency, as the connection doctor measured it (none: not asked).
    link_latency: Option<Duration>,
    /// A board's start waiting for the sound: set by STOP (or any other
    /// sound) before it goes out, and it never does.
    joining: Option<Arc<AtomicBool>>,
}

impl std::fmt::Debug for SoundDesk {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SoundDesk").field("file", &self.file).field("problem", &self.problem).finish_non_exhaustive()
    }
}

impl Default for SoundDesk {
    fn default() -> Self {
        Self {
            reading: None,
            read: None,
            problem: None,
            file: None,
            out: None,
            server: None,
            onsets: (u8::MAX, Vec::new()),
            picking: None,
            said: None,
            edit: None,
            adding: None,
            follow: None,
            link_latency: None,
            joining: None,
        }
    }
}

/// Where a project's sound file is: relative to the project's folder.
pub fn resolve(track: &str, folder: Option<&Path>) -> PathBuf {
    let path = Path::new(track);
    match folder {
        Some(folder) if path.is_relative() => folder.join(path),
        _ => path.to_path_buf(),
    }
}

/// How a project names a file: relative to its folder, `/` between folders (absolute outside it).
pub fn stored(file: &Path, folder: Option<&Path>) -> String {
    match folder.and_then(|folder| file.strip_prefix(folder).ok()) {
        Some(relative) => relative.iter().map(|part| part.to_string_lossy()).collect::<Vec<_>>().join("/"),
        None => file.to_string_lossy().into_owned(),
    }
}

impl SoundDesk {
    #[cfg(any(test, feature = "test-api"))]
    /// A desk that plays through the sound server at `socket` (tests run their own).
    pub fn with_server(socket: PathBuf) -> Self {
        Self { server: Some(socket), ..Self::default() }
    }

    /// Keeps up with the project: reads its sound when it names another file;
    /// takes in a finished reading. Returns an edit the project needs.
    pub fn sync(&mut self, project: &Project, folder: Option<&Path>, waker: &Waker) -> Option<(Edit, &'static str)> {
        let out = self.out.get_or_insert_with(|| SoundOut::new(self.server.clone(), waker.clone()));
        if let Some(said) = out.poll(Instant::now()) {
            self.said = Some(said);
        }
        let wanted = match (&self.adding, &project.sound) {
            (Some(adding), _) => Some(resolve(&adding.path, folder)),
            (None, Some(track)) => Some(resolve(&track.path, folder)),
            (None, None) => None,
        };
        if wanted != self.file {
            self.silence();
            self.read = None;
            self.problem = None;
            self.onsets = (u8::MAX, Vec::new());
            self.picking = None;
            self.reading = wanted.as_ref().map(|file| Reading::start(file.clone(), waker.clone()));
            self.file = wanted;
        }
        if let Some(done) = self.reading.as_mut().and_then(Reading::done) {
            self.reading = None;
            self.took(done, project);
        }
        if let (Some(track), Some(read)) = (&project.sound, &self.read) {
            let picking = self.picking.get_or_insert_with(|| {
                // The reading picked at 50 %: the lane has those at once.
                self.onsets = (READ_AT_PERCENT, read.analysis.onsets_s.clone());
                picking::Picking::start(Arc::new(read.analysis.found.clone()), waker.clone()).holding(READ_AT_PERCENT)
            });
            picking.ask(track.sensitivity_percent.min(100));
            if let Some(picked) = picking.answer() {
                self.onsets = picked;
            }
        }
        self.edit.take()
    }

    /// A reading has ended: the sound, or what is wrong.
    fn took(&mut self, done: Result<Read, Problem>, project: &Project) {
        match (done, self.adding.take()) {
            (Ok(read), Some(mut track)) => {
                track.duration_ms = read.duration_ms();
                track.sha256.clone_from(&read.sha256);
                self.edit = Some((Edit::SetSound(Some(track)), "sound"));
                self.read = Some(read);
            }
            (Ok(read), None) => {
                let changed = project.sound.as_ref().is_some_and(|track| track.sha256 != read.sha256);
                self.problem = changed.then(|| Problem::Changed(self.file.clone().unwrap_or_default()));
                self.read = Some(read);
            }
            (Err(problem), adding) => {
                if adding.is_some() {
                    // The file picked is no sound: the project keeps what it had.
                    self.said = Some(Said::Line(match &problem {
                        Problem::Unreadable(why) => why.clone(),
                        Problem::Missing(file) | Problem::Changed(file) => file.display().to_string(),
                    }));
                    self.file = None;
                } else {
                    self.problem = Some(problem);
                }
            }
        }
    }

    /// Applies a sound action; returns an edit of the project it makes.
    pub fn apply(
        &mut self,
        action: SoundAction,
        project: &Project,
        folder: Option<&Path>,
    ) -> Option<(Edit, &'static str)> {
        let track = project.sound.clone();
        let set = |track: SoundTrack| Some((Edit::SetSound(Some(track)), "sound"));
        match action {
            SoundAction::Add(file) => {
                self.adding = Some(SoundTrack {
                    path: stored(&file, folder),
                    duration_ms: 0,
                    sha256: String::new(),
                    offset_ms: 0,
                    sensitivity_percent: 50,
                });
                None
            }
            SoundAction::Locate(file) => {
                let (offset_ms, sensitivity_percent) =
                    track.map_or((0, 50), |track| (track.offset_ms, track.sensitivity_percent));
                let path = stored(&file, folder);
                self.adding =
                    Some(SoundTrack { path, duration_ms: 0, sha256: String::new(), offset_ms, sensitivity_percent });
                None
            }
            SoundAction::AcceptChanged => {
                let (mut track, read) = (track?, self.read.as_ref()?);
                track.duration_ms = read.duration_ms();
                track.sha256.clone_from(&read.sha256);
                self.problem = None;
                set(track)
            }
            SoundAction::Remove => Some((Edit::SetSound(None), "sound")),
            SoundAction::SetOffset(offset_ms) => set(SoundTrack { offset_ms, ..track? }),
            SoundAction::SetSensitivity(percent) => set(SoundTrack { sensitivity_percent: percent.min(100), ..track? }),
            SoundAction::OpenFollow => {
                self.follow.get_or_insert_with(follow::FollowForm::default);
                None
            }
            SoundAction::Play { from_ms } => {
                self.play(&track?, from_ms, None);
                None
            }
            SoundAction::Silence => {
                self.silence();
                None
            }
            SoundAction::Grain { at_ms } => {
                self.play(&track?, at_ms, Some(Duration::from_secs_f64(GRAIN_S)));
                None
            }
        }
    }

    /// Plays from the motion's `from_ms` (for `only` at most), off the frame.
    fn play(&mut self, track: &SoundTrack, from_ms: f64, only: Option<Duration>) {
        self.silence();
        let (Some(file), Some(read)) = (&self.file, &self.read) else { return };
        // Offsets and times within an hour: exact in f64.
        #[allow(clippy::cast_precision_loss)]
        let sound_s = (from_ms - track.offset_ms as f64) / 1000.0;
        if sound_s >= read.analysis.duration_s() {
            return;
        }
        let file = file.clone();
        if let Some(out) = &mut self.out {
            out.play(file, sound_s, only);
        }
    }

    /// Stops the sound, and a board's start still waiting for it (which then
    /// never goes out). Never waits on the output.
    pub fn silence(&mut self) {
        if let Some(cancelled) = self.joining.take() {
            cancelled.store(true, Ordering::SeqCst);
        }
        if let Some(out) = &mut self.out {
            out.silence();
        }
    }

    /// Starts the board and the sound together: the sound's point for the
    /// motion's `from_ms` is heard as the board starts moving; `start_board`
    /// sends the start command `link_delay` (the command's time on the line)
    /// plus the doctor's measured latency before. Off the frame: should the
    /// output turn out to be none, or stop answering, the board starts then,
    /// on its own. False when there is no sound to play (the caller starts
    /// the board alone).
    pub fn play_with_board(
        &mut self,
        project: &Project,
        from_ms: f64,
        (link_delay, _waker): (Duration, Waker),
        start_board: impl FnOnce() + Send + 'static,
    ) -> bool {
        let link_delay = link_delay + self.link_latency.unwrap_or_default();
        let (Some(track), Some(file), Some(_)) = (&project.sound, self.file.clone(), &self.read) else { return false };
        // Offsets within an hour: exact in f64.
        #[allow(clippy::cast_precision_loss)]
        let sound_s = (from_ms - track.offset_ms as f64) / 1000.0;
        self.silence();
        let Some(out) = self.out.as_mut().filter(|out| out.available()) else { return false };
        let start: out::BoardStart = Arc::new(Mutex::new(Some(Box::new(start_board))));
        let cancelled = Arc::new(AtomicBool::new(false));
        if !out.with_board(file, (sound_s, link_delay), start, Arc::clone(&cancelled)) {
            return false;
        }
        self.joining = Some(cancelled);
        true
    }

    /// The follow-the-sound dialog, while open (and the sound read).
    pub fn follow_window(
        &mut self,
        ctx: &egui::Context,
        (project, family): (&Project, Option<&dyn follow::SoundFollower>),
        language: crate::ui::i18n::Language,
        actions: &mut Vec<crate::ui::action::Action>,
    ) {
        let (Some(form), Some(read), Some(track)) = (&mut self.follow, &self.read, &project.sound) else { return };
        let loudness = read.analysis.found.loudness_db();
        let mut open = true;
        form.window(ctx, (project, &loudness, track.offset_ms), (family, language), &mut open, actions);
        if !open {
            self.follow = None;
        }
    }

    /// The link's first-byte latency as the connection doctor measured it (added to every Play on board's delay).
    pub fn set_link_latency(&mut self, latency: Option<Duration>) {
        self.link_latency = latency;
    }

    /// The link's measured latency, as Play on board counts it.
    pub fn link_latency(&self) -> Option<Duration> {
        self.link_latency
    }

    /// A line for the status bar, once ("no sound output", a file that is no sound).
    pub fn take_said(&mut self) -> Option<Said> {
        self.said.take()
    }

    /// What the lane draws from.
    pub fn view<'a>(&'a self, project: &'a Project) -> SoundView<'a> {
        SoundView {
            track: project.sound.as_ref(),
            read: self.read.as_ref().map(|read| &read.analysis),
            onsets_s: &self.onsets.1,
            progress: self.reading.as_ref().map(Reading::progress),
            problem: self.problem.as_ref(),
            file: self.file.as_deref(),
        }
    }

    /// Whether sound plays now (or has been asked to and not refused).
    pub fn is_playing(&self) -> bool {
        self.out.as_ref().is_some_and(SoundOut::is_playing)
    }

    /// When the sound output must be looked at again, without anything else
    /// happening (an answer it owes, which wakes the window when it comes).
    pub fn next_deadline(&self) -> Option<Instant> {
        self.out.as_ref().and_then(SoundOut::next_deadline)
    }
}

/// The sound as the lane and the panels see it.
#[derive(Clone, Copy, Debug)]
pub struct SoundView<'a> {
    /// The project's record of it.
    pub track: Option<&'a SoundTrack>,
    /// The sound read, once read.
    pub read: Option<&'a crate::audio::Analysis>,
    /// Its onsets at the track's sensitivity, s from the sound's start.
    pub onsets_s: &'a [f64],
    /// While reading: how far (0–1).
    pub progress: Option<f32>,
    /// What is wrong with it.
    pub problem: Option<&'a Problem>,
    /// The file.
    pub file: Option<&'a Path>,
}

impl SoundView<'_> {
    /// No sound at all.
    pub const NONE: SoundView<'static> =
        SoundView { track: None, read: None, onsets_s: &[], progress: None, problem: None, file: None };

    /// The waveform as the graphs draw it under their curves.
    pub fn strip(&self) -> Option<crate::ui::graph::SoundStrip<'_>> {
        let (track, read) = (self.track?, self.read?);
        // Offsets within an hour: exact in f64.
        #[allow(clippy::cast_precision_loss)]
        let offset_ms = track.offset_ms as f64;
        let end_ms = offset_ms + read.duration_s() * 1000.0;
        Some(crate::ui::graph::SoundStrip { peaks: &read.peaks, rate: read.sample_rate, offset_ms, end_ms })
    }

    /// The show's span on the motion's time, ms: the longer of the motion
    /// (`motion_end_ms`) and the sound, where it ends. The play bar, the
    /// sound lane and the graph all show this one axis.
    pub fn span_ms(&self, motion_end_ms: f64) -> f64 {
        self.strip().map_or(motion_end_ms, |strip| motion_end_ms.max(strip.end_ms))
    }

    /// The onsets on the motion's time, ms (what frames, steps and retimes snap to).
    pub fn onsets_ms(&self) -> Vec<f64> {
        let Some(track) = self.track else { return Vec::new() };
        // Offsets within an hour: exact in f64.
        #[allow(clippy::cast_precision_loss)]
        let offset = track.offset_ms as f64;
        self.onsets_s.iter().map(|s| s * 1000.0 + offset).filter(|t| *t >= 0.0).collect()
    }
}
