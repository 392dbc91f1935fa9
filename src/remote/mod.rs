//! Remote control: other programs — cue software (QLab, TouchDesigner),
//! control surfaces (Bitfocus Companion, a Stream Deck), Home Assistant —
//! play and stop a show's devices, pose them and drive them, over HTTP + JSON
//! (`http`, documented in `docs/remote-openapi.yaml`) or OSC over UDP
//! (`osc`). Both speak the same [`Verb`]s to one [`Remote`], which carries
//! them out on the show's held boards (`show::boards`): a pose paced and
//! limited as a slider, a base driven only while heartbeats arrive.
//! Who may get in, how much, and from where is `guard`'s.

pub mod guard;
pub mod http;
pub mod osc;
mod running;
mod verbs;

use std::net::SocketAddr;
use std::sync::{Arc, Weak};

use serde_json::{Value, json};

use crate::project::Project;
use crate::show::boards::{Boards, Refused, Run};
use crate::show::family;
use crate::show::passes::Axis;
use crate::show::{Device, Show};
pub use verbs::{BadRequest, Verb};

/// HTTP, and OSC when asked, serving one [`Remote`] under one [`guard::Guard`]:
/// what `servo-studio serve` and the editor's Settings → Remote control both start.
#[derive(Debug)]
pub struct Servers {
    /// The HTTP server.
    pub http: http::HttpServer,
    /// The OSC listener, when asked for.
    pub osc: Option<osc::OscServer>,
    /// What they serve.
    pub remote: Arc<Remote>,
    /// Whether a token is needed.
    pub needs_token: bool,
}

impl Servers {
    /// HTTP on `listen`, OSC on `osc_port` (on the same address), both serving `remote` under `guard`.
    pub fn start(
        listen: SocketAddr,
        osc_port: Option<u16>,
        guard: &Arc<guard::Guard>,
        remote: Arc<Remote>,
    ) -> Result<Self, guard::ServeError> {
        let http = http::HttpServer::start(listen, &remote, guard)
            .map_err(|error| guard::ServeError::HttpTaken { at: listen, why: error.to_string() })?;
        let osc = match osc_port {
            Some(port) => {
                let at = SocketAddr::new(listen.ip(), port);
                let osc = osc::OscServer::start(at, &remote, guard)
                    .map_err(|error| guard::ServeError::OscTaken { at, why: error.to_string() })?;
                Some(osc)
            }
            None => None,
        };
        Ok(Self { http, osc, remote, needs_token: guard.needs_token() })
    }
}

/// An answer: an HTTP status code (OSC replies with it too) and a JSON body.
#[derive(Clone, Debug, PartialEq)]
pub struct Reply {
    /// 200, 400, 404, 409, …
    pub code: u16,
    /// What it says.
    pub body: Value,
}

impl Reply {
    fn ok(body: Value) -> Self {
        Self { code: 200, body }
    }

    /// An error with its code and what to say.
    pub fn error(code: u16, said: impl Into<String>) -> Self {
        Self { code, body: json!({ "error": said.into() }) }
    }
}

/// The verbs carried out on a show's held boards.
#[derive(Debug, Clone)]
pub struct Remote {
    show: Show,
    boards: Weak<Boards>,
    /// A play on a busy device waits its turn (true) or is refused with 409.
    pub queue: bool,
}

impl Remote {
    /// The verbs on `show`'s devices, held by `boards` (gone: every verb is 503).
    pub fn new(show: Show, boards: Weak<Boards>, queue: bool) -> Self {
        Self { show, boards, queue }
    }

    /// The show served.
    pub fn show(&self) -> &Show {
        &self.show
    }

    /// The boards, while they are held.
    pub fn boards(&self) -> Option<Arc<Boards>> {
        self.boards.upgrade()
    }

    /// Carries out `verb`.
    pub fn act(&self, verb: &Verb) -> Reply {
        let Some(boards) = self.boards.upgrade() else {
            return Reply::error(503, "the show's boards are not connected");
        };
        match self.carried(verb, &boards) {
            Ok(reply) => reply,
            Err(reply) => reply,
        }
    }

    fn carried(&self, verb: &Verb, boards: &Boards) -> Result<Reply, Reply> {
        // While the whole show plays, its worker plays it: a device's own verb waits for no one.
        let own = matches!(verb, Verb::Play { .. } | Verb::Pose { .. } | Verb::Drive { .. } | Verb::Heartbeat(_));
        if own && boards.status().show_playing {
            return Err(Reply::error(409, "busy: the show is playing on the boards (POST /stop ends it)"));
        }
        Ok(match verb {
            Verb::Devices => Reply::ok(json!({ "devices": self.show.devices.iter().map(listed).collect::<Vec<_>>() })),
            Verb::Device(name) => Reply::ok(listed(self.device(name)?.1)),
            Verb::Show => Reply::ok(self.listed_show()),
            Verb::Status => Reply::ok(json!(boards.status())),
            Verb::Stop(None) => {
                boards.stop();
                Reply::ok(json!({ "stopped": "every device" }))
            }
            Verb::Stop(Some(name)) => {
                let (index, device) = self.device(name)?;
                boards.stop_one(index);
                Reply::ok(json!({ "stopped": device.name }))
            }
            Verb::Play { device, what } => {
                let (index, device) = self.device(device)?;
                let (run, caption) = runnable(device, what)?;
                let said = boards.run(index, run, &caption, self.queue).map_err(|why| refused(&why))?;
                Reply::ok(json!({ "device": device.name, "plays": caption, "as": said }))
            }
            Verb::PlayShow => {
                if boards.status().show_playing {
                    return Err(Reply::error(409, "the show is already playing"));
                }
                boards.play(&self.show, None);
                Reply::ok(json!({ "plays": "the show" }))
            }
            Verb::Pose { device, axis, value } => {
                let (index, device) = self.device(device)?;
                let axis_of = axis_of(device, axis)?;
                let took = boards.pose(index, axis_of, *value).map_err(|why| refused(&why))?;
                Reply::ok(json!({ "device": device.name, "axis": axis, "value": took }))
            }
            Verb::Drive { device, speed_m_s, turn_deg_s } => {
                let (index, device) = self.device(device)?;
                family::drives(device.project.family).map_err(|lacks| lacking(device, lacks))?;
                let drove = boards.drive(index, Some((*speed_m_s, *turn_deg_s))).map_err(|why| refused(&why))?;
                let (speed, turn) = drove.taken.unwrap_or_default();
                let mut body = json!({
                    "device": device.name,
                    "drives": [speed, turn],
                    "gap_ms": drove.gap.map(|gap| gap.as_secs_f64() * 1000.0),
                    "most_gap_ms": crate::show::boards::MOST_GAP.as_millis(),
                });
                if let Some(clamped) = clamped(device, (*speed_m_s, *turn_deg_s), (speed, turn)) {
                    body["clamped"] = json!(clamped);
                }
                Reply::ok(body)
            }
            Verb::Heartbeat(device) => {
                let (index, device) = self.device(device)?;
                family::drives(device.project.family).map_err(|lacks| lacking(device, lacks))?;
                let drove = boards.drive(index, None).map_err(|why| refused(&why))?;
                Reply::ok(json!({
                    "device": device.name,
                    "heartbeat": true,
                    "gap_ms": drove.gap.map(|gap| gap.as_secs_f64() * 1000.0),
                    "most_gap_ms": crate::show::boards::MOST_GAP.as_millis(),
                }))
            }
        })
    }

    /// The device called `name` and where it is in the show; or 404.
    fn device(&self, name: &str) -> Result<(usize, &Device), Reply> {
        self.show
            .devices
            .iter()
            .enumerate()
            .find(|(_, device)| device.name == name)
            .ok_or_else(|| Reply::error(404, format!("no device {name:?} in the show")))
    }

    fn listed_show(&self) -> Value {
        let cues: Vec<Value> = self
            .show
            .cues
            .iter()
            .map(|cue| json!({ "device": cue.device, "at_ms": cue.at_ms, "start": cue.start.to_string() }))
            .collect();
        json!({
            "devices": self.show.devices.iter().map(|device| device.name.clone()).collect::<Vec<_>>(),
            "cues": cues,
            "sound": self.show.sound.as_ref().map(|sound| sound.path.clone()),
        })
    }
}

/// What a refused order answers.
fn refused(refused: &Refused) -> Reply {
    let code = match refused {
        Refused::Busy(_) | Refused::NotDriven(crate::show::boards::NotDriven::Stopped(_)) => 409,
        Refused::NotDriven(crate::show::boards::NotDriven::Never) => 422,
        Refused::NotConnected(_) | Refused::Late => 503,
        Refused::Cannot(_) => 422,
    };
    Reply::error(code, refused.to_string())
}

/// What a drive held within the base's limits says: what was asked, the
/// limits, what it drives at; None when it drives as asked.
fn clamped(device: &Device, (speed, turn): (f64, f64), (taken_speed, taken_turn): (f64, f64)) -> Option<String> {
    let near = |a: f64, b: f64| (a - b).abs() <= 1e-9 * a.abs().max(1.0);
    if near(speed, taken_speed) && near(turn, taken_turn) {
        return None;
    }
    let rflex = &device.project.rflex;
    let limits = rflex.limits();
    Some(format!(
        "asked {speed} m/s turning {turn} °/s; {} is driven at most {} m/s and {:.1} °/s (its project's drive limits, never past the {}'s {} m/s and {:.1} °/s): it drives at {taken_speed} m/s turning {taken_turn:.1} °/s",
        device.name,
        limits.max_speed_m_per_s,
        limits.max_turn_rad_per_s.to_degrees(),
        rflex.robot.name(),
        rflex.robot.limits().max_speed_m_per_s,
        rflex.robot.limits().max_turn_rad_per_s.to_degrees(),
    ))
}

/// A device as listed: its family, link-free, and what it holds to play and pose.
fn listed(device: &Device) -> Value {
    let project = &device.project;
    let mut listed = json!({
        "name": device.name,
        "family": project.family.tag(),
        "axes": axes(device).into_iter().map(|(name, _)| name).collect::<Vec<_>>(),
    });
    // Every list any family keeps is in every device's listing (empty when
    // it keeps none such), then the device's own lists.
    let every = family::every().filter_map(|entry| Some((entry.runs.as_ref()?.listed)(&Project::empty(entry.family))));
    let own = family::runs(project.family).map(|runs| (runs.listed)(project)).ok();
    for (key, items) in every.flatten().chain(own.into_iter().flatten()) {
        listed[key] = Value::Array(items);
    }
    listed
}

/// What `what` names on `device`, as its family finds it (a servo board's
/// macro by id or caption, a PLEN2's motion by slot or name or play list by
/// name); 404 when it holds none such, 422 naming the family when it runs nothing.
fn runnable(device: &Device, what: &str) -> Result<(Run, String), Reply> {
    let runs = family::runs(device.project.family).map_err(|lacks| lacking(device, lacks))?;
    (runs.find)(&device.project, what).map_err(|none| Reply::error(404, format!("{} has {none}", device.name)))
}

/// The device's axes a pose may move, named as its family names them (a
/// servo's id, a PLEN2 joint's name); none when it poses nothing.
fn axes(device: &Device) -> Vec<(String, Axis)> {
    family::poses(device.project.family).map(|poses| (poses.axes)(&device.project)).unwrap_or_default()
}

/// The axis `name` names on `device` (by its name, or another it answers
/// to: a servo's caption, a joint's device id); 404 when none, 422 naming
/// the family when it poses nothing.
fn axis_of(device: &Device, name: &str) -> Result<Axis, Reply> {
    let poses = family::poses(device.project.family).map_err(|lacks| lacking(device, lacks))?;
    (poses.axes)(&device.project)
        .into_iter()
        .find(|(axis, _)| axis == name)
        .map(|(_, axis)| axis)
        .or_else(|| (poses.alias)(&device.project, name))
        .ok_or_else(|| Reply::error(404, format!("{} has no servo or joint {name:?}", device.name)))
}

/// `device` refused what its family lacks (422), named, with what it can
/// do instead: "base: an rFLEX base cannot pose a servo or joint; drive it
/// (POST /devices/base/drive)", "plen: a PLEN2 cannot drive; play what it
/// stores (POST /devices/plen/play)". A family that plays in no show gets no hint.
fn lacking(device: &Device, lacks: family::Lacks) -> Reply {
    use family::Capability;
    let (name, family) = (&device.name, lacks.family);
    let can = [
        (Capability::Run, family::runs(family).is_ok(), "play what it stores", "play"),
        (Capability::Pose, family::poses(family).is_ok(), "pose it", "pose"),
        (Capability::Drive, family::drives(family).is_ok(), "drive it", "drive"),
    ];
    let instead = can.into_iter().find(|(capability, able, ..)| *capability != lacks.lacks && *able);
    let hint = instead.map_or_else(String::new, |(_, _, what, verb)| format!("; {what} (POST /devices/{name}/{verb})"));
    Reply::error(422, format!("{name}: {lacks}{hint}"))
}

#[cfg(test)]
mod tests {
    use std::sync::{Arc, Weak};

    use proptest::prelude::*;
    use rosc::{OscMessage, OscPacket, OscType};

    use super::guard::Guard;
    use super::*;

    fn remote() -> Remote {
        let show = Show::of_one("skull", Project::empty(crate::project::Family::Servo));
        Remote::new(show, Weak::new(), false)
    }

    fn guard(token: Option<&str>) -> Guard {
        Guard::new("127.0.0.1:8765".parse().unwrap(), token.map(str::to_string)).unwrap()
    }

    proptest! {
        /// Any datagram is answered (400 when it is not OSC), never a panic.
        #[test]
        fn any_datagram_is_answered_and_never_panics(bytes in proptest::collection::vec(any::<u8>(), 0..600)) {
            for reply in osc::take(&bytes, &remote(), &guard(None)) {
                prop_assert!((200..600).contains(&reply.code));
            }
        }

        /// Any OSC message — any address, any arguments, a token or not — is answered.
        #[test]
        fn any_osc_message_is_answered(
            address in "/[a-z/]{0,30}",
            numbers in proptest::collection::vec(any::<f32>(), 0..4),
            text in ".{0,20}",
            token in proptest::option::of("[a-z]{16,20}"),
        ) {
            let mut args: Vec<OscType> = numbers.into_iter().map(OscType::Float).collect();
            args.push(OscType::String(text));
            let packet = rosc::encoder::encode(&OscPacket::Message(OscMessage { addr: address, args })).unwrap();
            let guard = guard(token.as_deref());
            for reply in osc::take(&packet, &remote(), &guard) {
                prop_assert!((200..600).contains(&reply.code));
                if token.is_some() {
                    prop_assert_eq!(reply.code, 401, "no token given: {}", reply.body);
                }
            }
        }

        /// Any HTTP method, path and body reads as a verb or as a bad request that says why.
        #[test]
        fn any_http_request_is_a_verb_or_says_why_not(
            method in "(GET|POST|PUT|DELETE)",
            path in "/[a-z%0-9/]{0,40}",
            body in proptest::collection::vec(any::<u8>(), 0..300),
        ) {
            match verbs::from_http(&method, &path, &body) {
                Ok(verb) => prop_assert!((200..600).contains(&remote().act(&verb).code)),
                Err(bad) => prop_assert!(matches!(bad.code, 400 | 404 | 405) && !bad.said.is_empty()),
            }
        }

        /// Any JSON-ish body for a pose or a drive never panics, and a number that is not finite is refused.
        #[test]
        fn any_body_of_a_pose_or_a_drive_is_read_or_refused(axis in ".{0,10}", value in any::<f64>(), junk in ".{0,10}") {
            let body = format!(r#"{{"axis": {}, "value": {value}{junk}}}"#, serde_json::json!(axis));
            let _ = verbs::from_http("POST", "/devices/skull/pose", body.as_bytes());
            let drive = format!(r#"{{"speed_m_s": {value}}}"#);
            if let Ok(Verb::Drive { speed_m_s, .. }) = verbs::from_http("POST", "/devices/base/drive", drive.as_bytes()) {
                prop_assert!(speed_m_s.is_finite());
            }
        }
    }

    /// A verb a device's family cannot carry is refused naming the family
    /// (and a base told to drive instead), never carried as another family's:
    /// a family that registered nothing for shows (one made up here), a PLEN2
    /// that does not drive, a base that stores nothing to run and has nothing to pose.
    #[test]
    fn a_verb_the_family_cannot_carry_is_refused_by_name() {
        use crate::project::{Family, Project};
        let bare = Family::named("bare", "Bare board");
        let mut show = Show::of_one("bare", Project::empty(bare));
        show.add_device("plen", Project::empty(Family::Plen2));
        show.add_device("base", Project::empty(Family::Rflex));
        // No device has a port: none is linked, and none is asked anything.
        let boards = Arc::new(Boards::connect(&show, crate::link::no_waker()).unwrap());
        let remote = Remote::new(show, Arc::downgrade(&boards), false);
        let said = |verb: Verb| {
            let reply = remote.act(&verb);
            assert_eq!(reply.code, 422, "{verb:?}: {}", reply.body);
            reply.body["error"].as_str().unwrap().to_string()
        };
        let pose = |device: &str| Verb::Pose { device: device.into(), axis: "0".into(), value: 10.0 };
        assert_eq!(said(pose("bare")), "bare: a Bare board cannot play in a show");
        assert_eq!(
            said(Verb::Play { device: "bare".into(), what: "1".into() }),
            "bare: a Bare board cannot play in a show"
        );
        assert_eq!(
            said(Verb::Drive { device: "plen".into(), speed_m_s: 0.1, turn_deg_s: 0.0 }),
            "plen: a PLEN2 cannot drive; play what it stores (POST /devices/plen/play)"
        );
        assert_eq!(
            said(Verb::Heartbeat("plen".into())),
            "plen: a PLEN2 cannot drive; play what it stores (POST /devices/plen/play)"
        );
        assert_eq!(
            said(pose("base")),
            "base: an rFLEX base cannot pose a servo or joint; drive it (POST /devices/base/drive)"
        );
        assert_eq!(
            said(Verb::Play { device: "base".into(), what: "1".into() }),
            "base: an rFLEX base cannot run a stored macro or motion; drive it (POST /devices/base/drive)"
        );
        assert!(listed(&remote.show().devices[0])["axes"].as_array().unwrap().is_empty(), "a bare board lists no axis");
    }

    /// A device's listing holds every list any family keeps to run, each
    /// under its key: its own filled, the others empty (the documented API).
    #[test]
    fn each_device_lists_what_its_family_keeps_under_every_family_s_keys() {
        use crate::project::plen2::{Motion, PlayEntry, PlayList};
        use crate::project::{Family, Macro};
        let mut servo = Project::empty(Family::Servo);
        servo.servo.macros.push(Macro { id: 3, caption: "wave".into(), commands: Vec::new() });
        let mut plen = Project::empty(Family::Plen2);
        plen.plen2.motions.push(Motion {
            slot: 2,
            name: "bow".into(),
            frames: Vec::new(),
            loop_range: None,
            jump_slot: None,
        });
        let entries = vec![PlayEntry { slot: 2, plays: 3 }];
        plen.plen2.play_lists.push(PlayList { name: "greet".into(), entries });
        let mut show = Show::of_one("skull", servo);
        show.add_device("plen", plen);
        show.add_device("base", Project::empty(Family::Rflex));
        let [skull, plen, base] = [0, 1, 2].map(|index| listed(&show.devices[index]));
        assert_eq!(skull["macros"], json!([{ "id": 3, "caption": "wave" }]));
        assert_eq!((&skull["motions"], &skull["play_lists"]), (&json!([]), &json!([])));
        assert_eq!(plen["motions"], json!([{ "slot": 2, "name": "bow" }]));
        assert_eq!(plen["play_lists"], json!([{ "name": "greet", "entries": 1 }]));
        assert_eq!(plen["macros"], json!([]));
        assert_eq!((&base["macros"], &base["motions"], &base["play_lists"]), (&json!([]), &json!([]), &json!([])));
        assert_eq!((base["family"].as_str(), plen["axes"].as_array().map(Vec::len)), (Some("rflex"), Some(18)));
    }

    #[test]
    fn with_the_boards_let_go_a_verb_is_answered_503() {
        let reply = remote().act(&Verb::Stop(None));
        assert_eq!(reply.code, 503, "{}", reply.body);
    }
}
