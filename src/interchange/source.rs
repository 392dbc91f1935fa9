//! What another tool's file holds, in that tool's own units and timing, before
//! a joint map turns it into a board's degrees.

/// How a tool's raw value becomes degrees by default (a joint map may say otherwise).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Unit {
    /// The raw value at 0°.
    pub zero: f64,
    /// Raw units per degree.
    pub per_degree: f64,
    /// What the raw value is, for the joint map table ("¼ µs", "AX units"…).
    pub label: &'static str,
}

impl Unit {
    /// Degrees already, centred on 0.
    pub const DEGREES: Self = Self { zero: 0.0, per_degree: 1.0, label: "degrees" };
}

/// One channel of the source: a Maestro channel, a Dynamixel id, a Blender bone.
#[derive(Clone, Debug, PartialEq)]
pub struct Channel {
    /// How the file names it, unique in the file ("0", "12", a bone's servo id).
    pub key: String,
    /// Its name, when the file has one.
    pub name: String,
    /// The default conversion to degrees.
    pub unit: Unit,
    /// Lowest and highest raw value the tool allows, when it says.
    pub limits: Option<(f64, f64)>,
    /// Where the tool puts it at power-up, raw.
    pub home: Option<f64>,
    /// Maestro: the speed limit, raw units per 10 ms (0 = as fast as the servo goes).
    pub speed: Option<f64>,
    /// The servo the file says drives it (R+ Motion's skeleton: "AX-12A", "XL-320"), if it says.
    pub motor: Option<String>,
}

impl Channel {
    /// A channel with no name, limits, home or speed.
    pub fn new(key: impl Into<String>, unit: Unit) -> Self {
        Self { key: key.into(), name: String::new(), unit, limits: None, home: None, speed: None, motor: None }
    }
}

/// How a key's time is spent.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Timing {
    /// Moves in `move_ms` (straight, every channel arriving together), then holds `hold_ms`.
    Move {
        /// The move, ms.
        move_ms: f64,
        /// The wait after it, ms.
        hold_ms: f64,
    },
    /// A Maestro frame: every channel heads for its target at its own speed
    /// limit; the next frame starts `duration_ms` later, arrived or not.
    Frame {
        /// Frame length, ms.
        duration_ms: f64,
    },
}

impl Timing {
    /// The same key played at `rate` (2 = twice as fast).
    pub fn at_rate(self, rate: f64) -> Self {
        match self {
            Self::Move { move_ms, hold_ms } => Self::Move { move_ms: move_ms / rate, hold_ms: hold_ms / rate },
            Self::Frame { duration_ms } => Self::Frame { duration_ms: duration_ms / rate },
        }
    }
}

/// One key: where each channel goes (raw; `None`: the channel is not driven) and when.
#[derive(Clone, Debug, PartialEq)]
pub struct Key {
    /// Per channel of the source, in its order.
    pub values: Vec<Option<f64>>,
    /// Its timing.
    pub timing: Timing,
    /// Its name in the file, if any.
    pub name: String,
}

/// A clip's content.
#[derive(Clone, Debug, PartialEq)]
pub enum Body {
    /// Keys played one after another.
    Keys(Vec<Key>),
    /// Positions sampled at a frame rate (raw, `rows[frame][channel]`).
    Samples {
        /// Frames per second.
        fps: f64,
        /// One row per frame, a value per channel.
        rows: Vec<Vec<f64>>,
    },
    /// Other clips played in turn (an R+ Motion flow).
    Chain(Vec<Link>),
}

/// One clip of a chain, played some number of times.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Link {
    /// The clip, by index.
    pub clip: usize,
    /// How many times (0 = until stopped).
    pub plays: u32,
    /// At this rate (1 = as authored).
    pub speed: f64,
}

/// One named motion: a Maestro sequence, a RoboPlus page, a Blender animation.
#[derive(Clone, Debug, PartialEq)]
pub struct Clip {
    /// Its name in the file.
    pub name: String,
    /// RoboPlus: the page number.
    pub number: Option<u32>,
    /// What it plays.
    pub body: Body,
    /// Plays this many times in all (RoboPlus repeat, R+ loop); at least 1.
    pub repeat: u32,
    /// Played at this rate (RoboPlus speed rate, R+ main speed): 1 = as authored.
    pub speed: f64,
    /// The clip played after it (RoboPlus next page), by index.
    pub next: Option<usize>,
    /// The clip played when it is stopped (RoboPlus exit page), by index.
    pub exit: Option<usize>,
}

impl Clip {
    /// A clip played once at its own speed, with nothing after it.
    pub fn new(name: impl Into<String>, body: Body) -> Self {
        Self { name: name.into(), number: None, body, repeat: 1, speed: 1.0, next: None, exit: None }
    }

    /// How long one pass lasts, ms (a Maestro frame counts its whole duration).
    pub fn duration_ms(&self) -> f64 {
        let one = match &self.body {
            Body::Keys(keys) => keys
                .iter()
                .map(|key| match key.timing {
                    Timing::Move { move_ms, hold_ms } => move_ms + hold_ms,
                    Timing::Frame { duration_ms } => duration_ms,
                })
                .sum(),
            // Frame counts far below 2^52.
            #[allow(clippy::cast_precision_loss)]
            Body::Samples { fps, rows } => rows.len().saturating_sub(1) as f64 * 1000.0 / fps,
            Body::Chain(_) => 0.0,
        };
        one / self.speed
    }
}

/// Everything read from one file.
#[derive(Clone, Debug, PartialEq)]
pub struct Source {
    /// The format it was read as.
    pub format: super::format::Format,
    /// Its channels.
    pub channels: Vec<Channel>,
    /// Its motions.
    pub clips: Vec<Clip>,
    /// What the file held that no board plays, said once each (scripts, compliance…).
    pub dropped: Vec<String>,
    /// What reading it took or found that the user should know (a checksum, a robot declared).
    pub notes: Vec<String>,
}

impl Source {
    /// Notes something the file held that is left out, once however often it comes.
    pub fn drop_note(&mut self, note: impl Into<String>) {
        let note = note.into();
        if !self.dropped.contains(&note) {
            self.dropped.push(note);
        }
    }
}
