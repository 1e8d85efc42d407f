// Placing colliders: Collider::placed is "rotate, then translate", computed in two halves
// (turned once per angle, at() per position), and the world keeps each body's turned collider
// and placed shape between uses. Every placed shape must be bit for bit what one rigid
// placement gives (Transform{p, Rot::from_angle(a)} applied to the collider), whatever the
// angle or position (zeros of either sign, huge, NaN, infinite), and the world's cached shape
// must follow every change of angle, position and collider.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <optional>
#include <variant>
#include <vector>

#include "jostle/core/rng.h"
#include "jostle/world.h"

namespace jostle {
namespace {

constexpr float kNan = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

bool same(float a, float b) { return std::bit_cast<std::uint32_t>(a) == std::bit_cast<std::uint32_t>(b); }
bool same(Vec2 a, Vec2 b) { return same(a.x, b.x) && same(a.y, b.y); }

// Bit for bit, field by field.
bool same(const Shape& x, const Shape& y) {
    if (x.index() != y.index()) return false;
    if (const auto* a = std::get_if<Aabb>(&x)) {
        const auto& b = std::get<Aabb>(y);
        return same(a->min, b.min) && same(a->max, b.max);
    }
    if (const auto* a = std::get_if<Obb>(&x)) {
        const auto& b = std::get<Obb>(y);
        return same(a->center, b.center) && same(a->half, b.half) && same(a->angle(), b.angle()) &&
               same(a->rotation().c, b.rotation().c) && same(a->rotation().s, b.rotation().s);
    }
    if (const auto* a = std::get_if<Circle>(&x)) {
        const auto& b = std::get<Circle>(y);
        return same(a->center, b.center) && same(a->radius, b.radius);
    }
    if (const auto* a = std::get_if<Segment>(&x)) {
        const auto& b = std::get<Segment>(y);
        return same(a->a, b.a) && same(a->b, b.b);
    }
    if (const auto* a = std::get_if<Polygon>(&x)) {
        const auto& b = std::get<Polygon>(y);
        if (a->count() != b.count()) return false;
        for (int i = 0; i < a->count(); ++i) {
            const auto k = static_cast<std::size_t>(i);
            if (!same(a->points()[k], b.points()[k]) || !same(a->normals()[k], b.normals()[k])) return false;
        }
        return true;
    }
    const auto& a = std::get<PlacedMask>(x);
    const auto& b = std::get<PlacedMask>(y);
    return a.mask == b.mask && a.x == b.x && a.y == b.y;
}

// One rigid placement, written out from the definition (COLLIDERS in world.h).
Shape rigid(const Shape& local, Vec2 p, float angle) {
    const Transform xf{p, Rot::from_angle(angle)};
    if (const auto* b = std::get_if<Aabb>(&local)) return Aabb{b->min + p, b->max + p};
    if (const auto* b = std::get_if<Obb>(&local)) return Obb{apply(xf, b->center), b->half, b->angle() + angle};
    if (const auto* c = std::get_if<Circle>(&local)) return Circle{apply(xf, c->center), c->radius};
    if (const auto* s = std::get_if<Segment>(&local)) return Segment{apply(xf, s->a), apply(xf, s->b)};
    return std::get<Polygon>(local).transformed(xf);
}

std::vector<Collider> colliders() {
    const std::vector<Vec2> quad{{-3, -2}, {4, -1}, {3, 5}, {-2, 3}};
    return {Collider::aabb({3, 2}, {1, -1}),        Collider::box({4, 1.5f}, {2, 1}, 0.3f),
            Collider::circle(2.5f, {1.5f, -0.5f}),  Collider::segment({-3, 1}, {4, -2}),
            Collider::polygon(*make_polygon(quad)), Collider::box({0, 0})};
}

TEST(Placement, TwoHalvesAreOneRigidPlacementBitForBit) {
    Rng rng(42);
    std::vector<float> angles{0.0f, -0.0f, 1.0f, -3.0f, 3.14159274f, 1e-30f, 1e6f};
    std::vector<Vec2> positions{{0, 0}, {-0.0f, -0.0f}, {-0.0f, 5}, {1e5f, -1e5f}, {3e38f, 1}};
    for (int k = 0; k < 200; ++k) {
        angles.push_back(rng.uniform(-10.0f, 10.0f));
        positions.push_back({rng.uniform(-2000.0f, 2000.0f), rng.uniform(-2000.0f, 2000.0f)});
    }
    for (const Collider& c : colliders()) {
        for (const float a : angles) {
            const Shape turned = c.turned(a);
            for (const Vec2 p : positions) {
                const Shape expected = rigid(c.local_shape(), p, a);
                ASSERT_TRUE(same(Collider::at(turned, p), expected)) << name_of(c.kind()) << " at angle " << a;
                ASSERT_TRUE(same(c.placed(p, a), expected)) << name_of(c.kind()) << " at angle " << a;
            }
        }
    }
}

// Collider::place reuses the storage of whatever `out` held before (the world's cached shape):
// the result must be at()'s, and a polygon's whole object (unused vertex slots included, which
// the SIMD paths read as zeros) the same bytes.
TEST(Placement, PlaceIntoAReusedShapeIsAtBitForBit) {
    std::vector<Collider> all = colliders();
    const std::vector<Vec2> triangle{{-3, -2}, {4, -1}, {3, 5}};
    const std::vector<Vec2> other_quad{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    all.push_back(Collider::polygon(*make_polygon(triangle)));
    all.push_back(Collider::polygon(*make_polygon(other_quad)));
    Rng rng(7);
    Shape out;  // carries over from one placement to the next, as a body's cached shape does
    for (int k = 0; k < 2000; ++k) {
        const Collider& c = all[rng.below(static_cast<std::uint32_t>(all.size()))];
        const float a = k % 50 == 0 ? kNan : rng.uniform(-4.0f, 4.0f);
        Vec2 p{rng.uniform(-3000.0f, 3000.0f), rng.uniform(-3000.0f, 3000.0f)};
        if (k % 37 == 0) p.x = kInf;
        if (k % 41 == 0) p.y = 3.4e38f;  // the sum overflows: the empty polygon
        const Shape turned = c.turned(a);
        const Shape expected = Collider::at(turned, p);
        Collider::place(turned, p, out);
        ASSERT_TRUE(same(out, expected)) << name_of(c.kind()) << " #" << k;
        if (const auto* poly = std::get_if<Polygon>(&out)) {
            ASSERT_EQ(std::memcmp(poly, &std::get<Polygon>(expected), sizeof(Polygon)), 0) << "#" << k;
        }
    }
}

// Collider::turn_into reuses `out` the same way (the world's turned collider): turned()'s
// shape, a polygon's whole object the same bytes, whatever out held before (another kind,
// another count, the same count, a non-finite angle's nowhere).
TEST(Placement, TurnIntoAReusedShapeIsTurnedBitForBit) {
    std::vector<Collider> all = colliders();
    const std::vector<Vec2> triangle{{-3, -2}, {4, -1}, {3, 5}};
    const std::vector<Vec2> other_quad{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    all.push_back(Collider::polygon(*make_polygon(triangle)));
    all.push_back(Collider::polygon(*make_polygon(other_quad)));
    Rng rng(11);
    Shape out;
    for (int k = 0; k < 2000; ++k) {
        const Collider& c = all[rng.below(static_cast<std::uint32_t>(all.size()))];
        float a = k % 50 == 0 ? kNan : rng.uniform(-4.0f, 4.0f);
        if (k % 43 == 0) a = kInf;
        const Shape expected = c.turned(a);
        c.turn_into(a, out);
        ASSERT_TRUE(same(out, expected)) << name_of(c.kind()) << " #" << k;
        if (const auto* poly = std::get_if<Polygon>(&out)) {
            ASSERT_EQ(std::memcmp(poly, &std::get<Polygon>(expected), sizeof(Polygon)), 0) << "#" << k;
        }
    }
}

TEST(Placement, NonFiniteAngleOrPositionMeetsNothing) {
    for (const Collider& c : colliders()) {
        for (const float a : {kNan, kInf, -kInf}) {
            const Shape s = Collider::at(c.turned(a), {1, 2});
            EXPECT_FALSE(overlaps(s, Circle{{1, 2}, 1e6f})) << name_of(c.kind());
        }
        for (const Vec2 p : {Vec2{kNan, 0}, Vec2{0, kInf}, Vec2{-kInf, kNan}}) {
            EXPECT_FALSE(overlaps(c.placed(p, 0.5f), Circle{{0, 0}, 1e6f})) << name_of(c.kind());
        }
    }
}

TEST(Placement, PolygonRotatedThenMovedIsTransformed) {
    const std::vector<Vec2> hexagon{{4, 0}, {2, 3.5f}, {-2, 3.5f}, {-4, 0}, {-2, -3.5f}, {2, -3.5f}};
    const Polygon poly = *make_polygon(hexagon);
    Rng rng(3);
    for (int k = 0; k < 500; ++k) {
        const Transform xf{{rng.uniform(-1e4f, 1e4f), rng.uniform(-1e4f, 1e4f)}, Rot::from_angle(rng.uniform(-7.0f, 7.0f))};
        ASSERT_TRUE(same(Shape{poly.rotated(xf.q).moved(xf.p)}, Shape{poly.transformed(xf)}));
    }
    // A rotation that overflows empties the polygon, as transformed() does.
    EXPECT_EQ(poly.rotated(Rot{kInf, 0}).count(), 0);
    EXPECT_EQ(poly.rotated(Rot{kNan, kNan}).count(), 0);
}

TEST(Placement, MasksMoveByWholePixelsAndNeverTurn) {
    const auto mask = std::make_shared<const Mask>(5, 3);
    const Collider c = Collider::mask(mask, -2, -1);
    for (const float a : {0.0f, 1.0f, -2.5f}) {
        const Shape s = Collider::at(c.turned(a), {10.4f, -3.6f});
        ASSERT_TRUE(std::holds_alternative<PlacedMask>(s));
        EXPECT_EQ(std::get<PlacedMask>(s).x, 8);
        EXPECT_EQ(std::get<PlacedMask>(s).y, -5);
        EXPECT_EQ(std::get<PlacedMask>(s).mask, mask.get());
    }
}

// The world's cached shapes follow spins, pushes, sweeps and every setter.
TEST(Placement, WorldShapesFollowEveryChange) {
    World world(WorldDesc{.gravity = {0, 0}});
    std::vector<EntityId> ids;
    Rng rng(9);
    const std::vector<Collider> kinds = colliders();
    for (int k = 0; k < 60; ++k) {
        EntityDesc d;
        d.kind = k % 7 == 0 ? BodyKind::kinematic : BodyKind::dynamic;
        d.position = {rng.uniform(0.0f, 200.0f), rng.uniform(0.0f, 200.0f)};
        d.angle = rng.uniform(-3.0f, 3.0f);
        d.velocity = {rng.uniform(-300.0f, 300.0f), rng.uniform(-300.0f, 300.0f)};
        d.angular_velocity = k % 3 == 0 ? 0.0f : rng.uniform(-5.0f, 5.0f);
        d.collider = kinds[static_cast<std::size_t>(k) % kinds.size()];
        d.restitution = 0.5f;
        ids.push_back(world.create(d));
    }
    world.create(EntityDesc{.position = {100, 210}, .collider = Collider::aabb({120, 5})});
    const auto check = [&](int step) {
        for (const EntityId id : ids) {
            const EntityDesc* d = world.get(id);
            ASSERT_NE(d, nullptr);
            ASSERT_TRUE(same(world.shape_of(id), d->collider.placed(d->position, d->angle)))
                << "entity " << id.index << " after step " << step;
        }
    };
    for (int step = 0; step < 120; ++step) {
        world.step(1.0f / 60.0f);
        check(step);
        const EntityId id = ids[static_cast<std::size_t>(step) % ids.size()];
        switch (step % 4) {
            case 0: world.set_angle(id, rng.uniform(-3.0f, 3.0f)); break;
            case 1: world.set_position(id, {rng.uniform(0.0f, 200.0f), rng.uniform(0.0f, 200.0f)}); break;
            case 2: world.set_collider(id, kinds[static_cast<std::size_t>(step / 4) % kinds.size()]); break;
            default: {
                EntityDesc d = *world.get(id);
                d.collider = kinds[static_cast<std::size_t>(step) % kinds.size()];
                d.angle += 0.5f;
                world.set(id, d);
            }
        }
        check(step);
    }
}

// The step's own cache (shape and bounds per body) must follow a new collider too: a static
// box that grows under a resting ball pushes it out in the next step, and every body's
// broadphase bounds hold its current shape after each setter.
TEST(Placement, StepSeesAStaticColliderGrow) {
    World world(WorldDesc{.gravity = {0, 0}});
    const EntityId wall = world.create(EntityDesc{.position = {0, 0}, .collider = Collider::aabb({5, 5})});
    const EntityId ball = world.create(
        EntityDesc{.kind = BodyKind::dynamic, .position = {12, 0}, .collider = Collider::circle(4)});
    for (int k = 0; k < 3; ++k) world.step(1.0f / 60.0f);  // apart: 3 px gap; nothing moves
    ASSERT_EQ(world.get(ball)->position.x, 12.0f);
    ASSERT_TRUE(world.set_collider(wall, Collider::aabb({10, 10})));  // now 2 px into the ball
    world.step(1.0f / 60.0f);
    EXPECT_GE(world.get(ball)->position.x, 14.0f - 0.01f);  // pushed out by the whole MTD
    ASSERT_TRUE(world.set(wall, EntityDesc{.position = {0, 0}, .collider = Collider::box({20, 20}, {}, 0.3f)}));
    world.step(1.0f / 60.0f);
    EXPECT_FALSE(overlaps(world.shape_of(ball), world.shape_of(wall)) &&
                 collide(world.shape_of(wall), world.shape_of(ball)).depth > 0.01f);
}

TEST(Placement, BroadphaseBoundsHoldTheShapeAfterEverySetter) {
    World world(WorldDesc{.gravity = {0, 0}});
    const std::vector<Collider> kinds = colliders();
    std::vector<EntityId> ids;
    for (std::size_t k = 0; k < kinds.size(); ++k) {
        ids.push_back(world.create(EntityDesc{.kind = k % 2 ? BodyKind::static_body : BodyKind::dynamic,
                                              .position = {30.0f * static_cast<float>(k), 0},
                                              .collider = kinds[k]}));
    }
    const auto holds = [&](EntityId id) {
        const std::optional<Aabb> fat = world.broadphase_bounds(id);
        const Aabb tight = bounds(world.shape_of(id));
        return fat && fat->min.x <= tight.min.x && fat->min.y <= tight.min.y && tight.max.x <= fat->max.x &&
               tight.max.y <= fat->max.y;
    };
    Rng rng(5);
    for (int round = 0; round < 50; ++round) {
        for (std::size_t k = 0; k < ids.size(); ++k) {
            const EntityId id = ids[k];
            switch ((round + static_cast<int>(k)) % 3) {
                case 0: world.set_collider(id, kinds[rng.below(static_cast<std::uint32_t>(kinds.size()))]); break;
                case 1: world.set_angle(id, rng.uniform(-3.0f, 3.0f)); break;
                default: world.set_position(id, {rng.uniform(-100.0f, 100.0f), rng.uniform(-100.0f, 100.0f)});
            }
            ASSERT_TRUE(holds(id)) << "entity " << k << " in round " << round;
        }
        world.step(1.0f / 60.0f);
        for (const EntityId id : ids) ASSERT_TRUE(holds(id)) << "after step " << round;
    }
}

}  // namespace
}  // namespace jostle
