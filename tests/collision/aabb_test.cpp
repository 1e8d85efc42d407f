// AABB tests (aabb.cpp, slides 09-6 to 09-34): translation, rotated bounds (box of the
// corners and tight bounds of model points), overlap, intersection region and the per-axis MTD.
#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "test_shapes.h"

namespace jostle {
namespace {

using test::kPi;
using test::kSqrt2;

TEST(AabbTranslate, MovesMinAndMax) {
    // 09-10: [1,2]-[3,5] + (10,-1) = [11,1]-[13,4].
    const Aabb b = translate(Aabb{{1, 2}, {3, 5}}, {10, -1});
    EXPECT_EQ(b.min, (Vec2{11, 1}));
    EXPECT_EQ(b.max, (Vec2{13, 4}));
}

TEST(AabbCorners, InPolygonOrder) {
    const auto c = corners(Aabb{{1, 2}, {3, 5}});
    EXPECT_EQ(c[0], (Vec2{1, 2}));
    EXPECT_EQ(c[1], (Vec2{3, 2}));
    EXPECT_EQ(c[2], (Vec2{3, 5}));
    EXPECT_EQ(c[3], (Vec2{1, 5}));
}

TEST(AabbRotatedBounds, TwoByTwoBoxAt45DegreesHasHalfDiagonalSqrt2) {
    // Corners (+-1, +-1) rotated 45 deg about the origin land on the axes at distance sqrt2.
    const Aabb b = rotated_bounds(Aabb{{-1, -1}, {1, 1}}, kPi / 4, {0, 0});
    EXPECT_VEC_NEAR(b.min, (Vec2{-kSqrt2, -kSqrt2}), 1e-5f);
    EXPECT_VEC_NEAR(b.max, (Vec2{kSqrt2, kSqrt2}), 1e-5f);
}

TEST(AabbRotatedBounds, AboutAPivotOffTheBox) {
    // [0,2]x[0,2] turned 90 deg (+x toward +y: (x,y) -> (-y,x)) about the origin:
    // (0,0)->(0,0), (2,0)->(0,2), (2,2)->(-2,2), (0,2)->(-2,0): bounds [-2,0]-[0,2].
    const Aabb b = rotated_bounds(Aabb{{0, 0}, {2, 2}}, kPi / 2, {0, 0});
    EXPECT_VEC_NEAR(b.min, (Vec2{-2, 0}), 1e-5f);
    EXPECT_VEC_NEAR(b.max, (Vec2{0, 2}), 1e-5f);
    // The same box about its own centre (1,1): a square stays the same square.
    const Aabb c = rotated_bounds(Aabb{{0, 0}, {2, 2}}, kPi / 2, {1, 1});
    EXPECT_VEC_NEAR(c.min, (Vec2{0, 0}), 1e-5f);
    EXPECT_VEC_NEAR(c.max, (Vec2{2, 2}), 1e-5f);
    // 180 deg about (3,0): x -> 6 - x, y -> -y: [4,6]x[-2,0].
    const Aabb d = rotated_bounds(Aabb{{0, 0}, {2, 2}}, kPi, {3, 0});
    EXPECT_VEC_NEAR(d.min, (Vec2{4, -2}), 1e-5f);
    EXPECT_VEC_NEAR(d.max, (Vec2{6, 0}), 1e-5f);
}

TEST(AabbRotatedBounds, ZeroAngleIsIdentity) {
    const Aabb b = rotated_bounds(Aabb{{-3, 1}, {4, 7}}, 0.0f, {10, 10});
    EXPECT_EQ(b.min, (Vec2{-3, 1}));
    EXPECT_EQ(b.max, (Vec2{4, 7}));
}

TEST(AabbRotatedBounds, TightBoundsOfModelPointsAreSmallerThanBoxOfBox) {
    // Triangle (0,0),(2,0),(0,2) turned 45 deg about the origin:
    // (0,0)->(0,0), (2,0)->(sqrt2, sqrt2), (0,2)->(-sqrt2, sqrt2): tight [-sqrt2,0]-[sqrt2,sqrt2].
    const std::array<Vec2, 3> tri{{{0, 0}, {2, 0}, {0, 2}}};
    const Aabb tight = rotated_bounds(std::span<const Vec2>(tri), kPi / 4, {0, 0});
    EXPECT_VEC_NEAR(tight.min, (Vec2{-kSqrt2, 0}), 1e-5f);
    EXPECT_VEC_NEAR(tight.max, (Vec2{kSqrt2, kSqrt2}), 1e-5f);
    // The triangle's box [0,2]^2 turned the same way also has corner (2,2)->(0, 2 sqrt2):
    // box-of-box [-sqrt2,0]-[sqrt2, 2 sqrt2], twice as tall.
    const Aabb loose = rotated_bounds(Aabb{{0, 0}, {2, 2}}, kPi / 4, {0, 0});
    EXPECT_VEC_NEAR(loose.min, (Vec2{-kSqrt2, 0}), 1e-5f);
    EXPECT_VEC_NEAR(loose.max, (Vec2{kSqrt2, 2 * kSqrt2}), 1e-5f);
    EXPECT_LT(tight.max.y - tight.min.y, loose.max.y - loose.min.y - 1.0f);
}

TEST(AabbRotatedBounds, TightBoundsAboutPivot) {
    // Points (1,0),(3,0) turned 90 deg about (1,0): (1,0)->(1,0), (3,0)->(1,2).
    const std::array<Vec2, 2> pts{{{1, 0}, {3, 0}}};
    const Aabb b = rotated_bounds(std::span<const Vec2>(pts), kPi / 2, {1, 0});
    EXPECT_VEC_NEAR(b.min, (Vec2{1, 0}), 1e-5f);
    EXPECT_VEC_NEAR(b.max, (Vec2{1, 2}), 1e-5f);
}

TEST(AabbOverlaps, SeparatedTouchingAndOverlapping) {
    const Aabb a{{0, 0}, {1, 1}};
    EXPECT_TRUE(overlaps(a, Aabb{{0.5f, 0.5f}, {2, 2}}));
    EXPECT_TRUE(overlaps(a, Aabb{{1, 0}, {2, 1}}));   // shared right edge: touching counts
    EXPECT_TRUE(overlaps(a, Aabb{{0, 1}, {1, 2}}));   // shared bottom edge
    EXPECT_TRUE(overlaps(a, Aabb{{1, 1}, {2, 2}}));   // shared corner
    EXPECT_TRUE(overlaps(a, Aabb{{-1, -1}, {0, 0}}));  // shared corner, other side
    EXPECT_FALSE(overlaps(a, Aabb{{1.001f, 0}, {2, 1}}));
    EXPECT_FALSE(overlaps(a, Aabb{{-2, 0}, {-0.001f, 1}}));
    EXPECT_FALSE(overlaps(a, Aabb{{0, 1.001f}, {1, 2}}));
    EXPECT_FALSE(overlaps(a, Aabb{{0, -2}, {1, -0.001f}}));
    // Overlap on x alone is not enough (09-23 needs all four tests).
    EXPECT_FALSE(overlaps(a, Aabb{{0, 5}, {1, 6}}));
    EXPECT_TRUE(overlaps(a, a));
    EXPECT_TRUE(overlaps(Aabb{{-10, -10}, {10, 10}}, a));  // containment
}

TEST(AabbIntersection, RegionIsMaxOfMinsAndMinOfMaxes) {
    // 09-28: [0,0]-[4,3] and [2,1]-[6,5]: (max(0,2), max(0,1)) - (min(4,6), min(3,5)) = [2,1]-[4,3].
    const auto r = intersection(Aabb{{0, 0}, {4, 3}}, Aabb{{2, 1}, {6, 5}});
    ASSERT_TRUE(r.has_value());
    EXPECT_EQ(r->min, (Vec2{2, 1}));
    EXPECT_EQ(r->max, (Vec2{4, 3}));
    // Containment: the small box itself.
    const auto c = intersection(Aabb{{0, 0}, {10, 10}}, Aabb{{1, 4}, {3, 6}});
    ASSERT_TRUE(c.has_value());
    EXPECT_EQ(c->min, (Vec2{1, 4}));
    EXPECT_EQ(c->max, (Vec2{3, 6}));
    // Touching: a zero-width region on the shared edge.
    const auto t = intersection(Aabb{{0, 0}, {1, 1}}, Aabb{{1, 0}, {2, 1}});
    ASSERT_TRUE(t.has_value());
    EXPECT_EQ(t->min, (Vec2{1, 0}));
    EXPECT_EQ(t->max, (Vec2{1, 1}));
    EXPECT_FALSE(intersection(Aabb{{0, 0}, {1, 1}}, Aabb{{1.001f, 0}, {2, 1}}).has_value());
    EXPECT_FALSE(intersection(Aabb{{0, 0}, {1, 1}}, Aabb{{0, 3}, {1, 4}}).has_value());
}

TEST(AabbCollide, MtdAlongTheSmallerPush) {
    // A=[0,10]^2, B=[8,12]x[2,4]. Pushes of A: x: left 10-8=2, right 12-0=12 -> 2;
    // y: up 10-2=8, down 4-0=4 -> 4. Smallest: 2 to the left, mtd = (-2,0) = -2 * (1,0).
    const Manifold m = collide(Aabb{{0, 0}, {10, 10}}, Aabb{{8, 2}, {12, 4}});
    EXPECT_TRUE(test::is_hit(m, 2.0f, {1, 0}));
    EXPECT_VEC_NEAR(m.mtd(), (Vec2{-2, 0}), 1e-6f);
}

TEST(AabbCollide, MtdAlongY) {
    // A=[0,4]x[0,4], B=[1,3]x[3,9]: x pushes min(4-1, 3-0) = 3; y pushes min(4-3, 9-0) = 1:
    // A moves up by 1, mtd (0,-1), normal (0,1).
    const Manifold m = collide(Aabb{{0, 0}, {4, 4}}, Aabb{{1, 3}, {3, 9}});
    EXPECT_TRUE(test::is_hit(m, 1.0f, {0, 1}));
    // Reverse order: B must move down by 1, normal (0,-1).
    EXPECT_TRUE(test::is_hit(collide(Aabb{{1, 3}, {3, 9}}, Aabb{{0, 0}, {4, 4}}), 1.0f, {0, -1}));
}

TEST(AabbCollide, ContainmentUsesTheSmallestPushNotTheIntersectionWidth) {
    // Big A=[0,10]^2 contains small B=[1,3]x[4,6]; the intersection is B, 2 wide and 2 tall
    // (the slide's "minimum dimension of the intersection" would say 2). A must actually move:
    // right until A.min.x = 3 (3), left until A.max.x = 1 (9), down to 6 (6), up to 4 (6):
    // the smallest is 3 to the right, mtd = (3,0) = -3 * (-1,0).
    const Aabb big{{0, 0}, {10, 10}};
    const Aabb small{{1, 4}, {3, 6}};
    const Manifold m = collide(big, small);
    EXPECT_TRUE(test::is_hit(m, 3.0f, {-1, 0}));
    EXPECT_VEC_NEAR(m.mtd(), (Vec2{3, 0}), 1e-6f);
    // B the first argument: B moves left by 3 (B.max.x = 0), normal (1,0).
    EXPECT_TRUE(test::is_hit(collide(small, big), 3.0f, {1, 0}));
    // After the push they only touch.
    const Manifold after = collide(translate(big, m.mtd()), small);
    EXPECT_TRUE(after.hit);
    EXPECT_EQ(after.depth, 0.0f);
}

TEST(AabbCollide, TouchingIsAHitWithDepthZero) {
    const Manifold m = collide(Aabb{{0, 0}, {1, 1}}, Aabb{{1, 0}, {2, 1}});
    EXPECT_TRUE(test::is_hit(m, 0.0f, {1, 0}, 0.0f));
    const Manifold below = collide(Aabb{{0, 0}, {1, 1}}, Aabb{{0, 1}, {1, 2}});
    EXPECT_TRUE(test::is_hit(below, 0.0f, {0, 1}, 0.0f));
}

TEST(AabbCollide, SeparatedIsAMissWithZeros) {
    EXPECT_TRUE(test::is_miss(collide(Aabb{{0, 0}, {1, 1}}, Aabb{{1.001f, 0}, {2, 1}})));
    EXPECT_TRUE(test::is_miss(collide(Aabb{{0, 0}, {1, 1}}, Aabb{{5, 5}, {6, 6}})));
}

TEST(AabbCollide, CoincidentBoxesHaveADefinedNormal) {
    // Identical [0,2]x[0,4]: pushes are 2 on x and 4 on y; depth 2 along +-x.
    const Aabb a{{0, 0}, {2, 4}};
    const Manifold m = collide(a, a);
    EXPECT_TRUE(m.hit);
    EXPECT_FLOAT_EQ(m.depth, 2.0f);
    EXPECT_TRUE(test::is_unit(m.normal));
    EXPECT_EQ(m.normal.y, 0.0f);
    // A square: depth = side, along some axis, never NaN.
    const Manifold s = collide(Aabb{{3, 3}, {5, 5}}, Aabb{{3, 3}, {5, 5}});
    EXPECT_TRUE(s.hit);
    EXPECT_FLOAT_EQ(s.depth, 2.0f);
    EXPECT_TRUE(test::is_unit(s.normal));
    EXPECT_TRUE(s.normal.x == 0.0f || s.normal.y == 0.0f);
}

TEST(AabbCollide, ZeroSizeBoxes) {
    // A point box at (1,2) inside [0,4]^2: it must move left 1 (to x=0): normal (1,0)
    // (x: min(1-0, 4-1) = 1; y: min(2-0, 4-2) = 2).
    EXPECT_TRUE(test::is_hit(collide(Aabb{{1, 2}, {1, 2}}, Aabb{{0, 0}, {4, 4}}), 1.0f, {1, 0}));
    // Two equal point boxes touch.
    const Manifold p = collide(Aabb{{1, 1}, {1, 1}}, Aabb{{1, 1}, {1, 1}});
    EXPECT_TRUE(p.hit);
    EXPECT_EQ(p.depth, 0.0f);
    EXPECT_TRUE(test::is_unit(p.normal));
    EXPECT_TRUE(test::is_miss(collide(Aabb{{1, 1}, {1, 1}}, Aabb{{2, 2}, {2, 2}})));
}

TEST(Bounds, EveryShape) {
    // Circle: centre +- r.
    const Aabb c = bounds(Circle{{1, 2}, 3});
    EXPECT_EQ(c.min, (Vec2{-2, -1}));
    EXPECT_EQ(c.max, (Vec2{4, 5}));
    // Segment: min/max of the ends, either order.
    const Aabb s = bounds(Segment{{5, -1}, {2, 3}});
    EXPECT_EQ(s.min, (Vec2{2, -1}));
    EXPECT_EQ(s.max, (Vec2{5, 3}));
    // Obb half (2,1) turned 90 deg at (10,10): world half extents (1,2).
    const Aabb o = bounds(Obb{{10, 10}, {2, 1}, kPi / 2});
    EXPECT_VEC_NEAR(o.min, (Vec2{9, 8}), 1e-5f);
    EXPECT_VEC_NEAR(o.max, (Vec2{11, 12}), 1e-5f);
    // Obb half (1,1) at 45 deg: half-diagonal sqrt2.
    const Aabb d = bounds(Obb{{0, 0}, {1, 1}, kPi / 4});
    EXPECT_VEC_NEAR(d.min, (Vec2{-kSqrt2, -kSqrt2}), 1e-5f);
    EXPECT_VEC_NEAR(d.max, (Vec2{kSqrt2, kSqrt2}), 1e-5f);
    // Polygon.
    const Aabb p = bounds(test::polygon_or_die({{0, 0}, {4, 1}, {1, 5}}));
    EXPECT_EQ(p.min, (Vec2{0, 0}));
    EXPECT_EQ(p.max, (Vec2{4, 5}));
    // Mask 3 wide, 2 tall at (10, 20): [10,13]x[20,22].
    const std::vector<std::string_view> rows{"#..", "..#"};
    const auto mask = Mask::from_rows(rows);
    ASSERT_TRUE(mask.has_value());
    const Aabb m = bounds(PlacedMask{&*mask, 10, 20});
    EXPECT_EQ(m.min, (Vec2{10, 20}));
    EXPECT_EQ(m.max, (Vec2{13, 22}));
    // Through the variant.
    const Aabb v = bounds(Shape{Circle{{1, 2}, 3}});
    EXPECT_EQ(v.min, (Vec2{-2, -1}));
    EXPECT_EQ(v.max, (Vec2{4, 5}));
    const Aabb a = bounds(Shape{Aabb{{1, 2}, {3, 4}}});
    EXPECT_EQ(a.min, (Vec2{1, 2}));
    EXPECT_EQ(a.max, (Vec2{3, 4}));
}

}  // namespace
}  // namespace jostle
