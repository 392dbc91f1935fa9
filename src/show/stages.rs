//! The devices a show plays on, connected: a servo board, a PLEN2 or an
//! rFLEX base behind its port, each a [`Stage`] the player starts and stops.

use std::collections::BTreeMap;
use std::time::{Duration, Instant};

use crossbeam_channel::Receiver;

use anyhow::bail;

use super::at::{Now, Posed};
use super::passes::Axis;
use super::play::Stage;
use super::{Device, Start};
use crate::audio::together::link_delay;
use crate::device::plen2::playback::{DEVICE_IDS, Settings, joint_settings};
use crate::device::plen2::{
    Command as Plen2Command, Plen2Handle, Plen2Notice, Plen2Options, Plen2Requester, start_delay,
};
use crate::device::rflex::{RflexBase, RflexNotice};
use crate::device::servo::{DEFAULT_BAUD, RequestError, Requester, ServoBoard, SessionConfig};
use crate::device::speed::{LiveSpeed, Slew};
use crate::device::{self};
use crate::link::{self, LineSettings, LinkEvent, PortName, no_waker};
use crate::project::plen2::Joint;
use crate::project::{Family, Servo};
use crate::protocol::servo::{ALL_SERVOS, Message, ServoMove, ServoSwitches};

/// Connects `device` on `port`: its stage and the delay of its first cue's start.
pub fn connect(port: &str, device: &Device) -> anyhow::Result<(Box<dyn Stage>, Duration)> {
    let family = device.project.family;
    let name = PortName::parse(port)?;
    let settings = device::line_settings(family);
    if family == Family::Servo {
        let board = ServoBoard::connect(&name, DEFAULT_BAUD, SessionConfig::default(), no_waker())?;
        let latency = round_trip(|| {
            board.requester().request(Message::QueryMemorySizeRequest).map(|_| ()).map_err(|e| e.to_string())
        })?;
        let servos = device.project.servo.servos.clone();
        let requester = board.requester();
        let (sent, battery) = (BTreeMap::new(), (None, None, None));
        let stage = ServoStage { requester, latency, board, lost: None, servos, sent, battery };
        let delay = stage.start_delay(&Start::Macro(0));
        return Ok((Box::new(stage), delay));
    }
    if family == Family::Plen2 {
        let connection = link::open(&name, &LineSettings { ..settings })?;
        let mut handle = Plen2Handle::over(connection, Plen2Options::default(), no_waker())?;
        let requester = handle.requester();
        let latency = round_trip(|| requester.probe().map_err(|e| e.to_string()))?;
        let lost = handle.pump(Instant::now()).into_iter().find_map(|notice| match notice {
            Plen2Notice::Disconnected(reason) => Some(reason.to_string()),
            _ => None,
        });
        let settings = joint_settings(&device.project.plen2);
        let stage = Plen2Stage { handle, requester, latency, lost, settings, sent: None, slew: None };
        let delay = stage.start_delay(&Start::Slot(0));
        return Ok((Box::new(stage), delay));
    }
    if family == Family::Rflex {
        let connection = link::open(&name, &settings)?;
        let base = RflexBase::over(connection, device.project.rflex.robot.conversion(), no_waker())?;
        base.start(false);
        let accel = device.project.rflex.drive.accel_m_per_s2;
        let stage = RflexStage { base, accel, baud: settings.baud, lost: None, driving: None };
        let delay = stage.start_delay(&Start::Drive { speed_m_s: 0.0, turn_deg_s: 0.0, for_ms: 0 });
        return Ok((Box::new(stage), delay));
    }
    bail!("a {} cannot play in a show", family.name())
}

impl ServoStage {
    /// Asks for the battery every [`BATTERY_EVERY`], taking the answer in when it came.
    fn ask_battery(&mut self, now: Instant) {
        let (asking, asked, permil) = &mut self.battery;
        if let Some(answer) = asking
            && let Ok(answered) = answer.try_recv()
        {
            if let Ok(Message::QueryRemainPowerResponse { permil: read }) = answered {
                *permil = Some(read);
            }
            *asking = None;
        }
        if asking.is_none() && asked.is_none_or(|at| now.saturating_duration_since(at) >= BATTERY_EVERY) {
            *asking = self.requester.request_async(Message::QueryRemainPowerRequest).ok();
            *asked = Some(now);
        }
    }
}

/// A question's answer on its way.
type Answer = Receiver<Result<Message, RequestError>>;

/// How often a held servo board is asked for its battery.
const BATTERY_EVERY: Duration = Duration::from_secs(5);

/// How long a servo not yet told where to be takes to get there while following, 10 ms units.
const EASE_IN_10MS: i16 = 100;

/// Whole 10 ms from `when` to `at` (at least one, at most the protocol's field).
fn ten_ms_since(when: Instant, at: Instant) -> i16 {
    let tens = at.saturating_duration_since(when).as_millis() / 10;
    i16::try_from(tens.clamp(1, 1000)).unwrap_or(1000)
}

/// Half the shortest of three round trips: the link's one-way latency, as well as it can be known.
fn round_trip(mut ask: impl FnMut() -> Result<(), String>) -> anyhow::Result<Duration> {
    let mut shortest = Duration::MAX;
    for _ in 0..3 {
        let asked = Instant::now();
        ask().map_err(|error| anyhow::anyhow!(error))?;
        shortest = shortest.min(asked.elapsed());
    }
    Ok(shortest / 2)
}

struct ServoStage {
    board: ServoBoard,
    requester: Requester,
    latency: Duration,
    lost: Option<String>,
    /// The servos, with their limits.
    servos: Vec<Servo>,
    /// What each servo was last told while following, and when.
    sent: BTreeMap<u8, (i16, Instant)>,
    /// The battery: the question out (and when it was asked), the last answer (‰).
    battery: (Option<Answer>, Option<Instant>, Option<i16>),
}

impl Stage for ServoStage {
    fn start_delay(&self, start: &Start) -> Duration {
        let Start::Macro(macro_id) = *start else { return Duration::ZERO };
        let bytes = Message::ExecuteMacroRequest { macro_id }.encode().map_or(16, |bytes| bytes.len());
        link_delay(bytes, DEFAULT_BAUD, self.latency)
    }

    fn start(&mut self, start: &Start) -> Result<(), String> {
        let Start::Macro(macro_id) = *start else { return Err(format!("a servo board cannot start {start:?}")) };
        self.requester.send(Message::ExecuteMacroRequest { macro_id }).map_err(|error| error.to_string())
    }

    fn stop(&mut self) {
        let all = ServoSwitches { servo_id: ALL_SERVOS, is_start: false, is_hold: true };
        let _ = self.requester.stop(Message::SetServoParameterRequest(all));
        // Where they stopped is not known: the next follow eases them in again.
        self.sent.clear();
    }

    fn resume(&mut self) {
        let all = ServoSwitches { servo_id: ALL_SERVOS, is_start: true, is_hold: true };
        let _ = self.requester.send(Message::SetServoParameterRequest(all));
    }

    fn follow(&mut self, now: &Now) -> Result<(), String> {
        let Now::Posed(Posed::Servos(degrees)) = now else { return Ok(()) };
        let at = Instant::now();
        let mut moves = Vec::new();
        for servo in &self.servos {
            let Some(&degree) = degrees.get(&servo.id) else { continue };
            // Degrees of a servo: within ±180.
            #[allow(clippy::cast_possible_truncation)]
            let degree = servo.clamp(degree.round() as i16);
            let interval_10ms = match self.sent.get(&servo.id) {
                Some(&(told, _)) if told == degree => continue,
                // Over the time since it was last told, as the show moved it.
                Some(&(_, when)) => ten_ms_since(when, at),
                // Where it is now is not known: eased in, not slammed.
                None => EASE_IN_10MS,
            };
            self.sent.insert(servo.id, (degree, at));
            moves.push(ServoMove { servo_id: servo.id, degree, interval_10ms });
        }
        if moves.is_empty() {
            return Ok(());
        }
        self.requester.live_move(moves).map_err(|error| error.to_string())
    }

    fn tick(&mut self, now: Instant) {
        for event in self.board.events().try_iter() {
            if let LinkEvent::Disconnected { reason } = event {
                self.lost = Some(reason.to_string());
            }
        }
        self.ask_battery(now);
    }

    fn pose(&mut self, axis: Axis, value_deg: f64, speed: LiveSpeed) -> Result<f64, String> {
        let Axis::Servo(id) = axis else { return Err("a servo board's axes are servos".into()) };
        let servo = self.servos.iter().find(|servo| servo.id == id).ok_or(format!("it has no servo {id}"))?;
        // Degrees of a servo: a finite value within ±180 once clamped.
        #[allow(clippy::cast_possible_truncation)]
        let degree = servo.clamp(value_deg.clamp(-180.0, 180.0).round() as i16);
        let from = match self.sent.get(&id) {
            Some(&(told, _)) => f64::from(told),
            // Where it is is not known: as if from the farther limit, so it cannot slam.
            None => servo.farther_limit(f64::from(degree)),
        };
        let interval_10ms = speed.interval_10ms(f64::from(degree) - from, 2);
        self.sent.insert(id, (degree, Instant::now()));
        let moves = vec![ServoMove { servo_id: id, degree, interval_10ms }];
        self.requester.live_move(moves).map_err(|error| error.to_string())?;
        Ok(f64::from(degree))
    }

    fn battery(&self) -> Option<String> {
        self.battery.2.map(device::servo::battery_text)
    }

    fn lost(&self) -> Option<String> {
        self.lost.clone()
    }
}

struct Plen2Stage {
    handle: Plen2Handle,
    requester: Plen2Requester,
    latency: Duration,
    lost: Option<String>,
    /// Each joint's home and limits, by device id.
    settings: Settings,
    /// The joints' values last told while following (from home).
    sent: Option<[i16; DEVICE_IDS]>,
    /// A remote's pose, walked toward a cycle at a time (absolute, by joint), and how fast.
    slew: Option<(Slew, LiveSpeed)>,
}

impl Stage for Plen2Stage {
    fn start_delay(&self, start: &Start) -> Duration {
        let Start::Slot(slot) = *start else { return Duration::ZERO };
        start_delay(&Plen2Command::PlayMotion { slot }, self.latency)
    }

    fn start(&mut self, start: &Start) -> Result<(), String> {
        let Start::Slot(slot) = *start else { return Err(format!("a PLEN2 cannot start {start:?}")) };
        self.requester.send(Plen2Command::PlayMotion { slot }).map_err(|error| error.to_string())
    }

    fn stop(&mut self) {
        self.handle.stop();
        // STOP sends the joints home (`$HP`).
        self.sent = Some([0; DEVICE_IDS]);
        self.slew = None;
    }

    fn follow(&mut self, now: &Now) -> Result<(), String> {
        let Now::Posed(Posed::Joints(values)) = now else { return Ok(()) };
        let before = self.sent.unwrap_or([i16::MIN; DEVICE_IDS]);
        let moves: Vec<(u8, i16)> = Joint::ALL
            .iter()
            .map(|joint| (joint.device_id(), usize::from(joint.device_id())))
            .filter(|&(_, device)| before[device] != values[device])
            .map(|(id, device)| {
                let (home, min, max) = self.settings[device];
                (id, home.saturating_add(values[device]).clamp(min.min(max), max.max(min)))
            })
            .collect();
        self.sent = Some(*values);
        if !moves.is_empty() {
            // Coalesced and paced by the driver, as the sliders are.
            self.handle.move_joints(moves);
        }
        Ok(())
    }

    fn tick(&mut self, now: Instant) {
        for notice in self.handle.pump(now) {
            if let Plen2Notice::Disconnected(reason) = notice {
                self.lost = Some(reason.to_string());
            }
        }
        if let Some((slew, speed)) = &mut self.slew {
            let moves: Vec<(u8, i16)> = slew
                .step(now, *speed)
                .into_iter()
                .map(|(index, angle)| (Joint::ALL[index].device_id(), angle))
                .collect();
            if !moves.is_empty() {
                self.handle.move_joints(moves);
            }
        }
    }

    fn start_list(&mut self, entries: &[(u8, u8)]) -> Result<(), String> {
        self.slew = None;
        self.handle.queue_list(entries);
        self.requester.send(Plen2Command::Pop).map_err(|error| error.to_string())
    }

    fn pose(&mut self, axis: Axis, value_deg: f64, speed: LiveSpeed) -> Result<f64, String> {
        let Axis::Joint(device) = axis else { return Err("a PLEN2's axes are joints".into()) };
        let joint = Joint::ALL.iter().find(|joint| joint.device_id() == device).ok_or(format!("no joint {device}"))?;
        let (home, min, max) = self.settings[usize::from(device)];
        // Tenths of a degree of a finite value within ±180°.
        #[allow(clippy::cast_possible_truncation)]
        let tenths = (value_deg.clamp(-180.0, 180.0) * 10.0).round() as i16;
        let target = home.saturating_add(tenths).clamp(min.min(max), max.max(min));
        let now = Instant::now();
        let (slew, pace) = self.slew.get_or_insert_with(|| {
            // Where the joints are: where they were last told, else home.
            let told = self.sent.unwrap_or([0; DEVICE_IDS]);
            let at: [i16; 18] = std::array::from_fn(|index| {
                let id = usize::from(Joint::ALL[index].device_id());
                self.settings[id].0.saturating_add(told[id])
            });
            (Slew::new(at, at, now), speed)
        });
        slew.target[joint.index()] = target;
        *pace = speed;
        Ok(f64::from(target - home) / 10.0)
    }

    fn lost(&self) -> Option<String> {
        self.lost.clone()
    }
}

struct RflexStage {
    base: RflexBase,
    accel: f64,
    baud: u32,
    lost: Option<String>,
    /// The drive last told while following (None: not yet).
    driving: Option<Option<(f64, f64)>>,
}

impl Stage for RflexStage {
    fn start_delay(&self, _start: &Start) -> Duration {
        // A velocity command's frame: under 40 bytes.
        link_delay(40, self.baud, Duration::ZERO)
    }

    fn start(&mut self, start: &Start) -> Result<(), String> {
        let Start::Drive { speed_m_s, turn_deg_s, .. } = *start else {
            return Err(format!("an rFLEX base cannot start {start:?}"));
        };
        self.base.set_brake(false);
        self.base.drive(speed_m_s, turn_deg_s.to_radians(), self.accel);
        Ok(())
    }

    fn stop(&mut self) {
        self.base.stop();
        self.base.set_brake(true);
        self.driving = Some(None);
    }

    fn drive(&mut self, drive: (f64, f64)) -> Result<(), String> {
        self.follow(&Now::Driving(Some(drive)))
    }

    fn follow(&mut self, now: &Now) -> Result<(), String> {
        let Now::Driving(driving) = *now else { return Ok(()) };
        if self.driving == Some(driving) {
            return Ok(());
        }
        self.driving = Some(driving);
        match driving {
            Some((speed_m_s, turn_deg_s)) => {
                self.base.set_brake(false);
                self.base.drive(speed_m_s, turn_deg_s.to_radians(), self.accel);
            }
            None => {
                self.base.stop();
                self.base.set_brake(true);
            }
        }
        Ok(())
    }

    fn tick(&mut self, now: Instant) {
        for notice in self.base.pump(now) {
            if let RflexNotice::Disconnected(reason) = notice {
                self.lost = Some(reason.to_string());
            }
        }
    }

    fn lost(&self) -> Option<String> {
        self.lost.clone().or_else(|| self.base.is_lost().then(|| "the link ended".to_string()))
    }
}
