//! What the device layer knows of a family, registered by the family itself
//! (`inventory::submit!` in `device/<family>/mod.rs`): how its line is set up
//! and how the connection doctor asks it who it is. Nothing here lists them.

use super::probe::Recogniser;
use crate::link::LineSettings;
use crate::project::Family;

/// A family's part of the device layer.
#[derive(Debug)]
pub struct Registered {
    /// The family.
    pub family: Family,
    /// How the line to its board is set up (line rate, DTR/RTS, write gap).
    pub line: fn() -> LineSettings,
    /// How the doctor asks it who it is; `None`: the doctor does not ask.
    pub doctor: Option<Doctor>,
}

/// How the connection doctor asks one family who it is.
#[derive(Debug)]
pub struct Doctor {
    /// Its place in the doctor's order (lowest is asked first).
    pub rank: u8,
    /// A fresh reader of its replies, which also holds its requests.
    pub recogniser: fn() -> Box<dyn Recogniser>,
}

inventory::collect!(Registered);

/// The device layer's entry of `family`, if it registered one.
pub fn registered(family: Family) -> Option<&'static Registered> {
    inventory::iter::<Registered>.into_iter().find(|entry| entry.family == family)
}

/// The families the doctor asks, in its order.
pub fn doctored() -> Vec<(Family, &'static Doctor)> {
    let mut families: Vec<(Family, &'static Doctor)> = inventory::iter::<Registered>
        .into_iter()
        .filter_map(|entry| entry.doctor.as_ref().map(|doctor| (entry.family, doctor)))
        .collect();
    families.sort_by_key(|(_, doctor)| doctor.rank);
    families
}

/// How the line to a board of `family` is set up: what the family registered,
/// or, for a family that registered none, a plain line at the usual rate.
pub fn line_settings(family: Family) -> LineSettings {
    registered(family).map_or_else(|| LineSettings::new(115_200), |entry| (entry.line)())
}
