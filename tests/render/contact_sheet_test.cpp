// Contact sheets: grid size, thumbnails scaled into their cells in order, labels in the
// built-in font under each, letterboxing, and the empty case.
#include <gtest/gtest.h>

#include "font.h"
#include "jostle/render/contact_sheet.h"
#include "render/render_test_util.h"

using namespace jostle;

namespace {

// The first letter of a label ('f' of "frame"), pixel by pixel, with its top left at (x0, y0).
void expect_f_at(const Image& sheet, int x0, int y0, const SheetDesc& desc) {
    const detail::Glyph& f = detail::glyph('f');
    for (int y = 0; y < detail::kGlyphHeight; ++y) {
        for (int x = 0; x < detail::kGlyphWidth; ++x) {
            const bool on = ((f.rows[y] >> (detail::kGlyphWidth - 1 - x)) & 1u) != 0;
            EXPECT_EQ(pixel_at(sheet, x0 + x, y0 + y), on ? desc.label : desc.background) << x << "," << y;
        }
    }
}

constexpr Color kRed{255, 0, 0, 255};
constexpr Color kGreen{0, 255, 0, 255};
constexpr Color kBlue{0, 0, 255, 255};

}  // namespace

TEST(ContactSheet, GridOfLabelledThumbnails) {
    const Image a = solid_image(40, 30, kRed), b = solid_image(40, 30, kGreen), c = solid_image(40, 30, kBlue);
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
    // The label "frame 0" starts 2 px under the thumbnail.
    expect_f_at(sheet, 4, 21, desc);
}

TEST(ContactSheet, FramesOfAnotherShapeAreLetterboxed) {
    const Image wide = solid_image(40, 30, kRed), tall = solid_image(10, 30, kGreen);
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
    const Image a = solid_image(8, 8, kRed);
    std::vector<SheetFrame> frames(5, SheetFrame{0, &a});
    const Image sheet = contact_sheet(frames);
    EXPECT_EQ(sheet.width, 4 + 3 * (8 + 4));  // ceil(sqrt(5)) = 3 columns
    EXPECT_EQ(sheet.height, 4 + 2 * (8 + 11 + 4));
    EXPECT_EQ(contact_sheet({}).width, 0);
}

// The builder draws each frame when it is added, so a caller can drop its frames as it goes:
// the same frames in the same order give contact_sheet()'s bytes (the contract play relies
// on), whatever their shapes, with frames that are not whole images (label only) before and
// after the first whole one.
TEST(ContactSheet, BuiltAFrameAtATimeGivesTheSameBytes) {
    const std::vector<std::pair<int, int>> sizes = {{0, 0}, {40, 30}, {10, 30}, {0, 0}, {33, 17}, {40, 30}, {7, 9}};
    std::vector<Image> images;
    for (std::size_t i = 0; i < sizes.size(); ++i) {
        const auto [w, h] = sizes[i];
        images.push_back(w > 0 ? solid_image(w, h, i % 2 ? kRed : kBlue) : Image{});
        if (w > 0) images.back().rgba[4 * (i % static_cast<std::size_t>(w))] = 77;  // not all one colour
    }
    for (const SheetDesc desc : {SheetDesc{}, SheetDesc{.columns = 3, .thumb_width = 21}, SheetDesc{.columns = 1, .thumb_width = 5}}) {
        std::vector<SheetFrame> frames;
        for (std::size_t i = 0; i < images.size(); ++i) frames.push_back({static_cast<std::int64_t>(100 * i), &images[i]});
        const Image whole = contact_sheet(frames, desc);

        ContactSheetBuilder builder(static_cast<int>(images.size()), desc);
        for (std::size_t i = 0; i < images.size(); ++i) {
            Image copy = images[i];
            builder.add(static_cast<std::int64_t>(100 * i), copy);
            copy = solid_image(3, 3, kGreen);  // the builder kept nothing of it
        }
        const Image built = builder.finish();
        EXPECT_EQ(built.width, whole.width);
        EXPECT_EQ(built.height, whole.height);
        EXPECT_TRUE(built.rgba == whole.rgba) << desc.columns << " columns, thumb " << desc.thumb_width;
    }
}

// A frame that is not a whole image before the first whole one: its label waits for the cell
// size, which the later frame sets, and lands in the first cell.
TEST(ContactSheet, ALabelBeforeTheFirstWholeFrameLandsInItsCell) {
    const Image empty, red = solid_image(40, 30, kRed);
    const SheetDesc desc{.columns = 2, .thumb_width = 20};
    ContactSheetBuilder builder(2, desc);
    builder.add(0, empty);
    builder.add(10, red);
    const Image sheet = builder.finish();
    ASSERT_EQ(sheet.width, 52);  // cells of 20 x 15, as in GridOfLabelledThumbnails
    ASSERT_EQ(sheet.height, 34);
    EXPECT_EQ(pixel_at(sheet, 4, 4), desc.background);  // no thumbnail in the first cell
    EXPECT_EQ(pixel_at(sheet, 28, 4), kRed);
    expect_f_at(sheet, 4, 21, desc);
}

TEST(ContactSheet, BuilderWithNoWholeFrameOrNoneAdded) {
    const Image empty;
    const SheetFrame frames[] = {{5, &empty}, {6, nullptr}};
    ContactSheetBuilder builder(2);
    builder.add(5, empty);
    builder.add(6, empty);
    EXPECT_TRUE(builder.finish().rgba == contact_sheet(frames).rgba);  // labels on a 64 x 48 grid

    ContactSheetBuilder none(0);
    EXPECT_EQ(none.finish().width, 0);
    ContactSheetBuilder one(1);
    EXPECT_DEATH(
        {
            one.add(1, empty);
            one.add(2, empty);
        },
        "assertion failed");
}
