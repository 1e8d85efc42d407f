// World::step: one fixed step in named phases (integrate, broadphase, narrowphase, resolve,
// sweeps, events). The sweeps phase is in continuous.cpp. See the MANUAL in jostle/world.h.
#include <algorithm>
#include <bit>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <functional>
#include <numbers>
#include <utility>

#include "internal.h"
#include "jostle/core/error.h"

namespace jostle {

using detail::BodyState;
using detail::Pair;
using detail::Slot;

namespace {

// overlaps()'s comparisons without its validity checks, inline and without branches: the
// same answer for usable bounds (finite, in order), which are all a body with a proxy has.
bool touch(const Aabb& a, const Aabb& b) {
    return (a.max.x >= b.min.x) & (a.min.x <= b.max.x) & (a.max.y >= b.min.y) & (a.min.y <= b.max.y);
}

// std::fmax(x, 0.0f) without the libm call (fmax_inline's answer): the pair loops take it
// many times a step.
inline float max0(float x) { return fmax_inline(x, 0.0f); }

float wrap_angle(float a) {
    constexpr float kPi = std::numbers::pi_v<float>;
    if (a >= -kPi && a <= kPi) return a;
    if (!std::isfinite(a)) return a;
    return std::remainder(a, 2.0f * kPi);  // exact, so the same in every build
}

float mixed_friction(float a, float b) {
    const float f = std::sqrt(std::fmax(a, 0.0f) * std::fmax(b, 0.0f));
    return std::isfinite(f) ? f : 0.0f;
}

float mixed_restitution(float a, float b) {
    const float e = std::fmax(a, b);
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
    Impl& w = impl();
    JOSTLE_ASSERT(!w.in_step, "World::step called during a step (from an event handler)");
    JOSTLE_ASSERT(std::isfinite(dt) && dt > 0.0f, "World::step needs dt > 0 and finite");
    StepGuard guard(w.in_step);
    w.events.clear();
    w.paths.clear();
    const std::uint64_t removals_before = w.removals;

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
        // (Nothing has moved since the narrowphase: the placements and packed records are
        // current, and read without going back to the bodies.)
        const Shape& a = w.placements[c.pair.a].shape;
        const Shape& b = w.placements[c.pair.b].shape;
        touching.push_back({{c.pair.a, w.pair_bodies[c.pair.a].generation}, {c.pair.b, w.pair_bodies[c.pair.b].generation},
                            detail::contact_point(a, b, c.manifold), c.manifold.normal, c.manifold.depth, c.trigger,
                            c.trigger && w.pair_bodies[c.pair.b].pushable < 0.0f, c.corner});
    }
    w.resolve(found, pairs, dt);
    w.sweeps(dt, touching, pairs);
    ++w.steps;
    w.emit_events(std::move(touching), w.removals != removals_before);
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
    // What a visit uses, for plain passes ([0]) and under shock propagation ([1], set by
    // solve_velocities from the ground levels): the masses, and 1 / (ima + imb), the
    // contact's effective mass (0 when neither body moves), so that a visit multiplies where
    // it would divide twice (the divisions were a quarter of the passes' time).
    struct Masses {
        float ima = 0.0f, imb = 0.0f, inv_k = 0.0f;
    };
    std::array<Masses, 2> masses;
    float normal_impulse = 0.0f;   // accumulated, >= 0
    float tangent_impulse = 0.0f;  // accumulated, |.| <= friction * normal_impulse
    // When the contact was last visited (solve_velocities' clock), and whether that visit
    // changed nothing, in a plain (0) or a shock (1) pass (-1: it did, or none yet): with
    // neither body's velocity changed since, a visit in the same kind of pass would compute
    // the same nothing again.
    std::uint32_t seen = 0;
    std::int8_t quiet = -1;
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
std::pair<std::uint32_t, std::uint32_t> ends(const Pair& p) { return {p.a, p.b}; }
std::pair<std::uint32_t, std::uint32_t> ends(const std::pair<std::uint32_t, std::uint32_t>& p) { return p; }

template <typename Edges, typename Seeds>
std::vector<int> ground_levels(const std::vector<float>& inverse_mass, const Edges& edges, const Seeds& seeds) {
    std::vector<int> level(inverse_mass.size(), kUnreached);
    const EdgesByBody by_body(inverse_mass.size(), edges);
    std::vector<std::uint32_t> queue;
    for (const auto& seed : seeds) {
        const auto [a, b] = ends(seed);
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

VelocityContact velocity_contact(std::uint32_t a, const BodyState& sa, std::uint32_t b, const BodyState& sb,
                                 Vec2 normal, float target) {
    return {a, b, normal, target, mixed_friction(sa.friction, sb.friction), sa.inverse_mass, sb.inverse_mass};
}

VelocityContact::Masses masses_of(float ima, float imb) {
    // (1 / k of a denormal k overflows: the largest float instead, so that a resting contact's
    // zero approach still makes a zero impulse, not 0 * inf.)
    const float k = ima + imb;
    return {ima, imb, k > 0.0f ? fmin_inline(1.0f / k, FLT_MAX) : 0.0f};
}

void solve_velocity(BodyState* motion, VelocityContact& vc, bool shock, std::uint32_t& clock) {
    // (Read in place: a structured binding copied the three floats through the stack.)
    const VelocityContact::Masses& masses = vc.masses[shock ? 1 : 0];
    const float ima = masses.ima, imb = masses.imb, inv_k = masses.inv_k;
    if (!(inv_k > 0.0f)) return;
    BodyState& sa = motion[vc.a];
    BodyState& sb = motion[vc.b];
    // Nothing changed since a visit that changed nothing: skipped (the same nothing).
    if (vc.quiet == (shock ? 1 : 0) && sa.stamp < vc.seen && sb.stamp < vc.seen) return;
    vc.seen = ++clock;
    const Vec2 n = vc.normal;
    const float vn = dot(sb.velocity - sa.velocity, n);
    const float total = max0(vc.normal_impulse + (vc.target - vn) * inv_k);
    const float dn = total - vc.normal_impulse;
    vc.normal_impulse = total;
    // Only a body the contact can move takes the impulse: an immovable one keeps its velocity
    // (zero, as contacts see a static body) even when a NaN or infinite velocity elsewhere
    // makes the impulse NaN, so that a floor does not pass one body's NaN on to the others.
    // A zero impulse changes no velocity (its stamp says when one last changed).
    if (dn != 0.0f) {
        if (ima > 0.0f) {
            sa.velocity -= (ima * dn) * n;
            sa.stamp = clock;
        }
        if (imb > 0.0f) {
            sb.velocity += (imb * dn) * n;
            sb.stamp = clock;
        }
    }
    // Friction along the tangent, bounded by the normal impulse (Coulomb).
    const Vec2 t = perp(n);
    const float vt = dot(sb.velocity - sa.velocity, t);
    const float limit = vc.friction * vc.normal_impulse;
    // (A NaN tangential speed, from a NaN velocity on the other body, changes no impulse: the
    // clamp would pass the NaN on to this body, and through it to everything it touches.)
    const float wanted = vc.tangent_impulse - vt * inv_k;
    const float total_t = wanted == wanted ? std::clamp(wanted, -limit, limit) : vc.tangent_impulse;
    const float dt_impulse = total_t - vc.tangent_impulse;
    vc.tangent_impulse = total_t;
    if (dt_impulse != 0.0f) {
        if (ima > 0.0f) {
            const Vec2 dva = -(ima * dt_impulse) * t;
            sa.velocity += dva;
            sa.friction_dv += dva;
            sa.stamp = clock;
        }
        if (imb > 0.0f) {
            const Vec2 dvb = (imb * dt_impulse) * t;
            sb.velocity += dvb;
            sb.friction_dv += dvb;
            sb.stamp = clock;
        }
    }
    vc.quiet = dn == 0.0f && dt_impulse == 0.0f ? static_cast<std::int8_t>(shock ? 1 : 0) : std::int8_t{-1};
}

// `passes` passes in the given order; the last one goes ground up with shock propagation,
// so a resting stack ends still. The bodies' velocities are the step's packed working copy.
void solve_velocities(std::vector<BodyState>& motion, const std::vector<int>& level, std::vector<VelocityContact>& vcs,
                      int passes) {
    const std::vector<std::uint32_t> ground_up =
        ground_up_order(level, vcs.size(), [&](std::size_t k) { return std::pair{vcs[k].a, vcs[k].b}; });
    for (VelocityContact& vc : vcs) {
        const auto [ima, imb] = shock_masses(vc.ima, vc.imb, level[vc.a], level[vc.b], true);
        vc.masses = {masses_of(vc.ima, vc.imb), masses_of(ima, imb)};
    }
    passes = std::max(passes, 1);
    BodyState* const bodies = motion.data();
    // The clock starts past every body's stamp (stamps are this solve's, reset here).
    std::uint32_t clock = 0;
    const auto restart_clock = [&] {
        for (VelocityContact& vc : vcs) {
            bodies[vc.a].stamp = bodies[vc.b].stamp = 0;
            vc.quiet = -1;  // (already so at the start)
        }
        clock = 0;
    };
    restart_clock();
    for (int pass = 0; pass < passes; ++pass) {
        // A pass ticks the clock at most once a contact. Before it could wrap (over 4 billion
        // visits: a huge velocity_passes), every contact forgets that it was quiet: skipping
        // only saves work, so the results are the same.
        if (clock > UINT32_MAX - vcs.size()) restart_clock();
        if (pass == passes - 1 && passes > 1) {
            for (const std::uint32_t k : ground_up) solve_velocity(bodies, vcs[k], true, clock);
        } else {
            for (VelocityContact& vc : vcs) solve_velocity(bodies, vc, false, clock);
        }
    }
}

}  // namespace

// ---------------------------------------------------------------------------------------
// integrate: velocities from gravity, held by the contacts carried from the last step, then
// positions (semi-implicit Euler)
// ---------------------------------------------------------------------------------------

void World::Impl::integrate(float dt) {
    fast_circles.clear();
    bullets.clear();
    // The step's packed copies of what its pair loops read of each body (one pass here
    // instead of a few cache misses a pair): state (with the working copy of the velocity,
    // from here to the end of resolve), pushability and filter keys.
    states.resize(slots.size());
    pair_bodies.resize(slots.size());
    for (std::uint32_t i = 0; i < slots.size(); ++i) {
        Slot& s = slots[i];
        EntityDesc& b = s.body;
        s.fast = false;
        if (s.alive && b.kind == BodyKind::dynamic) b.velocity += (b.gravity_scale * dt) * desc.gravity;
        const bool still = b.kind == BodyKind::static_body;
        states[i] = {detail::contact_velocity(b.velocity, still), {}, detail::resolution_inverse_mass(b), b.friction,
                     b.restitution, still};
        detail::PairBody& pb = pair_bodies[i];
        pb.pushable = detail::pushability(b);
        pb.generation = s.generation;
        pb.layer = b.layer;
        pb.collides_with = b.collides_with;
        pb.ignore = b.ignore;
    }
    // Bodies resting on something keep resting: the contacts carried from the last step take
    // the approach out of this step's velocity before it moves anything (Box2D's order). A
    // box on the floor then does not sink by gravity * dt^2 each step, so sliding over tiled
    // ground meets no tile's side at the seams.
    std::vector<VelocityContact> carried;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
    for (const Contact& c : contacts) {
        const std::uint32_t a = c.a.index, b = c.b.index;
        if (c.trigger || c.corner || !detail::resolvable(pair_bodies[a].pushable, pair_bodies[b].pushable) ||
            !detail::may_meet(pair_bodies[a], a, pair_bodies[b], b)) {
            continue;
        }
        carried.push_back(velocity_contact(a, states[a], b, states[b], c.normal, 0.0f));
        edges.emplace_back(a, b);
    }
    if (!carried.empty()) {
        std::vector<float> inverse_mass(slots.size());
        for (std::size_t i = 0; i < slots.size(); ++i) inverse_mass[i] = states[i].inverse_mass;
        solve_velocities(states, ground_levels(inverse_mass, edges, edges), carried, desc.velocity_passes);
        for (const auto& [a, b] : edges) states[a].friction_dv = states[b].friction_dv = {};  // friction here acts before the motion
    }

    // The motion, and in the same pass over the bodies what the broadphase gathers of each:
    // its packed position and bounds and its grid item (fat bounds).
    grid_items.clear();
    positions.resize(slots.size());
    grid_movers = 0;
    for (std::uint32_t i = 0; i < slots.size(); ++i) {
        Slot& s = slots[i];
        EntityDesc& b = s.body;
        // Bullets move along their path in the sweeps phase; static bodies never move (and
        // keep their velocity field, which contacts read as zero).
        if (s.alive && b.kind != BodyKind::static_body) {
            b.velocity = states[i].velocity;
            const float angle = wrap_angle(b.angle + b.angular_velocity * dt);
            if (std::bit_cast<std::uint32_t>(angle) != std::bit_cast<std::uint32_t>(b.angle)) {
                b.angle = angle;
                turn(i);
            }
            if (b.kind == BodyKind::bullet) {
                bullets.push_back(i);
            } else {
                const Vec2 motion = dt * b.velocity;
                if (b.kind == BodyKind::dynamic) {
                    if (const auto* c = std::get_if<Circle>(&b.collider.local_shape())) {
                        // More than half its radius in one step could carry it through a thin wall.
                        s.fast = length(motion) > 0.5f * c->radius;
                        if (s.fast) fast_circles.push_back(i);
                    }
                }
                if (!s.fast) b.position += motion;
                sync_proxy(i, motion, s.fast ? motion : Vec2{});
            }
        }
        // Every collider but bullets' (they only cast) goes to the broadphase at its fat bounds.
        positions[i] = b.position;
        if (!s.alive || s.proxy < 0 || b.kind == BodyKind::bullet) continue;
        const bool moves = detail::is_moving_kind(b.kind);
        grid_items.push_back({broadphase.fat_bounds(s.proxy), i, moves});
        grid_movers += moves ? 1 : 0;
        pair_bodies[i].box = placement(i).box;  // for the narrowphase and resolve
    }
    refattened.clear();  // the broadphase's pairs are over the fat bounds as they are now
}

// ---------------------------------------------------------------------------------------
// broadphase: candidate pairs from the grid (or tree queries), filtered, in (lower id, higher id) order
// ---------------------------------------------------------------------------------------

std::vector<Pair> World::Impl::broadphase_pairs() {
    // The colliders' fat bounds (grid_items, gathered by integrate); a pair needs one side
    // that moves. The pairs are those whose fat bounds overlap, found either by a tree query
    // from each moving body or, faster when many things move, all at once by the grid: the
    // same pairs either way (tests/world/pair_grid_test.cpp).
    const std::size_t moving = grid_movers;
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
        const detail::PairBody& ba = pair_bodies[g.a];
        const detail::PairBody& bb = pair_bodies[g.b];
        if (ba.pushable < 0.0f && bb.pushable < 0.0f) continue;  // two triggers
        if (!detail::may_meet(ba, g.a, bb, g.b)) continue;
        pairs.push_back({g.a, g.b, touch(ba.box, bb.box), ba.pushable < 0.0f || bb.pushable < 0.0f,
                         detail::resolvable(ba.pushable, bb.pushable)});
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
    std::size_t last_at = 0;
    Shape b_back;  // a body moved back for a kept contact: one shape's storage for them all
    // The last step's contact of a pair, if any. Ids order by index first, as the pairs do, so
    // the cursor compares indices, and generations only where they match (a slot's contacts
    // go when its entity does, so they always match; checked all the same).
    const auto last_step = [&](const Pair& p) -> const Contact* {
        const auto before = [&](const Contact& c) { return c.a.index != p.a ? c.a.index < p.a : c.b.index < p.b; };
        while (last_at < contacts.size() && before(contacts[last_at])) ++last_at;
        if (last_at == contacts.size()) return nullptr;
        const Contact& c = contacts[last_at];
        if (c.a.index != p.a || c.b.index != p.b) return nullptr;
        const bool same = c.a.generation == pair_bodies[p.a].generation && c.b.generation == pair_bodies[p.b].generation;
        return same ? &c : nullptr;
    };
    for (const Pair& p : pairs) {
        // Bounds first: cheap, and for masks it is the lecture's first test (09-30). The
        // packed boxes (p.touching, from broadphase_pairs) turn most candidates away without
        // reading their placements: they are the placements' bounds, usable (finite and in
        // order: a body has a proxy), so touching is exactly overlaps(pa.box, pb.box).
        // The broadphase placed every body and nothing has moved since, so the placements
        // are read directly (checking them against the bodies would be a cache miss each).
        const detail::Placement& pa = placements[p.a];
        if (p.touching) {
            const detail::Placement& pb = placements[p.b];
            JOSTLE_DEBUG_ASSERT(placement_current(p.a) && placement_current(p.b), "a stale placement in the narrowphase");
            JOSTLE_DEBUG_ASSERT(overlaps(pa.box, pb.box), "packed bounds that touch and placements' that do not");
            const Manifold m = collide(pa.shape, pb.shape);
            if (m.hit) {
                found.push_back({p, m, 0.0f, p.trigger, detail::corner_touch(pa.shape, pb.shape, m)});
                continue;
            }
        }
        // Bodies that touched last step and now miss by a rounding error (or a small gap)
        // stay in contact speculatively: B moved back toward A along the last normal by
        // kSpeculative shows how far apart they are. Without this a resting stack loses a
        // contact whenever rounding opens a 1e-5 px gap, and the body above falls through
        // a step of gravity.
        if (p.trigger || !p.resolvable) continue;
        const Contact* last = last_step(p);
        if (last == nullptr) continue;
        constexpr float kSpeculative = 1.0f;  // px
        place_into(p.b, positions[p.b] - kSpeculative * last->normal, b_back);
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
    // From the packed pushabilities (integrate): a trigger's -1 is inverse mass 0.
    std::vector<float> inverse_mass(slots.size());
    for (std::size_t i = 0; i < slots.size(); ++i) inverse_mass[i] = max0(pair_bodies[i].pushable);
    const auto resolvable = [](const Pair& p) { return p.resolvable; };
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
        const BodyState& sa = states[c->pair.a];
        const BodyState& sb = states[c->pair.b];
        const Vec2 n = c->manifold.normal;
        const float vn = dot(sb.velocity - sa.velocity, n);
        float target = 0.0f;
        if (c->separation > 0.0f) {
            target = -c->separation / dt;  // may close the gap in the next step, no more
        } else if (vn < -desc.restitution_threshold) {
            target = -mixed_restitution(sa.restitution, sb.restitution) * vn;
        }
        vcs.push_back(velocity_contact(c->pair.a, sa, c->pair.b, sb, n, target));
    }
    solve_velocities(states, level, vcs, desc.velocity_passes);
    for (const VelocityContact& vc : vcs) {
        for (const std::uint32_t i : {vc.a, vc.b}) {
            if (!states[i].still) slots[i].body.velocity = states[i].velocity;
        }
    }

    // What friction took from the tangential velocity is taken from this step's motion too
    // (semi-implicit Euler), so a body that friction stops does not slide on for a step.
    // The passes' working copy of the positions (from integrate's packed copy: the
    // narrowphase's), with each body's displacement since.
    std::vector<detail::Moving> moves(slots.size());
    for (std::size_t i = 0; i < slots.size(); ++i) moves[i].position = positions[i];
    std::vector<std::uint8_t> moved(slots.size(), 0);
    for (const NarrowContact* c : contacts_in) {
        for (std::uint32_t i : {c->pair.a, c->pair.b}) {
            Vec2& friction_dv = states[i].friction_dv;
            if ((friction_dv.x == 0.0f && friction_dv.y == 0.0f) || slots[i].fast) continue;
            Slot& s = slots[i];
            const Vec2 before = s.body.position;
            s.body.position += dt * friction_dv;
            friction_dv = {};  // once per body
            moves[i] = {s.body.position, s.body.position - before};
            moved[i] = 1;
        }
    }
    relax_positions(found, push_pairs, inverse_mass, level, moves, moved);
}

// ---------------------------------------------------------------------------------------
// resolve, position: relaxation passes along the contacts' MTD normals
// ---------------------------------------------------------------------------------------

namespace {

// A contact as the position passes see it. A pass only translates bodies, and a convex
// shape's extent along a fixed axis moves with it, so the overlap along the narrowphase's
// normal n is exactly offset - dot(db - da, n), where da and db are the bodies'
// displacements since the narrowphase: no shape test per visit. (Displacements, not
// positions: they are small, so the difference keeps the precision of the overlap.)
// That overlap bounds the MTD depth from above (the MTD is the smallest overlap over all
// axes), so a contact settled along n is settled.
// A circle against another circle or a corner (a vertex region: 09-90) is a pair of points
// instead, the centre and the other centre or the corner: its normal turns as they move, and
// the depth is reach - |gap| along the gap between the points, as collide() finds it. A
// centre pushed out of the corner's region (its cone of normals, between the normals of the
// corner's two faces) is measured from the face it moved beside, as collide() would: the
// distance to the corner would understate the depth there.
// Mask MTDs are whole pixels: mask contacts are placed and tested again at each visit.
enum class PassKind : std::uint8_t { along_normal, points, mask };

struct PassContact {
    std::uint32_t a = 0, b = 0;
    Vec2 normal;
    float offset = 0.0f;   // along_normal: the overlap when found + dot(db - da, n) then
    Vec2 gap;              // points: B's point - A's point when found - (db - da) then
    float reach = 0.0f;    // points: the radii
    float share_a = 0.0f, share_b = 0.0f;  // of a push: ima / (ima + imb), imb / (ima + imb)
    float shock_a = 0.0f, shock_b = 0.0f;  // the same under shock propagation
    PassKind kind = PassKind::along_normal;
    // points at a corner: the corner's faces' outward normals, turning from n_prev to n_next
    // through its region, and which body the corner is on (none: two circles, or a point).
    enum class Corner : std::uint8_t { none, of_a, of_b } corner = Corner::none;
    // The last visit that measured the contact (the passes' clock), and whether it found it
    // settled: with neither body moved since, a visit would find it settled again.
    bool quiet = false;
    std::uint32_t seen = 0;
    Vec2 n_prev, n_next;
};

// Each body's share of a push, 0 when neither moves (k = 0, or a NaN mass).
std::pair<float, float> push_shares(float ima, float imb) {
    const float k = ima + imb;
    if (!(k > 0.0f)) return {0.0f, 0.0f};
    return {ima / k, imb / k};
}

// Calls f(v, n_prev, n_next) for each vertex of a convex shape (none for a circle or mask),
// with the outward normals of the faces before and after it (its region lies between them,
// counterclockwise as the collision module winds polygons). A segment's end has the two sides
// of its line (the region beyond the end); a segment of zero length has no faces (zero normals).
template <typename F>
void for_each_vertex(const Shape& s, F&& f) {
    if (const auto* box = std::get_if<Aabb>(&s)) {
        const Vec2 v[4] = {box->min, Vec2{box->max.x, box->min.y}, box->max, Vec2{box->min.x, box->max.y}};
        constexpr Vec2 kNormals[4] = {{0.0f, -1.0f}, {1.0f, 0.0f}, {0.0f, 1.0f}, {-1.0f, 0.0f}};  // face i: v[i] -> v[i+1]
        for (int i = 0; i < 4; ++i) f(v[i], kNormals[(i + 3) % 4], kNormals[i]);
    } else if (const auto* obb = std::get_if<Obb>(&s)) {
        const Rot q = obb->rotation();
        const Vec2 h = obb->half;
        const Vec2 corners[4] = {h, {-h.x, h.y}, -h, {h.x, -h.y}};
        constexpr Vec2 kNormals[4] = {{0.0f, 1.0f}, {-1.0f, 0.0f}, {0.0f, -1.0f}, {1.0f, 0.0f}};  // face i: i -> i+1
        for (int i = 0; i < 4; ++i) {
            f(obb->center + rotate(q, corners[i]), rotate(q, kNormals[(i + 3) % 4]), rotate(q, kNormals[i]));
        }
    } else if (const auto* poly = std::get_if<Polygon>(&s)) {
        const int n = poly->count();
        for (int i = 0; i < n; ++i) f(poly->points()[i], poly->normals()[(i + n - 1) % n], poly->normals()[i]);
    } else if (const auto* seg = std::get_if<Segment>(&s)) {
        const Vec2 d = seg->b - seg->a;
        const float len = length(d);
        const Vec2 n = len > 0.0f ? Vec2{d.y / len, -d.x / len} : Vec2{};
        f(seg->a, -n, n);
        f(seg->b, n, -n);
    }
}

// Whether u (from a corner) lies in the corner's region, between the normals of its faces.
bool in_corner_region(Vec2 u, Vec2 n_prev, Vec2 n_next) { return cross(n_prev, u) >= 0.0f && cross(u, n_next) >= 0.0f; }

// The point of `other` that a hit `m` with `circle` came from, when it is a single point:
// the other circle's centre, or a vertex whose region holds the centre (m's normal then runs
// along the line from the vertex to the centre, and m's depth is the radius less their
// distance; a face's normal and depth do not). `toward` is +1 when the circle is B (the
// normal runs from other to circle), -1 when it is A.
struct PointFeature {
    Vec2 point;
    Vec2 n_prev, n_next;  // the corner's faces (zero for a circle's centre or a point)
};
std::optional<PointFeature> point_feature(const Shape& other, const Circle& circle, const Manifold& m, float toward) {
    if (const auto* c = std::get_if<Circle>(&other)) return PointFeature{c->center, {}, {}};
    std::optional<PointFeature> found;
    float nearest = INFINITY;
    const float reach = circle.radius;
    for_each_vertex(other, [&](Vec2 v, Vec2 n_prev, Vec2 n_next) {
        const Vec2 d = toward * (circle.center - v);  // along the normal in a vertex region
        const float len = length(d);
        if (!(len > 0.0f) || !(len < nearest)) return;
        nearest = len;
        // The vertex region's normal is d / |d| (09-90), and its depth reach - |d|, up to rounding.
        const bool along = length(Vec2{d.x / len, d.y / len} - m.normal) <= 1e-4f;
        const bool deep = std::fabs((reach - len) - m.depth) <= 1e-4f * (1.0f + reach);
        found = along && deep ? std::optional<PointFeature>(PointFeature{v, n_prev, n_next}) : std::nullopt;
    });
    return found;
}

// Translated bounds, grown by `margin`: a superset of the bounds the shape would have if it
// were placed again at its new position (placing rounds each vertex once).
bool touch_moved(const Aabb& a, Vec2 da, const Aabb& b, Vec2 db, float margin) {
    const Vec2 d = db - da;  // b relative to a
    return (a.max.x + margin >= b.min.x + d.x) & (a.min.x - margin <= b.max.x + d.x) &
           (a.max.y + margin >= b.min.y + d.y) & (a.min.y - margin <= b.max.y + d.y);
}

// resolve's position passes over one step's contacts, as the MANUAL describes them: the
// contacts (PassContact), the candidate pairs still apart that pushes may bring together,
// and the bodies' working positions.
class PositionPasses {
public:
    PositionPasses(World::Impl& w, const std::vector<Pair>& push_pairs, const std::vector<float>& inverse_mass,
                   const std::vector<int>& level, std::vector<detail::Moving>& moves, std::vector<std::uint8_t>& moved)
        : w_(w), push_pairs_(push_pairs), inverse_mass_(inverse_mass), level_(level), moves_(moves), moved_(moved),
          // A contact no deeper than half the slop is settled and not pushed: in a crowd most
          // pushes are that small, each moves bodies that then disturb their neighbours, and
          // the passes stop anyway once every contact is within it (Box2D likewise leaves the
          // last linear slop uncorrected). Resting contacts so end within the slop.
          settled_(std::fmax(0.5f * w.desc.slop, 0.0f)), apart_(push_pairs.size(), 1) {}

    // The narrowphase's contacts (hits, and kept contacts a gap apart: negative overlap) are
    // the passes' contacts; corner-to-corner touches have no true normal and wait with the
    // other candidate pairs (apart_) until a push brings them into each other.
    void take(const std::vector<World::Impl::NarrowContact>& found) {
        contacts_.reserve(found.size());
        for (std::size_t k = 0, f = 0; k < push_pairs_.size(); ++k) {
            const Pair& p = push_pairs_[k];
            while (f < found.size() && (found[f].pair.a < p.a || (found[f].pair.a == p.a && found[f].pair.b < p.b))) ++f;
            if (f == found.size() || found[f].pair.a != p.a || found[f].pair.b != p.b || found[f].corner) {
                if (immovable_in(p.a, p.b)) grounded_.push_back(static_cast<std::uint32_t>(k));
                continue;
            }
            const World::Impl::NarrowContact& c = found[f];
            const float overlap = c.separation > 0.0f ? -c.separation : c.manifold.depth;
            // (At the narrowphase's placements: friction may have moved the bodies since. A
            // kept contact a gap apart is pushed along its normal: its points are not in touch.)
            Manifold m = c.manifold;
            m.hit = c.separation <= 0.0f;
            add(p.a, p.b, w_.placements[p.a].shape, w_.placements[p.b].shape, m, overlap, {});
            apart_[k] = 0;
        }
        order();
    }

    void run(int passes) {
        bool settled_all = false;
        for (int pass = 0; pass < passes && !settled_all; ++pass) {
            const bool shock = pass >= passes / 2;
            // Whenever the passes settle every new overlap joins (and the passes go on if any
            // did); before each shock pass those with something immovable, which the
            // ground-up order takes first. (Joining every pair mid-way in a crowd that never
            // settles cost a shape test for each of its many near misses, to find a few
            // overlaps that the next step's narrowphase finds anyway.)
            if (shock) join_new(/*grounded_only=*/true);
            keep_clock();
            float deepest = 0.0f;
            for (std::size_t r = 0; r < contacts_.size(); ++r) {
                PassContact& c = contacts_[shock ? ground_up_[r] : r];
                // Most visits in a settling crowd find a still contact: tested here, not in a call.
                if (still(c)) continue;
                const float depth = visit(c, shock);  // >= 0
                deepest = depth > deepest ? depth : deepest;
            }
            settled_all = deepest <= settled_ && join_new(false) == 0;
        }
        // A crowd may use up its passes unsettled, and a push in the last of them can leave a
        // body inside a wall: the contacts with something immovable get one more pass, last
        // (what that leaves between movable bodies waits for the next step, as any unsettled
        // overlap).
        if (!settled_all) {
            join_new(/*grounded_only=*/true);
            keep_clock();
            for (PassContact& c : contacts_) {
                if (immovable_in(c.a, c.b)) visit(c, true);
            }
        }
    }

private:
    // A pass ticks the clock at most once a contact. Before it could wrap (over 4 billion
    // visits: a huge relaxation_passes), every contact forgets that it was settled: skipping
    // only saves work, so the results are the same.
    void keep_clock() {
        if (clock_ <= UINT32_MAX - contacts_.size()) return;
        for (PassContact& c : contacts_) {
            c.quiet = false;
            moves_[c.a].stamp = moves_[c.b].stamp = 0;
        }
        clock_ = 0;
    }

    bool immovable_in(std::uint32_t a, std::uint32_t b) const {
        return !(inverse_mass_[a] > 0.0f && inverse_mass_[b] > 0.0f);
    }

    // A contact between shapes sa and sb (placed when B had moved `since` more than A) whose
    // overlap along n is `overlap` (m.depth for a hit, or minus a kept contact's gap).
    void add(std::uint32_t a, std::uint32_t b, const Shape& sa, const Shape& sb, const Manifold& m, float overlap,
             Vec2 since) {
        PassContact c{a, b, m.normal, overlap + dot(since, m.normal)};
        std::tie(c.share_a, c.share_b) = push_shares(inverse_mass_[a], inverse_mass_[b]);
        const auto [ia, ib] = shock_masses(inverse_mass_[a], inverse_mass_[b], level_[a], level_[b], true);
        std::tie(c.shock_a, c.shock_b) = push_shares(ia, ib);
        const auto points = [&](Vec2 gap, float reach, PassContact::Corner corner, const PointFeature& f) {
            c.kind = PassKind::points;
            c.offset = 0.0f;
            c.gap = gap - since;
            c.reach = reach;
            c.corner = corner;
            c.n_prev = f.n_prev;
            c.n_next = f.n_next;
        };
        if (std::holds_alternative<PlacedMask>(sa) || std::holds_alternative<PlacedMask>(sb)) {
            c.kind = PassKind::mask;
        } else if (const auto* cb = std::get_if<Circle>(&sb); cb != nullptr && m.hit) {
            if (const std::optional<PointFeature> pa = point_feature(sa, *cb, m, 1.0f)) {
                const auto* ca = std::get_if<Circle>(&sa);
                points(cb->center - pa->point, (ca != nullptr ? ca->radius : 0.0f) + cb->radius,
                       ca != nullptr ? PassContact::Corner::none : PassContact::Corner::of_a, *pa);
            }
        } else if (const auto* ca = std::get_if<Circle>(&sa); ca != nullptr && m.hit) {
            if (const std::optional<PointFeature> pb = point_feature(sb, *ca, m, -1.0f)) {
                points(pb->point - ca->center, ca->radius, PassContact::Corner::of_b, *pb);
            }
        }
        contacts_.push_back(c);
    }

    void order() {
        ground_up_ = ground_up_order(level_, contacts_.size(),
                                     [&](std::size_t k) { return std::pair{contacts_[k].a, contacts_[k].b}; });
    }

    // Pushes can bring candidate pairs that were apart into each other: one with a body that
    // moved and bounds that now touch is tested again (placed where it is now; the placements
    // stay the narrowphase's), and joins the passes if it overlaps.
    bool join(std::uint32_t k) {
        if (!apart_[k]) return false;
        const Pair& p = push_pairs_[k];
        if (!(moved_[p.a] | moved_[p.b])) return false;
        // The bounds move by what the positions moved, rounding included (far from the origin
        // that differs from the sum of the pushes, moved_by, by more than the margin allows).
        constexpr float kBoundsMargin = 1.0f / 64.0f;  // px: rounding of placement, up to |x| = 1e5
        if (!touch_moved(w_.pair_bodies[p.a].box, moves_[p.a].position - w_.positions[p.a], w_.pair_bodies[p.b].box,
                         moves_[p.b].position - w_.positions[p.b], kBoundsMargin)) {
            return false;
        }
        w_.place_into(p.a, moves_[p.a].position, join_a_);
        w_.place_into(p.b, moves_[p.b].position, join_b_);
        const Manifold m = collide(join_a_, join_b_);
        if (!m.hit || !(m.depth > settled_)) return false;
        add(p.a, p.b, join_a_, join_b_, m, m.depth, moves_[p.b].moved_by - moves_[p.a].moved_by);
        apart_[k] = 0;
        return true;
    }

    // Every apart pair, or only those with an immovable body. Returns how many joined.
    std::size_t join_new(bool grounded_only) {
        std::size_t joined = 0;
        if (grounded_only) {
            for (const std::uint32_t k : grounded_) joined += join(k) ? 1 : 0;
        } else {
            for (std::uint32_t k = 0; k < push_pairs_.size(); ++k) joined += join(k) ? 1 : 0;
        }
        if (joined > 0) order();
        return joined;
    }

    // Settled when last visited, and neither body moved since: a visit would find it settled.
    bool still(const PassContact& c) const { return c.quiet && moves_[c.a].stamp < c.seen && moves_[c.b].stamp < c.seen; }

    // One visit: the contact's overlap now, and if deeper than settled, the push along its
    // normal, split by the shares. Returns the overlap (0 when not pushed).
    float visit(PassContact& c, bool shock) {
        const float wa = shock ? c.shock_a : c.share_a;
        const float wb = shock ? c.shock_b : c.share_b;
        if (!(wa + wb > 0.0f)) return 0.0f;
        if (still(c)) return 0.0f;
        detail::Moving& ma = moves_[c.a];
        detail::Moving& mb = moves_[c.b];
        c.seen = ++clock_;
        float depth = 0.0f;
        Vec2 normal = c.normal;
        if (c.kind == PassKind::along_normal) {
            depth = c.offset - dot(mb.moved_by - ma.moved_by, c.normal);
        } else if (c.kind == PassKind::points) {
            const Vec2 gap = c.gap + (mb.moved_by - ma.moved_by);  // from A's point to B's
            const Vec2 u = c.corner == PassContact::Corner::of_b ? -gap : gap;  // from the corner
            if (c.corner != PassContact::Corner::none && !(c.n_prev == Vec2{}) && !in_corner_region(u, c.n_prev, c.n_next)) {
                // Beside a face now: its normal, and the centre's distance from its line.
                const Vec2 face = dot(u, c.n_prev) >= dot(u, c.n_next) ? c.n_prev : c.n_next;
                depth = c.reach - dot(u, face);
                normal = c.corner == PassContact::Corner::of_a ? face : -face;
            } else {
                const float len = length(gap);
                depth = c.reach - len;
                if (len > 0.0f && len < INFINITY) normal = {gap.x / len, gap.y / len};  // else the narrowphase's
            }
        } else {
            w_.place_into(c.a, ma.position, join_a_);
            w_.place_into(c.b, mb.position, join_b_);
            const Manifold m = collide(join_a_, join_b_);
            depth = m.hit ? m.depth : 0.0f;
            normal = m.normal;
        }
        c.quiet = !(depth > settled_);
        if (c.quiet) return 0.0f;
        const Vec2 mtd = depth * normal;  // moves B out of A
        Vec2 push_a = wa * mtd;
        Vec2 push_b = wb * mtd;
        if (c.kind == PassKind::mask) {
            // Mask MTDs are whole pixels, and so is each body's share of one.
            const auto whole = [](Vec2 v) { return Vec2{std::floor(v.x + 0.5f), std::floor(v.y + 0.5f)}; };
            push_a = whole(push_a);
            push_b = whole(mtd) - push_a;
        }
        // A body whose share is 0 stays where it is, to the bit (not moved by 0 * a NaN push,
        // nor from -0 to +0): no stamp, no mark.
        if (wa > 0.0f) {
            ma.position -= push_a;
            ma.moved_by -= push_a;
            ma.stamp = clock_;
            moved_[c.a] = 1;
        }
        if (wb > 0.0f) {
            mb.position += push_b;
            mb.moved_by += push_b;
            mb.stamp = clock_;
            moved_[c.b] = 1;
        }
        return depth;
    }

    World::Impl& w_;
    const std::vector<Pair>& push_pairs_;
    const std::vector<float>& inverse_mass_;
    const std::vector<int>& level_;
    std::vector<detail::Moving>& moves_;
    std::vector<std::uint8_t>& moved_;
    const float settled_;
    std::vector<PassContact> contacts_;
    std::vector<std::uint32_t> ground_up_;  // contacts_'s ground-up order (shock passes)
    std::vector<std::uint8_t> apart_;       // by push pair: not (yet) one of contacts_
    std::vector<std::uint32_t> grounded_;   // the apart pairs with an immovable body
    Shape join_a_, join_b_;  // a pair placed where it is now (storage reused)
    std::uint32_t clock_ = 0;  // counts visits that measure a contact (Moving::stamp, PassContact::seen)
};

}  // namespace

void World::Impl::relax_positions(const std::vector<NarrowContact>& found, const std::vector<Pair>& push_pairs,
                                  const std::vector<float>& inverse_mass, const std::vector<int>& level,
                                  std::vector<detail::Moving>& moves, std::vector<std::uint8_t>& moved) {
    PositionPasses passes(*this, push_pairs, inverse_mass, level, moves, moved);
    passes.take(found);
    passes.run(std::max(desc.relaxation_passes, 1));
    // The bodies that moved (friction or pushes) take their new positions, and their
    // proxies follow.
    for (std::uint32_t i = 0; i < slots.size(); ++i) {
        if (!moved[i]) continue;
        slots[i].body.position = moves[i].position;
        sync_proxy(i);
    }
}

// ---------------------------------------------------------------------------------------
// events: compare this step's contacts with the last step's
// ---------------------------------------------------------------------------------------

void World::Impl::emit_events(std::vector<Contact> touching, bool removed_some) {
    const auto key_less = [](const Contact& x, const Contact& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; };
    // The narrowphase's contacts come sorted, those of the sweeps after them: sorting just the
    // rest and merging is the same stable sort.
    const auto sorted_end = std::is_sorted_until(touching.begin(), touching.end(), key_less);
    std::stable_sort(sorted_end, touching.end(), key_less);
    std::inplace_merge(touching.begin(), sorted_end, touching.end(), key_less);
    // A pair found by the narrowphase and again by a sweep keeps the narrowphase's entry.
    touching.erase(std::unique(touching.begin(), touching.end(),
                               [](const Contact& x, const Contact& y) { return x.a == y.a && x.b == y.b; }),
                   touching.end());
    // Contacts with an entity destroyed during the step (a bullet that despawned) are dropped.
    if (removed_some) std::erase_if(touching, [&](const Contact& c) { return find(c.a) == nullptr || find(c.b) == nullptr; });

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
