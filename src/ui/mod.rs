//! The editor window (egui / eframe). Panels read state and push
//! [`Action`]s; only the app shell ([`StudioApp::apply`]) applies them.

mod action;
mod app;
mod board_link;
mod connection_bar;
mod derive;
mod document;
mod dynamixel;
#[cfg(test)]
mod echo;
mod families;
mod family;
mod file_browser;
pub mod files;
pub mod fonts;
pub mod gamepad;
mod graph;
mod i18n;
pub mod import;
mod layout;
mod operation;
pub mod packet_log;
mod plen2;
mod plot;
mod remembered;
mod rflex;
mod rows;
mod servo;
mod shell;
pub mod show;
mod show_cue;
pub mod sound;
mod transport;
pub mod view3d;

pub use action::{Action, ActionOf, AfterUnsaved, FamilyAction, FileRequest, Pick, Tab};
pub use app::{Connecting, EXIT_WITHIN, Picker, PortLister, REMEMBERED_KEY, Remembered, StudioApp, system_lister};
pub use board_link::{BoardLink, FamilyLink, FamilyNotice, LinkNotice, LinkStarter, StartError};
pub use derive::Costing;
pub use document::Document;
pub use families::Families;
pub use family::FamilyUi;
pub use i18n::{Language, Strings, Worded};
pub use layout::{Layout, PARKED_ABOVE_BOTTOM};
pub use operation::{Operation, Step};
pub use plen2::{
    Plen2Action, Plen2BoardLink, Plen2Failure, Plen2Intent, Plen2Kind, Plen2Operation, Plen2Outcome, Plen2Result,
    Plen2Ui,
};
pub use rflex::{DrivePanel, DriveView, RflexAction, RflexBoardLink, RflexUi, WorldView};
pub use servo::{
    BoardIntent, BoardResult, CAPTURED_STEP_INTERVAL_10MS, LIVE_MOVE_INTERVAL_10MS, PendingConfirm, ServoAction,
    ServoBoardLink, ServoFailure, ServoKind, ServoOperation, ServoOutcome, ServoUi, demo_link as servo_demo_link,
    timeline_bars,
};
pub use shell::{RunningOperation, StatusLine};
pub use sound::{SoundAction, SoundDesk};

/// The sample robot `gui --demo` opens when no file is given: a 16-servo
/// biped with captions in English and Traditional Chinese, a few actions, a
/// macro and a joystick table.
pub fn sample_project() -> crate::project::Project {
    // The file ships with the binary and has a test; an unreadable copy opens an empty project.
    crate::project::from_json(include_str!("../../assets/sample-biped.json")).unwrap_or_default()
}

/// How the editor starts.
#[derive(Debug, Default)]
pub struct Start {
    /// The project to open (`None`: the sample with `demo`, else an empty one).
    pub project: Option<crate::project::Project>,
    /// Where it was read from.
    pub path: Option<std::path::PathBuf>,
    /// Connect to the built-in emulated board.
    pub demo: bool,
    /// The family to start with (else the project's, else the one used last).
    pub family: Option<crate::project::Family>,
    /// Signals asking the process to end (Ctrl-C, kill, a closing session):
    /// each stops the board and closes the window, keeping unsaved work.
    pub interrupts: Option<crossbeam_channel::Receiver<()>>,
    /// Another tool's file to open in the import window at once.
    pub import: Option<std::path::PathBuf>,
    /// A show to open in the show window at once.
    pub show: Option<std::path::PathBuf>,
}

impl Start {
    /// The editor this start describes: the document, its family and the demo board.
    pub fn into_app(self, waker: crate::link::Waker, remembered: Option<Remembered>) -> StudioApp {
        let from_file = self.project.is_some();
        let project = match self.project {
            Some(project) => project,
            None if self.demo => sample_project(),
            None => crate::project::Project::default(),
        };
        let mut app = StudioApp::new(project, self.path, waker);
        if let Some(remembered) = remembered {
            // A project's family wins over the one used last.
            app.restore(remembered, from_file || self.demo);
        }
        if let Some(family) = self.family {
            app.document.project.family = family;
        }
        if self.demo {
            app.apply(Action::ConnectDemo);
        }
        if let Some(path) = self.import {
            app.apply(Action::Import(import::ImportAction::Read(path)));
        }
        if let Some(path) = self.show {
            app.apply(Action::Show(action::ShowAction::Open(path)));
        }
        app
    }
}

/// The app's own icon (`assets/icons`), for its window.
const ICON_PNG: &[u8] = include_bytes!("../../assets/icons/servo-studio-128.png");

/// Opens the editor window and runs until it is closed.
pub fn run(mut start: Start) -> eframe::Result {
    let mut viewport = egui::ViewportBuilder::default()
        .with_title("Servo Studio")
        // The desktop entry's name: the window is the installed program's (its icon, its taskbar group).
        .with_app_id("servo-studio")
        .with_inner_size([1100.0, 720.0]);
    if let Ok(icon) = eframe::icon_data::from_png_bytes(ICON_PNG) {
        viewport = viewport.with_icon(icon);
    }
    let options = eframe::NativeOptions {
        viewport,
        // The 3D view draws meshes with a depth buffer.
        depth_buffer: 24,
        ..Default::default()
    };
    eframe::run_native(
        "Servo Studio",
        options,
        Box::new(move |creation| {
            fonts::install(&creation.egui_ctx);
            let ctx = creation.egui_ctx.clone();
            let waker: crate::link::Waker = std::sync::Arc::new(move || ctx.request_repaint());
            let remembered = creation.storage.and_then(|storage| eframe::get_value(storage, REMEMBERED_KEY));
            let interrupts = start.interrupts.take();
            let mut app = start.into_app(waker, remembered);
            if let Some(interrupts) = interrupts {
                // The signal arrives on its own thread; the window acts on it in its next frame.
                let (terminate, terminated) = crossbeam_channel::bounded(1);
                let ctx = creation.egui_ctx.clone();
                std::thread::Builder::new().name("interrupts".into()).spawn(move || {
                    for () in interrupts {
                        let _ = terminate.try_send(());
                        ctx.request_repaint();
                    }
                })?;
                app.terminate_on(terminated);
            }
            Ok(Box::new(app))
        }),
    )
}

/// The editor on `project` in a test harness of `size`, keeping its backups
/// in a folder of its own, drawn with the app's fonts (CJK included).
#[cfg(test)]
fn test_editor(project: crate::project::Project, size: egui::Vec2) -> egui_kittest::Harness<'static, StudioApp> {
    let data = tempfile::tempdir().unwrap().keep();
    let app = StudioApp::new(project, None, crate::link::no_waker()).with_data_dir(data);
    egui_kittest::Harness::builder()
        .with_size(size)
        .with_context_setup(|ctx| {
            fonts::install(ctx);
            Costing::IN_FRAME.install(ctx);
        })
        .build_ui_state(|ui, app: &mut StudioApp| app.show(ui), app)
}
