//! Every integration test in one binary: each test binary links the whole
//! crate, egui included, so one binary builds and links once. The families'
//! suites are modules (`cli::…`, `plen2::…`, `ui::…`); `cargo test ui::` runs
//! one of them.

mod common;

mod architecture;
mod cli;
mod fit;
mod interchange;
mod plen2;
mod probe;
mod project;
mod rflex;
mod services;
mod servo;
mod ui;
