// Dispatch tests (dispatch.cpp): every pair of shape kinds through collide(Shape, Shape) and
// overlaps(Shape, Shape) gives a defined result, agrees with the typed function, is symmetric
// with the normal flipped; and hostile input (NaN, infinities) is a miss with all zeros
// through every entry point, degenerate shapes give finite results.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include "test_shapes.h"

namespace jostle {
namespace {

using test::describe;
using test::is_miss;
using test::kInf;
using test::kNan;

Mask mask_or_die(std::vector<std::string_view> rows) {
    std::string error;
    auto m = Mask::from_rows(rows, &error);
    EXPECT_TRUE(m.has_value()) << error;
    return m.value_or(Mask{});
}

const Mask& block_mask() {
    static const Mask m = mask_or_die({"####", "####", "####"});
    return m;
}

const Mask& ell_mask() {
    static const Mask m = mask_or_die({"#..", "#..", "###"});
    return m;
}

// One shape of every kind, all overlapping each other around (1..5, 0..5), chosen without ties.
std::vector<Shape> first_shapes() {
    return {
        Aabb{{0, 0}, {4, 3}},
        Obb{{3, 2}, {2, 1}, 0.3f},
        test::polygon_or_die({{1, 1}, {6, 2}, {2, 5}}),
        Circle{{2, 1.5f}, 1.7f},
        Segment{{-1, 0.5f}, {5, 3.3f}},
        PlacedMask{&block_mask(), 1, 1},
    };
}

// A second set, other sizes and places, still overlapping the first.
std::vector<Shape> second_shapes() {
    return {
        Aabb{{2.3f, 1.6f}, {7, 4.1f}},
        Obb{{2.2f, 3.1f}, {1.5f, 2.5f}, -0.7f},
        test::polygon_or_die({{3, 0}, {7, 1}, {6, 4}, {2.5f, 3}}),
        Circle{{3.7f, 2.9f}, 2.2f},
        Segment{{1.2f, 4.6f}, {4.4f, -0.3f}},
        PlacedMask{&ell_mask(), 2, 2},
    };
}

::testing::AssertionResult is_defined(const Manifold& m, bool mask_pair) {
    if (!m.hit) return is_miss(m);
    if (!std::isfinite(m.depth) || m.depth < 0.0f) return ::testing::AssertionFailure() << "depth " << m.depth;
    if (mask_pair && m.depth < 1.0f) return ::testing::AssertionFailure() << "mask hit with depth " << m.depth;
    return test::is_unit(m.normal);
}

bool is_mask(const Shape& s) { return std::holds_alternative<PlacedMask>(s); }

TEST(Dispatch, EveryPairOfKindsIsDefinedSymmetricAndConsistent) {
    const auto as = first_shapes();
    const auto bs = second_shapes();
    int hits = 0;
    for (const Shape& a : as) {
        for (const Shape& b : bs) {
            SCOPED_TRACE(describe(a) + " vs " + describe(b));
            const bool mask_pair = is_mask(a) || is_mask(b);
            const Manifold ab = collide(a, b);
            const Manifold ba = collide(b, a);
            EXPECT_TRUE(is_defined(ab, mask_pair));
            EXPECT_TRUE(is_defined(ba, mask_pair));
            EXPECT_EQ(ab.hit, ba.hit);
            EXPECT_NEAR(ab.depth, ba.depth, 1e-5f);
            EXPECT_VEC_NEAR(ab.normal, -ba.normal, 1e-5f);
            EXPECT_EQ(overlaps(a, b), ab.hit);
            EXPECT_EQ(overlaps(b, a), ba.hit);
            hits += ab.hit ? 1 : 0;
        }
    }
    // The sets were chosen to overlap pairwise; a dispatcher that misses them all is broken.
    EXPECT_EQ(hits, 36);
}

TEST(Dispatch, FarApartEveryPairMisses) {
    const auto as = first_shapes();
    const auto bs = second_shapes();
    for (const Shape& a : as) {
        for (Shape b : bs) {
            b = test::moved(b, {100, 100});
            SCOPED_TRACE(describe(a) + " vs " + describe(b));
            EXPECT_TRUE(is_miss(collide(a, b)));
            EXPECT_TRUE(is_miss(collide(b, a)));
            EXPECT_FALSE(overlaps(a, b));
            EXPECT_FALSE(overlaps(b, a));
        }
    }
}

TEST(Dispatch, SameKindAgainstItselfIsAHit) {
    for (const Shape& a : first_shapes()) {
        SCOPED_TRACE(describe(a));
        const Manifold m = collide(a, a);
        EXPECT_TRUE(m.hit);
        EXPECT_TRUE(is_defined(m, is_mask(a)));
        EXPECT_TRUE(overlaps(a, a));
    }
}

::testing::AssertionResult same(const Manifold& a, const Manifold& b) {
    if (a.hit == b.hit && std::fabs(a.depth - b.depth) <= 1e-6f && test::vec_near(a.normal, b.normal, 1e-6f)) {
        return ::testing::AssertionSuccess();
    }
    return ::testing::AssertionFailure() << "dispatch gave hit=" << a.hit << " depth=" << a.depth << " normal=("
                                         << a.normal.x << ", " << a.normal.y << "), typed gave hit=" << b.hit
                                         << " depth=" << b.depth << " normal=(" << b.normal.x << ", " << b.normal.y
                                         << ")";
}

TEST(Dispatch, MatchesTheTypedFunctionsOfThePairTable) {
    const auto s1 = first_shapes();
    const auto s2 = second_shapes();
    const auto& a1 = std::get<Aabb>(s1[0]);
    const auto& o1 = std::get<Obb>(s1[1]);
    const auto& p1 = std::get<Polygon>(s1[2]);
    const auto& c1 = std::get<Circle>(s1[3]);
    const auto& g1 = std::get<Segment>(s1[4]);
    const auto& m1 = std::get<PlacedMask>(s1[5]);
    const auto& a2 = std::get<Aabb>(s2[0]);
    const auto& o2 = std::get<Obb>(s2[1]);
    const auto& p2 = std::get<Polygon>(s2[2]);
    const auto& c2 = std::get<Circle>(s2[3]);
    const auto& g2 = std::get<Segment>(s2[4]);
    const auto& m2 = std::get<PlacedMask>(s2[5]);
    EXPECT_TRUE(same(collide(Shape{a1}, Shape{a2}), collide(a1, a2)));
    EXPECT_TRUE(same(collide(Shape{a1}, Shape{o2}), collide(a1, o2)));
    EXPECT_TRUE(same(collide(Shape{o2}, Shape{a1}), test::flipped(collide(a1, o2))));
    EXPECT_TRUE(same(collide(Shape{o1}, Shape{o2}), collide(o1, o2)));
    EXPECT_TRUE(same(collide(Shape{p1}, Shape{p2}), collide(p1, p2)));
    EXPECT_TRUE(same(collide(Shape{p1}, Shape{g2}), collide(p1, g2)));
    EXPECT_TRUE(same(collide(Shape{g2}, Shape{p1}), test::flipped(collide(p1, g2))));
    EXPECT_TRUE(same(collide(Shape{g1}, Shape{g2}), collide(g1, g2)));
    EXPECT_TRUE(same(collide(Shape{c1}, Shape{c2}), collide(c1, c2)));
    EXPECT_TRUE(same(collide(Shape{p1}, Shape{c2}), collide(p1, c2)));
    EXPECT_TRUE(same(collide(Shape{c2}, Shape{p1}), test::flipped(collide(p1, c2))));
    EXPECT_TRUE(same(collide(Shape{a1}, Shape{c2}), collide(a1, c2)));
    EXPECT_TRUE(same(collide(Shape{c2}, Shape{a1}), test::flipped(collide(a1, c2))));
    EXPECT_TRUE(same(collide(Shape{o1}, Shape{c2}), collide(o1, c2)));
    EXPECT_TRUE(same(collide(Shape{c2}, Shape{o1}), test::flipped(collide(o1, c2))));
    EXPECT_TRUE(same(collide(Shape{g1}, Shape{c2}), collide(g1, c2)));
    EXPECT_TRUE(same(collide(Shape{c2}, Shape{g1}), test::flipped(collide(g1, c2))));
    EXPECT_TRUE(same(collide(Shape{m1}, Shape{m2}), collide(m1, m2)));
    EXPECT_TRUE(same(collide(Shape{m1}, Shape{a2}), collide(m1, a2)));
    EXPECT_TRUE(same(collide(Shape{a2}, Shape{m1}), test::flipped(collide(m1, a2))));
    EXPECT_TRUE(same(collide(Shape{m1}, Shape{o2}), collide(m1, o2)));
    EXPECT_TRUE(same(collide(Shape{m1}, Shape{p2}), collide(m1, p2)));
    EXPECT_TRUE(same(collide(Shape{m1}, Shape{c2}), collide(m1, c2)));
    EXPECT_TRUE(same(collide(Shape{c2}, Shape{m1}), test::flipped(collide(m1, c2))));
    EXPECT_TRUE(same(collide(Shape{m1}, Shape{g2}), collide(m1, g2)));
    // The kinds without a typed overload go through SAT on polygons.
    EXPECT_TRUE(same(collide(Shape{a1}, Shape{p2}), collide(to_polygon(a1), p2)));
    EXPECT_TRUE(same(collide(Shape{o1}, Shape{p2}), collide(to_polygon(o1), p2)));
    EXPECT_TRUE(same(collide(Shape{a1}, Shape{g2}), collide(to_polygon(a1), g2)));
    EXPECT_TRUE(same(collide(Shape{o1}, Shape{g2}), collide(to_polygon(o1), g2)));
}

TEST(Dispatch, HandComputedReversedPairs) {
    // Circle (5,2) r 2 against the square [0,4]^2: polygon first gives depth 1 along (1,0); the
    // circle first gives the same depth along (-1,0), through every box-like kind.
    const Circle c{{5, 2}, 2};
    for (const Shape& box : {Shape{Aabb{{0, 0}, {4, 4}}}, Shape{Obb{{2, 2}, {2, 2}, 0.0f}},
                             Shape{test::box_polygon(0, 0, 4, 4)}}) {
        SCOPED_TRACE(describe(box));
        EXPECT_TRUE(test::is_hit(collide(box, Shape{c}), 1.0f, {1, 0}));
        EXPECT_TRUE(test::is_hit(collide(Shape{c}, box), 1.0f, {-1, 0}));
    }
    // Circle-segment reversed: segment (0,0)-(10,0), circle (4,1) r 2: depth 1, circle first
    // normal (0,-1).
    EXPECT_TRUE(test::is_hit(collide(Shape{Circle{{4, 1}, 2}}, Shape{Segment{{0, 0}, {10, 0}}}), 1.0f, {0, -1}));
}

TEST(Dispatch, MaskPairsByThePixelRule) {
    // A 1x1 mask at (10,0) covers [10,11]x[0,1]; its pixel centre is (10.5,0.5).
    const Mask one = mask_or_die({"#"});
    const PlacedMask px{&one, 10, 0};
    // A circle containing the centre: hit; one that covers part of the pixel but not its centre: miss.
    EXPECT_TRUE(overlaps(Shape{px}, Shape{Circle{{10, 0.5f}, 0.6f}}));
    EXPECT_FALSE(overlaps(Shape{px}, Shape{Circle{{10, 0.5f}, 0.4f}}));
    // A segment touching the pixel's closed square at its corner: hit.
    EXPECT_TRUE(overlaps(Shape{px}, Shape{Segment{{9, -1}, {10, 0}}}));
    EXPECT_FALSE(overlaps(Shape{px}, Shape{Segment{{9, -1}, {9.9f, 0}}}));
    const Manifold m = collide(Shape{px}, Shape{Circle{{10, 0.5f}, 0.6f}});
    EXPECT_TRUE(m.hit);
    EXPECT_GE(m.depth, 1.0f);
    EXPECT_TRUE(test::is_unit(m.normal));
}

TEST(Dispatch, MaskCastAndSweepThroughTheGenericEntries) {
    // Pixels are closed squares for casts and sweeps: the pixel at (10,0) is [10,11]x[0,1].
    const Mask one = mask_or_die({"#"});
    const PlacedMask px{&one, 10, 0};
    const CastHit c = cast({0, 0.5f}, {20, 0.5f}, Shape{px});
    EXPECT_TRUE(c.hit);
    EXPECT_NEAR(c.t, 0.5f, 1e-6f);
    EXPECT_VEC_NEAR(c.point, (Vec2{10, 0.5f}), 1e-5f);
    EXPECT_VEC_NEAR(c.normal, (Vec2{-1, 0}), 1e-6f);
    EXPECT_TRUE(is_miss(cast({0, 1.5f}, {20, 1.5f}, Shape{px})));
    // r 1 from (0,0.5) by (20,0): the centre reaches x = 9 at t = 0.45.
    const SweepHit s = sweep(Circle{{0, 0.5f}, 1}, {20, 0}, Shape{px}, {0, 0});
    EXPECT_TRUE(s.hit);
    EXPECT_NEAR(s.t, 0.45f, 1e-6f);
    EXPECT_VEC_NEAR(s.point, (Vec2{10, 0.5f}), 1e-5f);
    EXPECT_VEC_NEAR(s.normal, (Vec2{1, 0}), 1e-6f);
}

// ---------------------------------------------------------------------------------------
// Hostile input: NaN and infinities make a shape hit nothing, through every entry point.
// ---------------------------------------------------------------------------------------

std::vector<Shape> hostile_shapes() {
    // A Polygon cannot hold a non-finite vertex: moving or turning one into NaN or infinity
    // gives the empty polygon, which is what these stand for.
    const Polygon nan_poly = test::box_polygon(0, 0, 4, 4).moved({kNan, 0});
    const Polygon inf_poly = test::box_polygon(0, 0, 4, 4).moved({0, kInf});
    const Polygon neg_inf_poly = test::box_polygon(0, 0, 4, 4).transformed(Transform{{-kInf, 0}, Rot{}});
    return {
        Aabb{{kNan, 0}, {4, 4}},
        Aabb{{0, 0}, {4, kInf}},
        Aabb{{-kInf, -kInf}, {kInf, kInf}},
        Aabb{{kNan, kNan}, {kNan, kNan}},
        Obb{{kNan, 2}, {2, 2}, 0.0f},
        Obb{{2, 2}, {kInf, 2}, 0.0f},
        Obb{{2, 2}, {2, 2}, kNan},
        Obb{{2, 2}, {2, 2}, kInf},
        Obb{{2, -kInf}, {2, 2}, 0.0f},
        nan_poly,
        inf_poly,
        neg_inf_poly,
        Circle{{kNan, 2}, 2},
        Circle{{2, 2}, kNan},
        Circle{{2, 2}, kInf},
        Circle{{-kInf, 2}, 2},
        Segment{{kNan, 0}, {4, 4}},
        Segment{{0, 0}, {4, kInf}},
        Segment{{-kInf, 2}, {kInf, 2}},
    };
}

// Valid shapes that the hostile ones would overlap if they were finite.
std::vector<Shape> valid_shapes() {
    return {
        Aabb{{1, 1}, {3, 3}},
        Obb{{2, 2}, {1, 0.5f}, 0.4f},
        test::polygon_or_die({{1, 1}, {3, 1.5f}, {2, 3}}),
        Circle{{2, 2}, 1},
        Segment{{-1, 2}, {5, 2.5f}},
        PlacedMask{&block_mask(), 1, 1},
    };
}

TEST(Hostile, CollideAndOverlapsMiss) {
    for (const Shape& h : hostile_shapes()) {
        for (const Shape& s : valid_shapes()) {
            SCOPED_TRACE(describe(h) + " vs " + describe(s));
            EXPECT_TRUE(is_miss(collide(h, s)));
            EXPECT_TRUE(is_miss(collide(s, h)));
            EXPECT_FALSE(overlaps(h, s));
            EXPECT_FALSE(overlaps(s, h));
        }
        SCOPED_TRACE(describe(h) + " vs itself");
        EXPECT_TRUE(is_miss(collide(h, h)));
        EXPECT_FALSE(overlaps(h, h));
    }
}

TEST(Hostile, TypedCollideMiss) {
    // The typed entry points, not only the dispatcher.
    const Polygon sq = test::box_polygon(0, 0, 4, 4);
    const Polygon bad = sq.moved({0, kNan});
    EXPECT_TRUE(is_miss(collide(Aabb{{kNan, 0}, {4, 4}}, Aabb{{1, 1}, {3, 3}})));
    EXPECT_TRUE(is_miss(collide(Aabb{{1, 1}, {3, 3}}, Aabb{{0, 0}, {kInf, 4}})));
    EXPECT_FALSE(overlaps(Aabb{{kNan, 0}, {4, 4}}, Aabb{{1, 1}, {3, 3}}));
    EXPECT_FALSE(intersection(Aabb{{kNan, 0}, {4, 4}}, Aabb{{1, 1}, {3, 3}}).has_value());
    EXPECT_TRUE(is_miss(collide(Obb{{2, 2}, {2, 2}, kNan}, Obb{{2, 2}, {1, 1}, 0.0f})));
    EXPECT_TRUE(is_miss(collide(Aabb{{1, 1}, {3, 3}}, Obb{{2, 2}, {kNan, 1}, 0.0f})));
    EXPECT_TRUE(is_miss(collide(bad, sq)));
    EXPECT_TRUE(is_miss(collide(sq, bad)));
    EXPECT_TRUE(is_miss(collide(bad, Segment{{1, 1}, {3, 3}})));
    EXPECT_TRUE(is_miss(collide(sq, Segment{{1, kNan}, {3, 3}})));
    EXPECT_TRUE(is_miss(collide(Segment{{1, 1}, {kInf, 3}}, Segment{{1, 3}, {3, 1}})));
    EXPECT_TRUE(is_miss(collide(Circle{{kNan, 0}, 1}, Circle{{0, 0}, 1})));
    EXPECT_TRUE(is_miss(collide(Circle{{0, 0}, 1}, Circle{{0, 0}, kNan})));
    EXPECT_TRUE(is_miss(collide(sq, Circle{{2, 2}, kInf})));
    EXPECT_TRUE(is_miss(collide_sat(sq, Circle{{2, 2}, kInf})));
    EXPECT_TRUE(is_miss(collide_sat(bad, Circle{{2, 2}, 1})));
    EXPECT_TRUE(is_miss(collide(bad, Circle{{2, 2}, 1})));
    EXPECT_TRUE(is_miss(collide(Aabb{{0, 0}, {4, 4}}, Circle{{kNan, 2}, 1})));
    EXPECT_TRUE(is_miss(collide(Obb{{2, 2}, {2, 2}, kInf}, Circle{{2, 2}, 1})));
    EXPECT_TRUE(is_miss(collide(Segment{{0, 0}, {4, 4}}, Circle{{2, 2}, kNan})));
    EXPECT_FALSE(contains(bad, {2, 2}));
    EXPECT_FALSE(intersect(Segment{{0, 0}, {kNan, 4}}, Segment{{0, 4}, {4, 0}}).hit);
}

TEST(Hostile, CastMisses) {
    for (const Shape& h : hostile_shapes()) {
        SCOPED_TRACE(describe(h));
        EXPECT_TRUE(is_miss(cast({-10, 2}, {10, 2.5f}, h)));
        EXPECT_TRUE(is_miss(cast({2, 2}, {2, 2}, h)));
    }
    // A hostile bullet against valid shapes.
    for (const Shape& s : valid_shapes()) {
        SCOPED_TRACE(describe(s));
        EXPECT_TRUE(is_miss(cast({kNan, 2}, {10, 2}, s)));
        EXPECT_TRUE(is_miss(cast({-10, 2}, {kInf, 2}, s)));
        EXPECT_TRUE(is_miss(cast({-kInf, 2}, {kInf, 2}, s)));
        EXPECT_TRUE(is_miss(cast({2, 2}, {kNan, kNan}, s)));
    }
}

TEST(Hostile, SweepMisses) {
    const Circle ball{{-10, 2}, 1};
    for (const Shape& h : hostile_shapes()) {
        SCOPED_TRACE(describe(h));
        EXPECT_TRUE(is_miss(sweep(ball, {20, 0}, h, {0, 0})));
        EXPECT_TRUE(is_miss(sweep(Circle{{2, 2}, 1}, {0, 0}, h, {0, 0})));
    }
    for (const Shape& s : valid_shapes()) {
        SCOPED_TRACE(describe(s));
        EXPECT_TRUE(is_miss(sweep(Circle{{kNan, 2}, 1}, {20, 0}, s, {0, 0})));
        EXPECT_TRUE(is_miss(sweep(Circle{{-10, 2}, kInf}, {20, 0}, s, {0, 0})));
        EXPECT_TRUE(is_miss(sweep(Circle{{-10, 2}, kNan}, {20, 0}, s, {0, 0})));
        EXPECT_TRUE(is_miss(sweep(ball, {kNan, 0}, s, {0, 0})));
        EXPECT_TRUE(is_miss(sweep(ball, {kInf, 0}, s, {0, 0})));
        EXPECT_TRUE(is_miss(sweep(ball, {20, 0}, s, {0, kNan})));
    }
    // Typed sweeps.
    EXPECT_TRUE(is_miss(sweep(ball, {20, 0}, Circle{{kNan, 2}, 1})));
    EXPECT_TRUE(is_miss(sweep(ball, {kNan, 0}, Circle{{2, 2}, 1})));
    EXPECT_TRUE(is_miss(sweep(ball, {20, 0}, Circle{{2, 2}, 1}, {kInf, 0})));
    EXPECT_TRUE(is_miss(sweep(ball, {20, 0}, Aabb{{0, 0}, {kInf, 4}})));
    EXPECT_TRUE(is_miss(sweep(ball, {20, 0}, Obb{{2, 2}, {2, 2}, kNan})));
    EXPECT_TRUE(is_miss(sweep(ball, {20, 0}, Segment{{2, kNan}, {2, 4}})));
    EXPECT_FALSE(swept_overlaps(ball, {kNan, 0}, Circle{{2, 2}, 1}));
    EXPECT_FALSE(swept_overlaps(ball, {20, 0}, Circle{{2, 2}, kNan}));
}

TEST(Hostile, ClosestPointIsNoPoint) {
    // A shape that hits nothing has no closest point: point {0,0} and an infinite distance
    // (a distance of 0 would claim the query point is inside it).
    for (const Shape& h : hostile_shapes()) {
        SCOPED_TRACE(describe(h));
        const ClosestPoint c = closest_point(h, {7, 7});
        EXPECT_EQ(c.point, (Vec2{0, 0}));
        EXPECT_EQ(c.distance, kInf);
    }
    // A hostile query point against valid shapes: the same.
    for (const Shape& s : valid_shapes()) {
        if (is_mask(s)) continue;  // masks: mask_test.cpp
        SCOPED_TRACE(describe(s));
        const ClosestPoint c = closest_point(s, {kNan, 7});
        EXPECT_EQ(c.point, (Vec2{0, 0}));
        EXPECT_EQ(c.distance, kInf);
    }
}

TEST(Hostile, DefaultConstructedPolygonHitsNothing) {
    // Polygon{} has no vertices (it did not come from make_polygon): a miss everywhere.
    const Shape empty{Polygon{}};
    for (const Shape& s : valid_shapes()) {
        SCOPED_TRACE(describe(s));
        EXPECT_TRUE(is_miss(collide(empty, s)));
        EXPECT_TRUE(is_miss(collide(s, empty)));
    }
    EXPECT_TRUE(is_miss(cast({-5, 0}, {5, 0}, empty)));
    EXPECT_TRUE(is_miss(sweep(Circle{{-5, 0}, 1}, {10, 0}, empty, {0, 0})));
    EXPECT_FALSE(contains(Polygon{}, {0, 0}));
}

TEST(Degenerate, ZeroSizeShapesGiveFiniteResults) {
    // Zero-size shapes at (2,2) against valid shapes that contain (2,2): a defined manifold,
    // symmetric; a cast along y = 2 from (-5,2) to (5,2) meets them at x = 2 (t = 0.7) unless said
    // otherwise; the closest point to (2,7).
    struct Case {
        Shape shape;
        float cast_t;
        float distance;
    };
    const Case cases[] = {
        {Aabb{{2, 2}, {2, 2}}, 0.7f, 5.0f},
        {Obb{{2, 2}, {0, 0}, 0.5f}, 0.7f, 5.0f},
        {Obb{{2, 2}, {1, 0}, test::kPi / 2}, 0.7f, 4.0f},  // a vertical segment (2,1)-(2,3)
        {Circle{{2, 2}, 0}, 0.7f, 5.0f},
        {Segment{{2, 2}, {2, 2}}, 0.7f, 5.0f},
        {Segment{{1, 2}, {3, 2}}, 0.6f, 5.0f},  // collinear with the cast
    };
    for (const Case& c : cases) {
        const Shape& d = c.shape;
        for (const Shape& s : valid_shapes()) {
            SCOPED_TRACE(describe(d) + " vs " + describe(s));
            const Manifold ab = collide(d, s);
            const Manifold ba = collide(s, d);
            EXPECT_TRUE(is_defined(ab, is_mask(s)));
            EXPECT_TRUE(is_defined(ba, is_mask(s)));
            EXPECT_EQ(ab.hit, ba.hit);
            EXPECT_NEAR(ab.depth, ba.depth, 1e-5f);
            EXPECT_EQ(overlaps(d, s), ab.hit);
            // (2,2) is inside every valid solid shape (masks decide by pixel centres instead).
            if (!std::holds_alternative<Segment>(s) && !is_mask(s)) {
                EXPECT_TRUE(ab.hit);
            }
        }
        SCOPED_TRACE(describe(d) + " alone");
        const Manifold self = collide(d, d);
        EXPECT_TRUE(self.hit);
        EXPECT_TRUE(is_defined(self, false));
        const CastHit h = cast({-5, 2}, {5, 2}, d);
        EXPECT_TRUE(h.hit);
        EXPECT_NEAR(h.t, c.cast_t, 1e-5f);
        EXPECT_TRUE(is_finite(h.normal));
        const ClosestPoint q = closest_point(d, {2, 7});
        EXPECT_TRUE(is_finite(q.point));
        EXPECT_NEAR(q.distance, c.distance, 1e-5f);
        const SweepHit w = sweep(Circle{{-5, 2}, 1}, {10, 0}, d, {0, 0});
        EXPECT_TRUE(w.hit);
        EXPECT_TRUE(is_finite(w.point));
        EXPECT_TRUE(test::is_unit(w.normal));
    }
}

TEST(Degenerate, ParallelEdgesAndCoincidentShapes) {
    // Boxes sharing whole edges and identical polygons: defined, finite, symmetric depths.
    const Polygon sq = test::box_polygon(0, 0, 4, 4);
    const Polygon right = test::box_polygon(4, 0, 8, 4);  // shares x = 4 exactly
    const Manifold t = collide(sq, right);
    EXPECT_TRUE(test::is_hit(t, 0.0f, {1, 0}, 0.0f));
    const Manifold same_shape = collide(Shape{sq}, Shape{Aabb{{0, 0}, {4, 4}}});
    EXPECT_TRUE(same_shape.hit);
    EXPECT_FLOAT_EQ(same_shape.depth, 4.0f);
    EXPECT_TRUE(test::is_unit(same_shape.normal));
    const Manifold circles = collide(Circle{{1, 1}, 0}, Circle{{1, 1}, 0});
    EXPECT_TRUE(test::is_hit(circles, 0.0f, {1, 0}, 0.0f));
}

}  // namespace
}  // namespace jostle
