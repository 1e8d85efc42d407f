// The world's private state, shared by the files that implement World: world.cpp (entities),
// step.cpp (the step's phases), continuous.cpp (bullets and fast circles), queries.cpp and
// state_hash.cpp.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "broadphase.h"
#include "pair_grid.h"
#include "jostle/world.h"

namespace jostle {

namespace detail {

struct Slot {
    EntityDesc body;
    std::uint32_t generation = 0;  // the live entity's, or the last one's when free
    bool alive = false;
    int proxy = -1;                // broadphase proxy, -1 when the collider meets nothing
    std::uint64_t mask_fingerprint = 0;  // hash of the mask's pixels (0: no mask)
    bool fast = false;             // this step: a dynamic circle left for the sweeps phase
    // The collider turned by turned_angle (Collider::turned): while the body's angle is the
    // same, placing it is a translation (no sine, cosine or rotation per placement).
    Shape turned;
    float turned_angle = 0.0f;
    bool turned_valid = false;
};

// A slot's collider placed at its body's transform, kept while the body's position and
// angle stay the same: both are compared by their bits on every use, so a move or a turn
// can never leave a stale shape; a new collider goes through turn(), which drops it. A step
// places each collider once per position it takes.
struct Placement {
    Vec2 position;  // the key first, next to the box: one cache line for both
    float angle = 0.0f;
    bool valid = false;
    Aabb box;  // bounds(shape)
    Shape shape;
};

// A body as the step's velocity passes and pair loops read it, packed once a step by
// integrate (an EntityDesc spans several cache lines; a step reads thousands of pairs). The
// velocity is the step's working copy from integrate to the end of resolve.
struct BodyState {
    Vec2 velocity;              // as contacts see it: zero for a static body (whose own is kept)
    Vec2 friction_dv;           // velocity change from friction impulses (within a solve)
    float inverse_mass = 0.0f;  // resolution_inverse_mass
    float friction = 0.0f;
    float restitution = 0.0f;
    bool still = false;         // a static body: contacts see it at rest
    std::uint32_t stamp = 0;    // a velocity solve's clock when the velocity last changed
};

// What the candidate-pair loops (broadphase filter, narrowphase, resolve) read of a body
// for every pair before anything else, in one place: the other body of a pair is anywhere
// in memory, so each array read there costs a cache miss.
struct PairBody {
    Aabb box;               // placement's bounds at the broadphase (bodies with a proxy)
    float pushable = 0.0f;  // pushability(body)
    std::uint32_t generation = 0;
    std::uint32_t layer = 0;          // the filter's fields (may_meet)
    std::uint32_t collides_with = 0;
    EntityId ignore;
};

// A body's position during resolve's passes, and how far it moved since the narrowphase.
struct Moving {
    Vec2 position;
    Vec2 moved_by;
    std::uint32_t stamp = 0;  // the passes' clock when a push last moved it (0: not yet)
};

// A candidate pair; a.index < b.index. broadphase_pairs reads both bodies' packed records
// once for its filter, and keeps here what the later loops ask of the pair first, so that
// they need not read them again (the other body of a pair is anywhere in memory).
struct Pair {
    std::uint32_t a = 0;
    std::uint32_t b = 0;
    bool touching = false;    // their bounds (PairBody::box) touch
    bool trigger = false;     // one of them is a trigger
    bool resolvable = false;  // resolvable(pushabilities): resolution moves one of them
};

// The point where two placed shapes meet, given their manifold (contact_point.cpp).
Vec2 contact_point(const Shape& a, const Shape& b, const Manifold& m);
// Shapes touching (depth 0) only corner to corner: the manifold's normal is then one of a
// tie (a box sliding onto the next floor tile), so it takes no velocity response.
bool corner_touch(const Shape& a, const Shape& b, const Manifold& m);

// Inverse mass as resolution sees it: 0 for everything that is not a dynamic body. These
// small predicates are inline: the step asks them for every candidate pair.
inline float resolution_inverse_mass(const EntityDesc& body) {
    if (body.kind != BodyKind::dynamic) return 0.0f;
    const float im = body.inverse_mass;
    return (std::isfinite(im) && im > 0.0f) ? im : 0.0f;
}
inline bool is_moving_kind(BodyKind k) {  // kinematic, dynamic, trigger
    return k == BodyKind::kinematic || k == BodyKind::dynamic || k == BodyKind::trigger;
}
// Velocity as contacts see it: a static body's is zero whatever its velocity field holds.
inline Vec2 contact_velocity(Vec2 velocity, bool is_static) { return is_static ? Vec2{} : velocity; }
inline Vec2 contact_velocity(const EntityDesc& body) {
    return contact_velocity(body.velocity, body.kind == BodyKind::static_body);
}
// What may_meet reads of a body, packed: the step filters tens of thousands of candidate
// pairs a step, and a body's EntityDesc spans several cache lines.
struct MeetKey {
    EntityId id;
    EntityId ignore;
    std::uint32_t layer = 0;
    std::uint32_t collides_with = 0;
};
inline MeetKey meet_key(const EntityDesc& body, EntityId id) { return {id, body.ignore, body.layer, body.collides_with}; }
// Layer bits and `ignore` (see the MANUAL).
inline bool may_meet(const MeetKey& a, const MeetKey& b) {
    if ((a.layer & b.collides_with) == 0 || (b.layer & a.collides_with) == 0) return false;
    return !(a.ignore == b.id || b.ignore == a.id);
}
inline bool may_meet(const EntityDesc& a, EntityId a_id, const EntityDesc& b, EntityId b_id) {
    return may_meet(meet_key(a, a_id), meet_key(b, b_id));
}
inline bool may_meet(const PairBody& a, std::uint32_t a_index, const PairBody& b, std::uint32_t b_index) {
    return may_meet(MeetKey{{a_index, a.generation}, a.ignore, a.layer, a.collides_with},
                    MeetKey{{b_index, b.generation}, b.ignore, b.layer, b.collides_with});
}
// Resolution moves one of them: no trigger, and at least one body with inverse mass > 0.
// On packed data (resolve keeps one float a body): -1 for a trigger, else the resolution
// inverse mass.
inline float pushability(const EntityDesc& body) {
    return body.kind == BodyKind::trigger ? -1.0f : resolution_inverse_mass(body);
}
inline bool resolvable(float pushability_a, float pushability_b) {
    return pushability_a >= 0.0f && pushability_b >= 0.0f && (pushability_a > 0.0f || pushability_b > 0.0f);
}
inline bool resolvable(const EntityDesc& a, const EntityDesc& b) { return resolvable(pushability(a), pushability(b)); }

}  // namespace detail

struct World::Impl {
    WorldDesc desc;
    std::vector<detail::Slot> slots;
    std::vector<detail::Placement> placements;  // one per slot
    std::vector<std::uint32_t> free_slots;  // reused last-in first-out
    std::size_t live = 0;
    detail::Broadphase broadphase;  // fat bounds, with a lazy tree for region queries (sweeps, World queries)
    detail::PairGrid pair_grid;     // all candidate pairs at once, over the same fat bounds
    std::vector<detail::GridItem> grid_items;  // gathered by integrate for broadphase_pairs
    std::size_t grid_movers = 0;               // of grid_items, those that move
    std::vector<detail::GridPair> grid_pairs;
    // Scratch of the step, one entry a slot: packed copies of what its pair loops read (an
    // EntityDesc spans several cache lines, and there are tens of thousands of pairs).
    // Filled by integrate:
    std::vector<detail::BodyState> states;
    std::vector<detail::PairBody> pair_bodies;  // all but the box; the box after the motion
    // and, after the motion, for resolve (the narrowphase's positions) and kept contacts:
    std::vector<Vec2> positions;           // body.position (every slot)
    // The slots whose fat bounds changed (proxy made, re-fattened or dropped) since the
    // step's broadphase: with the candidate pairs, all a fast circle's sweep can meet.
    std::vector<std::uint32_t> refattened;
    std::vector<std::uint32_t> fast_circles;  // this step's, in slot order (integrate)
    std::vector<std::uint32_t> bullets;       // this step's live bullets, in slot order (integrate)
    std::vector<Contact> contacts;          // after the last step, sorted by (a, b)
    std::vector<Event> events;
    std::vector<SweptPath> paths;
    EventHandler handler;
    Rng rng;
    std::uint64_t steps = 0;
    std::uint64_t removals = 0;  // remove() calls ever: a step that made none has no stale ids
    bool in_step = false;

    explicit Impl(const WorldDesc& d) : desc(d), rng(d.seed) {}

    detail::Slot* find(EntityId id);
    const detail::Slot* find(EntityId id) const;
    EntityId id_of(std::uint32_t index) const { return {index, slots[index].generation}; }
    Shape placed(std::uint32_t index) const;
    Shape placed_at(std::uint32_t index, Vec2 position) const;  // at another position
    // out = placed_at(index, position), reusing out's storage (see Collider::place).
    void place_into(std::uint32_t index, Vec2 position, Shape& out) const;
    // placed(index) and its bounds, computed only when the body moved or turned since the
    // last call. The reference is valid until the next create().
    const detail::Placement& placement(std::uint32_t index);
    bool placement_current(std::uint32_t index) const;  // placement(index) would not recompute
    // Brings slot index's turned collider up to date with its collider and angle; called
    // wherever either changes.
    void turn(std::uint32_t index);
    // Brings slot index's proxy up to date with its placed collider (creating or dropping
    // it when the bounds become usable or not).
    // A fast circle's proxy also covers where this step's motion (`sweep`) takes it, so that
    // its sweep's candidates are among its candidate pairs.
    void sync_proxy(std::uint32_t index, Vec2 displacement = {}, Vec2 sweep = {});
    void remove(std::uint32_t index);  // destroy: free the slot, drop its contacts

    // The phases of step(), in order (step.cpp, continuous.cpp).
    void integrate(float dt);
    std::vector<detail::Pair> broadphase_pairs();
    struct NarrowContact {
        detail::Pair pair;
        Manifold manifold;  // at the narrowphase, A = pair.a
        // > 0: a contact kept from the last step whose shapes are now this far apart
        // (speculative: the velocity solve lets them close the gap, no further).
        float separation = 0.0f;
        bool trigger = false;
        bool corner = false;   // corner_touch: no velocity response
    };
    std::vector<NarrowContact> narrowphase(const std::vector<detail::Pair>& pairs);
    // Pushes act on every candidate pair (`pairs`): a push can make a pair overlap that
    // did not at the narrowphase.
    void resolve(const std::vector<NarrowContact>& contacts, const std::vector<detail::Pair>& pairs, float dt);
    // resolve's position passes, from the bodies' positions after friction (`moves`, each with
    // its displacement since the narrowphase; `moved` marks the bodies moved).
    void relax_positions(const std::vector<NarrowContact>& found, const std::vector<detail::Pair>& push_pairs,
                         const std::vector<float>& inverse_mass, const std::vector<int>& level,
                         std::vector<detail::Moving>& moves, std::vector<std::uint8_t>& moved);
    // Appends the contacts fast circles stopped on to `touching`, and bullet hits to events.
    // `pairs` are the step's candidate pairs (broadphase_pairs).
    void sweeps(float dt, std::vector<Contact>& touching, const std::vector<detail::Pair>& pairs);
    // removed_some: an entity was destroyed during the step (contacts naming it are dropped).
    void emit_events(std::vector<Contact> touching, bool removed_some);

    // A single contact's velocity response (impulse with restitution and friction), used by
    // the sweeps; returns nothing, changes the velocities of dynamic bodies.
    void bounce(std::uint32_t a, std::uint32_t b, Vec2 normal);
};

}  // namespace jostle
