//! `servo-studio sim`: an emulated board of any family on a pseudo-terminal or
//! TCP. Each family takes its own options; one given to a family it does not
//! apply to is refused, never silently ignored.

use std::net::SocketAddr;
use std::path::PathBuf;

use anyhow::bail;
use clap::Args;

use super::bounds;
use super::out::say;
use crate::link::{Driver, LinkEvent, no_waker};
use crate::project::Family;
use crate::project::rflex::Robot;
use crate::sim::{self, Faults, LineNoise, LinkKind};

/// `servo-studio sim` options.
#[derive(Debug, Default, Args)]
pub struct SimArgs {
    /// Serve on a pseudo-terminal (the default on Linux and macOS).
    #[arg(long, conflicts_with = "tcp")]
    pub pty: bool,
    /// Serve on TCP at this address, e.g. 127.0.0.1:5000 (port 0 picks one).
    #[arg(long)]
    pub tcp: Option<SocketAddr>,
    /// Preload the board from this project file (servo board; PLEN2: a project, motion.json or folder).
    #[arg(long)]
    pub state: Option<PathBuf>,
    /// Servo board: emulate this line rate, 300..=4000000 (bytes take 10 bits each); default: as fast as the link goes.
    #[arg(long, allow_hyphen_values = true, value_parser = bounds::baud)]
    pub baud: Option<u32>,
    /// Servo board: time between a request and its response, 0..=60000 ms (default 0).
    #[arg(long, allow_hyphen_values = true, value_parser = bounds::turnaround_ms)]
    pub turnaround_ms: Option<u64>,
    /// Servo board: its memory in bytes (default 262144).
    #[arg(long, allow_hyphen_values = true, value_parser = bounds::memory_bytes)]
    pub memory: Option<i32>,
    /// Servo board: faults to inject, e.g. garbage-every=3,drop-every=7,disconnect-after=40,refuse-add=42.
    #[arg(long)]
    pub faults: Option<Faults>,
    /// rFLEX base: report only a B21r's six body panels (0x40–0x45), for the ROS b21_node.
    #[arg(long)]
    pub body_panels_only: bool,
    /// rFLEX base: send every frame stuffed.
    #[arg(long)]
    pub stuffed: bool,
    /// rFLEX base: line noise on the output, e.g. garbage-every=5,corrupt-every=7,cut-every=11.
    #[arg(long)]
    pub noise: Option<LineNoise>,
    /// rFLEX base: the robot, b21r (default), atrv-jr or magellan (its own sonars and bumpers).
    #[arg(long, value_parser = super::parse_robot)]
    pub robot: Option<Robot>,
    /// rFLEX base: the room it stands in, WIDTHxDEPTH metres (default 4.2x2.8).
    #[arg(long, value_parser = bounds::room)]
    pub room: Option<(f64, f64)>,
    /// rFLEX base: where it starts, X,Y,THETA_DEG — metres from the room's centre (x along its
    /// width) and its heading in degrees from +x (default 0,0,0).
    #[arg(long, allow_hyphen_values = true, value_parser = bounds::start)]
    pub start: Option<(f64, f64, f64)>,
    /// PLEN2: the line to the robot: clean (default), bursty[=MS][,whole] (a
    /// Bluetooth LE bridge, 7.5–30 ms connection interval, 15 by default;
    /// `whole`: replies buffered and delivered whole at the next event), late=MS
    /// (writes held back up to MS ms) or slow=BAUD.
    #[arg(long)]
    pub link: Option<LinkKind>,
    /// A servo bus: a servo's hardware error, ID:KIND@SECONDS after the bus first hears a
    /// packet (KIND: input-voltage, overheating, overload), e.g. 2:overheating@5; repeatable.
    #[arg(long, value_name = "ID:KIND@SECONDS")]
    pub hardware_error: Vec<String>,
    /// Write every command the board receives to FILE, a line each: the system's monotonic
    /// clock in nanoseconds when the board took it in, then the command (any family).
    #[arg(long, value_name = "FILE")]
    pub log: Option<PathBuf>,
}

impl SimArgs {
    /// Every option only some emulators take, by name, and whether it was given.
    fn given(&self) -> [(&'static str, bool); 13] {
        [
            ("--state", self.state.is_some()),
            ("--baud", self.baud.is_some()),
            ("--turnaround-ms", self.turnaround_ms.is_some()),
            ("--memory", self.memory.is_some()),
            ("--faults", self.faults.is_some()),
            ("--stuffed", self.stuffed),
            ("--body-panels-only", self.body_panels_only),
            ("--noise", self.noise.is_some()),
            ("--robot", self.robot.is_some()),
            ("--room", self.room.is_some()),
            ("--start", self.start.is_some()),
            ("--link", self.link.is_some()),
            ("--hardware-error", !self.hardware_error.is_empty()),
        ]
    }

    /// The options given, by name, that `emulator` does not take.
    fn foreign(&self, emulator: &Emulator) -> Vec<&'static str> {
        self.given()
            .into_iter()
            .filter(|(name, given)| *given && !emulator.takes.contains(name))
            .map(|(name, _)| name)
            .collect()
    }
}

/// A family's emulated board, as `sim` serves it: each family registers its
/// own (`inventory::submit!` in `cli/<family>.rs`).
#[derive(Debug)]
pub struct Emulator {
    /// The family it emulates.
    pub family: Family,
    /// The `sim` options it takes (the others are refused, never ignored).
    pub takes: &'static [&'static str],
    /// What else to say of them (e.g. what a slow line is written as).
    pub note: &'static str,
    /// Serves it until the client goes (pty) or forever (TCP).
    pub serve: fn(&SimArgs) -> anyhow::Result<()>,
}

inventory::collect!(Emulator);

fn emulator(family: Family) -> Option<&'static Emulator> {
    inventory::iter::<Emulator>.into_iter().find(|emulator| emulator.family == family)
}

/// Runs `sim --protocol FAMILY`: the emulator the family registered.
pub fn run(args: &SimArgs, family: Family) -> anyhow::Result<()> {
    let Some(emulator) = emulator(family) else {
        let served: Vec<&str> =
            Family::all().iter().filter(|family| emulator(**family).is_some()).map(|family| family.tag()).collect();
        bail!("the {} has no emulated board to serve; give {}", family.name(), served.join(", "));
    };
    let foreign = args.foreign(emulator);
    if !foreign.is_empty() {
        let takes = if emulator.takes.is_empty() { "none of these".to_string() } else { emulator.takes.join(", ") };
        bail!(
            "{} do(es) not apply to the emulated {family} board (it takes {takes}{}); nothing was started",
            foreign.join(", "),
            emulator.note
        );
    }
    (emulator.serve)(args)
}

/// Serves an emulator of any family on a pseudo-terminal or TCP; prints the port on
/// the first line of stdout, then runs until killed.
pub fn serve<D: Driver>(args: &SimArgs, emulator: D) -> anyhow::Result<()>
where
    D::Event: sim::Received,
{
    match &args.log {
        Some(path) => {
            let log = std::fs::File::create(path)
                .map_err(|error| anyhow::anyhow!("cannot write the log {}: {error}", path.display()))?;
            served(args, sim::Logged::new(emulator, log))
        }
        None => served(args, emulator),
    }
}

fn served<D: Driver>(args: &SimArgs, emulator: D) -> anyhow::Result<()> {
    let handle = match args.tcp {
        Some(address) => sim::spawn_tcp(emulator, address, no_waker())?,
        None => spawn_pty(emulator)?,
    };
    super::out::line(&handle.port_name)?;
    say!("emulated board ready on {} (Ctrl-C to stop)", handle.port_name);
    for event in handle.events() {
        if let LinkEvent::Disconnected { reason } = event {
            say!("client disconnected: {reason}");
            if args.tcp.is_none() {
                return Ok(());
            }
        }
    }
    Ok(())
}

#[cfg(unix)]
fn spawn_pty<D: Driver>(emulator: D) -> anyhow::Result<sim::SimHandle<D::Command, D::Event>> {
    Ok(sim::spawn_pty(emulator, no_waker())?)
}

#[cfg(not(unix))]
fn spawn_pty<D: Driver>(_emulator: D) -> anyhow::Result<sim::SimHandle<D::Command, D::Event>> {
    bail!("pseudo-terminals exist only on Linux and macOS; use --tcp 127.0.0.1:5000")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sim_serves_what_a_family_registered_and_names_the_families_that_have_one() {
        let none = Family::named("none", "None board");
        let refused = run(&SimArgs::default(), none).unwrap_err().to_string();
        // The test-only echo board registered its emulator too, from its own folder.
        assert!(
            refused.ends_with("has no emulated board to serve; give servo, plen2, rflex, dynamixel, echo"),
            "{refused}"
        );
        let args = SimArgs { link: Some(LinkKind::Clean), stuffed: true, ..SimArgs::default() };
        let refused = run(&args, Family::Servo).unwrap_err().to_string();
        assert_eq!(
            refused,
            "--stuffed, --link do(es) not apply to the emulated servo board (it takes --state, --baud, \
             --turnaround-ms, --memory, --faults); nothing was started"
        );
    }
}
