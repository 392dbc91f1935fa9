//! Requests read into [`Verb`]s: an HTTP method, path and JSON body, or an
//! OSC address and its arguments. Anything else is a [`BadRequest`] that
//! names where it went wrong.

use serde::Deserialize;

/// What a remote asks.
#[derive(Clone, Debug, PartialEq)]
pub enum Verb {
    /// Every device, with its macros, motions, play lists and axes.
    Devices,
    /// One device.
    Device(String),
    /// The show: its devices, cues and sound.
    Show,
    /// Every device's link, battery and what it plays.
    Status,
    /// Play a macro, motion or play list (by id, slot or name) on a device.
    Play {
        /// The device's name.
        device: String,
        /// What to play.
        what: String,
    },
    /// Play the whole show on its boards.
    PlayShow,
    /// Stop one device, or every device (None).
    Stop(Option<String>),
    /// An axis (a servo by id or caption, a joint by name) to a value in degrees.
    Pose {
        /// The device's name.
        device: String,
        /// The axis.
        axis: String,
        /// Degrees (a joint's from home).
        value: f64,
    },
    /// Drive a base; it stops unless heartbeats (or drives) keep coming.
    Drive {
        /// The device's name.
        device: String,
        /// Metres a second, forward positive.
        speed_m_s: f64,
        /// Degrees a second, left positive.
        turn_deg_s: f64,
    },
    /// Keep a driven base driving.
    Heartbeat(String),
}

impl Verb {
    /// Whether it stops something (served even when requests come too fast).
    pub fn stops(&self) -> bool {
        matches!(self, Self::Stop(_))
    }

    /// Whether it moves or asks something of the boards (everything but the
    /// questions about the show and its status).
    pub fn reaches_the_boards(&self) -> bool {
        !matches!(self, Self::Devices | Self::Device(_) | Self::Show | Self::Status)
    }

    /// Whether carrying it out waits for the boards' worker to answer (up to
    /// its bound); the others — STOP above all — are carried out at once.
    pub fn waits_for_the_boards(&self) -> bool {
        matches!(self, Self::Play { .. } | Self::Pose { .. } | Self::Drive { .. } | Self::Heartbeat(_))
    }
}

/// A request that is not one: its status code (400, 404, 405) and where it went wrong.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{said}")]
pub struct BadRequest {
    /// 400, 404 or 405.
    pub code: u16,
    /// What was wrong, and where.
    pub said: String,
}

fn bad(code: u16, said: impl Into<String>) -> BadRequest {
    BadRequest { code, said: said.into() }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct PlayBody {
    what: String,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct PoseBody {
    axis: String,
    value: f64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct DriveBody {
    speed_m_s: f64,
    #[serde(default)]
    turn_deg_s: f64,
}

/// An HTTP request as a verb: `method`, `path` (percent-encoded, no query), `body` (JSON or empty).
pub fn from_http(method: &str, path: &str, body: &[u8]) -> Result<Verb, BadRequest> {
    let segments: Vec<String> = path
        .trim_matches('/')
        .split('/')
        .map(|part| percent_encoding::percent_decode_str(part).decode_utf8_lossy().into_owned())
        .collect();
    let parts: Vec<&str> = segments.iter().map(String::as_str).collect();
    let verb = match (method, parts.as_slice()) {
        ("GET", ["devices"]) => Verb::Devices,
        ("GET", ["devices", device]) => Verb::Device((*device).to_string()),
        ("GET", ["show"]) => Verb::Show,
        ("GET", ["status"]) => Verb::Status,
        ("POST", ["stop"]) => Verb::Stop(None),
        ("POST", ["show", "play"]) => Verb::PlayShow,
        ("POST", ["devices", device, "stop"]) => Verb::Stop(Some((*device).to_string())),
        ("POST", ["devices", device, "heartbeat"]) => Verb::Heartbeat((*device).to_string()),
        ("POST", ["devices", device, "play"]) => {
            let body: PlayBody = json(body, r#"{"what": "wave"}"#)?;
            Verb::Play { device: (*device).to_string(), what: body.what }
        }
        ("POST", ["devices", device, "pose"]) => {
            let body: PoseBody = json(body, r#"{"axis": "1", "value": 30}"#)?;
            finite(body.value, "value")?;
            Verb::Pose { device: (*device).to_string(), axis: body.axis, value: body.value }
        }
        ("POST", ["devices", device, "drive"]) => {
            let body: DriveBody = json(body, r#"{"speed_m_s": 0.2, "turn_deg_s": 0}"#)?;
            finite(body.speed_m_s, "speed_m_s")?;
            finite(body.turn_deg_s, "turn_deg_s")?;
            Verb::Drive { device: (*device).to_string(), speed_m_s: body.speed_m_s, turn_deg_s: body.turn_deg_s }
        }
        (_, ["devices"] | ["devices", _] | ["show"] | ["status"] | ["stop"] | ["show", "play"])
        | (_, ["devices", _, "stop" | "heartbeat" | "play" | "pose" | "drive"]) => {
            return Err(bad(405, format!("{method} is not how {path} is asked (see docs/remote-openapi.yaml)")));
        }
        _ => return Err(bad(404, format!("no such path: {path} (see docs/remote-openapi.yaml)"))),
    };
    Ok(verb)
}

/// The body read as JSON of type `T`, or 400 saying where it went wrong and what is expected.
fn json<T: for<'de> Deserialize<'de>>(body: &[u8], example: &str) -> Result<T, BadRequest> {
    serde_json::from_slice(body).map_err(|error| {
        let at = if body.is_empty() {
            "the body is empty".to_string()
        } else {
            format!("line {} column {}: {error}", error.line(), error.column())
        };
        bad(400, format!("the JSON body is not one: {at}; expected e.g. {example}"))
    })
}

fn finite(value: f64, name: &str) -> Result<(), BadRequest> {
    if value.is_finite() { Ok(()) } else { Err(bad(400, format!("{name} must be a number"))) }
}

/// An OSC argument, as the verbs read it.
#[derive(Clone, Debug, PartialEq)]
pub enum Arg {
    /// A number (int, float or double).
    Number(f64),
    /// A string.
    Text(String),
}

/// An OSC message as a verb: its address and its arguments (the token already taken off).
pub fn from_osc(address: &str, args: &[Arg]) -> Result<Verb, BadRequest> {
    let parts: Vec<&str> = address.trim_matches('/').split('/').collect();
    let number = |index: usize, name: &str| match args.get(index) {
        Some(Arg::Number(value)) if value.is_finite() => Ok(*value),
        Some(other) => {
            Err(bad(400, format!("{address}: argument {} ({name}) must be a number, not {other:?}", index + 1)))
        }
        None => Err(bad(400, format!("{address}: argument {} ({name}) is missing", index + 1))),
    };
    Ok(match parts.as_slice() {
        ["stop"] => Verb::Stop(None),
        ["stop", device] => Verb::Stop(Some((*device).to_string())),
        ["show", "play"] => Verb::PlayShow,
        ["play", device, what] => Verb::Play { device: (*device).to_string(), what: (*what).to_string() },
        ["pose", device, axis] => {
            Verb::Pose { device: (*device).to_string(), axis: (*axis).to_string(), value: number(0, "degrees")? }
        }
        ["drive", device] => Verb::Drive {
            device: (*device).to_string(),
            speed_m_s: number(0, "speed m/s")?,
            turn_deg_s: if args.len() > 1 { number(1, "turn °/s")? } else { 0.0 },
        },
        ["heartbeat", device] => Verb::Heartbeat((*device).to_string()),
        _ => {
            return Err(bad(
                404,
                format!(
                    "{address}: no such OSC address (/play/DEVICE/WHAT, /stop, /stop/DEVICE, /pose/DEVICE/AXIS f, /drive/DEVICE f f, /heartbeat/DEVICE, /show/play)"
                ),
            ));
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn http_paths_and_bodies_read_as_verbs_and_bad_ones_say_where() {
        let pose = from_http("POST", "/devices/%E9%A0%AD/pose", br#"{"axis": "jaw", "value": 12.5}"#).unwrap();
        assert_eq!(pose, Verb::Pose { device: "頭".into(), axis: "jaw".into(), value: 12.5 });
        assert_eq!(from_http("POST", "/stop", b"").unwrap(), Verb::Stop(None));
        let broken = from_http("POST", "/devices/a/play", b"{\"what\": ").unwrap_err();
        assert_eq!(broken.code, 400);
        assert!(broken.said.contains("line 1 column"), "{}", broken.said);
        assert_eq!(from_http("GET", "/stop", b"").unwrap_err().code, 405);
        assert_eq!(from_http("GET", "/nowhere", b"").unwrap_err().code, 404);
        let unknown = from_http("POST", "/devices/a/pose", br#"{"axis": "1", "value": 1, "x": 2}"#).unwrap_err();
        assert!(unknown.said.contains("unknown field"), "{}", unknown.said);
    }

    #[test]
    fn osc_addresses_read_as_the_same_verbs() {
        let drive = from_osc("/drive/base", &[Arg::Number(0.2), Arg::Number(-15.0)]).unwrap();
        assert_eq!(drive, Verb::Drive { device: "base".into(), speed_m_s: 0.2, turn_deg_s: -15.0 });
        assert_eq!(
            from_osc("/play/skull/wave", &[]).unwrap(),
            Verb::Play { device: "skull".into(), what: "wave".into() }
        );
        let missing = from_osc("/pose/skull/1", &[]).unwrap_err();
        assert!(missing.code == 400 && missing.said.contains("argument 1 (degrees) is missing"), "{}", missing.said);
        assert_eq!(from_osc("/dance", &[]).unwrap_err().code, 404);
    }
}
