// sprites_test.cpp: the committed sprites (assets/sprites) are what tools/sprites/make_sprites
// draws today, byte for byte (regenerate with tools/make-sprites), and they are what the game
// needs: real transparency with anti-aliased edges, and irregular masks for the pixel-perfect
// things (a tree with a ragged outline, a wreck with a hole, a blob).
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "game/run_jostle.h"
#include "jostle/collision.h"
#include "jostle/render/png_io.h"
#include "test_support.h"

namespace jostle {
namespace {

namespace fs = std::filesystem;

using test::read_text;

const fs::path kSprites = fs::path(JOSTLE_ASSETS_DIR) / "sprites";

TEST(Sprites, TheCommittedFilesAreWhatTheProgramDraws) {
    const test::TempFolder temp("sprites");
    const fs::path& out = temp.path();
    const test::RunResult r = test::run_program(JOSTLE_MAKE_SPRITES, {out.string()});
    ASSERT_EQ(r.status, 0) << r.err;
    int files = 0;
    for (const auto& entry : fs::directory_iterator(out)) {
        ++files;
        const fs::path committed = kSprites / entry.path().filename();
        ASSERT_TRUE(fs::exists(committed)) << committed << " is not committed (run tools/make-sprites)";
        EXPECT_TRUE(read_text(entry.path()) == read_text(committed))
            << committed << " differs from what tools/sprites/make_sprites.cpp draws (run tools/make-sprites)";
    }
    EXPECT_EQ(files, 9);
    int committed_files = 0;
    for (const auto& entry : fs::directory_iterator(kSprites)) committed_files += entry.path().extension() == ".png";
    EXPECT_EQ(committed_files, files) << "a committed sprite the program no longer draws";
}

TEST(Sprites, EachHasTransparencyAndAntiAliasedEdges) {
    for (const char* name : {"ship", "crate", "boulder", "coin", "ball", "cannon", "tree", "wreck", "blob"}) {
        const Image image = read_png((kSprites / (std::string(name) + ".png")).string());
        int clear = 0, partial = 0;
        for (std::size_t i = 3; i < image.rgba.size(); i += 4) {
            clear += image.rgba[i] == 0;
            partial += image.rgba[i] > 0 && image.rgba[i] < 255;
        }
        if (std::string(name) != "crate") {  // the crate fills its box
            EXPECT_GT(clear, 0) << name;
        }
        EXPECT_GT(partial, 8) << name << ": edges should be anti-aliased";
    }
}

Mask mask_of(const char* name) {
    const Image image = read_png((kSprites / (std::string(name) + ".png")).string());
    return Mask::from_alpha(image.rgba.data(), image.width, image.height, 127);
}

TEST(Sprites, ThePixelPerfectThingsHaveIrregularMasks) {
    for (const char* name : {"tree", "wreck", "blob"}) {
        const Mask m = mask_of(name);
        const int area = m.width() * m.height();
        EXPECT_GT(m.count(), area / 3) << name;
        EXPECT_LT(m.count(), area * 3 / 4) << name << ": a mask close to its box would not need pixels";
    }
    // The wreck's hole: clear in the middle, solid around it.
    const Mask wreck = mask_of("wreck");
    EXPECT_FALSE(wreck.get(33, 22));
    EXPECT_TRUE(wreck.get(33, 12));
    EXPECT_TRUE(wreck.get(33, 32));
    EXPECT_TRUE(wreck.get(22, 22));
    EXPECT_TRUE(wreck.get(44, 22));
}

}  // namespace
}  // namespace jostle
