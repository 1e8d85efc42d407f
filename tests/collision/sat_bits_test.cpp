// The box pair's lane-parallel SAT (sat.cpp, box_box: four axes to an SSE register, the axis
// picked by a lane mask) against the plain scalar loop of the lecture (09-50 to 09-60: every
// axis's projected radii and centre distance, the smaller push of each axis, the least push
// of all, a later axis winning only when strictly smaller), bit for bit: hit, depth and normal
// of collide(Obb, Obb) and collide(Aabb, Obb), on seeded random boxes at every angle, at
// integer positions and sizes (ties between axes and pushes), touching, contained and
// coincident, and on inputs past the limits (NaN, infinities, -0, overflow). The polygon
// pair's faces in lanes (polygon_polygon, four faces a register, and its AVX2 twin, eight)
// against the slides' face loop the same way, at the end of the file.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "bits_check.h"
#include "test_shapes.h"

namespace jostle {
namespace {

using test::kInf;
using test::kNan;
using test::kPi;

bool finite(float v) { return std::isfinite(v); }

// collide(Obb, Obb)'s validity rule: finite centre, half extents and angle, half extents >= 0,
// and a size within float: the centre plus and minus twice the halves' sum finite.
bool valid_box(const Obb& b) {
    const float reach = 2.0f * (b.half.x + b.half.y);
    return finite(b.center.x) && finite(b.center.y) && finite(b.half.x) && finite(b.half.y) && finite(b.angle()) &&
           b.half.x >= 0.0f && b.half.y >= 0.0f && finite(b.center.x + reach) && finite(b.center.x - reach) &&
           finite(b.center.y + reach) && finite(b.center.y - reach);
}

using test::same_bits;
constexpr auto hit = test::scalar_hit;

// The lecture's loop over the four axes: A's x and y, then B's x and y. Each box's radius on
// an axis is its half extents times the |cos| of the angles between the axis and its own axes
// (on its own axes, its half extent); the push that separates along u is r - s (A moves by
// -push u, normal u) or r + s (normal -u), s = dot(d, u). Sums are taken in the order the
// lanes take them, so that the answer is the same bits.
Manifold scalar_box_box(Vec2 ha, Rot qa, Vec2 hb, Rot qb, Vec2 d) {
    const Vec2 u[4] = {{qa.c, qa.s}, {-qa.s, qa.c}, {qb.c, qb.s}, {-qb.s, qb.c}};
    // |cos| between A's axis i and B's axis j: x terms first, as the lanes add them.
    const auto cosine = [&](int i, int j) { return std::fabs(u[i].x * u[j].x + u[i].y * u[j].y); };
    const float c00 = cosine(0, 2), c01 = cosine(0, 3), c10 = cosine(1, 2), c11 = cosine(1, 3);
    const float r[4] = {ha.x + (hb.x * c00 + hb.y * c01), ha.y + (hb.x * c10 + hb.y * c11),
                        (ha.x * c00 + ha.y * c10) + hb.x, (ha.x * c01 + ha.y * c11) + hb.y};
    float best = kInf;
    Vec2 normal{};
    bool taken = false;
    for (int i = 0; i < 4; ++i) {
        const float s = u[i].x * d.x + u[i].y * d.y;
        const float push_pos = r[i] - s, push_neg = r[i] + s;
        if (!(push_pos >= 0.0f && push_neg >= 0.0f)) return {};  // a separating axis (or NaN)
        const bool pos = push_pos <= push_neg;
        const float push = pos ? push_pos : push_neg;
        if (push < best) {
            best = push;
            normal = pos ? u[i] : Vec2{-u[i].x, -u[i].y};
            taken = true;
        }
    }
    if (!taken) return {};  // every push overflowed: inf depth, a miss
    return hit(best, normal);
}

Manifold scalar_obb_obb(const Obb& a, const Obb& b) {
    const Manifold m = scalar_box_box(a.half, a.rotation(), b.half, b.rotation(), b.center - a.center);
    if (!m.hit || !(valid_box(a) && valid_box(b))) return {};
    return m;
}

Manifold scalar_aabb_obb(const Aabb& a, const Obb& b) {
    // A finite AABB whose extent is finite too (max - min may overflow), min <= max.
    if (!(finite(a.min.x) && finite(a.min.y) && finite(a.max.x) && finite(a.max.y) && a.min.x <= a.max.x &&
          a.min.y <= a.max.y && finite(a.max.x - a.min.x) && finite(a.max.y - a.min.y) && valid_box(b)))
        return {};
    const Vec2 half = (a.max - a.min) * 0.5f;
    return scalar_box_box(half, Rot{}, b.half, b.rotation(), (b.center - a.min) - half);
}

// The draws: seeded, one value in 16 past the limits, and the boxes this test needs.
struct Draw : test::BitsDraw {
    Draw() : BitsDraw(20261127, 16) {}
    // An angle: any, a multiple of a quarter turn (axes parallel: ties), or near one.
    float angle() {
        switch (below(4)) {
            case 0: return static_cast<float>(below(8)) * 0.5f * kPi;
            case 1: return static_cast<float>(below(8)) * 0.25f * kPi + uniform(-1e-6f, 1e-6f);
            default: return uniform(-4.0f * kPi, 4.0f * kPi);
        }
    }
    // A box near B: overlapping, touching, contained, coincident or apart.
    Obb box_near(Vec2 around, float scale, bool integers) {
        Vec2 c{around.x + uniform(-2.0f, 2.0f) * scale, around.y + uniform(-2.0f, 2.0f) * scale};
        Vec2 h{uniform(0.0f, scale), uniform(0.0f, scale)};
        if (integers) {
            c = {std::round(c.x), std::round(c.y)};
            h = {std::round(h.x), std::round(h.y)};
        }
        if (below(10) == 0) c = around;  // coincident centres
        return Obb({wild(c.x), wild(c.y)}, {wild(h.x), wild(h.y)}, wild(angle()));
    }
};

TEST(SatBits, ObbObbMatchesTheScalarLoop) {
    Draw g;
    for (int k = 0; k < 200000; ++k) {
        const bool integers = k % 3 == 0;
        const float scale = integers ? static_cast<float>(1 + g.below(20)) : g.uniform(0.01f, 100.0f);
        const Vec2 at = k % 5 == 0 ? Vec2{g.uniform(-1e5f, 1e5f), g.uniform(-1e5f, 1e5f)} : Vec2{};
        const Obb a = g.box_near(at, scale, integers);
        const Obb b = g.box_near(at, scale, integers);
        SCOPED_TRACE(testing::Message() << "case " << k);
        ASSERT_TRUE(same_bits(collide(a, b), scalar_obb_obb(a, b)));
        ASSERT_TRUE(same_bits(collide(b, a), scalar_obb_obb(b, a)));
    }
}

TEST(SatBits, AabbObbMatchesTheScalarLoop) {
    Draw g;
    for (int k = 0; k < 100000; ++k) {
        const bool integers = k % 3 == 0;
        const float scale = integers ? static_cast<float>(1 + g.below(20)) : g.uniform(0.01f, 100.0f);
        const Obb b = g.box_near({}, scale, integers);
        const Obb like = g.box_near({}, scale, integers);  // its centre and half extents as an AABB
        const Aabb a{like.center - like.half, like.center + like.half};
        SCOPED_TRACE(testing::Message() << "case " << k);
        ASSERT_TRUE(same_bits(collide(a, b), scalar_aabb_obb(a, b)));
    }
}

// The cases the lanes' selection must get right one by one: ties between A's and B's axes
// (the first wins), ties between the two pushes of an axis (+u wins), every push overflowing
// (a miss), and a -0 component in the normal (made +0).
TEST(SatBits, TiesOverflowAndSignedZeros) {
    const Obb unit({0.0f, 0.0f}, {1.0f, 1.0f});
    const Manifold cases[] = {
        collide(unit, unit),                                                   // all four axes tie
        collide(unit, Obb({0.0f, 0.0f}, {1.0f, 1.0f}, 0.5f * kPi)),           // B turned a quarter
        collide(unit, Obb({0.0f, 0.5f}, {1.0f, 1.0f}, kPi)),                  // -0 in B's axes
        collide(Obb({0.0f, 0.0f}, {3e38f, 3e38f}), Obb({1.0f, 0.0f}, {3e38f, 3e38f})),  // pushes overflow
        collide(Obb({-0.0f, -0.0f}, {1.0f, 2.0f}), Obb({0.0f, -0.0f}, {2.0f, 1.0f}, -kPi)),
    };
    const Manifold want[] = {
        scalar_obb_obb(unit, unit),
        scalar_obb_obb(unit, Obb({0.0f, 0.0f}, {1.0f, 1.0f}, 0.5f * kPi)),
        scalar_obb_obb(unit, Obb({0.0f, 0.5f}, {1.0f, 1.0f}, kPi)),
        scalar_obb_obb(Obb({0.0f, 0.0f}, {3e38f, 3e38f}), Obb({1.0f, 0.0f}, {3e38f, 3e38f})),
        scalar_obb_obb(Obb({-0.0f, -0.0f}, {1.0f, 2.0f}), Obb({0.0f, -0.0f}, {2.0f, 1.0f}, -kPi)),
    };
    for (std::size_t i = 0; i < std::size(cases); ++i) EXPECT_TRUE(same_bits(cases[i], want[i])) << "case " << i;
    EXPECT_TRUE(test::is_miss(cases[3]));  // inf depth
    EXPECT_EQ(std::bit_cast<std::uint32_t>(cases[0].normal.y), 0u);  // +0, not -0
}


// ---------------------------------------------------------------------------------------
// Polygon pairs (sat.cpp, polygon_polygon and its AVX2 twin polygon_polygon8: faces four or
// eight to a register, the gap and the largest separation from lane masks) against the
// slides' loop in its one-sided form (09-62 over the Minkowski difference's faces, as the
// comment above polygon_polygon derives it): for each face i of A in order, B's separation
// min_j dot(n_i, b_j - a_i), a gap (> 0, or NaN) ending the test; then B's faces against A;
// the largest separation, the first face of a tie and A's face on a tie between the two.

// The largest separation of `others` from the faces of `p`, or the first gap.
struct ScalarFace {
    float separation = -kInf;
    int face = 0;
    bool gap = false;
};
ScalarFace scalar_max_face_separation(const Polygon& p, const Polygon& others) {
    ScalarFace best;
    for (int i = 0; i < p.count(); ++i) {
        const Vec2 n = p.normals()[i], v = p.points()[i];
        float s = kInf;
        for (int j = 0; j < others.count(); ++j) {
            const Vec2 o = others.points()[j];
            const float d = n.x * (o.x - v.x) + n.y * (o.y - v.y);  // x term first, as the lanes
            s = j == 0 || d < s ? d : s;  // a NaN never replaces the smallest (nor is replaced)
        }
        if (!(s <= 0.0f)) return {s, i, true};
        if (s > best.separation) best = {s, i, false};
    }
    return best;
}

Manifold scalar_polygon_polygon(const Polygon& a, const Polygon& b) {
    if (a.count() == 0 || b.count() == 0) return {};
    const ScalarFace fa = scalar_max_face_separation(a, b);
    if (fa.gap) return {};
    const ScalarFace fb = scalar_max_face_separation(b, a);
    if (fb.gap) return {};
    const bool a_face = fa.separation >= fb.separation;
    const float depth = -(a_face ? fa.separation : fb.separation);
    if (!(depth < kInf)) return {};
    const Vec2 n = a_face ? a.normals()[fa.face] : -b.normals()[fb.face];
    return hit(depth, n);
}

// A convex polygon of 3..16 vertices (both paths' group sizes and the spare slots past them)
// around `at`, radius up to `size`; on the integer grid when `integers` (ties between faces,
// edges lying on each other).
std::optional<Polygon> random_polygon_up_to_16(test::BitsDraw& g, Vec2 at, float size, bool integers) {
    const int n = 3 + g.below(14);
    const float step = 2.0f * kPi / static_cast<float>(n);
    const float base = g.uniform(0.0f, 2.0f * kPi);
    const float ry = g.uniform(0.3f, 1.0f);
    std::vector<Vec2> pts;
    for (int i = 0; i < n; ++i) {
        const float angle = base + step * (static_cast<float>(i) + g.uniform(-0.3f, 0.3f));
        Vec2 v{at.x + size * std::cos(angle), at.y + size * ry * std::sin(angle)};
        if (integers) v = {std::round(v.x), std::round(v.y)};
        pts.push_back(v);
    }
    if (g.below(2) == 0) std::reverse(pts.begin(), pts.end());
    return make_polygon(pts);  // nullopt for points the rounding made collinear or repeated
}

// Every pair both ways, with the AVX2 paths on (where the CPU has them: else both runs take
// the SSE path, which the tests below record) and off.
::testing::AssertionResult polygon_pair_matches(const Polygon& a, const Polygon& b) {
    const Manifold want_ab = scalar_polygon_polygon(a, b), want_ba = scalar_polygon_polygon(b, a);
    for (const bool avx2 : {true, false}) {
        detail::use_avx2_paths(avx2);
        const Manifold got_ab = collide(a, b), got_ba = collide(b, a);
        detail::use_avx2_paths(true);
        if (auto r = same_bits(got_ab, want_ab); !r) return r << " (A, B; AVX2 paths " << (avx2 ? "on)" : "off)");
        if (auto r = same_bits(got_ba, want_ba); !r) return r << " (B, A; AVX2 paths " << (avx2 ? "on)" : "off)");
    }
    return ::testing::AssertionSuccess();
}

TEST(SatBits, PolygonPolygonMatchesTheScalarFaceLoop) {
    RecordProperty("avx2_paths", detail::use_avx2_paths(true) ? "on and off" : "none on this CPU: SSE only");
    test::BitsDraw g(0x9a1eu, 1000);
    int hits = 0, pairs = 0;
    for (int k = 0; k < 200000; ++k) {
        const bool integers = k % 3 == 0;
        const float size = integers ? static_cast<float>(2 + g.below(12)) : g.uniform(0.01f, 50.0f);
        const Vec2 at = k % 5 == 0 ? Vec2{g.uniform(-1e5f, 1e5f), g.uniform(-1e5f, 1e5f)} : Vec2{};
        const auto a = random_polygon_up_to_16(g, at, size, integers);
        const Vec2 near{at.x + g.uniform(-2.0f, 2.0f) * size, at.y + g.uniform(-2.0f, 2.0f) * size};
        // One pair in 8 the same polygon twice (every face tied with its twin), one in 8 a
        // smaller one inside (containment), else a second polygon nearby.
        const int kind = g.below(8);
        const auto b = kind == 0   ? a
                       : kind == 1 ? random_polygon_up_to_16(g, at, 0.25f * size, integers)
                                   : random_polygon_up_to_16(g, integers ? Vec2{std::round(near.x), std::round(near.y)} : near,
                                                             size * g.uniform(0.2f, 1.5f), integers);
        if (!a || !b) continue;
        SCOPED_TRACE(testing::Message() << "case " << k);
        ASSERT_TRUE(polygon_pair_matches(*a, *b));
        hits += collide(*a, *b).hit;
        ++pairs;
    }
    // The draws must reach what they are for: thousands of pairs, hits and misses.
    EXPECT_GT(pairs, 150000);
    EXPECT_GT(hits, 15000);
    EXPECT_LT(hits, pairs - 10000);
}

// Past the limits: polygons scaled and moved until separations overflow to +-inf or NaN,
// and an empty Polygon, which every query answers with a miss.
TEST(SatBits, PolygonPolygonMatchesTheScalarFaceLoopPastTheLimits) {
    RecordProperty("avx2_paths", detail::use_avx2_paths(true) ? "on and off" : "none on this CPU: SSE only");
    test::BitsDraw g(0x51c4u, 1000);
    const float scales[] = {1.0f, 1e6f, 1e17f, 1e18f};
    const float shifts[] = {0.0f, 1e30f, 1.7e38f, 2e38f, -2e38f};
    int compared = 0;
    for (int k = 0; k < 6000; ++k) {
        const float scale = scales[g.below(4)];
        const auto far = [&](Vec2 at) -> std::optional<Polygon> {
            const auto p = random_polygon_up_to_16(g, at * scale, 5.0f * scale, false);
            if (!p) return std::nullopt;
            return p->moved({shifts[g.below(5)], shifts[g.below(5)]});
        };
        const auto a = far({}), b = far({g.uniform(-5.0f, 5.0f), g.uniform(-5.0f, 5.0f)});
        if (!a || !b) continue;
        SCOPED_TRACE(testing::Message() << "case " << k);
        ASSERT_TRUE(polygon_pair_matches(*a, *b));
        ++compared;
    }
    EXPECT_GT(compared, 5000);
    const Polygon empty;
    const auto tri = make_polygon(std::vector<Vec2>{{0.0f, 0.0f}, {4.0f, 0.0f}, {0.0f, 3.0f}});
    ASSERT_TRUE(tri.has_value());
    EXPECT_TRUE(polygon_pair_matches(empty, *tri));
    EXPECT_TRUE(polygon_pair_matches(empty, empty));
}

}  // namespace
}  // namespace jostle
