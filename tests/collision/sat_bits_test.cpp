// The box pair's lane-parallel SAT (sat.cpp, box_box: four axes to an SSE register, the axis
// picked by a lane mask) against the plain scalar loop of the lecture (09-50 to 09-60: every
// axis's projected radii and centre distance, the smaller push of each axis, the least push
// of all, a later axis winning only when strictly smaller), bit for bit: hit, depth and normal
// of collide(Obb, Obb) and collide(Aabb, Obb), on seeded random boxes at every angle, at
// integer positions and sizes (ties between axes and pushes), touching, contained and
// coincident, and on inputs past the limits (NaN, infinities, -0, overflow).
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>

#include "bits_check.h"
#include "test_shapes.h"

namespace jostle {
namespace {

using test::kInf;
using test::kNan;
using test::kPi;

bool finite(float v) { return std::isfinite(v); }

// collide(Obb, Obb)'s validity rule: finite centre, half extents and angle, half extents >= 0.
bool valid_box(const Obb& b) {
    return finite(b.center.x) && finite(b.center.y) && finite(b.half.x) && finite(b.half.y) && finite(b.angle()) &&
           b.half.x >= 0.0f && b.half.y >= 0.0f;
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

}  // namespace
}  // namespace jostle
