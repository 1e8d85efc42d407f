// jostle/replay/check.h: gameplay regression checks. A scenario's goldens live beside it:
//
//   assets/scenarios/NAME.scn          the scenario
//   assets/scenarios/NAME.trace        the state hash of every tick, with dumps (replay.h)
//   assets/scenarios/NAME.tick_T.png   the frame at each "at T screenshot"
//
// check_scenario replays the scenario and compares: the hash trace (the first divergent
// tick, and the entities and fields that differ at the first dump from that tick on), the
// expectations, and the screenshots (image_compare.h). A missing golden is a failure; only an
// update creates goldens (commit_updates). An unreadable golden (a merge conflict in a trace,
// a truncated PNG) counts as missing, with the reason, so an update can replace it. Only a
// file named exactly NAME.tick_T.png, T a tick as the program writes it ("79", never "079"
// or "79.orig"), is a golden: one no screenshot asks for is stale, and an update removes it;
// any other file beside the scenario is left alone.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "jostle/render/image_compare.h"
#include "jostle/render/renderer.h"
#include "jostle/replay/simulation.h"

namespace jostle {

struct CheckOptions {
    CompareOptions image_tolerance;  // exact by default
    int dump_every = 10;             // for goldens written by an update
    RenderBackend backend = RenderBackend::osmesa;
    // The options the hints' 'jostle check --update SCENARIO' needs to find what this check
    // found, such as {"--assets", DIR} when the assets were given on the command line.
    std::vector<std::string> update_options;
};

// A field that differs between the golden and this run at one dumped tick.
struct FieldChange {
    std::string entity;
    std::string field;     // "" when the entity itself is missing on one side
    std::string expected;  // "(absent)" when the golden lacks it
    std::string actual;    // "(absent)" when this run lacks it
};

struct ImageCheck {
    std::int64_t tick = 0;
    std::string golden_path;
    bool golden_missing = false;  // absent, or unreadable (golden_error says why)
    std::string golden_error;
    CompareResult compare;
    Image expected;  // empty when missing
    Image actual;
    bool passed() const { return !golden_missing && compare.within_tolerance; }
};

struct FailedExpectation {
    int line = 0;
    std::int64_t tick = 0;
    std::string expected;  // the directive as written
    std::string actual;
};

struct ScenarioCheck {
    std::string path;  // the .scn file
    std::string name;  // its file name without .scn
    std::string error; // bad input (exit 2): the message; the rest is then empty

    std::string trace_path;
    bool trace_missing = false;  // absent, or unreadable (trace_error says why)
    std::string trace_error;
    std::int64_t expected_ticks = 0;
    std::int64_t actual_ticks = 0;
    std::optional<std::int64_t> first_divergent_tick;
    std::uint64_t expected_hash = 0, actual_hash = 0;  // at the first divergent tick
    std::optional<std::int64_t> dump_tick;             // where `changes` were found
    std::vector<FieldChange> changes;

    std::vector<FailedExpectation> failed_expectations;
    std::int64_t expectations = 0;
    std::vector<ImageCheck> images;
    std::vector<std::string> stale_goldens;  // NAME.tick_T.png files no screenshot asks for
    double seconds = 0.0;

    std::string new_trace;  // this run's trace, for an update
    // The command that re-blesses this scenario, as the hints give it (shell-quoted where a
    // word needs it, in double quotes): jostle check --update --assets my_assets "wall #2.scn".
    std::string update_command;

    bool bad_input() const { return !error.empty(); }
    bool trace_passed() const { return !trace_missing && !first_divergent_tick && expected_ticks == actual_ticks; }
    bool passed() const;
    // What an update would change: the trace, images, stale files.
    bool goldens_differ() const;
};

// Replays one scenario and compares it with its goldens. Bad input (the scenario, its level,
// a malformed golden trace) is reported in `error`, never thrown.
ScenarioCheck check_scenario(const Game& game, const std::string& scenario_path, const CheckOptions& options = {});

// Rewrites the goldens of every check whose goldens differ: all new files are written to
// temporary files first, then renamed into place (and stale goldens removed) with SIGINT and
// SIGTERM held back, so an interrupted update changes nothing or everything. Returns one
// line per changed scenario saying what changed. Throws InputError when a file cannot be
// written, and Interrupted (interrupt.h) when a signal arrives while the temporary files are
// written; nothing is then changed and no temporary file is left. `on_staged` is called after
// each temporary file is written, with the golden's path.
std::vector<std::string> commit_updates(const std::vector<ScenarioCheck>& checks,
                                        const std::function<void(const std::string& golden)>& on_staged = {});

// A readable account of one check: PASS/FAIL line, then the details of every failure.
std::string describe_check(const ScenarioCheck& check);

// The scenarios named by `args`: files as they are, folders searched (not recursively) for
// *.scn, in name order. A scenario named twice, by any spelling of its folder (M/x.scn and
// M/./x.scn; a folder and a file in it), is listed once, where it first appears. Throws
// InputError for a path that does not exist.
std::vector<std::string> collect_scenarios(const std::vector<std::string>& args);

// Sharding, as Bazel and GoogleTest do it: TEST_TOTAL_SHARDS and TEST_SHARD_INDEX (or the
// GTEST_ names) choose every total-th scenario from the index; TEST_SHARD_STATUS_FILE is
// touched to say the protocol is understood. Returns the scenarios of this shard. Throws
// InputError on malformed variables.
std::vector<std::string> select_shard(const std::vector<std::string>& scenarios);

// The failure report under `folder`: report.html (per failing scenario: its first divergent
// tick and field changes, failed expectations, and expected / actual / diff images side by
// side), the images it shows, and junit.xml with every scenario. Written atomically; then an
// earlier report's images in the folder that this one does not show are removed.
void write_report(const std::string& folder, const std::vector<ScenarioCheck>& checks);
// Makes the report's folder (as write_report does, with its InputError), so that a --report
// that cannot be written is found before the scenarios are run.
void create_report_folder(const std::string& folder);

}  // namespace jostle
