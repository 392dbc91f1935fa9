//! The show window's words, in each language.

use crate::project::Family;
use crate::ui::i18n::Language;

pub(super) fn family_name(family: Family, words: &ShowWords) -> &'static str {
    words.families.iter().find(|(tag, _)| *tag == family.tag()).map_or_else(|| family.name(), |(_, name)| name)
}

/// The show window's words.
#[derive(Debug)]
pub struct ShowWords {
    /// The window's title and the File menu's entry.
    pub title: &'static str,
    /// "Show the open project as a show".
    pub this_project: &'static str,
    /// "devices".
    pub devices: &'static str,
    /// Column heads.
    pub device: &'static str,
    /// "Family".
    pub family: &'static str,
    /// "Port".
    pub port: &'static str,
    /// "Sound".
    pub sound: &'static str,
    /// "Play on the boards".
    pub play: &'static str,
    /// "Stop all".
    pub stop_all: &'static str,
    /// "macro", "motion", "drive".
    pub macro_word: &'static str,
    /// "motion".
    pub motion_word: &'static str,
    /// "drive".
    pub drive_word: &'static str,
    /// Family names by tag.
    pub families: [(&'static str, &'static str); 3],
    /// "If its link is lost".
    pub if_lost: &'static str,
    /// "Connect the boards" (held while the window is open).
    pub connect_boards: &'static str,
    /// "Disconnect the boards".
    pub disconnect_boards: &'static str,
    /// What connected boards do.
    pub boards_follow: &'static str,
    /// The link column's head.
    pub link: &'static str,
    /// A device being connected.
    pub asking: &'static str,
    /// A device that answered.
    pub answered: &'static str,
    /// A device that did not answer.
    pub silent: &'static str,
    /// A device whose link was lost.
    pub lost: &'static str,
    /// After a lost link: every device was stopped.
    pub all_stopped: &'static str,
    /// Settings → "Remote control…".
    pub remote_menu: &'static str,
    /// The remote control window's title.
    pub remote_title: &'static str,
    /// Its on / off box.
    pub remote_serve: &'static str,
    /// "Listen on".
    pub remote_listen: &'static str,
    /// "OSC port".
    pub remote_osc: &'static str,
    /// "Token file".
    pub remote_token: &'static str,
    /// Queue a play on a busy device, or refuse it.
    pub remote_queue: &'static str,
    /// What it serves, and the token rule.
    pub remote_hint: &'static str,
    /// "listening on".
    pub remote_listening: &'static str,
    /// It stopped because the boards went.
    pub remote_stopped: &'static str,
    /// A base a remote drives.
    pub remote_driven: &'static str,
    /// "play on without it".
    pub play_on: &'static str,
    /// "At".
    pub at: &'static str,
    /// "Cue" (a row's name).
    pub cue: &'static str,
    /// "Starts".
    pub starts: &'static str,
    /// "Remove".
    pub remove: &'static str,
    /// "+ Cue".
    pub add_cue: &'static str,
    /// "Save show…".
    pub save: &'static str,
    /// "+ Device".
    pub add_device: &'static str,
    /// "The open project".
    pub from_open: &'static str,
    /// "A project file…".
    pub from_file: &'static str,
    /// "New" (before a family's name).
    pub new: &'static str,
    /// "Find by id".
    pub find: &'static str,
    /// Said when no USB serial device is attached.
    pub none_attached: &'static str,
    /// "its cues went with it" (after a count).
    pub cues_removed: &'static str,
    /// "Time shown" (the scrub's caption).
    pub scrub: &'static str,
    /// The stage view's name.
    pub stage: &'static str,
    /// "Heading".
    pub heading: &'static str,
    /// The timeline's name (a click shows that time).
    pub timeline: &'static str,
    /// "Preview".
    pub preview: &'static str,
    /// "Stop preview".
    pub stop_preview: &'static str,
    /// "Record a pass of".
    pub record_pass_of: &'static str,
    /// "● Record pass".
    pub record_pass: &'static str,
    /// "■ Stop pass".
    pub stop_pass: &'static str,
    /// "Undo pass".
    pub undo_pass: &'static str,
    /// "passes joined".
    pub passes_joined: &'static str,
    /// "steps" (a servo board's).
    pub steps: &'static str,
    /// "frames" (a PLEN2's).
    pub frames: &'static str,
    /// "largest error".
    pub largest_error: &'static str,
    /// "tolerance".
    pub tolerance: &'static str,
    /// "its own cue cuts the passes short at" (a board plays one at a time).
    pub cut_short_at: &'static str,
    /// "slider" (what moves a pass's axis).
    pub by_slider: &'static str,
    /// Said when no gamepad axis has moved yet.
    pub no_pad_axis: &'static str,
}

const ENGLISH: ShowWords = ShowWords {
    title: "Show…",
    this_project: "this project",
    devices: "devices",
    device: "Device",
    family: "Family",
    port: "Port",
    sound: "Sound",
    play: "Play on the boards",
    stop_all: "Stop all",
    macro_word: "macro",
    motion_word: "motion",
    drive_word: "drive",
    families: [("servo", "servo board"), ("plen2", "PLEN2"), ("rflex", "rFLEX base")],
    if_lost: "If its link is lost",
    connect_boards: "Connect the boards",
    disconnect_boards: "Disconnect the boards",
    boards_follow: "the boards follow the preview and record passes",
    link: "Link",
    asking: "connecting…",
    answered: "answered",
    silent: "did not answer",
    lost: "link lost",
    all_stopped: ": every device was stopped",
    remote_menu: "Remote control…",
    remote_title: "Remote control",
    remote_serve: "Serve remote control (HTTP + OSC)",
    remote_listen: "Listen on",
    remote_osc: "OSC port (empty: none)",
    remote_token: "Token file",
    remote_queue: "A play on a busy device waits its turn (else it is refused)",
    remote_hint: "Serves the show window's devices, their boards connected (the open project as a show when none is open). Any address but 127.0.0.1 needs a token file. docs/remote.md",
    remote_listening: "listening on",
    remote_stopped: "remote control stopped: the boards were disconnected",
    remote_driven: "driven (heartbeats arriving)",
    play_on: "play on without it",
    at: "At",
    cue: "Cue",
    starts: "Starts",
    remove: "Remove",
    add_cue: "+ Cue",
    save: "Save show…",
    add_device: "+ Device",
    from_open: "The open project",
    from_file: "A project file…",
    new: "New",
    find: "Find by id",
    none_attached: "No USB serial device is attached: plug it in, or type its port",
    cues_removed: "cues went with it",
    scrub: "Time shown",
    stage: "Stage: every device at the time shown",
    heading: "Heading",
    timeline: "Timeline: click to show that time",
    preview: "Preview",
    stop_preview: "Stop preview",
    record_pass_of: "Record a pass of",
    record_pass: "● Record pass",
    stop_pass: "■ Stop pass",
    undo_pass: "Undo pass",
    passes_joined: "passes joined",
    steps: "steps",
    frames: "frames",
    largest_error: "largest error",
    tolerance: "tolerance",
    cut_short_at: "another cue of it cuts them short (a board plays one at a time) at",
    by_slider: "slider",
    no_pad_axis: "No gamepad axis has moved: choose a gamepad (Gamepad tab) and move a stick",
};

const CHINESE: ShowWords = ShowWords {
    title: "演出…",
    this_project: "此專案",
    devices: "個裝置",
    device: "裝置",
    family: "種類",
    port: "連接埠",
    sound: "聲音",
    play: "在開發板上播放",
    stop_all: "全部停止",
    macro_word: "巨集",
    motion_word: "動作",
    drive_word: "行駛",
    families: [("servo", "伺服板"), ("plen2", "PLEN2"), ("rflex", "rFLEX 底盤")],
    if_lost: "連線中斷時",
    connect_boards: "連接所有板子",
    disconnect_boards: "中斷所有板子",
    boards_follow: "板子會跟著預覽與錄製播放",
    link: "連線",
    asking: "連線中…",
    answered: "已回應",
    silent: "沒有回應",
    lost: "連線中斷",
    all_stopped: "：所有裝置已停止",
    remote_menu: "遠端控制…",
    remote_title: "遠端控制",
    remote_serve: "開啟遠端控制（HTTP + OSC）",
    remote_listen: "監聽位址",
    remote_osc: "OSC 連接埠（空白：不使用）",
    remote_token: "權杖檔案",
    remote_queue: "裝置忙碌時，播放請求排隊等候（否則拒絕）",
    remote_hint: "控制演出視窗中的裝置，並連接它們的板子（沒有開啟演出時，以目前的專案作為演出）。127.0.0.1 以外的位址需要權杖檔案。docs/remote.md",
    remote_listening: "正在監聽",
    remote_stopped: "遠端控制已停止：板子已中斷連線",
    remote_driven: "遠端駕駛中（持續收到心跳）",
    play_on: "其他裝置繼續演出",
    at: "時間",
    cue: "提示點",
    starts: "開始",
    remove: "移除",
    add_cue: "+ 提示點",
    save: "儲存演出…",
    add_device: "+ 裝置",
    from_open: "目前開啟的專案",
    from_file: "專案檔…",
    new: "新增",
    find: "依 ID 尋找",
    none_attached: "沒有接上任何 USB 序列裝置：請接上，或輸入它的連接埠",
    cues_removed: "個提示點一併移除",
    scrub: "顯示時間",
    stage: "舞台：各裝置在顯示時間的姿勢",
    heading: "朝向",
    timeline: "時間軸：點一下顯示該時間",
    preview: "預覽",
    stop_preview: "停止預覽",
    record_pass_of: "錄製一軌：",
    record_pass: "● 錄製這一軌",
    stop_pass: "■ 停止這一軌",
    undo_pass: "復原上一軌",
    passes_joined: "軌已合併",
    steps: "個步驟",
    frames: "個影格",
    largest_error: "最大誤差",
    tolerance: "容許誤差",
    cut_short_at: "它的另一個提示點會中斷這些軌（控制板一次只播放一個），於",
    by_slider: "滑桿",
    no_pad_axis: "遊戲手把還沒有任何搖桿軸移動：請在遊戲手把分頁選擇手把並推動搖桿",
};

/// The words in `language`.
pub fn words(language: Language) -> &'static ShowWords {
    match language {
        Language::English => &ENGLISH,
        Language::TraditionalChinese => &CHINESE,
    }
}
