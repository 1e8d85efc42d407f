// Lines and closest points (lines.cpp, slides 09-73 to 09-102): the A x + B y = C form, line
// and segment intersection, closest points on a line, segment, circle, in a box and polygon.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <numeric>
#include <limits>

#include "test_shapes.h"

namespace jostle {
namespace {

using test::kPi;
using test::kSqrt2;

TEST(LineThrough, Coefficients) {
    // (1,2),(4,6): A = 6 - 2 = 4, B = 1 - 4 = -3, C = 4*1 + (-3)*2 = -2.
    const Line l = line_through({1, 2}, {4, 6});
    EXPECT_EQ(l.a, 4.0f);
    EXPECT_EQ(l.b, -3.0f);
    EXPECT_EQ(l.c, -2.0f);
    // Both points satisfy it: 4*4 - 3*6 = -2.
    EXPECT_EQ(l.a * 4.0f + l.b * 6.0f, l.c);
}

TEST(LineIntersect, CrossingPointBySlideFormulas) {
    // l1 through (0,0),(4,4): A1 = 4, B1 = -4, C1 = 0. l2 through (0,4),(4,0): A2 = -4, B2 = -4,
    // C2 = -16. det = A2 B1 - B2 A1 = 16 + 16 = 32; x = (C2 B1 - B2 C1)/det = 64/32 = 2;
    // y = (C1 A2 - A1 C2)/det = 64/32 = 2.
    const LineIntersection r = intersect(line_through({0, 0}, {4, 4}), line_through({0, 4}, {4, 0}));
    EXPECT_EQ(r.kind, LineRelation::point);
    EXPECT_EQ(r.point, (Vec2{2, 2}));
}

TEST(LineIntersect, NonSymmetricCase) {
    // l1: y = 1 through (0,1),(5,1): A1 = 0, B1 = -5, C1 = -5. l2 through (2,0),(4,4): A2 = 4,
    // B2 = -2, C2 = 8. det = 4*(-5) - (-2)*0 = -20; x = (8*(-5) - (-2)(-5))/-20 = -50/-20 = 2.5;
    // y = ((-5)*4 - 0*8)/-20 = 1. Check: on l2, y = 2(x - 2) = 1 at x = 2.5.
    const LineIntersection r = intersect(line_through({0, 1}, {5, 1}), line_through({2, 0}, {4, 4}));
    EXPECT_EQ(r.kind, LineRelation::point);
    EXPECT_VEC_NEAR(r.point, (Vec2{2.5f, 1}), 1e-6f);
}

TEST(LineIntersect, ParallelAndCoincident) {
    // Through (0,0),(1,1): (1,-1,0); through (0,1),(1,2): (1,-1,-1). det = 1*(-1) - (-1)*1 = 0.
    const LineIntersection p = intersect(line_through({0, 0}, {1, 1}), line_through({0, 1}, {1, 2}));
    EXPECT_EQ(p.kind, LineRelation::parallel);
    EXPECT_EQ(p.point, (Vec2{0, 0}));
    // Through (2,2),(5,5): (3,-3,0), the same line scaled: coincident.
    const LineIntersection c = intersect(line_through({0, 0}, {1, 1}), line_through({2, 2}, {5, 5}));
    EXPECT_EQ(c.kind, LineRelation::coincident);
    EXPECT_EQ(c.point, (Vec2{0, 0}));
    // Opposite direction, same line: (5,5)->(2,2) gives (-3,3,0).
    EXPECT_EQ(intersect(line_through({0, 0}, {1, 1}), line_through({5, 5}, {2, 2})).kind, LineRelation::coincident);
    // Vertical lines x = 1 and x = 3.
    EXPECT_EQ(intersect(line_through({1, 0}, {1, 5}), line_through({3, 0}, {3, 5})).kind, LineRelation::parallel);
    EXPECT_EQ(intersect(line_through({1, 0}, {1, 5}), line_through({1, 7}, {1, -2})).kind, LineRelation::coincident);
}

TEST(LineIntersect, DegenerateLineIsParallelToEverything) {
    const Line deg = line_through({3, 3}, {3, 3});
    EXPECT_EQ(intersect(deg, line_through({0, 0}, {4, 4})).kind, LineRelation::parallel);
    EXPECT_EQ(intersect(line_through({0, 0}, {4, 4}), deg).kind, LineRelation::parallel);
    EXPECT_EQ(intersect(deg, deg).kind, LineRelation::parallel);
    EXPECT_EQ(intersect(deg, deg).point, (Vec2{0, 0}));
}

// The decisions are exact for any float coefficients: det and the same-line test are zero
// only when they are zero in exact arithmetic (double holds the products exactly). Each case
// but the last failed when they were taken in float.
TEST(LineIntersect, ExactForTinyAndNearlyParallelCoefficients) {
    // Lines through points 1e-23 apart (y = x and y = 1): det = 1e-46 underflowed in float,
    // and both lines were called coincident.
    const LineIntersection tiny = intersect(line_through({0, 0}, {1e-23f, 1e-23f}), line_through({0, 1}, {1e-23f, 1}));
    EXPECT_EQ(tiny.kind, LineRelation::point);
    EXPECT_EQ(tiny.point, (Vec2{1, 1}));
    // e = 2^-13: A2 B1 = (1 + e)(1 - e) = 1 - 2^-26 rounds to 1 in float, so det = -2^-26
    // rounded to 0 (parallel, or coincident when both pass through the origin).
    const float e = std::ldexp(1.0f, -13);
    const Line l1{1.0f, 1.0f - e, 0.0f};
    const LineIntersection through_origin = intersect(l1, Line{1.0f + e, 1.0f, 0.0f});
    EXPECT_EQ(through_origin.kind, LineRelation::point);
    EXPECT_EQ(through_origin.point, (Vec2{0, 0}));
    // C2 = 2^-26: they cross at (-(1 - e), 1) (on l1: -(1 - e) + (1 - e) = 0; on l2:
    // -(1 + e)(1 - e) + 1 = e^2).
    const LineIntersection nearly = intersect(l1, Line{1.0f + e, 1.0f, e * e});
    EXPECT_EQ(nearly.kind, LineRelation::point);
    EXPECT_EQ(nearly.point, (Vec2{-(1.0f - e), 1.0f}));
    // A crossing beyond float's range is reported as parallel (no point to give), as before.
    EXPECT_EQ(intersect(Line{1.0f, 1.0f, 3e38f}, Line{1.0f + std::ldexp(1.0f, -23), 1.0f, -3e38f}).kind,
              LineRelation::parallel);
}

TEST(SegmentIntersect, Crossing) {
    const SegmentIntersection r = intersect(Segment{{0, 0}, {4, 4}}, Segment{{0, 4}, {4, 0}});
    EXPECT_TRUE(r.hit);
    EXPECT_EQ(r.point, (Vec2{2, 2}));
    // Lines cross at (2,2) but the second segment stops at (1,3): the range check fails.
    EXPECT_FALSE(intersect(Segment{{0, 0}, {4, 4}}, Segment{{0, 4}, {1, 3}}).hit);
    // Crossing beyond the first segment's end.
    EXPECT_FALSE(intersect(Segment{{0, 0}, {1, 1}}, Segment{{0, 4}, {4, 0}}).hit);
}

TEST(SegmentIntersect, EndpointsTouching) {
    // (0,0)-(2,2) and (2,2)-(4,0): det = 8, x = 16/8 = 2, y = 16/8 = 2: closed ranges accept it.
    const SegmentIntersection r = intersect(Segment{{0, 0}, {2, 2}}, Segment{{2, 2}, {4, 0}});
    EXPECT_TRUE(r.hit);
    EXPECT_EQ(r.point, (Vec2{2, 2}));
}

TEST(SegmentIntersect, TJunction) {
    const SegmentIntersection r = intersect(Segment{{0, 0}, {4, 0}}, Segment{{2, 0}, {2, 3}});
    EXPECT_TRUE(r.hit);
    EXPECT_EQ(r.point, (Vec2{2, 0}));
    const SegmentIntersection s = intersect(Segment{{2, 3}, {2, 0}}, Segment{{0, 0}, {4, 0}});
    EXPECT_TRUE(s.hit);
    EXPECT_EQ(s.point, (Vec2{2, 0}));
    EXPECT_FALSE(intersect(Segment{{0, 0}, {4, 0}}, Segment{{2, 0.001f}, {2, 3}}).hit);
}

TEST(SegmentIntersect, AxisAlignedRangeCheck) {
    // A horizontal and a vertical segment: the slide's range check on a zero-width x range.
    const SegmentIntersection r = intersect(Segment{{0, 1}, {4, 1}}, Segment{{3, -2}, {3, 5}});
    EXPECT_TRUE(r.hit);
    EXPECT_EQ(r.point, (Vec2{3, 1}));
    EXPECT_FALSE(intersect(Segment{{0, 1}, {4, 1}}, Segment{{5, -2}, {5, 5}}).hit);
}

TEST(SegmentIntersect, CollinearOverlapping) {
    // [0,3] and [2,5] on y = 0 share [2,3]; the shared point nearest s1.a = (0,0) is (2,0).
    const SegmentIntersection r = intersect(Segment{{0, 0}, {3, 0}}, Segment{{2, 0}, {5, 0}});
    EXPECT_TRUE(r.hit);
    EXPECT_EQ(r.point, (Vec2{2, 0}));
    // s1 reversed: s1.a = (3,0) is itself shared.
    const SegmentIntersection b = intersect(Segment{{3, 0}, {0, 0}}, Segment{{2, 0}, {5, 0}});
    EXPECT_TRUE(b.hit);
    EXPECT_EQ(b.point, (Vec2{3, 0}));
    // s2 inside s1 on a diagonal: (0,0)-(6,6) and (4,4)-(2,2): nearest to s1.a is (2,2).
    const SegmentIntersection d = intersect(Segment{{0, 0}, {6, 6}}, Segment{{4, 4}, {2, 2}});
    EXPECT_TRUE(d.hit);
    EXPECT_VEC_NEAR(d.point, (Vec2{2, 2}), 1e-6f);
    // Collinear, touching end to end.
    const SegmentIntersection t = intersect(Segment{{0, 0}, {2, 0}}, Segment{{2, 0}, {3, 0}});
    EXPECT_TRUE(t.hit);
    EXPECT_EQ(t.point, (Vec2{2, 0}));
    // Vertical collinear.
    const SegmentIntersection v = intersect(Segment{{1, 5}, {1, 0}}, Segment{{1, 2}, {1, 8}});
    EXPECT_TRUE(v.hit);
    EXPECT_EQ(v.point, (Vec2{1, 5}));
}

TEST(SegmentIntersect, CollinearDisjointAndParallelDisjoint) {
    EXPECT_FALSE(intersect(Segment{{0, 0}, {2, 0}}, Segment{{3, 0}, {5, 0}}).hit);
    EXPECT_FALSE(intersect(Segment{{0, 0}, {2, 2}}, Segment{{3, 3}, {5, 5}}).hit);
    EXPECT_FALSE(intersect(Segment{{0, 0}, {2, 0}}, Segment{{0, 1}, {2, 1}}).hit);
    EXPECT_FALSE(intersect(Segment{{0, 0}, {2, 2}}, Segment{{1, 0}, {3, 2}}).hit);
    EXPECT_EQ(intersect(Segment{{0, 0}, {2, 0}}, Segment{{0, 1}, {2, 1}}).point, (Vec2{0, 0}));
}

TEST(SegmentIntersect, ZeroLengthSegments) {
    // A point segment lying on the other segment shares that point.
    const SegmentIntersection r = intersect(Segment{{2, 0}, {2, 0}}, Segment{{0, 0}, {4, 0}});
    EXPECT_TRUE(r.hit);
    EXPECT_EQ(r.point, (Vec2{2, 0}));
    EXPECT_TRUE(intersect(Segment{{0, 0}, {4, 0}}, Segment{{2, 0}, {2, 0}}).hit);
    EXPECT_FALSE(intersect(Segment{{2, 1}, {2, 1}}, Segment{{0, 0}, {4, 0}}).hit);
    EXPECT_FALSE(intersect(Segment{{5, 0}, {5, 0}}, Segment{{0, 0}, {4, 0}}).hit);
    EXPECT_TRUE(intersect(Segment{{1, 1}, {1, 1}}, Segment{{1, 1}, {1, 1}}).hit);
    EXPECT_FALSE(intersect(Segment{{1, 1}, {1, 1}}, Segment{{1, 2}, {1, 2}}).hit);
}

// Short segments are not points: segments 1e-23 long cross (their cross product, 2e-46,
// underflowed in float, and s1 was taken for a point off s2).
TEST(SegmentIntersect, ShortSegmentsCrossAndOverlap) {
    const float d = 1e-23f;
    const SegmentIntersection x = intersect(Segment{{0, 0}, {d, d}}, Segment{{0, d}, {d, 0}});
    EXPECT_TRUE(x.hit);
    EXPECT_EQ(x.point, (Vec2{0.5f * d, 0.5f * d}));
    EXPECT_FALSE(intersect(Segment{{0, 0}, {d, d}}, Segment{{2 * d, 0}, {2 * d, d}}).hit);
    // Collinear and overlapping from the middle of s1.
    const SegmentIntersection c = intersect(Segment{{0, 0}, {2 * d, 0}}, Segment{{d, 0}, {3 * d, 0}});
    EXPECT_TRUE(c.hit);
    EXPECT_EQ(c.point, (Vec2{d, 0}));
}

TEST(ClosestPointLine, FootOfThePerpendicular) {
    // 09-83. Line y = 0 through (0,0),(4,0); p = (2,3) -> (2,0). Beyond the points too: (9,-2) -> (9,0).
    const Line x_axis = line_through({0, 0}, {4, 0});
    EXPECT_VEC_NEAR(closest_point(x_axis, {2, 3}), (Vec2{2, 0}), 1e-6f);
    EXPECT_VEC_NEAR(closest_point(x_axis, {9, -2}), (Vec2{9, 0}), 1e-6f);
    // Line y = x; p = (0,2): foot (1,1).
    EXPECT_VEC_NEAR(closest_point(line_through({0, 0}, {2, 2}), {0, 2}), (Vec2{1, 1}), 1e-6f);
    // Line x + y = 4; p = (0,0): foot (2,2).
    EXPECT_VEC_NEAR(closest_point(line_through({0, 4}, {4, 0}), {0, 0}), (Vec2{2, 2}), 1e-6f);
    // A point on the line is its own foot.
    EXPECT_VEC_NEAR(closest_point(line_through({0, 4}, {4, 0}), {1, 3}), (Vec2{1, 3}), 1e-6f);
}

TEST(ClosestPointSegment, InsideAndBeyondTheEnds) {
    // 09-85: (0,0)-(4,0).
    const Segment s{{0, 0}, {4, 0}};
    EXPECT_VEC_NEAR(closest_point(s, {1, 5}), (Vec2{1, 0}), 1e-6f);
    EXPECT_VEC_NEAR(closest_point(s, {6, 3}), (Vec2{4, 0}), 1e-6f);
    EXPECT_VEC_NEAR(closest_point(s, {-2, -1}), (Vec2{0, 0}), 1e-6f);
    // Diagonal (0,0)-(2,2): (0,2) -> (1,1); (5,3) -> foot at (4,4) is beyond -> (2,2).
    EXPECT_VEC_NEAR(closest_point(Segment{{0, 0}, {2, 2}}, {0, 2}), (Vec2{1, 1}), 1e-6f);
    EXPECT_VEC_NEAR(closest_point(Segment{{0, 0}, {2, 2}}, {5, 3}), (Vec2{2, 2}), 1e-6f);
    // Zero length: the point itself.
    EXPECT_EQ(closest_point(Segment{{3, 3}, {3, 3}}, {7, -1}), (Vec2{3, 3}));
}

// The TOLERANCES promise: shapes that touch exactly in float (integer coordinates) report a
// hit with depth 0. A point on an integer segment (3, 0) on (0, 0)-(21, 0) was 2.4e-7 off it by
// a + t (b - a) with t = 3/21 rounded: a zero-radius circle, a point segment, a zero-length cast
// and swept_overlaps all missed it (about 1 in 10 such points). The offset across the segment
// now comes from the cross product, exact there.
TEST(ClosestPointSegment, AnIntegerPointOnAnIntegerSegmentIsOnIt) {
    Rng rng(2026);
    int checked = 0;
    for (int k = 0; k < 20000; ++k) {
        const auto coordinate = [&] { return static_cast<float>(static_cast<int>(rng.below(401)) - 200); };
        // Near the origin, and far out (to 1e5, the documented range), on short segments.
        const Vec2 shift = k % 2 == 0 ? Vec2{} : Vec2{static_cast<float>(static_cast<int>(rng.below(200001)) - 100000),
                                                         static_cast<float>(static_cast<int>(rng.below(200001)) - 100000)};
        const Vec2 a = Vec2{coordinate(), coordinate()} + shift;
        const Vec2 b = Vec2{coordinate(), coordinate()} + shift;
        // The integer points on a-b: a + j (b - a) / g for g = gcd of the steps, 0 < j < g.
        const int dx = static_cast<int>(b.x - a.x), dy = static_cast<int>(b.y - a.y);
        const int g = std::gcd(std::abs(dx), std::abs(dy));
        if (g < 2) continue;
        const int j = 1 + static_cast<int>(rng.below(static_cast<std::uint32_t>(g - 1)));
        const Vec2 p{a.x + static_cast<float>(j * (dx / g)), a.y + static_cast<float>(j * (dy / g))};
        const Segment s{a, b};
        SCOPED_TRACE(testing::Message() << "(" << p.x << ", " << p.y << ") on (" << a.x << ", " << a.y << ")-(" << b.x
                                        << ", " << b.y << ")");
        ASSERT_EQ(closest_point(s, p), p);
        const Manifold m = collide(s, Circle{p, 0.0f});
        ASSERT_TRUE(m.hit);
        ASSERT_EQ(m.depth, 0.0f);
        ASSERT_TRUE(intersect(Segment{p, p}, s).hit);
        ASSERT_TRUE(intersect(s, Segment{p, p}).hit);
        ASSERT_TRUE(cast(p, p, s).hit);
        ASSERT_TRUE(swept_overlaps(Circle{a, 0.0f}, b - a, Circle{p, 0.0f}));
        ++checked;
    }
    EXPECT_GT(checked, 1000);
    // The first case found, by hand.
    EXPECT_EQ(closest_point(Segment{{0, 0}, {21, 0}}, {3, 0}), (Vec2{3, 0}));
    EXPECT_TRUE(collide(Segment{{0, 0}, {21, 0}}, Circle{{3, 0}, 0}).hit);
}

TEST(ClosestPointOnCircle, SlideFormula) {
    // 09-98: d = c - q, p = q + (|d| - r)/|d| d. c = (0,0), r = 5, q = (6,8): d = (-6,-8),
    // |d| = 10, p = (6,8) + 0.5 (-6,-8) = (3,4).
    EXPECT_VEC_NEAR(closest_point_on(Circle{{0, 0}, 5}, {6, 8}), (Vec2{3, 4}), 1e-5f);
    // q inside at (1,0): d = (-1,0), |d| = 1, p = (1,0) + (-4)(-1,0) = (5,0).
    EXPECT_VEC_NEAR(closest_point_on(Circle{{0, 0}, 5}, {1, 0}), (Vec2{5, 0}), 1e-5f);
    // Off-origin: c = (10,10), r = 1, q = (10,13) -> (10,11).
    EXPECT_VEC_NEAR(closest_point_on(Circle{{10, 10}, 1}, {10, 13}), (Vec2{10, 11}), 1e-5f);
    // q at the centre: any point of the circle, but a finite one on it.
    const Vec2 p = closest_point_on(Circle{{2, 3}, 4}, {2, 3});
    EXPECT_TRUE(is_finite(p));
    EXPECT_NEAR(length(p - Vec2{2, 3}), 4.0f, 1e-5f);
}

TEST(ClosestPointCircle, InTheClosedDisc) {
    const ClosestPoint out = closest_point(Circle{{0, 0}, 5}, {6, 8});
    EXPECT_VEC_NEAR(out.point, (Vec2{3, 4}), 1e-5f);
    EXPECT_NEAR(out.distance, 5.0f, 1e-5f);
    const ClosestPoint in = closest_point(Circle{{0, 0}, 5}, {1, 2});
    EXPECT_EQ(in.point, (Vec2{1, 2}));
    EXPECT_EQ(in.distance, 0.0f);
    const ClosestPoint on = closest_point(Circle{{0, 0}, 5}, {3, 4});
    EXPECT_VEC_NEAR(on.point, (Vec2{3, 4}), 1e-6f);
    EXPECT_NEAR(on.distance, 0.0f, 1e-6f);
}

TEST(ClosestPointCircle, FarBeyondTheSquaresRange) {
    // Found by the collision fuzz target (tests/fuzz/regressions/collision/): the centre 3.3e27
    // away from q; |d|^2 overflows, and (inf - r) / inf made the point and distance NaN. The
    // point is r short of the centre toward q. (The distance is |q - p|, whose square
    // overflows too: +infinity this far beyond the manual's LIMITS, never NaN.)
    const ClosestPoint far = closest_point(Circle{{3.349782e27f, -13.75f}, 2}, {0, 0});
    EXPECT_EQ(far.point.x, 3.349782e27f);  // 2 px is far below the rounding at 3e27
    EXPECT_NEAR(far.point.y, -13.75f, 1e-3f);
    EXPECT_FALSE(std::isnan(far.distance));
    EXPECT_GT(far.distance, 1e27f);
    // Toward negative x too: the scaled form keeps the direction (a radius up to ~1.8e19,
    // whose square is finite; a larger one is malformed, "no point").
    const ClosestPoint neg = closest_point(Circle{{-3e25f, 0}, 1e19f}, {0, 0});
    EXPECT_EQ(neg.point.x, -3e25f + 1e19f);
    EXPECT_EQ(neg.point.y, 0.0f);
    EXPECT_GT(neg.distance, 1e25f);
    const ClosestPoint malformed = closest_point(Circle{{-3e25f, 0}, 1e25f}, {0, 0});
    EXPECT_EQ(malformed.point, (Vec2{0, 0}));
    EXPECT_EQ(malformed.distance, INFINITY);
    // From the far side of float's range: c - q itself overflows.
    const float big = std::numeric_limits<float>::max();
    const ClosestPoint across = closest_point(Circle{{0, -1.7112253e38f}, 1}, {0, big});
    EXPECT_EQ(across.point, (Vec2{0, -1.7112253e38f + 1}));
    EXPECT_FALSE(std::isnan(across.distance));
    // A segment seen from (FLT_MAX, FLT_MAX): the projection's terms were inf and -inf.
    const ClosestPoint seg = closest_point(Shape{Segment{{-23.75f, 0}, {5.75f, -9.5f}}}, {big, big});
    EXPECT_EQ(seg.point, (Vec2{5.75f, -9.5f}));
    EXPECT_FALSE(std::isnan(seg.distance));
}

TEST(ClosestPointAabb, PushIn) {
    // 09-102 on [0,4]x[0,2].
    const Aabb box{{0, 0}, {4, 2}};
    const ClosestPoint a = closest_point(box, {6, -1});  // both axes clamped: (4,0), |(2,-1)| = sqrt5
    EXPECT_EQ(a.point, (Vec2{4, 0}));
    EXPECT_NEAR(a.distance, std::sqrt(5.0f), 1e-6f);
    const ClosestPoint b = closest_point(box, {-1, 1});  // x clamped: (0,1), distance 1
    EXPECT_EQ(b.point, (Vec2{0, 1}));
    EXPECT_FLOAT_EQ(b.distance, 1.0f);
    const ClosestPoint c = closest_point(box, {2, 1});  // inside: itself
    EXPECT_EQ(c.point, (Vec2{2, 1}));
    EXPECT_EQ(c.distance, 0.0f);
    const ClosestPoint d = closest_point(box, {3, 5});  // y clamped: (3,2), distance 3
    EXPECT_EQ(d.point, (Vec2{3, 2}));
    EXPECT_FLOAT_EQ(d.distance, 3.0f);
}

TEST(ClosestPointObb, InTheBoxFrame) {
    // Diamond (half 1 at 45 deg): q = (3,0) -> vertex (sqrt2,0), distance 3 - sqrt2.
    const Obb diamond{{0, 0}, {1, 1}, kPi / 4};
    const ClosestPoint v = closest_point(diamond, {3, 0});
    EXPECT_VEC_NEAR(v.point, (Vec2{kSqrt2, 0}), 1e-5f);
    EXPECT_NEAR(v.distance, 3.0f - kSqrt2, 1e-5f);
    // q = (2,2) -> foot on the face, (1/sqrt2, 1/sqrt2), distance 2 sqrt2 - 1.
    const ClosestPoint f = closest_point(diamond, {2, 2});
    EXPECT_VEC_NEAR(f.point, (Vec2{1 / kSqrt2, 1 / kSqrt2}), 1e-5f);
    EXPECT_NEAR(f.distance, 2 * kSqrt2 - 1, 1e-5f);
    const ClosestPoint in = closest_point(diamond, {0.2f, 0.3f});
    EXPECT_VEC_NEAR(in.point, (Vec2{0.2f, 0.3f}), 1e-6f);
    EXPECT_NEAR(in.distance, 0.0f, 1e-6f);
}

TEST(ClosestPointPolygon, OutsideInsideAndBoundary) {
    // Triangle (0,0),(4,0),(0,4).
    const Polygon tri = test::polygon_or_die({{0, 0}, {4, 0}, {0, 4}});
    const ClosestPoint h = closest_point(tri, {3, 3});  // foot on x + y = 4: (2,2), distance sqrt2
    EXPECT_VEC_NEAR(h.point, (Vec2{2, 2}), 1e-5f);
    EXPECT_NEAR(h.distance, kSqrt2, 1e-5f);
    const ClosestPoint v = closest_point(tri, {6, -1});  // vertex region of (4,0): distance sqrt5
    EXPECT_VEC_NEAR(v.point, (Vec2{4, 0}), 1e-5f);
    EXPECT_NEAR(v.distance, std::sqrt(5.0f), 1e-5f);
    const ClosestPoint e = closest_point(tri, {2, -3});  // foot on y = 0: (2,0), distance 3
    EXPECT_VEC_NEAR(e.point, (Vec2{2, 0}), 1e-6f);
    EXPECT_NEAR(e.distance, 3.0f, 1e-6f);
    const ClosestPoint in = closest_point(tri, {1, 1});  // inside: itself
    EXPECT_EQ(in.point, (Vec2{1, 1}));
    EXPECT_EQ(in.distance, 0.0f);
}

TEST(ClosestPointOnBoundary, InsidePointGoesToTheNearestEdge) {
    // Square [0,4]^2, q = (3,2): nearest edge x = 4, point (4,2).
    const Polygon sq = test::box_polygon(0, 0, 4, 4);
    int edge = -1;
    const Vec2 p = closest_point_on_boundary(sq, {3, 2}, &edge);
    EXPECT_VEC_NEAR(p, (Vec2{4, 2}), 1e-6f);
    ASSERT_GE(edge, 0);
    ASSERT_LT(edge, sq.count());
    EXPECT_VEC_NEAR(sq.normals()[static_cast<std::size_t>(edge)], (Vec2{1, 0}), 1e-6f);
    // Outside near the top: q = (1,-2) -> (1,0) on the edge with normal (0,-1).
    const Vec2 t = closest_point_on_boundary(sq, {1, -2}, &edge);
    EXPECT_VEC_NEAR(t, (Vec2{1, 0}), 1e-6f);
    EXPECT_VEC_NEAR(sq.normals()[static_cast<std::size_t>(edge)], (Vec2{0, -1}), 1e-6f);
    // Without the edge out-parameter.
    EXPECT_VEC_NEAR(closest_point_on_boundary(sq, {2, 0.5f}), (Vec2{2, 0}), 1e-6f);
}

// The closest points that answer a bare Vec2 give {0, 0} for a NaN or infinite input, as
// the ClosestPoint answers give point {0, 0} (at distance +inf): before, a NaN query point
// gave a plausible finite point (a segment's end, the circle's +x point) and the empty
// Polygon a boundary point on an edge it does not have.
TEST(ClosestPointVec2, NonFiniteInputOrNoBoundaryAnswersTheOrigin) {
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    const Vec2 origin{0, 0};
    const Segment seg{{5, 5}, {6, 5}};
    EXPECT_EQ(closest_point(seg, Vec2{nan, 1}), origin);
    EXPECT_EQ(closest_point(seg, Vec2{1, -inf}), origin);
    EXPECT_EQ(closest_point(Segment{{5, 5}, {inf, 5}}, Vec2{1, 1}), origin);
    EXPECT_EQ(closest_point_on(Circle{{5, 5}, 2}, Vec2{nan, nan}), origin);
    EXPECT_EQ(closest_point_on(Circle{{5, nan}, 2}, Vec2{1, 1}), origin);
    EXPECT_EQ(closest_point_on(Circle{{5, 5}, -1}, Vec2{1, 1}), origin);
    const Line x_axis = line_through({0, 0}, {1, 0});
    EXPECT_EQ(closest_point(x_axis, Vec2{inf, 3}), origin);
    EXPECT_EQ(closest_point(Line{nan, 1, 0}, Vec2{2, 3}), origin);
    EXPECT_EQ(closest_point(Line{1e-20f, 0, 3e38f}, Vec2{0, 0}), origin);  // the foot at x = 3e58
    int edge = 7;
    EXPECT_EQ(closest_point_on_boundary(Polygon{}, Vec2{7, 1}, &edge), origin);
    EXPECT_EQ(edge, -1);
    const Polygon square = test::box_polygon(0, 0, 1, 1);
    edge = 7;
    EXPECT_EQ(closest_point_on_boundary(square, Vec2{nan, 0}, &edge), origin);
    EXPECT_EQ(edge, -1);
    // Finite input is answered as before.
    EXPECT_EQ(closest_point(seg, Vec2{5.5f, 9}), (Vec2{5.5f, 5}));
    EXPECT_EQ(closest_point(x_axis, Vec2{2, 3}), (Vec2{2, 0}));
    EXPECT_EQ(closest_point_on(Circle{{5, 5}, 2}, Vec2{5, 5}), (Vec2{7, 5}));
    EXPECT_EQ(closest_point_on_boundary(square, Vec2{3, 0}, &edge), (Vec2{1, 0}));
    EXPECT_GE(edge, 0);
}

TEST(ClosestPointShape, DispatchesToTheShape) {
    EXPECT_EQ(closest_point(Shape{Aabb{{0, 0}, {4, 2}}}, {6, -1}).point, (Vec2{4, 0}));
    EXPECT_VEC_NEAR(closest_point(Shape{Circle{{0, 0}, 5}}, {6, 8}).point, (Vec2{3, 4}), 1e-5f);
    const ClosestPoint s = closest_point(Shape{Segment{{0, 0}, {4, 0}}}, {6, 3});
    EXPECT_VEC_NEAR(s.point, (Vec2{4, 0}), 1e-6f);
    EXPECT_NEAR(s.distance, std::sqrt(13.0f), 1e-5f);
    const ClosestPoint p = closest_point(Shape{test::box_polygon(0, 0, 4, 4)}, {5, 5});
    EXPECT_VEC_NEAR(p.point, (Vec2{4, 4}), 1e-6f);
    EXPECT_NEAR(p.distance, kSqrt2, 1e-6f);
    const ClosestPoint o = closest_point(Shape{Obb{{0, 0}, {1, 1}, kPi / 4}}, {3, 0});
    EXPECT_NEAR(o.distance, 3.0f - kSqrt2, 1e-5f);
}

}  // namespace
}  // namespace jostle
