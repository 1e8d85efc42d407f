// World::step: one fixed step in named phases (integrate, broadphase, narrowphase, resolve,
// sweeps, events). The sweeps phase is in continuous.cpp. See the MANUAL in jostle/world.h.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "internal.h"
#include "jostle/core/error.h"

namespace jostle {

using detail::Pair;
using detail::Slot;

namespace {

bool pair_less(const Pair& x, const Pair& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; }

float wrap_angle(float a) {
    constexpr float kPi = std::numbers::pi_v<float>;
    if (a >= -kPi && a <= kPi) return a;
    if (!std::isfinite(a)) return a;
    return std::remainder(a, 2.0f * kPi);  // exact, so the same in every build
}

float mixed_friction(const EntityDesc& a, const EntityDesc& b) {
    const float f = std::sqrt(std::fmax(a.friction, 0.0f) * std::fmax(b.friction, 0.0f));
    return std::isfinite(f) ? f : 0.0f;
}

float mixed_restitution(const EntityDesc& a, const EntityDesc& b) {
    const float e = std::fmax(a.restitution, b.restitution);
    return std::isfinite(e) && e > 0.0f ? e : 0.0f;
}

// Resets the flag even when the event handler throws.
struct StepGuard {
    bool& flag;
    explicit StepGuard(bool& f) : flag(f) { flag = true; }
    ~StepGuard() { flag = false; }
};

}  // namespace

void World::step(float dt) {
    Impl& w = *impl_;
    JOSTLE_ASSERT(!w.in_step, "World::step called during a step (from an event handler)");
    JOSTLE_ASSERT(std::isfinite(dt) && dt > 0.0f, "World::step needs dt > 0 and finite");
    StepGuard guard(w.in_step);
    w.events.clear();
    w.paths.clear();

    w.integrate(dt);
    const std::vector<Pair> pairs = w.broadphase_pairs();
    const std::vector<Impl::NarrowContact> found = w.narrowphase(pairs);
    // What touched at the narrowphase is what the events report (before resolution).
    std::vector<Contact> touching;
    touching.reserve(found.size());
    for (const Impl::NarrowContact& c : found) {
        const Shape a = w.placed(c.pair.a);
        const Shape b = w.placed(c.pair.b);
        touching.push_back({w.id_of(c.pair.a), w.id_of(c.pair.b), detail::contact_point(a, b, c.manifold),
                            c.manifold.normal, c.manifold.depth, c.trigger});
    }
    w.resolve(found, dt);
    w.sweeps(dt, touching);
    ++w.steps;
    w.emit_events(std::move(touching));
    // The handler may change the world, even replace itself: call a copy. The events vector
    // is not touched until the next step, so the loop is safe.
    if (w.handler) {
        const EventHandler handler = w.handler;
        for (std::size_t k = 0; k < w.events.size(); ++k) handler(*this, w.events[k]);
    }
}

// ---------------------------------------------------------------------------------------
// integrate: velocities from gravity, then positions (semi-implicit Euler)
// ---------------------------------------------------------------------------------------

void World::Impl::integrate(float dt) {
    for (std::uint32_t i = 0; i < slots.size(); ++i) {
        Slot& s = slots[i];
        s.fast = false;
        s.friction_dv = {};
        if (!s.alive) continue;
        EntityDesc& b = s.body;
        // Bullets move along their path in the sweeps phase; static bodies never move.
        if (b.kind == BodyKind::static_body) continue;
        b.angle = wrap_angle(b.angle + b.angular_velocity * dt);
        if (b.kind == BodyKind::bullet) continue;
        if (b.kind == BodyKind::dynamic) b.velocity += (b.gravity_scale * dt) * desc.gravity;
        const Vec2 motion = dt * b.velocity;
        if (b.kind == BodyKind::dynamic) {
            if (const auto* c = std::get_if<Circle>(&b.collider.local_shape())) {
                // More than half its radius in one step could carry it through a thin wall.
                s.fast = length(motion) > 0.5f * c->radius;
            }
        }
        if (!s.fast) b.position += motion;
        sync_proxy(i, motion);
    }
}

// ---------------------------------------------------------------------------------------
// broadphase: candidate pairs from the tree, filtered, in (lower id, higher id) order
// ---------------------------------------------------------------------------------------

std::vector<Pair> World::Impl::broadphase_pairs() {
    std::vector<Pair> pairs;
    for (std::uint32_t i = 0; i < slots.size(); ++i) {
        const Slot& s = slots[i];
        if (!s.alive || s.proxy < 0 || !detail::is_moving_kind(s.body.kind)) continue;
        broadphase.query(broadphase.fat_bounds(s.proxy), [&](std::uint32_t j) {
            if (j == i) return;
            const Slot& o = slots[j];
            if (o.body.kind == BodyKind::bullet) return;
            // Two moving bodies find each other twice; keep the pair once.
            if (detail::is_moving_kind(o.body.kind) && j < i) return;
            if (s.body.kind == BodyKind::trigger && o.body.kind == BodyKind::trigger) return;
            if (!detail::may_meet(s.body, id_of(i), o.body, id_of(j))) return;
            pairs.push_back({std::min(i, j), std::max(i, j)});
        });
    }
    std::sort(pairs.begin(), pairs.end(), pair_less);
    pairs.erase(std::unique(pairs.begin(), pairs.end(), [](const Pair& x, const Pair& y) { return x.a == y.a && x.b == y.b; }),
                pairs.end());
    return pairs;
}

// ---------------------------------------------------------------------------------------
// narrowphase: the collision module's collide() for each candidate
// ---------------------------------------------------------------------------------------

std::vector<World::Impl::NarrowContact> World::Impl::narrowphase(const std::vector<Pair>& pairs) {
    std::vector<NarrowContact> found;
    for (const Pair& p : pairs) {
        const Shape a = placed(p.a);
        const Shape b = placed(p.b);
        // Bounds first: cheap, and for masks it is the lecture's first test (09-30).
        if (!overlaps(bounds(a), bounds(b))) continue;
        const Manifold m = collide(a, b);
        if (!m.hit) continue;
        const EntityDesc& ba = slots[p.a].body;
        const EntityDesc& bb = slots[p.b].body;
        const bool trigger = ba.kind == BodyKind::trigger || bb.kind == BodyKind::trigger;
        const bool movable = detail::resolution_inverse_mass(ba) > 0.0f || detail::resolution_inverse_mass(bb) > 0.0f;
        found.push_back({p, m, trigger, !trigger && movable});
    }
    return found;
}

// ---------------------------------------------------------------------------------------
// resolve: velocity impulses, then MTD relaxation passes
// ---------------------------------------------------------------------------------------

namespace {

struct VelocityContact {
    std::uint32_t a, b;
    Vec2 normal;
    float target;   // normal speed to reach: 0, or the bounce
    float friction;
    float normal_impulse = 0.0f;   // accumulated, >= 0
    float tangent_impulse = 0.0f;  // accumulated, |.| <= friction * normal_impulse
};

}  // namespace

void World::Impl::resolve(const std::vector<NarrowContact>& found, float dt) {
    std::vector<const NarrowContact*> contacts_in;
    for (const NarrowContact& c : found) {
        if (c.resolvable) contacts_in.push_back(&c);
    }
    if (contacts_in.empty()) return;

    // Distance (in contacts) from something immovable, for the ground-up order of the last
    // passes (shock propagation). Bellman-Ford over the contact list: deterministic.
    constexpr int kUnreached = 1 << 30;
    std::vector<int> level(slots.size(), kUnreached);
    for (const NarrowContact* c : contacts_in) {
        for (std::uint32_t i : {c->pair.a, c->pair.b}) {
            if (detail::resolution_inverse_mass(slots[i].body) == 0.0f) level[i] = 0;
        }
    }
    for (bool changed = true; changed;) {
        changed = false;
        for (const NarrowContact* c : contacts_in) {
            int& la = level[c->pair.a];
            int& lb = level[c->pair.b];
            if (la != kUnreached && la + 1 < lb) { lb = la + 1; changed = true; }
            if (lb != kUnreached && lb + 1 < la) { la = lb + 1; changed = true; }
        }
    }
    // Contact indices in id order, and ground-up (stable, so ties stay in id order).
    std::vector<std::size_t> id_order(contacts_in.size());
    for (std::size_t k = 0; k < id_order.size(); ++k) id_order[k] = k;
    std::vector<std::size_t> ground_up = id_order;
    const auto low_level = [&](std::size_t k) { return std::min(level[contacts_in[k]->pair.a], level[contacts_in[k]->pair.b]); };
    std::stable_sort(ground_up.begin(), ground_up.end(), [&](std::size_t x, std::size_t y) { return low_level(x) < low_level(y); });
    // Under shock propagation the body nearer the ground stands still for the one above it.
    const auto masses = [&](std::uint32_t a, std::uint32_t b, bool shock) {
        float ima = detail::resolution_inverse_mass(slots[a].body);
        float imb = detail::resolution_inverse_mass(slots[b].body);
        if (shock && level[a] < level[b]) ima = 0.0f;
        if (shock && level[b] < level[a]) imb = 0.0f;
        return std::pair{ima, imb};
    };

    // Velocity: sequential impulses with accumulated, clamped impulses.
    std::vector<VelocityContact> vcs;
    vcs.reserve(contacts_in.size());
    for (const NarrowContact* c : contacts_in) {
        const EntityDesc& ba = slots[c->pair.a].body;
        const EntityDesc& bb = slots[c->pair.b].body;
        const Vec2 n = c->manifold.normal;
        const float vn = dot(bb.velocity - ba.velocity, n);
        const float target = vn < -desc.restitution_threshold ? -mixed_restitution(ba, bb) * vn : 0.0f;
        vcs.push_back({c->pair.a, c->pair.b, n, target, mixed_friction(ba, bb)});
    }
    const auto solve_velocity = [&](VelocityContact& vc, bool shock) {
        const auto [ima, imb] = masses(vc.a, vc.b, shock);
        const float k = ima + imb;
        if (!(k > 0.0f)) return;
        Slot& sa = slots[vc.a];
        Slot& sb = slots[vc.b];
        const Vec2 n = vc.normal;
        const float vn = dot(sb.body.velocity - sa.body.velocity, n);
        const float total = std::fmax(vc.normal_impulse + (vc.target - vn) / k, 0.0f);
        const float dn = total - vc.normal_impulse;
        vc.normal_impulse = total;
        sa.body.velocity -= (ima * dn) * n;
        sb.body.velocity += (imb * dn) * n;
        // Friction along the tangent, bounded by the normal impulse (Coulomb).
        const Vec2 t = perp(n);
        const float vt = dot(sb.body.velocity - sa.body.velocity, t);
        const float limit = vc.friction * vc.normal_impulse;
        const float total_t = std::clamp(vc.tangent_impulse - vt / k, -limit, limit);
        const float dt_impulse = total_t - vc.tangent_impulse;
        vc.tangent_impulse = total_t;
        const Vec2 dva = -(ima * dt_impulse) * t;
        const Vec2 dvb = (imb * dt_impulse) * t;
        sa.body.velocity += dva;
        sb.body.velocity += dvb;
        sa.friction_dv += dva;
        sb.friction_dv += dvb;
    };
    const int velocity_passes = std::max(desc.velocity_passes, 1);
    for (int pass = 0; pass < velocity_passes; ++pass) {
        // The last pass goes ground up with shock propagation, so a resting stack ends still.
        const bool shock = pass == velocity_passes - 1 && velocity_passes > 1;
        for (std::size_t k : shock ? ground_up : id_order) solve_velocity(vcs[k], shock);
    }

    // What friction took from the tangential velocity is taken from this step's motion too,
    // so a body held by friction stays put instead of creeping (semi-implicit Euler).
    for (const NarrowContact* c : contacts_in) {
        for (std::uint32_t i : {c->pair.a, c->pair.b}) {
            Slot& s = slots[i];
            if (s.fast || (s.friction_dv.x == 0.0f && s.friction_dv.y == 0.0f)) continue;
            s.body.position += dt * s.friction_dv;
            s.friction_dv = {};  // once per body
        }
    }

    // Position: relaxation passes along the MTD, recomputed from the current positions.
    const int passes = std::max(desc.relaxation_passes, 1);
    for (int pass = 0; pass < passes; ++pass) {
        const bool shock = pass >= passes / 2;
        float deepest = 0.0f;
        for (std::size_t index : shock ? ground_up : id_order) {
            const std::uint32_t a = contacts_in[index]->pair.a;
            const std::uint32_t b = contacts_in[index]->pair.b;
            const Manifold m = collide(placed(a), placed(b));
            if (!m.hit || !(m.depth > 0.0f)) continue;
            const auto [ima, imb] = masses(a, b, shock);
            const float k = ima + imb;
            if (!(k > 0.0f)) continue;
            slots[a].body.position -= (m.depth * ima / k) * m.normal;
            slots[b].body.position += (m.depth * imb / k) * m.normal;
            deepest = std::fmax(deepest, m.depth);
        }
        if (deepest <= 0.5f * desc.slop) break;
    }
    for (const NarrowContact* c : contacts_in) {
        sync_proxy(c->pair.a);
        sync_proxy(c->pair.b);
    }
}

// ---------------------------------------------------------------------------------------
// events: compare this step's contacts with the last step's
// ---------------------------------------------------------------------------------------

void World::Impl::emit_events(std::vector<Contact> touching) {
    const auto key_less = [](const Contact& x, const Contact& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; };
    std::stable_sort(touching.begin(), touching.end(), key_less);
    // A pair found by the narrowphase and again by a sweep keeps the narrowphase's entry.
    touching.erase(std::unique(touching.begin(), touching.end(),
                               [](const Contact& x, const Contact& y) { return x.a == y.a && x.b == y.b; }),
                   touching.end());
    std::erase_if(touching, [&](const Contact& c) { return find(c.a) == nullptr || find(c.b) == nullptr; });

    std::vector<Event> ends, begins, exits, enters;
    const auto make = [&](const Contact& c, bool begin) {
        Event e;
        e.a = c.a;
        e.b = c.b;
        e.point = c.point;
        e.normal = c.normal;
        e.depth = c.depth;
        if (c.trigger) {
            e.type = begin ? EventType::trigger_enter : EventType::trigger_exit;
            if (slots[c.a.index].body.kind != BodyKind::trigger) {  // the trigger comes first
                std::swap(e.a, e.b);
                e.normal = -e.normal;
            }
        } else {
            e.type = begin ? EventType::contact_begin : EventType::contact_end;
        }
        e.a_user_data = slots[e.a.index].body.user_data;
        e.b_user_data = slots[e.b.index].body.user_data;
        (c.trigger ? (begin ? enters : exits) : (begin ? begins : ends)).push_back(e);
    };
    std::size_t i = 0, j = 0;
    while (i < contacts.size() || j < touching.size()) {
        if (j == touching.size() || (i < contacts.size() && key_less(contacts[i], touching[j]))) {
            make(contacts[i++], false);
        } else if (i == contacts.size() || key_less(touching[j], contacts[i])) {
            make(touching[j++], true);
        } else {
            ++i;
            ++j;
        }
    }
    contacts = std::move(touching);
    for (auto* list : {&ends, &begins, &exits, &enters}) events.insert(events.end(), list->begin(), list->end());
}

}  // namespace jostle
