//! `servo-studio sim`: an emulated board of any family on a pseudo-terminal or
//! TCP. Each family takes its own options; one given to a family it does not
//! apply to is refused, never silently ignored.

use std::net::SocketAddr;
use std::path::PathBuf;
use std::time::Duration;

use anyhow::{Context, bail};
use clap::Args;

use super::bounds;
use super::out::say;
use crate::device::servo::ServoImage;
use crate::link::{Driver, LinkEvent, no_waker};
use crate::project::Family;
use crate::project::rflex::Robot;
use crate::sim::{
    self, Faults, LineNoise, LinkKind, Plen2Sim, Plen2Timing, RflexSim, RflexSimConfig, ServoSim, SimConfig,
};

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
}

impl SimArgs {
    /// The options given, by name, that `family`'s emulator does not take.
    fn foreign(&self, family: Family) -> Vec<&'static str> {
        let given = [
            ("--state", self.state.is_some(), [true, true, false]),
            ("--baud", self.baud.is_some(), [true, false, false]),
            ("--turnaround-ms", self.turnaround_ms.is_some(), [true, false, false]),
            ("--memory", self.memory.is_some(), [true, false, false]),
            ("--faults", self.faults.is_some(), [true, false, false]),
            ("--stuffed", self.stuffed, [false, false, true]),
            ("--body-panels-only", self.body_panels_only, [false, false, true]),
            ("--noise", self.noise.is_some(), [false, false, true]),
            ("--robot", self.robot.is_some(), [false, false, true]),
            ("--room", self.room.is_some(), [false, false, true]),
            ("--start", self.start.is_some(), [false, false, true]),
            ("--link", self.link.is_some(), [false, true, false]),
        ];
        let column = match family {
            Family::Servo => 0,
            Family::Plen2 => 1,
            Family::Rflex => 2,
            // A family without an emulator here takes none of them.
            _ => return given.into_iter().filter(|(_, given, _)| *given).map(|(name, _, _)| name).collect(),
        };
        given.into_iter().filter(|(_, given, takes)| *given && !takes[column]).map(|(name, _, _)| name).collect()
    }
}

/// What each family's emulator takes, for the refusal.
fn takes(family: Family) -> &'static str {
    match family {
        Family::Servo => "--state, --baud, --turnaround-ms, --memory, --faults",
        Family::Plen2 => "--state, --link (a slow line is --link slow=BAUD)",
        Family::Rflex => {
            "--robot, --room, --start, --stuffed, --noise, --body-panels-only (a base stores nothing to preload)"
        }
        _ => "nothing",
    }
}

/// Runs `sim --protocol FAMILY`.
pub fn run(args: &SimArgs, family: Family) -> anyhow::Result<()> {
    let foreign = args.foreign(family);
    if !foreign.is_empty() {
        bail!(
            "{} do(es) not apply to the emulated {family} board (it takes {}); nothing was started",
            foreign.join(", "),
            takes(family)
        );
    }
    match family {
        Family::Servo => servo(args),
        Family::Plen2 => plen2(args),
        Family::Rflex => serve(args, RflexSim::new(rflex_config(args)?)),
        other => bail!("the {} has no emulated board to serve; give servo, plen2 or rflex", other.name()),
    }
}

/// The emulated base's config: its robot, its room and where it stands in it
/// (refused when the robot would not fit there).
fn rflex_config(args: &SimArgs) -> anyhow::Result<RflexSimConfig> {
    let defaults = RflexSimConfig::default();
    let conversion = args.robot.unwrap_or_default().conversion();
    let room_m = args.room.unwrap_or(defaults.room_m);
    let (x, y, theta_deg) = args.start.unwrap_or((0.0, 0.0, 0.0));
    let radius = conversion.layout.body_radius_m;
    if x.abs() > room_m.0 / 2.0 - radius || y.abs() > room_m.1 / 2.0 - radius {
        bail!(
            "--start {x},{y}: the base (a radius of {radius} m) does not fit there in a {} × {} m room; nothing was started",
            room_m.0,
            room_m.1
        );
    }
    Ok(RflexSimConfig {
        conversion,
        stuffed: args.stuffed,
        noise: args.noise.clone().unwrap_or_default(),
        room_m,
        start: (x, y, theta_deg.to_radians()),
        body_panels_only: args.body_panels_only,
        ..defaults
    })
}

fn servo(args: &SimArgs) -> anyhow::Result<()> {
    let image = match &args.state {
        Some(path) => {
            let loaded = crate::project::read(path)
                .with_context(|| format!("cannot preload the board from {}", path.display()))?
                .project;
            if loaded.family != Family::Servo {
                bail!(
                    "{} is a {} project; the emulated servo board takes a servo project",
                    path.display(),
                    loaded.family
                );
            }
            ServoImage::from_project(&loaded.servo)
                .with_context(|| format!("{} cannot be stored on a board", path.display()))?
        }
        None => ServoImage::default(),
    };
    let defaults = SimConfig::default();
    let config = SimConfig {
        total_memory_bytes: args.memory.unwrap_or(defaults.total_memory_bytes),
        baud: args.baud,
        turnaround: Duration::from_millis(args.turnaround_ms.unwrap_or(0)),
        faults: args.faults.clone().unwrap_or_default(),
        ..defaults
    };
    serve(args, ServoSim::new(config, image))
}

/// Runs the emulated PLEN2; `--state` preloads its joint settings and slots
/// from a project file, a motion.json or a folder of them.
fn plen2(args: &SimArgs) -> anyhow::Result<()> {
    let link = args.link.unwrap_or(LinkKind::Clean);
    let mut robot = Plen2Sim::new(Plen2Timing::default()).with_link(link);
    if link != LinkKind::Clean {
        say!("the line to the robot: {link}");
    }
    if let Some(path) = &args.state {
        let plen2 = super::open_input(path)?.loaded.project.plen2;
        // A stand-in robot holds only what a robot can (check, import and trajectory refuse the same).
        crate::device::plen2::storable(&plen2)
            .map_err(|error| {
                anyhow::anyhow!(
                    "cannot preload the robot from {}: {error}. Fix the motion (`servo-studio check` lists every problem) and start it again",
                    path.display()
                )
            })?;
        robot.preload(&crate::device::plen2::store_commands(&plen2));
        say!(
            "preloaded {} motion(s) and {} joint setting(s) from {}",
            plen2.motions.len(),
            plen2.joints.len(),
            path.display()
        );
    }
    serve(args, robot)
}

/// Serves an emulator of any family on a pseudo-terminal or TCP; prints the port on
/// the first line of stdout, then runs until killed.
pub fn serve<D: Driver>(args: &SimArgs, emulator: D) -> anyhow::Result<()> {
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
