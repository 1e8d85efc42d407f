// check.cpp: golden comparison of a replay (trace, expectations, screenshots), the atomic
// update, sharding, and the HTML / JUnit report.
#include "jostle/replay/check.h"

#include <signal.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <string_view>
#include <vector>

#include "jostle/core/atomic_file.h"
#include "jostle/core/error.h"
#include "jostle/core/interrupt.h"
#include "jostle/core/text.h"
#include "jostle/render/png_io.h"
#include "jostle/replay/replay.h"
#include "jostle/replay/scenario.h"

namespace jostle {
namespace fs = std::filesystem;
namespace {

std::string golden_image_path(const std::string& scenario_path, std::int64_t tick) {
    const fs::path p(scenario_path);
    return (p.parent_path() / (p.stem().string() + ".tick_" + std::to_string(tick) + ".png")).string();
}

// Whether `file` is a name golden_image_path gives scenario `name`: exactly NAME.tick_T.png
// with T a tick as std::to_string writes it (no sign, no leading zero, below the tick limit).
// Anything else beside the goldens (pickup.tick_79.orig.png, a report's
// pickup.tick_80.actual.png) is the user's, never a stale golden.
bool is_golden_image_name(std::string_view file, std::string_view name) {
    const std::string_view prefix = ".tick_", suffix = ".png";
    if (file.size() < name.size() + prefix.size() + suffix.size() || !file.starts_with(name) ||
        file.substr(name.size()).substr(0, prefix.size()) != prefix || !file.ends_with(suffix)) {
        return false;
    }
    const std::string_view digits = file.substr(name.size() + prefix.size(), file.size() - name.size() - prefix.size() - suffix.size());
    std::int64_t tick = -1;
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), tick);
    return ec == std::errc{} && end == digits.data() + digits.size() && tick >= 0 && tick < kMaxScenarioTicks &&
           std::to_string(tick) == digits;
}

// The entities and fields that differ between two dumps of the same tick.
std::vector<FieldChange> diff_dumps(const std::vector<EntityDump>& expected, const std::vector<EntityDump>& actual) {
    std::vector<FieldChange> changes;
    auto find = [](const std::vector<EntityDump>& list, const std::string& name) -> const EntityDump* {
        for (const EntityDump& e : list) {
            if (e.name == name) return &e;
        }
        return nullptr;
    };
    for (const EntityDump& e : expected) {
        const EntityDump* a = find(actual, e.name);
        if (a == nullptr) {
            changes.push_back(FieldChange{e.name, "", "present", "(absent)"});
            continue;
        }
        for (const StateField& f : e.fields) {
            const auto it = std::find_if(a->fields.begin(), a->fields.end(), [&](const StateField& g) { return g.name == f.name; });
            if (it == a->fields.end()) {
                changes.push_back(FieldChange{e.name, f.name, f.value, "(absent)"});
            } else if (it->value != f.value) {
                changes.push_back(FieldChange{e.name, f.name, f.value, it->value});
            }
        }
        for (const StateField& g : a->fields) {
            const bool known = std::any_of(e.fields.begin(), e.fields.end(), [&](const StateField& f) { return f.name == g.name; });
            if (!known) changes.push_back(FieldChange{e.name, g.name, "(absent)", g.value});
        }
    }
    for (const EntityDump& a : actual) {
        if (find(expected, a.name) == nullptr) changes.push_back(FieldChange{a.name, "", "(absent)", "present"});
    }
    return changes;
}

std::string read_file(const std::string& path, bool* exists) {
    std::ifstream in(path, std::ios::binary);
    *exists = static_cast<bool>(in);
    if (!in) return {};
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

std::string html_escape(std::string_view text) {
    std::string out;
    for (char c : text) {
        switch (c) {
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '&': out += "&amp;"; break;
            case '"': out += "&quot;"; break;
            default: out += c;
        }
    }
    return out;
}

// A file name as a relative URL: everything but unreserved characters percent-encoded, so a
// scenario called "wall #2" still finds its images.
std::string url_escape(std::string_view text) {
    static constexpr char kHex[] = "0123456789ABCDEF";
    std::string out;
    for (const char c : text) {
        const auto u = static_cast<unsigned char>(c);
        if (std::isalnum(u) != 0 || c == '-' || c == '_' || c == '.' || c == '~') {
            out += c;
        } else {
            out += '%';
            out += kHex[u >> 4];
            out += kHex[u & 15];
        }
    }
    return out;
}

// `word` as one word of a shell command: as it is when it holds only characters no shell
// treats specially, else in single quotes.
std::string shell_word(std::string_view word) {
    const bool plain = !word.empty() && std::all_of(word.begin(), word.end(), [](char ch) {
        return std::isalnum(static_cast<unsigned char>(ch)) != 0 || std::string_view("_-./+,:=@%").find(ch) != std::string_view::npos;
    });
    if (plain) return std::string(word);
    // Single quotes: nothing inside them is special to any shell (double quotes leave $, `, \ and,
    // in an interactive bash, ! to expand); a single quote itself ends them, is escaped, reopens.
    std::string out = "'";
    for (const char ch : word) out += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
    return out + "'";
}

std::string update_command_for(const std::string& scenario_path, const CheckOptions& options) {
    std::string command = "jostle check --update";
    for (const std::string& option : options.update_options) command += " " + shell_word(option);
    if (scenario_path.starts_with("-")) command += " --";  // a scenario named -x.scn is not an option
    return command + " " + shell_word(scenario_path);
}

}  // namespace

bool ScenarioCheck::passed() const {
    if (bad_input() || !trace_passed() || !failed_expectations.empty() || !stale_goldens.empty()) return false;
    return std::all_of(images.begin(), images.end(), [](const ImageCheck& i) { return i.passed(); });
}

bool ScenarioCheck::goldens_differ() const {
    if (bad_input()) return false;
    if (!trace_passed() || !stale_goldens.empty()) return true;
    return std::any_of(images.begin(), images.end(), [](const ImageCheck& i) { return i.golden_missing || !i.compare.identical; });
}

ScenarioCheck check_scenario(const Game& game, const std::string& scenario_path, const CheckOptions& options) {
    ScenarioCheck c;
    c.path = scenario_path;
    c.name = fs::path(scenario_path).stem().string();
    c.trace_path = (fs::path(scenario_path).parent_path() / (c.name + ".trace")).string();
    c.update_command = update_command_for(scenario_path, options);
    try {
        const Scenario scenario = load_scenario(scenario_path, game.vocabulary());
        ReplayOptions replay_options;
        replay_options.keep_screenshots = true;
        replay_options.dump_every = options.dump_every;
        replay_options.backend = options.backend;
        const ReplayResult run = replay(game, scenario, replay_options);
        c.seconds = run.seconds;
        c.actual_ticks = run.ticks;
        c.new_trace = format_trace(run, options.dump_every);

        // The trace. (A folder opens as a stream that reads nothing: it would look like a
        // broken golden that --update could replace, which it cannot.)
        std::error_code folder_ec;
        if (fs::is_directory(c.trace_path, folder_ec)) {
            throw InputError(SourceLocation{c.trace_path, 0, 0}, "a folder is where the golden trace should be: move it away");
        }
        bool exists = false;
        const std::string golden_text = read_file(c.trace_path, &exists);
        c.trace_missing = !exists;
        std::optional<ReplayResult> parsed;
        if (exists) {
            try {
                parsed = parse_trace(golden_text, c.trace_path);
            } catch (const InputError& e) {
                c.trace_missing = true;
                c.trace_error = e.what();
            }
        }
        if (parsed) {
            const ReplayResult& golden = *parsed;
            c.expected_ticks = golden.ticks;
            const std::size_t common = std::min(golden.hashes.size(), run.hashes.size());
            for (std::size_t t = 0; t < common; ++t) {
                if (golden.hashes[t] != run.hashes[t]) {
                    c.first_divergent_tick = static_cast<std::int64_t>(t);
                    c.expected_hash = golden.hashes[t];
                    c.actual_hash = run.hashes[t];
                    break;
                }
            }
            if (!c.first_divergent_tick && golden.hashes.size() != run.hashes.size()) {
                c.first_divergent_tick = static_cast<std::int64_t>(common);
            }
            if (c.first_divergent_tick) {
                // The first tick from the divergence on that both runs dumped.
                for (const TraceDump& g : golden.dumps) {
                    if (g.tick < *c.first_divergent_tick) continue;
                    const auto a = std::find_if(run.dumps.begin(), run.dumps.end(), [&](const TraceDump& d) { return d.tick == g.tick; });
                    if (a == run.dumps.end()) continue;
                    c.dump_tick = g.tick;
                    c.changes = diff_dumps(g.entities, a->entities);
                    break;
                }
            }
        }

        // The expectations.
        c.expectations = static_cast<std::int64_t>(run.expectations.size());
        for (const ExpectationResult& r : run.expectations) {
            if (!r.passed) {
                c.failed_expectations.push_back(
                    FailedExpectation{r.expectation->line, r.expectation->tick, r.expectation->text, r.actual});
            }
        }

        // The screenshots, and goldens no screenshot asks for any more.
        std::set<std::string> wanted;
        for (const auto& [tick, image] : run.screenshots) {
            ImageCheck check;
            check.tick = tick;
            check.golden_path = golden_image_path(scenario_path, tick);
            if (!wanted.insert(check.golden_path).second) continue;  // two screenshots at one tick
            check.actual = image;
            if (fs::exists(check.golden_path)) {
                try {
                    check.expected = read_png(check.golden_path);
                    check.compare = compare_images(check.expected, check.actual, options.image_tolerance);
                } catch (const InputError& e) {
                    check.expected = Image{};
                    check.golden_missing = true;
                    check.golden_error = e.what();
                }
            } else {
                check.golden_missing = true;
            }
            c.images.push_back(std::move(check));
        }
        const fs::path folder = fs::path(scenario_path).parent_path().empty() ? fs::path(".") : fs::path(scenario_path).parent_path();
        std::error_code ec;
        for (const auto& entry : fs::directory_iterator(folder, ec)) {
            const std::string file = entry.path().filename().string();
            if (is_golden_image_name(file, c.name) && !wanted.count((fs::path(scenario_path).parent_path() / file).string())) {
                c.stale_goldens.push_back((fs::path(scenario_path).parent_path() / file).string());
            }
        }
        std::sort(c.stale_goldens.begin(), c.stale_goldens.end());
    } catch (const InputError& e) {
        ScenarioCheck bad;
        bad.path = c.path;
        bad.name = c.name;
        bad.error = e.what();
        return bad;
    }
    return c;
}

std::vector<std::string> commit_updates(const std::vector<ScenarioCheck>& checks,
                                        const std::function<void(const std::string& golden)>& on_staged) {
    // Phase 1: every new file into a temporary file beside its target. Any error or signal
    // here throws and the AtomicFiles remove their temporary files: nothing changed.
    std::vector<std::unique_ptr<AtomicFile>> files;
    std::vector<std::string> removals;
    std::vector<std::string> lines;
    auto staged = [&]() {
        if (on_staged) on_staged(files.back()->path());
        throw_if_interrupted();
    };
    for (const ScenarioCheck& c : checks) {
        if (!c.goldens_differ()) continue;
        std::string what;
        if (!c.trace_passed()) {
            files.push_back(std::make_unique<AtomicFile>(c.trace_path));
            files.back()->write(c.new_trace);
            staged();
            what += !c.trace_error.empty() ? "trace replaced (it could not be read)"
                    : c.trace_missing          ? "trace created"
                    : c.first_divergent_tick ? "trace changed from tick " + std::to_string(*c.first_divergent_tick)
                                             : "trace length changed";
        }
        for (const ImageCheck& image : c.images) {
            if (!image.golden_missing && image.compare.identical) continue;
            const std::vector<std::uint8_t> png = encode_png(image.actual, PngEncoding{.encoder = PngEncoder::libpng, .compression_level = 9});
            files.push_back(std::make_unique<AtomicFile>(image.golden_path));
            files.back()->write(png.data(), png.size());
            staged();
            what += std::string(what.empty() ? "" : ", ") + fs::path(image.golden_path).filename().string() +
                    (!image.golden_error.empty() ? " replaced (it could not be read)"
                     : image.golden_missing      ? " created"
                                                 : " changed");
        }
        for (const std::string& stale : c.stale_goldens) {
            removals.push_back(stale);
            what += std::string(what.empty() ? "" : ", ") + fs::path(stale).filename().string() + " removed";
        }
        lines.push_back("updated " + c.path + ": " + what);
    }
    // Phase 2: renames and removals, with Ctrl-C, SIGTERM and SIGHUP held until they are all done.
    throw_if_interrupted();
    sigset_t block, previous;
    sigemptyset(&block);
    sigaddset(&block, SIGINT);
    sigaddset(&block, SIGTERM);
    sigaddset(&block, SIGHUP);
    sigprocmask(SIG_BLOCK, &block, &previous);
    try {
        for (auto& file : files) file->commit();
        for (const std::string& path : removals) std::filesystem::remove(path);
    } catch (...) {
        sigprocmask(SIG_SETMASK, &previous, nullptr);
        throw;
    }
    sigprocmask(SIG_SETMASK, &previous, nullptr);
    return lines;
}

std::string describe_check(const ScenarioCheck& c) {
    std::ostringstream out;
    // "(to create it: COMMAND)": the command is not wrapped in quotes of its own, so it can be
    // copied whole whatever quotes its words need.
    const std::string command = c.update_command.empty() ? std::string("jostle check --update") : c.update_command;
    const auto run = [&](const char* what) { return std::string("(to ") + what + " it: " + command + ")"; };
    if (c.bad_input()) {
        out << "ERROR " << c.path << ": " << c.error << "\n";
        return out.str();
    }
    out << (c.passed() ? "PASS " : "FAIL ") << c.path << " (" << counted(c.actual_ticks, "tick") << ", "
        << counted(c.expectations, "expectation") << ", " << counted(static_cast<std::int64_t>(c.images.size()), "screenshot") << ")\n";
    if (!c.trace_error.empty()) {
        out << "  trace: the golden cannot be read: " << c.trace_error << " " << run("replace") << "\n";
    } else if (c.trace_missing) {
        out << "  trace: no golden " << c.trace_path << " " << run("create") << "\n";
    } else if (c.first_divergent_tick) {
        out << "  trace: first divergent tick " << *c.first_divergent_tick;
        if (c.expected_hash != c.actual_hash) out << " (expected hash " << hex16(c.expected_hash) << ", got " << hex16(c.actual_hash) << ")";
        if (c.expected_ticks != c.actual_ticks) out << " (the golden has " << counted(c.expected_ticks, "tick") << ", this run " << c.actual_ticks << ")";
        out << "\n";
        if (c.dump_tick) {
            out << "  at tick " << *c.dump_tick << " (the first dumped tick from there on), expected -> actual:\n";
            for (const FieldChange& f : c.changes) {
                out << "    " << f.entity << (f.field.empty() ? "" : " " + f.field) << ": " << f.expected << " -> " << f.actual << "\n";
            }
            if (c.changes.empty()) out << "    (no dumped field differs; the difference is in state the dump leaves out)\n";
        }
    }
    for (const FailedExpectation& e : c.failed_expectations) {
        out << "  " << c.path << ":" << e.line << ": expectation failed at tick " << e.tick << ": expected " << e.expected
            << ", found " << e.actual << "\n";
    }
    for (const ImageCheck& i : c.images) {
        if (!i.golden_error.empty()) {
            out << "  screenshot tick " << i.tick << ": the golden cannot be read: " << i.golden_error
                << " " << run("replace") << "\n";
        } else if (i.golden_missing) {
            out << "  screenshot tick " << i.tick << ": no golden " << i.golden_path << " " << run("create") << "\n";
        } else if (!i.compare.within_tolerance) {
            out << "  screenshot tick " << i.tick << ": ";
            if (!i.compare.same_size) {
                out << "size " << i.actual.width << "x" << i.actual.height << ", golden " << i.expected.width << "x" << i.expected.height;
            } else {
                out << i.compare.differing_pixels << " pixels differ (largest channel difference " << i.compare.max_channel_delta << ")";
            }
            out << " from " << i.golden_path << "\n";
        }
    }
    for (const std::string& stale : c.stale_goldens) {
        out << "  stale golden " << stale << ": no screenshot asks for it " << run("remove") << "\n";
    }
    return out.str();
}

std::vector<std::string> collect_scenarios(const std::vector<std::string>& args) {
    std::vector<std::string> out;
    // A scenario is its folder and its name: its goldens lie beside that name. Spellings of one
    // (M/x.scn, M/./x.scn, ./M/x.scn, a folder and a file in it, a link to the folder) are one
    // scenario, checked once under the first; a link to x.scn by another name or in another
    // folder is a scenario of its own, with its own goldens.
    std::set<fs::path> seen;
    const auto add = [&](const fs::path& scenario) {
        std::error_code ec;
        const fs::path folder = fs::canonical(scenario.has_parent_path() ? scenario.parent_path() : fs::path("."), ec);
        if (seen.insert(ec ? scenario.lexically_normal() : folder / scenario.filename()).second) out.push_back(scenario.string());
    };
    for (const std::string& arg : args) {
        std::error_code ec;
        if (fs::is_directory(arg, ec)) {
            std::vector<fs::path> found;
            for (const auto& entry : fs::directory_iterator(arg, ec)) {
                if (entry.path().extension() == ".scn") found.push_back(entry.path());
            }
            if (found.empty()) throw InputError(SourceLocation{arg, 0, 0}, "no scenario files (*.scn) in this folder");
            std::sort(found.begin(), found.end(), [](const fs::path& a, const fs::path& b) { return a.string() < b.string(); });
            for (const fs::path& scenario : found) add(scenario);
        } else if (fs::exists(arg, ec)) {
            add(arg);
        } else {
            throw InputError(SourceLocation{arg, 0, 0}, "no such scenario file or folder");
        }
    }
    return out;
}

std::vector<std::string> select_shard(const std::vector<std::string>& scenarios) {
    auto env = [](const char* a, const char* b) -> const char* {
        const char* v = std::getenv(a);
        return v != nullptr ? v : std::getenv(b);
    };
    const char* total_text = env("TEST_TOTAL_SHARDS", "GTEST_TOTAL_SHARDS");
    const char* index_text = env("TEST_SHARD_INDEX", "GTEST_SHARD_INDEX");
    if (const char* status = env("TEST_SHARD_STATUS_FILE", "GTEST_SHARD_STATUS_FILE"); status != nullptr && *status != '\0') {
        std::ofstream touch(status, std::ios::app);
        if (!touch) throw InputError(SourceLocation{status, 0, 0}, "cannot touch the shard status file");
    }
    if (total_text == nullptr && index_text == nullptr) return scenarios;
    auto number = [](const char* name, const char* text, std::int64_t min) {
        std::int64_t v = -1;
        const std::string_view s = text != nullptr ? text : "";
        const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
        if (text == nullptr || ec != std::errc() || end != s.data() + s.size() || v < min) {
            throw InputError(std::string(name) + ": expected a whole number >= " + std::to_string(min) + ", got '" +
                             std::string(s) + "'");
        }
        return v;
    };
    const std::int64_t total = number("TEST_TOTAL_SHARDS", total_text, 1);  // at least one shard
    const std::int64_t index = number("TEST_SHARD_INDEX", index_text, 0);
    if (index >= total) {
        throw InputError("TEST_SHARD_INDEX " + std::to_string(index) + " must be below TEST_TOTAL_SHARDS " + std::to_string(total));
    }
    std::vector<std::string> out;
    for (std::size_t i = 0; i < scenarios.size(); ++i) {
        if (static_cast<std::int64_t>(i) % total == index) out.push_back(scenarios[i]);
    }
    return out;
}

void create_report_folder(const std::string& folder) {
    std::error_code ec;
    fs::create_directories(folder, ec);
    if (ec) throw InputError(SourceLocation{folder, 0, 0}, "cannot create the report folder: " + ec.message());
}

namespace {

// An earlier report's images in the folder that this one does not show: NAME.tick_T.expected,
// .actual or .diff .png, the names write_report gives them. Left there they would read as
// this run's failures (a CI job that uploads the folder). Any other file is the user's and
// stays; one that cannot be removed stays too (the report itself is already written).
void remove_stale_report_images(const std::string& folder, const std::set<std::string>& shown) {
    std::vector<fs::path> stale;
    std::error_code ec;
    for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        const std::size_t tick = name.rfind(".tick_");
        std::error_code type_ec;
        if (tick == std::string::npos || shown.count(name) != 0 || !it->is_regular_file(type_ec)) continue;
        const std::string_view rest = std::string_view(name).substr(tick + 6);
        const std::size_t digits = rest.find_first_not_of("0123456789");
        if (digits == 0 || digits == std::string_view::npos) continue;
        const std::string_view kind = rest.substr(digits);
        if (kind == ".expected.png" || kind == ".actual.png" || kind == ".diff.png") stale.push_back(it->path());
    }
    for (const fs::path& file : stale) fs::remove(file, ec);  // best effort, as said above
}

}  // namespace

void write_report(const std::string& folder, const std::vector<ScenarioCheck>& checks) {
    create_report_folder(folder);
    std::ostringstream html;
    html << "<!doctype html>\n<html><head><meta charset=\"utf-8\"><title>jostle check report</title>\n"
            "<style>body{font-family:sans-serif;background:#1b1d22;color:#ddd} .scenario{margin:1em 0;padding:.5em;"
            "border:1px solid #444} .fail{color:#f66} .pass{color:#6c6} table{border-collapse:collapse} "
            "td,th{padding:2px 8px;border:1px solid #444} img{image-rendering:pixelated;max-width:420px;border:1px solid #555}"
            " .images{display:flex;gap:8px} figure{margin:0}</style></head><body>\n";
    int failed = 0;
    for (const ScenarioCheck& c : checks) failed += c.passed() ? 0 : 1;
    html << "<h1>jostle check: " << failed << " of " << counted(static_cast<std::int64_t>(checks.size()), "scenario") << " failed</h1>\n";
    std::set<std::string> ids;  // scenarios of the same name from different folders get _2, _3...
    std::set<std::string> images;  // the image files this report shows
    const auto write_image = [&](const std::string& name, const Image& image) {
        write_png_atomic((fs::path(folder) / name).string(), image);
        images.insert(name);
    };
    for (const ScenarioCheck& c : checks) {
        if (c.passed()) continue;
        std::string id = c.name;
        for (int n = 2; !ids.insert(id).second; ++n) id = c.name + "_" + std::to_string(n);
        html << "<div class=\"scenario\" id=\"" << html_escape(id) << "\">\n<h2 class=\"fail\">" << html_escape(c.path) << "</h2>\n";
        if (c.bad_input()) html << "<p class=\"error\">" << html_escape(c.error) << "</p>\n";
        if (!c.trace_error.empty()) {
            html << "<p class=\"trace\">the golden trace cannot be read: " << html_escape(c.trace_error) << "</p>\n";
        } else if (c.trace_missing) {
            html << "<p class=\"trace\">no golden trace</p>\n";
        }
        if (c.first_divergent_tick) {
            html << "<p class=\"divergence\">first divergent tick: <b class=\"first-divergent-tick\">" << *c.first_divergent_tick
                 << "</b></p>\n";
            if (c.dump_tick) {
                html << "<p>at tick " << *c.dump_tick << ":</p>\n<table class=\"changes\"><tr><th>entity</th><th>field</th>"
                        "<th>expected</th><th>actual</th></tr>\n";
                for (const FieldChange& f : c.changes) {
                    html << "<tr><td>" << html_escape(f.entity) << "</td><td>" << html_escape(f.field) << "</td><td>"
                         << html_escape(f.expected) << "</td><td>" << html_escape(f.actual) << "</td></tr>\n";
                }
                html << "</table>\n";
            }
        }
        for (const FailedExpectation& e : c.failed_expectations) {
            html << "<p class=\"expectation\">line " << e.line << ", tick " << e.tick << ": expected " << html_escape(e.expected)
                 << ", found " << html_escape(e.actual) << "</p>\n";
        }
        for (const ImageCheck& i : c.images) {
            if (i.passed()) continue;
            const std::string base = id + ".tick_" + std::to_string(i.tick);
            html << "<h3>screenshot at tick " << i.tick << "</h3>\n<div class=\"images\">\n";
            if (!i.golden_missing) {
                write_image(base + ".expected.png", i.expected);
                write_image(base + ".diff.png", diff_image(i.expected, i.actual));
                html << "<figure><img class=\"expected\" src=\"" << html_escape(url_escape(base)) << ".expected.png\"><figcaption>expected</figcaption></figure>\n";
            } else {
                html << "<figure><figcaption>expected: "
                     << (i.golden_error.empty() ? "no golden" : "unreadable golden: " + html_escape(i.golden_error))
                     << "</figcaption></figure>\n";
            }
            write_image(base + ".actual.png", i.actual);
            html << "<figure><img class=\"actual\" src=\"" << html_escape(url_escape(base)) << ".actual.png\"><figcaption>actual</figcaption></figure>\n";
            if (!i.golden_missing) {
                html << "<figure><img class=\"diff\" src=\"" << html_escape(url_escape(base)) << ".diff.png\"><figcaption>diff</figcaption></figure>\n";
            }
            html << "</div>\n";
        }
        html << "</div>\n";
    }
    html << "</body></html>\n";
    write_file_atomic((fs::path(folder) / "report.html").string(), html.str());

    std::ostringstream xml;
    double total_seconds = 0.0;
    for (const ScenarioCheck& c : checks) total_seconds += c.seconds;
    xml << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites>\n<testsuite name=\"jostle.scenarios\" tests=\""
        << checks.size() << "\" failures=\"" << failed << "\" time=\"" << total_seconds << "\">\n";
    for (const ScenarioCheck& c : checks) {
        xml << "  <testcase classname=\"scenario\" name=\"" << html_escape(c.name) << "\" file=\"" << html_escape(c.path)
            << "\" time=\"" << c.seconds << "\"";
        if (c.passed()) {
            xml << "/>\n";
        } else {
            xml << ">\n    <failure message=\"" << (c.bad_input() ? "bad input" : "regression") << "\">"
                << html_escape(describe_check(c)) << "</failure>\n  </testcase>\n";
        }
    }
    xml << "</testsuite>\n</testsuites>\n";
    write_file_atomic((fs::path(folder) / "junit.xml").string(), xml.str());
    remove_stale_report_images(folder, images);
}

}  // namespace jostle
