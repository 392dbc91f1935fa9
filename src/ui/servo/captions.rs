//! The servo board's own captions, in English and Traditional Chinese: the
//! words only its panels use (the shell's and the shared ones are in `ui::i18n`).
//! A panel holding the interface's [`Strings`] reaches them as `words.servo()`.

use crate::ui::i18n::Strings;

crate::words! {
    /// The servo board's own captions.
    #[derive(Debug)]
    pub struct ServoCaptions in "servo" {
        /// A rig joint's offset.
        pub offset_mm: &'static str,
        /// "Table".
        pub table: &'static str,
        /// "difference(s) between the project and the board:".
        pub differences: &'static str,
        /// "the board refused to run the macro: upload the project first".
        pub msg_macro_refused: &'static str,
        /// "Hold".
        pub hold: &'static str,
        /// "Upload anyway".
        pub upload_anyway: &'static str,
        /// Hover text of "Upload anyway".
        pub upload_anyway_hint: &'static str,
        /// "Free memory".
        pub free_memory: &'static str,
        /// "Read angles".
        pub read_angles: &'static str,
        /// "Capture pose".
        pub capture_pose: &'static str,
        /// What Record does (hover text).
        pub record_hint: &'static str,
        /// A recording's caption: "Recording".
        pub recording_caption: &'static str,
        /// "actions, run in order by macro".
        pub actions_run_by_macro: &'static str,
        /// The same after a count of one.
        pub action_run_by_macro: &'static str,
        /// "Capture from board".
        pub capture_from_board: &'static str,
        /// "No servos yet: read a board, or add one".
        pub no_servos: &'static str,
        /// "Add servo".
        pub add_servo: &'static str,
        /// "press".
        pub event_press: &'static str,
        /// "long press".
        pub event_long_press: &'static str,
        /// "release".
        pub event_release: &'static str,
        /// "connected to the demo board (emulated, preloaded with this project)".
        pub msg_connected_demo: &'static str,
        /// "STOP: every servo stopped where it is, holding torque".
        pub msg_stopped_all: &'static str,
        /// "connect a board to run a macro".
        pub msg_connect_for_macro: &'static str,
        /// "connect a board to pick buttons from its remote".
        pub msg_connect_for_pick: &'static str,
        /// "stopped: press Resume before moving servos".
        pub msg_press_resume: &'static str,
        /// "nothing to capture: the project has no servos".
        pub msg_nothing_to_capture: &'static str,
        /// "captured the pose as action".
        pub msg_captured: &'static str,
        /// "connect a board to play an action on it (Preview works without one)".
        pub msg_connect_for_play: &'static str,
        /// "picked button".
        pub msg_picked: &'static str,
        /// "added to the table: button".
        pub msg_added_button: &'static str,
        /// "Upload to board".
        pub upload_to_board: &'static str,
        /// "Read board into project".
        pub read_board: &'static str,
        /// "Compare, then replace the project (undoable)".
        pub read_hint: &'static str,
        /// "Reading the board to compare".
        pub reading_to_compare: &'static str,
        /// "Uploading".
        pub uploading: &'static str,
        /// "The board already holds exactly this project.".
        pub already_identical: &'static str,
        /// "Back up the board, then overwrite it".
        pub confirm_upload: &'static str,
        /// "Save the board to the file".
        pub confirm_export: &'static str,
        /// "project needs (bytes)".
        pub project_needs: &'static str,
        /// "of".
        pub of_capacity: &'static str,
        /// "Servo settings".
        pub servo_settings: &'static str,
        /// "Servo".
        pub servo_word: &'static str,
        /// "Add action".
        pub add_action: &'static str,
        /// "No actions yet: capture a pose, or add one".
        pub no_actions: &'static str,
        /// "Play on board".
        pub play_on_board: &'static str,
        /// "Add step".
        pub add_step: &'static str,
        /// "Macro".
        pub macro_word: &'static str,
        /// "Add macro".
        pub add_macro: &'static str,
        /// "No macros yet".
        pub no_macros: &'static str,
        /// "Run on board".
        pub run_on_board: &'static str,
        /// "Action".
        pub action_word: &'static str,
        /// "Delay".
        pub delay: &'static str,
        /// "+ Action".
        pub add_action_command: &'static str,
        /// "+ Delay".
        pub add_delay: &'static str,
        /// "+ Macro".
        pub add_macro_command: &'static str,
        /// "Add table".
        pub add_table: &'static str,
        /// "No joystick tables yet".
        pub no_tables: &'static str,
        /// "Live button events".
        pub live_events: &'static str,
        /// "Active".
        pub active: &'static str,
        /// "Press a button to pick it".
        pub pick_button: &'static str,
        /// "Waiting for a button… (click to stop)".
        pub waiting_for_button: &'static str,
        /// "Add button".
        pub add_button: &'static str,
        /// "Press".
        pub on_press: &'static str,
        /// "Long press".
        pub on_long_press: &'static str,
        /// "Release".
        pub on_release: &'static str,
        /// The lower pane of the action editor: "Timeline".
        pub timeline_and_plot: &'static str,
        /// The status after a board was read for comparison.
        pub msg_board_compared: &'static str,
        /// Hover text of a step's number (a click moves the preview's cursor to its end).
        pub step_seek_hint: &'static str,
        /// Servos shown as bars (no rig).
        pub not_rigged: &'static str,
        /// How to get a figure.
        pub rig_hint: &'static str,
        /// A rig joint's parent.
        pub mounted_on: &'static str,
        /// A rig joint's straight angle.
        pub straight_at: &'static str,
        /// The rig table's twin column: "Twin (Mirror L/R)".
        pub twin: &'static str,
        /// Its hover.
        pub end_hint: &'static str,
        /// A mesh button with none chosen: "Mesh…".
        pub choose_mesh: &'static str,
        /// Its hover.
        pub mesh_hint: &'static str,
        /// The file dialog's filter name.
        pub mesh_kind: &'static str,
        /// "Mirror L/R".
        pub mirror: &'static str,
        /// What Mirror L/R does (hover text).
        pub mirror_hint: &'static str,
        /// After a mesh file's error: what to do.
        pub mesh_error_hint: &'static str,
        /// Whether a servo is in the rig.
        pub in_rig: &'static str,
        /// The servo settings' part for hands and feet: "Hands & feet".
        pub ends_tab: &'static str,
        /// The servo settings' part for meshes: "Meshes".
        pub meshes_tab: &'static str,
        /// The hands-and-feet table's columns: hand or foot, the chain's first servo, the tip.
        pub end_columns: [&'static str; 3],
        /// The meshes table's columns: the file, its offset, its turn, its scale.
        pub mesh_columns: [&'static str; 4],
        /// The steps table's heading for a step's curve: "Curve".
        pub curve: &'static str,
        /// Each curve's name, in `Easing::ALL` order, then a shaped one's.
        pub curves: [&'static str; 6],
        /// What a curve does to what the board stores (hover text).
        pub curve_hint: &'static str,
        /// The budget meter's start: "On the board".
        pub on_board: &'static str,
        /// "steps".
        pub steps_word: &'static str,
        /// "for curves".
        pub for_curves: &'static str,
        /// "bytes".
        pub bytes_word: &'static str,
        /// "of".
        pub of_word: &'static str,
        /// "largest deviation from the curves".
        pub largest_deviation: &'static str,
        /// "the tolerance was widened from 1° so the curves fit the board's memory".
        pub tolerance_widened: &'static str,
        /// A plot line's suffix for what the board plays: "board".
        pub board_line: &'static str,
        /// After an upload: "Curves stored as straight steps; largest deviation".
        pub curves_stored: &'static str,
        /// A macro command's button that plays the macro from it: "Play here".
        pub play_here: &'static str,
        /// What "Play here" does (hover text).
        pub play_from_here_hint: &'static str,
    }
}

/// The servo board's captions in the interface's language.
pub trait ServoWords {
    /// The servo board's captions in this language.
    fn servo(&self) -> &'static ServoCaptions;
}

impl ServoWords for Strings {
    fn servo(&self) -> &'static ServoCaptions {
        ServoCaptions::of(self.lang)
    }
}
