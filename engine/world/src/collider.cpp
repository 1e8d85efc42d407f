// Colliders: shapes in an entity's frame, and placing them at the entity's transform.
// Also the names of body kinds and event types.
#include <cmath>
#include <limits>
#include <type_traits>
#include <variant>

#include "jostle/world.h"

namespace jostle {

namespace {

// A shape the collision module treats as invalid: it meets nothing.
Shape nowhere() {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    return Circle{{nan, nan}, 0.0f};
}

// The nearest whole pixel, for a mask's placement; bounded so the conversion is defined
// (far-away masks answer "miss" in the collision module anyway).
int nearest_pixel(float v) {
    const double r = std::floor(static_cast<double>(v) + 0.5);
    return static_cast<int>(std::fmax(-1e9, std::fmin(1e9, r)));
}

// position + offset without int overflow.
int add_offset(int position, int offset) {
    const long long sum = static_cast<long long>(position) + offset;
    return static_cast<int>(sum < -2000000000LL ? -2000000000LL : (sum > 2000000000LL ? 2000000000LL : sum));
}

}  // namespace

Collider Collider::aabb(Vec2 half_size, Vec2 offset) {
    Collider c;
    c.shape_ = Aabb{offset - half_size, offset + half_size};
    return c;
}

Collider Collider::box(Vec2 half_size, Vec2 offset, float angle) {
    Collider c;
    c.shape_ = Obb{offset, half_size, angle};
    return c;
}

Collider Collider::circle(float radius, Vec2 offset) {
    Collider c;
    c.shape_ = Circle{offset, radius};
    return c;
}

Collider Collider::polygon(const Polygon& poly) {
    Collider c;
    c.shape_ = poly;
    return c;
}

Collider Collider::segment(Vec2 a, Vec2 b) {
    Collider c;
    c.shape_ = Segment{a, b};
    return c;
}

Collider Collider::mask(std::shared_ptr<const Mask> mask) {
    const int w = mask ? mask->width() : 0;
    const int h = mask ? mask->height() : 0;
    return Collider::mask(std::move(mask), -(w / 2), -(h / 2));
}

Collider Collider::mask(std::shared_ptr<const Mask> mask, int offset_x, int offset_y) {
    Collider c;
    c.shape_ = PlacedMask{mask.get(), offset_x, offset_y};
    c.mask_ = std::move(mask);
    return c;
}

Shape Collider::placed(Vec2 position, float angle) const { return at(turned(angle), position); }

namespace {
struct Turn {
    Rot q;
    float angle;
    Shape operator()(const Aabb& b) const { return b; }  // never turns
    Shape operator()(const Obb& b) const { return Obb{rotate(q, b.center), b.half, b.angle() + angle}; }
    Shape operator()(const Circle& c) const { return Circle{rotate(q, c.center), c.radius}; }
    Shape operator()(const Segment& s) const { return Segment{rotate(q, s.a), rotate(q, s.b)}; }
    Shape operator()(const Polygon& p) const { return p.rotated(q); }
    Shape operator()(const PlacedMask& m) const { return m; }  // never turns
};
}  // namespace

Shape Collider::turned(float angle) const {
    if (!std::isfinite(angle)) return nowhere();
    return std::visit(Turn{Rot::from_angle(angle), angle}, shape_);
}

void Collider::turn_into(float angle, Shape& out) const {
    if (!std::isfinite(angle)) {
        out = nowhere();
        return;
    }
    const Rot q = Rot::from_angle(angle);
    // A polygon into the polygon already there (a Shape is as large as a Polygon: building
    // one and copying it was most of turning one); the other shapes are small.
    const Polygon* from = std::get_if<Polygon>(&shape_);
    Polygon* to = std::get_if<Polygon>(&out);
    if (from != nullptr && to != nullptr) {
        from->rotated_into(q, *to);
        return;
    }
    out = std::visit(Turn{q, angle}, shape_);
}

namespace {
// Translation only: rotate(q, v) + p is what apply(Transform{p, q}, v) computes, so the two
// halves round exactly as one placement would. Each alternative to its own type, so that
// place() can write it into a Shape that already holds one (a Shape is as large as a
// Polygon: building one per placement and copying it was most of placing a circle).
struct Move {
    Vec2 p;
    Aabb operator()(const Aabb& b) const { return Aabb{b.min + p, b.max + p}; }
    Obb operator()(Obb b) const {
        b.center = b.center + p;
        return b;
    }
    Circle operator()(const Circle& c) const { return Circle{c.center + p, c.radius}; }
    Segment operator()(const Segment& s) const { return Segment{s.a + p, s.b + p}; }
    Polygon operator()(const Polygon& poly) const { return poly.moved(p); }
    PlacedMask operator()(const PlacedMask& m) const {
        return PlacedMask{m.mask, add_offset(nearest_pixel(p.x), m.x), add_offset(nearest_pixel(p.y), m.y)};
    }
};
}  // namespace

Shape Collider::at(const Shape& turned, Vec2 position) {
    if (!is_finite(position)) return nowhere();
    return std::visit([&](const auto& t) -> Shape { return Move{position}(t); }, turned);
}

void Collider::place(const Shape& turned, Vec2 position, Shape& out) {
    if (!is_finite(position)) {
        out = nowhere();
        return;
    }
    std::visit(
        [&](const auto& t) {
            using T = std::decay_t<decltype(t)>;
            T* o = std::get_if<T>(&out);
            if constexpr (std::is_same_v<T, Polygon>) {
                if (o == nullptr) o = &out.emplace<Polygon>();
                t.moved_into(position, *o);
            } else if (o != nullptr) {
                *o = Move{position}(t);
            } else {
                out.emplace<T>(Move{position}(t));
            }
        },
        turned);
}

const char* name_of(BodyKind k) {
    switch (k) {
        case BodyKind::static_body: return "static";
        case BodyKind::kinematic: return "kinematic";
        case BodyKind::dynamic: return "dynamic";
        case BodyKind::bullet: return "bullet";
        case BodyKind::trigger: return "trigger";
    }
    return "?";
}

const char* name_of(EventType t) {
    switch (t) {
        case EventType::contact_begin: return "contact_begin";
        case EventType::contact_end: return "contact_end";
        case EventType::trigger_enter: return "trigger_enter";
        case EventType::trigger_exit: return "trigger_exit";
        case EventType::bullet_hit: return "bullet_hit";
    }
    return "?";
}

}  // namespace jostle
