// jostle/replay/scenario.h: the scenario file, a recorded run as readable text.
//
// A scenario names a level, a seed and a tick rate, and lists the actions held on each tick;
// replaying it gives the same run every time. Directives pin what the run is about:
// screenshots, expectations, the end. The format, line by line:
//
//   jostle-scenario 1                  the format version: always the first line
//   # a comment                        '#' starts a comment anywhere; blank lines are ignored
//   engine 0.1.0                       the jostle that recorded it (informational)
//   level arena                        the level it plays (one of the game's levels)
//   seed 42                            the world's RNG seed (0 .. 2^64-1)
//   tick-rate 60                       ticks per second (1 .. 1000)
//   level-hash 3f6a0c2e9b1d4a77        fingerprint of the level and assets it was recorded
//                                      against (a mismatch is reported, not an error)
//   0-29 right                         ticks 0 to 29 hold "right"
//   30 right fire                      tick 30 holds "right" and "fire"
//   31-59 up                           (ticks not listed hold nothing; "-" says so explicitly)
//   at 45 screenshot                   render and keep the frame after tick 45
//   at 60 expect player in 100 40 140 80     the entity's position is in [100,140]x[40,80]
//   at 60 expect player alive          ("gone" for the opposite)
//   at 60 expect count rock >= 3       how many entities of a kind: = != < <= > >=
//                                      (N whole and not negative)
//   at 60 expect var score = 10        a game variable, same comparisons
//   at 60 expect event pickup          the game reported "pickup" at or before tick 60
//   at 120 end                         the run is 120 ticks: 0 .. 119
//
// Ticks are numbered from 0 and written as plain digits (no sign: "-0" and "+0" are refused);
// "at T" happens after tick T's step (frame T shows that state). Other numbers are decimal; one
// finer than a double (1e-330) rounds to the nearest double (0), one beyond it is refused.
// The file is UTF-8 text (a leading byte order mark and CRLF line ends are accepted; each line
// passes check_text_line of jostle/core/text.h first: length, no binary bytes).
// Input lines go in increasing tick order without overlaps; directives may stand anywhere.
// Without "at T end" the run lasts until the last tick any line mentions. The header lines
// come before the first input or directive line, each exactly once.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "jostle/collision.h"

namespace jostle {

inline constexpr int kScenarioFormatVersion = 1;
inline constexpr int kMaxActions = 32;
// 2^24 ticks is over 77 hours at 60 Hz; the cap keeps a one-line file from asking for
// gigabytes of per-tick input and hashes.
inline constexpr std::int64_t kMaxScenarioTicks = std::int64_t{1} << 24;

// The actions held on one tick: bit i is the game's action i. Live input, a recorded log and
// a bot all produce this one struct, and the game reads input from nowhere else.
struct InputFrame {
    std::uint32_t held = 0;
    bool holds(int action) const { return (held >> action) & 1u; }
    friend constexpr bool operator==(InputFrame, InputFrame) = default;
};

// What a scenario may name: the game's actions (in bit order) and levels.
struct ScenarioVocabulary {
    std::vector<std::string> actions;
    std::vector<std::string> levels;
};

enum class Comparison : std::uint8_t { eq, ne, lt, le, gt, ge };
std::string_view comparison_text(Comparison c);  // "=", "!=", "<", ...
bool compare(double actual, Comparison c, double expected);

struct Expectation {
    enum class Kind : std::uint8_t { in_region, alive, gone, count, variable, event };
    Kind kind = Kind::alive;
    std::int64_t tick = 0;
    std::string name;    // entity (in_region, alive, gone), kind (count), variable, event
    Aabb region;         // in_region
    Comparison comparison = Comparison::eq;  // count, variable
    double value = 0.0;                      // count, variable
    int line = 0;        // where it was written
    int column = 0;      // where its name was written (the game checks the name, after parsing)
    std::string text;    // as written after "expect ", for reports: "player alive"
};

struct Screenshot {
    std::int64_t tick = 0;
    int line = 0;
};

struct Scenario {
    std::string source;  // the file it came from, for messages
    std::string engine_version;
    std::string level;
    std::uint64_t seed = 0;
    int tick_rate = 60;
    std::string level_hash;  // 16 hex digits
    std::vector<InputFrame> inputs;  // per tick; shorter than ticks() means the rest hold nothing
    std::vector<Screenshot> screenshots;  // sorted by tick
    std::vector<Expectation> expectations;  // sorted by tick (stable: file order within a tick)
    std::optional<std::int64_t> end_tick;

    // How many ticks the run has: end_tick, else one past the last tick any line mentions.
    std::int64_t ticks() const;
    InputFrame input(std::int64_t tick) const {
        return tick >= 0 && tick < static_cast<std::int64_t>(inputs.size()) ? inputs[static_cast<std::size_t>(tick)]
                                                                             : InputFrame{};
    }
};

// Parses scenario text. `source` names it in errors. Throws InputError naming source and line
// with what was expected: an unknown action or level, ticks out of order, a version other
// than kScenarioFormatVersion, a missing or repeated header line, a truncated file (the last
// line lacks its newline, or the header is incomplete), a malformed number or directive.
Scenario parse_scenario(std::string_view text, const std::string& source, const ScenarioVocabulary& vocabulary);
// Reads and parses a file (InputError when it cannot be read).
Scenario load_scenario(const std::string& path, const ScenarioVocabulary& vocabulary);

// The scenario as text in the format above: runs of equal input as "A-B actions" lines,
// then the directives. parse_scenario(format_scenario(s)) gives s back (but line numbers).
std::string format_scenario(const Scenario& scenario, const ScenarioVocabulary& vocabulary);

// One "expect ..." line (as in a scenario after "at T ", or a recorder script) as an
// expectation at `tick`. Throws InputError naming source:line_number:column.
Expectation parse_expectation(std::string_view line, std::int64_t tick, const std::string& source, int line_number);

// "right fire", or "-" for nothing held.
std::string format_input(InputFrame input, const ScenarioVocabulary& vocabulary);

}  // namespace jostle
