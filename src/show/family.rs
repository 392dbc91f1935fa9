//! What a family brings to shows and remote control — its capabilities —
//! registered by the family beside its show stage (`inventory::submit!` in
//! `show/stages/<family>.rs`): how a device of it is connected for a show,
//! what it stores to start, what a remote may run on it, the axes a pose may
//! move, whether it drives. Shows and remote control ask here; a family
//! without a capability is refused by name ("a PLEN2 cannot drive"), never
//! handled as another. Nothing here lists the families.

use super::at::Axis;
use super::stages::Linked;
use super::{Device, Run, Start};
use crate::link::{LineSettings, PortName};
use crate::project::{Family, Project};

/// A family's part of shows and remote control.
#[derive(Debug)]
pub struct ShowFamily {
    /// The family.
    pub family: Family,
    /// Connects a device of the family on a port (set up as the device layer
    /// sets up the family's line) for a show, measuring its link.
    pub connect: fn(&PortName, &LineSettings, &Device) -> anyhow::Result<Linked>,
    /// The first thing a project of the family stores to start (its lowest
    /// macro, motion…), a device's cue when the show gives it none.
    pub first_stored: fn(&Project) -> Option<Start>,
    /// Whether a project of the family holds what a cue starts (its macro,
    /// its motion; a drive of finite speed and turn).
    pub holds: fn(&Project, &Start) -> bool,
    /// Whether a cue's start is of a kind the family takes (a macro, a slot,
    /// a drive, one of its own [`Self::cues`]), whatever it names.
    pub takes: fn(&Start) -> bool,
    /// What a new cue for a device of it starts in the show window (its
    /// first stored macro or motion, a slow drive of a second…).
    /// `None`: the first it stores ([`Self::first_stored`]).
    pub new_cue: Option<fn(&Project) -> Option<Start>>,
    /// What a remote may run on it by name; `None`: it stores nothing to run.
    pub runs: Option<Runs>,
    /// What a pose may move; `None`: it has nothing to pose.
    pub poses: Option<Poses>,
    /// Whether it drives (speed and turn, kept up by heartbeats).
    pub drives: bool,
    /// The kinds of cue it adds to show files ([`FamilyCue`]; the first
    /// three families' are the show's own: macro, slot, drive).
    pub cues: &'static [&'static str],
}

inventory::collect!(ShowFamily);

/// A kind of cue a family added since the first three starts: its key in a
/// show file (registered in [`ShowFamily::cues`]), and the number it takes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FamilyCue {
    /// Its kind, as its family registered it (`"move"`).
    pub kind: &'static str,
    /// The number it takes (an angle, a motion's index…), finite.
    pub value: f64,
}

impl FamilyCue {
    /// The cue of the registered kind `kind` taking `value`; why not when no
    /// family registered that kind or the value is not a finite number.
    pub fn named(kind: &str, value: f64) -> Result<Self, String> {
        let kind =
            every().flat_map(|entry| entry.cues.iter()).find(|registered| **registered == kind).ok_or_else(|| {
                let known: Vec<&str> =
                    super::FILE_KINDS.into_iter().chain(every().flat_map(|entry| entry.cues.iter().copied())).collect();
                format!("no kind of cue is called {kind:?}; a cue starts one of: {}", known.join(", "))
            })?;
        if !value.is_finite() {
            return Err(format!("a {kind} cue takes a finite number"));
        }
        Ok(Self { kind, value })
    }
}

/// What a remote may run on a device of a family.
#[derive(Debug)]
pub struct Runs {
    /// What `what` names in the project (a number or a name), with the words
    /// that say what it is ("macro 3 wave"); else what it holds none of
    /// ("no macro \"x\"").
    pub find: fn(&Project, &str) -> Result<Named, String>,
    /// What it keeps to run, as a remote's listing of the device shows it:
    /// each list under its key (`"macros"`), every key even when empty.
    pub listed: fn(&Project) -> Vec<Listed>,
}

/// One list a family keeps to run, under its key in a remote's listing of the device.
pub type Listed = (&'static str, Vec<serde_json::Value>);

/// What a remote named: what runs, and the words that say what it is.
pub type Named = (Run, String);

/// What a pose may move on a device of a family.
#[derive(Debug)]
pub struct Poses {
    /// The axes, each with the name a remote gives it.
    pub axes: fn(&Project) -> Vec<(String, Axis)>,
    /// An axis by another name it answers to (a servo's caption, a joint's device id).
    pub alias: fn(&Project, &str) -> Option<Axis>,
}

/// What a family may lack.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Capability {
    /// Playing in a show at all.
    Show,
    /// Running what it stores.
    Run,
    /// Posing an axis.
    Pose,
    /// Driving.
    Drive,
    /// Recording passes.
    Record,
}

/// A family refused, by name, what it cannot do.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{} {} cannot {}", article(self.family.name()), self.family.name(), self.lacks.verb())]
pub struct Lacks {
    /// The family.
    pub family: Family,
    /// What it cannot do.
    pub lacks: Capability,
}

impl Capability {
    fn verb(self) -> &'static str {
        match self {
            Self::Show => "play in a show",
            Self::Run => "run a stored macro or motion",
            Self::Pose => "pose a servo or joint",
            Self::Drive => "drive",
            Self::Record => "record a pass",
        }
    }
}

/// "a" or "an" before `name`, as it is said: "an Echo board", "an rFLEX
/// base" (an initialism read letter by letter), "a PLEN2", "a Servo board".
fn article(name: &str) -> &'static str {
    let mut letters = name.chars();
    let first = letters.next().unwrap_or('x').to_ascii_lowercase();
    let spelled = letters.next().is_some_and(|second| second.is_ascii_uppercase() || second.is_ascii_digit());
    if "aeiou".contains(first) || (spelled && "fhlmnrsx".contains(first)) { "an" } else { "a" }
}

/// `family`'s part of shows, or that it cannot play in one.
pub fn of(family: Family) -> Result<&'static ShowFamily, Lacks> {
    inventory::iter::<ShowFamily>
        .into_iter()
        .find(|entry| entry.family == family)
        .ok_or(Lacks { family, lacks: Capability::Show })
}

/// Every family's part of shows, as each registered it.
pub fn every() -> impl Iterator<Item = &'static ShowFamily> {
    inventory::iter::<ShowFamily>.into_iter()
}

/// Connects `device` on `port` as its family connects one, measuring its
/// link; an error when nothing answers there, or naming the family when it
/// plays in no show.
pub fn connect(port: &str, device: &Device) -> anyhow::Result<Linked> {
    let family = device.project.family;
    let entry = of(family)?;
    let name = PortName::parse(port)?;
    (entry.connect)(&name, &crate::device::line_settings(family), device)
}

/// What a remote may run on `family`'s devices, or that it runs nothing.
pub fn runs(family: Family) -> Result<&'static Runs, Lacks> {
    of(family)?.runs.as_ref().ok_or(Lacks { family, lacks: Capability::Run })
}

/// What a pose may move on `family`'s devices, or that it poses nothing.
pub fn poses(family: Family) -> Result<&'static Poses, Lacks> {
    of(family)?.poses.as_ref().ok_or(Lacks { family, lacks: Capability::Pose })
}

/// Whether `family` drives, or that it cannot.
pub fn drives(family: Family) -> Result<(), Lacks> {
    if of(family)?.drives { Ok(()) } else { Err(Lacks { family, lacks: Capability::Drive }) }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_family_is_named_with_the_article_it_is_said_with() {
        assert_eq!(article("PLEN2"), "a");
        assert_eq!(article("Servo board"), "a");
        assert_eq!(article("rFLEX base"), "an");
        assert_eq!(article("Echo board"), "an");
        assert_eq!(article("Dynamixel"), "a");
        let lacks = Lacks { family: Family::Plen2, lacks: Capability::Drive };
        assert_eq!(lacks.to_string(), "a PLEN2 cannot drive");
    }

    /// A family that registered nothing for shows (none of the real ones: one made up here).
    const BARE: Family = Family::named("bare", "Bare board");

    /// Each family that plays in shows says what it can do (the test-only
    /// echo board from its own folder); one that registered nothing is refused by name.
    #[test]
    fn each_family_says_what_it_can_do_and_one_that_says_nothing_is_refused_by_name() {
        assert!(runs(Family::Servo).is_ok() && poses(Family::Servo).is_ok() && drives(Family::Servo).is_err());
        assert!(runs(Family::Plen2).is_ok() && poses(Family::Plen2).is_ok());
        assert_eq!(drives(Family::Plen2).unwrap_err().to_string(), "a PLEN2 cannot drive");
        assert!(drives(Family::Rflex).is_ok());
        assert_eq!(poses(Family::Rflex).unwrap_err().to_string(), "an rFLEX base cannot pose a servo or joint");
        assert_eq!(runs(Family::Rflex).unwrap_err().lacks, Capability::Run);
        let echo = Family::from_tag("echo").expect("the test-only echo family is registered in unit tests");
        assert!(poses(echo).is_ok() && runs(echo).is_err() && drives(echo).is_err());
        assert_eq!(FamilyCue::named("move", 12.0).unwrap().kind, "move", "its kind of cue, registered");
        assert!(FamilyCue::named("jump", 1.0).unwrap_err().contains("no kind of cue is called \"jump\""));
        assert!(FamilyCue::named("move", f64::NAN).is_err());
        assert_eq!(of(BARE).unwrap_err().to_string(), "a Bare board cannot play in a show");
        assert_eq!(poses(BARE).unwrap_err().lacks, Capability::Show);
    }

    /// A cue's kind is read from its key: one no family registered is
    /// refused naming the key, never read as another kind.
    #[test]
    fn a_cue_of_a_kind_no_family_registered_is_refused_by_its_key() {
        use crate::project::Project;
        use crate::show::{Cue, Show};
        let mut show = Show::of_one("skull", Project::empty(Family::Servo));
        show.cues.push(Cue { device: "skull".into(), at_ms: 0, start: Start::Macro(1) });
        let text = show.to_json();
        assert!(text.contains("\"macro\": 1"), "{text}");
        let error = Show::from_text(&text.replace("\"macro\": 1", "\"jump\": 1"), "show.json").unwrap_err();
        assert!(error.to_string().contains("no kind of cue is called \"jump\""), "{error}");
        // The echo board's kind, read as its own, is not a servo board's to start.
        let moved = Show::from_text(&text.replace("\"macro\": 1", "\"move\": 12.5"), "show.json").unwrap_err();
        let crate::show::ShowError::NotHeld { start, .. } = moved else { panic!("{moved:?}") };
        assert_eq!(start, Start::Family(FamilyCue { kind: "move", value: 12.5 }));
    }

    /// A show holding a device of a family that plays in no show says so
    /// by name, and none of its cues is taken for another family's.
    #[test]
    fn a_show_with_a_device_that_plays_in_no_show_names_it() {
        use crate::project::Project;
        use crate::show::{Cue, Show, ShowError};
        let mut show = Show::of_one("skull", Project::empty(Family::Servo));
        show.add_device("bare", Project::empty(BARE));
        show.cues.push(Cue { device: "bare".into(), at_ms: 0, start: Start::Macro(1) });
        let problems = show.problems();
        assert!(matches!(&problems[0], ShowError::PlaysInNoShow { device, .. } if device == "bare"), "{problems:?}");
        assert_eq!(
            problems[0].to_string(),
            "device \"bare\": a Bare board cannot play in a show; remove it from the show"
        );
        assert!(matches!(&problems[1], ShowError::NotHeld { device, .. } if device == "bare"), "{problems:?}");
        assert_eq!(problems.len(), 2);
        // Nor is it posed as a servo board on the show's timeline.
        assert!(crate::show::timeline::posed_at(&show, 0, 0).is_some());
        assert_eq!(crate::show::timeline::posed_at(&show, 1, 0), None);
        assert_eq!(crate::show::timeline::now_at(&show, 1, 0, None), None);
    }
}
