//! The gamepad in the editor, for every family: which one is read (picked
//! from those the computer has — listed off the frame as they come and go —
//! or given as a path), its live state (the Gamepad tab lights each button and
//! shows each axis: with Test mode on nothing fires or moves), and the
//! project's bindings for the family shown, edited there: "press a button to
//! bind it", "move an axis to bind it", conflicts named.

use std::path::PathBuf;
use std::time::{Duration, Instant};

use crossbeam_channel::Receiver;

use crate::gamepad::puppet::{Cue, Puppeteer};
use crate::gamepad::{EV_ABS, EV_KEY, Gamepad, GamepadInfo, Gone, PadState, PadUpdate, code_name};
use crate::link::Waker;
use crate::project::gamepad::{AxisBinding, AxisMode, AxisTarget, ButtonBinding, Conflict, Fire, Mapping};
use crate::project::{Edit, Family};
use crate::ui::action::{Action, Bind};
use crate::ui::i18n::{PadConflict, Strings};

/// How often the gamepad list is read again.
const RESCAN_EVERY: Duration = Duration::from_secs(2);
/// How far an axis must move from where it was to be bound.
const BIND_MOVE: f64 = 0.5;

/// Something an axis can move, as a family offers it.
#[derive(Clone, Debug, PartialEq)]
pub struct PadTarget {
    /// The servo or joint.
    pub target: AxisTarget,
    /// Its name in the interface.
    pub name: String,
    /// Its limits, degrees.
    pub limits: (f64, f64),
    /// Where it is now, degrees.
    pub at: f64,
}

/// The gamepad the editor reads.
#[derive(Debug, Default)]
pub struct PadInput {
    /// The path typed or picked.
    pub path: String,
    gamepad: Option<Gamepad>,
    /// Its state after the last frame it sent.
    pub state: Option<PadState>,
    /// Test mode: buttons light up, nothing fires or moves.
    pub test_mode: bool,
    /// Waiting for a press or a move to bind, and the state when that began.
    pub binding: Option<(Bind, Option<PadState>)>,
    puppet: Puppeteer,
    listed: Vec<GamepadInfo>,
    lists: Option<Receiver<Vec<GamepadInfo>>>,
}

impl PadInput {
    /// Starts reading `path`, or stops reading (None).
    pub fn choose(&mut self, path: Option<PathBuf>, waker: &Waker) -> Result<(), String> {
        self.gamepad = None;
        self.state = None;
        self.binding = None;
        self.puppet = Puppeteer::new();
        let Some(path) = path else { return Ok(()) };
        self.path = path.display().to_string();
        self.gamepad = Some(Gamepad::open(&path, None, waker.clone()).map_err(|error| error.to_string())?);
        Ok(())
    }

    /// Whether a gamepad is being read.
    pub fn in_use(&self) -> bool {
        self.gamepad.is_some()
    }

    /// What the gamepad sent since the last frame (its state kept); the
    /// gamepad is let go once it is gone, and why is returned too.
    pub fn take(&mut self) -> (Vec<(Instant, PadUpdate)>, Option<Gone>) {
        self.take_lists();
        let Some(gamepad) = &self.gamepad else { return (Vec::new(), None) };
        let updates: Vec<(Instant, PadUpdate)> = gamepad.updates().try_iter().collect();
        let mut gone = None;
        for (_, update) in &updates {
            match update {
                PadUpdate::State(state) => self.state = Some(state.clone()),
                PadUpdate::Dropped => self.state = None,
                PadUpdate::Gone(why) => gone = Some(why.clone()),
            }
        }
        if gone.is_some() {
            self.gamepad = None;
            self.state = None;
            self.binding = None;
        }
        (updates, gone)
    }

    /// The bindings at work: what `mapping` asks for after `updates` and at
    /// `now`. Nothing is asked while binding or in test mode (the pad is still
    /// followed, so a button held meanwhile does not fire later).
    pub fn cues(
        &mut self,
        mapping: &Mapping,
        now: Instant,
        updates: &[(Instant, PadUpdate)],
        targets: &[PadTarget],
    ) -> Vec<Cue> {
        let limits = |target: AxisTarget| targets.iter().find(|t| t.target == target).map_or((0.0, 0.0), |t| t.limits);
        let at = |target: AxisTarget| targets.iter().find(|t| t.target == target).map_or(0.0, |t| t.at);
        let mut cues = Vec::new();
        for (when, update) in updates {
            cues.extend(self.puppet.update(mapping, *when, update, &limits, &at));
        }
        cues.extend(self.puppet.tick(mapping, now, &limits, &at));
        // A binding to a servo or joint the project does not have (a file edited by hand) moves nothing.
        cues.retain(|cue| match cue {
            Cue::Move { target, .. } => targets.iter().any(|known| known.target == *target),
            Cue::Fire(_) => true,
        });
        if self.test_mode || self.binding.is_some() { Vec::new() } else { cues }
    }

    /// Whether a rate axis is deflected (the window keeps repainting).
    pub fn moving(&self, mapping: &Mapping) -> bool {
        self.puppet.moving(mapping)
    }

    /// While binding: the binding the pad's new state makes (a button newly
    /// pressed, an axis moved far), added to `mapping` as an edit.
    pub fn bound(
        &mut self,
        family: Family,
        mapping: &Mapping,
        targets: &[PadTarget],
        fires: &[(Fire, String)],
    ) -> Option<Action> {
        let (bind, base) = self.binding.clone()?;
        let state = self.state.as_ref()?;
        let mut mapping = mapping.clone();
        match bind {
            Bind::Button => {
                let button = state.buttons().find(|code| !base.as_ref().is_some_and(|base| base.pressed(*code)))?;
                let fire = fires.first().map_or(Fire::Stop, |(fire, _)| *fire);
                mapping.buttons.push(ButtonBinding { button, fire });
            }
            Bind::Axis => {
                let moved = |code: u16, value: f64| (value - base.as_ref().map_or(0.0, |base| base.axis(code))).abs();
                let (axis, _) = state.axes().find(|(code, value)| moved(*code, *value) >= BIND_MOVE)?;
                let target = targets.first()?;
                mapping.axes.push(AxisBinding::absolute(axis, target.target, target.limits));
            }
        }
        self.binding = None;
        Some(Action::Edit { edit: Edit::SetGamepad(family, Box::new(mapping)), coalesce: None })
    }

    fn take_lists(&mut self) {
        if let Some(lists) = &self.lists
            && let Some(listed) = lists.try_iter().last()
        {
            self.listed = listed;
        }
    }

    /// Starts reading the computer's gamepad list, once.
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
}

/// What the Gamepad tab shows of the family's side.
pub struct PadPanel<'a> {
    /// The family whose bindings are edited.
    pub family: Family,
    /// Its bindings.
    pub mapping: &'a Mapping,
    /// What its axes can move.
    pub targets: &'a [PadTarget],
    /// What its buttons can fire, with names.
    pub fires: &'a [(Fire, String)],
    /// Buttons another use holds (the rFLEX dead-man).
    pub reserved: &'a [u16],
    /// Wakes the window (the gamepad list's thread).
    pub waker: &'a Waker,
}

/// The buttons the test view always shows, lit when held.
const SHOWN_BUTTONS: [u16; 8] = [0x130, 0x131, 0x133, 0x134, 0x136, 0x137, 0x13a, 0x13b];
/// The axes the test view always shows.
const SHOWN_AXES: [u16; 8] = [0x00, 0x01, 0x03, 0x04, 0x02, 0x05, 0x10, 0x11];

/// The Gamepad tab.
pub fn panel(ui: &mut egui::Ui, pad: &mut PadInput, view: &PadPanel<'_>, words: &Strings, actions: &mut Vec<Action>) {
    pad.scan(view.waker);
    picker(ui, pad, words, actions);
    ui.separator();
    if !pad.in_use() {
        ui.label(words.gamepad_none);
    } else {
        test_view(ui, pad, words, actions);
    }
    ui.separator();
    egui::ScrollArea::vertical().auto_shrink([false, false]).show(ui, |ui| bindings(ui, pad, view, words, actions));
}

fn picker(ui: &mut egui::Ui, pad: &mut PadInput, words: &Strings, actions: &mut Vec<Action>) {
    ui.horizontal(|ui| {
        let label = ui.label(words.gamepad);
        ui.add_enabled_ui(!pad.in_use(), |ui| {
            ui.add(egui::TextEdit::singleline(&mut pad.path).hint_text("/dev/input/event5").desired_width(260.0))
                .labelled_by(label.id);
            let picked =
                egui::ComboBox::from_id_salt("gamepad-picker").selected_text("").width(24.0).show_ui(ui, |ui| {
                    for listed in &pad.listed {
                        let path = listed.path.display().to_string();
                        ui.selectable_value(&mut pad.path, path.clone(), format!("{} — {path}", listed.name));
                    }
                    if pad.listed.is_empty() {
                        ui.label("—");
                    }
                });
            picked.response.labelled_by(label.id);
        });
        if pad.in_use() {
            if ui.button(words.drop_gamepad).clicked() {
                actions.push(Action::UseGamepad(None));
            }
        } else if ui.add_enabled(!pad.path.trim().is_empty(), egui::Button::new(words.use_gamepad)).clicked() {
            actions.push(Action::UseGamepad(Some(PathBuf::from(pad.path.trim()))));
        }
        let mut test = pad.test_mode;
        if ui.checkbox(&mut test, words.pad_test_mode).changed() {
            actions.push(Action::PadTestMode(test));
        }
    });
}

/// Each button lit while held, each axis as a bar.
fn test_view(ui: &mut egui::Ui, pad: &PadInput, words: &Strings, actions: &mut Vec<Action>) {
    let state = pad.state.clone().unwrap_or_default();
    ui.horizontal_wrapped(|ui| {
        let mut shown: Vec<u16> = SHOWN_BUTTONS.to_vec();
        shown.extend(state.buttons().filter(|code| !SHOWN_BUTTONS.contains(code)));
        for code in shown {
            let held = state.pressed(code);
            let text = egui::RichText::new(code_name(EV_KEY, code)).monospace();
            let fill = if held { ui.visuals().selection.bg_fill } else { ui.visuals().extreme_bg_color };
            ui.add(egui::Button::new(text).fill(fill).selected(held).sense(egui::Sense::hover()));
        }
    });
    ui.horizontal_wrapped(|ui| {
        for code in SHOWN_AXES {
            let value = state.axis(code);
            ui.vertical(|ui| {
                ui.monospace(format!("{} {value:+.2}", code_name(EV_ABS, code)));
                // A bar's fill is an f32 anyway: the axis's −1..1 loses nothing visible.
                #[allow(clippy::cast_possible_truncation)]
                let filled = ((value + 1.0) / 2.0) as f32;
                ui.add(egui::ProgressBar::new(filled).desired_width(110.0));
            });
        }
    });
    if pad.binding.is_some() {
        ui.horizontal(|ui| {
            ui.spinner();
            ui.label(words.pad_binding_wait);
            if ui.button(words.cancel).clicked() {
                actions.push(Action::BindPad(None));
            }
        });
    }
}

fn bindings(ui: &mut egui::Ui, pad: &PadInput, view: &PadPanel<'_>, words: &Strings, actions: &mut Vec<Action>) {
    let mut mapping = view.mapping.clone();
    let conflicts = mapping.conflicts(view.reserved);
    for conflict in &conflicts {
        let button = |code: &u16| code_name(EV_KEY, *code);
        let what = match conflict {
            Conflict::Button(code) => words.lang.pad_conflict(PadConflict::Button(&button(code))),
            Conflict::Reserved(code) => words.lang.pad_conflict(PadConflict::Deadman(&button(code))),
            Conflict::Target(target) => {
                let name = view.targets.iter().find(|t| t.target == *target).map_or("?", |t| t.name.as_str());
                words.lang.pad_conflict(PadConflict::Target(name))
            }
        };
        ui.colored_label(ui.visuals().error_fg_color, format!("{}: {what}", words.pad_conflict));
    }
    ui.horizontal(|ui| {
        ui.heading(words.pad_axes);
        let can = pad.in_use() && pad.binding.is_none() && !view.targets.is_empty();
        if ui.add_enabled(can, egui::Button::new(words.pad_bind_axis)).clicked() {
            actions.push(Action::BindPad(Some(Bind::Axis)));
        }
        if view.targets.is_empty() {
            ui.weak(words.pad_nothing_to_move);
        }
    });
    let mut remove_axis = None;
    for (index, binding) in mapping.axes.iter_mut().enumerate() {
        ui.horizontal(|ui| {
            ui.push_id(("axis", index), |ui| axis_row(ui, binding, view, words, &mut remove_axis, index));
        });
    }
    ui.horizontal(|ui| {
        ui.heading(words.pad_buttons);
        if ui.add_enabled(pad.in_use() && pad.binding.is_none(), egui::Button::new(words.pad_bind_button)).clicked() {
            actions.push(Action::BindPad(Some(Bind::Button)));
        }
    });
    let mut remove_button = None;
    for (index, binding) in mapping.buttons.iter_mut().enumerate() {
        ui.horizontal(|ui| {
            ui.push_id(("button", index), |ui| {
                let held = pad.state.as_ref().is_some_and(|state| state.pressed(binding.button));
                let name = egui::RichText::new(code_name(EV_KEY, binding.button)).monospace();
                ui.add(egui::Button::new(name).selected(held).sense(egui::Sense::hover()));
                let label = ui.label(words.pad_fires);
                let shown =
                    view.fires.iter().find(|(fire, _)| *fire == binding.fire).map_or("?", |(_, name)| name.as_str());
                let picked = egui::ComboBox::from_id_salt("fire").selected_text(shown).show_ui(ui, |ui| {
                    for (fire, name) in view.fires {
                        ui.selectable_value(&mut binding.fire, *fire, name);
                    }
                });
                picked.response.labelled_by(label.id);
                if ui.button(words.pad_remove).clicked() {
                    remove_button = Some(index);
                }
            });
        });
    }
    if let Some(index) = remove_axis {
        mapping.axes.remove(index);
    }
    if let Some(index) = remove_button {
        mapping.buttons.remove(index);
    }
    if &mapping != view.mapping {
        let coalesce = Some(format!("gamepad {}", view.family));
        actions.push(Action::Edit { edit: Edit::SetGamepad(view.family, Box::new(mapping)), coalesce });
    }
}

fn axis_row(
    ui: &mut egui::Ui,
    binding: &mut AxisBinding,
    view: &PadPanel<'_>,
    words: &Strings,
    remove: &mut Option<usize>,
    index: usize,
) {
    ui.monospace(code_name(EV_ABS, binding.axis));
    let label = ui.label(words.pad_moves);
    let shown = view.targets.iter().find(|t| t.target == binding.target).map_or("?", |t| t.name.as_str());
    let picked = egui::ComboBox::from_id_salt("target").selected_text(shown).show_ui(ui, |ui| {
        for target in view.targets {
            ui.selectable_value(&mut binding.target, target.target, &target.name);
        }
    });
    picked.response.labelled_by(label.id);
    let (low, high) = view.targets.iter().find(|t| t.target == binding.target).map_or((-180.0, 180.0), |t| t.limits);
    let range = low.min(high)..=high.max(low);
    // A range past the target's limits is kept as the file has it (the target stops at its limits);
    // dragging stays within them.
    fn angle(value: &mut f64, range: std::ops::RangeInclusive<f64>) -> egui::DragValue<'_> {
        egui::DragValue::new(value).range(range).clamp_existing_to_range(false).speed(0.5)
    }
    let min = ui.label(words.pad_min);
    ui.add(angle(&mut binding.min_deg, range.clone())).labelled_by(min.id);
    let max = ui.label(words.pad_max);
    ui.add(angle(&mut binding.max_deg, range)).labelled_by(max.id);
    let zone = ui.label(words.pad_dead_zone);
    let zone_value = egui::DragValue::new(&mut binding.dead_zone).range(0.0..=0.9).clamp_existing_to_range(false);
    ui.add(zone_value.speed(0.01)).labelled_by(zone.id);
    ui.checkbox(&mut binding.invert, words.pad_invert);
    let mut rate = matches!(binding.mode, AxisMode::Rate { .. });
    if ui.checkbox(&mut rate, words.pad_rate).changed() {
        binding.mode = if rate { AxisMode::Rate { deg_per_s: 90.0 } } else { AxisMode::Absolute };
    }
    if let AxisMode::Rate { deg_per_s } = &mut binding.mode {
        let rate = egui::DragValue::new(deg_per_s).range(1.0..=720.0).clamp_existing_to_range(false);
        ui.add(rate.speed(1.0).suffix(" °/s")).labelled_by(label.id);
    }
    if ui.button(words.pad_remove).clicked() {
        *remove = Some(index);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gamepad::{ABS_RX, ABS_X, RawEvent};

    /// Axes move only what the project has; a binding to a servo it does not
    /// have (a file edited by hand) moves nothing, rather than send it to 0°.
    #[test]
    fn a_binding_to_a_missing_servo_moves_nothing() {
        let mapping = Mapping {
            axes: vec![
                AxisBinding::absolute(ABS_RX, AxisTarget::Servo(1), (-90.0, 90.0)),
                AxisBinding::absolute(ABS_X, AxisTarget::Servo(99), (-90.0, 90.0)),
            ],
            buttons: Vec::new(),
        };
        let targets = [PadTarget { target: AxisTarget::Servo(1), name: "#1".into(), limits: (-45.0, 45.0), at: 0.0 }];
        let mut state = PadState::default();
        state.apply(RawEvent::abs(ABS_RX, 32767));
        state.apply(RawEvent::abs(ABS_X, 32767));
        state.apply(RawEvent::report());
        let now = Instant::now();
        let mut pad = PadInput::default();
        let cues = pad.cues(&mapping, now, &[(now, PadUpdate::State(state))], &targets);
        assert_eq!(cues, [Cue::Move { target: AxisTarget::Servo(1), degrees: 45.0 }]);
    }
}
