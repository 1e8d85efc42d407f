// The debug overlay drawn from a const World: collider outlines in their body kind's colour
// at the right pixels (interiors left alone), contact normals, and nothing when turned off.
#include <gtest/gtest.h>

#include "jostle/render/overlay.h"

#include "render/render_test_util.h"

using namespace jostle;

namespace {

Color at(const Image& im, int x, int y) { return pixel_at(im, x, y); }

constexpr Color kBlack{0, 0, 0, 255};

}  // namespace


TEST(Overlay, OutlinesInTheirKindsColourAtTheirEdges) {
    World world;
    world.create({.position = {20, 20}, .collider = Collider::aabb({10, 5})});  // x 10..30, y 15..25
    world.create({.kind = BodyKind::dynamic, .position = {50, 30}, .collider = Collider::circle(8)});
    world.create({.kind = BodyKind::trigger, .position = {20, 40}, .collider = Collider::aabb({4, 4})});  // x 16..24, y 36..44
    Renderer r;
    r.begin_frame(64, 48, kBlack);
    draw_overlay(r, world, {.thickness = 2.0f});
    const Image& im = r.end_frame();
    // A 2 px line centred on the edge covers the pixels on both sides of it.
    EXPECT_EQ(at(im, 9, 20), kOverlayStatic);
    EXPECT_EQ(at(im, 10, 20), kOverlayStatic);
    EXPECT_EQ(at(im, 20, 14), kOverlayStatic);
    EXPECT_EQ(at(im, 20, 20), kBlack);  // interior
    EXPECT_EQ(at(im, 7, 20), kBlack);   // outside
    EXPECT_EQ(at(im, 57, 30), kOverlayDynamic);  // circle's right edge at x = 58
    EXPECT_EQ(at(im, 50, 30), kBlack);
    EXPECT_EQ(at(im, 15, 40), kOverlayTrigger);
}

TEST(Overlay, ContactNormalsAndNothingWhenOff) {
    World world;
    world.create({.position = {32, 30}, .collider = Collider::aabb({30, 4})});  // top at y = 26
    world.create({.kind = BodyKind::dynamic, .position = {32, 20}, .collider = Collider::aabb({4, 7})});  // 1 px deep
    world.step(1.0f / 60.0f);
    ASSERT_EQ(world.contacts().size(), 1u);
    const Contact c = world.contacts()[0];
    Renderer r;
    r.begin_frame(64, 48, kBlack);
    draw_overlay(r, world, {.colliders = false, .thickness = 2.0f});
    const Image& im = r.end_frame();
    // The normal (from the floor up to the box) is drawn upward from the contact point.
    const Vec2 tip = c.point + 6.0f * c.normal;
    EXPECT_EQ(at(im, static_cast<int>(tip.x), static_cast<int>(tip.y)), kOverlayContact);
    r.begin_frame(64, 48, kBlack);
    draw_overlay(r, world, {.colliders = false, .contacts = false, .paths = false});
    const Image& empty = r.end_frame();
    for (std::size_t i = 0; i < empty.rgba.size(); i += 4) ASSERT_EQ(empty.rgba[i], 0);
}
