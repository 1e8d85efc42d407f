// contacts(): the MTD with up to 2 contact points, by clipping the incident edge to the
// reference face. Hand-worked cases, then properties over random pairs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "collision/test_shapes.h"
#include "jostle/collision.h"
#include "jostle/core/rng.h"

namespace {

using namespace jostle;

Polygon poly(std::vector<Vec2> pts) { return make_polygon(pts).value(); }

// The contact points as a sorted list, for order-free comparison.
std::vector<Vec2> sorted_points(const ContactSet& c) {
    std::vector<Vec2> v(c.points.begin(), c.points.begin() + c.count);
    std::sort(v.begin(), v.end(), [](Vec2 a, Vec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    return v;
}

TEST(Contacts, MissHasNoPoints) {
    const ContactSet c = contacts(Obb{{0, 0}, {1, 1}}, Obb{{5, 0}, {1, 1}});
    EXPECT_FALSE(c.manifold.hit);
    EXPECT_EQ(c.count, 0);
    EXPECT_EQ(contacts(Polygon{}, poly({{0, 0}, {1, 0}, {0, 1}})).count, 0);
    EXPECT_EQ(contacts(Obb{{NAN, 0}, {1, 1}}, Obb{{0, 0}, {1, 1}}).count, 0);
}

TEST(Contacts, BoxLyingOnABoxTouchesAtTheEndsOfTheOverlap) {
    // A 4x2 box resting 0.5 deep in a wide floor, shifted right: the incident (bottom) edge
    // x in [1, 5] is clipped to the floor's top edge x in [-10, 10]; both ends are contacts.
    const Obb floor{{0, 10}, {10, 10}};  // top face at y = 0
    const Obb box{{3, -0.5f}, {2, 1}};   // bottom face at y = 0.5
    const ContactSet c = contacts(floor, box);
    ASSERT_TRUE(c.manifold.hit);
    EXPECT_FLOAT_EQ(c.manifold.depth, 0.5f);
    EXPECT_EQ(c.manifold.normal, (Vec2{0, -1}));
    ASSERT_EQ(c.count, 2);
    const auto p = sorted_points(c);
    EXPECT_EQ(p[0], (Vec2{1, 0.5f}));
    EXPECT_EQ(p[1], (Vec2{5, 0.5f}));
    EXPECT_FLOAT_EQ(c.depths[0], 0.5f);
    EXPECT_FLOAT_EQ(c.depths[1], 0.5f);
    // Overhanging the floor's end: the incident edge is cut at the reference edge's end.
    const ContactSet over = contacts(floor, Obb{{9, -0.5f}, {2, 1}});
    ASSERT_EQ(over.count, 2);
    const auto q = sorted_points(over);
    EXPECT_EQ(q[0], (Vec2{7, 0.5f}));
    EXPECT_EQ(q[1], (Vec2{10, 0.5f}));
}

TEST(Contacts, CornerIntoAFaceIsOnePoint) {
    // A diamond (a box turned 45 degrees) pushing its lowest corner 0.25 into a floor.
    const float h = 1.0f;
    const float reach = h * std::sqrt(2.0f);
    const Obb floor{{0, 10}, {10, 10}};
    const Obb diamond{{0, -reach + 0.25f}, {h, h}, 0.785398163f};
    const ContactSet c = contacts(floor, diamond);
    ASSERT_TRUE(c.manifold.hit);
    EXPECT_NEAR(c.manifold.depth, 0.25f, 1e-5f);
    ASSERT_EQ(c.count, 1);
    EXPECT_NEAR(c.points[0].x, 0.0f, 1e-5f);
    EXPECT_NEAR(c.points[0].y, 0.25f, 1e-5f);
    EXPECT_NEAR(c.depths[0], 0.25f, 1e-5f);
}

TEST(Contacts, ReversedOrderClipsTheOtherWay) {
    // B's face as the reference: the points come back in world coordinates.
    const Obb floor{{0, 10}, {10, 10}};
    const Obb box{{3, -0.5f}, {2, 1}};
    const ContactSet ab = contacts(floor, box);
    const ContactSet ba = contacts(box, floor);
    ASSERT_EQ(ba.count, ab.count);
    EXPECT_EQ(ba.manifold.normal, -ab.manifold.normal);
    EXPECT_FLOAT_EQ(ba.manifold.depth, ab.manifold.depth);
    // From box's side the floor's top edge is clipped to the box's bottom edge.
    const auto p = sorted_points(ba);
    EXPECT_EQ(p[0], (Vec2{1, 0}));
    EXPECT_EQ(p[1], (Vec2{5, 0}));
}

TEST(Contacts, ManifoldIsCollidesForBoxesAndPolygons) {
    Rng rng(7);
    for (int n = 0; n < 2000; ++n) {
        const Obb a{{rng.uniform(-5, 5), rng.uniform(-5, 5)}, {rng.uniform(0.2f, 3), rng.uniform(0.2f, 3)},
                    rng.uniform(-3.1f, 3.1f)};
        const Obb b{{rng.uniform(-5, 5), rng.uniform(-5, 5)}, {rng.uniform(0.2f, 3), rng.uniform(0.2f, 3)},
                    rng.uniform(-3.1f, 3.1f)};
        const Manifold m = collide(a, b);
        const ContactSet c = contacts(a, b);
        EXPECT_EQ(c.manifold.hit, m.hit);
        EXPECT_EQ(c.manifold.depth, m.depth);
        EXPECT_EQ(c.manifold.normal, m.normal);
        const Polygon pa = to_polygon(a), pb = to_polygon(b);
        const Manifold pm = collide(pa, pb);
        const ContactSet pc = contacts(pa, pb);
        EXPECT_EQ(pc.manifold.hit, pm.hit);
        EXPECT_EQ(pc.manifold.depth, pm.depth);
        EXPECT_EQ(pc.manifold.normal, pm.normal);
    }
}

// Every point lies on one shape's boundary (the incident shape) and at most the depth inside
// or outside the other; depths are in [0, depth]; a hit has 1 or 2 points.
TEST(Contacts, PointsLieOnTheIncidentBoundaryWithinTheDepth) {
    Rng rng(11);
    int hits = 0, pairs_of_two = 0;
    for (int n = 0; n < 4000; ++n) {
        const auto random_convex = [&](Vec2 c) {
            std::vector<Vec2> pts;
            const int k = 3 + static_cast<int>(rng.below(6));
            const float r = rng.uniform(0.5f, 4.0f);
            for (int i = 0; i < k; ++i) {
                const float t = 6.2831853f * (static_cast<float>(i) + rng.uniform(0.1f, 0.9f)) / static_cast<float>(k);
                pts.push_back(c + Vec2{r * std::cos(t), r * std::sin(t)});
            }
            return make_polygon(pts);
        };
        const auto a = random_convex({rng.uniform(-3, 3), rng.uniform(-3, 3)});
        const auto b = random_convex({rng.uniform(-3, 3), rng.uniform(-3, 3)});
        if (!a || !b) continue;
        const ContactSet c = contacts(*a, *b);
        if (!c.manifold.hit) {
            EXPECT_EQ(c.count, 0);
            continue;
        }
        ++hits;
        ASSERT_GE(c.count, 1);
        ASSERT_LE(c.count, 2);
        pairs_of_two += c.count == 2;
        const float tol = 1e-4f * 8.0f;
        for (int k = 0; k < c.count; ++k) {
            const Vec2 p = c.points[static_cast<std::size_t>(k)];
            const ClosestPoint ca = closest_point(*a, p), cb = closest_point(*b, p);
            const float on_a = length(closest_point_on_boundary(*a, p) - p);
            const float on_b = length(closest_point_on_boundary(*b, p) - p);
            EXPECT_LE(std::min(on_a, on_b), tol) << "pair " << n << " point " << k;
            EXPECT_LE(std::max(ca.distance, cb.distance), c.manifold.depth + tol) << "pair " << n;
            EXPECT_GE(c.depths[static_cast<std::size_t>(k)], 0.0f);
            EXPECT_LE(c.depths[static_cast<std::size_t>(k)], c.manifold.depth);
        }
    }
    EXPECT_GT(hits, 500);
    EXPECT_GT(pairs_of_two, 10);
}

}  // namespace
