// Determinism: a busy world (hundreds of mixed entities, stacks, kinematic movers, triggers,
// bullets fired from the world's RNG, a handler that destroys and creates) gives the same per-step
// state hashes twice in a run and in every build (golden file), and state_hash() sees every change.
#include <gtest/gtest.h>

#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "jostle/collision.h"
#include "jostle/core/rng.h"
#include "jostle/world.h"

using namespace jostle;

namespace {

constexpr float kDt = 1.0f / 60.0f;
constexpr int kBusySteps = 600;
constexpr float kPi = 3.14159265358979f;
constexpr std::uint64_t kBulletTag = 1ull << 40;
const char* const kGoldenPath = JOSTLE_TEST_DATA "/world_busy.hashes";

// ---------------------------------------------------------------------------------------
// The busy world
// ---------------------------------------------------------------------------------------

struct BusyWorld {
    World world;
    std::array<EntityId, 3> emitters{};
    std::vector<EntityId> movers;

    BusyWorld() : world(make_desc()) {}
    static WorldDesc make_desc() {
        WorldDesc d;
        d.gravity = {0.0f, 400.0f};
        d.seed = 0x5eed2024ull;
        return d;
    }
};

std::shared_ptr<const Mask> blob_mask(int radius) {
    auto m = std::make_shared<Mask>(2 * radius, 2 * radius);
    for (int y = 0; y < 2 * radius; ++y) {
        for (int x = 0; x < 2 * radius; ++x) {
            const int dx = x - radius, dy = y - radius;
            // A disc with a notch cut out of its top, so its pushes are not symmetric.
            if (dx * dx + dy * dy <= radius * radius && !(dy < -radius / 2 && dx > 0 && dx < radius / 2)) {
                m->set(x, y, true);
            }
        }
    }
    return m;
}

Polygon regular_polygon(int sides, float radius, float phase) {
    std::vector<Vec2> pts;
    for (int k = 0; k < sides; ++k) {
        const float a = phase + 2.0f * kPi * static_cast<float>(k) / static_cast<float>(sides);
        pts.push_back({radius * std::cos(a), radius * std::sin(a)});
    }
    std::string error;
    const std::optional<Polygon> p = make_polygon(pts, &error);
    EXPECT_TRUE(p.has_value()) << error;
    return p.value_or(Polygon{});
}

EntityId add_static(World& w, Vec2 p, const Collider& c, float angle = 0.0f, std::uint64_t user = 0) {
    EntityDesc d;
    d.kind = BodyKind::static_body;
    d.position = p;
    d.angle = angle;
    d.collider = c;
    d.user_data = user;
    d.restitution = 0.3f;
    return w.create(d);
}

// What the handler does: a bullet hitting a dynamic body whose user data is a multiple of 3
// breaks it into two small circles (user data from the world's RNG, never a multiple of 3);
// a dynamic body entering a trigger is launched upward and the trigger counts it in its user
// data; some contact_begins set a spin from the RNG.
void on_busy_event(World& w, const Event& e) {
    switch (e.type) {
        case EventType::bullet_hit: {
            const EntityDesc* b = w.get(e.b);
            if (b == nullptr || b->kind != BodyKind::dynamic || e.b_user_data % 3 != 0) break;
            const Vec2 p = b->position;
            w.destroy(e.b);
            for (int k = 0; k < 2; ++k) {
                EntityDesc f;
                f.kind = BodyKind::dynamic;
                f.position = p + Vec2{k == 0 ? -6.0f : 6.0f, 0.0f};
                f.velocity = {w.rng().uniform(-200.0f, 200.0f), w.rng().uniform(-300.0f, 0.0f)};
                f.collider = Collider::circle(4.0f);
                f.restitution = 0.5f;
                f.user_data = 3ull * w.rng().next_u32() + 1;
                w.create(f);
            }
            break;
        }
        case EventType::trigger_enter: {
            const EntityDesc* b = w.get(e.b);
            if (b != nullptr && b->kind == BodyKind::dynamic) w.set_velocity(e.b, {b->velocity.x, -450.0f});
            w.set_user_data(e.a, e.a_user_data + 1);
            break;
        }
        case EventType::contact_begin: {
            if ((e.a_user_data ^ e.b_user_data) % 11 != 0) break;
            const EntityDesc* b = w.get(e.b);
            if (b != nullptr && b->kind == BodyKind::dynamic)
                w.set_angular_velocity(e.b, w.rng().uniform(-3.0f, 3.0f));
            break;
        }
        default:
            break;
    }
}

std::unique_ptr<BusyWorld> make_busy_world() {
    auto bw = std::make_unique<BusyWorld>();
    World& w = bw->world;
    Rng rng(0xb05e5eedull);  // the layout; the world's own RNG drives the run

    // The arena: [-900, 900] x [-700, 700] inside 40 px thick walls.
    add_static(w, {0.0f, 720.0f}, Collider::aabb({940.0f, 20.0f}), 0.0f, 1);
    add_static(w, {0.0f, -720.0f}, Collider::aabb({940.0f, 20.0f}), 0.0f, 2);
    add_static(w, {-920.0f, 0.0f}, Collider::aabb({20.0f, 700.0f}), 0.0f, 3);
    add_static(w, {920.0f, 0.0f}, Collider::aabb({20.0f, 700.0f}), 0.0f, 4);

    // Obstacles of every collider kind across the middle band.
    const auto blob = blob_mask(14);
    for (int k = 0; k < 6; ++k) {
        const float x = -750.0f + 300.0f * static_cast<float>(k);
        add_static(w, {x, 150.0f}, Collider::box({40.0f, 6.0f}), rng.uniform(-0.6f, 0.6f),
                   10 + static_cast<std::uint64_t>(k));
        add_static(w, {x + 100.0f, 260.0f},
                   Collider::polygon(regular_polygon(5 + k % 3, 22.0f, rng.next_float())), 0.0f, 20);
        add_static(w, {x + 50.0f, 380.0f}, Collider::segment({-40.0f, -10.0f}, {40.0f, 10.0f}),
                   rng.uniform(-1.0f, 1.0f), 30);
        add_static(w, {x + 150.0f, 480.0f}, Collider::circle(18.0f), 0.0f, 40);
        add_static(w, {x, 560.0f}, Collider::aabb({30.0f, 10.0f}), 0.0f, 50);
        add_static(w, {std::round(x + 120.0f), 620.0f}, Collider::mask(blob), 0.0f, 60);
    }
    // A wide mask ledge built from rows.
    {
        const std::string_view rows[] = {
            "################################", "################################",
            "..############################..", "....########################....",
            "........################........"};
        std::optional<Mask> ledge = Mask::from_rows(rows);
        EXPECT_TRUE(ledge.has_value());
        add_static(w, {-500.0f, -100.0f},
                   Collider::mask(std::make_shared<Mask>(ledge.value_or(Mask{})), -16, -2), 0.0f, 70);
    }

    // Stacks on the floor (top at y = 700): three columns of boxes.
    for (int c = 0; c < 3; ++c) {
        for (int k = 0; k < 5; ++k) {
            EntityDesc d;
            d.kind = BodyKind::dynamic;
            d.position = {-600.0f + 500.0f * static_cast<float>(c), 685.0f - 30.0f * static_cast<float>(k)};
            d.collider = c == 1 ? Collider::box({15.0f, 15.0f}) : Collider::aabb({15.0f, 15.0f});
            d.user_data = 100 + static_cast<std::uint64_t>(c * 10 + k);
            w.create(d);
        }
    }

    // 240 dynamic bodies on a grid in the upper half, random kinds and velocities.
    for (int gy = 0; gy < 12; ++gy) {
        for (int gx = 0; gx < 20; ++gx) {
            EntityDesc d;
            d.kind = BodyKind::dynamic;
            d.position = {-850.0f + 89.0f * static_cast<float>(gx) + rng.uniform(-8.0f, 8.0f),
                          -650.0f + 55.0f * static_cast<float>(gy) + rng.uniform(-8.0f, 8.0f)};
            d.velocity = {rng.uniform(-250.0f, 250.0f), rng.uniform(-250.0f, 250.0f)};
            d.restitution = rng.next_float() * 0.8f;
            d.friction = rng.next_float();
            d.inverse_mass = rng.uniform(0.2f, 2.0f);
            d.user_data = rng.next_u32();
            switch (rng.below(5)) {
                case 0:
                    d.collider = Collider::aabb({rng.uniform(6.0f, 14.0f), rng.uniform(6.0f, 14.0f)});
                    break;
                case 1:
                    d.collider = Collider::box({rng.uniform(6.0f, 14.0f), rng.uniform(6.0f, 14.0f)});
                    d.angle = rng.uniform(-kPi, kPi);
                    d.angular_velocity = rng.uniform(-2.0f, 2.0f);
                    break;
                case 2: {
                    // Draws in separate statements: function arguments are evaluated in no fixed
                    // order (GCC and clang differ), braced lists left to right.
                    const int sides = 3 + static_cast<int>(rng.below(5));
                    const float radius = rng.uniform(8.0f, 14.0f);
                    d.collider = Collider::polygon(regular_polygon(sides, radius, 0.3f));
                    d.angular_velocity = rng.uniform(-1.0f, 1.0f);
                    break;
                }
                default: {
                    d.collider = Collider::circle(rng.uniform(4.0f, 14.0f));
                    // Some fast circles (swept).
                    if (rng.below(4) == 0)
                        d.velocity = {rng.uniform(-2500.0f, 2500.0f), rng.uniform(-2500.0f, 2500.0f)};
                    break;
                }
            }
            if (rng.below(10) == 0) d.gravity_scale = 0.0f;
            if (rng.below(8) == 0) d.layer = 4;  // a layer the bullets skip
            w.create(d);
        }
    }

    // Kinematic movers: platforms sweeping sideways and one moving vertically.
    for (int k = 0; k < 4; ++k) {
        EntityDesc d;
        d.kind = BodyKind::kinematic;
        d.position = {-600.0f + 400.0f * static_cast<float>(k), 40.0f};
        d.velocity = {k % 2 == 0 ? 120.0f : -120.0f, k == 3 ? 60.0f : 0.0f};
        d.collider = k == 2 ? Collider::box({50.0f, 8.0f}, {}, 0.2f) : Collider::aabb({50.0f, 8.0f});
        d.user_data = 200 + static_cast<std::uint64_t>(k);
        bw->movers.push_back(w.create(d));
    }

    // Triggers: still zones and one moving.
    for (int k = 0; k < 5; ++k) {
        EntityDesc d;
        d.kind = BodyKind::trigger;
        d.position = {-700.0f + 350.0f * static_cast<float>(k), 640.0f};
        d.collider = k % 2 == 0 ? Collider::aabb({60.0f, 40.0f}) : Collider::circle(45.0f);
        if (k == 4) d.velocity = {-80.0f, 0.0f};
        d.user_data = 300 + static_cast<std::uint64_t>(k);
        w.create(d);
    }

    // Emitters: small kinematic circles drifting; bullets ignore their emitter.
    for (int k = 0; k < 3; ++k) {
        EntityDesc d;
        d.kind = BodyKind::kinematic;
        d.position = {-600.0f + 600.0f * static_cast<float>(k), -300.0f};
        d.velocity = {30.0f, 10.0f * static_cast<float>(k)};
        d.collider = Collider::circle(5.0f);
        d.user_data = 400 + static_cast<std::uint64_t>(k);
        bw->emitters[static_cast<std::size_t>(k)] = w.create(d);
    }

    w.set_event_handler(on_busy_event);
    return bw;
}

// One step of the script, decided by the world's step count so a run can be resumed.
void busy_step(BusyWorld& bw) {
    World& w = bw.world;
    const std::uint64_t n = w.step_count();
    if (n % 4 == 0) {
        for (EntityId emitter : bw.emitters) {
            const EntityDesc* e = w.get(emitter);
            if (e == nullptr) continue;
            const float a = w.rng().uniform(-kPi, kPi);
            const float speed = w.rng().uniform(800.0f, 2400.0f);
            EntityDesc b;
            b.kind = BodyKind::bullet;
            b.position = e->position;
            b.velocity = {speed * std::cos(a), speed * std::sin(a)};
            b.on_hit = static_cast<BulletResponse>(w.rng().below(3));
            b.ignore = emitter;
            b.layer = 2;
            b.collides_with = ~4u;
            b.user_data = kBulletTag | n;
            w.create(b);
        }
    }
    if (n % 60 == 30) {
        for (EntityId m : bw.movers) {
            if (const EntityDesc* e = w.get(m)) w.set_velocity(m, -e->velocity);
        }
    }
    if (n % 50 == 10) {
        // Destroy the first dynamic body in slot order and make a new one (slot reuse).
        for (EntityId id : w.entities()) {
            const EntityDesc* e = w.get(id);
            if (e != nullptr && e->kind == BodyKind::dynamic) {
                w.destroy(id);
                break;
            }
        }
        EntityDesc d;
        d.kind = BodyKind::dynamic;
        d.position = {w.rng().uniform(-800.0f, 800.0f), -600.0f};
        d.velocity = {w.rng().uniform(-100.0f, 100.0f), 0.0f};
        d.collider = Collider::circle(w.rng().uniform(5.0f, 12.0f));
        d.user_data = 3ull * n;
        w.create(d);
    }
    w.step(kDt);
}

std::vector<std::uint64_t> run_busy(BusyWorld& bw, int steps) {
    std::vector<std::uint64_t> hashes;
    for (int i = 0; i < steps; ++i) {
        busy_step(bw);
        hashes.push_back(bw.world.state_hash());
    }
    return hashes;
}

std::string hex(std::uint64_t v) {
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
    return buf;
}

// The first step at which two hash lists differ, described; nullopt when equal.
std::optional<std::string> first_divergence(const std::vector<std::uint64_t>& expected,
                                            const std::vector<std::uint64_t>& actual) {
    const std::size_t n = std::min(expected.size(), actual.size());
    for (std::size_t i = 0; i < n; ++i) {
        if (expected[i] != actual[i]) {
            return "first divergent step " + std::to_string(i + 1) + " (of " + std::to_string(n) +
                   "): expected " + hex(expected[i]) + ", got " + hex(actual[i]);
        }
    }
    if (expected.size() != actual.size()) {
        return "lengths differ: expected " + std::to_string(expected.size()) + " steps, got " +
               std::to_string(actual.size());
    }
    return std::nullopt;
}

// ---------------------------------------------------------------------------------------
// A small world for the state hash's sensitivity
// ---------------------------------------------------------------------------------------

struct Small {
    World world;
    EntityId floor, ball, box, bullet, mask_wall;
    Small() : world(make_desc()) {}
    static WorldDesc make_desc() {
        WorldDesc d;
        d.gravity = {0.0f, 980.0f};
        d.seed = 77;
        return d;
    }
};

std::shared_ptr<const Mask> small_mask(bool extra_pixel) {
    auto m = std::make_shared<Mask>(8, 4);
    for (int x = 0; x < 8; ++x) m->set(x, 3, true);
    if (extra_pixel) m->set(2, 0, true);
    return m;
}

std::unique_ptr<Small> make_small(bool extra_pixel = false) {
    auto s = std::make_unique<Small>();
    World& w = s->world;
    EntityDesc floor;
    floor.position = {0.0f, 200.0f};
    floor.collider = Collider::aabb({300.0f, 10.0f});
    s->floor = w.create(floor);
    EntityDesc ball;
    ball.kind = BodyKind::dynamic;
    ball.position = {-50.0f, 100.0f};
    ball.velocity = {20.0f, -5.0f};
    ball.angular_velocity = 0.5f;
    ball.collider = Collider::circle(10.0f, {1.0f, 0.0f});
    ball.inverse_mass = 0.5f;
    ball.restitution = 0.25f;
    ball.friction = 0.4f;
    ball.gravity_scale = 0.75f;
    ball.layer = 3;
    ball.collides_with = 0xffu;
    ball.user_data = 1234;
    s->ball = w.create(ball);
    EntityDesc box;
    box.kind = BodyKind::dynamic;
    box.position = {60.0f, 150.0f};
    box.angle = 0.25f;
    box.collider = Collider::box({10.0f, 6.0f});
    s->box = w.create(box);
    EntityDesc bullet;
    bullet.kind = BodyKind::bullet;
    bullet.position = {-200.0f, 0.0f};
    bullet.velocity = {1000.0f, 300.0f};
    bullet.on_hit = BulletResponse::stop;
    bullet.ignore = s->ball;
    s->bullet = w.create(bullet);
    EntityDesc mw;
    mw.position = {150.0f, 180.0f};
    mw.collider = Collider::mask(small_mask(extra_pixel), 0, 0);
    s->mask_wall = w.create(mw);
    return s;
}

}  // namespace

TEST(Determinism, BusyWorldTwiceGivesTheSamePerStepHashes) {
    auto first = make_busy_world();
    auto second = make_busy_world();
    EXPECT_GE(first->world.entity_count(), 300u) << "the busy world should hold hundreds of entities";
    EXPECT_EQ(first->world.state_hash(), second->world.state_hash());
    const std::vector<std::uint64_t> a = run_busy(*first, kBusySteps);
    const std::vector<std::uint64_t> b = run_busy(*second, kBusySteps);
    const auto diff = first_divergence(a, b);
    EXPECT_FALSE(diff.has_value()) << *diff;
    // The run really was busy: bullets were fired and things hit, broke and were replaced.
    EXPECT_GE(first->world.entity_count(), 300u);
    // Hashes change from step to step (the world moves).
    int repeats = 0;
    for (std::size_t i = 1; i < a.size(); ++i) repeats += a[i] == a[i - 1] ? 1 : 0;
    EXPECT_EQ(repeats, 0);
}

TEST(Determinism, BusyWorldMovedMidRunContinuesIdentically) {
    auto reference = make_busy_world();
    const std::vector<std::uint64_t> expected = run_busy(*reference, kBusySteps / 2);
    auto original = make_busy_world();
    std::vector<std::uint64_t> actual = run_busy(*original, kBusySteps / 4);
    BusyWorld moved_into;  // a different world, replaced by move assignment
    moved_into.world = std::move(original->world);
    moved_into.emitters = original->emitters;
    moved_into.movers = original->movers;
    const std::vector<std::uint64_t> rest = run_busy(moved_into, kBusySteps / 2 - kBusySteps / 4);
    actual.insert(actual.end(), rest.begin(), rest.end());
    const auto diff = first_divergence(expected, actual);
    EXPECT_FALSE(diff.has_value()) << *diff;
}

// The golden is compared by every build (Release, Debug, sanitizers, clang), which makes this
// the cross-build determinism check. JOSTLE_UPDATE_GOLDEN=1 rewrites it instead (atomically).
TEST(Determinism, BusyWorldMatchesTheGoldenHashes) {
    auto bw = make_busy_world();
    const std::vector<std::uint64_t> hashes = run_busy(*bw, kBusySteps);

    const char* update = std::getenv("JOSTLE_UPDATE_GOLDEN");
    if (update != nullptr && std::string_view(update) == "1") {
        const std::filesystem::path path(kGoldenPath);
        std::filesystem::path tmp = path;
        tmp += ".tmp";
        {
            std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
            ASSERT_TRUE(out) << "cannot write " << tmp;
            out << "# state_hash() after each of the " << kBusySteps
                << " steps of the busy world in tests/world/determinism_test.cpp. Regenerate only when a "
                   "change"
                   " is meant to change the simulation: JOSTLE_UPDATE_GOLDEN=1 world_tests"
                   " --gtest_filter='Determinism.BusyWorldMatchesTheGoldenHashes'\n";
            for (std::uint64_t h : hashes) out << hex(h) << '\n';
            out.flush();
            ASSERT_TRUE(out) << "writing " << tmp << " failed";
        }
        std::error_code ec;
        std::filesystem::rename(tmp, path, ec);
        ASSERT_FALSE(ec) << "cannot rename " << tmp << " to " << path << ": " << ec.message();
        GTEST_SKIP() << "rewrote " << path;
    }

    std::ifstream in(kGoldenPath);
    ASSERT_TRUE(in) << "missing golden " << kGoldenPath << "; create it with JOSTLE_UPDATE_GOLDEN=1";
    std::vector<std::uint64_t> golden;
    std::string line;
    int line_number = 0;
    while (std::getline(in, line)) {
        ++line_number;
        if (line.empty() || line[0] == '#') continue;
        std::uint64_t v = 0;
        const auto [end, ec] = std::from_chars(line.data(), line.data() + line.size(), v, 16);
        ASSERT_TRUE(ec == std::errc{} && end == line.data() + line.size())
            << kGoldenPath << ":" << line_number << ": not a hex hash: \"" << line << "\"";
        golden.push_back(v);
    }
    ASSERT_EQ(golden.size(), static_cast<std::size_t>(kBusySteps))
        << kGoldenPath << " holds the wrong number of steps";
    const auto diff = first_divergence(golden, hashes);
    EXPECT_FALSE(diff.has_value()) << *diff << " (golden " << kGoldenPath << ")";
}

TEST(Determinism, StateHashIsEqualForWorldsBuiltByTheSameCalls) {
    auto a = make_small();
    auto b = make_small();
    EXPECT_EQ(a->world.state_hash(), b->world.state_hash());
    for (int i = 0; i < 120; ++i) {
        a->world.step(kDt);
        b->world.step(kDt);
        ASSERT_EQ(a->world.state_hash(), b->world.state_hash()) << "after step " << i + 1;
    }
}

TEST(Determinism, StateHashSeesEveryEntityField) {
    const std::uint64_t base = make_small()->world.state_hash();

    struct Mutation {
        const char* what;
        void (*apply)(Small&);
    };
    // Each changes one field of one entity through set() (the whole state) or a setter.
    auto with = [](Small& s, EntityId id, auto change) {
        EntityDesc d = *s.world.get(id);
        change(d);
        ASSERT_TRUE(s.world.set(id, d));
    };
    const Mutation mutations[] = {
        {"position.x (one ulp)",
         [](Small& s) {
             s.world.set_position(s.ball, {std::nextafter(-50.0f, 0.0f), 100.0f});
         }},
        {"position.y",
         [](Small& s) {
             s.world.set_position(s.ball, {-50.0f, 100.5f});
         }},
        {"angle", [](Small& s) { s.world.set_angle(s.box, 0.2500001f); }},
        {"velocity.x",
         [](Small& s) {
             s.world.set_velocity(s.ball, {21.0f, -5.0f});
         }},
        {"velocity.y",
         [](Small& s) {
             s.world.set_velocity(s.ball, {20.0f, -5.5f});
         }},
        {"angular_velocity", [](Small& s) { s.world.set_angular_velocity(s.ball, 0.6f); }},
        {"user_data", [](Small& s) { s.world.set_user_data(s.ball, 1235); }},
        {"collider radius",
         [](Small& s) {
             s.world.set_collider(s.ball, Collider::circle(10.5f, {1.0f, 0.0f}));
         }},
        {"collider offset",
         [](Small& s) {
             s.world.set_collider(s.ball, Collider::circle(10.0f, {0.0f, 1.0f}));
         }},
        {"collider kind",
         [](Small& s) {
             s.world.set_collider(s.ball, Collider::aabb({10.0f, 10.0f}, {1.0f, 0.0f}));
         }},
        {"box collider angle",
         [](Small& s) {
             s.world.set_collider(s.box, Collider::box({10.0f, 6.0f}, {}, 0.1f));
         }},
        {"mask collider offset",
         [](Small& s) { s.world.set_collider(s.mask_wall, Collider::mask(small_mask(false), 1, 0)); }},
    };
    for (const Mutation& m : mutations) {
        auto s = make_small();
        m.apply(*s);
        EXPECT_NE(s->world.state_hash(), base) << "changing " << m.what << " left state_hash() unchanged";
    }

    struct DescMutation {
        const char* what;
        int entity;  // 0 floor, 1 ball, 2 box, 3 bullet
        void (*change)(EntityDesc&);
    };
    const DescMutation desc_mutations[] = {
        {"kind (dynamic -> kinematic)", 1, [](EntityDesc& d) { d.kind = BodyKind::kinematic; }},
        {"kind (static -> trigger)", 0, [](EntityDesc& d) { d.kind = BodyKind::trigger; }},
        {"inverse_mass", 1, [](EntityDesc& d) { d.inverse_mass = 0.25f; }},
        {"restitution", 1, [](EntityDesc& d) { d.restitution = 0.5f; }},
        {"friction", 1, [](EntityDesc& d) { d.friction = 0.41f; }},
        {"gravity_scale", 1, [](EntityDesc& d) { d.gravity_scale = 1.0f; }},
        {"layer", 1, [](EntityDesc& d) { d.layer = 1; }},
        {"collides_with", 1, [](EntityDesc& d) { d.collides_with = 0x7fu; }},
        {"on_hit", 3, [](EntityDesc& d) { d.on_hit = BulletResponse::ricochet; }},
        {"ignore", 3, [](EntityDesc& d) { d.ignore = EntityId{}; }},
        {"position via set()", 2, [](EntityDesc& d) { d.position.x += 0.25f; }},
    };
    for (const DescMutation& m : desc_mutations) {
        auto s = make_small();
        const EntityId ids[] = {s->floor, s->ball, s->box, s->bullet};
        with(*s, ids[m.entity], m.change);
        EXPECT_NE(s->world.state_hash(), base) << "changing " << m.what << " left state_hash() unchanged";
    }
}

TEST(Determinism, StateHashSeesTheRngStepCountIdsAndContacts) {
    const std::uint64_t base = make_small()->world.state_hash();
    {
        auto s = make_small();
        s->world.rng().next_u32();
        EXPECT_NE(s->world.state_hash(), base) << "advancing the RNG left state_hash() unchanged";
    }
    {
        // A different seed is a different RNG state.
        WorldDesc d = Small::make_desc();
        World a(d);
        d.seed += 1;
        World b(d);
        EXPECT_NE(a.state_hash(), b.state_hash()) << "worlds seeded differently hash equal";
    }
    {
        // Only the step count changes: a world with one static entity steps once.
        World w;
        EntityDesc d;
        d.collider = Collider::aabb({5.0f, 5.0f});
        w.create(d);
        const std::uint64_t before = w.state_hash();
        w.step(kDt);
        EXPECT_EQ(w.step_count(), 1u);
        EXPECT_NE(w.state_hash(), before) << "the step count is not hashed";
    }
    {
        // The id allocator: destroying and re-creating an entity gives the same entity state in
        // the same slot, but a new generation.
        auto s = make_small();
        const EntityDesc bullet = *s->world.get(s->bullet);
        ASSERT_TRUE(s->world.destroy(s->bullet));
        const EntityId again = s->world.create(bullet);
        EXPECT_EQ(again.index, s->bullet.index);
        EXPECT_NE(again.generation, s->bullet.generation);
        EXPECT_NE(s->world.state_hash(), base) << "the id allocator is not hashed";
    }
    {
        // A destroyed entity is no longer hashed as live.
        auto s = make_small();
        s->world.destroy(s->box);
        EXPECT_NE(s->world.state_hash(), base);
    }
    {
        // The contacts carried to the next step: two worlds with equal entities, step count and
        // RNG, where only one has a ball touching the floor in its last step.
        auto make = []() {
            auto w = std::make_unique<World>();
            EntityDesc floor;
            floor.position = {0.0f, 20.0f};
            floor.collider = Collider::aabb({100.0f, 10.0f});
            w->create(floor);
            EntityDesc ball;
            ball.kind = BodyKind::dynamic;
            ball.collider = Collider::circle(10.0f);
            ball.gravity_scale = 0.0f;
            const EntityId id = w->create(ball);
            return std::make_pair(std::move(w), id);
        };
        auto [touching, ball_a] = make();
        auto [apart, ball_b] = make();
        apart->set_position(ball_b, {500.0f, 0.0f});
        touching->step(kDt);
        apart->step(kDt);
        touching->set_position(ball_a, {0.0f, 0.0f});
        touching->set_velocity(ball_a, {0.0f, 0.0f});
        apart->set_position(ball_b, {0.0f, 0.0f});
        apart->set_velocity(ball_b, {0.0f, 0.0f});
        EXPECT_EQ(touching->contacts().size(), 1u);
        EXPECT_EQ(apart->contacts().size(), 0u);
        EXPECT_NE(touching->state_hash(), apart->state_hash()) << "the carried contacts are not hashed";
    }
    {
        // A non-finite position is still hashed.
        auto s = make_small();
        s->world.set_position(s->box, {std::nanf(""), 150.0f});
        EXPECT_NE(s->world.state_hash(), base);
    }
}

TEST(Determinism, StateHashSeesTheMaskPixels) {
    // Two worlds whose mask walls differ in one pixel behave differently from then on.
    EXPECT_NE(make_small(false)->world.state_hash(), make_small(true)->world.state_hash());
}
