// world_bench.cpp: the world module's benchmarks (Google Benchmark): the broadphase's candidate
// pairs, a world stress scene and replaying the demo scenario. Speed is only measured here,
// never asserted.
//
// Conventions as in render_bench.cpp: names are BM_<Family>/<size...>/<variant>, the anchor of
// a family is registered first and labelled "anchor", and tools/bench-ratios turns the JSON
// output into a table of candidate/anchor ratios (a family without an anchor shows times only).
// Times are wall-clock (UseRealTime) in ms per iteration; on a shared 2-core machine they drift,
// ratios measured in the same run hold up better. A failed setup or sanity check ends the
// benchmark with SkipWithError ("ERROR OCCURRED"), which the ctest smoke test looks for.
//
// The families, what they compare and why the inputs are fair:
//
// BM_Broadphase/<n>/<variant>, n = 1,000, 10,000, 20,000 moving boxes. One iteration is one
//   step: every box moves (bouncing off the area's edges) and the algorithm produces the full,
//   sorted list of pairs whose tight AABBs overlap (touching counts). Variants:
//     brute_force     (anchor) every pair tested, O(n^2).
//     tree            jostle's own broadphase, detail::Broadphase (engine/world/src/broadphase.h,
//                     used directly: b2DynamicTree proxies with fattened bounds, re-inserted only
//                     when a box leaves its fat bounds, as World::step does, the tree catching
//                     up at the first query of a step and never scanning); one query per box
//                     as World::step makes, but with the tight bounds and pairs kept when the
//                     tight boxes overlap (the World keeps every fat-bounds overlap: a superset).
//     sort_and_sweep  written here: boxes kept sorted by min x across steps (insertion sort,
//                     nearly sorted after one step), then a sweep along x testing y.
//   Brute force and the sweep test a candidate without a branch on the (unpredictable)
//   outcome of each comparison; the tree's query is Box2D's own code.
//   All three see the same seeded boxes (sizes 4..16 px, speeds up to 120 px/s per axis) in a
//   square whose side grows with sqrt(n), so every n has the same density (about 3 neighbours
//   per box, 1.5 pairs per box), and all produce the same list: checked on the first steps
//   against brute force before timing (SkipWithError otherwise). Each sorts its pairs the
//   same way (std::sort of 64-bit keys; brute force finds them in order). Target: 10,000
//   boxes in <= 1 ms per step.
//
// BM_WorldStress/<n>/<variant>, n = 1,000, 2,000, 5,000, 10,000 mixed dynamic bodies (circles,
//   boxes, line segments, convex quads; 1 in 20 large) in a 1024x768 arena walled by four
//   static boxes, no gravity, restitution 0.8. The bodies spin slowly, and every K = 15 steps
//   each body (staggered, so 1/15 of them per step) gets its collider re-set at a slowly
//   changing scale (the world has no scale) and its speed restored to its own (the direction
//   kept: a game's movers; without this the scene would settle and later iterations would time
//   a resting world). Only the engine's step is timed (the re-sets are paused out). Each scene
//   is made once per program run and warmed up for 1,000 steps (the scene gathers contacts,
//   bodies bunching up, for about that long before it settles), then keeps running: each run
//   of the benchmark times exactly the next 120 steps (a fixed iteration count), so both
//   engines time the same stretches of the scene's life. Variants:
//     box2d   (anchor) Box2D 2.4.1's b2World of the same scene (8 px per metre, same bodies,
//             velocities, materials and schedule; fixedRotation, so contacts leave spin alone
//             as in jostle; 8 velocity and 3 position iterations, sleeping off, continuous
//             physics on as by default (time of impact against the walls); Box2D has no
//             edge-edge contacts and uses warm starting: not the same solver, the same scene).
//     jostle  World::step (8 velocity passes, up to 16 relaxation passes).
//   Sanity: no body may leave the arena (SkipWithError). Target: 10,000 bodies <= 8 ms/step.
//
// BM_Replay/demo/<variant>: assets/scenarios/demo.scn (2,280 ticks) replayed without rendering
//   through replay() with game::ArenaGame; counters ticks/s and x_realtime (ticks/s over the
//   scenario's 60 ticks/s). No anchor: nothing else plays the game. Variants: no_dumps
//   (dump_every 0) and dumps (the default, a readable dump every 10 ticks, as `jostle check`
//   keeps them). Sanity: the hashes equal demo.trace's and the expectations pass. Target:
//   >= 1,000x real time.
// BM_ReplayMemory/demo/40x: in each iteration (one at the usual minimum times), peak RSS
//   (VmHWM in /proc/self/status, reset first through /proc/self/clear_refs so that an earlier
//   stress scene's peak does not hide it) after replaying the demo once and after 40 times
//   back to back (91,200 ticks, each run checked against demo.trace); growth_kb should be ~0.
#include <benchmark/benchmark.h>
#include <box2d/box2d.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "arena.h"       // game/: game::ArenaGame
#include "broadphase.h"  // engine/world/src (private): detail::Broadphase
#include "pair_grid.h"   // engine/world/src (private): detail::PairGrid
#include "jostle/core/rng.h"
#include "jostle/replay/replay.h"
#include "jostle/replay/scenario.h"
#include "jostle/world.h"

namespace {

using namespace jostle;

constexpr float kStepSeconds = 1.0f / 60.0f;
constexpr float kTwoPi = 2.0f * std::numbers::pi_v<float>;

// Runs a benchmark body, turning an exception from setup (a missing asset, say) into a
// reported error instead of a crash.
void guarded(benchmark::State& state, const std::function<void()>& body) {
    try {
        body();
    } catch (const std::exception& e) {
        state.SkipWithError(e.what());
    }
}

// ---------------------------------------------------------------------------------------
// 5. Broadphase: candidate pairs of moving boxes
// ---------------------------------------------------------------------------------------

// A pair as one key, lower index in the high half: sorting keys sorts by (lower, higher).
using PairKey = std::uint64_t;
constexpr PairKey pair_key(std::uint32_t a, std::uint32_t b) {
    return a < b ? (PairKey{a} << 32) | b : (PairKey{b} << 32) | a;
}

// overlaps() from the collision module without its validity checks (every box here is
// finite), inline so that an inner loop is not a call. The four comparisons are combined
// without short-circuiting: each one alone is a coin toss the branch predictor loses, while
// their conjunction is almost always false (a few neighbours among thousands).
inline bool touch(const Aabb& a, const Aabb& b) {
    return (a.max.x >= b.min.x) & (a.min.x <= b.max.x) & (a.max.y >= b.min.y) & (a.min.y <= b.max.y);
}

// n boxes moving in a square [0, side]^2, bouncing off its edges.
struct MovingBoxes {
    float side = 0.0f;
    std::vector<Vec2> centre;
    std::vector<Vec2> half;
    std::vector<Vec2> velocity;  // px/s
    std::vector<Aabb> bounds;    // tight, now
    std::vector<Vec2> moved;     // this step's displacement

    std::uint32_t size() const { return static_cast<std::uint32_t>(centre.size()); }

    void step() {
        for (std::size_t i = 0; i < centre.size(); ++i) {
            Vec2& v = velocity[i];
            const Vec2 h = half[i];
            const Vec2 c = centre[i] + kStepSeconds * v;
            if ((c.x - h.x < 0.0f && v.x < 0.0f) || (c.x + h.x > side && v.x > 0.0f)) v.x = -v.x;
            if ((c.y - h.y < 0.0f && v.y < 0.0f) || (c.y + h.y > side && v.y > 0.0f)) v.y = -v.y;
            moved[i] = c - centre[i];
            centre[i] = c;
            bounds[i] = {c - h, c + h};
        }
    }
};

// Half sizes uniform in [2, 8] px per axis (mean 5). Two boxes touch when their centres are
// within the sums of their half sizes on both axes: 4 * E[hx + hx'] * E[hy + hy'] = 400 px^2
// of the area around a box, so an area of 400 / 3 px^2 per box gives about 3 neighbours.
MovingBoxes make_boxes(int n, std::uint64_t seed = 5) {
    constexpr float kAreaPerBox = 400.0f / 3.0f;
    Rng rng(seed);
    MovingBoxes s;
    s.side = std::sqrt(kAreaPerBox * static_cast<float>(n));
    for (int i = 0; i < n; ++i) {
        const Vec2 h{rng.uniform(2.0f, 8.0f), rng.uniform(2.0f, 8.0f)};
        const Vec2 c{rng.uniform(h.x, s.side - h.x), rng.uniform(h.y, s.side - h.y)};
        s.half.push_back(h);
        s.centre.push_back(c);
        s.velocity.push_back({rng.uniform(-120.0f, 120.0f), rng.uniform(-120.0f, 120.0f)});
        s.bounds.push_back({c - h, c + h});
        s.moved.push_back({});
    }
    return s;
}

// Every pair, in order: the reference list.
void brute_force_pairs(const MovingBoxes& s, std::vector<PairKey>& out) {
    out.clear();
    const std::uint32_t n = s.size();
    for (std::uint32_t i = 0; i < n; ++i) {
        const Aabb a = s.bounds[i];
        for (std::uint32_t j = i + 1; j < n; ++j) {
            if (touch(a, s.bounds[j])) out.push_back(pair_key(i, j));
        }
    }
}

// jostle's broadphase (b2DynamicTree behind detail::Broadphase), driven the way World::step
// drives it: move() every box with this step's displacement, then one query per box. The
// queries always use the tree (scan budget 0): this variant measures the tree, not the
// scans a query may make instead while the tree waits.
class TreePairs {
public:
    explicit TreePairs(const MovingBoxes& s) {
        for (std::uint32_t i = 0; i < s.size(); ++i) proxies_.push_back(tree_.create(s.bounds[i], i));
    }
    TreePairs(const TreePairs&) = delete;
    TreePairs& operator=(const TreePairs&) = delete;

    void pairs(const MovingBoxes& s, std::vector<PairKey>& out) {
        const std::uint32_t n = s.size();
        for (std::uint32_t i = 0; i < n; ++i) tree_.move(proxies_[i], s.bounds[i], s.moved[i]);
        out.clear();
        for (std::uint32_t i = 0; i < n; ++i) {
            const Aabb a = s.bounds[i];
            tree_.query(a, [&](std::uint32_t j) {
                if (j > i && touch(a, s.bounds[j])) out.push_back(pair_key(i, j));
            });
        }
        std::sort(out.begin(), out.end());
    }

private:
    detail::Broadphase tree_{0};
    std::vector<int> proxies_;
};

// Sort and sweep along x. The order by min x is kept from step to step; after one step of
// motion it is nearly sorted, so an insertion sort restores it in close to linear time.
class SortAndSweep {
public:
    explicit SortAndSweep(const MovingBoxes& s) {
        for (std::uint32_t i = 0; i < s.size(); ++i) order_.push_back({s.bounds[i].min.x, i});
        std::sort(order_.begin(), order_.end(), [](const Entry& x, const Entry& y) { return x.key < y.key; });
    }

    void pairs(const MovingBoxes& s, std::vector<PairKey>& out) {
        const std::size_t n = order_.size();
        for (Entry& e : order_) e.key = s.bounds[e.index].min.x;
        for (std::size_t k = 1; k < n; ++k) {
            const Entry e = order_[k];
            std::size_t m = k;
            for (; m > 0 && order_[m - 1].key > e.key; --m) order_[m] = order_[m - 1];
            order_[m] = e;
        }
        sorted_.resize(n);
        for (std::size_t k = 0; k < n; ++k) sorted_[k] = s.bounds[order_[k].index];
        // Later boxes start at or after a's min x; they overlap a in x while they start before
        // a's max x. Each of those is written and kept when it overlaps in y as well, without
        // a branch per candidate (most of them fail the y test, unpredictably).
        std::size_t count = 0;
        for (std::size_t k = 0; k < n; ++k) {
            const Aabb a = sorted_[k];
            const std::uint32_t i = order_[k].index;
            std::size_t end = k + 1;
            while (end < n && sorted_[end].min.x <= a.max.x) ++end;
            if (buffer_.size() < count + (end - k)) buffer_.resize(2 * (count + (end - k)));
            for (std::size_t m = k + 1; m < end; ++m) {
                const Aabb& b = sorted_[m];
                buffer_[count] = pair_key(i, order_[m].index);
                count += static_cast<std::size_t>((a.min.y <= b.max.y) & (b.min.y <= a.max.y));
            }
        }
        out.assign(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(count));
        std::sort(out.begin(), out.end());
    }

private:
    struct Entry {
        float key;  // min x
        std::uint32_t index;
    };
    std::vector<Entry> order_;
    std::vector<Aabb> sorted_;        // the bounds in order_, gathered for the sweep
    std::vector<PairKey> buffer_;     // the sweep's output, grown as needed, never shrunk
};

// The world's own way (detail::PairGrid, engine/world/src/pair_grid.h): every box into a
// uniform grid rebuilt each step, all pairs at once, sorted as they are gathered.
class GridPairs {
public:
    void pairs(const MovingBoxes& s, std::vector<PairKey>& out) {
        items_.resize(s.size());
        for (std::uint32_t i = 0; i < s.size(); ++i) items_[i] = {s.bounds[i], i, true};
        grid_.find(items_, found_);
        out.resize(found_.size());
        for (std::size_t k = 0; k < found_.size(); ++k) out[k] = pair_key(found_[k].a, found_[k].b);
    }

private:
    detail::PairGrid grid_;
    std::vector<detail::GridItem> items_;
    std::vector<detail::GridPair> found_;
};

// What World::step pays for its pairs: the proxies' fat bounds kept up to date (moved as in
// TreePairs; the tree over them, which answers region queries, catches up only when queried,
// and nothing here queries it: the best case, as a real step with long walls, bullets or
// fast circles queries), then the grid over the fat bounds, then the pairs whose tight boxes
// touch (the world keeps every fat-bounds pair).
class WorldPairs {
public:
    explicit WorldPairs(const MovingBoxes& s) {
        for (std::uint32_t i = 0; i < s.size(); ++i) proxies_.push_back(tree_.create(s.bounds[i], i));
    }
    WorldPairs(const WorldPairs&) = delete;
    WorldPairs& operator=(const WorldPairs&) = delete;

    void pairs(const MovingBoxes& s, std::vector<PairKey>& out) {
        const std::uint32_t n = s.size();
        items_.resize(n);
        for (std::uint32_t i = 0; i < n; ++i) {
            tree_.move(proxies_[i], s.bounds[i], s.moved[i]);
            items_[i] = {tree_.fat_bounds(proxies_[i]), i, true};
        }
        grid_.find(items_, found_);
        out.clear();
        for (const detail::GridPair& p : found_) {
            if (touch(s.bounds[p.a], s.bounds[p.b])) out.push_back(pair_key(p.a, p.b));
        }
    }

private:
    detail::Broadphase tree_;
    std::vector<int> proxies_;
    detail::PairGrid grid_;
    std::vector<detail::GridItem> items_;
    std::vector<detail::GridPair> found_;
};

enum class PairMethod { brute_force, tree, sort_and_sweep, grid, world };

const char* name_of(PairMethod m) {
    switch (m) {
        case PairMethod::brute_force: return "brute_force";
        case PairMethod::tree: return "tree";
        case PairMethod::sort_and_sweep: return "sort_and_sweep";
        case PairMethod::grid: return "grid";
        case PairMethod::world: return "world";
    }
    return "?";
}

// The three lists agree over the first kCheckedSteps steps of the scene: "" or what differs.
// Made once per n and shared by the three benchmarks of that n.
class BroadphaseChecks {
public:
    const std::string& result(int n) {
        if (const auto found = results_.find(n); found != results_.end()) return found->second;
        return results_[n] = check(n);
    }

private:
    static constexpr int kCheckedSteps = 5;

    static std::string check(int n) {
        MovingBoxes s = make_boxes(n);
        TreePairs tree(s);
        SortAndSweep sweep(s);
        GridPairs grid;
        WorldPairs world(s);
        std::vector<PairKey> reference, got;
        for (int step = 0; step < kCheckedSteps; ++step) {
            s.step();
            brute_force_pairs(s, reference);
            if (reference.empty()) return "the scene has no overlapping boxes";
            const auto differs = [&](const char* name) {
                std::ostringstream msg;
                msg << name << " gives " << got.size() << " pairs at step " << step << ", brute force "
                    << reference.size();
                return msg.str();
            };
            tree.pairs(s, got);
            if (got != reference) return differs("tree");
            sweep.pairs(s, got);
            if (got != reference) return differs("sort_and_sweep");
            grid.pairs(s, got);
            if (got != reference) return differs("grid");
            world.pairs(s, got);
            if (got != reference) return differs("world");
        }
        return {};
    }
    std::map<int, std::string> results_;
};

void bm_broadphase(benchmark::State& state, BroadphaseChecks& checks, int n, PairMethod method) {
    if (const std::string& error = checks.result(n); !error.empty()) {
        state.SkipWithError(error.c_str());
        return;
    }
    MovingBoxes s = make_boxes(n);
    std::vector<PairKey> out;
    std::unique_ptr<TreePairs> tree;
    std::unique_ptr<SortAndSweep> sweep;
    if (method == PairMethod::tree) tree = std::make_unique<TreePairs>(s);
    if (method == PairMethod::sort_and_sweep) sweep = std::make_unique<SortAndSweep>(s);
    GridPairs grid;
    std::unique_ptr<WorldPairs> world;
    if (method == PairMethod::world) world = std::make_unique<WorldPairs>(s);
    double pairs = 0.0;
    for (auto _ : state) {
        s.step();
        switch (method) {
            case PairMethod::brute_force: brute_force_pairs(s, out); break;
            case PairMethod::tree: tree->pairs(s, out); break;
            case PairMethod::sort_and_sweep: sweep->pairs(s, out); break;
            case PairMethod::grid: grid.pairs(s, out); break;
            case PairMethod::world: world->pairs(s, out); break;
        }
        benchmark::DoNotOptimize(out.data());
        pairs += static_cast<double>(out.size());
    }
    state.counters["pairs"] = benchmark::Counter(pairs, benchmark::Counter::kAvgIterations);
    state.counters["steps/s"] = benchmark::Counter(1, benchmark::Counter::kIsIterationInvariantRate);
}

// ---------------------------------------------------------------------------------------
// 6. World stress scene
// ---------------------------------------------------------------------------------------

constexpr Vec2 kArena{1024.0f, 768.0f};
constexpr float kWallThickness = 32.0f;
constexpr int kRescaleEvery = 15;    // steps between a body's collider re-sets (K)
constexpr int kScalePeriod = 240;    // steps: a body's scale goes 0.85 .. 1.15 .. 0.85 in 4 s
constexpr int kWarmupSteps = 1000;
constexpr float kRestitution = 0.8f;
constexpr float kFriction = 0.1f;
constexpr float kRestitutionThreshold = 30.0f;  // px/s, jostle's default

enum class Form : std::uint8_t { circle, box, segment, quad };

// One body of the stress scene, at scale 1, for both engines.
struct StressBody {
    Form form = Form::circle;
    float size = 0.0f;    // radius, half width or half length (px)
    float aspect = 1.0f;  // box: half height / half width
    std::array<Vec2, 4> quad{};  // convex, around the origin
    Vec2 position;
    Vec2 velocity;  // px/s
    float speed = 0.0f;  // |velocity|, restored at each re-set
    float angle = 0.0f;
    float spin = 0.0f;   // rad/s
    float phase = 0.0f;  // of the scale's cycle
};

// Small bodies 1.5 .. 3.5 px, large ones (1 in 20) 6 .. 10 px: at 10,000 bodies they cover
// about a quarter of the arena. Speeds 20 .. 50 px/s move a body at most 0.83 px per step,
// about half the smallest box's smallest extent (the world's LIMITS for non-circles; segments
// have no thickness to keep); the smallest circles are fast at the top speeds and go through
// the sweeps phase.
std::vector<StressBody> make_stress_scene(int n, std::uint64_t seed = 11) {
    Rng rng(seed);
    std::vector<StressBody> bodies;
    for (int i = 0; i < n; ++i) {
        StressBody b;
        const bool large = i % 20 == 0;
        b.form = static_cast<Form>((i + i / 20) % 4);  // large ones cycle through the forms too
        b.size = large ? rng.uniform(6.0f, 10.0f) : rng.uniform(1.5f, 3.5f);
        b.aspect = rng.uniform(0.6f, 1.0f);
        // Four vertices a quarter turn apart at radii 0.7 .. 1: always convex.
        for (int k = 0; k < 4; ++k) {
            const float a = static_cast<float>(k) * 0.5f * std::numbers::pi_v<float>;
            const float r = b.size * rng.uniform(0.7f, 1.0f);
            b.quad[static_cast<std::size_t>(k)] = {r * std::cos(a), r * std::sin(a)};
        }
        const float reach = b.form == Form::segment ? 1.5f * b.size * 1.15f : b.size * 1.15f * 1.42f;
        b.position = {rng.uniform(reach, kArena.x - reach), rng.uniform(reach, kArena.y - reach)};
        const float heading = rng.uniform(0.0f, kTwoPi);
        b.speed = rng.uniform(20.0f, 50.0f);
        b.velocity = {b.speed * std::cos(heading), b.speed * std::sin(heading)};
        b.angle = rng.uniform(-std::numbers::pi_v<float>, std::numbers::pi_v<float>);
        b.spin = rng.uniform(-1.0f, 1.0f);
        b.phase = rng.uniform(0.0f, kTwoPi);
        bodies.push_back(b);
    }
    return bodies;
}

float scale_at(const StressBody& b, std::uint64_t step) {
    return 1.0f + 0.15f * std::sin(b.phase + kTwoPi * static_cast<float>(step % kScalePeriod) / kScalePeriod);
}
bool resets_at(std::size_t body, std::uint64_t step) { return (step + body) % kRescaleEvery == 0; }

// Area in px^2 at scale 1 (segments: 1 px thick), for masses.
float area_of(const StressBody& b) {
    switch (b.form) {
        case Form::circle: return std::numbers::pi_v<float> * b.size * b.size;
        case Form::box: return 4.0f * b.size * b.size * b.aspect;
        case Form::segment: return 3.0f * b.size;
        case Form::quad: {
            float twice = 0.0f;
            for (std::size_t k = 0; k < 4; ++k) twice += cross(b.quad[k], b.quad[(k + 1) % 4]);
            return 0.5f * std::fabs(twice);
        }
    }
    return 1.0f;
}

// A body at rest against a wall may overlap it by up to the slop (a segment lying along it
// has its position on the wall's face), so leaving means going further than that.
bool outside_arena(Vec2 p) {
    constexpr float kSlop = WorldDesc{}.slop;
    return !is_finite(p) || p.x < -kSlop || p.x > kArena.x + kSlop || p.y < -kSlop || p.y > kArena.y + kSlop;
}

// The four walls, as (centre, half size), just outside the arena.
std::array<std::pair<Vec2, Vec2>, 4> walls() {
    const float t = kWallThickness;
    return {{{{kArena.x / 2.0f, -t / 2.0f}, {kArena.x / 2.0f + t, t / 2.0f}},
             {{kArena.x / 2.0f, kArena.y + t / 2.0f}, {kArena.x / 2.0f + t, t / 2.0f}},
             {{-t / 2.0f, kArena.y / 2.0f}, {t / 2.0f, kArena.y / 2.0f + t}},
             {{kArena.x + t / 2.0f, kArena.y / 2.0f}, {t / 2.0f, kArena.y / 2.0f + t}}}};
}

// A running stress scene in one engine: its bodies are the make_stress_scene() list.
class StressScene {
public:
    explicit StressScene(std::vector<StressBody> bodies) : bodies_(std::move(bodies)) {}
    virtual ~StressScene() = default;
    // The game's side of a step (untimed): re-set the colliders and speeds due this step.
    void game_side() {
        for (std::size_t i = 0; i < bodies_.size(); ++i) {
            if (resets_at(i, steps_)) reset(i, scale_at(bodies_[i], steps_));
        }
    }
    // The engine's step (timed).
    void step() {
        engine_step();
        ++steps_;
    }
    void warm_up() {
        for (int k = 0; k < kWarmupSteps; ++k) {
            game_side();
            step();
        }
    }
    virtual int escaped() const = 0;      // bodies outside the arena (or not finite)
    virtual std::size_t contacts() const = 0;

protected:
    virtual void reset(std::size_t i, float scale) = 0;
    virtual void engine_step() = 0;
    // The velocity with the body's own speed, in the direction it now moves.
    Vec2 restored_velocity(std::size_t i, Vec2 now) const {
        const StressBody& b = bodies_[i];
        const float len = length(now);
        return len > 1e-3f ? (b.speed / len) * now : b.velocity;
    }
    std::vector<StressBody> bodies_;
    std::uint64_t steps_ = 0;
};

Collider jostle_collider(const StressBody& b, float scale) {
    const float s = b.size * scale;
    switch (b.form) {
        case Form::circle: return Collider::circle(s);
        case Form::box: return Collider::box({s, s * b.aspect});
        case Form::segment: return Collider::segment({-1.5f * s, 0.0f}, {1.5f * s, 0.0f});
        case Form::quad: {
            std::array<Vec2, 4> points;
            for (std::size_t k = 0; k < 4; ++k) points[k] = scale * b.quad[k];
            const std::optional<Polygon> poly = make_polygon(points);
            return poly ? Collider::polygon(*poly) : Collider::box({s, s});
        }
    }
    return Collider::circle(s);
}

class JostleStress final : public StressScene {
public:
    explicit JostleStress(std::vector<StressBody> bodies)
        : StressScene(std::move(bodies)), world_(WorldDesc{.gravity = {0.0f, 0.0f}, .seed = 1}) {
        for (const auto& [centre, half] : walls()) {
            world_.create(EntityDesc{.kind = BodyKind::static_body, .position = centre, .collider = Collider::aabb(half),
                                     .restitution = kRestitution, .friction = kFriction});
        }
        for (const StressBody& b : bodies_) {
            ids_.push_back(world_.create(EntityDesc{.kind = BodyKind::dynamic,
                                                    .position = b.position,
                                                    .angle = b.angle,
                                                    .velocity = b.velocity,
                                                    .angular_velocity = b.spin,
                                                    .collider = jostle_collider(b, scale_at(b, 0)),
                                                    .inverse_mass = 1.0f / area_of(b),
                                                    .restitution = kRestitution,
                                                    .friction = kFriction,
                                                    .gravity_scale = 0.0f}));
        }
    }
    int escaped() const override {
        int out = 0;
        for (const EntityId id : ids_) {
            const EntityDesc* e = world_.get(id);
            if (e == nullptr || outside_arena(e->position)) ++out;
        }
        return out;
    }
    std::size_t contacts() const override { return world_.contacts().size(); }

private:
    void reset(std::size_t i, float scale) override {
        world_.set_collider(ids_[i], jostle_collider(bodies_[i], scale));
        world_.set_velocity(ids_[i], restored_velocity(i, world_.get(ids_[i])->velocity));
    }
    void engine_step() override { world_.step(kStepSeconds); }

    World world_;
    std::vector<EntityId> ids_;
};

// Box2D in metres: 8 px per metre puts the bodies at 0.19 .. 1.25 m, inside the sizes Box2D
// is tuned for, and the arena at 128 x 96 m.
constexpr float kPxPerMetre = 8.0f;
b2Vec2 to_b2(Vec2 px) { return {px.x / kPxPerMetre, px.y / kPxPerMetre}; }
Vec2 from_b2(b2Vec2 m) { return {m.x * kPxPerMetre, m.y * kPxPerMetre}; }

class Box2dStress final : public StressScene {
public:
    explicit Box2dStress(std::vector<StressBody> bodies)
        : StressScene(std::move(bodies)), world_(std::make_unique<b2World>(b2Vec2(0.0f, 0.0f))) {
        world_->SetAllowSleeping(false);  // jostle has no sleeping; the bodies keep moving anyway
        b2BodyDef wall_def;
        b2Body* wall = world_->CreateBody(&wall_def);
        for (const auto& [centre, half] : walls()) {
            b2PolygonShape box;
            const b2Vec2 h = to_b2(half);
            box.SetAsBox(h.x, h.y, to_b2(centre), 0.0f);
            add_fixture(wall, box);
        }
        for (std::size_t i = 0; i < bodies_.size(); ++i) {
            const StressBody& b = bodies_[i];
            b2BodyDef def;
            def.type = b2_dynamicBody;
            def.position = to_b2(b.position);
            def.angle = b.angle;
            def.linearVelocity = to_b2(b.velocity);
            def.angularVelocity = b.spin;
            def.fixedRotation = true;
            b2Body* body = world_->CreateBody(&def);
            bodies_b2_.push_back(body);
            attach(i, scale_at(b, 0));
        }
    }
    int escaped() const override {
        int out = 0;
        for (const b2Body* body : bodies_b2_) {
            if (outside_arena(from_b2(body->GetPosition()))) ++out;
        }
        return out;
    }
    std::size_t contacts() const override {
        std::size_t touching = 0;
        for (const b2Contact* c = world_->GetContactList(); c != nullptr; c = c->GetNext()) {
            if (c->IsTouching()) ++touching;
        }
        return touching;
    }

private:
    static void add_fixture(b2Body* body, const b2Shape& shape) {
        b2FixtureDef def;
        def.shape = &shape;
        def.density = 1.0f;
        def.friction = kFriction;
        def.restitution = kRestitution;
        def.restitutionThreshold = kRestitutionThreshold / kPxPerMetre;
        body->CreateFixture(&def);
    }
    // The body's one fixture at `scale` (replacing the old one: Box2D has no scale either).
    void attach(std::size_t i, float scale) {
        const StressBody& b = bodies_[i];
        b2Body* body = bodies_b2_[i];
        if (b2Fixture* old = body->GetFixtureList()) body->DestroyFixture(old);
        const float s = b.size * scale / kPxPerMetre;
        switch (b.form) {
            case Form::circle: {
                b2CircleShape circle;
                circle.m_radius = s;
                add_fixture(body, circle);
                break;
            }
            case Form::box: {
                b2PolygonShape box;
                box.SetAsBox(s, s * b.aspect);
                add_fixture(body, box);
                break;
            }
            case Form::segment: {
                b2EdgeShape edge;
                edge.SetTwoSided(b2Vec2(-1.5f * s, 0.0f), b2Vec2(1.5f * s, 0.0f));
                add_fixture(body, edge);
                // An edge has no area, so Box2D would give it 1 kg: give it its 1 px strip's.
                // (b2Vec2's constructor leaves it uninitialised, even in b2MassData{}.)
                b2MassData mass;
                mass.mass = 3.0f * s / kPxPerMetre;
                mass.center.SetZero();
                mass.I = 0.0f;
                body->SetMassData(&mass);
                break;
            }
            case Form::quad: {
                std::array<b2Vec2, 4> points;
                for (std::size_t k = 0; k < 4; ++k) points[k] = to_b2(scale * b.quad[k]);
                b2PolygonShape quad;
                quad.Set(points.data(), 4);
                add_fixture(body, quad);
                break;
            }
        }
    }
    void reset(std::size_t i, float scale) override {
        attach(i, scale);
        b2Body* body = bodies_b2_[i];
        body->SetLinearVelocity(to_b2(restored_velocity(i, from_b2(body->GetLinearVelocity()))));
    }
    void engine_step() override { world_->Step(kStepSeconds, 8, 3); }

    std::unique_ptr<b2World> world_;
    std::vector<b2Body*> bodies_b2_;
};

enum class StressEngine { box2d, jostle };

// Each scene is made and warmed up once, on first use, then keeps running: each run of the
// benchmark times the next kTimedSteps steps (a fixed iteration count), so runs time
// consecutive stretches of the scene's life, the same ones for both engines. The warm-up is
// long because the scene gathers contacts for its first ~1,000 steps (bodies bunch up) and
// only then settles into a steady state; timing earlier would flatter the engine that copes
// worse with crowds.
constexpr int kTimedSteps = 120;

class StressScenes {
public:
    StressScene& get(int n, StressEngine engine) {
        std::unique_ptr<StressScene>& scene = scenes_[{n, engine}];
        if (!scene) {
            if (engine == StressEngine::box2d) {
                scene = std::make_unique<Box2dStress>(make_stress_scene(n));
            } else {
                scene = std::make_unique<JostleStress>(make_stress_scene(n));
            }
            scene->warm_up();
        }
        return *scene;
    }

private:
    std::map<std::pair<int, StressEngine>, std::unique_ptr<StressScene>> scenes_;
};

void bm_world_stress(benchmark::State& state, StressScenes& scenes, int n, StressEngine engine) {
    guarded(state, [&] {
        StressScene& scene = scenes.get(n, engine);
        if (const int out = scene.escaped(); out > 0) {
            state.SkipWithError((std::to_string(out) + " bodies left the arena (warm-up)").c_str());
            return;
        }
        double contacts = 0.0;
        for (auto _ : state) {
            state.PauseTiming();
            scene.game_side();
            state.ResumeTiming();
            scene.step();
            state.PauseTiming();
            contacts += static_cast<double>(scene.contacts());
            state.ResumeTiming();
        }
        state.counters["contacts"] = benchmark::Counter(contacts, benchmark::Counter::kAvgIterations);
        state.counters["steps/s"] = benchmark::Counter(1, benchmark::Counter::kIsIterationInvariantRate);
        if (const int out = scene.escaped(); out > 0) {
            state.SkipWithError((std::to_string(out) + " bodies left the arena").c_str());
        }
    });
}

// ---------------------------------------------------------------------------------------
// 8. Replay
// ---------------------------------------------------------------------------------------

std::string read_text(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error("cannot read " + path);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// The demo scenario, the game and the recorded hashes (the golden trace).
struct Demo {
    game::ArenaGame game{JOSTLE_ASSETS_DIR};
    Scenario scenario;
    std::vector<std::uint64_t> golden;

    Demo() {
        const std::string base = std::string(JOSTLE_ASSETS_DIR) + "/scenarios/demo";
        scenario = load_scenario(base + ".scn", game.vocabulary());
        golden = parse_trace(read_text(base + ".trace"), base + ".trace").hashes;
    }
    // "" when the run is the recorded one, else what differs.
    std::string check(const ReplayResult& run) const {
        if (run.hashes != golden) return "the replay's hashes differ from demo.trace";
        if (!run.expectations_passed()) return "an expectation of demo.scn failed";
        return {};
    }
};

void bm_replay(benchmark::State& state, int dump_every) {
    guarded(state, [&] {
        const Demo demo;
        ReplayOptions options;
        options.dump_every = dump_every;
        if (const std::string error = demo.check(replay(demo.game, demo.scenario, options)); !error.empty()) {
            state.SkipWithError(error.c_str());
            return;
        }
        // Timed here as well, so that the counters are plain numbers (a rate counter would be
        // printed as "x_realtime=950/s").
        double seconds = 0.0;
        for (auto _ : state) {
            const auto start = std::chrono::steady_clock::now();
            const ReplayResult run = replay(demo.game, demo.scenario, options);
            seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            benchmark::DoNotOptimize(run.hashes.data());
        }
        const double ticks_per_second = static_cast<double>(demo.scenario.ticks()) *
                                        static_cast<double>(state.iterations()) / std::max(seconds, 1e-9);
        state.counters["ticks"] = static_cast<double>(demo.scenario.ticks());
        state.counters["ticks/s"] = ticks_per_second;
        state.counters["x_realtime"] = ticks_per_second / demo.scenario.tick_rate;
    });
}

// A "Name:   123 kB" line of /proc/self/status, in kB (-1 when missing).
double status_kb(const char* name) {
    std::ifstream in("/proc/self/status");
    const std::string prefix = std::string(name) + ":";
    for (std::string line; std::getline(in, line);) {
        if (line.rfind(prefix, 0) == 0) return std::stod(line.substr(prefix.size()));
    }
    return -1.0;
}

// Resets VmHWM to the current RSS (Linux 4.0+), so that the peak is this benchmark's and not
// that of a stress scene before it. False when the kernel does not allow it.
bool reset_peak_rss() {
    std::ofstream out("/proc/self/clear_refs");
    out << "5";
    out.flush();
    return static_cast<bool>(out);
}

void bm_replay_memory(benchmark::State& state, int replays) {
    guarded(state, [&] {
        const Demo demo;
        for (auto _ : state) {
            const bool reset = reset_peak_rss();
            std::string error = demo.check(replay(demo.game, demo.scenario));
            const double hwm_once = status_kb("VmHWM");
            const double rss_once = status_kb("VmRSS");
            for (int k = 1; k < replays && error.empty(); ++k) error = demo.check(replay(demo.game, demo.scenario));
            if (!error.empty()) {
                state.SkipWithError(error.c_str());
                break;
            }
            const double hwm_all = status_kb("VmHWM");
            state.counters["peak_reset"] = reset ? 1.0 : 0.0;
            state.counters["hwm_1x_kb"] = hwm_once;
            state.counters["hwm_kb"] = hwm_all;
            state.counters["growth_kb"] = hwm_all - hwm_once;
            state.counters["rss_growth_kb"] = status_kb("VmRSS") - rss_once;
            state.counters["ticks"] = static_cast<double>(demo.scenario.ticks() * replays);
        }
    });
}

// ---------------------------------------------------------------------------------------
// Registration
// ---------------------------------------------------------------------------------------

// Registers one benchmark; anchors carry the label "anchor" (tools/bench-ratios looks for it).
template <class Fn>
benchmark::internal::Benchmark* add(const std::string& name, bool anchor, Fn&& fn) {
    return benchmark::RegisterBenchmark(name.c_str(),
                                 [anchor, fn = std::forward<Fn>(fn)](benchmark::State& state) {
                                     fn(state);
                                     if (anchor) state.SetLabel("anchor");
                                 })
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond);
}

void register_all(BroadphaseChecks& checks, StressScenes& scenes) {
    for (const int n : {1000, 10000, 20000}) {
        for (const PairMethod m : {PairMethod::brute_force, PairMethod::tree, PairMethod::sort_and_sweep, PairMethod::grid,
                                   PairMethod::world}) {
            add("BM_Broadphase/" + std::to_string(n) + "/" + name_of(m), m == PairMethod::brute_force,
                [=, &checks](benchmark::State& s) { bm_broadphase(s, checks, n, m); });
        }
    }
    for (const int n : {1000, 2000, 5000, 10000}) {
        for (const StressEngine e : {StressEngine::box2d, StressEngine::jostle}) {
            add("BM_WorldStress/" + std::to_string(n) + "/" + (e == StressEngine::box2d ? "box2d" : "jostle"),
                e == StressEngine::box2d, [=, &scenes](benchmark::State& s) { bm_world_stress(s, scenes, n, e); })
                ->Iterations(kTimedSteps);
        }
    }
    add("BM_Replay/demo/no_dumps", false, [](benchmark::State& s) { bm_replay(s, 0); });
    add("BM_Replay/demo/dumps", false, [](benchmark::State& s) { bm_replay(s, 10); });
    add("BM_ReplayMemory/demo/40x", false, [](benchmark::State& s) { bm_replay_memory(s, 40); });
}

}  // namespace

int main(int argc, char** argv) {
    BroadphaseChecks checks;
    StressScenes scenes;
    register_all(checks, scenes);
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
