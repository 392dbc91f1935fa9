//! Every caption of the interface, in English and Traditional Chinese.

use super::Language;

crate::words! {
    /// Every caption of the interface.
    #[derive(Debug)]
    pub struct Strings in "strings" {
        /// The language these words are in.
        pub lang: Language,
        /// "Hardware" (the family chooser).
        pub family: &'static str,
        /// "Joints".
        pub joints: &'static str,
        /// "Motions".
        pub motions: &'static str,
        /// "Play lists".
        pub play_lists: &'static str,
        /// "Slot".
        pub slot: &'static str,
        /// "Name".
        pub name: &'static str,
        /// "Drive".
        pub drive: &'static str,
        /// "Telemetry".
        pub telemetry: &'static str,
        /// "Robot".
        pub robot: &'static str,
        /// "Pacing".
        pub pacing: &'static str,
        /// "Brake".
        pub brake: &'static str,
        /// "Commanded".
        pub commanded: &'static str,
        /// "Bump panels".
        pub bumpers: &'static str,
        /// "Reports dropped (bad checksum)".
        pub checksum_failures: &'static str,
        /// "Port".
        pub port: &'static str,
        /// "Baud".
        pub baud: &'static str,
        /// "Connect".
        pub connect: &'static str,
        /// "Disconnect".
        pub disconnect: &'static str,
        /// "Demo board".
        pub demo_board: &'static str,
        /// "Refresh".
        pub refresh: &'static str,
        /// "Gamepad" (its tab and picker).
        pub gamepad: &'static str,
        /// "Use" (a gamepad).
        pub use_gamepad: &'static str,
        /// "Let go" (stop reading the gamepad).
        pub drop_gamepad: &'static str,
        /// What the Gamepad tab says with no gamepad.
        pub gamepad_none: &'static str,
        /// The test mode checkbox.
        pub pad_test_mode: &'static str,
        /// "Axes" (bindings).
        pub pad_axes: &'static str,
        /// "Buttons" (bindings).
        pub pad_buttons: &'static str,
        /// Bind an axis by moving it.
        pub pad_bind_axis: &'static str,
        /// Bind a button by pressing it.
        pub pad_bind_button: &'static str,
        /// Waiting for the gamepad while binding.
        pub pad_binding_wait: &'static str,
        /// "moves" (an axis binding).
        pub pad_moves: &'static str,
        /// "fires" (a button binding).
        pub pad_fires: &'static str,
        /// The angle at the axis low end.
        pub pad_min: &'static str,
        /// The angle at the axis high end.
        pub pad_max: &'static str,
        /// "dead zone".
        pub pad_dead_zone: &'static str,
        /// "invert".
        pub pad_invert: &'static str,
        /// Rate mode checkbox.
        pub pad_rate: &'static str,
        /// Remove a binding.
        pub pad_remove: &'static str,
        /// Prefix of a conflict line.
        pub pad_conflict: &'static str,
        /// No servo or joint to bind an axis to.
        pub pad_nothing_to_move: &'static str,
        /// The gamepad went away (the reason follows).
        pub msg_pad_gone: &'static str,
        /// "Find board" (the connection doctor).
        pub find_board: &'static str,
        /// "Auto (find it)" (the family chooser's choice that asks the board).
        pub auto_family: &'static str,
        /// "Find a board on every port" (the port picker's last entry).
        pub find_every_board: &'static str,
        /// "No serial ports found: plug the board in, or type tcp://HOST:PORT".
        pub msg_no_ports: &'static str,
        /// "Connect to it" (what the doctor found).
        pub use_found: &'static str,
        /// "Not connected".
        pub not_connected: &'static str,
        /// "Connected to".
        pub connected_to: &'static str,
        /// "Project".
        pub project: &'static str,
        /// "Battery".
        pub battery: &'static str,
        /// "STOP".
        pub stop: &'static str,
        /// "Servos".
        pub servos: &'static str,
        /// "Undo".
        pub undo: &'static str,
        /// "Redo".
        pub redo: &'static str,
        /// "Language".
        pub language: &'static str,
        /// "Pose".
        pub pose: &'static str,
        /// "Board".
        pub board: &'static str,
        /// "Packet log".
        pub packet_log: &'static str,
        /// "opened".
        pub msg_opened: &'static str,
        /// "saved".
        pub msg_saved: &'static str,
        /// "saving…" (before the path, while the file is written).
        pub msg_saving: &'static str,
        /// "new project".
        pub msg_new_project: &'static str,
        /// "connect a board (or the demo board) first".
        pub msg_connect_first: &'static str,
        /// "connected to".
        pub msg_connected_to: &'static str,
        /// "disconnected".
        pub msg_disconnected: &'static str,
        /// The tooltip of Cancel while a lost link waits for its device: "Stop waiting for the board to come back".
        pub msg_stop_waiting: &'static str,
        /// "STOP: no board is connected".
        pub msg_stop_no_board: &'static str,
        /// "recovered the autosaved project: save it to keep it".
        pub msg_recovered: &'static str,
        /// "Filter".
        pub filter: &'static str,
        /// "name, field or hex".
        pub filter_hint: &'static str,
        /// "Copy".
        pub copy: &'static str,
        /// "Copy the shown lines".
        pub copy_hint: &'static str,
        /// "Clear".
        pub clear: &'static str,
        /// "Compare, then back the board up, write, and verify".
        pub upload_hint: &'static str,
        /// "Export board to file…".
        pub export_board: &'static str,
        /// "Connect a board (or the demo board) to upload or read.".
        pub connect_to_transfer: &'static str,
        /// "Replace the project with the board".
        pub confirm_read: &'static str,
        /// "Uploaded and verified, items:".
        pub uploaded_items: &'static str,
        /// "Backup of the previous contents:".
        pub backup_at: &'static str,
        /// "The project now holds the board's contents (Undo brings the previous project back).".
        pub read_done: &'static str,
        /// "Reading", "Writing", "Verifying": what a transfer's progress bar is doing.
        pub phases: [&'static str; 3],
        /// "Saved the board to".
        pub saved_board_to: &'static str,
        /// "Cancelled.".
        pub cancelled: &'static str,
        /// The editor ended while a board operation did not stop in time.
        pub msg_operation_left_running: &'static str,
        /// "Servo Studio did not close cleanly. Autosaved work can be recovered from".
        pub recover_body: &'static str,
        /// "Id".
        pub servo_id: &'static str,
        /// "Calibration".
        pub offset: &'static str,
        /// "Min".
        pub min: &'static str,
        /// "Max".
        pub max: &'static str,
        /// "Home".
        pub home: &'static str,
        /// "Actions".
        pub actions: &'static str,
        /// "Preview".
        pub preview: &'static str,
        /// "File".
        pub file: &'static str,
        /// "New".
        pub new_project: &'static str,
        /// "Open…".
        pub open: &'static str,
        /// "Save".
        pub save: &'static str,
        /// "Save As…".
        pub save_as: &'static str,
        /// "Recent".
        pub recent: &'static str,
        /// "● Record".
        pub record: &'static str,
        /// "■ Stop recording".
        pub stop_recording: &'static str,
        /// "Recording in" (the count-in).
        pub count_in: &'static str,
        /// "REC".
        pub recording: &'static str,
        /// "Recorded and fitted".
        pub msg_recorded: &'static str,
        /// Nothing was sampled.
        pub msg_nothing_recorded: &'static str,
        /// "largest error" (of a fitted recording).
        pub largest_error: &'static str,
        /// "Retime" (scale a span's times).
        pub retime: &'static str,
        /// "total".
        pub to_total: &'static str,
        /// "Settings" (the menu).
        pub settings: &'static str,
        /// "Live speed limit".
        pub live_speed_limit: &'static str,
        /// What the live speed limit does (hover text).
        pub live_speed_hint: &'static str,
        /// "Recover unsaved work?".
        pub recover_title: &'static str,
        /// "Recover".
        pub recover: &'static str,
        /// "Discard".
        pub discard: &'static str,
        /// "Cancel".
        pub cancel: &'static str,
        /// "Unsaved changes".
        pub unsaved_title: &'static str,
        /// "This project has unsaved changes. Save them first?".
        pub unsaved_question: &'static str,
        /// "Macros".
        pub macros: &'static str,
        /// "Total".
        pub total: &'static str,
        /// "Remove".
        pub remove: &'static str,
        /// "Joystick".
        pub joystick: &'static str,
        /// "Button".
        pub button: &'static str,
        /// "Caption".
        pub caption: &'static str,
        /// "Uninterruptible".
        pub uninterruptible: &'static str,
        /// The robot's 3D preview's name.
        pub robot_preview: &'static str,
        /// How the 3D preview is moved.
        pub preview_hint: &'static str,
        /// The toggle that shows the 3D preview.
        pub show_preview: &'static str,
        /// Play (the preview).
        pub play: &'static str,
        /// Pause (the preview).
        pub pause: &'static str,
        /// What Space does in a preview.
        pub space_plays: &'static str,
        /// "Preview speed" (the ×1 / ×0.5 / ×0.25 choice).
        pub preview_speed: &'static str,
        /// The preview's time cursor.
        pub time_cursor: &'static str,
        /// The rig's columns.
        pub rig: &'static str,
        /// The limits' columns.
        pub limits: &'static str,
        /// The robot's body (a rig root).
        pub body: &'static str,
        /// A rig joint's axis.
        pub axis: &'static str,
        /// A rig joint's sign.
        pub reversed: &'static str,
        /// "Copy" (a frame).
        pub copy_frame: &'static str,
    }
}
