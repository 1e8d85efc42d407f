// Regressions: each bug an adversarial review of the world found, with the input that
// showed it (boxes snagging on tile seams, events after a kind change, sweep settings).
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>

#include "jostle/world.h"

using namespace jostle;

namespace {

constexpr float kDt = 1.0f / 60.0f;

int count(const World& w, EventType type) {
    int n = 0;
    for (const Event& e : w.events()) n += e.type == type;
    return n;
}

}  // namespace

// A frictionless box sliding over a floor of 16 px tiles used to stop dead at a seam: it
// sank g*dt^2 into the floor each step, so the next tile's side was a shallower push than
// its top. Carried contacts now hold resting bodies before they move.
TEST(WorldRegression, BoxesAndBallsSlideOverTileSeams) {
    for (const float speed : {30.0f, 90.0f, 170.0f, 333.0f, 600.0f}) {
        for (const bool ball : {false, true}) {
            World w(WorldDesc{.gravity = {0.0f, 980.0f}});
            for (int k = 0; k < 400; ++k) {
                w.create({.position = {static_cast<float>(k) * 16.0f, 8.0f}, .collider = Collider::aabb({8.0f, 8.0f})});
            }
            const EntityId body = w.create({.kind = BodyKind::dynamic,
                                            .position = {20.0f, ball ? -3.0f : -5.0f},
                                            .velocity = {speed, 0.0f},
                                            .collider = ball ? Collider::circle(3.0f) : Collider::aabb({5.0f, 5.0f}),
                                            .friction = 0.0f});
            for (int s = 0; s < 300; ++s) {
                w.step(kDt);
                const EntityDesc* e = w.get(body);
                ASSERT_NEAR(e->velocity.x, speed, 0.02f * speed) << (ball ? "ball" : "box") << " at " << speed << " px/s, step " << s;
                ASSERT_NEAR(e->position.y, ball ? -3.0f : -5.0f, 0.01f) << "step " << s;
            }
        }
    }
}

// set() turning a touching dynamic body into a trigger ends the contact and enters the
// trigger; turning a trigger into a static body exits with the old trigger named first.
TEST(WorldRegression, KindChangeEndsOldContactsAndBeginsNewOnes) {
    World w;
    w.create({.position = {0.0f, 10.0f}, .collider = Collider::aabb({50.0f, 5.0f})});
    const EntityId d = w.create({.kind = BodyKind::dynamic, .collider = Collider::aabb({5.0f, 5.0f})});
    w.step(kDt);
    ASSERT_EQ(count(w, EventType::contact_begin), 1);
    EntityDesc t = *w.get(d);
    t.kind = BodyKind::trigger;
    w.set(d, t);
    w.step(kDt);
    EXPECT_EQ(count(w, EventType::contact_end), 1);
    ASSERT_EQ(count(w, EventType::trigger_enter), 1);
    w.set_position(d, {0.0f, -100.0f});
    w.step(kDt);
    ASSERT_EQ(count(w, EventType::trigger_exit), 1);
    EXPECT_EQ(w.events()[0].a, d);

    World w2;
    const EntityId trig = w2.create({.kind = BodyKind::trigger, .collider = Collider::aabb({5.0f, 5.0f})});
    const EntityId dyn = w2.create({.kind = BodyKind::dynamic, .position = {3.0f, 0.0f}, .collider = Collider::aabb({5.0f, 5.0f})});
    w2.step(kDt);
    ASSERT_EQ(count(w2, EventType::trigger_enter), 1);
    EntityDesc s = *w2.get(trig);
    s.kind = BodyKind::static_body;
    s.position = {500.0f, 0.0f};
    w2.set(trig, s);
    w2.step(kDt);
    ASSERT_EQ(w2.events().size(), 1u);
    EXPECT_EQ(w2.events()[0].type, EventType::trigger_exit);
    EXPECT_EQ(w2.events()[0].a, trig);
    EXPECT_EQ(w2.events()[0].b, dyn);
}

// max_sweep_hits <= 0 used to freeze every fast circle (it was never moved).
TEST(WorldRegression, NonPositiveMaxSweepHitsStillMovesFastCircles) {
    World w(WorldDesc{.max_sweep_hits = 0});
    const EntityId c = w.create({.kind = BodyKind::dynamic, .velocity = {600.0f, 0.0f}, .collider = Collider::circle(1.0f)});
    w.step(kDt);
    EXPECT_NEAR(w.get(c)->position.x, 10.0f, 1e-4f);
}

// A dynamic circle with no inverse mass cannot be pushed, so it passes through static
// bodies; swept (fast) it used to stop on them every step while gravity grew its speed.
TEST(WorldRegression, ImmovableFastCircleBehavesLikeASlowOne) {
    World w(WorldDesc{.gravity = {0.0f, 980.0f}});
    w.create({.position = {0.0f, 50.0f}, .collider = Collider::aabb({100.0f, 5.0f})});
    const EntityId c = w.create({.kind = BodyKind::dynamic, .position = {0.0f, 40.0f}, .velocity = {0.0f, 600.0f},
                                 .collider = Collider::circle(2.0f), .inverse_mass = 0.0f});
    for (int s = 0; s < 10; ++s) w.step(kDt);
    EXPECT_GT(w.get(c)->position.y, 60.0f);
}

// Found by tests/fuzz/world_fuzz.cpp: a bullet at rest that spins had its collider turned
// each step but its broadphase proxy left where the collider had been, so the queries (which
// go through the proxies) missed it where it now lay.
TEST(WorldRegression, ASpinningBulletAtRestIsFoundWhereItsColliderIs) {
    World w;
    const EntityId bullet = w.create({.kind = BodyKind::bullet,
                                      .angular_velocity = 3.0f,
                                      .collider = Collider::segment({-20.0f, 0.0f}, {20.0f, 0.0f})});
    for (int s = 0; s < 30; ++s) w.step(kDt);  // half a turn in all: about 1.5 rad
    const float angle = w.get(bullet)->angle;
    ASSERT_GT(angle, 1.4f);
    const Vec2 tip{19.0f * std::cos(angle), 19.0f * std::sin(angle)};
    EXPECT_EQ(w.query_point(tip), std::vector<EntityId>{bullet});
    EXPECT_EQ(w.query_aabb({tip - Vec2{0.5f, 0.5f}, tip + Vec2{0.5f, 0.5f}}), std::vector<EntityId>{bullet});
    const std::optional<RayHit> hit = w.cast_segment(tip + Vec2{-5.0f, 0.0f}, tip + Vec2{5.0f, 0.0f});
    ASSERT_TRUE(hit.has_value());
    EXPECT_EQ(hit->id, bullet);
}

// Found by tests/fuzz/world_fuzz.cpp: a fast circle's sweep gave the body it stopped on
// (inverse mass 0 to resolution) its share of the impulse, 0 * the impulse: a static body's
// velocity field of -0 came back +0 (so its state hash changed), and an infinite impulse
// would have made it NaN. Only bodies resolution can move take an impulse now.
TEST(WorldRegression, AFastCircleStoppingOnAnImmovableBodyLeavesItsVelocityFieldAlone) {
    for (const BodyKind kind : {BodyKind::static_body, BodyKind::kinematic}) {
        World w;
        const Vec2 field{-0.0f, kind == BodyKind::static_body ? -952.0f : -0.0f};
        const EntityId wall =
            w.create({.kind = kind, .position = {100.0f, 0.0f}, .velocity = field, .collider = Collider::aabb({5.0f, 50.0f})});
        const EntityId ball = w.create({.kind = BodyKind::dynamic,
                                        .position = {60.0f, 0.0f},
                                        .velocity = {3000.0f, 0.0f},
                                        .collider = Collider::circle(2.0f),
                                        .restitution = 0.5f,
                                        .gravity_scale = 0.0f});
        w.step(kDt);
        ASSERT_LT(w.get(ball)->velocity.x, 0.0f) << "the ball bounced off (" << name_of(kind) << ")";
        const Vec2 v = w.get(wall)->velocity;
        EXPECT_TRUE(std::signbit(v.x)) << name_of(kind) << ": " << v.x;
        EXPECT_EQ(std::bit_cast<std::uint32_t>(v.y), std::bit_cast<std::uint32_t>(field.y)) << name_of(kind);
    }
}

// Found by tests/fuzz/world_fuzz.cpp: a fast circle of inverse mass 0 crossing more bodies in
// a step than max_sweep_hits lost the rest of its motion, as a movable one does (stopping is
// safe for those), and spent its hits on the first body, met again at t = 0. Resolution never
// moves it, so it now goes all the way, as a slow one would, and hits the bodies on its way.
TEST(WorldRegression, AnImmovableFastCircleCrossingACrowdKeepsItsMotion) {
    World w;
    const EntityId ball = w.create({.kind = BodyKind::dynamic,
                                    .velocity = {6000.0f, 0.0f},  // 100 px a step
                                    .collider = Collider::circle(2.0f),
                                    .inverse_mass = 0.0f,
                                    .gravity_scale = 0.0f});
    std::vector<EntityId> crowd;
    for (int k = 1; k <= 8; ++k) {
        crowd.push_back(w.create({.kind = BodyKind::dynamic,
                                  .position = {10.0f * static_cast<float>(k), 0.0f},
                                  .collider = Collider::aabb({1.0f, 1.0f}),
                                  .gravity_scale = 0.0f}));
    }
    w.step(kDt);
    EXPECT_NEAR(w.get(ball)->position.x, 100.0f, 1e-3f);
    EXPECT_EQ(w.get(ball)->velocity.x, 6000.0f);
    // It meets the first max_sweep_hits (4) on its way, one after the other (it used to meet
    // the first again at t = 0, which had not moved yet); resolution pushes the rest next step.
    for (std::size_t k = 0; k < 4; ++k) EXPECT_GT(w.get(crowd[k])->velocity.x, 0.0f) << "body " << k + 1 << " was hit";
}
