//! The DYNAMIXEL family's side of the editor: the bus (a scan of both
//! protocols, a slider per servo clamped to its own limits, torque and LED,
//! each servo's position, load, voltage, temperature and hardware errors
//! live, a silent servo said), posing by hand (capture a pose into a step,
//! record a performance and fit it into steps; each one undo step), and the
//! motions, streamed from the computer (a DYNAMIXEL stores none) exactly as
//! the plot beside them draws them.

mod action;
mod bus;
mod link;
mod motions;
mod record;
mod show_cue;
mod state;
mod words;

use std::time::Instant;

pub use action::DynamixelAction;
pub use state::{BusServo, degrees, units};

use crate::device::dynamixel::{DynamixelCommand, DynamixelEvent, DynamixelHandle, HARDWARE_ERRORS, ONE_IDS};
use crate::project::dynamixel::{DynamixelSection, Motion, Profile, ServoSetup, Step};
use crate::project::{Easing, Edit, Family, Project};
use crate::say;
use crate::ui::action::{Action, FamilyAction, Tab};
use crate::ui::board_link::{BoardLink, FamilyNotice, LinkStarter, StartError};
use crate::ui::family::{FamilyBoard, FamilyMemory, FamilyPad, FamilyPanels, FamilyPose, FamilyUi, Panel};
use crate::ui::i18n::{Language, Strings};
use crate::ui::layout::Layout;
use crate::ui::shell::{Shell, ShellView};
use record::Recording;
use state::Bus;

#[allow(non_upper_case_globals)]
impl Tab {
    /// The servos on the bus, live.
    pub const Bus: Self = Self::named("Bus");
    /// A DYNAMIXEL project's motions.
    pub const DynamixelMotions: Self = Self::named("DynamixelMotions");
}

const PANELS: &[Panel] = &[
    Panel { tab: Tab::Bus, title: |words| words.lang.word("dynamixel.bus_tab"), has_view: false },
    Panel { tab: Tab::DynamixelMotions, title: |words| words.motions, has_view: false },
];

/// The DYNAMIXEL family's side of the editor.
#[derive(Debug, Default)]
pub struct DynamixelUi {
    /// The servos the bus said it has, and what each said last.
    pub bus: Bus,
    /// The motion shown and captured into.
    pub motion: usize,
    /// A recording under way.
    recording: Option<Recording>,
    /// The motion streaming, and since when.
    pub playing: Option<(usize, Instant)>,
    /// The tolerance a recording is fitted within, degrees.
    pub tolerance_deg: f64,
    /// Captions being typed, by servo ID.
    captions: std::collections::BTreeMap<u8, String>,
    layout: Layout,
}

impl DynamixelUi {
    fn handle<'a>(shell: &'a Shell<'_>) -> Option<&'a DynamixelHandle> {
        shell.link.as_ref().and_then(BoardLink::device::<DynamixelHandle>)
    }

    fn send(shell: &Shell<'_>, command: DynamixelCommand) -> bool {
        Self::handle(shell).map(|bus| bus.send(command)).is_some()
    }

    fn apply(&mut self, shell: &mut Shell<'_>, action: DynamixelAction) {
        let language = shell.language;
        match action {
            DynamixelAction::Scan => {
                self.bus = Bus { scanning: Some((0, ONE_IDS.len())), ..Bus::default() };
                Self::send(shell, DynamixelCommand::Scan { one: ONE_IDS });
            }
            DynamixelAction::Goal { id, position } => {
                let Some(servo) = self.bus.servos.get_mut(&id) else { return };
                let position = servo.clamp(position);
                servo.goal = Some(position);
                Self::send(shell, DynamixelCommand::Goal { id, position });
            }
            DynamixelAction::Torque { id, on } => {
                for servo in self.bus.servos.values_mut().filter(|servo| id.is_none_or(|id| servo.found.id == id)) {
                    servo.torque = on;
                    // A servo let go is where the hand leaves it: its slider follows it.
                    servo.goal = None;
                }
                if on {
                    // Torque back on holds each servo where it is, never a jump to an old goal.
                    Self::send(shell, DynamixelCommand::Hold);
                }
                Self::send(shell, DynamixelCommand::Torque { id, on });
            }
            DynamixelAction::Led { id, on } => {
                if let Some(servo) = self.bus.servos.get_mut(&id) {
                    servo.led = on;
                }
                Self::send(shell, DynamixelCommand::Led { id, on });
            }
            DynamixelAction::Capture => self.capture(shell, language),
            DynamixelAction::Record(start) => self.record(shell, start, language),
            DynamixelAction::SelectMotion(index) => self.motion = index,
            DynamixelAction::AddMotion => {
                let mut section = DynamixelSection::of(&shell.document.project);
                let name = say!(language, "dynamixel.new_motion", number = section.motions.len() + 1);
                section.motions.push(Motion { name, steps: Vec::new() });
                self.motion = section.motions.len() - 1;
                Self::keep(shell, &section);
            }
            DynamixelAction::Edit(section) => Self::keep(shell, &section),
            DynamixelAction::Profile { id, profile } => {
                let mut section = self.with_bus(&shell.document.project);
                if let Some(setup) = section.servos.iter_mut().find(|setup| setup.id == id) {
                    setup.profile = Some(profile);
                }
                Self::keep(shell, &section);
                let (velocity, acceleration) = (profile.velocity, profile.acceleration);
                Self::send(shell, DynamixelCommand::Profile { id, velocity, acceleration });
            }
            DynamixelAction::Play(index) => self.play(shell, index),
            DynamixelAction::Relax => {
                Self::send(shell, DynamixelCommand::Hold);
                self.apply(shell, DynamixelAction::Torque { id: None, on: false });
                shell.say(|language| language.word("dynamixel.relaxed"), false);
            }
        }
    }

    /// `section` becomes the project's (one undo step).
    fn keep(shell: &mut Shell<'_>, section: &DynamixelSection) {
        shell.document.apply(Edit::SetSection(Family::Dynamixel, section.kept()), None);
    }

    /// The section with every servo on the bus listed (by ID, with its model).
    fn with_bus(&self, project: &Project) -> DynamixelSection {
        let mut section = DynamixelSection::of(project);
        for servo in self.bus.servos.values() {
            if section.servo(servo.found.id).is_none() {
                section.servos.push(ServoSetup {
                    id: servo.found.id,
                    name: String::new(),
                    model_number: servo.found.model_number,
                    profile: None,
                });
            }
        }
        section.servos.sort_by_key(|servo| servo.id);
        section
    }

    /// Where every servo is now becomes a step of the motion shown (one undo step).
    fn capture(&mut self, shell: &mut Shell<'_>, language: Language) {
        let positions = self.bus.present();
        if positions.is_empty() {
            shell.say(|language| language.word("dynamixel.nothing_to_capture"), true);
            return;
        }
        let mut section = self.with_bus(&shell.document.project);
        if section.motions.is_empty() {
            section
                .motions
                .push(Motion { name: say!(language, "dynamixel.new_motion", number = 1), steps: Vec::new() });
        }
        self.motion = self.motion.min(section.motions.len() - 1);
        let motion = &mut section.motions[self.motion];
        motion.steps.push(Step { duration_ms: 1000, easing: Easing::Linear, positions });
        let (step, motion) = (motion.steps.len(), motion.name.clone());
        Self::keep(shell, &section);
        shell.say(move |language| say!(language, "dynamixel.captured", step, motion = motion.clone()), false);
    }

    /// Starts a recording, or ends one and fits it into the motion shown (one undo step).
    fn record(&mut self, shell: &mut Shell<'_>, start: bool, language: Language) {
        if start {
            self.recording = Some(Recording::new(&self.bus));
            shell.say(|language| language.word("dynamixel.recording"), false);
            return;
        }
        let Some(recording) = self.recording.take() else { return };
        let tolerance = if self.tolerance_deg > 0.0 { self.tolerance_deg } else { record::TOLERANCE_DEG };
        let Some(steps) = recording.fit(tolerance) else {
            shell.say(|language| language.word("dynamixel.recorded_nothing"), true);
            return;
        };
        let mut section = self.with_bus(&shell.document.project);
        let name = say!(language, "dynamixel.new_motion", number = section.motions.len() + 1);
        let (samples, count) = (recording.samples(), steps.len());
        let said = move |language: Language| {
            say!(language, "dynamixel.recorded", samples, steps = count, tolerance = format!("{tolerance:.1}"))
        };
        section.motions.push(Motion { name, steps });
        self.motion = section.motions.len() - 1;
        Self::keep(shell, &section);
        shell.say(said, false);
    }

    /// Streams motion `index` from where the servos are.
    fn play(&mut self, shell: &mut Shell<'_>, index: usize) {
        let section = DynamixelSection::of(&shell.document.project);
        let Some(motion) = section.motions.get(index) else { return };
        if Self::handle(shell).is_none() {
            shell.say(|language| language.word("dynamixel.connect_first"), true);
            return;
        }
        let frames = state::frames(motion, &self.bus);
        // The sliders follow the servos while the motion moves them.
        for servo in self.bus.servos.values_mut() {
            servo.goal = None;
        }
        Self::send(shell, DynamixelCommand::Stream { frames, every: state::FRAME });
        self.playing = Some((index, Instant::now()));
        self.motion = index;
    }

    /// What the bus said.
    fn heard(&mut self, shell: &mut Shell<'_>, event: DynamixelEvent) {
        match event {
            DynamixelEvent::Scanning { done, of } => self.bus.scanning = Some((done, of)),
            DynamixelEvent::Found(found) => {
                self.bus.servos.insert(found.id, BusServo::new(found));
                // Live moves at the servo's own profile: the project's, else a gentle one.
                let section = DynamixelSection::of(&shell.document.project);
                let profile = section.servo(found.id).map_or(Profile::LIVE, ServoSetup::live_profile);
                let (velocity, acceleration) = (profile.velocity, profile.acceleration);
                Self::send(shell, DynamixelCommand::Profile { id: found.id, velocity, acceleration });
            }
            DynamixelEvent::Scanned { found } => {
                self.bus.scanning = None;
                shell.say(move |language| say!(language, "dynamixel.scanned", count = found), found == 0);
            }
            DynamixelEvent::Limits { id, limits } => {
                if let Some(servo) = self.bus.servos.get_mut(&id) {
                    servo.limits = Some(limits);
                }
            }
            DynamixelEvent::Reading { id, reading } => {
                let Some(servo) = self.bus.servos.get_mut(&id) else { return };
                let new_errors = reading.hardware_error & !servo.reading.map_or(0, |last| last.hardware_error);
                servo.reading = Some(reading);
                if let Some(recording) = &mut self.recording {
                    recording.heard(id, reading.position, reading.at);
                }
                if new_errors != 0 {
                    let said = move |language: Language| {
                        let what: Vec<&str> = HARDWARE_ERRORS
                            .iter()
                            .filter(|(bit, _)| new_errors & bit != 0)
                            .map(|(_, name)| language.word(&format!("dynamixel.error_{}", name.replace(' ', "_"))))
                            .collect();
                        say!(language, "dynamixel.hardware_error", id, what = what.join(", "))
                    };
                    shell.say(said, true);
                }
            }
            DynamixelEvent::Refused { id, what, error } => {
                let error = format!("0x{error:02X}");
                shell.say(move |language| say!(language, "dynamixel.refused", id, what, error = error.clone()), true);
            }
            DynamixelEvent::Silent { id } => {
                if let Some(servo) = self.bus.servos.get_mut(&id) {
                    servo.silent = true;
                }
                shell.say(move |language| say!(language, "dynamixel.silent", id), true);
            }
            DynamixelEvent::Answering { id } => {
                if let Some(servo) = self.bus.servos.get_mut(&id) {
                    servo.silent = false;
                }
            }
            DynamixelEvent::Streamed => self.playing = None,
            // The editor pings nothing (a show's stage measures its link so); the log is the link's.
            DynamixelEvent::Pong { .. } | DynamixelEvent::Logged(_) => {}
        }
    }
}

impl FamilyUi for DynamixelUi {
    fn family(&self) -> Family {
        Family::Dynamixel
    }

    fn act(&mut self, shell: &mut Shell<'_>, action: Box<dyn FamilyAction>) {
        match action.into_any().downcast::<DynamixelAction>() {
            Ok(action) => self.apply(shell, *action),
            Err(_) => crate::ui::board_link::misrouted(
                Family::Dynamixel,
                "an action",
                std::any::type_name::<DynamixelAction>(),
            ),
        }
    }
}

impl FamilyPanels for DynamixelUi {
    fn panels(&self) -> &'static [Panel] {
        PANELS
    }

    fn layout(&self) -> Layout {
        self.layout
    }

    fn layout_mut(&mut self) -> &mut Layout {
        &mut self.layout
    }

    fn ui(&mut self, ui: &mut egui::Ui, tab: Tab, view: &ShellView<'_>, actions: &mut Vec<Action>) {
        if tab == Tab::DynamixelMotions {
            motions::ui(self, ui, view, actions);
        } else {
            bus::ui(self, ui, view, actions);
        }
    }
}

impl FamilyBoard for DynamixelUi {
    fn link_starter(&self, _baud: u32) -> LinkStarter {
        link::starter()
    }

    fn demo_link(&self, _project: &Project, waker: crate::link::Waker) -> Result<BoardLink, StartError> {
        link::demo_link(waker)
    }

    fn demo_server(
        &self,
        _project: &Project,
        waker: crate::link::Waker,
    ) -> Option<Result<crate::ui::family::DemoServer, StartError>> {
        Some(link::demo_server(waker))
    }

    fn demo_connected(&self, words: &Strings) -> &'static str {
        words.lang.word("dynamixel.demo_connected")
    }

    /// STOP: the stream ends and every servo holds where it is.
    fn stop(&mut self, shell: &mut Shell<'_>) {
        self.playing = None;
        Self::send(shell, DynamixelCommand::Hold);
        for servo in self.bus.servos.values_mut() {
            servo.goal = None;
        }
        shell.say(|language| language.word("dynamixel.stopped"), false);
    }

    fn halt(&mut self) -> bool {
        self.playing.take().is_some()
    }

    /// A new link: the bus is scanned at once.
    fn connected(&mut self, project: &Project) {
        // Every family hears of a link; only a DYNAMIXEL project's is a bus being scanned.
        let scanning = (project.family == Family::Dynamixel).then_some((0, ONE_IDS.len()));
        self.bus = Bus { scanning, ..Bus::default() };
        self.playing = None;
    }

    fn disconnected(&mut self) {
        self.bus = Bus::default();
        self.playing = None;
        // A recording outlives a pulled cable: Stop recording keeps what it holds.
    }

    fn tick(&mut self, _shell: &mut Shell<'_>, _now: Instant) -> bool {
        self.playing.is_some() || self.recording.is_some() || self.bus.scanning.is_some()
    }

    fn notice(&mut self, shell: &mut Shell<'_>, notice: FamilyNotice) {
        match notice.take::<DynamixelEvent>() {
            Ok(event) => self.heard(shell, event),
            Err(notice) => {
                let _ = notice.of::<DynamixelEvent>(Family::Dynamixel);
            }
        }
    }
}

impl FamilyPad for DynamixelUi {}

impl FamilyPose for DynamixelUi {}

impl FamilyMemory for DynamixelUi {}

#[cfg(test)]
mod tests;
