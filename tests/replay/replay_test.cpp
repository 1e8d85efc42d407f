// replay_test.cpp: the replay loop (replay.h) against a small fake game whose state is a
// counter: each tick gets exactly the scenario's input, hashes, expectation results and their
// `actual` text, validation errors, dumps, screenshots, frame files and progress are as documented.
#include "jostle/replay/replay.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <memory>

#include "jostle/core/error.h"
#include "test_support.h"

namespace jostle {
namespace {

// What the fake game saw, shared by the game and its runs.
struct Log {
    std::vector<InputFrame> inputs;        // tick() calls, in order
    std::vector<std::int64_t> draws;       // ticks_done() at each draw()
    std::string level;
    std::uint64_t seed = 0;
    int tick_rate = 0;
};

constexpr std::uint64_t kFnvStart = 14695981039346656037ull;
constexpr std::uint64_t kFnvPrime = 1099511628211ull;

// The fake run. After n ticks: the player is at (2n, 10) while n <= 6 and gone after; there
// are n rocks and no crates; score = 10n; "half" is listed but has no value; the event "boom"
// happened once n >= 3; the hash folds in every input.
class FakeSimulation : public Simulation {
public:
    explicit FakeSimulation(Log* log) : log_(log) {}

    void tick(InputFrame input) override {
        log_->inputs.push_back(input);
        hash_ = (hash_ ^ (input.held + 1u)) * kFnvPrime;
        ++ticks_;
    }
    std::int64_t ticks_done() const override { return ticks_; }
    std::uint64_t state_hash() const override { return hash_; }
    const World& world() const override { return world_; }
    std::optional<Vec2> entity_position(std::string_view name) const override {
        if (name == "player" && ticks_ <= 6) return Vec2{2.0f * static_cast<float>(ticks_), 10.0f};
        if (name == "half_pixel") return Vec2{0.5f, -1.25f};
        return std::nullopt;
    }
    // ("ghost" arrives at tick 5, never alive: only ever named.)
    bool entity_named(std::string_view name) const override {
        return name == "player" || name == "half_pixel" || (name == "ghost" && ticks_ > 5);
    }
    bool entity_name_possible(std::string_view name) const override {
        return name == "player" || name == "half_pixel" || name == "ghost";
    }
    std::int64_t count(std::string_view kind) const override { return kind == "rock" ? ticks_ : 0; }
    std::optional<double> variable(std::string_view name) const override {
        if (name == "score") return 10.0 * static_cast<double>(ticks_);
        return std::nullopt;
    }
    bool event_happened(std::string_view name) const override { return name == "boom" && ticks_ >= 3; }
    std::vector<std::string> kinds() const override { return {"rock", "crate"}; }
    std::vector<std::string> variables() const override { return {"score", "half"}; }
    std::vector<std::string> events() const override { return {"boom", "bang"}; }
    std::vector<EntityDump> dump() const override {
        return {EntityDump{"game", {{"ticks", std::to_string(ticks_)}}},
                EntityDump{"player", {{"x", std::to_string(2 * ticks_)}, {"y", "10"}}}};
    }
    Vec2 level_size() const override { return {64.0f, 48.0f}; }
    void draw(Renderer& renderer, const DrawOptions&) const override {
        log_->draws.push_back(ticks_);
        renderer.fill_rect(Aabb{{0.0f, 0.0f}, {64.0f, 48.0f}}, Color{200, 30, 10, 255});
    }

private:
    Log* log_;
    World world_{WorldDesc{}};
    std::int64_t ticks_ = 0;
    std::uint64_t hash_ = kFnvStart;
};

class FakeGame : public Game {
public:
    explicit FakeGame(Log* log) : log_(log) { vocabulary_ = {{"a", "b", "c"}, {"room", "bad"}}; }
    const ScenarioVocabulary& vocabulary() const override { return vocabulary_; }
    std::string level_hash(const std::string&) const override { return "0123456789abcdef"; }
    std::unique_ptr<Simulation> start(const std::string& level, std::uint64_t seed, int tick_rate) const override {
        if (level == "bad") throw InputError(SourceLocation{"levels/bad.level", 3, 1}, "broken level");
        log_->level = level;
        log_->seed = seed;
        log_->tick_rate = tick_rate;
        return std::make_unique<FakeSimulation>(log_);
    }

private:
    Log* log_;
    ScenarioVocabulary vocabulary_;
};

constexpr const char* kHeader =
    "jostle-scenario 1\n"
    "engine 0.1.0\n"
    "level room\n"
    "seed 99\n"
    "tick-rate 30\n"
    "level-hash 0123456789abcdef\n";

class Replay : public ::testing::Test {
protected:
    Scenario scenario(const std::string& body) {
        return parse_scenario(std::string(kHeader) + body, "s.scn", game_.vocabulary());
    }
    ReplayOptions null_options() const {
        ReplayOptions o;
        o.backend = RenderBackend::null;
        return o;
    }
    std::string error_of(const Scenario& s, const ReplayOptions& options) {
        try {
            replay(game_, s, options);
        } catch (const InputError& e) {
            return e.what();
        }
        return "no error";
    }

    Log log_;
    FakeGame game_{&log_};
};

TEST_F(Replay, EveryTickGetsExactlyTheScenariosInput) {
    const Scenario s = scenario("0-2 a\n3 a b c\n4 -\n5-6 c\n9 b\nat 12 end\n");
    const ReplayResult r = replay(game_, s, null_options());
    EXPECT_EQ(log_.level, "room");
    EXPECT_EQ(log_.seed, 99u);
    EXPECT_EQ(log_.tick_rate, 30);
    EXPECT_EQ(r.ticks, 12);
    ASSERT_EQ(log_.inputs.size(), 12u);
    const std::uint32_t expected[] = {1, 1, 1, 7, 0, 4, 4, 0, 0, 2, 0, 0};
    for (std::size_t t = 0; t < 12; ++t) {
        EXPECT_EQ(log_.inputs[t].held, expected[t]) << "tick " << t;
        EXPECT_EQ(log_.inputs[t], s.input(static_cast<std::int64_t>(t)));
    }
    EXPECT_TRUE(log_.draws.empty());  // no output asked for: nothing drawn
    EXPECT_EQ(r.frames_rendered, 0);
    EXPECT_TRUE(r.files_written.empty());
}

TEST_F(Replay, TheHashAfterEveryTick) {
    const Scenario s = scenario("0 a\n1 b\n2 -\n3 a c\n");
    const ReplayResult r = replay(game_, s, null_options());
    ASSERT_EQ(r.hashes.size(), 4u);
    std::uint64_t h = kFnvStart;
    const std::uint32_t held[] = {1, 2, 0, 5};
    for (std::size_t t = 0; t < 4; ++t) {
        h = (h ^ (held[t] + 1u)) * kFnvPrime;
        EXPECT_EQ(r.hashes[t], h) << t;
    }
    EXPECT_NE(r.hashes[0], r.hashes[1]);
    EXPECT_GE(r.seconds, 0.0);
}

TEST_F(Replay, TheSameScenarioGivesTheSameHashesEveryTime) {
    const Scenario s = scenario("0-20 a\n21-40 b c\nat 50 end\n");
    const ReplayResult a = replay(game_, s, null_options());
    const ReplayResult b = replay(game_, s, null_options());
    EXPECT_EQ(a.hashes, b.hashes);
    EXPECT_EQ(a.hashes.size(), 50u);
}

TEST_F(Replay, ExpectationsOfEveryKindPassOrFailWithWhatWasFound) {
    const Scenario s = scenario(
        "at 2 expect player alive\n"            // 7: after tick 2 the run has done 3 ticks: (6, 10)
        "at 2 expect player in 0 0 5 20\n"      // 8: x 6 > 5
        "at 2 expect player in 6 10 6 10\n"     // 9: the region is closed
        "at 2 expect player gone\n"             // 10
        "at 7 expect player gone\n"             // 11
        "at 7 expect player alive\n"            // 12
        "at 7 expect player in 0 0 100 100\n"   // 13
        "at 4 expect count rock = 5\n"          // 14
        "at 4 expect count rock > 5\n"          // 15
        "at 4 expect count crate <= 0\n"        // 16
        "at 4 expect var score = 50\n"          // 17
        "at 4 expect var score < 50\n"          // 18
        "at 4 expect var half = 0\n"            // 19: no value: NaN, which equals nothing
        "at 1 expect event boom\n"              // 20
        "at 2 expect event boom\n"              // 21
        "at 9 expect event bang\n"              // 22
        "at 0 expect half_pixel in 0.5 -1.25 1 0\n"  // 23
        "at 10 end\n");
    const ReplayResult r = replay(game_, s, null_options());
    ASSERT_EQ(r.expectations.size(), 17u);
    struct Want {
        int line;
        bool passed;
        const char* actual;
    };
    // In the scenario's order: by tick, file order within a tick.
    const Want want[] = {
        {23, true, "half_pixel is alive at (0.5, -1.25)"},
        {20, false, "event boom has not happened"},
        {7, true, "player is alive at (6, 10)"},
        {8, false, "player is alive at (6, 10)"},
        {9, true, "player is alive at (6, 10)"},
        {10, false, "player is alive at (6, 10)"},
        {21, true, "event boom happened"},
        {14, true, "count rock = 5"},
        {15, false, "count rock = 5"},
        {16, true, "count crate = 0"},
        {17, true, "score = 50"},
        {18, false, "score = 50"},
        {19, false, "half = nan"},
        {11, true, "player is gone"},
        {12, false, "player is gone"},
        {13, false, "player is gone"},
        {22, false, "event bang has not happened"},
    };
    for (std::size_t i = 0; i < r.expectations.size(); ++i) {
        const ExpectationResult& e = r.expectations[i];
        ASSERT_NE(e.expectation, nullptr);
        EXPECT_EQ(e.expectation, &s.expectations[i]);
        EXPECT_EQ(e.expectation->line, want[i].line) << i;
        EXPECT_EQ(e.passed, want[i].passed) << "line " << want[i].line;
        EXPECT_EQ(e.actual, want[i].actual) << "line " << want[i].line;
    }
    EXPECT_FALSE(r.expectations_passed());
}

TEST_F(Replay, AllPassingOrNoExpectationsPass) {
    EXPECT_TRUE(replay(game_, scenario("at 3 expect var score >= 40\nat 3 expect count rock != 3\n"), null_options())
                    .expectations_passed());
    EXPECT_TRUE(replay(game_, scenario("0-3 a\n"), null_options()).expectations_passed());
}

TEST_F(Replay, ExpectationsNamingWhatTheGameDoesNotHaveAreBadInputBeforeAnyTick) {
    ReplayOptions o = null_options();
    EXPECT_EQ(error_of(scenario("0 a\n\nat 5 expect count tree > 0\n"), o),
              "s.scn:9:19: unknown entity kind 'tree' (expected one of: rock, crate)");
    EXPECT_EQ(error_of(scenario("at 5 expect var lives = 3\n"), o),
              "s.scn:7:17: unknown game variable 'lives' (expected one of: score, half)");
    EXPECT_EQ(error_of(scenario("at 2 expect event boom\nat 5 expect event bam\n"), o),
              "s.scn:8:19: unknown event 'bam' (expected one of: boom, bang)");
    // An entity name the game never gives (a typo would make `gone` pass).
    EXPECT_EQ(error_of(scenario("0 a\nat 9 expect playr gone\n"), o),
              "s.scn:8:13: unknown entity 'playr': no entity of this run can have that name (the dumps of 'jostle play "
              "--trace' name every entity)");
    EXPECT_TRUE(log_.inputs.empty());  // refused before the first tick
}

// Entities come and go during a run, so a name the game can give is checked again at the
// expectation's tick: one that no entity has had by then cannot be met (`gone` would pass).
TEST_F(Replay, AnEntityNoEntityHasHadByTheExpectationsTickIsBadInput) {
    const ReplayOptions o = null_options();
    const std::string hint = " (a misspelt name? the dumps of 'jostle play --trace' name every entity)";
    EXPECT_EQ(error_of(scenario("at 2 expect ghost gone\n"), o), "s.scn:7:13: no entity named 'ghost' has been in the run by tick 2" + hint);
    EXPECT_EQ(log_.inputs.size(), 3u);  // found at its tick
    EXPECT_EQ(error_of(scenario("at 1 expect player alive\nat 3 expect ghost alive\n"), o),
              "s.scn:8:13: no entity named 'ghost' has been in the run by tick 3" + hint);
    EXPECT_EQ(error_of(scenario("at 4 expect ghost in 0 0 1 1\n"), o), "s.scn:7:13: no entity named 'ghost' has been in the run by tick 4" + hint);
    // From tick 5 on, ghost has been in the run (the fake's rule): gone is a check that passes.
    const ReplayResult r = replay(game_, scenario("at 5 expect ghost gone\nat 6 expect ghost alive\nat 7 end\n"), o);
    ASSERT_EQ(r.expectations.size(), 2u);
    EXPECT_TRUE(r.expectations[0].passed);
    EXPECT_FALSE(r.expectations[1].passed);
    EXPECT_EQ(r.expectations[1].actual, "ghost is gone");
}

TEST_F(Replay, ABadLevelIsAnInputError) {
    const Scenario s = parse_scenario(
        "jostle-scenario 1\nengine 0.1.0\nlevel bad\nseed 1\ntick-rate 60\nlevel-hash 0123456789abcdef\n0 a\n", "s.scn",
        game_.vocabulary());
    EXPECT_EQ(error_of(s, null_options()), "levels/bad.level:3:1: broken level");
}

TEST_F(Replay, DumpsEveryNthTickAndTheLastTick) {
    const auto dump_ticks = [&](int ticks, int every) {
        ReplayOptions o = null_options();
        o.dump_every = every;
        const ReplayResult r = replay(game_, scenario("at " + std::to_string(ticks) + " end\n"), o);
        std::vector<std::int64_t> out;
        for (const TraceDump& d : r.dumps) {
            out.push_back(d.tick);
            // The dump is the state after that tick: tick + 1 ticks done.
            EXPECT_EQ(d.entities.size(), 2u);
            EXPECT_EQ(d.entities[0].name, "game");
            EXPECT_EQ(d.entities[0].fields[0].value, std::to_string(d.tick + 1));
            EXPECT_EQ(d.entities[1].fields[0].value, std::to_string(2 * (d.tick + 1)));
        }
        return out;
    };
    EXPECT_EQ(dump_ticks(10, 3), (std::vector<std::int64_t>{0, 3, 6, 9}));
    EXPECT_EQ(dump_ticks(11, 3), (std::vector<std::int64_t>{0, 3, 6, 9, 10}));
    EXPECT_EQ(dump_ticks(4, 1), (std::vector<std::int64_t>{0, 1, 2, 3}));
    EXPECT_EQ(dump_ticks(1, 10), (std::vector<std::int64_t>{0}));
    EXPECT_EQ(dump_ticks(25, 10), (std::vector<std::int64_t>{0, 10, 20, 24}));
    EXPECT_EQ(dump_ticks(25, 0), (std::vector<std::int64_t>{}));
    EXPECT_EQ(dump_ticks(21, ReplayOptions{}.dump_every), (std::vector<std::int64_t>{0, 10, 20}));
}

TEST_F(Replay, ScreenshotsAreKeptAtTheirTicksOnlyWhenAsked) {
    const Scenario s = scenario("0-9 a\nat 4 screenshot\nat 1 screenshot\nat 4 screenshot\nat 10 end\n");
    ReplayOptions o = null_options();
    ReplayResult r = replay(game_, s, o);
    EXPECT_TRUE(r.screenshots.empty());
    EXPECT_EQ(r.frames_rendered, 0);
    const std::vector<std::uint64_t> plain_hashes = r.hashes;

    o.keep_screenshots = true;
    r = replay(game_, s, o);
    ASSERT_EQ(r.screenshots.size(), 2u);  // two lines at tick 4 make one picture
    EXPECT_EQ(r.screenshots[0].first, 1);
    EXPECT_EQ(r.screenshots[1].first, 4);
    EXPECT_EQ(r.frames_rendered, 2);
    EXPECT_EQ(log_.draws, (std::vector<std::int64_t>{2, 5}));  // drawn after tick 1 and tick 4
    for (const auto& [tick, image] : r.screenshots) {
        EXPECT_EQ(image.width, 64);  // the level's size
        EXPECT_EQ(image.height, 48);
        ASSERT_EQ(image.rgba.size(), 64u * 48u * 4u);
        EXPECT_EQ(image.rgba[0], 0);  // the null backend draws nothing: the clear colour
        EXPECT_EQ(image.rgba[3], 255);
    }
    EXPECT_EQ(r.hashes, plain_hashes);  // drawing changes nothing

    o.width = 16;
    o.height = 10;
    r = replay(game_, s, o);
    ASSERT_EQ(r.screenshots.size(), 2u);
    EXPECT_EQ(r.screenshots[0].second.width, 16);
    EXPECT_EQ(r.screenshots[0].second.height, 10);
}

TEST_F(Replay, OsmesaScreenshotShowsTheLevelFittedToTheFrame) {
    const Scenario s = scenario("at 0 screenshot\n");
    ReplayOptions o;
    o.backend = RenderBackend::osmesa;
    o.keep_screenshots = true;
    o.width = 16;
    o.height = 24;  // the 64x48 level is scaled by 1/4 to 16x12 and centred: rows 6..17
    const ReplayResult r = replay(game_, s, o);
    ASSERT_EQ(r.screenshots.size(), 1u);
    const Image& im = r.screenshots[0].second;
    ASSERT_EQ(im.width, 16);
    ASSERT_EQ(im.height, 24);
    const auto pixel = [&](int x, int y) {
        const std::size_t i = (static_cast<std::size_t>(y) * 16u + static_cast<std::size_t>(x)) * 4u;
        return std::vector<int>{im.rgba[i], im.rgba[i + 1], im.rgba[i + 2], im.rgba[i + 3]};
    };
    EXPECT_EQ(pixel(0, 0), (std::vector<int>{0, 0, 0, 255}));  // letterbox: the clear colour
    EXPECT_EQ(pixel(15, 23), (std::vector<int>{0, 0, 0, 255}));
    EXPECT_EQ(pixel(0, 6), (std::vector<int>{200, 30, 10, 255}));
    EXPECT_EQ(pixel(15, 17), (std::vector<int>{200, 30, 10, 255}));
    EXPECT_EQ(pixel(8, 5), (std::vector<int>{0, 0, 0, 255}));
    EXPECT_EQ(pixel(8, 18), (std::vector<int>{0, 0, 0, 255}));
}

TEST_F(Replay, FramesAreWrittenForTheSelectedTicks) {
    const test::TempFolder temp("replay_frames");
    const std::filesystem::path dir = temp.path() / "frames";
    ReplayOptions o = null_options();
    o.out_dir = dir.string();
    o.frames = *FrameSelection::parse("2-5");
    o.frames.set_every(2);
    const ReplayResult r = replay(game_, scenario("at 8 end\n"), o);
    EXPECT_EQ(r.frames_rendered, 2);
    EXPECT_EQ(r.files_written, (std::vector<std::string>{(dir / "frame_000002.png").string(), (dir / "frame_000004.png").string()}));
    EXPECT_EQ(test::file_names(dir), (std::vector<std::string>{"frame_000002.png", "frame_000004.png"}));
    const Image im = read_png((dir / "frame_000004.png").string());
    EXPECT_EQ(im.width, 64);
    EXPECT_EQ(im.height, 48);
}

TEST_F(Replay, ProgressIsCalledOncePerTickWithDoneAndTotal) {
    std::vector<std::pair<std::int64_t, std::int64_t>> calls;
    ReplayOptions o = null_options();
    o.progress = [&](std::int64_t done, std::int64_t total) {
        calls.emplace_back(done, total);
        EXPECT_EQ(static_cast<std::int64_t>(log_.inputs.size()), done);  // after the tick
    };
    replay(game_, scenario("0-3 a\nat 5 end\n"), o);
    EXPECT_EQ(calls, (std::vector<std::pair<std::int64_t, std::int64_t>>{{1, 5}, {2, 5}, {3, 5}, {4, 5}, {5, 5}}));
}

TEST_F(Replay, TraceOfAReplayReadsBack) {
    ReplayOptions o = null_options();
    o.dump_every = 4;
    const ReplayResult r = replay(game_, scenario("0-5 a b\nat 10 end\n"), o);
    const std::string text = format_trace(r, 4);
    const ReplayResult back = parse_trace(text, "t.trace");
    EXPECT_EQ(back.ticks, 10);
    EXPECT_EQ(back.hashes, r.hashes);
    ASSERT_EQ(back.dumps.size(), 4u);  // 0, 4, 8, 9
    EXPECT_EQ(back.dumps[3].tick, 9);
    EXPECT_EQ(back.dumps[3].entities[1].fields[0].value, "20");
    EXPECT_EQ(format_trace(back, 4), text);
}

}  // namespace
}  // namespace jostle
