//! The connection bar: port picker (refreshed as devices come and go, or
//! typed), baud, connect / disconnect, the demo board, and the board's status.

use std::time::{Duration, Instant};

use crate::link::{DEFAULT_BAUD, PortInfo, list_ports};
use crate::ui::action::Action;
use crate::ui::i18n::Strings;

/// Standard line rates offered in the picker.
const BAUDS: [u32; 8] = [9_600, 19_200, 38_400, 57_600, 115_200, 230_400, 460_800, 1_000_000];
/// How often the port list is read again.
const RESCAN_EVERY: Duration = Duration::from_secs(2);

/// What the bar shows of the current link.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct LinkStatus {
    /// What it is connected to, if connected.
    pub label: Option<String>,
    /// The board's project id.
    pub project_id: Option<i32>,
    /// Battery, ‰.
    pub battery_permil: Option<i16>,
    /// Free and total memory.
    pub memory: Option<(i32, Option<i32>)>,
}

/// The connection bar's own state.
#[derive(Debug)]
pub struct ConnectionBar {
    port: String,
    baud: u32,
    ports: Vec<PortInfo>,
    next_scan: Option<Instant>,
}

impl Default for ConnectionBar {
    fn default() -> Self {
        Self { port: String::new(), baud: DEFAULT_BAUD, ports: Vec::new(), next_scan: None }
    }
}

impl ConnectionBar {
    fn rescan(&mut self, now: Instant) {
        if self.next_scan.is_some_and(|at| now < at) {
            return;
        }
        self.next_scan = Some(now + RESCAN_EVERY);
        // A failed scan leaves the last list; the port can still be typed.
        if let Ok(ports) = list_ports() {
            self.ports = ports;
        }
        if self.port.is_empty()
            && let Some(first) = self.ports.first()
        {
            self.port = first.name.clone();
        }
    }

    /// Draws the bar.
    pub fn ui(&mut self, ui: &mut egui::Ui, status: &LinkStatus, words: &Strings, actions: &mut Vec<Action>) {
        self.rescan(Instant::now());
        ui.horizontal_wrapped(|ui| {
            let connected = status.label.is_some();
            ui.add_enabled_ui(!connected, |ui| {
                let port_label = ui.label(words.port);
                ui.add(
                    egui::TextEdit::singleline(&mut self.port)
                        .hint_text("/dev/ttyUSB0, COM3, tcp://host:port")
                        .desired_width(180.0),
                )
                .labelled_by(port_label.id);
                let picked =
                    egui::ComboBox::from_id_salt("port-picker").selected_text("").width(24.0).show_ui(ui, |ui| {
                        for port in &self.ports {
                            ui.selectable_value(
                                &mut self.port,
                                port.name.clone(),
                                format!("{} — {}", port.name, port.description),
                            );
                        }
                        if self.ports.is_empty() {
                            ui.label("—");
                        }
                    });
                picked.response.labelled_by(port_label.id);
                let baud_label = ui.label(words.baud);
                let picked = egui::ComboBox::from_id_salt("baud-picker").selected_text(self.baud.to_string()).show_ui(
                    ui,
                    |ui| {
                        for baud in BAUDS {
                            ui.selectable_value(&mut self.baud, baud, baud.to_string());
                        }
                    },
                );
                picked.response.labelled_by(baud_label.id);
            });
            if connected {
                if ui.button(words.disconnect).clicked() {
                    actions.push(Action::Disconnect);
                }
            } else {
                if ui.add_enabled(!self.port.trim().is_empty(), egui::Button::new(words.connect)).clicked() {
                    actions.push(Action::Connect { port: self.port.trim().to_string(), baud: self.baud });
                }
                if ui.button(words.demo_board).clicked() {
                    actions.push(Action::ConnectDemo);
                }
            }
            ui.separator();
            match &status.label {
                None => {
                    ui.label(words.not_connected);
                }
                Some(label) => {
                    ui.label(format!("{} {label}", words.connected_to));
                    if let Some(project_id) = status.project_id {
                        ui.label(format!("{} {project_id}", words.project));
                    }
                    if let Some(permil) = status.battery_permil {
                        ui.label(format!("{} {permil}‰", words.battery));
                    }
                    if let Some((free, total)) = status.memory {
                        let text = match total {
                            Some(total) => format!("{} {free} / {total} B", words.free_memory),
                            None => format!("{} {free} B", words.free_memory),
                        };
                        ui.label(text);
                    }
                }
            }
        });
    }
}
