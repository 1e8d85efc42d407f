// World resolution tests: hand-built overlaps of a dynamic body of every collider kind against a
// static body of every kind (the push is the collision module's MTD), mass splits, kinematic and
// trigger bodies, the velocity response (restitution, its threshold, friction), filters and NaN.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <limits>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "jostle/collision.h"
#include "jostle/world.h"

namespace jostle {

// Readable failure messages.
static void PrintTo(const EntityId& id, std::ostream* os) { *os << "{" << id.index << ", " << id.generation << "}"; }
static void PrintTo(const Vec2& v, std::ostream* os) { *os << "(" << v.x << ", " << v.y << ")"; }

namespace {

constexpr float kDt = 1.0f / 60.0f;
constexpr float kPosTol = 1e-4f;  // px
constexpr float kVelTol = 1e-3f;  // px/s
constexpr float kNan = std::numeric_limits<float>::quiet_NaN();

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

// ---------------------------------------------------------------------------------------
// Building colliders, and placing them independently of the world (so the expected MTD does
// not come from the code under test)
// ---------------------------------------------------------------------------------------

// A w x h mask with the pixels whose centres lie in the inscribed ellipse set.
std::shared_ptr<const Mask> ellipse_mask(int w, int h) {
    Mask m(w, h);
    const float rx = static_cast<float>(w) * 0.5f;
    const float ry = static_cast<float>(h) * 0.5f;
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const float px = (static_cast<float>(x) + 0.5f - rx) / rx;
            const float py = (static_cast<float>(y) + 0.5f - ry) / ry;
            if (px * px + py * py <= 1.0f) m.set(x, y, true);
        }
    }
    return std::make_shared<const Mask>(std::move(m));
}

std::shared_ptr<const Mask> full_mask(int w, int h) {
    Mask m(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) m.set(x, y, true);
    return std::make_shared<const Mask>(std::move(m));
}

Polygon polygon_of(const std::vector<Vec2>& pts) {
    std::string error;
    const std::optional<Polygon> p = make_polygon(pts, &error);
    EXPECT_TRUE(p.has_value()) << error;
    return p.value_or(Polygon{});
}

Vec2 turned(float angle, Vec2 v) {
    const float c = std::cos(angle);
    const float s = std::sin(angle);
    return {c * v.x - s * v.y, s * v.x + c * v.y};
}

int nearest_pixel(float v) { return static_cast<int>(std::lround(v)); }

// A collider, the entity angle it is tested at, and where its shape lands for a position.
struct Spec {
    std::string name;
    Collider collider;
    float angle = 0.0f;
    std::function<Shape(Vec2)> place;
};

Spec aabb_spec(std::string name, Vec2 half, Vec2 offset = {}, float entity_angle = 0.0f) {
    return {std::move(name), Collider::aabb(half, offset), entity_angle,
            [=](Vec2 p) -> Shape { return Aabb{p + offset - half, p + offset + half}; }};
}

Spec box_spec(std::string name, Vec2 half, Vec2 offset, float box_angle, float entity_angle) {
    return {std::move(name), Collider::box(half, offset, box_angle), entity_angle,
            [=](Vec2 p) -> Shape { return Obb{p + turned(entity_angle, offset), half, entity_angle + box_angle}; }};
}

Spec polygon_spec(std::string name, const std::vector<Vec2>& local, float entity_angle) {
    return {std::move(name), Collider::polygon(polygon_of(local)), entity_angle, [=](Vec2 p) -> Shape {
                std::vector<Vec2> world;
                for (Vec2 v : local) world.push_back(p + turned(entity_angle, v));
                return polygon_of(world);
            }};
}

Spec circle_spec(std::string name, float radius, Vec2 offset, float entity_angle) {
    return {std::move(name), Collider::circle(radius, offset), entity_angle,
            [=](Vec2 p) -> Shape { return Circle{p + turned(entity_angle, offset), radius}; }};
}

Spec segment_spec(std::string name, Vec2 a, Vec2 b, float entity_angle) {
    return {std::move(name), Collider::segment(a, b), entity_angle,
            [=](Vec2 p) -> Shape { return Segment{p + turned(entity_angle, a), p + turned(entity_angle, b)}; }};
}

// Mask with an explicit offset; the entity angle must not turn it.
Spec mask_spec(std::string name, std::shared_ptr<const Mask> mask, int ox, int oy, float entity_angle) {
    return {std::move(name), Collider::mask(mask, ox, oy), entity_angle, [mask, ox, oy](Vec2 p) -> Shape {
                return PlacedMask{mask.get(), nearest_pixel(p.x + static_cast<float>(ox)),
                                  nearest_pixel(p.y + static_cast<float>(oy))};
            }};
}

std::vector<Spec> static_specs() {
    std::vector<Spec> s;
    s.push_back(aabb_spec("aabb", {20, 15}));
    s.push_back(aabb_spec("aabb_offset_turned_entity", {20, 15}, {3, -4}, 0.6f));  // never turns
    s.push_back(box_spec("obb", {20, 15}, {}, 0.3f, 0.0f));
    s.push_back(box_spec("obb_turned_entity", {20, 15}, {3, -2}, 0.1f, 0.4f));
    s.push_back(polygon_spec("polygon", {{-18, -10}, {0, -20}, {20, -8}, {16, 14}, {-14, 12}}, 0.2f));
    s.push_back(circle_spec("circle", 18.0f, {2, -3}, 0.7f));
    s.push_back(segment_spec("segment", {-30, 0}, {30, 6}, 0.1f));
    s.push_back(mask_spec("mask", ellipse_mask(30, 24), -15, -12, 0.9f));
    return s;
}

std::vector<Spec> dynamic_specs() {
    std::vector<Spec> s;
    s.push_back(aabb_spec("aabb", {8, 6}));
    s.push_back(box_spec("box", {8, 6}, {}, 0.0f, 0.0f));
    s.push_back(box_spec("box_rotated", {8, 6}, {}, 0.4f, 0.0f));
    s.push_back(box_spec("box_turned_entity", {8, 6}, {1, 2}, 0.2f, -0.5f));
    s.push_back(polygon_spec("polygon", {{-7, -3}, {-2, -8}, {6, -6}, {9, 1}, {3, 7}, {-6, 5}}, 0.3f));
    s.push_back(circle_spec("circle", 7.0f, {1, -2}, 0.5f));
    s.push_back(mask_spec("mask", ellipse_mask(12, 10), -6, -5, 0.0f));
    return s;
}

EntityDesc desc_of(BodyKind kind, Vec2 position, const Collider& collider, float angle = 0.0f) {
    EntityDesc d;
    d.kind = kind;
    d.position = position;
    d.angle = angle;
    d.collider = collider;
    return d;
}

EntityDesc box_desc(BodyKind kind, Vec2 position, Vec2 half) {
    return desc_of(kind, position, Collider::aabb(half));
}

Vec2 position_of(const World& w, EntityId id) {
    const EntityDesc* d = w.get(id);
    EXPECT_NE(d, nullptr);
    return d ? d->position : Vec2{kNan, kNan};
}

Vec2 velocity_of(const World& w, EntityId id) {
    const EntityDesc* d = w.get(id);
    EXPECT_NE(d, nullptr);
    return d ? d->velocity : Vec2{kNan, kNan};
}

// The dynamic spec's position above the static shape, lowered in quarter pixels until the two
// overlap by 2.5 px or more (never a .5 coordinate, so mask rounding is unambiguous).
std::optional<Vec2> overlapping_position(const Spec& dyn, const Shape& fixed, Vec2 fixed_pos) {
    for (int k = 0; k < 600; ++k) {
        const Vec2 p{fixed_pos.x + 1.7f, fixed_pos.y - 80.1f + 0.25f * static_cast<float>(k)};
        const Manifold m = collide(dyn.place(p), fixed);
        if (m.hit && m.depth >= 2.5f) return p;
    }
    return std::nullopt;
}

// ---------------------------------------------------------------------------------------
// Every dynamic kind against every static kind
// ---------------------------------------------------------------------------------------

TEST(ResolutionMatrix, dynamic_body_moves_by_the_mtd_and_the_static_one_stays) {
    const Vec2 s_pos{100, 100};
    int cases = 0;
    for (const Spec& st : static_specs()) {
        const Shape fixed = st.place(s_pos);
        for (const Spec& dy : dynamic_specs()) {
            const std::optional<Vec2> start = overlapping_position(dy, fixed, s_pos);
            ASSERT_TRUE(start.has_value()) << dy.name << " never overlaps static " << st.name;
            const Vec2 d_pos = *start;
            const Shape moving = dy.place(d_pos);
            for (const bool dynamic_first : {true, false}) {
                SCOPED_TRACE("dynamic " + dy.name + " vs static " + st.name +
                             (dynamic_first ? " (dynamic has the lower id)" : " (static has the lower id)"));
                // The narrowphase calls collide(lower id, higher id); the dynamic body moves out
                // of the static one by the whole MTD.
                Vec2 expected_move;
                Manifold lower_first;
                if (dynamic_first) {
                    lower_first = collide(moving, fixed);
                    expected_move = lower_first.mtd();
                } else {
                    lower_first = collide(fixed, moving);
                    expected_move = lower_first.depth * lower_first.normal;
                }
                ASSERT_TRUE(lower_first.hit);
                ASSERT_GE(lower_first.depth, 2.5f);
                ASSERT_LE(lower_first.depth, 8.0f);

                World w;
                const EntityDesc sd = desc_of(BodyKind::static_body, s_pos, st.collider, st.angle);
                const EntityDesc dd = desc_of(BodyKind::dynamic, d_pos, dy.collider, dy.angle);
                EntityId s_id, d_id;
                if (dynamic_first) {
                    d_id = w.create(dd);
                    s_id = w.create(sd);
                } else {
                    s_id = w.create(sd);
                    d_id = w.create(dd);
                }
                w.step(kDt);

                EXPECT_VEC_NEAR(position_of(w, d_id), d_pos + expected_move, kPosTol);
                EXPECT_EQ(position_of(w, s_id), s_pos);
                EXPECT_EQ(w.get(s_id)->angle, st.angle);
                EXPECT_EQ(w.get(d_id)->angle, dy.angle);
                EXPECT_VEC_NEAR(velocity_of(w, d_id), Vec2{}, kVelTol);

                // The contact holds the narrowphase result before resolution, normal from the
                // lower id toward the higher.
                ASSERT_EQ(w.contacts().size(), 1u);
                const Contact& c = w.contacts()[0];
                EXPECT_EQ(c.a, dynamic_first ? d_id : s_id);
                EXPECT_EQ(c.b, dynamic_first ? s_id : d_id);
                EXPECT_NEAR(c.depth, lower_first.depth, kPosTol);
                EXPECT_VEC_NEAR(c.normal, lower_first.normal, kPosTol);
                EXPECT_FALSE(c.trigger);
                ASSERT_EQ(w.events().size(), 1u);
                EXPECT_EQ(w.events()[0].type, EventType::contact_begin);
                ++cases;
            }
        }
    }
    EXPECT_EQ(cases, 8 * 7 * 2);
}

// A fully hand-computed anchor for the matrix: box on box, circle on circle, mask on box.
TEST(ResolutionMatrix, hand_computed_pushes) {
    {
        World w;  // aabb [0,20]x[0,20] static; dynamic [17,37]x[5,25]: x overlap 3, y overlap 15
        const EntityId s = w.create(box_desc(BodyKind::static_body, {10, 10}, {10, 10}));
        const EntityId d = w.create(box_desc(BodyKind::dynamic, {27, 15}, {10, 10}));
        w.step(kDt);
        EXPECT_VEC_NEAR(position_of(w, d), xy(30, 15), kPosTol);
        EXPECT_EQ(position_of(w, s), xy(10, 10));
    }
    {
        World w;  // circles r 10 and 10, centres 15 apart along (0.8, 0.6): depth 5
        const EntityId s = w.create(desc_of(BodyKind::static_body, {0, 0}, Collider::circle(10)));
        const EntityId d = w.create(desc_of(BodyKind::dynamic, {12, 9}, Collider::circle(10)));
        w.step(kDt);
        EXPECT_VEC_NEAR(position_of(w, d), xy(16, 12), kPosTol);
        EXPECT_EQ(position_of(w, s), xy(0, 0));
    }
    {
        World w;  // a full 10x10 mask over pixels [0,10)x[0,10); a static box [8,30]x[-20,30]
        const EntityId d = w.create(desc_of(BodyKind::dynamic, {5, 5}, Collider::mask(full_mask(10, 10), -5, -5)));
        const EntityId s = w.create(desc_of(BodyKind::static_body, {19, 5}, Collider::aabb({11, 25})));
        w.step(kDt);
        // pixel centres 8.5 and 9.5 are inside: the mask moves 2 px left
        EXPECT_VEC_NEAR(position_of(w, d), xy(3, 5), kPosTol);
        EXPECT_EQ(position_of(w, s), xy(19, 5));
    }
}

// ---------------------------------------------------------------------------------------
// Mass split between dynamic bodies; kinematic, static and trigger bodies
// ---------------------------------------------------------------------------------------

struct SplitCase {
    float inv_a;
    float inv_b;
};

TEST(ResolutionMass, two_dynamic_boxes_split_the_mtd_by_inverse_mass) {
    // A [-10,10]^2 at (0,0), B at (17,3): collide(A, B) = depth 3 along (1, 0).
    for (const SplitCase sc : {SplitCase{1, 1}, SplitCase{1, 3}, SplitCase{3, 1}, SplitCase{0, 1}, SplitCase{1, 0},
                               SplitCase{2, 2}}) {
        SCOPED_TRACE("inverse masses " + std::to_string(sc.inv_a) + " and " + std::to_string(sc.inv_b));
        World w;
        EntityDesc da = box_desc(BodyKind::dynamic, {0, 0}, {10, 10});
        da.inverse_mass = sc.inv_a;
        EntityDesc db = box_desc(BodyKind::dynamic, {17, 3}, {10, 10});
        db.inverse_mass = sc.inv_b;
        const EntityId a = w.create(da);
        const EntityId b = w.create(db);
        w.step(kDt);
        const float share_a = sc.inv_a / (sc.inv_a + sc.inv_b);
        const float share_b = sc.inv_b / (sc.inv_a + sc.inv_b);
        EXPECT_VEC_NEAR(position_of(w, a), xy(-3.0f * share_a, 0), kPosTol);
        EXPECT_VEC_NEAR(position_of(w, b), xy(17.0f + 3.0f * share_b, 3), kPosTol);
    }
}

TEST(ResolutionMass, two_dynamic_circles_split_the_mtd_by_inverse_mass) {
    // r 10 and r 10, centres (0,0) and (12,9): depth 5 along (0.8, 0.6). Inverse masses 1 and 3:
    // A moves 5/4 back, B (inverse mass 3) moves 15/4 forward.
    World w;
    EntityDesc da = desc_of(BodyKind::dynamic, {0, 0}, Collider::circle(10));
    da.inverse_mass = 1.0f;
    EntityDesc db = desc_of(BodyKind::dynamic, {12, 9}, Collider::circle(10));
    db.inverse_mass = 3.0f;
    const EntityId a = w.create(da);
    const EntityId b = w.create(db);
    w.step(kDt);
    EXPECT_VEC_NEAR(position_of(w, a), xy(-1.0f, -0.75f), kPosTol);
    EXPECT_VEC_NEAR(position_of(w, b), xy(15.0f, 11.25f), kPosTol);
}

TEST(ResolutionKinds, kinematic_pushes_a_dynamic_body_and_is_never_pushed) {
    {
        // At rest: the dynamic box takes the whole MTD, even when it is light.
        World w;
        EntityDesc dd = box_desc(BodyKind::dynamic, {27, 15}, {10, 10});
        dd.inverse_mass = 5.0f;
        const EntityId d0 = w.create(dd);
        const EntityId k = w.create(box_desc(BodyKind::kinematic, {10, 10}, {10, 10}));
        w.step(kDt);
        EXPECT_VEC_NEAR(position_of(w, d0), xy(30, 15), kPosTol);
        EXPECT_EQ(position_of(w, k), xy(10, 10));
    }
    {
        // Moving: the kinematic box moves by its velocity (2 px), overlaps the dynamic one by
        // 1 px, pushes it 1 px and hands it its normal velocity.
        World w;
        EntityDesc kd = box_desc(BodyKind::kinematic, {0, 0}, {10, 10});
        kd.velocity = {120, 0};
        kd.friction = 0.0f;
        const EntityId k = w.create(kd);
        EntityDesc dd = box_desc(BodyKind::dynamic, {21, 0.5f}, {10, 10});
        dd.friction = 0.0f;
        const EntityId d = w.create(dd);
        w.step(kDt);
        EXPECT_VEC_NEAR(position_of(w, k), xy(2, 0), kPosTol);
        EXPECT_VEC_NEAR(velocity_of(w, k), xy(120, 0), 0.0f);
        EXPECT_VEC_NEAR(position_of(w, d), xy(22, 0.5f), kPosTol);
        EXPECT_VEC_NEAR(velocity_of(w, d), xy(120, 0), kVelTol);
    }
}

TEST(ResolutionKinds, a_kinematic_body_passes_into_a_static_one_unpushed) {
    World w;
    const EntityId s = w.create(box_desc(BodyKind::static_body, {0, 0}, {10, 10}));
    EntityDesc kd = box_desc(BodyKind::kinematic, {19, 0}, {10, 10});
    kd.velocity = {-120, 0};
    const EntityId k = w.create(kd);
    w.step(kDt);
    EXPECT_VEC_NEAR(position_of(w, k), xy(17, 0), kPosTol);
    EXPECT_EQ(position_of(w, s), xy(0, 0));
    EXPECT_VEC_NEAR(velocity_of(w, k), xy(-120, 0), 0.0f);
    ASSERT_EQ(w.events().size(), 1u);
    EXPECT_EQ(w.events()[0].type, EventType::contact_begin);
}

TEST(ResolutionKinds, static_bodies_never_move_even_with_a_velocity) {
    // A static body's velocity field does not make it move, so it does not move anything
    // either: the dynamic box it overlaps is pushed out by the MTD and stays at rest.
    World w;
    EntityDesc sd = box_desc(BodyKind::static_body, {5, 7}, {10, 10});
    sd.velocity = {300, -200};
    sd.angular_velocity = 2.0f;
    const EntityId s = w.create(sd);
    const EntityId d = w.create(box_desc(BodyKind::dynamic, {22, 7}, {10, 10}));  // 3 px deep along x
    w.step(kDt);
    EXPECT_EQ(position_of(w, s), xy(5, 7));
    EXPECT_EQ(w.get(s)->angle, 0.0f);
    EXPECT_VEC_NEAR(position_of(w, d), xy(25, 7), kPosTol);
    EXPECT_VEC_NEAR(velocity_of(w, d), xy(0, 0), kVelTol);
    for (int i = 0; i < 2; ++i) w.step(kDt);
    EXPECT_EQ(position_of(w, s), xy(5, 7));
    EXPECT_VEC_NEAR(position_of(w, d), xy(25, 7), kPosTol);
}

TEST(ResolutionKinds, triggers_are_never_pushed_and_never_push_but_report_enter) {
    World w;
    EntityDesc dd = box_desc(BodyKind::dynamic, {5, 0}, {10, 10});
    dd.velocity = {60, 0};
    dd.user_data = 7;
    const EntityId d = w.create(dd);  // the lower id
    EntityDesc td = box_desc(BodyKind::trigger, {0, 0}, {10, 10});
    td.velocity = {-60, 0};
    td.user_data = 8;
    const EntityId t = w.create(td);
    w.step(kDt);
    // Both moved by their velocities only.
    EXPECT_VEC_NEAR(position_of(w, d), xy(6, 0), kPosTol);
    EXPECT_VEC_NEAR(position_of(w, t), xy(-1, 0), kPosTol);
    EXPECT_VEC_NEAR(velocity_of(w, d), xy(60, 0), 0.0f);
    EXPECT_VEC_NEAR(velocity_of(w, t), xy(-60, 0), 0.0f);
    ASSERT_EQ(w.events().size(), 1u);
    const Event& e = w.events()[0];
    EXPECT_EQ(e.type, EventType::trigger_enter);
    EXPECT_EQ(e.a, t);  // a is the trigger, though it has the higher id
    EXPECT_EQ(e.b, d);
    EXPECT_EQ(e.a_user_data, 8u);
    EXPECT_EQ(e.b_user_data, 7u);
    // trigger [-11,9]x[-10,10], box [-4,16]x[-10,10]: overlap 13 along x, from the trigger to the box
    EXPECT_NEAR(e.depth, 13.0f, kPosTol);
    EXPECT_VEC_NEAR(e.normal, xy(1, 0), 1e-6f);
    ASSERT_EQ(w.contacts().size(), 1u);
    EXPECT_TRUE(w.contacts()[0].trigger);
}

TEST(ResolutionKinds, a_trigger_over_a_static_body_reports_enter_and_neither_moves) {
    World w;
    const EntityId s = w.create(box_desc(BodyKind::static_body, {0, 0}, {10, 10}));
    const EntityId t = w.create(box_desc(BodyKind::trigger, {4, 0}, {10, 10}));
    w.step(kDt);
    EXPECT_EQ(position_of(w, s), xy(0, 0));
    EXPECT_EQ(position_of(w, t), xy(4, 0));
    ASSERT_EQ(w.events().size(), 1u);
    EXPECT_EQ(w.events()[0].type, EventType::trigger_enter);
    EXPECT_EQ(w.events()[0].a, t);
    EXPECT_EQ(w.events()[0].b, s);
}

TEST(ResolutionKinds, two_triggers_never_meet) {
    World w;
    w.create(box_desc(BodyKind::trigger, {0, 0}, {10, 10}));
    w.create(box_desc(BodyKind::trigger, {4, 0}, {10, 10}));
    w.step(kDt);
    EXPECT_TRUE(w.events().empty());
    EXPECT_TRUE(w.contacts().empty());
}

// ---------------------------------------------------------------------------------------
// Velocity response: a box falling onto a static floor whose top is y = 100
// ---------------------------------------------------------------------------------------

struct Drop {
    Vec2 position{0, 89};
    Vec2 velocity{0, 120};
    float box_restitution = 0.0f;
    float floor_restitution = 0.0f;
    float box_friction = 0.0f;
    float floor_friction = 0.0f;
    float threshold = 30.0f;
};

struct DropResult {
    Vec2 position;
    Vec2 velocity;
};

DropResult drop(const Drop& c) {
    WorldDesc wd;
    wd.restitution_threshold = c.threshold;
    World w(wd);
    EntityDesc box = box_desc(BodyKind::dynamic, c.position, {10, 10});
    box.velocity = c.velocity;
    box.restitution = c.box_restitution;
    box.friction = c.box_friction;
    const EntityId b = w.create(box);
    EntityDesc floor = box_desc(BodyKind::static_body, {0, 150}, {200, 50});
    floor.restitution = c.floor_restitution;
    floor.friction = c.floor_friction;
    const EntityId f = w.create(floor);
    w.step(kDt);
    EXPECT_EQ(position_of(w, f), xy(0, 150));
    EXPECT_EQ(w.events().size(), 1u);
    return {position_of(w, b), velocity_of(w, b)};
}

TEST(ResolutionVelocity, restitution_zero_removes_the_normal_velocity) {
    // 89 + 2 = 91: 1 px into the floor, pushed back to 90.
    const DropResult r = drop(Drop{});
    EXPECT_VEC_NEAR(r.position, xy(0, 90), kPosTol);
    EXPECT_VEC_NEAR(r.velocity, xy(0, 0), kVelTol);
}

TEST(ResolutionVelocity, restitution_one_bounces_back_at_full_speed) {
    Drop c;
    c.box_restitution = 1.0f;
    const DropResult r = drop(c);
    EXPECT_VEC_NEAR(r.position, xy(0, 90), kPosTol);
    EXPECT_VEC_NEAR(r.velocity, xy(0, -120), kVelTol);
}

TEST(ResolutionVelocity, the_larger_restitution_of_the_two_applies) {
    Drop c;
    c.floor_restitution = 1.0f;
    EXPECT_VEC_NEAR(drop(c).velocity, xy(0, -120), kVelTol);
    c.box_restitution = 0.5f;
    c.floor_restitution = 0.25f;
    EXPECT_VEC_NEAR(drop(c).velocity, xy(0, -60), kVelTol);
}

TEST(ResolutionVelocity, no_bounce_below_the_restitution_threshold) {
    Drop c;
    c.position = {0, 89.9f};
    c.velocity = {0, 20};  // 20 px/s < 30 px/s
    c.box_restitution = 1.0f;
    const DropResult r = drop(c);
    EXPECT_VEC_NEAR(r.position, xy(0, 90), kPosTol);
    EXPECT_VEC_NEAR(r.velocity, xy(0, 0), kVelTol);
    // The same approach bounces once the threshold is lower.
    c.threshold = 10.0f;
    EXPECT_VEC_NEAR(drop(c).velocity, xy(0, -20), kVelTol);
}

TEST(ResolutionVelocity, friction_zero_keeps_the_tangential_velocity_exactly) {
    Drop c;
    c.velocity = {100, 120};
    c.box_friction = 0.0f;
    c.floor_friction = 0.5f;  // sqrt(0 * 0.5) = 0
    const DropResult r = drop(c);
    EXPECT_EQ(r.velocity.x, 100.0f);
    EXPECT_NEAR(r.velocity.y, 0.0f, kVelTol);
    EXPECT_VEC_NEAR(r.position, xy(100.0f * kDt, 90), kPosTol);
}

TEST(ResolutionVelocity, coulomb_friction_with_the_geometric_mean_coefficient) {
    // The normal impulse removes 120 px/s; friction sqrt(0.25 * 1) = 0.5 removes at most 60 px/s
    // of the 100 px/s sliding, and that much of this step's motion.
    Drop c;
    c.velocity = {100, 120};
    c.box_friction = 0.25f;
    c.floor_friction = 1.0f;
    const DropResult r = drop(c);
    EXPECT_VEC_NEAR(r.velocity, xy(40, 0), kVelTol);
    EXPECT_NEAR(r.position.x, 40.0f * kDt, 1e-3f);
    EXPECT_NEAR(r.position.y, 90.0f, kPosTol);
}

TEST(ResolutionVelocity, friction_holds_a_slow_slide_without_creep) {
    Drop c;
    c.velocity = {30, 120};
    c.box_friction = 0.5f;
    c.floor_friction = 0.5f;
    const DropResult r = drop(c);
    EXPECT_VEC_NEAR(r.velocity, xy(0, 0), kVelTol);
    EXPECT_VEC_NEAR(r.position, xy(0, 90), 1e-3f);
}

// ---------------------------------------------------------------------------------------
// Masks, filters, NaN
// ---------------------------------------------------------------------------------------

TEST(ResolutionMask, a_dynamic_mask_at_a_fractional_position_moves_whole_pixels) {
    const std::shared_ptr<const Mask> blob = ellipse_mask(12, 10);
    const Vec2 start{50.3f, 40.8f};  // pixel (0,0) at (44, 36)
    World w;
    const EntityId d = w.create(desc_of(BodyKind::dynamic, start, Collider::mask(blob)));
    // floor [20,80]x[43.25,69.75]: the mask rows with centres 43.5, 44.5, 45.5 are inside, so
    // the mask moves 3 px up
    const Aabb floor_box{{20, 43.25f}, {80, 69.75f}};
    const EntityId s = w.create(desc_of(BodyKind::static_body, {50, 56.5f}, Collider::aabb({30, 13.25f})));
    const PlacedMask placed{blob.get(), 44, 36};
    const Manifold m = collide(Shape{placed}, Shape{floor_box});
    ASSERT_TRUE(m.hit);
    EXPECT_VEC_NEAR(m.mtd(), xy(0, -3), 0.0f);
    w.step(kDt);
    const Vec2 moved = position_of(w, d) - start;
    EXPECT_NEAR(moved.x, std::round(moved.x), kPosTol);
    EXPECT_NEAR(moved.y, std::round(moved.y), kPosTol);
    EXPECT_VEC_NEAR(moved, m.mtd(), kPosTol);
    EXPECT_EQ(position_of(w, s), xy(50, 56.5f));
}

TEST(ResolutionMask, two_dynamic_masks_split_an_odd_depth_into_whole_pixels) {
    // Full 10x10 masks with offset 0: A over pixel columns [0,10), B over [7,17): 3 columns
    // overlap, so the MTD is 3 px along x. An even split would be 1.5 px each, which is not a
    // whole pixel. Whole-pixel pushes that sum to the MTD leave B's pixels exactly 10 columns
    // right of A's.
    const std::shared_ptr<const Mask> square = full_mask(10, 10);
    struct Start {
        Vec2 a, b;
    };
    for (const Start st : {Start{{0, 0}, {7, 0}}, Start{{0.4f, 0}, {6.9f, 0}}}) {
        SCOPED_TRACE("a at x " + std::to_string(st.a.x) + ", b at x " + std::to_string(st.b.x));
        World w;
        const EntityId a = w.create(desc_of(BodyKind::dynamic, st.a, Collider::mask(square, 0, 0)));
        const EntityId b = w.create(desc_of(BodyKind::dynamic, st.b, Collider::mask(square, 0, 0)));
        w.step(kDt);
        const Vec2 da = position_of(w, a) - st.a;
        const Vec2 db = position_of(w, b) - st.b;
        for (const float v : {da.x, da.y, db.x, db.y}) EXPECT_NEAR(v, std::round(v), kPosTol);
        EXPECT_LE(da.x, 0.0f);
        EXPECT_GE(db.x, 0.0f);
        const PlacedMask ma = std::get<PlacedMask>(w.shape_of(a));
        const PlacedMask mb = std::get<PlacedMask>(w.shape_of(b));
        EXPECT_FALSE(overlaps(ma, mb));
        EXPECT_EQ(mb.x - ma.x, 10) << "pixels of a at " << ma.x << ", of b at " << mb.x;
        EXPECT_EQ(ma.y, 0);
        EXPECT_EQ(mb.y, 0);
    }
}

struct LayerCase {
    const char* name;
    std::uint32_t dyn_layer, dyn_collides_with, static_layer, static_collides_with;
    bool meet;
};

TEST(ResolutionFilter, layer_bits_must_match_both_ways) {
    for (const LayerCase lc : {
             LayerCase{"defaults", 1, 0xffffffffu, 1, 0xffffffffu, true},
             LayerCase{"dynamic does not collide with the static layer", 1, ~2u, 2, 0xffffffffu, false},
             LayerCase{"static does not collide with the dynamic layer", 1, 0xffffffffu, 2, ~1u, false},
             LayerCase{"matching custom layers", 4, 8, 8, 4, true},
             LayerCase{"one way only", 4, 8, 8, 1, false},
         }) {
        SCOPED_TRACE(lc.name);
        World w;
        EntityDesc dd = box_desc(BodyKind::dynamic, {27, 15}, {10, 10});
        dd.layer = lc.dyn_layer;
        dd.collides_with = lc.dyn_collides_with;
        EntityDesc sd = box_desc(BodyKind::static_body, {10, 10}, {10, 10});
        sd.layer = lc.static_layer;
        sd.collides_with = lc.static_collides_with;
        const EntityId d = w.create(dd);
        w.create(sd);
        w.step(kDt);
        EXPECT_VEC_NEAR(position_of(w, d), lc.meet ? xy(30, 15) : xy(27, 15), kPosTol);
        EXPECT_EQ(w.contacts().size(), lc.meet ? 1u : 0u);
        EXPECT_EQ(w.events().size(), lc.meet ? 1u : 0u);
    }
}

TEST(ResolutionFilter, ignore_stops_a_pair_from_either_side) {
    for (const bool dynamic_ignores : {true, false}) {
        SCOPED_TRACE(dynamic_ignores ? "the dynamic body ignores the static one" : "the static body ignores");
        World w;
        const EntityId s = w.create(box_desc(BodyKind::static_body, {10, 10}, {10, 10}));
        EntityDesc dd = box_desc(BodyKind::dynamic, {27, 15}, {10, 10});
        if (dynamic_ignores) dd.ignore = s;
        const EntityId d = w.create(dd);
        if (!dynamic_ignores) {
            EntityDesc sd = *w.get(s);
            sd.ignore = d;
            ASSERT_TRUE(w.set(s, sd));
        }
        // A third body that is not ignored still meets the dynamic one.
        const EntityId other = w.create(box_desc(BodyKind::static_body, {27, 33}, {10, 10}));
        w.step(kDt);
        // only the other static box (overlap 2 along y) pushes it
        EXPECT_VEC_NEAR(position_of(w, d), xy(27, 13), kPosTol);
        ASSERT_EQ(w.contacts().size(), 1u);
        EXPECT_EQ(w.contacts()[0].b, other);
    }
}

TEST(ResolutionNan, a_nan_position_collides_with_nothing_and_is_still_hashed) {
    auto build = [](float nan_velocity) {
        World w;
        // static box at NaN: the dynamic box at the origin would overlap it anywhere
        EntityDesc nan_static = box_desc(BodyKind::static_body, {kNan, 0}, {1000, 1000});
        w.create(nan_static);
        // a dynamic box at NaN over a static floor
        EntityDesc nan_dyn = box_desc(BodyKind::dynamic, {kNan, kNan}, {10, 10});
        nan_dyn.velocity = {nan_velocity, 0};
        w.create(nan_dyn);
        w.create(box_desc(BodyKind::dynamic, {0, 0}, {10, 10}));
        // a static circle with a NaN radius overlapping the dynamic box
        w.create(desc_of(BodyKind::static_body, {5, 0}, Collider::circle(kNan)));
        return w;
    };
    World w = build(1.0f);
    const std::vector<EntityId> ids = w.entities();
    ASSERT_EQ(ids.size(), 4u);
    for (int i = 0; i < 5; ++i) w.step(kDt);
    EXPECT_EQ(position_of(w, ids[2]), xy(0, 0));
    EXPECT_TRUE(w.contacts().empty());
    EXPECT_TRUE(w.events().empty());
    EXPECT_TRUE(w.alive(ids[1]));
    EXPECT_TRUE(std::isnan(position_of(w, ids[1]).x));
    EXPECT_TRUE(w.query_point({0, 0}) == std::vector<EntityId>{ids[2]});
    EXPECT_FALSE(w.cast_segment({-50, 0}, {-20, 0}).has_value());

    // The hash is reproducible and covers the entity at NaN.
    World same = build(1.0f);
    World other = build(2.0f);
    for (int i = 0; i < 5; ++i) {
        same.step(kDt);
        other.step(kDt);
    }
    EXPECT_EQ(w.state_hash(), same.state_hash());
    EXPECT_NE(w.state_hash(), other.state_hash());
}

}  // namespace
}  // namespace jostle

namespace jostle {
namespace {

// The position passes push along the narrowphase's contacts; a pair a push brings together
// joins them in the same step.

// The deepest overlap among the world's bodies (collide() of the placed colliders).
float deepest_overlap(const World& w, const std::vector<EntityId>& ids) {
    float deepest = 0.0f;
    for (std::size_t i = 0; i < ids.size(); ++i) {
        for (std::size_t j = i + 1; j < ids.size(); ++j) {
            const EntityDesc& a = *w.get(ids[i]);
            const EntityDesc& b = *w.get(ids[j]);
            const Manifold m = collide(a.collider.placed(a.position, a.angle), b.collider.placed(b.position, b.angle));
            if (m.hit) deepest = std::fmax(deepest, m.depth);
        }
    }
    return deepest;
}

EntityDesc still_box(Vec2 at, BodyKind kind = BodyKind::dynamic) {
    return {.kind = kind, .position = at, .collider = Collider::aabb({5.0f, 5.0f}), .gravity_scale = 0.0f};
}

// A pushes B (A deep in B) into C, 0.5 px beyond B at the narrowphase: B-C was no contact then,
// and is settled within the slop by the end of the step.
TEST(ResolutionPasses, a_pair_a_push_brings_together_is_settled_in_the_same_step) {
    World w;
    const EntityId a = w.create(still_box({0.0f, 0.0f}));
    const EntityId b = w.create(still_box({6.0f, 0.0f}));  // 4 px into A
    const EntityId c = w.create(still_box({16.5f, 0.0f}));  // 0.5 px beyond B
    w.step(kDt);
    EXPECT_LE(deepest_overlap(w, {a, b, c}), WorldDesc{}.slop);
    // C was pushed: B went right by 2 px (half of A's 4), into C by 1.5 px.
    EXPECT_GT(w.get(c)->position.x, 16.5f + 0.5f);
}

// With one pass, a crowd of pushes is left unsettled, but not inside a wall: B, pushed by A
// into a static wall it did not touch at the narrowphase, ends outside it.
TEST(ResolutionPasses, contacts_with_something_immovable_have_the_last_word) {
    World w(WorldDesc{.relaxation_passes = 1});
    const EntityId wall = w.create(still_box({17.0f, 0.0f}, BodyKind::static_body));  // left face at 12
    const EntityId a = w.create(still_box({0.0f, 0.0f}));
    const EntityId b = w.create(still_box({6.0f, 0.0f}));  // 4 px into A, 1 px from the wall: pushed 1 px into it
    w.step(kDt);
    const EntityDesc& eb = *w.get(b);
    const Manifold m = collide(w.get(wall)->collider.placed(w.get(wall)->position, 0.0f), eb.collider.placed(eb.position, 0.0f));
    EXPECT_TRUE(!m.hit || m.depth <= WorldDesc{}.slop) << "B is " << m.depth << " px inside the wall";
    EXPECT_LE(w.get(b)->position.x, 7.0f + WorldDesc{}.slop);
    EXPECT_EQ(w.get(wall)->position.x, 17.0f);
    EXPECT_LT(w.get(a)->position.x, 0.0f);
}

// A NaN velocity stays with its body: a static floor under it and another box resting on the
// same floor keep finite positions and velocities (the floor is immovable for impulses: its
// velocity as contacts see it stays zero, whatever a NaN impulse would add).
TEST(ResolutionNan, a_nan_velocity_does_not_spread_to_the_bodies_it_touches) {
    // Found by review: the box under a NaN box (and everything under that) took the NaN
    // through the friction impulse, std::clamp passing a NaN through, even with friction 0.
    for (const float friction : {0.0f, 0.5f}) {
        World w(WorldDesc{.gravity = {0.0f, 980.0f}});
        w.create({.position = {0.0f, 100.0f}, .collider = Collider::aabb({200.0f, 10.0f})});
        std::vector<EntityId> stack;
        for (int k = 0; k < 4; ++k) {
            stack.push_back(w.create({.kind = BodyKind::dynamic, .position = {0.0f, 80.0f - 20.0f * static_cast<float>(k)},
                                      .collider = Collider::aabb({10.0f, 10.0f}), .friction = friction}));
        }
        for (int i = 0; i < 60; ++i) w.step(kDt);
        ASSERT_EQ(w.contacts().size(), 4u) << friction;  // a resting stack: every contact carried
        w.set_velocity(stack.back(), {kNan, 0.0f});
        for (int i = 0; i < 3; ++i) w.step(kDt);
        for (std::size_t k = 0; k + 1 < stack.size(); ++k) {
            const EntityDesc* body = w.get(stack[k]);
            EXPECT_TRUE(is_finite(body->position) && is_finite(body->velocity)) << friction << " box " << k;
        }
    }
}

TEST(ResolutionNan, a_nan_velocity_does_not_spread_through_a_static_floor) {
    World w(WorldDesc{.gravity = {0.0f, 980.0f}});
    const EntityId floor = w.create({.position = {0.0f, 20.0f}, .collider = Collider::aabb({200.0f, 10.0f})});
    const EntityId x = w.create({.kind = BodyKind::dynamic, .position = {-50.0f, 5.0f}, .collider = Collider::aabb({5.0f, 5.0f})});
    const EntityId y = w.create({.kind = BodyKind::dynamic, .position = {50.0f, 5.0f}, .collider = Collider::aabb({5.0f, 5.0f})});
    for (int i = 0; i < 10; ++i) w.step(kDt);
    ASSERT_EQ(w.contacts().size(), 2u);  // both resting: the next step carries both contacts
    w.set_velocity(x, {kNan, 0.0f});
    // A new box lands on the floor in the same step (its first contact with it).
    const EntityId z = w.create({.kind = BodyKind::dynamic, .position = {0.0f, 5.5f}, .collider = Collider::aabb({5.0f, 5.0f})});
    for (int i = 0; i < 3; ++i) w.step(kDt);
    EXPECT_EQ(position_of(w, floor), xy(0.0f, 20.0f));
    EXPECT_TRUE(std::isfinite(w.get(floor)->velocity.x) && std::isfinite(w.get(floor)->velocity.y));
    for (const EntityId id : {y, z}) {
        EXPECT_TRUE(std::isfinite(position_of(w, id).x) && std::isfinite(position_of(w, id).y)) << id.index;
        EXPECT_TRUE(std::isfinite(w.get(id)->velocity.x) && std::isfinite(w.get(id)->velocity.y)) << id.index;
    }
}

// A circle inside a polygon whose nearest vertex happens to lie along the face normal is a
// face contact, pushed out through the face (not taken for a circle at that vertex).
TEST(ResolutionPasses, a_circle_inside_a_polygon_is_pushed_out_through_the_face) {
    World w(WorldDesc{.gravity = {0.0f, 0.0f}});
    const std::vector<Vec2> tri{{0.0f, 0.0f}, {10.0f, -15.0f}, {10.0f, 15.0f}};
    const EntityId t = w.create({.position = {0.0f, 0.0f}, .collider = Collider::polygon(*make_polygon(tri))});
    const EntityId c = w.create({.kind = BodyKind::dynamic, .position = {9.0f, 0.0f}, .collider = Collider::circle(2.0f)});
    w.step(kDt);
    const EntityDesc& tri_body = *w.get(t);
    const EntityDesc& circle = *w.get(c);
    const Manifold m = collide(tri_body.collider.placed(tri_body.position, 0.0f), circle.collider.placed(circle.position, 0.0f));
    EXPECT_TRUE(!m.hit || m.depth <= WorldDesc{}.slop) << "the circle is " << m.depth << " px inside";
    EXPECT_NEAR(circle.position.x, 12.0f, 1e-3f);
}

// A circle at a static box's corner, pushed sideways by another body into the face's region
// during the passes, is not left deeper than the slop: its contact follows it from the corner
// to the face.
TEST(ResolutionPasses, a_circle_pushed_from_a_corner_onto_the_face_is_settled) {
    World w(WorldDesc{.gravity = {0.0f, 0.0f}});
    const EntityId box = w.create({.position = {-20.0f, 20.0f}, .collider = Collider::aabb({20.0f, 20.0f})});  // corner at (0, 0)
    const EntityId c = w.create({.kind = BodyKind::dynamic, .position = {0.5f, -9.95f}, .collider = Collider::circle(10.0f)});
    // A box 4 px into the circle's right side: the pair splits the push, 2 px to the left each.
    w.create({.kind = BodyKind::dynamic, .position = {10.5f + 5.0f - 4.0f, -9.95f}, .collider = Collider::aabb({5.0f, 5.0f}),
              .inverse_mass = 1.0f / (3.14159265f * 100.0f)});
    w.step(kDt);
    const EntityDesc& b = *w.get(box);
    const EntityDesc& circle = *w.get(c);
    const Manifold m = collide(b.collider.placed(b.position, 0.0f), circle.collider.placed(circle.position, 0.0f));
    EXPECT_LT(circle.position.x, 0.0f) << "the push reached the face's region";
    EXPECT_TRUE(!m.hit || m.depth <= WorldDesc{}.slop) << "the circle is " << m.depth << " px inside the box";
}

// A circle of negative radius meets nothing (the MANUAL), fast or not: its inverted bounds get
// no proxy even when a fast circle's bounds would also cover its motion (a Debug build used to
// stop there on an assertion about the packed bounds).
TEST(ResolutionNan, a_fast_circle_of_negative_radius_meets_nothing) {
    World w(WorldDesc{.gravity = {0.0f, 0.0f}});
    w.create({.position = {0.0f, 0.0f}, .collider = Collider::aabb({50.0f, 50.0f})});
    const EntityId c = w.create(
        {.kind = BodyKind::dynamic, .position = {0.0f, 0.0f}, .velocity = {600.0f, 600.0f}, .collider = Collider::circle(-1.0f)});
    for (int i = 0; i < 3; ++i) w.step(kDt);
    EXPECT_TRUE(w.contacts().empty());
    EXPECT_TRUE(w.events().empty());
    EXPECT_VEC_NEAR(position_of(w, c), xy(30.0f, 30.0f), 1e-3f);  // 600 px/s for 3 steps, unhindered
}

}  // namespace
}  // namespace jostle
