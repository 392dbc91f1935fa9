//! The project document: file format, properties, validation: one test binary (each binary links the whole crate, egui
//! included, so the suites share one).

mod file;
mod props;
mod validation;
