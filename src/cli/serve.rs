//! `servo-studio serve SHOW.json`: remote control with no window — every
//! device of the show connected and held (saying which answered), HTTP +
//! JSON on `--listen` (127.0.0.1:8765 unless told; any other address only
//! with `--token-file`), OSC on `--osc PORT` (the same address), until
//! Ctrl-C or SIGTERM: then every device is stopped (bases brake), every link
//! closed, and it exits 130 / 143. docs/remote.md

use std::net::SocketAddr;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Duration;

use anyhow::{Context, anyhow};
use clap::Args;

use super::out::{line, say};
use super::signals;
use crate::remote::guard::Guard;
use crate::remote::{Remote, Servers};
use crate::show::Show;
use crate::show::boards::{Boards, Heard};

/// `servo-studio serve` options.
#[derive(Debug, Args)]
pub struct ServeArgs {
    /// The show (or a project file: a show of one device).
    pub show: PathBuf,
    /// Where a device is connected, NAME=PORT (overrides the show's port; repeat for each).
    #[arg(long = "device", value_name = "NAME=PORT")]
    pub devices: Vec<String>,
    /// Where HTTP listens (another address than loopback needs --token-file).
    #[arg(long, value_name = "ADDR:PORT", default_value = "127.0.0.1:8765")]
    pub listen: SocketAddr,
    /// Also take OSC over UDP on this port (on --listen's address).
    #[arg(long, value_name = "PORT")]
    pub osc: Option<u16>,
    /// A file whose first line is the secret every request must bear (Authorization: Bearer …; OSC: the first argument).
    #[arg(long, value_name = "FILE")]
    pub token_file: Option<PathBuf>,
    /// A play on a device that is playing waits its turn (else it is refused with 409).
    #[arg(long)]
    pub queue: bool,
}

/// How long the devices have to answer before serving begins.
const ANSWER_WITHIN: Duration = Duration::from_secs(15);

/// Serves the show's devices until a signal.
pub fn run(args: &ServeArgs) -> anyhow::Result<()> {
    // Who may get in is settled first: nothing is connected for a server that may not start.
    let guard = Arc::new(Guard::from_file(args.listen, args.token_file.as_deref()).map_err(|error| anyhow!(error))?);
    let mut show = Show::open(&args.show).with_context(|| format!("cannot serve {}", args.show.display()))?;
    let ports = super::play::ports(&show, &args.devices)?;
    for (device, port) in show.devices.iter_mut().zip(ports) {
        device.port = Some(port);
    }
    let interrupts = signals::listen().context("cannot listen for Ctrl-C")?;
    let boards = Arc::new(Boards::connect(&show, crate::link::no_waker()).context("cannot start the boards' worker")?);
    answered(&boards, &show);
    let remote = Arc::new(Remote::new(show, Arc::downgrade(&boards), args.queue));
    let servers = Servers::start(args.listen, args.osc, &guard, remote).map_err(|error| anyhow!(error))?;
    let token = if servers.needs_token { "a bearer token is needed" } else { "no token: loopback only" };
    // Where it listens is the command's output (stdout): a program starting it reads the port there.
    let _ = line(&format!("listening on http://{} ({token}); docs/remote-openapi.yaml", servers.http.addr()));
    if let Some(osc) = &servers.osc {
        let _ = line(&format!("OSC on udp://{}", osc.addr()));
    }
    let interrupt = loop {
        crossbeam_channel::select! {
            recv(interrupts) -> interrupt => break interrupt.ok(),
            default(Duration::from_millis(200)) => said(&boards, &servers.remote),
        }
    };
    boards.stop();
    drop(servers);
    drop(boards);
    let interrupt = interrupt.unwrap_or(signals::Interrupt { name: "SIGTERM", exit_code: 143 });
    Err(super::interrupted(interrupt, "every device was stopped and its link closed"))
}

/// Says which device answered, waiting for each (up to [`ANSWER_WITHIN`]).
fn answered(boards: &Boards, show: &Show) {
    let mut told = 0;
    let deadline = std::time::Instant::now() + ANSWER_WITHIN;
    while told < show.devices.len() {
        let left = deadline.saturating_duration_since(std::time::Instant::now());
        let Some(heard) = boards.hear_within(left) else { return };
        if let Heard::Linked(index, answer) = heard {
            told += 1;
            let name = &show.devices[index].name;
            match answer {
                Ok(delay) => say!("{name} answered ({:.1} ms to reach it)", delay.as_secs_f64() * 1000.0),
                Err(why) => say!("{name} did not answer: {why}; requests to it are refused (503)"),
            }
        }
    }
}

/// Says what the boards said while serving (a link lost).
fn said(boards: &Boards, remote: &Remote) {
    for heard in boards.heard() {
        if let Heard::Lost { device, why, all_stopped } = heard {
            let name = remote.show().devices.get(device).map_or("?", |device| device.name.as_str());
            let then = if all_stopped { ": every device was stopped" } else { "" };
            say!("the link to {name} was lost ({why}){then}");
        }
    }
}
