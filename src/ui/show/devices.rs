//! The show window's devices, a row each: its name, family, port (typed, or
//! found by the USB id of the adapter behind it), what a lost link does, and
//! Remove (its cues go with it); **+ Device** adds the open project, a
//! project file, or a new servo board, PLEN2 or base.

use super::linked::{LinkState, state_words};
use super::{ShowAction, ShowSession, ShowWords, words::family_name};
use crate::link::by_id::Attached;
use crate::project::{Family, Project};
use crate::ui::Action;
use crate::ui::i18n::Said;

/// The devices' table, with each held link's state; `editable` while no
/// show plays and the boards are not held.
pub(super) fn devices_ui(
    ui: &mut egui::Ui,
    session: &mut ShowSession,
    (attached, links): (&[Attached], Option<&[LinkState]>),
    editable: bool,
    words: &ShowWords,
    actions: &mut Vec<Action>,
) {
    let mut remove = None;
    egui::Grid::new("show-devices").striped(true).show(ui, |ui| {
        for head in [words.device, words.family, words.port, "", words.if_lost, "", words.link] {
            ui.strong(head);
        }
        ui.end_row();
        for (index, (device, port)) in session.show.devices.iter_mut().zip(&mut session.ports).enumerate() {
            let label = ui.label(&device.name);
            ui.label(family_name(device.project.family, words));
            ui.add_enabled_ui(editable, |ui| {
                ui.add_sized([240.0, 20.0], egui::TextEdit::singleline(port).hint_text("/dev/ttyUSB0"))
                    .labelled_by(label.id);
            });
            ui.add_enabled_ui(editable, |ui| {
                ui.menu_button(words.find, |ui| find_menu(ui, port, attached, words));
            });
            ui.add_enabled(editable, egui::Checkbox::new(&mut device.play_on_without, words.play_on));
            if ui.add_enabled(editable, egui::Button::new(words.remove)).clicked() {
                remove = Some(index);
            }
            if let Some(state) = links.and_then(|links| links.get(index)) {
                let (said, well) = state_words(state, words);
                let color = if well { ui.visuals().text_color() } else { ui.visuals().warn_fg_color };
                // A long reason stays in its cell (whole on hover, and in the lines above).
                ui.scope(|ui| {
                    ui.set_max_width(300.0);
                    ui.add(egui::Label::new(egui::RichText::new(&said).color(color)).wrap());
                });
            }
            ui.end_row();
        }
    });
    if let Some(index) = remove {
        let name = session.show.devices.get(index).map(|device| device.name.clone()).unwrap_or_default();
        let cues = session.show.remove_device(index);
        session.touch();
        if index < session.ports.len() {
            session.ports.remove(index);
        }
        if cues > 0 {
            session
                .said
                .push(Said::new(|language| crate::say!(language, "show.cues_went", device = name, count = cues)));
        }
    }
    ui.add_enabled_ui(editable, |ui| ui.menu_button(words.add_device, |ui| add_menu(ui, session, words, actions)));
}

/// The USB serial adapters attached, listed on a thread of its own every
/// [`LIST_EVERY`] while the show window is open (a sysfs scan, not the frame's to wait for).
#[derive(Debug, Default)]
pub(super) struct Adapters {
    listed: Option<Vec<Attached>>,
    asked: Option<std::time::Instant>,
    coming: Option<crossbeam_channel::Receiver<Vec<Attached>>>,
}

/// How often the adapters are listed again.
const LIST_EVERY: std::time::Duration = std::time::Duration::from_secs(3);

impl Adapters {
    /// The adapters as last listed; a new listing asked for when it is time.
    pub(super) fn refresh(&mut self, ctx: &egui::Context) -> &[Attached] {
        if let Some(list) = self.coming.as_ref().and_then(|coming| coming.try_recv().ok()) {
            self.listed = Some(list);
            self.coming = None;
        }
        if self.coming.is_none() && self.asked.is_none_or(|at| at.elapsed() >= LIST_EVERY) {
            let (send, coming) = crossbeam_channel::bounded(1);
            let ctx = ctx.clone();
            let spawned = std::thread::Builder::new().name("usb adapters".into()).spawn(move || {
                let _ = send.send(crate::link::by_id::attached());
                ctx.request_repaint();
            });
            if spawned.is_ok() {
                self.coming = Some(coming);
            }
            self.asked = Some(std::time::Instant::now());
        }
        self.listed.as_deref().unwrap_or_default()
    }

    /// Whether they were listed at least once.
    #[cfg(any(test, feature = "test-api"))]
    pub(super) fn listed(&self) -> bool {
        self.listed.is_some()
    }
}

/// The USB serial devices attached now, each to pick as the port's id.
fn find_menu(ui: &mut egui::Ui, port: &mut String, attached: &[Attached], words: &ShowWords) {
    if attached.is_empty() {
        ui.label(words.none_attached);
    }
    for device in attached {
        let id = device.id.to_string();
        if ui.button(format!("{id} — {} ({})", device.description, device.port)).clicked() {
            *port = id;
            ui.close();
        }
    }
}

/// What a new device may hold: the open project, a project file, or a new one of a family.
fn add_menu(ui: &mut egui::Ui, session: &mut ShowSession, words: &ShowWords, actions: &mut Vec<Action>) {
    if ui.button(words.from_open).clicked() {
        actions.push(Action::Show(ShowAction::AddOpenProject));
        ui.close();
    }
    if ui.button(words.from_file).clicked() {
        actions.push(Action::AskFile(crate::ui::FileRequest::Pick(crate::ui::action::Pick {
            kind: words.lang.word("files.project"),
            extensions: &["json"],
            then: std::sync::Arc::new(|path| Action::Show(ShowAction::AddFromFile(path))),
        })));
        ui.close();
    }
    ui.separator();
    for &family in Family::all() {
        if ui.button(format!("{} {}", words.new, family_name(family, words))).clicked() {
            session.add(family.tag(), Project::empty(family));
            ui.close();
        }
    }
}
