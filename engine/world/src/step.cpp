// World::step: one fixed step in named phases (integrate, broadphase, narrowphase, resolve,
// sweeps, events). The sweeps phase is in continuous.cpp. See the MANUAL in jostle/world.h.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <functional>
#include <numbers>
#include <utility>

#include "internal.h"
#include "jostle/core/error.h"

namespace jostle {

using detail::Pair;
using detail::Slot;

namespace {

// A superset of overlaps(): the same comparisons without the validity checks, inline and
// without branches, to turn away candidates cheaply; overlaps() then decides.
bool touch(const Aabb& a, const Aabb& b) {
    return (a.max.x >= b.min.x) & (a.min.x <= b.max.x) & (a.max.y >= b.min.y) & (a.min.y <= b.max.y);
}

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

std::size_t g_marks_per_pair = 2;  // detail::set_marks_per_pair_before_visiting_all

// Resets the flag even when the event handler throws.
struct StepGuard {
    bool& flag;
    explicit StepGuard(bool& f) : flag(f) { flag = true; }
    ~StepGuard() { flag = false; }
};

}  // namespace

std::size_t detail::set_marks_per_pair_before_visiting_all(std::size_t n) {
    return std::exchange(g_marks_per_pair, n);
}

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
        // A kept contact still counts as touching while its gap is within the slop, so
        // rounding does not make begin/end events flicker.
        if (c.separation > w.desc.slop) continue;
        const Shape& a = w.placement(c.pair.a).shape;
        const Shape& b = w.placement(c.pair.b).shape;
        touching.push_back({w.id_of(c.pair.a), w.id_of(c.pair.b), detail::contact_point(a, b, c.manifold),
                            c.manifold.normal, c.manifold.depth, c.trigger,
                            c.trigger && w.slots[c.pair.b].body.kind == BodyKind::trigger, c.corner});
    }
    w.resolve(found, pairs, dt);
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
// Velocity constraints, shared by integrate (contacts carried from the last step) and
// resolve (this step's contacts): sequential impulses with accumulated, clamped impulses.
// ---------------------------------------------------------------------------------------

namespace {

struct VelocityContact {
    std::uint32_t a, b;
    Vec2 normal;
    float target;   // normal speed to reach: 0, a bounce, or closing a speculative gap
    float friction;
    float ima = 0.0f, imb = 0.0f;  // the bodies' inverse masses as resolution sees them (fixed
                                   // through a step; kept here, not re-read from the bodies)
    float normal_impulse = 0.0f;   // accumulated, >= 0
    float tangent_impulse = 0.0f;  // accumulated, |.| <= friction * normal_impulse
};

constexpr int kUnreached = 1 << 30;

// Indices 0..n-1 of pairs, ordered by the lower ground level of each pair's two bodies, ties
// in index order, pairs with nothing immovable below them last: the ground-up order of
// shock propagation. A counting sort (levels are small), so exactly a stable sort's order.
template <typename PairAt>
std::vector<std::uint32_t> ground_up_order(const std::vector<int>& level, std::size_t n, PairAt pair_at) {
    // First pass: each pair's level (kUnreached kept as is) and the highest reached level;
    // second: unreached pairs go after it.
    std::vector<std::uint32_t> key(n);
    std::uint32_t top = 0;
    for (std::size_t k = 0; k < n; ++k) {
        const auto [a, b] = pair_at(k);
        const int l = std::min(level[a], level[b]);
        key[k] = static_cast<std::uint32_t>(l);
        if (l != kUnreached) top = std::max(top, key[k]);
    }
    std::vector<std::uint32_t> start(static_cast<std::size_t>(top) + 3, 0);
    for (std::uint32_t& k : key) {
        if (k == static_cast<std::uint32_t>(kUnreached)) k = top + 1;
        ++start[k + 1];
    }
    for (std::size_t b = 1; b < start.size(); ++b) start[b] += start[b - 1];
    std::vector<std::uint32_t> order(n);
    for (std::size_t k = 0; k < n; ++k) order[start[key[k]]++] = static_cast<std::uint32_t>(k);
    return order;
}

// An undirected edge list by body (compressed rows): the edges at body i are
// at[first[i] .. first[i + 1]), in list order, each with its other end (so a walk over a
// body's edges does not go back to the list for it).
struct EdgesByBody {
    struct Entry {
        std::uint32_t edge;   // index into the list
        std::uint32_t other;  // the edge's other body (i itself for a self-edge)
    };
    std::vector<std::uint32_t> first;
    std::vector<Entry> at;

    template <typename Edges>
    EdgesByBody(std::size_t bodies, const Edges& edges) : first(bodies + 1, 0), at(2 * edges.size()) {
        for (const auto& [a, b] : edges) {
            ++first[a + 1];
            ++first[b + 1];
        }
        for (std::size_t i = 0; i < bodies; ++i) first[i + 1] += first[i];
        std::vector<std::uint32_t> next(first.begin(), first.end() - 1);
        for (std::uint32_t k = 0; k < edges.size(); ++k) {
            const auto& [a, b] = edges[k];
            at[next[a]++] = {k, b};
            at[next[b]++] = {k, a};
        }
    }
};

// Distance (in contacts) of each body from something immovable, for the ground-up order
// (shock propagation): a breadth-first search from the immovable bodies over the contact
// graph (the shortest distances, so the same levels as relaxing every edge until nothing
// changes, in linear time). The sources are the immovable bodies of `seeds` (pairs, which
// include the edges). Deterministic: the shortest distances depend only on the edges and the
// set of sources, not on the order they are found in.
template <typename Edges, typename Seeds>
std::vector<int> ground_levels(const std::vector<float>& inverse_mass, const Edges& edges, const Seeds& seeds) {
    std::vector<int> level(inverse_mass.size(), kUnreached);
    const EdgesByBody by_body(inverse_mass.size(), edges);
    std::vector<std::uint32_t> queue;
    for (const auto& [a, b] : seeds) {
        for (std::uint32_t i : {a, b}) {
            if (level[i] != 0 && inverse_mass[i] == 0.0f) {
                level[i] = 0;
                queue.push_back(i);
            }
        }
    }
    for (std::size_t head = 0; head < queue.size(); ++head) {
        const std::uint32_t i = queue[head];
        for (std::uint32_t e = by_body.first[i]; e < by_body.first[i + 1]; ++e) {
            const std::uint32_t j = by_body.at[e].other;
            if (level[j] == kUnreached) {
                level[j] = level[i] + 1;
                queue.push_back(j);
            }
        }
    }
    return level;
}

// Under shock propagation the body nearer the ground stands still for the one above it: its
// inverse mass counts as 0 (for position pushes and velocity impulses alike).
std::pair<float, float> shock_masses(float ima, float imb, int level_a, int level_b, bool shock) {
    if (shock && level_a < level_b) ima = 0.0f;
    if (shock && level_b < level_a) imb = 0.0f;
    return {ima, imb};
}

// Every body's resolution_inverse_mass, packed: the step's pair loops read it for thousands
// of pairs, and a body's EntityDesc spans several cache lines.
std::vector<float> inverse_masses(const std::vector<Slot>& slots) {
    std::vector<float> out(slots.size());
    for (std::size_t i = 0; i < slots.size(); ++i) out[i] = detail::resolution_inverse_mass(slots[i].body);
    return out;
}

VelocityContact velocity_contact(std::uint32_t a, const EntityDesc& ba, std::uint32_t b, const EntityDesc& bb,
                                 Vec2 normal, float target) {
    return {a, b, normal, target, mixed_friction(ba, bb), detail::resolution_inverse_mass(ba),
            detail::resolution_inverse_mass(bb)};
}

// A body's velocity state, packed for the solver's passes: each contact reads and writes
// two bodies many times, and an EntityDesc spans several cache lines.
struct Motion {
    Vec2 velocity;
    Vec2 friction_dv;
    bool still = false;  // a static body
};

Vec2 contact_velocity(const Motion& m) { return detail::contact_velocity(m.velocity, m.still); }

void solve_velocity(std::vector<Motion>& motion, const std::vector<int>& level, VelocityContact& vc, bool shock) {
    const auto [ima, imb] = shock_masses(vc.ima, vc.imb, level[vc.a], level[vc.b], shock);
    const float k = ima + imb;
    if (!(k > 0.0f)) return;
    Motion& sa = motion[vc.a];
    Motion& sb = motion[vc.b];
    const Vec2 n = vc.normal;
    const float vn = dot(contact_velocity(sb) - contact_velocity(sa), n);
    const float total = std::fmax(vc.normal_impulse + (vc.target - vn) / k, 0.0f);
    const float dn = total - vc.normal_impulse;
    vc.normal_impulse = total;
    sa.velocity -= (ima * dn) * n;
    sb.velocity += (imb * dn) * n;
    // Friction along the tangent, bounded by the normal impulse (Coulomb).
    const Vec2 t = perp(n);
    const float vt = dot(contact_velocity(sb) - contact_velocity(sa), t);
    const float limit = vc.friction * vc.normal_impulse;
    const float total_t = std::clamp(vc.tangent_impulse - vt / k, -limit, limit);
    const float dt_impulse = total_t - vc.tangent_impulse;
    vc.tangent_impulse = total_t;
    const Vec2 dva = -(ima * dt_impulse) * t;
    const Vec2 dvb = (imb * dt_impulse) * t;
    sa.velocity += dva;
    sb.velocity += dvb;
    sa.friction_dv += dva;
    sb.friction_dv += dvb;
}

// `passes` passes in the given order; the last one goes ground up with shock propagation,
// so a resting stack ends still. The contacts' bodies are solved in a packed copy of their
// velocities, written back at the end (the same operations on the same values).
void solve_velocities(std::vector<Slot>& slots, const std::vector<int>& level, std::vector<VelocityContact>& vcs,
                      int passes) {
    const std::vector<std::uint32_t> ground_up =
        ground_up_order(level, vcs.size(), [&](std::size_t k) { return std::pair{vcs[k].a, vcs[k].b}; });
    std::vector<Motion> motion(slots.size());
    for (const VelocityContact& vc : vcs) {
        for (const std::uint32_t i : {vc.a, vc.b}) {
            const Slot& s = slots[i];
            motion[i] = {s.body.velocity, s.friction_dv, s.body.kind == BodyKind::static_body};
        }
    }
    passes = std::max(passes, 1);
    for (int pass = 0; pass < passes; ++pass) {
        if (pass == passes - 1 && passes > 1) {
            for (const std::uint32_t k : ground_up) solve_velocity(motion, level, vcs[k], true);
        } else {
            for (VelocityContact& vc : vcs) solve_velocity(motion, level, vc, false);
        }
    }
    for (const VelocityContact& vc : vcs) {
        for (const std::uint32_t i : {vc.a, vc.b}) {
            slots[i].body.velocity = motion[i].velocity;
            slots[i].friction_dv = motion[i].friction_dv;
        }
    }
}

}  // namespace

// ---------------------------------------------------------------------------------------
// integrate: velocities from gravity, held by the contacts carried from the last step, then
// positions (semi-implicit Euler)
// ---------------------------------------------------------------------------------------

void World::Impl::integrate(float dt) {
    for (std::uint32_t i = 0; i < slots.size(); ++i) {
        Slot& s = slots[i];
        s.fast = false;
        s.friction_dv = {};
        if (s.alive && s.body.kind == BodyKind::dynamic) s.body.velocity += (s.body.gravity_scale * dt) * desc.gravity;
    }
    // Bodies resting on something keep resting: the contacts carried from the last step take
    // the approach out of this step's velocity before it moves anything (Box2D's order). A
    // box on the floor then does not sink by gravity * dt^2 each step, so sliding over tiled
    // ground meets no tile's side at the seams.
    std::vector<VelocityContact> carried;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
    for (const Contact& c : contacts) {
        const EntityDesc& ba = slots[c.a.index].body;
        const EntityDesc& bb = slots[c.b.index].body;
        if (c.trigger || c.corner || !detail::resolvable(ba, bb) || !detail::may_meet(ba, c.a, bb, c.b)) continue;
        carried.push_back(velocity_contact(c.a.index, ba, c.b.index, bb, c.normal, 0.0f));
        edges.emplace_back(c.a.index, c.b.index);
    }
    if (!carried.empty()) {
        solve_velocities(slots, ground_levels(inverse_masses(slots), edges, edges), carried, desc.velocity_passes);
        for (Slot& s : slots) s.friction_dv = {};  // friction here acts before the motion
    }

    for (std::uint32_t i = 0; i < slots.size(); ++i) {
        Slot& s = slots[i];
        if (!s.alive) continue;
        EntityDesc& b = s.body;
        // Bullets move along their path in the sweeps phase; static bodies never move.
        if (b.kind == BodyKind::static_body) continue;
        const float angle = wrap_angle(b.angle + b.angular_velocity * dt);
        if (std::bit_cast<std::uint32_t>(angle) != std::bit_cast<std::uint32_t>(b.angle)) {
            b.angle = angle;
            turn(i);
        }
        if (b.kind == BodyKind::bullet) continue;
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
// broadphase: candidate pairs from the grid (or tree queries), filtered, in (lower id, higher id) order
// ---------------------------------------------------------------------------------------

std::vector<Pair> World::Impl::broadphase_pairs() {
    // Every collider but bullets' (they only cast), at its fat bounds; a pair needs one side
    // that moves. The pairs are those whose fat bounds overlap, found either by a tree query
    // from each moving body or, faster when many things move, all at once by the grid: the
    // same pairs either way (tests/world/pair_grid_test.cpp).
    grid_items.clear();
    boxes.resize(slots.size());
    pushable.resize(slots.size());
    meet_keys.resize(slots.size());
    std::size_t moving = 0;
    for (std::uint32_t i = 0; i < slots.size(); ++i) {
        const Slot& s = slots[i];
        pushable[i] = detail::pushability(s.body);
        meet_keys[i] = detail::meet_key(s.body, id_of(i));
        if (!s.alive || s.proxy < 0 || s.body.kind == BodyKind::bullet) continue;
        const bool moves = detail::is_moving_kind(s.body.kind);
        grid_items.push_back({broadphase.fat_bounds(s.proxy), i, moves});
        moving += moves ? 1 : 0;
        boxes[i] = placement(i).box;  // for the narrowphase and resolve
    }
    grid_pairs.clear();
    if (moving * 16 < grid_items.size()) {
        // Few movers among many static colliders (a tile map): a tree query from each mover
        // costs less than gridding every tile.
        for (std::uint32_t i = 0; i < slots.size(); ++i) {
            const Slot& s = slots[i];
            if (!s.alive || s.proxy < 0 || !detail::is_moving_kind(s.body.kind)) continue;
            broadphase.query(broadphase.fat_bounds(s.proxy), [&](std::uint32_t j) {
                // Two moving bodies find each other twice; keep the pair once.
                if (j == i || slots[j].body.kind == BodyKind::bullet || (detail::is_moving_kind(slots[j].body.kind) && j < i)) {
                    return;
                }
                grid_pairs.push_back({std::min(i, j), std::max(i, j)});
            });
        }
        std::sort(grid_pairs.begin(), grid_pairs.end(),
                  [](const detail::GridPair& x, const detail::GridPair& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; });
    } else {
        // Big items (long walls) are looked up in the tree rather than tested against all.
        pair_grid.find(grid_items, grid_pairs, [&](const Aabb& box, const std::function<void(std::uint32_t)>& found) {
            broadphase.query(box, [&](std::uint32_t j) { found(j); });
        });
    }
    std::vector<Pair> pairs;
    pairs.reserve(grid_pairs.size());
    for (const detail::GridPair& g : grid_pairs) {
        if (pushable[g.a] < 0.0f && pushable[g.b] < 0.0f) continue;  // two triggers
        if (!detail::may_meet(meet_keys[g.a], meet_keys[g.b])) continue;
        pairs.push_back({g.a, g.b});
    }
    return pairs;
}

// ---------------------------------------------------------------------------------------
// narrowphase: the collision module's collide() for each candidate
// ---------------------------------------------------------------------------------------

std::vector<World::Impl::NarrowContact> World::Impl::narrowphase(const std::vector<Pair>& pairs) {
    std::vector<NarrowContact> found;
    // The pairs come in (a, b) order (broadphase_pairs; resolve's merge with `found` relies
    // on it too), and so do the last step's contacts (ids order by index first), so one
    // cursor walks the contacts once for all the pairs' look-ups.
    JOSTLE_DEBUG_ASSERT(std::is_sorted(pairs.begin(), pairs.end(),
                                       [](const Pair& x, const Pair& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; }),
                        "candidate pairs out of (a, b) order");
    const auto before = [](const Contact& c, EntityId a, EntityId b) { return c.a != a ? c.a < a : c.b < b; };
    std::size_t last_at = 0;
    const auto last_step = [&](EntityId a, EntityId b) -> const Contact* {
        while (last_at < contacts.size() && before(contacts[last_at], a, b)) ++last_at;
        return (last_at < contacts.size() && contacts[last_at].a == a && contacts[last_at].b == b) ? &contacts[last_at]
                                                                                                    : nullptr;
    };
    for (const Pair& p : pairs) {
        const bool trigger = pushable[p.a] < 0.0f || pushable[p.b] < 0.0f;
        // Bounds first: cheap, and for masks it is the lecture's first test (09-30). The
        // packed boxes turn most candidates away without reading their placements.
        // The broadphase placed every body and nothing has moved since, so the placements
        // are read directly (checking them against the bodies would be a cache miss each).
        Manifold m;
        const detail::Placement& pa = placements[p.a];
        const detail::Placement& pb = placements[p.b];
        if (touch(boxes[p.a], boxes[p.b])) {
            JOSTLE_DEBUG_ASSERT(placement_current(p.a) && placement_current(p.b), "a stale placement in the narrowphase");
            if (overlaps(pa.box, pb.box)) m = collide(pa.shape, pb.shape);
        }
        if (m.hit) {
            found.push_back({p, m, 0.0f, trigger, detail::corner_touch(pa.shape, pb.shape, m)});
            continue;
        }
        // Bodies that touched last step and now miss by a rounding error (or a small gap)
        // stay in contact speculatively: B moved back toward A along the last normal by
        // kSpeculative shows how far apart they are. Without this a resting stack loses a
        // contact whenever rounding opens a 1e-5 px gap, and the body above falls through
        // a step of gravity.
        if (trigger || !detail::resolvable(pushable[p.a], pushable[p.b])) continue;
        const Contact* last = last_step(meet_keys[p.a].id, meet_keys[p.b].id);
        if (last == nullptr) continue;
        constexpr float kSpeculative = 1.0f;  // px
        const Shape b_back = placed_at(p.b, slots[p.b].body.position - kSpeculative * last->normal);
        const Manifold back = collide(pa.shape, b_back);
        if (!back.hit) continue;
        Manifold touching = back;
        touching.depth = 0.0f;
        found.push_back({p, touching, std::fmax(kSpeculative - back.depth, 0.0f), false, false});
    }
    return found;
}

// ---------------------------------------------------------------------------------------
// resolve: velocity impulses, then MTD relaxation passes
// ---------------------------------------------------------------------------------------

void World::Impl::resolve(const std::vector<NarrowContact>& found, const std::vector<Pair>& pairs, float dt) {
    // From the packed pushabilities (broadphase_pairs): a trigger's -1 is inverse mass 0.
    std::vector<float> inverse_mass(slots.size());
    for (std::size_t i = 0; i < slots.size(); ++i) inverse_mass[i] = std::fmax(pushable[i], 0.0f);
    const auto resolvable = [&](const Pair& p) { return detail::resolvable(pushable[p.a], pushable[p.b]); };
    std::vector<const NarrowContact*> contacts_in;
    for (const NarrowContact& c : found) {
        if (resolvable(c.pair)) contacts_in.push_back(&c);
    }
    std::vector<Pair> push_pairs;
    for (const Pair& p : pairs) {
        if (resolvable(p)) push_pairs.push_back(p);
    }
    if (push_pairs.empty()) return;

    std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
    for (const NarrowContact* c : contacts_in) edges.emplace_back(c->pair.a, c->pair.b);
    // The sources are the immovable bodies of every push pair, not only of the contacts
    // (whose pairs are among them): pairs that only the pushes bring together still need
    // their immovable bodies at level 0 (both sides: an unseeded static body would look
    // "above" the dynamic one and make it stand still under shock propagation).
    const std::vector<int> level = ground_levels(inverse_mass, edges, push_pairs);

    // Velocity: new impacts (bounce above the threshold), kept contacts closing their gap.
    std::vector<VelocityContact> vcs;
    vcs.reserve(contacts_in.size());
    for (const NarrowContact* c : contacts_in) {
        // Corner to corner the normal is a tie (a box sliding onto the next floor tile
        // touches its corner): no response; if they go on into each other, the next step
        // has a real normal.
        if (c->corner) continue;
        const EntityDesc& ba = slots[c->pair.a].body;
        const EntityDesc& bb = slots[c->pair.b].body;
        const Vec2 n = c->manifold.normal;
        const float vn = dot(detail::contact_velocity(bb) - detail::contact_velocity(ba), n);
        float target = 0.0f;
        if (c->separation > 0.0f) {
            target = -c->separation / dt;  // may close the gap in the next step, no more
        } else if (vn < -desc.restitution_threshold) {
            target = -mixed_restitution(ba, bb) * vn;
        }
        vcs.push_back(velocity_contact(c->pair.a, ba, c->pair.b, bb, n, target));
    }
    solve_velocities(slots, level, vcs, desc.velocity_passes);

    // What friction took from the tangential velocity is taken from this step's motion too
    // (semi-implicit Euler), so a body that friction stops does not slide on for a step.
    std::vector<bool> friction_moved(slots.size(), false);
    for (const NarrowContact* c : contacts_in) {
        for (std::uint32_t i : {c->pair.a, c->pair.b}) {
            Slot& s = slots[i];
            if (s.fast || (s.friction_dv.x == 0.0f && s.friction_dv.y == 0.0f)) continue;
            s.body.position += dt * s.friction_dv;
            s.friction_dv = {};  // once per body
            friction_moved[i] = true;
        }
    }

    // Position: relaxation passes along the MTD, recomputed from the current positions, over
    // every candidate pair (a push can make a new overlap). A pair that pushed nothing when
    // last looked at, and neither of whose bodies has moved since, would push nothing again
    // (its manifold depends only on the two positions, and shock propagation only ever sets
    // a mass to zero), so each pass looks only at the pairs marked dirty: those that pushed
    // last time, and those with a body that moved since they were looked at. Same pushes in
    // the same order as testing every pair every pass, without re-testing the many that do
    // not touch.
    // A contact no deeper than half the slop is settled and not pushed: in a crowd most
    // pushes are that small, each moves bodies that then disturb their neighbours, and the
    // passes stop anyway once every contact is within it (Box2D likewise leaves the last
    // linear slop uncorrected). Resting contacts so end within the slop, as documented.
    const float settled = std::fmax(0.5f * desc.slop, 0.0f);
    const auto n_pairs = static_cast<std::uint32_t>(push_pairs.size());
    const std::vector<std::uint32_t> ground_up =
        ground_up_order(level, n_pairs, [&](std::size_t k) { return std::pair{push_pairs[k].a, push_pairs[k].b}; });
    // Each body's pairs, to mark them when the body moves: the entries name each pair by its
    // position in the order the passes walk, pair order and then, from the first shock pass
    // on, ground-up order (rewritten once, at the switch).
    EdgesByBody pairs_of(slots.size(), push_pairs);
    // Dirty marks as bits, by position in that order, converted at the switch too.
    const std::size_t words = (std::size_t{n_pairs} + 63) / 64;
    std::vector<std::uint64_t> dirty(words, 0);
    // Sets the mark of the pair at position r when `on` (without a branch: whether a moved
    // body's pair touches is a coin toss in a crowd).
    const auto set_dirty = [&](std::uint32_t r, bool on = true) { dirty[r / 64] |= std::uint64_t{on} << (r % 64); };
    // A body moved (boxes[i] already holds its new bounds): its pairs whose bounds now touch
    // become dirty. One whose bounds do not touch would be turned away when visited, unless
    // one of its bodies moves again first, which marks it then: the same pushes as marking
    // every pair of the body, without setting and visiting the many that are apart.
    // In a pile every body has a pair with every other, and marking them one move at a time
    // costs pushes x pairs per body. Visiting a clean pair pushes nothing (see above), so
    // treating every pair as dirty is always allowed: once a pass's marks outnumber twice
    // its pairs (g_marks_per_pair), the rest of the pass and all of the next visit every
    // pair instead (a pass then costs at most a few times its pairs; same pushes, same order).
    std::vector<bool> moved(slots.size(), false);
    bool all_now = false;   // this pass visits every pair from its cursor on
    bool all_next = false;  // the next pass visits every pair
    std::size_t marks = 0;  // this pass's so far
    const std::size_t mark_budget = g_marks_per_pair == 0                            ? 0
                                    : g_marks_per_pair > SIZE_MAX / (n_pairs + 65u) ? SIZE_MAX
                                                                                     : g_marks_per_pair * n_pairs + 64;
    const auto body_moved = [&](std::uint32_t i) {
        moved[i] = true;
        if (all_now && all_next) return;  // every mark would be redundant
        marks += pairs_of.first[i + 1] - pairs_of.first[i];
        if (marks > mark_budget) {
            all_now = all_next = true;
            return;
        }
        const Aabb box = boxes[i];
        for (std::uint32_t e = pairs_of.first[i]; e < pairs_of.first[i + 1]; ++e) {
            const auto [r, j] = pairs_of.at[e];
            set_dirty(r, touch(box, boxes[j]));  // touch is symmetric
        }
    };
    // The narrowphase already tested every pair at these positions: dirty are the pairs it
    // found overlapping, and those of bodies friction moved.
    for (std::size_t k = 0, f = 0; k < n_pairs; ++k) {
        const Pair& p = push_pairs[k];
        while (f < found.size() && (found[f].pair.a < p.a || (found[f].pair.a == p.a && found[f].pair.b < p.b))) ++f;
        if (f < found.size() && found[f].pair.a == p.a && found[f].pair.b == p.b && found[f].manifold.depth > settled) {
            set_dirty(static_cast<std::uint32_t>(k));
        }
    }
    // `boxes` (each body's bounds, packed, from broadphase_pairs) turns away the candidates
    // that do not touch without reaching the placements; friction moved some bodies since.
    for (std::uint32_t i = 0; i < slots.size(); ++i) {
        if (!friction_moved[i]) continue;
        boxes[i] = placement(i).box;
        body_moved(i);
    }
    // The next dirty position at or after `from` (marks ahead of the cursor are taken in this
    // pass, marks behind it in the next), or n_pairs.
    const auto next_dirty = [&](std::uint32_t from) {
        for (std::size_t w = from / 64; w < words; ++w) {
            std::uint64_t word = dirty[w];
            if (w == from / 64) word &= ~std::uint64_t{0} << (from % 64);
            if (word != 0) return static_cast<std::uint32_t>(w * 64 + static_cast<std::size_t>(std::countr_zero(word)));
        }
        return n_pairs;
    };
    const int passes = std::max(desc.relaxation_passes, 1);
    for (int pass = 0; pass < passes; ++pass) {
        const bool shock = pass >= passes / 2;
        if (pass == passes / 2) {
            // The first shock pass: from here on the passes walk in ground-up order, so the
            // marks and the entries move to the pairs' positions in it.
            std::vector<std::uint32_t> rank(n_pairs);
            for (std::uint32_t r = 0; r < n_pairs; ++r) rank[ground_up[r]] = r;
            std::vector<std::uint64_t> by_rank(words, 0);
            for (std::uint32_t k = next_dirty(0); k < n_pairs; k = next_dirty(k + 1)) {
                by_rank[rank[k] / 64] |= std::uint64_t{1} << (rank[k] % 64);
            }
            dirty = std::move(by_rank);
            for (EdgesByBody::Entry& e : pairs_of.at) e.edge = rank[e.edge];
        }
        float deepest = 0.0f;
        // (Marks made before the first pass count toward it: a pile is found at once.)
        all_now = all_next;
        all_next = false;
        marks = 0;
        const auto next = [&](std::uint32_t from) { return all_now ? from : next_dirty(from); };
        for (std::uint32_t r = next(0); r < n_pairs; r = next(r + 1)) {
            const std::uint32_t k = shock ? ground_up[r] : r;
            dirty[r / 64] &= ~(std::uint64_t{1} << (r % 64));
            const Pair& p = push_pairs[k];
            if (!touch(boxes[p.a], boxes[p.b])) continue;
            // Every placement here is current: the broadphase placed every body, and each
            // push or friction move above re-placed its bodies at once (so no need to check
            // them against the bodies' positions, a cache miss each).
            const detail::Placement& pa = placements[p.a];
            const detail::Placement& pb = placements[p.b];
            JOSTLE_DEBUG_ASSERT(placement_current(p.a) && placement_current(p.b), "a stale placement in resolve");
            if (!overlaps(pa.box, pb.box)) continue;
            const Shape& a = pa.shape;
            const Shape& b = pb.shape;
            const Manifold m = collide(a, b);
            if (!m.hit || !(m.depth > settled)) continue;
            const auto [ima, imb] = shock_masses(inverse_mass[p.a], inverse_mass[p.b], level[p.a], level[p.b], shock);
            const float k_sum = ima + imb;
            if (!(k_sum > 0.0f)) continue;  // under shock propagation only a mass can drop to 0
            const Vec2 mtd = m.depth * m.normal;  // moves B out of A
            const Vec2 a_before = slots[p.a].body.position;
            const Vec2 b_before = slots[p.b].body.position;
            Vec2 push_a = (ima / k_sum) * mtd;
            if (std::holds_alternative<PlacedMask>(a) || std::holds_alternative<PlacedMask>(b)) {
                // Mask MTDs are whole pixels, and so is each body's share of one.
                const auto whole = [](Vec2 v) { return Vec2{std::floor(v.x + 0.5f), std::floor(v.y + 0.5f)}; };
                push_a = whole(push_a);
                slots[p.b].body.position += whole(mtd) - push_a;
            } else {
                slots[p.b].body.position += (imb / k_sum) * mtd;
            }
            slots[p.a].body.position -= push_a;
            // This pair is looked at again next pass; the other pairs of a body only if the
            // push moved it (an immovable floor under a crowd keeps its many pairs clean).
            set_dirty(r);
            for (const auto& [i, before] : {std::pair{p.a, a_before}, std::pair{p.b, b_before}}) {
                const Vec2 now = slots[i].body.position;
                if (std::bit_cast<std::uint64_t>(now) == std::bit_cast<std::uint64_t>(before)) continue;
                boxes[i] = placement(i).box;
                body_moved(i);
            }
            deepest = std::fmax(deepest, m.depth);
        }
        if (deepest <= 0.5f * desc.slop) break;
    }
    // The proxies of bodies that moved here (friction above, or pushes); for the others
    // sync_proxy would find their bounds unchanged and do nothing.
    for (const Pair& p : push_pairs) {
        for (const std::uint32_t i : {p.a, p.b}) {
            if (moved[i]) sync_proxy(i);
        }
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
            if (c.trigger_is_b) {  // the trigger comes first
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
        } else if (contacts[i].trigger != touching[j].trigger || contacts[i].trigger_is_b != touching[j].trigger_is_b) {
            // A body changed kind (set()) between trigger and not: the old contact ends, the
            // new one begins.
            make(contacts[i++], false);
            make(touching[j++], true);
        } else {
            ++i;
            ++j;
        }
    }
    // Trigger events name the trigger first, which can change their order.
    const auto event_less = [](const Event& x, const Event& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; };
    std::stable_sort(exits.begin(), exits.end(), event_less);
    std::stable_sort(enters.begin(), enters.end(), event_less);
    contacts = std::move(touching);
    for (auto* list : {&ends, &begins, &exits, &enters}) events.insert(events.end(), list->begin(), list->end());
}

}  // namespace jostle
