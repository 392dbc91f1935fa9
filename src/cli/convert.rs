//! `servo-studio convert`: motions from another tool (Maestro settings,
//! RoboPlus `.mtn`, R+ Motion `.mtnx`, Blender add-on JSON) into a servo or
//! PLEN2 project, and projects (or those tools' files) out to a Maestro
//! settings file or add-on JSON. What was converted, approximated and dropped
//! is printed, each once; nothing is written unless everything converted.

use std::path::PathBuf;

use anyhow::Context;
use clap::Args;

use super::{bounds, out};

use crate::interchange::build::{self, Options, Selection};
use crate::interchange::{self, Format, JointMap, Report, export};
use crate::project::input::{MAX_PROJECT_BYTES, read_bytes, read_text};
use crate::project::{self, Family, Project, motion_json};

/// `servo-studio convert`'s arguments.
#[derive(Debug, Args)]
pub struct ConvertArgs {
    /// The file: a Maestro settings file, a RoboPlus .mtn, an R+ Motion .mtnx,
    /// a Blender servo-animation JSON, or a Servo Studio project / motion.json.
    pub input: PathBuf,
    /// Its format (default: told from the content): maestro, mtn, mtnx or blender.
    #[arg(long, value_parser = parse_from)]
    pub from: Option<Format>,
    /// What to write: servo, plen2 or dynamixel (a project), maestro (a settings file) or blender (add-on JSON).
    #[arg(long, value_parser = parse_to)]
    pub to: To,
    /// A joint map (JSON): which channel drives which servo or joint, with offset, direction and scale.
    #[arg(long)]
    pub map: Option<PathBuf>,
    /// Only this Maestro sequence / R+ page or flow (and what it plays); exporting: this macro or motion.
    #[arg(long)]
    pub sequence: Option<String>,
    /// Only this RoboPlus page (and the pages it leads to); exporting a PLEN2 motion: its slot.
    #[arg(long, value_parser = clap::value_parser!(u32).range(0..=65535))]
    pub page: Option<u32>,
    /// How far a fitted animation (Blender) may stray from the source, degrees.
    #[arg(long, default_value_t = 1.0, allow_hyphen_values = true, value_parser = bounds::tolerance_deg)]
    pub tolerance_deg: f64,
    /// Frames per second of Blender JSON written, 1..=1000.
    #[arg(long, default_value_t = 30.0, allow_hyphen_values = true, value_parser = bounds::fps)]
    pub fps: f64,
    /// Also write the joint map used (guessed where --map says nothing), to edit and give again with --map.
    #[arg(long)]
    pub save_map: Option<PathBuf>,
    /// The file to write.
    #[arg(long)]
    pub out: PathBuf,
    /// Replace the output file even when it is read-only.
    #[arg(long)]
    pub force: bool,
}

/// What `convert` writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum To {
    /// A servo-board project.
    Servo,
    /// A PLEN2 project.
    Plen2,
    /// A Maestro settings file.
    Maestro,
    /// Blender add-on JSON.
    Blender,
    /// A DYNAMIXEL project: each channel the servo of that ID, in its own units.
    Dynamixel,
}

/// `--to`'s words.
pub fn parse_to(text: &str) -> Result<To, String> {
    match text.to_ascii_lowercase().as_str() {
        "servo" => Ok(To::Servo),
        "plen2" => Ok(To::Plen2),
        "maestro" => Ok(To::Maestro),
        "blender" => Ok(To::Blender),
        "dynamixel" => Ok(To::Dynamixel),
        _ => Err(format!("{text:?}: convert to servo, plen2, dynamixel, maestro or blender")),
    }
}

/// `--from`'s words.
pub fn parse_from(text: &str) -> Result<Format, String> {
    Format::from_tag(text).ok_or_else(|| format!("{text:?}: read as maestro, mtn, mtnx or blender"))
}

/// What `convert` is asked.
#[derive(Clone, Debug)]
pub struct ConvertRequest {
    /// The file read.
    pub input: PathBuf,
    /// Its format, when not guessed.
    pub from: Option<Format>,
    /// What to write.
    pub to: To,
    /// A joint map file.
    pub map: Option<PathBuf>,
    /// A Maestro sequence, R+ page or flow, or a macro's or motion's name.
    pub sequence: Option<String>,
    /// A RoboPlus page, or a PLEN2 slot to export.
    pub page: Option<u32>,
    /// How far a fitted animation may stray, degrees.
    pub tolerance_deg: f64,
    /// Add-on JSON's frame rate.
    pub fps: f64,
    /// Where to also write the joint map used.
    pub save_map: Option<PathBuf>,
    /// The file written.
    pub out: PathBuf,
    /// Replace a read-only output.
    pub force: bool,
}

/// What the input was.
enum Input {
    Foreign(interchange::Source),
    Ours(Box<Project>),
}

fn read_input(request: &ConvertRequest) -> anyhow::Result<Input> {
    let bytes = read_bytes(&request.input, MAX_PROJECT_BYTES)?;
    let name = request.input.display();
    let decoded = interchange::text::decode(bytes).with_context(|| format!("{name} cannot be read as text"))?;
    let text = &decoded.text;
    if request.from.is_none() {
        if project::parse(text).is_ok() {
            return Ok(Input::Ours(Box::new(project::from_json(text)?)));
        }
        if motion_json::looks_like_motion(text) {
            let (motion, _) = motion_json::read_motion(text).map_err(|error| anyhow::anyhow!("{name}: {error}"))?;
            let mut project = Project::empty(Family::Plen2);
            project.plen2.motions.push(motion);
            return Ok(Input::Ours(Box::new(project)));
        }
    }
    let Some(format) = request.from.or_else(|| Format::guess(text)) else {
        anyhow::bail!(
            "cannot tell what {name} is (not a Maestro settings file, RoboPlus .mtn, R+ .mtnx or Blender servo-animation JSON by its content): give --from maestro, mtn, mtnx or blender"
        );
    };
    let source = interchange::read_decoded(Some(format), &decoded)
        .map_err(|error| {
            let try_ = error.what_to_try(format);
            anyhow::Error::new(error).context(format!(
                "{name} is not a {} ({}); nothing was written ({try_})",
                format.name(),
                format.tag()
            ))
        })?
        .ok_or_else(|| anyhow::anyhow!("{name}: no format"))?;
    Ok(Input::Foreign(source))
}

/// Converts and writes; returns the report's lines.
pub fn run(request: &ConvertRequest) -> anyhow::Result<Vec<String>> {
    let mut inputs = vec![request.input.as_path()];
    inputs.extend(request.map.as_deref());
    super::output_not_an_input(&request.out, &inputs)?;
    if let Some(save_map) = &request.save_map {
        inputs.push(&request.out);
        super::output_not_an_input(save_map, &inputs)?;
        super::writable_output(save_map, request.force)?;
    }
    super::writable_output(&request.out, request.force)?;
    let map = match &request.map {
        Some(path) => {
            let text = read_text(path, MAX_PROJECT_BYTES)?;
            Some(
                JointMap::from_json(&text)
                    .with_context(|| format!("{} cannot be used as a joint map", path.display()))?,
            )
        }
        None => None,
    };
    let (written, report, used_map) = match read_input(request)? {
        Input::Foreign(source) => foreign(request, &source, map.as_ref())?,
        Input::Ours(project) => {
            let (written, report) = ours(request, &project, map.as_ref())?;
            (written, report, None)
        }
    };
    // The output and the map used, both or neither.
    let map_json = used_map.map(|map: JointMap| map.to_json());
    let mut files = vec![(request.out.as_path(), written.as_bytes())];
    if let (Some(path), Some(json)) = (&request.save_map, &map_json) {
        files.push((path.as_path(), json.as_bytes()));
    }
    project::atomic_write_all(&files).with_context(|| {
        let names: Vec<String> = files.iter().map(|(path, _)| path.display().to_string()).collect();
        format!("cannot write {}: nothing was written", names.join(" and "))
    })?;
    let mut lines = report.lines();
    if let (Some(path), Some(_)) = (&request.save_map, &map_json) {
        lines.push(format!("wrote the joint map to {}", path.display()));
    }
    lines.push(format!("wrote {}", request.out.display()));
    Ok(lines)
}

fn selection(request: &ConvertRequest) -> Selection {
    match (&request.sequence, request.page) {
        (Some(name), _) => Selection::Named(name.clone()),
        (None, Some(page)) => Selection::Page(page),
        (None, None) => Selection::All,
    }
}

/// A foreign file converted: what is written, the report, and the joint map used.
fn foreign(
    request: &ConvertRequest,
    source: &interchange::Source,
    given: Option<&JointMap>,
) -> anyhow::Result<(String, Report, Option<JointMap>)> {
    if request.to == To::Dynamixel {
        // Onto the IDs the file names, in the servos' own units: no joint map to guess.
        let (project, report) =
            interchange::dynamixel::build(source, &selection(request)).context("nothing was written")?;
        return Ok((project::to_json(&project), report, None));
    }
    let family = match request.to {
        To::Plen2 => Family::Plen2,
        To::Servo | To::Maestro | To::Dynamixel => Family::Servo,
        // Through the family the map drives (servos unless it names PLEN2 joints).
        To::Blender => {
            let joints = given
                .is_some_and(|map| map.entries.iter().any(|e| e.target.is_some_and(|t| t.family() == Family::Plen2)));
            if joints { Family::Plen2 } else { Family::Servo }
        }
    };
    let map = JointMap::for_source(source, family, given);
    let options = Options { family, selection: selection(request), tolerance_deg: request.tolerance_deg };
    let built = build::build(source, &map, &options).context("nothing was written")?;
    let problems = project::validate(&built.project);
    if project::has_errors(&problems) {
        let first: Vec<String> = problems.iter().take(3).map(ToString::to_string).collect();
        anyhow::bail!(
            "the converted project would not pass `check` ({}); nothing was written. Please report this file",
            first.join("; ")
        );
    }
    let mut report = built.report;
    let written = match request.to {
        To::Servo | To::Plen2 | To::Dynamixel => project::to_json(&built.project),
        To::Maestro => merge(&mut report, export::maestro(&built.project.servo, Some(&map))?),
        To::Blender => {
            let mut request = request.clone();
            request.sequence = None;
            request.page = None;
            merge(&mut report, blender(&request, &built.project, Some(&map))?)
        }
    };
    Ok((written, report, Some(map)))
}

fn merge(report: &mut Report, (text, more): (String, Report)) -> String {
    report.converted.extend(more.converted);
    for note in more.approximated {
        report.approximated(note);
    }
    for note in more.dropped {
        report.dropped(note);
    }
    text
}

fn ours(request: &ConvertRequest, project: &Project, map: Option<&JointMap>) -> anyhow::Result<(String, Report)> {
    let name = request.input.display();
    match request.to {
        To::Servo | To::Plen2 | To::Dynamixel => {
            anyhow::bail!("{name} is a Servo Studio file already: convert it --to maestro or --to blender")
        }
        To::Maestro if project.family != Family::Servo => {
            anyhow::bail!("{name} is a {} project: only servo-board projects go to a Maestro", project.family.name())
        }
        To::Maestro => Ok(export::maestro(&project.servo, map)?),
        To::Blender => blender(request, project, map),
    }
}

fn blender(request: &ConvertRequest, project: &Project, map: Option<&JointMap>) -> anyhow::Result<(String, Report)> {
    if project.family == Family::Plen2 {
        let motions = &project.plen2.motions;
        let chosen = match (&request.sequence, request.page) {
            (Some(name), _) => motions.iter().find(|m| &m.name == name),
            (None, Some(slot)) => motions.iter().find(|m| u32::from(m.slot) == slot),
            (None, None) => motions.iter().min_by_key(|m| m.slot),
        };
        let Some(motion) = chosen else {
            let held: Vec<String> = motions.iter().map(|m| format!("slot {} {:?}", m.slot, m.name)).collect();
            anyhow::bail!(
                "no such motion (the project holds: {}); choose with --sequence NAME or --page SLOT",
                held.join(", ")
            );
        };
        let (text, mut report) = export::blender_plen2(&project.plen2, motion.slot, request.fps, map)?;
        if request.sequence.is_none() && request.page.is_none() && motions.len() > 1 {
            report.dropped(format!(
                "the other {} motions (one animation per file: choose with --sequence or --page)",
                motions.len() - 1
            ));
        }
        return Ok((text, report));
    }
    let macros = &project.servo.macros;
    let chosen = match &request.sequence {
        Some(name) => macros.iter().find(|m| &m.caption == name),
        None => macros.first(),
    };
    let Some(item) = chosen else {
        let held: Vec<String> = macros.iter().map(|m| format!("{} {:?}", m.id, m.caption)).collect();
        anyhow::bail!(
            "no such macro (the project holds: {}); choose with --sequence NAME",
            if held.is_empty() { "none".into() } else { held.join(", ") }
        );
    };
    let (text, mut report) = export::blender_servo(&project.servo, item.id, request.fps, map)?;
    if request.sequence.is_none() && macros.len() > 1 {
        report
            .dropped(format!("the other {} macros (one animation per file: choose with --sequence)", macros.len() - 1));
    }
    Ok((text, report))
}

/// `servo-studio convert`: converts, then prints the report's lines (a closed stdout is no failure).
pub fn run_args(args: ConvertArgs) -> anyhow::Result<()> {
    let request = ConvertRequest {
        input: args.input,
        from: args.from,
        to: args.to,
        map: args.map,
        sequence: args.sequence,
        page: args.page,
        tolerance_deg: args.tolerance_deg,
        fps: args.fps,
        save_map: args.save_map,
        out: args.out,
        force: args.force,
    };
    for line in run(&request)? {
        match out::line(&line) {
            Ok(()) => {}
            Err(out::Unwritten::Closed) => return Ok(()),
            Err(error) => return Err(error.into()),
        }
    }
    Ok(())
}
