//! The servo board's own captions, in English and Traditional Chinese: the
//! words only its panels use (the shell's and the shared ones are in `ui::i18n`).
//! A panel holding the interface's [`Strings`] reaches them as `words.servo()`.

use crate::ui::i18n::{Language, Strings};

/// The servo board's own captions.
#[derive(Debug)]
pub struct ServoCaptions {
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
    /// "Resume".
    pub resume: &'static str,
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
    /// "servos may move again".
    pub msg_resumed: &'static str,
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

const ENGLISH: ServoCaptions = ServoCaptions {
    offset_mm: "Offset x, y, z (mm)",
    table: "Table",
    differences: "difference(s) between the project and the board:",
    msg_macro_refused: "the board refused to run the macro: upload the project first",
    hold: "Hold",
    upload_anyway: "Upload anyway",
    upload_anyway_hint: "Restore it exactly as it is (e.g. a backup of a board another tool wrote). The board is still compared first, backed up, and verified after writing.",
    free_memory: "Free memory",
    resume: "Resume",
    read_angles: "Read angles",
    capture_pose: "Capture pose",
    record_hint: "Record the servos as you move them (sliders, keys, a gamepad), after a 3 s count-in; Stop fits what you did into the fewest steps the board plays within 1°: one action per step and a macro running them in order (an action's steps all start together, so a sequence is a macro). One undo step.",
    recording_caption: "Recording",
    actions_run_by_macro: "actions, run in order by macro",
    action_run_by_macro: "action, run by macro",
    capture_from_board: "Capture from board",
    no_servos: "No servos yet: read a board, or add one",
    add_servo: "Add servo",
    event_press: "press",
    event_long_press: "long press",
    event_release: "release",
    msg_connected_demo: "connected to the demo board (emulated, preloaded with this project)",
    msg_stopped_all: "STOP: every servo stopped where it is, holding torque",
    msg_resumed: "servos may move again",
    msg_connect_for_macro: "connect a board to run a macro",
    msg_connect_for_pick: "connect a board to pick buttons from its remote",
    msg_press_resume: "stopped: press Resume before moving servos",
    msg_nothing_to_capture: "nothing to capture: the project has no servos",
    msg_captured: "captured the pose as action",
    msg_connect_for_play: "connect a board to play an action on it (Preview works without one)",
    msg_picked: "picked button",
    msg_added_button: "added to the table: button",
    upload_to_board: "Upload to board",
    read_board: "Read board into project",
    read_hint: "Compare, then replace the project (undoable)",
    reading_to_compare: "Reading the board to compare",
    uploading: "Uploading",
    already_identical: "The board already holds exactly this project.",
    confirm_upload: "Back up the board, then overwrite it",
    confirm_export: "Save the board to the file",
    project_needs: "project needs (bytes)",
    of_capacity: "of",
    servo_settings: "Servo settings",
    servo_word: "Servo",
    add_action: "Add action",
    no_actions: "No actions yet: capture a pose, or add one",
    play_on_board: "Play on board",
    add_step: "Add step",
    macro_word: "Macro",
    add_macro: "Add macro",
    no_macros: "No macros yet",
    run_on_board: "Run on board",
    action_word: "Action",
    delay: "Delay",
    add_action_command: "+ Action",
    add_delay: "+ Delay",
    add_macro_command: "+ Macro",
    add_table: "Add table",
    no_tables: "No joystick tables yet",
    live_events: "Live button events",
    active: "Active",
    pick_button: "Press a button to pick it",
    waiting_for_button: "Waiting for a button… (click to stop)",
    add_button: "Add button",
    on_press: "Press",
    on_long_press: "Long press",
    on_release: "Release",
    timeline_and_plot: "Timeline",
    msg_board_compared: "Board read: check what differs on the Board tab, then confirm",
    step_seek_hint: "Show in the preview where this step's servo arrives",
    not_rigged: "Not in the rig",
    rig_hint: "Place the servos in a skeleton (Servo settings → Rig) to see the robot.",
    mounted_on: "Mounted on",
    straight_at: "Straight at (°)",
    twin: "Twin (Mirror L/R)",
    end_hint: "Mark the link as a hand or a foot: the 3D view gets a ring at its tip (x y z mm) to pose it by, the servos from the one chosen down to it solving",
    choose_mesh: "Mesh…",
    mesh_hint: "Draw the link with an STL or OBJ file (stored relative to the project); offset (mm), turn (° about x, y, z) and mm per unit beside it; × removes it",
    mesh_kind: "STL or OBJ mesh",
    mirror: "Mirror L/R",
    mesh_error_hint: "the link is drawn without it; fix the file or change it in Servo settings → Meshes",
    mirror_hint: "Each step moves the servo's twin instead (the rig's Twin column), its angle reflected about their homes: a left-arm wave becomes a right-arm wave. A servo without a twin keeps its step.",
    in_rig: "In rig",
    ends_tab: "Hands & feet",
    meshes_tab: "Meshes",
    end_columns: ["Hand or foot", "Chain from", "Tip x, y, z (mm)"],
    mesh_columns: ["Mesh file", "Offset x, y, z (mm)", "Turn about x, y, z (°)", "Scale (mm per unit)"],
    curve: "Curve",
    curves: ["Linear", "Ease in", "Ease out", "Ease in-out", "Hold", "Shaped"],
    curve_hint: "How the step's move runs. The board moves only in straight lines: a curve is stored as straight sub-steps within 1° of it (widened when the board's memory is short), run by a macro of their own, eased from where the macro has put the servo. The project keeps the curve.",
    on_board: "On the board",
    steps_word: "steps",
    for_curves: "for curves",
    bytes_word: "bytes",
    of_word: "of",
    largest_deviation: "largest deviation from the curves",
    tolerance_widened: "the tolerance was widened from 1° so the curves fit the board's memory",
    board_line: "board",
    curves_stored: "Curves stored as straight steps; largest deviation",
    play_here: "Play here",
    play_from_here_hint: "Play from here: on the board (connected), this command and those after it are sent live, one after another, from where the servos are; the preview's cursor goes to where it starts",
};

const TRADITIONAL_CHINESE: ServoCaptions = ServoCaptions {
    offset_mm: "位移 x, y, z（mm）",
    table: "對應表",
    differences: "項專案與控制板的差異：",
    msg_macro_refused: "控制板拒絕執行巨集：請先上傳專案",
    hold: "鎖定",
    upload_anyway: "仍要上傳",
    upload_anyway_hint: "照原樣還原（例如其他工具寫入的控制板備份）。仍會先比較、備份控制板，寫入後再驗證。",
    free_memory: "可用記憶體",
    resume: "繼續",
    read_angles: "讀取角度",
    capture_pose: "擷取姿勢",
    record_hint: "倒數 3 秒後錄下你移動伺服機的過程（滑桿、按鍵、遊戲手把）；停止時會擬合成板子播放誤差在 1° 內的最少步驟：每一步一個動作，加上依序執行它們的巨集（一個動作的所有步驟同時開始，所以序列要用巨集）。可一步復原。",
    recording_caption: "錄製",
    actions_run_by_macro: "個動作，依序由巨集執行：",
    action_run_by_macro: "個動作，由巨集執行：",
    capture_from_board: "從控制板擷取",
    no_servos: "尚無舵機：請讀取控制板或新增舵機",
    add_servo: "新增舵機",
    event_press: "按下",
    event_long_press: "長按",
    event_release: "放開",
    msg_connected_demo: "已連線至示範控制板（模擬，已載入此專案）",
    msg_stopped_all: "停止：所有舵機停在原處並保持鎖定",
    msg_resumed: "舵機可以再次移動",
    msg_connect_for_macro: "請連接控制板以執行巨集",
    msg_connect_for_pick: "請連接控制板以從遙控器選取按鍵",
    msg_press_resume: "已停止：移動舵機前請按「繼續」",
    msg_nothing_to_capture: "無法擷取：專案沒有舵機",
    msg_captured: "已將姿勢擷取為動作",
    msg_connect_for_play: "請連接控制板以播放動作（預覽不需控制板）",
    msg_picked: "已選取按鍵",
    msg_added_button: "已加入對應表：按鍵",
    upload_to_board: "上傳至控制板",
    read_board: "讀取控制板至專案",
    read_hint: "先比較，再取代專案（可復原）",
    reading_to_compare: "讀取控制板以比較",
    uploading: "上傳中",
    already_identical: "控制板內容已與此專案完全相同。",
    confirm_upload: "備份控制板後覆寫",
    confirm_export: "將控制板存成檔案",
    project_needs: "專案所需（位元組）",
    of_capacity: "／",
    servo_settings: "舵機設定",
    servo_word: "舵機",
    add_action: "新增動作",
    no_actions: "尚無動作：擷取姿勢或新增動作",
    play_on_board: "在控制板上播放",
    add_step: "新增步驟",
    macro_word: "巨集",
    add_macro: "新增巨集",
    no_macros: "尚無巨集",
    run_on_board: "在控制板上執行",
    action_word: "動作",
    delay: "延遲",
    add_action_command: "+ 動作",
    add_delay: "+ 延遲",
    add_macro_command: "+ 巨集",
    add_table: "新增對應表",
    no_tables: "尚無遙控對應表",
    live_events: "即時按鍵事件",
    active: "使用中",
    pick_button: "按下遙控器按鍵以選取",
    waiting_for_button: "等待按鍵…（按此停止）",
    add_button: "新增按鍵",
    on_press: "按下",
    on_long_press: "長按",
    on_release: "放開",
    timeline_and_plot: "時間軸",
    msg_board_compared: "已讀取控制板：請在「控制板」分頁檢查差異後再確認",
    step_seek_hint: "在預覽中顯示此步驟的伺服機到達的位置",
    not_rigged: "不在骨架中",
    rig_hint: "在「舵機設定 → 骨架」中把舵機放進骨架，就能看到機器人。",
    mounted_on: "裝在",
    straight_at: "伸直角度（°）",
    twin: "對側伺服機（左右鏡像）",
    end_hint: "將此連桿標為手或腳：3D 視圖會在其末端（x y z 公釐）顯示圓圈，拖曳即可擺姿勢，由所選伺服機到此連桿之間求解",
    choose_mesh: "外形…",
    mesh_hint: "以 STL 或 OBJ 檔繪製此連桿（以相對於專案的路徑儲存）；旁邊可設位移（公釐）、旋轉（繞 x、y、z 的角度）與每單位公釐數；× 移除",
    mesh_kind: "STL 或 OBJ 外形",
    mirror: "左右鏡像",
    mesh_error_hint: "此連桿以預設外形顯示；請修正檔案，或在「舵機設定 → 外形」更換",
    mirror_hint: "每個步驟改由該伺服機的對側伺服機執行（骨架表的「對側」欄），角度以原點對稱反轉：左手揮手變成右手揮手。沒有對側的伺服機保留原步驟。",
    in_rig: "在骨架中",
    ends_tab: "手與腳",
    meshes_tab: "外形",
    end_columns: ["手或腳", "鏈起點", "末端 x、y、z（公釐）"],
    mesh_columns: ["外形檔", "位移 x、y、z（公釐）", "繞 x、y、z 旋轉（°）", "比例（每單位公釐）"],
    curve: "曲線",
    curves: ["線性", "漸入", "漸出", "漸入漸出", "保持", "自訂曲線"],
    curve_hint: "此步驟的移動方式。控制板只會直線移動：曲線會存成數個誤差 1° 以內的直線子步驟（控制板記憶體不足時放寬），由專屬巨集依序執行，從巨集讓伺服機到達的角度開始漸變。專案保留曲線本身。",
    on_board: "控制板上",
    steps_word: "個步驟",
    for_curves: "用於曲線",
    bytes_word: "位元組",
    of_word: "／",
    largest_deviation: "與曲線的最大偏差",
    tolerance_widened: "已將容許誤差從 1° 放寬，讓曲線放得進控制板記憶體",
    board_line: "控制板",
    curves_stored: "曲線已存成直線步驟；最大偏差",
    play_here: "由此播放",
    play_from_here_hint: "從這裡播放：已連線時，從此指令起依序即時送到控制板，從伺服機目前的位置開始；預覽的時間游標移到此指令開始處",
};

/// The servo board's captions in the interface's language.
pub trait ServoWords {
    /// The servo board's captions in this language.
    fn servo(&self) -> &'static ServoCaptions;
}

impl ServoWords for Strings {
    fn servo(&self) -> &'static ServoCaptions {
        match self.lang {
            Language::English => &ENGLISH,
            Language::TraditionalChinese => &TRADITIONAL_CHINESE,
        }
    }
}
