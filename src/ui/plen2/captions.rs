//! The PLEN2's own captions, in English and Traditional Chinese: the
//! words only its panels use (the shell's and the shared ones are in `ui::i18n`).
//! A panel holding the interface's [`Strings`] reaches them as `words.plen2()`.

use crate::ui::i18n::{Language, Strings};

/// The PLEN2's own captions.
#[derive(Debug)]
pub struct Plen2Captions {
    /// "Factory joint settings".
    pub factory_reset: &'static str,
    /// "Frames".
    pub frames: &'static str,
    /// "Capture into frame".
    pub capture_frame: &'static str,
    /// "Add motion".
    pub add_motion: &'static str,
    /// "Loop frames".
    pub loop_frames: &'static str,
    /// "Then jump to slot".
    pub jump_to: &'static str,
    /// What a motion that jumps on plays into: `{slots}` and `{total}`.
    pub plays_on: &'static str,
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
    /// "Slot map: project / robot".
    pub slot_map: &'static str,
    /// "Joint settings (tenths of a degree; the robot stores them)".
    pub joint_settings: &'static str,
    /// "STOP: the motion stopped and every joint went home".
    pub msg_plen2_stopped: &'static str,
    /// What the pacing modes do (hover text).
    pub pacing_hint: &'static str,
    /// "connected to the demo PLEN2 (emulated, factory-fresh: its 90 slots are empty)".
    pub msg_connected_demo_plen2: &'static str,
    /// "Read the robot; motions it holds:".
    pub robot_read: &'static str,
    /// "Still different after writing again (check the cable and upload again), slots:".
    pub slots_differ: &'static str,
    /// The lower pane of the motion editor: "Frame values".
    pub frame_and_plot: &'static str,
    /// What the motion.json button does.
    pub motion_json_hint: &'static str,
    /// Which motion a PLEN2 motion is previewed after.
    pub played_after: &'static str,
    /// The robot just switched on (its frame buffer all zeros).
    pub power_up: &'static str,
    /// Where a PLEN2 motion starts from.
    pub snap_note: &'static str,
    /// The sliders' pose differs from where the motion starts.
    pub snap_warning: &'static str,
    /// The previewed motion never ends on the robot (plen2.md §6).
    pub motion_never_ends: &'static str,
    /// The previewed motion's first frame lasts 0 cycles: the robot divides by zero.
    pub first_frame_undefined: &'static str,
    /// Each curve's name, in `Easing::ALL` order, then a shaped one's.
    pub curves: [&'static str; 6],
    /// What a curve does to the frames the robot stores (hover text).
    pub curve_hint: &'static str,
    /// The budget meter: "On the robot".
    pub on_robot: &'static str,
    /// "frames of 20".
    pub frames_of_20: &'static str,
    /// "largest deviation from the curves".
    pub largest_deviation: &'static str,
    /// "the tolerance was widened from 1° so the curves fit in 20 frames".
    pub tolerance_widened: &'static str,
    /// What Record does (hover text).
    pub record_hint: &'static str,
    /// The motion has no room.
    pub msg_no_room: &'static str,
    /// Too long for the frames left.
    pub msg_recording_too_long: &'static str,
    /// "frames inserted after frame".
    pub frames_inserted_after: &'static str,
    /// The retimed span's last frame: "to frame".
    pub to_frame: &'static str,
}

const ENGLISH: Plen2Captions = Plen2Captions {
    factory_reset: "Factory joint settings",
    frames: "Frames",
    capture_frame: "Capture into frame",
    add_motion: "Add motion",
    loop_frames: "Loop frames",
    jump_to: "Then jump to slot",
    plays_on: "plays on into slot {slots} (each jumps to the next): {total} in all",
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
    slot_map: "Slot map (after Read robot — green: same as the project · amber: different · blue: only in the project · grey, in brackets: only on the robot)",
    joint_settings: "Joint settings (tenths of a degree; the robot stores them)",
    msg_plen2_stopped: "STOP: the motion stopped and every joint went home",
    pacing_hint: "How PLEN2 uploads are paced. Adaptive (default): fast, and more careful once the link shows it is late or bursty (a Bluetooth bridge) or a read-back differs. Fast: never widens. Safe: the official tool's 32 bytes, then 50 ms. Takes effect at the next connection.",
    msg_connected_demo_plen2: "connected to the demo PLEN2 (emulated, factory-fresh: its 90 slots are empty)",
    robot_read: "Read the robot; motions it holds:",
    slots_differ: "Still different after writing again (check the cable and upload again), slots:",
    frame_and_plot: "Frame values",
    motion_json_hint: "Save this motion as the official PLEN Motion Editor's motion.json",
    played_after: "Played after",
    power_up: "power-up (home)",
    snap_note: "On the robot a motion starts from the last frame the robot played (home after power-up), never from a pose set with the joint sliders.",
    snap_warning: "The joint sliders' pose is not where this motion starts: the robot will snap there at the first cycle.",
    motion_never_ends: "This motion never ends on the robot (a loop of count 0 or 255, or a jump to a slot it cannot play): the first 30 s are shown.",
    first_frame_undefined: "Its first frame lasts under 32 ms (0 cycles): the robot divides by zero there, so what it does is undefined. Give it 32 ms or more.",
    curves: ["Linear", "Ease in", "Ease out", "Ease in-out", "Hold", "Shaped"],
    curve_hint: "How the move to this frame runs. The robot plays only straight moves: a curve is stored as several straight frames within 1° of it (widened when the motion's 20 frames are short). The project keeps the curve.",
    on_robot: "On the robot",
    frames_of_20: "frames of 20",
    largest_deviation: "largest deviation from the curves",
    tolerance_widened: "the tolerance was widened from 1° so the curves fit in 20 frames",
    record_hint: "Record the joints as you move them (sliders, keys, a gamepad), after a 3 s count-in; Stop fits what you did into the fewest frames the robot plays within 1° (wider if the motion's 20 frames are short) and inserts them after the selected frame. One undo step.",
    msg_no_room: "The motion already holds 20 frames: nothing was inserted. Remove frames, or select another motion, and record again",
    msg_recording_too_long: "Too long for the frames left in the motion, at any tolerance (each frame lasts at most 8.2 s): nothing was inserted. Record a shorter movement, or remove frames first",
    frames_inserted_after: "frames inserted after frame",
    to_frame: "to frame",
};

const TRADITIONAL_CHINESE: Plen2Captions = Plen2Captions {
    factory_reset: "恢復出廠關節設定",
    frames: "影格",
    capture_frame: "擷取為影格",
    add_motion: "新增動作",
    loop_frames: "循環影格",
    jump_to: "接著跳到位置",
    plays_on: "接著播放位置 {slots}（每個動作接著跳到下一個）：共 {total}",
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
    slot_map: "槽位圖（讀取機器人後——綠：與專案相同 · 琥珀：不同 · 藍：僅在專案中 · 灰、括號內：僅在機器人上）",
    joint_settings: "關節設定（0.1 度；存於機器人）",
    msg_plen2_stopped: "停止：動作已停止，所有關節回到原點",
    pacing_hint: "PLEN2 上傳的傳送節奏。自動調整（預設）：快速，當連線顯示延遲或成批送達（藍牙橋接）或讀回內容不同時放慢。快速：不放慢。安全：官方工具的每 32 位元組等待 50 ms。下次連線時生效。",
    msg_connected_demo_plen2: "已連線至示範 PLEN2（模擬，出廠狀態：90 個槽位皆為空）",
    robot_read: "已讀取機器人；其中的動作數：",
    slots_differ: "重寫後仍不一致（請檢查連接線後再上傳一次），槽位：",
    frame_and_plot: "影格數值",
    motion_json_hint: "將此動作存成官方 PLEN Motion Editor 的 motion.json",
    played_after: "接在此動作之後",
    power_up: "開機（原位）",
    snap_note: "在機器人上，動作會從機器人最後播放的影格開始（開機後為原位），而不是從關節滑桿設定的姿勢開始。",
    snap_warning: "關節滑桿的姿勢與此動作的起點不同：機器人會在第一個週期瞬間跳到起點。",
    motion_never_ends: "這個動作在機器人上永遠不會結束（循環次數 0 或 255，或跳到無法播放的位置）：只顯示前 30 秒。",
    first_frame_undefined: "它的第一個影格不到 32 毫秒（0 個週期）：機器人會在這裡除以零，行為無法預測。請設為 32 毫秒以上。",
    curves: ["線性", "漸入", "漸出", "漸入漸出", "保持", "自訂曲線"],
    curve_hint: "移動到此影格的方式。機器人只播放直線移動：曲線會存成數個直線影格，與曲線相差不超過 1°（動作的 20 個影格不夠時會放寬）。專案保留原本的曲線。",
    on_robot: "機器人上",
    frames_of_20: "個影格（共 20）",
    largest_deviation: "與曲線的最大偏差",
    tolerance_widened: "為了讓曲線放進 20 個影格，容差已從 1° 放寬",
    record_hint: "倒數 3 秒後錄下你移動關節的過程（滑桿、按鍵、遊戲手把）；停止時會把動作擬合成機器人播放誤差在 1° 內的最少影格（動作的 20 個影格不夠時放寬），並插入在所選影格之後。可一步復原。",
    msg_no_room: "此動作已有 20 個影格：沒有插入任何內容。請刪除一些影格或選擇其他動作後再錄製",
    msg_recording_too_long: "對動作剩下的影格來說太長，任何容差都放不下（每個影格最長 8.2 秒）：沒有插入任何內容。請錄短一點，或先刪除一些影格",
    frames_inserted_after: "個影格，插入在影格之後：",
    to_frame: "到影格",
};

/// The PLEN2's captions in the interface's language.
pub trait Plen2Words {
    /// The PLEN2's captions in this language.
    fn plen2(&self) -> &'static Plen2Captions;
}

impl Plen2Words for Strings {
    fn plen2(&self) -> &'static Plen2Captions {
        match self.lang {
            Language::English => &ENGLISH,
            Language::TraditionalChinese => &TRADITIONAL_CHINESE,
        }
    }
}
