// Circle tests (circle.cpp, slides 09-70 to 09-72 and 09-86 to 09-102): circle-circle by
// squared distances and the lecture's MTD, polygon-circle by closest point and by SAT with the
// vertex axis, AABB/OBB-circle by clamping, segment-circle.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "test_shapes.h"

namespace jostle {
namespace {

using test::is_hit;
using test::is_miss;
using test::kPi;
using test::kSqrt2;

// The lecture's MTD for circle 1 (09-72): (c1 - c2) / |c1 - c2| * (r1 + r2 - |c1 - c2|).
Vec2 lecture_mtd(const Circle& a, const Circle& b) {
    const Vec2 d = a.center - b.center;
    const float len = length(d);
    return (a.radius + b.radius - len) / len * d;
}

TEST(CircleCircle, Overlapping) {
    // Centres 3 apart, radii 2 + 2: depth 4 - 3 = 1, normal (1,0).
    const Circle a{{0, 0}, 2};
    const Circle b{{3, 0}, 2};
    const Manifold m = collide(a, b);
    EXPECT_TRUE(is_hit(m, 1.0f, {1, 0}));
    EXPECT_VEC_NEAR(m.mtd(), (Vec2{-1, 0}), 1e-6f);
    EXPECT_VEC_NEAR(m.mtd(), lecture_mtd(a, b), 1e-6f);
}

TEST(CircleCircle, ThreeFourFive) {
    // d = (3,4), |d| = 5, r1 + r2 = 7: depth 2, normal (0.6, 0.8); 09-72: (-3,-4)/5 * 2 = (-1.2,-1.6).
    const Circle a{{1, 2}, 3};
    const Circle b{{4, 6}, 4};
    const Manifold m = collide(a, b);
    EXPECT_TRUE(is_hit(m, 2.0f, {0.6f, 0.8f}));
    EXPECT_VEC_NEAR(m.mtd(), (Vec2{-1.2f, -1.6f}), 1e-5f);
    EXPECT_VEC_NEAR(m.mtd(), lecture_mtd(a, b), 1e-5f);
    EXPECT_TRUE(is_hit(collide(b, a), 2.0f, {-0.6f, -0.8f}));
}

TEST(CircleCircle, TouchingExactlyIsAHitWithDepthZero) {
    // 09-71 with squared distances: |d|^2 = 9 + 16 = 25 = (2 + 3)^2, exact in floats.
    const Manifold m = collide(Circle{{0, 0}, 2}, Circle{{3, 4}, 3});
    EXPECT_TRUE(m.hit);
    EXPECT_EQ(m.depth, 0.0f);
    EXPECT_VEC_NEAR(m.normal, (Vec2{0.6f, 0.8f}), 1e-6f);
    const Manifold x = collide(Circle{{0, 0}, 1.5f}, Circle{{3, 0}, 1.5f});
    EXPECT_TRUE(x.hit);
    EXPECT_EQ(x.depth, 0.0f);
    EXPECT_VEC_NEAR(x.normal, (Vec2{1, 0}), 1e-6f);
}

TEST(CircleCircle, ApartIsAMiss) {
    EXPECT_TRUE(is_miss(collide(Circle{{0, 0}, 2}, Circle{{3.001f, 4}, 3})));
    EXPECT_TRUE(is_miss(collide(Circle{{0, 0}, 1}, Circle{{10, 0}, 1})));
}

TEST(CircleCircle, CoincidentCentresUseNormalPlusX) {
    const Manifold m = collide(Circle{{1, 1}, 1}, Circle{{1, 1}, 2});
    EXPECT_TRUE(is_hit(m, 3.0f, {1, 0}, 0.0f));
}

TEST(CircleCircle, ZeroRadius) {
    // A point at distance 1 from a unit circle's centre touches it.
    const Manifold t = collide(Circle{{0, 0}, 0}, Circle{{1, 0}, 1});
    EXPECT_TRUE(is_hit(t, 0.0f, {1, 0}, 0.0f));
    // A point 0.5 inside: depth 0.5.
    EXPECT_TRUE(is_hit(collide(Circle{{0.5f, 0}, 0}, Circle{{1, 0}, 1}), 0.5f, {1, 0}));
    EXPECT_TRUE(is_miss(collide(Circle{{-0.5f, 0}, 0}, Circle{{1, 0}, 1})));
    // Two equal points: touching, coincident-centre normal.
    EXPECT_TRUE(is_hit(collide(Circle{{2, 3}, 0}, Circle{{2, 3}, 0}), 0.0f, {1, 0}, 0.0f));
    EXPECT_TRUE(is_miss(collide(Circle{{2, 3}, 0}, Circle{{2, 4}, 0})));
}

// Polygon-circle: the closest-point method (09-90) and SAT with the vertex axis (09-96) must
// both give the expected manifold.
void expect_polygon_circle(const Polygon& p, const Circle& c, float depth, Vec2 normal, float tol = 1e-5f) {
    EXPECT_TRUE(is_hit(collide(p, c), depth, normal, tol)) << "collide";
    EXPECT_TRUE(is_hit(collide_sat(p, c), depth, normal, tol)) << "collide_sat";
}

TEST(PolygonCircle, CentreOutsideNearAnEdge) {
    // Square [0,4]^2, circle (5,2) r 2: closest point (4,2), distance 1, depth 1, normal (1,0).
    // The slide's MTD for the polygon: direction p - c = (-1,0), length r - |p - c| = 1.
    const Polygon sq = test::box_polygon(0, 0, 4, 4);
    expect_polygon_circle(sq, Circle{{5, 2}, 2}, 1.0f, {1, 0});
    EXPECT_VEC_NEAR(collide(sq, Circle{{5, 2}, 2}).mtd(), (Vec2{-1, 0}), 1e-6f);
    // Above the top edge: circle (1,-1) r 1.5: depth 0.5, normal (0,-1).
    expect_polygon_circle(sq, Circle{{1, -1}, 1.5f}, 0.5f, {0, -1});
}

TEST(PolygonCircle, CentreOutsideNearAVertex) {
    // Circle (5,5) r 2: closest point (4,4), distance sqrt2, depth 2 - sqrt2 = 0.5858, normal
    // (1,1)/sqrt2. SAT: the vertex axis gives 8/sqrt2 - (10/sqrt2 - 2) = 2 - sqrt2 < 1 (edges).
    expect_polygon_circle(test::box_polygon(0, 0, 4, 4), Circle{{5, 5}, 2}, 2.0f - kSqrt2,
                          {1.0f / kSqrt2, 1.0f / kSqrt2});
}

TEST(PolygonCircle, OnlyTheVertexAxisSeparates) {
    // Circle (5.5,5.5) r 2: distance to (4,4) is 1.5 sqrt2 = 2.12 > 2, a miss; yet on x and y
    // the circle spans [3.5,7.5], overlapping [0,4]: the edge normals alone would report a hit.
    const Polygon sq = test::box_polygon(0, 0, 4, 4);
    EXPECT_TRUE(is_miss(collide(sq, Circle{{5.5f, 5.5f}, 2})));
    EXPECT_TRUE(is_miss(collide_sat(sq, Circle{{5.5f, 5.5f}, 2})));
}

TEST(PolygonCircle, CentreOnTheBoundary) {
    // Centre (4,2) on the right edge, r 1: pushed out through that edge, depth r = 1.
    expect_polygon_circle(test::box_polygon(0, 0, 4, 4), Circle{{4, 2}, 1}, 1.0f, {1, 0});
}

TEST(PolygonCircle, CentreInside) {
    // Centre (3,2), r 0.5: nearest edge x = 4 at distance 1; depth 1 + 0.5 = 1.5, normal (1,0).
    // After the polygon moves by mtd (-1.5,0) its right edge is at 2.5 = 3 - 0.5: touching.
    const Polygon sq = test::box_polygon(0, 0, 4, 4);
    expect_polygon_circle(sq, Circle{{3, 2}, 0.5f}, 1.5f, {1, 0});
    // Centre (2,0.5), r 1: nearest edge y = 0 at 0.5; depth 1.5, normal (0,-1).
    expect_polygon_circle(sq, Circle{{2, 0.5f}, 1}, 1.5f, {0, -1});
}

TEST(PolygonCircle, TouchingAndMiss) {
    const Polygon sq = test::box_polygon(0, 0, 4, 4);
    // Circle (6,2) r 2 touches the right edge at (4,2).
    expect_polygon_circle(sq, Circle{{6, 2}, 2}, 0.0f, {1, 0}, 0.0f);
    EXPECT_TRUE(is_miss(collide(sq, Circle{{6.01f, 2}, 2})));
    EXPECT_TRUE(is_miss(collide_sat(sq, Circle{{6.01f, 2}, 2})));
}

TEST(PolygonCircle, SlantedEdge) {
    // Triangle (0,0),(4,0),(0,4); circle (3,3): distance to x + y = 4 is (6-4)/sqrt2 = sqrt2.
    const Polygon tri = test::polygon_or_die({{0, 0}, {4, 0}, {0, 4}});
    EXPECT_TRUE(is_miss(collide(tri, Circle{{3, 3}, 1})));
    EXPECT_TRUE(is_miss(collide_sat(tri, Circle{{3, 3}, 1})));
    // r 2: depth 2 - sqrt2, normal (1,1)/sqrt2 (closest point (2,2) inside the edge).
    expect_polygon_circle(tri, Circle{{3, 3}, 2}, 2.0f - kSqrt2, {1.0f / kSqrt2, 1.0f / kSqrt2});
}

TEST(PolygonCircle, ZeroRadius) {
    // A point at (1,2) in [0,4]^2: nearest edge x = 0 at 1: depth 1; the polygon moves right,
    // so the normal (polygon toward point) is (-1,0).
    expect_polygon_circle(test::box_polygon(0, 0, 4, 4), Circle{{1, 2}, 0}, 1.0f, {-1, 0});
    EXPECT_TRUE(is_miss(collide(test::box_polygon(0, 0, 4, 4), Circle{{5, 2}, 0})));
    EXPECT_TRUE(is_miss(collide_sat(test::box_polygon(0, 0, 4, 4), Circle{{5, 2}, 0})));
}

TEST(PolygonCircle, EveryVertexCountAndTiedFaces) {
    // The faces are measured four at a time (3..16 vertices, the slots past the last face NaN); a
    // centre inside must leave through the first face of greatest separation, exactly as a
    // loop over the faces names it. Regular polygons about (10, -7) and centres on a grid,
    // many on lines of symmetry, where faces tie.
    for (int n = 3; n <= kMaxPolygonVertices; ++n) {
        std::vector<Vec2> pts;
        for (int i = 0; i < n; ++i) {
            const float t = 2.0f * kPi * static_cast<float>(i) / static_cast<float>(n);
            pts.push_back({10.0f + 4.0f * std::cos(t), -7.0f + 4.0f * std::sin(t)});
        }
        const std::optional<Polygon> made = make_polygon(pts);
        ASSERT_TRUE(made.has_value());
        const Polygon& poly = *made;
        for (int gx = -4; gx <= 4; ++gx) {
            for (int gy = -4; gy <= 4; ++gy) {
                const Circle c{{10.0f + 0.5f * static_cast<float>(gx), -7.0f + 0.5f * static_cast<float>(gy)}, 0.25f};
                float most = -INFINITY;
                int face = 0;
                for (int i = 0; i < n; ++i) {
                    const float s = dot(poly.normals()[i], c.center - poly.points()[i]);
                    if (s > most) { most = s; face = i; }
                }
                if (!(most <= 0.0f)) continue;  // only centres inside (or on the boundary)
                SCOPED_TRACE(testing::Message() << n << " vertices, centre " << gx << ", " << gy);
                const Manifold m = collide(poly, c);
                EXPECT_TRUE(m.hit);
                EXPECT_EQ(m.depth, 0.25f - most);
                EXPECT_EQ(m.normal, poly.normals()[face]);
            }
        }
        // Far outside every face: a miss; NaN or infinite circles too.
        EXPECT_TRUE(is_miss(collide(poly, Circle{{10, 20}, 1})));
        EXPECT_TRUE(is_miss(collide(poly, Circle{{10, -7}, NAN})));
        EXPECT_TRUE(is_miss(collide(poly, Circle{{NAN, -7}, 1})));
        EXPECT_TRUE(is_miss(collide(poly, Circle{{10, -7}, INFINITY})));
        EXPECT_TRUE(is_miss(collide(poly, Circle{{10, -7}, -1})));
    }
    EXPECT_TRUE(is_miss(collide(Polygon{}, Circle{{0, 0}, 1})));
}

TEST(AabbCircle, ClampOutside) {
    // Box [0,4]x[0,2], circle (6,1) r 3: clamp -> (4,1), distance 2, depth 1, normal (1,0).
    const Aabb box{{0, 0}, {4, 2}};
    EXPECT_TRUE(is_hit(collide(box, Circle{{6, 1}, 3}), 1.0f, {1, 0}));
    // Circle (7,6) r 6: clamp -> (4,2), d = (3,4), distance 5, depth 1, normal (0.6,0.8).
    EXPECT_TRUE(is_hit(collide(box, Circle{{7, 6}, 6}), 1.0f, {0.6f, 0.8f}));
}

TEST(AabbCircle, TouchingACorner) {
    // Circle (7,6) r 5: |(3,4)|^2 = 25 = r^2, exactly touching the corner (4,2).
    const Manifold m = collide(Aabb{{0, 0}, {4, 2}}, Circle{{7, 6}, 5});
    EXPECT_TRUE(is_hit(m, 0.0f, {0.6f, 0.8f}, 1e-6f));
    EXPECT_EQ(m.depth, 0.0f);
    EXPECT_TRUE(is_miss(collide(Aabb{{0, 0}, {4, 2}}, Circle{{7.01f, 6}, 5})));
}

TEST(AabbCircle, CentreInsidePushedThroughTheNearestFace) {
    // Centre (3,0.5) in [0,4]x[0,2]: faces at 3 (left), 1 (right), 0.5 (top), 1.5 (bottom);
    // the top face y = 0 is nearest: depth 0.5 + 1 = 1.5, the box moves down, normal (0,-1).
    const Manifold m = collide(Aabb{{0, 0}, {4, 2}}, Circle{{3, 0.5f}, 1});
    EXPECT_TRUE(is_hit(m, 1.5f, {0, -1}));
    EXPECT_VEC_NEAR(m.mtd(), (Vec2{0, 1.5f}), 1e-6f);
    // Centre (3.8,1) r 0: nearest face x = 4 at 0.2.
    EXPECT_TRUE(is_hit(collide(Aabb{{0, 0}, {4, 2}}, Circle{{3.8f, 1}, 0}), 0.2f, {1, 0}, 1e-5f));
    // Centre exactly in the middle of a square: a tie, depth 2 + r along some axis.
    const Manifold tie = collide(Aabb{{0, 0}, {4, 4}}, Circle{{2, 2}, 1});
    EXPECT_TRUE(tie.hit);
    EXPECT_FLOAT_EQ(tie.depth, 3.0f);
    EXPECT_TRUE(test::is_unit(tie.normal));
    EXPECT_TRUE(tie.normal.x == 0.0f || tie.normal.y == 0.0f);
}

TEST(AabbCircle, PointOnTheBoundary) {
    // A zero-radius circle on the right face: touching, pushed through x = 4 (distance 0).
    EXPECT_TRUE(is_hit(collide(Aabb{{0, 0}, {4, 2}}, Circle{{4, 1}, 0}), 0.0f, {1, 0}, 0.0f));
}

TEST(ObbCircle, DiamondVertexAndFace) {
    // Half (1,1) at 45 deg: vertices (+-sqrt2, 0), (0, +-sqrt2).
    const Obb diamond{{0, 0}, {1, 1}, kPi / 4};
    // Circle (3,0) r 2: closest point the vertex (sqrt2,0), distance 3 - sqrt2: depth sqrt2 - 1.
    EXPECT_TRUE(is_hit(collide(diamond, Circle{{3, 0}, 2}), kSqrt2 - 1.0f, {1, 0}, 1e-5f));
    // Circle (2,2) r 2: the face with normal (1,1)/sqrt2 is 1 from the centre, the circle's
    // centre 2 sqrt2: depth 2 - (2 sqrt2 - 1) = 3 - 2 sqrt2 = 0.17157.
    EXPECT_TRUE(is_hit(collide(diamond, Circle{{2, 2}, 2}), 3.0f - 2.0f * kSqrt2, {1.0f / kSqrt2, 1.0f / kSqrt2}, 1e-5f));
    EXPECT_TRUE(is_miss(collide(diamond, Circle{{2, 2}, 1.5f})));
}

TEST(ObbCircle, QuarterTurnBox) {
    // Half (2,1) turned 90 deg at the origin covers x in [-1,1], y in [-2,2].
    const Obb box{{0, 0}, {2, 1}, kPi / 2};
    EXPECT_TRUE(is_hit(collide(box, Circle{{3, 0}, 2.5f}), 0.5f, {1, 0}, 1e-5f));
    // Inside at (0,1.5) r 0.25: nearest face y = 2 at 0.5: depth 0.75, normal (0,1).
    EXPECT_TRUE(is_hit(collide(box, Circle{{0, 1.5f}, 0.25f}), 0.75f, {0, 1}, 1e-5f));
    EXPECT_TRUE(is_miss(collide(box, Circle{{0, 3.1f}, 1})));
}

TEST(ObbCircle, InvalidShapesMissEvenWhereTheArithmeticWouldHit) {
    // The shapes are checked only for an answer that would be a hit; these would all be one
    // without the check (a negative radius inside the box, an infinite radius far away, a
    // negative or non-finite half extent or angle around the centre).
    const Obb box{{0, 0}, {2, 1}, 0.3f};
    EXPECT_TRUE(is_miss(collide(box, Circle{{0, 0}, -0.5f})));
    EXPECT_TRUE(is_miss(collide(box, Circle{{100, 0}, INFINITY})));
    EXPECT_TRUE(is_miss(collide(box, Circle{{0, 0}, NAN})));
    EXPECT_TRUE(is_miss(collide(box, Circle{{NAN, 0}, 1})));
    EXPECT_TRUE(is_miss(collide(box, Circle{{INFINITY, 0}, INFINITY})));
    EXPECT_TRUE(is_miss(collide(Obb{{0, 0}, {-2, 1}, 0.3f}, Circle{{0, 0}, 0.5f})));
    EXPECT_TRUE(is_miss(collide(Obb{{0, 0}, {2, INFINITY}, 0.3f}, Circle{{0, 0}, 0.5f})));
    EXPECT_TRUE(is_miss(collide(Obb{{0, 0}, {2, 1}, INFINITY}, Circle{{0, 0}, 0.5f})));
    EXPECT_TRUE(is_miss(collide(Obb{{0, -INFINITY}, {2, 1}, 0.0f}, Circle{{0, 0}, 0.5f})));
    // And the same shapes, valid, hit: centre inside (depth 1 + 0.5 through the y face).
    EXPECT_TRUE(is_hit(collide(Obb{{0, 0}, {2, 1}, 0.0f}, Circle{{0, 0}, 0.5f}), 1.5f, {0, -1}));
}

TEST(ObbCircle, CentreOnAFaceACornerAndSignedZeros) {
    // The clamp (a min then a max) on the boundary: a centre on the face or at a corner is
    // inside (distance 0) and leaves through the nearest face; -0 is the same point as 0.
    const Obb box{{0, 0}, {2, 1}, 0.0f};
    EXPECT_TRUE(is_hit(collide(box, Circle{{2, 0}, 0.5f}), 0.5f, {1, 0}));
    EXPECT_TRUE(is_hit(collide(box, Circle{{2, 1}, 0.5f}), 0.5f, {1, 0}));
    EXPECT_TRUE(is_hit(collide(box, Circle{{-0.0f, -1}, 0.25f}), 0.25f, {0, -1}));
    EXPECT_TRUE(is_hit(collide(box, Circle{{-2, -0.0f}, 0}), 0.0f, {-1, 0}));
    // Just outside the corner along the diagonal: distance sqrt2 / 100.
    EXPECT_TRUE(is_hit(collide(box, Circle{{2.01f, 1.01f}, 0.02f}), 0.02f - 0.01f * kSqrt2, {1 / kSqrt2, 1 / kSqrt2}, 1e-4f));
}

TEST(SegmentCircle, ClosestPointInTheMiddle) {
    // Segment (0,0)-(10,0), circle (4,1) r 2: p = (4,0), |p - c| = 1, depth 1. Normal segment ->
    // circle (0,1). 09-88: the segment's MTD is along p - c = (0,-1), length r - 1 = 1.
    const Manifold m = collide(Segment{{0, 0}, {10, 0}}, Circle{{4, 1}, 2});
    EXPECT_TRUE(is_hit(m, 1.0f, {0, 1}));
    EXPECT_VEC_NEAR(m.mtd(), (Vec2{0, -1}), 1e-6f);
}

TEST(SegmentCircle, BeyondTheEndpoint) {
    // Circle (11,1) r 2: p = (10,0), |p - c| = sqrt2: depth 2 - sqrt2, normal (1,1)/sqrt2.
    EXPECT_TRUE(is_hit(collide(Segment{{0, 0}, {10, 0}}, Circle{{11, 1}, 2}), 2.0f - kSqrt2,
                       {1.0f / kSqrt2, 1.0f / kSqrt2}));
    EXPECT_TRUE(is_miss(collide(Segment{{0, 0}, {10, 0}}, Circle{{11.5f, 1.5f}, 2})));
}

TEST(SegmentCircle, TouchingAndMiss) {
    EXPECT_TRUE(is_hit(collide(Segment{{0, 0}, {10, 0}}, Circle{{4, 2}, 2}), 0.0f, {0, 1}, 0.0f));
    EXPECT_TRUE(is_miss(collide(Segment{{0, 0}, {10, 0}}, Circle{{4, 2.01f}, 2})));
}

TEST(SegmentCircle, CentreOnTheSegment) {
    // p = c: the push is sideways, r = 1 (along the segment it would be 5 or 7).
    const Manifold m = collide(Segment{{0, 0}, {10, 0}}, Circle{{4, 0}, 1});
    EXPECT_TRUE(m.hit);
    EXPECT_FLOAT_EQ(m.depth, 1.0f);
    EXPECT_NEAR(std::fabs(m.normal.y), 1.0f, 1e-6f);
    EXPECT_EQ(m.normal.x, 0.0f);
}

TEST(SegmentCircle, ZeroLengthSegmentAndZeroRadius) {
    // A point segment at (1,1), circle (4,5): distance 5.
    EXPECT_TRUE(is_hit(collide(Segment{{1, 1}, {1, 1}}, Circle{{4, 5}, 5}), 0.0f, {0.6f, 0.8f}, 1e-6f));
    EXPECT_TRUE(is_hit(collide(Segment{{1, 1}, {1, 1}}, Circle{{4, 5}, 6}), 1.0f, {0.6f, 0.8f}));
    EXPECT_TRUE(is_miss(collide(Segment{{1, 1}, {1, 1}}, Circle{{4, 5}, 4.9f})));
    // A zero-radius circle on the segment touches it.
    const Manifold p = collide(Segment{{0, 0}, {10, 0}}, Circle{{3, 0}, 0});
    EXPECT_TRUE(p.hit);
    EXPECT_EQ(p.depth, 0.0f);
    EXPECT_TRUE(test::is_unit(p.normal));
}

TEST(CircleLimits, RadiusWhoseSquareOverflowsIsNoShape) {
    // Found by the collision fuzz target (tests/fuzz/regressions/collision/): a circle at
    // FLT_MAX with radius FLT_MAX against a box: distance^2 and r^2 both overflowed, inf <= inf
    // made it a hit, and the normal came out (0, 0). A radius whose square overflows (above
    // about 1.8e19) is malformed, like a box whose size overflows: a miss, all zeros.
    const float big = std::numeric_limits<float>::max();
    const Aabb box{{-24, 0}, {-24, 1}};
    EXPECT_TRUE(is_miss(collide(Shape{Circle{{big, big}, big}}, Shape{box})));
    EXPECT_TRUE(is_miss(collide(Circle{{0, 0}, 2e19f}, Circle{{1, 0}, 1})));
    EXPECT_FALSE(overlaps(Shape{Circle{{0, 0}, 2e19f}}, Shape{box}));
    // Circle pairs test squared distances themselves: an infinite centre or a distance whose
    // square overflows is a miss even when r^2 overflows too (inf <= inf was a hit).
    EXPECT_TRUE(is_miss(collide(Circle{{-INFINITY, -63999.5f}, 4000}, Circle{{63000.5f, 59000.5f}, 2.5940283e23f})));
    EXPECT_TRUE(is_miss(collide(Circle{{4.2535296e37f, -24}, 4.643608e36f}, Circle{{-23.25f, 1}, 5.75f})));
    // Two radii of FLT_MAX: r1 + r2 was infinite, a hit of infinite depth.
    EXPECT_TRUE(is_miss(collide(Circle{{-7.5f, -24}, big}, Circle{{-23.75f, -8.5f}, big})));
    // 1e19 squares to 1e38: an ordinary (huge) circle.
    EXPECT_TRUE(collide(Shape{Circle{{0, 0}, 1e19f}}, Shape{box}).hit);
}

TEST(CircleLimits, AFarVertexOfASliverWinningARoundingTieDoesNotTurnTheNormal) {
    // Found by the collision fuzz target: a polygon 0.012 px wide and 2e-7 px thick, a circle
    // of radius 10 centred 2 px above it. The squared distances to its vertices round to the
    // same float, the search named a bottom vertex, and the normal came from that vertex's
    // faces, looking away from the circle: the MTD pushed the wrong way (penetration 4 after).
    const std::vector<Vec2> pts = {{-0.004002967f, 2.219268e-08f}, {-0.0006868296f, 5.826877e-10f},
                                   {0.002847403f, 1.05369935e-08f}, {0.005477637f, 4.8895163e-08f},
                                   {0.0063687917f, 1.0347878e-07f}, {0.005237931f, 1.569579e-07f},
                                   {0.0024440975f, 1.9235327e-07f}, {-0.0011256904f, 1.9842716e-07f},
                                   {-0.004338046f, 1.732511e-07f}, {-0.006173071f, 1.2481834e-07f},
                                   {-0.006048158f, 6.850591e-08f}};
    for (int rot = 0; rot < static_cast<int>(pts.size()); ++rot) {  // every grouping of the faces
        std::vector<Vec2> q(pts.begin() + rot, pts.end());
        q.insert(q.end(), pts.begin(), pts.begin() + rot);
        const Polygon sliver = *make_polygon(q, nullptr);
        const Manifold m = collide(sliver, Circle{{1.1754944e-38f, 2}, 10});
        ASSERT_TRUE(m.hit) << rot;
        EXPECT_NEAR(m.depth, 8.0f, 1e-5f) << rot;
        EXPECT_GT(m.normal.y, 0.99f) << rot << ": the circle is pushed up, away from the sliver";
    }
}

TEST(CircleLimits, TwoVerticesFloatCannotTellApartGiveTheContactOfTheOneWhoseConeHoldsIt) {
    // Found by the collision fuzz target (regressions/collision/collide_circle_polygon_coincident_vertices_tie.bin):
    // a quad whose bottom face is 1.8e-41 px long, a circle of radius 10 centred 1.35 px below
    // and right of that corner. Both ends of the face are at the same squared distance; the
    // first won, the direction lies outside its cone (it belongs to the other end's), and the
    // bottom face's normal (0, -1) was taken: the MTD left 0.084 px of overlap. The other end's
    // direction and depth are the contact, from every starting vertex.
    const std::vector<Vec2> pts = {{18.75f, 10}, {0, 18.75f}, {0, -22.75f}, {1.7937e-41f, -22.75f}};
    const Circle c{{0.5f, -24}, 10};
    const Vec2 d = c.center - Vec2{0, -22.75f};
    const Vec2 dir = (1.0f / length(d)) * d;
    for (int rot = 0; rot < static_cast<int>(pts.size()); ++rot) {
        std::vector<Vec2> q(pts.begin() + rot, pts.end());
        q.insert(q.end(), pts.begin(), pts.begin() + rot);
        const Polygon quad = *make_polygon(q, nullptr);
        const Manifold m = collide(quad, c);
        ASSERT_TRUE(m.hit) << rot;
        EXPECT_NEAR(m.depth, 10.0f - length(d), 1e-5f) << rot;
        EXPECT_VEC_NEAR(m.normal, dir, 1e-6f) << rot;
        const Manifold back = collide(c, quad);  // the same contact, the normal from the circle
        ASSERT_TRUE(back.hit) << rot;
        EXPECT_VEC_NEAR(back.normal, -dir, 1e-6f) << rot;
    }
}

TEST(CircleLimits, ADenormalSquaredDistanceStillGivesAUnitNormal) {
    // Found by the collision fuzz target: a circle 5.6e-23 px from a box's face (dist^2 a
    // denormal, whose square root is a few percent off) gave the normal (0, -1.05). Each
    // circle query that divides by that root rescales instead: the exact direction.
    const Aabb box{{608, -5.5638883e-23f}, {1328, -5.563882e-23f}};
    const Manifold m = collide(Shape{Circle{{720, 6.4e-29f}, 80}}, Shape{box});
    ASSERT_TRUE(m.hit);
    EXPECT_EQ(m.normal, (Vec2{0, -1}));  // the box pushed down, out of the circle
    EXPECT_NEAR(m.depth, 80.0f, 1e-4f);
    // The same offsets from a circle, a polygon's vertex and a turned box's corner (d = (3, 4)
    // times 1e-23: the direction (0.6, 0.8)).
    const Vec2 tiny{3e-23f, 4e-23f};
    const Manifold cc = collide(Circle{{0, 0}, 1}, Circle{tiny, 1});
    ASSERT_TRUE(cc.hit);
    EXPECT_TRUE(test::is_unit(cc.normal));
    EXPECT_NEAR(cc.normal.x, 0.6f, 1e-6f);
    EXPECT_NEAR(cc.normal.y, 0.8f, 1e-6f);
    const Polygon tri = *make_polygon(std::vector<Vec2>{{0, 0}, {-10, -1}, {-1, -10}}, nullptr);
    const Manifold pc = collide(tri, Circle{tiny, 1});  // beyond the vertex at the origin, in its region
    ASSERT_TRUE(pc.hit);
    EXPECT_TRUE(test::is_unit(pc.normal));
    EXPECT_NEAR(pc.normal.x, 0.6f, 1e-6f);
    EXPECT_NEAR(pc.normal.y, 0.8f, 1e-6f);
    const Manifold bc = collide(Aabb{{-2, -2}, {0, 0}}, Circle{tiny, 1});  // beyond the corner
    ASSERT_TRUE(bc.hit);
    EXPECT_NEAR(bc.normal.x, 0.6f, 1e-6f);
    EXPECT_NEAR(bc.normal.y, 0.8f, 1e-6f);
    const Manifold oc = collide(Obb{{-1, -1}, {1, 1}, 0.0f}, Circle{tiny, 1});
    ASSERT_TRUE(oc.hit);
    EXPECT_TRUE(test::is_unit(oc.normal));
}

}  // namespace
}  // namespace jostle
