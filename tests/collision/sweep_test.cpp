// Sweep tests (sweep.cpp, slides 09-103 to 09-130): the D/F/G closed form for a moving circle
// against a static one, two moving circles by relative velocity, the swept capsule (with the
// slide's perpendicular corrected), and circles swept against boxes, polygons and segments.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "test_shapes.h"

namespace jostle {
namespace {

using test::is_miss;
using test::kPi;
using test::kSqrt2;
using test::is_sweep;


const Circle kMoving{{0, 0}, 1};

TEST(SweepCircle, HandComputedDFG) {
    // 09-118..122: moving r 1 at (0,0), v = (10,0); static r 1 at (5,0).
    // D = v/|v| . (Cs - Cd) = 5; F^2 = 25 - 25 = 0; G^2 = (1+1)^2 - 0 = 4, G = 2;
    // contact after D - G = 3 of |v| = 10: t = 0.3. Centre then (3,0); contact point (4,0).
    EXPECT_TRUE(is_sweep(sweep(kMoving, {10, 0}, Circle{{5, 0}, 1}), 0.3f, {4, 0}, {1, 0}));
}

TEST(SweepCircle, OffAxis) {
    // Static at (5,1): D = 5, F^2 = 26 - 25 = 1, G^2 = 4 - 1 = 3, D - G = 5 - sqrt3 = 3.268:
    // t = 0.3268. Centre (3.268,0); normal ((5,1) - (3.268,0))/2 = (0.8660, 0.5); point centre + n.
    const float s3 = std::sqrt(3.0f);
    const float t = (5 - s3) / 10;
    const Vec2 n{s3 / 2, 0.5f};
    EXPECT_TRUE(is_sweep(sweep(kMoving, {10, 0}, Circle{{5, 1}, 1}), t, Vec2{10 * t, 0} + n, n));
}

TEST(SweepCircle, MovingAwayMisses) {
    // (Cs - Cd) . v = 5 * -10 < 0 (09-114).
    EXPECT_TRUE(is_miss(sweep(kMoving, {-10, 0}, Circle{{5, 0}, 1})));
    EXPECT_TRUE(is_miss(sweep(kMoving, {0, 10}, Circle{{5, 0}, 1})));
}

TEST(SweepCircle, AlreadyOverlappingIsTimeZero) {
    const SweepHit h = sweep(kMoving, {10, 0}, Circle{{1, 0}, 1});
    EXPECT_TRUE(h.hit);
    EXPECT_EQ(h.t, 0.0f);
    EXPECT_TRUE(test::is_unit(h.normal));
    EXPECT_TRUE(is_finite(h.point));
    // Overlapping while moving apart: no contact ahead (the manual's moving-away rule, 09-114,
    // applies to shapes already in contact: a ball pushed out of a wall can leave it).
    EXPECT_TRUE(is_miss(sweep(kMoving, {-10, 0}, Circle{{1, 0}, 1})));
    // Moving sideways, or not at all: not moving into B either.
    EXPECT_TRUE(is_miss(sweep(kMoving, {0, 10}, Circle{{1, 0}, 1})));
    EXPECT_TRUE(is_miss(sweep(kMoving, {0, 0}, Circle{{1, 0}, 1})));
    EXPECT_TRUE(is_miss(sweep(kMoving, {0, 0}, Circle{{5, 0}, 1})));
}

TEST(SweepCircle, TouchingAtTheStart) {
    // Centres 2 apart, radii 1 + 1: touching at t = 0; a contact only when moving into B.
    const SweepHit in = sweep(kMoving, {1, 0}, Circle{{2, 0}, 1});
    EXPECT_TRUE(in.hit);
    EXPECT_EQ(in.t, 0.0f);
    EXPECT_VEC_NEAR(in.normal, (Vec2{1, 0}), 1e-6f);
    EXPECT_VEC_NEAR(in.point, (Vec2{1, 0}), 1e-6f);
    EXPECT_TRUE(is_miss(sweep(kMoving, {-1, 0}, Circle{{2, 0}, 1})));
    EXPECT_TRUE(is_miss(sweep(kMoving, {0, 1}, Circle{{2, 0}, 1})));  // sliding past
}

TEST(SweepCircle, PassesBeside) {
    // Static at (5,2.5): F^2 = 6.25 > (1+1)^2 = 4 (09-121): the closest approach is too far.
    EXPECT_TRUE(is_miss(sweep(kMoving, {10, 0}, Circle{{5, 2.5f}, 1})));
}

TEST(SweepCircle, Grazing) {
    // Static at (5,2): F^2 = 29 - 25 = 4 = R^2, G = 0: the path only touches it at t = 0.5 with
    // the normal (0,1) across the motion. A graze is no contact (the manual): the ball would
    // otherwise be stopped by a wall it only brushes.
    EXPECT_TRUE(is_miss(sweep(kMoving, {10, 0}, Circle{{5, 2}, 1})));
    // A hair closer it moves into B: F = 1.99, G = sqrt(4 - 3.9601) = 0.19975, t = (5 - G)/10.
    EXPECT_TRUE(is_sweep(sweep(kMoving, {10, 0}, Circle{{5, 1.99f}, 1}), 0.480025f, {4.80025f + 0.09988f, 0.99499f},
                         {0.09988f, 0.995f}, 1e-4f, 1e-3f));
}

// Slanted paths that graze exactly: integer motion and centres with cross(v, c)^2 = R^2 |v|^2,
// so F = R. The slide's F from the rounded unit vector was a hair short on 32 of these 1464,
// which then hit at a slant of a few 1e-4 (from (0,0) by (6,8) past (7,6): t = 0.9). The
// same path past a circle 0.01 larger is a hit.
TEST(SweepCircle, SlantedExactGrazesMissAndHitOnceTheCircleGrows) {
    int grazes = 0;
    for (int vx = -20; vx <= 20; ++vx)
        for (int vy = -20; vy <= 20; ++vy)
            for (int cx = -10; cx <= 10; ++cx)
                for (int cy = -10; cy <= 10; ++cy) {
                    const long v2 = long{vx} * vx + long{vy} * vy;
                    const long c = long{vx} * cy - long{vy} * cx;  // cross(v, centre)
                    const long d = long{vx} * cx + long{vy} * cy;  // dot(v, centre)
                    if (v2 == 0 || c * c != 4 * v2 || d <= 0 || d > v2) continue;
                    ++grazes;
                    const Vec2 v{static_cast<float>(vx), static_cast<float>(vy)};
                    const Vec2 centre{static_cast<float>(cx), static_cast<float>(cy)};
                    EXPECT_TRUE(is_miss(sweep(kMoving, v, Circle{centre, 1}))) << vx << "," << vy << " " << cx << "," << cy;
                    // With radius 1.01 the path goes 0.01 in: G = sqrt(2.01^2 - 4), t = (D - G) / |v|.
                    const SweepHit in = sweep(kMoving, v, Circle{centre, 1.01f});
                    const double speed = std::sqrt(static_cast<double>(v2));
                    const double t = (static_cast<double>(d) / speed - std::sqrt(2.01 * 2.01 - 4.0)) / speed;
                    EXPECT_TRUE(in.hit);
                    EXPECT_NEAR(in.t, std::max(0.0, t), 1e-4) << vx << "," << vy << " " << cx << "," << cy;
                }
    EXPECT_EQ(grazes, 1464);
}

TEST(SweepCircle, TooShort) {
    // |v| = 2 < D - G = 3.
    EXPECT_TRUE(is_miss(sweep(kMoving, {2, 0}, Circle{{5, 0}, 1})));
    EXPECT_TRUE(is_miss(sweep(kMoving, {2.99f, 0}, Circle{{5, 0}, 1})));
    // |v| = 3 exactly: contact at the end of the frame, t = 1.
    EXPECT_TRUE(is_sweep(sweep(kMoving, {3, 0}, Circle{{5, 0}, 1}), 1.0f, {4, 0}, {1, 0}));
}

TEST(SweepCircle, ZeroRadiusMovingPointIsARayCast) {
    // A point from (0,0) by (10,0) against r 2 at (5,0): contact at x = 3, t = 0.3.
    EXPECT_TRUE(is_sweep(sweep(Circle{{0, 0}, 0}, {10, 0}, Circle{{5, 0}, 2}), 0.3f, {3, 0}, {1, 0}));
}

TEST(SweepTwoCircles, HeadOn) {
    // a (0,0) by (5,0), b (10,0) by (-5,0): relative v = (10,0) against b fixed: contact after
    // 10 - 2 = 8: t = 0.8. Then a at (4,0), b at (6,0): point (5,0), normal (1,0).
    EXPECT_TRUE(is_sweep(sweep(kMoving, {5, 0}, Circle{{10, 0}, 1}, {-5, 0}), 0.8f, {5, 0}, {1, 0}));
}

TEST(SweepTwoCircles, ChasingAndParallel) {
    // a (0,0) by (10,0) catches b (4,0) by (5,0): relative (5,0), D - G = 4 - 2 = 2: t = 0.4.
    // Then a at (4,0), b at (6,0).
    EXPECT_TRUE(is_sweep(sweep(kMoving, {10, 0}, Circle{{4, 0}, 1}, {5, 0}), 0.4f, {5, 0}, {1, 0}));
    // Same velocity: the gap never closes.
    EXPECT_TRUE(is_miss(sweep(kMoving, {5, 0}, Circle{{3, 0}, 1}, {5, 0})));
    // b moving out of the way faster: relative (-5,0), moving apart.
    EXPECT_TRUE(is_miss(sweep(kMoving, {5, 0}, Circle{{3, 0}, 1}, {10, 0})));
}

TEST(SweptCapsule, CornersUseTheCorrectedPerpendicular) {
    // c = (1,2), r = 2, v = (3,4), |v| = 5: d = [-v_y, v_x] r/|v| = (-4,3)*0.4 = (-1.6,1.2).
    const Circle c{{1, 2}, 2};
    const Vec2 v{3, 4};
    const SweptCapsule cap = swept_capsule(c, v);
    EXPECT_EQ(cap.start.center, (Vec2{1, 2}));
    EXPECT_EQ(cap.start.radius, 2.0f);
    EXPECT_EQ(cap.end.center, (Vec2{4, 6}));
    EXPECT_EQ(cap.end.radius, 2.0f);
    // c + d, c + v + d, c + v - d, c - d.
    EXPECT_VEC_NEAR(cap.rectangle[0], (Vec2{-0.6f, 3.2f}), 1e-5f);
    EXPECT_VEC_NEAR(cap.rectangle[1], (Vec2{2.4f, 7.2f}), 1e-5f);
    EXPECT_VEC_NEAR(cap.rectangle[2], (Vec2{5.6f, 4.8f}), 1e-5f);
    EXPECT_VEC_NEAR(cap.rectangle[3], (Vec2{2.6f, 0.8f}), 1e-5f);
    // Every corner offset is perpendicular to v and r long.
    const Vec2 offsets[4] = {cap.rectangle[0] - c.center, cap.rectangle[1] - (c.center + v),
                             cap.rectangle[2] - (c.center + v), cap.rectangle[3] - c.center};
    for (const Vec2& d : offsets) {
        EXPECT_NEAR(dot(d, v), 0.0f, 1e-5f);
        EXPECT_NEAR(length(d), 2.0f, 1e-5f);
    }
}

TEST(SweptCapsule, TheSlidesPerpendicularIsWrong) {
    // The slide writes d = [-v_x, v_y] r/|v|. For v = (3,4): (-3,4) . (3,4) = -9 + 16 = 7 != 0,
    // so it is not perpendicular to v; [-v_y, v_x] = (-4,3) is: -12 + 12 = 0.
    const Vec2 v{3, 4};
    const Vec2 slide{-v.x, v.y};
    EXPECT_NE(dot(slide, v), 0.0f);
    EXPECT_EQ(dot(perp(v), v), 0.0f);
    // The capsule's corner is not where the slide's formula puts it.
    const SweptCapsule cap = swept_capsule(Circle{{0, 0}, 5}, v);
    const Vec2 slide_corner = (5.0f / 5.0f) * slide;  // r/|v| = 1
    EXPECT_GT(length(cap.rectangle[0] - slide_corner), 1.0f);
    EXPECT_VEC_NEAR(cap.rectangle[0], (Vec2{-4, 3}), 1e-5f);
}

TEST(SweptCapsule, AxisAlignedAndZeroVelocity) {
    // v = (5,0), r = 1 at the origin: d = (0,5)/5 = (0,1).
    const SweptCapsule cap = swept_capsule(Circle{{0, 0}, 1}, {5, 0});
    EXPECT_VEC_NEAR(cap.rectangle[0], (Vec2{0, 1}), 1e-6f);
    EXPECT_VEC_NEAR(cap.rectangle[1], (Vec2{5, 1}), 1e-6f);
    EXPECT_VEC_NEAR(cap.rectangle[2], (Vec2{5, -1}), 1e-6f);
    EXPECT_VEC_NEAR(cap.rectangle[3], (Vec2{0, -1}), 1e-6f);
    // v = 0: every corner is c, no NaN.
    const SweptCapsule still = swept_capsule(Circle{{3, 4}, 2}, {0, 0});
    for (const Vec2& p : still.rectangle) EXPECT_EQ(p, (Vec2{3, 4}));
    EXPECT_EQ(still.start.center, (Vec2{3, 4}));
    EXPECT_EQ(still.end.center, (Vec2{3, 4}));
}

TEST(SweptOverlaps, AgreesWithSweepOnHandCases) {
    struct Case {
        Vec2 v;
        Circle fixed;
        bool expected;        // swept_overlaps: the path touches `fixed` anywhere
        bool sweep_expected;  // sweep: a first contact ahead (none when moving off a contact)
    };
    const Case cases[] = {
        {{10, 0}, {{5, 0}, 1}, true, true},      // t = 0.3
        {{-10, 0}, {{5, 0}, 1}, false, false},   // moving away
        {{10, 0}, {{5, 2.5f}, 1}, false, false}, // passes beside
        {{10, 0}, {{5, 1.9f}, 1}, true, true},   // just inside the path
        {{2, 0}, {{5, 0}, 1}, false, false},     // too short
        {{3, 0}, {{5, 0}, 1}, true, true},       // ends touching
        {{10, 0}, {{1, 0}, 1}, true, true},      // overlapping at the start, moving in
        {{-10, 0}, {{1, 0}, 1}, true, false},    // overlapping at the start, moving away
        {{0, 0}, {{1, 0}, 1}, true, false},      // not moving, overlapping
        {{0, 0}, {{5, 0}, 1}, false, false},     // not moving, apart
        {{10, 10}, {{12, 12}, 1}, false, false}, // beyond the end, past the end cap
        {{10, 10}, {{11, 11}, 1}, true, true},   // inside the end cap
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(::testing::Message() << "v (" << c.v.x << ", " << c.v.y << ") fixed (" << c.fixed.center.x
                                          << ", " << c.fixed.center.y << ")");
        EXPECT_EQ(swept_overlaps(kMoving, c.v, c.fixed), c.expected);
        EXPECT_EQ(sweep(kMoving, c.v, c.fixed).hit, c.sweep_expected);
    }
}

TEST(SweptOverlaps, AgreesWithSweepFarFromTheOrigin) {
    // r 0.25 from (o,o) by (1,0); fixed r 0.25 at (o+0.5, o+0.4). The path passes 0.4 from the
    // fixed centre, closer than 0.25 + 0.25: they touch mid-frame (neither end circle does:
    // both are sqrt(0.41) = 0.64 away). All values are exact floats at these offsets.
    for (const float o : {0.0f, 10000.0f, 50000.0f, 100000.0f}) {
        SCOPED_TRACE(::testing::Message() << "offset " << o);
        const Circle moving{{o, o}, 0.25f};
        const Circle fixed{{o + 0.5f, o + 0.4f}, 0.25f};
        EXPECT_TRUE(sweep(moving, {1, 0}, fixed).hit);
        EXPECT_TRUE(swept_overlaps(moving, {1, 0}, fixed));
        // 0.2 further away the path clears it (0.6 > 0.5).
        EXPECT_FALSE(swept_overlaps(moving, {1, 0}, Circle{{o + 0.5f, o + 0.6f}, 0.25f}));
    }
}

TEST(SweepBox, FastBallAgainstAOnePixelWallStopsAtContact) {
    // r 2 ball at (0,500) moving 1e5 px: touches x = 100 when its centre is at 98: t = 98/1e5.
    const Circle ball{{0, 500}, 2};
    const Vec2 v{100000, 0};
    const float t = 98.0f / 100000.0f;
    EXPECT_TRUE(is_sweep(sweep(ball, v, Aabb{{100, 0}, {101, 1000}}), t, {100, 500}, {1, 0}, 1e-6f, 1e-2f));
    EXPECT_TRUE(is_sweep(sweep(ball, v, Obb{{100.5f, 500}, {0.5f, 500}, 0.0f}), t, {100, 500}, {1, 0}, 1e-6f, 1e-2f));
    EXPECT_TRUE(is_sweep(sweep(ball, v, test::box_polygon(100, 0, 101, 1000)), t, {100, 500}, {1, 0}, 1e-6f, 1e-2f));
    EXPECT_TRUE(is_sweep(sweep(ball, v, Segment{{100, 0}, {100, 1000}}), t, {100, 500}, {1, 0}, 1e-6f, 1e-2f));
    // At t the ball only touches the wall (never tunnels past it).
    const SweepHit h = sweep(ball, v, Aabb{{100, 0}, {101, 1000}});
    const Manifold m = collide(Aabb{{100, 0}, {101, 1000}}, Circle{ball.center + h.t * v, ball.radius});
    EXPECT_LE(m.depth, 0.02f);
}

TEST(SweepBox, CornerContact) {
    // r 1 from (0,0) by (10,0); box [5,7]x[0.5,3]. The centre's path y = 0 never meets the left
    // face's span; first contact is the corner (5,0.5): (x - 5)^2 + 0.25 = 1, x = 5 - sqrt(0.75):
    // t = (5 - 0.8660)/10 = 0.41340, normal (0.8660, 0.5), point the corner.
    const float k = std::sqrt(0.75f);
    EXPECT_TRUE(is_sweep(sweep(kMoving, {10, 0}, Aabb{{5, 0.5f}, {7, 3}}), (5 - k) / 10, {5, 0.5f}, {k, 0.5f}));
    EXPECT_TRUE(is_sweep(sweep(kMoving, {10, 0}, test::box_polygon(5, 0.5f, 7, 3)), (5 - k) / 10, {5, 0.5f}, {k, 0.5f}));
    EXPECT_TRUE(is_sweep(sweep(kMoving, {10, 0}, Obb{{6, 1.75f}, {1, 1.25f}, 0.0f}), (5 - k) / 10, {5, 0.5f},
                         {k, 0.5f}));
    // Box moved down by 0.6: the path clears it.
    EXPECT_TRUE(is_miss(sweep(kMoving, {10, 0}, Aabb{{5, 1.1f}, {7, 3}})));
}

TEST(SweepBox, StartsOverlappingAndMisses) {
    const SweepHit h = sweep(kMoving, {10, 0}, Aabb{{0.5f, -1}, {2, 1}});
    EXPECT_TRUE(h.hit);
    EXPECT_EQ(h.t, 0.0f);
    EXPECT_TRUE(is_miss(sweep(kMoving, {10, 0}, Aabb{{-5, 3}, {15, 4}})));
    EXPECT_TRUE(is_miss(sweep(kMoving, {-10, 0}, Aabb{{5, -1}, {7, 1}})));
    EXPECT_TRUE(is_miss(sweep(kMoving, {3, 0}, Aabb{{5, -1}, {7, 1}})));
    EXPECT_TRUE(is_sweep(sweep(kMoving, {4, 0}, Aabb{{5, -1}, {7, 1}}), 1.0f, {5, 0}, {1, 0}));
}

TEST(SweepObb, RotatedFace) {
    // Diamond half 1 at 45 deg around (5,5); r 1 from (0,0) by (5,5): the face with normal
    // (-1,-1)/sqrt2 lies 1 from the centre; contact when the centre is 2 from it along the
    // diagonal, i.e. after 5 sqrt2 - 2 of 5 sqrt2: t = 1 - 2/(5 sqrt2) = 0.71716.
    const float k = 1 / kSqrt2;
    const float t = 1 - 2 / (5 * kSqrt2);
    EXPECT_TRUE(is_sweep(sweep(kMoving, {5, 5}, Obb{{5, 5}, {1, 1}, kPi / 4}), t, {5 - k, 5 - k}, {k, k}));
}

TEST(SweepPolygon, Hypotenuse) {
    // Triangle (0,0),(4,0),(0,4); r 1 from (6,6) by (-6,-6): distance from (s,s) to x + y = 4 is
    // (2s - 4)/sqrt2 = 1 at s = 2 + 1/sqrt2: t = (6 - s)/6 = 0.54882; point (2,2); normal (-1,-1)/sqrt2.
    const Polygon tri = test::polygon_or_die({{0, 0}, {4, 0}, {0, 4}});
    const float k = 1 / kSqrt2;
    EXPECT_TRUE(is_sweep(sweep(Circle{{6, 6}, 1}, {-6, -6}, tri), (4 - k) / 6, {2, 2}, {-k, -k}));
    EXPECT_TRUE(is_miss(sweep(Circle{{6, 6}, 1}, {-2, -2}, tri)));
}

TEST(SweepSegment, FaceAndEndpoint) {
    const Segment wall{{0, -1}, {0, 1}};
    // r 0.5 from (-5,0) by (10,0): centre at x = -0.5: t = 0.45, point (0,0), normal (1,0).
    EXPECT_TRUE(is_sweep(sweep(Circle{{-5, 0}, 0.5f}, {10, 0}, wall), 0.45f, {0, 0}, {1, 0}));
    // r 1 from (-5,1.5): the end (0,1) is met when x^2 + 0.25 = 1, x = -0.8660: t = 0.41340,
    // normal (0.8660,-0.5), point (0,1).
    const float k = std::sqrt(0.75f);
    EXPECT_TRUE(is_sweep(sweep(Circle{{-5, 1.5f}, 1}, {10, 0}, wall), (5 - k) / 10, {0, 1}, {k, -0.5f}));
    EXPECT_TRUE(is_miss(sweep(Circle{{-5, 2.1f}, 1}, {10, 0}, wall)));
    // A zero-length segment is a point.
    EXPECT_TRUE(is_sweep(sweep(Circle{{-5, 0}, 1}, {10, 0}, Segment{{0, 0}, {0, 0}}), 0.4f, {0, 0}, {1, 0}));
}

TEST(SweepSegment, ACentreOnTheSegmentPushesIntoTheSideItMovesToward) {
    // The centre on the wall (or within rounding of it) has no side of its own: it touches at
    // t = 0 on the side it moves toward, the contact point is the wall's point under the
    // centre (where the circle's surface meets it along the normal, as for any start in
    // contact), and moving along the wall is no contact.
    const Segment wall{{0, 0}, {10, 0}};
    for (const float y : {0.0f, 1e-7f, -1e-7f}) {
        SCOPED_TRACE(y);
        const SweepHit up = sweep(Circle{{5, y}, 1}, {0, 2}, wall);
        EXPECT_TRUE(is_sweep(up, 0.0f, {5, 0}, {0, 1}, 0.0f, 2e-7f));
        const SweepHit down = sweep(Circle{{5, y}, 1}, {0, -2}, wall);
        EXPECT_TRUE(is_sweep(down, 0.0f, {5, 0}, {0, -1}, 0.0f, 2e-7f));
        EXPECT_TRUE(is_miss(sweep(Circle{{5, y}, 1}, {2, 0}, wall)));
    }
    // Just off the wall the point is the same: the surface meets the wall under the centre.
    EXPECT_TRUE(is_sweep(sweep(Circle{{5, 1e-3f}, 1}, {0, -2}, wall), 0.0f, {5, 0}, {0, -1}, 0.0f, 2e-7f));
}

TEST(SweepShape, RelativeMotion) {
    // r 1 from (0,0) by (5,0); box [8,10]x[-1,1] by (-5,0): relative (10,0), contact when the
    // centre is at x = 7 in the box's frame: t = 0.7. Then the ball is at (3.5,0), the box's
    // left face at 4.5: point (4.5,0).
    const SweepHit h = sweep(kMoving, {5, 0}, Shape{Aabb{{8, -1}, {10, 1}}}, {-5, 0});
    EXPECT_TRUE(is_sweep(h, 0.7f, {4.5f, 0}, {1, 0}));
    // Circle through the generic entry: same as the two-circle sweep.
    EXPECT_TRUE(is_sweep(sweep(kMoving, {5, 0}, Shape{Circle{{10, 0}, 1}}, {-5, 0}), 0.8f, {5, 0}, {1, 0}));
    // A static segment through the generic entry.
    EXPECT_TRUE(is_sweep(sweep(Circle{{-5, 0}, 0.5f}, {10, 0}, Shape{Segment{{0, -1}, {0, 1}}}, {0, 0}), 0.45f,
                         {0, 0}, {1, 0}));
}

TEST(SweepShape, ContactPointBeyondFloatRangeIsAMiss) {
    // Found by the collision fuzz target (tests/fuzz/regressions/collision/): a circle at
    // FLT_MAX with radius FLT_MAX already overlaps the triangle; its contact point, centre +
    // r * normal, is (inf, inf). A result is finite or a miss, so this is a miss.
    const float big = std::numeric_limits<float>::max();
    const Polygon tri = test::polygon_or_die({{1, 0}, {-0.5f, 0.8660254f}, {-0.5f, -0.8660254f}});
    EXPECT_TRUE(is_miss(sweep(Circle{{big, big}, big}, {1, 16}, Shape{tri}, {0, 0})));
    // An ordinary circle moving into the triangle still hits.
    EXPECT_TRUE(sweep(Circle{{-3, 0}, 1}, {4, 0}, Shape{tri}, {0, 0}).hit);
}

TEST(SweepObb, PointSizedBoxIsNotTunnelledThrough) {
    // Found by the collision fuzz target (regressions/collision/sweep_point_sized_obb_tunnels.bin):
    // a ball of radius 1.5 passes 1.18 px from a box 2e-7 px across. To float the box is a
    // point, every corner meets the ball at the same t, and rounding picked the far corner,
    // whose cone of normals faces away; its neighbours' cones did too, so the contact took a
    // face normal the ball only grazes, and the sweep missed. The opposite corner's cone holds
    // the direction: a hit where a point there would be hit.
    const Circle ball{{15.75f, 15.75f}, 1.5f};
    const Vec2 v{-23.75f, -24.0f};
    const Obb box{{1e-7f, 0.0f}, {1e-7f, 1e-7f}, 1e-7f};
    const SweepHit point = sweep(ball, v, Circle{box.center, 0.0f});
    ASSERT_TRUE(point.hit);
    for (const SweepHit h : {sweep(ball, v, box), sweep(ball, v, to_polygon(box))}) {
        ASSERT_TRUE(h.hit);
        EXPECT_NEAR(h.t, point.t, 1e-5f);
        EXPECT_GT(dot(h.normal, v), 0.0f) << "the normal points along the motion, into the box";
    }
}

TEST(SweepObb, AnEndFaceShorterThanItsRoundingDoesNotStopABallFarAway) {
    // Found by the collision fuzz target (regressions/collision/sweep_circle_past_rounding_thin_box_end.bin):
    // a box 402 px long and 1.3e-5 px thick, turned, its corners near x = 160 (where a float
    // step is 1.5e-5): an end face's direction was rounding, its window test passed, and a ball
    // of radius 1008 passing 69 px beyond the box's end was stopped there. The end faces are
    // measured along the direction their normals give: the ball misses, as it misses a segment
    // in the box's place.
    const Circle ball{{-1296, 1008}, 1008};
    const Vec2 v{96, -1520};
    const Obb box{{6.4e-06f, 0}, {201.06194f, 6.4e-06f}, 2.5f};
    const Vec2 u = rotate(box.rotation(), Vec2{box.half.x, 0.0f});
    EXPECT_TRUE(is_miss(sweep(ball, v, Segment{box.center - u, box.center + u})));
    EXPECT_TRUE(is_miss(sweep(ball, v, box)));
    EXPECT_TRUE(is_miss(sweep(ball, v, to_polygon(box))));
    // Moved 100 px closer (now passing within 1008 of the end), it hits at the end's corner.
    const Circle closer{ball.center + Vec2{100, 0}, ball.radius};
    const SweepHit seg = sweep(closer, v, Segment{box.center - u, box.center + u});
    const SweepHit hit = sweep(closer, v, box);
    ASSERT_TRUE(seg.hit);
    ASSERT_TRUE(hit.hit);
    EXPECT_NEAR(hit.t, seg.t, 1e-4f);
}

TEST(SweepObb, ABallMeetingAThinBoxNearItsEndIsStopped) {
    // Found by the collision fuzz target (regressions/collision/sweep_circle_thin_box_far_corner_tie.bin):
    // the box above, and a ball of radius 992 meeting its long face 0.24 px from the end. The
    // corner across the 1.3e-5 px end face met the ball first by a rounding step; its direction
    // lies outside that corner's cone, no corner claimed it, and the adjacent face it fell back
    // to ran along the motion, so the ball passed through. The face facing the direction most
    // is the long one it hits: the same t and normal as the segment in the box's place.
    const Circle ball{{-528, -976}, 992};
    const Vec2 va{1008, 96}, vb{-1536, -1536};
    const Obb box{{6.4e-06f, 0}, {201.06194f, 6.4e-06f}, 2.5f};
    const Vec2 u = rotate(box.rotation(), Vec2{box.half.x, 0.0f});
    const SweepHit seg = sweep(ball, va, Shape{Segment{box.center - u, box.center + u}}, vb);
    const SweepHit hit = sweep(ball, va, Shape{box}, vb);
    ASSERT_TRUE(seg.hit);
    ASSERT_TRUE(hit.hit);
    EXPECT_NEAR(hit.t, seg.t, 1e-4f);
    EXPECT_VEC_NEAR(hit.normal, seg.normal, 1e-3f);
    const SweepHit poly = sweep(ball, va - vb, to_polygon(box));
    ASSERT_TRUE(poly.hit);
    EXPECT_NEAR(poly.t, seg.t, 1e-4f);
}

TEST(SweepSegment, AShortSegmentFarFromTheOriginIsNotPassedThrough) {
    // Found by the collision fuzz target (regressions/collision/sweep_circle_short_segment_far_from_origin.bin):
    // faces shorter than 64 rounding steps of their ends' coordinates were left to their
    // vertices (the fix for the thin box above), which near the coordinate limit is 2 px: a
    // ball of radius 1 crossing the middle of a 1.4 px segment at x ~ 1e5 was stopped only by
    // an end's circle, 0.27 px into the segment. The same scene moved to the origin is the
    // answer float can give there.
    const Vec2 far{99930.0f, 99930.0f};
    const Circle ball{Vec2{-2.0f, 6.0f} + far, 1.0f};
    const Vec2 v{16.0f, 1.25f};
    const Segment seg{Vec2{7.57f, 7.0f} + far, Vec2{7.0f, 5.75f} + far};
    const SweepHit there = sweep(ball, v, seg);
    const SweepHit here = sweep(Circle{ball.center - far, 1.0f}, v, Segment{seg.a - far, seg.b - far});
    ASSERT_TRUE(there.hit);
    ASSERT_TRUE(here.hit);
    EXPECT_NEAR(there.t, here.t, 1e-4f);
    EXPECT_VEC_NEAR(there.normal, here.normal, 1e-3f);
    // The fuzz input as minimised: a ball of radius 0.5 moving diagonally onto a 1.3 px segment.
    const Circle small{{99937.0f, 99938.0f}, 0.5f};
    const Segment diagonal{{99936.0f, 99937.0f}, {99937.25f, 99937.25f}};
    const Vec2 shift{99936.0f, 99937.0f};
    const SweepHit s_there = sweep(small, {-24.0f, -24.0f}, diagonal);
    const SweepHit s_here = sweep(Circle{small.center - shift, 0.5f}, {-24.0f, -24.0f}, Segment{diagonal.a - shift, diagonal.b - shift});
    ASSERT_TRUE(s_there.hit);
    ASSERT_TRUE(s_here.hit);
    EXPECT_NEAR(s_there.t, s_here.t, 1e-4f);
}

}  // namespace
}  // namespace jostle
