// interrupt_test.cpp: Ctrl-C during `check --update`, `play` and `record`. An update
// interrupted at any moment changes no golden or all of them (never some), and leaves no
// temporary file; an interrupted play leaves only whole frames; an interrupted record writes
// nothing. Each interrupted run exits 130 and says so. The deterministic cases use the check
// command's JOSTLE_TEST_INTERRUPT hook (a signal after the first scenario is checked, or after
// the first new golden is staged); the rest send SIGINT at spread-out moments.
#include <csignal>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "arena.h"
#include "game/run_jostle.h"
#include "jostle/core/interrupt.h"
#include "jostle/render/png_io.h"
#include "jostle/replay/check.h"
#include "test_support.h"

namespace jostle {
namespace {

namespace fs = std::filesystem;

using test::EnvGuard;
using test::read_text;

const std::string kAssets = JOSTLE_ASSETS_DIR;
const std::string kInterrupted =
    "jostle: interrupted by SIGINT: stopped; files it finished are complete, unfinished ones were removed\n";

// Every file in a folder (not recursive) with its contents.
std::map<std::string, std::string> snapshot(const fs::path& folder) {
    std::map<std::string, std::string> files;
    for (const auto& entry : fs::directory_iterator(folder)) files[entry.path().filename().string()] = read_text(entry.path());
    return files;
}

// Equal folder snapshots, or the names of the files that differ (the contents are too long to print).
::testing::AssertionResult same_files(const std::map<std::string, std::string>& a, const std::map<std::string, std::string>& b) {
    if (a == b) return ::testing::AssertionSuccess();
    std::string names;
    for (const auto& [name, text] : a) {
        if (!b.contains(name)) names += " -" + name;
        else if (b.at(name) != text) names += " ~" + name;
    }
    for (const auto& [name, text] : b) {
        if (!a.contains(name)) names += " +" + name;
    }
    return ::testing::AssertionFailure() << "the files differ:" << names;
}

std::vector<std::string> temp_files(const fs::path& folder) {
    std::vector<std::string> found;
    for (const auto& entry : fs::recursive_directory_iterator(folder)) {
        if (entry.path().extension() == ".tmp") found.push_back(entry.path().string());
    }
    return found;
}

class Interrupt : public ::testing::Test {
protected:
    void SetUp() override {
        fs::create_directories(dir_.path() / "scenarios");
        level_hash_ = game::ArenaGame(kAssets).level_hash("arena");
    }

    fs::path scenarios() const { return dir_.path() / "scenarios"; }

    // An arena scenario: the ship turns, then drives, with a screenshot at `shot`.
    void scenario(const std::string& name, int turn_ticks, int drive_ticks, int shot) {
        std::ofstream(scenarios() / (name + ".scn"), std::ios::binary)
            << "jostle-scenario 1\nengine 0.1.0\nlevel arena\nseed 1\ntick-rate 60\nlevel-hash " << level_hash_ << "\n\n"
            << "0-" << turn_ticks - 1 << " left\n"
            << turn_ticks << "-" << turn_ticks + drive_ticks - 1 << " up\n"
            << "at " << shot << " screenshot\n";
    }

    // Three scenarios with goldens, then one golden made stale and one scenario with none, so
    // an update has something to change, to create and to keep.
    void suite_needing_update() {
        scenario("a", 10, 40, 30);
        scenario("b", 20, 40, 45);
        scenario("c", 5, 30, 20);
        ASSERT_EQ(check({"--update"}).status, 0);
        scenario("a", 12, 40, 30);  // changed: its trace and screenshot no longer match
        fs::remove(scenarios() / "b.trace");
        fs::remove(scenarios() / "b.tick_45.png");
    }

    test::RunResult check(std::vector<std::string> args, int sigint_after_ms = -1) {
        args.insert(args.begin(), {"check", "--assets", kAssets});
        args.push_back(scenarios().string());
        return test::run_jostle_binary(args, "/dev/null", "", sigint_after_ms);
    }

    const test::TempFolder dir_{"interrupt"};
    std::string level_hash_;
};

TEST_F(Interrupt, UpdateInterruptedAfterTheFirstGoldenIsStagedChangesNothing) {
    suite_needing_update();
    const auto before = snapshot(scenarios());
    const EnvGuard hook("JOSTLE_TEST_INTERRUPT", "after-staged");
    const test::RunResult r = check({"--update"});
    EXPECT_EQ(r.status, 130);
    EXPECT_EQ(r.err, kInterrupted);
    EXPECT_TRUE(same_files(snapshot(scenarios()), before));
    EXPECT_EQ(temp_files(dir_.path()), std::vector<std::string>{});
}

TEST_F(Interrupt, UpdateInterruptedBetweenScenariosChangesNothing) {
    suite_needing_update();
    const auto before = snapshot(scenarios());
    const EnvGuard hook("JOSTLE_TEST_INTERRUPT", "after-check");
    for (const char* jobs : {"1", "2"}) {
        const test::RunResult r = check({"--update", "--jobs", jobs});
        EXPECT_EQ(r.status, 130) << "--jobs " << jobs;
        EXPECT_EQ(r.err, kInterrupted);
        EXPECT_TRUE(same_files(snapshot(scenarios()), before));
        EXPECT_EQ(temp_files(dir_.path()), std::vector<std::string>{});
    }
}

TEST_F(Interrupt, PlainCheckInterruptedSaysSo) {
    scenario("a", 10, 40, 30);
    scenario("b", 10, 40, 30);
    ASSERT_EQ(check({"--update"}).status, 0);
    const EnvGuard hook("JOSTLE_TEST_INTERRUPT", "after-check");
    const test::RunResult r = check({});
    EXPECT_EQ(r.status, 130);
    EXPECT_EQ(r.err, kInterrupted);
    EXPECT_EQ(r.out.find("checked "), std::string::npos) << "no summary of a run that did not finish:\n" << r.out;
}

// SIGINT at moments spread over the whole update: each run leaves the goldens all old or all
// new, never a mix, and no temporary file.
TEST_F(Interrupt, UpdateInterruptedAnywhereIsAllOrNothing) {
    suite_needing_update();
    const auto before = snapshot(scenarios());
    const fs::path saved = dir_.path() / "saved";
    fs::copy(scenarios(), saved);
    ASSERT_EQ(check({"--update"}).status, 0);
    const auto after = snapshot(scenarios());
    ASSERT_FALSE(same_files(before, after));

    int interrupted = 0;
    for (int delay_ms : {0, 5, 20, 40, 60, 80, 100, 130, 160, 200, 250, 300}) {
        fs::remove_all(scenarios());
        fs::copy(saved, scenarios());
        const test::RunResult r = check({"--update"}, delay_ms);
        const auto now = snapshot(scenarios());
        EXPECT_TRUE(now == before || now == after) << "half-updated goldens after SIGINT at " << delay_ms << " ms";
        EXPECT_EQ(temp_files(dir_.path()), std::vector<std::string>{}) << delay_ms << " ms";
        if (r.status == 130) {
            ++interrupted;
            EXPECT_EQ(r.err, kInterrupted);
        } else if (r.term_signal == SIGINT) {
            // Killed by the default action: while starting, before the handler was installed
            // (nothing done), or while exiting, after it was removed (all done). Either way the
            // check above holds.
        } else {
            EXPECT_EQ(r.status, 0) << "SIGINT at " << delay_ms << " ms: " << r.err;
            EXPECT_TRUE(same_files(now, after)) << delay_ms << " ms";
        }
    }
    EXPECT_GT(interrupted, 0) << "no run was interrupted: the delays miss the update";
}

TEST_F(Interrupt, PlayInterruptedLeavesOnlyWholeFrames) {
    std::ofstream(dir_.path() / "long.scn", std::ios::binary)
        << "jostle-scenario 1\nengine 0.1.0\nlevel arena\nseed 1\ntick-rate 60\nlevel-hash " << level_hash_ << "\n\n"
        << "0-2999 up\n3000-5999 left up\n";
    int interrupted = 0;
    for (int delay_ms : {0, 50, 150, 300, 600}) {
        const fs::path out = dir_.path() / ("frames_" + std::to_string(delay_ms));
        const fs::path anim = dir_.path() / ("run_" + std::to_string(delay_ms) + ".png");
        const test::RunResult r = test::run_jostle_binary(
            {"play", dir_.file("long.scn"), "--assets", kAssets, "--out", out.string(), "--size", "160x120",
             "--anim", anim.string()},
            "/dev/null", "", delay_ms);
        if (r.status == 130) {
            ++interrupted;
            EXPECT_EQ(r.err, kInterrupted);
            EXPECT_FALSE(fs::exists(anim)) << "an unfinished animation is removed";
        } else if (r.term_signal == SIGINT) {
            EXPECT_FALSE(fs::exists(anim)) << "killed while starting";
        } else {
            EXPECT_EQ(r.status, 0) << r.err;
        }
        if (fs::exists(out)) {
            for (const auto& entry : fs::directory_iterator(out)) {
                EXPECT_NO_THROW(read_png(entry.path().string())) << entry.path() << " after SIGINT at " << delay_ms << " ms";
            }
        }
        EXPECT_EQ(temp_files(dir_.path()), std::vector<std::string>{}) << delay_ms << " ms";
    }
    EXPECT_GT(interrupted, 0);
}

TEST_F(Interrupt, RecordInterruptedWritesNothing) {
    std::ofstream(dir_.path() / "script.txt") << "hold up 200000\n";
    const fs::path scn = dir_.path() / "out.scn";
    const test::RunResult r = test::run_jostle_binary(
        {"record", "--assets", kAssets, "--level", "arena", "-o", scn.string(), "--script", dir_.file("script.txt")},
        "/dev/null", "", 300);
    EXPECT_EQ(r.status, 130);
    EXPECT_EQ(r.err, kInterrupted);
    EXPECT_FALSE(fs::exists(scn));
    EXPECT_EQ(temp_files(dir_.path()), std::vector<std::string>{});
}

// The library's side, in this process: a signal while commit_updates stages its files makes
// it throw Interrupted with every temporary file removed and no golden touched.
TEST_F(Interrupt, CommitUpdatesStopsBeforeRenamingAnything) {
    suite_needing_update();
    const auto before = snapshot(scenarios());
    const game::ArenaGame game(kAssets);
    std::vector<ScenarioCheck> checks;
    for (const std::string& path : collect_scenarios({scenarios().string()})) checks.push_back(check_scenario(game, path));

    const InterruptHandler handler;
    std::vector<std::string> staged;
    EXPECT_THROW(commit_updates(checks,
                                [&](const std::string& golden) {
                                    staged.push_back(fs::path(golden).filename().string());
                                    if (staged.size() == 2) std::raise(SIGINT);
                                }),
                 Interrupted);
    EXPECT_EQ(staged, (std::vector<std::string>{"a.trace", "a.tick_30.png"}));
    EXPECT_TRUE(same_files(snapshot(scenarios()), before));
    EXPECT_EQ(temp_files(dir_.path()), std::vector<std::string>{});
}

}  // namespace
}  // namespace jostle
