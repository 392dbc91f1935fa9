//! Control tables, as the ROBOTIS e-Manual lays them out (XL430-W250 and
//! XM430-W350: "Control Table of EEPROM Area" and "of RAM Area"; AX-12A: its
//! control table): address, size, factory value, and whether a controller
//! may write it. The emulator serves these tables (a field written outside
//! them is refused as the servos refuse it); the driver reads and writes a
//! servo through its model's [`Addresses`], found by the model number its
//! ping or its first bytes say ([`known`]).

use super::Protocol;

/// One field of a control table.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Field {
    /// Its address.
    pub addr: u16,
    /// Its size in bytes (1, 2 or 4, little-endian).
    pub size: u8,
    /// Its value at the factory.
    pub default: u32,
    /// Whether a controller may write it.
    pub writable: bool,
}

const fn r(addr: u16, size: u8, default: u32) -> Field {
    Field { addr, size, default, writable: false }
}

const fn w(addr: u16, size: u8, default: u32) -> Field {
    Field { addr, size, default, writable: true }
}

/// A model: its number, protocol and control table.
#[derive(Debug)]
pub struct Model {
    /// Its model number (what a ping answers).
    pub number: u16,
    /// Its name.
    pub name: &'static str,
    /// The protocol it speaks.
    pub protocol: Protocol,
    /// Its firmware version, as emulated (what the driver reads is the servo's own).
    pub firmware: u8,
    /// Its control table.
    pub fields: &'static [Field],
    /// Where its table's fields are (their addresses).
    pub at: Addresses,
    /// Position units in a turn (4096 for X-series; the AX's 1024 span 300°).
    pub units_per_turn: f64,
    /// Its top speed, position units a second, with no profile (or speed) set.
    pub top_speed: f64,
}

/// Where a model keeps what the driver and the emulator read and write.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Addresses {
    /// Its ID.
    pub id: u16,
    /// Its return delay time (2 µs units).
    pub return_delay: u16,
    /// Its status return level (0: ping only, 1: and reads, 2: all).
    pub status_return: u16,
    /// Torque enable: the EEPROM area (below it, on X-series) is locked while on.
    pub torque: u16,
    /// Its goal position.
    pub goal: u16,
    /// Its profile velocity (X) or moving speed (AX): 0 is top speed.
    pub speed: u16,
    /// Its present position.
    pub present: u16,
    /// Moving (1 while it moves).
    pub moving: u16,
    /// Hardware error status (X) or none (AX: errors ride in the status's error byte).
    pub hardware_error: Option<u16>,
    /// Its present temperature, °C.
    pub temperature: u16,
    /// The EEPROM area ends here: written only with the torque off (X-series).
    pub eeprom_end: Option<u16>,
    /// Speed units, position units a second for one unit of `speed`.
    pub speed_unit: f64,
    /// Its LED (1 lit).
    pub led: u16,
    /// Its position limits: (the lowest, the highest) position's fields.
    pub limits: (u16, u16),
    /// Its temperature limit, °C.
    pub temperature_limit: u16,
    /// Its present load (X: signed, 0.1 % a unit; AX: 0..=1023 and bit 10 the direction).
    pub load: u16,
    /// Its present input voltage (X: 2 bytes, AX: 1 byte; 0.1 V a unit).
    pub voltage: u16,
    /// Its profile acceleration (X), none on the AX.
    pub acceleration: Option<u16>,
    /// The size of a position field (4 on 2.0, 2 on 1.0).
    pub position_size: u8,
    /// Its Shutdown field (which errors let the torque go).
    pub shutdown: u16,
}

/// XL430-W250: Protocol 2.0, 4096 a turn.
pub static XL430_W250: Model = x_model("XL430-W250", &X_SERIES_XL);

/// XM430-W350: Protocol 2.0, 4096 a turn.
pub static XM430_W350: Model = x_model("XM430-W350", &X_SERIES_XM);

/// An X-series model whose table is `fields`: its model number and its top
/// speed (its Velocity Limit, 0.229 rev/min a unit) read from the table.
// A model number is a 2-byte field.
#[allow(clippy::cast_possible_truncation)]
const fn x_model(name: &'static str, fields: &'static [Field; 35]) -> Model {
    Model {
        number: factory(fields, 0) as u16,
        name,
        protocol: Protocol::Two,
        firmware: X_FIRMWARE,
        fields,
        at: X_AT,
        units_per_turn: 4096.0,
        top_speed: factory(fields, 44) as f64 * X_AT.speed_unit,
    }
}

/// The factory value of the field at `addr` of `fields` (0 where none is).
const fn factory(fields: &[Field], addr: u16) -> u32 {
    let mut index = 0;
    while index < fields.len() {
        if fields[index].addr == addr {
            return fields[index].default;
        }
        index += 1;
    }
    0
}

/// The X-series firmware version emulated.
const X_FIRMWARE: u8 = 46;

/// AX-12A: Protocol 1.0, 1024 over 300°.
pub static AX_12A: Model = Model {
    number: 12,
    name: "AX-12A",
    protocol: Protocol::One,
    firmware: 24,
    fields: &AX_FIELDS,
    at: Addresses {
        id: 3,
        return_delay: 5,
        status_return: 16,
        torque: 24,
        goal: 30,
        speed: 32,
        present: 36,
        moving: 46,
        hardware_error: None,
        temperature: 43,
        eeprom_end: None,
        // 0.111 rev/min a unit, 1024 units over 300° (1228.8 a turn).
        speed_unit: 0.111 / 60.0 * 1228.8,
        led: 25,
        // CW Angle Limit, CCW Angle Limit.
        limits: (6, 8),
        temperature_limit: 11,
        load: 40,
        voltage: 42,
        acceleration: None,
        position_size: 2,
        shutdown: 18,
    },
    units_per_turn: 1228.8,
    // 114 rev/min, its no-load speed at 12 V.
    top_speed: 114.0 / 60.0 * 1228.8,
};

/// Every model whose whole table is kept here (what the emulator can be).
pub static MODELS: [&Model; 3] = [&XL430_W250, &XM430_W350, &AX_12A];

const X_AT: Addresses = Addresses {
    id: 7,
    return_delay: 9,
    status_return: 68,
    torque: 64,
    goal: 116,
    speed: 112,
    present: 132,
    moving: 122,
    hardware_error: Some(70),
    temperature: 146,
    eeprom_end: Some(64),
    // 0.229 rev/min a unit.
    speed_unit: 0.229 / 60.0 * 4096.0,
    led: 65,
    // Min Position Limit, Max Position Limit.
    limits: (52, 48),
    temperature_limit: 31,
    load: 126,
    voltage: 144,
    acceleration: Some(108),
    position_size: 4,
    shutdown: 63,
};

static X_SERIES_XL: [Field; 35] = x_series(1060, 72, 140, 60, 265);
static X_SERIES_XM: [Field; 35] = x_series(1020, 80, 160, 95, 200);

/// An X-series table; what differs between the models as arguments.
const fn x_series(
    model: u32,
    temperature_limit: u32,
    max_volts: u32,
    min_volts: u32,
    velocity_limit: u32,
) -> [Field; 35] {
    [
        r(0, 2, model),
        r(2, 4, 0),
        r(6, 1, X_FIRMWARE as u32),
        w(7, 1, 1),
        w(8, 1, 1),
        w(9, 1, 250),
        w(10, 1, 0),
        w(11, 1, 3),
        w(12, 1, 255),
        w(13, 1, 2),
        w(20, 4, 0),
        w(24, 4, 10),
        w(31, 1, temperature_limit),
        w(32, 2, max_volts),
        w(34, 2, min_volts),
        w(36, 2, 885),
        w(44, 4, velocity_limit),
        w(48, 4, 4095),
        w(52, 4, 0),
        w(63, 1, 52),
        w(64, 1, 0),
        w(65, 1, 0),
        w(68, 1, 2),
        r(69, 1, 0),
        r(70, 1, 0),
        w(104, 4, 0),
        w(108, 4, 0),
        w(112, 4, 0),
        w(116, 4, 2048),
        r(122, 1, 0),
        r(126, 2, 0),
        r(128, 4, 0),
        r(132, 4, 2048),
        r(144, 2, 120),
        r(146, 1, 32),
    ]
}

const AX_FIELDS: [Field; 32] = [
    r(0, 2, 12),
    r(2, 1, 24),
    w(3, 1, 1),
    w(4, 1, 1),
    w(5, 1, 250),
    w(6, 2, 0),
    w(8, 2, 1023),
    w(11, 1, 70),
    w(12, 1, 60),
    w(13, 1, 140),
    w(14, 2, 1023),
    w(16, 1, 2),
    w(17, 1, 36),
    w(18, 1, 36),
    w(24, 1, 0),
    w(25, 1, 0),
    w(26, 1, 1),
    w(27, 1, 1),
    w(28, 1, 32),
    w(29, 1, 32),
    w(30, 2, 512),
    w(32, 2, 0),
    w(34, 2, 1023),
    r(36, 2, 512),
    r(38, 2, 0),
    r(40, 2, 0),
    r(42, 1, 120),
    r(43, 1, 32),
    r(44, 1, 0),
    r(46, 1, 0),
    w(47, 1, 0),
    w(48, 2, 32),
];

impl Model {
    /// The table's bytes as the factory leaves them (addresses no field covers read 0).
    pub fn factory(&self) -> Vec<u8> {
        let end = self.fields.iter().map(|field| usize::from(field.addr) + usize::from(field.size)).max().unwrap_or(0);
        let mut bytes = vec![0; end];
        for field in self.fields {
            let at = usize::from(field.addr);
            bytes[at..at + usize::from(field.size)]
                .copy_from_slice(&field.default.to_le_bytes()[..usize::from(field.size)]);
        }
        bytes
    }

    /// Whether a controller may write `len` bytes at `addr`: every byte in a writable field.
    pub fn writable(&self, addr: u16, len: usize) -> bool {
        (usize::from(addr)..usize::from(addr) + len).all(|byte| {
            self.fields.iter().any(|field| {
                field.writable
                    && (usize::from(field.addr)..usize::from(field.addr) + usize::from(field.size)).contains(&byte)
            })
        })
    }
}

/// How a model family lays out its control table, as the driver reads it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Layout {
    /// Where its fields are.
    pub at: Addresses,
    /// Position units in a turn (X and MX: 4096; AX: 1024 over 300°, 1228.8 a turn).
    pub units_per_turn: f64,
    /// The highest position (X and MX: 4095; AX: 1023).
    pub top_position: u32,
}

/// The X-series layout (MX 2.0 and the XL330 keep the same addresses).
pub const X_LAYOUT: Layout = Layout { at: X_AT, units_per_turn: 4096.0, top_position: 4095 };
/// The AX layout (AX-12, AX-18).
pub const AX_LAYOUT: Layout = Layout { at: AX_12A.at, units_per_turn: 1228.8, top_position: 1023 };
/// The XL-320 (Protocol 2.0, 1024 over 300°): the AX's first addresses
/// (limits, torque, LED, goal at 30, speed at 32), then its own — present
/// position at 37, load at 41, voltage at 45, temperature at 46, moving at
/// 49, Hardware Error Status at 50 (its e-Manual's control table).
pub const XL320_LAYOUT: Layout = Layout {
    at: Addresses {
        id: 3,
        return_delay: 5,
        status_return: 17,
        torque: 24,
        goal: 30,
        speed: 32,
        present: 37,
        moving: 49,
        hardware_error: Some(50),
        temperature: 46,
        eeprom_end: Some(24),
        speed_unit: 0.111 / 60.0 * 1228.8,
        led: 25,
        limits: (6, 8),
        temperature_limit: 12,
        load: 41,
        voltage: 45,
        acceleration: None,
        position_size: 2,
        shutdown: 18,
    },
    units_per_turn: 1228.8,
    top_position: 1023,
};
/// MX on Protocol 1.0: the AX's addresses, 4096 over 360°.
pub const MX_ONE_LAYOUT: Layout = Layout { at: AX_12A.at, units_per_turn: 4096.0, top_position: 4095 };

/// A model a scan may find, by the number its control table starts with.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Known {
    /// Its model number.
    pub number: u16,
    /// Its name, as ROBOTIS writes it.
    pub name: &'static str,
    /// How its table is laid out.
    pub layout: Layout,
}

/// The models the driver knows by number (the e-Manual's "Model Number" of
/// each): Bioloid's AX and MX 1.0, and the X-series and MX 2.0 labs build with.
pub static KNOWN: [Known; 20] = [
    Known { number: 12, name: "AX-12A", layout: AX_LAYOUT },
    Known { number: 300, name: "AX-12W", layout: AX_LAYOUT },
    Known { number: 18, name: "AX-18A", layout: AX_LAYOUT },
    Known { number: 350, name: "XL-320", layout: XL320_LAYOUT },
    Known { number: 29, name: "MX-28", layout: MX_ONE_LAYOUT },
    Known { number: 310, name: "MX-64", layout: MX_ONE_LAYOUT },
    Known { number: 320, name: "MX-106", layout: MX_ONE_LAYOUT },
    Known { number: 30, name: "MX-28(2.0)", layout: X_LAYOUT },
    Known { number: 311, name: "MX-64(2.0)", layout: X_LAYOUT },
    Known { number: 321, name: "MX-106(2.0)", layout: X_LAYOUT },
    Known { number: 1060, name: "XL430-W250", layout: X_LAYOUT },
    Known { number: 1090, name: "2XL430-W250", layout: X_LAYOUT },
    Known { number: 1190, name: "XL330-M077", layout: X_LAYOUT },
    Known { number: 1200, name: "XL330-M288", layout: X_LAYOUT },
    Known { number: 1020, name: "XM430-W350", layout: X_LAYOUT },
    Known { number: 1030, name: "XM430-W210", layout: X_LAYOUT },
    Known { number: 1010, name: "XH430-W210", layout: X_LAYOUT },
    Known { number: 1000, name: "XH430-W350", layout: X_LAYOUT },
    Known { number: 1120, name: "XM540-W270", layout: X_LAYOUT },
    Known { number: 1110, name: "XM540-W150", layout: X_LAYOUT },
];

/// The model numbered `number`, if the driver knows its table.
pub fn known(number: u16) -> Option<&'static Known> {
    KNOWN.iter().find(|model| model.number == number)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What the driver reads of a model agrees with the table the emulator serves.
    #[test]
    fn each_kept_table_is_known_by_its_number_with_the_same_addresses() {
        for model in MODELS {
            let known = known(model.number).unwrap();
            assert_eq!(known.name, model.name);
            assert_eq!(known.layout.at, model.at);
            assert!((known.layout.units_per_turn - model.units_per_turn).abs() < 1e-9);
            let sized = |addr: u16| model.fields.iter().find(|field| field.addr == addr).map(|field| field.size);
            let at = model.at;
            assert_eq!(sized(at.goal), Some(at.position_size), "{}", model.name);
            assert_eq!(sized(at.present), Some(at.position_size), "{}", model.name);
            for addr in [at.led, at.limits.0, at.limits.1, at.temperature_limit, at.load, at.voltage, at.shutdown] {
                assert!(sized(addr).is_some(), "{}: no field at {addr}", model.name);
            }
        }
        assert_eq!(known(7), None);
    }
}
