//! Every caption of the interface, in English and Traditional Chinese.

use super::Language;

/// Every caption of the interface.
#[derive(Debug)]
pub struct Strings {
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
    /// "Capture into frame".
    pub capture_frame: &'static str,
    /// "Add motion".
    pub add_motion: &'static str,
    /// "Slot".
    pub slot: &'static str,
    /// "Name".
    pub name: &'static str,
    /// "Loop frames".
    pub loop_frames: &'static str,
    /// "Then jump to slot".
    pub jump_to: &'static str,
    /// "Frames".
    pub frames: &'static str,
    /// "Transition (ms)".
    pub transition_ms: &'static str,
    /// "Paste after".
    pub paste: &'static str,
    /// "Mirror L/R".
    pub mirror: &'static str,
    /// "Play from here".
    pub play_from_here: &'static str,
    /// "Play on robot".
    pub play_on_robot: &'static str,
    /// "Add play list".
    pub add_play_list: &'static str,
    /// "Add motion".
    pub add_entry: &'static str,
    /// "Plays (0 = forever)".
    pub plays: &'static str,
    /// "Read robot".
    pub read_robot: &'static str,
    /// "Upload motions".
    pub upload_motions: &'static str,
    /// "Write joint settings".
    pub write_joints: &'static str,
    /// "Factory joint settings".
    pub factory_reset: &'static str,
    /// "Slot map: project / robot".
    pub slot_map: &'static str,
    /// "Joint settings (tenths of a degree; the robot stores them)".
    pub joint_settings: &'static str,
    /// "STOP: the motion stopped and every joint went home".
    pub msg_plen2_stopped: &'static str,
    /// "Drive".
    pub drive: &'static str,
    /// "Telemetry".
    pub telemetry: &'static str,
    /// "Robot".
    pub robot: &'static str,
    /// "Pacing".
    pub pacing: &'static str,
    /// What the pacing modes do (hover text).
    pub pacing_hint: &'static str,
    /// "Brake".
    pub brake: &'static str,
    /// "Sonar".
    pub sonar: &'static str,
    /// "Drag in the pad, or hold the arrow keys; release to stop. Space or Esc: STOP.".
    pub pad_hint: &'static str,
    /// "Top speed (m/s)".
    pub max_speed: &'static str,
    /// "Top turn (rad/s)".
    pub max_turn: &'static str,
    /// "Acceleration (m/s²)".
    pub acceleration: &'static str,
    /// "Commanded".
    pub commanded: &'static str,
    /// "Measured".
    pub measured: &'static str,
    /// "Odometry".
    pub odometry: &'static str,
    /// "Bump panels".
    pub bumpers: &'static str,
    /// "Joystick".
    pub joystick_state: &'static str,
    /// "Reports dropped (bad checksum)".
    pub checksum_failures: &'static str,
    /// "STOP: the base was told to stop at once".
    pub msg_base_stopped: &'static str,
    /// "The base stopped answering while driving; it was sent a stop. Check the cable and its power.".
    pub msg_base_silent: &'static str,
    /// "Port".
    pub port: &'static str,
    /// "Upload anyway".
    pub upload_anyway: &'static str,
    /// Hover text of "Upload anyway".
    pub upload_anyway_hint: &'static str,
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
    /// "Not connected".
    pub not_connected: &'static str,
    /// "Connected to".
    pub connected_to: &'static str,
    /// "Project".
    pub project: &'static str,
    /// "Battery".
    pub battery: &'static str,
    /// "Free memory".
    pub free_memory: &'static str,
    /// "STOP".
    pub stop: &'static str,
    /// "Resume".
    pub resume: &'static str,
    /// "Servos".
    pub servos: &'static str,
    /// "Hold".
    pub hold: &'static str,
    /// "Read angles".
    pub read_angles: &'static str,
    /// "Capture pose".
    pub capture_pose: &'static str,
    /// "Capture from board".
    pub capture_from_board: &'static str,
    /// "Undo".
    pub undo: &'static str,
    /// "Redo".
    pub redo: &'static str,
    /// "Language".
    pub language: &'static str,
    /// "No servos yet: read a board, or add one".
    pub no_servos: &'static str,
    /// "Add servo".
    pub add_servo: &'static str,
    /// "Pose".
    pub pose: &'static str,
    /// "Board".
    pub board: &'static str,
    /// "Packet log".
    pub packet_log: &'static str,
    /// "the board refused to run the macro: upload the project first".
    pub msg_macro_refused: &'static str,
    /// "press".
    pub event_press: &'static str,
    /// "long press".
    pub event_long_press: &'static str,
    /// "release".
    pub event_release: &'static str,
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
    /// "connected to the demo board (emulated, preloaded with this project)".
    pub msg_connected_demo: &'static str,
    /// "connected to the demo PLEN2 (emulated, factory-fresh: its 90 slots are empty)".
    pub msg_connected_demo_plen2: &'static str,
    /// "connected to the demo base (emulated, braked, in a 4.2 × 2.8 m room)".
    pub msg_connected_demo_rflex: &'static str,
    /// "disconnected".
    pub msg_disconnected: &'static str,
    /// "STOP: every servo stopped where it is, holding torque".
    pub msg_stopped_all: &'static str,
    /// "STOP: no board is connected".
    pub msg_stop_no_board: &'static str,
    /// "servos may move again".
    pub msg_resumed: &'static str,
    /// "this project has no file yet: use Save As".
    pub msg_no_file: &'static str,
    /// "recovered the autosaved project: save it to keep it".
    pub msg_recovered: &'static str,
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
    /// "the board link ended; your project is unchanged, reconnect when ready:".
    pub msg_link_ended: &'static str,
    /// "connect a board to play an action on it (Preview works without one)".
    pub msg_connect_for_play: &'static str,
    /// "picked button".
    pub msg_picked: &'static str,
    /// "added to the table: button".
    pub msg_added_button: &'static str,
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
    /// "Upload to board".
    pub upload_to_board: &'static str,
    /// "Compare, then back the board up, write, and verify".
    pub upload_hint: &'static str,
    /// "Read board into project".
    pub read_board: &'static str,
    /// "Compare, then replace the project (undoable)".
    pub read_hint: &'static str,
    /// "Export board to file…".
    pub export_board: &'static str,
    /// "Connect a board (or the demo board) to upload or read.".
    pub connect_to_transfer: &'static str,
    /// "Reading the board to compare".
    pub reading_to_compare: &'static str,
    /// "Uploading".
    pub uploading: &'static str,
    /// "Reading the board".
    pub reading_board: &'static str,
    /// "The board already holds exactly this project.".
    pub already_identical: &'static str,
    /// "difference(s) between the project and the board:".
    pub differences: &'static str,
    /// "Back up the board, then overwrite it".
    pub confirm_upload: &'static str,
    /// "Replace the project with the board".
    pub confirm_read: &'static str,
    /// "Save the board to the file".
    pub confirm_export: &'static str,
    /// "Uploaded and verified, items:".
    pub uploaded_items: &'static str,
    /// "Backup of the previous contents:".
    pub backup_at: &'static str,
    /// "The project now holds the board's contents (Undo brings the previous project back).".
    pub read_done: &'static str,
    /// "Read the robot; motions it holds:".
    pub robot_read: &'static str,
    /// "Reading", "Writing", "Verifying": what a transfer's progress bar is doing.
    pub phases: [&'static str; 3],
    /// "Still different after writing again (check the cable and upload again), slots:".
    pub slots_differ: &'static str,
    /// "Saved the board to".
    pub saved_board_to: &'static str,
    /// "Cancelled.".
    pub cancelled: &'static str,
    /// The editor ended while a board operation did not stop in time.
    pub msg_operation_left_running: &'static str,
    /// "Servo Studio did not close cleanly. Autosaved work can be recovered from".
    pub recover_body: &'static str,
    /// "project needs (bytes)".
    pub project_needs: &'static str,
    /// "of".
    pub of_capacity: &'static str,
    /// "Servo settings".
    pub servo_settings: &'static str,
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
    /// "Servo".
    pub servo_word: &'static str,
    /// "Actions".
    pub actions: &'static str,
    /// "Add action".
    pub add_action: &'static str,
    /// "No actions yet: capture a pose, or add one".
    pub no_actions: &'static str,
    /// "Play on board".
    pub play_on_board: &'static str,
    /// "Preview".
    pub preview: &'static str,
    /// "Add step".
    pub add_step: &'static str,
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
    /// "Macro".
    pub macro_word: &'static str,
    /// "Add macro".
    pub add_macro: &'static str,
    /// "No macros yet".
    pub no_macros: &'static str,
    /// "Total".
    pub total: &'static str,
    /// "Run on board".
    pub run_on_board: &'static str,
    /// "Remove".
    pub remove: &'static str,
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
    /// "Joystick".
    pub joystick: &'static str,
    /// "Add table".
    pub add_table: &'static str,
    /// "Table".
    pub table: &'static str,
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
    /// "Button".
    pub button: &'static str,
    /// "Caption".
    pub caption: &'static str,
    /// "Press".
    pub on_press: &'static str,
    /// "Long press".
    pub on_long_press: &'static str,
    /// "Release".
    pub on_release: &'static str,
    /// "Uninterruptible".
    pub uninterruptible: &'static str,
    /// The lower pane of the action editor: "Timeline and plot".
    pub timeline_and_plot: &'static str,
    /// The lower pane of the macro composer: "Plot".
    pub plot: &'static str,
    /// The lower pane of the motion editor: "Frame values and plot".
    pub frame_and_plot: &'static str,
    /// What the motion.json button does.
    pub motion_json_hint: &'static str,
    /// The status after the brake was set.
    pub msg_brake_on: &'static str,
    /// The status after the brake was released.
    pub msg_brake_released: &'static str,
    /// The status after a board was read for comparison.
    pub msg_board_compared: &'static str,
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
    /// Hover text of a step's number (a click moves the preview's cursor to its end).
    pub step_seek_hint: &'static str,
    /// The preview's time cursor.
    pub time_cursor: &'static str,
    /// Which motion a PLEN2 motion is previewed after.
    pub played_after: &'static str,
    /// The robot just switched on (its frame buffer all zeros).
    pub power_up: &'static str,
    /// Where a PLEN2 motion starts from.
    pub snap_note: &'static str,
    /// The sliders' pose differs from where the motion starts.
    pub snap_warning: &'static str,
    /// What "(+N ?)" after the sonar count means.
    pub sonar_unknown_hint: &'static str,
    /// The previewed motion never ends on the robot (plen2.md §6).
    pub motion_never_ends: &'static str,
    /// The previewed motion's first frame lasts 0 cycles: the robot divides by zero.
    pub first_frame_undefined: &'static str,
    /// Servos shown as bars (no rig).
    pub not_rigged: &'static str,
    /// How to get a figure.
    pub rig_hint: &'static str,
    /// The rig's columns.
    pub rig: &'static str,
    /// The limits' columns.
    pub limits: &'static str,
    /// A rig joint's parent.
    pub mounted_on: &'static str,
    /// The robot's body (a rig root).
    pub body: &'static str,
    /// A rig joint's axis.
    pub axis: &'static str,
    /// A rig joint's sign.
    pub reversed: &'static str,
    /// A rig joint's straight angle.
    pub straight_at: &'static str,
    /// A rig joint's offset.
    pub offset_mm: &'static str,
    /// Whether a servo is in the rig.
    pub in_rig: &'static str,
    /// The rFLEX world view.
    pub world_view: &'static str,
    /// Follow the base in the world view.
    pub follow: &'static str,
    /// Forget the echoes seen.
    pub clear_map: &'static str,
    /// How the world view is moved.
    pub world_hint: &'static str,
    /// What a click on a plot's legend entry does.
    pub plot_toggle_hint: &'static str,
    /// The drive pad says the window lacks keyboard focus.
    pub drive_needs_focus: &'static str,
}

impl Strings {
    /// "Copy" (a frame).
    pub fn copy_frame(&self) -> &'static str {
        match self.lang {
            Language::English => "Copy",
            Language::TraditionalChinese => "複製",
        }
    }
}

mod chinese;
mod english;

pub(super) use chinese::TRADITIONAL_CHINESE;
pub(super) use english::ENGLISH;
