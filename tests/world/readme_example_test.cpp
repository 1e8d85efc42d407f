// The README's world example, compiled and run as written, so the README stays true: the
// ball lands on the floor and rests there.
#include <gtest/gtest.h>

#include "jostle/world.h"

using namespace jostle;

TEST(ReadmeExample, BallLandsOnTheFloor) {
    World world(WorldDesc{.gravity = {0.0f, 980.0f}, .seed = 1});   // px, y down
    world.create({.position = {320, 470}, .collider = Collider::aabb({320, 10})});   // static floor
    const EntityId ball = world.create({.kind = BodyKind::dynamic, .position = {320, 0},
                                        .collider = Collider::circle(8), .restitution = 0.5f});
    world.set_event_handler([](World& w, const Event& e) {
        if (e.type == EventType::bullet_hit) w.destroy(e.b);   // the game decides what a hit does
    });
    for (int tick = 0; tick < 600; ++tick) world.step(1.0f / 60.0f);

    // Floor top at y = 460; the ball (radius 8) rests with its centre at 452.
    ASSERT_TRUE(world.alive(ball));
    EXPECT_NEAR(world.get(ball)->position.y, 452.0f, world.desc().slop);
    EXPECT_EQ(world.get(ball)->position.x, 320.0f);
}
