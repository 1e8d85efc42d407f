// `jostle imgdiff`, called in-process: identical, slightly different and very different
// images, tolerances, the diff picture it writes, and every usage and input error (exit 2).
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

#include "imgdiff.h"
#include "jostle/render/png_io.h"
#include "test_support.h"

using namespace jostle;

namespace {

struct Outcome {
    int status;
    std::string out;
    std::string err;
};

Outcome run(std::vector<std::string> args) {
    std::vector<std::string_view> views(args.begin(), args.end());
    std::ostringstream out, err;
    const int status = imgdiff_command(views, out, err);
    return {status, out.str(), err.str()};
}

class Imgdiff : public ::testing::Test {
protected:
    void SetUp() override {
        Image base{16, 8, std::vector<std::uint8_t>(16 * 8 * 4)};
        for (std::size_t i = 0; i < base.rgba.size(); i += 4) {
            base.rgba[i] = 40;
            base.rgba[i + 1] = 80;
            base.rgba[i + 2] = 120;
            base.rgba[i + 3] = 255;
        }
        write_png_atomic(path("a.png"), base);
        Image slight = base;
        slight.rgba[(3 * 16 + 5) * 4] = 42;  // one pixel, red off by 2
        write_png_atomic(path("slight.png"), slight);
        Image very = base;
        for (std::size_t i = 0; i < very.rgba.size(); i += 4) very.rgba[i] = 255;
        write_png_atomic(path("very.png"), very);
        Image wide{17, 8, std::vector<std::uint8_t>(17 * 8 * 4, 255)};
        write_png_atomic(path("wide.png"), wide);
    }
    std::string path(const std::string& name) const { return dir_.file(name); }

    const test::TempFolder dir_{"imgdiff"};
};

}  // namespace

TEST_F(Imgdiff, IdenticalImagesMatch) {
    const Outcome o = run({path("a.png"), path("a.png")});
    EXPECT_EQ(o.status, 0);
    EXPECT_EQ(o.out, "identical: 16x8\n");
}

TEST_F(Imgdiff, SlightDifferenceFailsExactlyAndPassesWithATolerance) {
    Outcome o = run({path("a.png"), path("slight.png")});
    EXPECT_EQ(o.status, 1);
    EXPECT_EQ(o.out, "differ: 1 of 128 pixels differ by more than 0 (allowed 0); largest channel difference 2\n");
    o = run({path("a.png"), path("slight.png"), "--tolerance", "2"});
    EXPECT_EQ(o.status, 0);
    EXPECT_EQ(o.out, "match: 0 of 128 pixels differ by more than 2 (allowed 0); largest channel difference 2\n");
    o = run({path("a.png"), path("slight.png"), "--max-pixels", "1"});
    EXPECT_EQ(o.status, 0);
}

TEST_F(Imgdiff, VeryDifferentImagesDifferAndTheDiffPictureMarksThem) {
    const Outcome o = run({path("a.png"), path("very.png"), "--out", path("diff.png"), "--tolerance", "10"});
    EXPECT_EQ(o.status, 1);
    EXPECT_EQ(o.out, "differ: 128 of 128 pixels differ by more than 10 (allowed 0); largest channel difference 215\n");
    const Image d = read_png(path("diff.png"));
    ASSERT_EQ(d.width, 16);
    for (std::size_t i = 0; i < d.rgba.size(); i += 4) {
        ASSERT_EQ(d.rgba[i], 255);
        ASSERT_EQ(d.rgba[i + 1], 0);
    }
}

TEST_F(Imgdiff, DifferentSizesDiffer) {
    const Outcome o = run({path("a.png"), path("wide.png"), "--max-pixels", "1000"});
    EXPECT_EQ(o.status, 1);
    EXPECT_EQ(o.out, "differ: sizes 16x8 and 17x8\n");
}

// --help (or -h) anywhere an option may stand prints the reference, as right after the command.
TEST_F(Imgdiff, HelpAnywhereAnOptionMayStand) {
    for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
             {path("a.png"), "--help"}, {path("a.png"), path("very.png"), "--tolerance", "3", "-h"}}) {
        const Outcome o = run(args);
        EXPECT_EQ(o.status, 0);
        EXPECT_EQ(o.out, imgdiff_help());
        EXPECT_EQ(o.err, "");
    }
}

TEST_F(Imgdiff, BadUsageAndBadInputExitTwo) {
    const auto expect_error = [](const Outcome& o, const std::string& message) {
        EXPECT_EQ(o.status, 2);
        EXPECT_EQ(o.out, "");
        EXPECT_NE(o.err.find(message), std::string::npos) << o.err;
    };
    expect_error(run({path("a.png")}), "expected two PNG files (EXPECTED and ACTUAL), got 1");
    expect_error(run({path("a.png"), path("a.png"), path("a.png")}), "got 3");
    expect_error(run({path("a.png"), path("a.png"), "--tolerance"}), "--tolerance needs a value");
    expect_error(run({path("a.png"), path("a.png"), "--out", "--tolerance"}), "--out needs a value, got the option '--tolerance'");
    expect_error(run({path("a.png"), path("a.png"), "--tolerance", "1", "--tolerance", "2"}), "--tolerance given twice");
    expect_error(run({path("a.png"), path("a.png"), "--tolerance", "256"}),
                 "--tolerance: expected a whole number from 0 to 255, got '256'");
    expect_error(run({path("a.png"), path("a.png"), "--max-pixels", "-1"}),
                 "--max-pixels: expected a whole number from 0 to 9223372036854775807, got '-1'");
    expect_error(run({path("a.png"), path("a.png"), "--tolerance", "+0"}),
                 "--tolerance: expected a whole number from 0 to 255, got '+0' (a number here is written without a sign)");
    // Past the largest value the message states the range, not only its lower end.
    expect_error(run({path("a.png"), path("a.png"), "--max-pixels", "18446744073709551615"}),
                 "--max-pixels: expected a whole number from 0 to 9223372036854775807, got '18446744073709551615'");
    EXPECT_EQ(run({path("a.png"), path("a.png"), "--max-pixels", "9223372036854775807"}).status, 0);
    expect_error(run({path("a.png"), path("a.png"), "--fast"}), "unknown option '--fast'");
    expect_error(run({path("a.png"), path("missing.png")}), "missing.png");
    expect_error(run({path("a.png"), std::string(JOSTLE_TEST_DATA) + "/truncated.png"}), "truncated.png");
    // A failed comparison never leaves a diff file behind.
    run({path("a.png"), path("missing.png"), "--out", path("never.png")});
    EXPECT_FALSE(std::filesystem::exists(path("never.png")));
}

// A diff picture in the assets' sprites folder ($JOSTLE_ASSETS, else the source tree's) would
// be a new sprite of the game, and one over a sprite or a level would replace it: refused.
TEST_F(Imgdiff, ADiffPictureInTheAssetsIsRefused) {
    const std::filesystem::path assets = std::filesystem::path(path("assets"));
    std::filesystem::create_directories(assets);
    std::filesystem::copy(std::filesystem::path(JOSTLE_ASSETS_DIR) / "levels", assets / "levels");
    std::filesystem::copy(std::filesystem::path(JOSTLE_ASSETS_DIR) / "sprites", assets / "sprites");
    const test::EnvGuard env("JOSTLE_ASSETS", assets.string());
    const std::vector<std::string> sprites = test::file_names(assets / "sprites");
    const std::pair<std::string, std::string> cases[] = {{"sprites/diff.png", "would be a new sprite 'diff'"},
                                                         {"sprites/ship.png", "is the sprite 'ship'"},
                                                         {"levels/arena.level", "is the level 'arena'"}};
    for (const auto& [file, what] : cases) {
        const std::string out = (assets / file).string();
        const Outcome o = run({path("a.png"), path("very.png"), "--out", out});
        EXPECT_EQ(o.status, 2) << file;
        EXPECT_EQ(o.err, "jostle imgdiff: --out: '" + out + "' " + what + " of the assets; give another path\n"
                         "Run 'jostle imgdiff --help' for usage.\n");
    }
    EXPECT_EQ(test::file_names(assets / "sprites"), sprites);
    // Without assets there is nothing to protect.
    const test::EnvGuard none("JOSTLE_ASSETS", path("no_assets"));
    EXPECT_EQ(run({path("a.png"), path("very.png"), "--out", path("d.png")}).status, 1);
}
