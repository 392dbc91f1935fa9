//! The editor's window, driven through egui_kittest.

mod actions;
mod board;
mod connect;
mod doctor;
mod drive;
mod files;
mod follow_chain;
mod frames;
mod gamepad;
mod graph;
mod ik;
mod import;
mod import_board;
mod joystick;
mod log;
mod macros;
mod plen2;
mod pose3d;
mod preview;
mod rig3d;
mod rows;
mod show;
mod show_boards;
mod sliders;
mod sound;
mod uncut;
