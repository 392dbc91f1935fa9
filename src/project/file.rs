//! The project file: versioned JSON, loaded with precise errors and saved
//! atomically. Field by field in `docs/project-format.md`.

use std::fs::File;
use std::io::{self, Write};
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::document::Project;
use super::family::Family;
use super::plen2::Plen2Project;
use super::rflex::RflexProject;
use super::servo::ServoProject;

/// The `format` tag every project file carries.
pub const FORMAT_TAG: &str = "servo-studio-project";
/// The version this build writes. Every older version keeps loading.
pub const CURRENT_VERSION: u32 = 2;

/// A project file could not be read.
#[derive(Debug, thiserror::Error)]
pub enum LoadError {
    /// The file could not be read (or is not a regular file, or is too large).
    #[error(transparent)]
    Read(#[from] super::read::ReadError),
    /// The text is not valid JSON for a project.
    #[error("line {line}, column {column}: {message}")]
    Syntax {
        /// 1-based line of the problem.
        line: usize,
        /// 1-based column of the problem.
        column: usize,
        /// What is wrong.
        message: String,
    },
    /// The JSON is not a Servo Studio project.
    #[error("not a Servo Studio project: expected \"format\": \"{FORMAT_TAG}\", found {found}")]
    WrongFormat {
        /// What the `format` key held (or that it was missing).
        found: String,
    },
    /// The file was written by a newer Servo Studio.
    #[error(
        "project file version {found} is newer than this Servo Studio understands (up to {supported}); update Servo Studio to open it"
    )]
    NewerVersion {
        /// The file's version.
        found: u32,
        /// The newest version this build reads.
        supported: u32,
    },
}

/// A project file could not be written. The previous file, if any, is intact.
#[derive(Debug, thiserror::Error)]
#[error("cannot save {path}: {source}; {}", if *.existed { "the previous file is unchanged" } else { "nothing was written" })]
pub struct SaveError {
    /// The file.
    pub path: PathBuf,
    /// The cause.
    pub source: io::Error,
    /// Whether a file was there before (and so is kept as it was).
    pub existed: bool,
}

impl SaveError {
    /// Writing `path` failed with `source`: whatever was there stays.
    pub fn new(path: &Path, source: io::Error) -> Self {
        Self { existed: std::fs::symlink_metadata(path).is_ok(), path: path.to_path_buf(), source }
    }
}

#[derive(Deserialize)]
struct Header {
    format: Option<String>,
    version: Option<u32>,
}

/// Version 2: the family, then one section per family.
#[derive(Serialize)]
struct Envelope<'a> {
    format: &'static str,
    version: u32,
    family: Family,
    #[serde(skip_serializing_if = "Option::is_none")]
    servo: Option<&'a ServoProject>,
    #[serde(skip_serializing_if = "Option::is_none")]
    plen2: Option<&'a Plen2Project>,
    #[serde(skip_serializing_if = "Option::is_none")]
    rflex: Option<&'a RflexProject>,
    #[serde(skip_serializing_if = "Option::is_none")]
    gamepad: Option<&'a super::gamepad::GamepadMappings>,
    #[serde(skip_serializing_if = "Option::is_none")]
    sound: Option<&'a super::SoundTrack>,
    /// The sections of families added since the first three, each under its tag.
    #[serde(flatten)]
    sections: std::collections::BTreeMap<&'a str, &'a serde_json::Value>,
}

#[derive(Deserialize)]
struct Sections {
    #[serde(default)]
    family: Family,
    #[serde(default)]
    servo: ServoProject,
    #[serde(default)]
    plen2: Plen2Project,
    #[serde(default)]
    rflex: RflexProject,
    #[serde(default)]
    gamepad: super::gamepad::GamepadMappings,
    #[serde(default)]
    sound: Option<super::SoundTrack>,
}

fn syntax(error: &serde_json::Error) -> LoadError {
    // serde_json appends " at line L column C" to its message; the numbers are kept separately.
    let text = error.to_string();
    let message = match text.rfind(" at line ") {
        Some(cut) => text[..cut].to_string(),
        None => text,
    };
    LoadError::Syntax { line: error.line(), column: error.column(), message }
}

/// A project read from a file, and the keys it held that Servo Studio does
/// not know (ignored, but worth a warning: a misspelt `min_degs` changes nothing).
#[derive(Clone, Debug, PartialEq)]
pub struct Loaded {
    /// The project.
    pub project: Project,
    /// Each unknown key's path, e.g. `servo.servos[3].min_degs`, in file order:
    /// the first [`MAX_UNKNOWN_KEYS_KEPT`].
    pub unknown_keys: Vec<String>,
    /// Unknown keys past those, counted but not kept (a hostile file can hold millions).
    pub unknown_keys_not_kept: usize,
}

impl Loaded {
    /// Every unknown key, kept or only counted.
    pub fn unknown_key_count(&self) -> usize {
        self.unknown_keys.len() + self.unknown_keys_not_kept
    }
}

/// How many unknown keys a load keeps by name; the rest are counted.
pub const MAX_UNKNOWN_KEYS_KEPT: usize = 1000;

/// A key's path as a person reads it: `servo.servos[3].min_degs`.
fn key_path(path: &serde_ignored::Path<'_>) -> String {
    use serde_ignored::Path;
    match path {
        Path::Root => String::new(),
        Path::Seq { parent, index } => format!("{}[{index}]", key_path(parent)),
        Path::Map { parent, key } => match key_path(parent) {
            parent if parent.is_empty() => key.clone(),
            parent => format!("{parent}.{key}"),
        },
        Path::Some { parent } | Path::NewtypeStruct { parent } | Path::NewtypeVariant { parent } => key_path(parent),
    }
}

/// `T` from `text`, and every key it ignored but the envelope's own
/// (`format`, `version`, and `envelope`): the first [`MAX_UNKNOWN_KEYS_KEPT`]
/// by path, then only how many more.
fn deserialize_noting<T: serde::de::DeserializeOwned>(
    text: &str,
    envelope: &[&str],
) -> Result<(T, Vec<String>, usize), LoadError> {
    let mut unknown = Vec::new();
    let mut not_kept = 0;
    let mut deserializer = serde_json::Deserializer::from_str(text);
    let value = serde_ignored::deserialize(&mut deserializer, |path| {
        if unknown.len() >= MAX_UNKNOWN_KEYS_KEPT {
            not_kept += 1;
            return;
        }
        let path = key_path(&path);
        if !matches!(path.as_str(), "format" | "version") && !envelope.contains(&path.as_str()) {
            unknown.push(path);
        }
    })
    .map_err(|error| syntax(&error))?;
    deserializer.end().map_err(|error| syntax(&error))?;
    Ok((value, unknown, not_kept))
}

/// The sections under `tags` in a project file's text (each family added
/// since the first three keeps its own); read only when such a family exists.
fn kept_sections(text: &str, tags: &[&'static str]) -> Result<super::document::Sections, LoadError> {
    let mut sections = super::document::Sections::default();
    if tags.is_empty() {
        return Ok(sections);
    }
    let mut deserializer = serde_json::Deserializer::from_str(text);
    let found =
        serde::de::DeserializeSeed::deserialize(Tagged(tags), &mut deserializer).map_err(|error| syntax(&error))?;
    for (tag, section) in found {
        if let Some(family) = Family::from_tag(tag) {
            sections.set(family, section);
        }
    }
    Ok(sections)
}

/// Reads a JSON object's members named by one of its tags, skipping the others.
struct Tagged<'t>(&'t [&'static str]);

impl<'de> serde::de::DeserializeSeed<'de> for Tagged<'_> {
    type Value = Vec<(&'static str, serde_json::Value)>;

    fn deserialize<D: serde::Deserializer<'de>>(self, deserializer: D) -> Result<Self::Value, D::Error> {
        deserializer.deserialize_map(self)
    }
}

impl<'de> serde::de::Visitor<'de> for Tagged<'_> {
    type Value = Vec<(&'static str, serde_json::Value)>;

    fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("a project object")
    }

    fn visit_map<A: serde::de::MapAccess<'de>>(self, mut map: A) -> Result<Self::Value, A::Error> {
        let mut found = Vec::new();
        while let Some(key) = map.next_key::<std::borrow::Cow<'de, str>>()? {
            match self.0.iter().find(|tag| **tag == key) {
                Some(tag) => found.push((*tag, map.next_value()?)),
                None => {
                    map.next_value::<serde::de::IgnoredAny>()?;
                }
            }
        }
        Ok(found)
    }
}

/// What a JSON text holds at its top level when it is not an object.
fn top_level(text: &str) -> Option<&'static str> {
    match text.trim_start().as_bytes().first()? {
        b'{' => None,
        b'[' => Some("a JSON array"),
        b'"' => Some("a JSON string"),
        b't' | b'f' => Some("a JSON true or false"),
        b'n' => Some("a JSON null"),
        _ => Some("a JSON number, or text that is not JSON"),
    }
}

/// Parses a project from the text of a project file, of any supported version.
pub fn from_json(text: &str) -> Result<Project, LoadError> {
    parse(text).map(|loaded| loaded.project)
}

/// Parses a project file, of any supported version, noting the keys it does
/// not know. A UTF-8 byte-order mark (as some Windows editors write) is skipped.
pub fn parse(text: &str) -> Result<Loaded, LoadError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    if let Some(found) = top_level(text)
        && serde_json::from_str::<serde::de::IgnoredAny>(text).is_ok()
    {
        // Valid JSON, but not an object: say what it is rather than what the first field lacks.
        return Err(LoadError::WrongFormat { found: found.to_string() });
    }
    let header: Header = serde_json::from_str(text).map_err(|error| syntax(&error))?;
    match header.format.as_deref() {
        Some(FORMAT_TAG) => {}
        Some(other) => {
            return Err(LoadError::WrongFormat { found: format!("{other:?}") });
        }
        None => {
            return Err(LoadError::WrongFormat { found: "no \"format\" key".into() });
        }
    }
    match header.version {
        // Version 1 held a servo board's content at the top level: it becomes
        // the servo section. Every later version adds an arm here.
        Some(1) | None => {
            // Version 1 named its board in the envelope.
            let (servo, unknown_keys, unknown_keys_not_kept) = deserialize_noting(text, &["board"])?;
            Ok(Loaded { project: Project::servo(servo), unknown_keys, unknown_keys_not_kept })
        }
        Some(2) => {
            let tags = super::kept_section::tags();
            let (sections, unknown_keys, unknown_keys_not_kept): (Sections, _, _) = deserialize_noting(text, &tags)?;
            let project = Project {
                family: sections.family,
                servo: sections.servo,
                plen2: sections.plen2,
                rflex: sections.rflex,
                gamepad: sections.gamepad,
                sound: sections.sound,
                sections: kept_sections(text, &tags)?,
            };
            Ok(Loaded { project, unknown_keys, unknown_keys_not_kept })
        }
        Some(found) => Err(LoadError::NewerVersion { found, supported: CURRENT_VERSION }),
    }
}

/// The text of a project file for `project`, in the current version. The
/// family's own section is always written; another only when it holds something.
pub fn to_json(project: &Project) -> String {
    let family = project.family;
    let wanted = |own: Family, empty: bool| family == own || !empty;
    let envelope = Envelope {
        format: FORMAT_TAG,
        version: CURRENT_VERSION,
        family,
        servo: wanted(Family::Servo, project.servo == ServoProject::default()).then_some(&project.servo),
        plen2: wanted(Family::Plen2, project.plen2 == Plen2Project::default()).then_some(&project.plen2),
        rflex: wanted(Family::Rflex, project.rflex == RflexProject::default()).then_some(&project.rflex),
        gamepad: (!project.gamepad.is_empty()).then_some(&project.gamepad),
        sound: project.sound.as_ref(),
        sections: project.sections.iter().filter(|(tag, _)| super::kept_section::tags().contains(tag)).collect(),
    };
    // Serializing plain structs of strings and integers to a String cannot fail.
    let mut text = serde_json::to_string_pretty(&envelope).unwrap_or_default();
    text.push('\n');
    text
}

/// Reads a project file.
pub fn load(path: &Path) -> Result<Project, LoadError> {
    read(path).map(|loaded| loaded.project)
}

/// Reads a project file, noting the keys it does not know. Only a regular
/// file is read, up to [`super::read::MAX_PROJECT_BYTES`].
pub fn read(path: &Path) -> Result<Loaded, LoadError> {
    let text = super::read::read_text(path, super::read::MAX_PROJECT_BYTES)?;
    let parsed = parse(&text);
    // The text goes before the caller builds on the document: a large file is not held twice.
    drop(text);
    parsed
}

/// Writes a project file atomically: a failure leaves the previous file intact.
pub fn save(path: &Path, project: &Project) -> Result<(), SaveError> {
    let text = to_json(project);
    atomic_write(path, |file| file.write_all(text.as_bytes())).map_err(|source| SaveError::new(path, source))
}

/// Where writing to `path` really goes: through symbolic links to the file
/// they name (a link is never replaced by a file). Refused, with a clear
/// error, when what is there is not a regular file: a folder, a named pipe, a
/// device or a socket is never replaced.
pub fn output_path(path: &Path) -> io::Result<PathBuf> {
    let mut target = path.to_path_buf();
    // As many links as the system itself follows before it gives up.
    for _ in 0..40 {
        let metadata = match std::fs::symlink_metadata(&target) {
            Ok(metadata) => metadata,
            // Nothing there yet: a new file.
            Err(error) if error.kind() == io::ErrorKind::NotFound => return Ok(target),
            Err(error) => return Err(error),
        };
        let kind = metadata.file_type();
        if kind.is_symlink() {
            let link = std::fs::read_link(&target)?;
            target = match target.parent() {
                Some(folder) if link.is_relative() => folder.join(link),
                _ => link,
            };
            continue;
        }
        if kind.is_file() {
            return Ok(target);
        }
        let what = if kind.is_dir() { "a folder: give a file name inside it" } else { not_a_file(&kind) };
        return Err(io::Error::new(io::ErrorKind::InvalidInput, format!("{} is {what}", target.display())));
    }
    Err(io::Error::new(io::ErrorKind::InvalidInput, format!("{}: too many symbolic links", path.display())))
}

#[cfg(unix)]
fn not_a_file(kind: &std::fs::FileType) -> &'static str {
    use std::os::unix::fs::FileTypeExt;
    if kind.is_fifo() {
        "a named pipe (FIFO), not a file: it is never replaced"
    } else if kind.is_char_device() || kind.is_block_device() {
        "a device, not a file: it is never replaced"
    } else if kind.is_socket() {
        "a socket, not a file: it is never replaced"
    } else {
        "not a regular file: it is never replaced"
    }
}

#[cfg(not(unix))]
fn not_a_file(_kind: &std::fs::FileType) -> &'static str {
    "not a regular file: it is never replaced"
}

/// Writes `path` by writing a temporary file in the same folder with `write`,
/// flushing it to disk, and renaming it over `path`. If anything fails, the
/// temporary file is removed and `path` is untouched. A symbolic link is
/// followed (the file it names is replaced, beside itself, keeping its
/// permissions); anything but a regular file is refused ([`output_path`]).
pub fn atomic_write(path: &Path, write: impl FnOnce(&mut File) -> io::Result<()>) -> io::Result<()> {
    let staged = Staged::write(path, write)?;
    staged.commit()
}

/// Writes every file of `files` or none: each is written whole beside
/// itself first (as [`atomic_write`] does), and only when all were written
/// are they renamed into place; if any fails, no file is touched and no
/// temporary file is left.
pub fn atomic_write_all(files: &[(&Path, &[u8])]) -> io::Result<()> {
    let mut staged = Vec::with_capacity(files.len());
    for (path, bytes) in files {
        staged.push(Staged::write(path, |file| Write::write_all(file, bytes))?);
    }
    for file in staged {
        file.commit()?;
    }
    Ok(())
}

/// A file written whole beside the file it will replace, not yet in place;
/// dropped uncommitted, it is removed.
struct Staged {
    temp: PathBuf,
    path: PathBuf,
    committed: bool,
}

impl Staged {
    fn write(path: &Path, write: impl FnOnce(&mut File) -> io::Result<()>) -> io::Result<Self> {
        let path = output_path(path)?;
        let permissions = std::fs::metadata(&path).ok().map(|metadata| metadata.permissions());
        let folder = match path.parent() {
            Some(parent) if !parent.as_os_str().is_empty() => parent.to_path_buf(),
            _ => PathBuf::from("."),
        };
        let name =
            path.file_name().ok_or_else(|| io::Error::new(io::ErrorKind::InvalidInput, "path has no file name"))?;
        let mut temp_name = std::ffi::OsString::from(".");
        temp_name.push(name);
        temp_name.push(format!(".{}.tmp", std::process::id()));
        let temp = folder.join(temp_name);
        let mut file = File::create(&temp)?;
        // From here the temporary file is removed if anything fails.
        let staged = Self { temp, path, committed: false };
        write(&mut file)?;
        if let Some(permissions) = permissions {
            file.set_permissions(permissions)?;
        }
        file.sync_all()?;
        Ok(staged)
    }

    fn commit(mut self) -> io::Result<()> {
        std::fs::rename(&self.temp, &self.path)?;
        self.committed = true;
        Ok(())
    }
}

impl Drop for Staged {
    fn drop(&mut self) {
        if !self.committed {
            // Best effort: nothing else can be done about a temporary file that will not go.
            let _ = std::fs::remove_file(&self.temp);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn malformed_json_reports_line_and_column() {
        let text = "{\n  \"format\": \"servo-studio-project\",\n  \"version\": 1,\n  \"project_id\": \"seven\"\n}";
        match from_json(text) {
            Err(LoadError::Syntax { line, column, message }) => {
                assert_eq!(line, 4);
                assert!(column > 10, "column {column}");
                assert!(message.contains("invalid type"), "{message}");
            }
            other => panic!("expected a syntax error, got {other:?}"),
        }
    }

    #[test]
    fn truncated_file_is_an_error_with_position() {
        let text = to_json(&Project::default());
        let err = from_json(&text[..text.len() / 2]).unwrap_err();
        assert!(matches!(err, LoadError::Syntax { line, .. } if line > 1), "{err}");
    }

    #[test]
    fn wrong_format_and_newer_versions_are_refused_clearly() {
        assert!(matches!(from_json(r#"{"format": "other"}"#), Err(LoadError::WrongFormat { .. })));
        assert!(matches!(from_json(r#"{"servos": []}"#), Err(LoadError::WrongFormat { .. })));
        let array = from_json("[1, 2]").unwrap_err();
        assert_eq!(
            array.to_string(),
            "not a Servo Studio project: expected \"format\": \"servo-studio-project\", found a JSON array"
        );
        let err = from_json(r#"{"format": "servo-studio-project", "version": 99}"#).unwrap_err();
        assert!(matches!(err, LoadError::NewerVersion { found: 99, supported: CURRENT_VERSION }));
        assert!(err.to_string().contains("update Servo Studio"));
    }

    #[test]
    fn a_byte_order_mark_is_skipped_and_unknown_keys_are_noted_with_their_place() {
        let mut project = Project::default();
        project.servo.servos.push(crate::project::Servo::new(3, "腕"));
        let text = to_json(&project).replacen("\"min_deg\"", "\"min_degs\"", 1).replacen("{", "{\"colour\": 1,", 1);
        let loaded = parse(&format!("\u{feff}{text}")).unwrap();
        assert_eq!(loaded.unknown_keys, ["colour", "servo.servos[0].min_degs"]);
        // The misspelt key is ignored: the servo keeps its default limit.
        assert_eq!(loaded.project.servo.servos[0].min_deg, crate::project::Servo::new(3, "").min_deg);
        assert!(parse(&to_json(&project)).unwrap().unknown_keys.is_empty(), "a file we wrote has none");
    }

    #[test]
    fn a_failed_write_leaves_the_previous_file_intact_and_no_temp_file() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("robot.json");
        std::fs::write(&path, "previous").unwrap();
        let err = atomic_write(&path, |file| {
            file.write_all(b"half a proj")?;
            Err(io::Error::other("disk full"))
        })
        .unwrap_err();
        assert_eq!(err.to_string(), "disk full");
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "previous");
        let names: Vec<_> = std::fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().file_name()).collect();
        assert_eq!(names, [std::ffi::OsString::from("robot.json")]);
    }

    #[test]
    fn saving_into_a_missing_folder_fails_without_creating_anything() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("missing").join("robot.json");
        let err = save(&path, &Project::default()).unwrap_err();
        assert!(err.to_string().ends_with("; nothing was written"), "there was no previous file: {err}");
        assert!(!dir.path().join("missing").exists());
    }
}
