#!/usr/bin/python3
"""The characters the shipped CJK font keeps (one `U+XXXX` per line):
Big5 (Traditional Chinese), JIS X 0208 with Microsoft's extensions (cp932:
Japanese kanji and kana), KS X 1001 (Korean, with its hanja), every Hangul
syllable and jamo, kana, bopomofo, and CJK / fullwidth punctuation and symbols.

    python3 assets/fonts/repertoire.py > unicodes.txt
    python3 -m fontTools.subset NotoSansCJK-Regular.ttc --font-number=3 \
        --unicodes-file=unicodes.txt --layout-features='*' --no-hinting \
        --output-file=assets/fonts/NotoSansCJK-Subset.otf
"""

chars = set()


def two_bytes(codec, leads, trails):
    for lead in leads:
        for trail in trails:
            try:
                chars.update(bytes([lead, trail]).decode(codec))
            except UnicodeDecodeError:
                pass


two_bytes("big5", range(0x81, 0xFF), list(range(0x40, 0x7F)) + list(range(0xA1, 0xFF)))
two_bytes("cp932", list(range(0x81, 0xA0)) + list(range(0xE0, 0xF0)), range(0x40, 0xFD))
two_bytes("euc_kr", range(0xA1, 0xFF), range(0xA1, 0xFF))
RANGES = [
    (0x0020, 0x007E), (0x00A0, 0x00FF),  # Latin (egui's own fonts come first)
    (0x1100, 0x11FF), (0x3130, 0x318F), (0xAC00, 0xD7A3),  # Hangul jamo, compatibility jamo, syllables
    (0x3040, 0x30FF), (0x31F0, 0x31FF),  # kana
    (0x3000, 0x303F), (0x3100, 0x312F), (0xFF00, 0xFFEF),  # CJK punctuation, bopomofo, fullwidth
    (0x2000, 0x206F), (0x2150, 0x218F), (0x2190, 0x21FF),  # punctuation, number forms, arrows
    (0x2460, 0x24FF), (0x25A0, 0x25FF), (0x2600, 0x26FF),  # enclosed numbers, shapes, symbols
    (0x3200, 0x32FF), (0x3300, 0x33FF),  # enclosed CJK, compatibility (units)
]
for first, last in RANGES:
    chars.update(chr(code) for code in range(first, last + 1))
print("\n".join(f"U+{ord(c):04X}" for c in sorted(chars) if ord(c) >= 0x20))
