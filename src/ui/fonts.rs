//! The shipped CJK font: egui's own fonts have no CJK glyphs, so captions in
//! Traditional Chinese would render as boxes without it.

use std::sync::Arc;

/// Noto Sans CJK TC, subset to the Big5 repertoire (see `assets/README.md`).
pub const CJK_FONT: &[u8] = include_bytes!("../../assets/fonts/NotoSansTC-Subset.otf");

/// Adds the CJK font as a fallback after egui's fonts, for both families.
pub fn install(ctx: &egui::Context) {
    let mut fonts = egui::FontDefinitions::default();
    fonts.font_data.insert("noto-sans-tc".into(), Arc::new(egui::FontData::from_static(CJK_FONT)));
    for family in [egui::FontFamily::Proportional, egui::FontFamily::Monospace] {
        fonts.families.entry(family).or_default().push("noto-sans-tc".into());
    }
    ctx.set_fonts(fonts);
}
