// record_test.cpp: `jostle record` end to end and the record/play round trip. Bad scripts and
// bad usage (exit 2, the exact message, the output file neither created nor changed), the
// script from stdin or --script giving the same bytes, the written file (header and body,
// read back by load_scenario), the recording's per-tick hashes against replay() of its file
// and against `jostle play --trace` (the same with and without rendering), re-recording with
// --from/--at (the kept ticks, their hashes and directives, the new script after them), and
// what an expectation that fails while recording does (a note; the file is still written).
#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "arena.h"
#include "game/run_jostle.h"
#include "jostle/replay/record.h"
#include "jostle/replay/replay.h"
#include "jostle/replay/scenario.h"
#include "record.h"
#include "test_support.h"

namespace jostle {
namespace {

namespace fs = std::filesystem;

using test::read_text;
using test::RunResult;
using ::testing::EndsWith;
using ::testing::HasSubstr;
using ::testing::StartsWith;

const std::string kAssets = JOSTLE_ASSETS_DIR;

// Where a command line names the output file; expect_rejected runs it with a new path and
// with an existing file there.
const std::string kOut = "@OUT@";

std::string usage_error(const std::string& message) {
    return "jostle record: " + message + "\nRun 'jostle record --help' for usage.\n";
}

// The first tick at which two runs' hashes differ (or one has ended), -1 when they are equal.
std::int64_t first_difference(const std::vector<std::uint64_t>& a, const std::vector<std::uint64_t>& b) {
    const std::size_t n = std::max(a.size(), b.size());
    for (std::size_t t = 0; t < n; ++t) {
        if (t >= a.size() || t >= b.size() || a[t] != b[t]) return static_cast<std::int64_t>(t);
    }
    return -1;
}

// 100 ticks: driving, turning while firing, a pause, driving on a curve; two screenshots and
// two expectations (both true in this run).
constexpr const char* kScript =
    "# drive, turn and fire\n"
    "hold up 30\n"
    "screenshot\n"
    "\n"
    "hold left fire 20   # turning\n"
    "press fire\n"
    "  expect player alive\n"
    "wait 9\n"
    "hold right up 40\n"
    "screenshot\n"
    "expect var shots >= 1\n";

// kScript's input and directives as the recorder writes them (ticks holding nothing are
// left out, screenshots before expectations).
constexpr const char* kScriptBody =
    "0-29 up\n"
    "30-49 left fire\n"
    "50 fire\n"
    "60-99 right up\n"
    "\n"
    "at 29 screenshot\n"
    "at 99 screenshot\n"
    "at 50 expect player alive\n"
    "at 99 expect var shots >= 1\n"
    "at 100 end\n";

class Record : public ::testing::Test {
protected:
    std::string path(const std::string& name) const { return dir_.file(name); }

    std::string write(const std::string& name, const std::string& text) const {
        std::ofstream(path(name), std::ios::binary) << text;
        return path(name);
    }

    // The files in the folder, sorted (a leftover temporary file shows here).
    std::vector<std::string> listing() const { return test::file_names(dir_.path()); }

    // The header the recorder writes for the arena.
    std::string header(std::uint64_t seed = 1, int tick_rate = 60) const {
        return "jostle-scenario 1\nengine " + std::string(engine_version()) + "\nlevel arena\nseed " + std::to_string(seed) +
               "\ntick-rate " + std::to_string(tick_rate) + "\nlevel-hash " + game_.level_hash("arena") + "\n\n";
    }

    // `jostle record ARGS` with the source tree's assets.
    RunResult run_record(std::vector<std::string> args, const std::string& stdin_path = "/dev/null") const {
        args.insert(args.begin(), "record");
        args.push_back("--assets");
        args.push_back(kAssets);
        return test::run_jostle_binary(args, stdin_path);
    }

    RunResult run_play(std::vector<std::string> args) const {
        args.insert(args.begin(), "play");
        args.push_back("--assets");
        args.push_back(kAssets);
        return test::run_jostle_binary(args);
    }

    // `jostle play SCENARIO --trace` and the hashes of the trace it wrote.
    std::vector<std::uint64_t> play_hashes(const std::string& scenario, const std::string& trace_name) const {
        const RunResult r = run_play({scenario, "--trace", path(trace_name), "--quiet"});
        EXPECT_EQ(r.status, 0) << r.err;
        return parse_trace(read_text(path(trace_name)), trace_name).hashes;
    }

    // Records `script` (from a file) to NAME and checks it succeeded.
    std::string record_file(const std::string& name, const std::string& script, std::vector<std::string> args = {},
                            const std::string& expected_err = "") {
        const std::string script_path = write(name + ".script", script);
        args.insert(args.end(), {"-o", path(name), "--script", script_path});
        if (std::find(args.begin(), args.end(), "--from") == args.end()) args.insert(args.end(), {"--level", "arena"});
        const RunResult r = run_record(args);
        EXPECT_EQ(r.status, 0) << r.err;
        EXPECT_EQ(r.err, expected_err);
        return path(name);
    }

    // record() in process.
    Recording record_script(const std::string& script, const RecordDesc& desc) const {
        const std::vector<ScriptStep> steps = parse_input_script(script, "script", game_.vocabulary());
        return record(game_, desc, steps, "script");
    }

    // The command fails with exit 2 and exactly `err`, writing nothing: run with kOut as a
    // path where no file is (not created), and as an existing file (left byte for byte).
    void expect_rejected(const std::vector<std::string>& args, const std::string& err,
                         const std::string& stdin_path = "/dev/null") {
        std::string command;
        for (const std::string& a : args) command += " " + a;
        SCOPED_TRACE("jostle record" + command);
        const std::string old_bytes = "jostle-scenario 1\n# the old file, which a failed record must not touch\n";
        const std::string existing = write("existing.scn", old_bytes);
        const bool names_out = std::find(args.begin(), args.end(), kOut) != args.end();
        for (const std::string& out : {path("new.scn"), existing}) {
            std::vector<std::string> a = args;
            std::replace(a.begin(), a.end(), kOut, out);
            const std::vector<std::string> before = listing();
            const RunResult r = run_record(a, stdin_path);
            EXPECT_EQ(r.status, 2);
            EXPECT_EQ(r.out, "");
            EXPECT_EQ(r.err, err);
            EXPECT_EQ(listing(), before);  // new.scn not created, no temporary file left behind
            EXPECT_EQ(read_text(existing), old_bytes);
            if (!names_out) break;
        }
    }

    const game::ArenaGame game_{kAssets};
    const test::TempFolder dir_{"record"};
};

TEST_F(Record, BadScriptStepsExitTwoNamingFileLineAndColumn) {
    const std::string actions = " (expected one of: left, right, up, down, fire)";
    const std::string ticks = "expected a number of ticks (1 .. 16777216), got ";
    const std::string expect_forms = "expected 'expect NAME alive|gone|in X0 Y0 X1 Y1, or count KIND OP N, var NAME OP V, event NAME'";
    const std::string unknown_step = " (expected hold, press, wait, screenshot or expect)";
    struct Case {
        const char* script;
        std::string where_what;  // "LINE:COLUMN: message"
    };
    const Case cases[] = {
        // Unknown actions.
        {"hold jump 5\n", "1:6: unknown action 'jump'" + actions},
        {"press right jump\n", "1:13: unknown action 'jump'" + actions},
        {"hold Right 5\n", "1:6: unknown action 'Right'" + actions},
        {"hold right 5 6\n", "1:12: expected an action, got '5' (a step has one number of ticks, at its end: 'hold ACTION... TICKS')"},
        // Missing, non-numeric, negative, zero and too large counts.
        {"hold\n", "1:5: expected 'hold ACTION... TICKS'"},
        {"hold right\n", "1:11: expected 'hold ACTION... TICKS'"},
        {"hold 5\n", "1:7: expected 'hold ACTION... TICKS'"},
        {"hold right x\n", "1:12: " + ticks + "'x'"},
        {"hold right -3\n", "1:12: " + ticks + "'-3'"},
        {"hold right 0\n", "1:12: " + ticks + "'0'"},
        {"wait\n", "1:5: expected 'wait TICKS'"},
        {"wait 0\n", "1:6: " + ticks + "'0'"},
        {"wait -1\n", "1:6: " + ticks + "'-1'"},
        {"wait 2.5\n", "1:6: " + ticks + "'2.5'"},
        {"wait 10x\n", "1:6: " + ticks + "'10x'"},
        {"wait 100000001\n", "1:6: " + ticks + "'100000001'"},
        {"press\n", "1:6: expected 'press ACTION...'"},
        // Unknown verbs (verbs are lower case).
        {"jump 3\n", "1:1: unknown step 'jump'" + unknown_step},
        {"  Wait 3\n", "1:3: unknown step 'Wait'" + unknown_step},
        {"# a comment\n\nwait 2   # two\nhld 3\n", "4:1: unknown step 'hld'" + unknown_step},
        // An invisible byte order mark (U+FEFF) is said, not shown as part of a word.
        {"wait 2\n\xef\xbb\xbfwait 3\n",
         "2:1: expected text, got a byte order mark (U+FEFF): it is only allowed at the start of the file"},
        // Trailing words.
        {"wait 3 now\n", "1:8: expected 'wait TICKS'"},
        {"\twait\t3\tnow\n", "1:9: expected 'wait TICKS'"},
        {"press fire now\n", "1:12: unknown action 'now'" + actions},
        {"hold right 5 more\n", "1:12: expected an action, got '5' (a step has one number of ticks, at its end: 'hold ACTION... TICKS')"},  // the last word is the count
        {"wait 1\nscreenshot now\n", "2:12: expected 'screenshot' alone"},
        // Bad expectations.
        {"wait 1\nexpect\n", "2:7: " + expect_forms},
        {"wait 1\nexpect player\n", "2:14: " + expect_forms},
        {"wait 1\nexpect player dancing\n", "2:15: expected 'alive', 'gone' or 'in' after the entity name, got 'dancing'"},
        {"wait 1\nexpect player alive now\n", "2:21: expected 'expect NAME alive|gone'"},
        {"wait 1\nexpect count rock ~ 3\n", "2:19: expected a comparison (= != < <= > >=), got '~'"},
        {"wait 1\nexpect var score = x\n", "2:20: expected a finite number, got 'x'"},
        {"wait 1\nexpect player in 10 10 0 0\n", "2:18: expected X0 <= X1 and Y0 <= Y1 (the region's top-left corner first)"},
        // A screenshot or an expectation needs a tick before it.
        {"screenshot\nwait 1\n", "1:1: nothing has been played yet: a screenshot or expectation needs a tick before it (add 'wait 1')"},
        {"# first\n  expect player alive\nwait 1\n",
         "2:1: nothing has been played yet: a screenshot or expectation needs a tick before it (add 'wait 1')"},
    };
    for (const Case& c : cases) {
        const std::string script = write("bad.script", c.script);
        expect_rejected({"--level", "arena", "-o", kOut, "--script", script}, "jostle record: " + script + ":" + c.where_what + "\n");
    }
    // From standard input the script is "<stdin>".
    const std::string stdin_script = write("stdin.script", "wait 5\nhold up fire jump 3\n");
    expect_rejected({"--level", "arena", "-o", kOut}, "jostle record: <stdin>:2:14: unknown action 'jump'" + actions + "\n",
                    stdin_script);
}

TEST_F(Record, AScriptThatPlaysNoTicksWritesNothing) {
    // An empty script (or only comments and blank lines) would be a 0-tick scenario, which the
    // format cannot hold: it is refused, naming the script without a line.
    const std::string empty = write("empty.script", "");
    expect_rejected({"--level", "arena", "-o", kOut, "--script", empty}, "jostle record: " + empty + ": the script plays no ticks\n");
    const std::string comments = write("comments.script", "# nothing yet\n\n   \n");
    expect_rejected({"--level", "arena", "-o", kOut, "--script", comments},
                    "jostle record: " + comments + ": the script plays no ticks\n");
    expect_rejected({"--level", "arena", "-o", kOut}, "jostle record: <stdin>: the script plays no ticks\n");  // /dev/null
}

TEST_F(Record, UsageErrorsExitTwoWithTheirMessage) {
    const std::string script = write("ok.script", "wait 3\n");
    const std::string s = "--script";
    expect_rejected({"--level", "arena", s, script}, usage_error("expected -o SCENARIO (the file to write)"));
    expect_rejected({"-o", kOut, s, script}, usage_error("expected --level LEVEL (or --from SCENARIO --at TICK)"));
    std::string levels;  // every level in the assets, in name order
    for (const std::string& name : game_.vocabulary().levels) levels += (levels.empty() ? "" : ", ") + name;
    ASSERT_THAT(levels, ::testing::StartsWith("arena, "));
    expect_rejected({"--level", "moon", "-o", kOut, s, script},
                    usage_error("--level: unknown level 'moon' (expected one of: " + levels + ")"));
    expect_rejected({"--level", "arena", "-o", kOut, s, script, "--fast"}, usage_error("unknown option '--fast'"));
    expect_rejected({"--level", "arena", "-o", kOut, s, script, "extra"}, usage_error("unexpected argument 'extra'"));
    expect_rejected({"--level", "arena", "-o", "", s, script}, usage_error("-o needs a value"));
    expect_rejected({"--level", "arena", "-o", kOut, "--seed", "-1", s, script},
                    usage_error("--seed: expected a whole number from 0 to 18446744073709551615, got '-1'"));
    expect_rejected({"--level", "arena", "-o", kOut, "--tick-rate", "0", s, script},
                    usage_error("--tick-rate: expected a whole number from 1 to 1000, got '0'"));
    expect_rejected({"--level", "arena", "-o", kOut, "--tick-rate", "1001", s, script},
                    usage_error("--tick-rate: expected a whole number from 1 to 1000, got '1001'"));
    for (const char* option : {"--level", "-o", "--out", "--script", "--seed", "--tick-rate", "--from", "--at"}) {
        const RunResult r = test::run_jostle_binary({"record", "--level", "arena", option});
        EXPECT_EQ(r.status, 2) << option;
        EXPECT_EQ(r.err, usage_error(std::string(option) + " needs a value"));
    }
    expect_rejected({"--level", "arena", "-o", "--seed", s, script},
                    usage_error("-o needs a value, got the option '--seed' (a path that begins with '-' is written ./--seed)"));
    expect_rejected({"--level", "arena", "--level", "blob", "-o", kOut, s, script}, usage_error("--level given twice"));
    expect_rejected({"--level", "arena", "-o", kOut, "--out", kOut, s, script}, usage_error("-o (or --out) given twice"));
    // A negative number reaches the option's own check.
    expect_rejected({"--level", "arena", "-o", kOut, "--seed", "-1", s, script},
                    usage_error("--seed: expected a whole number from 0 to 18446744073709551615, got '-1'"));

    // A script that cannot be opened is bad input, not bad usage.
    const std::string missing = path("no_such.script");
    expect_rejected({"--level", "arena", "-o", kOut, s, missing}, "jostle record: " + missing + ": cannot open the script: No such file or directory\n");

    // --from and --at go together, without --level; --at counts ticks of the --from scenario.
    const std::string from = write("from.scn", header() + "0-4 up\nat 9 expect player alive\n");  // 10 ticks
    expect_rejected({"--from", from, "-o", kOut, s, script}, usage_error("--from needs --at TICK (how many ticks to keep)"));
    expect_rejected({"--at", "3", "-o", kOut, s, script}, usage_error("--at needs --from SCENARIO"));
    expect_rejected({"--level", "arena", "--at", "3", "-o", kOut, s, script}, usage_error("--at needs --from SCENARIO"));
    expect_rejected({"--from", from, "--at", "3", "--level", "arena", "-o", kOut, s, script},
                    usage_error("--level cannot be used with --from (the level is the scenario's)"));
    expect_rejected({"--from", from, "--at", "11", "-o", kOut, s, script}, usage_error("--at 11: " + from + " has only 10 ticks"));
    for (const char* at : {"-1", "x", "3.5", "16777217", ""}) {
        expect_rejected({"--from", from, "--at", at, "-o", kOut, s, script},
                        *at == '\0' ? usage_error("--at needs a value")
                                    : usage_error(std::string("--at: expected a whole number from 0 to 16777216, got '") + at + "'"));
    }
    // A sign that a number in range would not need is named (the file formats refuse it too).
    for (const char* at : {"+3", "-0", "-00"}) {
        expect_rejected({"--from", from, "--at", at, "-o", kOut, s, script},
                        usage_error(std::string("--at: expected a whole number from 0 to 16777216, got '") + at +
                                    "' (a number here is written without a sign)"));
    }
    // The --from scenario is checked like any scenario.
    const std::string absent = path("absent.scn");
    expect_rejected({"--from", absent, "--at", "0", "-o", kOut, s, script}, "jostle record: " + absent + ": cannot open the scenario file: No such file or directory\n");
    const std::string no_rate = write("no_rate.scn", "jostle-scenario 1\nengine 0.1.0\nlevel arena\nseed 1\n0 up\n");
    expect_rejected({"--from", no_rate, "--at", "0", "-o", kOut, s, script},
                    "jostle record: " + no_rate + ":5:1: expected the header line 'tick-rate ...' before the input\n");
    expect_rejected({"--from", script, "--at", "0", "-o", kOut, s, script},
                    "jostle record: " + script + ":1:1: expected 'jostle-scenario 1' as the first line (is this a scenario file?)\n");
    const std::string truncated = write("truncated.scn", header() + "0-4 up");
    expect_rejected({"--from", truncated, "--at", "0", "-o", kOut, s, script},
                    "jostle record: " + truncated + ":8: truncated file: the last line has no newline (if the file is whole, end it with one)\n");
    const std::string jump = write("jump.scn", header() + "0-4 jump\n");
    expect_rejected({"--from", jump, "--at", "0", "-o", kOut, s, script},
                    "jostle record: " + jump + ":8:5: unknown action 'jump' (expected one of: left, right, up, down, fire, or '-' for none)\n");
}

TEST_F(Record, HelpExitsZero) {
    const RunResult r = test::run_jostle_binary({"record", "--help"});
    EXPECT_EQ(r.status, 0);
    EXPECT_EQ(r.out, record_help());
    EXPECT_THAT(r.out, StartsWith("usage: jostle record --level LEVEL -o SCENARIO"));
    EXPECT_EQ(r.err, "");
    // Anywhere an option may stand, as right after the command.
    const RunResult later = test::run_jostle_binary({"record", "--level", "arena", "-h"});
    EXPECT_EQ(later.status, 0);
    EXPECT_EQ(later.out, record_help());
}

TEST_F(Record, ScriptFromStdinAndFromAFileWriteTheSameBytes) {
    const std::string script = write("busy.script", kScript);
    const std::string from_file = path("file.scn");
    const std::string from_stdin = path("stdin.scn");
    RunResult r = run_record({"--level", "arena", "-o", from_file, "--script", script});
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_EQ(r.out, "recorded 100 ticks of level arena to " + from_file + " (read back and replayed: the same state on every tick)\n");
    r = run_record({"--level", "arena", "-o", from_stdin}, script);
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_EQ(r.out, "recorded 100 ticks of level arena to " + from_stdin + " (read back and replayed: the same state on every tick)\n");
    EXPECT_EQ(read_text(from_stdin), read_text(from_file));
    EXPECT_EQ(read_text(from_file), header() + kScriptBody);
    // The last line needs no newline.
    r = run_record({"--level", "arena", "-o", path("last.scn")}, write("last.script", "hold up 30\nhold left fire 20\npress fire"));
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(read_text(path("last.scn")), header() + "0-29 up\n30-49 left fire\n50 fire\n\nat 51 end\n");
}

TEST_F(Record, TheHeaderNamesEngineLevelSeedTickRateAndLevelHash) {
    EXPECT_STRNE(engine_version(), "0.0.0");  // the build's version reached the library
    const std::string hash = game_.level_hash("arena");
    EXPECT_THAT(hash, ::testing::MatchesRegex("[0-9a-f]{16}"));

    // The defaults: seed 1, 60 ticks per second.
    const std::string plain = record_file("plain.scn", "wait 3\n");
    EXPECT_EQ(read_text(plain), "jostle-scenario 1\nengine " + std::string(engine_version()) +
                                    "\nlevel arena\nseed 1\ntick-rate 60\nlevel-hash " + hash + "\n\n0-2 -\n\nat 3 end\n");

    const std::string big = record_file("big.scn", "hold down 4\n", {"--seed", "18446744073709551615", "--tick-rate", "1000"});
    EXPECT_EQ(read_text(big), header(18446744073709551615u, 1000) + "0-3 down\n\nat 4 end\n");
    const Scenario s = load_scenario(big, game_.vocabulary());
    EXPECT_EQ(s.engine_version, engine_version());
    EXPECT_EQ(s.level, "arena");
    EXPECT_EQ(s.seed, 18446744073709551615u);
    EXPECT_EQ(s.tick_rate, 1000);
    EXPECT_EQ(s.level_hash, hash);
    EXPECT_EQ(s.end_tick, 4);
    EXPECT_EQ(s.ticks(), 4);
    EXPECT_EQ(s.inputs, std::vector<InputFrame>(4, InputFrame{1u << game::kDown}));

    // The whole file reads back as what record() made.
    const std::string busy = record_file("busy.scn", kScript, {"--seed", "0", "--tick-rate", "30"});
    const Scenario b = load_scenario(busy, game_.vocabulary());
    const Recording rec = record_script(kScript, RecordDesc{.level = "arena", .seed = 0, .tick_rate = 30});
    EXPECT_EQ(b.seed, 0u);
    EXPECT_EQ(b.tick_rate, 30);
    EXPECT_EQ(b.inputs, rec.scenario.inputs);
    EXPECT_EQ(b.end_tick, rec.scenario.end_tick);
    ASSERT_EQ(b.screenshots.size(), 2u);
    EXPECT_EQ(b.screenshots[0].tick, 29);
    EXPECT_EQ(b.screenshots[1].tick, 99);
    ASSERT_EQ(b.expectations.size(), 2u);
    EXPECT_EQ(b.expectations[0].tick, 50);
    EXPECT_EQ(b.expectations[0].text, "player alive");
    EXPECT_EQ(b.expectations[1].tick, 99);
    EXPECT_EQ(b.expectations[1].text, "var shots >= 1");
    EXPECT_EQ(format_scenario(b, game_.vocabulary()), read_text(busy));
}

TEST_F(Record, RecordedHashesAreTheReplayOfTheWrittenFileTickByTick) {
    const Recording rec = record_script(kScript, RecordDesc{.level = "arena", .seed = 5, .tick_rate = 60});
    ASSERT_EQ(rec.hashes.size(), 100u);
    ASSERT_EQ(rec.scenario.inputs.size(), 100u);
    EXPECT_EQ(rec.scenario.end_tick, 100);
    // The run is not still: the state changes on (nearly) every tick.
    std::vector<std::uint64_t> distinct = rec.hashes;
    std::sort(distinct.begin(), distinct.end());
    EXPECT_GT(std::unique(distinct.begin(), distinct.end()) - distinct.begin(), 90);

    // In process: the file format_scenario writes, loaded and replayed.
    const std::string file = write("rec.scn", format_scenario(rec.scenario, game_.vocabulary()));
    const Scenario loaded = load_scenario(file, game_.vocabulary());
    ReplayOptions options;
    options.dump_every = 0;
    const ReplayResult replayed = replay(game_, loaded, options);
    EXPECT_EQ(replayed.ticks, 100);
    EXPECT_EQ(first_difference(replayed.hashes, rec.hashes), -1);
    EXPECT_TRUE(replayed.expectations_passed());
    EXPECT_EQ(replayed.expectations.size(), 2u);

    // The comparison can fail: another seed is another run from the first tick.
    const Recording other = record_script(kScript, RecordDesc{.level = "arena", .seed = 6, .tick_rate = 60});
    EXPECT_EQ(first_difference(other.hashes, rec.hashes), 0);

    // Through the binary: `jostle record` writes the same file, and `jostle play --trace` of
    // it gives the recorded hashes.
    const std::string binary_file = record_file("binary.scn", kScript, {"--seed", "5"});
    EXPECT_EQ(read_text(binary_file), read_text(file));
    EXPECT_EQ(first_difference(play_hashes(binary_file, "binary.trace"), rec.hashes), -1);
}

TEST_F(Record, PlayingARecordingGivesTheSameTraceEveryTimeWithOrWithoutRendering) {
    const std::string s = record_file("busy.scn", kScript, {"--seed", "3"});
    RunResult r = run_play({s, "--trace", path("a.trace"), "--quiet"});
    ASSERT_EQ(r.status, 0) << r.err;
    r = run_play({s, "--trace", path("b.trace"), "--quiet"});
    ASSERT_EQ(r.status, 0) << r.err;
    r = run_play({s, "--trace", path("c.trace"), "--out", path("frames"), "--every", "5", "--size", "160x120"});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_THAT(r.out, HasSubstr(", 20 frames rendered ("));  // ticks 0, 5, ..., 95
    EXPECT_EQ(std::distance(fs::directory_iterator(path("frames")), fs::directory_iterator{}), 20);

    const std::string a = read_text(path("a.trace"));
    EXPECT_EQ(read_text(path("b.trace")), a);
    EXPECT_EQ(read_text(path("c.trace")), a);  // rendering changes nothing
    const ReplayResult trace = parse_trace(a, "a.trace");
    EXPECT_EQ(trace.ticks, 100);
    const Recording rec = record_script(kScript, RecordDesc{.level = "arena", .seed = 3, .tick_rate = 60});
    EXPECT_EQ(first_difference(trace.hashes, rec.hashes), -1);
}

// The old run for the re-recording tests: kScript at seed 7 and 30 ticks per second.
constexpr std::uint64_t kOldSeed = 7;
constexpr int kOldRate = 30;
constexpr const char* kNewScript = "hold down 20\nexpect player alive\n";

TEST_F(Record, FromAtKeepsTheFirstTicksAndContinuesWithTheScript) {
    const std::string old = record_file("old.scn", kScript, {"--seed", "7", "--tick-rate", "30"});
    ASSERT_EQ(read_text(old), header(kOldSeed, kOldRate) + kScriptBody);

    // Keep ticks 0..50: the old input, the screenshot at 29 and the expectation at 50 (the last
    // kept tick); the directives at 99 go, and a note says so. The level, seed and tick rate
    // are the old file's.
    const std::string again = record_file("again.scn", kNewScript, {"--from", old, "--at", "51"},
                                          "jostle record: note: " + old + ": not kept, being at tick 51 or later: 1 expectation and 1 screenshot\n");
    EXPECT_EQ(read_text(again), header(kOldSeed, kOldRate) +
                                    "0-29 up\n"
                                    "30-49 left fire\n"
                                    "50 fire\n"
                                    "51-70 down\n"
                                    "\n"
                                    "at 29 screenshot\n"
                                    "at 50 expect player alive\n"
                                    "at 70 expect player alive\n"
                                    "at 71 end\n");
    const Scenario before = load_scenario(old, game_.vocabulary());
    const Scenario after = load_scenario(again, game_.vocabulary());
    ASSERT_EQ(after.inputs.size(), 71u);
    EXPECT_EQ(std::vector<InputFrame>(after.inputs.begin(), after.inputs.begin() + 51),
              std::vector<InputFrame>(before.inputs.begin(), before.inputs.begin() + 51));
    EXPECT_EQ(std::vector<InputFrame>(after.inputs.begin() + 51, after.inputs.end()), std::vector<InputFrame>(20, InputFrame{1u << game::kDown}));

    // The hashes: the same as the old run's up to tick 50, different from tick 51 on, and
    // exactly the run of the whole new input recorded from scratch.
    const std::vector<std::uint64_t> old_hashes = play_hashes(old, "old.trace");
    const std::vector<std::uint64_t> new_hashes = play_hashes(again, "again.trace");
    ASSERT_EQ(old_hashes.size(), 100u);
    ASSERT_EQ(new_hashes.size(), 71u);
    EXPECT_EQ(first_difference(old_hashes, new_hashes), 51);
    const Recording scratch = record_script("hold up 30\nhold left fire 20\npress fire\nhold down 20\n",
                                            RecordDesc{.level = "arena", .seed = kOldSeed, .tick_rate = kOldRate});
    EXPECT_EQ(first_difference(scratch.hashes, new_hashes), -1);

    // In process: record() with `from` gives the same hashes; at 50 the expectation at tick 50
    // is no longer kept (directives are kept only before the tick re-recording starts at).
    RecordDesc desc;
    desc.from = &before;
    desc.keep_ticks = 51;
    const Recording rec = record_script(kNewScript, desc);
    EXPECT_EQ(first_difference(rec.hashes, new_hashes), -1);
    EXPECT_EQ(format_scenario(rec.scenario, game_.vocabulary()), read_text(again));
    desc.keep_ticks = 50;
    const Recording at50 = record_script(kNewScript, desc);
    ASSERT_EQ(at50.scenario.screenshots.size(), 1u);
    EXPECT_EQ(at50.scenario.screenshots[0].tick, 29);
    ASSERT_EQ(at50.scenario.expectations.size(), 1u);
    EXPECT_EQ(at50.scenario.expectations[0].tick, 69);  // the new script's
    EXPECT_EQ(first_difference(at50.hashes, old_hashes), 50);
    // At 99 the screenshot and the expectation at tick 99 go, the earlier ones stay.
    desc.keep_ticks = 99;
    const Recording at99 = record_script("wait 1\n", desc);
    EXPECT_EQ(format_scenario(at99.scenario, game_.vocabulary()), header(kOldSeed, kOldRate) +
                                                                      "0-29 up\n"
                                                                      "30-49 left fire\n"
                                                                      "50 fire\n"
                                                                      "60-98 right up\n"
                                                                      "99 -\n"
                                                                      "\n"
                                                                      "at 29 screenshot\n"
                                                                      "at 50 expect player alive\n"
                                                                      "at 100 end\n");
    EXPECT_EQ(first_difference(at99.hashes, old_hashes), 99);
}

TEST_F(Record, FromAtZeroIsAFreshRecordingWithTheOldSettings) {
    const std::string old = record_file("old.scn", kScript, {"--seed", "7", "--tick-rate", "30"});
    const std::string again = record_file("again.scn", kNewScript, {"--from", old, "--at", "0"},
                                          "jostle record: note: " + old + ": not kept, being at tick 0 or later: 2 expectations and 2 screenshots\n");
    const std::string fresh = record_file("fresh.scn", kNewScript, {"--seed", "7", "--tick-rate", "30"});
    EXPECT_EQ(read_text(again), read_text(fresh));
    EXPECT_EQ(read_text(again), header(kOldSeed, kOldRate) + "0-19 down\n\nat 19 expect player alive\nat 20 end\n");
    EXPECT_EQ(first_difference(play_hashes(again, "again.trace"), play_hashes(old, "old.trace")), 0);

    // Nothing kept and nothing played: refused, and the --from file (also the output here) is
    // left as it was.
    const std::string old_bytes = read_text(old);
    const RunResult r = run_record({"--from", old, "--at", "0", "-o", old});
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.err, "jostle record: <stdin>: the script plays no ticks\n");
    EXPECT_EQ(read_text(old), old_bytes);
}

TEST_F(Record, FromAtTheEndKeepsTheWholeRun) {
    const std::string old = record_file("old.scn", kScript, {"--seed", "7", "--tick-rate", "30"});
    const std::string old_bytes = read_text(old);

    // All 100 ticks and nothing more: the same file, even re-recorded in place.
    const std::string copy = record_file("copy.scn", "", {"--from", old, "--at", "100"});
    EXPECT_EQ(read_text(copy), old_bytes);
    RunResult r = run_record({"--from", old, "--at", "100", "-o", old});
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out, "recorded 100 ticks of level arena to " + old + " (read back and replayed: the same state on every tick)\n");
    EXPECT_EQ(read_text(old), old_bytes);

    // All 100 ticks and five more: every old directive kept (those at tick 99 too).
    const std::string longer = record_file("longer.scn", "wait 4\npress fire\nscreenshot\n", {"--from", old, "--at", "100"});
    EXPECT_EQ(read_text(longer), header(kOldSeed, kOldRate) +
                                     "0-29 up\n"
                                     "30-49 left fire\n"
                                     "50 fire\n"
                                     "60-99 right up\n"
                                     "104 fire\n"
                                     "\n"
                                     "at 29 screenshot\n"
                                     "at 99 screenshot\n"
                                     "at 104 screenshot\n"
                                     "at 50 expect player alive\n"
                                     "at 99 expect var shots >= 1\n"
                                     "at 105 end\n");
    const std::vector<std::uint64_t> old_hashes = play_hashes(old, "old.trace");
    EXPECT_EQ(first_difference(old_hashes, play_hashes(longer, "longer.trace")), 100);  // where the old run ends

    // A hand-written scenario whose run outlasts its input (a directive at tick 9): its length
    // is 10 ticks, and the ticks past its input hold nothing.
    const std::string short_input = write("short.scn", header() + "0-4 up\nat 9 expect player alive\n");
    const std::string extended = record_file("extended.scn", "press left\n", {"--from", short_input, "--at", "10"});
    EXPECT_EQ(read_text(extended), header() + "0-4 up\n10 left\n\nat 9 expect player alive\nat 11 end\n");
}

TEST_F(Record, AFalseExpectationIsWrittenAndNotedNotRefused) {
    // The recorder writes what the script says; an expectation that is false in this run is a
    // note (exit 0), and `jostle play` of the file then fails on it.
    const std::string script = write("false.script", "hold up 10\nexpect var score = 5\nexpect player alive\n");
    const std::string out = path("false.scn");
    const RunResult r = run_record({"--level", "arena", "-o", out}, script);
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out, "recorded 10 ticks of level arena to " + out + " (read back and replayed: the same state on every tick)\n");
    // The note names the script's line (2), not the written file's.
    EXPECT_EQ(r.err, "jostle record: note: <stdin>:2: expectation fails in this run at tick 9: expected var score = 5, "
                     "found score = 0\n");
    EXPECT_EQ(read_text(out), header() + "0-9 up\n\nat 9 expect var score = 5\nat 9 expect player alive\nat 10 end\n");

    const RunResult played = run_play({out, "--quiet"});
    EXPECT_EQ(played.status, 1);
    EXPECT_EQ(played.err, "jostle play: " + out + ":10: expectation failed at tick 9: expected var score = 5, found score = 0\n");
}

// One tick is "1 tick", in the summary and in --at's limit.
TEST_F(Record, OneTickIsSaidInTheSingular) {
    const std::string script = write("one.script", "hold up 1\n");
    const std::string out = path("one.scn");
    const RunResult r = run_record({"--level", "arena", "-o", out}, script);
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_EQ(r.out, "recorded 1 tick of level arena to " + out + " (read back and replayed: the same state on every tick)\n");
    const RunResult at = run_record({"--from", out, "--at", "2", "-o", path("two.scn")}, script);
    EXPECT_EQ(at.status, 2);
    EXPECT_EQ(at.err, "jostle record: --at 2: " + out + " has only 1 tick\nRun 'jostle record --help' for usage.\n");
}

TEST_F(Record, AnExpectationNamingWhatTheGameLacksIsBadInput) {
    // The script parser does not know the game's variables; the read-back replay refuses the
    // name, and nothing is written.
    const std::string script = write("lives.script", "wait 5\nexpect var lives = 3\n");
    const std::string out = path("lives.scn");
    const RunResult r = run_record({"--level", "arena", "-o", out, "--script", script});
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.out, "");
    // The script and its line, checked as the script is played (not the unwritten output file).
    EXPECT_EQ(r.err, "jostle record: " + script + ":2:12: unknown game variable 'lives' (expected one of: score, shots, balls, fastest, touches)\n");
    EXPECT_FALSE(fs::exists(out));
    EXPECT_EQ(listing(), (std::vector<std::string>{"lives.script"}));  // no temporary file left either
}

// A note for an expectation kept by --from names the --from file and its line.
TEST_F(Record, ANoteForAKeptExpectationNamesTheFileItCameFrom) {
    const std::string old_scn = path("old.scn");
    const std::string old_script = write("old.script", "hold up 10\nexpect var score = 5\nwait 5\n");
    ASSERT_EQ(run_record({"--level", "arena", "-o", old_scn, "--script", old_script}).status, 0);
    const std::string more = write("more.script", "wait 3\nexpect var shots = 1\n");
    const std::string out = path("new.scn");
    const RunResult r = run_record({"--from", old_scn, "--at", "12", "-o", out, "--script", more});
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err, "jostle record: note: " + old_scn + ":11: expectation fails in this run at tick 9: expected var score = 5, "
                     "found score = 0\n"
                     "jostle record: note: " + more + ":2: expectation fails in this run at tick 14: expected var shots = 1, "
                     "found shots = 0\n");
}

// An expectation kept by --from that names an entity the run has not had by its tick is bad
// input at its line in the --from file (not in the output, which is never written).
TEST_F(Record, AKeptExpectationOnAnEntityNotYetThereIsBadInputInItsFile) {
    const std::string old_scn = write("old.scn", header() + "0-9 up\nat 5 expect bullet_1 gone\nat 10 end\n");
    const std::string more = write("more.script", "wait 1\n");
    const std::string out = path("new.scn");
    const RunResult r = run_record({"--from", old_scn, "--at", "8", "-o", out, "--script", more});
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.err, "jostle record: " + old_scn + ":9:13: no entity named 'bullet_1' has been in the run by tick 5 (a misspelt "
                     "name? the dumps of 'jostle play --trace' name every entity)\n");
    EXPECT_FALSE(fs::exists(out));
}

// A scenario holds at most kMaxScenarioTicks ticks: a longer script is refused at its line
// before anything is played, and a scenario that ends exactly at the cap reads back.
TEST_F(Record, AScriptLongerThanAScenarioCanBeIsRefusedAtItsLine) {
    const std::string script = write("long.script", "wait 10\nwait 16777207\n");
    const std::string out = path("long.scn");
    const RunResult r = run_record({"--level", "arena", "-o", out, "--script", script});
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.err, "jostle record: " + script + ":2:1: the recording would be longer than a scenario can be (16777216 ticks): 16777217 ticks by the end of this line\n");
    EXPECT_FALSE(fs::exists(out));
    const game::ArenaGame game(kAssets);
    const Scenario at_cap = parse_scenario(header() + "0 up\nat 16777216 end\n", "cap.scn", game.vocabulary());
    EXPECT_EQ(at_cap.ticks(), 16777216);
}

// -o /dev/stdout writes the scenario through descriptor 1 (opened again by name, it started at
// offset 0 of a redirected file and the summary overwrote it). Standard output then holds the
// scenario alone, a file play reads; the summary goes to stderr and says the file was not
// read back (it cannot be): its bytes were replayed before they were sent.
TEST_F(Record, AScenarioToDevStdoutIsTheWholeOfStandardOutput) {
    if (!fs::exists("/bin/sh")) GTEST_SKIP() << "needs /bin/sh";
    const std::string script = write("s.script", "hold up 3\n");
    const std::string expected = read_text(record_file("ref.scn", "hold up 3\n"));
    for (const std::string& redirect : {std::string(">"), std::string(">>")}) {
        SCOPED_TRACE(redirect);
        std::ofstream(path("f.scn"), std::ios::binary) << (redirect == ">" ? "old bytes\n" : "");
        const RunResult r = test::run_program("/bin/sh", {"-c", "exec \"$0\" \"$@\" " + redirect + " '" + path("f.scn") + "'",
                                                          JOSTLE_BINARY, "record", "--assets", kAssets, "--level", "arena", "-o",
                                                          "/dev/stdout", "--script", script});
        EXPECT_EQ(r.status, 0);
        EXPECT_EQ(r.err, "recorded 3 ticks of level arena to /dev/stdout (not read back, as it was written in place, to a "
                         "descriptor or a stream: the bytes sent were replayed first, the same state on every tick)\n");
        EXPECT_EQ(read_text(path("f.scn")), expected);
    }
    EXPECT_EQ(play_hashes(path("f.scn"), "f.trace"), play_hashes(path("ref.scn"), "ref.trace"));
    const RunResult piped = run_record({"--level", "arena", "-o", "/dev/stdout", "--script", script});
    EXPECT_EQ(piped.status, 0);
    EXPECT_EQ(piped.out, expected);
}

// -o naming a level or a sprite of the assets (the game's own files) is refused before the
// recording, and the file is left as it was.
TEST_F(Record, AnOutputNamingALevelOrASpriteOfTheAssetsIsRefused) {
    const fs::path assets = path("assets");
    fs::create_directories(assets);
    fs::copy(fs::path(kAssets) / "levels", assets / "levels");
    fs::copy(fs::path(kAssets) / "sprites", assets / "sprites");
    const std::string script = write("w.script", "wait 3\n");
    for (const auto& [file, what] : {std::pair{"levels/arena.level", "the level 'arena'"}, std::pair{"sprites/ship.png", "the sprite 'ship'"}}) {
        const std::string out = (assets / file).string();
        const std::string before = test::read_text(out);
        const RunResult r = test::run_jostle_binary({"record", "--assets", assets.string(), "--level", "arena", "-o", out, "--script", script});
        EXPECT_EQ(r.status, 2) << file;
        EXPECT_EQ(r.err, "jostle record: -o: '" + out + "' is " + std::string(what) +
                             " of the assets; give another path\nRun 'jostle record --help' for usage.\n");
        EXPECT_EQ(test::read_text(out), before);
    }
}

// An -o that cannot be written is said before the script is read (from a terminal, before
// anything is typed) and recorded: here the script's own error never comes.
TEST_F(Record, AnOutputThatCannotBeWrittenIsSaidBeforeTheScriptIsRead) {
    const std::string script = write("bad.script", "jump 3\n");
    const std::string out = path("no/such/folder/s.scn");
    const RunResult r = run_record({"--level", "arena", "-o", out, "--script", script});
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.err, "jostle record: " + out + ": cannot write: cannot create a file in " + path("no/such/folder") +
                         ": No such file or directory\n");
}

}  // namespace
}  // namespace jostle
