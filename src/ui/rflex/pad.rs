//! A gamepad on the Drive panel: chosen from the gamepads the computer has
//! (listed as they come and go) or given as a path, read on its own thread,
//! and turned into drive orders by the same teleop the command line uses
//! (dead-man, stick, dead zone). It drives only while the window has the
//! focus and the Drive tab is shown; STOP, losing the focus, leaving the tab
//! and the gamepad going away each stop the base, and after a halt the
//! dead-man must be let go and pressed again.

use std::path::PathBuf;
use std::time::{Duration, Instant};

use crossbeam_channel::Receiver;

use crate::gamepad::teleop::{Order, StopReason, Teleop, TeleopConfig};
use crate::gamepad::{Gamepad, GamepadInfo, PadState, PadUpdate};
use crate::link::Waker;
use crate::project::rflex::DriveSettings;
use crate::ui::action::{Action, RflexAction};
use crate::ui::i18n::Strings;
use crate::ui::rflex::RflexLink;
use crate::ui::rflex::captions::RflexWords;
use crate::ui::shell::Shell;

/// How often the gamepad list is read again.
const RESCAN_EVERY: Duration = Duration::from_secs(2);

/// The gamepad's state on the Drive panel.
#[derive(Debug, Default)]
pub struct PadDrive {
    /// The path typed or picked.
    pub path: String,
    gamepad: Option<Gamepad>,
    teleop: Option<Teleop>,
    /// What the pad last showed.
    pub state: Option<PadState>,
    /// Why the base is not being driven by it.
    pub stopped: Option<StopReason>,
    /// Whether the pad may drive now (the window focused, the Drive tab shown).
    armed: bool,
    listed: Vec<GamepadInfo>,
    lists: Option<Receiver<Vec<GamepadInfo>>>,
}

impl PadDrive {
    /// Starts reading `path` (None: stops reading the pad, stopping the base if it drove).
    pub fn choose(&mut self, shell: &mut Shell<'_>, path: Option<PathBuf>, settings: &DriveSettings) {
        self.halt(shell);
        self.gamepad = None;
        self.teleop = None;
        self.state = None;
        self.stopped = None;
        let Some(path) = path else { return };
        match Gamepad::open(&path, None, shell.waker.clone()) {
            Ok(gamepad) => {
                let config = TeleopConfig {
                    max_speed_m_per_s: settings.max_speed_m_per_s,
                    max_turn_rad_per_s: settings.max_turn_rad_per_s,
                    ..TeleopConfig::default()
                };
                self.gamepad = Some(gamepad);
                self.teleop = Some(Teleop::new(config));
                self.stopped = Some(StopReason::Released);
            }
            Err(error) => shell.report(error.to_string(), true),
        }
    }

    /// Whether a gamepad is being read.
    pub fn in_use(&self) -> bool {
        self.gamepad.is_some()
    }

    /// Whether the pad is driving the base.
    pub fn driving(&self) -> bool {
        self.teleop.as_ref().is_some_and(Teleop::driving)
    }

    /// The owner stopped the base (STOP, lost focus, the tab left, a new link):
    /// the pad lets go and waits for a fresh press.
    pub fn halt(&mut self, shell: &mut Shell<'_>) {
        self.armed = false;
        if let Some(Order::Stop(reason)) = self.teleop.as_mut().and_then(Teleop::halt) {
            self.stopped = Some(reason);
            if let Some(base) = shell.rflex_mut() {
                base.stop();
            }
        }
        if self.teleop.is_some() {
            self.stopped = Some(StopReason::Halted);
        }
    }

    /// Takes what the pad sent and drives the base by it; whether the window should keep repainting.
    pub fn tick(&mut self, shell: &mut Shell<'_>, now: Instant, accel: f64) -> bool {
        self.take_lists();
        let (Some(gamepad), Some(teleop)) = (&self.gamepad, &mut self.teleop) else { return false };
        let updates: Vec<(Instant, PadUpdate)> = gamepad.updates().try_iter().collect();
        let mut orders = Vec::new();
        let mut gone = None;
        for (at, update) in updates {
            let order = if self.armed {
                teleop.update(at, &update)
            } else {
                // Not allowed to drive (no focus, another tab): halted, and
                // only the dead-man followed — driving again takes a press
                // made once it is allowed.
                let halted = teleop.halt();
                teleop.follow(&update);
                halted
            };
            match update {
                PadUpdate::State(state) => self.state = Some(state),
                PadUpdate::Dropped => self.state = None,
                PadUpdate::Gone(why) => gone = Some(why),
            }
            orders.extend(order);
        }
        orders.extend(teleop.poll(now));
        let pending = teleop.poll_timeout().is_some();
        for order in orders {
            let Some(base) = shell.rflex_mut() else { break };
            match order {
                Order::Drive { speed_m_per_s, turn_rad_per_s } => {
                    self.stopped = None;
                    base.drive(speed_m_per_s, turn_rad_per_s, accel);
                }
                Order::Stop(reason) => {
                    self.stopped = Some(reason);
                    base.stop();
                }
            }
        }
        if !self.driving() && self.stopped.is_none() {
            self.stopped = Some(StopReason::Released);
        }
        if let Some(why) = gone {
            self.gamepad = None;
            self.teleop = None;
            self.state = None;
            self.stopped = Some(StopReason::Gone);
            let text = format!("{}: {why}", shell.words().rflex().msg_pad_gone);
            shell.report(text, true);
        }
        pending
    }

    /// The gamepads the computer has, read off the frame every two seconds.
    fn take_lists(&mut self) {
        if let Some(lists) = &self.lists
            && let Some(listed) = lists.try_iter().last()
        {
            self.listed = listed;
        }
    }

    fn scan(&mut self, waker: &Waker) {
        if self.lists.is_some() {
            return;
        }
        let (sender, lists) = crossbeam_channel::bounded(1);
        let waker = waker.clone();
        let started = std::thread::Builder::new().name("gamepad list".into()).spawn(move || {
            loop {
                match sender.try_send(crate::gamepad::list()) {
                    Ok(()) => waker(),
                    // The window has not taken the last list yet: this one waits for the next turn.
                    Err(crossbeam_channel::TrySendError::Full(_)) => {}
                    // Nobody looks any more.
                    Err(crossbeam_channel::TrySendError::Disconnected(_)) => return,
                }
                std::thread::sleep(RESCAN_EVERY);
            }
        });
        if started.is_ok() {
            self.lists = Some(lists);
        }
    }

    /// The gamepad row of the Drive panel. `focused`: whether the window has the focus.
    pub fn ui(&mut self, ui: &mut egui::Ui, words: &Strings, waker: &Waker, actions: &mut Vec<Action>) {
        self.scan(waker);
        let focused = ui.input(|input| input.focused);
        self.armed = focused;
        if !focused && self.driving() {
            // Losing the focus is letting go.
            actions.push(Action::Stop);
        }
        ui.horizontal(|ui| {
            let label = ui.label(words.rflex().gamepad);
            ui.add_enabled_ui(!self.in_use(), |ui| {
                ui.add(egui::TextEdit::singleline(&mut self.path).hint_text("/dev/input/event5").desired_width(220.0))
                    .labelled_by(label.id);
                let picked =
                    egui::ComboBox::from_id_salt("gamepad-picker").selected_text("").width(24.0).show_ui(ui, |ui| {
                        for pad in &self.listed {
                            let path = pad.path.display().to_string();
                            ui.selectable_value(&mut self.path, path.clone(), format!("{} — {path}", pad.name));
                        }
                        if self.listed.is_empty() {
                            ui.label("—");
                        }
                    });
                picked.response.labelled_by(label.id);
            });
            if self.in_use() {
                if ui.button(words.rflex().drop_gamepad).clicked() {
                    actions.push(Action::Rflex(RflexAction::UseGamepad(None)));
                }
            } else if ui
                .add_enabled(!self.path.trim().is_empty(), egui::Button::new(words.rflex().use_gamepad))
                .clicked()
            {
                actions.push(Action::Rflex(RflexAction::UseGamepad(Some(PathBuf::from(self.path.trim())))));
            }
        });
        if !self.in_use() {
            ui.add(egui::Label::new(egui::RichText::new(words.rflex().gamepad_hint).weak()).wrap());
            return;
        }
        let captions = words.rflex();
        let state = match self.stopped {
            None => captions.pad_driving,
            Some(StopReason::Released | StopReason::Gone) => captions.pad_released,
            Some(StopReason::Centred) => captions.pad_centred,
            Some(StopReason::Dropped) => captions.pad_dropped,
            Some(StopReason::Halted) => captions.pad_halted,
        };
        let stick = self
            .state
            .as_ref()
            .map_or((0.0, 0.0), |pad| (pad.axis(crate::gamepad::ABS_X), pad.axis(crate::gamepad::ABS_Y)));
        let held = self.state.as_ref().is_some_and(|pad| pad.pressed(crate::gamepad::BTN_TL));
        ui.monospace(format!(
            "BTN_TL {}  stick x {:+.2} y {:+.2}  — {state}",
            if held { "■" } else { "□" },
            stick.0,
            stick.1
        ));
    }
}
