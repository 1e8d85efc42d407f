// Pixel mask tests (mask.cpp, slides 09-0 to 09-5 and 09-30): Mask building and errors, the two
// mistakes of the lecture's loop pinned, the bit-packed path against reference:: on random masks,
// the integer MTD and its tie rule, masks vs the other shapes against per-pixel brute force.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <variant>
#include <vector>

#include "jostle/collision.h"
#include "jostle/core/rng.h"

namespace jostle {
namespace {

using i64 = std::int64_t;

Mask rows_of(std::initializer_list<std::string_view> rows) {
    const std::vector<std::string_view> v(rows);
    std::string error;
    const std::optional<Mask> m = Mask::from_rows(v, &error);
    EXPECT_TRUE(m.has_value()) << error;
    return m.value_or(Mask{});
}

int uniform_int(Rng& rng, int lo, int hi) {  // [lo, hi]
    return lo + static_cast<int>(rng.below(static_cast<std::uint32_t>(hi - lo + 1)));
}

Mask random_mask(Rng& rng, int w, int h, int min_density = 0) {
    Mask m(w, h);
    // percent, both ends included
    const std::uint32_t density = static_cast<std::uint32_t>(uniform_int(rng, min_density, 100));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (rng.below(100) < density) m.set(x, y, true);
    return m;
}

// A coordinate on the 1/8 pixel grid: every test below is then exact in double arithmetic,
// so pixel centres exactly on a boundary happen often and must count as inside.
float grid(Rng& rng, float lo, float hi) {
    const int steps = static_cast<int>((hi - lo) * 8.0f);
    return lo + static_cast<float>(rng.below(static_cast<std::uint32_t>(steps + 1))) / 8.0f;
}

// The convex polygon of the points' hull (make_polygon takes only convex input).
std::optional<Polygon> hull_polygon(std::vector<Vec2> pts) {
    std::sort(pts.begin(), pts.end(), [](Vec2 a, Vec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
    if (pts.size() < 3) return std::nullopt;
    auto turn = [](Vec2 o, Vec2 a, Vec2 b) {
        return (static_cast<double>(a.x) - o.x) * (static_cast<double>(b.y) - o.y) -
               (static_cast<double>(a.y) - o.y) * (static_cast<double>(b.x) - o.x);
    };
    std::vector<Vec2> h(2 * pts.size());
    std::size_t k = 0;
    for (std::size_t i = 0; i < pts.size(); ++i) {
        while (k >= 2 && turn(h[k - 2], h[k - 1], pts[i]) <= 0) --k;
        h[k++] = pts[i];
    }
    for (std::size_t i = pts.size() - 1, t = k + 1; i > 0; --i) {
        while (k >= t && turn(h[k - 2], h[k - 1], pts[i - 1]) <= 0) --k;
        h[k++] = pts[i - 1];
    }
    h.resize(k - 1);
    if (h.size() < 3 || h.size() > static_cast<std::size_t>(kMaxPolygonVertices)) return std::nullopt;
    return make_polygon(h);  // nullopt when its checks find the hull too thin
}

Polygon triangle(Vec2 a, Vec2 b, Vec2 c) { return hull_polygon({a, b, c}).value(); }

// ---- per-pixel brute force, written independently of mask.cpp --------------------------------

// Does the pixel whose top-left corner is (px, py) meet the shape? Centre rule for solid
// shapes, closed square for segments (the header's pair table).
using PixelTest = std::function<bool(double px, double py)>;

PixelTest pixel_test(const Aabb& b) {
    return [b](double px, double py) {
        const double cx = px + 0.5, cy = py + 0.5;
        return cx >= b.min.x && cx <= b.max.x && cy >= b.min.y && cy <= b.max.y;
    };
}

PixelTest pixel_test(const Circle& c) {
    return [c](double px, double py) {
        const double dx = px + 0.5 - c.center.x, dy = py + 0.5 - c.center.y;
        return dx * dx + dy * dy <= static_cast<double>(c.radius) * c.radius;
    };
}

PixelTest pixel_test(const Polygon& p) {
    return [p](double px, double py) {
        const double cx = px + 0.5, cy = py + 0.5;
        for (int i = 0; i < p.count(); ++i) {
            const Vec2 a = p.points()[static_cast<std::size_t>(i)];
            const Vec2 b = p.points()[static_cast<std::size_t>((i + 1) % p.count())];
            const double ex = static_cast<double>(b.x) - a.x, ey = static_cast<double>(b.y) - a.y;
            if (ex * (cy - a.y) - ey * (cx - a.x) < 0.0) return false;
        }
        return true;
    };
}

double orient(double ax, double ay, double bx, double by, double cx, double cy) {
    return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
}

bool on_segment(double ax, double ay, double bx, double by, double cx, double cy) {
    return std::min(ax, bx) <= cx && cx <= std::max(ax, bx) && std::min(ay, by) <= cy && cy <= std::max(ay, by);
}

// Closed segments p1p2 and p3p4 share a point (the textbook orientation test).
bool segments_touch(double x1, double y1, double x2, double y2, double x3, double y3, double x4, double y4) {
    const double d1 = orient(x3, y3, x4, y4, x1, y1), d2 = orient(x3, y3, x4, y4, x2, y2);
    const double d3 = orient(x1, y1, x2, y2, x3, y3), d4 = orient(x1, y1, x2, y2, x4, y4);
    if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return true;
    return (d1 == 0 && on_segment(x3, y3, x4, y4, x1, y1)) || (d2 == 0 && on_segment(x3, y3, x4, y4, x2, y2)) ||
           (d3 == 0 && on_segment(x1, y1, x2, y2, x3, y3)) || (d4 == 0 && on_segment(x1, y1, x2, y2, x4, y4));
}

// A segment meets the closed square when an end is inside or it touches one of the four sides.
PixelTest pixel_test(const Segment& s) {
    return [s](double px, double py) {
        const double ax = s.a.x, ay = s.a.y, bx = s.b.x, by = s.b.y;
        auto inside = [&](double x, double y) { return x >= px && x <= px + 1 && y >= py && y <= py + 1; };
        if (inside(ax, ay) || inside(bx, by)) return true;
        const double xs[4] = {px, px + 1, px + 1, px};
        const double ys[4] = {py, py, py + 1, py + 1};
        for (int i = 0; i < 4; ++i)
            if (segments_touch(ax, ay, bx, by, xs[i], ys[i], xs[(i + 1) % 4], ys[(i + 1) % 4])) return true;
        return false;
    };
}

struct BruteHits {
    int count = 0;
    std::optional<Pixel> first;
};

BruteHits brute_hits(const Mask& m, i64 x, i64 y, const PixelTest& test) {
    BruteHits out;
    for (int j = 0; j < m.height(); ++j)
        for (int i = 0; i < m.width(); ++i)
            if (m.get(i, j) && test(static_cast<double>(x + i), static_cast<double>(y + j))) {
                if (!out.first) out.first = Pixel{static_cast<int>(x + i), static_cast<int>(y + j)};
                ++out.count;
            }
    return out;
}

// The exhaustive mask MTD against a fixed shape: every T in the square of the cheapest pure-axis
// push, best by (length, larger dot(T, centre A - centre B), smaller |dy|, smaller dx, smaller dy).
std::optional<std::array<i64, 2>> brute_mtd(const Mask& m, i64 x, i64 y, const PixelTest& test, double bcx,
                                            double bcy) {
    auto blocked = [&](i64 dx, i64 dy) { return brute_hits(m, x + dx, y + dy, test).count > 0; };
    if (!blocked(0, 0)) return std::nullopt;
    i64 bound = std::numeric_limits<i64>::max();
    const std::array<std::array<i64, 2>, 4> axes{{{1, 0}, {-1, 0}, {0, 1}, {0, -1}}};
    for (const auto& a : axes)
        for (i64 k = 1; k < bound; ++k)
            if (!blocked(k * a[0], k * a[1])) {
                bound = k;
                break;
            }
    const double cx = static_cast<double>(x) + 0.5 * m.width() - bcx;
    const double cy = static_cast<double>(y) + 0.5 * m.height() - bcy;
    std::optional<std::tuple<i64, double, i64, i64, i64>> best;
    for (i64 dy = -bound; dy <= bound; ++dy)
        for (i64 dx = -bound; dx <= bound; ++dx) {
            const i64 r2 = dx * dx + dy * dy;
            if (r2 == 0 || r2 > bound * bound || blocked(dx, dy)) continue;
            const double dot = static_cast<double>(dx) * cx + static_cast<double>(dy) * cy;
            const std::tuple<i64, double, i64, i64, i64> key{r2, -dot, std::abs(dy), dx, dy};
            if (!best || key < *best) best = key;
        }
    return std::array<i64, 2>{std::get<3>(*best), std::get<4>(*best)};
}

// The translation a hit's manifold stands for (mtd() rounded to the integer it is).
std::array<i64, 2> translation_of(const Manifold& m) {
    const Vec2 t = m.mtd();
    return {static_cast<i64>(std::lround(t.x)), static_cast<i64>(std::lround(t.y))};
}

void expect_translation(const Manifold& got, i64 dx, i64 dy) {
    ASSERT_TRUE(got.hit);
    const double len = std::sqrt(static_cast<double>(dx * dx + dy * dy));
    EXPECT_FLOAT_EQ(got.depth, static_cast<float>(len));
    EXPECT_FLOAT_EQ(got.normal.x, static_cast<float>(-static_cast<double>(dx) / len));
    EXPECT_FLOAT_EQ(got.normal.y, static_cast<float>(-static_cast<double>(dy) / len));
    EXPECT_EQ(translation_of(got), (std::array<i64, 2>{dx, dy}));
}

void expect_miss(const Manifold& m) {
    EXPECT_FALSE(m.hit);
    EXPECT_EQ(m.depth, 0.0f);
    EXPECT_EQ(m.normal, (Vec2{0, 0}));
}

// ================================ Mask ========================================================

TEST(MaskBasics, ConstructorGivesClearPixels) {
    const Mask m(130, 3);
    EXPECT_EQ(m.width(), 130);
    EXPECT_EQ(m.height(), 3);
    EXPECT_EQ(m.words_per_row(), 3);
    EXPECT_EQ(m.count(), 0);
    const Mask empty(0, 5);
    EXPECT_EQ(empty.words_per_row(), 0);
    EXPECT_EQ(empty.count(), 0);
    EXPECT_EQ(empty.to_rows(), std::vector<std::string>(5, ""));
}

TEST(MaskBasics, SetGetCountAndBitsPastTheWidthStayClear) {
    Mask m(65, 2);
    for (int x = 0; x < 65; ++x) m.set(x, 1, true);
    EXPECT_EQ(m.count(), 65);
    EXPECT_EQ(m.row(1)[0], ~std::uint64_t{0});
    EXPECT_EQ(m.row(1)[1], std::uint64_t{1});  // only pixel 64; bits 65..127 clear
    EXPECT_EQ(m.row(0)[0], std::uint64_t{0});
    EXPECT_TRUE(m.get(64, 1));
    EXPECT_FALSE(m.get(65, 1));  // outside: false, not UB
    EXPECT_FALSE(m.get(-1, 1));
    EXPECT_FALSE(m.get(0, 2));
    m.set(64, 1, false);
    EXPECT_EQ(m.row(1)[1], std::uint64_t{0});
    EXPECT_EQ(m.count(), 64);
}

TEST(MaskBasicsDeathTest, SizeAndPixelOutOfRangeAssert) {
    EXPECT_DEATH(Mask(kMaxMaskSide + 1, 1), "assertion failed");
    EXPECT_DEATH(Mask(1, -1), "assertion failed");
    Mask m(2, 2);
    EXPECT_DEATH(m.set(2, 0, true), "assertion failed");
}

TEST(MaskFromRows, ParsesAndRoundTrips) {
    const Mask m = rows_of({"..##", ".###", "#..."});
    EXPECT_EQ(m.width(), 4);
    EXPECT_EQ(m.height(), 3);
    EXPECT_EQ(m.count(), 6);
    EXPECT_TRUE(m.get(2, 0));
    EXPECT_FALSE(m.get(1, 0));
    EXPECT_TRUE(m.get(0, 2));
    EXPECT_EQ(m.to_rows(), (std::vector<std::string>{"..##", ".###", "#..."}));
}

TEST(MaskFromRows, EmptyInputIsAValidEmptyMask) {
    std::string error = "untouched";
    const auto none = Mask::from_rows({}, &error);
    ASSERT_TRUE(none.has_value());
    EXPECT_EQ(none->width(), 0);
    EXPECT_EQ(none->height(), 0);
    const std::vector<std::string_view> blank{"", ""};
    const auto thin = Mask::from_rows(blank, &error);
    ASSERT_TRUE(thin.has_value());
    EXPECT_EQ(thin->width(), 0);
    EXPECT_EQ(thin->height(), 2);
    EXPECT_EQ(error, "untouched");
}

TEST(MaskFromRows, BadCharacterNamesRowAndColumn) {
    const std::vector<std::string_view> rows{"....", "....x", "...."};
    std::string error;
    // Row 2 is also too long, but the length is reported first.
    EXPECT_FALSE(Mask::from_rows(rows, &error).has_value());
    EXPECT_EQ(error, "row 2 has 5 pixels, expected 4 like row 1");
    const std::vector<std::string_view> bad{"#...#", "#...x", "....."};
    EXPECT_FALSE(Mask::from_rows(bad, &error).has_value());
    EXPECT_EQ(error, "row 2, column 5: expected '#' or '.', got 'x'");
    const std::vector<std::string_view> control{".\t"};
    EXPECT_FALSE(Mask::from_rows(control, &error).has_value());
    EXPECT_EQ(error, "row 1, column 2: expected '#' or '.', got byte 0x09");
    EXPECT_FALSE(Mask::from_rows(bad).has_value());  // no error string: still nullopt
}

TEST(MaskFromRows, RaggedRowNamesBothLengths) {
    const std::vector<std::string_view> rows{"....", "....", "#####"};
    std::string error;
    EXPECT_FALSE(Mask::from_rows(rows, &error).has_value());
    EXPECT_EQ(error, "row 3 has 5 pixels, expected 4 like row 1");
}

TEST(MaskFromRows, TooLargeIsAnError) {
    const std::string wide(kMaxMaskSide + 1, '.');
    const std::vector<std::string_view> one{wide};
    std::string error;
    EXPECT_FALSE(Mask::from_rows(one, &error).has_value());
    EXPECT_EQ(error, "row 1 has 4097 pixels, at most 4096");
    const std::vector<std::string_view> tall(kMaxMaskSide + 1, ".");
    EXPECT_FALSE(Mask::from_rows(tall, &error).has_value());
    EXPECT_EQ(error, "4097 rows, at most 4096");
    const std::string side(kMaxMaskSide, '#');
    const std::vector<std::string_view> largest{side};
    EXPECT_TRUE(Mask::from_rows(largest).has_value());
}

TEST(MaskFromAlpha, SetOnlyWhereAlphaIsAboveTheThreshold) {
    // 3 x 2 pixels; colour bytes are ignored, only alpha (byte 3) counts (09-4).
    const std::array<std::uint8_t, 24> rgba{
        255, 255, 255, 0,   0, 0, 0, 128,   9, 9, 9, 129,
        0,   0,   0,   255, 1, 2, 3, 127,   0, 0, 0, 1,
    };
    const Mask m = Mask::from_alpha(rgba.data(), 3, 2, 128);
    EXPECT_EQ(m.to_rows(), (std::vector<std::string>{"..#", "#.."}));
    const Mask any = Mask::from_alpha(rgba.data(), 3, 2, 0);  // the slide's A > 0
    EXPECT_EQ(any.to_rows(), (std::vector<std::string>{".##", "###"}));
    const Mask none = Mask::from_alpha(rgba.data(), 3, 2, 255);
    EXPECT_EQ(none.count(), 0);
    const Mask zero = Mask::from_alpha(nullptr, 0, 0, 0);
    EXPECT_EQ(zero.width(), 0);
}

// ================================ Mask vs mask ================================================

TEST(MaskOverlap, HandComputed) {
    const Mask a = rows_of({"##.", ".##"});
    const Mask b = rows_of({".#", "##", "#."});
    // a at (-1, 4): set world pixels (-1,4) (0,4) (0,5) (1,5).
    // b at (0, 3):  set world pixels (1,3) (0,4) (1,4) (0,5).
    const PlacedMask pa{&a, -1, 4};
    const PlacedMask pb{&b, 0, 3};
    EXPECT_TRUE(overlaps(pa, pb));
    EXPECT_EQ(count_overlap(pa, pb), 2);  // (0,4) and (0,5)
    EXPECT_EQ(first_overlap(pa, pb), (Pixel{0, 4}));
    EXPECT_EQ(first_overlap(pb, pa), (Pixel{0, 4}));
    // Rectangles overlap but no set pixel is shared.
    const PlacedMask moved{&a, 1, 4};  // (1,4) (2,4) (2,5) (3,5)
    EXPECT_TRUE(overlaps(moved, pb));
    const PlacedMask apart{&a, 2, 3};  // (2,3) (3,3) (3,4) (4,4)
    EXPECT_FALSE(overlaps(apart, pb));
    EXPECT_EQ(count_overlap(apart, pb), 0);
    EXPECT_EQ(first_overlap(apart, pb), std::nullopt);
}

TEST(MaskOverlap, ReadingOrderIsRowFirst) {
    // Shared pixels at world (5,0) and (0,1): the first is (5,0), the smaller y.
    const Mask a = rows_of({".....#", "#....."});
    const PlacedMask p{&a, 0, 0};
    EXPECT_EQ(first_overlap(p, p), (Pixel{5, 0}));
    EXPECT_EQ(count_overlap(p, p), 2);
}

TEST(MaskOverlap, NullAndEmptyMasksMiss) {
    const Mask a = rows_of({"##", "##"});
    const Mask empty;
    const Mask clear(4, 4);
    const Mask thin(0, 3);
    const PlacedMask pa{&a, 0, 0};
    for (const PlacedMask& other : {PlacedMask{}, PlacedMask{&empty, 0, 0}, PlacedMask{&clear, -1, -1},
                                    PlacedMask{&thin, 0, 0}}) {
        EXPECT_FALSE(overlaps(pa, other));
        EXPECT_FALSE(overlaps(other, pa));
        EXPECT_EQ(first_overlap(pa, other), std::nullopt);
        EXPECT_EQ(count_overlap(other, pa), 0);
        expect_miss(collide(pa, other));
        expect_miss(collide(other, pa));
        EXPECT_FALSE(reference::overlaps(pa, other));
        expect_miss(reference::collide(other, pa));
    }
}

// The slide's loop (09-3) transcribed literally: x + deltax, and bounds > 0. With fix_sign the
// lookup is x - deltax, with fix_bound the bounds are >= 0: each mistake can be shown alone.
bool slide_loop(const Mask& t1, int x1, int y1, const Mask& t2, int x2, int y2, bool fix_sign = false,
                bool fix_bound = false) {
    const int deltax = x2 - x1, deltay = y2 - y1;
    const int w1 = t1.width(), h1 = t1.height(), w2 = t2.width(), h2 = t2.height();
    const int sx = fix_sign ? -deltax : deltax, sy = fix_sign ? -deltay : deltay;
    const int low = fix_bound ? 0 : 1;  // "> 0" is ">= 1"
    for (int x = 0; x < w1; x++)
        for (int y = 0; y < h1; y++)
            if (x + sx >= low && x + sx < w2 && y + sy >= low && y + sy < h2 && t1.get(x, y) && t2.get(x + sx, y + sy))
                return true;
    return false;
}

TEST(MaskLecture, SlideSignMistakeIsFixed) {
    // A's pixel (0,1) and B's pixel (2,1) are both world (2,1). deltax = x2 - x1 = -2: the
    // slide looks at B's column 0 + deltax = -2, out of range, and misses; it is 0 - deltax = 2.
    const Mask a = rows_of({".", "#"});
    const Mask b = rows_of({"...", "..#"});
    const PlacedMask pa{&a, 2, 0}, pb{&b, 0, 0};
    EXPECT_FALSE(slide_loop(a, 2, 0, b, 0, 0));
    EXPECT_FALSE(slide_loop(a, 2, 0, b, 0, 0, false, true));  // the bound alone does not help
    EXPECT_TRUE(slide_loop(a, 2, 0, b, 0, 0, true, true));
    EXPECT_TRUE(reference::overlaps(pa, pb));
    EXPECT_TRUE(overlaps(pa, pb));
    EXPECT_EQ(reference::first_overlap(pa, pb), (Pixel{2, 1}));
    // The wrong sign also reports a collision that is not there: A's pixel is world (2,1), B's
    // only pixel world (6,3); deltax = 2, deltay = 1 and the slide reads B's (0+2, 0+1).
    const Mask c = rows_of({"#"});
    const Mask d = rows_of({"...", "..#"});
    const PlacedMask pc{&c, 2, 1}, pd{&d, 4, 2};
    EXPECT_TRUE(slide_loop(c, 2, 1, d, 4, 2));
    EXPECT_FALSE(slide_loop(c, 2, 1, d, 4, 2, true, true));
    EXPECT_FALSE(reference::overlaps(pc, pd));
    EXPECT_FALSE(overlaps(pc, pd));
    EXPECT_EQ(count_overlap(pc, pd), 0);
}

TEST(MaskLecture, SlideBoundMistakeIsFixed) {
    // Two one-pixel masks at the same place: the shared pixel is B's column 0 and row 0,
    // which "> 0" skips; the sign does not matter here (deltax = deltay = 0).
    const Mask a = rows_of({"#"});
    const PlacedMask pa{&a, 3, 7};
    EXPECT_FALSE(slide_loop(a, 3, 7, a, 3, 7));
    EXPECT_FALSE(slide_loop(a, 3, 7, a, 3, 7, true, false));
    EXPECT_TRUE(slide_loop(a, 3, 7, a, 3, 7, true, true));
    EXPECT_TRUE(reference::overlaps(pa, pa));
    EXPECT_EQ(reference::count_overlap(pa, pa), 1);
    EXPECT_EQ(first_overlap(pa, pa), (Pixel{3, 7}));
    // B's column 0 and row 0 hold the only shared pixel of a pair at different places.
    const Mask over = rows_of({"..", ".#"});  // at (-1,-1): its (1,1) is world (0,0)
    const Mask under = rows_of({"#.", ".."});  // at (0,0): its (0,0) is world (0,0), B's row 0
    EXPECT_FALSE(slide_loop(over, -1, -1, under, 0, 0, true, false));
    EXPECT_TRUE(reference::overlaps(PlacedMask{&over, -1, -1}, PlacedMask{&under, 0, 0}));
}

TEST(MaskDifferential, BitPackedEqualsReferenceOnRandomMasks) {
    Rng rng(0x6d61736bull);
    const std::array<int, 9> special{1, 63, 64, 65, 127, 128, 129, 150, 2};
    int hits = 0;
    for (int n = 0; n < 10000; ++n) {
        const int wa = n % 4 == 0 ? special[rng.below(9)] : uniform_int(rng, 1, 150);
        const int wb = n % 5 == 0 ? special[rng.below(9)] : uniform_int(rng, 1, 150);
        const Mask a = random_mask(rng, wa, uniform_int(rng, 1, 12));
        const Mask b = random_mask(rng, wb, uniform_int(rng, 1, 12));
        // B anywhere near the origin (both signs), now and then at large coordinates; A placed
        // so that the rectangles mostly overlap, every relative offset possible, some apart.
        const int base = n % 50 == 0 ? uniform_int(rng, -2000000, 2000000) : 0;
        const PlacedMask pb{&b, base + uniform_int(rng, -40, 40), base + uniform_int(rng, -20, 20)};
        const PlacedMask pa{&a, pb.x + uniform_int(rng, -wa - 3, wb + 3),
                            pb.y + uniform_int(rng, -a.height() - 2, b.height() + 2)};
        const int count = reference::count_overlap(pa, pb);
        ASSERT_EQ(count_overlap(pa, pb), count) << "case " << n << " wa " << wa << " wb " << wb;
        ASSERT_EQ(overlaps(pa, pb), count > 0) << "case " << n;
        ASSERT_EQ(reference::overlaps(pa, pb), count > 0) << "case " << n;
        ASSERT_EQ(first_overlap(pa, pb), reference::first_overlap(pa, pb)) << "case " << n;
        ASSERT_EQ(count_overlap(pb, pa), count) << "case " << n;
        hits += count > 0;
    }
    EXPECT_GT(hits, 4000);  // the cases really exercise overlaps, not only misses
    EXPECT_LT(hits, 9000);
}

TEST(MaskDifferential, EveryShiftAcrossWordBoundaries) {
    // Full masks of widths around 64: every x offset in +-140 shares exactly the overlap width.
    const std::array<int, 6> widths{63, 64, 65, 127, 128, 129};
    for (const int wa : widths) {
        for (const int wb : widths) {
            Mask a(wa, 2), b(wb, 1);
            for (int x = 0; x < wa; ++x) a.set(x, 1, true);
            for (int x = 0; x < wb; ++x) b.set(x, 0, true);
            for (int dx = -140; dx <= 140; ++dx) {
                const PlacedMask pa{&a, dx, -1}, pb{&b, 0, 0};
                const int expected = std::max(0, std::min(dx + wa, wb) - std::max(dx, 0));
                ASSERT_EQ(count_overlap(pa, pb), expected) << wa << " " << wb << " " << dx;
                ASSERT_EQ(first_overlap(pa, pb),
                          expected > 0 ? std::optional<Pixel>(Pixel{std::max(dx, 0), 0}) : std::nullopt);
            }
        }
    }
}

// Every kernel the CPU has (portable, bmi2, avx2, avx512: see mask.cpp) against reference:: on
// masks up to 600 wide (rows of 1..10 words, past the 8 lanes of a vector) and 40 tall (row
// blocks and their remainders), blobby or sparse, at every kind of offset: negative, huge,
// rectangles sharing one column, one row or one pixel.
TEST(MaskDifferential, EveryKernelEqualsReference) {
    using detail::MaskKernel;
    std::vector<MaskKernel> kernels{MaskKernel::portable};
    for (const MaskKernel k : {MaskKernel::bmi2, MaskKernel::avx2, MaskKernel::avx512})
        if (static_cast<int>(k) <= static_cast<int>(detail::best_mask_kernel())) kernels.push_back(k);
    Rng rng(0x6b65726eull);
    const std::array<int, 12> special{1, 2, 63, 64, 65, 127, 128, 129, 511, 512, 513, 600};
    int hits = 0;
    for (int n = 0; n < 3000; ++n) {
        const int wa = n % 3 == 0 ? special[rng.below(12)] : uniform_int(rng, 1, 600);
        const int wb = n % 4 == 0 ? special[rng.below(12)] : uniform_int(rng, 1, 600);
        const int ha = n % 7 == 0 ? 1 : uniform_int(rng, 1, 40);
        const int hb = uniform_int(rng, 1, 40);
        const Mask a = random_mask(rng, wa, ha, n % 2 == 0 ? 90 : 0);
        const Mask b = random_mask(rng, wb, hb);
        // Now and then far out, up to the ends of int (a mask there still fits in int).
        const int far = n % 2 == 0 ? std::numeric_limits<int>::max() - 1300 : std::numeric_limits<int>::min() + 1300;
        const int base = n % 97 == 0 ? far
                         : n % 20 == 0 ? uniform_int(rng, -1000000000, 1000000000)
                                       : uniform_int(rng, -300, 300);
        const PlacedMask pb{&b, base, -base / 2};
        PlacedMask pa{&a, pb.x + uniform_int(rng, -wa - 2, wb + 2), pb.y + uniform_int(rng, -ha - 2, hb + 2)};
        switch (n % 10) {  // rectangles sharing only an edge column or row, or a corner pixel
        case 0: pa.x = pb.x + wb - 1; break;
        case 1: pa.x = pb.x - wa + 1; break;
        case 2: pa.y = pb.y + hb - 1; break;
        case 3: pa = {&a, pb.x - wa + 1, pb.y - ha + 1}; break;
        default: break;
        }
        const int count = reference::count_overlap(pa, pb);
        const std::optional<Pixel> first = reference::first_overlap(pa, pb);
        for (const MaskKernel k : kernels) {
            const int kk = static_cast<int>(k);
            ASSERT_EQ(detail::count_overlap(pa, pb, k), count) << "case " << n << " kernel " << kk;
            ASSERT_EQ(detail::count_overlap(pb, pa, k), count) << "case " << n << " kernel " << kk;
            ASSERT_EQ(detail::overlaps(pa, pb, k), count > 0) << "case " << n << " kernel " << kk;
            ASSERT_EQ(detail::overlaps(pb, pa, k), count > 0) << "case " << n << " kernel " << kk;
            ASSERT_EQ(detail::first_overlap(pa, pb, k), first) << "case " << n << " kernel " << kk;
            ASSERT_EQ(detail::first_overlap(pb, pa, k), first) << "case " << n << " kernel " << kk;
        }
        ASSERT_EQ(count_overlap(pa, pb), count);
        ASSERT_EQ(first_overlap(pa, pb), first);
        hits += count > 0;
    }
    EXPECT_GT(hits, 1000);
    EXPECT_LT(hits, 2900);
}

// Masks of the same number of words per row (2, 3 or 4: the AVX-512 kernel packs 4 or 2 such
// rows into a vector) and of 1 or 2 (8 rows a vector), every kernel against reference::.
TEST(MaskDifferential, EqualStridesInEveryKernel) {
    using detail::MaskKernel;
    Rng rng(0x73747269ull);
    const std::array<std::array<int, 2>, 5> strides{{{1, 64}, {65, 128}, {129, 192}, {193, 256}, {1, 128}}};
    for (int n = 0; n < 2000; ++n) {
        const auto& range = strides[static_cast<std::size_t>(n) % strides.size()];
        const int wa = uniform_int(rng, range[0], range[1]);
        const int wb = uniform_int(rng, range[0], range[1]);
        const int ha = uniform_int(rng, 1, 30);
        const int hb = uniform_int(rng, 1, 30);
        const Mask a = random_mask(rng, wa, ha, n % 3 == 0 ? 0 : 97);
        const Mask b = random_mask(rng, wb, hb, n % 3 == 0 ? 0 : 97);
        const PlacedMask pb{&b, uniform_int(rng, -100, 100), uniform_int(rng, -100, 100)};
        const PlacedMask pa{&a, pb.x + uniform_int(rng, -wa, wb), pb.y + uniform_int(rng, -ha, hb)};
        const int count = reference::count_overlap(pa, pb);
        const std::optional<Pixel> first = reference::first_overlap(pa, pb);
        for (const MaskKernel k : {MaskKernel::portable, MaskKernel::bmi2, MaskKernel::avx2, MaskKernel::avx512}) {
            ASSERT_EQ(detail::count_overlap(pa, pb, k), count) << "case " << n;
            ASSERT_EQ(detail::overlaps(pb, pa, k), count > 0) << "case " << n;
            ASSERT_EQ(detail::first_overlap(pa, pb, k), first) << "case " << n;
            ASSERT_EQ(detail::first_overlap(pb, pa, k), first) << "case " << n;
        }
    }
}

// Every kernel against reference:: on one pair at one offset, both orders.
void expect_kernels_agree(const PlacedMask& pa, const PlacedMask& pb, const std::string& where) {
    using detail::MaskKernel;
    const int count = reference::count_overlap(pa, pb);
    const std::optional<Pixel> first = reference::first_overlap(pa, pb);
    for (const MaskKernel k : {MaskKernel::portable, MaskKernel::bmi2, MaskKernel::avx2, MaskKernel::avx512}) {
        const std::string at = where + " kernel " + std::to_string(static_cast<int>(k));
        ASSERT_EQ(detail::overlaps(pa, pb, k), count > 0) << at;
        ASSERT_EQ(detail::overlaps(pb, pa, k), count > 0) << at;
        ASSERT_EQ(detail::first_overlap(pa, pb, k), first) << at;
        ASSERT_EQ(detail::first_overlap(pb, pa, k), first) << at;
        ASSERT_EQ(detail::count_overlap(pa, pb, k), count) << at;
    }
}

// Pixels where (x + y) is even (parity 0) or odd, counted in world pixels from the mask's
// placement: two such masks of different parity never share a pixel, so a read of the wrong
// word, row or lane (a neighbouring column, the next row) would find one.
Mask checkerboard(int w, int h, int x, int y, int parity) {
    Mask m(w, h);
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i)
            if (((x + i + y + j) & 1) == parity) m.set(i, j, true);
    return m;
}

// Two masks of the same words per row, 1..8 (the AVX-512 kernel packs 8 / stride rows a vector
// for strides 1, 2, 4 and 8 and reads the first vector without a load mask, and the AVX2 one
// reads 8 words a step without one, up into the clear
// words after a mask's last row), at x offsets across the whole width and word boundaries, with
// 1..9 shared rows that end at a mask's last row or start at its first: random masks, sparse
// or dense, and checkerboards that never share a pixel.
TEST(MaskDifferential, SameStridesAtEveryAlignmentDownToTheLastRow) {
    Rng rng(0x70616464ull);
    int hits = 0;
    int cases = 0;
    for (int stride = 1; stride <= 8; ++stride) {
        for (int n = 0; n < 8; ++n) {
            const int wa = n == 0 ? 64 * stride : uniform_int(rng, 64 * stride - 63, 64 * stride);
            const int wb = n == 1 ? 64 * stride - 63 : uniform_int(rng, 64 * stride - 63, 64 * stride);
            const int ha = uniform_int(rng, 1, 20);
            const int hb = uniform_int(rng, 1, 20);
            // B's last `rows` rows under A's first ones, or A's last under B's first.
            const int rows = uniform_int(rng, 1, std::min(9, std::min(ha, hb)));
            const int by = n % 2 == 0 ? rows - hb : ha - rows;
            const int step = stride <= 2 ? 1 : 7;  // every alignment in 64 steps of 7
            for (int dx = -wb + 1; dx < wa; dx += dx < -wb + 66 || dx > wa - 66 ? 1 : step) {
                const std::string where = "stride " + std::to_string(stride) + " case " + std::to_string(n) +
                                          " dx " + std::to_string(dx);
                const int base = uniform_int(rng, -200, 200);
                if (n % 4 == 3) {
                    const Mask a = checkerboard(wa, ha, base, 0, 0);
                    const Mask b = checkerboard(wb, hb, base + dx, by, 1);
                    expect_kernels_agree({&a, base, 0}, {&b, base + dx, by}, where + " checkerboard");
                    ASSERT_FALSE(overlaps(PlacedMask{&a, base, 0}, PlacedMask{&b, base + dx, by})) << where;
                } else {
                    const Mask a = random_mask(rng, wa, ha, n % 4 == 0 ? 95 : 0);
                    const Mask b = random_mask(rng, wb, hb, n % 4 == 0 ? 95 : 0);
                    expect_kernels_agree({&a, base, 0}, {&b, base + dx, by}, where);
                    hits += overlaps(PlacedMask{&a, base, 0}, PlacedMask{&b, base + dx, by});
                }
                ++cases;
            }
        }
    }
    EXPECT_GT(cases, 3000);
    EXPECT_GT(hits, cases / 4);  // the random cases really exercise hits, not only misses
}

// The public queries run the best kernel the CPU has: a CPU check or a table that fell back
// to a lesser kernel would still pass every test above, only slower.
TEST(MaskDifferential, TheQueriesRunTheBestKernelTheCpuHas) {
    using detail::MaskKernel;
#if defined(__x86_64__) && defined(__GNUC__)
    __builtin_cpu_init();
    const bool bmi2 = __builtin_cpu_supports("popcnt") && __builtin_cpu_supports("bmi") && __builtin_cpu_supports("bmi2");
    const bool avx2 = bmi2 && __builtin_cpu_supports("avx") && __builtin_cpu_supports("avx2");
    const bool avx512 = avx2 && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
                        __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq") &&
                        __builtin_cpu_supports("avx512vpopcntdq") && __builtin_cpu_supports("avx512vbmi2");
    const MaskKernel expected = avx512 ? MaskKernel::avx512 : avx2 ? MaskKernel::avx2 : bmi2 ? MaskKernel::bmi2 : MaskKernel::portable;
#else
    const MaskKernel expected = MaskKernel::portable;
#endif
    EXPECT_EQ(static_cast<int>(detail::best_mask_kernel()), static_cast<int>(expected));
}

TEST(MaskDifferential, EmptyMasksMissInEveryKernel) {
    using detail::MaskKernel;
    const Mask full = rows_of({"###", "###"});
    const Mask none;
    const Mask clear(200, 30);
    const Mask flat(100, 0);
    for (const MaskKernel k : {MaskKernel::portable, MaskKernel::bmi2, MaskKernel::avx2, MaskKernel::avx512}) {
        for (const Mask* m : {&none, &clear, &flat}) {
            const PlacedMask pa{&full, 1, 1}, pb{m, 0, 0};
            EXPECT_FALSE(detail::overlaps(pa, pb, k));
            EXPECT_FALSE(detail::overlaps(pb, pa, k));
            EXPECT_EQ(detail::first_overlap(pb, pa, k), std::nullopt);
            EXPECT_EQ(detail::count_overlap(pa, pb, k), 0);
        }
        EXPECT_FALSE(detail::overlaps(PlacedMask{}, PlacedMask{&full, 0, 0}, k));
        EXPECT_EQ(detail::count_overlap(PlacedMask{&full, 0, 0}, PlacedMask{}, k), 0);
    }
}

// ================================ Mask MTD ====================================================

TEST(MaskMtd, HandComputed) {
    const Mask box = rows_of({"##", "##"});
    // B's column 1 is shared: the shortest push is one pixel left, away from B.
    expect_translation(collide(PlacedMask{&box, 0, 0}, PlacedMask{&box, 1, 0}), -1, 0);
    // Diagonal: A's one pixel on the centre of a plus; the four arms block every unit push, the
    // four diagonals are free and tie; centres equal, so the fixed order picks (-1, -1).
    const Mask dot = rows_of({"#"});
    const Mask plus = rows_of({".#.", "###", ".#."});
    const Manifold d = collide(PlacedMask{&dot, 0, 0}, PlacedMask{&plus, -1, -1});
    expect_translation(d, -1, -1);
    EXPECT_FLOAT_EQ(d.depth, std::sqrt(2.0f));
    // A hole: the rectangles overlap but no pixel is shared: a miss.
    const Mask ring = rows_of({"###", "#.#", "###"});
    expect_miss(collide(PlacedMask{&dot, 0, 0}, PlacedMask{&ring, -1, -1}));
    // Depth 2 through a thick wall, 1 through a thin part of it.
    const Mask wall = rows_of({"####", "####", "####"});
    expect_translation(collide(PlacedMask{&box, 1, 1}, PlacedMask{&wall, 0, 0}), 0, 2);
}

TEST(MaskMtd, TieRulePushesAwayFromTheCentreThenFixedOrder) {
    const Mask box = rows_of({"##", "##"});
    // Coincident: equal centres, (+-2, 0) and (0, +-2) tie; the fixed order gives (-2, 0),
    // normal {1, 0}, as for coincident circles.
    const Manifold same = collide(PlacedMask{&box, 5, 5}, PlacedMask{&box, 5, 5});
    expect_translation(same, -2, 0);
    EXPECT_EQ(same.normal, (Vec2{1, 0}));
    EXPECT_FALSE(std::signbit(same.normal.y));  // +0, not -0: state hashes read the bytes
    // Every unit push frees A's one pixel; B's rectangle reaches further down, so its centre is
    // below A's: A goes up, dot((0,-1), (0,-0.5)) is the largest.
    const Mask dot = rows_of({"#"});
    const Mask low = rows_of({"...", ".#.", "...", "..."});
    expect_translation(collide(PlacedMask{&dot, 0, 0}, PlacedMask{&low, -1, -1}), 0, -1);
    const Mask left = rows_of({"....", "..#.", "...."});
    expect_translation(collide(PlacedMask{&dot, 0, 0}, PlacedMask{&left, -2, -1}), 1, 0);
    // Equal dot (0) for (0, 1) and (0, -1): smaller dy first.
    const Mask bar = rows_of({"###"});
    expect_translation(collide(PlacedMask{&dot, 0, 0}, PlacedMask{&bar, -1, 0}), 0, -1);
}

TEST(MaskMtd, EqualsReferenceOnSmallMasks) {
    Rng rng(20240901);
    int hits = 0;
    int deep = 0;
    for (int n = 0; n < 4000; ++n) {
        // Half of them dense, for deep overlaps and long searches.
        const int dense = n % 2 == 0 ? 60 : 0;
        const Mask a = random_mask(rng, uniform_int(rng, 1, 12), uniform_int(rng, 1, 12), dense);
        const Mask b = random_mask(rng, uniform_int(rng, 1, 12), uniform_int(rng, 1, 12), dense);
        const PlacedMask pb{&b, uniform_int(rng, -4, 4), uniform_int(rng, -4, 4)};
        const PlacedMask pa{&a, pb.x + uniform_int(rng, -a.width(), b.width()),
                            pb.y + uniform_int(rng, -a.height(), b.height())};
        const Manifold fast = collide(pa, pb);
        const Manifold slow = reference::collide(pa, pb);
        ASSERT_EQ(fast.hit, slow.hit) << "case " << n;
        ASSERT_EQ(fast.depth, slow.depth) << "case " << n;
        ASSERT_EQ(fast.normal, slow.normal) << "case " << n;
        ASSERT_EQ(fast.hit, overlaps(pa, pb));
        if (!fast.hit) {
            expect_miss(fast);
            continue;
        }
        ++hits;
        deep += fast.depth >= 3.0f;
        ASSERT_GE(fast.depth, 1.0f);
        // After moving A by the MTD no pixel is shared.
        const auto t = translation_of(fast);
        const PlacedMask moved{&a, pa.x + static_cast<int>(t[0]), pa.y + static_cast<int>(t[1])};
        ASSERT_FALSE(reference::overlaps(moved, pb)) << "case " << n;
        ASSERT_NEAR(std::hypot(static_cast<double>(t[0]), static_cast<double>(t[1])), fast.depth, 1e-5);
    }
    EXPECT_GT(hits, 2000);
    EXPECT_GT(deep, 300);  // depth >= 3
}

TEST(MaskMtd, LargeMasksFinishWithTheShortestPush) {
    // 200 x 200 solid on 200 x 200 solid offset by (30, 170): the cheapest is 30 left... and
    // 30 up is (200 - 170) too; dot prefers away from B's centre: A is right and below B,
    // cA - cB = (30, 170): dot((-30, 0)) = -900 vs dot((0, 30)) = +5100; down wins: (0, 30).
    Mask big(200, 200);
    for (int y = 0; y < 200; ++y)
        for (int x = 0; x < 200; ++x) big.set(x, y, true);
    expect_translation(collide(PlacedMask{&big, 30, 170}, PlacedMask{&big, 0, 0}), 0, 30);
    expect_translation(collide(PlacedMask{&big, 0, 0}, PlacedMask{&big, 0, 0}), -200, 0);
}

// ================================ Mask vs shapes ==============================================

TEST(MaskShapes, AabbHandComputedCentreRule) {
    const Mask m = rows_of({"###", "###", "###"});
    const PlacedMask p{&m, 0, 0};
    // Column 2's centres are at x = 2.5, on the box's edge: closed, so they meet it.
    const Aabb edge{{2.5f, 0.0f}, {10.0f, 10.0f}};
    EXPECT_TRUE(overlaps(p, edge));
    EXPECT_EQ(count_overlap(p, edge), 3);
    EXPECT_EQ(first_overlap(p, edge), (Pixel{2, 0}));
    expect_translation(collide(p, edge), -1, 0);
    // Past the centres: no pixel, though the box covers part of column 2's square.
    const Aabb past{{2.6f, 0.0f}, {10.0f, 10.0f}};
    EXPECT_FALSE(overlaps(p, past));
    expect_miss(collide(p, past));
    // A box smaller than a pixel, around one centre.
    const Aabb tiny{{1.4f, 2.4f}, {1.6f, 2.6f}};
    EXPECT_EQ(first_overlap(p, tiny), (Pixel{1, 2}));
    EXPECT_EQ(count_overlap(p, tiny), 1);
    const Aabb point{{1.5f, 0.5f}, {1.5f, 0.5f}};
    EXPECT_EQ(count_overlap(p, point), 1);
}

TEST(MaskShapes, CirclePolygonSegmentHandComputed) {
    const Mask m = rows_of({"###", "###", "###"});
    const PlacedMask p{&m, 0, 0};
    // Radius 1 about the middle centre: the plus of 5 (corners are sqrt 2 away).
    EXPECT_EQ(count_overlap(p, Shape{Circle{{1.5f, 1.5f}, 1.0f}}), 5);
    EXPECT_EQ(first_overlap(p, Shape{Circle{{1.5f, 1.5f}, 1.0f}}), (Pixel{1, 0}));
    EXPECT_EQ(count_overlap(p, Shape{Circle{{1.5f, 1.5f}, 0.0f}}), 1);  // a point on a centre
    // x + y <= 3: centres with i + j + 1 <= 3, the boundary ones included.
    const Polygon tri = triangle({0, 0}, {3, 0}, {0, 3});
    EXPECT_EQ(count_overlap(p, Shape{tri}), 6);
    // The diagonal (0,0)-(3,3) touches the 3 diagonal squares and, through their shared
    // corners (1,1) and (2,2), the 4 squares beside them.
    EXPECT_EQ(count_overlap(p, Shape{Segment{{0, 0}, {3, 3}}}), 7);
    // x = 1 is the border of columns 0 and 1: both touch; x = 0.5 only column 0.
    EXPECT_EQ(count_overlap(p, Shape{Segment{{1, -5}, {1, 5}}}), 6);
    EXPECT_EQ(count_overlap(p, Shape{Segment{{0.5f, -5}, {0.5f, 5}}}), 3);
    EXPECT_EQ(count_overlap(p, Shape{Segment{{3, 3}, {3, 3}}}), 1);  // a point on a corner
    EXPECT_EQ(count_overlap(p, Shape{Segment{{3.01f, 0}, {3.01f, 3}}}), 0);
    // Segment MTD: the line y = 1 touches rows 0 and 1 (closed squares). Down 2 puts row 0 at
    // [2, 3], free; up needs 3; sideways more than 10.
    expect_translation(collide(p, Segment{{-10, 1}, {10, 1}}), 0, 2);
    // Circle MTD: radius 0.5 about pixel (0,0)'s centre holds that centre only. (1, 0) and
    // (0, 1) free it and tie on length and on dot with cA - cB = (1, 1); smaller |dy| wins.
    expect_translation(collide(p, Circle{{0.5f, 0.5f}, 0.5f}), 1, 0);
}

TEST(MaskShapes, OverlapQueriesMatchPerPixelBruteForce) {
    Rng rng(77);
    for (int n = 0; n < 2000; ++n) {
        const Mask m = random_mask(rng, uniform_int(rng, 1, 140), uniform_int(rng, 1, 16));
        const PlacedMask p{&m, uniform_int(rng, -30, 10), uniform_int(rng, -10, 5)};
        const float x0 = static_cast<float>(p.x) - 5.0f, x1 = static_cast<float>(p.x + m.width()) + 5.0f;
        const float y0 = static_cast<float>(p.y) - 5.0f, y1 = static_cast<float>(p.y + m.height()) + 5.0f;
        const auto point = [&]() { return Vec2{grid(rng, x0, x1), grid(rng, y0, y1)}; };
        std::vector<std::pair<Shape, PixelTest>> shapes;
        {
            const Vec2 a = point(), b = point();
            const Aabb box{min(a, b), max(a, b)};
            shapes.emplace_back(box, pixel_test(box));
        }
        {
            const Circle c{point(), grid(rng, 0.0f, 12.0f)};
            shapes.emplace_back(c, pixel_test(c));
        }
        {
            const Vec2 c = point();
            std::vector<Vec2> pts;
            for (int k = 0; k < 6; ++k) pts.push_back(c + Vec2{grid(rng, -10, 10), grid(rng, -6, 6)});
            if (const auto poly = hull_polygon(pts)) shapes.emplace_back(*poly, pixel_test(*poly));
        }
        {
            Segment s{point(), point()};
            if (n % 7 == 0) s.b = s.a;  // a point
            if (n % 7 == 1) s.b.y = s.a.y;  // horizontal
            if (n % 7 == 2) s.b.x = s.a.x;  // vertical
            if (n % 7 == 3) s.a = {std::round(s.a.x), std::round(s.a.y)}, s.b = {std::round(s.b.x), std::round(s.b.y)};
            shapes.emplace_back(s, pixel_test(s));
        }
        for (const auto& [shape, test] : shapes) {
            const BruteHits want = brute_hits(m, p.x, p.y, test);
            ASSERT_EQ(count_overlap(p, shape), want.count) << "case " << n << " shape " << shape.index();
            ASSERT_EQ(first_overlap(p, shape), want.first) << "case " << n << " shape " << shape.index();
            if (const Aabb* box = std::get_if<Aabb>(&shape)) {
                ASSERT_EQ(count_overlap(p, *box), want.count);
                ASSERT_EQ(first_overlap(p, *box), want.first);
                ASSERT_EQ(overlaps(p, *box), want.count > 0);
            }
        }
    }
}

TEST(MaskShapes, ObbMatchesItsBoxAndRotatedBruteForce) {
    Rng rng(99);
    for (int n = 0; n < 500; ++n) {
        const Mask m = random_mask(rng, uniform_int(rng, 1, 70), uniform_int(rng, 1, 20));
        const PlacedMask p{&m, uniform_int(rng, -10, 10), uniform_int(rng, -10, 10)};
        const Vec2 c{grid(rng, -10, 40), grid(rng, -10, 20)};
        const Vec2 half{grid(rng, 0, 15), grid(rng, 0, 10)};
        // Angle 0 is exactly its Aabb.
        const Obb straight{c, half, 0.0f};
        const Aabb box{c - half, c + half};
        ASSERT_EQ(count_overlap(p, Shape{straight}), count_overlap(p, box));
        ASSERT_EQ(first_overlap(p, Shape{straight}), first_overlap(p, box));
        const Manifold mo = collide(p, straight), mb = collide(p, box);
        ASSERT_EQ(mo.hit, mb.hit);
        ASSERT_EQ(mo.depth, mb.depth);
        ASSERT_EQ(mo.normal, mb.normal);
        // Rotated: agree with the box-frame test except for centres within 1e-3 of the edge.
        const Obb turned{c, half, rng.uniform(-3.2f, 3.2f)};
        const double cs = std::cos(static_cast<double>(turned.angle())), sn = std::sin(static_cast<double>(turned.angle()));
        int got = count_overlap(p, Shape{turned}), lo = 0, hi = 0;
        for (int j = 0; j < m.height(); ++j)
            for (int i = 0; i < m.width(); ++i) {
                if (!m.get(i, j)) continue;
                const double dx = p.x + i + 0.5 - c.x, dy = p.y + j + 0.5 - c.y;
                const double margin = std::max(std::abs(dx * cs + dy * sn) - half.x, std::abs(-dx * sn + dy * cs) - half.y);
                if (margin <= -1e-3) ++lo;
                if (margin <= 1e-3) ++hi;
            }
        ASSERT_GE(got, lo) << "case " << n;
        ASSERT_LE(got, hi) << "case " << n;
    }
}

TEST(MaskShapes, CollideMatchesExhaustiveSearch) {
    Rng rng(4242);
    int hits = 0;
    for (int n = 0; n < 800; ++n) {
        const Mask m = random_mask(rng, uniform_int(rng, 1, 8), uniform_int(rng, 1, 8));
        const PlacedMask p{&m, uniform_int(rng, -4, 4), uniform_int(rng, -4, 4)};
        const auto point = [&]() { return Vec2{grid(rng, -6, 10), grid(rng, -6, 10)}; };
        Manifold got;
        PixelTest test;
        double bcx = 0.0, bcy = 0.0;
        switch (n % 4) {
            case 0: {
                const Vec2 a = point(), b = point();
                const Aabb box{min(a, b), max(a, b)};
                got = collide(p, box);
                test = pixel_test(box);
                bcx = 0.5 * (static_cast<double>(box.min.x) + box.max.x);
                bcy = 0.5 * (static_cast<double>(box.min.y) + box.max.y);
                break;
            }
            case 1: {
                const Circle c{point(), grid(rng, 0, 7)};
                got = collide(p, c);
                test = pixel_test(c);
                bcx = c.center.x;
                bcy = c.center.y;
                break;
            }
            case 2: {
                std::vector<Vec2> pts;
                for (int k = 0; k < 5; ++k) pts.push_back(point());
                const auto poly = hull_polygon(pts);
                if (!poly) continue;
                got = collide(p, *poly);
                test = pixel_test(*poly);
                for (int k = 0; k < poly->count(); ++k) {  // the vertex mean
                    bcx += poly->points()[static_cast<std::size_t>(k)].x;
                    bcy += poly->points()[static_cast<std::size_t>(k)].y;
                }
                bcx /= poly->count();
                bcy /= poly->count();
                break;
            }
            default: {
                const Segment s{point(), point()};
                got = collide(p, s);
                test = pixel_test(s);
                bcx = 0.5 * (static_cast<double>(s.a.x) + s.b.x);
                bcy = 0.5 * (static_cast<double>(s.a.y) + s.b.y);
                break;
            }
        }
        const auto want = brute_mtd(m, p.x, p.y, test, bcx, bcy);
        ASSERT_EQ(got.hit, want.has_value()) << "case " << n;
        if (!want) {
            expect_miss(got);
            continue;
        }
        ++hits;
        SCOPED_TRACE("case " + std::to_string(n));
        expect_translation(got, (*want)[0], (*want)[1]);
    }
    EXPECT_GT(hits, 250);
}

// A segment or a sliver holds no pixel inside it, so crossing a solid mask the search jumps by
// the mask's own runs of set pixels: dense masks make those runs long (a jump one too long
// fails here).
TEST(MaskShapes, ThinShapesAcrossDenseMasksMatchTheExhaustiveSearch) {
    Rng rng(7177);
    int hits = 0;
    int slivers = 0;
    for (int n = 0; n < 330; ++n) {
        // The last 30 wide and short, so that the columns' words past the first are read (and
        // the exhaustive search stays quick: the push down or up is short).
        const bool wide = n >= 300;
        const Mask m = wide ? random_mask(rng, uniform_int(rng, 60, 140), uniform_int(rng, 2, 5), 85)
                            : random_mask(rng, uniform_int(rng, 3, 12), uniform_int(rng, 3, 12), 75);
        const PlacedMask p{&m, uniform_int(rng, -2, 2), uniform_int(rng, -2, 2)};
        // From one side of the mask to the other, across x or across y.
        const float w = static_cast<float>(m.width()), h = static_cast<float>(m.height());
        const float x = static_cast<float>(p.x), y = static_cast<float>(p.y);
        Vec2 a{grid(rng, x - 2, x + 1), grid(rng, y - 2, y + h + 2)};
        Vec2 b{grid(rng, x + w - 1, x + w + 2), grid(rng, y - 2, y + h + 2)};
        if (n % 4 >= 2 || wide) {
            a = {grid(rng, x - 2, x + w + 2), grid(rng, y - 2, y + 1)};
            b = {grid(rng, x - 2, x + w + 2), grid(rng, y + h - 1, y + h + 2)};
        }
        Manifold got;
        PixelTest test;
        double bcx = 0.0, bcy = 0.0;
        const std::optional<Polygon> sliver = n % 2 == 0 ? hull_polygon({a, b, a + Vec2{0.5f, -0.375f}}) : std::nullopt;
        if (sliver) {
            ++slivers;
            got = collide(p, *sliver);
            test = pixel_test(*sliver);
            for (const Vec2 q : sliver->points()) {
                bcx += q.x / 3.0;
                bcy += q.y / 3.0;
            }
        } else {
            const Segment s{a, b};
            got = collide(p, s);
            test = pixel_test(s);
            bcx = 0.5 * (static_cast<double>(s.a.x) + s.b.x);
            bcy = 0.5 * (static_cast<double>(s.a.y) + s.b.y);
        }
        const auto want = brute_mtd(m, p.x, p.y, test, bcx, bcy);
        ASSERT_EQ(got.hit, want.has_value()) << "case " << n;
        if (!want) continue;
        ++hits;
        SCOPED_TRACE("case " + std::to_string(n));
        expect_translation(got, (*want)[0], (*want)[1]);
    }
    EXPECT_GT(hits, 200);
    EXPECT_GT(slivers, 120);
}

// A thin mask under a solid one, both ways round: the jump reads either mask's column.
TEST(MaskMtd, LinesAcrossSolidMasksEqualReference) {
    Rng rng(9090);
    for (int n = 0; n < 330; ++n) {
        const bool wide = n >= 300;  // words past the first: wide and short, as above
        const Mask solid = wide ? random_mask(rng, uniform_int(rng, 60, 140), uniform_int(rng, 2, 6), 85)
                                : random_mask(rng, uniform_int(rng, 4, 14), uniform_int(rng, 4, 14), 85);
        Mask line(wide ? uniform_int(rng, 60, 140) : uniform_int(rng, 4, 14), wide ? uniform_int(rng, 2, 6) : uniform_int(rng, 4, 14));
        const int steps = std::max(line.width(), line.height());
        const int x0 = uniform_int(rng, 0, line.width() - 1), y0 = uniform_int(rng, 0, line.height() - 1);
        const int x1 = uniform_int(rng, 0, line.width() - 1), y1 = uniform_int(rng, 0, line.height() - 1);
        for (int k = 0; k <= steps; ++k)  // a digital line from (x0, y0) to (x1, y1)
            line.set(x0 + (x1 - x0) * k / steps, y0 + (y1 - y0) * k / steps, true);
        const PlacedMask ps{&solid, uniform_int(rng, -3, 3), uniform_int(rng, -3, 3)};
        const PlacedMask pl{&line, uniform_int(rng, -3, 3), uniform_int(rng, -3, 3)};
        for (const auto& [pa, pb] : {std::pair{ps, pl}, std::pair{pl, ps}}) {
            const Manifold fast = collide(pa, pb);
            const Manifold slow = reference::collide(pa, pb);
            ASSERT_EQ(fast.hit, slow.hit) << "case " << n;
            ASSERT_EQ(fast.depth, slow.depth) << "case " << n;
            ASSERT_EQ(fast.normal, slow.normal) << "case " << n;
            detail::use_mask_search_shortcuts(false);  // the plain scan: B's runs only
            const Manifold plain = collide(pa, pb);
            detail::use_mask_search_shortcuts(true);
            ASSERT_EQ(plain.depth, fast.depth) << "case " << n;
            ASSERT_EQ(plain.normal, fast.normal) << "case " << n;
        }
    }
}

TEST(MaskShapes, DeepInsideLargeShapes) {
    Mask m(8, 8);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) m.set(x, y, true);
    const PlacedMask p{&m, 0, 0};
    // The nearest face is the top: centres 0.5..7.5 must all get below y = -500: 508 up.
    expect_translation(collide(p, Aabb{{-1000, -500}, {3000, 20000}}), 0, -508);
    // A huge box: only the nearest face matters (centres 0.5.. must pass y = 30: 30 down),
    // and the search stays short.
    expect_translation(collide(p, Aabb{{-90000, -90000}, {90000, 30}}), 0, 30);
    // A disc and a polygon 30 px around the mask, against the exhaustive search.
    Mask small(4, 3);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 4; ++x) small.set(x, y, x != 1 || y != 1);
    const PlacedMask q{&small, 0, 0};
    const Circle disc{{2.125f, 1.5f}, 30.0f};
    const auto want_disc = brute_mtd(small, 0, 0, pixel_test(disc), 2.125, 1.5);
    expect_translation(collide(q, disc), (*want_disc)[0], (*want_disc)[1]);
    const Polygon tri = triangle({-20, -30}, {40, 5}, {-25, 35});
    const auto want_tri = brute_mtd(small, 0, 0, pixel_test(tri), (-20.0 + 40 - 25) / 3, (-30.0 + 5 + 35) / 3);
    expect_translation(collide(q, tri), (*want_tri)[0], (*want_tri)[1]);
}

// A push longer than 16 px is searched with the convex regions' seeds and skipped columns
// (search_mtd's hooks): the same answer as the plain column scan, bit for bit, and as the
// exhaustive search where that is affordable.
Shape random_deep_shape(Rng& rng, Vec2 c, float size) {
    const float hx = rng.uniform(0.3f, 1.0f) * size, hy = rng.uniform(0.3f, 1.0f) * size;
    switch (uniform_int(rng, 0, 3)) {
        case 0: return Aabb{{c.x - hx, c.y - hy}, {c.x + hx, c.y + hy}};
        case 1: {
            // Axis-aligned, nearly so, and any angle: vertical faces are the bound's special case.
            const int k = uniform_int(rng, 0, 3);
            const float angle = k == 0 ? 0.0f : k == 1 ? 1.5707964f : k == 2 ? rng.uniform(-1e-6f, 1e-6f) : rng.uniform(-3.2f, 3.2f);
            return Obb{c, {hx, hy}, angle};
        }
        case 2: return Circle{c, hx};
        default: {
            // Made about the origin, then turned and moved in float as the world places its
            // colliders: the rounded vertices need not be convex any more.
            std::vector<Vec2> pts;
            const int n = uniform_int(rng, 3, 9);
            for (int i = 0; i < n; ++i) {
                const float a = rng.uniform(0.0f, 6.2831853f);
                pts.push_back({hx * std::cos(a), hy * std::sin(a)});
            }
            if (const auto poly = hull_polygon(pts)) return poly->transformed({c, Rot::from_angle(rng.uniform(-3.2f, 3.2f))});
            return Circle{c, hx};
        }
    }
}

TEST(MaskShapes, SearchShortcutsGiveThePlainScansAnswer) {
    Rng rng(77);
    int deep = 0;
    for (int n = 0; n < 1500; ++n) {
        const Mask m = random_mask(rng, uniform_int(rng, 1, 40), uniform_int(rng, 1, 40), 20);
        const float size = std::pow(10.0f, rng.uniform(1.2f, 2.7f));  // 16 to 500 px
        // A third far out, where a float vertex rounds to 1/128 px.
        const float far = n % 3 == 2 ? static_cast<float>(uniform_int(rng, -99000, 99000)) : 0.0f;
        const Vec2 c{far + rng.uniform(-size, size), far + rng.uniform(-size, size)};
        const Shape shape = random_deep_shape(rng, c, size);
        // Mostly inside the shape, some across its boundary.
        const float spread = n % 3 == 0 ? 1.2f : 0.5f;
        const PlacedMask p{&m, static_cast<int>(std::floor(c.x + rng.uniform(-spread, spread) * size)),
                           static_cast<int>(std::floor(c.y + rng.uniform(-spread, spread) * size))};
        const Manifold fast = collide(Shape{p}, shape);
        detail::use_mask_search_shortcuts(false);
        const Manifold plain = collide(Shape{p}, shape);
        detail::use_mask_search_shortcuts(true);
        ASSERT_EQ(fast.hit, plain.hit) << "case " << n;
        // Bit for bit: the state hashes read these bytes.
        ASSERT_EQ(std::bit_cast<std::uint32_t>(fast.depth), std::bit_cast<std::uint32_t>(plain.depth)) << "case " << n;
        ASSERT_EQ(std::bit_cast<std::uint64_t>(fast.normal), std::bit_cast<std::uint64_t>(plain.normal)) << "case " << n;
        if (fast.depth > 16.0f) ++deep;
    }
    EXPECT_GT(deep, 600);  // most cases take the shortcuts
}

// Found by review: a polygon moved in float has its vertical face at x = 20000.498 and the next
// vertex two ulps to its right, so the vertices' bounds reach past the faces' intersection (the
// region). The bound took the column's probe at x = 20000.5 as inside and skipped column 0,
// which holds the answer: the push was (1, -4) where (0, -4) is free.
TEST(MaskShapes, SearchShortcutsReadTheFacesNotTheVerticesBounds) {
    const std::array<Vec2, 5> pts{Vec2{-0.00095f, 0}, Vec2{0.00095f, 10}, Vec2{0.00296f, 200}, Vec2{-100, 200}, Vec2{-100, 0}};
    const Polygon poly = make_polygon(pts).value().moved({20000.498046875f, 0});
    ASSERT_EQ(poly.points()[0].x, poly.points()[1].x);
    ASSERT_GT(poly.points()[2].x, poly.points()[1].x);
    Mask m(30, 161);
    for (int i = 0; i < 29; ++i)
        for (int j = 0; j < 3; ++j) m.set(i, j, true);
    for (int j = 150; j < 161; ++j) m.set(29, j, true);
    const PlacedMask p{&m, 19971, 1};
    expect_translation(collide(p, poly), 0, -4);
    detail::use_mask_search_shortcuts(false);
    expect_translation(collide(p, poly), 0, -4);
    detail::use_mask_search_shortcuts(true);
}

TEST(MaskShapes, SearchShortcutsMatchTheExhaustiveSearch) {
    Rng rng(78);
    int deep = 0;
    for (int n = 0; n < 120; ++n) {
        const Mask m = random_mask(rng, uniform_int(rng, 1, 6), uniform_int(rng, 1, 6), 30);
        const Vec2 c{grid(rng, -4, 4), grid(rng, -4, 4)};
        const Shape shape = random_deep_shape(rng, c, rng.uniform(28.0f, 36.0f));
        const PlacedMask p{&m, uniform_int(rng, -6, 2), uniform_int(rng, -6, 2)};
        const Manifold got = collide(Shape{p}, shape);
        double bcx = 0.0, bcy = 0.0;  // B's centre, as the tie rule reads it
        PixelTest test;
        std::visit(
            [&](const auto& b) {
                using B = std::decay_t<decltype(b)>;
                if constexpr (std::is_same_v<B, Aabb>) {
                    test = pixel_test(b);
                    bcx = 0.5 * (static_cast<double>(b.min.x) + b.max.x);
                    bcy = 0.5 * (static_cast<double>(b.min.y) + b.max.y);
                } else if constexpr (std::is_same_v<B, Circle>) {
                    test = pixel_test(b);
                    bcx = b.center.x;
                    bcy = b.center.y;
                } else if constexpr (std::is_same_v<B, Obb>) {
                    // The module's own pixel rule (one pixel as a mask): what is checked here is
                    // the search, which RotatedObbMtdIsShortestAndFrees also reads this way.
                    test = [&b](double px, double py) {
                        static const Mask one = rows_of({"#"});
                        return count_overlap(PlacedMask{&one, static_cast<int>(px), static_cast<int>(py)}, Shape{b}) > 0;
                    };
                    bcx = b.center.x;
                    bcy = b.center.y;
                } else if constexpr (std::is_same_v<B, Polygon>) {
                    test = pixel_test(b);
                    for (const Vec2 v : b.points()) {
                        bcx += v.x;
                        bcy += v.y;
                    }
                    bcx /= b.count();
                    bcy /= b.count();
                }
            },
            shape);
        const auto want = brute_mtd(m, p.x, p.y, test, bcx, bcy);
        ASSERT_EQ(got.hit, want.has_value()) << "case " << n;
        if (!want) continue;
        SCOPED_TRACE("case " + std::to_string(n));
        expect_translation(got, (*want)[0], (*want)[1]);
        if (got.depth > 16.0f) ++deep;  // long enough for the shortcuts
    }
    EXPECT_GT(deep, 40);
}

TEST(MaskShapes, RotatedObbMtdIsShortestAndFrees) {
    Rng rng(5);
    for (int n = 0; n < 200; ++n) {
        const Mask m = random_mask(rng, uniform_int(rng, 1, 10), uniform_int(rng, 1, 10));
        const PlacedMask p{&m, uniform_int(rng, -5, 5), uniform_int(rng, -5, 5)};
        const Obb box{{rng.uniform(-4, 8), rng.uniform(-4, 8)}, {rng.uniform(0, 8), rng.uniform(0, 5)},
                      rng.uniform(-3.2f, 3.2f)};
        const Manifold got = collide(p, box);
        ASSERT_EQ(got.hit, count_overlap(p, Shape{box}) > 0);
        if (!got.hit) continue;
        // No shorter translation is free, and the chosen one is (by the module's own pixel test).
        const auto t = translation_of(got);
        const i64 r2 = t[0] * t[0] + t[1] * t[1];
        const int reach = static_cast<int>(std::ceil(got.depth));
        for (int dy = -reach; dy <= reach; ++dy)
            for (int dx = -reach; dx <= reach; ++dx)
                if (dx * dx + dy * dy < r2) {
                    ASSERT_GT(count_overlap(PlacedMask{&m, p.x + dx, p.y + dy}, Shape{box}), 0) << n;
                }
        ASSERT_EQ(count_overlap(PlacedMask{&m, p.x + static_cast<int>(t[0]), p.y + static_cast<int>(t[1])}, Shape{box}), 0);
    }
}

TEST(MaskShapes, NonFiniteShapesAndEmptyMasksMiss) {
    const Mask m = rows_of({"##", "##"});
    const PlacedMask p{&m, 0, 0};
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    const std::vector<Shape> bad{
        Aabb{{nan, 0}, {5, 5}},
        Aabb{{-inf, -inf}, {inf, inf}},
        Obb{{1, 1}, {5, 5}, nan},
        Obb{{1, 1}, {inf, 5}, 0},
        Circle{{1, 1}, inf},
        Circle{{nan, 1}, 5},
        Circle{{1, 1}, -1},
        Segment{{0, 0}, {nan, 1}},
        triangle({0, 0}, {5, 0}, {0, 5}),
        // Malformed by the module's one rule (detail::valid), as for every other query.
        Obb{{1, 1}, {-1, 5}, 0},
        Obb{{1, 1}, {2e38f, 1}, 0.5f},
        Aabb{{2, 2}, {0, 0}},
        Segment{{-3e38f, 0}, {3e38f, 0}},
    };
    for (std::size_t k = 0; k < bad.size(); ++k) {
        Shape s = bad[k];
        if (const auto* poly = std::get_if<Polygon>(&s)) s = poly->moved({0, nan});  // the empty polygon
        EXPECT_EQ(count_overlap(p, s), 0) << k;
        EXPECT_EQ(first_overlap(p, s), std::nullopt) << k;
    }
    expect_miss(collide(p, Aabb{{nan, 0}, {5, 5}}));
    expect_miss(collide(p, Obb{{1, 1}, {5, 5}, nan}));
    expect_miss(collide(p, Circle{{1, 1}, inf}));
    expect_miss(collide(p, Segment{{inf, 0}, {1, 1}}));
    expect_miss(collide(p, triangle({0, 0}, {5, 0}, {0, 5}).moved({inf, 0})));  // the empty polygon
    expect_miss(collide(p, Polygon{}));
    EXPECT_FALSE(overlaps(p, Aabb{{nan, nan}, {nan, nan}}));
    // An inverted box contains nothing.
    EXPECT_FALSE(overlaps(p, Aabb{{2, 2}, {0, 0}}));
    // Null and empty masks.
    const Mask empty;
    for (const PlacedMask& none : {PlacedMask{}, PlacedMask{&empty, 0, 0}}) {
        EXPECT_FALSE(overlaps(none, Aabb{{-9, -9}, {9, 9}}));
        EXPECT_EQ(count_overlap(none, Shape{Circle{{0, 0}, 9}}), 0);
        EXPECT_EQ(first_overlap(none, Shape{Segment{{0, 0}, {1, 1}}}), std::nullopt);
        expect_miss(collide(none, Circle{{0, 0}, 9}));
        expect_miss(collide(none, Segment{{0, 0}, {1, 1}}));
    }
}

TEST(MaskShapes, ShapeVariantWithAMaskUsesMaskRules) {
    const Mask a = rows_of({"##.", ".##"});
    const Mask b = rows_of({".#", "##", "#."});
    const PlacedMask pa{&a, -1, 4}, pb{&b, 0, 3};
    EXPECT_EQ(count_overlap(pa, Shape{pb}), 2);
    EXPECT_EQ(first_overlap(pa, Shape{pb}), (Pixel{0, 4}));
}

// ================================ closest_point ===============================================

TEST(MaskClosestPoint, HandComputed) {
    const Mask m = rows_of({"#..", "...", "..#"});
    const PlacedMask p{&m, 10, 20};  // set squares [10,11]x[20,21] and [12,13]x[22,23]
    const ClosestPoint inside = closest_point(p, {10.5f, 20.25f});
    EXPECT_EQ(inside.point, (Vec2{10.5f, 20.25f}));
    EXPECT_EQ(inside.distance, 0.0f);
    const ClosestPoint edge = closest_point(p, {13, 22.5f});  // on the closed square's side
    EXPECT_EQ(edge.distance, 0.0f);
    const ClosestPoint gap = closest_point(p, {11.5f, 21.5f});  // the clear middle pixel
    EXPECT_FLOAT_EQ(gap.distance, std::sqrt(0.5f));
    const ClosestPoint left = closest_point(p, {7, 20.5f});
    EXPECT_EQ(left.point, (Vec2{10, 20.5f}));
    EXPECT_EQ(left.distance, 3.0f);
    const ClosestPoint below = closest_point(p, {16, 27});
    EXPECT_EQ(below.point, (Vec2{13, 23}));
    EXPECT_EQ(below.distance, 5.0f);
}

TEST(MaskClosestPoint, EmptyMaskOrNonFiniteQueryHasNoPoint) {
    const Mask clear(5, 5);
    const Vec2 q{3, 4};
    for (const PlacedMask& none : {PlacedMask{}, PlacedMask{&clear, 0, 0}}) {
        const ClosestPoint c = closest_point(none, q);
        EXPECT_EQ(c.point, (Vec2{0, 0}));  // the manual: point {0, 0} at distance +infinity
        EXPECT_EQ(c.distance, std::numeric_limits<float>::infinity());
    }
    const Mask one = rows_of({"#"});
    const ClosestPoint nan_query = closest_point(PlacedMask{&one, 0, 0}, {std::nanf(""), 0});
    EXPECT_EQ(nan_query.point, (Vec2{0, 0}));
    EXPECT_EQ(nan_query.distance, std::numeric_limits<float>::infinity());
}

TEST(MaskClosestPoint, MatchesBruteForce) {
    Rng rng(31337);
    for (int n = 0; n < 1000; ++n) {
        const Mask m = random_mask(rng, uniform_int(rng, 1, 140), uniform_int(rng, 1, 12));
        if (m.count() == 0) continue;
        const PlacedMask p{&m, uniform_int(rng, -20, 20), uniform_int(rng, -20, 20)};
        const Vec2 q{grid(rng, -40, 180), grid(rng, -40, 40)};
        double best = std::numeric_limits<double>::infinity();
        for (int j = 0; j < m.height(); ++j)
            for (int i = 0; i < m.width(); ++i) {
                if (!m.get(i, j)) continue;
                const double x0 = p.x + i, y0 = p.y + j;
                const double gx = std::max({0.0, x0 - q.x, q.x - (x0 + 1)});
                const double gy = std::max({0.0, y0 - q.y, q.y - (y0 + 1)});
                best = std::min(best, std::sqrt(gx * gx + gy * gy));
            }
        const ClosestPoint c = closest_point(p, q);
        ASSERT_EQ(c.distance, static_cast<float>(best)) << "case " << n;
        ASSERT_NEAR(length(c.point - q), c.distance, 1e-4f * (1.0f + c.distance));
        // The point lies on a set pixel's closed square.
        const int i = static_cast<int>(std::floor(c.point.x)) - p.x, j = static_cast<int>(std::floor(c.point.y)) - p.y;
        ASSERT_TRUE(m.get(i, j) || m.get(i - 1, j) || m.get(i, j - 1) || m.get(i - 1, j - 1)) << "case " << n;
    }
}

}  // namespace
}  // namespace jostle
