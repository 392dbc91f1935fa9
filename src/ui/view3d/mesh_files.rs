//! Mesh files read off the frame: the first time a figure asks for a file it
//! is read on its own thread, and the figure draws its link without it until
//! it is there (a repaint is asked for then). A file that cannot be read
//! stays an error the preview shows, naming the file; the project opens
//! and plays as ever.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use crossbeam_channel::Receiver;

use crate::figure::mesh::Mesh;

#[derive(Debug)]
enum Loading {
    Reading(Receiver<Result<Mesh, String>>),
    Ready(Arc<Mesh>),
    Failed(String),
}

/// The mesh files asked for so far, by path.
#[derive(Debug, Default)]
pub struct MeshFiles {
    files: HashMap<PathBuf, Loading>,
}

impl MeshFiles {
    /// The mesh in `path` once read (reading starts the first time it is asked for).
    pub fn get(&mut self, path: &Path, ctx: &egui::Context) -> Option<Arc<Mesh>> {
        let loading = self.files.entry(path.to_path_buf()).or_insert_with(|| {
            let (done, reading) = crossbeam_channel::bounded(1);
            let (path, ctx) = (path.to_path_buf(), ctx.clone());
            std::thread::spawn(move || {
                // The receiver may be gone (the editor closed): nothing to tell then.
                let _ = done.send(Mesh::load(&path).map_err(|error| error.to_string()));
                ctx.request_repaint();
            });
            Loading::Reading(reading)
        });
        if let Loading::Reading(reading) = loading
            && let Ok(read) = reading.try_recv()
        {
            *loading = match read {
                Ok(mesh) => Loading::Ready(Arc::new(mesh)),
                Err(error) => Loading::Failed(error),
            };
        }
        match loading {
            Loading::Ready(mesh) => Some(Arc::clone(mesh)),
            _ => None,
        }
    }

    /// Whether every file asked for is read (or failed).
    pub fn settled(&self) -> bool {
        self.files.values().all(|loading| !matches!(loading, Loading::Reading(_)))
    }

    /// What could not be read, among `paths`.
    pub fn errors<'a>(&'a self, paths: impl IntoIterator<Item = &'a Path>) -> Vec<&'a str> {
        paths
            .into_iter()
            .filter_map(|path| match self.files.get(path) {
                Some(Loading::Failed(error)) => Some(error.as_str()),
                _ => None,
            })
            .collect()
    }

    /// Forgets every file (read again when next asked for: "reload").
    pub fn clear(&mut self) {
        self.files.clear();
    }
}
