// jostle/replay/replay.h: playing a scenario. The loop is the whole of it:
//
//   for tick in 0 .. ticks-1:
//       simulation.tick(scenario.input(tick))      the one place input enters the game
//       hash, check the expectations due now, keep a trace dump, render wanted frames
//
// Rendering only reads the simulation, so the hashes are the same with or without it.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "jostle/render/frame_output.h"
#include "jostle/render/png_io.h"
#include "jostle/replay/scenario.h"
#include "jostle/replay/simulation.h"

namespace jostle {

struct ReplayOptions {
    // Frames as PNG files in this folder (frame_NNNNNN.png, by tick), when not empty.
    std::string out_dir;
    FrameSelection frames;             // which ticks become frames (--frames, --every)
    int width = 0, height = 0;         // frame size; 0: the level's size (longer side at most kMaxFrameSide)
    DrawOptions draw;                  // overlay, HUD
    std::string sheet_path;            // a contact sheet of the selected frames, when not empty
    std::string anim_path;             // an animated PNG of the selected frames, when not empty
    bool keep_screenshots = false;     // render the scenario's screenshot ticks into the result
    int dump_every = 10;               // keep a readable dump every Nth tick (0: none)
    RenderBackend backend = RenderBackend::osmesa;
    // Called after every tick with (ticks done, ticks in all); for progress lines.
    std::function<void(std::int64_t, std::int64_t)> progress;
};

inline constexpr int kMaxSheetFrames = 64;

struct ExpectationResult {
    const Expectation* expectation = nullptr;
    bool passed = false;
    std::string actual;  // what was found, in words: "player is alive at (212.5, 80)", "count rock = 2"
};

struct TraceDump {
    std::int64_t tick = 0;
    std::vector<EntityDump> entities;
};

struct ReplayResult {
    std::int64_t ticks = 0;
    std::vector<std::uint64_t> hashes;            // the state hash after each tick
    std::vector<TraceDump> dumps;                 // every dump_every ticks, and the last tick
    std::vector<ExpectationResult> expectations;  // in the scenario's order
    std::vector<std::pair<std::int64_t, Image>> screenshots;  // when keep_screenshots
    std::int64_t frames_rendered = 0;
    std::vector<std::string> files_written;       // frames, sheet, animation
    double seconds = 0.0;                         // wall time of the whole replay
    bool expectations_passed() const;
};

// Plays `scenario` with `game`. Throws InputError when the level is bad, an expectation names
// a kind, variable, event or entity name the game does not have (before the first tick) or an
// entity no entity of the run has had by the expectation's tick (bullet_9 before the ninth
// shot), or an output cannot be written.
ReplayResult replay(const Game& game, const Scenario& scenario, const ReplayOptions& options = {});

// An expectation must name kinds, variables and events the game has, and an entity name the
// game can give in this run: a typo is bad input (InputError at source:line), not a failing
// check. replay() checks every expectation so, before the first tick.
void validate_expectation(const Expectation& e, const Simulation& sim, const std::string& source);

// An expectation about an entity (in, alive, gone) must name one that has lived in the run by
// the expectation's tick (Simulation::entity_named), checked at that tick: otherwise a typo
// would make `gone` pass and `alive` fail for the wrong reason. InputError at source:line.
void validate_entity_name(const Expectation& e, const Simulation& sim, const std::string& source);

// The trace file: the hash of every tick and the dumps, readable and diffable:
//   jostle-trace 1
//   ticks 120
//   dump-every 10
//   0 9f3c1a2b3c4d5e6f
//     player x=104.25 y=80 angle=0 vx=0 vy=0 ...
//     game score=0 ...
//   1 0d1c...
std::string format_trace(const ReplayResult& result, int dump_every);
// Reads a trace back into a ReplayResult's ticks, hashes and dumps. Throws InputError naming
// `source` and the line on malformed text.
ReplayResult parse_trace(std::string_view text, const std::string& source);

}  // namespace jostle
