//! `servo-studio play SHOW.json`: a show played with no window — every
//! device connected (saying which answered), the show's sound through the
//! system's sound server (or silent, said), each run's start, skew and end
//! logged; Ctrl-C and SIGTERM stop every device (bases brake) and exit 130
//! and 143. The boards must hold the show's content (`servo-studio import`).

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, bail};
use clap::Args;

use super::out::{line, say};
use super::signals;
use crate::link::no_waker;
use crate::show::play::{Player, Ran, Sent, Stage, Stopped};
use crate::show::{Cue, Show};
use crate::sim::MonotonicClock;

/// `servo-studio play` options.
#[derive(Debug, Args)]
pub struct PlayArgs {
    /// The show (or a project file: a show of one device).
    pub show: PathBuf,
    /// Where a device is connected, NAME=PORT (overrides the show's port; repeat for each).
    #[arg(long = "device", value_name = "NAME=PORT")]
    pub devices: Vec<String>,
    /// Plays the show this many times (default 1; with --at or --wait-gamepad, run after run until stopped).
    #[arg(long = "loop", value_name = "N", value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    pub runs: Option<u32>,
    /// Starts a run at this local time, HH:MM (repeat for several; each day).
    #[arg(long = "at", value_name = "HH:MM", value_parser = parse_at)]
    pub at: Vec<(u32, u32)>,
    /// Before each run, waits for a press of this button on this gamepad (an event device,
    /// e.g. /dev/input/event5:BTN_SOUTH): a visitor starts the show.
    #[arg(long = "wait-gamepad", value_name = "PATH:BUTTON", value_parser = parse_pad)]
    pub wait_gamepad: Option<(PathBuf, u16)>,
}

fn parse_pad(text: &str) -> Result<(PathBuf, u16), String> {
    let (path, button) =
        text.rsplit_once(':').ok_or_else(|| format!("{text:?}: give PATH:BUTTON, e.g. /dev/input/event5:BTN_SOUTH"))?;
    let code = crate::gamepad::code_by_name(button)
        .filter(|code| *code >= 0x100)
        .ok_or_else(|| format!("{button:?} is not a gamepad button (BTN_SOUTH, BTN_EAST, BTN_NORTH, BTN_WEST, BTN_TL, BTN_TR, BTN_SELECT, BTN_START)"))?;
    Ok((PathBuf::from(path), code))
}

/// Waits for a press (not a hold) of `button`, keeping the devices' links
/// fresh; `Ok(Err)` when STOP, a signal or a lost device came first, `Err`
/// when the gamepad went.
fn wait_for_press(
    pad: &crate::gamepad::Gamepad,
    button: u16,
    held: &mut bool,
    player: &mut Player<'_>,
) -> anyhow::Result<Result<(), Stopped>> {
    let stop = player.stop.clone();
    loop {
        crossbeam_channel::select! {
            recv(stop) -> what => return Ok(Err(Stopped::Asked(what.unwrap_or_default()))),
            recv(pad.updates()) -> update => match update.map(|(_, update)| update) {
                Ok(crate::gamepad::PadUpdate::State(state)) => {
                    let now = state.pressed(button);
                    let pressed = now && !*held;
                    *held = now;
                    if pressed {
                        return Ok(Ok(()));
                    }
                }
                Ok(crate::gamepad::PadUpdate::Dropped) => {}
                Ok(crate::gamepad::PadUpdate::Gone(gone)) => bail!("the gamepad {} is gone: {gone}", pad.path.display()),
                Err(_) => bail!("the gamepad {} is gone", pad.path.display()),
            },
            default(LOOK_EVERY) => {
                if let Err(stopped) = player.wait_between(Instant::now()) {
                    return Ok(Err(stopped));
                }
            }
        }
    }
}

/// How often the devices' links are looked at while a run waits for its button.
const LOOK_EVERY: std::time::Duration = std::time::Duration::from_millis(20);

fn parse_at(text: &str) -> Result<(u32, u32), String> {
    let (hours, minutes) = text.split_once(':').ok_or_else(|| format!("{text:?}: give a time as HH:MM"))?;
    match (hours.parse::<u32>(), minutes.parse::<u32>()) {
        (Ok(hours), Ok(minutes)) if hours < 24 && minutes < 60 => Ok((hours, minutes)),
        _ => Err(format!("{text:?} is not a time of day (00:00..23:59)")),
    }
}

/// Plays the show; `Ok` after the last run.
pub fn run(args: &PlayArgs) -> anyhow::Result<()> {
    let mut show = Show::open(&args.show).with_context(|| format!("cannot play {}", args.show.display()))?;
    default_cue(&mut show)?;
    let ports = ports(&show, &args.devices)?;
    for (device, port) in show.devices.iter_mut().zip(ports) {
        device.port = Some(port);
    }
    let interrupts = signals::listen().context("cannot listen for Ctrl-C")?;
    let mut stages: Vec<Box<dyn Stage>> = Vec::new();
    for device in &show.devices {
        let stage = connect(device).with_context(|| {
            let port = device.port.as_deref().unwrap_or_default();
            format!("{} ({}) did not answer on {port}; nothing was played", device.name, device.project.family.name())
        })?;
        stages.push(stage);
    }
    let sound = show.sound.as_ref().map(|track| args.show.parent().unwrap_or(Path::new(".")).join(&track.path));
    let (stop, stopped) = crossbeam_channel::unbounded();
    let exit_code = std::sync::Arc::new(std::sync::atomic::AtomicU8::new(0));
    let code = std::sync::Arc::clone(&exit_code);
    std::thread::spawn(move || {
        for interrupt in interrupts {
            code.store(interrupt.exit_code, std::sync::atomic::Ordering::SeqCst);
            if stop.send(interrupt.name.to_string()).is_err() {
                return;
            }
        }
    });
    let pad = match &args.wait_gamepad {
        Some((path, _)) => Some(
            crate::gamepad::Gamepad::open(path, None, no_waker())
                .with_context(|| format!("cannot read the gamepad {}", path.display()))?,
        ),
        None => None,
    };
    let mut held = false;
    let mut player = Player::new(&show, stages, sound, stopped.clone(), |error| {
        say!("no sound output ({error}): playing silent");
    });
    // Unattended (by the clock or a visitor's button): run after run until stopped, unless --loop says.
    let unattended = !args.at.is_empty() || args.wait_gamepad.is_some();
    let runs = args.runs.unwrap_or(if unattended { u32::MAX } else { 1 });
    let clock = MonotonicClock::now();
    for run in 1..=runs {
        if let Some(at) = next_time(&args.at, run) {
            match player.wait_between(at) {
                Ok(()) => {}
                Err(Stopped::Asked(what)) => return Err(interrupted(&exit_code, &what)),
                Err(stopped) => bail!("before run {run}: {stopped}"),
            }
        }
        if let (Some(pad), Some((path, button))) = (&pad, &args.wait_gamepad) {
            say!(
                "run {run} waits for {} on {}",
                crate::gamepad::code_name(crate::gamepad::EV_KEY, *button),
                path.display()
            );
            match wait_for_press(pad, *button, &mut held, &mut player)? {
                Ok(()) => {}
                Err(Stopped::Asked(what)) => return Err(interrupted(&exit_code, &what)),
                Err(stopped) => bail!("before run {run}: {stopped}"),
            }
        }
        if run > 1 {
            reconnect_lost(&mut player);
        }
        match player.run() {
            Ok(ran) => log_run(run, &ran, &clock)?,
            Err(Stopped::Asked(what)) => return Err(interrupted(&exit_code, &what)),
            Err(stopped) => bail!("run {run}: {stopped}"),
        }
    }
    Ok(())
}

/// Connects `device` on its port, saying how it answered and how its link was measured.
fn connect(device: &crate::show::Device) -> anyhow::Result<Box<dyn Stage>> {
    let port = device.port.as_deref().unwrap_or_default();
    let linked = crate::show::boards::connect_one(device)?;
    let opened = crate::link::by_id::resolve(port).unwrap_or_else(|_| port.to_string());
    let port = if opened == port.trim() { opened } else { format!("{port} ({opened})") };
    say!(
        "{} ({}) answered on {port}; its start takes {:.1} ms to reach it (its link {:.1} ms each way ± {:.1} ms, from {} round trips)",
        device.name,
        device.project.family.name(),
        linked.start_delay.as_secs_f64() * 1000.0,
        linked.link.one_way.as_secs_f64() * 1000.0,
        linked.link.spread.as_secs_f64() * 1000.0,
        crate::show::stages::ROUND_TRIPS,
    );
    Ok(linked.stage)
}

/// Before a run after the first: each device lost in an earlier run (one the
/// show plays on without) is connected again, or the run plays on without it (said).
fn reconnect_lost(player: &mut Player<'_>) {
    for (stage, device) in player.stages.iter_mut().zip(&player.show.devices) {
        let Some(why) = stage.lost() else { continue };
        // Its old link is let go first (told to stop, closed): a board or a
        // bridge that serves one client at a time takes the new one only then.
        *stage = Box::new(crate::show::play::Gone(why.clone()));
        match connect(device) {
            Ok(again) => *stage = again,
            Err(error) => say!("{} is still lost ({why}; {error:#}): this run plays on without it", device.name),
        }
    }
}

fn interrupted(exit_code: &std::sync::atomic::AtomicU8, what: &str) -> anyhow::Error {
    let code = exit_code.load(std::sync::atomic::Ordering::SeqCst);
    super::interrupted(
        signals::Interrupt { name: signal_name(what), exit_code: code.max(1) },
        "every device was stopped",
    )
}

fn signal_name(what: &str) -> &'static str {
    match what {
        "SIGINT" => "SIGINT",
        "SIGTERM" => "SIGTERM",
        "SIGHUP" => "SIGHUP",
        _ => "Ctrl-C",
    }
}

/// A show of one device with no cue (a project file) starts its first macro or motion at 0, said.
fn default_cue(show: &mut Show) -> anyhow::Result<()> {
    if !show.cues.is_empty() {
        return Ok(());
    }
    let [device] = show.devices.as_slice() else { bail!("the show has no cue: nothing to play") };
    let Some(start) = device.first_stored() else { bail!("{} has no cue and no macro or motion to play", device.name) };
    say!("{} has no cue: playing {start} from the start", device.name);
    show.cues.push(Cue { device: device.name.clone(), at_ms: 0, start });
    Ok(())
}

/// Each device's port: `--device NAME=PORT`, else the show's.
pub(super) fn ports(show: &Show, given: &[String]) -> anyhow::Result<Vec<String>> {
    let mut named: Vec<(String, String)> = Vec::new();
    for pair in given {
        let Some((name, port)) = pair.split_once('=') else { bail!("--device {pair:?}: give NAME=PORT") };
        if show.device(name).is_none() {
            let names: Vec<&str> = show.devices.iter().map(|d| d.name.as_str()).collect();
            bail!("--device {name}: the show has no device {name:?} (it has {})", names.join(", "));
        }
        named.push((name.to_string(), port.to_string()));
    }
    show.devices
        .iter()
        .map(|device| {
            named
                .iter()
                .find(|(name, _)| *name == device.name)
                .map(|(_, port)| port.clone())
                .or_else(|| device.port.clone())
                .ok_or_else(|| anyhow::anyhow!("{} has no port: give --device {}=PORT", device.name, device.name))
        })
        .collect()
}

/// The next of the day's `--at` times for run `run`, as an instant (`None`: start now).
fn next_time(at: &[(u32, u32)], run: u32) -> Option<Instant> {
    if at.is_empty() {
        return None;
    }
    let now = chrono::Local::now();
    let (hours, minutes) = at[usize::try_from(run - 1).unwrap_or(0) % at.len()];
    let today = now.date_naive().and_hms_opt(hours, minutes, 0)?;
    let mut when = today.and_local_timezone(chrono::Local).earliest()?;
    if when <= now {
        when += chrono::Duration::days(1);
    }
    let wait = (when - now).to_std().unwrap_or_default();
    say!("run {run} waits for {when}");
    Some(Instant::now() + wait)
}

fn log_run(run: u32, ran: &Ran, clock: &MonotonicClock) -> anyhow::Result<()> {
    line(&format!(
        "run {run}: show's 0 at {} ns (monotonic){}",
        clock.ns(ran.zero),
        if ran.with_sound { ", with its sound" } else { ", silent" }
    ))?;
    for sent in &ran.sent {
        line(&format!(
            "run {run}: {} {} due at {} ns, written {:.2} ms late, moving at {} ns ± {:.2} ms ({})",
            sent.device,
            sent.start,
            clock.ns(sent.due_at),
            sent.late_ms(),
            clock.ns(sent.moving_at),
            sent.uncertain_ms(),
            sent.uncertain_of,
        ))?;
    }
    for (device, why) in &ran.lost {
        line(&format!("run {run}: the link to {device} was lost ({why}): the show played on without it"))?;
    }
    let worst = ran.sent.iter().map(Sent::skew_ms).fold(0.0, f64::max);
    let late = ran.sent.iter().map(Sent::late_ms).fold(0.0, f64::max);
    line(&format!(
        "run {run}: ended after {:.2} s; largest skew {worst:.2} ms (written up to {late:.2} ms late, plus each link's spread and a PLEN2's wait for its cycle)",
        ran.ended.saturating_duration_since(ran.zero).as_secs_f64()
    ))?;
    Ok(())
}
