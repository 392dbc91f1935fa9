//! The app shell's connection: opening a port off the UI thread, starting the
//! family's driver, the port list, the running operation, and turning what
//! the board reports into status lines and family events.

use std::time::Duration;

use super::*;
use crate::link::{PortName, list_ports};
use crate::project::Edit;
use crate::ui::board_link::LinkNotice;
use crate::ui::connection_bar::LinkStatus;

/// How often the port list is read again.
const RESCAN_EVERY: Duration = Duration::from_secs(2);

impl StudioApp {
    /// Picks up what the board and the running operation sent since the last frame.
    pub fn pump(&mut self, now: Instant) {
        self.poll_operation();
        self.poll_connecting();
        let polling = self.servo.polling;
        let Some(link) = &mut self.link else { return };
        for notice in link.pump(now, polling) {
            match notice {
                LinkNotice::SendFailed(error) => self.report(self.language.send_failed(&error), true),
                LinkNotice::RequestFailed(error) => self.report(self.language.request_error(&error), true),
                LinkNotice::PacingWidened(widened) => {
                    // Not an error: the upload goes on, more carefully.
                    self.report(self.language.pacing_widened(&widened), false);
                }
                LinkNotice::BaseSilent => {
                    self.rflex.stopped();
                    self.report(self.words().msg_base_silent, true);
                }
                LinkNotice::MacroRefused => self.report(self.words().msg_macro_refused, true),
                LinkNotice::Disconnected(reason) => {
                    self.report(self.language.link_ended(&reason), true);
                    self.link = None;
                    self.servo.polling = false;
                    self.rflex.stopped();
                    return;
                }
                LinkNotice::Button { button_id, event } => {
                    let (mut shell, servo, _, _) = self.shell();
                    servo.button(&mut shell, button_id, event);
                }
            }
        }
    }

    /// Hands the running operation's outcome to the family that started it.
    fn poll_operation(&mut self) {
        self.finish_operation(None);
    }

    /// Hands the running operation's outcome to the family that started it,
    /// waiting up to `wait` for it (None: not at all); returns the whole summary it left.
    pub(super) fn finish_operation(&mut self, wait: Option<std::time::Duration>) -> Option<(String, bool)> {
        let outcome = match (&mut self.operation, wait) {
            (Some(RunningOperation::Servo(operation)), None) => operation.poll().map(Finished::Servo),
            (Some(RunningOperation::Plen2(operation)), None) => operation.poll().map(Finished::Plen2),
            (Some(RunningOperation::Servo(operation)), Some(wait)) => operation.wait(wait).map(Finished::Servo),
            (Some(RunningOperation::Plen2(operation)), Some(wait)) => operation.wait(wait).map(Finished::Plen2),
            (None, _) => None,
        };
        let outcome = outcome?;
        let operation = self.operation.take()?;
        let summary = match (outcome, operation) {
            (Finished::Servo(outcome), RunningOperation::Servo(operation)) => {
                self.servo.finish(&operation, outcome);
                self.servo.summary(self.language)
            }
            (Finished::Plen2(outcome), _) => {
                self.plen2.finish(outcome);
                self.plen2.summary(self.language)
            }
            (Finished::Servo(_), RunningOperation::Plen2(_)) => None,
        };
        // The status line follows: what the connection said of the board
        // ("factory-fresh") may no longer hold.
        // The status line holds its first line; the whole text (what an upload left) is returned.
        if let Some((text, is_error)) = &summary {
            self.report(text.lines().next().unwrap_or_default(), *is_error);
        }
        summary
    }

    /// Reads the list of serial ports, at most every two seconds.
    pub(super) fn scan_ports(&mut self, now: Instant) {
        if self.next_scan.is_some_and(|at| now < at) {
            return;
        }
        self.next_scan = Some(now + RESCAN_EVERY);
        // A failed scan leaves the last list; the port can still be typed.
        if let Ok(ports) = list_ports() {
            self.ports = ports;
        }
    }

    /// The connected servo board, if any.
    pub fn servo_board(&self) -> Option<&crate::device::servo::ServoHandle> {
        self.link.as_ref().and_then(BoardLink::servo)
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

    /// Starts the built-in emulated board of the document's family.
    pub(super) fn connect_demo(&mut self) {
        if self.link.is_some() {
            return;
        }
        match BoardLink::demo(&self.document.project, self.plen2_pacing, self.waker.clone()) {
            Ok(link) => {
                self.link = Some(link);
                self.connected();
                let words = self.words();
                let text = match self.document.project.family {
                    Family::Servo => words.msg_connected_demo,
                    Family::Plen2 => words.msg_connected_demo_plen2,
                    Family::Rflex => words.msg_connected_demo_rflex,
                };
                self.report(text, false);
            }
            Err(error) => self.report(self.language.start_error(&error), true),
        }
    }

    /// A link was made: the families start from rest.
    fn connected(&mut self) {
        self.rflex.connected(self.document.project.rflex.drive.sonar_on_connect);
        self.servo.polling = false;
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
                    self.report(format!("{} {}", self.words().msg_connected_to, link.label), false);
                    self.link = Some(link);
                    self.connected();
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

/// An operation's outcome, by family.
enum Finished {
    Servo(crate::ui::servo::ServoOutcome),
    Plen2(crate::ui::plen2::Plen2Outcome),
}
