// compare_images and diff_image: the exact fast path, tolerances on channel difference and
// on the number of differing pixels, different sizes, and the diff picture's colours.
#include <gtest/gtest.h>

#include "jostle/render/image_compare.h"

using namespace jostle;

namespace {

Image solid(int w, int h, std::uint8_t r, std::uint8_t g, std::uint8_t b, std::uint8_t a = 255) {
    Image im{w, h, std::vector<std::uint8_t>(static_cast<std::size_t>(w * h) * 4)};
    for (std::size_t i = 0; i < im.rgba.size(); i += 4) {
        im.rgba[i] = r;
        im.rgba[i + 1] = g;
        im.rgba[i + 2] = b;
        im.rgba[i + 3] = a;
    }
    return im;
}

std::uint8_t* px(Image& im, int x, int y) { return im.rgba.data() + (y * im.width + x) * 4; }

}  // namespace

TEST(ImageCompare, IdenticalImagesTakeTheFastPath) {
    const Image a = solid(8, 4, 10, 20, 30);
    const CompareResult r = compare_images(a, a);
    EXPECT_TRUE(r.identical);
    EXPECT_TRUE(r.within_tolerance);
    EXPECT_EQ(r.differing_pixels, 0);
    EXPECT_EQ(r.max_channel_delta, 0);
}

TEST(ImageCompare, ChannelToleranceAndPixelBudget) {
    const Image a = solid(10, 10, 100, 100, 100);
    Image b = a;
    px(b, 3, 4)[0] = 103;  // off by 3 in red
    px(b, 7, 1)[3] = 250;  // off by 5 in alpha
    CompareResult r = compare_images(a, b);
    EXPECT_FALSE(r.identical);
    EXPECT_FALSE(r.within_tolerance);
    EXPECT_EQ(r.differing_pixels, 2);
    EXPECT_EQ(r.max_channel_delta, 5);

    r = compare_images(a, b, {.max_channel_delta = 3});
    EXPECT_EQ(r.differing_pixels, 1);  // only the alpha pixel is over 3
    EXPECT_FALSE(r.within_tolerance);
    r = compare_images(a, b, {.max_channel_delta = 3, .max_differing_pixels = 1});
    EXPECT_TRUE(r.within_tolerance);
    r = compare_images(a, b, {.max_channel_delta = 5});
    EXPECT_EQ(r.differing_pixels, 0);
    EXPECT_TRUE(r.within_tolerance);
}

TEST(ImageCompare, VeryDifferentImagesCountEveryPixel) {
    const CompareResult r = compare_images(solid(6, 5, 0, 0, 0), solid(6, 5, 255, 255, 255), {.max_channel_delta = 254});
    EXPECT_EQ(r.differing_pixels, 30);
    EXPECT_EQ(r.max_channel_delta, 255);
    EXPECT_FALSE(r.within_tolerance);
}

TEST(ImageCompare, DifferentSizesNeverMatch) {
    const CompareResult r = compare_images(solid(4, 4, 1, 2, 3), solid(5, 4, 1, 2, 3), {.max_differing_pixels = 1000});
    EXPECT_FALSE(r.same_size);
    EXPECT_FALSE(r.within_tolerance);
    EXPECT_EQ(r.differing_pixels, 4);  // the extra column
}

TEST(ImageCompare, MalformedImagesNeverMatch) {
    Image bad{4, 4, std::vector<std::uint8_t>(10)};
    EXPECT_FALSE(compare_images(bad, bad).within_tolerance);
    EXPECT_EQ(diff_image(bad, bad).width, 0);
}

TEST(ImageCompare, DiffPictureIsRedOverAFadedCopy) {
    const Image a = solid(3, 2, 0, 100, 200);
    Image b = a;
    px(b, 1, 1)[1] = 0;
    Image d = diff_image(a, b);
    ASSERT_EQ(d.width, 3);
    ASSERT_EQ(d.height, 2);
    const std::uint8_t* changed = px(d, 1, 1);
    EXPECT_EQ(changed[0], 255);
    EXPECT_EQ(changed[1], 0);
    EXPECT_EQ(changed[2], 0);
    EXPECT_EQ(changed[3], 255);
    // Faded: 255 - (255 - c) / 4 per channel, opaque.
    const std::uint8_t* same = px(d, 0, 0);
    EXPECT_EQ(same[0], 255 - 255 / 4);
    EXPECT_EQ(same[1], 255 - 155 / 4);
    EXPECT_EQ(same[2], 255 - 55 / 4);
    EXPECT_EQ(same[3], 255);
    // With a tolerance above the change, nothing is red.
    d = diff_image(a, b, 100);
    EXPECT_NE(px(d, 1, 1)[1], 0);
}

TEST(ImageCompare, DiffPictureCoversTheLargerSize) {
    Image d = diff_image(solid(2, 2, 0, 0, 0), solid(3, 1, 0, 0, 0));
    ASSERT_EQ(d.width, 3);
    ASSERT_EQ(d.height, 2);
    EXPECT_EQ(px(d, 2, 0)[1], 0);    // only the second image has it: red
    EXPECT_EQ(px(d, 0, 1)[1], 0);    // only the first: red
    EXPECT_NE(px(d, 0, 0)[1], 0);    // shared and equal: faded
}
