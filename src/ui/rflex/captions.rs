//! The rFLEX base's own captions, in English and Traditional Chinese: the
//! words only its panels use (the shell's and the shared ones are in `ui::i18n`).
//! A panel holding the interface's [`Strings`] reaches them as `words.rflex()`.

use crate::ui::i18n::{Language, Strings};

/// The rFLEX base's own captions.
#[derive(Debug)]
pub struct RflexCaptions {
    /// "Odometry".
    pub odometry: &'static str,
    /// "Measured".
    pub measured: &'static str,
    /// "Acceleration (m/s²)".
    pub acceleration: &'static str,
    /// "Sonar".
    pub sonar: &'static str,
    /// "Drag in the pad, or hold the arrow keys; release to stop. Space or Esc: STOP.".
    pub pad_hint: &'static str,
    /// "Top speed (m/s)".
    pub max_speed: &'static str,
    /// "Top turn (rad/s)".
    pub max_turn: &'static str,
    /// "Joystick".
    pub joystick_state: &'static str,
    /// "STOP: the base was told to stop at once".
    pub msg_base_stopped: &'static str,
    /// "The base stopped answering while driving; it was sent a stop. Check the cable and its power.".
    pub msg_base_silent: &'static str,
    /// "connected to the demo base (emulated, braked, in a 4.2 × 2.8 m room)".
    pub msg_connected_demo_rflex: &'static str,
    /// The status after the brake was set.
    pub msg_brake_on: &'static str,
    /// The status after the brake was released.
    pub msg_brake_released: &'static str,
    /// What "(+N ?)" after the sonar count means.
    pub sonar_unknown_hint: &'static str,
    /// The rFLEX world view.
    pub world_view: &'static str,
    /// Follow the base in the world view.
    pub follow: &'static str,
    /// Forget the echoes seen.
    pub clear_map: &'static str,
    /// How the world view is moved.
    pub world_hint: &'static str,
    /// The drive pad says the window lacks keyboard focus.
    pub drive_needs_focus: &'static str,
    /// How the gamepad drives.
    pub gamepad_hint: &'static str,
    /// "driving".
    pub pad_driving: &'static str,
    /// "stopped: the dead-man button is not held".
    pub pad_released: &'static str,
    /// "stopped: the stick is centred".
    pub pad_centred: &'static str,
    /// "stopped: the gamepad's events were dropped; press the dead-man again".
    pub pad_dropped: &'static str,
    /// "stopped: let go of the dead-man and press it again to drive".
    pub pad_halted: &'static str,
}

const ENGLISH: RflexCaptions = RflexCaptions {
    odometry: "Odometry",
    measured: "Measured",
    acceleration: "Acceleration (m/s²)",
    sonar: "Sonar",
    pad_hint: "Drag in the pad, or hold the arrow keys; release to stop. Space or Esc: STOP.",
    max_speed: "Top speed (m/s)",
    max_turn: "Top turn (rad/s)",
    joystick_state: "Joystick",
    msg_base_stopped: "STOP: the base was told to stop at once",
    msg_base_silent: "The base stopped answering while driving; it was sent a stop. Check the cable and its power.",
    msg_connected_demo_rflex: "connected to the demo base (emulated, braked, in a 4.2 × 2.8 m room)",
    msg_brake_on: "Brake on: the base holds still",
    msg_brake_released: "Brake released: the base can drive",
    sonar_unknown_hint: "(+N ?): readings for sonar ids this robot does not have; they are not drawn.",
    world_view: "World view",
    follow: "Follow the base",
    clear_map: "Clear the map",
    world_hint: "Drag to pan, wheel to zoom, double-click to centre on the base",
    drive_needs_focus: "The keys do nothing: the window does not have the keyboard focus. Click in the window first.",
    gamepad_hint: "A gamepad drives too: hold the left shoulder (BTN_TL) and move the left stick; let go to stop. Choose it on the Gamepad tab.",
    pad_driving: "driving",
    pad_released: "stopped: the dead-man button (left shoulder) is not held",
    pad_centred: "stopped: the stick is centred",
    pad_dropped: "stopped: the gamepad's events were dropped; press the dead-man again",
    pad_halted: "stopped: let go of the dead-man and press it again to drive",
};

const TRADITIONAL_CHINESE: RflexCaptions = RflexCaptions {
    odometry: "里程",
    measured: "實測",
    acceleration: "加速度（m/s²）",
    sonar: "聲納",
    pad_hint: "在方塊中拖曳，或按住方向鍵；放開即停止。空白鍵或 Esc：停止。",
    max_speed: "最高速度（m/s）",
    max_turn: "最高轉速（rad/s）",
    joystick_state: "搖桿",
    msg_base_stopped: "停止：已命令底盤立即停止",
    msg_base_silent: "行駛中底盤停止回應，已送出停止指令。請檢查線材與電源。",
    msg_connected_demo_rflex: "已連線至示範底盤（模擬，已煞車，位於 4.2 × 2.8 公尺的房間）",
    msg_brake_on: "煞車已啟用：底盤保持不動",
    msg_brake_released: "煞車已放開：底盤可以行駛",
    sonar_unknown_hint: "（+N ?）：這台機器人沒有的聲納編號的讀數；不會畫出。",
    world_view: "環境地圖",
    follow: "跟隨底盤",
    clear_map: "清除地圖",
    world_hint: "拖曳平移，滾輪縮放，按兩下回到底盤",
    drive_needs_focus: "按鍵沒有作用：視窗沒有鍵盤焦點。請先點一下視窗。",
    gamepad_hint: "也可用遊戲手把行駛：按住左肩鍵（BTN_TL）並推動左搖桿；放開即停止。請在「遊戲手把」分頁選擇手把。",
    pad_driving: "行駛中",
    pad_released: "已停止：未按住安全鍵（左肩鍵）",
    pad_centred: "已停止：搖桿在中央",
    pad_dropped: "已停止：手把的事件遺失；請重新按下安全鍵",
    pad_halted: "已停止：放開安全鍵再按一次才能行駛",
};

/// The rFLEX base's captions in the interface's language.
pub trait RflexWords {
    /// The rFLEX base's captions in this language.
    fn rflex(&self) -> &'static RflexCaptions;
}

impl RflexWords for Strings {
    fn rflex(&self) -> &'static RflexCaptions {
        match self.lang {
            Language::English => &ENGLISH,
            Language::TraditionalChinese => &TRADITIONAL_CHINESE,
        }
    }
}
