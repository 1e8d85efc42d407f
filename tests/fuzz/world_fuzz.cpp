// tests/fuzz/world_fuzz.cpp: fuzzes the World API (jostle/world.h) with a program of calls
// read from the input bytes: creating entities of every kind and collider (masks included),
// destroying them, changing them, stepping, and asking queries, with an event handler that
// changes the world during the step on some inputs. Values are mostly small grid numbers (so
// bodies touch, stack and coincide), sometimes special floats (NaN, infinities, huge, -0).
//
// Every input, whatever its values:
// - no crash, assertion or sanitizer report;
// - the same program run twice gives the same state hash after every step (DETERMINISM);
// - contacts() are sorted by (a, b), a < b, both alive; a destroyed entity's id is stale
//   everywhere and no id is handed out twice; the broadphase's bounds cover every collider;
// - within the LIMITS, query_aabb, query_point and cast_segment agree with the collision
//   module asked of every entity's placed collider (the broadphase misses nothing, adds nothing).
// Without a handler, also:
// - every contact is a pair that may meet (BODY KINDS, layer bits, ignore);
// - the events are the difference between the contacts before and after the step (CONTACTS
//   AND EVENTS), name live entities (but despawned bullets) and carry their user data;
// - static bodies stay put; kinematic bodies, triggers and dynamic bodies of inverse mass 0
//   move by their velocity (and gravity) alone, and nothing else changes their velocity.
// Inputs whose every value is finite and ordinary (no special value was read): every live
// entity's position and velocity stay finite, and every contact has a unit normal and a finite
// depth >= 0.
#include <algorithm>
#include <array>
#include <bit>
#include <cfloat>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "fuzz_support.h"
#include "jostle/world.h"

namespace jostle {
namespace {

using fuzz::fuzz_fail;

constexpr std::size_t kMaxEntities = 48;
constexpr int kMaxSteps = 48;
constexpr int kMaxCalls = 400;

class Reader {
public:
    // Half the programs (by their first byte) read only ordinary values, so that the checks
    // that need them run on as many programs as the rest.
    Reader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size), specials_(size > 0 && data[0] >= 0x80) {}
    bool done() const { return at_ >= size_; }
    std::uint8_t byte() { return at_ < size_ ? data_[at_++] : 0; }
    // Mostly half steps in [-60, 60) (bodies a few px across touch, stack and coincide);
    // sometimes a special value, which marks the program as not ordinary.
    float number() {
        static constexpr std::array<float, 16> kSpecial = {
            std::numeric_limits<float>::quiet_NaN(), INFINITY, -INFINITY, FLT_MAX, -FLT_MAX, 1e30f, -1e30f,
            std::numeric_limits<float>::denorm_min(), -0.0f, 1e5f, -1e5f, 1e6f, 1e-30f, 3e38f, 16777216.0f, 1e-7f};
        return value(2.0f, kSpecial);
    }
    // A coordinate of a collider: mostly quarter steps in [-30, 30), sometimes a special
    // value, but never a large finite one. (A mask deep inside a shape 1e5 px across is a legal
    // query, but its MTD search takes about 0.2 us a pixel of depth, 20 ms there: the runs
    // would crawl.)
    float extent() {
        static constexpr std::array<float, 16> kSpecial = {
            std::numeric_limits<float>::quiet_NaN(), INFINITY, -INFINITY, FLT_MAX, -FLT_MAX, 1e30f, -1e30f,
            std::numeric_limits<float>::denorm_min(), -0.0f, 0.0f, 1e-30f, -1e-30f, 1e-7f, -1e-7f, 3e38f, 1e20f};
        return value(4.0f, kSpecial);
    }
    // A size: mostly 0 .. 15 px in eighth steps (0 included: degenerate shapes).
    float size() {
        const float v = extent();
        return std::isfinite(v) && std::fabs(v) <= 30.0f ? std::fabs(v) / 2.0f : v;
    }
    bool special() const { return special_; }

private:
    // (tag - 120) / divisor for most tags; the top 16 pick a special value when this program
    // may read them.
    float value(float divisor, const std::array<float, 16>& special) {
        const std::uint8_t tag = byte();
        if (tag < 0xf0 || !specials_) return static_cast<float>(static_cast<int>(tag) - 120) / divisor;
        special_ = true;
        return special[tag - 0xf0];
    }

    const std::uint8_t* data_;
    std::size_t size_;
    std::size_t at_ = 0;
    bool specials_;         // this program may read special values
    bool special_ = false;  // it has read one
};

Collider read_collider(Reader& in) {
    switch (in.byte() % 7) {
        case 0: return Collider::aabb({in.size(), in.size()}, {in.extent() / 4.0f, in.extent() / 4.0f});
        case 1: return Collider::box({in.size(), in.size()}, {in.extent() / 4.0f, in.extent() / 4.0f}, in.number() / 8.0f);
        case 2: return Collider::circle(in.size(), {in.extent() / 4.0f, in.extent() / 4.0f});
        case 3: return Collider::segment({in.extent(), in.extent()}, {in.extent(), in.extent()});
        case 4: {
            std::vector<Vec2> points(3 + in.byte() % 6);
            for (Vec2& p : points) p = {in.extent(), in.extent()};
            if (const std::optional<Polygon> poly = make_polygon(points)) return Collider::polygon(*poly);
            return Collider::circle(in.size());
        }
        case 5: {
            const int w = in.byte() % 20, h = in.byte() % 20;
            auto mask = std::make_shared<Mask>(w, h);
            for (int y = 0; y < h; ++y) {
                const std::uint8_t row = in.byte();
                for (int x = 0; x < w; ++x) mask->set(x, y, ((row >> (x % 8)) & 1) != 0 || (row > 0xc0 && x % 2 == 0));
            }
            return Collider::mask(std::move(mask), static_cast<int>(in.byte() % 9) - 4, static_cast<int>(in.byte() % 9) - 4);
        }
        default: return Collider{};  // a point
    }
}

EntityDesc read_desc(Reader& in) {
    EntityDesc d;
    d.kind = static_cast<BodyKind>(in.byte() % 5);
    d.position = {in.number(), in.number()};
    d.angle = in.number() / 8.0f;
    d.velocity = {in.number() * 16.0f, in.number() * 16.0f};
    d.angular_velocity = in.number() / 4.0f;
    d.collider = read_collider(in);
    const std::uint8_t material = in.byte();
    d.inverse_mass = material % 4 == 0 ? 0.0f : static_cast<float>(material % 16) / 4.0f;
    d.restitution = static_cast<float>((material >> 4) % 5) / 4.0f;
    d.friction = static_cast<float>(in.byte() % 5) / 4.0f;
    d.gravity_scale = static_cast<float>(in.byte() % 3);
    const std::uint8_t bits = in.byte();
    d.layer = 1u + (bits & 3u);
    d.collides_with = bits & 4 ? 1u : 0xffffffffu;
    d.on_hit = static_cast<BulletResponse>((bits >> 3) % 3);
    d.user_data = bits;
    return d;
}

std::set<std::pair<EntityId, EntityId>> pairs_of(std::span<const Contact> contacts) {
    std::set<std::pair<EntityId, EntityId>> out;
    for (const Contact& c : contacts) out.insert({c.a, c.b});
    return out;
}

std::string id_text(EntityId id) { return std::to_string(id.index) + "/" + std::to_string(id.generation); }

void check_contacts(const World& w, bool ordinary) {
    const std::span<const Contact> contacts = w.contacts();
    for (std::size_t k = 0; k < contacts.size(); ++k) {
        const Contact& c = contacts[k];
        if (!(c.a < c.b)) fuzz_fail("contact " + id_text(c.a) + " - " + id_text(c.b) + " is not in (lower, higher) order");
        if (k > 0 && !(std::pair{contacts[k - 1].a, contacts[k - 1].b} < std::pair{c.a, c.b})) {
            fuzz_fail("contacts are not sorted by (a, b)");
        }
        if (!w.alive(c.a) || !w.alive(c.b)) fuzz_fail("a contact names a dead entity: " + id_text(c.a) + " - " + id_text(c.b));
        if (ordinary) {
            if (!(std::fabs(length(c.normal) - 1.0f) < 1e-3f)) {
                fuzz_fail("contact " + id_text(c.a) + " - " + id_text(c.b) + " has a normal of length " +
                          std::to_string(length(c.normal)));
            }
            if (!(c.depth >= 0.0f && std::isfinite(c.depth))) fuzz_fail("contact depth " + std::to_string(c.depth));
        }
    }
}

// Text for the failure messages.
std::string box_text(const Aabb& b) {
    std::ostringstream out;
    out << "(" << b.min.x << ", " << b.min.y << ") - (" << b.max.x << ", " << b.max.y << ")";
    return out.str();
}

std::string ids_text(const World& w, const std::vector<EntityId>& ids) {
    std::ostringstream out;
    out << "[";
    for (const EntityId id : ids) {
        const EntityDesc* e = w.get(id);
        if (e == nullptr) {
            out << " " << id_text(id) << " (stale)";
            continue;
        }
        const Aabb b = bounds(w.shape_of(id));
        out << " " << id_text(id) << " " << name_of(e->kind) << " " << name_of(e->collider.kind()) << " at ("
            << e->position.x << ", " << e->position.y << ") bounds " << box_text(b);
    }
    out << " ]";
    return out.str();
}

struct Query {
    Vec2 p, q;
    std::uint32_t layers = 0;
    EntityId ignore;
};

Query read_query(Reader& in) {
    Query query;
    query.p = {in.number(), in.number()};
    query.q = {in.number(), in.number()};
    const std::uint8_t bits = in.byte();
    query.layers = bits % 2 ? 0xffffffffu : 1u + (bits >> 1) % 4;
    if (bits & 8) query.ignore = EntityId{(bits >> 4) % 8u, 1};
    return query;
}

// Within the LIMITS (|x|, |y| <= kMaxCoordinate) the collision module is exact; beyond them
// its answers are defined but not exact, so there the query may answer either way.
bool within_limits(const Aabb& b) {
    return std::fabs(b.min.x) <= kMaxCoordinate && std::fabs(b.min.y) <= kMaxCoordinate &&
           std::fabs(b.max.x) <= kMaxCoordinate && std::fabs(b.max.y) <= kMaxCoordinate;
}

// The queries against the collision module asked of every live entity, in id order.
void check_queries(const World& w, const Query& query) {
    const Vec2 p = query.p, q = query.q;
    const Aabb box{min(p, q), max(p, q)};
    if (!within_limits(box)) return;
    const std::uint32_t layers = query.layers;
    const EntityId ignore = query.ignore;
    std::vector<EntityId> want_box, want_point;
    std::optional<RayHit> want_ray;
    for (const EntityId id : w.entities()) {
        const EntityDesc* e = w.get(id);
        const Shape s = w.shape_of(id);
        if ((e->layer & layers) == 0 || !within_limits(bounds(s))) continue;
        if (overlaps(s, Shape{box})) want_box.push_back(id);
        if (overlaps(s, Shape{Segment{p, p}})) want_point.push_back(id);
        if (id == ignore) continue;
        const CastHit h = cast(p, q, s);
        if (h.hit && (!want_ray || h.t < want_ray->t)) want_ray = RayHit{id, h.t, h.point, h.normal};
    }
    // Entities beyond the LIMITS (or not finite) may be in the answers or not.
    const auto beyond = [&](EntityId id) { return !within_limits(bounds(w.shape_of(id))); };
    const auto without_beyond = [&](std::vector<EntityId> ids) {
        std::erase_if(ids, beyond);
        return ids;
    };
    if (const std::vector<EntityId> got = w.query_aabb(box, layers); without_beyond(got) != want_box) {
        fuzz_fail("query_aabb" + box_text(box) + " gives " + ids_text(w, got) + ", collide() " + ids_text(w, want_box));
    }
    if (const std::vector<EntityId> got = w.query_point(p, layers); without_beyond(got) != want_point) {
        fuzz_fail("query_point gives " + ids_text(w, got) + ", collide() " + ids_text(w, want_point));
    }
    const std::optional<RayHit> ray = w.cast_segment(p, q, layers, ignore);
    if (ray && beyond(ray->id)) return;
    if (ray.has_value() != want_ray.has_value() || (ray && (ray->id != want_ray->id || ray->t != want_ray->t))) {
        fuzz_fail("cast_segment gives " + (ray ? ids_text(w, {ray->id}) : std::string("none")) + ", cast() " +
                  (want_ray ? ids_text(w, {want_ray->id}) : std::string("none")));
    }
}

// Every contact is a pair the MANUAL lets meet (BODY KINDS: never static-static, bullet-
// anything or trigger-trigger; layer bits both ways; neither ignoring the other).
void check_contact_pairs(const World& w) {
    for (const Contact& c : w.contacts()) {
        const EntityDesc& a = *w.get(c.a);
        const EntityDesc& b = *w.get(c.b);
        const auto is = [&](BodyKind k) { return a.kind == k || b.kind == k; };
        const bool both_static = a.kind == BodyKind::static_body && b.kind == BodyKind::static_body;
        const bool both_triggers = a.kind == BodyKind::trigger && b.kind == BodyKind::trigger;
        const bool layers = (a.layer & b.collides_with) != 0 && (b.layer & a.collides_with) != 0;
        const bool ignored = a.ignore == c.b || b.ignore == c.a;
        if (both_static || both_triggers || is(BodyKind::bullet) || !layers || ignored) {
            fuzz_fail("contact " + ids_text(w, {c.a, c.b}) + " is a pair that never meets");
        }
        if (c.trigger != is(BodyKind::trigger)) fuzz_fail("contact " + ids_text(w, {c.a, c.b}) + " has the wrong trigger flag");
    }
}

// The broadphase's fat bounds of every entity cover its collider as placed now (a stale proxy
// is what queries, bullets and sweeps would miss it by).
void check_proxies(const World& w) {
    for (const EntityId id : w.entities()) {
        const Aabb tight = bounds(w.shape_of(id));
        if (!within_limits(tight) || !(tight.min.x <= tight.max.x && tight.min.y <= tight.max.y)) continue;
        const std::optional<Aabb> fat = w.broadphase_bounds(id);
        if (!fat || fat->min.x > tight.min.x || fat->min.y > tight.min.y || fat->max.x < tight.max.x ||
            fat->max.y < tight.max.y) {
            fuzz_fail("the broadphase's bounds of " + ids_text(w, {id}) + " are " + (fat ? box_text(*fat) : "none"));
        }
    }
}

// The events of a step without a handler, against the contacts before and after it.
void check_events(const World& w, const std::vector<Contact>& before) {
    const auto after = pairs_of(w.contacts());
    std::set<std::pair<EntityId, EntityId>> began, ended;
    for (const Event& e : w.events()) {
        if (e.type == EventType::bullet_hit) {
            if (!w.alive(e.b)) fuzz_fail("bullet_hit names a dead target " + id_text(e.b));
            if (!(e.fraction >= 0.0f && e.fraction <= 1.0f)) fuzz_fail("bullet_hit at fraction " + std::to_string(e.fraction));
            if (e.b_user_data != w.get(e.b)->user_data) fuzz_fail("bullet_hit carries the wrong user data");
            continue;
        }
        if (!w.alive(e.a) || !w.alive(e.b)) fuzz_fail(std::string(name_of(e.type)) + " names a dead entity");
        if (e.a_user_data != w.get(e.a)->user_data || e.b_user_data != w.get(e.b)->user_data) {
            fuzz_fail(std::string(name_of(e.type)) + " carries the wrong user data");
        }
        const auto pair = std::minmax(e.a, e.b);
        const bool begin = e.type == EventType::contact_begin || e.type == EventType::trigger_enter;
        (begin ? began : ended).insert(pair);
        if (begin && !after.contains(pair)) fuzz_fail(std::string(name_of(e.type)) + " for a pair not in contact after the step");
    }
    const auto was = pairs_of(before);
    for (const auto& pair : after) {
        if (!was.contains(pair) && !began.contains(pair)) {
            fuzz_fail("pair " + id_text(pair.first) + " - " + id_text(pair.second) + " came into contact without an event");
        }
    }
    for (const auto& pair : was) {
        if (w.alive(pair.first) && w.alive(pair.second) && !after.contains(pair) && !ended.contains(pair)) {
            fuzz_fail("pair " + id_text(pair.first) + " - " + id_text(pair.second) + " left contact without an event");
        }
    }
    for (const auto& pair : ended) {
        if (after.contains(pair) && !began.contains(pair)) fuzz_fail("an end event for a pair still in contact");
    }
}

// What a step may do to the bodies resolution never moves: a static body stays where it is;
// a kinematic body, a trigger or a dynamic body of inverse mass 0 moves by its velocity
// (position + dt * velocity, the step's own expression; the last after gravity, and swept in
// pieces when it is a fast circle), and nothing else changes their velocity. (Without a
// handler, which may change them.)
struct Before {
    EntityId id;
    EntityDesc desc;
};

void check_unpushed(const World& w, const std::vector<Before>& before, float dt) {
    for (const Before& b : before) {
        const EntityDesc* e = w.get(b.id);
        if (e == nullptr) continue;
        const BodyKind kind = b.desc.kind;
        // A dynamic body of inverse mass 0 is immovable too: gravity alone changes its velocity.
        const bool immovable_dynamic = kind == BodyKind::dynamic && !(b.desc.inverse_mass > 0.0f);
        if (kind != BodyKind::static_body && kind != BodyKind::kinematic && kind != BodyKind::trigger && !immovable_dynamic) {
            continue;
        }
        const Vec2 velocity =
            immovable_dynamic ? b.desc.velocity + (b.desc.gravity_scale * dt) * w.desc().gravity : b.desc.velocity;
        const Vec2 want = kind == BodyKind::static_body ? b.desc.position : b.desc.position + dt * velocity;
        const auto same = [](Vec2 x, Vec2 y) {
            return std::bit_cast<std::uint64_t>(x) == std::bit_cast<std::uint64_t>(y);
        };
        // (A fast circle's sweep moves it in pieces, stopping at each contact: the sum of its
        // pieces is its motion up to rounding.)
        const auto near = [&](Vec2 x, Vec2 y) {
            return same(x, y) || length(x - y) <= 1e-5f * (std::fabs(y.x) + std::fabs(y.y)) + 1e-6f;
        };
        const bool swept = immovable_dynamic && e->collider.kind() == ShapeKind::circle;
        if (!(swept ? near(e->position, want) : same(e->position, want)) || !same(e->velocity, velocity)) {
            std::ostringstream out;
            out << name_of(kind) << " " << id_text(b.id) << " went from (" << b.desc.position.x << ", " << b.desc.position.y
                << ") at velocity (" << b.desc.velocity.x << ", " << b.desc.velocity.y << ") to (" << e->position.x << ", "
                << e->position.y << ") at (" << e->velocity.x << ", " << e->velocity.y << "); resolution must not move it";
            fuzz_fail(out.str());
        }
    }
}

void check_finite(const World& w) {
    for (const EntityId id : w.entities()) {
        const EntityDesc* e = w.get(id);
        if (!is_finite(e->position) || !is_finite(e->velocity) || !std::isfinite(e->angle)) {
            fuzz_fail("entity " + id_text(id) + " (" + name_of(e->kind) + ") went non-finite from ordinary input");
        }
    }
}

// Runs the program; returns the state hash after each step.
std::vector<std::uint64_t> run(const std::uint8_t* data, std::size_t size, bool check) {
    Reader in(data, size);
    const std::uint8_t setup = in.byte();
    World w(WorldDesc{.gravity = {0.0f, setup % 2 ? 980.0f : 0.0f},
                      .seed = setup,
                      .velocity_passes = 1 + (setup >> 1) % 8,
                      .relaxation_passes = 1 + (setup >> 4) % 16,
                      .max_sweep_hits = 1 + (setup >> 3) % 4});
    const bool handler = in.byte() % 4 == 0;
    int created_by_handler = 0;
    if (handler) {
        // A game's handler: bullets that hit are destroyed, a trigger entered spawns a body
        // (a few at most), the first body of a contact is sometimes removed.
        w.set_event_handler([&created_by_handler](World& world, const Event& e) {
            if (e.type == EventType::bullet_hit) world.destroy(e.a);
            if (e.type == EventType::trigger_enter && created_by_handler < 4) {
                ++created_by_handler;
                world.create(EntityDesc{.kind = BodyKind::dynamic, .position = e.point, .collider = Collider::circle(2.0f)});
            }
            if (e.type == EventType::contact_begin && e.a_user_data % 7 == 3) world.destroy(e.a);
        });
    }
    std::vector<EntityId> ids;
    std::vector<std::uint64_t> hashes;
    const auto pick = [&]() { return ids.empty() ? EntityId{} : ids[in.byte() % ids.size()]; };
    for (int call = 0; call < kMaxCalls && !in.done() && static_cast<int>(hashes.size()) < kMaxSteps; ++call) {
        switch (in.byte() % 10) {
            case 0:
            case 1:
                if (w.entity_count() < kMaxEntities) {
                    EntityDesc d = read_desc(in);
                    if (d.user_data & 0x40) d.ignore = pick();
                    const EntityId id = w.create(d);
                    // A reused slot has a new generation: no id is ever handed out twice.
                    if (check && std::find(ids.begin(), ids.end(), id) != ids.end()) fuzz_fail("id " + id_text(id) + " handed out twice");
                    ids.push_back(id);
                }
                break;
            case 2: {
                // A crowd: a row of equal bodies a few px apart (they overlap, stack, jam).
                EntityDesc d = read_desc(in);
                const float gap = in.size();
                for (int k = 0; k < 6 && w.entity_count() < kMaxEntities; ++k) {
                    ids.push_back(w.create(d));
                    d.position.x += gap;
                }
                break;
            }
            case 3: {
                // A destroyed entity's id is stale everywhere (ENTITIES).
                const EntityId id = pick();
                if (w.destroy(id) && check &&
                    (w.alive(id) || w.get(id) != nullptr || w.destroy(id) || w.set_position(id, {}) || w.set(id, {}))) {
                    fuzz_fail("a destroyed entity's id " + id_text(id) + " is not stale");
                }
                break;
            }
            case 4: {
                const EntityId id = pick();
                switch (in.byte() % 5) {
                    case 0: w.set_position(id, {in.number(), in.number()}); break;
                    case 1: w.set_angle(id, in.number() / 8.0f); break;
                    case 2: w.set_velocity(id, {in.number() * 16.0f, in.number() * 16.0f}); break;
                    case 3: w.set_angular_velocity(id, in.number() / 4.0f); break;
                    default: w.set_user_data(id, in.byte()); break;
                }
                break;
            }
            case 5: w.set_collider(pick(), read_collider(in)); break;
            case 6: w.set(pick(), read_desc(in)); break;
            case 7: {
                const Query query = read_query(in);
                if (check) {
                    check_proxies(w);
                    check_queries(w, query);
                }
                break;
            }
            default: {
                static constexpr float kDt[] = {1.0f / 60.0f, 1.0f / 60.0f, 1.0f / 120.0f, 1.0f / 30.0f, 0.1f, 1e-4f};
                const float dt = kDt[in.byte() % std::size(kDt)];
                const std::vector<Contact> before(w.contacts().begin(), w.contacts().end());
                std::vector<Before> bodies;
                if (check) {
                    for (const EntityId id : w.entities()) bodies.push_back({id, *w.get(id)});
                    if (bodies.size() != w.entity_count()) fuzz_fail("entities() and entity_count() disagree");
                }
                w.step(dt);
                hashes.push_back(w.state_hash());
                if (check) {
                    check_proxies(w);
                    check_contacts(w, !in.special());
                    if (!handler) {
                        check_contact_pairs(w);
                        check_events(w, before);
                        check_unpushed(w, bodies, dt);
                    }
                    if (!in.special()) check_finite(w);
                }
            }
        }
    }
    return hashes;
}

}  // namespace
}  // namespace jostle

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::vector<std::uint64_t> first = jostle::run(data, size, true);
    const std::vector<std::uint64_t> second = jostle::run(data, size, false);
    if (first != second) jostle::fuzz::fuzz_fail("the same calls gave different state hashes");
    return 0;
}
