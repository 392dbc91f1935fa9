//! The editor's board lent to remote control. Turned on while the editor is
//! connected and the show's device that is the open project has no port
//! (a plain project: the show is the project, opened for remote control),
//! remote control serves the board the editor is connected to. A port is
//! one program's at a time: the editor lets it go, the show's device takes
//! it, and once remote control and the show's boards let it go, the editor
//! connects to it again. The built-in demo board is served the same way: as
//! the same emulated board, preloaded as the demo is, on a loopback port.

use std::time::{Duration, Instant};

use super::StudioApp;
use crate::ui::family::DemoServer;
use crate::ui::i18n::Worded;

/// The longest the frame waits for the editor's link to let its port go.
const LET_GO_WITHIN: Duration = Duration::from_secs(2);

/// What the editor lent, to connect to again when it comes back.
pub(super) enum Lent {
    /// A port the editor was connected to, at its line rate.
    Port {
        /// The port.
        port: String,
        /// Its line rate.
        baud: u32,
    },
    /// The demo board, served on loopback (its server, kept while lent).
    Demo(DemoServer),
}

impl Lent {
    /// The port the show's device opens.
    fn port(&self) -> &str {
        match self {
            Self::Port { port, .. } => port,
            Self::Demo((_, port)) => port,
        }
    }
}

impl StudioApp {
    /// Lends the editor's board to remote control when remote control is
    /// turned on for a project whose device has no port; said.
    pub(super) fn lend_board_to_remote(&mut self) {
        let Some(link) = &self.link else { return };
        if self.links.lent.is_some() || !self.desks.show.project_without_port() {
            return;
        }
        let family = link.family();
        let lent = if link.is_demo() {
            let waker = self.window.waker.clone();
            match self.family_ui(family).demo_server(&self.document.project, waker) {
                Some(Ok(server)) => Lent::Demo(server),
                Some(Err(error)) => return self.say(|language| error.worded(language), true),
                // A family no show plays: remote control says so for its device.
                None => return,
            }
        } else {
            let Some((port, baud)) = self.link_port() else { return };
            Lent::Port { port, baud }
        };
        // The port let go before the show's device opens it (the base stops as its link goes).
        self.forget_link();
        self.drop_link();
        self.links.wait_for_closing(Instant::now() + LET_GO_WITHIN);
        let port = lent.port().to_string();
        self.desks.show.lend_port(&self.document.project, &port);
        let demo = matches!(lent, Lent::Demo(_));
        self.links.lent = Some(lent);
        if demo {
            self.say(|language| crate::say!(language, "strings.msg_demo_lent", port), false);
        } else {
            self.say(|language| crate::say!(language, "strings.msg_board_lent", port), false);
        }
    }

    /// The board lent comes back to the editor once remote control and the
    /// show's boards have let it go: connected to again, said.
    pub(super) fn take_lent_board_back(&mut self) {
        if self.links.lent.is_none() || self.desks.show.holds_boards() {
            return;
        }
        let Some(lent) = self.links.lent.take() else { return };
        self.desks.show.unlend_port(lent.port());
        match lent {
            Lent::Port { port, baud } => self.connect(&port, baud),
            Lent::Demo(server) => {
                // The served board stops; the editor's own demo starts again.
                drop(server);
                self.connect_demo();
            }
        }
    }
}
