// Frame selection (--frames / --every), frame file names, and the threaded frame writer:
// frames land as complete PNGs in order, and a write error surfaces instead of vanishing.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "jostle/core/error.h"
#include "jostle/render/frame_output.h"
#include "test_support.h"

using namespace jostle;

namespace {

std::vector<std::int64_t> selected(const FrameSelection& s, std::int64_t upto) {
    std::vector<std::int64_t> out;
    for (std::int64_t f = 0; f <= upto; ++f) {
        if (s.contains(f)) out.push_back(f);
    }
    return out;
}

FrameSelection must_parse(std::string_view text) {
    std::string error;
    auto s = FrameSelection::parse(text, &error);
    EXPECT_TRUE(s.has_value()) << error;
    return s.value_or(FrameSelection{});
}

Image gradient(int w, int h, std::uint8_t seed) {
    Image im{w, h, std::vector<std::uint8_t>(static_cast<std::size_t>(w * h) * 4)};
    for (std::size_t i = 0; i < im.rgba.size(); ++i) im.rgba[i] = static_cast<std::uint8_t>(i * 7 + seed);
    return im;
}

}  // namespace

TEST(FrameSelection, AllRangesListsAndEvery) {
    EXPECT_EQ(selected(FrameSelection{}, 3), (std::vector<std::int64_t>{0, 1, 2, 3}));
    EXPECT_EQ(selected(must_parse("all"), 2), (std::vector<std::int64_t>{0, 1, 2}));
    EXPECT_EQ(selected(must_parse("7"), 20), (std::vector<std::int64_t>{7}));
    EXPECT_EQ(selected(must_parse("3-5"), 20), (std::vector<std::int64_t>{3, 4, 5}));
    EXPECT_EQ(selected(must_parse("0-1,4,9-"), 11), (std::vector<std::int64_t>{0, 1, 4, 9, 10, 11}));
    FrameSelection s = must_parse("10-20");
    s.set_every(5);
    EXPECT_EQ(selected(s, 30), (std::vector<std::int64_t>{10, 15, 20}));
    FrameSelection every = FrameSelection{};
    every.set_every(4);
    EXPECT_EQ(selected(every, 9), (std::vector<std::int64_t>{0, 4, 8}));
    EXPECT_EQ(must_parse("3-5,8").last(), 8);
    EXPECT_EQ(must_parse("3-").last(), std::nullopt);
    EXPECT_EQ(FrameSelection{}.last(), std::nullopt);
}

TEST(FrameSelection, BadTextSaysWhatWasExpected) {
    const auto error_of = [](std::string_view text) {
        std::string error;
        EXPECT_FALSE(FrameSelection::parse(text, &error).has_value()) << text;
        return error;
    };
    EXPECT_EQ(error_of(""), "frames '': expected a frame number or a range A-B, got an empty item");
    EXPECT_EQ(error_of("1,,2"), "frames '1,,2': expected a frame number or a range A-B, got an empty item");
    EXPECT_EQ(error_of("x"), "frames 'x': expected a frame number (0 or more), got 'x'");
    EXPECT_EQ(error_of("-3"), "frames '-3': expected a range A-B with A a frame number, got '-3'");
    EXPECT_EQ(error_of("5-x"), "frames '5-x': expected a range A-B with B a frame number, got '5-x'");
    EXPECT_EQ(error_of("10-5"), "frames '10-5': range 10-5 ends before it starts");
    EXPECT_EQ(error_of("1-2-3"), "frames '1-2-3': expected a range A-B with B a frame number, got '1-2-3'");
}

TEST(FrameFileName, ZeroPaddedRealFrameNumbers) {
    EXPECT_EQ(frame_file_name(123), "frame_000123.png");
    EXPECT_EQ(frame_file_name(0), "frame_000000.png");
    EXPECT_EQ(frame_file_name(1234567), "frame_1234567.png");
    EXPECT_EQ(frame_file_name(5, "shot_", 3), "shot_005.png");
}

TEST(FrameWriter, WritesEveryFrameCompletelyAndInOrder) {
    const test::TempFolder temp("frames");
    const auto dir = temp.path() / "ok";
    std::vector<Image> images;
    {
        FrameWriter writer({.folder = dir.string(), .max_queued = 2});
        for (int f = 0; f < 12; ++f) {
            images.push_back(gradient(40 + f, 30, static_cast<std::uint8_t>(f)));
            writer.write(f * 10, images.back());
        }
        writer.finish();
        const auto paths = writer.written();
        ASSERT_EQ(paths.size(), 12u);
        EXPECT_EQ(paths[3], (dir / "frame_000030.png").string());
    }
    for (int f = 0; f < 12; ++f) {
        const Image back = read_png((dir / frame_file_name(f * 10)).string());
        EXPECT_EQ(back.width, images[static_cast<std::size_t>(f)].width);
        EXPECT_EQ(back.rgba, images[static_cast<std::size_t>(f)].rgba) << "frame " << f * 10;
    }
    // Nothing but the frames: no temporary files left behind.
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator{}), 12);
}

TEST(FrameWriter, FolderThatCannotBeMadeIsAnInputError) {
    const test::TempFolder temp("frames");
    const auto dir = temp.path() / "blocked";
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "file") << "x";
    try {
        FrameWriter writer({.folder = (dir / "file" / "frames").string()});
        FAIL() << "expected an InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("cannot create the frame folder"), std::string::npos) << e.what();
    }
}

TEST(FrameWriter, AWriteErrorSurfacesInFinishAndLaterWrites) {
    const test::TempFolder temp("frames");
    const auto dir = temp.path() / "vanishing";
    FrameWriter writer({.folder = dir.string()});
    writer.finish();
    // The folder disappears under the writer and a file takes its name: writes must fail.
    std::filesystem::remove_all(dir);
    std::ofstream(dir) << "not a folder";
    writer.write(1, gradient(8, 8, 1));
    EXPECT_THROW(writer.finish(), InputError);
    EXPECT_THROW(writer.write(2, gradient(8, 8, 2)), InputError);
}
