// record.cpp: the input-script parser and the live recording run.
#include "jostle/replay/record.h"

#include <charconv>

#include "jostle/core/error.h"
#include "jostle/core/interrupt.h"
#include "jostle/replay/replay.h"
#include "jostle/core/text.h"

#ifndef JOSTLE_VERSION
#define JOSTLE_VERSION "0.0.0"
#endif

namespace jostle {
namespace {

std::string join(const std::vector<std::string>& names) {
    std::string out;
    for (const std::string& name : names) out += (out.empty() ? "" : ", ") + name;
    return out;
}

}  // namespace

const char* engine_version() { return JOSTLE_VERSION; }

std::vector<ScriptStep> parse_input_script(std::string_view text, const std::string& source,
                                           const ScenarioVocabulary& vocabulary) {
    std::vector<ScriptStep> steps;
    int line_number = 0;
    std::size_t at = 0;
    text = skip_utf8_bom(text);
    while (at < text.size()) {
        std::size_t end = text.find('\n', at);
        if (end == std::string_view::npos) end = text.size();
        const std::string_view line = text.substr(at, end - at);
        at = end + 1;
        ++line_number;
        check_text_line(line, source, line_number);
        const std::vector<Word> words = split_words(line);
        if (words.empty()) continue;
        auto fail = [&](int column, const std::string& what) -> void {
            throw InputError(SourceLocation{source, line_number, column}, what);
        };
        auto action = [&](const Word& w) -> int {
            for (std::size_t i = 0; i < vocabulary.actions.size(); ++i) {
                if (vocabulary.actions[i] == w.text) return static_cast<int>(i);
            }
            if (!w.text.empty() && w.text.find_first_not_of("0123456789") == std::string_view::npos) {
                // 'hold right 5 6': a number among the actions (the ticks come last, once).
                fail(w.column, "expected an action, got '" + std::string(w.text) +
                                   "' (a step has one number of ticks, at its end: 'hold ACTION... TICKS')");
            }
            fail(w.column, "unknown action '" + std::string(w.text) + "' (expected one of: " + join(vocabulary.actions) + ")");
            return 0;
        };
        auto count = [&](const Word& w) -> std::int64_t {
            std::int64_t n = 0;
            const auto [ptr, ec] = std::from_chars(w.text.data(), w.text.data() + w.text.size(), n);
            // (At most a whole scenario's ticks: the sum of the steps is checked against it too.)
            if (ec != std::errc() || ptr != w.text.data() + w.text.size() || n < 1 || n > kMaxScenarioTicks) {
                fail(w.column, "expected a number of ticks (1 .. " + std::to_string(kMaxScenarioTicks) + "), got '" +
                                   std::string(w.text) + "'");
            }
            return n;
        };
        ScriptStep step;
        step.line = line_number;
        const std::string_view verb = words[0].text;
        if (verb == "hold") {
            if (words.size() < 3) fail(words.back().column + static_cast<int>(words.back().text.size()), "expected 'hold ACTION... TICKS'");
            for (std::size_t i = 1; i + 1 < words.size(); ++i) step.input.held |= 1u << action(words[i]);
            step.ticks = count(words.back());
        } else if (verb == "press") {
            if (words.size() < 2) fail(words[0].column + 5, "expected 'press ACTION...'");
            for (std::size_t i = 1; i < words.size(); ++i) step.input.held |= 1u << action(words[i]);
            step.ticks = 1;
        } else if (verb == "wait") {
            if (words.size() != 2) fail(words.size() > 2 ? words[2].column : words[0].column + 4, "expected 'wait TICKS'");
            step.ticks = count(words[1]);
        } else if (verb == "screenshot") {
            if (words.size() != 1) fail(words[1].column, "expected 'screenshot' alone");
            step.kind = ScriptStep::Kind::screenshot;
        } else if (verb == "expect") {
            step.kind = ScriptStep::Kind::expect;
            step.expectation = parse_expectation(line, 0, source, line_number);
        } else {
            fail(words[0].column, "unknown step '" + std::string(verb) + "' (expected hold, press, wait, screenshot or expect)");
        }
        steps.push_back(std::move(step));
    }
    return steps;
}

Recording record(const Game& game, const RecordDesc& desc, std::span<const ScriptStep> script,
                 const std::string& script_source) {
    Recording out;
    Scenario& s = out.scenario;
    s.engine_version = engine_version();
    if (desc.from != nullptr) {
        s.level = desc.from->level;
        s.seed = desc.from->seed;
        s.tick_rate = desc.from->tick_rate;
    } else {
        s.level = desc.level;
        s.seed = desc.seed;
        s.tick_rate = desc.tick_rate;
    }
    // A script too long for a scenario is refused before anything is played, at the step that
    // goes past the limit (not after minutes of recording).
    std::int64_t total = desc.from != nullptr ? desc.keep_ticks : 0;
    for (const ScriptStep& step : script) {
        if (step.kind != ScriptStep::Kind::hold) continue;
        total += step.ticks;
        if (total > kMaxScenarioTicks) {
            throw InputError(SourceLocation{script_source, step.line, 1},
                             "the recording would be longer than a scenario can be (" + std::to_string(kMaxScenarioTicks) +
                                 " ticks): " + std::to_string(total) + " ticks by the end of this line");
        }
    }
    s.level_hash = game.level_hash(s.level);
    s.source = script_source;
    std::unique_ptr<Simulation> sim = game.start(s.level, s.seed, s.tick_rate);

    auto play = [&](InputFrame input) {
        throw_if_interrupted();
        sim->tick(input);
        s.inputs.push_back(input);
        out.hashes.push_back(sim->state_hash());
    };
    if (desc.from != nullptr) {
        for (const Expectation& e : desc.from->expectations) {
            if (e.tick < desc.keep_ticks) validate_expectation(e, *sim, desc.from->source);
        }
        // The kept expectations (sorted by tick) are checked for their entities at their tick,
        // against the file they came from.
        std::size_t next = 0;
        for (std::int64_t t = 0; t < desc.keep_ticks; ++t) {
            play(desc.from->input(t));
            for (; next < desc.from->expectations.size() && desc.from->expectations[next].tick == t; ++next) {
                const Expectation& e = desc.from->expectations[next];
                validate_entity_name(e, *sim, desc.from->source);
                s.expectations.push_back(e);
                out.expectation_sources.push_back(desc.from->source);
            }
        }
        for (const Screenshot& shot : desc.from->screenshots) {
            if (shot.tick < desc.keep_ticks) {
                s.screenshots.push_back(shot);
            } else {
                ++out.dropped_screenshots;
            }
        }
        out.dropped_expectations = static_cast<std::int64_t>(desc.from->expectations.size() - next);
    }
    for (const ScriptStep& step : script) {
        const std::int64_t last = static_cast<std::int64_t>(s.inputs.size()) - 1;
        switch (step.kind) {
            case ScriptStep::Kind::hold:
                JOSTLE_ASSERT(step.ticks <= kMaxScenarioTicks - static_cast<std::int64_t>(s.inputs.size()),
                              "record: the script's length was checked before playing");
                for (std::int64_t i = 0; i < step.ticks; ++i) play(step.input);
                break;
            case ScriptStep::Kind::screenshot:
            case ScriptStep::Kind::expect:
                if (last < 0) {
                    throw InputError(SourceLocation{script_source, step.line, 1},
                                     "nothing has been played yet: a screenshot or expectation needs a tick before it "
                                     "(add 'wait 1')");
                }
                if (step.kind == ScriptStep::Kind::screenshot) {
                    s.screenshots.push_back(Screenshot{last, step.line});
                } else {
                    Expectation e = step.expectation;
                    e.tick = last;
                    validate_expectation(e, *sim, script_source);
                    validate_entity_name(e, *sim, script_source);
                    s.expectations.push_back(std::move(e));
                    out.expectation_sources.push_back(script_source);
                }
                break;
        }
    }
    if (s.inputs.empty()) throw InputError(SourceLocation{script_source, 0, 0}, "the script plays no ticks");
    s.end_tick = static_cast<std::int64_t>(s.inputs.size());
    return out;
}

}  // namespace jostle
