// Cast tests (cast.cpp, slide 09-103): a bullet as a segment from its last to its next
// position against circles, boxes, polygons and segments; first contact t, point and normal.
#include <gtest/gtest.h>

#include <cmath>

#include "test_shapes.h"

namespace jostle {
namespace {

using test::is_miss;
using test::kPi;
using test::kSqrt2;
using test::is_cast;


const Circle kCircle{{0, 0}, 2};
const Aabb kBox{{0, 0}, {2, 2}};

TEST(CastCircle, HeadOn) {
    // (-5,0) -> (5,0), r 2 at the origin: first contact at x = -2, t = 3/10.
    EXPECT_TRUE(is_cast(cast({-5, 0}, {5, 0}, kCircle), 0.3f, {-2, 0}, {-1, 0}));
    // From below-right along a 3-4-5 line: (6,8) -> (0,0) hits (1.2,1.6) at t = (10-2)/10 = 0.8,
    // normal (0.6,0.8).
    EXPECT_TRUE(is_cast(cast({6, 8}, {0, 0}, kCircle), 0.8f, {1.2f, 1.6f}, {0.6f, 0.8f}));
}

TEST(CastCircle, OffCentreChord) {
    // (-5,1) -> (5,1): enters where x^2 + 1 = 4, x = -sqrt3; t = (5 - sqrt3)/10 = 0.32679;
    // normal (-sqrt3, 1)/2.
    const float s3 = std::sqrt(3.0f);
    EXPECT_TRUE(is_cast(cast({-5, 1}, {5, 1}, kCircle), (5 - s3) / 10, {-s3, 1}, {-s3 / 2, 0.5f}));
}

TEST(CastCircle, StartingInside) {
    const CastHit h = cast({0.5f, 0}, {5, 0}, kCircle);
    EXPECT_TRUE(h.hit);
    EXPECT_EQ(h.t, 0.0f);
    EXPECT_EQ(h.point, (Vec2{0.5f, 0}));
    EXPECT_EQ(h.normal, (Vec2{0, 0}));
    // Ending inside as well.
    const CastHit g = cast({0.5f, 0}, {-0.5f, 0}, kCircle);
    EXPECT_TRUE(g.hit);
    EXPECT_EQ(g.t, 0.0f);
    EXPECT_EQ(g.point, (Vec2{0.5f, 0}));
    EXPECT_EQ(g.normal, (Vec2{0, 0}));
}

TEST(CastCircle, StartingOnTheBoundary) {
    // On the boundary: t = 0, point = from, normal the outward normal there.
    EXPECT_TRUE(is_cast(cast({-2, 0}, {5, 0}, kCircle), 0.0f, {-2, 0}, {-1, 0}));
    // Moving away from it still starts on the shape.
    EXPECT_TRUE(is_cast(cast({-2, 0}, {-5, 0}, kCircle), 0.0f, {-2, 0}, {-1, 0}));
}

TEST(CastCircle, MissesAndShortSegments) {
    EXPECT_TRUE(is_miss(cast({-5, 2.01f}, {5, 2.01f}, kCircle)));
    EXPECT_TRUE(is_miss(cast({-5, 0}, {-10, 0}, kCircle)));  // pointing away
    EXPECT_TRUE(is_miss(cast({-5, 0}, {-3, 0}, kCircle)));   // stops short
    // Ending exactly on the circle: t = 1.
    EXPECT_TRUE(is_cast(cast({-5, 0}, {-2, 0}, kCircle), 1.0f, {-2, 0}, {-1, 0}));
}

TEST(CastCircle, Tangent) {
    // (-5,2) -> (5,2) grazes the circle's lowest point (0,2) (y down). With d = (10,0),
    // f = from - c = (-5,2): a = 100, b = 2 f.d = -100, c = 25 + 4 - 4 = 25, discriminant 0:
    // touching at t = 0.5, normal (0,1).
    EXPECT_TRUE(is_cast(cast({-5, 2}, {5, 2}, kCircle), 0.5f, {0, 2}, {0, 1}, 1e-4f));
}

TEST(CastCircle, ZeroLengthSegment) {
    EXPECT_TRUE(is_miss(cast({5, 5}, {5, 5}, kCircle)));
    const CastHit in = cast({1, 1}, {1, 1}, kCircle);
    EXPECT_TRUE(in.hit);
    EXPECT_EQ(in.t, 0.0f);
    EXPECT_EQ(in.point, (Vec2{1, 1}));
    EXPECT_EQ(in.normal, (Vec2{0, 0}));
    EXPECT_TRUE(is_cast(cast({0, 2}, {0, 2}, kCircle), 0.0f, {0, 2}, {0, 1}));
}

TEST(CastCircle, ZeroRadius) {
    // A point target on the path: hit at the point itself.
    const CastHit h = cast({-5, 0}, {5, 0}, Circle{{1, 0}, 0});
    EXPECT_TRUE(h.hit);
    EXPECT_NEAR(h.t, 0.6f, 1e-5f);
    EXPECT_VEC_NEAR(h.point, (Vec2{1, 0}), 1e-5f);
    EXPECT_TRUE(is_miss(cast({-5, 0.5f}, {5, 0.5f}, Circle{{1, 0}, 0})));
}

TEST(CastAabb, FacesAndNormals) {
    // Box [0,2]^2. From the left at y = 1: t = 2/4, point (0,1), normal (-1,0).
    EXPECT_TRUE(is_cast(cast({-2, 1}, {2, 1}, kBox), 0.5f, {0, 1}, {-1, 0}));
    // From above (y down: smaller y): (1,-4) -> (1,4): t = 4/8, point (1,0), normal (0,-1).
    EXPECT_TRUE(is_cast(cast({1, -4}, {1, 4}, kBox), 0.5f, {1, 0}, {0, -1}));
    // From the right and from below.
    EXPECT_TRUE(is_cast(cast({6, 1.5f}, {1, 1.5f}, kBox), 0.8f, {2, 1.5f}, {1, 0}));
    EXPECT_TRUE(is_cast(cast({0.5f, 4}, {0.5f, 0}, kBox), 0.5f, {0.5f, 2}, {0, 1}));
    // Slanted: (-1,0) -> (3,2) enters x = 0 at t = 1/4, y = 0.5.
    EXPECT_TRUE(is_cast(cast({-1, 0}, {3, 2}, kBox), 0.25f, {0, 0.5f}, {-1, 0}));
}

TEST(CastAabb, MissesAndEdges) {
    EXPECT_TRUE(is_miss(cast({-2, 3}, {4, 3}, kBox)));
    EXPECT_TRUE(is_miss(cast({-2, 1}, {-1, 1}, kBox)));
    EXPECT_TRUE(is_miss(cast({-2, 1}, {-4, 1}, kBox)));
    // Slanted ray passing the corner (0,2) on y = x + 2.1, though its bounds overlap the box.
    EXPECT_TRUE(is_miss(cast({-1, 1.1f}, {3, 5.1f}, kBox)));
    // Grazing along the top face y = 0: touches (0,0) at t = 2/6.
    const CastHit g = cast({-2, 0}, {4, 0}, kBox);
    EXPECT_TRUE(g.hit);
    EXPECT_NEAR(g.t, 1.0f / 3.0f, 1e-5f);
    EXPECT_VEC_NEAR(g.point, (Vec2{0, 0}), 1e-5f);
    EXPECT_TRUE(test::is_unit(g.normal));
    EXPECT_LE(dot(g.normal, Vec2{1, 0}), 0.0f);
    // Through the corner diagonally: touches (0,0) at t = 0.5.
    const CastHit c = cast({-1, -1}, {1, 1}, kBox);
    EXPECT_TRUE(c.hit);
    EXPECT_NEAR(c.t, 0.5f, 1e-5f);
    EXPECT_VEC_NEAR(c.point, (Vec2{0, 0}), 1e-5f);
    EXPECT_TRUE(test::is_unit(c.normal));
    EXPECT_LT(dot(c.normal, Vec2{1, 1}), 0.0f);
}

TEST(CastAabb, StartingInsideAndOnTheBoundary) {
    const CastHit in = cast({1, 1}, {5, 1}, kBox);
    EXPECT_TRUE(in.hit);
    EXPECT_EQ(in.t, 0.0f);
    EXPECT_EQ(in.point, (Vec2{1, 1}));
    EXPECT_EQ(in.normal, (Vec2{0, 0}));
    EXPECT_TRUE(is_cast(cast({0, 1}, {2, 1}, kBox), 0.0f, {0, 1}, {-1, 0}));
    EXPECT_TRUE(is_cast(cast({0, 1}, {-2, 1}, kBox), 0.0f, {0, 1}, {-1, 0}));
    EXPECT_TRUE(is_cast(cast({1, 2}, {1, 7}, kBox), 0.0f, {1, 2}, {0, 1}));
}

TEST(CastAabb, ZeroLengthSegment) {
    EXPECT_TRUE(is_miss(cast({3, 3}, {3, 3}, kBox)));
    const CastHit in = cast({1, 1}, {1, 1}, kBox);
    EXPECT_TRUE(in.hit);
    EXPECT_EQ(in.t, 0.0f);
    EXPECT_EQ(in.normal, (Vec2{0, 0}));
}

TEST(CastAabb, ZeroSizeBox) {
    // A point box at (1,0) on the path (-5,0) -> (5,0): t = 0.6.
    const CastHit h = cast({-5, 0}, {5, 0}, Aabb{{1, 0}, {1, 0}});
    EXPECT_TRUE(h.hit);
    EXPECT_NEAR(h.t, 0.6f, 1e-6f);
    EXPECT_VEC_NEAR(h.point, (Vec2{1, 0}), 1e-6f);
}

TEST(CastObb, DiamondFace) {
    // Half 1 at 45 deg: its face with normal (-1,-1)/sqrt2 is 1 from the centre, crossed by the
    // diagonal at (-1/sqrt2, -1/sqrt2). (-3,-3) -> (3,3): t = (3 - 1/sqrt2)/6 = 0.38215.
    const Obb d{{0, 0}, {1, 1}, kPi / 4};
    const float k = 1 / kSqrt2;
    EXPECT_TRUE(is_cast(cast({-3, -3}, {3, 3}, d), (3 - k) / 6, {-k, -k}, {-k, -k}));
    EXPECT_TRUE(is_miss(cast({-3, -3}, {-1, -1}, d)));
    // Through the left vertex (-sqrt2, 0) along y = 0: t = (5 - sqrt2)/10.
    const CastHit v = cast({-5, 0}, {5, 0}, d);
    EXPECT_TRUE(v.hit);
    EXPECT_NEAR(v.t, (5 - kSqrt2) / 10, 1e-5f);
    EXPECT_VEC_NEAR(v.point, (Vec2{-kSqrt2, 0}), 1e-4f);
    EXPECT_TRUE(test::is_unit(v.normal));
    EXPECT_LT(v.normal.x, 0.0f);
}

TEST(CastObb, TranslatedAxisAligned) {
    // Centre (10,5), half (2,1), angle 0: x in [8,12]. (0,5) -> (20,5): t = 8/20.
    EXPECT_TRUE(is_cast(cast({0, 5}, {20, 5}, Obb{{10, 5}, {2, 1}, 0.0f}), 0.4f, {8, 5}, {-1, 0}));
    const CastHit in = cast({10, 5}, {20, 5}, Obb{{10, 5}, {2, 1}, 0.0f});
    EXPECT_TRUE(in.hit);
    EXPECT_EQ(in.t, 0.0f);
    EXPECT_EQ(in.normal, (Vec2{0, 0}));
}

TEST(CastPolygon, Hypotenuse) {
    // Triangle (0,0),(4,0),(0,4); (5,5) -> (0,0) meets x + y = 4 at (2,2), t = 3/5, normal (1,1)/sqrt2.
    const Polygon tri = test::polygon_or_die({{0, 0}, {4, 0}, {0, 4}});
    const float k = 1 / kSqrt2;
    EXPECT_TRUE(is_cast(cast({5, 5}, {0, 0}, tri), 0.6f, {2, 2}, {k, k}));
    // From the left at y = 1: x = 0 at t = 2/4.
    EXPECT_TRUE(is_cast(cast({-2, 1}, {2, 1}, tri), 0.5f, {0, 1}, {-1, 0}));
    EXPECT_TRUE(is_miss(cast({5, 5}, {3, 3}, tri)));
    EXPECT_TRUE(is_miss(cast({-1, 5}, {5, -1}, test::polygon_or_die({{0, 0}, {2, 0}, {0, 2}}))));
    const CastHit in = cast({1, 1}, {9, 9}, tri);
    EXPECT_TRUE(in.hit);
    EXPECT_EQ(in.t, 0.0f);
    EXPECT_EQ(in.point, (Vec2{1, 1}));
    EXPECT_EQ(in.normal, (Vec2{0, 0}));
    EXPECT_TRUE(is_cast(cast({2, 0}, {2, -5}, tri), 0.0f, {2, 0}, {0, -1}));
}

TEST(CastPolygon, StartOnTheBoundaryNonFiniteAndParallel) {
    // Square (0,0)-(4,4) as a polygon. A start on a vertex lies on two edges: the first of them
    // in the polygon's order gives the normal, whichever way the bullet goes.
    const Polygon sq = test::box_polygon(0, 0, 4, 4);
    const CastHit corner = cast({4, 4}, {9, 9}, sq);
    EXPECT_TRUE(corner.hit);
    EXPECT_EQ(corner.t, 0.0f);
    int first_on = -1;
    for (int i = 0; i < sq.count() && first_on < 0; ++i)
        if (dot(sq.normals()[i], sq.points()[i] - Vec2{4, 4}) == 0.0f) first_on = i;
    ASSERT_GE(first_on, 0);
    EXPECT_EQ(corner.normal, sq.normals()[first_on]);
    EXPECT_TRUE(is_cast(cast({4, 2}, {9, 2}, sq), 0.0f, {4, 2}, {1, 0}));
    // The last edge is the one it starts on.
    EXPECT_TRUE(is_cast(cast({0, 2}, {-3, 2}, sq), 0.0f, {0, 2}, {-1, 0}));
    // Parallel to an edge: outside it a miss, along it a hit at the corner.
    EXPECT_TRUE(is_miss(cast({-1, 5}, {9, 5}, sq)));
    EXPECT_TRUE(is_cast(cast({-2, 4}, {2, 4}, sq), 0.5f, {0, 4}, {-1, 0}));
    // Non-finite motion is a miss even where the arithmetic would say "inside" or "hit".
    EXPECT_TRUE(is_miss(cast({NAN, 2}, {2, 2}, sq)));
    EXPECT_TRUE(is_miss(cast({2, 2}, {NAN, 2}, sq)));
    EXPECT_TRUE(is_miss(cast({-INFINITY, 2}, {2, 2}, sq)));
    EXPECT_TRUE(is_miss(cast({-3e38f, 2}, {3e38f, 2}, sq)));  // the motion overflows
    EXPECT_TRUE(is_miss(cast({1, 1}, {2, 2}, Polygon{})));
}

TEST(CastSegment, CrossingAndParallel) {
    // Wall (0,-1)-(0,1); (-2,0) -> (2,0): t = 0.5, point (0,0), normal facing the bullet (-1,0).
    const Segment wall{{0, -1}, {0, 1}};
    EXPECT_TRUE(is_cast(cast({-2, 0}, {2, 0}, wall), 0.5f, {0, 0}, {-1, 0}));
    EXPECT_TRUE(is_cast(cast({3, 0.5f}, {-1, 0.5f}, wall), 0.75f, {0, 0.5f}, {1, 0}));
    EXPECT_TRUE(is_miss(cast({-2, 1.5f}, {2, 1.5f}, wall)));
    EXPECT_TRUE(is_miss(cast({-2, 0}, {-1, 0}, wall)));
    // Parallel beside it.
    EXPECT_TRUE(is_miss(cast({1, -5}, {1, 5}, wall)));
    // Hitting the end point exactly: (-2,1) -> (2,1) passes through (0,1) at t = 0.5.
    const CastHit e = cast({-2, 1}, {2, 1}, wall);
    EXPECT_TRUE(e.hit);
    EXPECT_NEAR(e.t, 0.5f, 1e-6f);
    EXPECT_VEC_NEAR(e.point, (Vec2{0, 1}), 1e-6f);
}

TEST(CastSegment, CollinearAlongTheWall) {
    // Along the wall's own line from (0,-5): first touches the end (0,-1) at t = 4/10.
    const CastHit h = cast({0, -5}, {0, 5}, Segment{{0, -1}, {0, 1}});
    EXPECT_TRUE(h.hit);
    EXPECT_NEAR(h.t, 0.4f, 1e-6f);
    EXPECT_VEC_NEAR(h.point, (Vec2{0, -1}), 1e-6f);
    EXPECT_TRUE(test::is_unit(h.normal));
    EXPECT_TRUE(is_miss(cast({0, -5}, {0, -2}, Segment{{0, -1}, {0, 1}})));
}

TEST(CastSegment, StartingOnAndZeroLength) {
    // A wall has no inside: a start on it is on a face and takes the wall's normal, on the
    // side against the motion (the side it leaves from) when the motion crosses it.
    const CastHit s = cast({0, 0}, {2, 0}, Segment{{0, -1}, {0, 1}});
    EXPECT_TRUE(s.hit);
    EXPECT_EQ(s.t, 0.0f);
    EXPECT_EQ(s.point, (Vec2{0, 0}));
    EXPECT_EQ(s.normal, (Vec2{-1, 0}));
    EXPECT_EQ(cast({0, 0}, {-2, 0}, Segment{{0, -1}, {0, 1}}).normal, (Vec2{1, 0}));
    // Along the wall from on it (or from its end), either side's normal, never none.
    for (const Vec2 from : {Vec2{0, 0}, Vec2{0, 1}, Vec2{0, -1}}) {
        const CastHit along = cast(from, from + Vec2{0, 3}, Segment{{0, -1}, {0, 1}});
        EXPECT_TRUE(along.hit);
        EXPECT_EQ(along.t, 0.0f);
        EXPECT_EQ(along.point, from);
        EXPECT_EQ(std::fabs(along.normal.x), 1.0f);
        EXPECT_EQ(along.normal.y, 0.0f);
    }
    // A zero-length bullet on the wall hits at t = 0 (with the wall's normal); off the wall misses.
    const CastHit z = cast({0, 0.5f}, {0, 0.5f}, Segment{{0, -1}, {0, 1}});
    EXPECT_TRUE(z.hit);
    EXPECT_EQ(z.t, 0.0f);
    EXPECT_EQ(std::fabs(z.normal.x), 1.0f);
    EXPECT_EQ(z.normal.y, 0.0f);
    EXPECT_TRUE(is_miss(cast({1, 0}, {1, 0}, Segment{{0, -1}, {0, 1}})));
    // A zero-length wall (a point) crossed by the bullet.
    const CastHit p = cast({-2, 0}, {2, 0}, Segment{{1, 0}, {1, 0}});
    EXPECT_TRUE(p.hit);
    EXPECT_NEAR(p.t, 0.75f, 1e-6f);
}

TEST(CastThinWall, OnePixelWallAtVeryHighSpeedIsHit) {
    // 1-px wall at x in [100,101]; the bullet moves 1e5 px in one frame: t = 100/1e5 = 0.001.
    const Vec2 from{0, 500};
    const Vec2 to{100000, 500};
    const float t = 100.0f / 100000.0f;
    EXPECT_TRUE(is_cast(cast(from, to, Aabb{{100, 0}, {101, 1000}}), t, {100, 500}, {-1, 0}, 1e-6f, 1e-2f));
    EXPECT_TRUE(is_cast(cast(from, to, Obb{{100.5f, 500}, {0.5f, 500}, 0.0f}), t, {100, 500}, {-1, 0}, 1e-6f, 1e-2f));
    EXPECT_TRUE(is_cast(cast(from, to, test::box_polygon(100, 0, 101, 1000)), t, {100, 500}, {-1, 0}, 1e-6f, 1e-2f));
    EXPECT_TRUE(is_cast(cast(from, to, Segment{{100, 0}, {100, 1000}}), t, {100, 500}, {-1, 0}, 1e-6f, 1e-2f));
    EXPECT_TRUE(is_cast(cast(from, to, Circle{{100.5f, 500}, 0.5f}), t, {100, 500}, {-1, 0}, 1e-6f, 1e-2f));
    // A wall of zero thickness as a box.
    const CastHit z = cast(from, to, Aabb{{100, 0}, {100, 1000}});
    EXPECT_TRUE(z.hit);
    EXPECT_NEAR(z.t, t, 1e-6f);
    // Coming back the other way: first contact at x = 101, t = (1e5 - 101)/1e5.
    const CastHit back = cast(to, from, Aabb{{100, 0}, {101, 1000}});
    EXPECT_TRUE(back.hit);
    EXPECT_NEAR(back.t, (100000.0f - 101.0f) / 100000.0f, 1e-6f);
    EXPECT_VEC_NEAR(back.normal, (Vec2{1, 0}), 1e-6f);
}

TEST(CastSegment, MotionWhoseSquaredLengthOverflowsIsAMiss) {
    // Found by the collision fuzz target (tests/fuzz/regressions/collision/): a cast 1.7e38 long
    // along a point segment's line; dot(r, r) overflowed and t = inf / inf was NaN, reported as
    // a hit. A motion whose squared length overflows is no motion (as a Segment's is no shape).
    const Segment dot_at_end{{-24, -24}, {-24, -24}};
    EXPECT_TRUE(test::is_miss(cast({-1.70141183e38f, -24}, {-24, -24}, dot_at_end)));
    EXPECT_TRUE(test::is_miss(cast({-1e20f, 0}, {0, 0}, Aabb{{-1, -1}, {1, 1}})));
    // Just below the limit it is an ordinary cast.
    const CastHit h = cast({-1e19f, 0}, {0, 0}, Aabb{{-1, -1}, {1, 1}});
    EXPECT_TRUE(h.hit);
    EXPECT_EQ(h.point.y, 0.0f);
}

TEST(CastShape, DispatchesToTheShape) {
    EXPECT_TRUE(is_cast(cast({-5, 0}, {5, 0}, Shape{kCircle}), 0.3f, {-2, 0}, {-1, 0}));
    EXPECT_TRUE(is_cast(cast({-2, 1}, {2, 1}, Shape{kBox}), 0.5f, {0, 1}, {-1, 0}));
    EXPECT_TRUE(is_cast(cast({-2, 0}, {2, 0}, Shape{Segment{{0, -1}, {0, 1}}}), 0.5f, {0, 0}, {-1, 0}));
    EXPECT_TRUE(is_cast(cast({0, 5}, {20, 5}, Shape{Obb{{10, 5}, {2, 1}, 0.0f}}), 0.4f, {8, 5}, {-1, 0}));
    EXPECT_TRUE(is_cast(cast({-2, 1}, {2, 1}, Shape{test::box_polygon(0, 0, 2, 2)}), 0.5f, {0, 1}, {-1, 0}));
    EXPECT_TRUE(is_miss(cast({-5, 9}, {5, 9}, Shape{kCircle})));
}

}  // namespace
}  // namespace jostle
