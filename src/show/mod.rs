//! A show: several devices — servo boards, PLEN2s, rFLEX bases in any mix,
//! each a name, a port, a place on the floor and its own project — on one
//! timeline with one sound, and cues saying what each device starts when.
//! Saved as project format version 3 (`docs/show.md`); a version 1 or 2
//! project file opens as a show of one device whose project is that file,
//! byte for byte ([`Show::open`]).

pub mod alive;
pub mod at;
pub mod boards;
pub mod family;
pub mod passes;
pub mod play;
pub mod stages;
pub mod timeline;

use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::project::{self, Family, Project, SoundTrack};

/// The `format` tag a show file carries.
pub const FORMAT_TAG: &str = "servo-studio-show";
/// The version a show file is (a project file is 1 or 2).
pub const VERSION: u32 = 3;

/// Several devices on one timeline with one sound.
#[derive(Clone, Debug, PartialEq)]
pub struct Show {
    /// The devices, in the order they are connected and listed.
    pub devices: Vec<Device>,
    /// The sound the show is timed to.
    pub sound: Option<SoundTrack>,
    /// What each device starts when.
    pub cues: Vec<Cue>,
}

/// One device of a show.
#[derive(Clone, Debug, PartialEq)]
pub struct Device {
    /// Its name, unique in the show ("skull", "arms", "plen").
    pub name: String,
    /// Where it is connected (`/dev/ttyUSB0`, `tcp://…`); `None`: given when played (`--device NAME=PORT`).
    pub port: Option<String>,
    /// Where it stands on the floor: x and y in metres, heading in degrees.
    pub place: Place,
    /// Its family and what it holds (motions, macros, settings).
    pub project: Project,
    /// When its link is lost mid-show, the others play on without it (else every device stops).
    pub play_on_without: bool,
}

impl Device {
    /// The first thing it stores to start, as its family says (a servo
    /// board's lowest macro, a PLEN2's lowest motion slot); none for a family
    /// that stores nothing to start or plays in no show.
    pub fn first_stored(&self) -> Option<Start> {
        family::of(self.project.family).ok().and_then(|entry| (entry.first_stored)(&self.project))
    }
}

/// Where a device stands on the floor.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Place {
    /// Metres along the floor's x.
    #[serde(default)]
    pub x_m: f64,
    /// Metres along the floor's y.
    #[serde(default)]
    pub y_m: f64,
    /// Heading, degrees from +x.
    #[serde(default)]
    pub heading_deg: f64,
}

/// What a device starts, and when.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Cue {
    /// The device, by name.
    pub device: String,
    /// When, ms from the show's start (the sound's start plus its offset).
    pub at_ms: u64,
    /// What it starts.
    #[serde(flatten)]
    pub start: Start,
}

/// What a cue starts on its device. In a show file a cue holds one key
/// naming its kind: `"macro": 3`, `"slot": 2`, `"drive": {…}`, or a kind a
/// family added since registered (`show::family::ShowFamily::cues`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", try_from = "StartFile", into = "StartFile")]
pub enum Start {
    /// A servo board's macro, by id.
    Macro(i32),
    /// A PLEN2's motion, by slot.
    Slot(u8),
    /// An rFLEX base drives straight at `speed_m_s` turning `turn_deg_s`, for `for_ms`, then stops.
    Drive {
        /// Forward speed, m/s (negative: backwards).
        speed_m_s: f64,
        /// Turn rate, degrees a second (positive: left).
        turn_deg_s: f64,
        /// How long, ms.
        for_ms: u64,
    },
    /// A kind of cue of a family added since the first three, as it registered it.
    Family(family::FamilyCue),
}

/// As a log or a message says it: "macro 3", "slot 2", "drive 0.2 m/s
/// turning 0°/s for 1000 ms", "move 30" (a family's kind, then its number).
impl std::fmt::Display for Start {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Macro(id) => write!(f, "macro {id}"),
            Self::Slot(slot) => write!(f, "slot {slot}"),
            Self::Drive { speed_m_s, turn_deg_s, for_ms } => {
                write!(f, "drive {speed_m_s} m/s turning {turn_deg_s}°/s for {for_ms} ms")
            }
            Self::Family(cue) => write!(f, "{} {}", cue.kind, cue.value),
        }
    }
}

impl Start {
    /// Feeds what it starts to `hasher` (a fingerprint of a show's cues).
    pub fn fingerprint<H: std::hash::Hasher>(&self, hasher: &mut H) {
        use std::hash::Hash;
        match *self {
            Self::Macro(id) => (0u8, i64::from(id)).hash(hasher),
            Self::Slot(slot) => (1u8, i64::from(slot)).hash(hasher),
            Self::Drive { speed_m_s, turn_deg_s, for_ms } => {
                (2u8, speed_m_s.to_bits(), turn_deg_s.to_bits(), for_ms).hash(hasher);
            }
            Self::Family(cue) => (3u8, cue.kind, cue.value.to_bits()).hash(hasher),
        }
    }
}

/// The keys of the kinds of cue show files have always had (`StartFile`'s
/// named variants); a family added since registers its own.
const FILE_KINDS: [&str; 3] = ["macro", "slot", "drive"];

/// A cue's start as a show file holds it: the first three kinds by name, any
/// other under its kind's key, with the number it takes.
#[derive(Clone, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
enum StartFile {
    Macro(i32),
    Slot(u8),
    Drive {
        speed_m_s: f64,
        turn_deg_s: f64,
        for_ms: u64,
    },
    #[serde(untagged)]
    Family(std::collections::BTreeMap<String, f64>),
}

impl TryFrom<StartFile> for Start {
    type Error = String;

    fn try_from(file: StartFile) -> Result<Self, String> {
        Ok(match file {
            StartFile::Macro(id) => Self::Macro(id),
            StartFile::Slot(slot) => Self::Slot(slot),
            StartFile::Drive { speed_m_s, turn_deg_s, for_ms } => Self::Drive { speed_m_s, turn_deg_s, for_ms },
            StartFile::Family(keys) => {
                let mut keys = keys.into_iter();
                let (Some((kind, value)), None) = (keys.next(), keys.next()) else {
                    return Err("a cue starts one thing: a macro, a slot, a drive or a family's kind of cue".into());
                };
                Self::Family(family::FamilyCue::named(&kind, value)?)
            }
        })
    }
}

impl From<Start> for StartFile {
    fn from(start: Start) -> Self {
        match start {
            Start::Macro(id) => Self::Macro(id),
            Start::Slot(slot) => Self::Slot(slot),
            Start::Drive { speed_m_s, turn_deg_s, for_ms } => Self::Drive { speed_m_s, turn_deg_s, for_ms },
            Start::Family(cue) => Self::Family(std::iter::once((cue.kind.to_string(), cue.value)).collect()),
        }
    }
}

/// What a remote runs on a device: a cue's start, or a play list its device keeps (a PLEN2's).
#[derive(Clone, Debug, PartialEq)]
pub enum Run {
    /// What a cue starts: a macro, a motion, a timed drive…
    Start(Start),
    /// A play list: each start played so many times (0: forever), in order.
    List(Vec<(Start, u8)>),
}

/// A show file that cannot be read, or a show that cannot be played.
#[derive(Debug, thiserror::Error)]
pub enum ShowError {
    /// Not readable, or not a show or a project.
    #[error(transparent)]
    Load(#[from] project::LoadError),
    /// JSON that is not a show.
    #[error("not a show: {0}")]
    Json(String),
    /// A show file newer than this Servo Studio.
    #[error(
        "show file version {found} is newer than this Servo Studio understands (up to {VERSION}); update Servo Studio to open it"
    )]
    NewerVersion {
        /// The file's version.
        found: u32,
    },
    /// A device's project does not read.
    #[error("device {name:?}: {error}")]
    DeviceProject {
        /// The device.
        name: String,
        /// Why its project does not read.
        error: project::LoadError,
    },
    /// A device without a name (numbered from 1).
    #[error("device {0} has no name")]
    NoName(usize),
    /// Two devices of one name.
    #[error("two devices are called {0:?}: names must differ")]
    SameName(String),
    /// A cue names no device of the show.
    #[error("a cue at {at_ms} ms starts {device:?}, which is not a device of the show")]
    NoDevice {
        /// When the cue starts, ms.
        at_ms: u64,
        /// The name it gives.
        device: String,
    },
    /// A device of a family that plays in no show (it has no show stage).
    #[error("device {device:?}: {lacks}; remove it from the show")]
    PlaysInNoShow {
        /// The device.
        device: String,
        /// Its family, refused by name.
        lacks: family::Lacks,
    },
    /// A cue starts what its device does not hold.
    #[error("the cue at {at_ms} ms asks {device:?} ({}) to start {start}, which it does not hold", .family.name())]
    NotHeld {
        /// When the cue starts, ms.
        at_ms: u64,
        /// The device.
        device: String,
        /// Its family.
        family: Family,
        /// What the cue starts.
        start: Start,
    },
}

/// A device as the file holds it: its project as a whole project file's JSON.
#[derive(Serialize, Deserialize)]
struct DeviceFile {
    name: String,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    port: Option<String>,
    #[serde(default)]
    place: Place,
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    play_on_without: bool,
    project: serde_json::Value,
}

#[derive(Serialize, Deserialize)]
struct ShowFile {
    format: String,
    version: u32,
    devices: Vec<DeviceFile>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    sound: Option<SoundTrack>,
    #[serde(default)]
    cues: Vec<Cue>,
}

impl Show {
    /// A show of one device, `name`, holding `project` (its sound becomes the show's).
    pub fn of_one(name: &str, mut project: Project) -> Self {
        let sound = project.sound.take();
        let device =
            Device { name: name.to_string(), port: None, place: Place::default(), project, play_on_without: false };
        Self { devices: vec![device], sound, cues: Vec::new() }
    }

    /// Whether `path` is a show file (its `format` says so): what a double-click hands the editor may be either.
    pub fn is_show_file(path: &Path) -> bool {
        #[derive(serde::Deserialize)]
        struct Format {
            format: Option<String>,
        }
        project::input::read_text(path, project::input::MAX_PROJECT_BYTES)
            .ok()
            .and_then(|text| serde_json::from_str::<Format>(&text).ok())
            .is_some_and(|file| file.format.as_deref() == Some(FORMAT_TAG))
    }

    /// A show file (version 3), or a project file (version 1 or 2) as a show of one device named after the file.
    pub fn open(path: &Path) -> Result<Self, ShowError> {
        let text = project::input::read_text(path, project::input::MAX_PROJECT_BYTES)
            .map_err(|error| ShowError::Load(error.into()))?;
        let name = path.file_stem().map_or_else(|| "board".to_string(), |stem| stem.to_string_lossy().into_owned());
        Self::from_text(&text, &name)
    }

    /// `text` as a show, or as a project of one device named `name`.
    pub fn from_text(text: &str, name: &str) -> Result<Self, ShowError> {
        let value: serde_json::Value =
            serde_json::from_str(text).map_err(|error| ShowError::Json(format!("line {}: {error}", error.line())))?;
        if value.get("format").and_then(serde_json::Value::as_str) != Some(FORMAT_TAG) {
            return Ok(Self::of_one(name, project::from_json(text)?));
        }
        let file: ShowFile = serde_json::from_value(value).map_err(|error| ShowError::Json(error.to_string()))?;
        if file.version > VERSION {
            return Err(ShowError::NewerVersion { found: file.version });
        }
        let mut devices = Vec::new();
        for device in file.devices {
            let project = project::from_json(&device.project.to_string())
                .map_err(|error| ShowError::DeviceProject { name: device.name.clone(), error })?;
            devices.push(Device {
                name: device.name,
                port: device.port,
                place: device.place,
                project,
                play_on_without: device.play_on_without,
            });
        }
        let show = Self { devices, sound: file.sound, cues: file.cues };
        show.check()?;
        Ok(show)
    }

    /// The show as a version 3 file.
    pub fn to_json(&self) -> String {
        let devices = self
            .devices
            .iter()
            .map(|device| DeviceFile {
                name: device.name.clone(),
                port: device.port.clone(),
                place: device.place,
                play_on_without: device.play_on_without,
                project: serde_json::from_str(&project::to_json(&device.project)).unwrap_or_default(),
            })
            .collect();
        let file = ShowFile {
            format: FORMAT_TAG.into(),
            version: VERSION,
            devices,
            sound: self.sound.clone(),
            cues: self.cues.clone(),
        };
        serde_json::to_string_pretty(&file).unwrap_or_default()
    }

    /// Adds a device holding `project`, named `name` or, when a device has
    /// that name, `name 2`, `name 3`…; the project's sound becomes the show's
    /// when the show has none. Returns the name given.
    pub fn add_device(&mut self, name: &str, mut project: Project) -> String {
        let name = if name.trim().is_empty() { "device" } else { name.trim() };
        let unique = std::iter::once(name.to_string())
            .chain((2..).map(|n| format!("{name} {n}")))
            .find(|candidate| self.device(candidate).is_none())
            .unwrap_or_default();
        let sound = project.sound.take();
        if self.sound.is_none() {
            self.sound = sound;
        }
        self.devices.push(Device {
            name: unique.clone(),
            port: None,
            place: Place { x_m: 0.6 * f64::from(u32::try_from(self.devices.len()).unwrap_or(0)), ..Place::default() },
            project,
            play_on_without: false,
        });
        unique
    }

    /// Removes the device at `index` and every cue of it; how many cues went with it.
    pub fn remove_device(&mut self, index: usize) -> usize {
        if index >= self.devices.len() {
            return 0;
        }
        let device = self.devices.remove(index);
        let before = self.cues.len();
        self.cues.retain(|cue| cue.device != device.name);
        before - self.cues.len()
    }

    /// The device called `name`.
    pub fn device(&self, name: &str) -> Option<&Device> {
        self.devices.iter().find(|device| device.name == name)
    }

    /// Whether names are unique, every cue names a device and starts what it holds.
    pub fn check(&self) -> Result<(), ShowError> {
        match self.problems().into_iter().next() {
            Some(problem) => Err(problem),
            None => Ok(()),
        }
    }

    /// Every problem of the show itself, in order: a device of a family that
    /// plays in no show, without a name or with another's, a cue that names no device or starts what its device
    /// does not hold.
    pub fn problems(&self) -> Vec<ShowError> {
        let mut problems = Vec::new();
        for (index, device) in self.devices.iter().enumerate() {
            if let Err(lacks) = family::of(device.project.family) {
                problems.push(ShowError::PlaysInNoShow { device: device.name.clone(), lacks });
            }
            if device.name.trim().is_empty() {
                problems.push(ShowError::NoName(index + 1));
            } else if self.devices[..index].iter().any(|other| other.name == device.name) {
                problems.push(ShowError::SameName(device.name.clone()));
            }
        }
        for cue in &self.cues {
            let Some(device) = self.device(&cue.device) else {
                problems.push(ShowError::NoDevice { at_ms: cue.at_ms, device: cue.device.clone() });
                continue;
            };
            let family = device.project.family;
            let holds = family::of(family).is_ok_and(|entry| (entry.holds)(&device.project, &cue.start));
            if !holds {
                problems.push(ShowError::NotHeld {
                    at_ms: cue.at_ms,
                    device: cue.device.clone(),
                    family,
                    start: cue.start,
                });
            }
        }
        problems
    }
}

/// A show file read for `check`: each device's project as its loader read it
/// (with the keys it did not know), the keys of the show itself it did not
/// know, and every problem of the show (as [`Show::problems`] finds them, a
/// device whose project does not read left out of the cues' checks).
#[derive(Debug)]
pub struct Checked {
    /// Each device's name and its project, read, or why not.
    pub devices: Vec<(String, Result<project::Loaded, project::LoadError>)>,
    /// Keys of the show file (outside the devices' projects) it does not know.
    pub unknown_keys: Vec<String>,
    /// The show's own problems.
    pub problems: Vec<ShowError>,
}

/// `text` read as a show file for `check` (the whole file is read: every
/// problem found, not only the first); an error when it is not a show at all.
pub fn checked(text: &str) -> Result<Checked, ShowError> {
    let mut unknown_keys = Vec::new();
    let file: ShowFile = serde_ignored::deserialize(&mut serde_json::Deserializer::from_str(text), |path| {
        unknown_keys.push(path.to_string());
    })
    .map_err(|error| ShowError::Json(format!("line {}: {error}", error.line())))?;
    if file.format != FORMAT_TAG {
        return Err(ShowError::Json(format!("its \"format\" is {:?}, not {FORMAT_TAG:?}", file.format)));
    }
    if file.version > VERSION {
        return Err(ShowError::NewerVersion { found: file.version });
    }
    let mut devices = Vec::new();
    let mut read = Vec::new();
    for device in file.devices {
        let loaded = project::parse(&device.project.to_string());
        if let Ok(loaded) = &loaded {
            read.push(Device {
                name: device.name.clone(),
                port: device.port,
                place: device.place,
                project: loaded.project.clone(),
                play_on_without: device.play_on_without,
            });
        }
        devices.push((device.name, loaded));
    }
    let show = Show { devices: read, sound: file.sound, cues: file.cues };
    let unread: Vec<&str> =
        devices.iter().filter(|(_, loaded)| loaded.is_err()).map(|(name, _)| name.as_str()).collect();
    // A cue of a device whose project does not read is not said twice.
    let problems = show
        .problems()
        .into_iter()
        .filter(|problem| !matches!(problem, ShowError::NoDevice { device, .. } if unread.contains(&device.as_str())))
        .collect();
    Ok(Checked { devices, unknown_keys, problems })
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    /// A start is said in words in logs, errors and a remote's `GET /show`, never as a Rust value.
    #[test]
    fn a_start_is_said_in_words() {
        let said: Vec<String> = [
            Start::Macro(3),
            Start::Slot(2),
            Start::Drive { speed_m_s: 0.2, turn_deg_s: -15.0, for_ms: 1000 },
            Start::Family(family::FamilyCue { kind: "move", value: 30.0 }),
        ]
        .iter()
        .map(ToString::to_string)
        .collect();
        assert_eq!(said, ["macro 3", "slot 2", "drive 0.2 m/s turning -15°/s for 1000 ms", "move 30"]);
    }

    #[test]
    fn a_project_is_a_show_of_one_device_and_a_show_reads_back_as_written() {
        let project = Project::servo(project::ServoProject::default());
        let text = project::to_json(&project);
        let show = Show::from_text(&text, "skull").unwrap();
        assert_eq!(show.devices.len(), 1);
        assert_eq!((show.devices[0].name.as_str(), &show.devices[0].project), ("skull", &project));
        let again = Show::from_text(&show.to_json(), "other").unwrap();
        assert_eq!(again, show);
    }

    #[test]
    fn devices_are_added_under_names_of_their_own_and_removed_with_their_cues() {
        let mut show = Show::of_one("arms", Project::servo(project::ServoProject::default()));
        let mut plen = Project::empty(Family::Plen2);
        plen.sound = Some(SoundTrack {
            path: "song.wav".into(),
            duration_ms: 1000,
            sha256: String::new(),
            offset_ms: 0,
            sensitivity_percent: 50,
        });
        assert_eq!(show.add_device("arms", plen), "arms 2");
        assert_eq!(
            show.sound.as_ref().map(|s| s.path.as_str()),
            Some("song.wav"),
            "the show had none: it takes the device's"
        );
        assert_eq!(show.add_device(" ", Project::empty(Family::Rflex)), "device");
        assert!(show.devices.iter().all(|d| d.project.sound.is_none()));
        show.cues = vec![
            Cue { device: "arms 2".into(), at_ms: 0, start: Start::Slot(1) },
            Cue {
                device: "device".into(),
                at_ms: 10,
                start: Start::Drive { speed_m_s: 0.1, turn_deg_s: 0.0, for_ms: 100 },
            },
            Cue { device: "arms 2".into(), at_ms: 20, start: Start::Slot(2) },
        ];
        assert_eq!(show.remove_device(1), 2);
        assert_eq!(show.devices.iter().map(|d| d.name.as_str()).collect::<Vec<_>>(), ["arms", "device"]);
        assert_eq!(show.cues.len(), 1);
        assert_eq!(show.remove_device(7), 0, "no such device: nothing removed");
    }

    #[test]
    fn cues_must_name_devices_and_what_they_hold() {
        let mut show = Show::of_one("skull", Project::servo(project::ServoProject::default()));
        show.cues.push(Cue { device: "arms".into(), at_ms: 0, start: Start::Macro(1) });
        assert!(show.check().unwrap_err().to_string().contains("\"arms\", which is not a device"));
        show.cues[0].device = "skull".into();
        assert!(show.check().unwrap_err().to_string().contains("which it does not hold"));
        show.devices.push(show.devices[0].clone());
        show.cues.clear();
        assert!(show.check().unwrap_err().to_string().contains("two devices are called \"skull\""));
    }
}
