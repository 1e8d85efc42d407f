// scenario.cpp: parsing and writing the scenario format (see scenario.h for the grammar).
// The parser reads line by line, splits each line into whitespace-separated words (after
// dropping a '#' comment) and reports the first problem with its line and column.
#include "jostle/replay/scenario.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>

#include "jostle/core/error.h"
#include "jostle/core/text.h"

namespace jostle {
namespace {

std::string join(const std::vector<std::string>& names) {
    std::string out;
    for (const std::string& name : names) out += (out.empty() ? "" : ", ") + name;
    return out;
}

class Parser {
public:
    Parser(const std::string& source, const ScenarioVocabulary& vocabulary) : source_(source), vocabulary_(vocabulary) {}

    [[noreturn]] void fail(int line, int column, const std::string& what) const {
        throw InputError(SourceLocation{source_, line, column}, what);
    }
    [[noreturn]] void fail(const Word& word, const std::string& what) const { fail(line_, word.column, what); }

    void set_line(int line) { line_ = line; }

    // A tick the run plays (0 .. kMaxScenarioTicks - 1), or with `end` the tick it ends before
    // (up to kMaxScenarioTicks).
    std::int64_t tick(const Word& word, bool end_tick = false) const {
        const std::int64_t most = end_tick ? kMaxScenarioTicks : kMaxScenarioTicks - 1;
        std::int64_t value = 0;
        const auto [end, ec] = std::from_chars(word.text.data(), word.text.data() + word.text.size(), value);
        // "-0" is 0 to from_chars, but a tick is written without a sign: refused like "+0".
        if (ec != std::errc() || end != word.text.data() + word.text.size() || word.text.starts_with('-') || value < 0 ||
            value > most) {
            fail(word, "expected a tick number (0 .. " + std::to_string(most) + "), got '" + std::string(word.text) + "'");
        }
        return value;
    }

    double number(const Word& word) const {
        // A number finer than a double (1e-330) is rounded to one (0 or a denormal), like any other.
        const std::optional<double> value = parse_double(word.text);
        if (!value || !std::isfinite(*value)) fail(word, "expected a finite number, got '" + std::string(word.text) + "'");
        return *value;
    }

    // A region corner: stored as a float, so a finite double beyond the float range (which
    // would turn into infinity) is refused.
    float float_number(const Word& word) const {
        const double value = number(word);
        if (std::fabs(value) > static_cast<double>(std::numeric_limits<float>::max())) {
            fail(word, "expected a number from -3.4e38 to 3.4e38, got '" + std::string(word.text) + "'");
        }
        return static_cast<float>(value);
    }

    std::uint64_t unsigned_number(const Word& word, std::uint64_t max, const char* what) const {
        std::uint64_t value = 0;
        const auto [end, ec] = std::from_chars(word.text.data(), word.text.data() + word.text.size(), value);
        if (ec != std::errc() || end != word.text.data() + word.text.size() || value > max) {
            fail(word, std::string("expected ") + what + ", got '" + std::string(word.text) + "'");
        }
        return value;
    }

    int action(const Word& word) const {
        for (std::size_t i = 0; i < vocabulary_.actions.size(); ++i) {
            if (vocabulary_.actions[i] == word.text) return static_cast<int>(i);
        }
        fail(word, "unknown action '" + std::string(word.text) + "' (expected one of: " + join(vocabulary_.actions) +
                       ", or '-' for none)");
    }

    Comparison comparison(const Word& word) const {
        static constexpr Comparison kAll[] = {Comparison::eq, Comparison::ne, Comparison::lt,
                                              Comparison::le, Comparison::gt, Comparison::ge};
        for (Comparison c : kAll) {
            if (comparison_text(c) == word.text) return c;
        }
        fail(word, "expected a comparison (= != < <= > >=), got '" + std::string(word.text) + "'");
    }

    void expect_count(const std::vector<Word>& words, std::size_t count, const char* form) const {
        if (words.size() != count) {
            const Word& at = words.size() > count ? words[count] : words.back();
            fail(line_, words.size() > count ? at.column : at.column + static_cast<int>(at.text.size()),
                 std::string("expected '") + form + "'");
        }
    }

    int line() const { return line_; }
    const ScenarioVocabulary& vocabulary() const { return vocabulary_; }

private:
    const std::string& source_;
    const ScenarioVocabulary& vocabulary_;
    int line_ = 0;
};

// The line's text from words[first] to the last word, comment and outer spaces removed.
std::string directive_text(std::string_view line, const std::vector<Word>& words, std::size_t first) {
    const std::size_t from = static_cast<std::size_t>(words[first].column - 1);
    const Word& last = words.back();
    const std::size_t to = static_cast<std::size_t>(last.column - 1) + last.text.size();
    return std::string(line.substr(from, to - from));
}

// The words from words[first] ("expect") on, as an expectation at `tick`; `prefix` is what
// comes before "expect" in the forms shown in errors ("at TICK " in scenarios).
Expectation parse_expect(const Parser& p, std::string_view line, const std::vector<Word>& all_words, std::size_t first,
                         std::int64_t tick, const std::string& prefix) {
    const std::vector<Word> words(all_words.begin() + static_cast<std::ptrdiff_t>(first), all_words.end());
    auto form = [&](const char* rest) { return prefix + rest; };
    if (words.size() < 3) {
        p.expect_count(words, 3, form("expect NAME alive|gone|in X0 Y0 X1 Y1, or count KIND OP N, var NAME OP V, event NAME").c_str());
    }
    Expectation e;
    e.tick = tick;
    e.line = p.line();
    e.text = directive_text(line, words, 1);
    const std::string_view subject = words[1].text;
    if (subject == "count" || subject == "var") {
        p.expect_count(words, 5, form(subject == "count" ? "expect count KIND OP N" : "expect var NAME OP VALUE").c_str());
        e.kind = subject == "count" ? Expectation::Kind::count : Expectation::Kind::variable;
        e.name = std::string(words[2].text);
        e.column = words[2].column;
        e.comparison = p.comparison(words[3]);
        e.value = p.number(words[4]);
        // A count of entities is whole and not negative: 'count bullet = 1.5' could never hold.
        if (e.kind == Expectation::Kind::count && !(e.value >= 0.0 && e.value == std::floor(e.value))) {
            p.fail(words[4], "expected a whole count (0 or more), got '" + std::string(words[4].text) + "'");
        }
    } else if (subject == "event") {
        p.expect_count(words, 3, form("expect event NAME").c_str());
        e.kind = Expectation::Kind::event;
        e.name = std::string(words[2].text);
        e.column = words[2].column;
    } else {
        e.name = std::string(subject);
        e.column = words[1].column;
        const std::string_view verb = words[2].text;
        if (verb == "alive" || verb == "gone") {
            p.expect_count(words, 3, form("expect NAME alive|gone").c_str());
            e.kind = verb == "alive" ? Expectation::Kind::alive : Expectation::Kind::gone;
        } else if (verb == "in") {
            p.expect_count(words, 7, form("expect NAME in X0 Y0 X1 Y1").c_str());
            e.kind = Expectation::Kind::in_region;
            e.region = Aabb{{p.float_number(words[3]), p.float_number(words[4])},
                            {p.float_number(words[5]), p.float_number(words[6])}};
            if (e.region.min.x > e.region.max.x || e.region.min.y > e.region.max.y) {
                p.fail(words[3], "expected X0 <= X1 and Y0 <= Y1 (the region's top-left corner first)");
            }
        } else {
            p.fail(words[2], "expected 'alive', 'gone' or 'in' after the entity name, got '" + std::string(verb) + "'");
        }
    }
    return e;
}

}  // namespace

std::string_view comparison_text(Comparison c) {
    switch (c) {
        case Comparison::eq: return "=";
        case Comparison::ne: return "!=";
        case Comparison::lt: return "<";
        case Comparison::le: return "<=";
        case Comparison::gt: return ">";
        case Comparison::ge: return ">=";
    }
    return "?";
}

bool compare(double actual, Comparison c, double expected) {
    switch (c) {
        case Comparison::eq: return actual == expected;
        case Comparison::ne: return actual != expected;
        case Comparison::lt: return actual < expected;
        case Comparison::le: return actual <= expected;
        case Comparison::gt: return actual > expected;
        case Comparison::ge: return actual >= expected;
    }
    return false;
}

std::int64_t Scenario::ticks() const {
    if (end_tick) return *end_tick;
    std::int64_t last = static_cast<std::int64_t>(inputs.size()) - 1;
    for (const Screenshot& s : screenshots) last = std::max(last, s.tick);
    for (const Expectation& e : expectations) last = std::max(last, e.tick);
    return last + 1;
}

Scenario parse_scenario(std::string_view text, const std::string& source, const ScenarioVocabulary& vocabulary) {
    JOSTLE_ASSERT(vocabulary.actions.size() <= static_cast<std::size_t>(kMaxActions),
                  "parse_scenario: at most kMaxActions actions");
    Parser p(source, vocabulary);
    Scenario s;
    s.source = source;

    text = skip_utf8_bom(text);
    if (text.empty()) p.fail(1, 0, "empty file: expected 'jostle-scenario " + std::to_string(kScenarioFormatVersion) + "'");
    // Every line is text of a sane length before anything else is said about it (binary
    // garbage is called that, not a truncated file).
    for (std::size_t at = 0, line = 1; at < text.size(); ++line) {
        const std::size_t end = std::min(text.find('\n', at), text.size());
        check_text_line(text.substr(at, end - at), source, static_cast<int>(line));
        at = end + 1;
    }
    if (text.back() != '\n') {
        const int lines = static_cast<int>(std::count(text.begin(), text.end(), '\n')) + 1;
        p.fail(lines, 0, "truncated file: the last line has no newline (if the file is whole, end it with one)");
    }

    bool have_engine = false, have_level = false, have_seed = false, have_rate = false, have_hash = false;
    bool header_done = false;
    std::int64_t next_input_tick = 0;  // the first tick the next input line may start at
    int last_input_line = 0;
    std::optional<int> end_line;

    auto finish_header = [&](int line) {
        if (header_done) return;
        const char* missing = !have_engine ? "engine" : !have_level ? "level" : !have_seed ? "seed"
                              : !have_rate ? "tick-rate" : !have_hash ? "level-hash" : nullptr;
        if (missing != nullptr) p.fail(line, 1, std::string("expected the header line '") + missing + " ...' before the input");
        header_done = true;
    };

    int line_number = 0;
    std::size_t at = 0;
    while (at < text.size()) {
        const std::size_t newline = text.find('\n', at);
        const std::string_view line = text.substr(at, newline - at);
        at = newline + 1;
        ++line_number;
        p.set_line(line_number);
        const std::vector<Word> words = split_words(line);

        if (line_number == 1) {
            if (words.empty() || words[0].text != "jostle-scenario") {
                p.fail(1, 1, "expected 'jostle-scenario " + std::to_string(kScenarioFormatVersion) +
                                 "' as the first line (is this a scenario file?)");
            }
            p.expect_count(words, 2, "jostle-scenario VERSION");
            const std::uint64_t version = p.unsigned_number(words[1], 1'000'000, "a format version number");
            if (version != static_cast<std::uint64_t>(kScenarioFormatVersion)) {
                p.fail(words[1], "format version " + std::to_string(version) + " is not supported (this jostle reads version " +
                                     std::to_string(kScenarioFormatVersion) + ")");
            }
            continue;
        }
        if (words.empty()) continue;
        const std::string_view head = words[0].text;

        // Header lines.
        auto header = [&](bool& seen, const char* form) {
            if (header_done) p.fail(words[0], std::string("'") + std::string(head) + "' belongs in the header, before the input");
            if (seen) p.fail(words[0], "'" + std::string(head) + "' given twice");
            p.expect_count(words, 2, form);
            seen = true;
        };
        if (head == "engine") {
            header(have_engine, "engine VERSION");
            s.engine_version = std::string(words[1].text);
            continue;
        }
        if (head == "level") {
            header(have_level, "level NAME");
            s.level = std::string(words[1].text);
            if (std::find(vocabulary.levels.begin(), vocabulary.levels.end(), s.level) == vocabulary.levels.end()) {
                p.fail(words[1], "unknown level '" + s.level + "' (expected one of: " + join(vocabulary.levels) + ")");
            }
            continue;
        }
        if (head == "seed") {
            header(have_seed, "seed NUMBER");
            s.seed = p.unsigned_number(words[1], UINT64_MAX, "a seed (0 .. 18446744073709551615)");
            continue;
        }
        if (head == "tick-rate") {
            header(have_rate, "tick-rate TICKS_PER_SECOND");
            const std::uint64_t rate = p.unsigned_number(words[1], 1000, "a tick rate (1 .. 1000)");
            if (rate < 1) p.fail(words[1], "expected a tick rate (1 .. 1000), got '" + std::string(words[1].text) + "'");
            s.tick_rate = static_cast<int>(rate);
            continue;
        }
        if (head == "level-hash") {
            header(have_hash, "level-hash HEX16");
            const std::string_view hex = words[1].text;
            if (hex.size() != 16 || hex.find_first_not_of("0123456789abcdef") != std::string_view::npos) {
                p.fail(words[1], "expected 16 lowercase hex digits, got '" + std::string(hex) + "'");
            }
            s.level_hash = std::string(hex);
            continue;
        }

        finish_header(line_number);

        // Directives.
        if (head == "at") {
            if (words.size() < 3) p.expect_count(words, 3, "at TICK screenshot|expect ...|end");
            const std::string_view what = words[2].text;
            const std::int64_t tick = p.tick(words[1], what == "end");
            if (what == "screenshot") {
                p.expect_count(words, 3, "at TICK screenshot");
                s.screenshots.push_back(Screenshot{tick, line_number});
            } else if (what == "end") {
                p.expect_count(words, 3, "at TICK end");
                if (end_line) p.fail(words[0], "a second 'end' (the first is on line " + std::to_string(*end_line) + ")");
                if (tick < 1) p.fail(words[1], "expected an end tick of at least 1 (the run is ticks 0 .. end-1)");
                s.end_tick = tick;
                end_line = line_number;
            } else if (what == "expect") {
                s.expectations.push_back(parse_expect(p, line, words, 2, tick, "at TICK "));
            } else {
                p.fail(words[2], "expected 'screenshot', 'expect' or 'end' after 'at TICK', got '" + std::string(what) + "'");
            }
            continue;
        }

        // Input lines: "T actions..." or "A-B actions...". A line starting with a letter is
        // none of the line kinds (a misspelt directive, say): say what a line can be.
        if ((head[0] >= 'a' && head[0] <= 'z') || (head[0] >= 'A' && head[0] <= 'Z')) {
            p.fail(words[0], "unknown line '" + std::string(head) + "' (expected 'TICK actions', 'A-B actions' or 'at TICK ...')");
        }
        const std::string_view range = head;
        const std::size_t dash = range.find('-', 1);
        const Word first_word{range.substr(0, dash), words[0].column};
        const std::int64_t first = p.tick(first_word);
        std::int64_t last = first;
        if (dash != std::string_view::npos) {
            const Word last_word{range.substr(dash + 1), words[0].column + static_cast<int>(dash) + 1};
            last = p.tick(last_word);
            if (last < first) p.fail(last_word, "range " + std::string(range) + " ends before it starts");
        }
        if (first < next_input_tick) {
            p.fail(words[0], "tick " + std::to_string(first) + " is out of order: input lines must go forward in time (line " +
                                 std::to_string(last_input_line) + " reaches tick " + std::to_string(next_input_tick - 1) + ")");
        }
        if (words.size() < 2) p.fail(line_number, words[0].column + static_cast<int>(words[0].text.size()),
                                      "expected the actions held (or '-' for none) after the tick");
        InputFrame input;
        if (!(words.size() == 2 && words[1].text == "-")) {
            for (std::size_t i = 1; i < words.size(); ++i) {
                if (words[i].text == "-") p.fail(words[i], "'-' means no action and stands alone");
                input.held |= 1u << p.action(words[i]);
            }
        }
        if (last >= kMaxScenarioTicks) p.fail(words[0], "too many ticks");
        s.inputs.resize(static_cast<std::size_t>(last + 1));
        for (std::int64_t t = first; t <= last; ++t) s.inputs[static_cast<std::size_t>(t)] = input;
        next_input_tick = last + 1;
        last_input_line = line_number;
    }
    if (line_number < 1) p.fail(1, 0, "empty file");
    if (!header_done) {
        const char* missing = !have_engine ? "engine" : !have_level ? "level" : !have_seed ? "seed"
                              : !have_rate ? "tick-rate" : !have_hash ? "level-hash" : nullptr;
        if (missing != nullptr) {
            p.fail(line_number, 0, std::string("truncated file: the header has no '") + missing + "' line");
        }
    }

    if (s.end_tick) {
        const std::int64_t end = *s.end_tick;
        if (static_cast<std::int64_t>(s.inputs.size()) > end) {
            p.fail(last_input_line, 1, "input at tick " + std::to_string(s.inputs.size() - 1) + " comes after the end (tick " +
                                           std::to_string(end) + ", line " + std::to_string(*end_line) + ")");
        }
        for (const Screenshot& shot : s.screenshots) {
            if (shot.tick >= end) p.fail(shot.line, 1, "screenshot at tick " + std::to_string(shot.tick) + " is not before the end (tick " + std::to_string(end) + ")");
        }
        for (const Expectation& e : s.expectations) {
            if (e.tick >= end) p.fail(e.line, 1, "expectation at tick " + std::to_string(e.tick) + " is not before the end (tick " + std::to_string(end) + ")");
        }
    }
    if (s.ticks() < 1) p.fail(line_number, 0, "the scenario has no ticks: expected input lines or 'at TICK end'");
    std::stable_sort(s.screenshots.begin(), s.screenshots.end(), [](const Screenshot& a, const Screenshot& b) { return a.tick < b.tick; });
    std::stable_sort(s.expectations.begin(), s.expectations.end(), [](const Expectation& a, const Expectation& b) { return a.tick < b.tick; });
    return s;
}

Scenario load_scenario(const std::string& path, const ScenarioVocabulary& vocabulary) {
    return parse_scenario(read_text_file(path, "the scenario file"), path, vocabulary);
}

std::string format_input(InputFrame input, const ScenarioVocabulary& vocabulary) {
    std::string out;
    for (std::size_t i = 0; i < vocabulary.actions.size(); ++i) {
        if (input.holds(static_cast<int>(i))) out += (out.empty() ? "" : " ") + vocabulary.actions[i];
    }
    return out.empty() ? "-" : out;
}

std::string format_scenario(const Scenario& s, const ScenarioVocabulary& vocabulary) {
    std::string out = "jostle-scenario " + std::to_string(kScenarioFormatVersion) + "\n";
    out += "engine " + s.engine_version + "\n";
    out += "level " + s.level + "\n";
    out += "seed " + std::to_string(s.seed) + "\n";
    out += "tick-rate " + std::to_string(s.tick_rate) + "\n";
    out += "level-hash " + s.level_hash + "\n\n";
    // Runs of equal input; ticks holding nothing are left out.
    std::size_t t = 0;
    while (t < s.inputs.size()) {
        std::size_t end = t + 1;
        while (end < s.inputs.size() && s.inputs[end] == s.inputs[t]) ++end;
        if (s.inputs[t].held != 0 || end == s.inputs.size()) {
            out += end - t == 1 ? std::to_string(t) : std::to_string(t) + "-" + std::to_string(end - 1);
            out += " " + format_input(s.inputs[t], vocabulary) + "\n";
        }
        t = end;
    }
    if (!s.screenshots.empty() || !s.expectations.empty() || s.end_tick) out += "\n";
    for (const Screenshot& shot : s.screenshots) out += "at " + std::to_string(shot.tick) + " screenshot\n";
    for (const Expectation& e : s.expectations) {
        out += "at " + std::to_string(e.tick) + " expect ";
        switch (e.kind) {
            case Expectation::Kind::in_region:
                out += e.name + " in " + shortest_text(e.region.min.x) + " " + shortest_text(e.region.min.y) + " " +
                       shortest_text(e.region.max.x) + " " + shortest_text(e.region.max.y);
                break;
            case Expectation::Kind::alive: out += e.name + " alive"; break;
            case Expectation::Kind::gone: out += e.name + " gone"; break;
            case Expectation::Kind::count:
                out += "count " + e.name + " " + std::string(comparison_text(e.comparison)) + " " + shortest_text(e.value);
                break;
            case Expectation::Kind::variable:
                out += "var " + e.name + " " + std::string(comparison_text(e.comparison)) + " " + shortest_text(e.value);
                break;
            case Expectation::Kind::event: out += "event " + e.name; break;
        }
        out += "\n";
    }
    if (s.end_tick) out += "at " + std::to_string(*s.end_tick) + " end\n";
    return out;
}

}  // namespace jostle

namespace jostle {

Expectation parse_expectation(std::string_view line, std::int64_t tick, const std::string& source, int line_number) {
    static const ScenarioVocabulary kNone;
    Parser p(source, kNone);
    p.set_line(line_number);
    const std::vector<Word> words = split_words(line);
    if (words.empty() || words[0].text != "expect") p.fail(line_number, 1, "expected 'expect ...'");
    return parse_expect(p, line, words, 0, tick, "");
}

}  // namespace jostle
