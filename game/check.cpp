// `jostle check`: arguments, parallel runs, the summary and the exit status; the comparison
// is engine/replay (jostle/replay/check.h).
#include "check.h"

#include <atomic>
#include <cstdlib>
#include <csignal>
#include <filesystem>
#include <mutex>
#include <optional>
#include <ostream>
#include <thread>

#include "arena.h"
#include "cli.h"
#include "jostle/core/error.h"
#include "jostle/core/interrupt.h"
#include "jostle/core/text.h"
#include "jostle/replay/check.h"

namespace jostle {
namespace fs = std::filesystem;
namespace {

int usage(std::ostream& err, const std::string& message) {
    err << "jostle check: " << message << "\nRun 'jostle check --help' for usage.\n";
    return 2;
}

}  // namespace

std::string_view check_help() {
    return R"(usage: jostle check [SCENARIO|DIR ...] [--update] [--report DIR] [--jobs N]
                    [--tolerance N] [--max-pixels N]

Replays each scenario and compares the run with its goldens, which live beside it:
NAME.trace (the state hash of every tick, with entity dumps) and NAME.tick_T.png (the frame
at each screenshot). A folder means every *.scn in it; the default is the assets' scenarios folder
(--assets DIR/scenarios). Reported per scenario: the first divergent tick with the entities and
fields that differ, failed expectations, and screenshots that differ.

options:
  --update          re-bless the goldens of every scenario that differs, and print what
                    changed. All new files are written first and renamed together, so an
                    interrupted update changes nothing. Missing goldens are created only so.
                    Not of a scenario in the assets' sprites folder (a golden image there
                    would be a sprite)
  --report DIR      write DIR/report.html (each failing scenario with its expected, actual
                    and diff images side by side) and DIR/junit.xml (every scenario); not
                    a folder of the scenarios checked (it would mix with goldens) nor the
                    assets' levels or sprites folder (the images would be sprites)
  --jobs N          check N scenarios at once, 1 to 256 (default 1); the results are
                    printed in scenario order all the same
  --tolerance N     per-channel difference (0..255) that still counts as equal in images
  --max-pixels N    how many pixels may differ in each image (0..9223372036854775807; default 0)
  --assets DIR      where the levels are (default: $JOSTLE_ASSETS, else the source tree's)
  --                what follows are scenarios and folders, even if they start with '-'

Sharding: with TEST_TOTAL_SHARDS and TEST_SHARD_INDEX (or GTEST_TOTAL_SHARDS and
GTEST_SHARD_INDEX) set, only scenario i with i % total == index is checked;
TEST_SHARD_STATUS_FILE is touched.

Ctrl-C (SIGTERM, SIGHUP) stops between ticks; an update then changes no golden, and no temporary
file is left.

exit status: 0 every scenario passed (or was updated), 1 a regression (with --update: an
expectation failed, which new goldens cannot fix), 2 bad usage or input (or standard output
could not be written: an update's goldens are written all the same),
130 (143, 129) stopped by Ctrl-C (SIGTERM, SIGHUP).
)";
}

int check_command(std::span<const std::string_view> args, std::ostream& out, std::ostream& err) {
    std::vector<std::string> paths;
    bool update = false;
    std::string report;
    std::int64_t jobs = 1;
    CheckOptions options;
    std::string assets = game::default_assets_dir();
    bool options_ended = false;  // after "--", a scenario named "-x.scn" is a scenario
    game::OnceOnly once;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string_view a = args[i];
        if (options_ended || a.size() < 2 || a.front() != '-') {
            if (a.empty()) return usage(err, "expected a scenario file or folder, got an empty argument");
            paths.emplace_back(a);
            continue;
        }
        if (a == "--") {
            options_ended = true;
            continue;
        }
        if (a == "--update") {
            update = true;
            continue;
        }
        if (a == "--report" || a == "--jobs" || a == "--tolerance" || a == "--max-pixels" || a == "--assets") {
            std::string_view v;
            if (std::string e = game::option_value(args, i, a, v); !e.empty()) return usage(err, e);
            if (std::string e = once.take(a); !e.empty()) return usage(err, e);
            if (a == "--report") report = std::string(v);
            if (a == "--assets") {
                assets = std::string(v);
                options.update_options = {"--assets", assets};  // for the hints' 'jostle check --update'
            }
            if (a == "--jobs") {
                const auto n = game::parse_whole(v, 1, 256);
                if (!n) return usage(err, game::whole_number_error("--jobs", 1, 256, v));
                jobs = static_cast<int>(*n);
            }
            if (a == "--tolerance") {
                const auto n = game::parse_whole(v, 0, 255);
                if (!n) return usage(err, game::whole_number_error("--tolerance", 0, 255, v));
                options.image_tolerance.max_channel_delta = static_cast<int>(*n);
            }
            if (a == "--max-pixels") {
                const auto n = game::parse_whole(v, 0, INT64_MAX);
                if (!n) return usage(err, game::whole_number_error("--max-pixels", 0, INT64_MAX, v));
                options.image_tolerance.max_differing_pixels = static_cast<std::int64_t>(*n);
            }
            continue;
        }
        if (a == "--help" || a == "-h") {  // anywhere an option may stand, as right after the command
            out << check_help();
            return 0;
        }
        return usage(err, "unknown option '" + std::string(a) + "'");
    }
    if (paths.empty()) paths.push_back(assets + "/scenarios");

    try {
        const game::ArenaGame game(assets);
        // The report's images in the sprites folder would be new sprites.
        if (const std::string folder = report.empty() ? "" : game.asset_folder(report); !folder.empty()) {
            return usage(err, "--report: '" + report + "' " + folder + "; give another folder");
        }
        const std::vector<std::string> all_scenarios = collect_scenarios(paths);
        // Screenshot goldens (NAME.tick_T.png) written into the assets' sprites folder would be
        // new sprites of the game, read into every level's hash: an update there is refused
        // before the run, and a plain check says so beside the hints that name an update.
        for (const std::string& scenario : all_scenarios) {
            const fs::path folder = fs::path(scenario).parent_path().empty() ? fs::path(".") : fs::path(scenario).parent_path();
            std::error_code ec;
            if (!fs::equivalent(folder, fs::path(assets) / "sprites", ec)) continue;
            const std::string why = "the scenario '" + scenario +
                                    "' is in the sprites folder of the assets, where its goldens do not belong (a golden "
                                    "image there would be a sprite); give it a folder of its own";
            if (update) return usage(err, "--update: " + why);
            err << "jostle check: note: " << why << " (--update refuses it)\n";
        }
        if (!report.empty()) {
            // The report's images and pages among goldens would be mistaken for them, or
            // committed with them: a scenario's folder is not a report folder.
            for (const std::string& scenario : all_scenarios) {
                const fs::path folder = fs::path(scenario).parent_path().empty() ? fs::path(".") : fs::path(scenario).parent_path();
                std::error_code ec;
                if (fs::equivalent(report, folder, ec)) {
                    return usage(err, "--report: '" + report + "' holds the scenario '" + scenario +
                                          "' and its goldens; give the report a folder of its own");
                }
            }
        }
        const std::vector<std::string> scenarios = select_shard(all_scenarios);
        if (!report.empty()) create_report_folder(report);  // a bad --report is said before the run
        std::vector<ScenarioCheck> checks(scenarios.size());
        std::atomic<std::size_t> next{0};
        // Results are printed in scenario order whatever the order the jobs finish in: one that
        // finishes early waits in `shown` until those before it are printed.
        std::mutex print;
        std::vector<std::optional<std::string>> shown(scenarios.size());
        std::size_t printed = 0;
        // Tests interrupt a run at a chosen point: JOSTLE_TEST_INTERRUPT=after-check raises SIGINT
        // once the first scenario is checked, =after-staged once the first new golden is staged.
        const char* test_hook = std::getenv("JOSTLE_TEST_INTERRUPT");
        const std::string_view interrupt_at = test_hook != nullptr ? test_hook : "";
        // Each worker takes the next scenario; results land in scenario order. A signal stops
        // every worker between ticks (Interrupted); the main thread rethrows it after the join.
        auto worker = [&]() {
            try {
                for (std::size_t i = next++; i < scenarios.size(); i = next++) {
                    ScenarioCheck check = check_scenario(game, scenarios[i], options);
                    // An update reports the goldens it changes at the end; what it cannot fix
                    // (a failed expectation, bad input) is reported here as in a plain check.
                    const bool report_now = !update || !check.goldens_differ() || check.bad_input() ||
                                            !check.failed_expectations.empty();
                    std::string text = report_now ? describe_check(check) : std::string();
                    {
                        const std::lock_guard<std::mutex> lock(print);
                        checks[i] = std::move(check);
                        shown[i] = std::move(text);
                        for (; printed < shown.size() && shown[printed]; ++printed) out << *shown[printed] << std::flush;
                    }
                    if (interrupt_at == "after-check" && i == 0) std::raise(SIGINT);
                    throw_if_interrupted();
                }
            } catch (const Interrupted&) {
                next = scenarios.size();
            }
        };
        std::vector<std::thread> threads;
        for (std::int64_t j = 1; j < std::min<std::int64_t>(jobs, static_cast<std::int64_t>(scenarios.size())); ++j) {
            threads.emplace_back(worker);
        }
        worker();
        for (std::thread& t : threads) t.join();
        // Stopped by a signal: the results finished after one that was stopped, still in order.
        for (; printed < shown.size(); ++printed) {
            if (shown[printed]) out << *shown[printed] << std::flush;
        }
        throw_if_interrupted();

        int bad = 0, failed = 0;
        for (const ScenarioCheck& c : checks) {
            if (c.bad_input()) ++bad;
            else if (!c.passed()) ++failed;
        }
        if (update && bad == 0) {
            bool raised = false;
            const std::vector<std::string> lines = commit_updates(checks, [&](const std::string&) {
                if (interrupt_at == "after-staged" && !raised) {
                    raised = true;
                    std::raise(SIGINT);
                }
            });
            for (const std::string& line : lines) out << line << "\n";
            std::size_t expectations_failed = 0;
            for (const ScenarioCheck& c : checks) expectations_failed += c.failed_expectations.empty() ? 0 : 1;
            out << "checked " << counted(static_cast<std::int64_t>(checks.size()), "scenario") << ": " << lines.size() << " updated";
            if (expectations_failed > 0) {
                out << ", " << expectations_failed << " with failing expectations (an update cannot fix those)";
            }
            out << "\n";
            if (!report.empty()) write_report(report, checks);
            return expectations_failed > 0 ? 1 : 0;
        }
        if (!report.empty()) write_report(report, checks);
        out << "checked " << counted(static_cast<std::int64_t>(checks.size()), "scenario") << ": " << checks.size() - static_cast<std::size_t>(failed + bad)
            << " passed, " << failed << " failed" << (bad > 0 ? ", " + std::to_string(bad) + " with bad input" : "") << "\n";
        if (update && bad > 0) err << "jostle check: nothing updated: fix the bad input first\n";
        return bad > 0 ? 2 : failed > 0 ? 1 : 0;
    } catch (const InputError& e) {
        err << "jostle check: " << e.what() << '\n';
        return 2;
    }
}

}  // namespace jostle
