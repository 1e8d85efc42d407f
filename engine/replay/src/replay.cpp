// replay.cpp: the replay loop, expectation checks, frame output and the trace format.
#include "jostle/replay/replay.h"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <utility>

#include "jostle/core/atomic_file.h"
#include "jostle/core/error.h"
#include "jostle/core/interrupt.h"
#include "jostle/core/text.h"
#include "jostle/render/animation.h"
#include "jostle/render/contact_sheet.h"
#include "jostle/render/renderer.h"

namespace jostle {
namespace {

std::string join(const std::vector<std::string>& names) {
    std::string out;
    for (const std::string& name : names) out += (out.empty() ? "" : ", ") + name;
    return out.empty() ? "none" : out;
}


ExpectationResult check(const Expectation& e, const Simulation& sim) {
    ExpectationResult r;
    r.expectation = &e;
    switch (e.kind) {
        case Expectation::Kind::in_region:
        case Expectation::Kind::alive:
        case Expectation::Kind::gone: {
            const std::optional<Vec2> at = sim.entity_position(e.name);
            if (!at) {
                r.passed = e.kind == Expectation::Kind::gone;
                r.actual = e.name + " is gone";
            } else {
                r.actual = e.name + " is alive at (" + shortest_text(at->x) + ", " + shortest_text(at->y) + ")";
                r.passed = e.kind == Expectation::Kind::alive ||
                           (e.kind == Expectation::Kind::in_region && at->x >= e.region.min.x && at->x <= e.region.max.x &&
                            at->y >= e.region.min.y && at->y <= e.region.max.y);
            }
            break;
        }
        case Expectation::Kind::count: {
            const std::int64_t n = sim.count(e.name);
            r.passed = compare(static_cast<double>(n), e.comparison, e.value);
            r.actual = "count " + e.name + " = " + std::to_string(n);
            break;
        }
        case Expectation::Kind::variable: {
            const double v = sim.variable(e.name).value_or(std::nan(""));
            r.passed = compare(v, e.comparison, e.value);
            r.actual = e.name + " = " + shortest_text(v);
            break;
        }
        case Expectation::Kind::event: {
            r.passed = sim.event_happened(e.name);
            r.actual = "event " + e.name + (r.passed ? " happened" : " has not happened");
            break;
        }
    }
    return r;
}

// Up to kMaxSheetFrames of the selected ticks, evenly spread.
std::vector<std::int64_t> sheet_ticks(const FrameSelection& frames, std::int64_t ticks) {
    std::vector<std::int64_t> selected;
    for (std::int64_t t = 0; t < ticks; ++t) {
        if (frames.contains(t)) selected.push_back(t);
    }
    if (selected.size() <= static_cast<std::size_t>(kMaxSheetFrames)) return selected;
    std::vector<std::int64_t> spread;
    const std::size_t n = selected.size();
    for (std::size_t i = 0; i < static_cast<std::size_t>(kMaxSheetFrames); ++i) {
        spread.push_back(selected[i * (n - 1) / (kMaxSheetFrames - 1)]);
    }
    return spread;
}

}  // namespace

void validate_expectation(const Expectation& e, const Simulation& sim, const std::string& source) {
    const char* what = nullptr;
    std::vector<std::string> known;
    if (e.kind == Expectation::Kind::count) {
        known = sim.kinds();
        what = "entity kind";
    } else if (e.kind == Expectation::Kind::variable) {
        known = sim.variables();
        what = "game variable";
    } else if (e.kind == Expectation::Kind::event) {
        known = sim.events();
        what = "event";
    } else {
        if (!sim.entity_name_possible(e.name)) {
            throw InputError(SourceLocation{source, e.line, e.column},
                             "unknown entity '" + e.name +
                                 "': no entity of this run can have that name (the dumps of 'jostle play --trace' name every entity)");
        }
        return;
    }
    if (std::find(known.begin(), known.end(), e.name) == known.end()) {
        throw InputError(SourceLocation{source, e.line, e.column},
                         std::string("unknown ") + what + " '" + e.name + "' (expected one of: " + join(known) + ")");
    }
}

void validate_entity_name(const Expectation& e, const Simulation& sim, const std::string& source) {
    if (e.kind != Expectation::Kind::in_region && e.kind != Expectation::Kind::alive && e.kind != Expectation::Kind::gone) return;
    if (sim.entity_named(e.name)) return;
    throw InputError(SourceLocation{source, e.line, e.column},
                     "no entity named '" + e.name + "' has been in the run by tick " + std::to_string(e.tick) +
                         " (a misspelt name? the dumps of 'jostle play --trace' name every entity)");
}

bool ReplayResult::expectations_passed() const {
    return std::all_of(expectations.begin(), expectations.end(), [](const ExpectationResult& r) { return r.passed; });
}

namespace {

// The frame: the options' size, else the level's, scaled down to kMaxFrameSide on its longer
// side when it is larger (a level may be up to 2e5 px wide; the camera fits it either way).
std::pair<int, int> frame_size(const ReplayOptions& options, Vec2 level) {
    if (options.width > 0 && options.height > 0) return {options.width, options.height};
    const float longer = std::max({level.x, level.y, 1.0f});
    const float scale = longer > static_cast<float>(kMaxFrameSide) ? static_cast<float>(kMaxFrameSide) / longer : 1.0f;
    const auto side = [&](float extent) {
        return std::clamp(static_cast<int>(std::lround(extent * scale)), 1, kMaxFrameSide);
    };
    return {side(level.x), side(level.y)};
}

}  // namespace

ReplayResult replay(const Game& game, const Scenario& scenario, const ReplayOptions& options) {
    const auto started = std::chrono::steady_clock::now();
    std::unique_ptr<Simulation> sim = game.start(scenario.level, scenario.seed, scenario.tick_rate);
    for (const Expectation& e : scenario.expectations) validate_expectation(e, *sim, scenario.source);

    ReplayResult result;
    result.ticks = scenario.ticks();
    result.hashes.reserve(static_cast<std::size_t>(result.ticks));

    // What to render, decided up front.
    const std::vector<std::int64_t> sheet = options.sheet_path.empty() ? std::vector<std::int64_t>{}
                                                                        : sheet_ticks(options.frames, result.ticks);
    const bool any_output = !options.out_dir.empty() || !options.anim_path.empty() || !sheet.empty() ||
                            (options.keep_screenshots && !scenario.screenshots.empty());
    std::unique_ptr<Renderer> renderer;
    std::unique_ptr<FrameWriter> writer;
    std::unique_ptr<AnimationWriter> animation;
    const Vec2 level = sim->level_size();
    const auto [width, height] = frame_size(options, level);
    // The level fits the frame, centred.
    Camera camera;
    camera.zoom = std::min(static_cast<float>(width) / std::max(level.x, 1.0f), static_cast<float>(height) / std::max(level.y, 1.0f));
    camera.origin = Vec2{level.x * 0.5f - static_cast<float>(width) * 0.5f / camera.zoom,
                         level.y * 0.5f - static_cast<float>(height) * 0.5f / camera.zoom};
    if (any_output) {
        renderer = std::make_unique<Renderer>(RendererDesc{.backend = options.backend});
        if (!options.out_dir.empty()) writer = std::make_unique<FrameWriter>(FrameWriterDesc{.folder = options.out_dir});
        if (!options.anim_path.empty()) {
            const std::int64_t every = std::min<std::int64_t>(options.frames.every(), 65535);
            animation = std::make_unique<AnimationWriter>(
                options.anim_path, AnimationDesc{.delay_num = static_cast<int>(every), .delay_den = scenario.tick_rate});
        }
    }
    // Each sheet frame is drawn into the sheet when rendered, not kept (64 frames at full size
    // were most of a play run's memory).
    std::optional<ContactSheetBuilder> sheet_builder;
    if (!sheet.empty()) sheet_builder.emplace(static_cast<int>(sheet.size()));
    std::size_t next_sheet = 0;
    std::size_t next_expectation = 0;
    std::size_t next_screenshot = 0;

    for (std::int64_t t = 0; t < result.ticks; ++t) {
        throw_if_interrupted();  // between ticks: finished frames are whole files, the rest are not started
        sim->tick(scenario.input(t));
        result.hashes.push_back(sim->state_hash());
        while (next_expectation < scenario.expectations.size() && scenario.expectations[next_expectation].tick == t) {
            validate_entity_name(scenario.expectations[next_expectation], *sim, scenario.source);
            result.expectations.push_back(check(scenario.expectations[next_expectation], *sim));
            ++next_expectation;
        }
        if (options.dump_every > 0 && (t % options.dump_every == 0 || t == result.ticks - 1)) {
            result.dumps.push_back(TraceDump{t, sim->dump()});
        }

        const bool to_files = writer && options.frames.contains(t);
        const bool to_animation = animation && options.frames.contains(t);
        const bool to_sheet = next_sheet < sheet.size() && sheet[next_sheet] == t;
        bool to_screenshot = false;
        while (options.keep_screenshots && next_screenshot < scenario.screenshots.size() &&
               scenario.screenshots[next_screenshot].tick == t) {
            to_screenshot = true;
            ++next_screenshot;
        }
        if (to_files || to_animation || to_sheet || to_screenshot) {
            renderer->begin_frame(width, height, Color{0, 0, 0, 255}, camera);
            sim->draw(*renderer, options.draw);
            const Image& image = renderer->end_frame();
            ++result.frames_rendered;
            if (to_animation) animation->add(image);
            if (to_sheet) {
                sheet_builder->add(t, image);
                ++next_sheet;
            }
            if (to_screenshot) result.screenshots.emplace_back(t, image);
            if (to_files) writer->write(t, image);  // last: it takes a copy for its thread
        }
        if (options.progress) options.progress(t + 1, result.ticks);
    }

    if (writer) {
        writer->finish();
        for (const std::string& path : writer->written()) result.files_written.push_back(path);
    }
    if (animation) {
        if (animation->frames_added() > 0) {
            animation->finish();
            result.files_written.push_back(options.anim_path);
        }
    }
    if (next_sheet > 0) {
        write_png_atomic(options.sheet_path, sheet_builder->finish());
        result.files_written.push_back(options.sheet_path);
    }
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    return result;
}

// ---------------------------------------------------------------------------------------
// Traces
// ---------------------------------------------------------------------------------------

std::string format_trace(const ReplayResult& result, int dump_every) {
    std::string out = "jostle-trace 1\nticks " + std::to_string(result.ticks) + "\ndump-every " +
                      std::to_string(dump_every) + "\n";
    std::size_t next_dump = 0;
    for (std::size_t t = 0; t < result.hashes.size(); ++t) {
        out += std::to_string(t) + " " + hex16(result.hashes[t]) + "\n";
        while (next_dump < result.dumps.size() && result.dumps[next_dump].tick == static_cast<std::int64_t>(t)) {
            for (const EntityDump& entity : result.dumps[next_dump].entities) {
                out += "  " + entity.name;
                for (const StateField& field : entity.fields) out += " " + field.name + "=" + field.value;
                out += "\n";
            }
            ++next_dump;
        }
    }
    return out;
}

ReplayResult parse_trace(std::string_view text, const std::string& source) {
    ReplayResult result;
    int line_number = 0;
    std::size_t at = 0;
    auto fail = [&](const std::string& what) -> void { throw InputError(SourceLocation{source, line_number, 0}, what); };
    auto next_line = [&](std::string_view* line) {
        if (at >= text.size()) return false;
        std::size_t end = text.find('\n', at);
        if (end == std::string_view::npos) {
            ++line_number;
            fail("truncated file: the last line has no newline (if the file is whole, end it with one)");
        }
        *line = text.substr(at, end - at);
        at = end + 1;
        ++line_number;
        return true;
    };
    auto header = [&](std::string_view key) -> std::int64_t {
        std::string_view line;
        if (!next_line(&line)) fail("truncated file: expected '" + std::string(key) + " N'");
        std::int64_t value = -1;
        if (line.substr(0, key.size() + 1) != std::string(key) + " " ||
            std::from_chars(line.data() + key.size() + 1, line.data() + line.size(), value).ptr != line.data() + line.size() ||
            value < 0) {
            fail("expected '" + std::string(key) + " N', got '" + std::string(line) + "'");
        }
        return value;
    };
    std::string_view line;
    if (!next_line(&line) || line != "jostle-trace 1") fail("expected 'jostle-trace 1' as the first line");
    result.ticks = header("ticks");
    header("dump-every");
    while (next_line(&line)) {
        if (line.substr(0, 2) == "  ") {
            if (result.hashes.empty()) fail("an entity line before the first tick line");
            const std::int64_t tick = static_cast<std::int64_t>(result.hashes.size()) - 1;
            if (result.dumps.empty() || result.dumps.back().tick != tick) result.dumps.push_back(TraceDump{tick, {}});
            EntityDump entity;
            std::size_t i = 2;
            auto word = [&]() {
                const std::size_t start = i;
                while (i < line.size() && line[i] != ' ') ++i;
                std::string_view w = line.substr(start, i - start);
                if (i < line.size()) ++i;
                return w;
            };
            entity.name = std::string(word());
            while (i < line.size()) {
                const std::string_view field = word();
                const std::size_t eq = field.find('=');
                if (eq == std::string_view::npos) fail("expected NAME=VALUE, got '" + std::string(field) + "'");
                entity.fields.push_back(StateField{std::string(field.substr(0, eq)), std::string(field.substr(eq + 1))});
            }
            result.dumps.back().entities.push_back(std::move(entity));
            continue;
        }
        const std::size_t space = line.find(' ');
        std::int64_t tick = -1;
        std::uint64_t hash = 0;
        if (space == std::string_view::npos ||
            std::from_chars(line.data(), line.data() + space, tick).ptr != line.data() + space ||
            line.size() - space - 1 != 16 ||
            std::from_chars(line.data() + space + 1, line.data() + line.size(), hash, 16).ptr != line.data() + line.size()) {
            fail("expected 'TICK HASH' (a tick number and 16 hex digits), got '" + std::string(line) + "'");
        }
        if (tick != static_cast<std::int64_t>(result.hashes.size())) {
            fail("expected tick " + std::to_string(result.hashes.size()) + ", got " + std::to_string(tick));
        }
        result.hashes.push_back(hash);
    }
    if (static_cast<std::int64_t>(result.hashes.size()) != result.ticks) {
        fail("truncated file: " + std::to_string(result.hashes.size()) + " tick lines, the header says " +
             std::to_string(result.ticks));
    }
    return result;
}

}  // namespace jostle
