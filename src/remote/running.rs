//! The thread a remote server runs on: a tokio runtime of its own — one
//! thread for every connection or datagram, and a pool of at most
//! [`WAITING_FOR_BOARDS`] threads for the requests that wait on the boards'
//! worker — serving until it is dropped.

use std::future::Future;
use std::sync::Arc;
use std::time::Duration;

use tokio::sync::Notify;

/// How many requests may wait for the boards' worker at once, on each server
/// (a pose, a play, a drive); the next is answered 503 at once.
pub const WAITING_FOR_BOARDS: usize = 8;
/// How long requests still waiting for the boards may take once the server is dropped.
const ENDING_WITHIN: Duration = Duration::from_secs(3);

/// A runtime for a server whose blocking pool's threads are called `name waits`.
pub fn runtime(name: &str) -> std::io::Result<tokio::runtime::Runtime> {
    tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .max_blocking_threads(WAITING_FOR_BOARDS + 1)
        .thread_name(format!("{name} waits"))
        .build()
}

/// A server's future, running on a thread of its own until dropped.
#[derive(Debug)]
pub struct Running {
    done: Arc<Notify>,
    thread: Option<std::thread::JoinHandle<()>>,
}

impl Running {
    /// Runs `serve` on `runtime` on a thread called `name`.
    pub fn spawn(
        name: &str,
        runtime: tokio::runtime::Runtime,
        serve: impl Future<Output = ()> + Send + 'static,
    ) -> std::io::Result<Self> {
        let done = Arc::new(Notify::new());
        let told = Arc::clone(&done);
        let thread = std::thread::Builder::new().name(name.into()).spawn(move || {
            runtime.block_on(async {
                tokio::select! {
                    () = serve => {}
                    () = told.notified() => {}
                }
            });
            // Requests still waiting for the boards end within their own bound.
            runtime.shutdown_timeout(ENDING_WITHIN);
        })?;
        Ok(Self { done, thread: Some(thread) })
    }
}

impl Drop for Running {
    fn drop(&mut self) {
        self.done.notify_one();
        if let Some(thread) = self.thread.take() {
            let _ = thread.join();
        }
    }
}
