// jostle/world.h: the entity/world loop. Entities with one collider each, a fixed step that
// calls the collision module and resolves every overlap by pushing along the MTD, bullets
// and fast circles moved continuously, contact events, queries and a state hash.
// Depends on jostle/core, jostle/collision and (inside, never in this header) Box2D's
// b2DynamicTree, an index over every collider's fat bounds for region queries.
//
// ===================================== MANUAL =====================================
//
// ENTITIES
//   An entity is referred to by an EntityId {index, generation}. Destroying an entity makes
//   every copy of its id stale: get() returns nullptr, setters return false, destroy()
//   returns false. A slot is reused by a later create() with a new generation, so a stale
//   id never reaches the new entity. EntityId{} (generation 0) is the null id, never alive.
//   Each entity has a transform (position, angle), velocities, one Collider, a BodyKind,
//   mass and material, layer bits and user data (a number: never a pointer, so that it can
//   be hashed and replayed).
//
// COLLIDERS are shapes in the entity's frame: the entity's position is the origin and its
//   angle turns Obb, Polygon and Segment colliders and the offset of a Circle. Aabb and mask
//   colliders never turn (they are axis-aligned by definition); a mask collider's pixel (0,0)
//   sits at the entity's position plus its offset, rounded to the nearest whole pixel.
//
// BODY KINDS
//   static_body  never moves (its velocity field is ignored, contacts see zero); meets
//                everything that moves.
//   kinematic    moves by its velocity; pushes dynamic bodies, is never pushed.
//   dynamic      moves by velocity and gravity; pushed out of everything it overlaps.
//   bullet       a point moving along a segment each step (last to next position); hits the
//                first collider on its path, at any speed (a path that starts on a surface
//                and leaves it or runs along it does not hit that surface). Never pushed,
//                never pushes.
//   trigger      moves by its velocity; reports trigger_enter/exit; never pushed or pushing.
//                A fast circle's sweep passes through triggers but puts those it meets in
//                contact that step (trigger_enter, then trigger_exit the next step if it has
//                left): one crossed within a single step is still reported. Bullets never
//                meet triggers.
//   Pairs that are never tested: static-static, bullet-anything (bullets only cast),
//   trigger-trigger, and pairs filtered out by layer bits: A and B meet only when
//   (A.layer & B.collides_with) != 0 and (B.layer & A.collides_with) != 0.
//
// THE STEP, World::step(dt), in named phases:
//   integrate    velocities += gravity * gravity_scale * dt (dynamic); the contacts carried
//                from the last step take the approach out of those velocities (so resting
//                bodies do not sink, and boxes slide over tile seams); positions += v * dt
//                (dynamic, kinematic, trigger); angles += w * dt, wrapped to [-pi, pi].
//                A dynamic circle moving more than half its radius this step is "fast": it
//                is not moved here but swept in the sweeps phase.
//   broadphase   tight bounds of every moved collider (a fast circle's cover its motion too);
//                fat bounds (fattened) are re-made only when the bounds leave them; the
//                candidate pairs are every pair whose fat bounds overlap, at least one of them
//                moving, found all at once by a uniform grid over those bounds (faster than
//                one tree query per body), or by one tree query per mover when fewer than 1
//                in 16 colliders move (a tile map); a b2DynamicTree over the fat bounds also
//                answers World queries' and bullets' regions, catching up only when queried.
//                Sorted by (lower id, higher id).
//   narrowphase  collide(A, B) from the collision module for each candidate (A is the lower
//                id); mask pairs test bounds first, then pixels over the overlap, then the
//                integer mask MTD. A pair in contact last step that now misses (a rounding
//                gap, or a gap under 1 px) is kept as a speculative contact: the velocity
//                solve lets it close the gap in the next step, no further.
//   resolve      velocity: per contact, the approach speed along the normal is removed
//                (bounced back times the larger restitution when faster than
//                restitution_threshold) and friction (sqrt of the two coefficients) opposes
//                sliding, as impulses split by inverse mass, iterated velocity_passes times.
//                The tangential velocity friction removed is also taken back out of this
//                step's motion, so a body that friction stops does not slide on a step.
//                position: relaxation passes over the narrowphase's contacts, each pushing
//                along its MTD normal by the overlap still left along it (exact for the
//                translations the passes make, and never less than the MTD depth; a circle
//                against another circle or a corner is a pair of points, its normal turning
//                as they move; mask contacts are tested again at each visit): a dynamic body
//                against a static or kinematic one moves by the whole push; two dynamic
//                bodies split it by inverse mass. A contact no deeper than slop / 2 counts as
//                settled and is not pushed. Candidate pairs that pushes bring into each other
//                join the passes: all of them whenever the passes settle, those with an
//                immovable body before every shock pass. The passes stop once nothing is
//                deeper than slop / 2 and nothing joined; the second half order contacts from
//                the ground up and let the body nearer an immovable one stand still (shock
//                propagation), so resting stacks end within `slop`. A crowd that uses up its
//                passes unsettled leaves the rest to the next step; its contacts with
//                immovable bodies (and new overlaps with them) get one more pass, last, so
//                that its final pushes do not leave bodies in walls.
//   sweeps       bullets in id order: segment cast from the old to the new position against
//                everything they can hit (a bullet at rest casts nothing, so a stopped
//                bullet reports its hit once); the first hit (ties: the lower id) is a bullet_hit
//                event and the bullet then despawns, stops, or ricochets (mirror reflection,
//                continuing with the rest of its path from just off the surface, lifted by
//                `slop` so it does not start on it, up to max_sweep_hits per step).
//                Fast circles in id order: swept against every collider they can hit, they
//                stop at the time of first contact, take the contact's velocity response,
//                and continue with the rest of the step (up to max_sweep_hits contacts;
//                motion left after them is dropped, but a circle of inverse mass 0, which
//                resolution never moves, goes all the way, and goes on past a body it has
//                just hit instead of meeting it again where it stopped).
//   events       contact_end, contact_begin, trigger_exit, trigger_enter, each kind sorted by
//                (a, b); bullet_hit events come first, in the order they happened. The event
//                handler (if any) is called for each, in order, then events() holds them
//                until the next step.
//
// CONTACTS AND EVENTS
//   A pair is in contact in a step when the narrowphase reports a hit (touching counts), a
//   kept contact's gap is at most `slop` (so rounding does not make events flicker), or a
//   fast circle's sweep stopped on it (or, for a trigger, met it on the way). contact_begin: in contact now, not in the previous
//   step; contact_end: the reverse (normal, depth and point are the last ones seen). A body
//   that changes kind (set()) between trigger and not ends its old contacts and begins new
//   ones. A pair whose entity was destroyed is dropped without an end event. normal points
//   from a to b; for contacts a < b; for trigger events a is the trigger; for bullet_hit a
//   is the bullet. point is where the shapes meet (the middle of the overlap along the
//   normal; for masks the middle of the overlapping bounds). Shapes touching only corner to
//   corner (depth 0, a tied normal: a box sliding onto the next floor tile) are in contact
//   but get no velocity response.
//
// CHANGES DURING A STEP
//   The handler may create and destroy entities and change them. A created entity exists
//   at once (a valid id; queries see it) and takes part from the next step. A destroyed one
//   is gone at once; events already queued still carry its (now stale) id and its user data.
//   Calling step() from the handler is a programming error (asserted), and so is replacing or
//   destroying the world it is called from (to restart a level, set a flag in the handler and
//   replace the world after step() returns). A moved-from World may only be assigned to or
//   destroyed (any other use is asserted).
//
// DETERMINISM
//   No clocks, no unordered iteration, no uninitialised bytes: the same calls give the same
//   state, bit for bit, in every build. state_hash() covers every field that affects the
//   future: each live entity's state (in slot order), the id allocator, the contacts carried
//   to the next step, the RNG and the step count. Non-finite positions or shapes make an
//   entity collide with nothing (as in the collision module); it is still hashed.
//
// LIMITS
//   Resolution is translational: contacts change velocities, never angular velocity (the
//   game sets spin). Non-circle dynamic bodies are moved discretely: keep their motion per
//   step below half their smallest extent, or make them circles. A circle is swept along
//   its entity's linear motion: a circle collider offset from a spinning entity is not swept
//   for the spin. Pushes are not swept either: a small body crushed between a heavy mover
//   and a thin wall can be pushed through the wall when the mover's motion per step exceeds
//   the small body's radius. Mask pushes are whole pixels, and so is each body's share of
//   one. Coordinates as in the collision module (|x|, |y| <= 1e5 px).
// ==================================================================================
#pragma once

#include <compare>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "jostle/collision.h"
#include "jostle/core/rng.h"
#include "jostle/core/vec2.h"

namespace jostle {

struct EntityId {
    std::uint32_t index = 0;
    std::uint32_t generation = 0;  // 0: the null id, never alive

    constexpr bool is_null() const { return generation == 0; }
    friend constexpr bool operator==(EntityId, EntityId) = default;
    friend constexpr auto operator<=>(EntityId, EntityId) = default;  // by index, then generation
};

enum class BodyKind : std::uint8_t { static_body, kinematic, dynamic, bullet, trigger };
const char* name_of(BodyKind k);  // "static", "kinematic", ...

// What a bullet does after it hits something (the game chooses per bullet).
enum class BulletResponse : std::uint8_t { despawn, stop, ricochet };

// A shape in the entity's frame (see COLLIDERS). A mask collider owns a share of its mask,
// so the mask lives as long as any collider using it.
class Collider {
public:
    Collider() = default;  // a point at the entity's position
    static Collider aabb(Vec2 half_size, Vec2 offset = {});
    static Collider box(Vec2 half_size, Vec2 offset = {}, float angle = 0.0f);  // an Obb
    static Collider circle(float radius, Vec2 offset = {});
    static Collider polygon(const Polygon& poly);  // points relative to the entity
    static Collider segment(Vec2 a, Vec2 b);
    // offset: where the mask's pixel (0, 0) sits relative to the entity, in whole pixels.
    // Default: the mask centred on the entity.
    static Collider mask(std::shared_ptr<const Mask> mask);
    static Collider mask(std::shared_ptr<const Mask> mask, int offset_x, int offset_y);

    ShapeKind kind() const { return kind_of(shape_); }
    const Shape& local_shape() const { return shape_; }  // a mask's x, y is its offset
    const std::shared_ptr<const Mask>& mask_ptr() const { return mask_; }
    // The collider placed at a transform: the shape the collision module sees.
    Shape placed(Vec2 position, float angle) const;
    // placed() in two halves, for placing a collider at many positions with one angle (the
    // world does this each step): turned(angle) is the collider turned about the entity's
    // origin, once per angle (the sines and cosines); at(turned(a), p) is placed(p, a), bit
    // for bit.
    Shape turned(float angle) const;
    // out = turned(angle), reusing out's storage (as place() below).
    void turn_into(float angle, Shape& out) const;
    static Shape at(const Shape& turned, Vec2 position);
    // out = at(turned, position), reusing out's storage (a polygon's vertices are written in
    // place rather than copied three times through temporaries).
    static void place(const Shape& turned, Vec2 position, Shape& out);

private:
    Shape shape_ = Circle{};
    std::shared_ptr<const Mask> mask_;
};

// How to make an entity; also the entity's current state, as get() returns it. The zero
// value is usable: a static point at the origin.
struct EntityDesc {
    BodyKind kind = BodyKind::static_body;
    Vec2 position;
    float angle = 0.0f;  // radians
    Vec2 velocity;       // px/s
    float angular_velocity = 0.0f;  // rad/s
    Collider collider;
    float inverse_mass = 1.0f;  // dynamic bodies; 0 makes a dynamic body immovable by pushes
    float restitution = 0.0f;   // 0 no bounce .. 1 elastic
    float friction = 0.2f;      // Coulomb coefficient
    float gravity_scale = 1.0f; // dynamic bodies
    std::uint32_t layer = 1;                 // the layers this entity is on
    std::uint32_t collides_with = 0xffffffffu;  // the layers it meets
    BulletResponse on_hit = BulletResponse::despawn;  // bullets
    EntityId ignore;            // never meets this entity (a bullet's shooter, say)
    std::uint64_t user_data = 0;
};

enum class EventType : std::uint8_t { contact_begin, contact_end, trigger_enter, trigger_exit, bullet_hit };
const char* name_of(EventType t);  // "contact_begin", ...

struct Event {
    EventType type = EventType::contact_begin;
    EntityId a;  // contacts: the lower id; trigger events: the trigger; bullet_hit: the bullet
    EntityId b;
    std::uint64_t a_user_data = 0;
    std::uint64_t b_user_data = 0;
    Vec2 point;     // where they meet
    Vec2 normal;    // unit, from a toward b (bullet_hit: b's outward surface normal)
    float depth = 0.0f;     // contacts and triggers: overlap depth (0 when touching)
    float fraction = 0.0f;  // bullet_hit: fraction of the step's path travelled at the hit
};

// A contact kept for the next step and for debug drawing.
struct Contact {
    EntityId a;  // lower id
    EntityId b;
    Vec2 point;
    Vec2 normal;  // from a toward b
    float depth = 0.0f;  // at the narrowphase, before resolution
    bool trigger = false;       // one of them is a trigger: events are trigger_enter/exit
    bool trigger_is_b = false;  // which one (a otherwise), as it was when they met
    bool corner = false;        // touching corner to corner: the normal is a tie, no response
};

// What the last step moved continuously, for the debug overlay.
struct SweptPath {
    EntityId id;
    Vec2 from;
    Vec2 to;
    float radius = 0.0f;  // 0 for bullets
};

struct RayHit {
    EntityId id;
    float t = 0.0f;  // fraction of from->to
    Vec2 point;
    Vec2 normal;
};

struct WorldDesc {
    Vec2 gravity;                        // px/s^2 (y down: {0, 980} falls)
    std::uint64_t seed = 0;              // the world's RNG
    int velocity_passes = 8;
    int relaxation_passes = 16;          // position passes at most
    float slop = 0.01f;                  // px: penetration left in a resting contact
    float restitution_threshold = 30.0f; // px/s: slower approaches do not bounce
    int max_sweep_hits = 4;              // per bullet or fast circle per step
};

// Turns variable frame time into whole fixed steps, for callers with a clock (replays and
// tests call World::step directly).
class FixedStepper {
public:
    explicit FixedStepper(float step_seconds = 1.0f / 60.0f, int max_steps_per_frame = 8)
        : step_(step_seconds), max_steps_(max_steps_per_frame) {}
    // Adds elapsed time and returns how many steps to run now (at most max_steps_per_frame;
    // time beyond that is dropped, so a long stall does not snowball).
    int advance(double elapsed_seconds);
    float step_seconds() const { return step_; }
    // Fraction of a step left in the accumulator, in [0, 1): for drawing between steps.
    float alpha() const { return static_cast<float>(accumulator_ / step_); }

private:
    float step_;
    int max_steps_;
    double accumulator_ = 0.0;
};

class World {
public:
    explicit World(const WorldDesc& desc = {});
    ~World();
    World(World&&) noexcept;
    World& operator=(World&&) noexcept;
    World(const World&) = delete;
    World& operator=(const World&) = delete;

    // Entities. create() asserts on a programming error (a negative radius, say, is not
    // one: such a collider simply hits nothing).
    EntityId create(const EntityDesc& desc);
    bool destroy(EntityId id);  // false if stale
    bool alive(EntityId id) const;
    const EntityDesc* get(EntityId id) const;  // nullptr if stale
    Shape shape_of(EntityId id) const;         // the placed collider; a miss-shape if stale
    std::size_t entity_count() const;
    std::vector<EntityId> entities() const;    // live ids in slot order

    // Changes; each returns false for a stale id.
    bool set_position(EntityId id, Vec2 position);
    bool set_angle(EntityId id, float angle);
    bool set_velocity(EntityId id, Vec2 velocity);
    bool set_angular_velocity(EntityId id, float angular_velocity);
    bool set_collider(EntityId id, const Collider& collider);
    bool set_user_data(EntityId id, std::uint64_t user_data);
    // Anything else: replace the whole state (kind, mass, material, layers, ...).
    bool set(EntityId id, const EntityDesc& desc);

    // One fixed step of dt seconds (dt > 0 and finite, asserted).
    void step(float dt);
    std::span<const Event> events() const;       // the last step's, in order
    std::span<const Contact> contacts() const;   // pairs in contact after the last step
    std::span<const SweptPath> swept_paths() const;
    // The broadphase's fattened bounds of an entity (for the debug overlay); nullopt when the
    // id is stale or its collider meets nothing (non-finite).
    std::optional<Aabb> broadphase_bounds(EntityId id) const;
    using EventHandler = std::function<void(World&, const Event&)>;
    void set_event_handler(EventHandler handler);

    // Queries, answered from current positions; results in id order. `layers` filters by
    // the entities' layer bits.
    std::vector<EntityId> query_aabb(const Aabb& box, std::uint32_t layers = 0xffffffffu) const;
    std::vector<EntityId> query_point(Vec2 p, std::uint32_t layers = 0xffffffffu) const;
    // First collider along from->to (ties: the lower id), ignoring `ignore`.
    std::optional<RayHit> cast_segment(Vec2 from, Vec2 to, std::uint32_t layers = 0xffffffffu,
                                       EntityId ignore = {}) const;

    std::uint64_t state_hash() const;
    std::uint64_t step_count() const;
    Rng& rng();
    const WorldDesc& desc() const;

    struct Impl;  // the implementation's state (engine/world/src/internal.h)

private:
    Impl& impl() const;  // asserts the World was not moved from
    std::unique_ptr<Impl> impl_;
};

}  // namespace jostle
