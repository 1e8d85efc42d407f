// Polygon construction tests (shapes.cpp): make_polygon validation and normalisation, the
// box-to-polygon conversions, OBB corners and the closed point-in-polygon test.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "test_shapes.h"

namespace jostle {
namespace {

using test::kInf;
using test::kNan;
using test::kPi;
using test::kSqrt2;

// Stored form: cross(e[i], e[i+1]) > 0 for every i, and normals[i] the outward unit normal of
// edge i. With y down and that winding, the outward normal of e is (e.y, -e.x) / |e|, and it
// points away from the centroid. Checked here from the points alone.
void expect_normalised(const Polygon& p) {
    ASSERT_GE(p.count(), 3);
    ASSERT_LE(p.count(), kMaxPolygonVertices);
    const auto n = static_cast<std::size_t>(p.count());
    Vec2 centroid{};
    for (std::size_t i = 0; i < n; ++i) centroid += p.points()[i];
    centroid = (1.0f / static_cast<float>(n)) * centroid;
    for (std::size_t i = 0; i < n; ++i) {
        const Vec2 e0 = p.points()[(i + 1) % n] - p.points()[i];
        const Vec2 e1 = p.points()[(i + 2) % n] - p.points()[(i + 1) % n];
        EXPECT_GT(cross(e0, e1), 0.0f) << "vertex " << i;
        const float len = length(e0);
        const Vec2 expected{e0.y / len, -e0.x / len};
        EXPECT_VEC_NEAR(p.normals()[i], expected, 1e-5f);
        EXPECT_TRUE(test::is_unit(p.normals()[i]));
        EXPECT_LT(dot(p.normals()[i], centroid - p.points()[i]), 0.0f) << "normal " << i << " points inward";
    }
}

bool same_vertex_set(const Polygon& p, const std::vector<Vec2>& pts) {
    if (static_cast<std::size_t>(p.count()) != pts.size()) return false;
    for (const Vec2& q : pts) {
        if (std::find(p.points().begin(), p.points().begin() + p.count(), q) == p.points().begin() + p.count()) return false;
    }
    return true;
}

std::optional<Polygon> make(const std::vector<Vec2>& pts, std::string* error) {
    return make_polygon(std::span<const Vec2>(pts), error);
}

TEST(MakePolygon, StoredWindingIsAcceptedAsIs) {
    // (0,0),(4,0),(4,4),(0,4): e0=(4,0), e1=(0,4), cross = 16 > 0 (clockwise on screen).
    const std::vector<Vec2> pts{{0, 0}, {4, 0}, {4, 4}, {0, 4}};
    std::string error;
    const auto p = make(pts, &error);
    ASSERT_TRUE(p.has_value()) << error;
    EXPECT_EQ(p->count(), 4);
    EXPECT_TRUE(same_vertex_set(*p, pts));
    expect_normalised(*p);
    // Edge (0,0)->(4,0) is the top edge (y down): outward normal (0,-1).
    for (int i = 0; i < 4; ++i) {
        const auto k = static_cast<std::size_t>(i);
        if (p->points()[k] == Vec2{0, 0}) {
            EXPECT_EQ(p->points()[(k + 1) % 4], (Vec2{4, 0}));
            EXPECT_VEC_NEAR(p->normals()[k], (Vec2{0, -1}), 1e-6f);
        }
    }
}

TEST(MakePolygon, OppositeWindingIsReversed) {
    // (0,0),(0,4),(4,4),(4,0): e0=(0,4), e1=(4,0), cross = 0*0 - 4*4 = -16 < 0.
    const std::vector<Vec2> pts{{0, 0}, {0, 4}, {4, 4}, {4, 0}};
    std::string error;
    const auto p = make(pts, &error);
    ASSERT_TRUE(p.has_value()) << error;
    EXPECT_TRUE(same_vertex_set(*p, pts));
    expect_normalised(*p);
}

TEST(MakePolygon, TriangleBothWindings) {
    const std::vector<Vec2> cw{{0, 0}, {3, 1}, {1, 4}};  // cross((3,1),(-2,3)) = 9+2 = 11 > 0
    const std::vector<Vec2> ccw{{1, 4}, {3, 1}, {0, 0}};
    for (const auto& pts : {cw, ccw}) {
        const auto p = make(pts, nullptr);
        ASSERT_TRUE(p.has_value());
        EXPECT_EQ(p->count(), 3);
        EXPECT_TRUE(same_vertex_set(*p, pts));
        expect_normalised(*p);
    }
}

TEST(MakePolygon, SixteenVerticesAcceptedSeventeenRejected) {
    auto ring = [](int n) {
        std::vector<Vec2> pts;
        for (int i = 0; i < n; ++i) {
            const float a = 2.0f * kPi * static_cast<float>(i) / static_cast<float>(n);
            pts.push_back({100.0f * std::cos(a), 100.0f * std::sin(a)});
        }
        return pts;
    };
    const auto p16 = make(ring(16), nullptr);
    ASSERT_TRUE(p16.has_value());
    EXPECT_EQ(p16->count(), 16);
    expect_normalised(*p16);
    std::string error;
    EXPECT_FALSE(make(ring(17), &error).has_value());
    EXPECT_FALSE(error.empty());
}

TEST(MakePolygon, TooFewVerticesRejected) {
    std::string error;
    EXPECT_FALSE(make({{0, 0}, {1, 0}}, &error).has_value());
    EXPECT_FALSE(error.empty());
    error.clear();
    EXPECT_FALSE(make({}, &error).has_value());
    EXPECT_FALSE(error.empty());
}

TEST(MakePolygon, NonConvexRejected) {
    // The dent (2,1) turns the other way: cross((−2,1),(2,3)) = -6-2 = -8 while the others are > 0.
    std::string error;
    EXPECT_FALSE(make({{0, 0}, {4, 0}, {2, 1}, {4, 4}, {0, 4}}, &error).has_value());
    EXPECT_FALSE(error.empty());
}

TEST(MakePolygon, CollinearRejected) {
    std::string error;
    EXPECT_FALSE(make({{0, 0}, {2, 0}, {4, 0}, {4, 4}, {0, 4}}, &error).has_value());
    EXPECT_FALSE(error.empty());
    error.clear();
    EXPECT_FALSE(make({{0, 0}, {1, 1}, {2, 2}}, &error).has_value());  // zero area
    EXPECT_FALSE(error.empty());
}

TEST(MakePolygon, RepeatedVertexRejected) {
    std::string error;
    EXPECT_FALSE(make({{0, 0}, {4, 0}, {4, 0}, {4, 4}}, &error).has_value());
    EXPECT_FALSE(error.empty());
    error.clear();
    // A closed loop (first point repeated at the end).
    EXPECT_FALSE(make({{0, 0}, {4, 0}, {4, 4}, {0, 0}}, &error).has_value());
    EXPECT_FALSE(error.empty());
}

TEST(MakePolygon, NonFiniteRejected) {
    std::string error;
    EXPECT_FALSE(make({{0, 0}, {4, 0}, {kNan, 4}}, &error).has_value());
    EXPECT_FALSE(error.empty());
    error.clear();
    EXPECT_FALSE(make({{0, 0}, {kInf, 0}, {4, 4}}, &error).has_value());
    EXPECT_FALSE(error.empty());
    error.clear();
    EXPECT_FALSE(make({{0, 0}, {4, 0}, {4, -kInf}, {0, 4}}, &error).has_value());
    EXPECT_FALSE(error.empty());
}

TEST(MakePolygon, PentagramRejectedThoughEveryTurnHasTheSameSign) {
    // A regular pentagon's vertices taken 0,2,4,1,3: each edge spans 144 deg, every turn has
    // the same sign, but the boundary winds twice and crosses itself.
    std::vector<Vec2> star;
    for (int k : {0, 2, 4, 1, 3}) {
        const float a = 2.0f * kPi * static_cast<float>(k) / 5.0f;
        star.push_back({10.0f * std::cos(a), 10.0f * std::sin(a)});
    }
    // Precondition: all turns really have one sign.
    for (std::size_t i = 0; i < 5; ++i) {
        const Vec2 e0 = star[(i + 1) % 5] - star[i];
        const Vec2 e1 = star[(i + 2) % 5] - star[(i + 1) % 5];
        ASSERT_GT(cross(e0, e1), 0.0f);
    }
    std::string error;
    EXPECT_FALSE(make(star, &error).has_value());
    EXPECT_FALSE(error.empty());
    // The same in the other winding.
    std::reverse(star.begin(), star.end());
    error.clear();
    EXPECT_FALSE(make(star, &error).has_value());
    EXPECT_FALSE(error.empty());
}

TEST(MakePolygon, DoubleWoundSquareRejected) {
    // A square traced twice (8 points, all turns +90 deg, no repeated point within a loop
    // except by going round again): the repeated vertices or the winding must reject it.
    std::string error;
    EXPECT_FALSE(make({{0, 0}, {4, 0}, {4, 4}, {0, 4}, {0, 0}, {4, 0}, {4, 4}, {0, 4}}, &error).has_value());
    EXPECT_FALSE(error.empty());
}

TEST(MakePolygon, SmallPolygonsFarFromTheOriginAccepted) {
    // LIMITS: |x|, |y| <= 1e5 px. Integer vertices there are exact floats, and these shapes
    // are plainly convex with area 0.5 .. 256 px^2; the winding must not depend on where the
    // polygon sits (a signed area summed from absolute coordinates loses it: cross products
    // near 1e10 carry rounding errors of ~1e3).
    struct Case {
        float offset;
        float size;
    };
    for (const Case c : {Case{10000, 1}, Case{30000, 4}, Case{100000, 1}, Case{100000, 16}, Case{-100000, 8}}) {
        const float o = c.offset;
        const float s = c.size;
        SCOPED_TRACE(::testing::Message() << "offset " << o << ", size " << s);
        const std::vector<Vec2> tri{{o, o}, {o + s, o}, {o, o + s}};
        const std::vector<Vec2> tri_reversed{{o, o + s}, {o + s, o}, {o, o}};
        const std::vector<Vec2> square{{o, o}, {o + s, o}, {o + s, o + s}, {o, o + s}};
        for (const auto& pts : {tri, tri_reversed, square}) {
            std::string error;
            const auto p = make(pts, &error);
            ASSERT_TRUE(p.has_value()) << error;
            EXPECT_TRUE(same_vertex_set(*p, pts));
            expect_normalised(*p);
        }
    }
}

TEST(MakePolygon, ADenormalEdgeGetsItsTrueNormal) {
    // Found by fuzzing: an edge 1.8e-41 px long has a squared length of 0 in float, so its
    // normal fell back to (1, 0) and a cast through the polygon missed it. Distinct floats
    // always differ, so the edge has a direction, and the polygon is plainly convex.
    const std::vector<Vec2> pts{{4, 2}, {0, 0}, {0, -22.75f}, {1.7937e-41f, -22.75f}};
    std::string error;
    const auto p = make(pts, &error);
    ASSERT_TRUE(p.has_value()) << error;
    // Every normal is a unit vector with every other vertex strictly behind it (the shared
    // expect_normalised divides by the edge's float length, which is 0 here).
    const auto n = static_cast<std::size_t>(p->count());
    for (std::size_t i = 0; i < n; ++i) {
        EXPECT_TRUE(test::is_unit(p->normals()[i])) << "normal " << i;
        for (std::size_t j = 0; j < n; ++j) {
            if (j == i || j == (i + 1) % n) continue;
            EXPECT_LT(dot(p->normals()[i], p->points()[j] - p->points()[i]), 0.0f) << "normal " << i;
        }
    }
    // The short edge faces -y (it lies along y = -22.75, below everything else).
    EXPECT_TRUE(std::any_of(p->normals().begin(), p->normals().begin() + p->count(),
                            [](Vec2 u) { return u == Vec2{0.0f, -1.0f}; }));
    // Enters through the edge y = x / 2 at t = 1/47.
    const CastHit hit = cast(Vec2{1.5f, 1}, Vec2{1, -11}, *p);
    EXPECT_TRUE(hit.hit);
    EXPECT_NEAR(hit.t, 1.0f / 47.0f, 1e-6f);
}

TEST(ToPolygon, FromAabb) {
    const Polygon p = to_polygon(Aabb{{1, 2}, {5, 3}});
    EXPECT_EQ(p.count(), 4);
    EXPECT_TRUE(same_vertex_set(p, {{1, 2}, {5, 2}, {5, 3}, {1, 3}}));
    expect_normalised(p);
}

TEST(ToPolygon, FromObbAndCorners) {
    // Half (2,1) turned 90 deg at (10,10): local (x,y) -> (-y,x), so (+-2, +-1) -> (-+1, +-2):
    // corners (9,12), (11,12), (11,8), (9,8) in some order.
    const Obb box{{10, 10}, {2, 1}, kPi / 2};
    const auto c = corners(box);
    const std::vector<Vec2> expected{{9, 8}, {11, 8}, {11, 12}, {9, 12}};
    for (const Vec2& e : expected) {
        EXPECT_TRUE(std::any_of(c.begin(), c.end(), [&](Vec2 q) { return test::vec_near(q, e, 1e-5f); }))
            << "missing corner " << e.x << ", " << e.y;
    }
    for (std::size_t i = 0; i < 4; ++i) {
        const Vec2 e0 = c[(i + 1) % 4] - c[i];
        const Vec2 e1 = c[(i + 2) % 4] - c[(i + 1) % 4];
        EXPECT_GT(cross(e0, e1), 0.0f) << "corners() must be in polygon order";
    }
    const Polygon p = to_polygon(box);
    EXPECT_EQ(p.count(), 4);
    expect_normalised(p);
}

TEST(ToPolygon, FromRotatedObbAt45) {
    // Half (1,1) at 45 deg about (0,0): corners on the axes at distance sqrt2.
    const auto c = corners(Obb{{0, 0}, {1, 1}, kPi / 4});
    for (const Vec2& e : {Vec2{kSqrt2, 0}, Vec2{0, kSqrt2}, Vec2{-kSqrt2, 0}, Vec2{0, -kSqrt2}}) {
        EXPECT_TRUE(std::any_of(c.begin(), c.end(), [&](Vec2 q) { return test::vec_near(q, e, 1e-5f); }));
    }
}

TEST(ContainsPolygon, ClosedPointInPolygon) {
    const Polygon tri = test::polygon_or_die({{0, 0}, {4, 0}, {0, 4}});
    EXPECT_TRUE(contains(tri, {1, 1}));
    EXPECT_TRUE(contains(tri, {0, 0}));   // vertex
    EXPECT_TRUE(contains(tri, {2, 0}));   // on an edge
    EXPECT_TRUE(contains(tri, {2, 2}));   // on the hypotenuse x + y = 4
    EXPECT_FALSE(contains(tri, {2.01f, 2.01f}));
    EXPECT_FALSE(contains(tri, {-0.01f, 1}));
    EXPECT_FALSE(contains(tri, {5, 5}));
}

TEST(ShapeKinds, KindOfAndNameOf) {
    const std::vector<std::string_view> rows{"#"};
    const auto mask = Mask::from_rows(rows);
    ASSERT_TRUE(mask.has_value());
    EXPECT_EQ(kind_of(Shape{Aabb{}}), ShapeKind::aabb);
    EXPECT_EQ(kind_of(Shape{Obb{}}), ShapeKind::obb);
    EXPECT_EQ(kind_of(Shape{Polygon{}}), ShapeKind::polygon);
    EXPECT_EQ(kind_of(Shape{Circle{}}), ShapeKind::circle);
    EXPECT_EQ(kind_of(Shape{Segment{}}), ShapeKind::segment);
    EXPECT_EQ(kind_of(Shape{PlacedMask{&*mask, 0, 0}}), ShapeKind::mask);
    EXPECT_STREQ(name_of(ShapeKind::aabb), "aabb");
    EXPECT_STREQ(name_of(ShapeKind::obb), "obb");
    EXPECT_STREQ(name_of(ShapeKind::polygon), "polygon");
    EXPECT_STREQ(name_of(ShapeKind::circle), "circle");
    EXPECT_STREQ(name_of(ShapeKind::segment), "segment");
    EXPECT_STREQ(name_of(ShapeKind::mask), "mask");
}

// A Polygon is valid or empty by construction: moved() and transformed() keep it valid, and a
// motion that leaves the floats gives the empty polygon (which hits nothing).
TEST(PolygonMotion, MovedAndTransformedStayValid) {
    const Polygon p = make_polygon(std::vector<Vec2>{{0, 0}, {4, 0}, {4, 2}, {0, 3}}).value();
    const Polygon m = p.moved({10, -5});
    ASSERT_EQ(m.count(), 4);
    for (int i = 0; i < 4; ++i) {
        EXPECT_EQ(m.points()[static_cast<std::size_t>(i)], (p.points()[static_cast<std::size_t>(i)] + Vec2{10, -5}));
        EXPECT_EQ(m.normals()[static_cast<std::size_t>(i)], p.normals()[static_cast<std::size_t>(i)]);
    }
    expect_normalised(m);
    const Transform xf{{3, 4}, Rot::from_angle(0.7f)};
    const Polygon t = p.transformed(xf);
    ASSERT_EQ(t.count(), 4);
    for (int i = 0; i < 4; ++i) {
        EXPECT_EQ(t.points()[static_cast<std::size_t>(i)], apply(xf, p.points()[static_cast<std::size_t>(i)]));
        EXPECT_EQ(t.normals()[static_cast<std::size_t>(i)], rotate(xf.q, p.normals()[static_cast<std::size_t>(i)]));
    }
    expect_normalised(t);
    // The same contact as the original placed by hand.
    EXPECT_TRUE(collide(m, Circle{{14, -4}, 0.5f}).hit);
}

TEST(PolygonMotion, NonFiniteResultIsTheEmptyPolygon) {
    const Polygon p = make_polygon(std::vector<Vec2>{{0, 0}, {4, 0}, {0, 3}}).value();
    EXPECT_EQ(p.moved({NAN, 0}).count(), 0);
    EXPECT_EQ(p.moved({0, INFINITY}).count(), 0);
    EXPECT_EQ(p.moved({3e38f, 0}).moved({3e38f, 0}).count(), 0);  // overflows to infinity
    EXPECT_EQ(p.transformed(Transform{{0, 0}, Rot{NAN, 0}}).count(), 0);
    EXPECT_EQ(Polygon{}.moved({1, 1}).count(), 0);
    EXPECT_FALSE(collide(p.moved({NAN, 0}), p).hit);
    EXPECT_EQ(to_polygon(Obb{{0, 0}, {-1, 1}}).count(), 0);  // a malformed box has no polygon
    EXPECT_EQ(to_polygon(Aabb{{1, 1}, {0, 0}}).count(), 0);
}

// Rot is a plain pair: one that scales (or is zero) would leave normals that are not unit
// (depth 5 for a circle 3 deep), or none; such a turn gives the empty polygon.
TEST(PolygonMotion, ATurnThatIsNotARotationIsTheEmptyPolygon) {
    const Polygon sq = make_polygon(std::vector<Vec2>{{0, 0}, {2, 0}, {2, 2}, {0, 2}}).value();
    for (const Rot q : {Rot{2, 0}, Rot{0, 0}, Rot{0.5f, 0.5f}, Rot{1.001f, 0}, Rot{INFINITY, 0}}) {
        SCOPED_TRACE(testing::Message() << q.c << ", " << q.s);
        EXPECT_EQ(sq.rotated(q).count(), 0);
        EXPECT_EQ(sq.transformed(Transform{{1, 1}, q}).count(), 0);
        Polygon out = sq;
        sq.rotated_into(q, out);
        EXPECT_EQ(out.count(), 0);
        EXPECT_FALSE(collide(sq.transformed(Transform{{0, 0}, q}), Circle{{2, 2}, 1}).hit);
    }
    // Rotations as cos and sin give them, and as a unit vector normalised in float, turn.
    for (const Rot q : {Rot::from_angle(0.3f), Rot::from_angle(-2.0f), Rot{0.6f, 0.8f}, Rot{0, -1}}) {
        EXPECT_EQ(sq.rotated(q).count(), 4);
        Polygon out;
        sq.rotated_into(q, out);
        EXPECT_EQ(out.count(), 4);
    }
}

// The Obb's stored rotation is the one its angle gives, whichever way the angle was set.
TEST(ObbRotation, FollowsTheAngle) {
    Obb b{{1, 2}, {3, 4}, 0.5f};
    EXPECT_EQ(b.angle(), 0.5f);
    EXPECT_EQ(b.rotation().c, std::cos(0.5f));
    EXPECT_EQ(b.rotation().s, std::sin(0.5f));
    b.set_angle(-1.25f);
    EXPECT_EQ(b.angle(), -1.25f);
    EXPECT_EQ(b.rotation().c, std::cos(-1.25f));
    EXPECT_EQ(b.rotation().s, std::sin(-1.25f));
    EXPECT_EQ(Obb{}.rotation().c, 1.0f);
    EXPECT_EQ(Obb{}.rotation().s, 0.0f);
}

}  // namespace
}  // namespace jostle
