// check_test.cpp: `jostle check`, the gameplay regression check, on scenarios in a temporary
// folder. In process (check_scenario with a tweaked game::Rules): a rule change is caught at
// the first tick it can matter, naming the changed fields, with a differing screenshot and a
// report (expected / actual / diff PNGs); a rule the scenario never reaches changes nothing.
// End to end (the built binary): missing and stale goldens fail (exit 1) and a plain check
// creates nothing; --update creates, changes and removes goldens and says exactly what it did,
// changes nothing the second time, and writes nothing when any scenario is bad input (exit 2);
// sharding (TEST_ / GTEST_ variables, the status file, malformed values); --jobs gives the
// same results and files as one job (OSMesa rendering on several threads); usage errors;
// --report (report.html with the first divergent tick and its images, junit.xml).
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "arena.h"
#include "check.h"
#include "jostle/core/text.h"
#include "jostle/render/png_io.h"
#include "jostle/replay/check.h"
#include "jostle/replay/replay.h"
#include "game/run_jostle.h"
#include "test_support.h"

namespace jostle {
namespace {

namespace fs = std::filesystem;

using ::testing::HasSubstr;
using ::testing::Not;
using test::EnvGuard;
using test::read_text;
using test::RunResult;

const std::string kAssets = JOSTLE_ASSETS_DIR;

// The command the hints give to re-bless `scenario_path` in a check run with the source tree's
// assets given, as the fixture's check() gives them.
std::string update(const std::string& scenario_path) { return "jostle check --update --assets " + kAssets + " " + scenario_path; }

std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
}

std::string usage_error(const std::string& message) {
    return "jostle check: " + message + "\nRun 'jostle check --help' for usage.\n";
}

// The pixels diff_image paints solid red: the ones that differ (the rest is faded toward white).
std::int64_t red_pixels(const Image& image) {
    std::int64_t n = 0;
    for (std::size_t i = 0; i + 3 < image.rgba.size(); i += 4) {
        n += image.rgba[i] == 255 && image.rgba[i + 1] == 0 && image.rgba[i + 2] == 0 && image.rgba[i + 3] == 255 ? 1 : 0;
    }
    return n;
}

constexpr const char* kShardVariables[] = {"TEST_TOTAL_SHARDS",  "TEST_SHARD_INDEX",  "TEST_SHARD_STATUS_FILE",
                                           "GTEST_TOTAL_SHARDS", "GTEST_SHARD_INDEX", "GTEST_SHARD_STATUS_FILE"};

// Nothing held for ticks 0-9, then "up" (drive forward) from tick 10; the frame after tick 29.
// The ship starts at (100, 240) facing +x (angle 0), with nothing in its way for 50 px.
constexpr const char* kDrive =
    "0-9 -\n"
    "10-29 up\n"
    "at 29 screenshot\n"
    "at 30 end\n";

// The same scenario with the drive starting at tick 15, and another screenshot.
constexpr const char* kDriveLater =
    "0-14 -\n"
    "15-29 up\n"
    "at 25 screenshot\n"
    "at 29 screenshot\n"
    "at 30 end\n";

// Five ticks of turning, no screenshot.
constexpr const char* kTurn =
    "0-4 left\n"
    "at 5 end\n";

class Check : public ::testing::Test {
protected:
    void SetUp() override {
        level_hash_ = game::ArenaGame(kAssets).level_hash("arena");
        // The child must not inherit a sharding of this test binary, test hooks or other assets.
        for (const char* name : kShardVariables) env_.unset(name);
        env_.unset("JOSTLE_ASSETS");
        env_.unset("JOSTLE_TEST_INTERRUPT");
    }

    std::string path(const std::string& name) const { return dir_.file(name); }
    std::string folder() const { return dir_.path().string(); }

    // The arena scenario header (the current level hash) and `body`, as NAME in `where`.
    std::string scenario(const std::string& name, const std::string& body, const fs::path& where = {}) {
        const fs::path file = (where.empty() ? dir_.path() : where) / name;
        std::ofstream(file, std::ios::binary) << "jostle-scenario 1\nengine 0.1.0\nlevel arena\nseed 1\ntick-rate 60\nlevel-hash "
                                              << level_hash_ << "\n"
                                              << body;
        return file.string();
    }

    // Creates the goldens of `scenario_path` with the standard rules, in process.
    void bless(const std::string& scenario_path) {
        const ScenarioCheck c = check_scenario(standard_, scenario_path);
        ASSERT_FALSE(c.bad_input()) << c.error;
        commit_updates({c});
        ASSERT_TRUE(check_scenario(standard_, scenario_path).passed());
    }

    // `jostle check` with the source tree's assets (given first, so an option left without
    // its value at the end stays without it).
    RunResult check(std::vector<std::string> args) {
        args.insert(args.begin(), {"check", "--assets", kAssets});
        return test::run_jostle_binary(args);
    }

    // The file names in a folder, sorted.
    std::vector<std::string> listing(const fs::path& where) const { return test::file_names(where); }

    // Every file's contents and modification time, by name.
    std::map<std::string, std::pair<std::string, fs::file_time_type>> snapshot(const fs::path& where) const {
        std::map<std::string, std::pair<std::string, fs::file_time_type>> files;
        for (const auto& entry : fs::directory_iterator(where)) {
            files[entry.path().filename().string()] = {read_text(entry.path()), fs::last_write_time(entry.path())};
        }
        return files;
    }

    std::string pass_line(const std::string& scenario_path, int ticks, int screenshots) const {
        return "PASS " + scenario_path + " (" + std::to_string(ticks) + " ticks, 0 expectations, " + std::to_string(screenshots) +
               (screenshots == 1 ? " screenshot)" : " screenshots)");
    }

    const test::TempFolder dir_{"check"};
    std::string level_hash_;
    EnvGuard env_;
    const game::ArenaGame standard_{kAssets};
};

// ---- rules (in process) ----------------------------------------------------------------

TEST_F(Check, ARuleChangeIsCaughtAtTheFirstTickItCanMatter) {
    const std::string s = scenario("drive.scn", kDrive);
    const ScenarioCheck first = check_scenario(standard_, s);
    ASSERT_FALSE(first.bad_input()) << first.error;
    EXPECT_TRUE(first.trace_missing);
    EXPECT_EQ(commit_updates({first}), std::vector<std::string>{"updated " + s + ": trace created, drive.tick_29.png created"});
    ASSERT_TRUE(check_scenario(standard_, s).passed()) << describe_check(check_scenario(standard_, s));

    game::Rules faster;
    faster.drive_speed = 160.0f;  // from 150
    const game::ArenaGame changed(kAssets, faster);
    const ScenarioCheck c = check_scenario(changed, s);
    ASSERT_FALSE(c.bad_input()) << c.error;
    EXPECT_FALSE(c.passed());
    EXPECT_TRUE(c.goldens_differ());
    EXPECT_FALSE(c.trace_missing);
    EXPECT_EQ(c.expected_ticks, 30);
    EXPECT_EQ(c.actual_ticks, 30);

    // Why tick 10: drive_speed enters only through drive_player, and only on a tick that holds
    // "up" (velocity = forward * drive_speed); on ticks 0-9 nothing is held, so the ship's
    // velocity stays 0 * coast = 0 and every state after ticks 0..9 is the same under both
    // rules. Tick 10 is the first to hold "up": its velocity is set to 150 or 160 px/s before
    // the world steps, so the state after tick 10 (hashes[10]) is the first that differs.
    ASSERT_TRUE(c.first_divergent_tick.has_value());
    EXPECT_EQ(*c.first_divergent_tick, 10);
    const ReplayResult golden = parse_trace(read_text(c.trace_path), c.trace_path);
    const ReplayResult run = replay(changed, load_scenario(s, changed.vocabulary()));
    ASSERT_EQ(golden.hashes.size(), 30u);
    ASSERT_EQ(run.hashes.size(), 30u);
    for (std::size_t t = 0; t < 10; ++t) EXPECT_EQ(golden.hashes[t], run.hashes[t]) << "tick " << t;
    EXPECT_NE(golden.hashes[10], run.hashes[10]);
    EXPECT_EQ(c.expected_hash, golden.hashes[10]);
    EXPECT_EQ(c.actual_hash, run.hashes[10]);

    // Dumps are every 10th tick: tick 10 itself. The ship drives along +x, so exactly its x
    // and its x velocity differ (y stays 240 with sin(0) = 0); nothing else has been touched.
    ASSERT_EQ(c.dump_tick, std::optional<std::int64_t>(10));
    ASSERT_EQ(c.changes.size(), 2u) << describe_check(c);
    EXPECT_EQ(c.changes[0].entity, "player");
    EXPECT_EQ(c.changes[0].field, "x");
    EXPECT_EQ(c.changes[0].expected, "102.5");  // 100 + 150 / 60
    EXPECT_EQ(c.changes[0].actual, shortest_text(100.0f + 160.0f / 60.0f));
    EXPECT_EQ(c.changes[1].entity, "player");
    EXPECT_EQ(c.changes[1].field, "vx");
    EXPECT_EQ(c.changes[1].expected, "150");
    EXPECT_EQ(c.changes[1].actual, "160");

    // The screenshot after tick 29: 20 ticks at 10 px/s more put the ship 3 1/3 px further right.
    ASSERT_EQ(c.images.size(), 1u);
    const ImageCheck& image = c.images[0];
    EXPECT_EQ(image.tick, 29);
    EXPECT_EQ(image.golden_path, path("drive.tick_29.png"));
    EXPECT_FALSE(image.golden_missing);
    EXPECT_FALSE(image.passed());
    EXPECT_TRUE(image.compare.same_size);
    EXPECT_FALSE(image.compare.identical);
    EXPECT_GT(image.compare.differing_pixels, 0);
    EXPECT_TRUE(c.stale_goldens.empty());
    EXPECT_TRUE(c.failed_expectations.empty());

    EXPECT_EQ(describe_check(c),
              "FAIL " + s + " (30 ticks, 0 expectations, 1 screenshot)\n"
              "  trace: first divergent tick 10 (expected hash " + hex16(golden.hashes[10]) + ", got " + hex16(run.hashes[10]) + ")\n"
              "  at tick 10 (the first dumped tick from there on), expected -> actual:\n"
              "    player x: 102.5 -> " + c.changes[0].actual + "\n"
              "    player vx: 150 -> 160\n"
              "  screenshot tick 29: " + std::to_string(image.compare.differing_pixels) + " pixels differ (largest channel difference " +
              std::to_string(image.compare.max_channel_delta) + ") from " + path("drive.tick_29.png") + "\n");

    // The report: the golden as expected.png, this run as actual.png, and the diff with
    // exactly the differing pixels in red.
    const fs::path report = dir_.path() / "report";
    write_report(report.string(), {c});
    EXPECT_TRUE(fs::exists(report / "report.html"));
    EXPECT_TRUE(fs::exists(report / "junit.xml"));
    ASSERT_TRUE(fs::exists(report / "drive.tick_29.expected.png"));
    ASSERT_TRUE(fs::exists(report / "drive.tick_29.actual.png"));
    ASSERT_TRUE(fs::exists(report / "drive.tick_29.diff.png"));
    EXPECT_EQ(read_png((report / "drive.tick_29.expected.png").string()).rgba, read_png(path("drive.tick_29.png")).rgba);
    EXPECT_EQ(read_png((report / "drive.tick_29.actual.png").string()).rgba, image.actual.rgba);
    const Image diff = read_png((report / "drive.tick_29.diff.png").string());
    EXPECT_EQ(diff.width, 640);
    EXPECT_EQ(diff.height, 480);
    EXPECT_GT(red_pixels(diff), 0);
    EXPECT_EQ(red_pixels(diff), image.compare.differing_pixels);

    // The goldens are untouched by a failing check.
    EXPECT_EQ(listing(dir_.path()), (std::vector<std::string>{"drive.scn", "drive.tick_29.png", "drive.trace", "report"}));
}

TEST_F(Check, ARuleTheScenarioNeverReachesChangesNothing) {
    // ball_lifetime only matters once a cannon has fired: assets/levels/arena.level has one
    // cannon, period 120, which fires when (ticks done + 1) % 120 == 0, first on tick 119. The
    // 30-tick drive never gets there (and fires nothing itself), so it passes.
    const std::string s = scenario("drive.scn", kDrive);
    bless(s);
    game::Rules short_balls;
    short_balls.ball_lifetime = 10;  // from 240
    const game::ArenaGame changed(kAssets, short_balls);
    const ScenarioCheck c = check_scenario(changed, s);
    EXPECT_TRUE(c.passed()) << describe_check(c);
    EXPECT_FALSE(c.goldens_differ());
    EXPECT_EQ(describe_check(c), pass_line(s, 30, 1) + "\n");

    // The rule is live: a run long enough for the cannon's first ball diverges on tick 119,
    // when the ball is made with a lifetime of 10 instead of 240 (its lifetime is hashed).
    const std::string wait = scenario("wait.scn", "at 125 end\n");
    bless(wait);
    const ScenarioCheck w = check_scenario(changed, wait);
    EXPECT_FALSE(w.passed());
    ASSERT_TRUE(w.first_divergent_tick.has_value()) << describe_check(w);
    EXPECT_EQ(*w.first_divergent_tick, 119);
}

// ---- missing and stale goldens ---------------------------------------------------------

TEST_F(Check, AMissingTraceFailsAndAPlainCheckCreatesNothing) {
    const std::string s = scenario("drive.scn", kDrive);
    const RunResult r = check({s});
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(r.err, "");
    EXPECT_EQ(r.out, "FAIL " + s + " (30 ticks, 0 expectations, 1 screenshot)\n"
                     "  trace: no golden " + path("drive.trace") + " (to create it: " + update(s) + ")\n"
                     "  screenshot tick 29: no golden " + path("drive.tick_29.png") + " (to create it: " + update(s) + ")\n"
                     "checked 1 scenario: 0 passed, 1 failed\n");
    EXPECT_EQ(listing(dir_.path()), std::vector<std::string>{"drive.scn"});
}

// A --report that cannot be made is said before any scenario runs (not after the whole
// suite, where its exit 2 would also hide the suite's result).
TEST_F(Check, AReportFolderThatCannotBeMadeIsSaidBeforeTheRun) {
    const std::string s = scenario("drive.scn", kDrive);
    std::ofstream(path("file")) << "x";
    const RunResult r = check({s, "--report", path("file/report")});
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(r.err, "jostle check: " + path("file/report") + ": cannot create the report folder: Not a directory\n");
}

// A report folder that is the assets' sprites (or levels) folder is refused before the run:
// its images would be new sprites of the game.
TEST_F(Check, AReportFolderThatIsTheAssetsSpritesFolderIsRefused) {
    const fs::path assets = path("assets");
    fs::create_directories(assets);
    fs::copy(fs::path(kAssets) / "levels", assets / "levels");
    fs::copy(fs::path(kAssets) / "sprites", assets / "sprites");
    const std::vector<std::string> sprites = listing(assets / "sprites");
    const std::string s = scenario("drive.scn", kDrive);
    for (const auto& [report, what] : {std::pair{assets / "sprites", "sprites"}, std::pair{assets / "levels", "levels"}}) {
        const RunResult r = test::run_jostle_binary({"check", "--assets", assets.string(), s, "--report", report.string()});
        EXPECT_EQ(r.status, 2);
        EXPECT_EQ(r.out, "");
        EXPECT_EQ(r.err, "jostle check: --report: '" + report.string() + "' is the " + what +
                             " folder of the assets; give another folder\nRun 'jostle check --help' for usage.\n");
    }
    EXPECT_EQ(listing(assets / "sprites"), sprites);
}

// An update of a scenario kept in the assets' sprites folder is refused before the run: its
// screenshot goldens would be new sprites of the game. A plain check writes nothing there.
TEST_F(Check, AnUpdateOfAScenarioInTheAssetsSpritesFolderIsRefused) {
    const fs::path assets = path("assets");
    fs::create_directories(assets);
    fs::copy(fs::path(kAssets) / "levels", assets / "levels");
    fs::copy(fs::path(kAssets) / "sprites", assets / "sprites");
    const std::string s = scenario("drive.scn", kDrive, assets / "sprites");
    const std::vector<std::string> sprites = listing(assets / "sprites");
    RunResult r = test::run_jostle_binary({"check", "--assets", assets.string(), "--update", s});
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.out, "");
    const std::string why = "the scenario '" + s +
                            "' is in the sprites folder of the assets, where its goldens do not belong (a golden image "
                            "there would be a sprite); give it a folder of its own";
    EXPECT_EQ(r.err, "jostle check: --update: " + why + "\nRun 'jostle check --help' for usage.\n");
    EXPECT_EQ(listing(assets / "sprites"), sprites);
    // A plain check runs it, and says beside the hints that an update is refused.
    r = test::run_jostle_binary({"check", "--assets", assets.string(), s});
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_EQ(r.err, "jostle check: note: " + why + " (--update refuses it)\n");
    EXPECT_EQ(listing(assets / "sprites"), sprites);
}

// The hints give the command that does what they say: this scenario's path as it was given
// (single-quoted when it needs it, after '--' when it starts with '-'), and --assets when it was
// given. The command creates the goldens run by sh -c, and typed into an interactive bash,
// which expands ! inside double quotes.
TEST_F(Check, TheHintsCommandCreatesTheGoldens) {
    const fs::path assets = dir_.path() / "my assets";
    for (const char* part : {"levels", "sprites"}) {
        fs::create_directories(assets / part);
        fs::copy(fs::path(kAssets) / part, assets / part, fs::copy_options::recursive);
    }
    const fs::path cwd = dir_.path() / "work";
    fs::create_directories(cwd);
    const std::string stem = "-my \"drive\" $1 it's\\ !!";
    const std::string given = stem + ".scn";
    scenario(given, kDrive, cwd);
    const std::string quoted = "'-my \"drive\" $1 it'\\''s\\ !!.scn'";
    const std::string assets_text = (fs::path("..") / "my assets").string();
    const std::string command = "jostle check --update --assets '" + assets_text + "' -- " + quoted;

    RunResult r = test::run_jostle_binary({"check", "--assets", assets_text, "--", given}, "/dev/null", cwd.string());
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_EQ(r.out, "FAIL " + given + " (30 ticks, 0 expectations, 1 screenshot)\n"
                     "  trace: no golden " + stem + ".trace (to create it: " + command + ")\n"
                     "  screenshot tick 29: no golden " + stem + ".tick_29.png (to create it: " + command + ")\n"
                     "checked 1 scenario: 0 passed, 1 failed\n");

    // Without --assets (here $JOSTLE_ASSETS says where they are) the command has none.
    env_.set("JOSTLE_ASSETS", assets.string());
    r = test::run_jostle_binary({"check", "--", given}, "/dev/null", cwd.string());
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_THAT(r.out, HasSubstr("(to create it: jostle check --update -- " + quoted + ")\n"));
    env_.unset("JOSTLE_ASSETS");

    // The hint's command, run by the shell where the check ran, with jostle on the PATH.
    const std::string jostle_folder = fs::path(JOSTLE_BINARY).parent_path().string();
    EnvGuard path_guard("PATH", jostle_folder + ":" + (std::getenv("PATH") != nullptr ? std::getenv("PATH") : "/usr/bin:/bin"));
    const std::vector<std::string> blessed = {given, stem + ".tick_29.png", stem + ".trace"};
    for (const bool interactive : {false, true}) {
        for (const std::string& name : blessed) {
            if (name != given) fs::remove(cwd / name);
        }
        if (interactive) {
            // As typed at a prompt: bash -i reading the line from its input, with no startup
            // files and no history file (history expansion stays on, as at a terminal).
            const fs::path typed = dir_.path() / "typed.sh";
            std::ofstream(typed) << command << "\n";
            EnvGuard histfile("HISTFILE", "/dev/null");
            r = test::run_program("/bin/bash", {"--norc", "--noprofile", "-i"}, typed.string(), cwd.string());
        } else {
            r = test::run_program("/bin/sh", {"-c", command}, "/dev/null", cwd.string());
        }
        EXPECT_EQ(r.status, 0) << r.out << r.err;
        EXPECT_THAT(r.err, Not(HasSubstr("event not found")));
        EXPECT_EQ(listing(cwd), blessed) << (interactive ? "bash -i" : "sh -c");
        r = test::run_jostle_binary({"check", "--assets", assets_text, "--", given}, "/dev/null", cwd.string());
        EXPECT_EQ(r.status, 0) << r.out << r.err;
    }
}

TEST_F(Check, AMissingScreenshotGoldenFails) {
    const std::string s = scenario("drive.scn", kDrive);
    bless(s);
    fs::remove(path("drive.tick_29.png"));
    const RunResult r = check({s});
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(r.err, "");
    EXPECT_EQ(r.out, "FAIL " + s + " (30 ticks, 0 expectations, 1 screenshot)\n"
                     "  screenshot tick 29: no golden " + path("drive.tick_29.png") + " (to create it: " + update(s) + ")\n"
                     "checked 1 scenario: 0 passed, 1 failed\n");
    EXPECT_EQ(listing(dir_.path()), (std::vector<std::string>{"drive.scn", "drive.trace"}));
}

TEST_F(Check, AStaleScreenshotGoldenFails) {
    const std::string s = scenario("drive.scn", kDrive);
    bless(s);
    fs::copy_file(path("drive.tick_29.png"), path("drive.tick_5.png"));
    const RunResult r = check({s});
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(r.err, "");
    EXPECT_EQ(r.out, "FAIL " + s + " (30 ticks, 0 expectations, 1 screenshot)\n"
                     "  stale golden " + path("drive.tick_5.png") + ": no screenshot asks for it (to remove it: " + update(s) + ")\n"
                     "checked 1 scenario: 0 passed, 1 failed\n");
    EXPECT_TRUE(fs::exists(path("drive.tick_5.png")));  // only an update removes it
}

// A golden is exactly NAME.tick_T.png with T a tick as the program writes it. Files that only
// start like one (a user's backup, a report's images, a zero-padded or signed tick, a tick
// past the limit) are the user's: never stale, never removed. A real stale golden among them
// is still found, and only it is removed.
TEST_F(Check, OnlyExactGoldenNamesAreStaleAndUpdateRemovesNothingElse) {
    const std::string s = scenario("drive.scn", kDrive);
    bless(s);
    const std::vector<std::string> users = {
        "drive.tick_29.orig.png", "drive.tick_before-fix.png", "drive.tick_29.actual.png", "drive.tick_29.diff.png",
        "drive.tick_29.expected.png", "drive.tick_029.png", "drive.tick_+5.png", "drive.tick_-5.png", "drive.tick_.png",
        "drive.tick_5 .png", "drive.tick_16777216.png", "drive.tick_99999999999999999999.png", "drive.tick_5.PNG",
        "drive.tick_5.png.bak", "drivex.tick_5.png"};
    for (const std::string& name : users) fs::copy_file(path("drive.tick_29.png"), path(name));

    RunResult r = check({folder()});
    EXPECT_EQ(r.status, 0) << r.out;
    EXPECT_EQ(r.err, "");
    EXPECT_EQ(r.out, pass_line(s, 30, 1) + "\nchecked 1 scenario: 1 passed, 0 failed\n");

    fs::copy_file(path("drive.tick_29.png"), path("drive.tick_5.png"));
    r = check({folder()});
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(r.out, "FAIL " + s + " (30 ticks, 0 expectations, 1 screenshot)\n"
                     "  stale golden " + path("drive.tick_5.png") + ": no screenshot asks for it (to remove it: " + update(s) + ")\n"
                     "checked 1 scenario: 0 passed, 1 failed\n");

    r = check({"--update", folder()});
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_EQ(r.out, "updated " + s + ": drive.tick_5.png removed\nchecked 1 scenario: 1 updated\n");
    std::vector<std::string> expected = users;
    expected.insert(expected.end(), {"drive.scn", "drive.tick_29.png", "drive.trace"});
    std::sort(expected.begin(), expected.end());
    EXPECT_EQ(listing(dir_.path()), expected);
}

TEST_F(Check, ToleranceAndMaxPixelsLetSmallScreenshotDifferencesPass) {
    const std::string s = scenario("drive.scn", kDrive);
    bless(s);
    // Three pixels of the golden off by 5 in one channel each (a driver's rounding, say).
    Image golden = read_png(path("drive.tick_29.png"));
    for (const std::size_t pixel : {0u, 1000u, 2000u}) {
        std::uint8_t& red = golden.rgba[pixel * 4];
        red = static_cast<std::uint8_t>(red >= 5 ? red - 5 : red + 5);
    }
    write_png_atomic(path("drive.tick_29.png"), golden);
    const auto status_with = [&](std::vector<std::string> options) {
        options.insert(options.begin(), s);
        return check(options).status;
    };
    EXPECT_EQ(status_with({}), 1);  // exact by default
    EXPECT_EQ(status_with({"--tolerance", "5"}), 0);
    EXPECT_EQ(status_with({"--tolerance", "4"}), 1);
    EXPECT_EQ(status_with({"--max-pixels", "3"}), 0);
    EXPECT_EQ(status_with({"--max-pixels", "2"}), 1);
    EXPECT_EQ(status_with({"--tolerance", "4", "--max-pixels", "3"}), 0);
    const RunResult pass = check({s, "--tolerance", "5"});
    EXPECT_EQ(pass.out, pass_line(s, 30, 1) + "\nchecked 1 scenario: 1 passed, 0 failed\n");
    EXPECT_EQ(pass.err, "");
}

// ---- --update --------------------------------------------------------------------------

TEST_F(Check, UpdateCreatesChangesAndRemovesGoldensSayingHow) {
    const std::string a = scenario("a.scn", kDrive);
    const std::string b = scenario("b.scn", kTurn);
    RunResult r = check({"--update", folder()});
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_EQ(r.out, "updated " + a + ": trace created, a.tick_29.png created\n"
                     "updated " + b + ": trace created\n"
                     "checked 2 scenarios: 2 updated\n");
    EXPECT_EQ(listing(dir_.path()), (std::vector<std::string>{"a.scn", "a.tick_29.png", "a.trace", "b.scn", "b.trace"}));

    r = check({folder()});
    EXPECT_EQ(r.status, 0) << r.out;
    EXPECT_EQ(r.out, pass_line(a, 30, 1) + "\n" + pass_line(b, 5, 0) + "\nchecked 2 scenarios: 2 passed, 0 failed\n");

    // a.scn now drives from tick 15 (its trace first differs on tick 10, where the old run
    // started driving) and adds a screenshot; a.tick_3.png is stale. b.scn is unchanged, so
    // it is reported as it is checked.
    scenario("a.scn", kDriveLater);
    fs::copy_file(path("a.tick_29.png"), path("a.tick_3.png"));
    r = check({"--update", folder()});
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_EQ(r.out, pass_line(b, 5, 0) + "\n"
                     "updated " + a + ": trace changed from tick 10, a.tick_25.png created, a.tick_29.png changed, a.tick_3.png removed\n"
                     "checked 2 scenarios: 1 updated\n");
    EXPECT_EQ(listing(dir_.path()), (std::vector<std::string>{"a.scn", "a.tick_25.png", "a.tick_29.png", "a.trace", "b.scn", "b.trace"}));

    r = check({folder()});
    EXPECT_EQ(r.status, 0) << r.out;
    EXPECT_EQ(r.out, pass_line(a, 30, 2) + "\n" + pass_line(b, 5, 0) + "\nchecked 2 scenarios: 2 passed, 0 failed\n");

    // Nothing left to change: no file is touched.
    const auto before = snapshot(dir_.path());
    r = check({"--update", folder()});
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_EQ(r.out, pass_line(a, 30, 2) + "\n" + pass_line(b, 5, 0) + "\nchecked 2 scenarios: 0 updated\n");
    EXPECT_TRUE(snapshot(dir_.path()) == before);
}

TEST_F(Check, UpdateWithBadInputWritesNothing) {
    const std::string bad = scenario("bad.scn", "0 up\n1 jump\n");
    const std::string good = scenario("good.scn", kDrive);  // no goldens yet
    fs::path stale = path("good.tick_3.png");
    std::ofstream(stale, std::ios::binary) << "not looked at";
    const auto before = snapshot(dir_.path());
    const RunResult r = check({"--update", folder()});
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.out, "ERROR " + bad + ": " + bad +
                         ":8:3: unknown action 'jump' (expected one of: left, right, up, down, fire, or '-' for none)\n"
                         "checked 2 scenarios: 0 passed, 1 failed, 1 with bad input\n");
    EXPECT_EQ(r.err, "jostle check: nothing updated: fix the bad input first\n");
    EXPECT_TRUE(snapshot(dir_.path()) == before);
    EXPECT_EQ(listing(dir_.path()), (std::vector<std::string>{"bad.scn", "good.scn", "good.tick_3.png"}));
}

// An update re-blesses traces and screenshots, but an expectation is the scenario's own claim:
// a failing one is reported as in a plain check and makes the update exit 1.
TEST_F(Check, UpdateCannotFixAFailingExpectation) {
    const std::string s = scenario("e.scn", "0-9 up\nat 9 expect var score = 5\nat 10 end\n");
    RunResult r = check({"--update", s});
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(r.err, "");
    EXPECT_EQ(r.out, "FAIL " + s + " (10 ticks, 1 expectation, 0 screenshots)\n"
                     "  trace: no golden " + path("e.trace") + " (to create it: " + update(s) + ")\n"
                     "  " + s + ":8: expectation failed at tick 9: expected var score = 5, found score = 0\n"
                     "updated " + s + ": trace created\n"
                     "checked 1 scenario: 1 updated, 1 with failing expectations (an update cannot fix those)\n");
    EXPECT_TRUE(fs::exists(path("e.trace"))) << "the trace is still blessed";

    r = check({"--update", s});
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(r.out, "FAIL " + s + " (10 ticks, 1 expectation, 0 screenshots)\n"
                     "  " + s + ":8: expectation failed at tick 9: expected var score = 5, found score = 0\n"
                     "checked 1 scenario: 0 updated, 1 with failing expectations (an update cannot fix those)\n");
}

// A golden that cannot be read (a merge conflict in the trace, a truncated PNG) fails the
// check with the reason, and an update replaces it.
TEST_F(Check, UnreadableGoldensFailAndAnUpdateReplacesThem) {
    const std::string s = scenario("drive.scn", kDrive);
    bless(s);
    const std::string trace = read_text(path("drive.trace"));
    const std::string png = read_text(path("drive.tick_29.png"));
    std::ofstream(path("drive.trace"), std::ios::binary) << "<<<<<<< HEAD\n" << trace;
    std::ofstream(path("drive.tick_29.png"), std::ios::binary) << png.substr(0, png.size() / 2);

    RunResult r = check({s});
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(r.err, "");
    EXPECT_THAT(r.out, HasSubstr("FAIL " + s + " (30 ticks, 0 expectations, 1 screenshot)\n"
                                 "  trace: the golden cannot be read: " + path("drive.trace") + ":1:"));
    EXPECT_THAT(r.out, HasSubstr("(to replace it: " + update(s) + ")\n"
                                 "  screenshot tick 29: the golden cannot be read: " + path("drive.tick_29.png")));
    EXPECT_THAT(r.out, HasSubstr("checked 1 scenario: 0 passed, 1 failed\n"));

    r = check({"--update", s});
    EXPECT_EQ(r.status, 0) << r.out << r.err;
    EXPECT_EQ(r.out, "updated " + s + ": trace replaced (it could not be read), drive.tick_29.png replaced (it could not be read)\n"
                     "checked 1 scenario: 1 updated\n");
    EXPECT_EQ(read_text(path("drive.trace")), trace);
    EXPECT_EQ(read_text(path("drive.tick_29.png")), png);
}

// ---- sharding --------------------------------------------------------------------------

TEST_F(Check, ShardsCheckEveryTotalthScenarioAndTouchTheStatusFile) {
    std::vector<std::string> all;
    for (int i = 0; i < 5; ++i) {
        all.push_back(scenario(std::string("s") + std::to_string(i) + ".scn", kTurn));
        bless(all.back());
    }
    for (const std::string prefix : {"TEST_", "GTEST_"}) {
        std::set<std::string> seen;
        for (int index = 0; index < 3; ++index) {
            SCOPED_TRACE(prefix + "SHARD_INDEX " + std::to_string(index));
            const std::string status = path(prefix + "status_" + std::to_string(index));
            EnvGuard env;
            env.set(prefix + "TOTAL_SHARDS", "3");
            env.set(prefix + "SHARD_INDEX", std::to_string(index));
            env.set(prefix + "SHARD_STATUS_FILE", status);
            const RunResult r = check({folder()});
            EXPECT_EQ(r.status, 0) << r.err;
            EXPECT_EQ(r.err, "");
            std::string expected;
            int count = 0;
            for (int i = index; i < 5; i += 3) {
                expected += pass_line(all[static_cast<std::size_t>(i)], 5, 0) + "\n";
                ++count;
                EXPECT_TRUE(seen.insert(all[static_cast<std::size_t>(i)]).second);
            }
            expected += std::string("checked ") + std::to_string(count) + (count == 1 ? " scenario: " : " scenarios: ") + std::to_string(count) + " passed, 0 failed\n";
            EXPECT_EQ(r.out, expected);
            EXPECT_TRUE(fs::exists(status));
        }
        EXPECT_EQ(seen, std::set<std::string>(all.begin(), all.end()));
    }

    // In process: every third from the index, the status file touched even when no shard is set.
    const std::vector<std::string> names = {"n0", "n1", "n2", "n3", "n4", "n5", "n6"};
    {
        EnvGuard env;
        env.set("TEST_TOTAL_SHARDS", "3");
        env.set("TEST_SHARD_INDEX", "1");
        EXPECT_EQ(select_shard(names), (std::vector<std::string>{"n1", "n4"}));
        env.set("TEST_SHARD_INDEX", "2");
        EXPECT_EQ(select_shard(names), (std::vector<std::string>{"n2", "n5"}));
        env.set("TEST_TOTAL_SHARDS", "1");
        env.set("TEST_SHARD_INDEX", "0");
        EXPECT_EQ(select_shard(names), names);
    }
    {
        EnvGuard env;
        env.set("TEST_SHARD_STATUS_FILE", path("touched"));
        EXPECT_EQ(select_shard(names), names);
        EXPECT_TRUE(fs::exists(path("touched")));
    }
}

TEST_F(Check, MalformedShardVariablesExitTwo) {
    const std::string s = scenario("s.scn", kTurn);
    struct Case {
        const char* total;  // nullptr: unset
        const char* index;
        std::string message;
    };
    const Case cases[] = {
        {"3", "3", "TEST_SHARD_INDEX 3 must be below TEST_TOTAL_SHARDS 3"},
        {"3", "7", "TEST_SHARD_INDEX 7 must be below TEST_TOTAL_SHARDS 3"},
        {"0", "0", "TEST_TOTAL_SHARDS: expected a whole number >= 1, got '0'"},
        {"1", "1", "TEST_SHARD_INDEX 1 must be below TEST_TOTAL_SHARDS 1"},
        {"3", "x", "TEST_SHARD_INDEX: expected a whole number >= 0, got 'x'"},
        {"3", "-1", "TEST_SHARD_INDEX: expected a whole number >= 0, got '-1'"},
        {"3", "1.5", "TEST_SHARD_INDEX: expected a whole number >= 0, got '1.5'"},
        {"three", "0", "TEST_TOTAL_SHARDS: expected a whole number >= 1, got 'three'"},
        {"-3", "0", "TEST_TOTAL_SHARDS: expected a whole number >= 1, got '-3'"},
        {"3", nullptr, "TEST_SHARD_INDEX: expected a whole number >= 0, got ''"},
        {nullptr, "0", "TEST_TOTAL_SHARDS: expected a whole number >= 1, got ''"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.message);
        EnvGuard env;
        if (c.total != nullptr) env.set("TEST_TOTAL_SHARDS", c.total);
        if (c.index != nullptr) env.set("TEST_SHARD_INDEX", c.index);
        const RunResult r = check({s});
        EXPECT_EQ(r.status, 2);
        EXPECT_EQ(r.out, "");
        EXPECT_EQ(r.err, "jostle check: " + c.message + "\n");
    }
}

// ---- which scenarios -------------------------------------------------------------------

TEST_F(Check, AScenarioNamedTwiceByAnySpellingIsCheckedOnce) {
    const fs::path m = dir_.path() / "m";
    fs::create_directories(m);
    const std::string a = scenario("a.scn", kTurn, m);
    const std::string b = scenario("b.scn", kTurn, m);
    bless(a);
    bless(b);
    const std::string dotted = (m / "." / "b.scn").string();
    const std::string up = (m / ".." / "m" / "a.scn").string();
    fs::create_directory_symlink(m, dir_.path() / "link");
    const std::string through_link = (dir_.path() / "link" / "a.scn").string();
    // A link to a.scn by another name is a scenario of its own: its goldens are alias.*.
    fs::create_symlink("a.scn", m / "alias.scn");
    const std::string alias = (m / "alias.scn").string();

    // In process: the first spelling, in the order given; folders in name order.
    EXPECT_EQ(collect_scenarios({m.string(), a, dotted, up, through_link}), (std::vector<std::string>{a, alias, b}));
    EXPECT_EQ(collect_scenarios({dotted, up, m.string(), b, through_link}), (std::vector<std::string>{dotted, up, alias}));
    EXPECT_EQ(collect_scenarios({through_link, a, a}), (std::vector<std::string>{through_link}));

    // End to end: `check M M/b.scn M/./b.scn` checks M's three scenarios once each.
    fs::remove(m / "alias.scn");
    const RunResult r = check({m.string(), b, dotted});
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_EQ(r.out, pass_line(a, 5, 0) + "\n" + pass_line(b, 5, 0) + "\nchecked 2 scenarios: 2 passed, 0 failed\n");
}

// ---- --jobs ----------------------------------------------------------------------------

TEST_F(Check, JobsGiveTheSameResultsAndFilesAsOneJob) {
    // Four scenarios with two screenshots each, in two folders: goldens made by one job in
    // `one`, by four at once in `four` (OSMesa contexts on four threads).
    const fs::path one = dir_.path() / "one";
    const fs::path four = dir_.path() / "four";
    fs::create_directories(one);
    fs::create_directories(four);
    std::vector<std::string> scenarios;
    for (int i = 0; i < 4; ++i) {
        const std::string body = std::string("0-") + std::to_string(4 + 3 * i) + " left\n" + std::to_string(5 + 3 * i) +
                                 "-29 up fire\nat 15 screenshot\nat 29 screenshot\nat 30 end\n";
        const std::string name = std::string("j") + std::to_string(i) + ".scn";
        scenarios.push_back(scenario(name, body, one));
        scenario(name, body, four);
    }
    RunResult r = check({"--update", "--jobs", "1", one.string()});
    ASSERT_EQ(r.status, 0) << r.err;
    r = check({"--update", "--jobs", "4", four.string()});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(lines_of(r.out).size(), 5u) << r.out;  // four "updated" lines, in scenario order, and the summary
    EXPECT_EQ(listing(one), listing(four));
    EXPECT_EQ(listing(one).size(), 16u);  // .scn, .trace, two PNGs each
    for (const std::string& name : listing(one)) {
        EXPECT_TRUE(read_text(one / name) == read_text(four / name)) << name << " differs between --jobs 1 and --jobs 4";
    }

    // Each folder checked by 1, 2 and 4 jobs: the same output, all PASS in scenario order, the
    // summary last.
    for (const fs::path& where : {one, four}) {
        std::string expected;
        for (const char* name : {"j0.scn", "j1.scn", "j2.scn", "j3.scn"}) expected += pass_line((where / name).string(), 30, 2) + "\n";
        expected += "checked 4 scenarios: 4 passed, 0 failed\n";
        r = check({"--jobs", "1", where.string()});
        EXPECT_EQ(r.status, 0);
        EXPECT_EQ(r.out, expected);
        for (const char* jobs : {"2", "4"}) {
            SCOPED_TRACE(where.filename().string() + " --jobs " + jobs);
            r = check({"--jobs", jobs, where.string()});
            EXPECT_EQ(r.status, 0);
            EXPECT_EQ(r.err, "");
            EXPECT_EQ(r.out, expected);
        }
    }

    // One scenario regresses: the run says so for exactly that one.
    const std::string changed = scenario("j2.scn", "0-29 right\nat 15 screenshot\nat 29 screenshot\nat 30 end\n", one);
    r = check({"--jobs", "4", one.string()});
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(r.err, "");
    const std::vector<std::string> lines = lines_of(r.out);
    ASSERT_FALSE(lines.empty());
    EXPECT_EQ(lines.back(), "checked 4 scenarios: 3 passed, 1 failed");
    std::vector<std::string> verdicts;
    for (const std::string& line : lines) {
        if (line.rfind("PASS ", 0) == 0 || line.rfind("FAIL ", 0) == 0) verdicts.push_back(line);
    }
    std::sort(verdicts.begin(), verdicts.end());
    EXPECT_EQ(verdicts, (std::vector<std::string>{"FAIL " + changed + " (30 ticks, 0 expectations, 2 screenshots)",
                                                  pass_line(scenarios[0], 30, 2), pass_line(scenarios[1], 30, 2),
                                                  pass_line(scenarios[3], 30, 2)}));
    // The details of the failure are the same as one job prints, in the same order.
    const RunResult serial = check({"--jobs", "1", one.string()});
    EXPECT_EQ(serial.status, 1);
    EXPECT_EQ(r.out, serial.out);
}

TEST_F(Check, JobsPrintTheResultsInScenarioOrder) {
    // The first scenario takes far longer than the four after it: the other job checks those
    // while the first one runs, and their results wait for it.
    std::vector<std::string> scenarios;
    scenarios.push_back(scenario("a_long.scn", "0-29999 left\nat 30000 end\n"));
    for (const char* name : {"b1.scn", "b2.scn", "b3.scn", "b4.scn"}) scenarios.push_back(scenario(name, kTurn));
    for (const std::string& s : scenarios) bless(s);
    std::string expected = pass_line(scenarios[0], 30000, 0) + "\n";
    for (std::size_t i = 1; i < scenarios.size(); ++i) expected += pass_line(scenarios[i], 5, 0) + "\n";
    expected += "checked 5 scenarios: 5 passed, 0 failed\n";
    for (const char* jobs : {"2", "3"}) {
        SCOPED_TRACE(std::string("--jobs ") + jobs);
        const RunResult r = check({"--jobs", jobs, folder()});
        EXPECT_EQ(r.status, 0) << r.err;
        EXPECT_EQ(r.err, "");
        EXPECT_EQ(r.out, expected);
    }
}

// ---- usage -----------------------------------------------------------------------------

TEST_F(Check, UsageErrorsExitTwoWithTheirMessage) {
    const std::string s = scenario("s.scn", kTurn);
    struct Case {
        std::vector<std::string> args;
        std::string message;
    };
    const Case cases[] = {
        {{s, "--jobs", "0"}, "--jobs: expected a whole number from 1 to 256, got '0'"},
        {{s, "--jobs", "x"}, "--jobs: expected a whole number from 1 to 256, got 'x'"},
        {{s, "--jobs", "257"}, "--jobs: expected a whole number from 1 to 256, got '257'"},
        {{s, "--jobs", "-2"}, "--jobs: expected a whole number from 1 to 256, got '-2'"},
        {{s, "--jobs", "+2"}, "--jobs: expected a whole number from 1 to 256, got '+2' (a number here is written without a sign)"},
        {{s, "--jobs", "+999"}, "--jobs: expected a whole number from 1 to 256, got '+999'"},  // no sign would help
        {{s, "--jobs", "-0"}, "--jobs: expected a whole number from 1 to 256, got '-0'"},
        {{s, "--tolerance", "-0"}, "--tolerance: expected a whole number from 0 to 255, got '-0' (a number here is written without a sign)"},
        {{s, "--tolerance", "256"}, "--tolerance: expected a whole number from 0 to 255, got '256'"},
        {{s, "--tolerance", "-1"}, "--tolerance: expected a whole number from 0 to 255, got '-1'"},
        {{s, "--max-pixels", "-1"}, "--max-pixels: expected a whole number from 0 to 9223372036854775807, got '-1'"},
        {{s, "--max-pixels", "many"}, "--max-pixels: expected a whole number from 0 to 9223372036854775807, got 'many'"},
        {{s, "--max-pixels", "18446744073709551615"},
         "--max-pixels: expected a whole number from 0 to 9223372036854775807, got '18446744073709551615'"},
        {{s, "--fast"}, "unknown option '--fast'"},
        {{"-u", s}, "unknown option '-u'"},
        {{s, "--jobs"}, "--jobs needs a value"},
        {{s, "--tolerance"}, "--tolerance needs a value"},
        {{s, "--report"}, "--report needs a value"},
        {{s, "--report", ""}, "--report needs a value"},
        {{s, "--report", "--update"},
         "--report needs a value, got the option '--update' (a path that begins with '-' is written ./--update)"},
        {{s, "--jobs", "1", "--jobs", "2"}, "--jobs given twice"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.message);
        const RunResult r = check(c.args);
        EXPECT_EQ(r.status, 2);
        EXPECT_EQ(r.out, "");
        EXPECT_EQ(r.err, usage_error(c.message));
    }
    EXPECT_EQ(listing(dir_.path()), std::vector<std::string>{"s.scn"});

    // A path that does not exist is bad input, named.
    const std::string missing = path("nowhere.scn");
    const RunResult r = check({s, missing});
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(r.err, "jostle check: " + missing + ": no such scenario file or folder\n");

    const RunResult help = test::run_jostle_binary({"check", "--help"});
    EXPECT_EQ(help.status, 0);
    EXPECT_EQ(help.out, check_help());
    EXPECT_EQ(help.err, "");
    // Anywhere an option may stand, as right after the command.
    const RunResult later = test::run_jostle_binary({"check", s, "--jobs", "2", "-h"});
    EXPECT_EQ(later.status, 0);
    EXPECT_EQ(later.out, check_help());
}

// ---- --report --------------------------------------------------------------------------

// A report into a folder of the scenarios checked would mix its images and pages with the
// goldens (and be committed with them): a usage error before anything runs, however the
// folder is written. A folder below it, or another scenario's folder, is fine.
TEST_F(Check, AReportIntoAScenarioFolderIsRefusedBeforeTheRun) {
    const fs::path other = dir_.path() / "other";
    fs::create_directories(other);
    const std::string s = scenario("drive.scn", kDrive);
    const std::string t = scenario("turn.scn", kTurn, other);
    bless(s);
    bless(t);
    const auto before = snapshot(dir_.path());
    const auto before_other = snapshot(other);
    const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
        {{s, "--report", folder()}, folder()},
        {{s, "--update", "--report", folder() + "/."}, folder() + "/."},
        {{t, folder(), "--report", (other / ".." / "other").string()}, (other / ".." / "other").string()},
    };
    for (const auto& [args, report] : cases) {
        SCOPED_TRACE(report);
        const std::string first = args[0] == t ? t : s;
        const RunResult r = check(args);
        EXPECT_EQ(r.status, 2);
        EXPECT_EQ(r.out, "");
        EXPECT_EQ(r.err, usage_error("--report: '" + report + "' holds the scenario '" + first +
                                     "' and its goldens; give the report a folder of its own"));
        EXPECT_TRUE(snapshot(dir_.path()) == before);
        EXPECT_TRUE(snapshot(other) == before_other);
    }
    // Relative to the working folder, as typed.
    const RunResult r = test::run_jostle_binary({"check", "--assets", kAssets, "drive.scn", "--report", "."}, "/dev/null", folder());
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.err, usage_error("--report: '.' holds the scenario 'drive.scn' and its goldens; give the report a folder of its own"));
    EXPECT_TRUE(snapshot(dir_.path()) == before);

    // Another scenario's folder, or one below this one's, holds no golden of the scenarios checked.
    const RunResult below = check({s, "--report", (dir_.path() / "report").string()});
    EXPECT_EQ(below.status, 0) << below.out << below.err;
    const RunResult elsewhere = check({s, "--report", other.string()});
    EXPECT_EQ(elsewhere.status, 0) << elsewhere.out << elsewhere.err;
    EXPECT_TRUE(fs::exists(other / "report.html"));
}

// The elements <img class="C" src="S"> of an HTML text, as (C, S).
std::vector<std::pair<std::string, std::string>> images_in(const std::string& html) {
    std::vector<std::pair<std::string, std::string>> out;
    const std::string open = "<img class=\"";
    for (std::size_t at = html.find(open); at != std::string::npos; at = html.find(open, at + 1)) {
        const std::size_t class_start = at + open.size();
        const std::size_t class_end = html.find('"', class_start);
        const std::string src = " src=\"";
        if (class_end == std::string::npos || html.compare(class_end + 1, src.size(), src) != 0) {
            ADD_FAILURE() << "unexpected img element at " << at;
            break;
        }
        const std::size_t src_start = class_end + 1 + src.size();
        const std::size_t src_end = html.find('"', src_start);
        out.emplace_back(html.substr(class_start, class_end - class_start), html.substr(src_start, src_end - src_start));
    }
    return out;
}

TEST_F(Check, ReportShowsTheFailingScenarioWithItsImages) {
    const std::string fail = scenario("fail.scn", kDrive);
    const std::string pass = scenario("pass.scn", kDrive);
    bless(fail);
    bless(pass);
    // Now idle on tick 10, where the golden drives; the new screenshot at 25 has no golden.
    scenario("fail.scn", kDriveLater);
    const fs::path report = dir_.path() / "report";
    const RunResult r = check({folder(), "--report", report.string()});
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(r.err, "");
    EXPECT_THAT(r.out, HasSubstr("FAIL " + fail + " (30 ticks, 0 expectations, 2 screenshots)\n"
                                 "  trace: first divergent tick 10 (expected hash "));
    EXPECT_THAT(r.out, HasSubstr(std::string("\n") + pass_line(pass, 30, 1) + "\nchecked 2 scenarios: 1 passed, 1 failed\n"));

    const std::string html = read_text(report / "report.html");
    EXPECT_THAT(html, HasSubstr("<h1>jostle check: 1 of 2 scenarios failed</h1>"));
    EXPECT_THAT(html, HasSubstr("<h2 class=\"fail\">" + fail + "</h2>"));
    EXPECT_THAT(html, ::testing::Not(HasSubstr(pass)));  // only failures are shown
    EXPECT_THAT(html, HasSubstr("<b class=\"first-divergent-tick\">10</b>"));
    EXPECT_THAT(html, HasSubstr("<tr><td>player</td><td>x</td><td>102.5</td><td>100</td></tr>"));
    // Tick 25 has no golden: only the actual image. Tick 29 differs: all three.
    const auto images = images_in(html);
    EXPECT_EQ(images, (std::vector<std::pair<std::string, std::string>>{{"actual", "fail.tick_25.actual.png"},
                                                                        {"expected", "fail.tick_29.expected.png"},
                                                                        {"actual", "fail.tick_29.actual.png"},
                                                                        {"diff", "fail.tick_29.diff.png"}}));
    for (const auto& [cls, src] : images) {
        EXPECT_TRUE(fs::exists(report / src)) << src;
        if (fs::exists(report / src)) {
            const Image im = read_png((report / src).string());
            EXPECT_EQ(im.width, 640) << src;
            EXPECT_EQ(im.height, 480) << src;
        }
    }
    EXPECT_GT(red_pixels(read_png((report / "fail.tick_29.diff.png").string())), 0);
    EXPECT_EQ(listing(report), (std::vector<std::string>{"fail.tick_25.actual.png", "fail.tick_29.actual.png", "fail.tick_29.diff.png",
                                                         "fail.tick_29.expected.png", "junit.xml", "report.html"}));

    // junit.xml: both scenarios, a failure only for the failing one.
    const std::string xml = read_text(report / "junit.xml");
    EXPECT_THAT(xml, HasSubstr("<testsuite name=\"jostle.scenarios\" tests=\"2\" failures=\"1\" time=\""));
    const std::vector<std::string> lines = lines_of(xml);
    std::vector<std::string> testcases;
    for (const std::string& line : lines) {
        if (line.rfind("  <testcase ", 0) == 0) testcases.push_back(line);
    }
    ASSERT_EQ(testcases.size(), 2u) << xml;
    EXPECT_THAT(testcases[0], ::testing::StartsWith("  <testcase classname=\"scenario\" name=\"fail\" file=\"" + fail + "\" time=\""));
    EXPECT_THAT(testcases[0], ::testing::EndsWith("\">"));  // with a <failure> inside
    EXPECT_THAT(testcases[1], ::testing::StartsWith("  <testcase classname=\"scenario\" name=\"pass\" file=\"" + pass + "\" time=\""));
    EXPECT_THAT(testcases[1], ::testing::EndsWith("\"/>"));  // passed: empty
    std::size_t failures = 0;
    for (std::size_t at = xml.find("<failure "); at != std::string::npos; at = xml.find("<failure ", at + 1)) ++failures;
    EXPECT_EQ(failures, 1u);
    EXPECT_THAT(xml, HasSubstr("<failure message=\"regression\">FAIL " + fail + " (30 ticks"));

    // The same folder again once fail.scn is re-blessed and a third scenario fails: the first
    // report's images go (they would read as this run's failures), the user's files stay.
    bless(fail);
    const std::string other = scenario("other.scn", kDrive);
    bless(other);
    scenario("other.scn", kDriveLater);
    for (const char* mine : {"notes.txt", "fail.tick_29.png", "fail.tick_29.orig.png", "fail.tick_x.diff.png"})
        std::ofstream(report / mine) << "mine";
    const RunResult again = check({folder(), "--report", report.string()});
    EXPECT_EQ(again.status, 1);
    EXPECT_EQ(listing(report), (std::vector<std::string>{"fail.tick_29.orig.png", "fail.tick_29.png", "fail.tick_x.diff.png",
                                                         "junit.xml", "notes.txt", "other.tick_25.actual.png",
                                                         "other.tick_29.actual.png", "other.tick_29.diff.png",
                                                         "other.tick_29.expected.png", "report.html"}));
}

}  // namespace
}  // namespace jostle
