//! Each robot's sensors as a datasheet gives them (rflex.md §6): sonar banks
//! and their sizes, each transducer's ring, bearing and mount, the range
//! scale, and the bump panels. A sonar id on the wire is `bank × 16 + index`;
//! transducer `k` counts through the banks in order. A fourth base type is
//! one more table here.

use std::f64::consts::PI;

/// Which ring a transducer belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Ring {
    /// A B21r's upper (body) ring.
    Body,
    /// A B21r's lower (base) ring.
    Base,
    /// An ATRV-Jr's rear bank.
    Rear,
    /// An ATRV-Jr's left side.
    Left,
    /// An ATRV-Jr's front bank.
    Front,
    /// An ATRV-Jr's right side.
    Right,
    /// A Magellan's one ring.
    Around,
}

impl Ring {
    /// Its name, as `rflex status` prints it.
    pub fn name(self) -> &'static str {
        match self {
            Self::Body => "body",
            Self::Base => "base",
            Self::Rear => "rear",
            Self::Left => "left",
            Self::Front => "front",
            Self::Right => "right",
            Self::Around => "ring",
        }
    }
}

/// Where a ring's transducers sit.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Placement {
    /// Evenly round a circle: the first faces `first_deg`, each next one
    /// `step_deg` further (negative: clockwise), mounted at `radius_m` along its bearing.
    Circle { first_deg: f64, step_deg: f64, radius_m: f64 },
    /// Each transducer by (x mm, y mm, bearing °), in order.
    Table(&'static [(f64, f64, f64)]),
}

/// A ring: the banks it takes (in order) and where their transducers sit.
#[derive(Clone, Debug, PartialEq)]
struct RingSpec {
    ring: Ring,
    banks: std::ops::Range<u8>,
    placement: Placement,
}

/// How a robot reports its bumpers in DIO_REPORT.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Bumps {
    /// One panel per address from `first` (`count` of them), the low 4 bits of data its pressed corners (B21r).
    Panels {
        /// The first panel's address.
        first: u16,
        /// How many panels.
        count: u16,
    },
    /// Each bit of data at the addresses from `first` one bumper (`bytes` addresses, Magellan).
    Bits {
        /// The first address.
        first: u16,
        /// How many addresses.
        bytes: u16,
    },
    /// No bumpers the drivers know.
    None,
}

/// One sonar transducer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transducer {
    /// Its id on the wire: bank × 16 + index.
    pub id: u8,
    /// Its number counting through the banks, from 0.
    pub number: u8,
    /// Its ring.
    pub ring: Ring,
    /// Where it faces, radians counter-clockwise from the base's heading.
    pub bearing_rad: f64,
    /// Where it is mounted, metres in the base's frame (x ahead, y left).
    pub mount_m: (f64, f64),
}

/// A robot's sensor layout.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Layout {
    /// Sonars in each bank, bank 0 first.
    pub banks: &'static [u8],
    /// Raw range units per metre.
    pub raw_per_m: f64,
    /// Its bumpers.
    pub bumps: Bumps,
    /// How far its body reaches from its centre, metres (for drawing it, and the
    /// emulated room's walls it cannot pass).
    pub body_radius_m: f64,
    rings: &'static [RingSpec],
}

/// Above this a raw range means no echo.
pub const NO_ECHO_RAW: u16 = 3000;

/// A B21r: a body ring of 24 in six banks of four and a base ring of 24 in
/// eight banks of three, both clockwise; 14 bump panels.
pub const B21R: Layout = Layout {
    banks: &[4, 4, 4, 4, 4, 4, 3, 3, 3, 3, 3, 3, 3, 3],
    raw_per_m: 1476.0,
    bumps: Bumps::Panels { first: 0x40, count: 14 },
    body_radius_m: 0.26,
    rings: &[
        RingSpec {
            ring: Ring::Body,
            banks: 0..6,
            placement: Placement::Circle { first_deg: 172.5, step_deg: -15.0, radius_m: 0.25 },
        },
        RingSpec {
            ring: Ring::Base,
            banks: 6..14,
            placement: Placement::Circle { first_deg: 240.0, step_deg: -15.0, radius_m: 0.26 },
        },
    ],
};

/// An ATRV-Jr: 26 sonars in banks of 5, 8, 5, 8 (rear, left, front, right), each placed by the table; no bump panels.
pub const ATRV_JR: Layout = Layout {
    banks: &[5, 8, 5, 8],
    raw_per_m: 1476.0,
    bumps: Bumps::None,
    // Half its diagonal: 0.35 m reaches its rear sonars' mounts.
    body_radius_m: 0.40,
    rings: &[
        RingSpec {
            ring: Ring::Rear,
            banks: 0..1,
            placement: Placement::Table(&[
                (-334.95, -104.39, -150.0),
                (-340.41, -49.91, -165.0),
                (-347.06, 0.0, 180.0),
                (-340.41, 49.91, 165.0),
                (-334.95, 104.39, 150.0),
            ]),
        },
        RingSpec {
            ring: Ring::Left,
            banks: 1..2,
            placement: Placement::Table(&[
                (230.23, 175.0, 45.0),
                (172.49, 178.6, 60.0),
                (117.2, 181.1, 75.0),
                (72.26, 181.1, 90.0),
                (-72.26, 181.1, 90.0),
                (-117.2, 181.1, 105.0),
                (-172.49, 178.6, 120.0),
                (-230.23, 175.0, 135.0),
            ]),
        },
        RingSpec {
            ring: Ring::Front,
            banks: 2..3,
            placement: Placement::Table(&[
                (296.2, 103.6, 30.0),
                (301.5, 49.5, 15.0),
                (308.1, 0.0, 0.0),
                (301.5, -49.5, -15.0),
                (296.2, -103.6, -30.0),
            ]),
        },
        RingSpec {
            ring: Ring::Right,
            banks: 3..4,
            placement: Placement::Table(&[
                (230.23, -175.0, -45.0),
                (172.49, -178.6, -60.0),
                (117.2, -181.1, -75.0),
                (72.26, -181.1, -90.0),
                (-72.26, -181.1, -90.0),
                (-117.2, -181.1, -105.0),
                (-172.49, -178.6, -120.0),
                (-230.23, -175.0, -135.0),
            ]),
        },
    ],
};

/// A Magellan: 16 sonars in two banks of eight, one clockwise ring; 16 bumpers as bits.
pub const MAGELLAN: Layout = Layout {
    banks: &[8, 8],
    raw_per_m: 1474.0,
    bumps: Bumps::Bits { first: 0x40, bytes: 2 },
    body_radius_m: 0.20,
    rings: &[RingSpec {
        ring: Ring::Around,
        banks: 0..2,
        placement: Placement::Circle { first_deg: 247.5, step_deg: -22.5, radius_m: 0.20 },
    }],
};

/// One bumper pressed, as a robot's style names it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Bump {
    /// Panel `panel` (from 0), with these corners pressed (low 4 bits).
    Panel {
        /// The panel.
        panel: u16,
        /// Its pressed corners.
        corners: u8,
    },
    /// Bumper `bumper` (from 0).
    Bit {
        /// The bumper.
        bumper: u16,
    },
}

impl Layout {
    /// How many banks report: a sweep is whole when each has.
    pub fn bank_count(&self) -> u8 {
        u8::try_from(self.banks.len()).unwrap_or(u8::MAX)
    }

    /// The sonar ids of bank `bank`.
    pub fn bank_ids(&self, bank: u8) -> impl Iterator<Item = u8> + '_ {
        let size = self.banks.get(usize::from(bank)).copied().unwrap_or(0);
        (0..size).map(move |index| bank * 16 + index)
    }

    /// The DIO addresses its bumpers report at.
    pub fn bump_addresses(&self) -> std::ops::Range<u16> {
        match self.bumps {
            Bumps::Panels { first, count } => first..first + count,
            Bumps::Bits { first, bytes } => first..first + bytes,
            Bumps::None => 0..0,
        }
    }

    /// How many transducers it has.
    pub fn sonar_count(&self) -> usize {
        self.banks.iter().map(|&size| usize::from(size)).sum()
    }

    /// The transducer that reports as `id`, or `None` for an id this robot does not have.
    pub fn transducer(&self, id: u8) -> Option<Transducer> {
        let (bank, index) = (id / 16, id % 16);
        if index >= *self.banks.get(usize::from(bank))? {
            return None;
        }
        let before = |bank: u8| self.banks[..usize::from(bank)].iter().map(|&size| u16::from(size)).sum::<u16>();
        let number = u8::try_from(before(bank) + u16::from(index)).ok()?;
        let spec = self.rings.iter().find(|spec| spec.banks.contains(&bank))?;
        let in_ring = usize::from(number) - usize::from(before(spec.banks.start));
        let (bearing_rad, mount_m) = match spec.placement {
            Placement::Circle { first_deg, step_deg, radius_m } => {
                // A ring has at most a few dozen transducers: exact in f64.
                #[allow(clippy::cast_precision_loss)]
                let bearing = (first_deg + step_deg * in_ring as f64).to_radians();
                (bearing, (radius_m * bearing.cos(), radius_m * bearing.sin()))
            }
            Placement::Table(table) => {
                let (x_mm, y_mm, deg) = *table.get(in_ring)?;
                (deg.to_radians(), (x_mm / 1000.0, y_mm / 1000.0))
            }
        };
        Some(Transducer { id, number, ring: spec.ring, bearing_rad: normalised(bearing_rad), mount_m })
    }

    /// Every transducer, in number order.
    pub fn transducers(&self) -> Vec<Transducer> {
        let mut out = Vec::new();
        for (bank, &size) in (0u8..).zip(self.banks) {
            out.extend((0..size).filter_map(|index| self.transducer(bank * 16 + index)));
        }
        out
    }

    /// A raw range in metres; `None` for no echo.
    pub fn range_m(&self, raw: u16) -> Option<f64> {
        (raw <= NO_ECHO_RAW).then(|| f64::from(raw) / self.raw_per_m)
    }

    /// What a DIO report at `address` with `data` says of the bumpers, or
    /// `None` when the address is not a bumper's.
    pub fn bumps(&self, address: u16, data: u16) -> Option<Vec<Bump>> {
        match self.bumps {
            Bumps::Panels { first, count } if (first..first + count).contains(&address) => {
                // The mask is the point: the low 4 bits are the corners.
                #[allow(clippy::cast_possible_truncation)]
                let corners = (data & 0x0f) as u8;
                Some(if corners == 0 { Vec::new() } else { vec![Bump::Panel { panel: address - first, corners }] })
            }
            Bumps::Bits { first, bytes } if (first..first + bytes).contains(&address) => Some(
                (0..8)
                    .filter(|bit| data & (1 << bit) != 0)
                    .map(|bit| Bump::Bit { bumper: (address - first) * 8 + bit })
                    .collect(),
            ),
            _ => None,
        }
    }
}

/// An angle in (−π, π].
fn normalised(angle: f64) -> f64 {
    let wrapped = angle.rem_euclid(2.0 * PI);
    if wrapped > PI { wrapped - 2.0 * PI } else { wrapped }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn degrees(transducer: &Transducer) -> f64 {
        (transducer.bearing_rad.to_degrees() * 1000.0).round() / 1000.0
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() < 1e-9
    }

    #[test]
    fn a_b21rs_two_rings_are_banks_of_four_and_three_going_clockwise() {
        assert_eq!(B21R.sonar_count(), 48);
        // Ids 16–19 are transducers 4–7, facing 112.5° … 67.5°.
        let second_bank: Vec<(u8, f64)> =
            (16..20).map(|id| B21R.transducer(id).unwrap()).map(|t| (t.number, degrees(&t))).collect();
        assert_eq!(second_bank, [(4, 112.5), (5, 97.5), (6, 82.5), (7, 67.5)]);
        assert!(B21R.transducer(4).is_none(), "bank 0 holds four: id 4 is not a sonar");
        assert!(B21R.transducer(99).is_none(), "bank 6 holds three");
        let first = B21R.transducer(0).unwrap();
        assert_eq!((first.ring, degrees(&first)), (Ring::Body, 172.5));
        assert!(close(first.mount_m.0, 0.25 * 172.5f64.to_radians().cos()));
        // The base ring: ids 96–98 are transducers 24–26, from 240° (= −120°).
        let base = B21R.transducer(96).unwrap();
        assert_eq!((base.number, base.ring, degrees(&base)), (24, Ring::Base, -120.0));
        assert!(close(base.mount_m.0.hypot(base.mount_m.1), 0.26));
        let last = B21R.transducer(210).unwrap();
        assert_eq!(last.number, 47);
        let ids: Vec<u8> = B21R.transducers().iter().map(|t| t.id).collect();
        assert_eq!(&ids[..8], [0, 1, 2, 3, 16, 17, 18, 19]);
        assert_eq!(ids.len(), 48);
    }

    #[test]
    fn an_atrv_jrs_sonars_are_placed_by_its_table() {
        assert_eq!(ATRV_JR.sonar_count(), 26);
        // Id 34 (bank 2, index 2): the front centre sonar at (0.308 m, 0), facing 0°.
        let front = ATRV_JR.transducer(34).unwrap();
        assert_eq!((front.number, front.ring, degrees(&front)), (15, Ring::Front, 0.0));
        assert!(close(front.mount_m.0, 0.3081) && close(front.mount_m.1, 0.0));
        let rear = ATRV_JR.transducer(2).unwrap();
        assert_eq!((rear.ring, degrees(&rear)), (Ring::Rear, 180.0));
        let right = ATRV_JR.transducer(55).unwrap();
        assert_eq!((right.number, right.ring, degrees(&right)), (25, Ring::Right, -135.0));
        assert!(ATRV_JR.transducer(5).is_none() && ATRV_JR.transducer(37).is_none());
        assert_eq!(ATRV_JR.bumps(0x40, 0xff), None, "no bump panels");
    }

    #[test]
    fn a_magellans_ring_range_scale_and_bumper_bits() {
        assert_eq!(MAGELLAN.sonar_count(), 16);
        assert_eq!(MAGELLAN.range_m(1474), Some(1.0));
        assert_eq!(B21R.range_m(1476), Some(1.0));
        assert_eq!(MAGELLAN.range_m(3001), None, "no echo");
        let first = MAGELLAN.transducer(0).unwrap();
        assert_eq!(degrees(&first), -112.5, "247.5°");
        assert_eq!(degrees(&MAGELLAN.transducer(23).unwrap()), -90.0, "transducer 15: 247.5 − 337.5");
        assert!(MAGELLAN.transducer(8).is_none());
        assert_eq!(MAGELLAN.bumps(0x41, 0b1000_0001), Some(vec![Bump::Bit { bumper: 8 }, Bump::Bit { bumper: 15 }]));
        assert_eq!(MAGELLAN.bumps(0x42, 1), None, "not a bumper's address");
        assert_eq!(B21R.bumps(0x4d, 0x35), Some(vec![Bump::Panel { panel: 13, corners: 5 }]));
        assert_eq!(B21R.bumps(0x40, 0x30), Some(vec![]), "no corner pressed");
        assert_eq!(B21R.bumps(0x4e, 1), None);
    }
}
