//! The command line, run as a user runs it.

mod audio;
mod commands;
mod dynamixel;
mod follow_audio;
mod honest;
mod hostile;
mod inputs;
mod installed;
pub mod play;
mod play_links;
mod robust;
pub mod serve;
mod serve_hostile;
mod servo;
mod sim_log;
mod trajectory;
