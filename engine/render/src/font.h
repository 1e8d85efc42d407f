// The renderer's built-in bitmap font: a fixed-width 5x7 pixel face for printable ASCII (32..126),
// so text (debug overlays, labels) needs no font files. glyph() gives a character's bitmap;
// layout_text() places a string's glyphs and measures it. The glyph art itself is in font.cpp.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

namespace jostle::detail {

// A glyph is 5x7 pixels; its cell is 6x8 (one empty column to the right, one empty row below) so
// neighbouring glyphs never touch. Lines are 9 pixels apart, leaving two empty rows between them.
inline constexpr int kGlyphWidth = 5, kGlyphHeight = 7, kGlyphAdvance = 6, kLineAdvance = 9;

// One glyph's bitmap: rows[y] has bit (4 - x) set when pixel (x, y) is on (x = 0 is the left
// column, y = 0 the top row). Bits 5..7 are always clear.
struct Glyph {
    std::uint8_t rows[kGlyphHeight];
    bool operator==(const Glyph&) const = default;
};

// The glyph for a character. Characters outside 32..126 (control characters, DEL, bytes of
// UTF-8 sequences) give the glyph for '?', so unsupported text shows up instead of vanishing.
const Glyph& glyph(char c);

// Where one character of laid-out text is drawn.
struct PlacedGlyph {
    char c;    // the character as given; draw glyph(c)
    int x, y;  // top-left of its cell in pixels, y down, relative to the text's top-left
};

// Lays out `text` with its top-left at (0, 0): characters advance kGlyphAdvance to the right and
// '\n' starts a new line kLineAdvance lower at x = 0. Returns one PlacedGlyph per character that
// draws something, in text order: ' ' and '\n' take space but give no entry (an empty glyph
// would be a wasted draw); every other character, including ones drawn as '?', gives one.
//
// Stores the text's size in pixels in *width and *height (either may be null): width is the
// widest line, a line of n characters (spaces included) being n * kGlyphAdvance - 1 wide (the
// last cell's spacing column is not part of the text); height is lines * kLineAdvance - 2 (the
// last line's spacing rows likewise), where a trailing '\n' counts as starting an empty line.
// Empty text is 0 x 0.
std::vector<PlacedGlyph> layout_text(std::string_view text, int* width, int* height);

}  // namespace jostle::detail
