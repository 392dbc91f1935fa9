//! The shipped CJK font: egui's own fonts have no CJK glyphs, so captions in
//! Chinese, Japanese or Korean would render as boxes without it.

use std::sync::Arc;

/// Noto Sans CJK TC, subset to Big5, JIS X 0208, KS X 1001, every Hangul
/// syllable and kana (28,563 characters, 8.8 MB; see `assets/README.md`).
pub const CJK_FONT: &[u8] = include_bytes!("../../assets/fonts/NotoSansCJK-Subset.otf");

/// The replacement character `�` alone (DejaVu Sans): what a name read from a
/// file in another code page shows, which neither egui's fonts nor Noto CJK have.
pub const REPLACEMENT_FONT: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans-Replacement.ttf");

/// The fonts of the interface: egui's, then the CJK font and the replacement
/// character as fallbacks, for both families.
pub fn definitions() -> egui::FontDefinitions {
    let mut fonts = egui::FontDefinitions::default();
    fonts.font_data.insert("noto-sans-cjk".into(), Arc::new(egui::FontData::from_static(CJK_FONT)));
    fonts.font_data.insert("replacement".into(), Arc::new(egui::FontData::from_static(REPLACEMENT_FONT)));
    for family in [egui::FontFamily::Proportional, egui::FontFamily::Monospace] {
        fonts.families.entry(family).or_default().extend(["noto-sans-cjk".into(), "replacement".into()]);
    }
    fonts
}

/// Installs [`definitions`] in `ctx`.
pub fn install(ctx: &egui::Context) {
    ctx.set_fonts(definitions());
    // No text smaller than the body's: a note, a hint, a log line is read as
    // easily as a caption (egui's "small" style is 9 px, CJK unreadable at it).
    ctx.all_styles_mut(|style| {
        let body = style.text_styles.get(&egui::TextStyle::Body).map_or(13.0, |font| font.size);
        style.text_styles.insert(egui::TextStyle::Small, egui::FontId::proportional(body));
    });
}

#[cfg(test)]
mod tests {
    use crate::ui::i18n::{Catalogue, Language};

    /// Every string of a language's file, an array's in turn.
    fn strings(value: &toml::Value, into: &mut Vec<String>) {
        match value {
            toml::Value::String(text) => into.push(text.clone()),
            toml::Value::Array(values) => values.iter().for_each(|value| strings(value, into)),
            toml::Value::Table(table) => table.values().for_each(|value| strings(value, into)),
            _ => {}
        }
    }

    /// The characters of `texts` the interface's fonts have no glyph for.
    fn missing_glyphs(texts: &[String]) -> Vec<char> {
        let ctx = egui::Context::default();
        super::install(&ctx);
        ctx.run_ui(egui::RawInput::default(), |_| {}).textures_delta.clear();
        let font = egui::FontId::proportional(14.0);
        let mut missing: Vec<char> = ctx.fonts_mut(|fonts| {
            for text in texts {
                // Laid out as a label would be, so a missing glyph is what the label would show.
                let _ = fonts.layout_no_wrap(text.clone(), font.clone(), egui::Color32::WHITE);
            }
            texts
                .iter()
                .flat_map(|text| text.chars())
                .filter(|c| !c.is_control() && !fonts.has_glyph(&font, *c))
                .collect()
        });
        missing.sort_unstable();
        missing.dedup();
        missing
    }

    /// Every string of every language's file renders with the shipped fonts.
    #[test]
    fn every_string_of_every_language_has_its_glyphs() {
        for language in Language::ALL {
            let mut texts = Vec::new();
            for key in Catalogue::of(language).keys() {
                strings(Catalogue::of(language).value(&key).unwrap(), &mut texts);
            }
            assert!(texts.len() > 700, "{}: {} strings", language.name(), texts.len());
            let missing = missing_glyphs(&texts);
            assert!(missing.is_empty(), "{}: no glyph for {missing:?}", language.name());
        }
    }

    /// Captions and names a user types, in any of the four scripts: every
    /// kana, every Hangul syllable, and Han characters of each language.
    #[test]
    fn names_in_every_script_have_their_glyphs() {
        let ranges =
            [('\u{3041}', '\u{3096}'), ('\u{30a1}', '\u{30fa}'), ('\u{ac00}', '\u{d7a3}'), ('\u{3131}', '\u{318e}')];
        let mut texts: Vec<String> = ranges.iter().map(|(first, last)| (*first..=*last).collect()).collect();
        texts.push("機器人動作巨集 繁體中文 舵機控制板".into());
        texts.push("関節モーション 変換 図 応答 選択 続行 読込 歩行 気温".into());
        texts.push("로봇 서보 관절 모션 똠방각하 펲시콜라 뷁".into());
        assert_eq!(missing_glyphs(&texts), Vec::<char>::new());
    }
}
