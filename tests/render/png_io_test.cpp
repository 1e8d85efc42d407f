// png_io_test.cpp: read_png on every colour type in tests/data (made by make_pngs.py)
// and on broken files, and write_png_atomic: round trips, overwrites, no temporary files
// left behind, errors naming the path; jostle's fast encoder (PngEncoder::fast): round trips
// through libpng and through a decoder written here (zlib's inflate and the PNG filters undone
// by hand), the same bytes whatever the thread count.
#include <zlib.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <utility>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "jostle/core/error.h"
#include "jostle/render/png_io.h"
#include "png_fast.h"  // engine/render/src (private): detail::adler32
#include "pixel_rows.h"  // engine/render/src (private): detail::encode_png_rows
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
    EXPECT_EQ(read_error(kData), kData + ": is a folder, expected a PNG file");
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

TEST(ReadPng, AHugeAncillaryChunkIsNotAllocated) {
    // Found by tests/fuzz/png_fuzz.cpp (regressions/png/): 112 bytes whose zTXt chunk declares
    // 1.8 GB. libpng allocated the declared length before reading it; now libpng's allocations
    // are bounded, so the file fails as what it is (truncated), with no large allocation.
    const std::vector<std::uint8_t> bytes = {
        0x89,0x50,0x4e,0x47,0x0d,0x0a,0x1a,0x0a,0x00,0x00,0x00,0x0d,0x49,0x48,0x44,0x52,0x00,0x00,0x00,0x02,
        0x00,0x00,0x00,0x02,0x02,0x03,0x00,0x00,0x00,0x0f,0xd8,0xe5,0xb7,0x00,0x00,0x00,0x0c,0x50,0x4c,0x54,
        0x45,0xff,0x00,0x00,0x00,0xff,0x00,0x00,0x00,0xff,0xff,0xff,0xff,0xfb,0x00,0x60,0xf6,0x00,0x00,0x00,
        0x03,0x74,0x52,0x4e,0x53,0x3f,0x80,0x00,0x78,0x00,0x68,0x00,0x6d,0x00,0x7f,0x0c,0x7a,0x54,0x58,0x74,
        0x49,0x44,0x41,0x54,0x78,0x9c,0x63,0x10,0x60,0xd8,0x00,0x00,0x00,0xe4,0x00,0xc1,0x27,0xa8,0xe8,0x57,
        0x00,0x00,0x00,0x00,0x49,0x45,0x4e,0x44,0xae,0x42,0x60,0x82,
    };
    try {
        decode_png(bytes, "ztxt.png");
        FAIL() << "expected an InputError";
    } catch (const InputError& e) {
        EXPECT_STREQ(e.what(), "ztxt.png: corrupt PNG: unexpected end of file (truncated)");
    }
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
        EXPECT_THAT(e.what(), StartsWith(path + ": cannot write: cannot create a file in "));
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
        EXPECT_EQ(std::string(e.what()), path + ": cannot write: it is a folder");
    }
    EXPECT_EQ(files(), std::vector<std::string>{"taken"});
}

TEST_F(WritePng, MalformedImageIsAProgrammingError) {
    const std::string path = folder_.file("a.png");
    EXPECT_DEATH(write_png_atomic(path, Image{2, 2, {}}), "rgba.size");
    EXPECT_DEATH(write_png_atomic(path, Image{}), "image sides");
    EXPECT_DEATH(write_png_atomic(path, pattern_image(1, 1, 0), 10), "compression level");
}


// ---------------------------------------------------------------------------------------
// The fast encoder
// ---------------------------------------------------------------------------------------

// Images the encoder's paths meet: noise (stored blocks), flat colour (long runs), a frame-like
// picture (flat background, patches, soft gradients) and a repeated tile (matches far back).
Image fast_test_image(int width, int height, int kind, std::uint32_t seed) {
    Image image = pattern_image(width, height, seed);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            std::uint8_t* p = image.rgba.data() + (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) * 4;
            const std::uint8_t noise = p[0];
            switch (kind) {
                case 0: break;  // noise
                case 1: p[0] = 38; p[1] = 42; p[2] = 54; p[3] = 255; break;
                case 2: {
                    const bool patch = ((x / 13 + y / 7) % 5) == 0;
                    p[0] = patch ? static_cast<std::uint8_t>(x * 3) : 38;
                    p[1] = patch ? static_cast<std::uint8_t>(y * 5 + (noise & 3)) : 42;
                    p[2] = patch ? static_cast<std::uint8_t>(x + y) : 54;
                    p[3] = patch ? static_cast<std::uint8_t>(128 + (x & 127)) : 255;
                    break;
                }
                default: {
                    const std::uint32_t v = static_cast<std::uint32_t>((x % 24) * 2654435761u + (y % 24) * 40503u);
                    p[0] = static_cast<std::uint8_t>(v >> 24); p[1] = static_cast<std::uint8_t>(v >> 16);
                    p[2] = static_cast<std::uint8_t>(v >> 8); p[3] = static_cast<std::uint8_t>(v);
                    break;
                }
            }
        }
    }
    return image;
}

std::uint32_t be32(const std::uint8_t* p) {
    return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) | p[3];
}

// A PNG decoder for 8-bit RGBA files written from the PNG spec, not from either encoder:
// chunk CRCs checked, IDATs joined and inflated by zlib (which checks the Adler-32), each row's
// filter undone by hand.
Image decode_by_hand(const std::vector<std::uint8_t>& png) {
    const std::uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    EXPECT_EQ(std::memcmp(png.data(), signature, 8), 0);
    std::size_t at = 8;
    Image image;
    std::vector<std::uint8_t> zdata;
    bool ended = false;
    while (at + 12 <= png.size() && !ended) {
        const std::uint32_t length = be32(png.data() + at);
        const std::string type(reinterpret_cast<const char*>(png.data() + at + 4), 4);
        const std::uint8_t* data = png.data() + at + 8;
        EXPECT_EQ(crc32(0, png.data() + at + 4, length + 4), be32(data + length)) << type;
        if (type == "IHDR") {
            image.width = static_cast<int>(be32(data));
            image.height = static_cast<int>(be32(data + 4));
            EXPECT_EQ(std::vector<std::uint8_t>(data + 8, data + 13), bytes({8, 6, 0, 0, 0}));
        } else if (type == "IDAT") {
            zdata.insert(zdata.end(), data, data + length);
        } else if (type == "IEND") {
            ended = true;
        }
        at += 12 + length;
    }
    EXPECT_TRUE(ended);
    EXPECT_EQ(at, png.size());
    const std::size_t row = static_cast<std::size_t>(image.width) * 4;
    std::vector<std::uint8_t> raw((row + 1) * static_cast<std::size_t>(image.height));
    uLongf raw_size = static_cast<uLongf>(raw.size());
    EXPECT_EQ(uncompress(raw.data(), &raw_size, zdata.data(), static_cast<uLong>(zdata.size())), Z_OK);
    EXPECT_EQ(raw_size, raw.size());
    image.rgba.assign(row * static_cast<std::size_t>(image.height), 0);
    for (std::size_t y = 0; y < static_cast<std::size_t>(image.height); ++y) {
        const std::uint8_t type = raw[y * (row + 1)];
        const std::uint8_t* in = raw.data() + y * (row + 1) + 1;
        std::uint8_t* out = image.rgba.data() + y * row;
        const std::uint8_t* up = y > 0 ? out - row : nullptr;
        for (std::size_t i = 0; i < row; ++i) {
            const int a = i >= 4 ? out[i - 4] : 0;
            const int b = up ? up[i] : 0;
            const int c = (up && i >= 4) ? up[i - 4] : 0;
            int predicted = 0;
            if (type == 1) predicted = a;
            if (type == 2) predicted = b;
            if (type == 3) predicted = (a + b) / 2;
            if (type == 4) {
                const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
                predicted = (pa <= pb && pa <= pc) ? a : (pb <= pc ? b : c);
            }
            EXPECT_LE(type, 4);
            out[i] = static_cast<std::uint8_t>(in[i] + predicted);
        }
    }
    return image;
}

TEST(FastPng, RoundTripsEveryFilterSizeAndKindOfPicture) {
    const std::pair<int, int> sizes[] = {{1, 1}, {2, 3}, {5, 1}, {1, 7}, {37, 23}, {300, 700}, {1030, 5}};
    const PngFilter filters[] = {PngFilter::up, PngFilter::none, PngFilter::sub, PngFilter::paeth, PngFilter::adaptive,
                                 PngFilter::libpng_default};
    for (const auto& [w, h] : sizes) {
        for (int kind = 0; kind < 4; ++kind) {
            const Image image = fast_test_image(w, h, kind, static_cast<std::uint32_t>(w * 31 + h));
            for (const PngFilter filter : filters) {
                const std::vector<std::uint8_t> png = encode_png(image, PngEncoding{.filter = filter});
                const Image back = decode_png(png, "fast");
                EXPECT_EQ(back.width, w);
                EXPECT_EQ(back.height, h);
                EXPECT_EQ(back.rgba, image.rgba) << w << "x" << h << " kind " << kind << " filter " << static_cast<int>(filter);
                EXPECT_EQ(decode_by_hand(png).rgba, image.rgba) << w << "x" << h << " kind " << kind;
            }
        }
    }
}

TEST(FastPng, SameBytesWhateverTheThreadCount) {
    // 300 px wide: several strips of rows.
    for (int kind = 0; kind < 4; ++kind) {
        const Image image = fast_test_image(300, 700, kind, 5);
        const std::vector<std::uint8_t> one = encode_png(image);
        for (int threads : {2, 3, 16}) EXPECT_EQ(encode_png(image, PngEncoding{.threads = threads}), one) << threads;
        EXPECT_EQ(encode_png(image), one);
    }
}

TEST(FastPng, CompressesWhatRepeatsAndStoresNoise) {
    const Image flat = fast_test_image(640, 480, 1, 1);
    EXPECT_LT(encode_png(flat).size(), flat.rgba.size() / 200);
    const Image tile = fast_test_image(640, 480, 3, 1);
    EXPECT_LT(encode_png(tile).size(), tile.rgba.size() / 10);
    // Noise does not compress: stored blocks, a little over the raw size.
    const Image noise = fast_test_image(640, 480, 0, 1);
    const std::size_t filtered = noise.rgba.size() + 480;
    EXPECT_GE(encode_png(noise).size(), filtered);
    EXPECT_LT(encode_png(noise).size(), filtered + filtered / 1000 + 200);
}

// An animation encodes each frame's changed rectangle where it lies in the frame: the bytes
// are those of a PNG of the rectangle copied out, for both encoders, every filter, and
// rectangles at the edges, one pixel wide or high, and the whole image.
TEST(FastPng, ARectangleInPlaceIsTheSameBytesAsItsCopy) {
    const Image image = fast_test_image(300, 200, 2, 9);
    const int rects[][4] = {{0, 0, 300, 200}, {0, 0, 1, 1}, {299, 199, 1, 1}, {17, 0, 1, 200}, {0, 123, 300, 1},
                            {5, 7, 290, 180}, {150, 100, 150, 100}, {33, 41, 64, 3}};
    const PngEncoding encodings[] = {PngEncoding{}, PngEncoding{.filter = PngFilter::paeth}, PngEncoding{.filter = PngFilter::adaptive},
                                     PngEncoding{.threads = 3}, PngEncoding{.encoder = PngEncoder::libpng},
                                     PngEncoding{.encoder = PngEncoder::libpng, .compression_level = 9, .filter = PngFilter::sub}};
    for (const auto& r : rects) {
        Image copy;
        copy.width = r[2];
        copy.height = r[3];
        for (int y = r[1]; y < r[1] + r[3]; ++y) {
            const auto* row = image.rgba.data() + (static_cast<std::size_t>(y) * 300 + static_cast<std::size_t>(r[0])) * 4;
            copy.rgba.insert(copy.rgba.end(), row, row + static_cast<std::size_t>(r[2]) * 4);
        }
        for (const PngEncoding& e : encodings) {
            EXPECT_EQ(detail::encode_png_rows(detail::rows_of(image, r[0], r[1], r[2], r[3]), e), encode_png(copy, e))
                << r[0] << "," << r[1] << " " << r[2] << "x" << r[3] << " encoder " << static_cast<int>(e.encoder)
                << " filter " << static_cast<int>(e.filter);
        }
    }
}

TEST_F(WritePng, DefaultIsTheFastEncoder) {
    const Image image = fast_test_image(64, 48, 2, 3);
    const std::string path = folder_.file("frame.png");
    write_png_atomic(path, image);
    std::ifstream in(path, std::ios::binary);
    const std::vector<std::uint8_t> file{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    EXPECT_EQ(file, encode_png(image));
    EXPECT_EQ(read_png(path).rgba, image.rgba);
}

}  // namespace
}  // namespace jostle

// jostle's Adler-32 (16 bytes a step) is zlib's, for every length around the chunk and run
// boundaries, from any starting value, and on all-0xff bytes (the largest sums: overflow).
TEST(Adler32, EqualsZlibForEveryLengthAndStart) {
    std::vector<std::uint8_t> data(3 * 5552 + 100);
    std::uint32_t x = 12345;
    for (std::uint8_t& b : data) {
        x = x * 1664525u + 1013904223u;
        b = static_cast<std::uint8_t>(x >> 24);
    }
    std::vector<std::uint8_t> ones(3 * 5552 + 100, 0xff);
    for (const auto* bytes : {&data, &ones}) {
        for (std::size_t n = 0; n <= bytes->size(); n += (n < 64 || (n % 5536) < 40 || (n % 5536) > 5500) ? 1 : 97) {
            for (const std::uint32_t start : {1u, 0xfff0fff0u % 65521u, (65520u << 16) | 65520u}) {
                const auto expected = static_cast<std::uint32_t>(adler32_z(start, bytes->data(), n));
                ASSERT_EQ(jostle::detail::adler32(start, bytes->data(), n), expected) << "n " << n << " start " << start;
            }
        }
    }
    // Long runs (several MB, as a 1280x720 frame's rows).
    std::vector<std::uint8_t> big(4 << 20);
    for (std::size_t i = 0; i < big.size(); ++i) big[i] = static_cast<std::uint8_t>((i * 2654435761u) >> 13);
    EXPECT_EQ(jostle::detail::adler32(1, big.data(), big.size()), static_cast<std::uint32_t>(adler32_z(1, big.data(), big.size())));
}
