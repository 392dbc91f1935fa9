//! The servo family's driver: the session, the client that talks to it over
//! the I/O thread, the non-blocking handle the editor uses, and the operations
//! built on it (export, import, verify).

mod client;
mod doctor;
mod handle;
mod image;
mod item;
mod live;
mod live_pose;
mod log;
mod ops;
mod session;

/// Default line rate of the servo board.
pub const DEFAULT_BAUD: u32 = 115_200;

inventory::submit! {
    crate::device::family::Registered {
        family: crate::project::Family::Servo,
        line: || crate::link::LineSettings::new(DEFAULT_BAUD),
        doctor: Some(crate::device::family::Doctor { rank: 1, recogniser: doctor::recogniser }),
    }
}

/// How long the board takes to receive the command that runs `macro_id` at
/// `baud` after the link's `latency`: what a sound started with it waits for.
pub fn run_macro_delay(macro_id: i32, baud: u32, latency: std::time::Duration) -> std::time::Duration {
    let bytes =
        crate::protocol::servo::Message::ExecuteMacroRequest { macro_id }.encode().map_or(0, |bytes| bytes.len());
    crate::audio::together::link_delay(bytes, baud, latency)
}

/// Battery ‰ as a person reads it: `81.5 %`.
pub fn battery_text(permil: i16) -> String {
    format!("{:.1} %", f64::from(permil) / 10.0)
}

/// Servo-board values the interface shows, re-exported so that the UI reaches
/// the protocol only through this driver.
pub use crate::protocol::servo::{ALL_SERVOS, ButtonEvent, EncodeError, ServoMove, ServoStatus};

pub use client::{Reply, Requester, ServoBoard, ServoCommand, ServoDriver, ServoEvent};
pub use doctor::Said;
pub use handle::{ServoHandle, ServoNotice};
pub use image::{Difference, ImageError, RecordKind, ServoImage};
pub use item::Item;
pub use live_pose::{Known, LivePose};
pub use log::{fields as message_fields, log_entry};
pub use ops::{
    CurveCost, ImportFailure, ImportOptions, ImportReport, OpError, Phase, Progress, ServoInfo, backup_path,
    board_info, export, import, read_image,
};
pub use session::{RequestError, RequestId, Session, SessionConfig, SessionEvent, Traffic, is_idempotent};
