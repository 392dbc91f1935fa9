//! The servo board driver: the session, the client that talks to it over the
//! I/O thread, and the operations built on it (export, import, verify).

mod client;
mod image;
mod item;
mod live;
mod ops;
mod session;

pub use client::{Board, BoardCommand, BoardDriver, BoardEvent, Reply, Requester};
pub use image::{BoardImage, Difference, ImageError, RecordKind};
pub use item::Item;
pub use ops::{
    BoardInfo, Cancel, ImportOptions, ImportReport, OpError, Phase, Progress, backup_path, board_info, export, import,
    read_image,
};
pub use session::{RequestError, RequestId, Session, SessionConfig, SessionEvent, Traffic, is_idempotent};
