//! A servo board on a show's stage: macros started, servos followed and
//! posed within their limits, asked for its battery twice a second (which
//! is also how it is known to be there).

mod lane;

use std::collections::BTreeMap;
use std::time::{Duration, Instant};

use crossbeam_channel::Receiver;

use super::LinkDelay;
use super::Linked;
use crate::audio::together::link_delay;
use crate::authoring::fit::{self as fit, ServoBoard as FitServo};
use crate::authoring::fitted::{self, SERVO_UPDATE_MS};
use crate::device;
use crate::device::servo::{DEFAULT_BAUD, Known, LivePose, RequestError, Requester, ServoBoard, SessionConfig};
use crate::device::speed::LiveSpeed;
use crate::link::{LineSettings, LinkEvent, PortName, no_waker};
use crate::project::next_free_id;
use crate::project::{Project, Servo};
use crate::protocol::servo::{ALL_SERVOS, Message, ServoMove, ServoSwitches};
use crate::show::Device;
use crate::show::Start;
use crate::show::alive::{Alive, Loss};
use crate::show::at::{Now, Posed};
use crate::show::boards::Run;
use crate::show::passes::{self, Axis, JoinError, Joined, Made, Moves, TOLERANCE_DEG};
use crate::show::play::Stage;

inventory::submit! {
    crate::show::family::ShowFamily {
        family: crate::project::Family::Servo,
        connect,
        first_stored: |project| project.servo.macros.iter().map(|m| m.id).min().map(Start::Macro),
        takes: |start| matches!(start, Start::Macro(_)),
        new_cue: None,
        holds: |project, start| matches!(*start, Start::Macro(id) if project.servo.macro_by_id(id).is_some()),
        runs: Some(crate::show::family::Runs {
            find: macro_named,
            listed: |project| {
                let macros = project.servo.macros.iter().map(|m| serde_json::json!({ "id": m.id, "caption": m.caption }));
                vec![("macros", macros.collect())]
            },
        }),
        poses: Some(crate::show::family::Poses {
            axes: |project| project.servo.servos.iter().map(|servo| (servo.id.to_string(), Axis::Servo(servo.id))).collect(),
            alias: |project, name| project.servo.servos.iter().find(|servo| servo.caption == name).map(|s| Axis::Servo(s.id)),
        }),
        drives: false,
        cues: &[],
    }
}

/// Every pass of a servo board joined into one macro of actions, each
/// servo on its own interval, fitted within the tolerance; from home, where
/// the servos are when its cue starts it (a board's start of a show).
fn join(
    project: &mut Project,
    axes: &passes::Latest<'_>,
    span: (u64, u64),
    _device: &str,
) -> Result<Joined, JoinError> {
    let ids: Vec<u8> =
        axes.keys().filter_map(|axis| if let Axis::Servo(id) = axis { Some(*id) } else { None }).collect();
    let rows = passes::rows(axes, span, SERVO_UPDATE_MS, 1.0);
    let rest = rows.get(1..).filter(|rest| !rest.is_empty()).ok_or(JoinError::TooShort)?;
    let project = &mut project.servo;
    let home = |id: &u8| project.servos.iter().find(|s| s.id == *id).map_or(0, |s| i32::from(s.home_deg));
    let start: Vec<i32> = ids.iter().map(home).collect();
    let fitted = fit::fit(&FitServo, &start, rest, TOLERANCE_DEG);
    let macro_id = next_free_id(project.macros.iter().map(|m| m.id));
    let mut actions = fitted::servo_actions(&fitted, &ids, 0, "pass");
    for action in &mut actions {
        action.id = next_free_id(project.actions.iter().map(|known| known.id));
        project.actions.push(action.clone());
    }
    project.macros.push(fitted::macro_running(macro_id, "Recorded passes", &actions));
    let parts = actions.iter().map(|a| a.id).collect();
    let made = Made { start: Start::Macro(macro_id), parts, moves_are: Moves::Steps };
    Ok(Joined { made, moves: actions.len(), max_error_deg: fitted.max_error, tolerance_deg: TOLERANCE_DEG })
}

/// What a servo board's passes made, taken out: their actions and macro.
fn forget(project: &mut Project, made: &Made) {
    project.servo.actions.retain(|action| !made.parts.contains(&action.id));
    if let Start::Macro(macro_id) = made.start {
        project.servo.macros.retain(|m| m.id != macro_id);
    }
}

/// A servo board's servos, captioned by id and caption, each within its limits.
fn recorded_axes(project: &Project) -> Vec<passes::Recordable> {
    let servos = project.servo.servos.iter();
    servos
        .map(|s| (Axis::Servo(s.id), format!("{} {}", s.id, s.caption), f64::from(s.min_deg)..=f64::from(s.max_deg)))
        .collect()
}

inventory::submit! {
    passes::FamilyPasses { family: crate::project::Family::Servo, axes: recorded_axes, join, forget }
}

/// The macro `what` names (its id or its caption).
fn macro_named(project: &Project, what: &str) -> Result<crate::show::family::Named, String> {
    let number: Option<i64> = what.trim().parse().ok();
    let found = project.servo.macros.iter().find(|m| number == Some(i64::from(m.id)) || m.caption == what);
    found
        .map(|m| (Run::Start(Start::Macro(m.id)), format!("macro {} {}", m.id, m.caption)))
        .ok_or_else(|| format!("no macro {what:?}"))
}

/// Connects the servo board on `port` (at the protocol's line rate), its link measured on memory-size questions.
fn connect(port: &PortName, _line: &LineSettings, device: &Device) -> anyhow::Result<Linked> {
    let board = ServoBoard::connect(port, DEFAULT_BAUD, SessionConfig::default(), no_waker())?;
    let requester = board.requester();
    let link = LinkDelay::measured(|| {
        requester.request(Message::QueryMemorySizeRequest).map(|_| ()).map_err(|error| error.to_string())
    })?;
    let servos = device.project.servo.servos.clone();
    let alive = Alive::new(Instant::now());
    let stage = ServoStage {
        requester,
        link,
        board,
        lost: None,
        alive,
        servos,
        sent: BTreeMap::new(),
        live: LivePose::default(),
        battery: (None, None),
    };
    let start_delay = stage.start_delay(&Start::Macro(0));
    Ok(Linked { stage: Box::new(stage), start_delay, link })
}

impl ServoStage {
    /// Asks for the battery twice a second, taking the answer in when it
    /// came: an answer is a sign of life; none for long, the board is lost.
    fn ask_alive(&mut self, now: Instant) {
        let (asking, permil) = &mut self.battery;
        if let Some(answer) = asking {
            match answer.try_recv() {
                Ok(Ok(answered)) => {
                    self.alive.heard(now);
                    if let Message::QueryRemainPowerResponse { permil: read } = answered {
                        *permil = Some(read);
                    }
                    *asking = None;
                }
                Ok(Err(RequestError::Stopped { .. })) => {
                    self.alive.withdrawn();
                    *asking = None;
                }
                Ok(Err(_)) | Err(crossbeam_channel::TryRecvError::Disconnected) => *asking = None,
                Err(crossbeam_channel::TryRecvError::Empty) => {}
            }
        }
        if asking.is_none() && self.alive.ask(now) {
            *asking = self.requester.request_async(Message::QueryRemainPowerRequest).ok();
        }
        if let Some(quiet) = self.alive.silent(now) {
            self.lost.get_or_insert_with(|| Loss::silence(quiet));
        }
    }
}

/// A question's answer on its way.
type Answer = Receiver<Result<Message, RequestError>>;

/// How long a servo not yet told where to be takes to get there while following, 10 ms units.
const EASE_IN_10MS: i16 = 100;

/// Whole 10 ms from `when` to `at` (at least one, at most the protocol's field).
fn ten_ms_since(when: Instant, at: Instant) -> i16 {
    let tens = at.saturating_duration_since(when).as_millis() / 10;
    i16::try_from(tens.clamp(1, 1000)).unwrap_or(1000)
}

struct ServoStage {
    board: ServoBoard,
    requester: Requester,
    link: LinkDelay,
    lost: Option<Loss>,
    /// Its signs of life: asked for its battery twice a second.
    alive: Alive,
    /// The servos, with their limits.
    servos: Vec<Servo>,
    /// What each servo was last told while following, and when.
    sent: BTreeMap<u8, (i16, Instant)>,
    /// The live-pose rule a remote pose follows, as the editor's sliders do.
    live: LivePose,
    /// The battery question out, and the last answer (‰).
    battery: (Option<Answer>, Option<i16>),
}

impl Stage for ServoStage {
    fn start_delay(&self, start: &Start) -> Duration {
        let Start::Macro(macro_id) = *start else { return Duration::ZERO };
        let bytes = Message::ExecuteMacroRequest { macro_id }.encode().map_or(16, |bytes| bytes.len());
        link_delay(bytes, DEFAULT_BAUD, self.link.one_way)
    }

    fn start_uncertainty(&self, _start: &Start) -> Duration {
        self.link.spread
    }

    fn start(&mut self, start: &Start) -> Result<(), String> {
        let Start::Macro(macro_id) = *start else { return Err(format!("a servo board cannot start {start}")) };
        self.requester.send(Message::ExecuteMacroRequest { macro_id }).map_err(|error| error.to_string())
    }

    fn stop(&mut self) {
        let all = ServoSwitches { servo_id: ALL_SERVOS, is_start: false, is_hold: true };
        let _ = self.requester.stop(Message::SetServoParameterRequest(all));
        // Where they stopped is not known: the next follow eases them in again,
        // the next pose is timed from the far end of the limits.
        self.sent.clear();
        self.live.board_moved_them(self.servos.iter().map(|servo| servo.id), Instant::now());
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
            let from = self.live.at(servo.id, at).unwrap_or_else(|| servo.farther_limit(f64::from(degree)));
            self.live.moved(servo.id, (from, degree), at, interval_10ms);
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
                self.lost = Some(Loss::Link(reason.clone()));
            }
        }
        self.ask_alive(now);
    }

    fn pose(&mut self, axis: Axis, value_deg: f64, speed: LiveSpeed) -> Result<f64, String> {
        let Axis::Servo(id) = axis else { return Err("a servo board's axes are servos".into()) };
        let servo = self.servos.iter().find(|servo| servo.id == id).ok_or(format!("it has no servo {id}"))?;
        // The live-pose rule the editor's sliders share: nothing but its own moves tells
        // where a servo is here, so one not moved since the board was connected or
        // stopped is timed from the far end of its limits.
        let now = Instant::now();
        let moved = self.live.limited_move((servo, value_deg), Known::default(), (speed, 2), now);
        self.sent.insert(id, (moved.degree, now));
        self.requester.live_move(vec![moved]).map_err(|error| error.to_string())?;
        Ok(f64::from(moved.degree))
    }

    fn battery(&self) -> Option<String> {
        self.battery.1.map(device::servo::battery_text)
    }

    fn lost(&self) -> Option<Loss> {
        self.lost.clone()
    }
}
