// make_sprites: draws the demo game's sprites and writes them as PNG files with real
// transparency (run by tools/make-sprites, which writes assets/sprites/). Every sprite is drawn
// from shapes described here: each pixel is the average of 8 x 8 samples, so edges are
// anti-aliased; surface detail comes from a hashed value noise, so the output is the same on
// every run and every machine (tests/game/sprites_test.cpp regenerates them and compares).
//
// The game's collision masks come from these pictures (alpha >= 128 is solid), so the shapes
// of the tree, the wreck and the blob are what the pixel-perfect collisions see.
//
// usage: make_sprites OUTPUT_DIR
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <functional>
#include <string>
#include <vector>

#include "jostle/core/atomic_file.h"
#include "jostle/render/png_io.h"

namespace {

struct Rgba {
    float r = 0, g = 0, b = 0, a = 0;  // straight colour, 0..1
};

Rgba rgb(float r, float g, float b, float a = 1.0f) { return Rgba{r / 255.0f, g / 255.0f, b / 255.0f, a}; }

Rgba mix(Rgba x, Rgba y, float t) {
    return Rgba{x.r + (y.r - x.r) * t, x.g + (y.g - x.g) * t, x.b + (y.b - x.b) * t, x.a + (y.a - x.a) * t};
}

Rgba shade(Rgba c, float f) {  // f < 1 darker, > 1 lighter (clamped)
    return Rgba{std::min(1.0f, c.r * f), std::min(1.0f, c.g * f), std::min(1.0f, c.b * f), c.a};
}

// Integer hash -> [0, 1): the same everywhere (no library randomness).
float hash01(int x, int y, int seed) {
    std::uint32_t h = static_cast<std::uint32_t>(x) * 0x8da6b343u ^ static_cast<std::uint32_t>(y) * 0xd8163841u ^
                      static_cast<std::uint32_t>(seed) * 0xcb1ab31fu;
    h ^= h >> 13;
    h *= 0x5bd1e995u;
    h ^= h >> 15;
    return static_cast<float>(h & 0xffffffu) / 16777216.0f;
}

// Smooth value noise in [0, 1) with features `cell` pixels apart.
float noise(float x, float y, float cell, int seed) {
    const float fx = x / cell, fy = y / cell;
    const int ix = static_cast<int>(std::floor(fx)), iy = static_cast<int>(std::floor(fy));
    const float tx = fx - static_cast<float>(ix), ty = fy - static_cast<float>(iy);
    const float sx = tx * tx * (3 - 2 * tx), sy = ty * ty * (3 - 2 * ty);
    const float a = hash01(ix, iy, seed), b = hash01(ix + 1, iy, seed);
    const float c = hash01(ix, iy + 1, seed), d = hash01(ix + 1, iy + 1, seed);
    return (a + (b - a) * sx) + ((c + (d - c) * sx) - (a + (b - a) * sx)) * sy;
}

// A sprite is a function from a point (pixel units, y down, origin at the top-left corner) to
// a colour, painted layer over layer by the function itself.
using Paint = std::function<Rgba(float x, float y)>;

// "Over" for straight colours.
Rgba over(Rgba top, Rgba below) {
    const float a = top.a + below.a * (1 - top.a);
    if (a <= 0) return Rgba{};
    auto ch = [&](float t, float b) { return (t * top.a + b * below.a * (1 - top.a)) / a; };
    return Rgba{ch(top.r, below.r), ch(top.g, below.g), ch(top.b, below.b), a};
}

jostle::Image render(int width, int height, const Paint& paint) {
    constexpr int kSamples = 8;
    jostle::Image image{width, height, std::vector<std::uint8_t>(static_cast<std::size_t>(width * height * 4))};
    for (int py = 0; py < height; ++py) {
        for (int px = 0; px < width; ++px) {
            // Average premultiplied colour over the samples, then back to straight.
            float r = 0, g = 0, b = 0, a = 0;
            for (int sy = 0; sy < kSamples; ++sy) {
                for (int sx = 0; sx < kSamples; ++sx) {
                    const Rgba c = paint(static_cast<float>(px) + (static_cast<float>(sx) + 0.5f) / kSamples,
                                         static_cast<float>(py) + (static_cast<float>(sy) + 0.5f) / kSamples);
                    r += c.r * c.a;
                    g += c.g * c.a;
                    b += c.b * c.a;
                    a += c.a;
                }
            }
            const float n = kSamples * kSamples;
            auto byte = [](float v) { return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); };
            std::uint8_t* out = &image.rgba[static_cast<std::size_t>((py * width + px) * 4)];
            out[3] = byte(a / n);
            if (a > 0) {
                out[0] = byte(r / a);
                out[1] = byte(g / a);
                out[2] = byte(b / a);
            }
        }
    }
    return image;
}

bool in_circle(float x, float y, float cx, float cy, float r) { return (x - cx) * (x - cx) + (y - cy) * (y - cy) <= r * r; }

// Inside a polygon (any shape, even-odd rule).
bool in_polygon(float x, float y, const std::vector<std::pair<float, float>>& p) {
    bool inside = false;
    for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) {
        const auto [xi, yi] = p[i];
        const auto [xj, yj] = p[j];
        if ((yi > y) != (yj > y) && x < (xj - xi) * (y - yi) / (yj - yi) + xi) inside = !inside;
    }
    return inside;
}

// The player's ship, pointing along +x; its centre (16, 12) is the entity's position and the
// hull is the collider's triangle (14, 0), (-10, -9), (-10, 9).
Rgba ship(float x, float y) {
    const std::vector<std::pair<float, float>> hull = {{30, 12}, {6, 3}, {6, 21}};
    const std::vector<std::pair<float, float>> flame = {{6, 9}, {1, 12}, {6, 15}};
    Rgba c{};
    if (in_polygon(x, y, flame)) c = over(rgb(255, 170, 60, 0.9f), c);
    if (in_polygon(x, y, hull)) {
        c = over(x < 7.5f ? rgb(40, 100, 170) : mix(rgb(120, 200, 255), rgb(50, 120, 200), (y - 3) / 18), c);
        if (in_circle(x, y, 19, 12, 3.2f)) c = over(rgb(210, 240, 255), c);
    }
    return c;
}

// A wooden crate, drawn at 32 x 32 and scaled to each crate's size.
Rgba crate(float x, float y) {
    if (x < 0.5f || y < 0.5f || x > 31.5f || y > 31.5f) return Rgba{};
    const bool border = x < 4 || y < 4 || x > 28 || y > 28;
    const bool brace = std::abs(x - y) < 2.5f;
    const float grain = noise(x * 0.3f, y * 3.0f, 2.0f, 7);
    Rgba wood = mix(rgb(170, 120, 70), rgb(135, 92, 50), grain);
    if (!border && static_cast<int>(y) % 8 == 0) wood = shade(wood, 0.75f);  // plank gaps
    if (border || brace) wood = shade(mix(rgb(120, 80, 42), rgb(100, 66, 34), grain), 1.0f);
    return wood;
}

// A round boulder, shaded from the top left; scaled to each rock's radius.
Rgba boulder(float x, float y) {
    const float cx = 16, cy = 16, r = 15.5f;
    if (!in_circle(x, y, cx, cy, r)) return Rgba{};
    const float light = std::clamp(1.15f - ((x - cx) + (y - cy)) / (2.4f * r), 0.55f, 1.25f);
    const float grit = noise(x, y, 3.0f, 11) * 0.25f + noise(x, y, 7.0f, 12) * 0.2f;
    return shade(mix(rgb(128, 120, 108), rgb(96, 90, 82), grit), light);
}

Rgba coin(float x, float y) {
    if (!in_circle(x, y, 8, 8, 7.5f)) return Rgba{};
    if (!in_circle(x, y, 8, 8, 6.0f)) return rgb(200, 150, 30);
    if (in_circle(x, y, 6, 6, 2.0f)) return rgb(255, 250, 200);
    return rgb(250, 210, 60);
}

Rgba ball(float x, float y) {
    if (!in_circle(x, y, 6, 6, 5.5f)) return Rgba{};
    if (in_circle(x, y, 4.5f, 4.5f, 1.6f)) return rgb(255, 230, 190);
    return mix(rgb(255, 150, 50), rgb(200, 80, 20), std::sqrt((x - 6) * (x - 6) + (y - 6) * (y - 6)) / 5.5f);
}

// The cannon: a round base and a barrel along +x (the collider is the base's circle).
Rgba cannon(float x, float y) {
    Rgba c{};
    if (x > 16 && x < 31 && std::abs(y - 16) < 3.5f) c = rgb(90, 30, 30);
    if (in_circle(x, y, 16, 16, 10)) c = over(mix(rgb(170, 50, 50), rgb(120, 35, 35), (y - 6) / 20), c);
    if (in_circle(x, y, 16, 16, 4)) c = over(rgb(60, 20, 20), c);
    return c;
}

// A tree seen from above: a canopy of overlapping leaf clumps with ragged, semi-transparent
// edges and gaps between the outer clumps (a mask, not a circle, is the right collider).
Rgba tree(float x, float y) {
    struct Clump { float x, y, r; };
    static const Clump clumps[] = {{32, 32, 15}, {18, 24, 10}, {45, 22, 11}, {48, 43, 10}, {22, 46, 11},
                                   {33, 12, 8},  {10, 38, 6},  {56, 31, 6},  {36, 54, 7}};
    float best = -1e9f;  // how deep inside the deepest clump, in pixels
    for (const Clump& k : clumps) {
        const float d = k.r - std::sqrt((x - k.x) * (x - k.x) + (y - k.y) * (y - k.y));
        best = std::max(best, d);
    }
    const float ragged = (noise(x, y, 2.5f, 21) - 0.5f) * 3.0f;
    if (best + ragged < 0) return Rgba{};
    const float leaf = noise(x, y, 3.0f, 22);
    Rgba c = mix(rgb(60, 140, 50), rgb(30, 95, 35), leaf);
    if (best + ragged < 1.5f) c.a = 0.55f;  // the thin outer leaves let the ground through
    return c;
}

// A wrecked hull, not convex, with a hole punched through it.
Rgba wreck(float x, float y) {
    const std::vector<std::pair<float, float>> hull = {{4, 20},  {14, 6},  {30, 4},  {44, 8},  {52, 4},  {60, 14},
                                                       {56, 22}, {61, 32}, {50, 42}, {36, 40}, {30, 45}, {16, 42},
                                                       {8, 36},  {12, 28}};
    if (!in_polygon(x, y, hull)) return Rgba{};
    if (in_circle(x, y, 33, 22, 6.5f)) return Rgba{};  // the hole
    const float rust = noise(x, y, 4.0f, 31);
    Rgba c = mix(rgb(120, 110, 100), rgb(150, 80, 40), rust);
    if (static_cast<int>(x) % 10 == 0) c = shade(c, 0.8f);  // hull ribs
    return c;
}

// The blob creature: a wobbly, slightly translucent body with two eyes looking along +x.
Rgba blob(float x, float y) {
    const float cx = 20, cy = 16;
    const float dx = x - cx, dy = y - cy;
    const float angle = std::atan2(dy, dx);
    const float radius = 14.0f * (1.0f + 0.12f * std::sin(3 * angle) + 0.07f * std::sin(5 * angle + 1.0f));
    const float dist = std::sqrt(dx * dx + dy * dy);
    if (dist > radius) return Rgba{};
    Rgba c = mix(rgb(170, 90, 200, 0.88f), rgb(120, 50, 160, 0.95f), dist / radius);
    for (const float ey : {11.0f, 21.0f}) {
        if (in_circle(x, y, 27, ey, 3.6f)) c = rgb(250, 250, 250);
        if (in_circle(x, y, 28.5f, ey, 1.7f)) c = rgb(20, 10, 30);
    }
    return c;
}

struct Sprite {
    const char* name;
    int width, height;
    Rgba (*paint)(float, float);
};

constexpr Sprite kSprites[] = {
    {"ship", 32, 24, ship},    {"crate", 32, 32, crate}, {"boulder", 32, 32, boulder}, {"coin", 16, 16, coin},
    {"ball", 12, 12, ball},    {"cannon", 32, 32, cannon}, {"tree", 64, 64, tree},    {"wreck", 64, 48, wreck},
    {"blob", 40, 32, blob},
};

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: make_sprites OUTPUT_DIR\n");
        return 2;
    }
    try {
        for (const Sprite& s : kSprites) {
            const std::string path = std::string(argv[1]) + "/" + s.name + ".png";
            // Best compression: these files are committed.
            const std::vector<std::uint8_t> png =
                jostle::encode_png(render(s.width, s.height, s.paint), jostle::PngEncoding{.encoder = jostle::PngEncoder::libpng, .compression_level = 9});
            jostle::write_file_atomic(path, std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
            std::printf("%s (%dx%d)\n", path.c_str(), s.width, s.height);
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "make_sprites: %s\n", e.what());
        return 2;
    }
    return 0;
}
