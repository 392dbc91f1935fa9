//! The app shell's connection: opening a port off the UI thread, starting the
//! family's driver, and turning what the board reports into status lines.

use super::*;

impl StudioApp {
    /// Picks up what the board sent since the last frame.
    pub fn pump(&mut self, now: Instant) {
        self.poll_job();
        self.poll_plen2_job();
        self.advance_stream(now);
        self.poll_connecting();
        let Some(link) = &mut self.link else { return };
        for notice in link.pump(now, self.polling) {
            match notice {
                LinkNotice::SendFailed(error) => {
                    self.status = Some(StatusLine { text: self.language.send_failed(&error), is_error: true });
                }
                LinkNotice::RequestFailed(error) => {
                    self.status = Some(StatusLine { text: self.language.request_error(&error), is_error: true });
                }
                LinkNotice::PacingWidened(widened) => {
                    // Not an error: the upload goes on, more carefully.
                    self.status = Some(StatusLine { text: self.language.pacing_widened(&widened), is_error: false });
                }
                LinkNotice::BaseSilent => {
                    self.drive_panel = DrivePanel::default();
                    self.status = Some(StatusLine { text: self.words().msg_base_silent.into(), is_error: true });
                }
                LinkNotice::MacroRefused => {
                    self.status =
                        Some(StatusLine { text: self.language.strings().msg_macro_refused.into(), is_error: true });
                }
                LinkNotice::Disconnected(reason) => {
                    self.status = Some(StatusLine { text: self.language.link_ended(&reason), is_error: true });
                    self.link = None;
                    self.polling = false;
                    return;
                }
                LinkNotice::Button { button_id, event } => {
                    self.button_events.push((button_id, event));
                    if let Some(table_index) = self.picking.take() {
                        self.pick_button(table_index, button_id);
                    }
                }
            }
        }
    }

    /// The connected servo board, if any.
    pub fn servo(&self) -> Option<&ServoHandle> {
        self.link.as_ref().and_then(BoardLink::servo)
    }

    pub(super) fn servo_mut(&mut self) -> Option<&mut ServoHandle> {
        self.link.as_mut().and_then(BoardLink::servo_mut)
    }

    /// Opens `port` off the UI thread with the document's family's line settings.
    pub(super) fn connect(&mut self, port: &str, baud: u32) {
        let name = match PortName::parse(port) {
            Ok(name) => name,
            Err(error) => {
                self.report(self.language.link_error(&error), true);
                return;
            }
        };
        let family = self.document.project.family;
        if !BoardLink::supports(family) {
            // Say so before touching the port.
            self.report(self.language.family_not_in_build(family), true);
            return;
        }
        let settings = crate::link::LineSettings { baud, ..crate::device::line_settings(family) };
        self.report(self.language.connecting_to(&name.to_string()), false);
        let opening = Opening::start(name, settings, self.opener.clone(), self.waker.clone());
        self.connecting = Some(Connecting { opening, family, baud });
    }

    /// Starts the driver once the port is open, or reports why it did not open.
    pub(super) fn poll_connecting(&mut self) {
        let Some(connecting) = &self.connecting else { return };
        let Some(result) = connecting.opening.poll() else { return };
        let Some(Connecting { opening, baud, .. }) = self.connecting.take() else { return };
        match result {
            Ok(connection) => match BoardLink::start(
                &self.document.project,
                connection,
                (baud, self.plen2_pacing),
                self.waker.clone(),
            ) {
                Ok(mut link) => {
                    link.label = opening.port.to_string();
                    self.sonar_on = self.document.project.rflex.drive.sonar_on_connect;
                    self.report(format!("{} {}", self.words().msg_connected_to, link.label), false);
                    self.link = Some(link);
                }
                Err(error) => self.report(self.language.start_error(&error), true),
            },
            Err(error) => self.report(self.language.link_error(&error), true),
        }
    }

    /// Switches the document's family (one undo step); the tabs follow.
    pub(super) fn set_family(&mut self, family: Family) {
        if self.link.is_some() || self.connecting.is_some() {
            return;
        }
        self.document.apply(Edit::SetFamily(family), None);
        if !Tab::for_family(family).contains(&self.tab) {
            self.tab = Tab::for_family(family)[0];
        }
    }

    /// What the Drive panel asks the base for now (m/s, rad/s).
    pub fn drive_asked(&self) -> (f64, f64) {
        self.drive_panel.asked()
    }

    /// Opens ports with `opener` instead of the system's (tests use a double).
    pub fn with_opener(mut self, opener: Opener) -> Self {
        self.opener = opener;
        self
    }

    pub(super) fn link_status(&self) -> LinkStatus {
        let family = self.document.project.family;
        let connecting = self.connecting.as_ref().map(|connecting| connecting.opening.port.to_string());
        let robot = (family == Family::Rflex).then_some(self.document.project.rflex.robot);
        let pacing = (family == Family::Plen2).then_some(self.plen2_pacing);
        match &self.link {
            None => LinkStatus {
                family,
                robot,
                pacing,
                connecting,
                can_connect: BoardLink::supports(family),
                ..LinkStatus::default()
            },
            Some(link) => {
                let label = if link.is_demo() { self.words().demo_board.to_string() } else { link.label.clone() };
                let servo = link.servo();
                let volts = link.rflex().and_then(|base| base.telemetry.battery_volts);
                LinkStatus {
                    family,
                    robot,
                    pacing,
                    volts,
                    label: Some(label),
                    connecting,
                    can_connect: true,
                    project_id: servo.and_then(|servo| servo.project_id),
                    battery_permil: servo.and_then(|servo| servo.battery_permil),
                    memory: servo.and_then(|servo| servo.memory),
                }
            }
        }
    }
}
