//! The add-on's JSON read straight into what it says, every count bounded as
//! it is read: positions go into columns of numbers (no tree of values is
//! built first), a file naming more servos than a board has or more
//! positions than any animation is refused where it passes, and every error
//! names the key it was reading ("servos.3.positions[12]") and its line.

use std::cell::RefCell;
use std::fmt;

use serde::Deserializer as _;
use serde::de::{self, DeserializeSeed, IgnoredAny, MapAccess, SeqAccess, Visitor};

use super::super::bounds::{MAX_CHANNELS, MAX_CLIP_MS, MAX_SAMPLED_POSITIONS};
use super::super::format::{CUT_SHORT, ReadError};
use super::super::source::{Channel, Unit};
use super::ADDON_DEFAULT;
use super::loose::{Scalar, ScalarVisitor, UnitHint};

/// A file's servos and, per servo, a position per frame.
pub type Columns = (Vec<Channel>, Vec<Vec<f64>>);

/// What an export's top level says, each key as the add-on means it.
#[derive(Default)]
pub struct Export {
    /// `fps`, when it is a number.
    pub fps: Option<f64>,
    /// `scene`, when it is a string.
    pub scene: Option<String>,
    /// Servo Studio's own key saying the positions' unit.
    pub unit: Option<Unit>,
    /// `servos` (id → name, positions).
    pub servos: Option<Columns>,
    /// `positions` as a list of frames (id → position).
    pub frames: Option<Columns>,
    /// `positions` as bones (bone → positions).
    pub bones: Option<Columns>,
    /// `pulses` as bones (the add-on's 1.0).
    pub pulses: Option<Columns>,
}

/// Where reading is (each key and index on the way), what was wrong there,
/// and how many positions have been read.
#[derive(Default)]
struct Trail {
    path: Vec<String>,
    wrong: Option<(String, String)>,
    positions: f64,
    /// The most frames the file's frame rate allows, and the rate.
    most_frames: Option<(f64, f64)>,
}

impl Trail {
    fn here(&self) -> String {
        let mut joined = String::new();
        for step in &self.path {
            if !step.starts_with('[') && !joined.is_empty() {
                joined.push('.');
            }
            joined.push_str(step);
        }
        joined
    }
}

/// Reads `text` as an export.
pub fn read(text: &str) -> Result<Export, ReadError> {
    let trail = RefCell::new(Trail::default());
    let mut deserializer = serde_json::Deserializer::from_str(text);
    let read = deserializer.deserialize_any(Root(&trail)).and_then(|export| deserializer.end().map(|()| export));
    read.map_err(|error| {
        let trail = trail.into_inner();
        let line = Some(error.line()).filter(|line| *line > 0);
        if let Some((element, message)) = trail.wrong {
            return ReadError { line, element: (!element.is_empty()).then_some(element), message };
        }
        let element = Some(trail.here()).filter(|here| !here.is_empty());
        let message = if error.is_eof() {
            format!("not JSON: {error} — {CUT_SHORT}")
        } else if error.is_data() {
            // Well-formed, but not what the add-on writes there.
            error.to_string()
        } else {
            format!("not JSON: {error}")
        };
        ReadError { line, element, message }
    })
}

/// The error of a key that does not say what the add-on writes there.
fn wrong<E: de::Error>(trail: &RefCell<Trail>, message: impl Into<String>) -> E {
    let mut trail = trail.borrow_mut();
    let message = message.into();
    let here = trail.here();
    trail.wrong = Some((here, message.clone()));
    E::custom(message)
}

/// Reads the value of key or index `step`, the trail saying so meanwhile
/// (and still saying so when reading stopped there).
fn within<T, E>(trail: &RefCell<Trail>, step: String, read: impl FnOnce() -> Result<T, E>) -> Result<T, E> {
    trail.borrow_mut().path.push(step);
    let value = read()?;
    trail.borrow_mut().path.pop();
    Ok(value)
}

/// One more frame after `frames`, refused past an hour at the file's frame
/// rate (when `fps` came first, as the add-on writes it).
fn count_frame<E: de::Error>(trail: &RefCell<Trail>, frames: usize) -> Result<(), E> {
    let most = trail.borrow().most_frames;
    match most {
        // Frame counts far below 2^52.
        #[allow(clippy::cast_precision_loss)]
        Some((most, fps)) if frames as f64 >= most => Err(wrong(
            trail,
            format!("more than {most} frames at {fps} fps: an animation lasts at most an hour (is the file damaged?)"),
        )),
        _ => Ok(()),
    }
}

struct Root<'t>(&'t RefCell<Trail>);

impl<'de> Visitor<'de> for Root<'_> {
    type Value = Export;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("the add-on's JSON object")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Export, A::Error> {
        let trail = self.0;
        let mut export = Export::default();
        while let Some(key) = map.next_key::<String>()? {
            within(trail, key.clone(), || -> Result<(), A::Error> {
                match key.as_str() {
                    "fps" => {
                        export.fps = map.next_value::<Scalar>()?.number;
                        trail.borrow_mut().most_frames = export
                            .fps
                            .filter(|fps| *fps > 0.0 && *fps <= 1000.0)
                            .map(|fps| ((fps * MAX_CLIP_MS / 1000.0).floor() + 1.0, fps));
                    }
                    "scene" => export.scene = map.next_value::<Scalar>()?.text,
                    super::UNIT_KEY => {
                        export.unit = map.next_value::<UnitHint>()?.unit();
                    }
                    "servos" => export.servos = Some(map.next_value_seed(Servos(trail))?),
                    "positions" => match map.next_value_seed(Positions(trail))? {
                        Some(Layout::Frames(columns)) => export.frames = Some(columns),
                        Some(Layout::Bones(columns)) => export.bones = Some(columns),
                        None => {}
                    },
                    "pulses" => {
                        if let Some(Layout::Bones(columns)) = map.next_value_seed(Positions(trail))? {
                            export.pulses = Some(columns);
                        }
                    }
                    _ => {
                        map.next_value::<IgnoredAny>()?;
                    }
                }
                Ok(())
            })?;
        }
        Ok(export)
    }

    fn visit_seq<A: SeqAccess<'de>>(self, _: A) -> Result<Export, A::Error> {
        Err(wrong(self.0, "the file is not a JSON object"))
    }
}

/// One more servo, refused past a board's channels.
fn count_servo<E: de::Error>(trail: &RefCell<Trail>, channels: &[Channel]) -> Result<(), E> {
    if channels.len() >= MAX_CHANNELS {
        return Err(wrong(
            trail,
            format!("more than {MAX_CHANNELS} servos: a board has no more channels (is the file damaged?)"),
        ));
    }
    Ok(())
}

/// A position: a number, or a number written as a string (the add-on's first
/// releases); counted against the most any animation holds.
struct Position<'t>(&'t RefCell<Trail>);

impl<'de> DeserializeSeed<'de> for Position<'_> {
    type Value = f64;

    fn deserialize<D: de::Deserializer<'de>>(self, deserializer: D) -> Result<f64, D::Error> {
        let value = deserializer.deserialize_any(ScalarVisitor)?;
        let number = value.number.or_else(|| value.text.as_deref().and_then(|text| text.trim().parse().ok()));
        let Some(number) = number.filter(|n: &f64| n.is_finite()) else {
            let shown = value.text.map_or_else(|| "it".to_string(), |text| format!("{text:?}"));
            return Err(wrong(self.0, format!("{shown} is not a number")));
        };
        let mut trail = self.0.borrow_mut();
        trail.positions += 1.0;
        if trail.positions > MAX_SAMPLED_POSITIONS {
            drop(trail);
            return Err(wrong(
                self.0,
                format!(
                    "more than {MAX_SAMPLED_POSITIONS} positions: no animation holds as many (is the file damaged?)"
                ),
            ));
        }
        Ok(number)
    }
}

/// `servos`: id → `name`, `positions` (the add-on's 1.x–2.x releases).
struct Servos<'t>(&'t RefCell<Trail>);

impl<'de> DeserializeSeed<'de> for Servos<'_> {
    type Value = Columns;

    fn deserialize<D: de::Deserializer<'de>>(self, deserializer: D) -> Result<Columns, D::Error> {
        deserializer.deserialize_any(self)
    }
}

impl<'de> Visitor<'de> for Servos<'_> {
    type Value = Columns;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("an object of servos by id")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Columns, A::Error> {
        let trail = self.0;
        let (mut channels, mut columns) = (Vec::new(), Vec::new());
        while let Some(id) = map.next_key::<String>()? {
            within(trail, id.clone(), || -> Result<(), A::Error> {
                count_servo(trail, &channels)?;
                let (name, positions) = map.next_value_seed(Servo(trail))?;
                let mut channel = Channel::new(id.clone(), ADDON_DEFAULT);
                channel.name = name;
                channels.push(channel);
                columns.push(positions);
                Ok(())
            })?;
        }
        Ok((channels, columns))
    }

    fn visit_seq<A: SeqAccess<'de>>(self, _: A) -> Result<Columns, A::Error> {
        Err(wrong(self.0, "not an object of servos by id"))
    }
}

/// One servo of `servos`: its bone's name and its positions.
struct Servo<'t>(&'t RefCell<Trail>);

impl<'de> DeserializeSeed<'de> for Servo<'_> {
    type Value = (String, Vec<f64>);

    fn deserialize<D: de::Deserializer<'de>>(self, deserializer: D) -> Result<Self::Value, D::Error> {
        deserializer.deserialize_any(self)
    }
}

impl<'de> Visitor<'de> for Servo<'_> {
    type Value = (String, Vec<f64>);

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a servo: name and positions")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Self::Value, A::Error> {
        let trail = self.0;
        let (mut name, mut positions) = (String::new(), None);
        while let Some(key) = map.next_key::<String>()? {
            within(trail, key.clone(), || -> Result<(), A::Error> {
                match key.as_str() {
                    "name" => name = map.next_value::<Scalar>()?.text.unwrap_or_default(),
                    "positions" => positions = Some(map.next_value_seed(List(trail))?),
                    _ => {
                        map.next_value::<IgnoredAny>()?;
                    }
                }
                Ok(())
            })?;
        }
        positions.map(|positions| (name, positions)).ok_or_else(|| wrong(trail, "no positions"))
    }
}

/// A list of positions, one per frame.
struct List<'t>(&'t RefCell<Trail>);

impl<'de> DeserializeSeed<'de> for List<'_> {
    type Value = Vec<f64>;

    fn deserialize<D: de::Deserializer<'de>>(self, deserializer: D) -> Result<Vec<f64>, D::Error> {
        deserializer.deserialize_any(self)
    }
}

impl<'de> Visitor<'de> for List<'_> {
    type Value = Vec<f64>;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a list of positions")
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Vec<f64>, A::Error> {
        let trail = self.0;
        let mut list = Vec::new();
        loop {
            let next = within(trail, format!("[{}]", list.len()), || {
                count_frame(trail, list.len())?;
                seq.next_element_seed(Position(trail))
            })?;
            let Some(position) = next else { break };
            list.push(position);
        }
        Ok(list)
    }

    fn visit_map<A: MapAccess<'de>>(self, _: A) -> Result<Vec<f64>, A::Error> {
        Err(wrong(self.0, "not a list of positions"))
    }

    fn visit_str<E: de::Error>(self, _: &str) -> Result<Vec<f64>, E> {
        Err(wrong(self.0, "not a list of positions"))
    }

    fn visit_f64<E: de::Error>(self, _: f64) -> Result<Vec<f64>, E> {
        Err(wrong(self.0, "not a list of positions"))
    }
}

/// What `positions` (or `pulses`) holds.
enum Layout {
    /// One object per frame, id → position (since 2024).
    Frames(Columns),
    /// Bone → positions (the first releases).
    Bones(Columns),
}

/// `positions` or `pulses`: either layout, or (None) something else.
struct Positions<'t>(&'t RefCell<Trail>);

impl<'de> DeserializeSeed<'de> for Positions<'_> {
    type Value = Option<Layout>;

    fn deserialize<D: de::Deserializer<'de>>(self, deserializer: D) -> Result<Self::Value, D::Error> {
        deserializer.deserialize_any(self)
    }
}

impl<'de> Visitor<'de> for Positions<'_> {
    type Value = Option<Layout>;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("positions by frame or by bone")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Self::Value, A::Error> {
        let trail = self.0;
        let (mut channels, mut columns) = (Vec::new(), Vec::new());
        while let Some(bone) = map.next_key::<String>()? {
            within(trail, bone.clone(), || -> Result<(), A::Error> {
                count_servo(trail, &channels)?;
                columns.push(map.next_value_seed(List(trail))?);
                let mut channel = Channel::new(bone.clone(), ADDON_DEFAULT);
                channel.name.clone_from(&bone);
                channels.push(channel);
                Ok(())
            })?;
        }
        Ok(Some(Layout::Bones((channels, columns))))
    }

    /// One object per frame; a servo a frame leaves out holds where it was
    /// (the add-on writes only what changed), and one first named later held
    /// its first position before.
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Self::Value, A::Error> {
        let trail = self.0;
        let mut columns: Columns = (Vec::new(), Vec::new());
        let mut frame = 0;
        loop {
            let next = within(trail, format!("[{frame}]"), || {
                count_frame(trail, frame)?;
                seq.next_element_seed(Frame { trail, frame, columns: &mut columns })
            })?;
            if next.is_none() {
                break;
            }
            frame += 1;
            for column in &mut columns.1 {
                if let Some(&held) = column.last().filter(|_| column.len() == frame - 1) {
                    column.push(held);
                }
            }
        }
        Ok(Some(Layout::Frames(columns)))
    }

    fn visit_str<E>(self, _: &str) -> Result<Self::Value, E> {
        Ok(None)
    }

    fn visit_f64<E>(self, _: f64) -> Result<Self::Value, E> {
        Ok(None)
    }

    fn visit_i64<E>(self, _: i64) -> Result<Self::Value, E> {
        Ok(None)
    }

    fn visit_u64<E>(self, _: u64) -> Result<Self::Value, E> {
        Ok(None)
    }

    fn visit_bool<E>(self, _: bool) -> Result<Self::Value, E> {
        Ok(None)
    }

    fn visit_unit<E>(self) -> Result<Self::Value, E> {
        Ok(None)
    }
}

/// One frame of the per-frame layout, its positions put in their columns.
struct Frame<'t, 'c> {
    trail: &'t RefCell<Trail>,
    frame: usize,
    columns: &'c mut Columns,
}

impl<'de> DeserializeSeed<'de> for Frame<'_, '_> {
    type Value = ();

    fn deserialize<D: de::Deserializer<'de>>(self, deserializer: D) -> Result<(), D::Error> {
        deserializer.deserialize_any(self)
    }
}

impl<'de> Visitor<'de> for Frame<'_, '_> {
    type Value = ();

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("an object of positions by servo id")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<(), A::Error> {
        let Self { trail, frame, columns: (channels, columns) } = self;
        while let Some(id) = map.next_key::<String>()? {
            within(trail, id.clone(), || -> Result<(), A::Error> {
                let value = map.next_value_seed(Position(trail))?;
                let column = if let Some(column) = channels.iter().position(|channel| channel.key == id) {
                    column
                } else {
                    count_servo(trail, channels)?;
                    channels.push(Channel::new(id.clone(), ADDON_DEFAULT));
                    columns.push(vec![value; frame]);
                    columns.len() - 1
                };
                columns[column].push(value);
                Ok(())
            })?;
        }
        Ok(())
    }

    fn visit_seq<A: SeqAccess<'de>>(self, _: A) -> Result<(), A::Error> {
        Err(wrong(self.trail, "not an object of positions by servo id"))
    }
}
