// Resting contact: a pile of boxes, polygons and circles on a floor (columns, a pyramid, circles
// on the floor, in a corner and in pockets) and a stack of ten boxes settle under gravity, then
// stay within `slop` of penetration and do not move or drift over 10,000 steps.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "jostle/collision.h"
#include "jostle/core/rng.h"
#include "jostle/world.h"
#include "sanitizer_scale.h"

using namespace jostle;

namespace {

constexpr float kDt = 1.0f / 60.0f;
constexpr int kSettleSteps = 300;
// The issue asks for 10,000 steps; Release runs them all, ASan a tenth.
constexpr int kRestSteps = 10000 / kSanitizerDivisor;
// Penetration after a step may be at most `slop` plus float rounding: the positions here are
// below 1024 px, where a float resolves 6e-5 px, and the depth recomputed below is the collision
// module's own answer for the very shapes the world holds.
constexpr double kDepthRounding = 1e-4;
// Total drift allowed over the whole run, from the positions after settling.
constexpr double kMaxDrift = 0.05;
// How far from its designed resting place a body may settle: the jitter is 0.3 px, and a circle
// dropped into a pocket spreads the boxes under it by up to about a pixel before friction holds
// them (which lowers the circle a little). A collapse moves bodies by tens of pixels.
constexpr float kMaxSettleOffsetX = 2.0f;
constexpr float kMaxSettleOffsetY = 1.0f;

struct Body {
    EntityId id;
    std::string label;
    bool dynamic = false;
    Vec2 rest;  // where the scene was designed to rest
};

// Bodies start a little above where they will rest, with gaps between them and small sideways
// offsets (seeded), so the pile really falls, lands and settles rather than starting at rest;
// their masses differ (heavy bodies on light ones too).
struct Scene {
    World world;
    std::vector<Body> bodies;
    Rng jitter;

    explicit Scene(std::uint64_t seed) : world(make_desc()), jitter(seed) {}
    static WorldDesc make_desc() {
        WorldDesc d;
        d.gravity = {0.0f, 980.0f};
        return d;
    }

    EntityId add(const EntityDesc& d, std::string label, Vec2 rest) {
        const EntityId id = world.create(d);
        bodies.push_back({id, std::move(label), d.kind == BodyKind::dynamic, rest});
        return id;
    }
    EntityId add_static_aabb(Vec2 centre, Vec2 half, std::string label) {
        EntityDesc d;
        d.kind = BodyKind::static_body;
        d.position = centre;
        d.collider = Collider::aabb(half);
        return add(d, std::move(label), centre);
    }
    // A gap to leave below the next body: 0.5 to 4 px.
    float gap() { return jitter.uniform(0.5f, 4.0f); }
    // rest: where the body would rest; lift: how far above that it starts. Also shifted
    // sideways by up to 0.3 px.
    EntityId add_dynamic(Vec2 rest, float lift, const Collider& c, std::string label) {
        EntityDesc d;
        d.kind = BodyKind::dynamic;
        d.position = {rest.x + jitter.uniform(-0.3f, 0.3f), rest.y - lift};
        d.inverse_mass = jitter.uniform(0.2f, 2.0f);  // masses from 0.5 to 5
        d.collider = c;
        return add(d, std::move(label), rest);
    }
};

std::string fmt(const char* format, double a, double b = 0.0, double c = 0.0) {
    char buf[256];
    std::snprintf(buf, sizeof buf, format, a, b, c);
    return buf;
}

// Settles the scene, then runs kRestSteps steps checking after each: the deepest overlap of
// any pair that can touch (recomputed with collide() on the world's placed shapes), how far
// any body moved in the step, and how far it is from where it settled.
void check_resting(Scene& scene) {
    World& world = scene.world;
    for (int i = 0; i < kSettleSteps; ++i) world.step(kDt);
    const double slop = world.desc().slop;

    // The pile formed as built: every body came to rest near where it was designed to.
    std::vector<Vec2> settled, previous;
    for (const Body& b : scene.bodies) {
        const EntityDesc* e = world.get(b.id);
        ASSERT_NE(e, nullptr) << b.label << " is gone after settling";
        settled.push_back(e->position);
        EXPECT_LE(std::fabs(e->position.x - b.rest.x), kMaxSettleOffsetX)
            << b.label << " settled at (" << e->position.x << ", " << e->position.y << "), built to rest at ("
            << b.rest.x << ", " << b.rest.y << ")";
        EXPECT_LE(std::fabs(e->position.y - b.rest.y), kMaxSettleOffsetY)
            << b.label << " settled at (" << e->position.x << ", " << e->position.y << "), built to rest at ("
            << b.rest.x << ", " << b.rest.y << ")";
    }
    previous = settled;

    double worst_depth = 0.0, worst_move = 0.0, worst_drift = 0.0;
    std::string depth_where = "none", move_where = "none", drift_where = "none";
    int depth_failures = 0, move_failures = 0;
    for (int step = 1; step <= kRestSteps; ++step) {
        world.step(kDt);
        // Penetration of every pair with a dynamic body in it.
        for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
            for (std::size_t j = i + 1; j < scene.bodies.size(); ++j) {
                const Body& a = scene.bodies[i];
                const Body& b = scene.bodies[j];
                if (!a.dynamic && !b.dynamic) continue;
                const Manifold m = collide(world.shape_of(a.id), world.shape_of(b.id));
                if (!m.hit) continue;
                if (m.depth > slop + kDepthRounding) ++depth_failures;
                if (m.depth > worst_depth) {
                    worst_depth = m.depth;
                    depth_where =
                        a.label + " / " + b.label +
                        fmt(" at rest step %.0f, normal (%.4f, %.4f)", step, m.normal.x, m.normal.y);
                }
            }
        }
        // Motion in this step and drift since settling.
        for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
            const Body& b = scene.bodies[i];
            const EntityDesc* e = world.get(b.id);
            ASSERT_NE(e, nullptr) << b.label << " is gone at rest step " << step;
            const Vec2 p = e->position;
            const double move = std::hypot(p.x - previous[i].x, p.y - previous[i].y);
            const double drift = std::hypot(p.x - settled[i].x, p.y - settled[i].y);
            if (!(move < slop)) ++move_failures;
            if (!(move <= worst_move)) {
                worst_move = move;
                move_where = b.label + fmt(" at rest step %.0f, now (%.4f, %.4f)", step, p.x, p.y);
            }
            if (!(drift <= worst_drift)) {
                worst_drift = drift;
                drift_where = b.label + fmt(" at rest step %.0f, now (%.4f, %.4f)", step, p.x, p.y) +
                              fmt(", settled at (%.4f, %.4f)", settled[i].x, settled[i].y);
            }
            previous[i] = p;
        }
    }
    EXPECT_LE(worst_depth, slop + kDepthRounding)
        << "deepest overlap " << worst_depth << " px (slop " << slop << "): " << depth_where << "; "
        << depth_failures << " pair-steps over";
    EXPECT_LT(worst_move, slop) << "largest motion in one step " << worst_move << " px: " << move_where
                                << "; " << move_failures << " body-steps at or over slop";
    EXPECT_LT(worst_drift, kMaxDrift)
        << "largest drift from the settled position " << worst_drift << " px: " << drift_where;
}

}  // namespace

TEST(Resting, PileOfBoxesAndCirclesSettlesWithinSlopAndDoesNotDrift) {
    Scene s(0x9113);
    // The bin: a floor whose top is y = 500 and walls whose inner faces are x = -400 and 400.
    s.add_static_aabb({0.0f, 520.0f}, {600.0f, 20.0f}, "floor");
    s.add_static_aabb({-420.0f, 300.0f}, {20.0f, 220.0f}, "left wall");
    s.add_static_aabb({420.0f, 300.0f}, {20.0f, 220.0f}, "right wall");

    // Column A: four 40 x 40 Aabb boxes, and a circle on top.
    float lift = 0.0f;
    for (int k = 0; k < 4; ++k) {
        lift += s.gap();
        s.add_dynamic({-300.0f, 480.0f - 40.0f * static_cast<float>(k)}, lift, Collider::aabb({20.0f, 20.0f}),
                      "column A box " + std::to_string(k));
    }
    lift += s.gap();
    s.add_dynamic({-300.0f, 340.0f - 10.0f}, lift, Collider::circle(10.0f), "circle on column A");
    // Column B: five 30 x 20 Obb boxes.
    lift = 0.0f;
    for (int k = 0; k < 5; ++k) {
        lift += s.gap();
        s.add_dynamic({-220.0f, 490.0f - 20.0f * static_cast<float>(k)}, lift, Collider::box({15.0f, 10.0f}),
                      "column B obb " + std::to_string(k));
    }
    // Column C: a wide box, a narrower one, and a trapezoid polygon on top (flat bottom and top).
    lift = s.gap();
    s.add_dynamic({-140.0f, 485.0f}, lift, Collider::aabb({30.0f, 15.0f}), "column C wide box");
    lift += s.gap();
    s.add_dynamic({-140.0f, 455.0f}, lift, Collider::box({20.0f, 15.0f}), "column C narrow obb");
    {
        const Vec2 pts[] = {{-15.0f, 10.0f}, {15.0f, 10.0f}, {10.0f, -10.0f}, {-10.0f, -10.0f}};
        const std::optional<Polygon> trapezoid = make_polygon(pts);
        ASSERT_TRUE(trapezoid.has_value());
        lift += s.gap();
        s.add_dynamic({-140.0f, 430.0f}, lift, Collider::polygon(*trapezoid), "column C trapezoid");
    }
    // A pyramid of 40 x 40 boxes, 3 + 2 + 1, with 2 px gaps in each row; each row starts above
    // the highest start of the row below.
    float row_lift = 0.0f;
    for (int k = 0; k < 3; ++k) {
        const float l = s.gap();
        row_lift = std::max(row_lift, l);
        s.add_dynamic({-42.0f + 42.0f * static_cast<float>(k), 480.0f}, l, Collider::aabb({20.0f, 20.0f}),
                      "pyramid base " + std::to_string(k));
    }
    float next_row = row_lift;
    for (int k = 0; k < 2; ++k) {
        const float l = row_lift + s.gap();
        next_row = std::max(next_row, l);
        s.add_dynamic({-21.0f + 42.0f * static_cast<float>(k), 440.0f}, l, Collider::aabb({20.0f, 20.0f}),
                      "pyramid middle " + std::to_string(k));
    }
    s.add_dynamic({0.0f, 400.0f}, next_row + s.gap(), Collider::box({20.0f, 20.0f}), "pyramid top obb");
    // Circles on the floor.
    s.add_dynamic({100.0f, 488.0f}, s.gap(), Collider::circle(12.0f), "floor circle r12");
    s.add_dynamic({160.0f, 480.0f}, s.gap(), Collider::circle(20.0f), "floor circle r20");
    s.add_dynamic({200.0f, 492.0f}, s.gap(), Collider::circle(8.0f), "floor circle r8");
    // A circle in the corner of the floor and the left wall (it starts 0.3 px from the wall at
    // most, so the jitter may press it into the wall: it is pushed out).
    s.add_dynamic({-385.0f, 485.0f}, s.gap(), Collider::circle(15.0f), "corner circle");
    // A circle in the pocket over the 10 px gap between two boxes: it rests on their top inner
    // corners, about 5 px to each side, so its centre is about sqrt(15^2 - 5^2) above their tops.
    const float box_lift = s.gap();
    s.add_dynamic({250.0f, 480.0f}, box_lift, Collider::aabb({20.0f, 20.0f}), "pocket left box");
    s.add_dynamic({300.0f, 480.0f}, box_lift, Collider::aabb({20.0f, 20.0f}), "pocket right box");
    s.add_dynamic({275.0f, 460.0f - std::sqrt(200.0f)}, box_lift + s.gap(), Collider::circle(15.0f),
                  "pocket circle");
    // A circle in the 20 px slot between a box and the right wall, on the floor.
    s.add_dynamic({359.0f, 480.0f}, s.gap(), Collider::aabb({20.0f, 20.0f}), "slot box");
    s.add_dynamic({390.0f, 490.0f}, s.gap(), Collider::circle(9.5f), "slot circle");

    check_resting(s);
}

TEST(Resting, StackOfTenBoxesSettlesWithinSlopAndDoesNotDrift) {
    Scene s(0x57ac);
    s.add_static_aabb({0.0f, 520.0f}, {600.0f, 20.0f}, "floor");
    // Ten 40 x 40 Aabb boxes on the left, ten 40 x 30 Obb boxes on the right (far apart),
    // dropped with gaps between them.
    float lift = 0.0f;
    for (int k = 0; k < 10; ++k) {
        lift += s.gap();
        s.add_dynamic({-200.0f, 480.0f - 40.0f * static_cast<float>(k)}, lift, Collider::aabb({20.0f, 20.0f}),
                      "aabb stack box " + std::to_string(k));
    }
    lift = 0.0f;
    for (int k = 0; k < 10; ++k) {
        lift += s.gap();
        s.add_dynamic({200.0f, 485.0f - 30.0f * static_cast<float>(k)}, lift, Collider::box({20.0f, 15.0f}),
                      "obb stack box " + std::to_string(k));
    }
    check_resting(s);
}
