// World entity and event tests: ids (stale, reuse, null), changes made from the event handler,
// contact/trigger/bullet events and their order, fast circles, queries, the FixedStepper, and
// where a collider lands for an entity's position and angle.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <numbers>
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "jostle/collision.h"
#include "jostle/world.h"

namespace jostle {

// Readable failure messages.
static void PrintTo(const EntityId& id, std::ostream* os) { *os << "{" << id.index << ", " << id.generation << "}"; }
static void PrintTo(const Vec2& v, std::ostream* os) { *os << "(" << v.x << ", " << v.y << ")"; }
static void PrintTo(EventType t, std::ostream* os) { *os << name_of(t); }

namespace {

constexpr float kDt = 1.0f / 60.0f;
constexpr float kPosTol = 1e-4f;
constexpr float kPi = std::numbers::pi_v<float>;
// A ricochet continues from just off the surface (WorldDesc{}.slop plus rounding).
constexpr float kRicochetTol = 0.01f + 1e-3f;

::testing::AssertionResult vec_near(Vec2 actual, Vec2 expected, float tol) {
    if (std::fabs(actual.x - expected.x) <= tol && std::fabs(actual.y - expected.y) <= tol) {
        return ::testing::AssertionSuccess();
    }
    return ::testing::AssertionFailure() << "(" << actual.x << ", " << actual.y << ") is not within " << tol
                                         << " of (" << expected.x << ", " << expected.y << ")";
}
#define EXPECT_VEC_NEAR(actual, expected, tol) EXPECT_TRUE(vec_near((actual), (expected), (tol)))

// A vector in one token, for use inside assertion macros.
constexpr Vec2 xy(float x, float y) { return {x, y}; }

EntityDesc box_desc(BodyKind kind, Vec2 position, Vec2 half, std::uint64_t user_data = 0) {
    EntityDesc d;
    d.kind = kind;
    d.position = position;
    d.collider = Collider::aabb(half);
    d.user_data = user_data;
    return d;
}

EntityDesc bullet_desc(Vec2 position, Vec2 velocity, BulletResponse on_hit, std::uint64_t user_data = 0) {
    EntityDesc d;
    d.kind = BodyKind::bullet;
    d.position = position;
    d.velocity = velocity;
    d.on_hit = on_hit;
    d.user_data = user_data;
    return d;
}

Vec2 position_of(const World& w, EntityId id) {
    const EntityDesc* d = w.get(id);
    EXPECT_NE(d, nullptr);
    return d ? d->position : Vec2{};
}

Vec2 velocity_of(const World& w, EntityId id) {
    const EntityDesc* d = w.get(id);
    EXPECT_NE(d, nullptr);
    return d ? d->velocity : Vec2{};
}

std::vector<Event> events_of(const World& w) { return {w.events().begin(), w.events().end()}; }

std::vector<EventType> types_of(const std::vector<Event>& events) {
    std::vector<EventType> out;
    for (const Event& e : events) out.push_back(e.type);
    return out;
}

// Does the shape hit anything at all? (A stale id's shape must not.)
bool hits_anything(const Shape& s) {
    const Aabb everything{{-1e5f, -1e5f}, {1e5f, 1e5f}};
    return collide(s, Shape{everything}).hit;
}

// ---------------------------------------------------------------------------------------
// Ids
// ---------------------------------------------------------------------------------------

TEST(EntityIds, the_null_id_is_never_alive) {
    World w;
    const EntityId e = w.create(box_desc(BodyKind::static_body, {0, 0}, {1, 1}));
    EXPECT_FALSE(e.is_null());
    EXPECT_NE(e.generation, 0u);
    for (const EntityId id : {EntityId{}, EntityId{e.index, 0}}) {
        EXPECT_TRUE(id.is_null());
        EXPECT_FALSE(w.alive(id));
        EXPECT_EQ(w.get(id), nullptr);
        EXPECT_FALSE(w.set_position(id, {1, 1}));
        EXPECT_FALSE(w.destroy(id));
    }
    EXPECT_TRUE(w.alive(e));
    EXPECT_EQ(w.entity_count(), 1u);
}

TEST(EntityIds, an_id_out_of_range_is_stale) {
    World w;
    w.create(EntityDesc{});
    const EntityId far{1000, 1};
    EXPECT_FALSE(w.alive(far));
    EXPECT_EQ(w.get(far), nullptr);
    EXPECT_FALSE(w.set_velocity(far, {1, 0}));
    EXPECT_FALSE(w.destroy(far));
}

TEST(EntityIds, a_destroyed_id_is_stale_everywhere) {
    World w;
    EntityDesc d = box_desc(BodyKind::dynamic, {5, 6}, {2, 2}, 42);
    const EntityId e = w.create(d);
    ASSERT_NE(w.get(e), nullptr);
    EXPECT_EQ(w.get(e)->user_data, 42u);
    EXPECT_TRUE(w.destroy(e));
    EXPECT_FALSE(w.alive(e));
    EXPECT_EQ(w.get(e), nullptr);
    EXPECT_FALSE(w.set_position(e, {1, 1}));
    EXPECT_FALSE(w.set_angle(e, 1.0f));
    EXPECT_FALSE(w.set_velocity(e, {1, 1}));
    EXPECT_FALSE(w.set_angular_velocity(e, 1.0f));
    EXPECT_FALSE(w.set_collider(e, Collider::circle(3)));
    EXPECT_FALSE(w.set_user_data(e, 7));
    EXPECT_FALSE(w.set(e, d));
    EXPECT_FALSE(w.destroy(e));  // destroying twice
    EXPECT_FALSE(hits_anything(w.shape_of(e)));
    EXPECT_EQ(w.entity_count(), 0u);
    EXPECT_TRUE(w.entities().empty());
    w.step(kDt);  // nothing left to step
    EXPECT_TRUE(w.events().empty());
}

TEST(EntityIds, a_reused_slot_gets_a_new_generation_and_the_old_id_stays_stale) {
    World w;
    const EntityId a = w.create(box_desc(BodyKind::static_body, {0, 0}, {1, 1}, 1));
    const EntityId b = w.create(box_desc(BodyKind::static_body, {10, 0}, {1, 1}, 2));
    ASSERT_TRUE(w.destroy(a));
    const EntityId c = w.create(box_desc(BodyKind::static_body, {20, 0}, {1, 1}, 3));
    EXPECT_EQ(c.index, a.index);  // the free slot is reused
    EXPECT_NE(c.generation, a.generation);
    EXPECT_NE(c, a);
    EXPECT_FALSE(w.alive(a));
    EXPECT_TRUE(w.alive(b));
    EXPECT_TRUE(w.alive(c));
    EXPECT_EQ(w.get(a), nullptr);
    // The stale id never reaches the entity now in its slot.
    EXPECT_FALSE(w.set_position(a, {99, 99}));
    EXPECT_FALSE(w.set_user_data(a, 99));
    EXPECT_FALSE(w.destroy(a));
    EXPECT_TRUE(w.alive(c));
    EXPECT_EQ(position_of(w, c), xy(20, 0));
    EXPECT_EQ(w.get(c)->user_data, 3u);
    EXPECT_FALSE(hits_anything(w.shape_of(a)));
    EXPECT_TRUE(hits_anything(w.shape_of(c)));
    // Destroy and reuse again: every earlier id of the slot stays stale.
    ASSERT_TRUE(w.destroy(c));
    const EntityId d = w.create(EntityDesc{});
    EXPECT_EQ(d.index, a.index);
    EXPECT_NE(d.generation, a.generation);
    EXPECT_NE(d.generation, c.generation);
    EXPECT_FALSE(w.alive(a));
    EXPECT_FALSE(w.alive(c));
    EXPECT_TRUE(w.alive(d));
}

TEST(EntityIds, entity_count_and_entities_in_slot_order) {
    World w;
    std::vector<EntityId> ids;
    for (int i = 0; i < 5; ++i) ids.push_back(w.create(box_desc(BodyKind::static_body, {0, 0}, {1, 1})));
    EXPECT_EQ(w.entity_count(), 5u);
    EXPECT_EQ(w.entities(), ids);
    ASSERT_TRUE(w.destroy(ids[1]));
    ASSERT_TRUE(w.destroy(ids[3]));
    EXPECT_FALSE(w.destroy(ids[3]));
    EXPECT_EQ(w.entity_count(), 3u);
    EXPECT_EQ(w.entities(), (std::vector<EntityId>{ids[0], ids[2], ids[4]}));
    const EntityId n = w.create(EntityDesc{});
    EXPECT_EQ(w.entity_count(), 4u);
    const std::vector<EntityId> live = w.entities();
    ASSERT_EQ(live.size(), 4u);
    EXPECT_TRUE(std::is_sorted(live.begin(), live.end(), [](EntityId x, EntityId y) { return x.index < y.index; }));
    EXPECT_NE(std::find(live.begin(), live.end(), n), live.end());
    for (const EntityId id : {ids[0], ids[2], ids[4]})
        EXPECT_NE(std::find(live.begin(), live.end(), id), live.end());
}

TEST(EntityIds, get_returns_the_state_and_setters_change_it) {
    World w;
    EntityDesc d = box_desc(BodyKind::kinematic, {3, 4}, {2, 2}, 9);
    d.layer = 6;
    d.collides_with = 5;
    d.restitution = 0.25f;
    const EntityId e = w.create(d);
    const EntityDesc* got = w.get(e);
    ASSERT_NE(got, nullptr);
    EXPECT_EQ(got->kind, BodyKind::kinematic);
    EXPECT_EQ(got->position, xy(3, 4));
    EXPECT_EQ(got->layer, 6u);
    EXPECT_EQ(got->collides_with, 5u);
    EXPECT_EQ(got->restitution, 0.25f);
    EXPECT_EQ(got->user_data, 9u);
    EXPECT_TRUE(w.set_position(e, {7, 8}));
    EXPECT_TRUE(w.set_velocity(e, {60, 0}));
    EXPECT_TRUE(w.set_user_data(e, 10));
    EXPECT_EQ(w.get(e)->position, xy(7, 8));
    EXPECT_EQ(w.get(e)->user_data, 10u);
    w.step(kDt);
    EXPECT_VEC_NEAR(position_of(w, e), xy(8, 8), kPosTol);
    EXPECT_STREQ(name_of(BodyKind::static_body), "static");
    EXPECT_STREQ(name_of(BodyKind::kinematic), "kinematic");
    EXPECT_STREQ(name_of(EventType::contact_begin), "contact_begin");
    EXPECT_STREQ(name_of(EventType::bullet_hit), "bullet_hit");
}

// ---------------------------------------------------------------------------------------
// Contacts and triggers over several steps
// ---------------------------------------------------------------------------------------

TEST(EntityContacts, begin_once_no_repeat_while_touching_end_on_separation) {
    World w;
    // Box [-10,10]x[80.5,100.5] over a floor whose top is y = 100: 0.5 px deep.
    const EntityId box = w.create(box_desc(BodyKind::dynamic, {0, 90.5f}, {10, 10}, 1));
    const EntityId floor = w.create(box_desc(BodyKind::static_body, {0, 150}, {200, 50}, 2));

    w.step(kDt);
    std::vector<Event> ev = events_of(w);
    ASSERT_EQ(ev.size(), 1u);
    EXPECT_EQ(ev[0].type, EventType::contact_begin);
    EXPECT_EQ(ev[0].a, box);
    EXPECT_EQ(ev[0].b, floor);
    EXPECT_EQ(ev[0].a_user_data, 1u);
    EXPECT_EQ(ev[0].b_user_data, 2u);
    EXPECT_VEC_NEAR(ev[0].normal, xy(0, 1), 1e-6f);
    EXPECT_NEAR(ev[0].depth, 0.5f, kPosTol);
    EXPECT_NEAR(ev[0].point.y, 100.25f, kPosTol);  // the middle of the overlap along the normal
    EXPECT_GE(ev[0].point.x, -10.0f);
    EXPECT_LE(ev[0].point.x, 10.0f);
    EXPECT_VEC_NEAR(position_of(w, box), xy(0, 90), kPosTol);
    ASSERT_EQ(w.contacts().size(), 1u);
    EXPECT_EQ(w.contacts()[0].a, box);
    EXPECT_NEAR(w.contacts()[0].depth, 0.5f, kPosTol);

    // Touching (depth 0) is still contact: no event while they stay together.
    for (int i = 0; i < 3; ++i) {
        w.step(kDt);
        EXPECT_TRUE(w.events().empty()) << "step " << i;
        ASSERT_EQ(w.contacts().size(), 1u);
        EXPECT_NEAR(w.contacts()[0].depth, 0.0f, kPosTol);
    }

    ASSERT_TRUE(w.set_position(box, {0, 0}));
    w.step(kDt);
    ev = events_of(w);
    ASSERT_EQ(ev.size(), 1u);
    EXPECT_EQ(ev[0].type, EventType::contact_end);
    EXPECT_EQ(ev[0].a, box);
    EXPECT_EQ(ev[0].b, floor);
    EXPECT_EQ(ev[0].a_user_data, 1u);
    EXPECT_EQ(ev[0].b_user_data, 2u);
    // the last ones seen: touching, at y = 100
    EXPECT_VEC_NEAR(ev[0].normal, xy(0, 1), 1e-6f);
    EXPECT_NEAR(ev[0].depth, 0.0f, kPosTol);
    EXPECT_NEAR(ev[0].point.y, 100.0f, kPosTol);
    EXPECT_TRUE(w.contacts().empty());

    w.step(kDt);
    EXPECT_TRUE(w.events().empty());
}

TEST(EntityContacts, a_box_resting_under_gravity_begins_once) {
    WorldDesc wd;
    wd.gravity = {0, 980};
    World w(wd);
    const EntityId box = w.create(box_desc(BodyKind::dynamic, {0, 85}, {10, 10}));
    w.create(box_desc(BodyKind::static_body, {0, 150}, {200, 50}));
    int begins = 0;
    int ends = 0;
    for (int i = 0; i < 90; ++i) {
        w.step(kDt);
        for (const Event& e : w.events()) {
            begins += e.type == EventType::contact_begin;
            ends += e.type == EventType::contact_end;
        }
    }
    EXPECT_EQ(begins, 1);
    EXPECT_EQ(ends, 0);
    EXPECT_NEAR(position_of(w, box).y, 90.0f, 0.01f + 1e-4f);  // within slop
    EXPECT_EQ(w.contacts().size(), 1u);
}

TEST(EntityContacts, trigger_enter_once_and_exit) {
    World w;
    const EntityId d = w.create(box_desc(BodyKind::dynamic, {0, 0}, {5, 5}, 5));
    const EntityId t = w.create(box_desc(BodyKind::trigger, {100, 0}, {10, 10}, 6));
    w.step(kDt);
    EXPECT_TRUE(w.events().empty());

    ASSERT_TRUE(w.set_position(d, {100, 3}));
    w.step(kDt);
    std::vector<Event> ev = events_of(w);
    ASSERT_EQ(ev.size(), 1u);
    EXPECT_EQ(ev[0].type, EventType::trigger_enter);
    EXPECT_EQ(ev[0].a, t);
    EXPECT_EQ(ev[0].b, d);
    EXPECT_EQ(ev[0].a_user_data, 6u);
    EXPECT_EQ(ev[0].b_user_data, 5u);
    // trigger [90,110]x[-10,10] holds box [95,105]x[-2,8]: the trigger leaves by 12 px upward
    EXPECT_NEAR(ev[0].depth, 12.0f, kPosTol);
    EXPECT_VEC_NEAR(ev[0].normal, xy(0, 1), 1e-6f);
    EXPECT_EQ(position_of(w, d), xy(100, 3));  // not pushed

    w.step(kDt);
    EXPECT_TRUE(w.events().empty());

    ASSERT_TRUE(w.set_position(d, {0, 0}));
    w.step(kDt);
    ev = events_of(w);
    ASSERT_EQ(ev.size(), 1u);
    EXPECT_EQ(ev[0].type, EventType::trigger_exit);
    EXPECT_EQ(ev[0].a, t);
    EXPECT_EQ(ev[0].b, d);
}

TEST(EntityEvents, sorted_by_kind_then_by_ids) {
    World w;
    const EntityId s1 = w.create(box_desc(BodyKind::static_body, {0, 0}, {10, 10}));
    const EntityId d1 = w.create(box_desc(BodyKind::dynamic, {15, 0}, {10, 10}));  // touches s1 now
    const EntityId s2 = w.create(box_desc(BodyKind::static_body, {200, 0}, {10, 10}));
    const EntityId d2 = w.create(box_desc(BodyKind::dynamic, {200, 100}, {5, 5}));
    const EntityId s3 = w.create(box_desc(BodyKind::static_body, {400, 0}, {10, 10}));
    const EntityId d3 = w.create(box_desc(BodyKind::dynamic, {400, 100}, {5, 5}));
    const EntityId d5 = w.create(box_desc(BodyKind::dynamic, {600, 0}, {5, 5}));
    const EntityId t3 = w.create(box_desc(BodyKind::trigger, {800, 100}, {5, 5}));
    const EntityId t2 = w.create(box_desc(BodyKind::trigger, {600, 100}, {5, 5}));
    const EntityId d6 = w.create(box_desc(BodyKind::dynamic, {800, 0}, {5, 5}));
    const EntityId t1 = w.create(box_desc(BodyKind::trigger, {1000, 0}, {10, 10}));
    const EntityId d4 = w.create(box_desc(BodyKind::dynamic, {1000, 0}, {5, 5}));  // inside t1
    const EntityId s4 = w.create(box_desc(BodyKind::static_body, {1200, 0}, {10, 10}));

    w.step(kDt);
    std::vector<Event> ev = events_of(w);
    ASSERT_EQ(ev.size(), 2u);
    EXPECT_EQ(ev[0].type, EventType::contact_begin);
    EXPECT_EQ(ev[0].a, s1);
    EXPECT_EQ(ev[0].b, d1);
    EXPECT_EQ(ev[1].type, EventType::trigger_enter);
    EXPECT_EQ(ev[1].a, t1);
    EXPECT_EQ(ev[1].b, d4);

    ASSERT_TRUE(w.set_position(d1, {0, 300}));     // contact_end (s1, d1)
    ASSERT_TRUE(w.set_position(d2, {200, 12}));    // contact_begin (s2, d2): 3 px deep
    ASSERT_TRUE(w.set_position(d3, {400, 12}));    // contact_begin (s3, d3)
    ASSERT_TRUE(w.set_position(t1, {1000, 300}));  // trigger_exit (t1, d4)
    ASSERT_TRUE(w.set_position(t2, {600, 0}));     // trigger_enter (t2, d5), d5 < t2
    ASSERT_TRUE(w.set_position(t3, {800, 0}));     // trigger_enter (t3, d6), t3 < t2 < d6
    // A bullet crossing s4's left face (x = 1190) half way along its 20 px path.
    const EntityId bullet = w.create(bullet_desc({1180, 0}, {1200, 0}, BulletResponse::stop));

    std::vector<Event> handled;
    w.set_event_handler([&](World&, const Event& e) { handled.push_back(e); });
    w.step(kDt);
    ev = events_of(w);
    const std::vector<EventType> expected_types{EventType::bullet_hit,    EventType::contact_end,
                                                EventType::contact_begin, EventType::contact_begin,
                                                EventType::trigger_exit,  EventType::trigger_enter,
                                                EventType::trigger_enter};
    ASSERT_EQ(types_of(ev), expected_types);
    const std::vector<std::pair<EntityId, EntityId>> expected_ids{
        {bullet, s4}, {s1, d1}, {s2, d2}, {s3, d3}, {t1, d4}, {t3, d6}, {t2, d5}};
    for (std::size_t i = 0; i < ev.size(); ++i) {
        EXPECT_EQ(ev[i].a, expected_ids[i].first) << "event " << i;
        EXPECT_EQ(ev[i].b, expected_ids[i].second) << "event " << i;
    }
    // The handler saw the same events in the same order.
    ASSERT_EQ(handled.size(), ev.size());
    for (std::size_t i = 0; i < ev.size(); ++i) {
        EXPECT_EQ(handled[i].type, ev[i].type);
        EXPECT_EQ(handled[i].a, ev[i].a);
        EXPECT_EQ(handled[i].b, ev[i].b);
    }
    EXPECT_NEAR(ev[2].depth, 3.0f, kPosTol);
    EXPECT_VEC_NEAR(ev[2].normal, xy(0, 1), 1e-6f);
}

// ---------------------------------------------------------------------------------------
// Changes made from the event handler
// ---------------------------------------------------------------------------------------

TEST(EntityHandler, destroying_entities_of_this_and_later_events) {
    World w;
    const EntityId a = w.create(box_desc(BodyKind::dynamic, {0, 0}, {10, 10}, 11));
    const EntityId b = w.create(box_desc(BodyKind::static_body, {15, 0}, {10, 10}, 12));
    const EntityId c = w.create(box_desc(BodyKind::dynamic, {200, 0}, {10, 10}, 13));
    const EntityId d = w.create(box_desc(BodyKind::static_body, {215, 0}, {10, 10}, 14));

    std::vector<Event> handled;
    std::vector<bool> destroy_results;
    w.set_event_handler([&](World& world, const Event& e) {
        handled.push_back(e);
        if (handled.size() == 1) {
            destroy_results.push_back(world.destroy(e.a));
            destroy_results.push_back(world.destroy(e.b));
            destroy_results.push_back(world.destroy(c));  // named in the next event
            destroy_results.push_back(world.destroy(e.a));  // twice
            EXPECT_FALSE(world.alive(e.a));
            EXPECT_EQ(world.get(c), nullptr);
        }
    });
    w.step(kDt);
    EXPECT_EQ(destroy_results, (std::vector<bool>{true, true, true, false}));
    ASSERT_EQ(handled.size(), 2u);
    EXPECT_EQ(handled[0].a, a);
    EXPECT_EQ(handled[0].b, b);
    // The later event is still delivered, with the stale id and its user data.
    EXPECT_EQ(handled[1].type, EventType::contact_begin);
    EXPECT_EQ(handled[1].a, c);
    EXPECT_EQ(handled[1].b, d);
    EXPECT_EQ(handled[1].a_user_data, 13u);
    EXPECT_EQ(handled[1].b_user_data, 14u);
    const std::vector<Event> ev = events_of(w);
    ASSERT_EQ(ev.size(), 2u);
    EXPECT_EQ(ev[0].a_user_data, 11u);
    EXPECT_EQ(ev[0].b_user_data, 12u);
    EXPECT_EQ(ev[1].a, c);
    EXPECT_EQ(ev[1].a_user_data, 13u);

    EXPECT_FALSE(w.alive(a));
    EXPECT_FALSE(w.alive(b));
    EXPECT_FALSE(w.alive(c));
    EXPECT_TRUE(w.alive(d));
    EXPECT_EQ(w.entity_count(), 1u);
    EXPECT_EQ(w.entities(), std::vector<EntityId>{d});

    // Pairs with a destroyed entity are dropped without an end event.
    handled.clear();
    w.step(kDt);
    EXPECT_TRUE(w.events().empty());
    EXPECT_TRUE(handled.empty());
    EXPECT_TRUE(w.contacts().empty());
}

TEST(EntityHandler, entities_created_in_the_handler_exist_at_once_and_move_from_the_next_step) {
    World w;
    w.create(box_desc(BodyKind::dynamic, {0, 0}, {10, 10}));
    w.create(box_desc(BodyKind::static_body, {15, 0}, {10, 10}));
    const EntityId s2 = w.create(box_desc(BodyKind::static_body, {700, 10}, {5, 5}));

    EntityId mover, sinker;
    bool seen_by_query = false;
    w.set_event_handler([&](World& world, const Event&) {
        if (!mover.is_null()) return;
        EntityDesc m = box_desc(BodyKind::dynamic, {500, 0}, {5, 5}, 77);
        m.velocity = {60, 0};
        mover = world.create(m);
        // 3 px into s2 ([695,705]x[5,15] against [695,705]x[-2,8])
        sinker = world.create(box_desc(BodyKind::dynamic, {700, 3}, {5, 5}));
        EXPECT_TRUE(world.alive(mover));
        ASSERT_NE(world.get(mover), nullptr);
        EXPECT_EQ(world.get(mover)->user_data, 77u);
        const std::vector<EntityId> q = world.query_point({500, 0});
        seen_by_query = std::find(q.begin(), q.end(), mover) != q.end();
    });
    w.step(kDt);
    ASSERT_FALSE(mover.is_null());
    EXPECT_TRUE(seen_by_query);
    EXPECT_TRUE(w.alive(mover));
    EXPECT_TRUE(w.alive(sinker));
    // Created during the step: not moved, not pushed, no contact in it.
    EXPECT_EQ(position_of(w, mover), xy(500, 0));
    EXPECT_EQ(position_of(w, sinker), xy(700, 3));
    EXPECT_EQ(w.events().size(), 1u);
    EXPECT_EQ(w.entity_count(), 5u);

    w.step(kDt);
    EXPECT_VEC_NEAR(position_of(w, mover), xy(501, 0), kPosTol);
    EXPECT_VEC_NEAR(position_of(w, sinker), xy(700, 0), kPosTol);
    const std::vector<Event> ev = events_of(w);
    ASSERT_EQ(ev.size(), 1u);
    EXPECT_EQ(ev[0].type, EventType::contact_begin);
    EXPECT_EQ(ev[0].a, s2);
    EXPECT_EQ(ev[0].b, sinker);
}

// ---------------------------------------------------------------------------------------
// Bullets
// ---------------------------------------------------------------------------------------

// A bullet at (0, 50) moving 10 px right per step toward a static box whose left face is x = 5.
struct BulletScene {
    World w;
    EntityId bullet;
    EntityId target;
    explicit BulletScene(BulletResponse response) {
        target = w.create(box_desc(BodyKind::static_body, {22.5f, 50}, {17.5f, 10}, 21));
        bullet = w.create(bullet_desc({0, 50}, {600, 0}, response, 20));
        w.step(kDt);
    }
};

void expect_hit_event(const World& w, EntityId bullet, EntityId target) {
    const std::vector<Event> ev = events_of(w);
    ASSERT_EQ(ev.size(), 1u);
    EXPECT_EQ(ev[0].type, EventType::bullet_hit);
    EXPECT_EQ(ev[0].a, bullet);
    EXPECT_EQ(ev[0].b, target);
    EXPECT_EQ(ev[0].a_user_data, 20u);
    EXPECT_EQ(ev[0].b_user_data, 21u);
    EXPECT_NEAR(ev[0].fraction, 0.5f, 1e-5f);
    EXPECT_VEC_NEAR(ev[0].point, xy(5, 50), kPosTol);
    EXPECT_VEC_NEAR(ev[0].normal, xy(-1, 0), 1e-6f);
}

TEST(EntityBullets, despawn_removes_the_bullet_after_the_hit) {
    BulletScene s(BulletResponse::despawn);
    expect_hit_event(s.w, s.bullet, s.target);
    EXPECT_FALSE(s.w.alive(s.bullet));
    EXPECT_TRUE(s.w.alive(s.target));
    EXPECT_EQ(position_of(s.w, s.target), xy(22.5f, 50));
    EXPECT_EQ(s.w.entity_count(), 1u);
}

TEST(EntityBullets, stop_leaves_the_bullet_at_the_hit_point_at_rest) {
    BulletScene s(BulletResponse::stop);
    expect_hit_event(s.w, s.bullet, s.target);
    ASSERT_TRUE(s.w.alive(s.bullet));
    EXPECT_VEC_NEAR(position_of(s.w, s.bullet), xy(5, 50), kPosTol);
    EXPECT_EQ(velocity_of(s.w, s.bullet), xy(0, 0));
}

TEST(EntityBullets, ricochet_reflects_and_continues_with_the_rest_of_the_path) {
    BulletScene s(BulletResponse::ricochet);
    expect_hit_event(s.w, s.bullet, s.target);
    ASSERT_TRUE(s.w.alive(s.bullet));
    EXPECT_VEC_NEAR(velocity_of(s.w, s.bullet), xy(-600, 0), 1e-3f);
    // 5 px in, 5 px back; the engine lifts a ricochet off the surface by about `slop` along the
    // normal so the rest of the path does not start on it.
    EXPECT_VEC_NEAR(position_of(s.w, s.bullet), xy(0, 50), kRicochetTol);
    EXPECT_LE(position_of(s.w, s.bullet).x, 0.0f);
}

TEST(EntityBullets, ricochet_at_45_degrees) {
    World w;
    const EntityId floor = w.create(box_desc(BodyKind::static_body, {0, 52.5f}, {100, 7.5f}));  // top y = 45
    const EntityId b = w.create(bullet_desc({0, 40}, {600, 600}, BulletResponse::ricochet));
    w.step(kDt);
    const std::vector<Event> ev = events_of(w);
    ASSERT_EQ(ev.size(), 1u);
    EXPECT_EQ(ev[0].b, floor);
    EXPECT_NEAR(ev[0].fraction, 0.5f, 1e-5f);
    EXPECT_VEC_NEAR(ev[0].point, xy(5, 45), kPosTol);
    EXPECT_VEC_NEAR(ev[0].normal, xy(0, -1), 1e-6f);
    EXPECT_VEC_NEAR(velocity_of(w, b), xy(600, -600), 1e-3f);
    EXPECT_NEAR(position_of(w, b).x, 10.0f, kPosTol);
    EXPECT_NEAR(position_of(w, b).y, 40.0f, kRicochetTol);
}

TEST(EntityBullets, a_miss_moves_the_bullet_by_its_velocity) {
    World w;
    w.create(box_desc(BodyKind::static_body, {0, 100}, {10, 10}));
    const EntityId b = w.create(bullet_desc({0, 0}, {600, 0}, BulletResponse::despawn));
    w.step(kDt);
    EXPECT_TRUE(w.events().empty());
    EXPECT_VEC_NEAR(position_of(w, b), xy(10, 0), kPosTol);
}

TEST(EntityBullets, the_shooter_and_filtered_layers_are_passed_through_and_dynamic_targets_not_pushed) {
    World w;
    // On the path (y = 0) from x = 0 to x = 30: the shooter [0,4], a layer-2 box [8,12], a
    // dynamic target [20,40].
    const EntityId shooter = w.create(box_desc(BodyKind::dynamic, {2, 0}, {2, 5}));
    EntityDesc other_layer = box_desc(BodyKind::static_body, {10, 0}, {2, 5});
    other_layer.layer = 2;
    w.create(other_layer);
    const EntityId target = w.create(box_desc(BodyKind::dynamic, {30, 0}, {10, 5}));
    EntityDesc bd = bullet_desc({0, 0}, {1800, 0}, BulletResponse::despawn, 3);
    bd.ignore = shooter;
    bd.collides_with = ~2u;
    const EntityId b = w.create(bd);
    w.step(kDt);
    const std::vector<Event> ev = events_of(w);
    ASSERT_EQ(ev.size(), 1u);
    EXPECT_EQ(ev[0].type, EventType::bullet_hit);
    EXPECT_EQ(ev[0].a, b);
    EXPECT_EQ(ev[0].b, target);
    EXPECT_NEAR(ev[0].fraction, 20.0f / 30.0f, 1e-5f);
    EXPECT_FALSE(w.alive(b));
    // bullets never push
    EXPECT_EQ(position_of(w, target), xy(30, 0));
    EXPECT_EQ(velocity_of(w, target), xy(0, 0));
    EXPECT_EQ(position_of(w, shooter), xy(2, 0));
}

// ---------------------------------------------------------------------------------------
// Fast circles
// ---------------------------------------------------------------------------------------

TEST(EntityFastCircle, a_circle_at_20000_px_per_s_stops_at_a_thin_wall) {
    World w;
    EntityDesc cd;
    cd.kind = BodyKind::dynamic;
    cd.position = {0, 0};
    cd.velocity = {20000, 0};  // 333 px per step
    cd.collider = Collider::circle(5);
    const EntityId c = w.create(cd);
    const EntityId wall = w.create(box_desc(BodyKind::static_body, {202, 0}, {2, 50}));  // x in [200, 204]
    w.step(kDt);
    const Vec2 p = position_of(w, c);
    EXPECT_NEAR(p.x, 195.0f, 0.01f);  // touching the wall's left face
    EXPECT_LE(p.x, 195.0f + 0.01f);
    EXPECT_NEAR(p.y, 0.0f, kPosTol);
    EXPECT_NEAR(velocity_of(w, c).x, 0.0f, 1e-3f);
    const std::vector<Event> ev = events_of(w);
    ASSERT_EQ(ev.size(), 1u);
    EXPECT_EQ(ev[0].type, EventType::contact_begin);
    EXPECT_EQ(ev[0].a, c);
    EXPECT_EQ(ev[0].b, wall);
    EXPECT_VEC_NEAR(ev[0].normal, xy(1, 0), 1e-5f);
    bool swept = false;
    for (const SweptPath& sp : w.swept_paths()) {
        if (sp.id != c) continue;
        swept = true;
        EXPECT_EQ(sp.from, xy(0, 0));
        EXPECT_EQ(sp.radius, 5.0f);
    }
    EXPECT_TRUE(swept);
    // It stays at the wall.
    for (int i = 0; i < 5; ++i) w.step(kDt);
    EXPECT_LE(position_of(w, c).x, 195.0f + 0.01f);
}

TEST(EntityFastCircle, an_elastic_fast_circle_bounces_back_for_the_rest_of_the_step) {
    World w;
    EntityDesc cd;
    cd.kind = BodyKind::dynamic;
    cd.velocity = {20000, 0};
    cd.restitution = 1.0f;
    cd.collider = Collider::circle(5);
    const EntityId c = w.create(cd);
    w.create(box_desc(BodyKind::static_body, {202, 0}, {2, 50}));
    w.step(kDt);
    // 195 px to the contact, the remaining 333.33 - 195 px back again.
    const float path = 20000.0f * kDt;
    EXPECT_NEAR(position_of(w, c).x, 195.0f - (path - 195.0f), 0.02f);
    EXPECT_VEC_NEAR(velocity_of(w, c), xy(-20000, 0), 0.5f);
    EXPECT_EQ(w.events().size(), 1u);
}

// ---------------------------------------------------------------------------------------
// Queries
// ---------------------------------------------------------------------------------------

struct QueryScene {
    World w;
    EntityId a, b, c, gone;
    QueryScene() {
        gone = w.create(box_desc(BodyKind::static_body, {10, 10}, {5, 5}));
        a = w.create(box_desc(BodyKind::static_body, {10, 10}, {5, 5}));  // [5,15]^2, layer 1
        EntityDesc bd;
        bd.kind = BodyKind::dynamic;
        bd.position = {30, 10};
        bd.collider = Collider::circle(5);
        bd.layer = 2;
        b = w.create(bd);
        EntityDesc cd = box_desc(BodyKind::static_body, {50, 10}, {5, 5});
        cd.layer = 4;
        c = w.create(cd);
        w.destroy(gone);
    }
};

TEST(EntityQueries, query_aabb_by_layers_in_id_order) {
    QueryScene s;
    EXPECT_EQ(s.w.query_aabb({{0, 0}, {28, 20}}), (std::vector<EntityId>{s.a, s.b}));
    EXPECT_EQ(s.w.query_aabb({{0, 0}, {100, 100}}), (std::vector<EntityId>{s.a, s.b, s.c}));
    EXPECT_EQ(s.w.query_aabb({{0, 0}, {100, 100}}, 2u), std::vector<EntityId>{s.b});
    EXPECT_EQ(s.w.query_aabb({{0, 0}, {100, 100}}, 4u | 1u), (std::vector<EntityId>{s.a, s.c}));
    EXPECT_TRUE(s.w.query_aabb({{0, 50}, {100, 100}}).empty());
}

TEST(EntityQueries, query_point_uses_the_shape_and_the_layers) {
    QueryScene s;
    EXPECT_EQ(s.w.query_point({12, 12}), std::vector<EntityId>{s.a});
    EXPECT_EQ(s.w.query_point({30, 10}), std::vector<EntityId>{s.b});
    EXPECT_TRUE(s.w.query_point({30, 10}, 1u).empty());
    EXPECT_TRUE(s.w.query_point({34, 14}).empty());  // in the circle's bounds, outside the circle
    EXPECT_TRUE(s.w.query_point({20, 10}).empty());
    // A second entity over the first: both, in id order (the new one reuses the lower slot).
    const EntityId over = s.w.create(box_desc(BodyKind::static_body, {12, 12}, {3, 3}));
    std::vector<EntityId> expected{over, s.a};
    std::sort(expected.begin(), expected.end());
    EXPECT_EQ(s.w.query_point({12, 12}), expected);
}

TEST(EntityQueries, cast_segment_first_hit_layers_ignore_and_ties) {
    QueryScene s;
    std::optional<RayHit> h = s.w.cast_segment({0, 10}, {100, 10});
    ASSERT_TRUE(h.has_value());
    EXPECT_EQ(h->id, s.a);
    EXPECT_NEAR(h->t, 0.05f, 1e-6f);
    EXPECT_VEC_NEAR(h->point, xy(5, 10), kPosTol);
    EXPECT_VEC_NEAR(h->normal, xy(-1, 0), 1e-6f);

    h = s.w.cast_segment({0, 10}, {100, 10}, 2u | 4u);
    ASSERT_TRUE(h.has_value());
    EXPECT_EQ(h->id, s.b);
    EXPECT_NEAR(h->t, 0.25f, 1e-6f);
    EXPECT_VEC_NEAR(h->point, xy(25, 10), kPosTol);
    EXPECT_VEC_NEAR(h->normal, xy(-1, 0), 1e-5f);

    h = s.w.cast_segment({0, 10}, {100, 10}, 0xffffffffu, s.a);
    ASSERT_TRUE(h.has_value());
    EXPECT_EQ(h->id, s.b);

    h = s.w.cast_segment({0, 10}, {100, 10}, 4u);
    ASSERT_TRUE(h.has_value());
    EXPECT_EQ(h->id, s.c);
    EXPECT_NEAR(h->t, 0.45f, 1e-6f);

    EXPECT_FALSE(s.w.cast_segment({0, 10}, {-100, 10}).has_value());
    EXPECT_FALSE(s.w.cast_segment({0, 10}, {100, 10}, 8u).has_value());

    // Two identical boxes: the lower id wins; ignoring it gives the other.
    World w;
    const EntityId first = w.create(box_desc(BodyKind::static_body, {50, 0}, {5, 5}));
    const EntityId second = w.create(box_desc(BodyKind::static_body, {50, 0}, {5, 5}));
    h = w.cast_segment({0, 0}, {100, 0});
    ASSERT_TRUE(h.has_value());
    EXPECT_EQ(h->id, first);
    EXPECT_NEAR(h->t, 0.45f, 1e-6f);
    h = w.cast_segment({0, 0}, {100, 0}, 0xffffffffu, first);
    ASSERT_TRUE(h.has_value());
    EXPECT_EQ(h->id, second);
}

// ---------------------------------------------------------------------------------------
// FixedStepper
// ---------------------------------------------------------------------------------------

TEST(EntityFixedStepper, whole_steps_remainders_and_the_cap) {
    FixedStepper f;  // 1/60 s, at most 8 steps per frame
    EXPECT_EQ(f.step_seconds(), 1.0f / 60.0f);
    EXPECT_EQ(f.advance(0.05), 3);
    EXPECT_GE(f.alpha(), 0.0f);
    EXPECT_LT(f.alpha(), 1.0f);
    EXPECT_LT(f.alpha(), 1e-3f);  // nothing (or rounding) left over

    FixedStepper g;
    EXPECT_EQ(g.advance(0.01), 0);
    EXPECT_NEAR(g.alpha(), 0.6f, 1e-5f);
    EXPECT_EQ(g.advance(0.01), 1);  // 0.02 s accumulated
    EXPECT_NEAR(g.alpha(), 0.2f, 1e-5f);
    EXPECT_EQ(g.advance(0.0), 0);
    EXPECT_EQ(g.advance(1.0), 8);  // 60 steps' worth: capped, the rest dropped
    EXPECT_GE(g.alpha(), 0.0f);
    EXPECT_LT(g.alpha(), 1.0f);
    EXPECT_EQ(g.advance(0.0), 0);
    EXPECT_EQ(g.advance(0.02), 1);

    // A frame of exactly one step, every frame: one step each time, nothing left over.
    FixedStepper per_frame;
    EXPECT_EQ(per_frame.advance(1.0 / 60.0), 1);
    int steps = 0;
    for (int frame = 0; frame < 9; ++frame) steps += per_frame.advance(1.0 / 60.0);
    EXPECT_EQ(steps, 9);
    EXPECT_LT(per_frame.alpha(), 1e-3f);

    // Exact binary step: every number below is exact.
    FixedStepper h(0.25f, 3);
    EXPECT_EQ(h.advance(0.625), 2);
    EXPECT_FLOAT_EQ(h.alpha(), 0.5f);
    EXPECT_EQ(h.advance(0.125), 1);
    EXPECT_FLOAT_EQ(h.alpha(), 0.0f);
    EXPECT_EQ(h.advance(10.0), 3);
    EXPECT_GE(h.alpha(), 0.0f);
    EXPECT_LT(h.alpha(), 1.0f);
    EXPECT_EQ(h.advance(0.0), 0);
    EXPECT_EQ(h.advance(0.25), 1);
}

// ---------------------------------------------------------------------------------------
// Where a collider lands
// ---------------------------------------------------------------------------------------

// Every point of `expected` is within tol of some point of `actual`, and the counts agree.
::testing::AssertionResult same_points(std::vector<Vec2> actual, std::vector<Vec2> expected, float tol) {
    if (actual.size() != expected.size()) {
        return ::testing::AssertionFailure() << actual.size() << " points, expected " << expected.size();
    }
    for (const Vec2 e : expected) {
        const auto it = std::find_if(actual.begin(), actual.end(), [&](Vec2 a) {
            return std::fabs(a.x - e.x) <= tol && std::fabs(a.y - e.y) <= tol;
        });
        if (it == actual.end()) return ::testing::AssertionFailure() << "no point near (" << e.x << ", " << e.y << ")";
        actual.erase(it);
    }
    return ::testing::AssertionSuccess();
}

std::vector<Vec2> points_of(const Polygon& p) {
    return {p.points().begin(), p.points().begin() + p.count()};
}

Vec2 turned(float angle, Vec2 v) {
    return {std::cos(angle) * v.x - std::sin(angle) * v.y, std::sin(angle) * v.x + std::cos(angle) * v.y};
}

TEST(EntityColliders, a_rotated_box_follows_the_entity_angle) {
    World w;
    EntityDesc d;
    d.position = {100, 100};
    d.angle = 0.5f;
    d.collider = Collider::box({5, 3}, {10, 0}, 0.25f);
    const EntityId e = w.create(d);
    const Shape s = w.shape_of(e);
    ASSERT_TRUE(std::holds_alternative<Obb>(s));
    const Obb expected{xy(100, 100) + turned(0.5f, {10, 0}), {5, 3}, 0.75f};
    const auto got = corners(std::get<Obb>(s));
    const auto want = corners(expected);
    EXPECT_TRUE(same_points({got.begin(), got.end()}, {want.begin(), want.end()}, 1e-4f));
}

TEST(EntityColliders, a_polygon_turns_with_the_entity) {
    World w;
    EntityDesc d;
    d.kind = BodyKind::kinematic;  // static bodies never move, nor turn
    d.position = {50, 50};
    d.angle = kPi / 2;
    const std::vector<Vec2> local{{0, 0}, {10, 0}, {0, 5}};
    d.collider = Collider::polygon(*make_polygon(local));
    const EntityId e = w.create(d);
    const Shape s = w.shape_of(e);
    ASSERT_TRUE(std::holds_alternative<Polygon>(s));
    const Polygon& p = std::get<Polygon>(s);
    EXPECT_TRUE(same_points(points_of(p), {{50, 50}, {50, 60}, {45, 50}}, 1e-4f));
    // still a valid polygon: positive winding, outward unit normals
    for (int i = 0; i < p.count(); ++i) {
        const auto k = static_cast<std::size_t>(i);
        const Vec2 e0 = p.points()[(k + 1) % 3] - p.points()[k];
        const Vec2 e1 = p.points()[(k + 2) % 3] - p.points()[(k + 1) % 3];
        EXPECT_GT(cross(e0, e1), 0.0f);
        EXPECT_NEAR(dot(p.normals()[k], e0), 0.0f, 1e-4f);
        EXPECT_NEAR(length(p.normals()[k]), 1.0f, 1e-5f);
        const Vec2 inward = p.points()[(k + 2) % 3] - p.points()[k];
        EXPECT_LT(dot(p.normals()[k], inward), 0.0f);
    }
    // Turning it by a step with angular velocity: an eighth of a turn more, to 3 pi / 4.
    ASSERT_TRUE(w.set_angular_velocity(e, (kPi / 4) * 60.0f));
    w.step(kDt);
    EXPECT_NEAR(w.get(e)->angle, 3 * kPi / 4, 1e-5f);
    const float h = std::sqrt(0.5f);
    EXPECT_TRUE(same_points(points_of(std::get<Polygon>(w.shape_of(e))),
                            {{50, 50}, {50 - 10 * h, 50 + 10 * h}, {50 - 5 * h, 50 - 5 * h}}, 1e-4f));
}

TEST(EntityColliders, angles_wrap_to_minus_pi_pi) {
    World w;
    EntityDesc d = box_desc(BodyKind::kinematic, {0, 0}, {1, 1});
    d.collider = Collider::box({4, 2});
    d.angle = 3.0f;
    d.angular_velocity = 60.0f;  // one radian this step: 4 - 2 pi
    const EntityId e = w.create(d);
    d.position = {100, 0};
    d.angle = -3.0f;
    d.angular_velocity = -60.0f;
    const EntityId f = w.create(d);
    w.step(kDt);
    EXPECT_NEAR(w.get(e)->angle, 4.0f - 2.0f * kPi, 1e-5f);
    EXPECT_NEAR(w.get(f)->angle, 2.0f * kPi - 4.0f, 1e-5f);
    // the box turned with it
    const auto got = corners(std::get<Obb>(w.shape_of(e)));
    const auto want = corners(Obb{{0, 0}, {4, 2}, 4.0f - 2.0f * kPi});
    EXPECT_TRUE(same_points({got.begin(), got.end()}, {want.begin(), want.end()}, 1e-4f));
}

TEST(EntityColliders, a_segment_and_a_circle_offset_turn) {
    World w;
    EntityDesc d;
    d.position = {0, 0};
    d.angle = kPi / 2;
    d.collider = Collider::segment({-10, 0}, {10, 2});
    const EntityId seg = w.create(d);
    const Shape s = w.shape_of(seg);
    ASSERT_TRUE(std::holds_alternative<Segment>(s));
    EXPECT_VEC_NEAR(std::get<Segment>(s).a, xy(0, -10), 1e-4f);
    EXPECT_VEC_NEAR(std::get<Segment>(s).b, xy(-2, 10), 1e-4f);

    d.position = {20, 30};
    d.angle = 0.3f;
    d.collider = Collider::circle(4, {10, 0});
    const EntityId circ = w.create(d);
    const Shape c = w.shape_of(circ);
    ASSERT_TRUE(std::holds_alternative<Circle>(c));
    EXPECT_VEC_NEAR(std::get<Circle>(c).center, xy(20, 30) + turned(0.3f, {10, 0}), 1e-4f);
    EXPECT_EQ(std::get<Circle>(c).radius, 4.0f);
}

TEST(EntityColliders, aabb_colliders_never_turn) {
    World w;
    EntityDesc d;
    d.position = {100, 100};
    d.angle = kPi / 2;
    d.collider = Collider::aabb({5, 3}, {10, 0});
    const EntityId e = w.create(d);
    const Shape s = w.shape_of(e);
    ASSERT_TRUE(std::holds_alternative<Aabb>(s));
    EXPECT_VEC_NEAR(std::get<Aabb>(s).min, xy(105, 97), 1e-4f);
    EXPECT_VEC_NEAR(std::get<Aabb>(s).max, xy(115, 103), 1e-4f);
    ASSERT_TRUE(w.set_angle(e, 1.0f));
    const Shape t = w.shape_of(e);
    EXPECT_VEC_NEAR(std::get<Aabb>(t).min, xy(105, 97), 1e-4f);
}

TEST(EntityColliders, masks_round_to_the_nearest_pixel_and_never_turn) {
    const auto mask = std::make_shared<const Mask>(4, 6);
    const Collider centred = Collider::mask(mask);
    ASSERT_TRUE(std::holds_alternative<PlacedMask>(centred.local_shape()));
    EXPECT_EQ(std::get<PlacedMask>(centred.local_shape()).x, -2);
    EXPECT_EQ(std::get<PlacedMask>(centred.local_shape()).y, -3);
    EXPECT_EQ(centred.kind(), ShapeKind::mask);
    EXPECT_EQ(centred.mask_ptr(), mask);

    struct Case {
        Vec2 position;
        float angle;
        int ox, oy;
        int want_x, want_y;
    };
    World w;
    for (const Case c : {Case{{10.4f, 20.6f}, 0.0f, 2, -3, 12, 18}, Case{{10.6f, 20.4f}, 1.0f, 2, -3, 13, 17},
                         Case{{-10.6f, -0.4f}, 2.0f, 0, 0, -11, 0}, Case{{-10.4f, -7.7f}, -1.0f, -1, 1, -11, -7}}) {
        EntityDesc d;
        d.position = c.position;
        d.angle = c.angle;
        d.collider = Collider::mask(mask, c.ox, c.oy);
        const EntityId e = w.create(d);
        const Shape s = w.shape_of(e);
        ASSERT_TRUE(std::holds_alternative<PlacedMask>(s));
        const PlacedMask& pm = std::get<PlacedMask>(s);
        EXPECT_EQ(pm.mask, mask.get());
        EXPECT_EQ(pm.x, c.want_x) << "at " << c.position.x << ", " << c.position.y;
        EXPECT_EQ(pm.y, c.want_y) << "at " << c.position.x << ", " << c.position.y;
    }
    // the default offset centres the mask
    EntityDesc d;
    d.position = {100.2f, 50.9f};
    d.collider = centred;
    const PlacedMask pm = std::get<PlacedMask>(w.shape_of(w.create(d)));
    EXPECT_EQ(pm.x, 98);
    EXPECT_EQ(pm.y, 48);
}

}  // namespace
}  // namespace jostle
