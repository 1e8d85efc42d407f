// The built-in 5x7 font: every printable character has its own non-empty glyph within 5 columns,
// other characters fall back to '?', a few bitmaps exactly (bit order included), and the layout's
// positions and measured size.
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "font.h"

using namespace jostle::detail;

namespace {

constexpr int kFirst = 32;
constexpr int kLast = 126;

bool pixel(const Glyph& g, int x, int y) { return ((g.rows[y] >> (kGlyphWidth - 1 - x)) & 1) != 0; }

// The glyph as rows of '.' and '#', so a failing comparison shows the shapes.
std::string art(const Glyph& g) {
    std::string s;
    for (int y = 0; y < kGlyphHeight; ++y) {
        for (int x = 0; x < kGlyphWidth; ++x) s += pixel(g, x, y) ? '#' : '.';
        s += '\n';
    }
    return s;
}

bool empty(const Glyph& g) {
    for (const std::uint8_t row : g.rows) {
        if (row != 0) return false;
    }
    return true;
}

}  // namespace

TEST(Font, EveryPrintableCharacterHasItsOwnGlyph) {
    // A character that fell back would share '?''s table entry.
    const Glyph* question = &glyph('?');
    for (int c = kFirst; c <= kLast; ++c) {
        if (c == '?') continue;
        EXPECT_NE(&glyph(static_cast<char>(c)), question) << "'" << static_cast<char>(c) << "'";
    }
}

TEST(Font, SpaceIsEmptyAndEveryOtherPrintableGlyphHasPixels) {
    EXPECT_TRUE(empty(glyph(' ')));
    for (int c = kFirst + 1; c <= kLast; ++c) {
        EXPECT_FALSE(empty(glyph(static_cast<char>(c)))) << "'" << static_cast<char>(c) << "'";
    }
}

TEST(Font, NoTwoPrintableCharactersLookTheSame) {
    std::map<std::string, char> seen;
    for (int c = kFirst; c <= kLast; ++c) {
        const auto [it, inserted] = seen.emplace(art(glyph(static_cast<char>(c))), static_cast<char>(c));
        EXPECT_TRUE(inserted) << "'" << static_cast<char>(c) << "' looks like '" << it->second << "':\n"
                              << it->first;
    }
}

TEST(Font, NoPixelOutsideTheFiveColumns) {
    for (int c = 0; c < 256; ++c) {
        for (const std::uint8_t row : glyph(static_cast<char>(c)).rows) {
            EXPECT_EQ(row & ~0x1F, 0) << "character " << c;
        }
    }
}

TEST(Font, CharactersOutsidePrintableAsciiDrawAsQuestionMark) {
    const Glyph& question = glyph('?');
    for (const char c : {'\0', '\x01', '\t', '\n', '\x1f', '\x7f', '\x80', '\xe9', '\xff'}) {
        EXPECT_EQ(glyph(c), question) << "character " << static_cast<int>(static_cast<unsigned char>(c));
    }
}

TEST(Font, ExactBitmaps) {
    // Bit 4 is the leftmost column, so 0b10000 is x = 0.
    EXPECT_EQ(art(glyph('A')), art(Glyph{{0b01110, 0b10001, 0b10001, 0b11111, 0b10001, 0b10001, 0b10001}}));
    EXPECT_EQ(art(glyph('0')), art(Glyph{{0b01110, 0b10001, 0b10011, 0b10101, 0b11001, 0b10001, 0b01110}}));
    EXPECT_EQ(art(glyph('1')), art(Glyph{{0b00100, 0b01100, 0b00100, 0b00100, 0b00100, 0b00100, 0b01110}}));
    EXPECT_EQ(art(glyph('.')), art(Glyph{{0, 0, 0, 0, 0, 0b01100, 0b01100}}));
    EXPECT_EQ(art(glyph('-')), art(Glyph{{0, 0, 0, 0b11111, 0, 0, 0}}));
    EXPECT_EQ(glyph('A'), (Glyph{{0x0E, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11}}));
}

TEST(Font, BitOrderPutsXZeroOnTheLeft) {
    // '/' rises to the right: on at the top right and bottom left, off at the other corners.
    const Glyph& slash = glyph('/');
    EXPECT_TRUE(pixel(slash, kGlyphWidth - 1, 0));
    EXPECT_TRUE(pixel(slash, 0, kGlyphHeight - 1));
    EXPECT_FALSE(pixel(slash, 0, 0));
    EXPECT_FALSE(pixel(slash, kGlyphWidth - 1, kGlyphHeight - 1));
    // '_' is the bottom row only.
    EXPECT_EQ(glyph('_').rows[kGlyphHeight - 1], 0x1F);
}

TEST(FontLayout, TwoLines) {
    int w = -1;
    int h = -1;
    const std::vector<PlacedGlyph> placed = layout_text("ab\nc", &w, &h);
    ASSERT_EQ(placed.size(), 3u);
    EXPECT_EQ(placed[0].c, 'a');
    EXPECT_EQ(placed[0].x, 0);
    EXPECT_EQ(placed[0].y, 0);
    EXPECT_EQ(placed[1].c, 'b');
    EXPECT_EQ(placed[1].x, kGlyphAdvance);
    EXPECT_EQ(placed[1].y, 0);
    EXPECT_EQ(placed[2].c, 'c');
    EXPECT_EQ(placed[2].x, 0);
    EXPECT_EQ(placed[2].y, kLineAdvance);
    EXPECT_EQ(w, 11);  // two cells, less the last spacing column
    EXPECT_EQ(h, 16);  // two lines, less the last line's two spacing rows
}

TEST(FontLayout, SpacesAdvanceWithoutAnEntry) {
    int w = 0;
    int h = 0;
    const std::vector<PlacedGlyph> placed = layout_text(" a  b ", &w, &h);
    ASSERT_EQ(placed.size(), 2u);
    EXPECT_EQ(placed[0].x, kGlyphAdvance);
    EXPECT_EQ(placed[1].x, 4 * kGlyphAdvance);
    EXPECT_EQ(w, 6 * kGlyphAdvance - 1);  // trailing spaces are part of the line
    EXPECT_EQ(h, kGlyphHeight);
}

TEST(FontLayout, WidestLineSetsTheWidth) {
    int w = 0;
    int h = 0;
    layout_text("a\nabcd\nab", &w, &h);
    EXPECT_EQ(w, 4 * kGlyphAdvance - 1);
    EXPECT_EQ(h, 3 * kLineAdvance - 2);
}

TEST(FontLayout, EmptyTextAndEmptyLines) {
    int w = -1;
    int h = -1;
    EXPECT_TRUE(layout_text("", &w, &h).empty());
    EXPECT_EQ(w, 0);
    EXPECT_EQ(h, 0);

    // A trailing newline starts a (empty) second line.
    const std::vector<PlacedGlyph> placed = layout_text("a\n", &w, &h);
    ASSERT_EQ(placed.size(), 1u);
    EXPECT_EQ(w, kGlyphWidth);
    EXPECT_EQ(h, 2 * kLineAdvance - 2);

    layout_text("\n\nx", &w, &h);
    EXPECT_EQ(w, kGlyphWidth);
    EXPECT_EQ(h, 3 * kLineAdvance - 2);
}

TEST(FontLayout, UnsupportedCharactersStillTakeACell) {
    const std::vector<PlacedGlyph> placed = layout_text("a\001b", nullptr, nullptr);  // sizes not wanted
    ASSERT_EQ(placed.size(), 3u);
    EXPECT_EQ(placed[1].c, '\x01');
    EXPECT_EQ(glyph(placed[1].c), glyph('?'));
    EXPECT_EQ(placed[2].x, 2 * kGlyphAdvance);
}
