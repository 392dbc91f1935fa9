//! File dialogs, asked for by panels and opened by the shell, off the frame:
//! the dialog's future runs on its own thread, the window keeps repainting,
//! and the answer comes back as the action that was waiting for it. Tests
//! inject a [`Picker`] that answers without a window.

use std::future::Future;
use std::path::PathBuf;
use std::pin::Pin;
use std::sync::Arc;

use crossbeam_channel::Receiver;

use crate::link::Waker;
use crate::ui::action::{Action, FileRequest};

/// Opens the dialog for a request; the path chosen (or `None`) arrives on the receiver.
pub type Picker = Arc<dyn Fn(&FileRequest, Waker) -> Receiver<Option<PathBuf>> + Send + Sync>;

/// The system's file dialogs (rfd, asynchronous: on Linux the desktop portal).
pub fn system_picker() -> Picker {
    Arc::new(|request: &FileRequest, waker: Waker| {
        let project = (crate::ui::action::PROJECT_FILE, &["json"][..]);
        let dialog = rfd::AsyncFileDialog::new();
        let (sender, answer) = crossbeam_channel::bounded(1);
        // The dialog is made here, on the window's thread (macOS wants that);
        // waiting for the user happens on another.
        let chosen: Pin<Box<dyn Future<Output = Option<rfd::FileHandle>> + Send>> = match request {
            FileRequest::Open => Box::pin(dialog.add_filter(project.0, project.1).pick_file()),
            FileRequest::SaveAs | FileRequest::SaveAsThenContinue => {
                Box::pin(dialog.add_filter(project.0, project.1).set_file_name("project.json").save_file())
            }
            FileRequest::Export(export) => {
                Box::pin(dialog.add_filter(export.kind, &[export.extension]).set_file_name(&export.name).save_file())
            }
            FileRequest::Pick(pick) => Box::pin(dialog.add_filter(pick.kind, pick.extensions).pick_file()),
        };
        let spawned = std::thread::Builder::new().name("file dialog".into()).spawn(move || {
            let path = pollster::block_on(chosen).map(|handle| handle.path().to_path_buf());
            let _ = sender.send(path);
            waker();
        });
        if spawned.is_err() {
            // No thread: nothing was chosen (the receiver sees the sender gone).
        }
        answer
    })
}

/// What the answer to `request` asks of the shell (the actions it was waiting for).
pub fn answered(request: &FileRequest, path: PathBuf) -> Vec<Action> {
    match request {
        FileRequest::Open => vec![Action::Open(path)],
        FileRequest::SaveAs => vec![Action::SaveAs(path)],
        FileRequest::SaveAsThenContinue => vec![Action::SaveAs(path), Action::UnsavedSave],
        FileRequest::Export(export) => vec![(export.then)(path)],
        FileRequest::Pick(pick) => vec![(pick.then)(path)],
    }
}
