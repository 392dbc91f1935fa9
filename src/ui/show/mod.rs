//! File → Open show…: a show's devices and their ports, its cues on one
//! timeline (a lane per device under the sound's), and Play on the boards —
//! every device connected and started together by the same player as
//! `servo-studio play`, off the frame; Stop all (and the window's STOP)
//! stops every device, bases braking.

mod apply;
mod cues;
mod devices;
mod lanes;
pub mod linked;
mod record;
mod remote;
mod said;
mod stage;
mod words;

use crate::ui::i18n::Worded;
use crate::ui::shell::StatusLine;
use std::path::PathBuf;

use crossbeam_channel::{Receiver, Sender};

use crate::link::Waker;
use crate::link::by_id::Attached;
use crate::project::Project;

use crate::show::Show;
pub use crate::ui::action::ShowAction;
use crate::ui::i18n::{Language, Said};
use linked::LinkState;
pub use linked::Linked;
pub use words::{ShowWords, words};

/// An open show.
#[derive(Debug)]
pub struct ShowSession {
    /// Where it came from (its sound is beside it).
    pub path: Option<PathBuf>,
    /// The show.
    pub show: Show,
    /// Each device's port, as typed.
    pub ports: Vec<String>,
    /// What playing it said, line by line (in every language).
    pub said: Vec<Said>,
    /// The device that is the editor's open project (the show was opened
    /// from it, or it was added): a pass joined into it is an edit of the
    /// project, and the project's edits reach it.
    pub editor: Option<String>,
    /// The document's revision the editor's device last took.
    synced: Option<u64>,
    /// Changes whenever a device's project does (what the stage and lanes worked out is then worked out again).
    pub projects: u64,
}

/// Project revisions, unique across sessions.
static NEXT_PROJECTS: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(1);

struct Running {
    stop: Sender<String>,
    told: Receiver<crate::show::boards::Told>,
}

/// A line worded from the show window's words, in every language.
pub(crate) fn said_by(word: impl Fn(&ShowWords) -> String) -> Said {
    Said::new(|language| word(words(language)))
}

impl ShowSession {
    /// A device's project changed.
    pub fn touch(&mut self) {
        self.projects = NEXT_PROJECTS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    }

    /// The run log, each line in `language`.
    pub fn log(&self, language: Language) -> Vec<&str> {
        self.said.iter().map(|line| line.in_(language)).collect()
    }

    /// The show with each device's port as typed (none where the field is empty).
    pub fn with_ports(&self) -> Show {
        let mut show = self.show.clone();
        for (device, port) in show.devices.iter_mut().zip(&self.ports) {
            device.port = (!port.trim().is_empty()).then(|| port.trim().to_string());
        }
        show
    }

    /// Adds a device holding `project` (named `name`, or made unique), with no port yet.
    pub fn add(&mut self, name: &str, project: Project) -> String {
        let name = self.show.add_device(name, project);
        self.ports.push(String::new());
        self.touch();
        name
    }

    /// The index of the device that is the editor's project.
    fn editor_index(&self) -> Option<usize> {
        let name = self.editor.as_deref()?;
        self.show.devices.iter().position(|device| device.name == name)
    }
}

/// The show window and a show playing.
#[derive(Default)]
pub struct ShowDesk {
    /// The open show.
    pub session: Option<ShowSession>,
    running: Option<Running>,
    /// The USB serial devices attached (for "find by id"), listed off the frame.
    adapters: devices::Adapters,
    /// The stage: every device in 3D at the scrub's time.
    pub stage: stage::Stage,
    /// Record passes: the passes kept and the one being recorded.
    pub passes: record::Passes,
    /// The boards were connected by turning remote control on (they go when it stops).
    boards_for_remote: bool,
    /// A pass joined, not yet recorded in the editor's history (see `take_joined`).
    joined: Option<Option<Project>>,
    /// The boards, held connected (Connect the boards).
    pub linked: Option<Linked>,
    /// Settings → Remote control: its settings and servers.
    pub remote: remote::RemoteDesk,
    /// The editor's live speed limit (a remote's poses keep to it), and the one last told to the boards.
    pub live_speed: (crate::device::speed::LiveSpeed, Option<crate::device::speed::LiveSpeed>),
}

impl std::fmt::Debug for ShowDesk {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ShowDesk").field("session", &self.session).field("playing", &self.running.is_some()).finish()
    }
}

impl ShowDesk {
    /// A pass being recorded takes the axis's value at the time shown, and
    /// shows it on the figure; it ends with the show's end.
    fn follow_pass(&mut self, actions: &mut Vec<crate::ui::Action>) {
        let Some(pass) = &self.passes.recording else { return };
        self.stage.held = Some((pass.device.clone(), pass.axis, self.passes.value));
        self.passes.sample(self.stage.scrub_ms);
        if !self.stage.previewing() {
            actions.push(crate::ui::Action::Show(ShowAction::RecordPass(false)));
        }
    }

    /// Ends the pass being recorded (and the preview under it) and joins it, saying how.
    fn end_pass(&mut self) {
        self.stage.stop_preview();
        self.stage.held = None;
        let Some(session) = &mut self.session else { return };
        let Some((said, joined)) = self.passes.end(&mut session.show) else { return };
        session.said.push(said);
        session.touch();
        if let Some(device) = joined {
            // What the pass made of the editor's project, when it was recorded on it.
            let editor = session.editor_index().filter(|&index| session.show.devices[index].name == device);
            self.joined = Some(editor.map(|index| session.show.devices[index].project.clone()));
        }
    }

    /// Whether the device that is the editor's project has no port (or no
    /// show is open: remote control opens the project as one): the editor's
    /// own board is what it would serve.
    pub fn project_without_port(&self) -> bool {
        let Some(session) = &self.session else { return true };
        session.editor_index().is_some_and(|index| session.ports.get(index).is_some_and(|port| port.trim().is_empty()))
    }

    /// The editor's board's `port` given to the device that is the project
    /// (the project opened as a show first when none is open).
    pub fn lend_port(&mut self, project: &Project, port: &str) {
        if self.session.is_none() {
            self.opened_project(project);
        }
        let Some(session) = &mut self.session else { return };
        if let Some(slot) = session.editor_index().and_then(|index| session.ports.get_mut(index)) {
            *slot = port.to_string();
        }
    }

    /// The lent `port` given back: no device names it any more.
    pub fn unlend_port(&mut self, port: &str) {
        let Some(session) = &mut self.session else { return };
        session.ports.iter_mut().filter(|each| each.trim() == port).for_each(String::clear);
    }

    /// STOP: the stage's preview (and a pass recorded over it) stops where
    /// it is, said in the show's log with the time it stopped at; whether one ran.
    pub fn stop_preview_said(&mut self) -> bool {
        if !self.stage.previewing() {
            return false;
        }
        self.stage.stop_preview();
        // Whole ms of a show: exact in f64.
        #[allow(clippy::cast_precision_loss)]
        let seconds = self.stage.scrub_ms as f64 / 1000.0;
        if let Some(session) = &mut self.session {
            session.said.push(Said::new(|language| crate::say!(language, "show.preview_stopped", seconds)));
        }
        true
    }

    /// Whether the show's boards are held (connected, or served to remote control).
    pub fn holds_boards(&self) -> bool {
        self.linked.is_some() || self.remote.serving()
    }

    /// A pass joined since this was last asked: what it made of the editor's
    /// project (`Some(None)`: it joined into another device). The editor
    /// records it as one step of its undo history.
    pub fn take_joined(&mut self) -> Option<Option<Project>> {
        self.joined.take()
    }

    /// The editor's Undo reached a pass: it is taken back (the show, the
    /// passes and the log line it said as they were before it).
    pub fn undo_pass(&mut self) {
        if let Some(session) = &mut self.session {
            self.passes.undo(&mut session.show, &mut session.said);
            session.touch();
            self.stage.held = None;
        }
    }

    /// The editor's Redo reached a pass: it is joined again.
    pub fn redo_pass(&mut self) {
        if let Some(session) = &mut self.session {
            self.passes.redo(&mut session.show, &mut session.said);
            session.touch();
        }
    }

    /// The editor's project, as it is now, in the device that is it (the
    /// project edited, undone or redone since).
    pub fn follow_editor(&mut self, project: &Project, revision: u64) {
        let Some(session) = &mut self.session else { return };
        let Some(index) = session.editor_index() else { return };
        if session.synced != Some(revision) {
            session.synced = Some(revision);
            if session.show.devices[index].project != *project {
                session.show.devices[index].project = project.clone();
                session.touch();
            }
        }
    }

    /// Adds every device of a show file, or a project file as one device named after it.
    fn add_from(&mut self, path: &std::path::Path, language: Language) -> Option<StatusLine> {
        let session = self.session.as_mut()?;
        match Show::open(path) {
            Ok(show) => {
                for device in show.devices {
                    session.add(&device.name, device.project);
                }
                None
            }
            Err(error) => {
                let said = |language: Language| format!("{}: {}", path.display(), error.worded(language));
                Some(StatusLine::worded(language, said, true))
            }
        }
    }

    fn opened(&mut self, path: Option<PathBuf>, show: Show) {
        self.stop();
        self.remote.stop(None);
        self.linked = None;
        // The passes were the last show's.
        let pad_axis = self.passes.pad_axis;
        self.passes = record::Passes::default();
        self.passes.pad_axis = pad_axis;
        self.joined = None;
        let ports = show.devices.iter().map(|device| device.port.clone().unwrap_or_default()).collect();
        let mut session = ShowSession { path, show, ports, said: Vec::new(), editor: None, synced: None, projects: 0 };
        session.touch();
        self.session = Some(session);
    }

    /// The editor's open project as a show of one device, which is it.
    fn opened_project(&mut self, project: &Project) {
        self.opened(None, Show::of_one("board", project.clone()));
        if let Some(session) = &mut self.session {
            session.editor = session.show.devices.first().map(|device| device.name.clone());
        }
    }

    /// Lets the held boards go (every device stopped, every link closed), and the remote control with them.
    pub fn let_boards_go(&mut self) {
        self.boards_for_remote = false;
        if self.linked.take().is_some() {
            self.remote.stop(Some(said_by(|words| words.remote_stopped.to_string())));
        }
    }

    /// Serves remote control on the show's boards: the open project as a
    /// show when none is open, its boards connected when they are not.
    fn serve(&mut self, project: &Project, language: Language, waker: &Waker) -> Option<StatusLine> {
        if self.session.is_none() {
            self.opened_project(project);
        }
        if self.linked.is_none() {
            if let Some(said) = self.apply(ShowAction::Boards(true), (project, language), waker) {
                return Some(said);
            }
            // Connected for remote control: let go with it.
            self.boards_for_remote = true;
        }
        let (Some(session), Some(linked)) = (&self.session, &self.linked) else { return None };
        self.live_speed.1 = None;
        self.remote.start(session.with_ports(), linked);
        if !self.remote.serving() && self.boards_for_remote {
            self.let_boards_go();
        }
        None
    }

    #[cfg(any(test, feature = "test-api"))]
    /// Whether the USB adapters attached were listed at least once since the window opened.
    pub fn adapters_listed(&self) -> bool {
        self.adapters.listed()
    }

    /// Whether a show is playing.
    pub fn playing(&self) -> bool {
        self.running.is_some() || self.linked.as_ref().is_some_and(|linked| linked.playing)
    }

    /// Stops every device of a show that plays.
    pub fn stop(&mut self) {
        self.stage.stop_preview();
        if let Some(running) = &self.running {
            let _ = running.stop.send("STOP".into());
        }
        if let Some(linked) = &mut self.linked {
            linked.stop();
        }
    }

    fn play(&mut self, waker: Waker) {
        if self.playing() {
            return;
        }
        let Some(session) = &mut self.session else { return };
        let show = session.with_ports();
        let folder = session.path.as_ref().and_then(|path| path.parent().map(PathBuf::from));
        if let Some(linked) = &mut self.linked {
            session.said.clear();
            let sound = show.sound.as_ref().map(|track| folder.unwrap_or_default().join(&track.path));
            linked.play(&show, sound);
            return;
        }
        let (stop, stopped) = crossbeam_channel::unbounded();
        let (tell, told) = crossbeam_channel::unbounded();
        session.said.clear();
        let spawned = std::thread::Builder::new().name("show".into()).spawn(move || {
            let tell = |what| {
                let _ = tell.send(what);
                waker();
            };
            crate::show::boards::play_once(&show, folder, stopped, &tell);
        });
        if spawned.is_ok() {
            self.running = Some(Running { stop, told });
        }
    }

    /// Takes in what a playing show said; ends it when it is done.
    pub fn poll(&mut self) {
        let Some(running) = &self.running else { return };
        // Every line said so far; the player is done once its end of the channel is gone.
        let mut lines = Vec::new();
        let ended = loop {
            match running.told.try_recv() {
                Ok(told) => lines.extend(said::told(&told)),
                Err(crossbeam_channel::TryRecvError::Empty) => break false,
                Err(crossbeam_channel::TryRecvError::Disconnected) => break true,
            }
        };
        if let Some(session) = &mut self.session {
            session.said.extend(lines);
        }
        if ended {
            self.running = None;
        }
    }

    /// Takes in what the held boards said; a lost link the show needs stops the preview too.
    fn poll_boards(&mut self) {
        let (Some(linked), Some(session)) = (&mut self.linked, &mut self.session) else { return };
        let taken = linked.poll(&session.show);
        session.said.extend(taken.said);
        if taken.all_stopped {
            self.stage.stop_preview();
        }
    }

    /// The held boards follow the preview (and the pass's axis) at the time shown.
    fn boards_follow(&mut self) {
        let (Some(linked), Some(session)) = (&mut self.linked, &self.session) else { return };
        let held = self.passes.recording.as_ref().and_then(|pass| {
            let index = session.show.devices.iter().position(|device| device.name == pass.device)?;
            Some((index, pass.axis, self.passes.value))
        });
        linked.follow(&session.show, self.stage.previewing(), self.stage.scrub_ms, held);
    }

    /// The window, when a show is open.
    /// `pad`: each moved axis of the gamepad in use (by code, −1 … 1), for a pass to record.
    pub fn window(
        &mut self,
        ctx: &egui::Context,
        (language, pad): (Language, &[(u16, f64)]),
        actions: &mut Vec<crate::ui::Action>,
    ) {
        self.poll();
        let words = words(language);
        self.remote.window(ctx, words, actions);
        if let Some(linked) = &self.linked
            && self.live_speed.1 != Some(self.live_speed.0)
        {
            linked.set_speed(self.live_speed.0);
            self.live_speed.1 = Some(self.live_speed.0);
        }
        self.poll_boards();
        let playing = self.playing();
        let Some(session) = &mut self.session else { return };
        // Listed again every few seconds while the window is open (an adapter plugged in meanwhile).
        let attached = self.adapters.refresh(ctx);
        let mut open = true;
        // Below the toolbar (File, Settings and STOP stay in reach), as tall as the rest allows.
        let room = ctx.content_rect().size() - egui::vec2(40.0, 130.0);
        let window = crate::ui::layout::parked_when_collapsed(egui::Window::new(words.title), ctx, "show-window", 0);
        window
            .open(&mut open)
            .default_pos(egui::pos2(20.0, 100.0))
            .resizable(true)
            .default_size(egui::vec2(1000.0, room.y).min(room))
            .max_size(room)
            .show(ctx, |ui| {
                // A show of many devices is taller than the window: it scrolls.
                egui::ScrollArea::vertical().id_salt("show-window").show(ui, |ui| {
                    let links = self.linked.as_ref().map(|linked| linked.states.as_slice());
                    session_ui(
                        ui,
                        (session, &mut self.stage, &mut self.passes),
                        (attached, pad, links),
                        playing,
                        words,
                        actions,
                    );
                });
            });
        if playing {
            ctx.request_repaint_after(std::time::Duration::from_millis(100));
        }
        // A pass of a show with no sound records until it is stopped, not only to the last cue's end.
        let open_ended = |show: &Show| self.passes.recording.is_some() && show.sound.is_none();
        if let Some(session) = &self.session
            && self.stage.advance(if open_ended(&session.show) { u64::MAX } else { self.stage.span_ms })
        {
            ctx.request_repaint();
        }
        self.follow_pass(actions);
        self.boards_follow();
        if !open {
            actions.push(crate::ui::Action::Show(ShowAction::Close));
        }
    }
}

/// What the window shows beside the show: the USB adapters attached, the
/// gamepad's moved axes (by code, −1 … 1), each held link's state.
type Around<'a> = (&'a [Attached], &'a [(u16, f64)], Option<&'a [LinkState]>);

fn session_ui(
    ui: &mut egui::Ui,
    (session, stage, passes): (&mut ShowSession, &mut stage::Stage, &mut record::Passes),
    (attached, pad, links): Around<'_>,
    playing: bool,
    words: &ShowWords,
    actions: &mut Vec<crate::ui::Action>,
) {
    let name = session
        .path
        .as_ref()
        .and_then(|p| p.file_name())
        .map_or_else(|| words.this_project.to_string(), |n| n.to_string_lossy().into_owned());
    let devices = crate::say!(words.lang, "show.device_count", count = session.show.devices.len());
    ui.label(egui::RichText::new(format!("{name} — {devices}")).strong());
    // What each device does over time, and whether the show holds together: worked out once per show as it stands.
    stage.timeline.keep_to(&session.show, session.projects);
    let problem = stage.timeline.problem(&session.show).map(|error| error.worded(words.lang));
    // Play, Save and Stop all first, where a tall show does not scroll them away.
    buttons(ui, session, (playing, links.is_some()), problem.is_none(), words, actions);
    egui::ScrollArea::vertical().id_salt("show-said").max_height(150.0).show(ui, |ui| {
        for line in &session.said {
            ui.label(line.in_(words.lang));
        }
    });
    ui.separator();
    // Devices change only while their boards are not held (a link per device, in order).
    devices::devices_ui(ui, session, (attached, links), !playing && links.is_none(), words, actions);
    ui.separator();
    // The cues' blocks are worked out once a frame, by the lanes: their span serves the stage too.
    // Devices or cues may have changed above, this frame.
    stage.timeline.keep_to(&session.show, session.projects);
    let (clicked, span) = lanes::lanes(ui, (&session.show, &mut stage.timeline), stage.scrub_ms, words);
    if let Some(clicked) = clicked {
        stage.scrub_ms = clicked;
    }
    stage.span_ms = span;
    stage.ui(ui, (&mut session.show, span), !playing, words, actions);
    record::passes_ui(ui, (&session.show, pad, stage.scrub_ms), passes, !playing, words, actions);
    ui.separator();
    cues::cues_ui(ui, &mut session.show, !playing, words);
    if let Some(problem) = problem {
        ui.colored_label(ui.visuals().warn_fg_color, problem);
    }
}

/// Connect / Disconnect the boards, Play on the boards, Save show… (both
/// only when the show `holds` together), Stop all.
fn buttons(
    ui: &mut egui::Ui,
    session: &ShowSession,
    (playing, linked): (bool, bool),
    holds: bool,
    words: &ShowWords,
    actions: &mut Vec<crate::ui::Action>,
) {
    ui.horizontal(|ui| {
        let (connect, caption) = if linked { (false, words.disconnect_boards) } else { (true, words.connect_boards) };
        if ui.add_enabled(!playing, egui::Button::new(caption)).clicked() {
            actions.push(crate::ui::Action::Show(ShowAction::Boards(connect)));
        }
        let can = !playing && !session.show.cues.is_empty() && holds;
        if ui.add_enabled(can, egui::Button::new(words.play)).clicked() {
            actions.push(crate::ui::Action::Show(ShowAction::Play));
        }
        if ui.add_enabled(holds, egui::Button::new(words.save)).clicked() {
            let offered = session
                .path
                .as_ref()
                .and_then(|p| p.file_name())
                .map_or_else(|| "show.json".into(), |n| n.to_string_lossy().into_owned());
            actions.push(crate::ui::Action::AskFile(crate::ui::FileRequest::Export(crate::ui::action::Export::json(
                offered,
                "Servo Studio show",
                |path| crate::ui::Action::Show(ShowAction::Save(path)),
            ))));
        }
        if ui.add_enabled(playing || linked, egui::Button::new(words.stop_all)).clicked() {
            actions.push(crate::ui::Action::Show(ShowAction::StopAll));
        }
        if playing {
            ui.spinner();
        } else if linked {
            ui.weak(words.boards_follow);
        }
    });
}
