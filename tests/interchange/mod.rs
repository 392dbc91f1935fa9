//! Other tools' files in and out (`servo_studio::interchange`, `servo-studio
//! convert`): each format read as its own tool plays it, checked against
//! figures worked out by hand from the tools' documented timing and units, and
//! against the official PLEN2 motions; malformed files said by line.

#![allow(clippy::unwrap_used)]

mod blender;
mod bounded;
mod cli;
mod damaged;
pub mod maestro;
mod real;
pub mod robotis;

use servo_studio::interchange::build::{self, Built, Options};
use servo_studio::interchange::{self, Format, JointMap, Source};
use servo_studio::project::Family;

/// `text` read as `format`, every channel mapped by the guess, built for `family`.
pub fn built(format: Format, text: &str, family: Family) -> (Source, JointMap, Built) {
    let source = interchange::read(format, text).unwrap();
    let map = JointMap::for_source(&source, family, None);
    let built = build::build(&source, &map, &Options::new(family)).unwrap();
    let problems = servo_studio::project::validate(&built.project);
    assert!(!servo_studio::project::has_errors(&problems), "the converted project passes check: {problems:?}");
    (source, map, built)
}
