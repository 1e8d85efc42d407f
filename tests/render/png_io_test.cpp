// png_io_test.cpp: read_png on every colour type in tests/data (made by make_pngs.py)
// and on broken files, and write_png_atomic: round trips, overwrites, no temporary files
// left behind, errors naming the path.
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "jostle/core/error.h"
#include "jostle/render/png_io.h"
#include "test_support.h"

namespace jostle {
namespace {

namespace fs = std::filesystem;
using ::testing::StartsWith;

const std::string kData = JOSTLE_TEST_DATA;

std::vector<std::uint8_t> bytes(std::initializer_list<int> values) {
    std::vector<std::uint8_t> out;
    for (int v : values) out.push_back(static_cast<std::uint8_t>(v));
    return out;
}

// The message read_png throws for `file`, or "" if it does not throw an InputError.
std::string read_error(const std::string& path) {
    try {
        read_png(path);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TEST(ReadPng, Rgba8) {
    const Image image = read_png(kData + "/mask_4x4.png");
    ASSERT_EQ(image.width, 4);
    ASSERT_EQ(image.height, 4);
    ASSERT_EQ(image.rgba.size(), 64u);
    const int alpha[4][4] = {{0, 0, 0, 100}, {0, 255, 255, 0}, {0, 255, 255, 0}, {0, 0, 0, 0}};
    for (int y = 0; y < 4; ++y) {
        for (int x = 0; x < 4; ++x) {
            const std::size_t i = static_cast<std::size_t>(y * 4 + x) * 4;
            EXPECT_EQ(image.rgba[i + 0], 200);
            EXPECT_EQ(image.rgba[i + 1], 50);
            EXPECT_EQ(image.rgba[i + 2], 25);
            EXPECT_EQ(image.rgba[i + 3], alpha[y][x]) << x << "," << y;
        }
    }
}

TEST(ReadPng, TwoBitPaletteWithTransparency) {
    const Image image = read_png(kData + "/palette_trns.png");
    ASSERT_EQ(image.width, 2);
    ASSERT_EQ(image.height, 2);
    EXPECT_EQ(image.rgba, bytes({255, 0, 0, 255, 0, 255, 0, 128, 0, 0, 255, 0, 255, 255, 255, 255}));
}

TEST(ReadPng, SixteenBitGreyIsScaledAndOpaque) {
    const Image image = read_png(kData + "/gray16.png");
    ASSERT_EQ(image.width, 3);
    ASSERT_EQ(image.height, 1);
    EXPECT_EQ(image.rgba, bytes({0, 0, 0, 255, 128, 128, 128, 255, 255, 255, 255, 255}));
}

TEST(ReadPng, GreyAlpha) {
    const Image image = read_png(kData + "/gray_alpha.png");
    ASSERT_EQ(image.width, 2);
    ASSERT_EQ(image.height, 1);
    EXPECT_EQ(image.rgba, bytes({10, 10, 10, 20, 200, 200, 200, 255}));
}

TEST(ReadPng, InterlacedRgb) {
    const Image image = read_png(kData + "/rgb_adam7.png");
    ASSERT_EQ(image.width, 3);
    ASSERT_EQ(image.height, 3);
    std::vector<std::uint8_t> expected;
    for (int y = 0; y < 3; ++y) {
        for (int x = 0; x < 3; ++x) {
            for (int v : {10 * x + y, 100 + x, 200 + y, 255}) expected.push_back(static_cast<std::uint8_t>(v));
        }
    }
    EXPECT_EQ(image.rgba, expected);
}

TEST(ReadPng, ErrorsNameTheFile) {
    EXPECT_EQ(read_error(kData + "/missing.png"), kData + "/missing.png: cannot open: No such file or directory");
    EXPECT_EQ(read_error(kData), kData + ": cannot read: Is a directory");
    EXPECT_EQ(read_error(kData + "/not_png.png"), kData + "/not_png.png: not a PNG file (no PNG signature)");
    EXPECT_EQ(read_error(kData + "/corrupt_crc.png"), kData + "/corrupt_crc.png: corrupt PNG: IDAT: CRC error");
    EXPECT_EQ(read_error(kData + "/truncated.png"),
              kData + "/truncated.png: corrupt PNG: unexpected end of file (truncated)");
}

TEST(ReadPng, SizeLimitsAreCheckedFromTheHeader) {
    // Both files are under 100 bytes: the sizes come from the header, nothing is allocated.
    EXPECT_EQ(read_error(kData + "/too_wide.png"),
              kData + "/too_wide.png: image is 20000 x 1 pixels; the limit is 16384 x 16384 and 67108864 pixels in total");
    EXPECT_EQ(read_error(kData + "/too_many_pixels.png"),
              kData +
                  "/too_many_pixels.png: image is 16384 x 8192 pixels; the limit is 16384 x 16384 and 67108864 pixels "
                  "in total");
}

class WritePng : public ::testing::Test {
protected:
    std::vector<std::string> files() const { return test::file_names(folder_.path()); }

    const test::TempFolder folder_{"jostle_png_test"};
};

Image pattern_image(int width, int height, std::uint32_t seed) {
    Image image{width, height, {}};
    image.rgba.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4);
    for (std::uint8_t& byte : image.rgba) {
        seed = seed * 1664525u + 1013904223u;
        byte = static_cast<std::uint8_t>(seed >> 24);
    }
    return image;
}

TEST_F(WritePng, RoundTripsAtEveryLevelAndLeavesNoTemporaryFile) {
    const Image image = pattern_image(37, 23, 7);
    const std::string path = folder_.file("frame.png");
    for (int level : {0, 1, 6, 9}) {
        write_png_atomic(path, image, level);
        const Image back = read_png(path);
        EXPECT_EQ(back.width, 37);
        EXPECT_EQ(back.height, 23);
        EXPECT_EQ(back.rgba, image.rgba) << "level " << level;
        EXPECT_EQ(files(), std::vector<std::string>{"frame.png"});
    }
}

TEST_F(WritePng, OverwritesAnExistingFile) {
    const std::string path = folder_.file("a.png");
    write_png_atomic(path, pattern_image(5, 5, 1));
    const Image second = pattern_image(2, 3, 2);
    write_png_atomic(path, second);
    EXPECT_EQ(read_png(path).rgba, second.rgba);
    EXPECT_EQ(files(), std::vector<std::string>{"a.png"});
}

TEST_F(WritePng, MissingFolderIsAnErrorNamingThePath) {
    const std::string path = (folder_.path() / "no_such_folder" / "a.png").string();
    try {
        write_png_atomic(path, pattern_image(2, 2, 3));
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_THAT(e.what(), StartsWith(path + ": cannot write: cannot create temporary file "));
    }
    EXPECT_TRUE(files().empty());
}

TEST_F(WritePng, FailedRenameRemovesTheTemporaryFile) {
    // The target is a non-empty folder: the rename fails after the data is written.
    fs::create_directories(folder_.path() / "taken" / "inside");
    const std::string path = folder_.file("taken");
    try {
        write_png_atomic(path, pattern_image(2, 2, 4));
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_THAT(e.what(), StartsWith(path + ": cannot write: cannot rename "));
    }
    EXPECT_EQ(files(), std::vector<std::string>{"taken"});
}

TEST_F(WritePng, MalformedImageIsAProgrammingError) {
    const std::string path = folder_.file("a.png");
    EXPECT_DEATH(write_png_atomic(path, Image{2, 2, {}}), "rgba.size");
    EXPECT_DEATH(write_png_atomic(path, Image{}), "image sides");
    EXPECT_DEATH(write_png_atomic(path, pattern_image(1, 1, 0), 10), "compression level");
}

}  // namespace
}  // namespace jostle
