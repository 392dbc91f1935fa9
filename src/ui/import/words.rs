//! The import window's own captions, in English and Traditional Chinese.

use crate::interchange::map::Target;
use crate::project::Family;
use crate::project::plen2::Joint;
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
    /// "Converted", "Approximated", "Dropped", "Notes".
    pub report_heads: [&'static str; 4],
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
    /// "Working out what the board plays…".
    pub checking: &'static str,
    /// "The board cannot play this:".
    pub board_cannot: &'static str,
    /// "The board plays this as the file says (within 0.1°)."
    pub same_as_file: &'static str,
    /// Where the board plays farthest from the file: channel, what it drives, degrees, seconds, whether at a limit.
    pub differs: fn(&str, &str, f64, f64, bool) -> String,
    /// "servo {id}".
    pub servo: fn(u8) -> String,
    /// A family's name: servo board, PLEN2, rFLEX base.
    pub families: [(&'static str, &'static str); 3],
    /// The formats read, by their command-line word.
    pub read_formats: [(&'static str, &'static str); 4],
    /// A PLEN2 joint's name from its parts: side, part, axis.
    pub joint: fn(Joint) -> String,
    /// The notes of a conversion in this language: (English pattern, this language's), `{}` a hole.
    pub notes: &'static [(&'static str, &'static str)],
    /// "The servo {id} is already in this project: …" — a map entry landing on a servo in use.
    pub in_use: fn(&str, &str) -> String,
    /// "Two channels drive {target}: …".
    pub twice: fn(&str, &str) -> String,
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
    report_heads: ["Converted", "Approximated", "Dropped", "Notes"],
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
    checking: "Working out what the board plays…",
    board_cannot: "The board cannot play this:",
    same_as_file: "The board plays this as the file says (within 0.1°).",
    differs: |channel, target, degrees, seconds, limited| {
        let why = if limited { "held at its limit" } else { "see Approximated" };
        format!(
            "The board plays channel {channel} ({target}) up to {degrees:.1}° from the file (at {seconds:.2} s): {why}."
        )
    },
    servo: |id| format!("servo {id}"),
    families: [("servo", "servo board"), ("plen2", "PLEN2"), ("rflex", "rFLEX base")],
    read_formats: [
        ("maestro", "Maestro settings file"),
        ("mtn", "RoboPlus Motion .mtn"),
        ("mtnx", "R+ Motion .mtnx"),
        ("blender", "Blender servo-animation JSON"),
    ],
    joint: |joint| joint.name().to_string(),
    notes: &[],
    in_use: |channel, target| {
        format!(
            "Channel {channel} drives {target}, which this project already has: its limits and home in the project are kept."
        )
    },
    twice: |channels, target| format!("Channels {channels} all drive {target}: only one of them will be seen."),
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
    report_heads: ["已轉換", "近似處理", "已捨棄", "附註"],
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
    checking: "正在推算開發板實際播放的動作…",
    board_cannot: "開發板無法播放：",
    same_as_file: "開發板播放的與檔案相同（誤差 0.1° 以內）。",
    differs: |channel, target, degrees, seconds, limited| {
        let why = if limited { "停在其限制值" } else { "見「近似處理」" };
        format!("開發板播放的通道 {channel}（{target}）與檔案最多相差 {degrees:.1}°（於 {seconds:.2} 秒）：{why}。")
    },
    servo: |id| format!("伺服機 {id}"),
    families: [("servo", "伺服板"), ("plen2", "PLEN2"), ("rflex", "rFLEX 底盤")],
    read_formats: [
        ("maestro", "Maestro 設定檔"),
        ("mtn", "RoboPlus Motion .mtn 檔"),
        ("mtnx", "R+ Motion .mtnx 檔"),
        ("blender", "Blender 伺服動畫 JSON"),
    ],
    joint: chinese_joint,
    notes: CHINESE_NOTES,
    in_use: |channel, target| format!("通道 {channel} 驅動的{target}已在此專案中：保留專案中它的限制與原點。"),
    twice: |channels, target| format!("通道 {channels} 都驅動{target}：只會看到其中一個。"),
};

/// A PLEN2 joint in Chinese: side, part, axis.
fn chinese_joint(joint: Joint) -> String {
    let name = joint.name();
    let side = if name.starts_with("left") { "左" } else { "右" };
    let part = [("shoulder", "肩"), ("elbow", "肘"), ("thigh", "大腿"), ("knee", "膝"), ("foot", "腳踝")]
        .iter()
        .find(|(word, _)| name.contains(word))
        .map_or("", |(_, part)| part);
    let axis = [("pitch", "俯仰"), ("roll", "側滾"), ("yaw", "偏擺")]
        .iter()
        .find(|(word, _)| name.ends_with(word))
        .map_or("", |(_, axis)| axis);
    format!("{side}{part}{axis}")
}

/// A family's name in these words.
pub fn family(family: Family, words: &ImportWords) -> &'static str {
    words.families.iter().find(|(tag, _)| *tag == family.tag()).map_or_else(|| family.name(), |(_, name)| name)
}

/// A format's name in these words.
pub fn format(format: crate::interchange::Format, words: &ImportWords) -> &'static str {
    words.read_formats.iter().find(|(tag, _)| *tag == format.tag()).map_or_else(|| format.name(), |(_, name)| name)
}

/// What a map entry drives, in these words.
pub fn target(target: Target, words: &ImportWords) -> String {
    match target {
        Target::Servo(id) => (words.servo)(id),
        Target::Joint(joint) => (words.joint)(joint),
    }
}

/// A conversion's note or error in these words: the first pattern it fits,
/// its holes carried over; as it is when none fits (English).
pub fn note(text: &str, words: &ImportWords) -> String {
    words.notes.iter().find_map(|(english, ours)| fill(text, english, ours)).unwrap_or_else(|| text.to_string())
}

/// `text` read by `pattern` (`{}` a hole: as little as reaches the next
/// literal part, the last hole up to the pattern's end) and written by `into`.
fn fill(text: &str, pattern: &str, into: &str) -> Option<String> {
    let parts: Vec<&str> = pattern.split("{}").collect();
    let (first, rest) = parts.split_first()?;
    let mut left = text.strip_prefix(first)?;
    let mut holes = Vec::new();
    for (index, part) in rest.iter().enumerate() {
        let end = if index + 1 == rest.len() {
            if !left.ends_with(part) {
                return None;
            }
            left.len() - part.len()
        } else if part.is_empty() {
            0
        } else {
            left.find(part)?
        };
        holes.push(&left[..end]);
        left = &left[end + part.len()..];
    }
    if !left.is_empty() && rest.is_empty() {
        return None;
    }
    let mut out = String::new();
    let mut holes = holes.into_iter();
    for (index, part) in into.split("{}").enumerate() {
        if index > 0 {
            out.push_str(holes.next().unwrap_or_default());
        }
        out.push_str(part);
    }
    Some(out)
}

/// Every note and error a conversion says, in Traditional Chinese.
const CHINESE_NOTES: &[(&str, &str)] = &[
    ("{} servos, {} actions, {} macros", "{} 個伺服機、{} 個動作步、{} 個巨集"),
    ("{}: motion in slot {} ({} frames)", "{}：動作存於第 {} 格（{} 個影格）"),
    (
        "{}: {} samples at {} fps fitted into {} steps within {}° (asked {}°)",
        "{}：{} 個取樣（每秒 {} 格）擬合為 {} 步，誤差 {}°（要求 {}°）",
    ),
    (
        "{}: {} samples at {} fps fitted into {} frames within {}° (asked {}°)",
        "{}：{} 個取樣（每秒 {} 格）擬合為 {} 個影格，誤差 {}°（要求 {}°）",
    ),
    (
        "next pages: the jumped-to motion plays on the same cycles as the one before, so the robot plays the chain as one",
        "下一頁：跳至的動作沿用前一個動作的週期，機器人將整串當成一個動作播放",
    ),
    (
        "times kept on the board's {} ms updates: every key within {} ms of the file's time, rounding never adding up",
        "時間以開發板的 {} 毫秒更新累計：每個關鍵點與檔案時間相差不超過 {} 毫秒，捨入誤差不會累加",
    ),
    (
        "times kept on the PLEN2's {} ms cycles: every key within {} ms of the file's time, rounding never adding up",
        "時間以 PLEN2 的 {} 毫秒週期累計：每個關鍵點與檔案時間相差不超過 {} 毫秒，捨入誤差不會累加",
    ),
    (
        "steps shorter than a {} ms cycle take a whole cycle (a PLEN2 does no less): the key after one is up to {} ms late, the keys after it keep their time",
        "短於一個 {} 毫秒週期的步驟佔用整個週期（PLEN2 無法更短）：其後的關鍵點最多晚 {} 毫秒，之後的關鍵點仍保持原時間",
    ),
    (
        "a repeated motion loops its frames: each pass after the first ends one {} ms cycle later than the file's (the first pass's first cycle is output as it starts, a loop's is not)",
        "重複的動作以迴圈播放其影格：第一遍之後每一遍都比檔案晚一個 {} 毫秒週期結束（第一遍的第一個週期在開始時即輸出，迴圈則否）",
    ),
    (
        "a repeated motion over 20 frames: a play list repeats it (a loop stays within one motion)",
        "超過 20 個影格的重複動作：以播放清單重複（迴圈只能在一個動作之內）",
    ),
    (
        "a move of no time (a jump): it takes as long as the live speed limit (180°/s) needs, so that no servo slams",
        "零時間的移動（跳躍）：依即時速度限制（180°/秒）所需的時間移動，避免伺服機猛撞",
    ),
    (
        "a Maestro frame shorter than a channel's speed limit needs: the servo goes as far as the Maestro gets it before the next frame",
        "Maestro 影格短於通道速度限制所需：伺服機只走到 Maestro 在下一影格前能帶到的位置",
    ),
    (
        "exit pages: a macro \"… then exit\" plays the page, then its exit page (a board has no stop-then-exit)",
        "結束頁：巨集「…然後結束」先播放該頁，再播放其結束頁（開發板沒有「停止後結束」）",
    ),
    (
        "exit pages: a play list \"… then exit\" plays the page, then its exit page",
        "結束頁：播放清單「…然後結束」先播放該頁，再播放其結束頁",
    ),
    (
        "next pages that loop forever: the macros play the loop once through (a macro cannot call itself)",
        "無限循環的下一頁：巨集只播放一輪（巨集不能呼叫自己）",
    ),
    (
        "played until stopped: the macro plays it once (a macro's loop count is at least 1)",
        "播放到停止為止：巨集只播放一次（巨集的迴圈次數至少為 1）",
    ),
    ("played faster than authored: a macro plays at most at 100 %", "比原速更快的播放：巨集最多以 100 % 播放"),
    (
        "a flow's unit speeds: a play list plays each motion at its own speed",
        "流程單元的速度：播放清單以各動作自身的速度播放",
    ),
    ("a flow of over {} units: its play list keeps the first {}", "超過 {} 個單元的流程：播放清單只保留前 {} 個"),
    ("motion names cut to a PLEN2's 20 ASCII characters", "動作名稱截短為 PLEN2 的 20 個 ASCII 字元"),
    ("joint angles beyond ±180° from home are held at ±180°", "超出原點 ±180° 的關節角度保持在 ±180°"),
    ("positions beyond a servo's limits are held at the limit", "超出伺服機限制的位置保持在限制值"),
    ("a move over 327 s is cut to 327 s (a step's longest)", "超過 327 秒的移動截為 327 秒（單步最長）"),
    (
        "the servos start the animation from its first frame: their home is set there",
        "伺服機從動畫的第一格開始：原點設在該處",
    ),
    ("compliance and inertial force (each step moves straight)", "柔順度與慣性力（每步都直線移動）"),
    ("acceleration limits (the board moves each step at one speed)", "加速度限制（開發板每步以單一速度移動）"),
    ("the script (a board runs no Maestro script)", "腳本（開發板不執行 Maestro 腳本）"),
    (
        "buckets (a controller's list of flows to call by number): convert each flow",
        "Bucket（控制器依編號呼叫的流程清單）：請逐一轉換各流程",
    ),
    ("joints the file's robot has switched off (enable=\"False\")", "檔案中機器人已關閉的關節（enable=\"False\"）"),
    ("channels mapped to PLEN2 joints (this is a servo board)", "對應到 PLEN2 關節的通道（這是伺服板）"),
    ("a target of 0 (a channel's pulses off): the servo stays where it is", "目標為 0（通道關閉脈衝）：伺服機停在原處"),
    ("channel {}: not mapped", "通道 {}：未對應"),
    ("channel {} ({}): not a servo", "通道 {}（{}）：不是伺服機"),
    ("flow {}: no units, nothing to play", "流程 {}：沒有單元，無可播放"),
    ("page {}: a next or exit page with no steps", "第 {} 頁：下一頁或結束頁沒有步驟"),
    ("frames past {} in one sequence", "單一序列中超過 {} 的影格"),
    ("macros nested over {} deep", "巢狀超過 {} 層的巨集"),
    ("made for a robot of {}: ids and ranges are taken from it", "為 {} 的機器人製作：採用其編號與轉動範圍"),
    ("made for {}, a robot of {}: ids and ranges are taken from it", "為 {}（{} 的機器人）製作：採用其編號與轉動範圍"),
    ("its controller: {}", "控制器：{}"),
    (
        "its ids are a Bioloid humanoid's, so PLEN2 joints are guessed from them",
        "其編號屬於 Bioloid 人形機器人，因此據以推測 PLEN2 關節",
    ),
    (
        "not a Bioloid humanoid, so no PLEN2 joint is guessed: map them in the table or with --map",
        "不是 Bioloid 人形機器人，因此不推測 PLEN2 關節：請在表格中或以 --map 對應",
    ),
    (
        "RoboPlus's checksum after the last page matches: the file is as RoboPlus saved it",
        "最後一頁後的 RoboPlus 檢查碼相符：檔案與 RoboPlus 儲存時相同",
    ),
    (
        "RoboPlus's checksum after the last page is {}, the content's is {}: the file was edited outside RoboPlus (it is read all the same)",
        "最後一頁後的 RoboPlus 檢查碼為 {}，內容計算為 {}：檔案曾在 RoboPlus 以外編輯（仍照常讀取）",
    ),
    (
        "saved on a decimal-comma locale: \"0,096\" read as 0.096 s",
        "以逗號為小數點的地區設定儲存：「0,096」讀作 0.096 秒",
    ),
    ("read as UTF-16 (its byte-order mark says so)", "依位元組順序記號以 UTF-16 讀取"),
    (
        "bytes that are not UTF-8 (the first on line {}) are shown as \u{fffd}: a name saved in another code page; save the file as UTF-8 to keep it",
        "非 UTF-8 的位元組（第一個在第 {} 行）顯示為 \u{fffd}：名稱以其他字碼頁儲存；請將檔案存為 UTF-8 以保留",
    ),
    (
        "no channel drives a {}: give a joint map (--map) that says which channel drives which",
        "沒有通道驅動{}：請提供關節對應（--map）說明哪個通道驅動哪個",
    ),
    ("{} is not in the file; it holds: {}", "檔案中沒有 {}；它包含：{}"),
    ("the file holds no motion to convert", "檔案中沒有可轉換的動作"),
    ("servos already in the project keep their settings: {}", "專案中已有的伺服機保留其設定：{}"),
    ("actions and macros take ids the project does not use yet", "動作步與巨集使用專案尚未使用的編號"),
    (
        "the import needs {} motion slots and the project has {} free: remove motions, or import fewer (choose one)",
        "匯入需要 {} 個動作格，專案只有 {} 格空著：請移除動作，或少匯入一些（選擇單一動作）",
    ),
    (
        "the motions need {} slots and a PLEN2 holds {}: convert fewer at once (--page, --sequence)",
        "這些動作需要 {} 格，PLEN2 只有 {} 格：請一次轉換較少（選擇單一動作）",
    ),
    (
        "{} steps are needed to stay within {}° and at most {} fit: the smallest tolerance that fits is --tolerance-deg {}. Nothing was written",
        "需要 {} 個步驟才能維持在 {}° 以內，最多只能放 {} 個：可行的最小容許誤差為 {}°。未寫入任何內容",
    ),
    (
        "{} frames are needed to stay within {}° and at most {} fit: the smallest tolerance that fits is --tolerance-deg {}. Nothing was written",
        "需要 {} 個影格才能維持在 {}° 以內，最多只能放 {} 個：可行的最小容許誤差為 {}°。未寫入任何內容",
    ),
    (
        "the animation lasts {} board updates: that takes at least {} steps at any tolerance, and at most {} fit. Nothing was written",
        "動畫長達 {} 次開發板更新：任何容許誤差下至少需要 {} 個步驟，最多只能放 {} 個。未寫入任何內容",
    ),
    (
        "the animation lasts {} board updates: that takes at least {} frames at any tolerance, and at most {} fit. Nothing was written",
        "動畫長達 {} 次開發板更新：任何容許誤差下至少需要 {} 個影格，最多只能放 {} 個。未寫入任何內容",
    ),
];

/// The captions in `language`.
pub fn words(language: Language) -> &'static ImportWords {
    match language {
        Language::English => &ENGLISH,
        Language::TraditionalChinese => &CHINESE,
    }
}
