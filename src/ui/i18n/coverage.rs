//! Every language has every word: each file has the keys English has (the
//! reference), with the same holes, translated; every key the program asks
//! for is in it.

use std::collections::BTreeSet;

use super::{Catalogue, Language, Table, holes};

/// Every key the program's sources name in `say!(…, "key"…)` and `.word("key")`.
fn keys_in_sources() -> BTreeSet<String> {
    let mut keys = BTreeSet::new();
    let mut folders = vec![std::path::PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/src"))];
    while let Some(folder) = folders.pop() {
        for entry in std::fs::read_dir(&folder).unwrap().map(Result::unwrap) {
            let path = entry.path();
            if path.is_dir() {
                folders.push(path);
            } else if path.extension().is_some_and(|ext| ext == "rs") {
                keys.extend(named_keys(&std::fs::read_to_string(&path).unwrap()));
            }
        }
    }
    keys
}

/// The keys `text` names: the first string after `say!(language,` or in `.word(`.
fn named_keys(text: &str) -> Vec<String> {
    let mut keys = Vec::new();
    for (marker, skip_argument) in [("say!(", true), (".word(", false)] {
        for (at, _) in text.match_indices(marker) {
            let mut rest = &text[at + marker.len()..];
            if skip_argument {
                let Some(comma) = rest.find(',') else { continue };
                rest = &rest[comma + 1..];
            }
            let rest = rest.trim_start();
            let Some(quoted) = rest.strip_prefix('"') else { continue };
            let Some(end) = quoted.find('"') else { continue };
            let key = &quoted[..end];
            if key.contains('.') && !key.contains(' ') && !key.contains('{') {
                keys.push(key.to_string());
            }
        }
    }
    keys
}

fn english_keys() -> BTreeSet<String> {
    Catalogue::of(Language::English).keys().into_iter().collect()
}

#[test]
fn every_language_has_every_key_of_english_and_no_other() {
    let english = english_keys();
    assert!(english.len() > 700, "English has {} keys", english.len());
    for language in Language::ALL {
        let keys: BTreeSet<String> = Catalogue::of(language).keys().into_iter().collect();
        let missing: Vec<_> = english.difference(&keys).collect();
        let extra: Vec<_> = keys.difference(&english).collect();
        assert!(missing.is_empty(), "{} lacks {} words: {missing:?}", language.name(), missing.len());
        assert!(extra.is_empty(), "{} has words English does not: {extra:?}", language.name());
    }
}

#[test]
fn every_key_the_program_asks_for_is_in_english() {
    let english = english_keys();
    // A table's `lang` is the language itself, read from no key.
    let tables: Vec<(&str, &str)> = inventory::iter::<Table>
        .into_iter()
        .flat_map(|table| table.keys.iter().map(|key| (table.name, *key)))
        .filter(|(_, key)| !key.ends_with(".lang"))
        .collect();
    assert!(tables.len() > 500, "the tables have {} keys", tables.len());
    let named = keys_in_sources();
    assert!(named.len() > 150, "the sources name {} keys", named.len());
    let asked = tables.into_iter().chain(named.iter().map(|key| ("say!", key.as_str())));
    let missing: Vec<(&str, &str)> = asked.filter(|(_, key)| !english.contains(*key)).collect();
    assert!(missing.is_empty(), "English lacks {missing:?}");
}

/// Keys whose translation may use other holes of the ones the program fills
/// (a joint's name: English says it whole, others by side, part and axis).
const OTHER_HOLES: [(&str, &[&str]); 1] = [("import.joint", &["name", "side", "part", "axis"])];

#[test]
fn every_translation_has_the_holes_of_its_english() {
    let english = Catalogue::of(Language::English);
    for language in Language::ALL {
        let catalogue = Catalogue::of(language);
        for key in english.keys() {
            let (Some(ours), Some(theirs)) = (catalogue.value(&key), english.value(&key)) else { continue };
            let (Some(ours), Some(theirs)) = (ours.as_str(), theirs.as_str()) else { continue };
            let (ours, theirs): (BTreeSet<_>, BTreeSet<_>) =
                (holes(ours).into_iter().collect(), holes(theirs).into_iter().collect());
            match OTHER_HOLES.iter().find(|(other, _)| *other == key) {
                Some((_, filled)) => assert!(ours.iter().all(|hole| filled.contains(hole)), "{key}: {ours:?}"),
                None => assert_eq!(ours, theirs, "{}: {key} fills other holes than English", language.name()),
            }
        }
    }
}

/// Every string of a value (an array's in turn), but the first of a pair:
/// a tag (`["servo", "Servo board"]`) or the English a note is read by.
fn strings(value: &toml::Value) -> Vec<&str> {
    match value {
        toml::Value::String(text) => vec![text.as_str()],
        toml::Value::Array(pair) if pair.len() == 2 && pair.iter().all(toml::Value::is_str) => {
            pair.iter().filter_map(toml::Value::as_str).skip(1).collect()
        }
        toml::Value::Array(values) => values.iter().flat_map(strings).collect(),
        _ => Vec::new(),
    }
}

/// Whether `text` reads the same in every language: no English word of three
/// letters or more outside its holes, names (PLEN2, rFLEX, JSON…) and units.
fn reads_the_same_everywhere(text: &str) -> bool {
    const NAMES: [&str; 18] = [
        "PLEN2",
        "rFLEX",
        "JSON",
        "Maestro",
        "Blender",
        "RoboPlus",
        "Motion",
        "Servo",
        "Studio",
        "ROBOTIS",
        "mtnx",
        "mtn",
        "OSC",
        "HTTP",
        "USB",
        "socket",
        "DYNAMIXEL",
        "LED",
    ];
    let mut bare = text.to_string();
    for hole in holes(text) {
        bare = bare.replace(&format!("{{{hole}}}"), " ");
    }
    for name in NAMES {
        bare = bare.replace(name, " ");
    }
    !bare.split(|c: char| !c.is_ascii_alphabetic()).any(|word| word.len() >= 3)
}

#[test]
fn no_caption_is_left_in_english() {
    let english = Catalogue::of(Language::English);
    for language in Language::ALL.into_iter().filter(|language| *language != Language::English) {
        let catalogue = Catalogue::of(language);
        let mut untranslated = Vec::new();
        for key in english.keys().into_iter().filter(|key| !key.starts_with("language.")) {
            let (Some(ours), Some(theirs)) = (catalogue.value(&key), english.value(&key)) else { continue };
            for (ours, theirs) in strings(ours).into_iter().zip(strings(theirs)) {
                if ours == theirs && !reads_the_same_everywhere(theirs) {
                    untranslated.push(format!("{key} = {ours:?}"));
                }
            }
        }
        assert!(untranslated.is_empty(), "{} left in English: {untranslated:#?}", language.name());
    }
}

#[test]
fn the_scan_finds_keys_in_both_forms() {
    let text = "say!(self, \"link.busy\", port); say!(\n    language,\n    \"op.verify\",\n); language.word(\"file.and_more\")";
    assert_eq!(named_keys(text), ["link.busy", "op.verify", "file.and_more"]);
    assert!(reads_the_same_everywhere("PLEN2 {port}"));
    assert!(!reads_the_same_everywhere("Save {file}"));
}

/// How many holes a note's English has (`{}`), and which a translation
/// fills (`{}` in turn, `{N}` by number).
fn note_holes(pattern: &str, translation: &str) -> (usize, BTreeSet<usize>) {
    let count = pattern.matches("{}").count();
    let mut filled = BTreeSet::new();
    let mut next = 0;
    for hole in holes(translation) {
        if hole.is_empty() {
            filled.insert(next);
            next += 1;
        } else if let Ok(index) = hole.parse() {
            filled.insert(index);
        }
    }
    (count, filled)
}

#[test]
fn every_language_words_every_note_of_an_import_with_all_its_holes() {
    let english = Catalogue::of(Language::English).value("import.notes").and_then(toml::Value::as_array).unwrap();
    let patterns: Vec<&str> = english.iter().filter_map(|pair| pair.as_array()?.first()?.as_str()).collect();
    assert!(patterns.len() > 50, "{} notes", patterns.len());
    for language in Language::ALL {
        let notes = Catalogue::of(language).value("import.notes").and_then(toml::Value::as_array).unwrap();
        let pairs: Vec<(&str, &str)> = notes
            .iter()
            .filter_map(toml::Value::as_array)
            .filter_map(|pair| Some((pair.first()?.as_str()?, pair.get(1)?.as_str()?)))
            .collect();
        assert_eq!(pairs.iter().map(|(pattern, _)| *pattern).collect::<Vec<_>>(), patterns, "{}", language.name());
        for (pattern, translation) in pairs {
            let (count, filled) = note_holes(pattern, translation);
            assert_eq!(
                filled,
                (0..count).collect(),
                "{}: {translation:?} fills other holes than {pattern:?}",
                language.name()
            );
        }
    }
}
