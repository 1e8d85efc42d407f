// The sweeps phase: continuous collision. Bullets move as segment casts from their last to
// their next position; fast dynamic circles are swept (time of first contact) and stop at
// the first contact instead of passing through. See the MANUAL in jostle/world.h.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "internal.h"
#include "jostle/core/error.h"

namespace jostle {

using detail::Slot;

namespace {

// Bullets and fast circles meet everything but bullets and triggers.
bool blocks(const EntityDesc& b) { return b.kind != BodyKind::bullet && b.kind != BodyKind::trigger; }

Aabb segment_bounds(Vec2 a, Vec2 b) { return {min(a, b), max(a, b)}; }

// How far a ricocheting bullet is set off the surface it hit, so the rest of its path (and
// the next step's) does not start on that surface: more than a float step at its coordinates.
float lift_off(Vec2 p, float slop) { return slop + 1e-6f * std::fmax(std::fabs(p.x), std::fabs(p.y)); }

}  // namespace

void World::Impl::bounce(std::uint32_t a, std::uint32_t b, Vec2 n) {
    EntityDesc& ba = slots[a].body;
    EntityDesc& bb = slots[b].body;
    const float ima = detail::resolution_inverse_mass(ba);
    const float imb = detail::resolution_inverse_mass(bb);
    const float k = ima + imb;
    if (!(k > 0.0f)) return;
    const float vn = dot(detail::contact_velocity(bb) - detail::contact_velocity(ba), n);
    if (!(vn < 0.0f)) return;
    const float e = std::fmax(std::isfinite(ba.restitution) ? ba.restitution : 0.0f,
                              std::isfinite(bb.restitution) ? bb.restitution : 0.0f);
    const float target = vn < -desc.restitution_threshold ? -std::fmax(e, 0.0f) * vn : 0.0f;
    const float jn = (target - vn) / k;
    // Only a body the contact can move takes the impulse: a static or kinematic one keeps its
    // velocity field to the bit (0 * an impulse would turn its -0 into +0, or an infinity
    // into NaN).
    if (ima > 0.0f) ba.velocity -= (ima * jn) * n;
    if (imb > 0.0f) bb.velocity += (imb * jn) * n;
    const Vec2 t = perp(n);
    const float mu = std::sqrt(std::fmax(ba.friction, 0.0f) * std::fmax(bb.friction, 0.0f));
    const float limit = std::isfinite(mu) ? mu * jn : 0.0f;
    const float jt = std::clamp(-dot(detail::contact_velocity(bb) - detail::contact_velocity(ba), t) / k, -limit, limit);
    if (ima > 0.0f) ba.velocity -= (ima * jt) * t;
    if (imb > 0.0f) bb.velocity += (imb * jt) * t;
}

void World::Impl::sweeps(float dt, std::vector<Contact>& touching, const std::vector<detail::Pair>& pairs) {
    const auto n_slots = static_cast<std::uint32_t>(slots.size());

    // Bullets, in id order.
    for (const std::uint32_t i : bullets) {
        if (!slots[i].alive || slots[i].body.kind != BodyKind::bullet) continue;
        const EntityId id = id_of(i);
        Vec2 from = slots[i].body.position;
        Vec2 velocity = slots[i].body.velocity;
        // A bullet at rest (stopped on a hit, say) has no path, so it hits nothing again. (Its
        // proxy still follows its collider, which integrate may have turned.)
        if (velocity.x == 0.0f && velocity.y == 0.0f) {
            sync_proxy(i);
            continue;
        }
        float done = 0.0f;  // fraction of the step's path already travelled
        std::uint32_t last_hit = n_slots;  // none
        bool despawned = false;
        for (int hits = 0;; ++hits) {
            const Vec2 to = from + ((1.0f - done) * dt) * velocity;
            paths.push_back({id, from, to, 0.0f});
            if (!is_finite(to) || !is_finite(from)) {
                slots[i].body.position = to;
                break;
            }
            const EntityDesc& me = slots[i].body;
            std::uint32_t best = n_slots;
            CastHit best_hit;
            broadphase.query(segment_bounds(from, to), [&](std::uint32_t j) {
                if (j == i || !blocks(slots[j].body) || !detail::may_meet(me, id, slots[j].body, id_of(j))) return;
                const CastHit h = cast(from, to, placement(j).shape);
                if (!h.hit || (j == last_hit && h.t == 0.0f)) return;
                // On a surface and moving off it or along it (a bullet stopped on a wall and fired
                // away, or made touching one): t = 0 there is where the path starts, not a path
                // into the shape. (A start strictly inside has no normal, and is a hit.)
                if (h.t == 0.0f && (h.normal.x != 0.0f || h.normal.y != 0.0f) && dot(to - from, h.normal) >= 0.0f) return;
                if (best == n_slots || h.t < best_hit.t || (h.t == best_hit.t && j < best)) {
                    best = j;
                    best_hit = h;
                }
            });
            if (best == n_slots) {
                slots[i].body.position = to;
                break;
            }
            paths.back().to = best_hit.point;
            Event e;
            e.type = EventType::bullet_hit;
            e.a = id;
            e.b = id_of(best);
            e.a_user_data = me.user_data;
            e.b_user_data = slots[best].body.user_data;
            e.point = best_hit.point;
            e.normal = best_hit.normal;
            e.fraction = std::fmin(done + best_hit.t * (1.0f - done), 1.0f);
            events.push_back(e);
            const bool reflectable = best_hit.normal.x != 0.0f || best_hit.normal.y != 0.0f;
            if (me.on_hit == BulletResponse::despawn) {
                remove(i);
                despawned = true;
                break;
            }
            if (me.on_hit == BulletResponse::stop || !reflectable) {
                slots[i].body.position = best_hit.point;
                slots[i].body.velocity = {};
                break;
            }
            // Ricochet: mirror the velocity in the surface and go on with the rest of the path.
            const Vec2 n = best_hit.normal;
            velocity = velocity - (2.0f * dot(velocity, n)) * n;
            slots[i].body.velocity = velocity;
            from = best_hit.point + lift_off(best_hit.point, desc.slop) * n;
            done = e.fraction;
            last_hit = best;
            if (hits + 1 >= std::max(desc.max_sweep_hits, 1) || done >= 1.0f) {
                slots[i].body.position = from;
                break;
            }
        }
        if (!despawned) sync_proxy(i, slots[i].body.position - paths.back().from);
    }

    // Fast circles, in id order: each against everything at its current (resolved) place,
    // that is every collider whose fat bounds overlap the swept circle's bounds. While those
    // bounds lie inside the circle's own fat bounds, unchanged since the broadphase, such a
    // collider is the other body of one of the circle's candidate pairs, or one whose fat
    // bounds changed since (`refattened`, a few in a step): the same colliders as a tree query,
    // found without bringing the tree up to date with every body that moved.
    if (fast_circles.empty()) return;
    std::vector<std::uint32_t> rank(n_slots, UINT32_MAX);  // in fast_circles
    for (std::uint32_t k = 0; k < fast_circles.size(); ++k) rank[fast_circles[k]] = k;
    std::vector<std::uint32_t> first(fast_circles.size() + 1, 0);  // each circle's partners: CSR
    for (const detail::Pair& p : pairs) {
        if (rank[p.a] != UINT32_MAX) ++first[rank[p.a] + 1];
        if (rank[p.b] != UINT32_MAX) ++first[rank[p.b] + 1];
    }
    for (std::size_t k = 0; k < fast_circles.size(); ++k) first[k + 1] += first[k];
    std::vector<std::uint32_t> partners(first.back());
    {
        std::vector<std::uint32_t> next(first.begin(), first.end() - 1);
        for (const detail::Pair& p : pairs) {
            if (rank[p.a] != UINT32_MAX) partners[next[rank[p.a]]++] = p.b;
            if (rank[p.b] != UINT32_MAX) partners[next[rank[p.b]]++] = p.a;
        }
    }
    // Which bodies' fat bounds changed before the sweeps (a circle's own change only after its
    // sweep, so this is all a circle asks of itself).
    std::vector<std::uint8_t> changed(n_slots, 0);
    for (const std::uint32_t j : refattened) changed[j] = 1;
    // Calls f(j) for every collider whose fat bounds overlap `region`, circle i's sweep (some
    // more than once; the best hit is the same whichever order they come in).
    const auto colliders_near = [&](std::uint32_t i, const Aabb& region, const auto& f) {
        const int proxy = slots[i].proxy;
        const bool unchanged = proxy >= 0 && changed[i] == 0;
        const Aabb own = proxy >= 0 ? broadphase.fat_bounds(proxy) : Aabb{};
        if (!unchanged || !(own.min.x <= region.min.x && own.min.y <= region.min.y && region.max.x <= own.max.x &&
                            region.max.y <= own.max.y)) {
            broadphase.query(region, [&](std::uint32_t j) { f(j); });
            return;
        }
#ifndef NDEBUG
        std::vector<std::uint32_t> by_pairs;  // what this path hands on, checked below
#endif
        const auto near = [&](std::uint32_t j) {
            const int pj = slots[j].proxy;
            if (pj < 0 || !detail::Broadphase::overlap(broadphase.fat_bounds(pj), region)) return;
#ifndef NDEBUG
            by_pairs.push_back(j);
#endif
            f(j);
        };
        for (std::uint32_t e = first[rank[i]]; e < first[rank[i] + 1]; ++e) near(partners[e]);
        for (const std::uint32_t j : refattened) near(j);
#ifndef NDEBUG
        // Debug builds (CI plays every scenario in one) check the claim against the tree, for
        // the colliders a sweep may meet (the candidate pairs leave out pairs that never meet).
        const auto meets = [&](std::uint32_t j) {
            return j != i && blocks(slots[j].body) && detail::may_meet(slots[i].body, id_of(i), slots[j].body, id_of(j));
        };
        std::vector<std::uint32_t> by_tree;
        broadphase.query(region, [&](std::uint32_t j) {
            if (meets(j)) by_tree.push_back(j);
        });
        std::erase_if(by_pairs, [&](std::uint32_t j) { return !meets(j); });
        for (auto* v : {&by_pairs, &by_tree}) {
            std::sort(v->begin(), v->end());
            v->erase(std::unique(v->begin(), v->end()), v->end());
        }
        JOSTLE_ASSERT(by_pairs == by_tree, "a fast circle's candidates are not the colliders the tree finds");
#endif
    };
    std::vector<std::pair<std::uint32_t, SweepHit>> crossed;  // triggers met by one stretch of a sweep
    for (const std::uint32_t i : fast_circles) {
        Slot& s = slots[i];
        if (!s.alive || !s.fast) continue;
        const EntityId id = id_of(i);
        const Vec2 start = s.body.position;
        float remaining = 1.0f;  // fraction of the step still to move
        // A circle resolution cannot move (inverse mass 0) would meet the body it just hit
        // again at t = 0 (its bounce changed that body's velocity, not its place): it goes on
        // to the next body instead.
        const bool immovable = detail::resolution_inverse_mass(s.body) == 0.0f;
        std::uint32_t last_hit = n_slots;  // none
        for (int hits = 0; hits < std::max(desc.max_sweep_hits, 1) && remaining > 0.0f; ++hits) {
            const Shape shape = placed(i);
            const Circle* circle = std::get_if<Circle>(&shape);
            const Vec2 motion = (remaining * dt) * s.body.velocity;
            if (circle == nullptr || !is_finite(motion)) {
                s.body.position += motion;
                remaining = 0.0f;
                break;
            }
            const Aabb from_box = bounds(*circle);
            const Aabb to_box = bounds(Circle{circle->center + motion, circle->radius});
            std::uint32_t best = n_slots;
            SweepHit best_hit;
            crossed.clear();
            colliders_near(i, Aabb{min(from_box.min, to_box.min), max(from_box.max, to_box.max)}, [&](std::uint32_t j) {
                // A trigger does not stop it, but one it meets on the way is in contact this
                // step (the narrowphase sees the circle only where the step began).
                if (j != i && slots[j].body.kind == BodyKind::trigger && detail::may_meet(s.body, id, slots[j].body, id_of(j))) {
                    if (const SweepHit h = sweep(*circle, motion, placement(j).shape, Vec2{}); h.hit) crossed.push_back({j, h});
                    return;
                }
                // Only what resolution could push it out of stops it (a body with no inverse
                // mass passes through static ones, swept or not).
                if (j == i || !blocks(slots[j].body) || !detail::may_meet(s.body, id, slots[j].body, id_of(j)) ||
                    !detail::resolvable(s.body, slots[j].body)) {
                    return;
                }
                const SweepHit h = sweep(*circle, motion, placement(j).shape, Vec2{});
                if (!h.hit || (immovable && j == last_hit && h.t == 0.0f)) return;
                if (best == n_slots || h.t < best_hit.t || (h.t == best_hit.t && j < best)) {
                    best = j;
                    best_hit = h;
                }
            });
            // The triggers met before it stops (all of them when nothing stops it), in the
            // order found (colliders_near may name one twice: the events keep one entry a pair).
            for (const auto& [j, h] : crossed) {
                if (best != n_slots && h.t > best_hit.t) continue;
                const EntityId trigger = id_of(j);
                if (i < j) {
                    touching.push_back({id, trigger, h.point, h.normal, 0.0f, true, true});
                } else {
                    touching.push_back({trigger, id, h.point, -h.normal, 0.0f, true, false});
                }
            }
            if (best == n_slots) {
                s.body.position += motion;
                remaining = 0.0f;
                break;
            }
            s.body.position += best_hit.t * motion;
            remaining *= 1.0f - best_hit.t;
            const EntityId other = id_of(best);
            if (i < best) {
                touching.push_back({id, other, best_hit.point, best_hit.normal, 0.0f, false});
            } else {
                touching.push_back({other, id, best_hit.point, -best_hit.normal, 0.0f, false});
            }
            bounce(i, best, best_hit.normal);
            last_hit = best;
        }
        // Motion left after max_sweep_hits contacts is dropped: stopping is safe, guessing is
        // not. But a circle resolution cannot move (inverse mass 0) goes all the way, as a
        // slow one would: its contacts push the others, never it.
        if (remaining > 0.0f && immovable) {
            s.body.position += (remaining * dt) * s.body.velocity;
        }
        const Shape end = placed(i);
        const float radius = std::holds_alternative<Circle>(end) ? std::get<Circle>(end).radius : 0.0f;
        const Vec2 offset = std::holds_alternative<Circle>(end) ? std::get<Circle>(end).center - s.body.position : Vec2{};
        paths.push_back({id, start + offset, s.body.position + offset, radius});
        sync_proxy(i, s.body.position - start);
    }
}

}  // namespace jostle
