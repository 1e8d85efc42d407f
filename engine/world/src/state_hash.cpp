// World::state_hash: every field that affects the future, hashed from exact bytes, field by
// field (never whole structs, whose padding is not part of the state).
#include "internal.h"
#include "jostle/core/hash.h"

namespace jostle {

namespace {

void hash_vec(Hasher& h, Vec2 v) {
    h.f32(v.x);
    h.f32(v.y);
}

void hash_id(Hasher& h, EntityId id) {
    h.u32(id.index);
    h.u32(id.generation);
}

void hash_shape(Hasher& h, const Shape& shape, std::uint64_t mask_fingerprint) {
    h.u32(static_cast<std::uint32_t>(shape.index()));
    struct Visit {
        Hasher& h;
        std::uint64_t fingerprint;
        void operator()(const Aabb& b) const { hash_vec(h, b.min); hash_vec(h, b.max); }
        void operator()(const Obb& b) const { hash_vec(h, b.center); hash_vec(h, b.half); h.f32(b.angle()); }
        void operator()(const Circle& c) const { hash_vec(h, c.center); h.f32(c.radius); }
        void operator()(const Segment& s) const { hash_vec(h, s.a); hash_vec(h, s.b); }
        void operator()(const Polygon& p) const {
            h.u32(static_cast<std::uint32_t>(p.count()));
            for (int i = 0; i < p.count(); ++i) {
                hash_vec(h, p.points()[i]);
                hash_vec(h, p.normals()[i]);
            }
        }
        void operator()(const PlacedMask& m) const {
            h.u32(static_cast<std::uint32_t>(m.x));
            h.u32(static_cast<std::uint32_t>(m.y));
            h.u64(fingerprint);  // the mask's pixels, hashed once when the collider was set
        }
    };
    std::visit(Visit{h, mask_fingerprint}, shape);
}

}  // namespace

std::uint64_t World::state_hash() const {
    const Impl& w = impl();
    Hasher h;
    h.u64(w.steps);
    h.u64(w.rng.state());
    h.u64(w.rng.stream());
    h.u64(w.slots.size());
    for (const detail::Slot& s : w.slots) {
        h.u32(s.generation);
        h.u32(s.alive ? 1u : 0u);
        if (!s.alive) continue;
        const EntityDesc& b = s.body;
        h.u32(static_cast<std::uint32_t>(b.kind));
        hash_vec(h, b.position);
        h.f32(b.angle);
        hash_vec(h, b.velocity);
        h.f32(b.angular_velocity);
        hash_shape(h, b.collider.local_shape(), s.mask_fingerprint);
        h.f32(b.inverse_mass);
        h.f32(b.restitution);
        h.f32(b.friction);
        h.f32(b.gravity_scale);
        h.u32(b.layer);
        h.u32(b.collides_with);
        h.u32(static_cast<std::uint32_t>(b.on_hit));
        hash_id(h, b.ignore);
        h.u64(b.user_data);
    }
    // The id allocator decides the ids of entities created later.
    h.u64(w.free_slots.size());
    for (std::uint32_t f : w.free_slots) h.u32(f);
    // Contacts carried over decide the next step's begin and end events.
    h.u64(w.contacts.size());
    for (const Contact& c : w.contacts) {
        hash_id(h, c.a);
        hash_id(h, c.b);
        hash_vec(h, c.point);
        hash_vec(h, c.normal);
        h.f32(c.depth);
        h.u32(c.trigger ? 1u : 0u);
        h.u32(c.trigger_is_b ? 1u : 0u);
        h.u32(c.corner ? 1u : 0u);
    }
    return h.value();
}

}  // namespace jostle
