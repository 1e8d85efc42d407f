// `jostle play`: argument parsing, progress and the summary; the replay loop itself is
// engine/replay (jostle/replay/replay.h).
#include "play.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <system_error>
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "arena.h"
#include "cli.h"
#include "jostle/core/atomic_file.h"
#include "jostle/core/error.h"
#include "jostle/core/interrupt.h"
#include "jostle/core/text.h"
#include "jostle/render/renderer.h"
#include "jostle/replay/replay.h"

namespace jostle {
namespace {

int usage(std::ostream& err, const std::string& message) {
    err << "jostle play: " << message << "\nRun 'jostle play --help' for usage.\n";
    return 2;
}

// "640x480" -> {640, 480}, sides in 1..kMaxFrameSide.
std::optional<std::pair<int, int>> parse_size(std::string_view text) {
    const std::size_t x = text.find('x');
    if (x == std::string_view::npos) return std::nullopt;
    const auto w = game::parse_whole(text.substr(0, x), 1, kMaxFrameSide);
    const auto h = game::parse_whole(text.substr(x + 1), 1, kMaxFrameSide);
    if (!w || !h) return std::nullopt;
    return std::pair<int, int>{static_cast<int>(*w), static_cast<int>(*h)};
}

// An output that would replace the scenario, another output or a frame file: refused before
// the run (each write is atomic, but the run would still lose the file). "" when none.
std::string output_clash(const std::string& scenario, const ReplayOptions& options, const std::string& trace) {
    const std::pair<const char*, const std::string*> outputs[] = {
        {"--trace", &trace}, {"--sheet", &options.sheet_path}, {"--anim", &options.anim_path}};
    for (std::size_t i = 0; i < std::size(outputs); ++i) {
        const auto& [flag, path] = outputs[i];
        if (path->empty()) continue;
        if (same_file(*path, scenario)) return std::string(flag) + ": '" + *path + "' is the scenario being played; give another path";
        for (std::size_t j = 0; j < i; ++j) {
            if (same_file(*path, *outputs[j].second)) {
                return std::string(outputs[j].first) + " and " + flag + " name the same file '" + *path + "'; give each its own";
            }
        }
        // frame_NNNNNN.png in the --out folder is a frame's name.
        if (!options.out_dir.empty()) {
            const std::filesystem::path p(*path);
            const std::string name = p.filename().string();
            const bool frame_name = name.size() >= 16 && name.starts_with("frame_") && name.ends_with(".png") &&
                                    std::all_of(name.begin() + 6, name.end() - 4, [](char c) { return c >= '0' && c <= '9'; });
            std::error_code ea, eb;
            // (Canonical without a trailing separator: "out/" and "out" are one folder.)
            const auto folder_of = [](const std::filesystem::path& f, std::error_code& ec) {
                const std::filesystem::path c = std::filesystem::weakly_canonical(std::filesystem::absolute(f, ec), ec);
                return c.has_filename() ? c : c.parent_path();
            };
            const std::filesystem::path folder = p.has_parent_path() ? p.parent_path() : std::filesystem::path(".");
            if (frame_name && folder_of(folder, ea) == folder_of(options.out_dir, eb) && !ea && !eb) {
                return std::string(flag) + ": '" + *path + "' is a frame's name in the --out folder; give another path";
            }
        }
    }
    return "";
}

std::string ratio_text(double v) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.1f", v);
    return buffer;
}

}  // namespace

std::string_view play_help() {
    return R"(usage: jostle play SCENARIO [--out DIR] [--frames LIST] [--every N] [--size WxH] [--overlay]
                   [--no-hud] [--sheet FILE] [--anim FILE] [--trace FILE] [--dump-every N]
                   [--quiet] [--assets DIR]

Replays a scenario of the arena game: the level, the seed and the input of every tick come
from the file, so every run is the same run. Without an output option it only simulates, as
fast as it can (--frames, --every, --size, --overlay and --no-hud shape the images of --out,
--sheet and --anim: without one of those they are a note on stderr). At the end it prints a
summary: ticks, expectations passed, time, speed.

options:
  --out DIR         write frames as DIR/frame_NNNNNN.png (the tick number, zero-padded); not
                    the assets' levels or sprites folder (the frames would be sprites)
  --frames LIST     which ticks become frames: all (default), 120, 10-20, 300- (to the end),
                    or a comma-separated list of numbers and ranges (120,200-240)
  --every N         keep every Nth frame of each range (default 1)
  --size WxH        frame size in pixels, sides 1 to 8192 (default: the level's size, scaled
                    down to 8192 on its longer side; the level is scaled to fit and centred)
  --overlay         draw the debug overlay: colliders, contacts and MTD arrows, paths
  --no-hud          leave out the score and tick line
  --sheet FILE      write a contact sheet (a PNG grid) of the selected frames, at most 64
                    spread evenly over them
  --anim FILE       write an animated PNG of the selected frames (plays in any browser)
  --trace FILE      write the state hash of every tick, with a readable dump of every
                    entity every --dump-every ticks (default 10) and at the last tick
  --dump-every N    see --trace
  --quiet           no progress line and no summary
  --assets DIR      where the levels are (default: $JOSTLE_ASSETS, else the source tree's)
  --                what follows is the scenario, even if it starts with '-'

Files are written atomically: an interrupted run never leaves a half-written file. An output
named /dev/stdout (/dev/fd/1) goes to standard output itself, which then holds it alone (the
summary goes to stderr), and after >> it is appended; --anim needs a file it can patch, not a
pipe or >>, and says so before the run.
Ctrl-C (SIGTERM, SIGHUP) stops between ticks: frames already written are complete, an unfinished
animation, sheet or trace is not written (but for one sent to a descriptor or pipe, which has
its bytes as they are made).

exit status: 0 the run's expectations passed, 1 one failed, 2 bad usage or bad input (or
standard output could not be written: the files written are complete), 130 (143, 129)
stopped by Ctrl-C (SIGTERM, SIGHUP).
)";
}

int play_command(std::span<const std::string_view> args, std::ostream& out, std::ostream& err) {
    std::string scenario_path;
    ReplayOptions options;
    std::string frames_text = "all";
    std::int64_t every = 1;
    std::string trace_path;
    bool quiet = false;
    std::string assets = game::default_assets_dir();
    bool options_ended = false;  // after "--", a scenario named "-x.scn" is a scenario
    // The options that only shape images (frames, sheet, animation), and whether each was given.
    constexpr std::string_view kImageOptions[] = {"--frames", "--every", "--size", "--overlay", "--no-hud"};
    bool image_option_given[std::size(kImageOptions)] = {};
    bool dump_every_given = false;
    const auto given = [&](std::string_view option) {
        for (std::size_t k = 0; k < std::size(kImageOptions); ++k) image_option_given[k] |= option == kImageOptions[k];
        dump_every_given |= option == "--dump-every";
    };
    game::OnceOnly once;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string_view a = args[i];
        const bool option = !options_ended && a.size() > 1 && a.front() == '-';
        if (option && a == "--") {
            options_ended = true;
        } else if (!option) {
            if (a.empty()) return usage(err, "expected a scenario file, got an empty argument");
            if (!scenario_path.empty()) return usage(err, "expected one scenario, got a second: '" + std::string(a) + "'");
            scenario_path = std::string(a);
        } else if (a == "--overlay") {
            options.draw.overlay = true;
            given(a);
        } else if (a == "--no-hud") {
            options.draw.hud = false;
            given(a);
        } else if (a == "--quiet") {
            quiet = true;
        } else if (a == "--out" || a == "--frames" || a == "--every" || a == "--size" || a == "--sheet" ||
                   a == "--anim" || a == "--trace" || a == "--dump-every" || a == "--assets") {
            std::string_view v;
            if (std::string e = game::option_value(args, i, a, v); !e.empty()) return usage(err, e);
            if (std::string e = once.take(a); !e.empty()) return usage(err, e);
            given(a);
            if (a == "--out") options.out_dir = std::string(v);
            if (a == "--frames") frames_text = std::string(v);
            if (a == "--sheet") options.sheet_path = std::string(v);
            if (a == "--anim") options.anim_path = std::string(v);
            if (a == "--trace") trace_path = std::string(v);
            if (a == "--assets") assets = std::string(v);
            if (a == "--every") {
                const auto n = game::parse_whole(v, 1, 1'000'000);
                if (!n) return usage(err, game::whole_number_error("--every", 1, 1000000, v));
                every = static_cast<std::int64_t>(*n);
            }
            if (a == "--dump-every") {
                const auto n = game::parse_whole(v, 1, 1'000'000);
                if (!n) return usage(err, game::whole_number_error("--dump-every", 1, 1000000, v));
                options.dump_every = static_cast<int>(*n);
            }
            if (a == "--size") {
                const auto size = parse_size(v);
                if (!size) return usage(err, "--size: expected WIDTHxHEIGHT with sides from 1 to 8192, got '" + std::string(v) + "'");
                options.width = size->first;
                options.height = size->second;
            }
        } else if (a == "--help" || a == "-h") {  // anywhere an option may stand, as right after the command
            out << play_help();
            return 0;
        } else {
            return usage(err, "unknown option '" + std::string(a) + "'");
        }
    }
    if (scenario_path.empty()) return usage(err, "expected a scenario file");
    if (const std::string clash = output_clash(scenario_path, options, trace_path); !clash.empty()) return usage(err, clash);
    std::string selection_error;
    const std::optional<FrameSelection> selection = FrameSelection::parse(frames_text, &selection_error);
    if (!selection) return usage(err, "--frames: " + selection_error);
    options.frames = *selection;
    options.frames.set_every(every);
    if (trace_path.empty() && dump_every_given && !quiet) {
        err << "jostle play: note: --dump-every has no effect without --trace\n";
    }
    if (options.out_dir.empty() && options.sheet_path.empty() && options.anim_path.empty() && !quiet) {
        std::vector<std::string_view> unused;
        for (std::size_t k = 0; k < std::size(kImageOptions); ++k) {
            if (image_option_given[k]) unused.push_back(kImageOptions[k]);
        }
        if (!unused.empty()) {
            err << "jostle play: note: ";
            for (std::size_t k = 0; k < unused.size(); ++k) {
                err << (k == 0 ? "" : k + 1 == unused.size() ? " and " : ", ") << unused[k];
            }
            err << (unused.size() == 1 ? " has" : " have") << " no effect without --out, --sheet or --anim\n";
        }
    }
    if (trace_path.empty()) options.dump_every = 0;

    try {
        const game::ArenaGame game(assets);
        // Frames in the sprites folder would be new sprites (and change every level-hash).
        if (const std::string folder = options.out_dir.empty() ? "" : game.asset_folder(options.out_dir); !folder.empty()) {
            return usage(err, "--out: '" + options.out_dir + "' " + folder + "; give another folder");
        }
        for (const auto& [flag, path] : {std::pair{"--trace", &trace_path}, std::pair{"--sheet", &options.sheet_path},
                                         std::pair{"--anim", &options.anim_path}}) {
            if (const std::string asset = game.asset_named(*path); !asset.empty()) {
                return usage(err, std::string(flag) + ": '" + *path + "' " + asset + "; give another path");
            }
        }
        // A trace or sheet path that cannot be written to is said now, not after the run (the
        // animation's file and the frame folder are made when the run starts). One in a folder
        // that does not exist yet waits for the end when there is an --out folder: the run may
        // be making that folder.
        for (const std::string* path : {&trace_path, &options.sheet_path}) {
            if (path->empty()) continue;
            std::error_code ec;
            const std::filesystem::path parent = std::filesystem::path(*path).parent_path();
            if (!options.out_dir.empty() && !parent.empty() && !std::filesystem::exists(parent, ec)) continue;
            check_writable(*path);
        }
        const Scenario scenario = load_scenario(scenario_path, game.vocabulary());
        const std::string hash = game.level_hash(scenario.level);
        if (hash != scenario.level_hash && !quiet) {
            err << "jostle play: note: " << scenario_path << ": level '" << scenario.level
                << "' has changed since the scenario was recorded (level-hash " << scenario.level_hash << ", now "
                << hash << ")\n";
        }
        // A progress line on a terminal, at most ten times a second.
        const bool progress = !quiet && ::isatty(2) == 1;
        auto last_shown = std::chrono::steady_clock::now();
        if (progress) {
            options.progress = [&](std::int64_t done, std::int64_t total) {
                const auto now = std::chrono::steady_clock::now();
                if (done != total && now - last_shown < std::chrono::milliseconds(100)) return;
                last_shown = now;
                err << "\rtick " << done << " / " << total << " (" << done * 100 / total << "%)" << std::flush;
                if (done == total) err << "\r\033[K" << std::flush;
            };
        }
        const ReplayResult result = [&] {
            try {
                return replay(game, scenario, options);
            } catch (const Interrupted&) {
                if (progress) err << "\n";  // keep the progress line; main says what happened
                throw;
            }
        }();
        if (!trace_path.empty()) write_file_atomic(trace_path, format_trace(result, options.dump_every));

        std::int64_t passed = 0;
        for (const ExpectationResult& r : result.expectations) {
            if (r.passed) {
                ++passed;
                continue;
            }
            const Expectation& e = *r.expectation;
            err << "jostle play: " << scenario_path << ":" << e.line << ": expectation failed at tick " << e.tick << ": expected "
                << e.text << ", found " << r.actual << "\n";
        }
        // An output asked for and not written says so, --quiet or not (the --out folder too,
        // made but left empty).
        std::int64_t frames = 0;
        for (const std::string& path : result.files_written) frames += path != options.sheet_path && path != options.anim_path;
        const std::string why_none = result.ticks == 0 ? std::string("the run has no ticks")
                                                       : "--frames " + frames_text + " selects no tick of this run (ticks 0 to " +
                                                             std::to_string(result.ticks - 1) + ")";
        for (const std::string* path : {&options.sheet_path, &options.anim_path}) {
            if (!path->empty() && std::find(result.files_written.begin(), result.files_written.end(), *path) == result.files_written.end()) {
                err << "jostle play: note: " << *path << " not written: " << why_none << "\n";
            }
        }
        if (!options.out_dir.empty() && frames == 0) err << "jostle play: note: no frames in " << options.out_dir << ": " << why_none << "\n";
        // A file sent to standard output keeps it to itself (text after a trace's last line
        // or a PNG's last chunk would make it unreadable): the summary goes to stderr then.
        std::ostream& summary = [&]() -> std::ostream& {
            for (const std::string* path : {&trace_path, &options.sheet_path, &options.anim_path}) {
                if (!path->empty() && same_file(*path, "/dev/stdout")) return err;
            }
            return out;
        }();
        if (!quiet) {
            summary << "played " << scenario_path << ": " << counted(result.ticks, "tick") << ", " << passed << "/"
                    << counted(static_cast<std::int64_t>(result.expectations.size()), "expectation") << " passed, "
                    << ratio_text(result.seconds) << " s ("
                    << ratio_text(static_cast<double>(result.ticks) / std::max(result.seconds, 1e-9)) << " ticks/s)";
            if (result.frames_rendered > 0) {
                summary << ", " << counted(result.frames_rendered, "frame") << " rendered ("
                        << ratio_text(static_cast<double>(result.frames_rendered) / std::max(result.seconds, 1e-9))
                        << " frames/s)";
            }
            summary << "\n";
            // Only what was written: a frame selection past the end of the run writes nothing.
            const auto wrote = [&](const std::string& path) {
                return std::find(result.files_written.begin(), result.files_written.end(), path) != result.files_written.end();
            };
            if (!options.out_dir.empty()) {
                summary << "frames: " << frames << " in " << options.out_dir << (options.out_dir.ends_with('/') ? "" : "/") << "\n";
            }
            if (wrote(options.sheet_path)) summary << "contact sheet: " << options.sheet_path << "\n";
            if (wrote(options.anim_path)) summary << "animation: " << options.anim_path << "\n";
            if (!trace_path.empty()) summary << "trace: " << trace_path << "\n";
        }
        return result.expectations_passed() ? 0 : 1;
    } catch (const InputError& e) {
        err << "jostle play: " << e.what() << '\n';
        return 2;
    }
}

}  // namespace jostle
