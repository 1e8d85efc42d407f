// animation_test.cpp: AnimationWriter's APNG files, read back by the independent reader in
// apng_reader.h: the frames a viewer shows equal the frames added (pixel for pixel, for the
// right time), only changed rectangles are stored, equal frames merge, the file is atomic.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "jostle/core/error.h"
#include "jostle/render/animation.h"
#include "render/apng_reader.h"
#include "test_support.h"

namespace jostle {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::StartsWith;

Image solid(int w, int h, std::uint8_t r, std::uint8_t g, std::uint8_t b, std::uint8_t a = 255) {
    Image image{w, h, {}};
    image.rgba.resize(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 4);
    for (std::size_t i = 0; i < image.rgba.size(); i += 4) {
        image.rgba[i] = r;
        image.rgba[i + 1] = g;
        image.rgba[i + 2] = b;
        image.rgba[i + 3] = a;
    }
    return image;
}

void set_pixel(Image& image, int x, int y, std::uint8_t r, std::uint8_t g, std::uint8_t b, std::uint8_t a) {
    std::uint8_t* p = &image.rgba[(static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width) +
                                   static_cast<std::size_t>(x)) * 4];
    p[0] = r;
    p[1] = g;
    p[2] = b;
    p[3] = a;
}

// What a viewer shows, one entry per 1/den-second unit of the given delay_num: each stored
// frame repeated delay / unit times.
std::vector<Image> shown_frames(const test::Apng& apng, int unit) {
    std::vector<Image> out;
    for (const test::ApngFrame& frame : apng.frames) {
        EXPECT_EQ(frame.delay_num % unit, 0);
        for (int i = 0; i < frame.delay_num / unit; ++i) out.push_back(frame.canvas);
    }
    return out;
}

class Animation : public ::testing::Test {
protected:
    std::vector<std::string> files() const { return test::file_names(folder_.path()); }
    std::string path(const char* name) const { return folder_.file(name); }
    const test::TempFolder folder_{"jostle_anim"};
};

TEST_F(Animation, ViewerShowsExactlyTheFramesAddedAndPlainPngReadersSeeTheFirst) {
    std::vector<Image> frames;
    Image image = solid(20, 10, 10, 20, 30);
    frames.push_back(image);
    set_pixel(image, 3, 4, 255, 0, 0, 255);  // one pixel
    frames.push_back(image);
    frames.push_back(image);  // unchanged: merges with the previous one
    for (int x = 0; x < 20; ++x) set_pixel(image, x, 9, 0, 0, 255, 128);  // bottom row, half transparent
    frames.push_back(image);
    set_pixel(image, 19, 0, 0, 0, 0, 0);  // fully transparent pixel: SOURCE blending keeps it
    frames.push_back(image);

    AnimationWriter writer(path("run.png"), AnimationDesc{.delay_num = 1, .delay_den = 60, .loops = 3});
    for (const Image& frame : frames) writer.add(frame);
    writer.finish();
    EXPECT_EQ(writer.frames_added(), 5);
    EXPECT_EQ(writer.frames_stored(), 4);

    const test::Apng apng = test::read_apng(path("run.png"));
    EXPECT_EQ(apng.width, 20);
    EXPECT_EQ(apng.height, 10);
    EXPECT_EQ(apng.num_frames, 4u);
    EXPECT_EQ(apng.plays, 3u);
    EXPECT_TRUE(apng.first_frame_is_idat);
    const std::vector<Image> shown = shown_frames(apng, 1);
    ASSERT_EQ(shown.size(), frames.size());
    for (std::size_t i = 0; i < frames.size(); ++i) EXPECT_EQ(shown[i].rgba, frames[i].rgba) << "frame " << i;
    for (const test::ApngFrame& frame : apng.frames) EXPECT_EQ(frame.delay_den, 60);
    EXPECT_EQ(apng.frames[1].delay_num, 2);  // the merged pair

    // Only the changed rectangles are stored.
    EXPECT_EQ((std::vector<int>{apng.frames[1].x, apng.frames[1].y, apng.frames[1].width, apng.frames[1].height}),
              (std::vector<int>{3, 4, 1, 1}));
    EXPECT_EQ((std::vector<int>{apng.frames[2].x, apng.frames[2].y, apng.frames[2].width, apng.frames[2].height}),
              (std::vector<int>{0, 9, 20, 1}));
    EXPECT_EQ((std::vector<int>{apng.frames[3].x, apng.frames[3].y, apng.frames[3].width, apng.frames[3].height}),
              (std::vector<int>{19, 0, 1, 1}));

    // A viewer that knows only PNG shows frame 0.
    EXPECT_EQ(read_png(path("run.png")).rgba, frames[0].rgba);
    EXPECT_EQ(files(), std::vector<std::string>{"run.png"});
}

TEST_F(Animation, RandomRunsRoundTripPixelForPixel) {
    std::mt19937 rng(1234);
    for (int run = 0; run < 40; ++run) {
        const int w = 1 + static_cast<int>(rng() % 40);
        const int h = 1 + static_cast<int>(rng() % 40);
        const int delay = 1 + static_cast<int>(rng() % 5);
        Image image = solid(w, h, 0, 0, 0, run % 2 == 0 ? 255 : 0);
        std::vector<Image> frames;
        AnimationWriter writer(path("random.png"), AnimationDesc{.delay_num = delay, .delay_den = 30});
        const int count = 1 + static_cast<int>(rng() % 25);
        for (int f = 0; f < count; ++f) {
            const int changes = static_cast<int>(rng() % 4);  // 0: an equal frame
            for (int c = 0; c < changes; ++c) {
                const auto v = static_cast<std::uint8_t>(rng());
                // Half the runs opaque (frames drawn OVER), half any alpha (mostly SOURCE).
                const auto alpha = run % 2 == 0 ? std::uint8_t{255} : static_cast<std::uint8_t>(rng());
                set_pixel(image, static_cast<int>(rng() % static_cast<unsigned>(w)),
                          static_cast<int>(rng() % static_cast<unsigned>(h)), v, static_cast<std::uint8_t>(v * 3),
                          static_cast<std::uint8_t>(v * 7), alpha);
            }
            frames.push_back(image);
            writer.add(image);
        }
        writer.finish();
        const test::Apng apng = test::read_apng(path("random.png"));
        EXPECT_EQ(static_cast<std::int64_t>(apng.frames.size()), writer.frames_stored());
        const std::vector<Image> shown = shown_frames(apng, delay);
        ASSERT_EQ(shown.size(), frames.size()) << "run " << run;
        for (std::size_t i = 0; i < frames.size(); ++i) {
            ASSERT_EQ(shown[i].rgba, frames[i].rgba) << "run " << run << " frame " << i;
        }
    }
}

// A frame's unchanged pixels are stored transparent and the rectangle drawn OVER the previous
// frame, so two sprites far apart cost little more than their own pixels; a rectangle with a
// changed pixel that is not opaque (OVER would blend it) is stored as it is, as the SOURCE.
// Either way the viewer shows exactly the frames added.
TEST_F(Animation, OpaqueChangesAreDrawnOverThePreviousFrameOthersReplaceIt) {
    std::mt19937 rng(99);
    Image base = solid(64, 48, 0, 0, 0);
    for (std::size_t i = 0; i < base.rgba.size(); i += 4) {  // noise, opaque: it compresses badly
        for (int c = 0; c < 3; ++c) base.rgba[i + static_cast<std::size_t>(c)] = static_cast<std::uint8_t>(rng());
    }
    set_pixel(base, 30, 20, 10, 20, 30, 128);  // one translucent pixel
    std::vector<Image> frames{base};
    const auto next = [&](int x, int y, std::uint8_t a) {
        Image f = frames.back();
        set_pixel(f, x, y, 200, 100, 50, a);
        frames.push_back(f);
    };
    next(1, 1, 255);
    frames.back().rgba[(46 * 64 + 62) * 4] ^= 0x55;  // and a second opaque change far away
    next(5, 5, 77);     // a translucent change
    next(30, 20, 255);  // the translucent pixel made opaque
    next(7, 40, 0);     // an opaque pixel made transparent
    AnimationWriter writer(path("over.png"));
    for (const Image& f : frames) writer.add(f);
    writer.finish();
    const test::Apng apng = test::read_apng(path("over.png"));
    ASSERT_EQ(apng.frames.size(), frames.size());
    const int blend[] = {0, 1, 0, 1, 0};
    for (std::size_t i = 0; i < frames.size(); ++i) {
        EXPECT_EQ(apng.frames[i].canvas.rgba, frames[i].rgba) << "frame " << i;
        EXPECT_EQ(apng.frames[i].blend_op, blend[i]) << "frame " << i;
    }
    EXPECT_EQ(apng.frames[1].width, 62);  // one rectangle around both changes
    EXPECT_EQ(apng.frames[1].height, 46);
    // The 62 x 46 rectangle of noise costs almost nothing beyond its two changed pixels.
    AnimationWriter first_only(path("first.png"));
    first_only.add(frames[0]);
    first_only.finish();
    AnimationWriter two(path("two.png"));
    two.add(frames[0]);
    two.add(frames[1]);
    two.finish();
    EXPECT_LT(fs::file_size(path("two.png")) - fs::file_size(path("first.png")), 200u);
}

TEST_F(Animation, ALongStillSplitsWhenItsDelayWouldOverflowSixteenBits) {
    const Image image = solid(4, 4, 1, 2, 3);
    AnimationWriter writer(path("still.png"), AnimationDesc{.delay_num = 30000, .delay_den = 1});
    for (int i = 0; i < 5; ++i) writer.add(image);
    writer.finish();
    const test::Apng apng = test::read_apng(path("still.png"));
    // 30000 * 2 fits in 65535, 30000 * 3 does not: 2 + 2 + 1.
    ASSERT_EQ(apng.frames.size(), 3u);
    EXPECT_EQ(apng.frames[0].delay_num, 60000);
    EXPECT_EQ(apng.frames[1].delay_num, 60000);
    EXPECT_EQ(apng.frames[2].delay_num, 30000);
    for (const test::ApngFrame& frame : apng.frames) EXPECT_EQ(frame.canvas.rgba, image.rgba);
}

TEST_F(Animation, OneFrameIsAValidAnimation) {
    const Image image = solid(3, 2, 9, 8, 7, 6);
    AnimationWriter writer(path("one.png"));
    writer.add(image);
    writer.finish();
    const test::Apng apng = test::read_apng(path("one.png"));
    ASSERT_EQ(apng.frames.size(), 1u);
    EXPECT_EQ(apng.frames[0].canvas.rgba, image.rgba);
    EXPECT_EQ(apng.frames[0].delay_num, 1);
    EXPECT_EQ(apng.frames[0].delay_den, 60);
    EXPECT_EQ(apng.plays, 0u);  // forever
}

TEST_F(Animation, UnfinishedWriterLeavesNoFileAndKeepsTheOldOne) {
    {
        AnimationWriter writer(path("new.png"));
        writer.add(solid(2, 2, 1, 1, 1));
    }
    EXPECT_TRUE(files().empty());

    write_png_atomic(path("old.png"), solid(2, 2, 5, 5, 5));
    {
        AnimationWriter writer(path("old.png"));
        writer.add(solid(2, 2, 1, 1, 1));
    }
    EXPECT_EQ(files(), std::vector<std::string>{"old.png"});
    EXPECT_EQ(read_png(path("old.png")).rgba, solid(2, 2, 5, 5, 5).rgba);
}

TEST_F(Animation, FinishWithoutFramesIsAnErrorNamingThePath) {
    {
        AnimationWriter writer(path("empty.png"));
        try {
            writer.finish();
            FAIL() << "no error";
        } catch (const InputError& e) {
            EXPECT_EQ(std::string(e.what()), path("empty.png") + ": cannot write an animation without frames");
        }
    }
    EXPECT_TRUE(files().empty());  // the temporary file went with the writer
}

TEST_F(Animation, BadSettingsAndUnwritablePathsAreErrorsNamingThePath) {
    const std::string p = path("a.png");
    auto error_of = [&](const AnimationDesc& desc) -> std::string {
        try {
            AnimationWriter writer(p, desc);
        } catch (const InputError& e) {
            return e.what();
        }
        return "no error";
    };
    EXPECT_EQ(error_of({.delay_num = 0}), p + ": delay_num 0: expected 1..65535");
    EXPECT_EQ(error_of({.delay_den = 70000}), p + ": delay_den 70000: expected 1..65535");
    EXPECT_EQ(error_of({.loops = -1}), p + ": loops -1: expected 0..65535");

    const std::string missing = (folder_.path() / "no_such_folder" / "a.png").string();
    try {
        AnimationWriter writer(missing);
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_THAT(e.what(), StartsWith(missing + ": cannot write: cannot create a file in "));
    }
    EXPECT_TRUE(files().empty());
}

TEST_F(Animation, FramesOfAnotherSizeAreAProgrammingError) {
    EXPECT_DEATH(
        {
            AnimationWriter writer(path("a.png"));
            writer.add(solid(2, 2, 0, 0, 0));
            writer.add(solid(3, 2, 0, 0, 0));
        },
        "first frame's size");
}

TEST_F(Animation, StillFootageCostsAlmostNothingPerFrame) {
    // 100 frames where one 4x4 square moves across a 200x100 image: every stored frame but
    // the first is a small rectangle, so the file is far smaller than 100 whole frames.
    AnimationWriter writer(path("moving.png"));
    Image image = solid(200, 100, 30, 60, 90);
    std::int64_t single = 0;
    for (int f = 0; f < 100; ++f) {
        Image frame = image;
        for (int y = 0; y < 4; ++y) {
            for (int x = 0; x < 4; ++x) set_pixel(frame, f + x, 40 + y, 250, 250, 0, 255);
        }
        if (f == 0) single = static_cast<std::int64_t>(encode_png(frame).size());
        writer.add(frame);
    }
    writer.finish();
    const auto size = static_cast<std::int64_t>(fs::file_size(path("moving.png")));
    EXPECT_EQ(writer.frames_stored(), 100);
    EXPECT_LT(size, single + 100 * 200) << "whole frames would be about " << 100 * single << " bytes";
}

}  // namespace
}  // namespace jostle
