//! The DYNAMIXEL family on the command line: `sim --protocol dynamixel`
//! serves an emulated bus (the demo's three servos, or the servos a
//! project's section lists with `--state`; hardware errors on a schedule
//! with `--hardware-error`; every packet a line of `--log`), and `board info`
//! / `export` scan a real bus: every servo by ID, model, firmware and limits,
//! written into a project's section. A DYNAMIXEL stores no motion, so
//! `import` says how its motions are played instead.

use std::path::Path;
use std::time::{Duration, Instant};

use anyhow::{Context, bail};

use super::PortArgs;
use super::bounds::Slots;
use super::family::{BoardCommands, ImportChoices, Registered};
use super::out::say;
use super::sim::{Emulator, SimArgs};
use crate::device::dynamixel::{DynamixelCommand, DynamixelEvent, DynamixelHandle, Found, Limits, ONE_IDS};
use crate::link::{self, LinkEvent, PortName, no_waker};
use crate::project::dynamixel::{DynamixelSection, ServoSetup};
use crate::project::{self, Family, Project};
use crate::sim::dynamixel::{BusCommand, DynamixelBus, Fault as DynamixelFault, MODELS, Servo as DynamixelServo};

inventory::submit! {
    Emulator {
        family: Family::Dynamixel,
        takes: &["--state", "--hardware-error"],
        note: " (--state: a project whose DYNAMIXEL section lists the servos on the bus)",
        serve: emulate,
    }
}
inventory::submit! {
    Registered {
        family: Family::Dynamixel,
        timeout_ms: 1000,
        paced: false,
        board: Ok(BoardCommands { info, export, import }),
    }
}

/// The emulated bus `args` ask for.
fn bus(args: &SimArgs) -> anyhow::Result<DynamixelBus> {
    let mut bus = match &args.state {
        None => DynamixelBus::demo(),
        Some(path) => {
            let loaded = project::load(path).with_context(|| format!("cannot read {}", path.display()))?;
            let section = DynamixelSection::of(&loaded);
            if section.servos.is_empty() {
                bail!(
                    "{} lists no DYNAMIXEL servo (its \"dynamixel\" section has none); nothing was started",
                    path.display()
                );
            }
            let mut servos = Vec::new();
            for servo in &section.servos {
                let Some(model) = MODELS.iter().find(|model| model.number == servo.model_number) else {
                    let emulated: Vec<String> =
                        MODELS.iter().map(|model| format!("{} ({})", model.name, model.number)).collect();
                    bail!(
                        "servo {}: model {} is not emulated (use one of {}); nothing was started",
                        servo.id,
                        servo.model_number,
                        emulated.join(", ")
                    );
                };
                servos.push(DynamixelServo::new(model, servo.id));
            }
            DynamixelBus::new(servos)
        }
    };
    for said in &args.hardware_error {
        let (after, command) = hardware_error(said)?;
        bus = bus.scheduling(after, command);
    }
    Ok(bus)
}

/// `ID:KIND@SECONDS`, e.g. `2:overheating@5`.
fn hardware_error(said: &str) -> anyhow::Result<(Duration, BusCommand)> {
    let wrong = || {
        anyhow::anyhow!(
            "--hardware-error {said:?}: write ID:KIND@SECONDS, e.g. 2:overheating@5 (KIND: input-voltage, overheating, overload)"
        )
    };
    let (id, rest) = said.split_once(':').ok_or_else(wrong)?;
    let (kind, seconds) = rest.split_once('@').ok_or_else(wrong)?;
    let id: u8 = id.trim().parse().map_err(|_| wrong())?;
    let fault = DynamixelFault::named(kind.trim()).ok_or_else(wrong)?;
    let seconds: f64 = seconds.trim().parse().map_err(|_| wrong())?;
    if !(0.0..=86_400.0).contains(&seconds) {
        return Err(wrong());
    }
    Ok((Duration::from_secs_f64(seconds), BusCommand::Fault { id, fault }))
}

fn emulate(args: &SimArgs) -> anyhow::Result<()> {
    super::sim::serve(args, bus(args)?)
}

/// What a scan found: each servo and its limits.
type Scanned = Vec<(Found, Option<Limits>)>;

/// The line rates a scan tries, in order, when none is given: the X-series'
/// factory rate, the AX's, then the others ROBOTIS's tools offer.
pub const USUAL_RATES: [u32; 7] = [57_600, 1_000_000, 115_200, 2_000_000, 3_000_000, 4_000_000, 9_600];

/// Scans the bus at `port`: at `--baud` when given (and over TCP, which has
/// no rate), else at each of [`USUAL_RATES`] until servos answer (a bus runs
/// at one rate). The rate they answered at (none over TCP) and what was found.
fn scan(port: &PortArgs) -> anyhow::Result<(Option<u32>, Scanned)> {
    let name = PortName::parse(&port.port)?;
    let tcp = matches!(name, PortName::Tcp(_));
    let rates: Vec<u32> = match port.baud {
        _ if tcp => vec![port.baud(Family::Dynamixel)],
        Some(baud) => vec![baud],
        None => USUAL_RATES.to_vec(),
    };
    for (tried, &baud) in rates.iter().enumerate() {
        if tried > 0 {
            say!("no servo answered at {} baud; trying {baud}", rates[tried - 1]);
        }
        let found = scan_at(&name, baud)?;
        if !found.is_empty() {
            return Ok(((!tcp).then_some(baud), found));
        }
    }
    Ok((None, Vec::new()))
}

/// Scans the bus at `name` at `baud` (2.0 by broadcast, 1.0 ID by ID), progress on stderr.
fn scan_at(name: &PortName, baud: u32) -> anyhow::Result<Scanned> {
    let settings = link::LineSettings { baud, ..crate::device::line_settings(Family::Dynamixel) };
    let connection = link::open(name, &settings)?;
    let handle =
        DynamixelHandle::over(connection, no_waker()).with_context(|| format!("cannot start talking to {name}"))?;
    handle.send(DynamixelCommand::Read(false));
    handle.send(DynamixelCommand::Scan { one: ONE_IDS });
    let mut found: Scanned = Vec::new();
    let mut last_said = Instant::now();
    // The scan's own deadlines end it; this only guards against a driver that never says so.
    let deadline = Instant::now() + Duration::from_secs(60);
    let mut scanned = false;
    while Instant::now() < deadline {
        let wait = if scanned { Duration::from_millis(300) } else { Duration::from_secs(5) };
        let Ok(event) = handle.events().recv_timeout(wait) else {
            if scanned {
                break;
            }
            continue;
        };
        match event {
            LinkEvent::Driver(DynamixelEvent::Found(servo)) => found.push((servo, None)),
            LinkEvent::Driver(DynamixelEvent::Limits { id, limits }) => {
                if let Some(entry) = found.iter_mut().find(|(servo, _)| servo.id == id) {
                    entry.1 = Some(limits);
                }
                if scanned && found.iter().all(|(_, limits)| limits.is_some()) {
                    break;
                }
            }
            LinkEvent::Driver(DynamixelEvent::Scanning { done, of })
                if last_said.elapsed() > Duration::from_millis(500) =>
            {
                last_said = Instant::now();
                say!("scanning: Protocol 1.0 ID {done} of {of}");
            }
            LinkEvent::Driver(DynamixelEvent::Scanned { .. }) => {
                scanned = true;
                if found.iter().all(|(_, limits)| limits.is_some()) {
                    break;
                }
            }
            LinkEvent::Disconnected { reason } => bail!("the link to {name} ended during the scan: {reason}"),
            LinkEvent::Driver(_) => {}
        }
    }
    if !scanned {
        bail!("the scan of {name} did not end within a minute");
    }
    Ok(found)
}

/// `board info --protocol dynamixel`: every servo found, a line each.
fn info(port: &PortArgs) -> anyhow::Result<()> {
    let (rate, found) = scan(port)?;
    if let Some(rate) = rate {
        say!("{} servo(s) answered at {rate} baud", found.len());
    }
    if found.is_empty() {
        let tried = match port.baud {
            Some(baud) => format!("at {baud} baud"),
            None => format!("at any of {} baud", USUAL_RATES.map(|rate| rate.to_string()).join(", ")),
        };
        bail!(
            "no servo answered {tried} in either protocol: check the power and the cable (X-series leave the factory at 57600, AX at 1000000)"
        );
    }
    for (servo, limits) in &found {
        let limits = limits.map_or_else(
            || "limits not read".to_string(),
            |limits| {
                format!("positions {}..={}, {} °C at most", limits.lowest, limits.highest, limits.temperature_limit_c)
            },
        );
        let protocol = if servo.protocol == crate::device::dynamixel::Protocol::Two { "2.0" } else { "1.0" };
        super::out::line(&format!(
            "ID {:>3}  {:<12} model {:>5}  firmware {:>3}  protocol {protocol}  {limits}",
            servo.id,
            servo.model_name(),
            servo.model_number,
            servo.firmware
        ))?;
    }
    Ok(())
}

/// `export --protocol dynamixel`: the servos found, into a project's section.
fn export(port: &PortArgs, out: &Path, _slots: Option<&Slots>) -> anyhow::Result<()> {
    let (_, found) = scan(port)?;
    let section = DynamixelSection {
        servos: found
            .iter()
            .map(|(servo, _)| ServoSetup {
                id: servo.id,
                name: String::new(),
                model_number: servo.model_number,
                profile: None,
            })
            .collect(),
        motions: Vec::new(),
    };
    let mut project = Project::empty(Family::Dynamixel);
    project.sections.set(Family::Dynamixel, section.kept());
    project::save(out, &project)?;
    say!("exported {} servo(s) to {}", found.len(), out.display());
    Ok(())
}

/// `import --protocol dynamixel`: a DYNAMIXEL stores no motion.
fn import(_port: &PortArgs, _file: &Path, _project: &Project, _choices: ImportChoices) -> anyhow::Result<()> {
    bail!(
        "a DYNAMIXEL stores no motion to import: its motions are streamed from the computer — open the project in the editor (servo-studio gui) and play them, or play a show with `servo-studio play`. Nothing was written"
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_hardware_error_is_read_as_written_or_refused_with_the_form() {
        let (after, command) = hardware_error("2:overheating@5").unwrap();
        assert_eq!(after, Duration::from_secs(5));
        assert_eq!(command, BusCommand::Fault { id: 2, fault: DynamixelFault::Overheating });
        let refused = hardware_error("2:melting@5").unwrap_err().to_string();
        assert!(refused.contains("write ID:KIND@SECONDS"), "{refused}");
        assert!(hardware_error("2:overload").is_err());
    }
}
