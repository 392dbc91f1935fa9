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
    /// "connected to the demo base (emulated, braked, in a 3.6 × 2.4 m room)".
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

pub(super) const ENGLISH: Strings = Strings {
    lang: Language::English,
    family: "Hardware",
    joints: "Joints",
    motions: "Motions",
    play_lists: "Play lists",
    capture_frame: "Capture into frame",
    add_motion: "Add motion",
    slot: "Slot",
    name: "Name",
    loop_frames: "Loop frames",
    jump_to: "Then jump to slot",
    frames: "Frames",
    transition_ms: "Transition (ms)",
    paste: "Paste after",
    mirror: "Mirror L/R",
    play_from_here: "Play from here",
    play_on_robot: "Play on robot",
    add_play_list: "Add play list",
    add_entry: "Add motion",
    plays: "Plays (0 = forever)",
    read_robot: "Read robot",
    upload_motions: "Upload motions",
    write_joints: "Write joint settings",
    factory_reset: "Factory joint settings",
    slot_map: "Slot map (after Read robot — green: same as the project · amber: different · blue: only in the project · grey, in brackets: only on the robot)",
    joint_settings: "Joint settings (tenths of a degree; the robot stores them)",
    msg_plen2_stopped: "STOP: the motion stopped and every joint went home",
    drive: "Drive",
    telemetry: "Telemetry",
    robot: "Robot",
    pacing: "Pacing",
    pacing_hint: "How PLEN2 uploads are paced. Adaptive (default): fast, and more careful once the link shows it is late or bursty (a Bluetooth bridge) or a read-back differs. Fast: never widens. Safe: the official tool's 32 bytes, then 50 ms. Takes effect at the next connection.",
    brake: "Brake",
    sonar: "Sonar",
    pad_hint: "Drag in the pad, or hold the arrow keys; release to stop. Space or Esc: STOP.",
    max_speed: "Top speed (m/s)",
    max_turn: "Top turn (rad/s)",
    acceleration: "Acceleration (m/s²)",
    commanded: "Commanded",
    measured: "Measured",
    odometry: "Odometry",
    bumpers: "Bump panels",
    joystick_state: "Joystick",
    checksum_failures: "Reports dropped (bad checksum)",
    msg_base_stopped: "STOP: the base was told to stop at once",
    msg_base_silent: "The base stopped answering while driving; it was sent a stop. Check the cable and its power.",
    upload_anyway: "Upload anyway",
    upload_anyway_hint: "Restore it exactly as it is (e.g. a backup of a board another tool wrote). The board is still compared first, backed up, and verified after writing.",
    port: "Port",
    baud: "Baud",
    connect: "Connect",
    disconnect: "Disconnect",
    demo_board: "Demo board",
    refresh: "Refresh",
    not_connected: "Not connected",
    connected_to: "Connected to",
    project: "Project",
    battery: "Battery",
    free_memory: "Free memory",
    stop: "STOP",
    resume: "Resume",
    servos: "Servos",
    hold: "Hold",
    read_angles: "Read angles",
    capture_pose: "Capture pose",
    capture_from_board: "Capture from board",
    undo: "Undo",
    redo: "Redo",
    language: "Language",
    no_servos: "No servos yet: read a board, or add one",
    add_servo: "Add servo",
    pose: "Pose",
    board: "Board",
    packet_log: "Packet log",
    msg_macro_refused: "the board refused to run the macro: upload the project first",
    event_press: "press",
    event_long_press: "long press",
    event_release: "release",
    msg_opened: "opened",
    msg_saved: "saved",
    msg_new_project: "new project",
    msg_connect_first: "connect a board (or the demo board) first",
    msg_connected_to: "connected to",
    msg_connected_demo: "connected to the demo board (emulated, preloaded with this project)",
    msg_connected_demo_plen2: "connected to the demo PLEN2 (emulated, factory-fresh: its 90 slots are empty)",
    msg_connected_demo_rflex: "connected to the demo base (emulated, braked, in a 3.6 × 2.4 m room)",
    msg_disconnected: "disconnected",
    msg_stopped_all: "STOP: every servo stopped where it is, holding torque",
    msg_stop_no_board: "STOP: no board is connected",
    msg_resumed: "servos may move again",
    msg_no_file: "this project has no file yet: use Save As",
    msg_recovered: "recovered the autosaved project: save it to keep it",
    msg_connect_for_macro: "connect a board to run a macro",
    msg_connect_for_pick: "connect a board to pick buttons from its remote",
    msg_press_resume: "stopped: press Resume before moving servos",
    msg_nothing_to_capture: "nothing to capture: the project has no servos",
    msg_captured: "captured the pose as action",
    msg_link_ended: "the board link ended; your project is unchanged, reconnect when ready:",
    msg_connect_for_play: "connect a board to play an action on it (Preview works without one)",
    msg_picked: "picked button",
    msg_added_button: "added to the table: button",
    filter: "Filter",
    filter_hint: "name, field or hex",
    copy: "Copy",
    copy_hint: "Copy the shown lines",
    clear: "Clear",
    upload_to_board: "Upload to board",
    upload_hint: "Compare, then back the board up, write, and verify",
    read_board: "Read board into project",
    read_hint: "Compare, then replace the project (undoable)",
    export_board: "Export board to file…",
    connect_to_transfer: "Connect a board (or the demo board) to upload or read.",
    reading_to_compare: "Reading the board to compare",
    uploading: "Uploading",
    reading_board: "Reading the board",
    already_identical: "The board already holds exactly this project.",
    differences: "difference(s) between the project and the board:",
    confirm_upload: "Back up the board, then overwrite it",
    confirm_read: "Replace the project with the board",
    confirm_export: "Save the board to the file",
    uploaded_items: "Uploaded and verified, items:",
    backup_at: "Backup of the previous contents:",
    read_done: "The project now holds the board's contents (Undo brings the previous project back).",
    robot_read: "Read the robot; motions it holds:",
    phases: ["Reading", "Writing", "Verifying"],
    slots_differ: "Still different after writing again (check the cable and upload again), slots:",
    saved_board_to: "Saved the board to",
    cancelled: "Cancelled.",
    recover_body: "Servo Studio did not close cleanly. Autosaved work can be recovered from",
    project_needs: "project needs (bytes)",
    of_capacity: "of",
    servo_settings: "Servo settings",
    servo_id: "Id",
    offset: "Calibration",
    min: "Min",
    max: "Max",
    home: "Home",
    servo_word: "Servo",
    actions: "Actions",
    add_action: "Add action",
    no_actions: "No actions yet: capture a pose, or add one",
    play_on_board: "Play on board",
    preview: "Preview",
    add_step: "Add step",
    file: "File",
    new_project: "New",
    open: "Open…",
    save: "Save",
    save_as: "Save As…",
    recent: "Recent",
    recover_title: "Recover unsaved work?",
    recover: "Recover",
    discard: "Discard",
    cancel: "Cancel",
    unsaved_title: "Unsaved changes",
    unsaved_question: "This project has unsaved changes. Save them first?",
    macros: "Macros",
    macro_word: "Macro",
    add_macro: "Add macro",
    no_macros: "No macros yet",
    total: "Total",
    run_on_board: "Run on board",
    remove: "Remove",
    action_word: "Action",
    delay: "Delay",
    add_action_command: "+ Action",
    add_delay: "+ Delay",
    add_macro_command: "+ Macro",
    joystick: "Joystick",
    add_table: "Add table",
    table: "Table",
    no_tables: "No joystick tables yet",
    live_events: "Live button events",
    active: "Active",
    pick_button: "Press a button to pick it",
    waiting_for_button: "Waiting for a button… (click to stop)",
    add_button: "Add button",
    button: "Button",
    caption: "Caption",
    on_press: "Press",
    on_long_press: "Long press",
    on_release: "Release",
    uninterruptible: "Uninterruptible",
};

pub(super) const TRADITIONAL_CHINESE: Strings = Strings {
    lang: Language::TraditionalChinese,
    family: "硬體",
    joints: "關節",
    motions: "動作",
    play_lists: "播放清單",
    capture_frame: "擷取為影格",
    add_motion: "新增動作",
    slot: "位置",
    name: "名稱",
    loop_frames: "循環影格",
    jump_to: "接著跳到位置",
    frames: "影格",
    transition_ms: "過渡時間（ms）",
    paste: "貼在後面",
    mirror: "左右鏡像",
    play_from_here: "從這裡播放",
    play_on_robot: "在機器人上播放",
    add_play_list: "新增播放清單",
    add_entry: "加入動作",
    plays: "次數（0 = 無限）",
    read_robot: "讀取機器人",
    upload_motions: "上傳動作",
    write_joints: "寫入關節設定",
    factory_reset: "恢復出廠關節設定",
    slot_map: "槽位圖（讀取機器人後——綠：與專案相同 · 琥珀：不同 · 藍：僅在專案中 · 灰、括號內：僅在機器人上）",
    joint_settings: "關節設定（0.1 度；存於機器人）",
    msg_plen2_stopped: "停止：動作已停止，所有關節回到原點",
    drive: "駕駛",
    telemetry: "遙測",
    robot: "機器人",
    pacing: "傳送節奏",
    pacing_hint: "PLEN2 上傳的傳送節奏。自動調整（預設）：快速，當連線顯示延遲或成批送達（藍牙橋接）或讀回內容不同時放慢。快速：不放慢。安全：官方工具的每 32 位元組等待 50 ms。下次連線時生效。",
    brake: "煞車",
    sonar: "聲納",
    pad_hint: "在方塊中拖曳，或按住方向鍵；放開即停止。空白鍵或 Esc：停止。",
    max_speed: "最高速度（m/s）",
    max_turn: "最高轉速（rad/s）",
    acceleration: "加速度（m/s²）",
    commanded: "指令",
    measured: "實測",
    odometry: "里程",
    bumpers: "防撞板",
    joystick_state: "搖桿",
    checksum_failures: "丟棄的報告（校驗錯誤）",
    msg_base_stopped: "停止：已命令底盤立即停止",
    msg_base_silent: "行駛中底盤停止回應，已送出停止指令。請檢查線材與電源。",
    upload_anyway: "仍要上傳",
    upload_anyway_hint: "照原樣還原（例如其他工具寫入的控制板備份）。仍會先比較、備份控制板，寫入後再驗證。",
    port: "連接埠",
    baud: "鮑率",
    connect: "連線",
    disconnect: "中斷連線",
    demo_board: "示範控制板",
    refresh: "重新整理",
    not_connected: "未連線",
    connected_to: "已連線至",
    project: "專案",
    battery: "電量",
    free_memory: "可用記憶體",
    stop: "停止",
    resume: "繼續",
    servos: "舵機",
    hold: "鎖定",
    read_angles: "讀取角度",
    capture_pose: "擷取姿勢",
    capture_from_board: "從控制板擷取",
    undo: "復原",
    redo: "重做",
    language: "語言",
    no_servos: "尚無舵機：請讀取控制板或新增舵機",
    add_servo: "新增舵機",
    pose: "姿勢",
    board: "控制板",
    packet_log: "封包紀錄",
    msg_macro_refused: "控制板拒絕執行巨集：請先上傳專案",
    event_press: "按下",
    event_long_press: "長按",
    event_release: "放開",
    msg_opened: "已開啟",
    msg_saved: "已儲存",
    msg_new_project: "新專案",
    msg_connect_first: "請先連接控制板（或示範控制板）",
    msg_connected_to: "已連線至",
    msg_connected_demo: "已連線至示範控制板（模擬，已載入此專案）",
    msg_connected_demo_plen2: "已連線至示範 PLEN2（模擬，出廠狀態：90 個槽位皆為空）",
    msg_connected_demo_rflex: "已連線至示範底盤（模擬，已煞車，位於 3.6 × 2.4 公尺的房間）",
    msg_disconnected: "已中斷連線",
    msg_stopped_all: "停止：所有舵機停在原處並保持鎖定",
    msg_stop_no_board: "停止：尚未連接控制板",
    msg_resumed: "舵機可以再次移動",
    msg_no_file: "此專案尚未存檔：請使用另存新檔",
    msg_recovered: "已復原自動儲存的專案：請儲存以保留",
    msg_connect_for_macro: "請連接控制板以執行巨集",
    msg_connect_for_pick: "請連接控制板以從遙控器選取按鍵",
    msg_press_resume: "已停止：移動舵機前請按「繼續」",
    msg_nothing_to_capture: "無法擷取：專案沒有舵機",
    msg_captured: "已將姿勢擷取為動作",
    msg_link_ended: "與控制板的連線已中斷；專案未變更，準備好後請重新連線：",
    msg_connect_for_play: "請連接控制板以播放動作（預覽不需控制板）",
    msg_picked: "已選取按鍵",
    msg_added_button: "已加入對應表：按鍵",
    filter: "篩選",
    filter_hint: "名稱、欄位或十六進位",
    copy: "複製",
    copy_hint: "複製顯示的列",
    clear: "清除",
    upload_to_board: "上傳至控制板",
    upload_hint: "先比較，再備份控制板、寫入並驗證",
    read_board: "讀取控制板至專案",
    read_hint: "先比較，再取代專案（可復原）",
    export_board: "匯出控制板至檔案…",
    connect_to_transfer: "請連接控制板（或示範控制板）以上傳或讀取。",
    reading_to_compare: "讀取控制板以比較",
    uploading: "上傳中",
    reading_board: "讀取控制板中",
    already_identical: "控制板內容已與此專案完全相同。",
    differences: "項專案與控制板的差異：",
    confirm_upload: "備份控制板後覆寫",
    confirm_read: "以控制板內容取代專案",
    confirm_export: "將控制板存成檔案",
    uploaded_items: "已上傳並驗證，項目數：",
    backup_at: "先前內容的備份：",
    read_done: "專案已換成控制板的內容（復原可取回先前的專案）。",
    robot_read: "已讀取機器人；其中的動作數：",
    phases: ["讀取中", "寫入中", "驗證中"],
    slots_differ: "重寫後仍不一致（請檢查連接線後再上傳一次），槽位：",
    saved_board_to: "已將控制板存至",
    cancelled: "已取消。",
    recover_body: "Servo Studio 未正常關閉。可以復原自動儲存的工作，時間：",
    project_needs: "專案所需（位元組）",
    of_capacity: "／",
    servo_settings: "舵機設定",
    servo_id: "編號",
    offset: "校正",
    min: "最小",
    max: "最大",
    home: "原點",
    servo_word: "舵機",
    actions: "動作",
    add_action: "新增動作",
    no_actions: "尚無動作：擷取姿勢或新增動作",
    play_on_board: "在控制板上播放",
    preview: "預覽",
    add_step: "新增步驟",
    file: "檔案",
    new_project: "新增",
    open: "開啟…",
    save: "儲存",
    save_as: "另存新檔…",
    recent: "最近的檔案",
    recover_title: "復原未儲存的工作？",
    recover: "復原",
    discard: "捨棄",
    cancel: "取消",
    unsaved_title: "未儲存的變更",
    unsaved_question: "此專案有未儲存的變更，要先儲存嗎？",
    macros: "巨集",
    macro_word: "巨集",
    add_macro: "新增巨集",
    no_macros: "尚無巨集",
    total: "總長",
    run_on_board: "在控制板上執行",
    remove: "移除",
    action_word: "動作",
    delay: "延遲",
    add_action_command: "+ 動作",
    add_delay: "+ 延遲",
    add_macro_command: "+ 巨集",
    joystick: "遙控器",
    add_table: "新增對應表",
    table: "對應表",
    no_tables: "尚無遙控對應表",
    live_events: "即時按鍵事件",
    active: "使用中",
    pick_button: "按下遙控器按鍵以選取",
    waiting_for_button: "等待按鍵…（按此停止）",
    add_button: "新增按鍵",
    button: "按鍵",
    caption: "標題",
    on_press: "按下",
    on_long_press: "長按",
    on_release: "放開",
    uninterruptible: "不可中斷",
};
