//! What the device layer knows of a family, registered by the family itself
//! (`inventory::submit!` in `device/<family>/mod.rs`): how its line is set up
//! and how the connection doctor ([`super::probe`]) asks it who it is — its
//! [`Recogniser`], and what its devices say of themselves ([`Said`]). Nothing
//! here lists the families.

use std::any::Any;
use std::fmt;
use std::sync::Arc;

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

/// More line rates the doctor asks a family at, besides its own line's: a
/// family whose devices leave the factory at several (DYNAMIXEL servos: an
/// X-series at 57600, an AX at 1000000).
#[derive(Debug)]
pub struct MoreRates {
    /// The family.
    pub family: Family,
    /// The rates, in the order they are tried after its own.
    pub rates: &'static [u32],
}

inventory::collect!(MoreRates);

/// The rates the doctor asks `family` at: its line's, then any more it registered.
pub fn doctor_rates(family: Family, line_baud: u32) -> Vec<u32> {
    let more = inventory::iter::<MoreRates>.into_iter().filter(|entry| entry.family == family);
    std::iter::once(line_baud).chain(more.flat_map(|entry| entry.rates.iter().copied())).collect()
}

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

/// One family's side of the doctor, registered by the family
/// ([`super::family::Doctor`]): the requests that ask it who it is, and a
/// reader that recognises its replies in every byte that comes.
pub trait Recogniser: Send + fmt::Debug {
    /// The requests, in the order they go out; none changes anything on any family.
    fn requests(&self) -> Vec<Vec<u8>>;
    /// One of its requests goes out (for a reader that must know what it asked).
    fn asking(&mut self, _request: &[u8]) {}
    /// Bytes came (they may be any family's, or noise): what they said.
    fn read(&mut self, bytes: &[u8]) -> Vec<Heard>;
    /// The request was given up: forget a reply it began.
    fn abandon(&mut self) {}
}

/// What a family's reader heard.
#[derive(Debug)]
pub enum Heard {
    /// The device said who it is.
    Said(Identity),
    /// A request was answered with nothing more to tell (read for its timing).
    Answered,
}

/// What a device said of itself, in its family's own terms: each family
/// defines what its devices say (`device::servo::Said`, …) and words it.
pub trait Said: Any + Send + Sync + fmt::Debug + fmt::Display + SameSaid {
    /// The family it belongs to.
    fn family(&self) -> Family;
    /// What it says now merged with what it said before (a servo board
    /// answers two questions); `None`: the later answer stands alone.
    fn merged(&self, _earlier: &dyn Any) -> Option<Arc<dyn Said>> {
        None
    }
}

/// Equality of what was said, across the families' types.
pub trait SameSaid {
    /// Whether `other` is the same type and value.
    fn same(&self, other: &dyn Any) -> bool;
}

impl<T: PartialEq + 'static> SameSaid for T {
    fn same(&self, other: &dyn Any) -> bool {
        other.downcast_ref::<T>().is_some_and(|other| other == self)
    }
}

/// What a device said of itself.
#[derive(Clone, Debug)]
pub struct Identity(Arc<dyn Said>);

impl Identity {
    /// What a device of the family that defines `said` said.
    pub fn new(said: impl Said) -> Self {
        Self(Arc::new(said))
    }

    /// The family it belongs to.
    pub fn family(&self) -> Family {
        self.0.family()
    }

    /// What it said, as its family's type (`None` for another family's).
    pub fn said<T: Said>(&self) -> Option<&T> {
        let said: &dyn Any = &*self.0;
        said.downcast_ref()
    }

    /// This, merged with what the same device said `earlier`.
    pub(super) fn after(self, earlier: &Self) -> Self {
        let earlier: &dyn Any = &*earlier.0;
        self.0.merged(earlier).map_or(self, Self)
    }
}

impl PartialEq for Identity {
    fn eq(&self, other: &Self) -> bool {
        let other: &dyn Any = &*other.0;
        self.0.same(other)
    }
}

impl Eq for Identity {}

impl fmt::Display for Identity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.0.fmt(f)
    }
}
