//! The editor window (egui / eframe). Panels read state and push
//! [`Action`]s; only the app shell ([`StudioApp::apply`]) applies them.

mod action;
mod action_panel;
mod app;
mod board_link;
mod board_panel;
mod connection_bar;
mod document;
pub mod files;
pub mod fonts;
mod i18n;
mod job;
mod joystick_panel;
mod macro_panel;
pub mod packet_log;
mod servo_panel;

pub use action::{Action, AfterUnsaved, BoardIntent, Tab};
pub use action_panel::timeline_bars;
pub use app::{
    CAPTURED_STEP_INTERVAL_10MS, LIVE_MOVE_INTERVAL_10MS, REMEMBERED_KEY, Remembered, StatusLine, StudioApp,
};
pub use board_link::{BoardLink, LinkNotice};
pub use board_panel::{BoardResult, PendingConfirm};
pub use document::Document;
pub use i18n::{Language, Strings};
pub use job::{Job, JobKind, JobOutcome};

/// Opens the editor window and runs until it is closed.
pub fn run(project: crate::project::Project, path: Option<std::path::PathBuf>, demo: bool) -> eframe::Result {
    let options = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default().with_title("Servo Studio").with_inner_size([1100.0, 720.0]),
        ..Default::default()
    };
    eframe::run_native(
        "Servo Studio",
        options,
        Box::new(move |creation| {
            fonts::install(&creation.egui_ctx);
            let ctx = creation.egui_ctx.clone();
            let waker: crate::link::Waker = std::sync::Arc::new(move || ctx.request_repaint());
            let mut app = StudioApp::new(project, path, waker);
            if let Some(remembered) = creation.storage.and_then(|storage| eframe::get_value(storage, REMEMBERED_KEY)) {
                app.restore(remembered);
            }
            if demo {
                app.apply(Action::ConnectDemo);
            }
            Ok(Box::new(app))
        }),
    )
}
