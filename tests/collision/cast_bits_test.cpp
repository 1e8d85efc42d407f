// cast(Polygon)'s AVX2 path (cast.cpp: every edge in a lane, one VDIVPS for every t, a min over
// lanes and lane masks) against the plain loop, bit for bit: hit, t, point and normal, on seeded
// random casts against polygons of 3..16 vertices, with starts and ends on vertices, on edges,
// along edges (parallel), on a grid of integers (ties between edges), zero-length motions, and
// inputs past the limits (NaN, infinities, huge and denormal coordinates); and against polygons
// made every way the module makes them, since the AVX2 path reads the unused slots up to 8 and
// counts on their normals being zero.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <optional>
#include <vector>

#include "test_shapes.h"

namespace jostle {
namespace {

using test::kInf;
using test::kNan;

std::uint32_t bits(float f) { return std::bit_cast<std::uint32_t>(f); }

bool same_bits(const CastHit& a, const CastHit& b) {
    return a.hit == b.hit && bits(a.t) == bits(b.t) && bits(a.point.x) == bits(b.point.x) &&
           bits(a.point.y) == bits(b.point.y) && bits(a.normal.x) == bits(b.normal.x) &&
           bits(a.normal.y) == bits(b.normal.y);
}

// Points a cast can start or end at: near the polygon, on its vertices and edges, along an
// edge's line, on the integer grid, or past the limits.
Vec2 pick_point(Rng& rng, const Polygon& p) {
    const auto pts = p.points();
    const Vec2 a = pts[rng.below(static_cast<std::uint32_t>(pts.size()))];
    const Vec2 b = pts[rng.below(static_cast<std::uint32_t>(pts.size()))];
    const float odd[] = {kNan, kInf, -kInf, 3e38f, -3e38f, 1e-45f, 1e19f, 0.0f};
    switch (rng.below(8)) {
        case 0:
            return a;
        case 1:
            return a + 0.5f * (b - a);
        case 2:
            return a + rng.uniform(-3.0f, 3.0f) * (b - a);  // along a chord or an edge
        case 3:
            return {static_cast<float>(rng.below(21)) - 10.0f, static_cast<float>(rng.below(21)) - 10.0f};
        case 4:
            return {odd[rng.below(8)], rng.uniform(-10.0f, 10.0f)};
        default:
            return a + Vec2{rng.uniform(-8.0f, 8.0f), rng.uniform(-8.0f, 8.0f)};
    }
}

// A polygon of 3..8 random vertices, a box or an integer hexagon (exact ties), of 16 vertices
// (the loop on both paths), scaled and shifted toward the limits.
std::optional<Polygon> pick_polygon(Rng& rng) {
    std::vector<Vec2> pts;
    switch (rng.below(4)) {
        case 0:
            pts = {{-2, -1}, {0, -2}, {2, -1}, {2, 1}, {0, 2}, {-2, 1}};
            break;
        case 1:
            pts = {{0, 0}, {3, 0}, {3, 2}, {0, 2}};
            break;
        case 2:
            for (int i = 0; i < 16; ++i) {
                const float a = 2.0f * test::kPi * static_cast<float>(i) / 16.0f;
                pts.push_back({5.0f * std::cos(a), 5.0f * std::sin(a)});
            }
            break;
        default: {
            const Polygon p = test::random_polygon(rng, 10.0f);
            pts.assign(p.points().begin(), p.points().end());
        }
    }
    const float scales[] = {1.0f, 1.0f, 1e-30f, 1e-38f, 1e17f, 1e30f};
    const float shifts[] = {0.0f, 0.0f, 1e7f, 1e30f, -3e38f};
    const float scale = scales[rng.below(6)];
    const Vec2 shift{shifts[rng.below(5)], shifts[rng.below(5)]};
    for (Vec2& v : pts) v = v * scale + shift;
    return make_polygon(pts);
}

TEST(CastPolygonBits, Avx2AndLoopAgree) {
    if (!detail::use_avx2_paths(true)) GTEST_SKIP() << "this CPU has no AVX2: the loop is the only path";
    Rng rng(0xca57u);
    long compared = 0, hits = 0;
    for (int n = 0; n < 100000 && !HasFailure(); ++n) {
        const auto poly = pick_polygon(rng);
        if (!poly) continue;
        for (int k = 0; k < 100; ++k) {
            const Vec2 from = pick_point(rng, *poly);
            const Vec2 to = rng.below(8) == 0 ? from : pick_point(rng, *poly);  // zero-length motions too
            detail::use_avx2_paths(true);
            const CastHit simd = cast(from, to, *poly);
            detail::use_avx2_paths(false);
            const CastHit loop = cast(from, to, *poly);
            ++compared;
            hits += loop.hit;
            if (!same_bits(simd, loop)) {
                ADD_FAILURE() << "polygon " << n << " of " << poly->count() << " vertices, from (" << from.x
                              << ", " << from.y << ") to (" << to.x << ", " << to.y << "): AVX2 hit "
                              << simd.hit << " t " << simd.t << " normal (" << simd.normal.x << ", "
                              << simd.normal.y << "), loop hit " << loop.hit << " t " << loop.t << " normal ("
                              << loop.normal.x << ", " << loop.normal.y << ")";
                break;
            }
        }
    }
    detail::use_avx2_paths(true);
    EXPECT_GT(compared, 1500000);
    EXPECT_GT(hits, compared / 10);  // the generators reach the polygons
}

// Every way of making a Polygon keeps the slots past its vertices zero (the AVX2 path reads 8
// slots, and a nonzero normal there would act as an extra edge): test::polygons_made_every_way.
TEST(CastPolygonBits, PolygonsMadeEveryWayAgreeWithTheLoop) {
    if (!detail::use_avx2_paths(true)) GTEST_SKIP() << "this CPU has no AVX2: the loop is the only path";
    Rng rng(0x510757u);
    long compared = 0;
    Polygon reused = test::random_polygon(rng);  // moved_into's target, its count changing
    for (int n = 0; n < 2000 && !HasFailure(); ++n) {
        const Polygon base = test::random_polygon(rng, 10.0f);
        const Vec2 shift{rng.uniform(-5.0f, 5.0f), rng.uniform(-5.0f, 5.0f)};
        const float angle = rng.uniform(-3.0f, 3.0f);
        const Vec2 half{rng.uniform(0.5f, 4.0f), rng.uniform(0.5f, 4.0f)};
        for (const Polygon& poly : test::polygons_made_every_way(base, shift, angle, half, reused)) {
            ASSERT_GE(poly.count(), 3);
            for (int k = 0; k < 20; ++k) {
                const Vec2 from = pick_point(rng, poly);
                const Vec2 to = pick_point(rng, poly);
                detail::use_avx2_paths(true);
                const CastHit simd = cast(from, to, poly);
                detail::use_avx2_paths(false);
                const CastHit loop = cast(from, to, poly);
                ++compared;
                if (!same_bits(simd, loop)) {
                    ADD_FAILURE() << "polygon " << n << " of " << poly.count() << " vertices: AVX2 hit " << simd.hit
                                  << " t " << simd.t << ", loop hit " << loop.hit << " t " << loop.t;
                    break;
                }
            }
        }
        reused = test::random_polygon(rng);  // a new count, most of the time
    }
    detail::use_avx2_paths(true);
    EXPECT_GT(compared, 300000);
}

}  // namespace
}  // namespace jostle
