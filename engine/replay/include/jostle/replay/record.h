// jostle/replay/record.h: making scenarios. An input script says what to do in words; the
// recorder plays it live against the game, tick by tick, and writes the scenario that
// reproduces the run. The script, one step per line ('#' comments, blank lines ignored):
//
//   hold right up 30       hold these actions for 30 ticks
//   press fire             hold it for one tick
//   wait 10                hold nothing for 10 ticks
//   screenshot             keep a screenshot of the state after the last tick played
//   expect player alive    an expectation about that state (the forms of scenario.h)
//
// Text as in scenario.h: a BOM and CRLF line ends are accepted, binary bytes are refused.
//
// Doom's rule: the recorder then reads its own file back and replays it; the recording is
// good only when the replay gives the recorded run's hash on every tick.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "jostle/replay/scenario.h"
#include "jostle/replay/simulation.h"

namespace jostle {

struct ScriptStep {
    enum class Kind : std::uint8_t { hold, screenshot, expect };
    Kind kind = Kind::hold;
    InputFrame input;         // hold
    std::int64_t ticks = 0;   // hold
    Expectation expectation;  // expect (its tick is filled in when recorded)
    int line = 0;
};

// Parses a script; `source` names it in errors (InputError with source:line:column).
std::vector<ScriptStep> parse_input_script(std::string_view text, const std::string& source,
                                           const ScenarioVocabulary& vocabulary);

struct RecordDesc {
    std::string level;
    std::uint64_t seed = 1;
    int tick_rate = 60;
    // Re-recording: keep the first `keep_ticks` ticks of `from` (its input, and its directives
    // before that tick) and continue with the script. from's level, seed and tick rate win.
    const Scenario* from = nullptr;
    std::int64_t keep_ticks = 0;
};

struct Recording {
    Scenario scenario;                  // ready for format_scenario
    std::vector<std::uint64_t> hashes;  // the live run's state hash after each tick
    std::string source;                 // for messages: where a step came from
    // Where each of scenario.expectations was written (the --from file or the script), for
    // messages with the right file and line.
    std::vector<std::string> expectation_sources;
    // With --from: the expectations and screenshots of that file at or after the kept ticks'
    // end, which the new scenario does not have (the caller says so).
    std::int64_t dropped_expectations = 0;
    std::int64_t dropped_screenshots = 0;
};

// Plays the kept ticks and the script live and returns the scenario and the run's hashes.
// InputError (at the step's line) for a step that makes no tick (screenshot, expect) before
// any tick, an expectation naming what the game lacks, and a script longer than a scenario
// can be (kMaxScenarioTicks).
Recording record(const Game& game, const RecordDesc& desc, std::span<const ScriptStep> script,
                 const std::string& script_source);

// The engine version written into scenarios ("0.1.0").
const char* engine_version();

}  // namespace jostle
