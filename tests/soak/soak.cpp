// soak: plays a level for a long time (1,000,000 ticks by default) driven by a seeded random
// bot, twice side by side, and checks what a long unattended run must keep true:
//   - every entity's position, angle and velocities stay finite, and its position stays in
//     the level's rectangle (checked every tick);
//   - the two runs give the same state hash at every checkpoint (every 10,000 ticks);
//   - memory does not grow: resident memory at the end is within 1 MiB of what it was at
//     the first checkpoint after the warm-up (a tenth of the run).
// (Not under AddressSanitizer, whose quarantine holds freed memory.)
// It prints one line per checkpoint (tick, hash, entities, resident kB) and, with --hashes,
// writes the checkpoint hashes to a file, so runs from different builds can be compared
// line for line. Exit 0: all held; 1: a check failed (the message says which, where, when);
// 2: bad command line.
#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "arena.h"
#include "cli.h"
#include "jostle/core/rng.h"
#include "jostle/replay/simulation.h"

namespace {

// AddressSanitizer keeps freed memory in quarantine (up to 256 MB), so resident memory grows
// under it whatever the program does: the growth check is for ordinary builds (LeakSanitizer
// checks leaks in that build).
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kMeasureGrowth = false;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kMeasureGrowth = false;
#else
constexpr bool kMeasureGrowth = true;
#endif
#else
constexpr bool kMeasureGrowth = true;
#endif

constexpr const char* kUsage =
    "usage: soak [--ticks N] [--seed S] [--every K] [--level NAME] [--assets DIR] [--hashes FILE]\n"
    "  --ticks N     ticks to play (default 1000000, at most 100000000)\n"
    "  --seed S      the bot's and the world's seed (default 1)\n"
    "  --every K     ticks between checkpoints (default 10000)\n"
    "  --level NAME  the level (default demo)\n"
    "  --assets DIR  the assets folder (default: $JOSTLE_ASSETS or the source tree's)\n"
    "  --hashes FILE also write 'tick hash' per checkpoint to FILE\n";

struct Options {
    std::int64_t ticks = 1'000'000;
    std::uint64_t seed = 1;
    std::int64_t every = 10'000;
    std::string level = "demo";
    std::string assets;
    std::string hashes;
};

[[noreturn]] void usage_error(const std::string& message) {
    std::cerr << "soak: " << message << "\n" << kUsage;
    std::exit(2);
}

// The jostle command line's rules (game/cli.h): a value that is another option, a value option
// given twice and a number with a sign or past its range are usage errors.
std::int64_t whole_number(std::string_view flag, std::string_view text, std::uint64_t lo, std::uint64_t hi) {
    const auto n = jostle::game::parse_whole(text, lo, hi);
    if (!n) usage_error(jostle::game::whole_number_error(flag, lo, hi, text));
    return static_cast<std::int64_t>(*n);
}

Options parse(int argc, char** argv) {
    Options o;
    const std::vector<std::string_view> args(argv + 1, argv + argc);
    jostle::game::OnceOnly once;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string_view flag = args[i];
        if (flag == "--help" || flag == "-h") {
            std::cout << kUsage;
            std::exit(0);
        }
        if (flag != "--ticks" && flag != "--seed" && flag != "--every" && flag != "--level" && flag != "--assets" &&
            flag != "--hashes") {
            usage_error("unknown option '" + std::string(flag) + "'");
        }
        std::string_view value;
        if (std::string e = jostle::game::option_value(args, i, flag, value); !e.empty()) usage_error(e);
        if (std::string e = once.take(flag); !e.empty()) usage_error(e);
        if (flag == "--ticks") o.ticks = whole_number(flag, value, 1, 100'000'000);
        if (flag == "--seed") o.seed = static_cast<std::uint64_t>(whole_number(flag, value, 0, INT64_MAX));
        if (flag == "--every") o.every = whole_number(flag, value, 1, 100'000'000);
        if (flag == "--level") o.level = std::string(value);
        if (flag == "--assets") o.assets = std::string(value);
        if (flag == "--hashes") o.hashes = std::string(value);
    }
    if (o.assets.empty()) o.assets = jostle::game::default_assets_dir();
    return o;
}

// Resident memory in kB (VmRSS of /proc/self/status), or -1 where there is none.
long resident_kb() {
    std::ifstream in("/proc/self/status");
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
    }
    return -1;
}

// The bot: holds a random set of actions for a random 1..90 ticks, then draws again. Fire is
// in about half the draws, so bullets and ricochets stay frequent over the whole run.
class Bot {
public:
    explicit Bot(std::uint64_t seed) : rng_(seed, 0x50a6u) {}
    jostle::InputFrame next() {
        if (left_ == 0) {
            held_ = rng_.next_u32() & ((1u << jostle::game::kActionCount) - 1u);
            left_ = 1 + static_cast<int>(rng_.below(90));
        }
        --left_;
        return jostle::InputFrame{held_};
    }

private:
    jostle::Rng rng_;
    std::uint32_t held_ = 0;
    int left_ = 0;
};

// Why the world's state is bad, or empty: a non-finite field or a position outside the level.
std::string bad_entity(const jostle::Simulation& sim) {
    const jostle::World& world = sim.world();
    const jostle::Vec2 size = sim.level_size();
    for (const jostle::EntityId id : world.entities()) {
        const jostle::EntityDesc* e = world.get(id);
        const bool finite = std::isfinite(e->position.x) && std::isfinite(e->position.y) && std::isfinite(e->angle) &&
                            std::isfinite(e->velocity.x) && std::isfinite(e->velocity.y) &&
                            std::isfinite(e->angular_velocity);
        const bool inside = e->position.x >= 0.0f && e->position.x <= size.x && e->position.y >= 0.0f &&
                            e->position.y <= size.y;
        if (finite && inside) continue;
        char text[200];
        std::snprintf(text, sizeof text, "entity (slot %u, user data %llu) at (%g, %g), velocity (%g, %g), angle %g: %s",
                      id.index, static_cast<unsigned long long>(e->user_data), e->position.x, e->position.y,
                      e->velocity.x, e->velocity.y, e->angle,
                      finite ? "outside the level" : "a field is not finite");
        return text;
    }
    return {};
}

}  // namespace

int main(int argc, char** argv) {
    const Options o = parse(argc, argv);
    std::unique_ptr<std::ofstream> hashes;
    try {
        const jostle::game::ArenaGame game(o.assets);
        std::unique_ptr<jostle::Simulation> runs[2] = {game.start(o.level, o.seed, 60), game.start(o.level, o.seed, 60)};
        if (!o.hashes.empty()) {
            hashes = std::make_unique<std::ofstream>(o.hashes);
            if (!*hashes) usage_error("cannot write '" + o.hashes + "'");
        }
        Bot bot(o.seed);
        const std::int64_t warmup = std::max<std::int64_t>(o.every, o.ticks / 10);
        long baseline_kb = -1;
        long last_kb = -1;
        std::printf("soak: level %s, seed %llu, %lld ticks, checkpoints every %lld\n", o.level.c_str(),
                    static_cast<unsigned long long>(o.seed), static_cast<long long>(o.ticks),
                    static_cast<long long>(o.every));
        for (std::int64_t tick = 1; tick <= o.ticks; ++tick) {
            const jostle::InputFrame input = bot.next();
            for (auto& run : runs) run->tick(input);
            if (const std::string bad = bad_entity(*runs[0]); !bad.empty()) {
                std::printf("soak: FAILED at tick %lld: %s\n", static_cast<long long>(tick), bad.c_str());
                return 1;
            }
            if (tick % o.every != 0 && tick != o.ticks) continue;
            const std::uint64_t hash = runs[0]->state_hash();
            const std::uint64_t other = runs[1]->state_hash();
            last_kb = resident_kb();
            if (baseline_kb < 0 && tick >= warmup) baseline_kb = last_kb;
            std::printf("tick %9lld  hash %016llx  entities %4zu  resident %6ld kB\n", static_cast<long long>(tick),
                        static_cast<unsigned long long>(hash), runs[0]->world().entity_count(), last_kb);
            std::fflush(stdout);
            if (hashes) *hashes << tick << ' ' << std::hex << hash << std::dec << '\n';
            if (hash != other) {
                std::printf("soak: FAILED at tick %lld: the second run's hash is %016llx\n", static_cast<long long>(tick),
                            static_cast<unsigned long long>(other));
                return 1;
            }
        }
        if (hashes && !hashes->flush()) usage_error("cannot write '" + o.hashes + "'");
        const long growth = baseline_kb >= 0 && last_kb >= 0 ? last_kb - baseline_kb : 0;
        std::printf("soak: %lld ticks, 2 runs agree at every checkpoint, all entities finite and inside, "
                    "resident memory %ld kB after the warm-up and %ld kB at the end (growth %ld kB)\n",
                    static_cast<long long>(o.ticks), baseline_kb, last_kb, growth);
        if (!kMeasureGrowth) {
            std::printf("soak: memory growth not judged under AddressSanitizer (its quarantine keeps freed memory)\n");
        } else if (growth > 1024) {
            std::printf("soak: FAILED: memory grew by %ld kB (more than 1024)\n", growth);
            return 1;
        }
        return 0;
    } catch (const std::exception& e) {
        std::cerr << "soak: " << e.what() << '\n';
        return 2;
    }
}
