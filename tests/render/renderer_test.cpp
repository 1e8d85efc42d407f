// The Renderer on both backends: exact pixels for solid shapes (pixel centres inside a shape
// are covered), orientation (world top-left is image top-left), sprites and their rotation,
// alpha blending, the camera, batching into one draw call, and run-to-run identical frames.
#include <gtest/gtest.h>

#include <cstring>

#include "font.h"
#include "jostle/core/error.h"
#include "jostle/render/renderer.h"

#include "render/render_test_util.h"

using namespace jostle;

namespace {

constexpr Color kBlack{0, 0, 0, 255};
constexpr Color kRed{255, 0, 0, 255};
constexpr Color kGreen{0, 255, 0, 255};
constexpr Color kBlue{0, 0, 255, 255};
constexpr Color kWhite{255, 255, 255, 255};

Color at(const Image& im, int x, int y) { return pixel_at(im, x, y); }

// A w x h sprite whose four quadrants are red (top-left), green (top-right), blue
// (bottom-left) and white (bottom-right).
Image quadrant_sprite(int w, int h) {
    Image im{w, h, std::vector<std::uint8_t>(static_cast<std::size_t>(w * h) * 4)};
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const Color c = y < h / 2 ? (x < w / 2 ? kRed : kGreen) : (x < w / 2 ? kBlue : kWhite);
            std::uint8_t* p = im.rgba.data() + (y * w + x) * 4;
            p[0] = c.r; p[1] = c.g; p[2] = c.b; p[3] = c.a;
        }
    }
    return im;
}

}  // namespace


TEST(RendererNull, ImageIsTheClearColourAndNoDrawCalls) {
    Renderer r({.backend = RenderBackend::null});
    r.begin_frame(7, 3, {1, 2, 3, 4});
    r.fill_rect({{0, 0}, {7, 3}}, kRed);
    const Image& im = r.end_frame();
    ASSERT_EQ(im.width, 7);
    ASSERT_EQ(im.height, 3);
    for (int y = 0; y < 3; ++y) {
        for (int x = 0; x < 7; ++x) EXPECT_EQ(at(im, x, y), (Color{1, 2, 3, 4}));
    }
    EXPECT_EQ(r.last_draw_calls(), 0);
}

TEST(RendererOsmesa, FilledRectangleCoversExactlyItsPixels) {
    Renderer r;
    r.begin_frame(10, 8, kBlack);
    r.fill_rect({{2, 3}, {6, 5}}, kRed);  // pixels x 2..5, y 3..4
    const Image& im = r.end_frame();
    ASSERT_EQ(im.width, 10);
    ASSERT_EQ(im.height, 8);
    for (int y = 0; y < 8; ++y) {
        for (int x = 0; x < 10; ++x) {
            const bool inside = x >= 2 && x < 6 && y >= 3 && y < 5;
            EXPECT_EQ(at(im, x, y), inside ? kRed : kBlack) << "pixel " << x << "," << y;
        }
    }
    EXPECT_EQ(r.last_draw_calls(), 1);
}

TEST(RendererOsmesa, SpriteInTheTopLeftOfTheWorldIsInTheTopLeftOfTheImage) {
    Renderer r;
    const SpriteId s = r.add_sprite(quadrant_sprite(8, 8));
    EXPECT_EQ(r.sprite_size(s), (Vec2{8, 8}));
    r.begin_frame(32, 24, kBlack);
    r.draw_sprite(s, {4, 4});  // covers world pixels 0..7 x 0..7
    const Image& im = r.end_frame();
    EXPECT_EQ(at(im, 0, 0), kRed);
    EXPECT_EQ(at(im, 7, 0), kGreen);
    EXPECT_EQ(at(im, 0, 7), kBlue);
    EXPECT_EQ(at(im, 7, 7), kWhite);
    EXPECT_EQ(at(im, 8, 8), kBlack);
    EXPECT_EQ(at(im, 31, 23), kBlack);
}

TEST(RendererOsmesa, SpriteTurnsByQuarterTurns) {
    Renderer r;
    const SpriteId s = r.add_sprite(quadrant_sprite(8, 8));
    // +pi/2 turns +x toward +y (clockwise on screen): the top-left (red) quadrant goes to the
    // top-right, and so on around.
    const float quarter = 1.5707963f;
    const Color expected_top_left[4] = {kRed, kBlue, kWhite, kGreen};
    for (int k = 0; k < 4; ++k) {
        r.begin_frame(16, 16, kBlack);
        r.draw_sprite(s, {8, 8}, quarter * static_cast<float>(k));
        const Image& im = r.end_frame();
        EXPECT_EQ(at(im, 5, 5), expected_top_left[k]) << "turn " << k;
        // Every pixel of the sprite's square is covered, none outside.
        EXPECT_NE(at(im, 4, 4), kBlack) << "turn " << k;
        EXPECT_NE(at(im, 11, 11), kBlack) << "turn " << k;
        EXPECT_EQ(at(im, 3, 8), kBlack) << "turn " << k;
        EXPECT_EQ(at(im, 12, 8), kBlack) << "turn " << k;
    }
}

TEST(RendererOsmesa, HalfTransparentRedOverBlueBlends) {
    Renderer r;
    r.begin_frame(4, 4, kBlack);
    r.fill_rect({{0, 0}, {4, 4}}, kBlue);
    r.fill_rect({{0, 0}, {2, 4}}, {255, 0, 0, 128});
    const Image& im = r.end_frame();
    const Color blended = at(im, 0, 0);
    EXPECT_NEAR(blended.r, 128, 1);
    EXPECT_EQ(blended.g, 0);
    EXPECT_NEAR(blended.b, 127, 1);
    EXPECT_EQ(blended.a, 255);
    EXPECT_EQ(at(im, 3, 0), kBlue);
}

TEST(RendererOsmesa, CameraMovesAndZooms) {
    Renderer r;
    r.begin_frame(8, 8, kBlack, {.origin = {10, 20}, .zoom = 2.0f});
    r.fill_rect({{11, 21}, {12, 22}}, kGreen);  // image pixels 2..3 x 2..3
    const Image& im = r.end_frame();
    EXPECT_EQ(at(im, 2, 2), kGreen);
    EXPECT_EQ(at(im, 3, 3), kGreen);
    EXPECT_EQ(at(im, 1, 2), kBlack);
    EXPECT_EQ(at(im, 4, 3), kBlack);
}

TEST(RendererOsmesa, ManySpritesAndShapesAreOneDrawCall) {
    Renderer r;
    std::vector<SpriteId> sprites;
    for (int i = 0; i < 20; ++i) sprites.push_back(r.add_sprite(quadrant_sprite(4 + i, 6)));
    r.begin_frame(320, 240, kBlack);
    for (int i = 0; i < 1000; ++i) {
        r.draw_sprite(sprites[static_cast<std::size_t>(i) % sprites.size()], {static_cast<float>(i % 300), static_cast<float>(i % 200)}, 0.01f * static_cast<float>(i));
    }
    r.fill_shape(Circle{{100, 100}, 30}, kRed);
    r.outline_shape(Obb{{50, 50}, {20, 10}, 0.3f}, kGreen, 2.0f);
    r.end_frame();
    EXPECT_EQ(r.last_draw_calls(), 1);
}

TEST(RendererOsmesa, SameFrameSamePixels) {
    const auto render = [] {
        Renderer r;
        const SpriteId s = r.add_sprite(quadrant_sprite(16, 12));
        r.begin_frame(64, 48, {10, 20, 30, 255});
        r.draw_sprite(s, {20, 20}, 0.7f, {1.5f, 0.75f}, {255, 255, 255, 200});
        r.fill_shape(Circle{{40, 30}, 9.5f}, {200, 100, 0, 180});
        r.outline_shape(Polygon{}, kRed);  // invalid: nothing
        r.draw_line({0, 47}, {63, 0}, kWhite, 1.5f);
        return r.end_frame();
    };
    const Image a = render();
    const Image b = render();
    EXPECT_EQ(a.rgba, b.rgba);
}

TEST(RendererOsmesa, MaskFillCoversItsSetPixels) {
    const auto mask = Mask::from_rows(std::vector<std::string_view>{"#.#", ".##"});
    ASSERT_TRUE(mask.has_value());
    Renderer r;
    r.begin_frame(6, 4, kBlack);
    r.fill_shape(PlacedMask{&*mask, 1, 1}, kWhite);
    const Image& im = r.end_frame();
    for (int y = 0; y < 4; ++y) {
        for (int x = 0; x < 6; ++x) {
            EXPECT_EQ(at(im, x, y), mask->get(x - 1, y - 1) ? kWhite : kBlack) << x << "," << y;
        }
    }
}

TEST(RendererOsmesa, TextIsTheFontsPixelsAtEachScale) {
    Renderer r;
    for (const int scale : {1, 2, 3}) {
        r.begin_frame(40, 30, kBlack);
        const Vec2 size = r.draw_text({2, 3}, "A\x01", kGreen, scale);  // '\x01' shows as '?'
        const Image& im = r.end_frame();
        EXPECT_EQ(size, (Vec2{static_cast<float>(11 * scale), static_cast<float>(7 * scale)}));
        for (int y = 0; y < 30; ++y) {
            for (int x = 0; x < 40; ++x) {
                // Which font pixel this image pixel shows, if any.
                const int fx = (x - 2) / scale, fy = (y - 3) / scale;
                bool on = false;
                if (x >= 2 && y >= 3 && fy < 7) {
                    const char c = fx < 6 ? 'A' : '?';
                    const int gx = fx < 6 ? fx : fx - 6;
                    on = gx < 5 && ((detail::glyph(c).rows[fy] >> (4 - gx)) & 1u) != 0;
                }
                ASSERT_EQ(at(im, x, y), on ? kGreen : kBlack) << "scale " << scale << " pixel " << x << "," << y;
            }
        }
    }
}

TEST(RendererOsmesa, SpritesPastTheAtlasGrowItAndEverySpriteStillDraws) {
    // The atlas starts at 256 x 256 and doubles when its shelves run out, keeping every sprite
    // where it is; the backend takes the bigger atlas at the next frame.
    Renderer r;
    const SpriteId first = r.add_sprite(quadrant_sprite(8, 8));
    r.begin_frame(16, 16, kBlack);
    r.draw_sprite(first, {4, 4});
    EXPECT_EQ(at(r.end_frame(), 0, 0), kRed);  // the 256 x 256 atlas is on the backend now
    std::vector<std::pair<SpriteId, Color>> solids;
    for (int i = 0; i < 40; ++i) {  // 40 of 64 x 64: more than 256 x 256 holds
        const Color c{static_cast<std::uint8_t>(50 + i * 5), static_cast<std::uint8_t>(200 - i * 3), static_cast<std::uint8_t>(i * 6), 255};
        solids.emplace_back(r.add_sprite(solid_image(64, 64, c)), c);
    }
    const SpriteId wide = r.add_sprite(quadrant_sprite(600, 40));  // wider than the atlas so far
    r.begin_frame(700, 340, kBlack);
    r.draw_sprite(first, {4, 4});
    for (std::size_t i = 0; i < solids.size(); ++i) {
        r.draw_sprite(solids[i].first, {static_cast<float>(32 + 64 * (i % 10)), static_cast<float>(48 + 64 * (i / 10))});
    }
    r.draw_sprite(wide, {300, 320});  // covers x 0..599, y 300..339
    const Image& im = r.end_frame();
    EXPECT_EQ(at(im, 0, 0), kRed);
    EXPECT_EQ(at(im, 7, 7), kWhite);
    for (std::size_t i = 0; i < solids.size(); ++i) {
        const int x0 = static_cast<int>(64 * (i % 10)), y0 = static_cast<int>(16 + 64 * (i / 10));
        for (const auto& [dx, dy] : {std::pair{0, 0}, {63, 0}, {0, 63}, {63, 63}, {31, 31}}) {
            EXPECT_EQ(at(im, x0 + dx, y0 + dy), solids[i].second) << "sprite " << i << " at " << dx << "," << dy;
        }
    }
    EXPECT_EQ(at(im, 0, 300), kRed);
    EXPECT_EQ(at(im, 599, 300), kGreen);
    EXPECT_EQ(at(im, 0, 339), kBlue);
    EXPECT_EQ(at(im, 599, 339), kWhite);
    EXPECT_EQ(at(im, 650, 320), kBlack);
    EXPECT_EQ(at(im, 300, 290), kBlack);
}

// Which texel a pixel shows is chosen in the sprite's own coordinates, so a sprite draws the
// same pixels wherever it was packed: after other sprites, in a grown atlas. (With atlas
// coordinates, the rounding of x / width moved texel boundaries, and a new sprite in the
// assets changed other sprites' pixels in every screenshot.) A sprite of distinct texels,
// turned, scaled and placed at fractional positions, in three renderers.
TEST(RendererOsmesa, ASpriteDrawsTheSamePixelsWhereverTheAtlasHoldsIt) {
    Image pattern{13, 11, std::vector<std::uint8_t>(13u * 11u * 4u)};
    for (int y = 0; y < 11; ++y) {
        for (int x = 0; x < 13; ++x) {
            std::uint8_t* p = pattern.rgba.data() + (y * 13 + x) * 4;
            p[0] = static_cast<std::uint8_t>(x * 19);
            p[1] = static_cast<std::uint8_t>(y * 23);
            p[2] = static_cast<std::uint8_t>((x + y) % 2 * 255);
            p[3] = static_cast<std::uint8_t>(x == 0 || y == 0 ? 128 : 255);
        }
    }
    const auto draw = [&](Renderer& r, SpriteId id) {
        r.begin_frame(240, 240, kBlack);
        int k = 0;
        for (int row = 0; row < 6; ++row) {
            for (int col = 0; col < 6; ++col, ++k) {
                const float angle = 0.37f * static_cast<float>(k) - 3.0f;
                const float scale = k % 3 == 0 ? 1.0f / 3.0f + 0.25f * static_cast<float>(k % 7) : 0.9f + 0.17f * static_cast<float>(k % 11);
                const Vec2 at{20.0f + 40.0f * static_cast<float>(col) + 0.125f * static_cast<float>(k % 8),
                              20.0f + 40.0f * static_cast<float>(row) + 0.3f * static_cast<float>(k % 5)};
                r.draw_sprite(id, at, k % 4 == 0 ? 0.0f : angle, {scale, scale * (k % 2 == 0 ? 1.0f : 1.3f)});
            }
        }
        return r.end_frame();
    };
    Renderer first;
    const Image alone = draw(first, first.add_sprite(pattern));
    Renderer after_one;
    after_one.add_sprite(solid_image(5, 3, kRed));  // moves it 6 texels along the shelf
    const Image shifted = draw(after_one, after_one.add_sprite(pattern));
    Renderer grown;
    for (int i = 0; i < 40; ++i) grown.add_sprite(solid_image(64, 64, kGreen));  // the atlas doubles
    const Image in_grown = draw(grown, grown.add_sprite(pattern));
    int drawn = 0;
    for (int y = 0; y < 240; ++y) {
        for (int x = 0; x < 240; ++x) drawn += at(alone, x, y) != kBlack;
    }
    EXPECT_GT(drawn, 3000);
    const auto differing = [](const Image& a, const Image& b) {
        int n = 0;
        for (std::size_t i = 0; i < a.rgba.size(); i += 4) n += std::memcmp(&a.rgba[i], &b.rgba[i], 4) != 0;
        return n;
    };
    EXPECT_EQ(differing(alone, shifted), 0);
    EXPECT_EQ(differing(alone, in_grown), 0);
}

TEST(RendererOsmesa, ASpriteOfNoPixelsOrTooLargeOrAFullAtlasIsAnInputError) {
    Renderer r;
    const auto message_of = [&](const Image& image) -> std::string {
        try {
            r.add_sprite(image);
        } catch (const InputError& e) {
            return e.what();
        }
        return "no error";
    };
    EXPECT_EQ(message_of(Image{0, 4, {}}), "sprite of 0x4 pixels: sides must be 1..2048 with 4 bytes per pixel");
    EXPECT_EQ(message_of(Image{2049, 1, std::vector<std::uint8_t>(2049 * 4)}),
              "sprite of 2049x1 pixels: sides must be 1..2048 with 4 bytes per pixel");
    EXPECT_EQ(message_of(Image{2, 2, std::vector<std::uint8_t>(15)}), "sprite of 2x2 pixels: sides must be 1..2048 with 4 bytes per pixel");
    // The atlas stops at 4096 x 4096: sprites of 2048 x 2048 (the largest) fill it.
    const SpriteId small = r.add_sprite(quadrant_sprite(8, 8));
    const Image big = solid_image(2048, 2048, kGreen);
    std::string last;
    int added = 0;
    for (; added < 8; ++added) {
        last = message_of(big);
        if (last != "no error") break;
    }
    EXPECT_GE(added, 1);
    EXPECT_LT(added, 4);  // four would fill it exactly, and the white block and the first sprite take room
    EXPECT_EQ(last.rfind("sprite atlas full: ", 0), 0u) << last;
    EXPECT_NE(last.find("4096x4096 pixels"), std::string::npos) << last;
    // The renderer still draws what it holds.
    r.begin_frame(8, 8, kBlack);
    r.draw_sprite(small, {4, 4});
    const Image& im = r.end_frame();
    EXPECT_EQ(at(im, 0, 0), kRed);
    EXPECT_EQ(at(im, 7, 7), kWhite);
}
