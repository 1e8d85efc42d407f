// trace_test.cpp: the trace file (replay.h): format_trace writes the exact text documented,
// parse_trace reads back every hash and dump (by hand and on seeded random traces), and
// malformed traces are refused with source:line and what was expected.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <string>

#include "jostle/core/error.h"
#include "jostle/replay/replay.h"

namespace jostle {
namespace {

std::string error_of(const std::string& text) {
    try {
        parse_trace(text, "t.trace");
    } catch (const InputError& e) {
        return e.what();
    }
    return "no error";
}

ReplayResult small_result() {
    ReplayResult r;
    r.ticks = 3;
    r.hashes = {0x9f3c1a2b3c4d5e6full, 0, UINT64_MAX};
    r.dumps.push_back(TraceDump{0,
                                {EntityDump{"game", {{"score", "0"}, {"shots", "0"}}},
                                 EntityDump{"player", {{"x", "104.25"}, {"y", "80"}, {"angle", "-0.05"}}}}});
    r.dumps.push_back(TraceDump{2, {EntityDump{"game", {{"score", "10"}, {"shots", "1"}}}, EntityDump{"bullet#1", {}}}});
    return r;
}

constexpr const char* kSmallTrace =
    "jostle-trace 1\n"
    "ticks 3\n"
    "dump-every 2\n"
    "0 9f3c1a2b3c4d5e6f\n"
    "  game score=0 shots=0\n"
    "  player x=104.25 y=80 angle=-0.05\n"
    "1 0000000000000000\n"
    "2 ffffffffffffffff\n"
    "  game score=10 shots=1\n"
    "  bullet#1\n";

TEST(Trace, FormatWritesTheDocumentedText) { EXPECT_EQ(format_trace(small_result(), 2), kSmallTrace); }

TEST(Trace, ParseReadsBackHashesAndDumps) {
    const ReplayResult r = parse_trace(kSmallTrace, "t.trace");
    EXPECT_EQ(r.ticks, 3);
    const std::vector<std::uint64_t> hashes = {0x9f3c1a2b3c4d5e6full, 0, UINT64_MAX};
    EXPECT_EQ(r.hashes, hashes);
    ASSERT_EQ(r.dumps.size(), 2u);
    EXPECT_EQ(r.dumps[0].tick, 0);
    ASSERT_EQ(r.dumps[0].entities.size(), 2u);
    EXPECT_EQ(r.dumps[0].entities[1].name, "player");
    ASSERT_EQ(r.dumps[0].entities[1].fields.size(), 3u);
    EXPECT_EQ(r.dumps[0].entities[1].fields[0].name, "x");
    EXPECT_EQ(r.dumps[0].entities[1].fields[0].value, "104.25");
    EXPECT_EQ(r.dumps[0].entities[1].fields[2].name, "angle");
    EXPECT_EQ(r.dumps[0].entities[1].fields[2].value, "-0.05");
    EXPECT_EQ(r.dumps[1].tick, 2);
    ASSERT_EQ(r.dumps[1].entities.size(), 2u);
    EXPECT_EQ(r.dumps[1].entities[0].fields[0].value, "10");
    EXPECT_EQ(r.dumps[1].entities[1].name, "bullet#1");
    EXPECT_TRUE(r.dumps[1].entities[1].fields.empty());
    EXPECT_EQ(format_trace(r, 2), kSmallTrace);
}

TEST(Trace, AFieldValueMayHoldAnEqualsSign) {
    const ReplayResult r = parse_trace("jostle-trace 1\nticks 1\ndump-every 1\n0 0000000000000001\n  game note=a=b\n", "t.trace");
    ASSERT_EQ(r.dumps.size(), 1u);
    ASSERT_EQ(r.dumps[0].entities[0].fields.size(), 1u);
    EXPECT_EQ(r.dumps[0].entities[0].fields[0].name, "note");
    EXPECT_EQ(r.dumps[0].entities[0].fields[0].value, "a=b");
}

TEST(Trace, ATraceWithNoTicks) {
    ReplayResult empty;
    const std::string text = format_trace(empty, 10);
    EXPECT_EQ(text, "jostle-trace 1\nticks 0\ndump-every 10\n");
    const ReplayResult back = parse_trace(text, "t.trace");
    EXPECT_EQ(back.ticks, 0);
    EXPECT_TRUE(back.hashes.empty());
    EXPECT_TRUE(back.dumps.empty());
}

TEST(TraceProperty, RandomTracesRoundTrip) {
    std::mt19937_64 rng(7);
    for (int round = 0; round < 100; ++round) {
        ReplayResult r;
        r.ticks = static_cast<std::int64_t>(rng() % 200);
        for (std::int64_t t = 0; t < r.ticks; ++t) r.hashes.push_back(rng() % 4 == 0 ? rng() % 16 : rng());
        const int every = 1 + static_cast<int>(rng() % 12);
        for (std::int64_t t = 0; t < r.ticks; ++t) {
            if (t % every != 0 && t != r.ticks - 1) continue;
            TraceDump d{t, {}};
            const int entities = 1 + static_cast<int>(rng() % 5);
            for (int i = 0; i < entities; ++i) {
                // (Built with append: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string.)
                EntityDump e;
                e.name.append("e").append(std::to_string(i));
                if (i % 2 == 1) e.name.append("#").append(std::to_string(rng() % 100));
                const int fields = static_cast<int>(rng() % 6);
                for (int f = 0; f < fields; ++f) {
                    StateField field;
                    field.name.append("f").append(std::to_string(f));
                    field.value.append(std::to_string(static_cast<std::int64_t>(rng() % 2001) - 1000)).append(".").append(std::to_string(rng() % 100));
                    e.fields.push_back(std::move(field));
                }
                d.entities.push_back(std::move(e));
            }
            r.dumps.push_back(std::move(d));
        }
        const std::string text = format_trace(r, every);
        const ReplayResult back = parse_trace(text, "random.trace");
        SCOPED_TRACE("round " + std::to_string(round));
        EXPECT_EQ(back.ticks, r.ticks);
        EXPECT_EQ(back.hashes, r.hashes);
        ASSERT_EQ(back.dumps.size(), r.dumps.size());
        for (std::size_t i = 0; i < r.dumps.size(); ++i) {
            EXPECT_EQ(back.dumps[i].tick, r.dumps[i].tick);
            ASSERT_EQ(back.dumps[i].entities.size(), r.dumps[i].entities.size());
            for (std::size_t j = 0; j < r.dumps[i].entities.size(); ++j) {
                const EntityDump& a = r.dumps[i].entities[j];
                const EntityDump& b = back.dumps[i].entities[j];
                EXPECT_EQ(b.name, a.name);
                ASSERT_EQ(b.fields.size(), a.fields.size());
                for (std::size_t k = 0; k < a.fields.size(); ++k) {
                    EXPECT_EQ(b.fields[k].name, a.fields[k].name);
                    EXPECT_EQ(b.fields[k].value, a.fields[k].value);
                }
            }
        }
        EXPECT_EQ(format_trace(back, every), text);
    }
}

// ---------------------------------------------------------------------------------------
// Malformed traces
// ---------------------------------------------------------------------------------------

const std::string kHead = "jostle-trace 1\nticks 2\ndump-every 10\n";

TEST(TraceErrors, NotATrace) {
    EXPECT_EQ(error_of("jostle-scenario 1\nengine 0.1.0\n"), "t.trace:1: expected 'jostle-trace 1' as the first line");
    EXPECT_EQ(error_of("jostle-trace 2\nticks 0\ndump-every 10\n"), "t.trace:1: expected 'jostle-trace 1' as the first line");
    EXPECT_EQ(error_of("\n"), "t.trace:1: expected 'jostle-trace 1' as the first line");
    EXPECT_EQ(error_of(""), "t.trace: expected 'jostle-trace 1' as the first line");
}

TEST(TraceErrors, Truncated) {
    EXPECT_EQ(error_of("jostle-trace 1"), "t.trace:1: truncated file: the last line has no newline (if the file is whole, end it with one)");
    EXPECT_EQ(error_of(kHead + "0 0000000000000001\n1 0000000000000002"), "t.trace:5: truncated file: the last line has no newline (if the file is whole, end it with one)");
    EXPECT_EQ(error_of(kHead + "0 0000000000000001\n"), "t.trace:4: truncated file: 1 tick lines, the header says 2");
    EXPECT_EQ(error_of(kHead), "t.trace:3: truncated file: 0 tick lines, the header says 2");
    EXPECT_EQ(error_of("jostle-trace 1\n"), "t.trace:1: truncated file: expected 'ticks N'");
    EXPECT_EQ(error_of("jostle-trace 1\nticks 2\n"), "t.trace:2: truncated file: expected 'dump-every N'");
}

TEST(TraceErrors, MoreTickLinesThanTheHeaderSays) {
    // Refused; the message says "truncated" although the file is too long (reported).
    EXPECT_EQ(error_of(kHead + "0 0000000000000001\n1 0000000000000002\n2 0000000000000003\n"),
              "t.trace:6: truncated file: 3 tick lines, the header says 2");
}

TEST(TraceErrors, BadHeaderLines) {
    EXPECT_EQ(error_of("jostle-trace 1\nticks x\ndump-every 10\n"), "t.trace:2: expected 'ticks N', got 'ticks x'");
    EXPECT_EQ(error_of("jostle-trace 1\nticks -1\ndump-every 10\n"), "t.trace:2: expected 'ticks N', got 'ticks -1'");
    EXPECT_EQ(error_of("jostle-trace 1\nticks 2 3\ndump-every 10\n"), "t.trace:2: expected 'ticks N', got 'ticks 2 3'");
    EXPECT_EQ(error_of("jostle-trace 1\ndump-every 10\nticks 2\n"), "t.trace:2: expected 'ticks N', got 'dump-every 10'");
    EXPECT_EQ(error_of("jostle-trace 1\nticks 2\ndump_every 10\n"), "t.trace:3: expected 'dump-every N', got 'dump_every 10'");
}

TEST(TraceErrors, BadHash) {
    const std::string message = "t.trace:4: expected 'TICK HASH' (a tick number and 16 hex digits), got '";
    EXPECT_EQ(error_of(kHead + "0 123\n"), message + "0 123'");
    EXPECT_EQ(error_of(kHead + "0 0123456789abcdef0\n"), message + "0 0123456789abcdef0'");
    EXPECT_EQ(error_of(kHead + "0 zzzzzzzzzzzzzzzz\n"), message + "0 zzzzzzzzzzzzzzzz'");
    EXPECT_EQ(error_of(kHead + "0 0123456789abcdeg\n"), message + "0 0123456789abcdeg'");
    EXPECT_EQ(error_of(kHead + "0\n"), message + "0'");
    EXPECT_EQ(error_of(kHead + "0  0123456789abcdef\n"), message + "0  0123456789abcdef'");
    EXPECT_EQ(error_of(kHead + "x 0123456789abcdef\n"), message + "x 0123456789abcdef'");
    EXPECT_EQ(error_of(kHead + "0 0123456789abcdef\r\n"), message + "0 0123456789abcdef\r'");
}

TEST(TraceErrors, TickOutOfOrder) {
    EXPECT_EQ(error_of(kHead + "1 0000000000000001\n"), "t.trace:4: expected tick 0, got 1");
    EXPECT_EQ(error_of(kHead + "0 0000000000000001\n0 0000000000000002\n"), "t.trace:5: expected tick 1, got 0");
    EXPECT_EQ(error_of(kHead + "0 0000000000000001\n  game a=1\n2 0000000000000002\n"), "t.trace:6: expected tick 1, got 2");
}

TEST(TraceErrors, EntityLineBeforeATickAndFieldsWithoutValues) {
    EXPECT_EQ(error_of(kHead + "  player x=1\n0 0000000000000001\n"), "t.trace:4: an entity line before the first tick line");
    EXPECT_EQ(error_of(kHead + "0 0000000000000001\n  player x=1 y\n"), "t.trace:5: expected NAME=VALUE, got 'y'");
}

}  // namespace
}  // namespace jostle
