//! Values of the add-on's export read loosely: a key whose value is not
//! what the add-on writes there is passed over, never an error (a top-level
//! number or string, Servo Studio's own unit key).

use std::fmt;

use serde::de::{self, IgnoredAny, MapAccess, SeqAccess, Visitor};

use super::super::source::Unit;

/// A top-level scalar (fps, scene), anything else passed over.
#[derive(Default)]
pub struct Scalar {
    /// It, when a number.
    pub number: Option<f64>,
    /// It, when a string.
    pub text: Option<String>,
}

impl<'de> de::Deserialize<'de> for Scalar {
    fn deserialize<D: de::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_any(ScalarVisitor)
    }
}

/// Any value as a [`Scalar`]: numbers and strings kept, the rest passed over.
pub struct ScalarVisitor;

impl<'de> Visitor<'de> for ScalarVisitor {
    type Value = Scalar;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a value")
    }

    fn visit_f64<E>(self, value: f64) -> Result<Scalar, E> {
        Ok(Scalar { number: Some(value), text: None })
    }

    // JSON integers past 2^53 are read as the nearest float, as JavaScript reads them.
    #[allow(clippy::cast_precision_loss)]
    fn visit_i64<E>(self, value: i64) -> Result<Scalar, E> {
        Ok(Scalar { number: Some(value as f64), text: None })
    }

    #[allow(clippy::cast_precision_loss)]
    fn visit_u64<E>(self, value: u64) -> Result<Scalar, E> {
        Ok(Scalar { number: Some(value as f64), text: None })
    }

    fn visit_str<E>(self, value: &str) -> Result<Scalar, E> {
        Ok(Scalar { number: None, text: Some(value.to_string()) })
    }

    fn visit_bool<E>(self, _: bool) -> Result<Scalar, E> {
        Ok(Scalar::default())
    }

    fn visit_unit<E>(self) -> Result<Scalar, E> {
        Ok(Scalar::default())
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Scalar, A::Error> {
        while seq.next_element::<IgnoredAny>()?.is_some() {}
        Ok(Scalar::default())
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Scalar, A::Error> {
        while map.next_entry::<IgnoredAny, IgnoredAny>()?.is_some() {}
        Ok(Scalar::default())
    }
}

/// Servo Studio's unit key: `zero` and `per_degree` when both are numbers.
#[derive(Default)]
pub struct UnitHint {
    zero: Option<f64>,
    per_degree: Option<f64>,
}

impl UnitHint {
    /// The unit it says, when both are numbers and it is one.
    pub fn unit(self) -> Option<Unit> {
        let (zero, per_degree) = (self.zero?, self.per_degree?);
        (per_degree != 0.0 && zero.is_finite() && per_degree.is_finite()).then_some(Unit {
            zero,
            per_degree,
            label: "as written",
        })
    }
}

impl<'de> de::Deserialize<'de> for UnitHint {
    fn deserialize<D: de::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Hint;
        impl<'de> Visitor<'de> for Hint {
            type Value = UnitHint;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a unit")
            }
            fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<UnitHint, A::Error> {
                let mut hint = UnitHint::default();
                while let Some(key) = map.next_key::<String>()? {
                    let value = map.next_value::<Scalar>()?.number;
                    match key.as_str() {
                        "zero" => hint.zero = value,
                        "per_degree" => hint.per_degree = value,
                        _ => {}
                    }
                }
                Ok(hint)
            }
            // Anything else says no unit.
            fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<UnitHint, A::Error> {
                ScalarVisitor.visit_seq(seq).map(|_| UnitHint::default())
            }
            fn visit_str<E>(self, _: &str) -> Result<UnitHint, E> {
                Ok(UnitHint::default())
            }
            fn visit_f64<E>(self, _: f64) -> Result<UnitHint, E> {
                Ok(UnitHint::default())
            }
            fn visit_i64<E>(self, _: i64) -> Result<UnitHint, E> {
                Ok(UnitHint::default())
            }
            fn visit_u64<E>(self, _: u64) -> Result<UnitHint, E> {
                Ok(UnitHint::default())
            }
            fn visit_bool<E>(self, _: bool) -> Result<UnitHint, E> {
                Ok(UnitHint::default())
            }
            fn visit_unit<E>(self) -> Result<UnitHint, E> {
                Ok(UnitHint::default())
            }
        }
        deserializer.deserialize_any(Hint)
    }
}
