// scenario_test.cpp: the scenario format: parsing every line kind, the run length, the
// writer's round trip, and every bad-input case with its exact message.
#include "jostle/replay/scenario.h"

#include <gtest/gtest.h>

#include "jostle/core/error.h"

namespace jostle {
namespace {

const ScenarioVocabulary kVocabulary{{"left", "right", "up", "down", "fire"}, {"arena", "crowd"}};

constexpr const char* kHeader =
    "jostle-scenario 1\n"
    "engine 0.1.0\n"
    "level arena\n"
    "seed 42\n"
    "tick-rate 60\n"
    "level-hash 0123456789abcdef\n";

std::string error_of(const std::string& text) {
    try {
        parse_scenario(text, "s.scn", kVocabulary);
    } catch (const InputError& e) {
        return e.what();
    }
    return "no error";
}

TEST(Scenario, ParsesTheHeaderInputAndDirectives) {
    const Scenario s = parse_scenario(std::string(kHeader) +
                                          "0-2 right   # a comment\n"
                                          "3 right fire\n"
                                          "\n"
                                          "6-7 -\n"
                                          "at 4 screenshot\n"
                                          "at 5 expect player in 1 2 3.5 4\n"
                                          "at 1 expect count rock >= 3\n"
                                          "at 9 end\n",
                                      "s.scn", kVocabulary);
    EXPECT_EQ(s.level, "arena");
    EXPECT_EQ(s.seed, 42u);
    EXPECT_EQ(s.tick_rate, 60);
    EXPECT_EQ(s.level_hash, "0123456789abcdef");
    EXPECT_EQ(s.ticks(), 9);
    ASSERT_EQ(s.inputs.size(), 8u);
    EXPECT_EQ(s.input(0).held, 0b10u);
    EXPECT_EQ(s.input(3).held, 0b10010u);
    EXPECT_EQ(s.input(4).held, 0u);  // not listed: nothing held
    EXPECT_EQ(s.input(8).held, 0u);
    ASSERT_EQ(s.expectations.size(), 2u);
    EXPECT_EQ(s.expectations[0].tick, 1);  // sorted by tick
    EXPECT_EQ(s.expectations[0].text, "count rock >= 3");
    EXPECT_EQ(s.expectations[1].region.max.x, 3.5f);
    ASSERT_EQ(s.screenshots.size(), 1u);
    EXPECT_EQ(s.screenshots[0].tick, 4);
}

TEST(Scenario, FormatReadsBackAsTheSameScenario) {
    const Scenario s = parse_scenario(std::string(kHeader) + "0-2 right\n5 fire up\n10-11 -\nat 3 expect var score = 10\nat 12 end\n",
                                      "s.scn", kVocabulary);
    const std::string text = format_scenario(s, kVocabulary);
    const Scenario again = parse_scenario(text, "again.scn", kVocabulary);
    EXPECT_EQ(again.inputs, s.inputs);
    EXPECT_EQ(again.ticks(), s.ticks());
    EXPECT_EQ(format_scenario(again, kVocabulary), text);
}

TEST(Scenario, BadInputNamesFileLineAndWhatWasExpected) {
    EXPECT_EQ(error_of(std::string(kHeader) + "0 jump\n"),
              "s.scn:7:3: unknown action 'jump' (expected one of: left, right, up, down, fire, or '-' for none)");
    EXPECT_EQ(error_of(std::string(kHeader) + "5 up\n3 up\n"),
              "s.scn:8:1: tick 3 is out of order: input lines must go forward in time (line 7 reaches tick 5)");
    EXPECT_EQ(error_of("jostle-scenario 2\n"), "s.scn:1:17: format version 2 is not supported (this jostle reads version 1)");
    EXPECT_EQ(error_of(std::string(kHeader) + "0 up"), "s.scn:7: truncated file: the last line has no newline");
    EXPECT_EQ(error_of("jostle-scenario 1\nengine 0.1.0\nlevel arena\n"), "s.scn:3: truncated file: the header has no 'seed' line");
    std::string unknown_level = kHeader;
    unknown_level.replace(unknown_level.find("level arena"), 11, "level arnea");
    EXPECT_EQ(error_of(unknown_level + "0 up\n"), "s.scn:3:7: unknown level 'arnea' (expected one of: arena, crowd)");
}

}  // namespace
}  // namespace jostle
