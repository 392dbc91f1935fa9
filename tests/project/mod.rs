//! The project document: file format, properties, validation.

mod file;
mod props;
mod show;
mod validation;
