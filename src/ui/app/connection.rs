//! The app shell's connection: opening a port off the UI thread, starting the
//! family's driver, the port list, the running operation, and turning what
//! the board reports into status lines and family events.

use super::*;
use crate::link::{Opening, PortName};
use crate::project::Edit;
use crate::ui::board_link::LinkNotice;
use crate::ui::connection_bar::LinkStatus;
use crate::ui::i18n::Worded;

impl StudioApp {
    /// Picks up what the board and the running operation sent since the last frame.
    pub fn pump(&mut self, now: Instant) {
        self.poll_operation();
        self.poll_connecting();
        // A link made just now is due its first status queries: they go out in this pump, not
        // at a later frame that nothing may ask for.
        let now = now.max(Instant::now());
        let Some(family) = self.link.as_ref().map(BoardLink::family) else { return };
        let polling = self.family_ui(family).polling();
        let Some(link) = &mut self.link else { return };
        for notice in link.pump(now, polling) {
            match notice {
                LinkNotice::Disconnected(reason) => {
                    self.link_ended(&reason);
                    self.drop_link();
                    return;
                }
                LinkNotice::Family(notice) => {
                    let (mut shell, family_ui) = self.parts(family);
                    family_ui.notice(&mut shell, notice);
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
    pub(super) fn finish_operation(&mut self, wait: Option<Duration>) -> Option<StatusLine> {
        self.operation.as_ref()?;
        let mut summary = None;
        self.each_family(|family_ui, shell| {
            if summary.is_none() {
                summary = family_ui.finish_operation(shell, wait);
            }
        });
        // The status line follows: what the connection said of the board
        // ("factory-fresh") may no longer hold.
        // The status line holds its first line; the whole text (what an upload left) is returned.
        if let Some(said) = &summary {
            self.status = Some(said.first_line());
        }
        summary
    }

    /// Opens `port` off the UI thread with the document's family's line settings.
    pub(super) fn connect(&mut self, port: &str, baud: u32) {
        self.open_port(port, baud, false);
    }

    /// Tries to make a lost link again: a port that does not open yet is waited for, not reported.
    pub(super) fn connect_quietly(&mut self, port: &str, baud: u32) {
        self.open_port(port, baud, true);
    }

    fn open_port(&mut self, port: &str, baud: u32, quiet: bool) {
        let name = match PortName::parse(port) {
            Ok(name) => name,
            Err(error) => {
                self.say(|language| language.link_error(&error), true);
                return;
            }
        };
        let family = self.document.project.family;
        let settings = crate::link::LineSettings { baud, ..crate::device::line_settings(family) };
        if !quiet {
            self.say(|language| language.connecting_to(&name.to_string()), false);
        }
        let opening = Opening::start(name, settings, self.links.opener.clone(), self.window.waker.clone());
        let starter = self.family_ui(family).link_starter(baud);
        self.links.connecting = Some(Connecting { opening, family, baud, starter, quiet });
    }

    /// Starts the built-in emulated board of the document's family.
    pub(super) fn connect_demo(&mut self) {
        if self.link.is_some() {
            return;
        }
        let family = self.document.project.family;
        match self.family_ui(family).demo_link(&self.document.project, self.window.waker.clone()) {
            Ok(link) => {
                self.link = Some(link);
                self.connected();
                let family_ui = self.family_ui(family);
                let said =
                    StatusLine::worded(self.language, |language| family_ui.demo_connected(language.strings()), false);
                self.status = Some(said);
            }
            Err(error) => self.say(|language| error.worded(language), true),
        }
    }

    /// A link was made: the families start from rest.
    fn connected(&mut self) {
        self.each_family(|family_ui, shell| family_ui.connected(&shell.document.project));
    }

    /// Starts the driver once the port is open, or reports why it did not open.
    pub(super) fn poll_connecting(&mut self) {
        let Some(connecting) = &self.links.connecting else { return };
        let Some(result) = connecting.opening.poll() else { return };
        let Some(Connecting { opening, family, baud, starter, quiet }) = self.links.connecting.take() else { return };
        match result {
            Ok(connection) => match starter(&self.document.project, connection, self.window.waker.clone()) {
                Ok(device) => {
                    let label = opening.port.to_string();
                    self.say(|language| format!("{} {label}", language.strings().msg_connected_to), false);
                    self.link = Some(BoardLink::new(device, label.clone()));
                    self.link_made(&label, baud, family);
                    self.connected();
                }
                Err(error) => self.say(|language| error.worded(language), true),
            },
            // Still gone: tried again at the next turn.
            Err(_) if quiet => {}
            Err(error) => self.say(|language| language.link_error(&error), true),
        }
    }

    /// Switches the document's family (one undo step); the tabs follow.
    pub(super) fn set_family(&mut self, family: Family) {
        if self.link.is_some() || self.links.connecting.is_some() {
            return;
        }
        self.document.apply(Edit::SetFamily(family), None);
        self.show_family_tab(family);
    }

    #[cfg(any(test, feature = "test-api"))]
    /// Opens ports with `opener` instead of the system's (tests use a double).
    pub fn with_opener(mut self, opener: crate::link::Opener) -> Self {
        self.links.opener = opener;
        self
    }

    pub(super) fn link_status(&self) -> LinkStatus {
        let family = self.document.project.family;
        let connecting = self.links.connecting.as_ref().map(|connecting| connecting.opening.port.to_string());
        let busy = self.links.connecting.is_some() || self.link.is_some() || self.finding_board();
        let doctor = self.doctor_lines();
        match &self.link {
            None => LinkStatus {
                family,
                connecting,
                busy,
                doctor,
                reconnecting: self.waiting_to_reconnect(),
                ..LinkStatus::default()
            },
            Some(link) => {
                let label = if link.is_demo() { self.words().demo_board.to_string() } else { link.label.clone() };
                let details = self.family_ui(link.family()).link_details(link, self.words());
                LinkStatus { family, busy, label: Some(label), connecting, details, ..LinkStatus::default() }
            }
        }
    }
}
