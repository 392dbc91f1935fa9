//! ROBOTIS motion files: RoboPlus Motion 1.0 `.mtn` (text: pages of steps,
//! each a Dynamixel position per id, a pause and a play time in seconds, and
//! the page's play parameters) and R+ Motion 2.0 `.mtnx` (XML: pages of steps
//! at absolute times in 1/128 s with poses in degrees, and flows of units).

mod clock;

use super::bounds;
use super::format::{Format, ReadError, number};
use super::source::{Body, Channel, Clip, Key, Link, Source, Timing, Unit};
use super::xml;

/// AX-12/AX-18 positions: 0..=1023 over 300°, 512 at the centre.
pub const AX: Unit = Unit { zero: 512.0, per_degree: 1024.0 / 300.0, label: "AX units" };
/// MX positions: 0..=4095 over 360°, 2048 at the centre.
pub const MX: Unit = Unit { zero: 2048.0, per_degree: 4096.0 / 360.0, label: "MX units" };
/// R+ Motion's ticks: 128 a second.
const MTNX_TICKS_PER_S: f64 = 128.0;

/// The farthest a straight move strays from the controller's eased one (the
/// page's inertial force) over every step of every page, degrees, and the
/// page: each step's move from the step before it (the page's last, for its first).
fn eased_most(pages: &[&Page], ids: &[usize], unit: Unit) -> Option<(f64, u32)> {
    let mut most: Option<(f64, u32)> = None;
    for page in pages {
        let Some(last) = page.steps.last() else { continue };
        let mut before = &last.0;
        for (values, _, time, _) in &page.steps {
            let distance = ids
                .iter()
                .filter_map(|&id| Some((values.get(id)? - before.get(id)?).abs() / unit.per_degree))
                .fold(0.0, f64::max);
            let strays = distance * clock::eased_share(*time, page.ease);
            if strays > most.map_or(0.05, |(deg, _)| deg) {
                most = Some((strays, page.number));
            }
            before = values;
        }
    }
    most
}

/// A page's next page, exit page, repeat (as written: 0 is kept) and speed rate.
type Play = (u32, u32, u32, f64);

/// A page as read, before its links are resolved.
struct Page {
    number: u32,
    name: String,
    /// `(values by id, pause s, time s, line)`.
    steps: Vec<(Vec<f64>, f64, f64, usize)>,
    play: Play,
    /// The inertial force: each step's ease-in and ease-out, in ticks.
    ease: f64,
}

/// A line's numbers: at most a value per channel and a step's pause and time,
/// counted before they are kept.
fn numbers(text: &str, line: usize, key: &str) -> Result<Vec<f64>, ReadError> {
    let most = bounds::MAX_CHANNELS + 2;
    if text.split_whitespace().nth(most).is_some() {
        return Err(ReadError::at(
            line,
            key,
            format!("more than {most} values: a board has no more channels (is the file damaged?)"),
        ));
    }
    text.split_whitespace().map(|word| number(word, line, key, "value")).collect()
}

/// Reads a RoboPlus Motion 1.0 file.
pub fn read_mtn(text: &str) -> Result<Source, ReadError> {
    let mut enabled: Option<Vec<bool>> = None;
    let mut pages: Vec<Page> = Vec::new();
    let mut open: Option<Page> = None;
    let mut saw_motion = false;
    let mut commas = false;
    let mut steps = 0;
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    for (index, raw) in text.lines().enumerate() {
        let line = index + 1;
        let trimmed = raw.trim();
        if trimmed.is_empty() {
            continue;
        }
        let (key, value) = trimmed.split_once('=').map_or((trimmed, ""), |(key, value)| (key.trim(), value.trim()));
        match (key, open.as_mut()) {
            ("type", _) => saw_motion |= value == "motion",
            ("version" | "motor_type", _) => {}
            ("enable", _) => enabled = Some(numbers(value, line, key)?.iter().map(|flag| *flag != 0.0).collect()),
            ("page_begin", None) => {
                if pages.len() >= bounds::MAX_KEYS {
                    return Err(too_many(line, key, "pages"));
                }
                let number = u32::try_from(pages.len() + 1).unwrap_or(u32::MAX);
                open = Some(Page { number, name: String::new(), steps: Vec::new(), play: (0, 0, 1, 1.0), ease: 0.0 });
            }
            ("page_begin", Some(_)) => {
                return Err(ReadError::at(line, key, "a page begins before the last one ended (page_end missing)"));
            }
            ("page_end", Some(_)) => pages.extend(open.take()),
            ("page_end", None) => return Err(ReadError::at(line, key, "page_end without page_begin")),
            ("name", Some(page)) => page.name = value.to_string(),
            ("compliance", Some(_)) => {}
            ("play_param", Some(page)) => (page.play, page.ease) = play_param(value, line)?,
            ("step", Some(page)) => {
                steps += 1;
                if steps > bounds::MAX_KEYS {
                    return Err(too_many(line, key, "steps"));
                }
                commas |= value.contains(',');
                page.steps.push(step_line(value, line)?);
            }
            (_, None) if ["name", "compliance", "play_param", "step"].contains(&key) => {
                return Err(ReadError::at(line, key, "outside a page (page_begin missing)"));
            }
            _ => return Err(ReadError::at(line, key, format!("{trimmed:?} is not a line of a RoboPlus motion file"))),
        }
    }
    if open.is_some() {
        return Err(ReadError {
            line: Some(text.lines().count()),
            element: None,
            message: "the last page never ends (page_end missing): is the file cut short?".into(),
        });
    }
    if !saw_motion && pages.is_empty() {
        return Err(ReadError {
            line: Some(1),
            element: None,
            message: "no page and no type=motion: is this a RoboPlus .mtn file?".into(),
        });
    }
    let mut source = mtn_source(&pages, enabled.as_deref());
    if commas {
        source.notes.push("saved on a decimal-comma locale: \"0,096\" read as 0.096 s".into());
    }
    Ok(source)
}

/// More of `what` than any tool writes, at `line`.
fn too_many(line: usize, key: &str, what: &str) -> ReadError {
    ReadError::at(line, key, format!("more than {} {what}: {}", bounds::MAX_KEYS, bounds::TOO_MANY_KEYS))
}

/// `step=P0 P1 … Pn PAUSE TIME`: the positions, the pause and play time (s), and the line.
fn step_line(value: &str, line: usize) -> Result<(Vec<f64>, f64, f64, usize), ReadError> {
    let values = numbers(value, line, "step")?;
    let [.., pause, time] = values[..] else {
        return Err(ReadError::at(line, "step", "a step needs positions, a pause and a play time"));
    };
    if pause < 0.0 || time < 0.0 {
        return Err(ReadError::at(line, "step", "a negative pause or play time"));
    }
    Ok((values[..values.len() - 2].to_vec(), pause, time, line))
}

/// `play_param=NEXT EXIT REPEAT SPEED_RATE INERTIAL_FORCE`: the page's play
/// (repeat as written) and its ease.
fn play_param(value: &str, line: usize) -> Result<(Play, f64), ReadError> {
    let words: Vec<&str> = value.split_whitespace().collect();
    let whole = |at: usize, what: &str| -> Result<u32, ReadError> {
        let Some(word) = words.get(at) else { return Ok(if what == "repeat" { 1 } else { 0 }) };
        word.parse::<u32>()
            .map_err(|_| ReadError::at(line, "play_param", format!("{what} {word:?} is not a whole number")))
    };
    let speed = match words.get(3) {
        Some(word) => number(word, line, "play_param", "speed rate")?,
        None => 1.0,
    };
    if speed <= 0.0 {
        return Err(ReadError::at(line, "play_param", format!("speed rate {speed} must be above 0")));
    }
    let ease = match words.get(4) {
        Some(word) => number(word, line, "play_param", "inertial force")?.clamp(0.0, 255.0),
        None => 0.0,
    };
    Ok(((whole(0, "next page")?, whole(1, "exit page")?, whole(2, "repeat")?, speed), ease))
}

fn mtn_source(pages: &[Page], enabled: Option<&[bool]>) -> Source {
    let width = pages.iter().flat_map(|page| page.steps.iter().map(|step| step.0.len())).max().unwrap_or(0);
    let mx = pages.iter().flat_map(|page| &page.steps).flat_map(|step| &step.0).any(|value| *value > 1023.0);
    let unit = if mx { MX } else { AX };
    // Id 0 is never a servo in RoboPlus (its column is a placeholder).
    let ids: Vec<usize> = (1..width)
        .filter(|&id| match enabled {
            Some(flags) => flags.get(id).copied().unwrap_or(false),
            None => pages.iter().flat_map(|page| &page.steps).any(|step| step.0.get(id).is_some_and(|v| *v != 0.0)),
        })
        .collect();
    let mut source = Source {
        format: Format::Mtn,
        channels: ids.iter().map(|id| Channel::new(id.to_string(), unit)).collect(),
        clips: Vec::new(),
        dropped: Vec::new(),
        notes: Vec::new(),
    };
    let kept: Vec<&Page> = pages.iter().filter(|page| !page.steps.is_empty()).collect();
    let index_of = |number: u32| kept.iter().position(|page| page.number == number);
    for page in &kept {
        let keys = page
            .steps
            .iter()
            .map(|(values, pause, time, _)| {
                let (reach, stand) = clock::step_ticks(*time, *pause, page.ease);
                Key {
                    values: ids.iter().map(|&id| values.get(id).copied()).collect(),
                    timing: Timing::Move { move_ms: reach * clock::TICK_MS, hold_ms: stand * clock::TICK_MS },
                    name: String::new(),
                }
            })
            .collect();
        let (next, exit, repeat, speed) = page.play;
        // A page that leads to one RoboPlus would not play (repeat 0) ends there, as RoboPlus ends.
        let next = if kept.iter().any(|other| other.number == next && other.play.2 == 0) {
            source.drop_note(format!(
                "page {}: its next page {next} repeats 0 times: RoboPlus stops before it",
                page.number
            ));
            0
        } else {
            next
        };
        let repeat = repeat.max(1);
        let name = if page.name.is_empty() { format!("page {}", page.number) } else { page.name.clone() };
        let mut clip = Clip::new(name, Body::Keys(keys));
        clip.number = Some(page.number);
        (clip.repeat, clip.speed) = (repeat, speed);
        clip.next = (next != 0).then(|| index_of(next)).flatten();
        clip.exit = (exit != 0).then(|| index_of(exit)).flatten();
        if (next != 0 && clip.next.is_none()) || (exit != 0 && clip.exit.is_none()) {
            source.drop_note(format!("page {}: a next or exit page with no steps", page.number));
        }
        source.clips.push(clip);
    }
    source.drop_note("compliance and inertial force (each step moves straight)");
    if let Some((strays, page)) = eased_most(&kept, &ids, unit) {
        source.notes.push(format!(
            "inertial force: the controller eases each step in and out; moved straight here, up to {strays:.1}° from its path mid-step (page {page})"
        ));
    }
    source.notes.push(
        "timed as a ROBOTIS controller plays a page: 128 ticks a second, each step its time and 3 ticks more, a pause 1 more"
            .into(),
    );
    source
}

/// What an R+ Motion file may hold, counted as it is read.
const MTNX_MOST: [xml::Most; 4] = [
    xml::Most { name: "Page", count: bounds::MAX_KEYS, because: bounds::TOO_MANY_KEYS },
    xml::Most { name: "step", count: bounds::MAX_KEYS, because: bounds::TOO_MANY_KEYS },
    xml::Most { name: "unit", count: bounds::MAX_KEYS, because: bounds::TOO_MANY_KEYS },
    xml::Most {
        name: "joint",
        count: bounds::MAX_CHANNELS,
        because: "a robot has no more joints (is the file damaged?)",
    },
];

/// Reads an R+ Motion 2.0 file.
pub fn read_mtnx(text: &str) -> Result<Source, ReadError> {
    let root = xml::parse_within(text, &MTNX_MOST)?;
    let pages = root.descendants_named("Page");
    if pages.is_empty() && !root.name.eq_ignore_ascii_case("Page") {
        return Err(ReadError::at(root.line, &root.name, "no <Page>: is this an R+ Motion .mtnx file?"));
    }
    let mut clips = Vec::new();
    let mut width = 0;
    let mut poses: Vec<Vec<(f64, Vec<f64>)>> = Vec::new();
    for page in &pages {
        let mut steps = Vec::new();
        let mut last = -1.0;
        for step in page.descendants_named("step") {
            let frame = step.attr("frame").ok_or_else(|| ReadError::at(step.line, "step", "no frame"))?;
            let frame = number(frame, step.line, "step", "frame")?;
            if frame < last {
                return Err(ReadError::at(
                    step.line,
                    "step",
                    format!("frame {frame} comes before the step above it ({last})"),
                ));
            }
            last = frame;
            let pose = step.attr("pose").ok_or_else(|| ReadError::at(step.line, "step", "no pose"))?;
            let pose = numbers(pose, step.line, "step")?;
            width = width.max(pose.len());
            steps.push((frame, pose));
        }
        poses.push(steps);
    }
    let robot = Robot::declared(&root);
    let (channels, driven) = robot.channels(width);
    for (page, steps) in pages.iter().zip(&poses) {
        let mut at = 0.0;
        let keys = steps
            .iter()
            .map(|(frame, pose)| {
                let move_ms = (frame - at) * 1000.0 / MTNX_TICKS_PER_S;
                at = *frame;
                Key {
                    values: (0..width).filter(|index| driven[*index]).map(|index| pose.get(index).copied()).collect(),
                    timing: Timing::Move { move_ms, hold_ms: 0.0 },
                    name: String::new(),
                }
            })
            .collect();
        clips.push(Clip::new(page.attr("name").unwrap_or("page"), Body::Keys(keys)));
    }
    let mut source = Source { format: Format::Mtnx, channels, clips, dropped: Vec::new(), notes: Vec::new() };
    source.notes.extend(robot.note());
    if driven.iter().any(|on| !on) {
        source.drop_note("joints the file's robot has switched off (enable=\"False\")");
    }
    for flow in root.descendants_named("Flow") {
        let chain = flow_links(flow, &source.clips)?;
        let name = flow.attr("name").unwrap_or("flow");
        if chain.is_empty() {
            // R+ Motion's new file holds empty flows (and people use them as headings).
            source.drop_note(format!("flow {name:?}: no units, nothing to play"));
            continue;
        }
        source.clips.push(Clip::new(name, Body::Chain(chain)));
    }
    if root.descendants_named("Bucket").iter().any(|bucket| !bucket.children.is_empty()) {
        source.drop_note("buckets (a controller's list of flows to call by number): convert each flow");
    }
    Ok(source)
}

/// The robot an R+ Motion file declares (`<DesignRoot>`: its name,
/// controller and `<skeleton>` of joints, each a motor, an id and whether it is on).
struct Robot {
    name: String,
    controller: String,
    /// `(id, motor, enabled)` in pose order.
    joints: Vec<(String, String, bool)>,
}

impl Robot {
    fn declared(root: &xml::Element) -> Self {
        let design = root.descendants_named("DesignRoot");
        let design = design.first();
        let attr = |name: &str| design.and_then(|d| d.attr(name)).unwrap_or_default().trim().to_string();
        let joints = design
            .map(|d| d.descendants_named("joint"))
            .unwrap_or_default()
            .into_iter()
            .map(|joint| {
                (
                    joint.attr("id").unwrap_or_default().trim().to_string(),
                    joint.attr("motor").unwrap_or_default().trim().to_string(),
                    !joint.attr("enable").is_some_and(|on| on.eq_ignore_ascii_case("false")),
                )
            })
            .collect();
        Self { name: attr("name"), controller: attr("controller"), joints }
    }

    /// The channels for poses of `width` values (by the declared ids when
    /// the skeleton has one joint per value), and which values are driven.
    fn channels(&self, width: usize) -> (Vec<Channel>, Vec<bool>) {
        let declared = self.joints.len() == width && self.joints.iter().all(|(id, ..)| id.parse::<u8>().is_ok());
        let mut channels = Vec::new();
        let mut driven = Vec::new();
        for index in 0..width {
            let (key, motor, on) = match self.joints.get(index).filter(|_| declared) {
                Some((id, motor, on)) => (id.clone(), motor.as_str(), *on),
                None => ((index + 1).to_string(), "", true),
            };
            driven.push(on);
            if !on {
                continue;
            }
            let mut channel = Channel::new(key, Unit::DEGREES);
            channel.limits = motor_range(motor).map(|half| (-half, half));
            channel.motor = (!motor.is_empty()).then(|| motor.to_string());
            if self.is_bioloid() {
                channel.name = super::map::bioloid_joint(&channel.key).unwrap_or_default().replace('_', " ");
            }
            channels.push(channel);
        }
        (channels, driven)
    }

    /// A Bioloid-class humanoid (ids 1..=18 of AX or MX servos, at least 16),
    /// or no declaration at all (R+ Motion's first files): its ids name PLEN2 joints.
    fn is_bioloid(&self) -> bool {
        let ids = self.joints.iter().filter_map(|(id, ..)| id.parse::<u8>().ok()).filter(|id| (1..=18).contains(id));
        self.joints.is_empty()
            || (ids.count() == self.joints.len()
                && self.joints.len() >= 16
                && self.joints.iter().all(|(_, motor, _)| {
                    let upper = motor.to_ascii_uppercase();
                    upper.starts_with("AX-") || upper.starts_with("MX-")
                }))
    }

    /// What the file says it is for, in words.
    fn note(&self) -> Vec<String> {
        if self.joints.is_empty() {
            return Vec::new();
        }
        let mut motors: Vec<(String, usize)> = Vec::new();
        for (_, motor, _) in &self.joints {
            match motors.iter_mut().find(|(name, _)| name == motor) {
                Some((_, count)) => *count += 1,
                None => motors.push((motor.clone(), 1)),
            }
        }
        let motors: Vec<String> = motors.iter().map(|(motor, count)| format!("{count} × {motor}")).collect();
        let mut notes = vec![if self.name.is_empty() {
            format!("made for a robot of {}: ids and ranges are taken from it", motors.join(", "))
        } else {
            format!("made for {:?}, a robot of {}: ids and ranges are taken from it", self.name, motors.join(", "))
        }];
        if !self.controller.is_empty() {
            notes.push(format!("its controller: {}", self.controller));
        }
        notes.push(if self.is_bioloid() {
            "its ids are a Bioloid humanoid's, so PLEN2 joints are guessed from them".into()
        } else {
            "not a Bioloid humanoid, so no PLEN2 joint is guessed: map them in the table or with --map".into()
        });
        notes
    }
}

/// Half the range of a Dynamixel model, degrees from its centre (R+ poses are degrees from centre).
fn motor_range(motor: &str) -> Option<f64> {
    let upper = motor.to_ascii_uppercase();
    if ["AX-", "XL-320", "XL320", "DX-", "RX-"].iter().any(|prefix| upper.starts_with(prefix)) {
        Some(150.0)
    } else if ["MX-", "XL-430", "XL430", "XM", "XH", "XC", "2XL", "2XC"].iter().any(|prefix| upper.starts_with(prefix))
    {
        Some(180.0)
    } else {
        None
    }
}

fn flow_links(flow: &xml::Element, pages: &[Clip]) -> Result<Vec<Link>, ReadError> {
    let page = |name: &str, line: usize| {
        pages
            .iter()
            .position(|clip| clip.name == name && !matches!(clip.body, Body::Chain(_)))
            .ok_or_else(|| ReadError::at(line, "unit", format!("page {name:?} is not in the file")))
    };
    let speed = |unit: &xml::Element, name: &str| -> Result<f64, ReadError> {
        let value = unit.attr(name).map_or(Ok(1.0), |text| number(text, unit.line, "unit", name))?;
        if value <= 0.0 {
            return Err(ReadError::at(unit.line, "unit", format!("{name} {value} must be above 0")));
        }
        Ok(value)
    };
    let mut links = Vec::new();
    for unit in flow.descendants_named("unit") {
        let main = unit.attr("main").unwrap_or_default();
        if !main.is_empty() {
            let plays = unit.attr("loop").map_or(Ok(1.0), |text| number(text, unit.line, "unit", "loop"))?;
            // Whole, non-negative loop counts only (R+ writes whole numbers).
            #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
            let plays = plays.max(0.0).min(f64::from(u32::MAX)) as u32;
            links.push(Link { clip: page(main, unit.line)?, plays, speed: speed(unit, "mainSpeed")? });
        }
        let exit = unit.attr("exit").unwrap_or_default();
        if !exit.is_empty() {
            links.push(Link { clip: page(exit, unit.line)?, plays: 1, speed: speed(unit, "exitSpeed")? });
        }
    }
    Ok(links)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::float_cmp)]
    use super::*;

    fn step(values: &[f64], pause: &str, time: &str) -> String {
        let mut line = String::from("step=0");
        for value in values {
            line.push_str(&format!(" {value}"));
        }
        format!("{line} {pause} {time}\n")
    }

    #[test]
    fn mtn_pages_steps_and_play_parameters_are_read() {
        let text = format!(
            "type=motion\nversion=1.01\nenable=0 1 1\nmotor_type=0 0 0\npage_begin\nname=Bow\ncompliance=5 5\nplay_param=2 0 3 2.0 32\n{}{}page_end\npage_begin\nname=\nplay_param=0 0 1 1.0 32\n{}page_end\n",
            step(&[512.0, 600.0], "0.000", "0.496"),
            step(&[700.0, 600.0], "0.296", "1.000"),
            step(&[512.0, 512.0], "0", "0.2")
        );
        let source = read_mtn(&text).unwrap();
        assert_eq!(source.channels.len(), 2);
        assert_eq!(source.channels[0].unit, AX);
        let bow = &source.clips[0];
        assert_eq!((bow.repeat, bow.speed, bow.next, bow.number), (3, 2.0, Some(1), Some(1)));
        let Body::Keys(keys) = &bow.body else { panic!() };
        assert_eq!(keys[1].values, [Some(700.0), Some(600.0)]);
        // 1.000 s: 125 units, reached on tick 126; 0.296 s: 37 units, standing 2 + 38 ticks.
        assert_eq!(keys[1].timing, Timing::Move { move_ms: 126.0 * 7.8125, hold_ms: 40.0 * 7.8125 });
        assert_eq!(source.clips[1].name, "page 2");
    }

    #[test]
    fn bad_mtn_files_say_which_line() {
        let word = read_mtn("type=motion\npage_begin\nstep=0 512 x 0 0.5\npage_end\n").unwrap_err();
        assert_eq!(word.line, Some(3), "{word}");
        let cut = read_mtn("type=motion\npage_begin\nname=a\n").unwrap_err();
        assert!(cut.message.contains("cut short"), "{cut}");
        let garbage = read_mtn("hello world\n").unwrap_err();
        assert_eq!(garbage.line, Some(1), "{garbage}");
    }

    #[test]
    fn mtnx_pages_are_timed_in_128ths_and_flows_chain_them() {
        let text = r#"<?xml version="1.0" encoding="utf-8"?>
<Root>
  <FlowRoot><Flow name="dance" return="-1"><units>
    <unit main="Wave" mainSpeed="1" loop="2" exit="Rest" exitSpeed="1" callSite="False" />
  </units></Flow></FlowRoot>
  <PageRoot>
    <Page name="Wave"><param /><steps>
      <step frame="64" pose="10 -10.5" />
      <step frame="192" pose="0 0" />
    </steps></Page>
    <Page name="Rest"><steps><step frame="128" pose="0 0" /></steps></Page>
  </PageRoot>
</Root>"#;
        let source = read_mtnx(text).unwrap();
        let Body::Keys(keys) = &source.clips[0].body else { panic!() };
        assert_eq!(keys[0].timing, Timing::Move { move_ms: 500.0, hold_ms: 0.0 });
        assert_eq!(keys[1].timing, Timing::Move { move_ms: 1000.0, hold_ms: 0.0 });
        assert_eq!(keys[0].values, [Some(10.0), Some(-10.5)]);
        let Body::Chain(links) = &source.clips[2].body else { panic!() };
        assert_eq!(links, &[Link { clip: 0, plays: 2, speed: 1.0 }, Link { clip: 1, plays: 1, speed: 1.0 }]);
        let bad = read_mtnx(&text.replace("frame=\"192\"", "frame=\"ten\"")).unwrap_err();
        assert_eq!((bad.line, bad.element.as_deref()), (Some(9), Some("step")), "{bad}");
        assert!(read_mtnx("<Root></Root>").unwrap_err().message.contains("no <Page>"));
    }
}
