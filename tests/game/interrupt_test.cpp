// interrupt_test.cpp: Ctrl-C during `check --update`, `play` and `record`. An update
// interrupted at any moment changes no golden or all of them (never some), and leaves no
// temporary file; an interrupted play leaves only whole frames; an interrupted record writes
// nothing. Each interrupted run exits 130 and says so. The deterministic cases use the check
// command's JOSTLE_TEST_INTERRUPT hook (a signal after the first scenario is checked, or after
// the first new golden is staged); the rest send SIGINT at spread-out moments.
#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "arena.h"
#include "game/run_jostle.h"
#include "jostle/core/interrupt.h"
#include "jostle/core/rng.h"
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

// What a run stopped by `sig` prints (SIGINT or SIGTERM).
std::string interrupted_by(int sig) {
    return std::string("jostle: interrupted by ") + (sig == SIGINT ? "SIGINT" : "SIGTERM") +
           ": stopped; files it finished are complete, unfinished ones were removed\n";
}

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

    test::RunResult check(std::vector<std::string> args, int signal_after_ms = -1, int signal = SIGINT) {
        args.insert(args.begin(), {"check", "--assets", kAssets});
        args.push_back(scenarios().string());
        return test::run_jostle_binary(args, "/dev/null", "", signal_after_ms, -1, signal);
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

// The terminal closing (SIGHUP) stops a run as Ctrl-C does: exit 129, only whole files.
TEST_F(Interrupt, SighupStopsARunCleanly) {
    std::ofstream(dir_.path() / "script.txt") << "hold up 200000\n";
    const fs::path scn = dir_.path() / "out.scn";
    const test::RunResult r = test::run_jostle_binary(
        {"record", "--assets", kAssets, "--level", "arena", "-o", scn.string(), "--script", dir_.file("script.txt")},
        "/dev/null", "", 300, -1, SIGHUP);
    EXPECT_EQ(r.status, 129);
    EXPECT_EQ(r.err, "jostle: interrupted by SIGHUP: stopped; files it finished are complete, unfinished ones were removed\n");
    EXPECT_FALSE(fs::exists(scn));
    EXPECT_EQ(temp_files(dir_.path()), std::vector<std::string>{});
}

// ... unless it is ignored, as under nohup: the run is to outlive the terminal.
TEST_F(Interrupt, AnIgnoredSighupIsLeftIgnored) {
    std::ofstream(dir_.path() / "script.txt") << "hold up 20000\n";
    const fs::path scn = dir_.path() / "out.scn";
    struct sigaction ignore {}, previous {};
    ignore.sa_handler = SIG_IGN;
    sigaction(SIGHUP, &ignore, &previous);  // inherited by the child, as nohup does
    const test::RunResult r = test::run_jostle_binary(
        {"record", "--assets", kAssets, "--level", "arena", "-o", scn.string(), "--script", dir_.file("script.txt")},
        "/dev/null", "", 50, -1, SIGHUP);
    sigaction(SIGHUP, &previous, nullptr);
    EXPECT_TRUE(r.signalled);
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(fs::exists(scn));
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

// The trial: 60 runs of `play`, `check` and `check --update` (20 each), each sent
// SIGINT or SIGTERM at a seeded random moment between its start and a little after the time
// an uninterrupted run takes. Whatever the moment: frames on disk are whole PNGs and an
// unfinished animation is absent; a plain check writes nothing; an update leaves the goldens
// all old or all new; no temporary file is left; and the exit status says what happened:
// 128 + the signal with the message naming it, the signal's default action (before the
// handler is installed, when nothing was done yet), or the uninterrupted result.
TEST_F(Interrupt, SixtyRandomSignalsDuringPlayCheckAndUpdate) {
    suite_needing_update();
    const auto before = snapshot(scenarios());
    const fs::path saved = dir_.path() / "saved";
    fs::copy(scenarios(), saved);
    std::ofstream(dir_.path() / "long.scn", std::ios::binary)
        << "jostle-scenario 1\nengine 0.1.0\nlevel arena\nseed 1\ntick-rate 60\nlevel-hash " << level_hash_ << "\n\n"
        << "0-299 up fire\n300-599 left up\n";
    const auto play = [&](const std::string& tag, int delay_ms, int sig) {
        return test::run_jostle_binary({"play", dir_.file("long.scn"), "--assets", kAssets, "--out",
                                        (dir_.path() / ("frames_" + tag)).string(), "--size", "160x120", "--every", "4",
                                        "--anim", (dir_.path() / ("run_" + tag + ".png")).string()},
                                       "/dev/null", "", delay_ms, -1, sig);
    };
    const auto restore = [&](const fs::path& from) {
        fs::remove_all(scenarios());
        fs::copy(from, scenarios());
    };
    // How long each command takes when left alone (this machine, this build), and its results.
    const auto timed = [](auto&& run) {
        const auto start = std::chrono::steady_clock::now();
        const test::RunResult r = run();
        const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() - start);
        return std::pair{r, static_cast<int>(ms.count())};
    };
    const auto [play_run, play_ms] = timed([&] { return play("whole", -1, SIGINT); });
    ASSERT_EQ(play_run.status, 0) << play_run.err;
    const auto [update_run, update_ms] = timed([&] { return check({"--update"}); });
    ASSERT_EQ(update_run.status, 0) << update_run.err;
    const auto after = snapshot(scenarios());
    ASSERT_FALSE(same_files(before, after));
    const auto [check_run, check_ms] = timed([&] { return check({}); });
    ASSERT_EQ(check_run.status, 0) << check_run.err;
    const fs::path updated = dir_.path() / "updated";  // goldens a plain check passes
    fs::copy(scenarios(), updated);

    Rng rng(20261126);
    int interrupted = 0, killed = 0, finished = 0;
    for (int trial = 0; trial < 60; ++trial) {
        const int command = trial % 3;  // 0 play, 1 check, 2 check --update
        const int full_ms = command == 0 ? play_ms : command == 1 ? check_ms : update_ms;
        const int delay_ms = static_cast<int>(rng.below(static_cast<std::uint32_t>(full_ms * 11 / 10 + 1)));
        const int sig = rng.below(2) == 0 ? SIGINT : SIGTERM;
        const std::string what = std::string(command == 0 ? "play" : command == 1 ? "check" : "check --update") +
                                 " with " + (sig == SIGINT ? "SIGINT" : "SIGTERM") + " at " +
                                 std::to_string(delay_ms) + " ms (trial " + std::to_string(trial) + ")";
        test::RunResult r;
        if (command == 0) {
            r = play(std::to_string(trial), delay_ms, sig);
            const fs::path frames = dir_.path() / ("frames_" + std::to_string(trial));
            const fs::path anim = dir_.path() / ("run_" + std::to_string(trial) + ".png");
            if (fs::exists(frames)) {
                for (const auto& entry : fs::directory_iterator(frames)) {
                    EXPECT_NO_THROW(read_png(entry.path().string())) << entry.path() << ", " << what;
                }
            }
            // Absent, or complete (a signal while the last file was renamed into place is held
            // back until it is there, and then still reported).
            if (r.status == 0 || fs::exists(anim)) {
                EXPECT_NO_THROW(read_png(anim.string())) << what;
            }
        } else {
            restore(command == 1 ? updated : saved);
            const auto start = snapshot(scenarios());
            r = command == 1 ? check({}, delay_ms, sig) : check({"--update"}, delay_ms, sig);
            const auto now = snapshot(scenarios());
            if (command == 1) {
                EXPECT_TRUE(same_files(now, start)) << "a plain check writes nothing, " << what;
            } else {
                EXPECT_TRUE(now == before || now == after) << "half-updated goldens, " << what;
                if (r.status == 0) {
                    EXPECT_TRUE(same_files(now, after)) << what;
                }
            }
        }
        EXPECT_EQ(temp_files(dir_.path()), std::vector<std::string>{}) << what;
        if (r.status == 128 + sig) {
            ++interrupted;
            EXPECT_EQ(r.err, interrupted_by(sig)) << what;
        } else if (r.term_signal != 0) {
            // The default action: the signal came before the handler was installed, or after
            // it was removed on the way out. The checks above hold either way.
            EXPECT_EQ(r.term_signal, sig) << what;
            ++killed;
        } else {
            EXPECT_EQ(r.status, 0) << what << ": " << r.err;
            ++finished;
        }
    }
    std::cout << "60 trials (play " << play_ms << " ms, check " << check_ms << " ms, update " << update_ms
              << " ms uninterrupted): " << interrupted << " stopped cleanly, " << killed
              << " ended by the signal's default action, " << finished << " finished first\n";
    // Most moments fall inside the run; a build so slow to start that none does is a bad trial.
    EXPECT_GE(interrupted, 20) << "too few runs were interrupted: the moments miss the work";
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
