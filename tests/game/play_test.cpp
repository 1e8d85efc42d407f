// play_test.cpp: `jostle play` end to end, running the built binary on scenario files in a
// temporary folder: usage and input errors (exit 2, exact messages), failing expectations
// (exit 1), the summary, frames, traces (the same with and without rendering), APNG and sheet.
#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "arena.h"
#include "jostle/render/contact_sheet.h"
#include "jostle/render/png_io.h"
#include "jostle/replay/replay.h"
#include "play.h"
#include "render/apng_reader.h"
#include "game/run_jostle.h"
#include "test_support.h"

namespace jostle {
namespace {

namespace fs = std::filesystem;

using test::read_text;
using test::RunResult;

RunResult run_jostle(const std::vector<std::string>& args) { return test::run_jostle_binary(args); }

std::string usage_error(const std::string& message) {
    return "jostle play: " + message + "\nRun 'jostle play --help' for usage.\n";
}

const std::string kAssets = JOSTLE_ASSETS_DIR;

class Play : public ::testing::Test {
protected:
    void SetUp() override { level_hash_ = game::ArenaGame(kAssets).level_hash("arena"); }

    std::string path(const std::string& name) const { return dir_.file(name); }

    // The arena scenario header (the current level hash) and `body`, as NAME in the folder.
    std::string scenario(const std::string& name, const std::string& body, const std::string& hash = "") {
        std::ofstream(path(name), std::ios::binary)
            << "jostle-scenario 1\nengine 0.1.0\nlevel arena\nseed 1\ntick-rate 60\nlevel-hash "
            << (hash.empty() ? level_hash_ : hash) << "\n"
            << body;
        return path(name);
    }

    // `jostle play` with the source tree's assets.
    RunResult play(std::vector<std::string> args) {
        args.insert(args.begin(), "play");
        args.push_back("--assets");
        args.push_back(kAssets);
        return run_jostle(args);
    }

    void expect_usage_error(const std::vector<std::string>& args, const std::string& message) {
        const RunResult r = play(args);
        EXPECT_EQ(r.status, 2) << message;
        EXPECT_EQ(r.out, "");
        EXPECT_EQ(r.err, usage_error(message));
    }

    // The sheet at sheet_path is contact_sheet() of the frames of these ticks in out_dir.
    void expect_contact_sheet_of(const std::string& sheet_path, const std::string& out_dir, const std::vector<std::int64_t>& ticks) {
        std::vector<Image> images;
        for (const std::int64_t tick : ticks) {
            const std::string number = std::to_string(tick);
            images.push_back(read_png(out_dir + "/frame_" + std::string(6 - number.size(), '0') + number + ".png"));
        }
        std::vector<SheetFrame> frames;
        for (std::size_t i = 0; i < images.size(); ++i) frames.push_back({ticks[i], &images[i]});
        const Image expected = contact_sheet(frames);
        const Image sheet = read_png(sheet_path);
        EXPECT_EQ(sheet.width, expected.width);
        EXPECT_EQ(sheet.height, expected.height);
        EXPECT_TRUE(sheet.rgba == expected.rgba);
    }

    const test::TempFolder dir_{"play"};
    std::string level_hash_;
};

// Ten ticks of driving right from (100, 240): the ship ends at x = 125.
constexpr const char* kDrive =
    "0-9 up\n"
    "at 9 expect player in 120 230 130 250\n"
    "at 9 expect var score = 0\n"
    "at 10 end\n";

// A busier run for the trace: turning, driving, firing, and the cannon's first ball (tick 119).
constexpr const char* kBusy =
    "0-19 left fire\n"
    "20-79 up fire\n"
    "80-99 right\n"
    "100-139 up\n"
    "at 150 end\n";

TEST_F(Play, UsageErrorsExitTwoWithTheirMessage) {
    const RunResult none = run_jostle({"play"});
    EXPECT_EQ(none.status, 2);
    EXPECT_EQ(none.out, "");
    EXPECT_EQ(none.err, usage_error("expected a scenario file"));
    const std::string s = scenario("s.scn", kDrive);
    expect_usage_error({s, "--fast"}, "unknown option '--fast'");
    expect_usage_error({"-x", s}, "unknown option '-x'");
    expect_usage_error({s, "other.scn"}, "expected one scenario, got a second: 'other.scn'");
    expect_usage_error({"--quiet"}, "expected a scenario file");
    for (const char* option : {"--out", "--frames", "--every", "--size", "--sheet", "--anim", "--trace", "--dump-every"}) {
        const RunResult r = run_jostle({"play", s, option});
        EXPECT_EQ(r.status, 2) << option;
        EXPECT_EQ(r.err, usage_error(std::string(option) + " needs a value"));
    }
    expect_usage_error({s, "--out", ""}, "--out needs a value");
    // An option in a value's place is not taken as a file name (that wrote a file '--quiet').
    expect_usage_error({s, "--trace", "--quiet"},
                       "--trace needs a value, got the option '--quiet' (a path that begins with '-' is written ./--quiet)");
    expect_usage_error({s, "--out", "-h"}, "--out needs a value, got the option '-h' (a path that begins with '-' is written ./-h)");
    // A value given twice is refused, not the last one silently kept.
    expect_usage_error({s, "--trace", "a.trace", "--trace", "b.trace"}, "--trace given twice");
    expect_usage_error({s, "--size", "4x4", "--size", "8x6"}, "--size given twice");
}

TEST_F(Play, BadSizeFramesAndEvery) {
    const std::string s = scenario("s.scn", kDrive);
    for (const char* size : {"64", "0x48", "64x", "x48", "8193x10", "64x48x2", "-64x48", "64X48"}) {
        expect_usage_error({s, "--size", size},
                           std::string("--size: expected WIDTHxHEIGHT with sides from 1 to 8192, got '") + size + "'");
    }
    expect_usage_error({s, "--frames", "10-5"}, "--frames: frames '10-5': range 10-5 ends before it starts");
    expect_usage_error({s, "--frames", "x"}, "--frames: frames 'x': expected a frame number (0 or more), got 'x'");
    expect_usage_error({s, "--frames", "1,,2"}, "--frames: frames '1,,2': expected a frame number or a range A-B, got an empty item");
    for (const char* every : {"0", "-1", "x", "1000001", "2.5"}) {
        expect_usage_error({s, "--every", every},
                           std::string("--every: expected a whole number from 1 to 1000000, got '") + every + "'");
    }
    expect_usage_error({s, "--dump-every", "0"}, "--dump-every: expected a whole number from 1 to 1000000, got '0'");
    expect_usage_error({s, "--every", "+2"},
                       "--every: expected a whole number from 1 to 1000000, got '+2' (a number here is written without a sign)");
}

TEST_F(Play, HelpExitsZero) {
    const RunResult r = run_jostle({"play", "--help"});
    EXPECT_EQ(r.status, 0);
    EXPECT_EQ(r.out, play_help());
    EXPECT_EQ(r.out.rfind("usage: jostle play SCENARIO", 0), 0u);
    EXPECT_EQ(r.err, "");
    // Anywhere an option may stand (not as an option's value: `--trace -h` names a file).
    for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
             {"play", "s.scn", "--quiet", "--help"}, {"play", "s.scn", "-h", "--every", "0"}}) {
        const RunResult later = run_jostle(args);
        EXPECT_EQ(later.status, 0) << args[2];
        EXPECT_EQ(later.out, play_help());
        EXPECT_EQ(later.err, "");
    }
}

TEST_F(Play, BadInputExitsTwoNamingFileAndLine) {
    const std::string bad = scenario("bad.scn", "0 up\n1 jump\n");
    RunResult r = play({bad});
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(r.err, "jostle play: " + bad + ":8:3: unknown action 'jump' (expected one of: left, right, up, down, fire, or '-' for none)\n");

    const std::string missing = path("missing.scn");
    r = play({missing});
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.err, "jostle play: " + missing + ": cannot open the scenario file: No such file or directory\n");

    const std::string lives = scenario("lives.scn", "0 up\nat 0 expect var lives = 3\n");
    r = play({lives});
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(r.err, "jostle play: " + lives + ":8:17: unknown game variable 'lives' (expected one of: score, shots, balls, fastest, touches)\n");

    // The levels come from --assets: a level unknown there, and a broken level file.
    const fs::path assets = dir_.path() / "assets";
    fs::create_directories(assets / "levels");
    std::ofstream((assets / "levels" / "arena.level").string(), std::ios::binary) << "jostle-level 1\nsize 0 480\nplayer 1 1\n";
    std::ofstream((assets / "levels" / "other.level").string(), std::ios::binary) << "jostle-level 1\n";
    const std::string s = scenario("s.scn", kDrive);
    r = run_jostle({"play", s, "--assets", assets.string(), "--quiet"});
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.err, "jostle play: " + (assets / "levels" / "arena.level").string() + ":2:6: expected a positive width, got '0'\n");
    fs::remove(assets / "levels" / "arena.level");
    r = run_jostle({"play", s, "--assets", assets.string()});
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.err, "jostle play: " + s + ":3:7: unknown level 'arena' (expected one of: other)\n");
}

TEST_F(Play, AFailingExpectationExitsOneSayingWhatWasFound) {
    const std::string s = scenario("fail.scn",
                                   "0-9 up\n"
                                   "at 9 expect var score = 5\n"
                                   "at 9 expect player in 120 230 130 250\n"
                                   "at 9 expect count pickup < 2\n"
                                   "at 4 expect player in 0 0 10 10\n"
                                   "at 10 end\n");
    const RunResult r = play({s});
    EXPECT_EQ(r.status, 1);
    // Prefixed like every other message of the program, the scenario's file:line after it.
    EXPECT_EQ(r.err, "jostle play: " + s + ":11: expectation failed at tick 4: expected player in 0 0 10 10, found player is alive at (112.5, 240)\n"
                     "jostle play: " + s + ":8: expectation failed at tick 9: expected var score = 5, found score = 0\n"
                     "jostle play: " + s + ":10: expectation failed at tick 9: expected count pickup < 2, found count pickup = 2\n");
    EXPECT_EQ(r.out.rfind("played " + s + ": 10 ticks, 1/4 expectations passed, ", 0), 0u) << r.out;
}

TEST_F(Play, APassingRunPrintsTheSummary) {
    const std::string s = scenario("s.scn", kDrive);
    RunResult r = play({s});
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err, "");
    const std::string prefix = "played " + s + ": 10 ticks, 2/2 expectations passed, ";
    ASSERT_EQ(r.out.rfind(prefix, 0), 0u) << r.out;
    // GoogleTest's regex (POSIX): std::regex trips a false -Wmaybe-uninitialized in GCC 12's
    // sanitizer build.
    EXPECT_THAT(r.out.substr(prefix.size()), ::testing::MatchesRegex("[0-9]+\\.[0-9] s \\([0-9]+\\.[0-9] ticks/s\\)\n")) << r.out;

    r = play({s, "--quiet"});
    EXPECT_EQ(r.status, 0);
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(r.err, "");
}

// One of a thing is said in the singular: "1 tick, 1/1 expectation passed ... 1 frame rendered".
TEST_F(Play, TheSummarySaysOneInTheSingular) {
    const std::string s = scenario("one.scn", "0 up\nat 0 expect var score = 0\nat 1 end\n");
    const std::string out = path("frames");
    const RunResult r = play({s, "--out", out, "--size", "64x48"});
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err, "");
    const std::string prefix = "played " + s + ": 1 tick, 1/1 expectation passed, ";
    ASSERT_EQ(r.out.rfind(prefix, 0), 0u) << r.out;
    EXPECT_THAT(r.out.substr(prefix.size()),
                ::testing::MatchesRegex("[0-9]+\\.[0-9] s \\([0-9]+\\.[0-9] ticks/s\\), 1 frame rendered \\([0-9]+\\.[0-9] frames/s\\)\n"
                                        "frames: 1 in .*/\n"))
        << r.out;
}

TEST_F(Play, AChangedLevelIsANoteNotAnError) {
    const std::string s = scenario("old.scn", kDrive, "0000000000000000");
    RunResult r = play({s});
    EXPECT_EQ(r.status, 0);
    EXPECT_EQ(r.err, "jostle play: note: " + s + ": level 'arena' has changed since the scenario was recorded (level-hash " +
                         "0000000000000000, now " + level_hash_ + ")\n");
    r = play({s, "--quiet"});
    EXPECT_EQ(r.status, 0);
    EXPECT_EQ(r.err, "");
}

TEST_F(Play, OutWritesExactlyTheSelectedFrames) {
    const std::string s = scenario("s.scn", kDrive);
    const std::string out = path("frames");
    const RunResult r = play({s, "--out", out, "--frames", "2-5", "--every", "2", "--size", "64x48"});
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find(", 2 frames rendered ("), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("\nframes: 2 in " + out + "/\n"), std::string::npos) << r.out;
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(out)) names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{"frame_000002.png", "frame_000004.png"}));
    for (const std::string& name : names) {
        const Image im = read_png(out + "/" + name);
        EXPECT_EQ(im.width, 64);
        EXPECT_EQ(im.height, 48);
    }
    // The 640x480 arena at a tenth of its size: the left wall in the first column, the floor
    // colour at world (200, 400).
    const Image im = read_png(out + "/frame_000002.png");
    const auto pixel = [&](int x, int y) {
        const std::size_t i = (static_cast<std::size_t>(y) * 64u + static_cast<std::size_t>(x)) * 4u;
        return std::vector<int>{im.rgba[i], im.rgba[i + 1], im.rgba[i + 2], im.rgba[i + 3]};
    };
    EXPECT_EQ(pixel(0, 24), (std::vector<int>{110, 110, 120, 255}));
    EXPECT_EQ(pixel(20, 40), (std::vector<int>{24, 26, 32, 255}));
}

TEST_F(Play, TheTraceReadsBackAndIsTheSameWithAndWithoutRendering) {
    const std::string s = scenario("busy.scn", kBusy);
    RunResult r = play({s, "--trace", path("a.trace"), "--quiet"});
    ASSERT_EQ(r.status, 0) << r.err;
    r = play({s, "--trace", path("b.trace"), "--quiet"});
    ASSERT_EQ(r.status, 0) << r.err;
    r = play({s, "--trace", path("c.trace"), "--out", path("frames"), "--every", "10", "--size", "64x48", "--overlay"});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find(", 15 frames rendered ("), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("\ntrace: " + path("c.trace") + "\n"), std::string::npos) << r.out;

    const std::string a = read_text(path("a.trace"));
    EXPECT_EQ(read_text(path("b.trace")), a);
    EXPECT_EQ(read_text(path("c.trace")), a);  // rendering changes nothing
    const ReplayResult trace = parse_trace(a, "a.trace");
    EXPECT_EQ(trace.ticks, 150);
    EXPECT_EQ(trace.hashes.size(), 150u);
    ASSERT_EQ(trace.dumps.size(), 16u);  // every 10th tick and the last
    EXPECT_EQ(trace.dumps.back().tick, 149);
    EXPECT_EQ(trace.dumps[0].entities[0].name, "game");
    // The run did what the input says: shots fired and the cannon's first ball.
    const auto game_field = [&](const TraceDump& d, const std::string& name) {
        for (const StateField& f : d.entities[0].fields) {
            if (f.name == name) return f.value;
        }
        return std::string("(none)");
    };
    EXPECT_EQ(game_field(trace.dumps.back(), "shots"), "10");  // 80 ticks of fire, every 8th
    EXPECT_EQ(game_field(trace.dumps.back(), "balls"), "1");
    EXPECT_EQ(game_field(trace.dumps[11], "balls"), "0");  // tick 110

    // --dump-every changes the dumps, never the hashes.
    r = play({s, "--trace", path("d.trace"), "--dump-every", "50", "--quiet"});
    ASSERT_EQ(r.status, 0) << r.err;
    const ReplayResult every50 = parse_trace(read_text(path("d.trace")), "d.trace");
    EXPECT_EQ(every50.hashes, trace.hashes);
    ASSERT_EQ(every50.dumps.size(), 4u);  // 0, 50, 100, 149
    EXPECT_EQ(every50.dumps[2].tick, 100);
}

TEST_F(Play, DumpEveryWithoutTraceIsANote) {
    const std::string s = scenario("s.scn", kDrive);
    const RunResult r = play({s, "--dump-every", "5"});
    EXPECT_EQ(r.status, 0);
    EXPECT_EQ(r.err, "jostle play: note: --dump-every has no effect without --trace\n");
}

TEST_F(Play, ImageOptionsWithoutAnImageOutputAreANote) {
    const std::string s = scenario("s.scn", kDrive);
    RunResult r = play({s, "--overlay"});
    EXPECT_EQ(r.status, 0);
    EXPECT_EQ(r.err, "jostle play: note: --overlay has no effect without --out, --sheet or --anim\n");
    EXPECT_EQ(r.out.rfind("played " + s + ": 10 ticks", 0), 0u) << r.out;
    r = play({s, "--no-hud", "--size", "64x48"});
    EXPECT_EQ(r.status, 0);
    EXPECT_EQ(r.err, "jostle play: note: --size and --no-hud have no effect without --out, --sheet or --anim\n");
    r = play({s, "--no-hud", "--overlay", "--size", "64x48", "--every", "2", "--frames", "0-9", "--dump-every", "5"});
    EXPECT_EQ(r.status, 0);
    EXPECT_EQ(r.err,
              "jostle play: note: --dump-every has no effect without --trace\n"
              "jostle play: note: --frames, --every, --size, --overlay and --no-hud have no effect without --out, --sheet or --anim\n");
    // Given with its default value, an option still does nothing.
    r = play({s, "--every", "1", "--dump-every", "10"});
    EXPECT_EQ(r.status, 0);
    EXPECT_EQ(r.err,
              "jostle play: note: --dump-every has no effect without --trace\n"
              "jostle play: note: --every has no effect without --out, --sheet or --anim\n");
    // --quiet says nothing; any image output uses them.
    r = play({s, "--overlay", "--frames", "3", "--quiet"});
    EXPECT_EQ(r.status, 0);
    EXPECT_EQ(r.err, "");
    for (const char* output : {"--out", "--sheet", "--anim"}) {
        SCOPED_TRACE(output);
        const std::string where = path(std::string(output + 2) + (std::string(output) == "--out" ? "" : ".png"));
        r = play({s, output, where, "--overlay", "--no-hud", "--frames", "3", "--every", "1", "--size", "32x24"});
        EXPECT_EQ(r.status, 0);
        EXPECT_EQ(r.err, "");
    }
    // Not an error: a failing expectation still exits 1.
    const std::string failing = scenario("f.scn", "0-9 -\nat 9 expect var score = 99\nat 10 end\n");
    r = play({failing, "--overlay"});
    EXPECT_EQ(r.status, 1);
    EXPECT_THAT(r.err, ::testing::HasSubstr("jostle play: note: --overlay has no effect without --out, --sheet or --anim\n"));
}

TEST_F(Play, AnimAndSheetAreValidPngs) {
    const std::string s = scenario("s.scn", kDrive);
    const RunResult r = play({s, "--anim", path("run.png"), "--sheet", path("sheet.png"), "--frames", "0-9", "--every", "3",
                              "--size", "64x48"});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("\nanimation: " + path("run.png") + "\n"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("\ncontact sheet: " + path("sheet.png") + "\n"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find(", 4 frames rendered ("), std::string::npos) << r.out;  // ticks 0, 3, 6, 9

    const test::Apng apng = test::read_apng(path("run.png"));  // checks every chunk and CRC
    EXPECT_EQ(apng.width, 64);
    EXPECT_EQ(apng.height, 48);
    ASSERT_EQ(apng.frames.size(), 4u);  // the ship moves: no two frames are equal
    EXPECT_EQ(apng.frames[0].delay_num, 3);
    EXPECT_EQ(apng.frames[0].delay_den, 60);
    const Image first = read_png(path("run.png"));  // a plain PNG reader sees the first frame
    EXPECT_EQ(first.width, 64);

    const Image sheet = read_png(path("sheet.png"));
    EXPECT_GE(sheet.width, 2 * 64);  // four thumbnails at 64 px, in a grid
    EXPECT_GT(sheet.height, 2 * 48);
}

// play draws each sheet frame into the sheet as it renders it instead of keeping the frames:
// the sheet is still the contact sheet of the frames it wrote as files.
TEST_F(Play, TheSheetIsTheContactSheetOfTheFrames) {
    const std::string s = scenario("s.scn", kDrive);
    const std::string out = path("frames");
    const RunResult r = play({s, "--out", out, "--sheet", path("sheet.png"), "--frames", "0-9", "--every", "3", "--size", "64x48"});
    ASSERT_EQ(r.status, 0) << r.err;
    expect_contact_sheet_of(path("sheet.png"), out, {0, 3, 6, 9});
}

TEST_F(Play, NoHudLeavesOutOnlyTheScoreLine) {
    const std::string s = scenario("s.scn", kDrive);
    ASSERT_EQ(play({s, "--out", path("hud"), "--frames", "5", "--quiet"}).status, 0);
    const RunResult r = play({s, "--out", path("plain"), "--frames", "5", "--no-hud", "--quiet"});
    ASSERT_EQ(r.status, 0) << r.err;
    const Image hud = read_png(path("hud/frame_000005.png"));
    const Image plain = read_png(path("plain/frame_000005.png"));
    ASSERT_EQ(hud.width, plain.width);
    ASSERT_EQ(hud.height, plain.height);
    // The line "SCORE 0   TICK 5" is drawn at (8, 8) at twice the font's size: every pixel
    // that differs lies in its box, and some do.
    int differing = 0, outside = 0;
    for (int y = 0; y < hud.height; ++y) {
        for (int x = 0; x < hud.width; ++x) {
            const std::size_t i = (static_cast<std::size_t>(y) * static_cast<std::size_t>(hud.width) + static_cast<std::size_t>(x)) * 4u;
            if (std::equal(hud.rgba.begin() + static_cast<std::ptrdiff_t>(i), hud.rgba.begin() + static_cast<std::ptrdiff_t>(i) + 4,
                           plain.rgba.begin() + static_cast<std::ptrdiff_t>(i))) {
                continue;
            }
            ++differing;
            outside += (x < 8 || x >= 240 || y < 8 || y >= 30) ? 1 : 0;
        }
    }
    EXPECT_GT(differing, 50);
    EXPECT_EQ(outside, 0);
}

TEST_F(Play, ASheetOfMoreFramesThanItHoldsSpreadsThemEvenly) {
    // 100 frames selected, 64 on the sheet (kMaxSheetFrames): ticks i * 99 / 63, first and last kept.
    const std::string s = scenario("s.scn", kBusy);
    const std::string out = path("frames");
    const RunResult r = play({s, "--out", out, "--sheet", path("sheet.png"), "--frames", "0-99", "--size", "32x24", "--quiet"});
    ASSERT_EQ(r.status, 0) << r.err;
    ASSERT_EQ(kMaxSheetFrames, 64);
    std::vector<std::int64_t> ticks;
    for (std::int64_t i = 0; i < kMaxSheetFrames; ++i) ticks.push_back(i * 99 / (kMaxSheetFrames - 1));
    ASSERT_EQ(ticks.back(), 99);
    expect_contact_sheet_of(path("sheet.png"), out, ticks);
}

// "--" ends the options in every command: files named like options come after it.
TEST_F(Play, DoubleDashEndsTheOptionsForFilesNamedLikeThem) {
    const std::string s = scenario("-x.scn", kDrive);
    const std::string cwd = dir_.path().string();
    const auto run_in_folder = [&](const std::vector<std::string>& args) { return test::run_jostle_binary(args, "/dev/null", cwd); };
    const RunResult refused = run_in_folder({"play", "-x.scn", "--assets", kAssets});
    EXPECT_EQ(refused.status, 2);
    EXPECT_EQ(refused.err, usage_error("unknown option '-x.scn'"));
    const RunResult played = run_in_folder({"play", "--assets", kAssets, "--", "-x.scn"});
    EXPECT_EQ(played.status, 0) << played.err;
    EXPECT_THAT(played.out, ::testing::StartsWith("played -x.scn: 10 ticks, 2/2 expectations passed"));
    // After "--" even an option's name is a file: here a second scenario.
    EXPECT_EQ(run_in_folder({"play", "--", "-x.scn", "--quiet"}).err, usage_error("expected one scenario, got a second: '--quiet'"));
    const RunResult updated = run_in_folder({"check", "--assets", kAssets, "--update", "--", "-x.scn"});
    EXPECT_EQ(updated.status, 0) << updated.err;
    EXPECT_TRUE(fs::exists(path("-x.trace")));
    EXPECT_EQ(run_in_folder({"check", "--assets", kAssets, "--", "-x.scn"}).status, 0);
    fs::copy_file(std::string(JOSTLE_TEST_DATA) + "/mask_4x4.png", path("-a.png"));
    const RunResult compared = run_in_folder({"imgdiff", "--", "-a.png", "-a.png"});
    EXPECT_EQ(compared.status, 0) << compared.err;
    EXPECT_EQ(compared.out, "identical: 4x4\n");
    const RunResult recorded = run_in_folder({"record", "--level", "arena", "-o", "r.scn", "--", "-x.scn"});
    EXPECT_EQ(recorded.status, 2);
    EXPECT_EQ(recorded.err, "jostle record: unexpected argument '-x.scn'\nRun 'jostle record --help' for usage.\n");
}

// Output that cannot reach standard output (a full disk, a closed descriptor) is an error
// saying so and why, exit 2, for every command: a summary or a listing is never lost in silence.
TEST(CommandLine, AStandardOutputThatCannotBeWrittenIsAnErrorExitTwo) {
    if (!fs::exists("/dev/full") || !fs::exists("/bin/sh")) GTEST_SKIP() << "needs /dev/full and /bin/sh";
    const std::string scenario = kAssets + "/scenarios/demo.scn";
    const std::string png = std::string(JOSTLE_TEST_DATA) + "/mask_4x4.png";
    struct Case {
        std::string command;
        std::vector<std::string> args;
        std::string stdin_path = "/dev/null";
    };
    // Short outputs (a summary, one line) fail when flushed at the end; long ones (help texts,
    // check's lines, query's answers, flushed each) during the run.
    const Case cases[] = {{"play", {"play", scenario, "--assets", kAssets}},
                          {"check", {"check", scenario, "--assets", kAssets}},
                          {"imgdiff", {"imgdiff", png, png}},
                          {"help", {"--help"}},
                          {"help", {"help", "play"}},
                          {"play", {"play", "--help"}},
                          {"query", {"query"}, std::string(JOSTLE_TEST_DATA) + "/queries_good.jsonl"},
                          {"query", {"query"}, std::string(JOSTLE_TEST_DATA) + "/queries_mixed.jsonl"}};  // exit 2 anyway
    for (const Case& c : cases) {
        for (const auto& [redirect, reason] : {std::pair<std::string, std::string>{"> /dev/full", "No space left on device"},
                                               {">&-", "Bad file descriptor"}}) {
            std::vector<std::string> args = {"-c", "exec \"$0\" \"$@\" " + redirect, JOSTLE_BINARY};
            args.insert(args.end(), c.args.begin(), c.args.end());
            SCOPED_TRACE(args.back() + " " + redirect);
            const RunResult r = test::run_program("/bin/sh", args, c.stdin_path);
            EXPECT_EQ(r.status, 2);
            EXPECT_EQ(r.err, "jostle " + c.command + ": standard output: cannot write: " + reason + "\n");
        }
    }
    // Writable, the same runs exit 0 with nothing on stderr.
    const RunResult ok = test::run_program("/bin/sh", {"-c", "exec \"$0\" \"$@\" > /dev/null", JOSTLE_BINARY, "imgdiff", png, png});
    EXPECT_EQ(ok.status, 0);
    EXPECT_EQ(ok.err, "");
}

// An --out folder that is the assets' sprites folder would make every frame a sprite (and
// change every scenario's level-hash); the levels folder is the game's too. Either is refused
// before the run, by any spelling, and nothing is written there.
TEST_F(Play, AnOutFolderThatIsTheAssetsSpritesOrLevelsFolderIsRefused) {
    const fs::path assets = path("assets");
    fs::create_directories(assets);
    fs::copy(fs::path(kAssets) / "levels", assets / "levels");
    fs::copy(fs::path(kAssets) / "sprites", assets / "sprites");
    const std::vector<std::string> sprites = test::file_names(assets / "sprites"), levels = test::file_names(assets / "levels");
    const std::string s = scenario("s.scn", kDrive);
    const std::pair<std::string, std::string> cases[] = {{(assets / "sprites").string(), "sprites"},
                                                         {(assets / "levels").string() + "/", "levels"},
                                                         {(assets / "levels" / ".." / "sprites").string(), "sprites"}};
    for (const auto& [out, what] : cases) {
        const RunResult r = run_jostle({"play", s, "--assets", assets.string(), "--out", out, "--frames", "3", "--quiet"});
        EXPECT_EQ(r.status, 2) << out;
        EXPECT_EQ(r.err, usage_error("--out: '" + out + "' is the " + what + " folder of the assets; give another folder"));
    }
    EXPECT_EQ(test::file_names(assets / "sprites"), sprites);
    EXPECT_EQ(test::file_names(assets / "levels"), levels);
    // A folder below them is not read by the game: frames may go there.
    const RunResult below = run_jostle({"play", s, "--assets", assets.string(), "--out", (assets / "sprites" / "frames").string(),
                                        "--frames", "3", "--size", "32x24", "--quiet"});
    EXPECT_EQ(below.status, 0) << below.err;
    EXPECT_TRUE(fs::exists(assets / "sprites" / "frames" / "frame_000003.png"));
}

// An output named /dev/stdout goes through the program's descriptor 1 (README: it "stays the
// descriptor it stands for"), after and before what the program prints there, whatever stdout
// is: a file (`>`), a file appended to (`>>`) or a pipe. Opened again by name, it started at
// offset 0 of the file: the summary overwrote the trace's start, and `>>` lost the old lines.
TEST_F(Play, AnOutputToDevStdoutGoesThroughTheDescriptorInOrder) {
    if (!fs::exists("/bin/sh")) GTEST_SKIP() << "needs /bin/sh";
    const std::string s = scenario("s.scn", kDrive);
    // `jostle ARGS REDIRECT` through the shell.
    const auto shell = [&](const std::string& redirect, const std::vector<std::string>& jostle_args) {
        std::vector<std::string> args = {"-c", "exec \"$0\" \"$@\" " + redirect, JOSTLE_BINARY};
        args.insert(args.end(), jostle_args.begin(), jostle_args.end());
        return test::run_program("/bin/sh", args);
    };
    ASSERT_EQ(play({s, "--trace", path("ref.trace"), "--quiet"}).status, 0);
    const std::string trace = read_text(path("ref.trace"));
    ASSERT_THAT(trace, ::testing::StartsWith("jostle-trace 1\n"));

    // `>`: the trace alone (a line after it would make it unreadable); the summary on stderr.
    const RunResult plain = shell("> '" + path("tr.txt") + "'", {"play", s, "--assets", kAssets, "--trace", "/dev/stdout"});
    EXPECT_EQ(plain.status, 0) << plain.err;
    EXPECT_EQ(read_text(path("tr.txt")), trace);
    EXPECT_THAT(plain.err, ::testing::StartsWith("played " + s + ": 10 ticks"));
    EXPECT_THAT(plain.err, ::testing::EndsWith("\ntrace: /dev/stdout\n"));
    // `>>`: appended after what the file held.
    std::ofstream(path("pre.txt"), std::ios::binary) << "hi\n";
    const RunResult appended = shell(">> '" + path("pre.txt") + "'", {"play", s, "--assets", kAssets, "--trace", "/dev/stdout", "--quiet"});
    EXPECT_EQ(appended.status, 0) << appended.err;
    EXPECT_EQ(read_text(path("pre.txt")), "hi\n" + trace);
    // A pipe, and the other spellings of descriptor 1.
    for (const char* name : {"/dev/stdout", "/dev/fd/1", "/proc/self/fd/1"}) {
        const RunResult piped = play({s, "--trace", name, "--quiet"});
        EXPECT_EQ(piped.status, 0) << piped.err;
        EXPECT_EQ(piped.out, trace) << name;
    }

    // An animation, whose header is patched at the end, is whole and alone.
    const std::vector<std::string> anim = {"play", s, "--assets", kAssets, "--frames", "0-5", "--size", "32x24", "--anim"};
    const auto with = [](std::vector<std::string> args, const std::vector<std::string>& more) {
        args.insert(args.end(), more.begin(), more.end());
        return args;
    };
    ASSERT_EQ(run_jostle(with(anim, {path("ref.png"), "--quiet"})).status, 0);
    const std::string apng = read_text(path("ref.png"));
    const RunResult animated = shell("> '" + path("anim.png") + "'", with(anim, {"/dev/stdout"}));
    EXPECT_EQ(animated.status, 0) << animated.err;
    EXPECT_EQ(read_text(path("anim.png")), apng);
    EXPECT_THAT(animated.err, ::testing::StartsWith("played "));
    // Appending cannot patch a header: said before the run (no frame is selected until tick
    // 5,000, which this run never reaches), and the file keeps its lines.
    const std::vector<std::string> late = {"play", s, "--assets", kAssets, "--frames", "5000", "--size", "32x24", "--anim"};
    const RunResult refused = shell(">> '" + path("pre.txt") + "'", with(late, {"/dev/stdout"}));
    EXPECT_EQ(refused.status, 2);
    EXPECT_EQ(refused.err, "jostle play: /dev/stdout: cannot write: it is open for appending (>>), and this file's header is "
                           "patched once the rest is written: give a file path\n");
    EXPECT_EQ(read_text(path("pre.txt")), "hi\n" + trace);

    // imgdiff: the diff picture alone on stdout, the verdict on stderr.
    ASSERT_EQ(run_jostle({"play", s, "--assets", kAssets, "--out", path("f"), "--frames", "9", "--size", "32x24", "--quiet"}).status, 0);
    const std::string a = path("f/frame_000009.png"), b = std::string(JOSTLE_TEST_DATA) + "/mask_4x4.png";
    ASSERT_EQ(run_jostle({"imgdiff", a, b, "--out", path("ref_diff.png")}).status, 1);
    const RunResult diffed = shell("> '" + path("diff.png") + "'", {"imgdiff", a, b, "--out", "/dev/stdout"});
    EXPECT_EQ(diffed.status, 1);
    EXPECT_THAT(diffed.err, ::testing::StartsWith("differ: "));
    EXPECT_EQ(read_text(path("diff.png")), read_text(path("ref_diff.png")));
}

// A level wider than the largest frame (8192 px) renders at its own shape, scaled down to
// 8192 px on its longer side, instead of stopping at the renderer's limit.
TEST_F(Play, ALevelWiderThanAFrameIsScaledDownToFit) {
    const fs::path assets = dir_.path() / "assets";
    fs::create_directories(assets / "levels");
    std::ofstream((assets / "levels" / "wide.level").string(), std::ios::binary) << "jostle-level 1\nsize 9000 100\nplayer 100 50\n";
    const std::string s = path("wide.scn");
    std::ofstream(s, std::ios::binary) << "jostle-scenario 1\nengine 0.1.0\nlevel wide\nseed 1\ntick-rate 60\nlevel-hash "
                                       << game::ArenaGame(assets.string()).level_hash("wide") << "\n\n0-2 left\n";
    const RunResult r = run_jostle({"play", s, "--assets", assets.string(), "--out", path("frames"), "--frames", "1", "--quiet"});
    ASSERT_EQ(r.status, 0) << r.err;
    const Image frame = read_png(path("frames/frame_000001.png"));
    EXPECT_EQ(frame.width, 8192);
    EXPECT_EQ(frame.height, 91);  // 100 * 8192 / 9000, rounded
}

TEST_F(Play, AnOutputThatCannotBeWrittenIsBadInput) {
    const std::string s = scenario("s.scn", kDrive);
    const std::string trace = path("no/such/folder/t.trace");
    const RunResult r = play({s, "--trace", trace, "--quiet"});
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.err.rfind("jostle play: " + trace + ": cannot write: ", 0), 0u) << r.err;
    EXPECT_FALSE(fs::exists(trace));
}

// An --out folder the run makes may hold the other outputs (they are checked at the end there).
TEST_F(Play, OutputsMayGoInTheOutFolderTheRunMakes) {
    const std::string s = scenario("s.scn", kDrive);
    const fs::path run = dir_.path() / "run";
    const RunResult r = play({s, "--out", run.string(), "--frames", "0-2", "--trace", (run / "t.trace").string(), "--sheet",
                              (run / "sheet.png").string(), "--anim", (run / "a.png").string(), "--quiet"});
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(test::file_names(run), (std::vector<std::string>{"a.png", "frame_000000.png", "frame_000001.png",
                                                               "frame_000002.png", "sheet.png", "t.trace"}));
}

// An expectation naming an entity the game never gives is refused before the run: no frame
// is written first.
TEST_F(Play, AMisspeltEntityIsRefusedBeforeTheRun) {
    const std::string s = scenario("s.scn", "0-9 up\nat 9 expect plyer alive\nat 10 end\n");
    const std::string frames = path("frames");
    const RunResult r = play({s, "--out", frames, "--quiet"});
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.err, "jostle play: " + s + ":8:13: unknown entity 'plyer': no entity of this run can have that name (the dumps "
                     "of 'jostle play --trace' name every entity)\n");
    EXPECT_FALSE(fs::exists(frames));
    // One the game gives, but not by then (no shot fired): refused at its tick.
    const std::string early = scenario("early.scn", "0-9 up\nat 9 expect bullet_1 gone\nat 10 end\n");
    const RunResult e = play({early, "--quiet"});
    EXPECT_EQ(e.status, 2);
    EXPECT_EQ(e.err, "jostle play: " + early + ":8:13: no entity named 'bullet_1' has been in the run by tick 9 (a misspelt "
                     "name? the dumps of 'jostle play --trace' name every entity)\n");
}

// ... and is said before the run: no frame is rendered or written first (the frame folder the
// run made is gone again), whichever output it is.
TEST_F(Play, AnOutputThatCannotBeWrittenIsSaidBeforeTheRun) {
    const std::string s = scenario("s.scn", kDrive);
    for (const std::string flag : {"--trace", "--sheet", "--anim"}) {
        const std::string frames = path("frames");
        const RunResult r = play({s, "--out", frames, flag, dir_.path().string(), "--quiet"});
        EXPECT_EQ(r.status, 2) << flag;
        EXPECT_EQ(r.err, "jostle play: " + dir_.path().string() + ": cannot write: it is a folder\n") << flag;
        EXPECT_FALSE(fs::exists(frames)) << flag;
    }
}

// The game's own files are inputs too: an output naming a level or a sprite of the assets (by
// any spelling of its path) is refused before the run, and the file is left as it was.
TEST_F(Play, AnOutputNamingALevelOrASpriteOfTheAssetsIsRefused) {
    const fs::path assets = path("assets");
    fs::create_directories(assets);
    fs::copy(fs::path(kAssets) / "levels", assets / "levels");
    fs::copy(fs::path(kAssets) / "sprites", assets / "sprites");
    const std::string s = scenario("s.scn", kDrive);
    const std::string level = (assets / "levels" / "arena.level").string();
    const std::string sprite = (assets / "sprites" / ".." / "sprites" / "tree.png").string();
    const std::string level_bytes = test::read_text(level), sprite_bytes = test::read_text(sprite);
    const std::pair<std::string, std::string> cases[] = {
        {"--trace", level}, {"--sheet", sprite}, {"--anim", level}};
    for (const auto& [flag, output] : cases) {
        const RunResult r = run_jostle({"play", s, "--assets", assets.string(), flag, output, "--quiet"});
        EXPECT_EQ(r.status, 2) << flag;
        const std::string what = output == level ? "the level 'arena'" : "the sprite 'tree'";
        EXPECT_EQ(r.err, usage_error(flag + ": '" + output + "' is " + what + " of the assets; give another path"));
    }
    EXPECT_EQ(test::read_text(level), level_bytes);
    EXPECT_EQ(test::read_text(sprite), sprite_bytes);
    // A new file there would be read as a level or a sprite too.
    for (const auto& [flag, file, what] : {std::tuple{"--trace", "levels/new.level", "a new level 'new'"},
                                           std::tuple{"--sheet", "sprites/sheet.png", "a new sprite 'sheet'"}}) {
        const std::string output = (assets / file).string();
        const RunResult r = run_jostle({"play", s, "--assets", assets.string(), flag, output, "--quiet"});
        EXPECT_EQ(r.status, 2) << file;
        EXPECT_EQ(r.err, usage_error(std::string(flag) + ": '" + output + "' would be " + what + " of the assets; give another path"));
        EXPECT_FALSE(fs::exists(output));
    }
}

}  // namespace
}  // namespace jostle
