// World: creating, finding, changing and destroying entities; the fixed-step driver.
// The step itself is in step.cpp and continuous.cpp.
#include <algorithm>
#include <bit>
#include <cmath>

#include "internal.h"
#include "jostle/core/error.h"
#include "jostle/core/hash.h"

namespace jostle {

namespace {

std::uint64_t fingerprint(const Collider& c) {
    const Mask* m = c.mask_ptr().get();
    if (m == nullptr) return 0;
    Hasher h;
    h.u32(static_cast<std::uint32_t>(m->width()));
    h.u32(static_cast<std::uint32_t>(m->height()));
    for (int y = 0; y < m->height(); ++y) {
        h.bytes(m->row(y), static_cast<std::size_t>(m->words_per_row()) * sizeof(std::uint64_t));
    }
    return h.value();
}

}  // namespace

// ---------------------------------------------------------------------------------------
// Impl helpers
// ---------------------------------------------------------------------------------------

detail::Slot* World::Impl::find(EntityId id) {
    if (id.generation == 0 || id.index >= slots.size()) return nullptr;
    detail::Slot& s = slots[id.index];
    return (s.alive && s.generation == id.generation) ? &s : nullptr;
}

const detail::Slot* World::Impl::find(EntityId id) const {
    return const_cast<World::Impl*>(this)->find(id);
}

namespace {
// Whether the slot's turned collider is its collider at the body's angle. The angle's bits,
// not its value: a turned collider is only ever reused for exactly the angle it was turned
// by (and never for NaN).
bool turned_current(const detail::Slot& s) {
    return s.turned_valid && std::bit_cast<std::uint32_t>(s.turned_angle) == std::bit_cast<std::uint32_t>(s.body.angle);
}
}  // namespace

Shape World::Impl::placed(std::uint32_t index) const { return placed_at(index, slots[index].body.position); }

Shape World::Impl::placed_at(std::uint32_t index, Vec2 position) const {
    const detail::Slot& s = slots[index];
    return turned_current(s) ? Collider::at(s.turned, position) : s.body.collider.placed(position, s.body.angle);
}

void World::Impl::place_into(std::uint32_t index, Vec2 position, Shape& out) const {
    const detail::Slot& s = slots[index];
    if (turned_current(s)) {
        Collider::place(s.turned, position, out);
    } else {
        out = s.body.collider.placed(position, s.body.angle);
    }
}

void World::Impl::turn(std::uint32_t index) {
    detail::Slot& s = slots[index];
    s.body.collider.turn_into(s.body.angle, s.turned);
    s.turned_angle = s.body.angle;
    s.turned_valid = std::isfinite(s.body.angle);
    placements[index].valid = false;  // the collider may have changed
}

bool World::Impl::placement_current(std::uint32_t index) const {
    const auto same = [](float x, float y) { return std::bit_cast<std::uint32_t>(x) == std::bit_cast<std::uint32_t>(y); };
    const EntityDesc& b = slots[index].body;
    const detail::Placement& p = placements[index];
    return p.valid && same(p.position.x, b.position.x) && same(p.position.y, b.position.y) && same(p.angle, b.angle);
}

const detail::Placement& World::Impl::placement(std::uint32_t index) {
    detail::Placement& p = placements[index];
    if (!placement_current(index)) {
        const detail::Slot& s = slots[index];
        const EntityDesc& b = s.body;
        if (turned_current(s)) {
            Collider::place(s.turned, b.position, p.shape);  // placed(index), built in place
        } else {
            p.shape = b.collider.placed(b.position, b.angle);
        }
        p.box = bounds(p.shape);
        p.position = b.position;
        p.angle = b.angle;
        p.valid = true;
    }
    return p;
}

void World::Impl::sync_proxy(std::uint32_t index, Vec2 displacement, Vec2 sweep) {
    detail::Slot& s = slots[index];
    Aabb tight = placement(index).box;
    // (Only bounds that are usable themselves: a shape with inverted bounds, such as a circle
    // of negative radius, meets nothing, and its swept union must not give it a proxy.)
    if ((sweep.x != 0.0f || sweep.y != 0.0f) && detail::Broadphase::usable(tight)) {
        tight = {min(tight.min, tight.min + sweep), max(tight.max, tight.max + sweep)};
    }
    const bool usable = s.alive && detail::Broadphase::usable(tight);
    if (!usable) {
        if (s.proxy < 0) return;
        broadphase.destroy(s.proxy);
        s.proxy = -1;
    } else if (s.proxy < 0) {
        s.proxy = broadphase.create(tight, index);
    } else if (!broadphase.move(s.proxy, tight, displacement)) {
        return;
    }
    if (in_step) refattened.push_back(index);  // between steps, the next broadphase sees it
}

void World::Impl::remove(std::uint32_t index) {
    detail::Slot& s = slots[index];
    if (s.proxy >= 0) {
        broadphase.destroy(s.proxy);
        if (in_step) refattened.push_back(index);
    }
    s.proxy = -1;
    s.alive = false;
    const EntityId id{index, s.generation};
    s.body = EntityDesc{};  // drop the mask share and user data; the slot stays hashed as free
    s.mask_fingerprint = 0;
    s.turned = Shape{};
    s.turned_valid = false;
    placements[index] = {};
    s.fast = false;
    free_slots.push_back(index);
    ++removals;
    --live;
    std::erase_if(contacts, [&](const Contact& c) { return c.a == id || c.b == id; });
}

// ---------------------------------------------------------------------------------------
// World
// ---------------------------------------------------------------------------------------

World::World(const WorldDesc& desc) : impl_(std::make_unique<Impl>(desc)) {}
// A world replaced or destroyed by its own event handler would pull the step's state out from
// under the step (a use after free): a programming error, asserted like step() from a handler.
World::~World() { JOSTLE_ASSERT(impl_ == nullptr || !impl_->in_step, "a World destroyed during its own step (from an event handler)"); }
World::World(World&&) noexcept = default;
// Every member but assignment and destruction: a moved-from World has no state to use (a
// programming error, asserted rather than a null dereference).
World::Impl& World::impl() const {
    JOSTLE_ASSERT(impl_ != nullptr, "a moved-from World used (it may only be assigned to or destroyed)");
    return *impl_;
}
World& World::operator=(World&& other) noexcept {
    JOSTLE_ASSERT(impl_ == nullptr || !impl_->in_step, "a World replaced during its own step (from an event handler)");
    impl_ = std::move(other.impl_);
    return *this;
}

EntityId World::create(const EntityDesc& desc) {
    std::uint32_t index;
    if (!impl().free_slots.empty()) {
        index = impl().free_slots.back();
        impl().free_slots.pop_back();
    } else {
        JOSTLE_ASSERT(impl().slots.size() < 0xffffffffu, "too many entities");
        index = static_cast<std::uint32_t>(impl().slots.size());
        impl().slots.emplace_back();
        impl().placements.emplace_back();
    }
    detail::Slot& s = impl().slots[index];
    // Generations count up from 1 and skip 0 (the null id) when they wrap.
    s.generation = (s.generation == 0xffffffffu) ? 1u : s.generation + 1u;
    s.alive = true;
    s.body = desc;
    s.mask_fingerprint = fingerprint(desc.collider);
    s.proxy = -1;
    ++impl().live;
    impl().turn(index);
    impl().sync_proxy(index);
    return {index, s.generation};
}

bool World::destroy(EntityId id) {
    if (impl().find(id) == nullptr) return false;
    impl().remove(id.index);
    return true;
}

bool World::alive(EntityId id) const { return impl().find(id) != nullptr; }

const EntityDesc* World::get(EntityId id) const {
    const detail::Slot* s = impl().find(id);
    return s ? &s->body : nullptr;
}

Shape World::shape_of(EntityId id) const {
    if (impl().find(id) == nullptr) return Collider{}.placed({NAN, NAN}, 0.0f);
    return impl().placed(id.index);
}

std::size_t World::entity_count() const { return impl().live; }

std::vector<EntityId> World::entities() const {
    std::vector<EntityId> out;
    out.reserve(impl().live);
    for (std::uint32_t i = 0; i < impl().slots.size(); ++i) {
        if (impl().slots[i].alive) out.push_back(impl().id_of(i));
    }
    return out;
}

namespace {
// Changes an entity, then brings its turned collider (when the collider or angle may have
// changed) and its broadphase proxy up to date.
template <typename F>
bool change(World::Impl& impl, EntityId id, bool turns, F&& f) {
    detail::Slot* s = impl.find(id);
    if (s == nullptr) return false;
    f(*s);
    if (turns) impl.turn(id.index);
    impl.sync_proxy(id.index);
    return true;
}
}  // namespace

bool World::set_position(EntityId id, Vec2 position) {
    return change(impl(), id, false, [&](detail::Slot& s) { s.body.position = position; });
}
bool World::set_angle(EntityId id, float angle) {
    return change(impl(), id, true, [&](detail::Slot& s) { s.body.angle = angle; });
}
bool World::set_velocity(EntityId id, Vec2 velocity) {
    return change(impl(), id, false, [&](detail::Slot& s) { s.body.velocity = velocity; });
}
bool World::set_angular_velocity(EntityId id, float angular_velocity) {
    return change(impl(), id, false, [&](detail::Slot& s) { s.body.angular_velocity = angular_velocity; });
}
bool World::set_collider(EntityId id, const Collider& collider) {
    return change(impl(), id, true, [&](detail::Slot& s) {
        s.body.collider = collider;
        s.mask_fingerprint = fingerprint(collider);
    });
}
bool World::set_user_data(EntityId id, std::uint64_t user_data) {
    return change(impl(), id, false, [&](detail::Slot& s) { s.body.user_data = user_data; });
}
bool World::set(EntityId id, const EntityDesc& desc) {
    return change(impl(), id, true, [&](detail::Slot& s) {
        s.body = desc;
        s.mask_fingerprint = fingerprint(desc.collider);
    });
}

std::span<const Event> World::events() const { return impl().events; }
std::span<const Contact> World::contacts() const { return impl().contacts; }
std::span<const SweptPath> World::swept_paths() const { return impl().paths; }
void World::set_event_handler(EventHandler handler) { impl().handler = std::move(handler); }
std::uint64_t World::step_count() const { return impl().steps; }
Rng& World::rng() { return impl().rng; }
const WorldDesc& World::desc() const { return impl().desc; }

// ---------------------------------------------------------------------------------------
// FixedStepper
// ---------------------------------------------------------------------------------------

int FixedStepper::advance(double elapsed_seconds) {
    if (std::isfinite(elapsed_seconds) && elapsed_seconds > 0.0) accumulator_ += elapsed_seconds;
    // A float step is not exactly 1/60: frames of exactly 1/60 s must still give one step
    // each, so a step is due once the accumulator is within a millionth of it.
    const double step = step_;
    const double due = step * (1.0 - 1e-6);
    int steps = 0;
    while (accumulator_ >= due && steps < max_steps_) {
        accumulator_ = std::fmax(accumulator_ - step, 0.0);
        ++steps;
    }
    // Beyond the cap, whole steps are dropped rather than owed to later frames.
    if (accumulator_ >= due) accumulator_ = std::fmod(accumulator_, step);
    return steps;
}

}  // namespace jostle
