//! The import window's own captions, in English and Traditional Chinese.

use crate::ui::i18n::Language;

/// The import window's captions.
#[derive(Debug)]
pub struct ImportWords {
    /// The File menu's entry and the window's title.
    pub title: &'static str,
    /// "Reading".
    pub reading: &'static str,
    /// "Motion".
    pub motion: &'static str,
    /// "All".
    pub all: &'static str,
    /// "For".
    pub for_board: &'static str,
    /// "Tolerance for fitted animations (°)".
    pub tolerance: &'static str,
    /// Column heads.
    pub channel: &'static str,
    /// "Name".
    pub name: &'static str,
    /// "Drives".
    pub drives: &'static str,
    /// "Zero".
    pub zero: &'static str,
    /// "Units per °".
    pub per_degree: &'static str,
    /// "Reversed".
    pub reversed: &'static str,
    /// "Offset °".
    pub offset: &'static str,
    /// "Now °".
    pub now: &'static str,
    /// "— not imported".
    pub not_imported: &'static str,
    /// "Time".
    pub time: &'static str,
    /// "Play".
    pub play: &'static str,
    /// "Pause".
    pub pause: &'static str,
    /// "Load map…".
    pub load_map: &'static str,
    /// "Save map…".
    pub save_map: &'static str,
    /// "Create".
    pub create: &'static str,
    /// "Cancel".
    pub cancel: &'static str,
    /// "Close".
    pub close: &'static str,
    /// "Not taken from the file".
    pub left_out: &'static str,
    /// "No rig: the Now column shows each servo's angle".
    pub no_rig: &'static str,
    /// "A base stores no motions".
    pub rflex: &'static str,
    /// "Imported".
    pub imported: &'static str,
    /// "Converted", "Approximated", "Dropped".
    pub report_heads: [&'static str; 3],
    /// "Joint map".
    pub joint_map: &'static str,
    /// The File menu's export entry and its window's title.
    pub export_title: &'static str,
    /// "Format".
    pub format: &'static str,
    /// The two formats written.
    pub formats: [&'static str; 2],
    /// "Macro", "Motion".
    pub subjects: [&'static str; 2],
    /// "Frames per second".
    pub fps: &'static str,
    /// "Export…".
    pub export: &'static str,
    /// "Nothing to export: the project holds no macro or motion".
    pub nothing: &'static str,
    /// "A Maestro takes a servo board's project".
    pub maestro_servo_only: &'static str,
    /// "Exported".
    pub exported: &'static str,
}

const ENGLISH: ImportWords = ImportWords {
    title: "Import from another tool…",
    reading: "Reading",
    motion: "Motion",
    all: "All",
    for_board: "Into this project's",
    tolerance: "Tolerance for fitted animations (°)",
    channel: "Channel",
    name: "Name",
    drives: "Drives",
    zero: "Zero",
    per_degree: "Units per °",
    reversed: "Reversed",
    offset: "Offset °",
    now: "Now °",
    not_imported: "— not imported",
    time: "Time (s)",
    play: "Play",
    pause: "Pause",
    load_map: "Load map…",
    save_map: "Save map…",
    create: "Create",
    cancel: "Cancel",
    close: "Close",
    left_out: "Not taken from the file",
    no_rig: "This project has no rig to draw: the Now column shows each servo's angle.",
    rflex: "An rFLEX base stores no motions: switch the project to a servo board or a PLEN2 first.",
    imported: "Imported",
    report_heads: ["Converted", "Approximated", "Dropped"],
    joint_map: "Servo Studio joint map",
    export_title: "Export for another tool…",
    format: "Format",
    formats: ["Maestro settings file (sequences)", "Blender servo-animation JSON"],
    subjects: ["Macro", "Motion"],
    fps: "Frames per second",
    export: "Export…",
    nothing: "Nothing to export: the project holds no macro or motion.",
    maestro_servo_only: "A Maestro settings file is written from a servo board's project.",
    exported: "Exported",
};

const CHINESE: ImportWords = ImportWords {
    title: "從其他工具匯入…",
    reading: "讀取中",
    motion: "動作",
    all: "全部",
    for_board: "匯入此專案的",
    tolerance: "擬合動畫的容許誤差（°）",
    channel: "通道",
    name: "名稱",
    drives: "驅動",
    zero: "零點",
    per_degree: "每度單位",
    reversed: "反向",
    offset: "偏移 °",
    now: "目前 °",
    not_imported: "— 不匯入",
    time: "時間（秒）",
    play: "播放",
    pause: "暫停",
    load_map: "載入對應…",
    save_map: "儲存對應…",
    create: "建立",
    cancel: "取消",
    close: "關閉",
    left_out: "未從檔案取用",
    no_rig: "此專案沒有可繪製的骨架：「目前」欄顯示各伺服機角度。",
    rflex: "rFLEX 底盤不儲存動作：請先將專案切換為伺服板或 PLEN2。",
    imported: "已匯入",
    report_heads: ["已轉換", "近似處理", "已捨棄"],
    joint_map: "Servo Studio 關節對應",
    export_title: "匯出給其他工具…",
    format: "格式",
    formats: ["Maestro 設定檔（序列）", "Blender 伺服動畫 JSON"],
    subjects: ["巨集", "動作"],
    fps: "每秒影格數",
    export: "匯出…",
    nothing: "沒有可匯出的內容：專案中沒有巨集或動作。",
    maestro_servo_only: "Maestro 設定檔只能由伺服板專案匯出。",
    exported: "已匯出",
};

/// The captions in `language`.
pub fn words(language: Language) -> &'static ImportWords {
    match language {
        Language::English => &ENGLISH,
        Language::TraditionalChinese => &CHINESE,
    }
}
