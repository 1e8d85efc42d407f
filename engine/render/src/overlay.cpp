// The debug overlay (jostle/render/overlay.h): reads the world through a const reference and
// draws outlines, bounds, contacts and continuous paths with the Renderer's primitives.
#include "jostle/render/overlay.h"

namespace jostle {

namespace {

// An arrow from a to b in world pixels, its head a fixed size on screen.
void arrow(Renderer& r, Vec2 a, Vec2 b, Color color, float thickness) {
    r.draw_line(a, b, color, thickness);
    const Vec2 dir = normalize_or(b - a, Vec2{});
    if (dir == Vec2{}) return;
    const Vec2 back = b - 4.0f * dir;
    r.draw_line(b, back + 3.0f * perp(dir), color, thickness);
    r.draw_line(b, back - 3.0f * perp(dir), color, thickness);
}

}  // namespace

Color overlay_color(BodyKind kind) {
    switch (kind) {
        case BodyKind::static_body: return kOverlayStatic;
        case BodyKind::kinematic: return kOverlayKinematic;
        case BodyKind::dynamic: return kOverlayDynamic;
        case BodyKind::bullet: return kOverlayBullet;
        case BodyKind::trigger: return kOverlayTrigger;
    }
    return kOverlayStatic;
}

void draw_overlay(Renderer& r, const World& world, const OverlayOptions& o) {
    const std::vector<EntityId> ids = world.entities();
    if (o.broadphase) {
        for (EntityId id : ids) {
            if (const auto box = world.broadphase_bounds(id)) r.outline_shape(*box, kOverlayBroadphase, o.thickness);
        }
    }
    if (o.colliders) {
        for (EntityId id : ids) r.outline_shape(world.shape_of(id), overlay_color(world.get(id)->kind), o.thickness);
    }
    if (o.paths) {
        for (const SweptPath& p : world.swept_paths()) {
            r.draw_line(p.from, p.to, kOverlayPath, o.thickness);
            if (p.radius > 0.0f) {
                r.outline_shape(Circle{p.from, p.radius}, kOverlayPath, o.thickness);
                r.outline_shape(Circle{p.to, p.radius}, kOverlayPath, o.thickness);
            }
        }
    }
    if (o.contacts) {
        for (const Contact& c : world.contacts()) {
            // The normal from a toward b, 10 px long; the MTD (how far b was pushed) when deep.
            arrow(r, c.point, c.point + 10.0f * c.normal, kOverlayContact, o.thickness);
            if (c.depth > 0.5f) arrow(r, c.point, c.point + c.depth * c.normal, kOverlayMtd, o.thickness);
            r.fill_shape(Circle{c.point, 1.5f}, kOverlayContact);
        }
    }
}

}  // namespace jostle
