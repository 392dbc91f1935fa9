//! Settings → Remote control…: the same server as `servo-studio serve`,
//! from the open editor, on the show window's boards (connecting them, and
//! opening the open project as a show of one device when no show is open).
//! Off at every start; the address, OSC port and token file are typed here.
//! Disconnecting the boards or closing the show turns it off.

use crate::ui::i18n::{Said, Worded};
use std::sync::Arc;

use crate::remote::guard::Guard;
use crate::remote::{Remote, Servers};

use super::ShowWords;
use super::linked::Linked;

/// The remote control's settings and its servers while on.
#[derive(Debug)]
pub struct RemoteDesk {
    /// Whether its window is open.
    pub open: bool,
    /// Where HTTP listens, as typed.
    pub listen: String,
    /// The OSC port, as typed (empty: no OSC).
    pub osc: String,
    /// The token file, as typed (empty: none; needed off loopback).
    pub token_file: String,
    /// A play on a busy device waits its turn (else 409).
    pub queue: bool,
    /// The servers while on.
    serving: Option<Servers>,
    /// What it says: where it listens, or why it could not (in every language).
    pub said: Option<Said>,
}

impl Default for RemoteDesk {
    fn default() -> Self {
        Self {
            open: false,
            listen: "127.0.0.1:8765".into(),
            osc: String::new(),
            token_file: String::new(),
            queue: false,
            serving: None,
            said: None,
        }
    }
}

impl RemoteDesk {
    /// Whether it serves.
    pub fn serving(&self) -> bool {
        self.serving.is_some()
    }

    /// Where HTTP listens while on.
    pub fn addr(&self) -> Option<std::net::SocketAddr> {
        self.serving.as_ref().map(|servers| servers.http.addr())
    }

    /// Starts serving `show` on `linked`'s boards, saying where or why not.
    pub fn start(&mut self, show: crate::show::Show, linked: &Linked) {
        self.serving = None;
        match self.servers(show, linked) {
            Ok(servers) => {
                let osc = servers.osc.as_ref().map(|osc| format!(" · OSC udp://{}", osc.addr())).unwrap_or_default();
                let (needs_token, http) = (servers.needs_token, servers.http.addr());
                self.said = Some(super::said_by(|words| {
                    let token = if needs_token { words.remote_token_needed } else { words.remote_loopback };
                    format!("{} http://{http}{osc} ({token})", words.remote_listening)
                }));
                self.serving = Some(servers);
            }
            Err(why) => self.said = Some(why),
        }
    }

    fn servers(&self, show: crate::show::Show, linked: &Linked) -> Result<Servers, Said> {
        let listen: std::net::SocketAddr = self.listen.trim().parse().map_err(|_| {
            let listen = format!("{:?}", self.listen);
            Said::new(|language| crate::say!(language, "show.remote_bad_listen", listen))
        })?;
        let token_file = Some(self.token_file.trim()).filter(|file| !file.is_empty()).map(std::path::Path::new);
        let guard =
            Guard::from_file(listen, token_file).map_err(|error| Said::new(|language| error.worded(language)))?;
        let osc = match self.osc.trim() {
            "" => None,
            port => Some(port.parse::<u16>().map_err(|_| {
                let port = format!("{port:?}");
                Said::new(|language| crate::say!(language, "show.remote_bad_osc", port))
            })?),
        };
        Servers::start(listen, osc, &Arc::new(guard), Arc::new(Remote::new(show, linked.shared(), self.queue)))
            .map_err(|error| Said::new(|language| error.worded(language)))
    }

    /// Stops serving (saying why, when it is not the user's click).
    pub fn stop(&mut self, why: Option<Said>) {
        if self.serving.take().is_some() {
            self.said = why;
        }
    }

    /// The window: on / off, where, the token file, queue or refuse; what it says.
    pub fn window(&mut self, ctx: &egui::Context, words: &ShowWords, actions: &mut Vec<crate::ui::Action>) {
        let mut open = self.open;
        let right = ctx.content_rect().right();
        let window = egui::Window::new(words.remote_title);
        let window =
            crate::ui::layout::parked_when_collapsed(window, ctx, "remote-window", 2).open(&mut open).resizable(false);
        window.default_pos(egui::pos2(right - 560.0, 100.0)).show(ctx, |ui| {
            ui.set_max_width(520.0);
            let mut on = self.serving();
            if ui.checkbox(&mut on, words.remote_serve).changed() {
                actions.push(crate::ui::Action::Show(super::ShowAction::Remote(on)));
            }
            ui.add_enabled_ui(!self.serving(), |ui| {
                egui::Grid::new("remote-settings").num_columns(2).show(ui, |ui| {
                    let field = |ui: &mut egui::Ui, label: &str, text: &mut String, hint: &str| {
                        let label = ui.label(label);
                        ui.add(egui::TextEdit::singleline(text).hint_text(hint).desired_width(300.0))
                            .labelled_by(label.id);
                        ui.end_row();
                    };
                    field(ui, words.remote_listen, &mut self.listen, "127.0.0.1:8765");
                    field(ui, words.remote_osc, &mut self.osc, "9000");
                    field(ui, words.remote_token, &mut self.token_file, "/home/me/.servo-studio-token");
                });
                ui.checkbox(&mut self.queue, words.remote_queue);
            });
            ui.weak(words.remote_hint);
            if let Some(said) = &self.said {
                ui.label(said.in_(words.lang));
            }
            // What the remotes have the devices doing now (looked at twice a second while serving).
            if self.serving() {
                ui.ctx().request_repaint_after(std::time::Duration::from_millis(500));
            }
            let status =
                self.serving.as_ref().and_then(|servers| servers.remote.boards()).map(|boards| boards.status());
            for device in status.iter().flat_map(|status| &status.devices) {
                let doing = match (&device.playing, device.driven) {
                    (Some(playing), _) => playing.clone(),
                    (None, true) => words.remote_driven.to_string(),
                    (None, false) => continue,
                };
                ui.weak(format!("{}: {doing}", device.name));
            }
        });
        self.open = open;
    }
}
