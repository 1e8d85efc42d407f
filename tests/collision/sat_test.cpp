// Separating axis tests (sat.cpp, slides 09-35 to 09-69): OBB-OBB (09-58), AABB-OBB,
// polygon-polygon (09-62), polygon-segment and segment-segment, with MTD by the least push.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "test_shapes.h"

namespace jostle {
namespace {

using test::is_hit;
using test::is_miss;
using test::kPi;
using test::kSqrt2;

const Obb kUnitBox{{0, 0}, {1, 1}, 0.0f};

TEST(SatObb, Separated) {
    // x: A [-1,1], B [2,4]: gap 1.
    EXPECT_TRUE(is_miss(collide(kUnitBox, Obb{{3, 0}, {1, 1}, 0.0f})));
    EXPECT_TRUE(is_miss(collide(kUnitBox, Obb{{0, -2.001f}, {1, 1}, 0.0f})));
}

TEST(SatObb, Overlapping) {
    // B at (1.5,0.5): x pushes min(1-0.5, 2.5+1) = 0.5; y pushes min(1+0.5, 1.5+1) = 1.5.
    EXPECT_TRUE(is_hit(collide(kUnitBox, Obb{{1.5f, 0.5f}, {1, 1}, 0.0f}), 0.5f, {1, 0}));
    // B above-left at (-0.5,-1.75): x push min(1+1.5, 0.5+1) = 1.5; y push min(1+2.75, -0.75+1) = 0.25;
    // A moves down by 0.25: normal (0,-1).
    EXPECT_TRUE(is_hit(collide(kUnitBox, Obb{{-0.5f, -1.75f}, {1, 1}, 0.0f}), 0.25f, {0, -1}));
}

TEST(SatObb, TouchingIsAHitWithDepthZero) {
    // Integer coordinates, axis-aligned edges: x extents [-1,1] and [1,3] share x = 1.
    const Manifold m = collide(kUnitBox, Obb{{2, 0}, {1, 1}, 0.0f});
    EXPECT_TRUE(m.hit);
    EXPECT_EQ(m.depth, 0.0f);
    EXPECT_VEC_NEAR(m.normal, (Vec2{1, 0}), 1e-6f);
}

TEST(SatObb, RotatedCornerContact) {
    // B: half (1,1) turned 45 deg, its left corner at c - sqrt2 = 0.75, i.e. 0.25 inside A's
    // right face. A's x axis: push min(1 - 0.75, ...) = 0.25. A's y axis: min(1+sqrt2, sqrt2+1)
    // = 2.41. B's axes (+-1,1)/sqrt2: A spans [-sqrt2, sqrt2], B's centre projects to
    // +-c/sqrt2 = +-1.530, extent 1: push sqrt2 - 0.530 = 0.884. Least: 0.25 along (1,0).
    const float c = 1.0f + kSqrt2 - 0.25f;
    const Manifold m = collide(kUnitBox, Obb{{c, 0}, {1, 1}, kPi / 4});
    EXPECT_TRUE(is_hit(m, 0.25f, {1, 0}, 1e-5f));
    // 0.01 short of touching: a miss.
    EXPECT_TRUE(is_miss(collide(kUnitBox, Obb{{1.0f + kSqrt2 + 0.01f, 0}, {1, 1}, kPi / 4})));
}

TEST(SatObb, EarlyExitMustNotStopAtOverlappingAxes) {
    // A = [0,2]^2. B = a diamond (half 1 at 45 deg) off A's corner. Both of A's axes overlap
    // (B spans x, y in [c - sqrt2, c + sqrt2]); only B's diagonal axis separates.
    const Obb a{{1, 1}, {1, 1}, 0.0f};
    // c = 3.2: on (1,1)/sqrt2 A reaches 4/sqrt2 = 2.828, B starts at 6.4/sqrt2 - 1 = 3.525.
    EXPECT_TRUE(is_miss(collide(a, Obb{{3.2f, 3.2f}, {1, 1}, kPi / 4})));
    EXPECT_FALSE(overlaps(Shape{a}, Shape{Obb{{3.2f, 3.2f}, {1, 1}, kPi / 4}}));
    // c = 2.5: B starts at 5/sqrt2 - 1 = 2.5355: push 2.8284 - 2.5355 = 1 - 1/sqrt2 = 0.29289.
    // Other axes: x, y: min(2 - (2.5 - sqrt2), ...) = 0.914; (-1,1)/sqrt2: 1 + sqrt2 = 2.414.
    const Manifold m = collide(a, Obb{{2.5f, 2.5f}, {1, 1}, kPi / 4});
    EXPECT_TRUE(is_hit(m, 1.0f - 1.0f / kSqrt2, {1.0f / kSqrt2, 1.0f / kSqrt2}, 1e-5f));
    // The same in the other order: the separating axis is now the first shape's.
    EXPECT_TRUE(is_miss(collide(Obb{{3.2f, 3.2f}, {1, 1}, kPi / 4}, a)));
    EXPECT_TRUE(is_hit(collide(Obb{{2.5f, 2.5f}, {1, 1}, kPi / 4}, a), 1.0f - 1.0f / kSqrt2,
                       {-1.0f / kSqrt2, -1.0f / kSqrt2}, 1e-5f));
}

TEST(SatObb, CoincidentIdenticalBoxes) {
    // Same box twice, half (2,1) at 0.3 rad: the pushes are the full widths, 4 along the box's
    // x axis and 2 along its y axis (-sin .3, cos .3): depth 2 along +-y axis.
    const Obb b{{5, -3}, {2, 1}, 0.3f};
    const Manifold m = collide(b, b);
    EXPECT_TRUE(m.hit);
    EXPECT_NEAR(m.depth, 2.0f, 1e-5f);
    EXPECT_TRUE(test::is_unit(m.normal));
    EXPECT_NEAR(std::fabs(dot(m.normal, Vec2{-std::sin(0.3f), std::cos(0.3f)})), 1.0f, 1e-5f);
}

TEST(SatObb, Containment) {
    // A: [-5,5]^2; B: [3.5,4.5]x[-0.5,0.5] (half 0.5 at (4,0)). A moves: left until A.max.x = 3.5
    // (1.5), right (9.5), up/down (5.5): 1.5 to the left, normal (1,0). The intersection width is 1.
    EXPECT_TRUE(is_hit(collide(Obb{{0, 0}, {5, 5}, 0.0f}, Obb{{4, 0}, {0.5f, 0.5f}, 0.0f}), 1.5f, {1, 0}));
    EXPECT_TRUE(is_hit(collide(Obb{{4, 0}, {0.5f, 0.5f}, 0.0f}, Obb{{0, 0}, {5, 5}, 0.0f}), 1.5f, {-1, 0}));
}

TEST(SatObb, TiedAxesGiveTheFirstAxisOfA) {
    // B at (1,1), both half (1,1): every axis needs a push of 1 (A's x, A's y, B's x, B's y).
    // The axes are tested side by side; the first of the tied ones, A's x, must still win.
    EXPECT_TRUE(is_hit(collide(kUnitBox, Obb{{1, 1}, {1, 1}, 0.0f}), 1.0f, {1, 0}));
    EXPECT_TRUE(is_hit(collide(kUnitBox, Obb{{-1, 1}, {1, 1}, 0.0f}), 1.0f, {-1, 0}));
    // B turned a quarter turn (its axes are A's y and -x, up to rounding): A's x needs 0.5,
    // every other axis 1.
    EXPECT_TRUE(is_hit(collide(kUnitBox, Obb{{1.5f, 1}, {1, 1}, kPi / 2}), 0.5f, {1, 0}, 1e-6f));
    // A = 6x2 box, B = 2x6 box 1.5 below: x axes need 4, A's y and B's y both 2.5.
    const Manifold m = collide(Obb{{0, 0}, {3, 1}, 0.0f}, Obb{{0, 1.5f}, {1, 3}, 0.0f});
    EXPECT_TRUE(is_hit(m, 2.5f, {0, 1}));
}

TEST(SatObb, NonFiniteOrMalformedBoxesMissWhateverTheField) {
    // Each field of either box in turn: NaN, +inf and -inf are a miss, and so is a negative
    // half extent (the boxes' validity is tested without a branch per field).
    const float bad[] = {NAN, INFINITY, -INFINITY};
    for (const float v : bad) {
        for (int field = 0; field < 5; ++field) {
            Obb b{{0.5f, 0.5f}, {1, 1}, 0.25f};
            if (field == 0) b.center.x = v;
            if (field == 1) b.center.y = v;
            if (field == 2) b.half.x = v;
            if (field == 3) b.half.y = v;
            if (field == 4) b.set_angle(v);
            SCOPED_TRACE(field);
            EXPECT_TRUE(is_miss(collide(kUnitBox, b)));
            EXPECT_TRUE(is_miss(collide(b, kUnitBox)));
            EXPECT_TRUE(is_miss(collide(Aabb{{-1, -1}, {1, 1}}, b)));
            EXPECT_EQ(contacts(b, kUnitBox).count, 0);
            EXPECT_TRUE(is_miss(contacts(kUnitBox, b).manifold));
            EXPECT_TRUE(is_miss(collide(b, Circle{{0, 0}, 1})));
        }
    }
    EXPECT_TRUE(is_miss(collide(kUnitBox, Obb{{0, 0}, {-1, 1}, 0.0f})));
    EXPECT_TRUE(is_miss(collide(Obb{{0, 0}, {1, -0.5f}, 0.0f}, kUnitBox)));
    // A zero-size box is a point: a hit inside, a miss outside.
    EXPECT_TRUE(is_hit(collide(kUnitBox, Obb{{0.5f, 0}, {0, 0}, 0.0f}), 0.5f, {1, 0}));
    EXPECT_TRUE(is_miss(collide(kUnitBox, Obb{{1.5f, 0}, {0, 0}, 0.3f})));
    // Boxes at the limits of float, whose pushes overflow: a defined result, never NaN.
    const Manifold huge = collide(Obb{{0, 0}, {3e38f, 3e38f}, 0.0f}, Obb{{0, 0}, {3e38f, 3e38f}, 0.0f});
    EXPECT_FALSE(std::isnan(huge.depth));
    EXPECT_FALSE(std::isnan(huge.normal.x) || std::isnan(huge.normal.y));
}

TEST(SatAabbObb, MatchesTheObbOfTheSameBox) {
    const Aabb a{{0, 0}, {2, 2}};
    // The diamond cases from EarlyExitMustNotStopAtOverlappingAxes.
    EXPECT_TRUE(is_miss(collide(a, Obb{{3.2f, 3.2f}, {1, 1}, kPi / 4})));
    EXPECT_TRUE(is_hit(collide(a, Obb{{2.5f, 2.5f}, {1, 1}, kPi / 4}), 1.0f - 1.0f / kSqrt2,
                       {1.0f / kSqrt2, 1.0f / kSqrt2}, 1e-5f));
    // Axis-aligned OBB overlapping the right face by 0.5: B x [1.5,3.5], y [0.5,1.5].
    EXPECT_TRUE(is_hit(collide(a, Obb{{2.5f, 1}, {1, 0.5f}, 0.0f}), 0.5f, {1, 0}));
    // Touching: B x [2,4].
    const Manifold t = collide(a, Obb{{3, 1}, {1, 1}, 0.0f});
    EXPECT_TRUE(t.hit);
    EXPECT_EQ(t.depth, 0.0f);
}

TEST(SatPolygon, SquareAndTriangle) {
    // A = [0,4]^2, B = (3,1),(6,2),(3,3). Pushes of A: x: min(4-3, 6-0) = 1; y: min(4-1, 3-0) = 3;
    // B's edge (3,1)->(6,2), normal (1,-3)/sqrt10: A [-12,4], B [-6,0] -> min(10, 12)/sqrt10 = 3.16;
    // edge (6,2)->(3,3), normal (1,3)/sqrt10: A [0,16], B [6,12] -> min(10,12)/sqrt10 = 3.16.
    // Least: 1 along (1,0).
    const Polygon a = test::box_polygon(0, 0, 4, 4);
    const Polygon b = test::polygon_or_die({{3, 1}, {6, 2}, {3, 3}});
    EXPECT_TRUE(is_hit(collide(a, b), 1.0f, {1, 0}));
    EXPECT_TRUE(is_hit(collide(b, a), 1.0f, {-1, 0}));
    // Moved right by 1.01: separated on x.
    EXPECT_TRUE(is_miss(collide(a, test::moved(b, {1.01f, 0}))));
    // Moved right by 1: touching.
    const Manifold t = collide(a, test::moved(b, {1, 0}));
    EXPECT_TRUE(t.hit);
    EXPECT_EQ(t.depth, 0.0f);
}

TEST(SatPolygon, ContainmentGivesTheSmallestPush) {
    // Big A = [0,10]^2 holds the small triangle (4,1),(6,1),(5,2) near its top edge. A must move
    // down until A.min.y = 2 (push 2) rather than up (9); x: min(10-4, 6-0) = 6; the triangle's
    // slanted normals (1,1)/sqrt2 and (-1,1)/sqrt2: 7/sqrt2 = 4.95. Depth 2, mtd (0,2), normal (0,-1).
    // (The intersection is the triangle itself, 1 tall: not the answer.)
    const Polygon big = test::box_polygon(0, 0, 10, 10);
    const Polygon tri = test::polygon_or_die({{4, 1}, {6, 1}, {5, 2}});
    const Manifold m = collide(big, tri);
    EXPECT_TRUE(is_hit(m, 2.0f, {0, -1}));
    EXPECT_VEC_NEAR(m.mtd(), (Vec2{0, 2}), 1e-5f);
    EXPECT_TRUE(is_hit(collide(tri, big), 2.0f, {0, 1}));
}

TEST(SatPolygon, CoincidentIdenticalTriangles) {
    // (0,0),(4,0),(0,3) against itself: widths along the normals are 3 (y), 4 (x) and the
    // altitude to the hypotenuse, 2 * area / 5 = 12/5 = 2.4, along +-(3,4)/5.
    const Polygon t = test::polygon_or_die({{0, 0}, {4, 0}, {0, 3}});
    const Manifold m = collide(t, t);
    EXPECT_TRUE(m.hit);
    EXPECT_NEAR(m.depth, 2.4f, 1e-5f);
    EXPECT_NEAR(std::fabs(dot(m.normal, Vec2{0.6f, 0.8f})), 1.0f, 1e-5f);
}

TEST(SatPolygon, SeparatedOnlyOnTheDiagonalAxis) {
    // Triangle A (0,0),(4,0),(0,4) and triangle B (3,3),(5,3),(3,5): on x and y they overlap
    // ([0,4] vs [3,5]); only the hypotenuse normal (1,1)/sqrt2 separates: A reaches 4/sqrt2,
    // B starts at 6/sqrt2.
    const Polygon a = test::polygon_or_die({{0, 0}, {4, 0}, {0, 4}});
    const Polygon b = test::polygon_or_die({{3, 3}, {5, 3}, {3, 5}});
    EXPECT_TRUE(is_miss(collide(a, b)));
    EXPECT_TRUE(is_miss(collide(b, a)));
    // B moved by (-1.5,-1.5): starts at 3/sqrt2, push (4-3)/sqrt2 = 0.7071 along (1,1)/sqrt2;
    // x: min(4-1.5, 3.5-0) = 2.5, y the same.
    const Manifold m = collide(a, test::moved(b, {-1.5f, -1.5f}));
    EXPECT_TRUE(is_hit(m, 1.0f / kSqrt2, {1.0f / kSqrt2, 1.0f / kSqrt2}, 1e-5f));
}

// The polygon SAT as a plain loop over faces and vertices (the form the lanes must match bit
// for bit): the largest over A's faces of min over B's vertices of dot(n, b - p), the same with
// B's faces, ties to the first face and to A.
Manifold face_loop_sat(const Polygon& a, const Polygon& b) {
    struct Best {
        float sep = -INFINITY;
        int face = 0;
    };
    const auto side = [](const Polygon& f, const Polygon& o, Best& best) {
        for (int i = 0; i < f.count(); ++i) {
            float s = INFINITY;
            for (int j = 0; j < o.count(); ++j) {
                const float d = f.normals()[i].x * (o.points()[j].x - f.points()[i].x) +
                                f.normals()[i].y * (o.points()[j].y - f.points()[i].y);
                s = d < s ? d : s;
            }
            if (!(s <= 0.0f)) return false;
            if (s > best.sep) best = {s, i};
        }
        return true;
    };
    Best fa, fb;
    if (!side(a, b, fa) || !side(b, a, fb)) return {};
    const bool a_face = fa.sep >= fb.sep;
    const float depth = -(a_face ? fa.sep : fb.sep);
    const Vec2 n = a_face ? a.normals()[fa.face] : -b.normals()[fb.face];
    return Manifold{true, depth > 0.0f ? depth : 0.0f, {n.x + 0.0f, n.y + 0.0f}};
}

TEST(SatPolygon, EveryVertexCountMatchesTheFaceLoop) {
    // Faces are tested four at a time; counts that are not a multiple of 4 leave spare lanes,
    // which must never name a face or a gap. Regular polygons of 3..16 vertices, turned, at
    // offsets that overlap, touch and miss.
    const auto regular = [](int n, Vec2 c, float r, float turn) {
        std::vector<Vec2> pts;
        for (int i = 0; i < n; ++i) {
            const float t = turn + 2.0f * kPi * static_cast<float>(i) / static_cast<float>(n);
            pts.push_back({c.x + r * std::cos(t), c.y + r * std::sin(t)});
        }
        return *make_polygon(pts);
    };
    int hits = 0, misses = 0;
    for (int n = 3; n <= kMaxPolygonVertices; ++n) {
        const Polygon a = regular(n, {1, 2}, 3.0f, 0.1f * static_cast<float>(n));
        for (int m = 3; m <= kMaxPolygonVertices; ++m) {
            for (const Vec2 at : {Vec2{1, 2}, Vec2{3, 2.5f}, Vec2{6.5f, 2}, Vec2{-4, -1}, Vec2{1, 9}}) {
                const Polygon b = regular(m, at, 2.0f, 0.3f * static_cast<float>(m));
                SCOPED_TRACE(testing::Message() << n << " and " << m << " vertices, B at " << at.x << ", " << at.y);
                const Manifold want = face_loop_sat(a, b);
                const Manifold got = collide(a, b);
                EXPECT_EQ(got.hit, want.hit);
                EXPECT_EQ(got.depth, want.depth);
                EXPECT_EQ(got.normal, want.normal);
                EXPECT_EQ(contacts(a, b).manifold.normal, want.normal);
                (want.hit ? hits : misses) += 1;
            }
        }
    }
    EXPECT_GT(hits, 200);
    EXPECT_GT(misses, 200);
}

// collide and contacts of a pair with the AVX2 paths on, then off: the same bits (every
// slot of the contact set too). Leaves the AVX2 paths on; returns whether it is a hit.
bool expect_same_answers_on_both_paths(const Polygon& a, const Polygon& b) {
    const auto bits = [](float v) { return std::bit_cast<std::uint32_t>(v); };
    EXPECT_TRUE(detail::use_avx2_paths(true));
    const Manifold on = collide(a, b);
    const ContactSet on_set = contacts(a, b);
    detail::use_avx2_paths(false);
    const Manifold off = collide(a, b);
    const ContactSet off_set = contacts(a, b);
    detail::use_avx2_paths(true);
    EXPECT_EQ(on.hit, off.hit);
    EXPECT_EQ(bits(on.depth), bits(off.depth));
    EXPECT_EQ(bits(on.normal.x), bits(off.normal.x));
    EXPECT_EQ(bits(on.normal.y), bits(off.normal.y));
    EXPECT_EQ(on_set.count, off_set.count);
    for (std::size_t k = 0; k < 2; ++k) {
        EXPECT_EQ(bits(on_set.points[k].x), bits(off_set.points[k].x));
        EXPECT_EQ(bits(on_set.points[k].y), bits(off_set.points[k].y));
        EXPECT_EQ(bits(on_set.depths[k]), bits(off_set.depths[k]));
    }
    return on.hit;
}

// The polygon MTD runs faces eight at a time with AVX2 where the CPU has it, four at a time
// with SSE elsewhere: the same answers bit for bit, or a replay would differ between
// machines. Random polygons of 3..8 vertices, half of them on an integer grid (exact ties
// between faces, identical and touching polygons), each pair with the AVX2 path on and off.
TEST(SatPolygon, Avx2AndSsePathsGiveTheSameAnswers) {
    if (!detail::use_avx2_paths(true)) GTEST_SKIP() << "this CPU has no AVX2: the SSE path is the only one";
    Rng rng(0xa5c2u);
    int hits = 0;
    for (int n = 0; n < 20000; ++n) {
        Polygon a = test::random_polygon(rng, 10.0f);
        Polygon b = n % 5 == 0 ? a : test::random_polygon(rng, 10.0f);
        if (n % 2 == 0) {  // snapped to whole numbers: many exact ties
            const auto snap = [](const Polygon& p) {
                std::vector<Vec2> pts;
                for (const Vec2 v : p.points()) pts.push_back({std::round(v.x), std::round(v.y)});
                return make_polygon(pts);
            };
            const auto sa = snap(a), sb = snap(b);
            if (!sa || !sb) continue;
            a = *sa;
            b = *sb;
        }
        SCOPED_TRACE(testing::Message() << "pair " << n);
        hits += expect_same_answers_on_both_paths(a, b);
        if (HasFailure()) break;
    }
    EXPECT_GT(hits, 2000);
}

// The same past the limits: polygons scaled and moved until separations overflow to +-inf
// or NaN (a miss, or a depth that is not finite), where the 8-face path takes its face from
// a lane mask rather than a loop. (make_polygon refuses edges whose cross products
// overflow, so the sizes stay below about 1e19, and moved() takes them far away.)
TEST(SatPolygon, Avx2AndSsePathsAgreePastTheLimits) {
    if (!detail::use_avx2_paths(true)) GTEST_SKIP() << "this CPU has no AVX2: the SSE path is the only one";
    const float scales[] = {1.0f, 1e6f, 1e17f, 1e18f};
    const float shifts[] = {0.0f, 1e30f, 1.7e38f, 2e38f, -2e38f};
    Rng rng(0x51c3u);
    int compared = 0;
    for (int n = 0; n < 4000; ++n) {
        const float scale = scales[rng.below(4)], shift_a = shifts[rng.below(5)], shift_b = shifts[rng.below(5)];
        const auto big = [&](const Polygon& p, float shift) -> std::optional<Polygon> {
            std::vector<Vec2> pts;
            for (const Vec2 v : p.points()) pts.push_back(v * scale);
            const auto scaled = make_polygon(pts);
            if (!scaled) return std::nullopt;
            const Polygon moved = scaled->moved({shift, -shift});  // may round vertices together
            if (moved.count() == 0) return std::nullopt;
            return moved;
        };
        const Polygon pa = test::random_polygon(rng, 10.0f), pb = n % 7 == 0 ? pa : test::random_polygon(rng, 10.0f);
        const auto a = big(pa, shift_a), b = big(pb, shift_b);
        if (!a || !b) continue;
        SCOPED_TRACE(testing::Message() << "pair " << n);
        expect_same_answers_on_both_paths(*a, *b);
        ++compared;
        if (HasFailure()) break;
    }
    EXPECT_GT(compared, 1000);
}

TEST(SatPolygonSegment, SegmentCrossingASquare) {
    // A = [0,4]^2, segment x = 3 from y = -1 to 5. x: min(4-3, 3-0) = 1; y: min(4+1, 5-0) = 5.
    const Polygon a = test::box_polygon(0, 0, 4, 4);
    EXPECT_TRUE(is_hit(collide(a, Segment{{3, -1}, {3, 5}}), 1.0f, {1, 0}));
    // Inside, at y = 1 from x = 1 to 3: y: min(4-1, 1-0) = 1 (A moves down), x: 3. normal (0,-1).
    EXPECT_TRUE(is_hit(collide(a, Segment{{1, 1}, {3, 1}}), 1.0f, {0, -1}));
    EXPECT_TRUE(is_miss(collide(a, Segment{{5, 0}, {6, 5}})));
    // A segment across the square's corner on x + y = 7, from (2,5) to (5,2): the corner (4,4)
    // is (8-7)/sqrt2 = 0.7071 beyond it along (1,1)/sqrt2. x and y: min(4-2, 5-0) = 2; the
    // segment's direction (1,-1)/sqrt2: A [-2.83, 2.83], S [-2.12, 2.12]: 4.95.
    EXPECT_TRUE(is_hit(collide(a, Segment{{2, 5}, {5, 2}}), 1.0f / kSqrt2, {1.0f / kSqrt2, 1.0f / kSqrt2}, 1e-5f));
    // x + y = 8.2: missed though the bounds overlap ([3.1,5.1] x [3.1,5.1] vs [0,4]^2).
    EXPECT_TRUE(is_miss(collide(a, Segment{{3.1f, 5.1f}, {5.1f, 3.1f}})));
}

TEST(SatPolygonSegment, TouchingAVertexEndOn) {
    // Segment (4,4)-(6,6) starts at A's corner: a hit with depth 0.
    const Manifold m = collide(test::box_polygon(0, 0, 4, 4), Segment{{4, 4}, {6, 6}});
    EXPECT_TRUE(m.hit);
    EXPECT_EQ(m.depth, 0.0f);
    EXPECT_TRUE(test::is_unit(m.normal));
    EXPECT_GT(dot(m.normal, Vec2{1, 1}), 0.0f);
}

TEST(SatPolygonSegment, PointSegmentInsideSquare) {
    // A zero-length segment at (1,2) in [0,4]^2: A moves right by 1 (x: min(4-1, 1-0) = 1;
    // y: min(4-2, 2-0) = 2), mtd (1,0), normal (-1,0).
    EXPECT_TRUE(is_hit(collide(test::box_polygon(0, 0, 4, 4), Segment{{1, 2}, {1, 2}}), 1.0f, {-1, 0}));
}

TEST(SatSegment, CrossingSegmentsHit) {
    // S1 (0,0)-(10,0), S2 (5,-1)-(5,3). Axes: S1's normal: S1 [0,0], S2 [-1,3]: min(0+1, 3-0) = 1;
    // S1's direction: [0,10] vs [5,5]: 5; S2's axes are the same two. The Minkowski difference
    // is the rectangle [-5,5]x[-3,1]: depth 1, S1 moves up, normal (0,1).
    EXPECT_TRUE(is_hit(collide(Segment{{0, 0}, {10, 0}}, Segment{{5, -1}, {5, 3}}), 1.0f, {0, 1}));
    // An X: depth 2 sqrt2 on every axis.
    const Manifold x = collide(Segment{{0, 0}, {4, 4}}, Segment{{0, 4}, {4, 0}});
    EXPECT_TRUE(x.hit);
    EXPECT_NEAR(x.depth, 2 * kSqrt2, 1e-5f);
    EXPECT_TRUE(test::is_unit(x.normal));
}

TEST(SatSegment, TJunctionTouches) {
    // S2 starts on S1: S1's normal gives push min(0-0, 3-0) = 0, S1 moves up by 0: normal (0,1).
    const Manifold m = collide(Segment{{0, 0}, {4, 0}}, Segment{{2, 0}, {2, 3}});
    EXPECT_TRUE(m.hit);
    EXPECT_EQ(m.depth, 0.0f);
    EXPECT_VEC_NEAR(m.normal, (Vec2{0, 1}), 1e-6f);
    EXPECT_TRUE(is_miss(collide(Segment{{0, 0}, {4, 0}}, Segment{{2, 0.001f}, {2, 3}})));
}

TEST(SatSegment, CollinearDisjointSegmentsDoNotHit) {
    // Same line, [0,2] and [3,5]: both normals give push 0, only the direction axis separates.
    EXPECT_TRUE(is_miss(collide(Segment{{0, 0}, {2, 0}}, Segment{{3, 0}, {5, 0}})));
    EXPECT_TRUE(is_miss(collide(Segment{{0, 0}, {2, 2}}, Segment{{3, 3}, {5, 5}})));
    EXPECT_TRUE(is_miss(collide(Segment{{0, 0}, {0, 2}}, Segment{{0, -1}, {0, -3}})));
    EXPECT_FALSE(overlaps(Shape{Segment{{0, 0}, {2, 0}}}, Shape{Segment{{3, 0}, {5, 0}}}));
}

TEST(SatSegment, CollinearTouchingAndOverlapping) {
    const Manifold t = collide(Segment{{0, 0}, {2, 0}}, Segment{{2, 0}, {5, 0}});
    EXPECT_TRUE(t.hit);
    EXPECT_EQ(t.depth, 0.0f);
    EXPECT_TRUE(test::is_unit(t.normal));
    // Overlapping on [2,3]: any sideways nudge separates them, so depth 0 (normal +-y).
    const Manifold o = collide(Segment{{0, 0}, {3, 0}}, Segment{{2, 0}, {5, 0}});
    EXPECT_TRUE(o.hit);
    EXPECT_EQ(o.depth, 0.0f);
    EXPECT_TRUE(test::is_unit(o.normal));
}

TEST(SatSegment, ParallelDisjointMiss) {
    EXPECT_TRUE(is_miss(collide(Segment{{0, 0}, {2, 0}}, Segment{{0, 1}, {2, 1}})));
    EXPECT_TRUE(is_miss(collide(Segment{{0, 0}, {2, 2}}, Segment{{1, 0}, {3, 2}})));
}

TEST(SatSegment, ZeroLengthSegments) {
    // A point on a segment touches it.
    const Manifold p = collide(Segment{{2, 0}, {2, 0}}, Segment{{0, 0}, {4, 0}});
    EXPECT_TRUE(p.hit);
    EXPECT_EQ(p.depth, 0.0f);
    EXPECT_TRUE(test::is_unit(p.normal));
    // A point beside a segment misses.
    EXPECT_TRUE(is_miss(collide(Segment{{2, 0.5f}, {2, 0.5f}}, Segment{{0, 0}, {4, 0}})));
    // A point beyond the segment's end on its line misses.
    EXPECT_TRUE(is_miss(collide(Segment{{5, 0}, {5, 0}}, Segment{{0, 0}, {4, 0}})));
    // Two equal points touch, with a defined unit normal.
    const Manifold q = collide(Segment{{1, 1}, {1, 1}}, Segment{{1, 1}, {1, 1}});
    EXPECT_TRUE(q.hit);
    EXPECT_EQ(q.depth, 0.0f);
    EXPECT_TRUE(test::is_unit(q.normal));
    EXPECT_TRUE(is_miss(collide(Segment{{1, 1}, {1, 1}}, Segment{{2, 1}, {2, 1}})));
}

// A box whose size overflows float is malformed, an Obb as an Aabb: a miss for every query.
TEST(SatLimits, AnObbWhoseSizeOverflowsIsAMissAsAnAabbIs) {
    const Obb huge{{0, 0}, {2e38f, 2e38f}};  // 4e38 across
    const Aabb same{{-2e38f, -2e38f}, {2e38f, 2e38f}};
    for (const Shape& other : {Shape{Circle{{0, 0}, 1}}, Shape{Obb{{0, 0}, {1, 1}}}, Shape{Segment{{-1, 0}, {1, 0}}},
                               Shape{make_polygon(std::vector<Vec2>{{0, 0}, {1, 0}, {0, 1}}).value()}}) {
        EXPECT_TRUE(is_miss(collide(Shape{same}, other)));
        EXPECT_TRUE(is_miss(collide(Shape{huge}, other)));
        EXPECT_TRUE(is_miss(collide(other, Shape{huge})));
    }
    EXPECT_FALSE(cast({0, 0}, {1, 0}, huge).hit);
    EXPECT_FALSE(sweep(Circle{{5, 0}, 1}, {1, 0}, huge).hit);
    // A corner beyond float: the centre far out, the halves modest.
    EXPECT_TRUE(is_miss(collide(Obb{{3e38f, 0}, {1e38f, 1}}, Circle{{0, 0}, 1})));
    // Large but finite boxes stay boxes.
    EXPECT_TRUE(collide(Obb{{0, 0}, {1e37f, 1e37f}}, Circle{{0, 0}, 1}).hit);
}

TEST(SatLimits, ProjectionsBeyondFloatRangeAreAMiss) {
    // Found by the collision fuzz target (tests/fuzz/regressions/collision/): two boxes with
    // half extents of FLT_MAX; their projections overflow and SAT reported depth inf. A depth
    // or normal that is not finite is no answer: a miss, all zeros.
    const float big = std::numeric_limits<float>::max();
    const Obb a{{big, big}, {big, 1e6f}, -24.0f};
    const Obb b{{99928.25f, big}, {big, big}, -7.75f};
    EXPECT_TRUE(is_miss(collide(a, b)));
    EXPECT_TRUE(is_miss(collide(Shape{b}, Shape{a})));
    EXPECT_FALSE(overlaps(Shape{a}, Shape{b}));
    // Their contact points overflow even where the MTD does not: no contact set.
    const Obb c{{big, big}, {big, 1e6f}, -16.0f};
    const Obb d{{99928.25f, big}, {big, 1e6f}, -24.0f};
    const ContactSet cs = contacts(c, d);
    EXPECT_EQ(cs.count, 0);
    EXPECT_TRUE(is_miss(cs.manifold));
}

}  // namespace
}  // namespace jostle
