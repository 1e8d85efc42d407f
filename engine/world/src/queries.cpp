// Queries for the game: entities overlapping a box, entities at a point, and the first
// entity along a segment. Answered from current positions through the broadphase, exactly
// by the collision module; results in id order.
#include <algorithm>

#include "internal.h"

namespace jostle {

namespace {

std::vector<EntityId> overlapping(const World::Impl& w, const Aabb& box, const Shape& probe, std::uint32_t layers) {
    std::vector<std::uint32_t> hits;
    w.broadphase.query(box, [&](std::uint32_t j) {
        const detail::Slot& s = w.slots[j];
        if ((s.body.layer & layers) == 0) return;
        if (overlaps(w.placed(j), probe)) hits.push_back(j);
    });
    std::sort(hits.begin(), hits.end());
    std::vector<EntityId> out;
    out.reserve(hits.size());
    for (std::uint32_t j : hits) out.push_back(w.id_of(j));
    return out;
}

}  // namespace

std::vector<EntityId> World::query_aabb(const Aabb& box, std::uint32_t layers) const {
    if (!detail::Broadphase::usable(box)) return {};
    return overlapping(impl(), box, box, layers);
}

std::vector<EntityId> World::query_point(Vec2 p, std::uint32_t layers) const {
    const Aabb box{p, p};
    if (!detail::Broadphase::usable(box)) return {};
    // A point as a zero-length segment: for masks it meets the pixel squares it touches.
    return overlapping(impl(), box, Segment{p, p}, layers);
}

std::optional<RayHit> World::cast_segment(Vec2 from, Vec2 to, std::uint32_t layers, EntityId ignore) const {
    const Aabb box{min(from, to), max(from, to)};
    if (!detail::Broadphase::usable(box)) return std::nullopt;
    const Impl& w = impl();
    std::optional<RayHit> best;
    w.broadphase.query(box, [&](std::uint32_t j) {
        const detail::Slot& s = w.slots[j];
        const EntityId id = w.id_of(j);
        if ((s.body.layer & layers) == 0 || id == ignore) return;
        const CastHit h = cast(from, to, w.placed(j));
        if (!h.hit) return;
        if (!best || h.t < best->t || (h.t == best->t && id < best->id)) best = RayHit{id, h.t, h.point, h.normal};
    });
    return best;
}

std::optional<Aabb> World::broadphase_bounds(EntityId id) const {
    const detail::Slot* s = impl().find(id);
    if (s == nullptr || s->proxy < 0) return std::nullopt;
    return impl().broadphase.fat_bounds(s->proxy);
}

}  // namespace jostle
