//! Lists in a file are read up to what a board's count fields can say (a
//! 16-bit count: 32767 entries), so that a hostile file of millions of entries
//! is refused where it overflows instead of filling the memory.

use std::marker::PhantomData;

use serde::de::{Deserialize, Deserializer, SeqAccess, Visitor};

/// The most entries a list of a project file holds: a board's list counts are
/// 16-bit signed (`board.md` §2: actionCount, stepCount, servoCount… are i16).
pub const MAX_LIST_LEN: usize = i16::MAX as usize;

struct Bounded<T>(PhantomData<T>);

impl<'de, T: Deserialize<'de>> Visitor<'de> for Bounded<T> {
    type Value = Vec<T>;

    fn expecting(&self, formatter: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(formatter, "a list of at most {MAX_LIST_LEN} entries")
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Vec<T>, A::Error> {
        let mut items = Vec::with_capacity(seq.size_hint().unwrap_or(0).min(1024));
        while let Some(item) = seq.next_element()? {
            if items.len() == MAX_LIST_LEN {
                return Err(serde::de::Error::custom(format_args!(
                    "a list holds more than {MAX_LIST_LEN} entries, more than a board can count (its counts are 16-bit)"
                )));
            }
            items.push(item);
        }
        Ok(items)
    }
}

/// Deserializes a list of at most [`MAX_LIST_LEN`] entries (`deserialize_with`).
pub fn list<'de, D: Deserializer<'de>, T: Deserialize<'de>>(deserializer: D) -> Result<Vec<T>, D::Error> {
    deserializer.deserialize_seq(Bounded(PhantomData))
}

#[cfg(test)]
mod tests {
    #[derive(serde::Deserialize, Debug)]
    struct Holder {
        #[serde(deserialize_with = "super::list")]
        items: Vec<u8>,
    }

    #[test]
    fn a_list_longer_than_a_board_counts_is_refused_where_it_overflows() {
        let ok = format!("{{\"items\": [{}]}}", vec!["1"; super::MAX_LIST_LEN].join(","));
        assert_eq!(serde_json::from_str::<Holder>(&ok).unwrap().items.len(), super::MAX_LIST_LEN);
        let over = format!("{{\"items\": [{}]}}", vec!["1"; super::MAX_LIST_LEN + 5].join(","));
        let error = serde_json::from_str::<Holder>(&over).unwrap_err().to_string();
        assert!(error.starts_with("a list holds more than 32767 entries"), "{error}");
        // Just after the first entry too many (column 12 + 2 × 32767), not at the end of the list.
        assert!(error.contains(&format!("column {}", 13 + 2 * super::MAX_LIST_LEN)), "where it overflows: {error}");
    }
}
