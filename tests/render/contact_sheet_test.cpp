// Contact sheets: grid size, thumbnails scaled into their cells in order, labels in the
// built-in font under each, letterboxing, and the empty case.
#include <gtest/gtest.h>

#include "font.h"
#include "jostle/render/contact_sheet.h"
#include "render/render_test_util.h"

using namespace jostle;

namespace {

Image solid(int w, int h, Color c) {
    Image im{w, h, std::vector<std::uint8_t>(static_cast<std::size_t>(w * h) * 4)};
    for (std::size_t i = 0; i < im.rgba.size(); i += 4) {
        im.rgba[i] = c.r;
        im.rgba[i + 1] = c.g;
        im.rgba[i + 2] = c.b;
        im.rgba[i + 3] = c.a;
    }
    return im;
}

constexpr Color kRed{255, 0, 0, 255};
constexpr Color kGreen{0, 255, 0, 255};
constexpr Color kBlue{0, 0, 255, 255};

}  // namespace

TEST(ContactSheet, GridOfLabelledThumbnails) {
    const Image a = solid(40, 30, kRed), b = solid(40, 30, kGreen), c = solid(40, 30, kBlue);
    const SheetFrame frames[] = {{0, &a}, {10, &b}, {20, &c}};
    const SheetDesc desc{.columns = 2, .thumb_width = 20};
    const Image sheet = contact_sheet(frames, desc);
    // Cells 20 x 15 thumbnails + 11 px label rows, 4 px gaps: 4 + 2 * 24 wide, 4 + 2 * 30 high.
    ASSERT_EQ(sheet.width, 52);
    ASSERT_EQ(sheet.height, 64);
    EXPECT_EQ(pixel_at(sheet, 4, 4), kRed);
    EXPECT_EQ(pixel_at(sheet, 23, 18), kRed);
    EXPECT_EQ(pixel_at(sheet, 24, 18), desc.background);
    EXPECT_EQ(pixel_at(sheet, 28, 4), kGreen);
    EXPECT_EQ(pixel_at(sheet, 4, 34), kBlue);
    EXPECT_EQ(pixel_at(sheet, 30, 40), desc.background);  // no fourth frame
    // The label "frame 0" starts 2 px under the thumbnail: compare the 'f' pixel by pixel.
    const detail::Glyph& f = detail::glyph('f');
    for (int y = 0; y < detail::kGlyphHeight; ++y) {
        for (int x = 0; x < detail::kGlyphWidth; ++x) {
            const bool on = ((f.rows[y] >> (4 - x)) & 1u) != 0;
            EXPECT_EQ(pixel_at(sheet, 4 + x, 21 + y), on ? desc.label : desc.background) << x << "," << y;
        }
    }
}

TEST(ContactSheet, FramesOfAnotherShapeAreLetterboxed) {
    const Image wide = solid(40, 30, kRed), tall = solid(10, 30, kGreen);
    const SheetFrame frames[] = {{1, &wide}, {2, &tall}};
    const Image sheet = contact_sheet(frames, {.columns = 2, .thumb_width = 40});
    // The second cell starts at x = 4 + 44; the tall frame is 10 x 30 in its 40 x 30 thumbnail:
    // centred (x 15..24 of the cell), background either side.
    EXPECT_EQ(pixel_at(sheet, 48 + 15, 10), kGreen);
    EXPECT_EQ(pixel_at(sheet, 48 + 24, 10), kGreen);
    EXPECT_EQ(pixel_at(sheet, 48 + 14, 10), SheetDesc{}.background);
    EXPECT_EQ(pixel_at(sheet, 48 + 25, 10), SheetDesc{}.background);
}

TEST(ContactSheet, AutomaticColumnsAndEmptyInput) {
    const Image a = solid(8, 8, kRed);
    std::vector<SheetFrame> frames(5, SheetFrame{0, &a});
    const Image sheet = contact_sheet(frames);
    EXPECT_EQ(sheet.width, 4 + 3 * (8 + 4));  // ceil(sqrt(5)) = 3 columns
    EXPECT_EQ(sheet.height, 4 + 2 * (8 + 11 + 4));
    EXPECT_EQ(contact_sheet({}).width, 0);
}
