// arena_test.cpp: the arena game through the Game/Simulation interfaces: driving, turning,
// firing with its cooldown, pickups, cannons, the variables, events and dumps expectations
// read, determinism of the state hash (and that it covers the score), and level errors.
#include "arena.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include "jostle/core/error.h"
#include "jostle/replay/replay.h"
#include "test_support.h"

namespace jostle::game {
namespace {

namespace fs = std::filesystem;

constexpr float kDt = 1.0f / 60.0f;

InputFrame hold(std::initializer_list<Action> actions) {
    InputFrame f;
    for (Action a : actions) f.held |= 1u << a;
    return f;
}

// An open room: the player at (100, 150) facing +x, a wall on the right from x = 380.
constexpr const char* kOpenRoom =
    "jostle-level 1\n"
    "size 400 300\n"
    "player 100 150 0\n"
    "wall left 0 0 8 300\n"
    "wall right 380 0 390 300\n";

// An assets folder of our own in the test's temporary folder, with levels written by the test.
class Arena : public ::testing::Test {
protected:
    void SetUp() override {
        fs::create_directories(dir_.path() / "levels");
        write_level("open", kOpenRoom);
    }

    void write_level(const std::string& name, const std::string& text) {
        std::ofstream((dir_.path() / "levels" / (name + ".level")).string(), std::ios::binary) << text;
    }
    std::string assets() const { return dir_.path().string(); }
    std::unique_ptr<Simulation> start(const std::string& level, Rules rules = {}) const {
        return ArenaGame(assets(), rules).start(level, 1, 60);
    }

    const test::TempFolder dir_{"arena"};
};

// A field of an entity's dump ("" when the entity or field is missing).
std::string field(const Simulation& sim, std::string_view entity, std::string_view name) {
    for (const EntityDump& d : sim.dump()) {
        if (d.name != entity) continue;
        for (const StateField& f : d.fields) {
            if (f.name == name) return f.value;
        }
    }
    return "";
}

float float_field(const Simulation& sim, std::string_view entity, std::string_view name) {
    const std::string text = field(sim, entity, name);
    EXPECT_FALSE(text.empty()) << entity << "." << name;
    return text.empty() ? NAN : std::stof(text);
}

Vec2 position(const Simulation& sim, std::string_view name) {
    const std::optional<Vec2> p = sim.entity_position(name);
    EXPECT_TRUE(p.has_value()) << name << " is gone";
    return p.value_or(Vec2{NAN, NAN});
}

double variable(const Simulation& sim, std::string_view name) { return sim.variable(name).value_or(NAN); }

TEST_F(Arena, TheGamesVocabularyAndLevels) {
    const ArenaGame source(JOSTLE_ASSETS_DIR);
    EXPECT_EQ(source.vocabulary().actions, (std::vector<std::string>{"left", "right", "up", "down", "fire"}));
    EXPECT_NE(std::find(source.vocabulary().levels.begin(), source.vocabulary().levels.end(), "arena"),
              source.vocabulary().levels.end());
    EXPECT_EQ(source.level_path("arena"), std::string(JOSTLE_ASSETS_DIR) + "/levels/arena.level");
    write_level("b_second", kOpenRoom);
    const ArenaGame mine(assets());
    EXPECT_EQ(mine.vocabulary().levels, (std::vector<std::string>{"b_second", "open"}));  // sorted
}

TEST_F(Arena, LevelHashIsAFingerprintOfTheFile) {
    const ArenaGame game(assets());
    const std::string hash = game.level_hash("open");
    ASSERT_EQ(hash.size(), 16u);
    EXPECT_EQ(hash.find_first_not_of("0123456789abcdef"), std::string::npos);
    EXPECT_EQ(game.level_hash("open"), hash);
    write_level("open", std::string(kOpenRoom) + "# one more comment\n");
    EXPECT_NE(game.level_hash("open"), hash);
}

TEST_F(Arena, WhatExpectationsCanName) {
    const auto sim = start("open");
    EXPECT_EQ(sim->kinds(), (std::vector<std::string>{"player", "wall", "crate", "rock", "pickup", "cannon", "bullet", "ball",
                                                       "prop", "blob"}));
    EXPECT_EQ(sim->variables(), (std::vector<std::string>{"score", "shots", "balls", "fastest", "touches"}));
    EXPECT_EQ(sim->events(), (std::vector<std::string>{"fire", "bullet_hit", "rock_hit", "pickup", "cannon_fire", "player_hit",
                                                        "ricochet", "blob_touch"}));
    EXPECT_EQ(sim->ticks_done(), 0);
    EXPECT_EQ(sim->level_size().x, 400.0f);
    EXPECT_EQ(sim->level_size().y, 300.0f);
    EXPECT_EQ(sim->count("player"), 1);
    EXPECT_EQ(sim->count("wall"), 2);
    EXPECT_EQ(sim->count("bullet"), 0);
    EXPECT_EQ(sim->count("dragon"), 0);
    EXPECT_EQ(variable(*sim, "score"), 0.0);
    EXPECT_FALSE(sim->variable("lives").has_value());
    EXPECT_FALSE(sim->event_happened("fire"));
    EXPECT_FALSE(sim->event_happened("nonsense"));
    EXPECT_EQ(position(*sim, "player").x, 100.0f);
    EXPECT_TRUE(sim->entity_position("left").has_value());  // walls have positions (their centre)
    EXPECT_EQ(position(*sim, "left").x, 4.0f);
    EXPECT_FALSE(sim->entity_position("nobody").has_value());
    // The dump: the game's variables first, then every live entity but the walls.
    const std::vector<EntityDump> dump = sim->dump();
    ASSERT_EQ(dump.size(), 2u);
    EXPECT_EQ(dump[0].name, "game");
    ASSERT_EQ(dump[0].fields.size(), 5u);
    EXPECT_EQ(dump[0].fields[0].name, "score");
    EXPECT_EQ(dump[0].fields[3].name, "touches");
    EXPECT_EQ(dump[0].fields[4].name, "cooldown");
    EXPECT_EQ(dump[1].name, "player");
    EXPECT_EQ(field(*sim, "player", "kind"), "player");
    EXPECT_EQ(field(*sim, "player", "x"), "100");
    EXPECT_EQ(field(*sim, "player", "y"), "150");
}

TEST_F(Arena, HoldingUpDrivesForwardAtTheDriveSpeed) {
    const auto sim = start("open");
    for (int t = 0; t < 10; ++t) {
        sim->tick(hold({kUp}));
        const Vec2 p = position(*sim, "player");
        EXPECT_NEAR(p.x, 100.0f + 2.5f * static_cast<float>(t + 1), 1e-3f) << "tick " << t;  // 150 px/s at 60 Hz
        EXPECT_EQ(p.y, 150.0f);
    }
    EXPECT_EQ(sim->ticks_done(), 10);
    EXPECT_NEAR(float_field(*sim, "player", "vx"), 150.0f, 1e-3f);
    EXPECT_EQ(float_field(*sim, "player", "vy"), 0.0f);
    // Let go: the ship coasts, keeping 0.85 of its speed per tick.
    const float x = position(*sim, "player").x;
    sim->tick(InputFrame{});
    EXPECT_NEAR(position(*sim, "player").x - x, 150.0f * 0.85f * kDt, 1e-3f);
    EXPECT_NEAR(float_field(*sim, "player", "vx"), 127.5f, 1e-3f);
    // Down reverses at the reverse speed.
    sim->tick(hold({kDown}));
    EXPECT_NEAR(float_field(*sim, "player", "vx"), -75.0f, 1e-3f);
}

TEST_F(Arena, DrivingFollowsTheShipsAngle) {
    write_level("down", "jostle-level 1\nsize 400 300\nplayer 100 100 1.5707964\n");
    const auto sim = start("down");
    for (int t = 0; t < 4; ++t) sim->tick(hold({kUp}));
    const Vec2 p = position(*sim, "player");
    EXPECT_NEAR(p.x, 100.0f, 1e-3f);
    EXPECT_NEAR(p.y, 110.0f, 1e-3f);  // angle pi/2 is +y: down the screen
}

TEST_F(Arena, LeftTurnsCounterClockwiseOnScreenAndRightClockwise) {
    const auto sim = start("open");
    for (int t = 0; t < 10; ++t) {
        sim->tick(hold({kLeft}));
        EXPECT_NEAR(float_field(*sim, "player", "angle"), -3.0f * kDt * static_cast<float>(t + 1), 1e-5f) << "tick " << t;
    }
    EXPECT_EQ(position(*sim, "player").x, 100.0f);  // turning alone does not move
    sim->tick(hold({kLeft, kRight}));                // both: no turn
    EXPECT_NEAR(float_field(*sim, "player", "angle"), -0.5f, 1e-5f);
    for (int t = 0; t < 5; ++t) sim->tick(hold({kRight}));
    EXPECT_NEAR(float_field(*sim, "player", "angle"), -0.25f, 1e-5f);

    // Left while driving: the ship heads up the screen (y decreases, as y points down).
    const auto left = start("open");
    for (int t = 0; t < 20; ++t) left->tick(hold({kLeft, kUp}));
    EXPECT_LT(position(*left, "player").y, 140.0f);
    EXPECT_GT(position(*left, "player").x, 120.0f);
    const auto right = start("open");
    for (int t = 0; t < 20; ++t) right->tick(hold({kRight, kUp}));
    EXPECT_GT(position(*right, "player").y, 160.0f);
    EXPECT_NEAR(position(*right, "player").y - 150.0f, 150.0f - position(*left, "player").y, 1e-3f);  // mirror images
}

TEST_F(Arena, FireSpawnsABulletAndObeysTheCooldown) {
    const auto sim = start("open");
    EXPECT_FALSE(sim->event_happened("fire"));
    // Held for 17 ticks: shots on ticks 0, 8 and 16 (the cooldown is 8 ticks).
    for (int t = 0; t <= 16; ++t) {
        sim->tick(hold({kFire}));
        const double expected_shots = t < 8 ? 1 : t < 16 ? 2 : 3;
        EXPECT_EQ(variable(*sim, "shots"), expected_shots) << "tick " << t;
        EXPECT_EQ(sim->count("bullet"), static_cast<std::int64_t>(expected_shots)) << "tick " << t;
        if (t == 0) {
            EXPECT_TRUE(sim->event_happened("fire"));
            // 15 px ahead of the ship, then one step at 900 px/s.
            EXPECT_NEAR(position(*sim, "bullet_1").x, 130.0f, 1e-3f);
            EXPECT_EQ(position(*sim, "bullet_1").y, 150.0f);
            EXPECT_NEAR(float_field(*sim, "bullet_1", "vx"), 900.0f, 1e-3f);
            EXPECT_EQ(field(*sim, "bullet_1", "kind"), "bullet");
            EXPECT_EQ(field(*sim, "bullet_1", "lifetime"), "89");
            EXPECT_EQ(field(*sim, "game", "cooldown"), "8");
        }
    }
    EXPECT_NEAR(position(*sim, "bullet_1").x, 115.0f + 17.0f * 15.0f, 1e-2f);
    EXPECT_FALSE(sim->event_happened("bullet_hit"));
    // Tick 17: bullet_1 reaches the wall at x = 380 and ricochets straight back.
    sim->tick(InputFrame{});
    EXPECT_TRUE(sim->event_happened("bullet_hit"));
    EXPECT_TRUE(sim->event_happened("ricochet"));
    EXPECT_FALSE(sim->event_happened("rock_hit"));
    EXPECT_NEAR(float_field(*sim, "bullet_1", "vx"), -900.0f, 1e-3f);
    EXPECT_EQ(field(*sim, "bullet_1", "bounces"), "1");
    EXPECT_EQ(sim->count("bullet"), 3);
    EXPECT_EQ(variable(*sim, "shots"), 3.0);
    EXPECT_EQ(variable(*sim, "score"), 0.0);  // walls score nothing
    // Back across the room (372 px at 15 px a tick) to the left wall: the second and last
    // bounce, then across again: the third wall hit ends it, long before its lifetime would.
    int gone_at = -1;
    for (int t = 18; t < 89 && gone_at < 0; ++t) {
        sim->tick(InputFrame{});
        if (t == 44) {
            EXPECT_EQ(field(*sim, "bullet_1", "bounces"), "0");
        }
        if (!sim->entity_position("bullet_1")) gone_at = t;
    }
    EXPECT_EQ(gone_at, 67);
}

// The names an expectation may use: the level's things and the player from the start, bullet_N
// and ball_N once the Nth is fired, and still after it is gone.
TEST_F(Arena, EntityNamedKnowsEveryNameTheRunHasHad) {
    const auto sim = start("open");
    for (const char* name : {"player", "left"}) EXPECT_TRUE(sim->entity_named(name)) << name;
    for (const char* name : {"nobody", "bullet_1", "bullet_0", "ball_1", "bullet_", "bullet", "Player"}) {
        EXPECT_FALSE(sim->entity_named(name)) << name;
    }
    sim->tick(hold({kFire}));
    EXPECT_TRUE(sim->entity_named("bullet_1"));
    for (const char* name : {"bullet_2", "bullet_01", "bullet_1x", "bullet_+1", "bullet_-1", "ball_1"}) {
        EXPECT_FALSE(sim->entity_named(name)) << name;
    }
    for (int t = 1; t < 89 && sim->entity_position("bullet_1"); ++t) sim->tick(InputFrame{});
    EXPECT_FALSE(sim->entity_position("bullet_1").has_value());
    EXPECT_TRUE(sim->entity_named("bullet_1"));  // gone, but it was there
    // Names the run can give at some time, and those it never gives.
    for (const char* name : {"player", "left", "bullet_1", "bullet_99999", "ball_7"}) EXPECT_TRUE(sim->entity_name_possible(name)) << name;
    for (const char* name : {"nobody", "bullet_0", "bullet_01", "ball_", "ball_x", "Player"}) {
        EXPECT_FALSE(sim->entity_name_possible(name)) << name;
    }
}

TEST_F(Arena, TappingFireInsideTheCooldownDoesNothing) {
    const auto shots_after = [&](const std::vector<int>& fire_ticks, Rules rules = {}) {
        const auto sim = start("open", rules);
        for (int t = 0; t <= fire_ticks.back(); ++t) {
            const bool fire = std::find(fire_ticks.begin(), fire_ticks.end(), t) != fire_ticks.end();
            sim->tick(fire ? hold({kFire}) : InputFrame{});
        }
        return variable(*sim, "shots");
    };
    EXPECT_EQ(shots_after({0, 7}), 1.0);
    EXPECT_EQ(shots_after({0, 8}), 2.0);
    EXPECT_EQ(shots_after({0, 3, 8, 9, 16}), 3.0);
    EXPECT_EQ(shots_after({0, 2, 4}, Rules{.fire_cooldown = 2}), 3.0);
    EXPECT_EQ(shots_after({0, 1}, Rules{.fire_cooldown = 2}), 1.0);
}

TEST_F(Arena, DrivingIntoAPickupCollectsIt) {
    // The ship's nose is 14 px ahead of it; the coin's edge is at x = 122: the nose passes it
    // on tick 3 (x = 110).
    write_level("coin", std::string(kOpenRoom) + "pickup coin 130 150 8\n");
    const auto sim = start("coin");
    EXPECT_EQ(sim->count("pickup"), 1);
    for (int t = 0; t < 3; ++t) sim->tick(hold({kUp}));
    EXPECT_EQ(variable(*sim, "score"), 0.0);
    EXPECT_EQ(sim->count("pickup"), 1);
    EXPECT_FALSE(sim->event_happened("pickup"));
    EXPECT_TRUE(sim->entity_position("coin").has_value());
    sim->tick(hold({kUp}));
    EXPECT_EQ(variable(*sim, "score"), 10.0);
    EXPECT_EQ(sim->count("pickup"), 0);
    EXPECT_TRUE(sim->event_happened("pickup"));
    EXPECT_FALSE(sim->entity_position("coin").has_value());
    EXPECT_EQ(field(*sim, "game", "score"), "10");
    EXPECT_NEAR(position(*sim, "player").x, 110.0f, 1e-3f);  // a trigger does not slow the ship
    // Driving on through where it was scores nothing more.
    for (int t = 0; t < 10; ++t) sim->tick(hold({kUp}));
    EXPECT_EQ(variable(*sim, "score"), 10.0);
}

TEST_F(Arena, ACannonFiresABallEveryPeriod) {
    write_level("cannon", std::string(kOpenRoom) + "cannon k 200 60 0 10 120\n");
    const auto sim = start("cannon");
    for (int t = 0; t < 9; ++t) sim->tick(InputFrame{});
    EXPECT_EQ(variable(*sim, "balls"), 0.0);
    EXPECT_FALSE(sim->event_happened("cannon_fire"));
    sim->tick(InputFrame{});  // tick 9: the 10th tick
    EXPECT_EQ(variable(*sim, "balls"), 1.0);
    EXPECT_EQ(sim->count("ball"), 1);
    EXPECT_TRUE(sim->event_happened("cannon_fire"));
    // Just clear of the cannon (10 + 5 + 2 px along its angle), then one step at 120 px/s.
    EXPECT_NEAR(position(*sim, "ball_1").x, 219.0f, 1e-3f);
    EXPECT_EQ(position(*sim, "ball_1").y, 60.0f);
    for (int t = 10; t < 30; ++t) sim->tick(InputFrame{});
    EXPECT_EQ(variable(*sim, "balls"), 3.0);
    EXPECT_EQ(sim->count("ball"), 3);
    EXPECT_NEAR(position(*sim, "ball_1").x, 219.0f + 20.0f * 2.0f, 1e-2f);
    EXPECT_NEAR(position(*sim, "ball_3").x, 219.0f, 1e-3f);
}

TEST(ArenaSource, TheShippedArenasCannonFiresEvery120Ticks) {
    const auto sim = ArenaGame(JOSTLE_ASSETS_DIR).start("arena", 1, 60);
    std::vector<double> balls;
    for (int t = 0; t < 240; ++t) {
        sim->tick(InputFrame{});
        balls.push_back(variable(*sim, "balls"));
    }
    EXPECT_EQ(balls[118], 0.0);
    EXPECT_EQ(balls[119], 1.0);
    EXPECT_EQ(balls[238], 1.0);
    EXPECT_EQ(balls[239], 2.0);
    EXPECT_EQ(sim->count("pickup"), 2);
    EXPECT_EQ(sim->count("rock"), 3);
    EXPECT_EQ(sim->count("crate"), 2);
}

// The input of `ticks` random ticks (seeded: the same every run).
std::vector<InputFrame> random_input(unsigned seed, int ticks) {
    std::mt19937 rng(seed);
    std::vector<InputFrame> out;
    while (static_cast<int>(out.size()) < ticks) {
        const InputFrame f{static_cast<std::uint32_t>(rng() % 32)};
        const int run = 1 + static_cast<int>(rng() % 20);
        for (int i = 0; i < run && static_cast<int>(out.size()) < ticks; ++i) out.push_back(f);
    }
    return out;
}

// The state hash after each tick of `input`.
std::vector<std::uint64_t> hashes_of(Simulation& sim, const std::vector<InputFrame>& input) {
    std::vector<std::uint64_t> out;
    for (InputFrame f : input) {
        sim.tick(f);
        out.push_back(sim.state_hash());
    }
    return out;
}

TEST(ArenaSource, TheSameInputGivesTheSameHashes) {
    const ArenaGame game(JOSTLE_ASSETS_DIR);
    const std::vector<InputFrame> input = random_input(11, 300);
    auto a = game.start("arena", 5, 60);
    auto b = game.start("arena", 5, 60);
    const std::vector<std::uint64_t> ha = hashes_of(*a, input);
    const std::vector<std::uint64_t> hb = hashes_of(*b, input);
    EXPECT_EQ(ha, hb);
    EXPECT_EQ(a->dump().size(), b->dump().size());
    EXPECT_GT(variable(*a, "shots"), 5.0);  // the input did things
    // Every tick changes the state (at least the tick count).
    for (std::size_t t = 1; t < ha.size(); ++t) EXPECT_NE(ha[t], ha[t - 1]) << t;
    // Another seed is another run: the world's RNG is part of the state.
    auto c = game.start("arena", 6, 60);
    EXPECT_NE(hashes_of(*c, input)[0], ha[0]);
    // Other input: the hashes part ways.
    auto d = game.start("arena", 5, 60);
    EXPECT_NE(hashes_of(*d, random_input(12, 300)), ha);
}

TEST(ArenaSource, ReplayingAScenarioGivesTheHashesOfDrivingTheRunDirectly) {
    const ArenaGame game(JOSTLE_ASSETS_DIR);
    Scenario s;
    s.level = "arena";
    s.seed = 9;
    s.tick_rate = 60;
    s.inputs = random_input(3, 200);
    ReplayOptions options;
    options.backend = RenderBackend::null;
    const ReplayResult r = replay(game, s, options);
    auto sim = game.start("arena", 9, 60);
    EXPECT_EQ(r.hashes, hashes_of(*sim, s.inputs));
}

TEST(ArenaSource, DrawingDoesNotChangeTheRun) {
    const ArenaGame game(JOSTLE_ASSETS_DIR);
    const std::vector<InputFrame> input = random_input(21, 150);
    auto plain = game.start("arena", 1, 60);
    const std::vector<std::uint64_t> expected = hashes_of(*plain, input);
    auto drawn = game.start("arena", 1, 60);
    Renderer renderer(RendererDesc{.backend = RenderBackend::null});
    std::vector<std::uint64_t> got;
    for (InputFrame f : input) {
        drawn->tick(f);
        renderer.begin_frame(64, 48, Color{0, 0, 0, 255});
        drawn->draw(renderer, DrawOptions{.overlay = true, .hud = true});
        renderer.end_frame();
        got.push_back(drawn->state_hash());
    }
    EXPECT_EQ(got, expected);
}

TEST_F(Arena, TheStateHashCoversTheScore) {
    // Two runs whose worlds move identically; only the points a pickup is worth differ.
    write_level("coin", std::string(kOpenRoom) + "pickup coin 130 150 8\n");
    const auto ten = start("coin", Rules{.pickup_score = 10});
    const auto twenty = start("coin", Rules{.pickup_score = 20});
    for (int t = 0; t < 6; ++t) {
        ten->tick(hold({kUp}));
        twenty->tick(hold({kUp}));
        if (t < 3) {
            EXPECT_EQ(ten->state_hash(), twenty->state_hash()) << "tick " << t;
        } else {
            EXPECT_NE(ten->state_hash(), twenty->state_hash()) << "tick " << t;
            EXPECT_EQ(position(*ten, "player").x, position(*twenty, "player").x);
        }
    }
    EXPECT_EQ(variable(*ten, "score"), 10.0);
    EXPECT_EQ(variable(*twenty, "score"), 20.0);
}

TEST_F(Arena, BadOrMissingLevelFilesAreInputErrors) {
    write_level("bad", "jostle-level 1\nsize 0 480\nplayer 1 1\n");
    const ArenaGame game(assets());
    const std::string bad = (dir_.path() / "levels" / "bad.level").string();
    try {
        game.start("bad", 1, 60);
        ADD_FAILURE() << "no error";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()), bad + ":2:6: expected a positive width, got '0'");
    }
    const std::string missing = (dir_.path() / "levels" / "missing.level").string();
    try {
        game.start("missing", 1, 60);
        ADD_FAILURE() << "no error";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()), missing + ": cannot open the level file: No such file or directory");
    }
    EXPECT_THROW(game.level_hash("missing"), InputError);
}

TEST_F(Arena, PropsAndBlobsNeedTheirSprites) {
    write_level("treed", std::string(kOpenRoom) + "prop t1 tree 200 150\n");
    write_level("blobbed", std::string(kOpenRoom) + "blob b1 200 150 300 150 30\n");
    const ArenaGame game(assets());
    const std::string level = (dir_.path() / "levels" / "treed.level").string();
    try {
        game.start("treed", 1, 60);
        ADD_FAILURE() << "no error";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()), level + ":6:9: no sprite 'tree' (expected a file sprites/tree.png in the assets)");
    }
    EXPECT_THROW(game.start("blobbed", 1, 60), InputError);
    // With the sprites they start, and a sprite changes the level's hash.
    const std::string before = game.level_hash("treed");
    fs::copy(fs::path(JOSTLE_ASSETS_DIR) / "sprites", dir_.path() / "sprites");
    EXPECT_NE(game.level_hash("treed"), before);
    EXPECT_NO_THROW(game.start("treed", 1, 60));
}

TEST_F(Arena, ABlobWalksToTheEndOfItsPatrolAndBack) {
    fs::copy(fs::path(JOSTLE_ASSETS_DIR) / "sprites", dir_.path() / "sprites");
    // 60 px at 30 px/s: 120 ticks out, 120 back.
    write_level("blobbed", std::string(kOpenRoom) + "blob b1 200 250 260 250 30\n");
    const auto sim = start("blobbed");
    for (int t = 0; t < 60; ++t) sim->tick(InputFrame{});
    EXPECT_NEAR(position(*sim, "b1").x, 230.0f, 1e-3f);
    for (int t = 60; t < 120; ++t) sim->tick(InputFrame{});
    EXPECT_NEAR(position(*sim, "b1").x, 260.0f, 1e-3f);
    EXPECT_EQ(position(*sim, "b1").y, 250.0f);
    for (int t = 120; t < 180; ++t) sim->tick(InputFrame{});
    EXPECT_NEAR(position(*sim, "b1").x, 230.0f, 1e-3f);
    for (int t = 180; t < 240; ++t) sim->tick(InputFrame{});
    EXPECT_NEAR(position(*sim, "b1").x, 200.0f, 1e-3f);
    EXPECT_EQ(sim->count("blob"), 1);
    EXPECT_FALSE(sim->event_happened("blob_touch"));
}

TEST_F(Arena, FastestIsTheQuickestCrateOrRock) {
    write_level("pushed", std::string(kOpenRoom) + "rock r1 circle 125 150 8\n");
    const auto sim = start("pushed");
    EXPECT_EQ(variable(*sim, "fastest"), 0.0);
    double most = 0.0;
    for (int t = 0; t < 20; ++t) {
        sim->tick(hold({kUp}));
        most = std::max(most, variable(*sim, "fastest"));
    }
    EXPECT_GT(most, 50.0) << "the ship pushes the rock";
    for (int t = 0; t < 200; ++t) sim->tick(InputFrame{});
    EXPECT_LT(variable(*sim, "fastest"), 0.01) << "drag stops it";
}

}  // namespace
}  // namespace jostle::game
