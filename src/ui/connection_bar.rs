//! The connection bar: the board family, the port picker (refreshed as
//! devices come and go, or typed), baud, connect / cancel / disconnect, the
//! demo board, and the board's status.

use crate::device::line_settings;
use crate::link::PortInfo;
use crate::project::Family;
use crate::ui::action::Action;
use crate::ui::i18n::Language;

/// Standard line rates offered in the picker, up to the PLEN2's 2,000,000.
const BAUDS: [u32; 11] =
    [9_600, 19_200, 38_400, 57_600, 115_200, 230_400, 460_800, 500_000, 921_600, 1_000_000, 2_000_000];

/// What the bar shows of the current link.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LinkStatus {
    /// The family of the document and of the connection.
    pub family: Family,
    /// Whether a link is open or opening (the settings cannot change then).
    pub busy: bool,
    /// What it is connected to, if connected.
    pub label: Option<String>,
    /// The port being opened, while connecting.
    pub connecting: Option<String>,
    /// What the family says of its connected board (project id, battery…), in words.
    pub details: Vec<String>,
    /// What the connection doctor found, a line per port, while not connected.
    pub doctor: Vec<DoctorLine>,
    /// A lost link waits for its device to come back (it can be given up).
    pub reconnecting: bool,
}

/// The connection doctor's line under the bar.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct DoctorLine {
    /// The port asked.
    pub port: String,
    /// What it found (or is doing), in words.
    pub text: String,
    /// A board that answered: its family and line rate.
    pub offer: Option<(Family, u32)>,
    /// Still asking.
    pub busy: bool,
}

/// The connection bar's own state.
#[derive(Debug)]
pub struct ConnectionBar {
    port: String,
    baud: u32,
    /// The family whose default baud `baud` was set from.
    baud_family: Option<Family>,
    /// Hardware = Auto: Connect asks the board which family it is first.
    auto: bool,
}

impl Default for ConnectionBar {
    fn default() -> Self {
        Self { port: String::new(), baud: line_settings(Family::Servo).baud, baud_family: None, auto: false }
    }
}

impl ConnectionBar {
    /// Draws the bar; `extras` draws the family's own pickers after the family's.
    pub fn ui(
        &mut self,
        ui: &mut egui::Ui,
        (status, ports, language): (&LinkStatus, &[PortInfo], Language),
        actions: &mut Vec<Action>,
        extras: impl FnOnce(&mut egui::Ui, &mut Vec<Action>),
    ) {
        let words = language.strings();
        if self.port.is_empty()
            && let Some(first) = ports.first()
        {
            self.port = first.name.clone();
        }
        if self.baud_family != Some(status.family) {
            // Each family has its own line rate; switching family picks it.
            self.baud_family = Some(status.family);
            self.baud = line_settings(status.family).baud;
        }
        ui.horizontal_wrapped(|ui| {
            ui.add_enabled_ui(!status.busy, |ui| self.pickers(ui, (status, ports, language), actions, extras));
            self.buttons(ui, status, language, actions);
        });
        // Its own line, never wrapped: the controls above must not move when the status arrives.
        let text = status_text(status, language);
        ui.add(egui::Label::new(&text).truncate()).on_hover_text(text);
        for doctor in &status.doctor {
            ui.horizontal(|ui| {
                if doctor.busy {
                    ui.spinner();
                }
                if let Some((family, baud)) = doctor.offer
                    && ui.add_enabled(!status.busy, egui::Button::new(words.use_found)).clicked()
                {
                    // The pickers show the port, family and rate it connects with.
                    (self.port, self.baud_family, self.baud) = (doctor.port.clone(), Some(family), baud);
                    actions.push(Action::ConnectFound { port: doctor.port.clone(), family, baud });
                }
                ui.add(egui::Label::new(&doctor.text).truncate()).on_hover_text(&doctor.text);
            });
        }
    }

    /// The family, the family's own pickers, the port and the line rate.
    fn pickers(
        &mut self,
        ui: &mut egui::Ui,
        (status, ports, language): (&LinkStatus, &[PortInfo], Language),
        actions: &mut Vec<Action>,
        extras: impl FnOnce(&mut egui::Ui, &mut Vec<Action>),
    ) {
        let words = language.strings();
        let family_label = ui.label(words.family);
        // `None` is Auto: the board is asked which family it is when Connect is pressed.
        let mut family = (!self.auto).then_some(status.family);
        let shown = match family {
            Some(family) => language.family(family).to_string(),
            None => format!("{} · {}", words.auto_family, language.family(status.family)),
        };
        let picked = egui::ComboBox::from_id_salt("family-picker").selected_text(shown).show_ui(ui, |ui| {
            ui.selectable_value(&mut family, None, words.auto_family);
            for &option in Family::all() {
                ui.selectable_value(&mut family, Some(option), language.family(option));
            }
        });
        picked.response.labelled_by(family_label.id);
        self.auto = family.is_none();
        if let Some(family) = family.filter(|family| *family != status.family) {
            actions.push(Action::SetFamily(family));
        }
        extras(ui, actions);
        let port_label = ui.label(words.port);
        // While connected the field shows what the link is to (the demo board
        // has no port), not what was last typed.
        let mut shown = status.label.clone().or_else(|| status.connecting.clone());
        let field = shown.as_mut().unwrap_or(&mut self.port);
        ui.add(egui::TextEdit::singleline(field).hint_text("/dev/ttyUSB0, COM3, tcp://host:port").desired_width(180.0))
            .labelled_by(port_label.id);
        let picked = egui::ComboBox::from_id_salt("port-picker").selected_text("").width(24.0).show_ui(ui, |ui| {
            for port in ports {
                ui.selectable_value(&mut self.port, port.name.clone(), format!("{} — {}", port.name, port.description));
            }
            if ports.is_empty() {
                ui.label("—");
            } else if ui.button(words.find_every_board).clicked() {
                actions.push(Action::FindEveryBoard);
            }
        });
        picked.response.labelled_by(port_label.id);
        let baud_label = ui.label(words.baud);
        let picked =
            egui::ComboBox::from_id_salt("baud-picker").selected_text(self.baud.to_string()).show_ui(ui, |ui| {
                for baud in BAUDS {
                    ui.selectable_value(&mut self.baud, baud, baud.to_string());
                }
            });
        picked.response.labelled_by(baud_label.id);
    }

    /// Connect, Find board and Demo board; Cancel or Disconnect once started.
    fn buttons(&mut self, ui: &mut egui::Ui, status: &LinkStatus, language: Language, actions: &mut Vec<Action>) {
        let words = language.strings();
        if status.connecting.is_some() {
            ui.spinner();
            if ui.button(words.cancel).clicked() {
                actions.push(Action::CancelConnect);
            }
        } else if status.label.is_some() {
            if ui.button(words.disconnect).clicked() {
                actions.push(Action::Disconnect);
            }
        } else {
            let connect = ui.add_enabled(!self.port.trim().is_empty(), egui::Button::new(words.connect));
            if connect.clicked() {
                let port = self.port.trim().to_string();
                actions.push(if self.auto {
                    Action::FindBoard { port, connect: true }
                } else {
                    Action::Connect { port, baud: self.baud }
                });
            }
            let find =
                ui.add_enabled(!status.busy && !self.port.trim().is_empty(), egui::Button::new(words.find_board));
            if find.clicked() {
                actions.push(Action::FindBoard { port: self.port.trim().to_string(), connect: false });
            }
            let demo = ui.button(words.demo_board);
            if demo.clicked() {
                actions.push(Action::ConnectDemo);
            }
            if status.reconnecting {
                ui.spinner();
                if ui.button(words.cancel).on_hover_text(words.msg_stop_waiting).clicked() {
                    actions.push(Action::CancelConnect);
                }
            }
        }
    }
}

/// The bar's status words: one sentence in the interface's language.
pub fn status_text(status: &LinkStatus, language: Language) -> String {
    let words = language.strings();
    if let Some(port) = &status.connecting {
        return language.connecting_to(port);
    }
    let Some(label) = &status.label else { return words.not_connected.to_string() };
    let mut parts = vec![format!("{} {label}", words.connected_to)];
    parts.extend(status.details.iter().cloned());
    parts.join(" · ")
}

#[cfg(test)]
mod tests {
    use egui::accesskit::Role;
    use egui_kittest::Harness;
    use egui_kittest::kittest::{Queryable, by};

    use super::*;

    type Bar = (ConnectionBar, Vec<Action>);

    fn bar(status: LinkStatus, ports: Vec<PortInfo>) -> Harness<'static, Bar> {
        Harness::builder()
            .with_size(egui::vec2(1100.0, 120.0))
            .with_context_setup(crate::ui::fonts::install)
            .build_ui_state(
                move |ui, (bar, actions): &mut Bar| {
                    bar.ui(ui, (&status, &ports, Language::English), actions, |ui, _| {
                        ui.label("the family's own picker");
                    });
                },
                (ConnectionBar::default(), Vec::new()),
            )
    }

    #[test]
    fn connect_sends_the_first_port_found_at_the_familys_line_rate_and_the_family_picker_is_in_the_bar() {
        let status = LinkStatus { family: Family::Plen2, ..LinkStatus::default() };
        let ports = vec![PortInfo { name: "/dev/ttyUSB7".into(), description: "test adapter".into() }];
        let mut harness = bar(status, ports);
        harness.run();
        assert!(harness.query_by_label("the family's own picker").is_some());
        harness.get_by_label("Connect").click();
        harness.run();
        assert_eq!(harness.state().1, [Action::Connect { port: "/dev/ttyUSB7".into(), baud: 2_000_000 }]);
    }

    /// Hardware = Auto: Connect asks the board which family it is first;
    /// Find board only asks; what was found is offered with its family and rate.
    #[test]
    fn auto_connects_through_the_doctor_and_a_finding_is_offered() {
        let status = LinkStatus { family: Family::Servo, ..LinkStatus::default() };
        let ports = vec![PortInfo { name: "/dev/ttyACM0".into(), description: String::new() }];
        let mut harness = bar(status.clone(), ports.clone());
        harness.run();
        harness.get_by_label("Find board").click();
        harness.run();
        harness.get(by().role(Role::ComboBox).label("Hardware")).click();
        harness.run();
        harness.get_by_label("Auto (find it)").click();
        harness.run();
        harness.get_by_label("Connect").click();
        harness.run();
        let asked = vec![
            Action::FindBoard { port: "/dev/ttyACM0".into(), connect: false },
            Action::FindBoard { port: "/dev/ttyACM0".into(), connect: true },
        ];
        assert_eq!(harness.state().1, asked);
        assert!(harness.state().0.auto, "the picker stays on Auto");

        let doctor = DoctorLine {
            port: "/dev/ttyACM0".into(),
            text: "/dev/ttyACM0: PLEN2 Cytisus 1.4.2".into(),
            offer: Some((Family::Plen2, 2_000_000)),
            busy: false,
        };
        let mut harness = bar(LinkStatus { doctor: vec![doctor], ..status }, ports);
        harness.run();
        assert!(harness.query_by_label("/dev/ttyACM0: PLEN2 Cytisus 1.4.2").is_some());
        harness.get_by_label("Connect to it").click();
        harness.run();
        let found = Action::ConnectFound { port: "/dev/ttyACM0".into(), family: Family::Plen2, baud: 2_000_000 };
        assert_eq!(harness.state().1, [found]);
    }

    #[test]
    fn the_status_line_says_what_the_family_said_of_its_board() {
        let status = LinkStatus {
            label: Some("Demo board".into()),
            details: vec!["Project 7".into(), "Battery 81.5 %".into()],
            ..LinkStatus::default()
        };
        assert_eq!(status_text(&status, Language::English), "Connected to Demo board · Project 7 · Battery 81.5 %");
        let connecting = LinkStatus { connecting: Some("/dev/ttyUSB0".into()), ..LinkStatus::default() };
        assert!(status_text(&connecting, Language::English).contains("/dev/ttyUSB0"));
    }
}
