// tests/fuzz/scenario_fuzz.cpp: fuzzes parse_scenario (engine/replay) with the arena game's
// vocabulary, as `jostle play` and `jostle check` call it. Bad input must be an InputError;
// a scenario that parses must survive format_scenario and parse again unchanged (the promise in
// scenario.h), so the formatter is fuzzed too.
#include <bit>
#include <cstring>
#include <string>
#include <string_view>

#include "arena.h"
#include "fuzz_support.h"
#include "jostle/core/error.h"
#include "jostle/replay/scenario.h"

namespace {

using jostle::fuzz::fuzz_fail;

const jostle::ScenarioVocabulary& vocabulary() {
    static const jostle::game::ArenaGame game(jostle::game::default_assets_dir());
    return game.vocabulary();
}

bool same_number(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }
bool same_number(float a, float b) { return std::bit_cast<std::uint32_t>(a) == std::bit_cast<std::uint32_t>(b); }

bool same(const jostle::Expectation& a, const jostle::Expectation& b) {
    return a.kind == b.kind && a.tick == b.tick && a.name == b.name && same_number(a.region.min.x, b.region.min.x) &&
           same_number(a.region.min.y, b.region.min.y) && same_number(a.region.max.x, b.region.max.x) &&
           same_number(a.region.max.y, b.region.max.y) && a.comparison == b.comparison &&
           same_number(a.value, b.value);
}

void check_round_trip(const jostle::Scenario& s, const std::string& text) {
    const std::string formatted = jostle::format_scenario(s, vocabulary());
    jostle::Scenario again;
    try {
        again = jostle::parse_scenario(formatted, "formatted.scn", vocabulary());
    } catch (const jostle::InputError& e) {
        fuzz_fail("format_scenario wrote text parse_scenario rejects: " + std::string(e.what()) + "\ninput:\n" + text +
                  "\nformatted:\n" + formatted);
    }
    bool ok = again.engine_version == s.engine_version && again.level == s.level && again.seed == s.seed &&
              again.tick_rate == s.tick_rate && again.level_hash == s.level_hash && again.inputs == s.inputs &&
              again.end_tick == s.end_tick && again.ticks() == s.ticks() &&
              again.screenshots.size() == s.screenshots.size() && again.expectations.size() == s.expectations.size();
    for (std::size_t i = 0; ok && i < s.screenshots.size(); ++i) ok = again.screenshots[i].tick == s.screenshots[i].tick;
    for (std::size_t i = 0; ok && i < s.expectations.size(); ++i) ok = same(again.expectations[i], s.expectations[i]);
    if (!ok) fuzz_fail("parse_scenario(format_scenario(s)) differs from s\ninput:\n" + text + "\nformatted:\n" + formatted);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    jostle::Scenario scenario;
    try {
        scenario = jostle::parse_scenario(text, "fuzz.scn", vocabulary());
    } catch (const jostle::InputError& e) {
        // Errors name the source first ("fuzz.scn:LINE...").
        if (std::strncmp(e.what(), "fuzz.scn", 8) != 0) fuzz_fail(std::string("error without its source: ") + e.what());
        return 0;
    }
    check_round_trip(scenario, text);
    return 0;
}
