// `jostle record`: argument parsing, the read-back check and the summary; scripts and the
// live recording are engine/replay (jostle/replay/record.h).
#include "record.h"

#include <algorithm>
#include <fstream>
#include <ios>
#include <istream>
#include <optional>
#include <ostream>
#include <string>
#include <system_error>

#include "arena.h"
#include "cli.h"
#include "jostle/core/atomic_file.h"
#include "jostle/core/error.h"
#include "jostle/core/interrupt.h"
#include "jostle/core/text.h"
#include "jostle/replay/record.h"
#include "jostle/replay/replay.h"

namespace jostle {
namespace {

int usage(std::ostream& err, const std::string& message) {
    err << "jostle record: " << message << "\nRun 'jostle record --help' for usage.\n";
    return 2;
}

// The whole script on standard input. A read that fails (stdin is a folder) says so instead of
// ending the script there (`text << in.rdbuf()` would swallow the error: an empty script).
std::string read_all(std::istream& in) {
    std::string text;
    std::streambuf* input = in.rdbuf();
    if (input == nullptr) return text;
    try {
        char chunk[4096];
        for (std::streamsize n = 0; (n = input->sgetn(chunk, sizeof chunk)) > 0;) {
            text.append(chunk, static_cast<std::size_t>(n));
        }
    } catch (const std::ios_base::failure& e) {
        throw_if_interrupted();  // Ctrl-C while the script was typed
        // Said as a script file's would be (core/text.cpp), not as strerror's "Is a directory".
        if (e.code() == std::errc::is_a_directory) throw InputError("<stdin>: is a folder, expected the script");
        throw InputError("<stdin>: cannot read the script: " + e.code().message());
    }
    return text;
}

}  // namespace

std::string_view record_help() {
    return R"(usage: jostle record --level LEVEL -o SCENARIO [--script FILE] [--seed N] [--tick-rate N]
       jostle record --from SCENARIO --at TICK -o SCENARIO [--script FILE]

Plays an input script live against the arena game and writes the scenario that reproduces
the run. Then it reads the file back and replays it: the file is kept only when the replay
gives the recorded run's state hash on every tick.

The script (from FILE, or from standard input without --script), one step per line:
  hold ACTION... TICKS    hold these actions for TICKS ticks ("hold right up 30")
  press ACTION...         hold them for one tick
  wait TICKS              hold nothing for TICKS ticks
  screenshot              keep a screenshot of the state after the last tick played
  expect ...              an expectation about that state: NAME alive, NAME gone,
                          NAME in X0 Y0 X1 Y1, count KIND OP N, var NAME OP V, event NAME
  # comment
Actions: left, right, up, down, fire.

options:
  --level LEVEL     the level to play (a file assets/levels/LEVEL.level)
  -o, --out FILE    the scenario to write (atomically; an existing file is replaced);
                    /dev/stdout: standard output, which then holds the scenario alone (the
                    summary goes to stderr); it cannot be read back, so the bytes are
                    replayed before they are sent
  --script FILE     the input script (default: standard input)
  --seed N          the world's RNG seed (default 1)
  --tick-rate N     ticks per second, 1..1000 (default 60)
  --from SCENARIO   re-record: keep the start of this scenario (its level, seed, tick rate,
  --at TICK         and its first TICK ticks of input with their directives), then continue
                    with the script
  --assets DIR      where the levels are (default: $JOSTLE_ASSETS, else the source tree's)

exit status: 0 written and verified, 1 the read-back replay differed (nothing written),
2 bad usage or bad input (nothing written) or standard output could not be written (the
scenario is written and verified), 130 (143, 129) stopped by Ctrl-C (SIGTERM, SIGHUP):
nothing written.
)";
}

int record_command(std::span<const std::string_view> args, std::istream& in, std::ostream& out, std::ostream& err) {
    std::string level, out_path, script_path, from_path;
    std::optional<std::int64_t> at;
    bool seed_given = false, tick_rate_given = false;
    RecordDesc desc;
    std::string assets = game::default_assets_dir();
    game::OnceOnly once;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string_view a = args[i];
        if (a == "--") {  // the end of the options: record takes no other arguments
            if (i + 1 < args.size()) return usage(err, "unexpected argument '" + std::string(args[i + 1]) + "'");
            continue;
        }
        if (a != "--level" && a != "-o" && a != "--out" && a != "--script" && a != "--seed" && a != "--tick-rate" &&
            a != "--from" && a != "--at" && a != "--assets") {
            if (a == "--help" || a == "-h") {  // anywhere an option may stand, as right after the command
                out << record_help();
                return 0;
            }
            if (a.size() > 1 && a.front() == '-') return usage(err, "unknown option '" + std::string(a) + "'");
            return usage(err, "unexpected argument '" + std::string(a) + "'");
        }
        std::string_view v;
        if (std::string e = game::option_value(args, i, a, v); !e.empty()) return usage(err, e);
        const std::string_view key = a == "--out" ? "-o" : a;  // one option, two spellings
        if (!once.take(key).empty()) return usage(err, key == "-o" ? "-o (or --out) given twice" : std::string(a) + " given twice");
        if (a == "--level") level = std::string(v);
        if (a == "-o" || a == "--out") out_path = std::string(v);
        if (a == "--script") script_path = std::string(v);
        if (a == "--from") from_path = std::string(v);
        if (a == "--assets") assets = std::string(v);
        if (a == "--seed") {
            const auto n = game::parse_whole(v, 0, UINT64_MAX);
            if (!n) return usage(err, game::whole_number_error("--seed", 0, UINT64_MAX, v));
            desc.seed = *n;
            seed_given = true;
        }
        if (a == "--tick-rate") {
            const auto n = game::parse_whole(v, 1, 1000);
            if (!n) return usage(err, game::whole_number_error("--tick-rate", 1, 1000, v));
            desc.tick_rate = static_cast<int>(*n);
            tick_rate_given = true;
        }
        if (a == "--at") {
            const auto n = game::parse_whole(v, 0, static_cast<std::uint64_t>(kMaxScenarioTicks));
            if (!n) return usage(err, game::whole_number_error("--at", 0, static_cast<std::uint64_t>(kMaxScenarioTicks), v));
            at = static_cast<std::int64_t>(*n);
        }
    }
    if (out_path.empty()) return usage(err, "expected -o SCENARIO (the file to write)");
    if (from_path.empty() == at.has_value()) {  // one without the other
        if (from_path.empty()) return usage(err, "--at needs --from SCENARIO");
        return usage(err, "--from needs --at TICK (how many ticks to keep)");
    }
    if (!from_path.empty() && !level.empty()) return usage(err, "--level cannot be used with --from (the level is the scenario's)");
    if (!from_path.empty() && seed_given) return usage(err, "--seed cannot be used with --from (the seed is the scenario's)");
    if (!from_path.empty() && tick_rate_given) {
        return usage(err, "--tick-rate cannot be used with --from (the tick rate is the scenario's)");
    }
    if (same_file(out_path, script_path)) return usage(err, "-o: '" + out_path + "' is the script being read; give another path");
    // (-o may be the --from scenario: re-recording in place reads it whole before anything is written.)
    if (from_path.empty() && level.empty()) return usage(err, "expected --level LEVEL (or --from SCENARIO --at TICK)");

    try {
        const game::ArenaGame game(assets);
        if (const std::string asset = game.asset_named(out_path); !asset.empty()) {
            return usage(err, "-o: '" + out_path + "' " + asset + "; give another path");
        }
        // A path -o cannot be written to is said before the script is read (typed) and recorded.
        check_writable(out_path);
        std::optional<Scenario> from;
        if (!from_path.empty()) {
            from = load_scenario(from_path, game.vocabulary());
            if (*at > from->ticks()) {
                return usage(err, "--at " + std::to_string(*at) + ": " + from_path + " has only " +
                                      counted(from->ticks(), "tick"));
            }
            desc.from = &*from;
            desc.keep_ticks = *at;
        } else {
            const auto& levels = game.vocabulary().levels;
            if (std::find(levels.begin(), levels.end(), level) == levels.end()) {
                std::string known;
                for (const std::string& name : levels) known += (known.empty() ? "" : ", ") + name;
                return usage(err, "--level: unknown level '" + level + "' (expected one of: " + known + ")");
            }
            desc.level = level;
        }

        std::string script_text;
        std::string script_source = script_path.empty() ? "<stdin>" : script_path;
        if (script_path.empty()) {
            script_text = read_all(in);
        } else {
            script_text = read_text_file(script_path, "the script");
        }
        throw_if_interrupted();  // Ctrl-C while the script was typed: the read ended early
        const std::vector<ScriptStep> script = parse_input_script(script_text, script_source, game.vocabulary());
        const Recording recording = record(game, desc, script, script_source);
        const std::string text = format_scenario(recording.scenario, game.vocabulary());

        // Doom's rule: write the file, read it back from the disk, replay it, and keep it only
        // when the replay is the recorded run, tick for tick.
        // (A target written in place, such as /dev/stdout on a pipe, cannot be read back: its
        // bytes are replayed from memory and sent only once they pass.)
        AtomicFile file(out_path);
        std::string read_back = text;
        if (!file.in_place()) {
            file.write(text);
            file.flush();
            std::ifstream back(file.temp_path(), std::ios::binary);
            read_back = read_all(back);
        }
        const Scenario reread = parse_scenario(read_back, out_path, game.vocabulary());
        ReplayOptions options;
        options.dump_every = 0;
        const ReplayResult replayed = replay(game, reread, options);
        std::int64_t first_difference = -1;
        const std::size_t n = std::max(replayed.hashes.size(), recording.hashes.size());
        for (std::size_t t = 0; t < n && first_difference < 0; ++t) {
            if (t >= replayed.hashes.size() || t >= recording.hashes.size() || replayed.hashes[t] != recording.hashes[t]) {
                first_difference = static_cast<std::int64_t>(t);
            }
        }
        if (first_difference >= 0) {
            err << "jostle record: " << out_path << ": the recorded file does not reproduce the run: the replay differs from tick "
                << first_difference << " on; nothing was written\n";
            return 1;
        }
        if (file.in_place()) file.write(text);
        file.commit();
        // What --from's file had past the kept ticks is not in the new scenario: said, not
        // silently gone (re-recording a file in place would otherwise lose its checks).
        if (recording.dropped_expectations > 0 || recording.dropped_screenshots > 0) {
            err << "jostle record: note: " << from_path << ": not kept, being at tick " << *at << " or later: ";
            if (recording.dropped_expectations > 0) err << counted(recording.dropped_expectations, "expectation");
            if (recording.dropped_expectations > 0 && recording.dropped_screenshots > 0) err << " and ";
            if (recording.dropped_screenshots > 0) err << counted(recording.dropped_screenshots, "screenshot");
            err << "\n";
        }
        // The replay's expectations are the recording's, in the same order (both sorted by
        // tick); the recording knows which file and line each came from.
        for (std::size_t i = 0; i < replayed.expectations.size(); ++i) {
            const ExpectationResult& r = replayed.expectations[i];
            if (r.passed) continue;
            const bool known = i < recording.scenario.expectations.size();
            const std::string where = known ? recording.expectation_sources[i] : out_path;
            const int line = known ? recording.scenario.expectations[i].line : r.expectation->line;
            err << "jostle record: note: " << where << ":" << line << ": expectation fails in this run at tick "
                << r.expectation->tick << ": expected " << r.expectation->text << ", found " << r.actual << "\n";
        }
        // A scenario on standard output keeps it to itself (a line after `at N end` would make
        // the file unreadable): the summary goes to stderr. A target written in place was not
        // read back, and the summary says so.
        std::ostream& summary = same_file(out_path, "/dev/stdout") ? err : out;
        summary << "recorded " << counted(static_cast<std::int64_t>(recording.hashes.size()), "tick") << " of level "
                << recording.scenario.level << " to " << out_path
                << (file.in_place() ? " (not read back, as it was written in place, to a descriptor or a stream: the bytes "
                                      "sent were replayed first, the same state on every tick)\n"
                                    : " (read back and replayed: the same state on every tick)\n");
        return 0;
    } catch (const InputError& e) {
        err << "jostle record: " << e.what() << '\n';
        return 2;
    }
}

}  // namespace jostle
