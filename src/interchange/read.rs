//! A file's text read as its format: each format's reader, by name.

use super::format::{Format, ReadError};
use super::source::Source;
use super::text::Decoded;
use super::{blender, maestro, robotis};

/// Reads `text` as `format`; what it asks for is then checked against what
/// a board can mean ([`super::bounds`]) before anything is made of it.
pub fn read(format: Format, text: &str) -> Result<Source, ReadError> {
    let source = match format {
        Format::Maestro => maestro::read(text),
        Format::Mtn => robotis::read_mtn(text),
        Format::Mtnx => robotis::read_mtnx(text),
        Format::Blender => blender::read(text),
    }?;
    super::bounds::check(&source)?;
    Ok(source)
}

/// A file's decoded text read as `format`, or as the format its content
/// shows (`Ok(None)`: no format of ours), with what decoding it took in the notes.
pub fn read_decoded(format: Option<Format>, decoded: &Decoded) -> Result<Option<Source>, ReadError> {
    let Some(format) = format.or_else(|| Format::guess(&decoded.text)) else { return Ok(None) };
    let mut source = read(format, &decoded.text)?;
    source.notes.splice(0..0, decoded.notes.iter().cloned());
    Ok(Some(source))
}
