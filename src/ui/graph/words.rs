//! The graph pane's words, in both languages.

use crate::ui::i18n::Language;

/// Every caption of the graph pane.
#[derive(Debug)]
pub struct GraphWords {
    /// The pane's title: "Graph".
    pub title: &'static str,
    /// "All" (show every channel).
    pub all: &'static str,
    /// "None" (hide every channel).
    pub none: &'static str,
    /// A channel's solo toggle: "Solo".
    pub solo: &'static str,
    /// Hover of a legend entry.
    pub toggle_hint: &'static str,
    /// "Copy curve".
    pub copy_curve: &'static str,
    /// "Paste curve".
    pub paste_curve: &'static str,
    /// "Curve" (the preset picker for the selected keys).
    pub curve: &'static str,
    /// Each preset's name, in `Easing::ALL` order, then a shaped curve's.
    pub presets: [&'static str; 6],
    /// "keys selected".
    pub selected: &'static str,
    /// How to work the graph (hover of the help mark).
    pub how: &'static str,
    /// The legend's entry for what the board plays: "dashed: what the board plays".
    pub baked: &'static str,
    /// The value axis: "Angle (°)".
    pub angle_axis: &'static str,
    /// A key's accessible name: "key".
    pub key: &'static str,
    /// A handle's accessible name: "handle".
    pub handle: &'static str,
}

const ENGLISH: GraphWords = GraphWords {
    title: "Graph",
    all: "All",
    none: "None",
    solo: "Solo",
    toggle_hint: "Click to show or hide this channel",
    copy_curve: "Copy curve",
    paste_curve: "Paste curve",
    curve: "Curve",
    presets: ["Linear", "Ease in", "Ease out", "Ease in-out", "Hold", "Shaped"],
    selected: "keys selected",
    how: "Drag a key to move it in time (snapped to the board's updates) and value (kept within the limits); \
          drag a handle to shape the move into it; Shift+drag on the graph selects keys (Shift+click adds one), \
          and dragging one of them moves them all. Every drag is one undo step. Drag the background to pan, \
          scroll with Ctrl to zoom.",
    baked: "dashed: what the board plays",
    angle_axis: "Angle (°)",
    key: "key",
    handle: "handle",
};

const TRADITIONAL_CHINESE: GraphWords = GraphWords {
    title: "曲線圖",
    all: "全部",
    none: "全不選",
    solo: "單獨",
    toggle_hint: "按一下以顯示或隱藏此通道",
    copy_curve: "複製曲線",
    paste_curve: "貼上曲線",
    curve: "曲線",
    presets: ["線性", "漸入", "漸出", "漸入漸出", "保持", "自訂曲線"],
    selected: "個關鍵點已選取",
    how: "拖曳關鍵點可改變時間（對齊控制板的更新）與數值（限制在範圍內）；拖曳控制桿可調整進入該點的曲線；\
          在圖上按住 Shift 拖曳可框選關鍵點（Shift+按一下可加選），拖曳其中一個會一起移動。每次拖曳是一個復原步驟。\
          拖曳背景可平移，按住 Ctrl 捲動可縮放。",
    baked: "虛線：控制板實際播放",
    angle_axis: "角度 (°)",
    key: "關鍵點",
    handle: "控制桿",
};

/// The graph's words in `language`.
pub fn words(language: Language) -> &'static GraphWords {
    match language {
        Language::English => &ENGLISH,
        Language::TraditionalChinese => &TRADITIONAL_CHINESE,
    }
}
