// collision_bench.cpp: the collision module's benchmarks (Google Benchmark): jostle's narrowphase
// queries against Box2D 2.4.1 (the engine the differential suite uses as its oracle) and its
// pixel-mask queries against the lecture's brute-force loop and a byte-per-pixel mask. Speed is
// only measured here, never asserted.
//
// Every family pairs candidates with an anchor measured side by side in the same run (its label
// is "anchor"), because on a shared 2-core machine absolute times drift while ratios hold up
// better. Names are BM_<Family>/<inputs...>/<variant>, registered anchor first;
// tools/bench-ratios turns the JSON output into a table of time / anchor (the speed-up of a
// candidate is 1 / that).
//
// FAMILIES (the anchor first)
//   BM_ObbMtd/mix            b2CollidePolygons on SetAsBox boxes vs collide(Obb, Obb) (the 2 + 2
//                            axis "SAT box"), vs collide(Shape, Shape) (the variant dispatch the
//                            world calls), and vs contacts(Obb, Obb) (jostle_point: the MTD with
//                            the 2-point contact set, clipped as Box2D clips its manifold).
//   BM_HexMtd/mix            the same for hexagons: b2CollidePolygons vs collide(Polygon, Polygon)
//                            and contacts(Polygon, Polygon).
//   BM_PolyCircle/hex|obb/mix  b2CollidePolygonAndCircle vs collide(Polygon|Obb, Circle), vs
//                            collide(Shape, Shape) (jostle_shape), and for hexagons collide_sat
//                            (the lecture's second method) as well.
//   BM_CircleCircle/mix      b2CollideCircles vs collide(Circle, Circle) and collide(Shape, Shape).
//   BM_CastPolygon/hex/mix   b2PolygonShape::RayCast vs cast(from, to, Polygon) and cast(from, to,
//                            Shape) (the dispatch the world's bullets call).
//   BM_SweepCircle/mix       b2TimeOfImpact (linear sweeps, circle proxies) vs sweep(Circle, v,
//                            Circle): a moving circle against a static one.
//   BM_Mask{Overlaps,First,Count}/<side>/vs_lecture   reference:: (the lecture's loop, 09-3,
//                            corrected) vs jostle's bit-packed query;
//   BM_Mask{Overlaps,First,Count}/<side>/vs_bytes     a byte-per-pixel mask (one uint8 per pixel,
//                            a plain loop over the overlap, written below) vs the same jostle
//                            query (measured in both groups, so each ratio reads directly).
//   BM_MaskMtdDeep/<box|obb|hexagon|circle>/<depth>/plain_scan   collide(mask, shape) for a
//                            32 px round mask about <depth> px inside a large shape, with the
//                            MTD search's shortcuts off (the column scan alone) vs on (jostle):
//                            no target, it shows what the shortcuts do to a deeply buried mask.
//   BM_MaskMtdThin/<segment|line>/<side>/plain_scan   collide(mask, thin shape) for a full
//                            side x side mask crossed by four segments (corner to corner, the
//                            other diagonal, two slants) or the same lines as one-pixel masks,
//                            shortcuts off (anchor) vs on: no target, it shows the column jumps.
//
// FAIR INPUTS
//   Each side gets the same seeded pairs in its own native form, built once per benchmark
//   outside the timed loop: Box2D shapes made by SetAsBox / Set with m_radius = 0 and identity
//   transforms (world-space vertices), exactly as box2d_diff_test.cpp maps jostle's shapes
//   (its oracle header is shared, tests/collision/box2d_oracle.h). Geometry is in Box2D's units
//   (shapes 1..10 across within ~10 of the origin), so b2_linearSlop means what it means in a
//   Box2D world. A pool of 1024 pairs is walked in order, so branch prediction cannot memorise
//   one pair; an iteration is 64 passes over it (65,536 queries) for the geometric families and
//   1 (count) or 16 passes for the masks, to keep times in the table readable. The geometric
//   pools are about a third overlapping (or hitting), a third near misses (a gap of 1e-3..3e-2
//   of the scene's size) and a third far (drawn at random per pair, not in a repeating pattern).
//   Casts and sweeps start outside the target (Box2D reports nothing for a ray starting inside,
//   and TOI treats starting overlaps its own way). Box2D's virtual RayCast is called
//   non-virtually, like jostle's free functions; the byte-mask queries are noinline, like the
//   library calls they sit beside. The masks are eight blobby 50%-full masks per size (value
//   noise thresholded at its median), in pairs at random offsets whose rectangles share at
//   least a pixel.
//
// COUNTERS
//   ns/query   the timed loop's wall time per query (the time tools/bench-ratios reads)
//   hit_frac   the share of the pool the timed side reports as a hit
//   band       touching/grazing-band disagreements with Box2D (allowed, see CHECKS)
//   px/ns      masks: pixels a reading-order scan of the shared rectangles examines (up to the
//              first shared pixel for yes/no and first, all of them for the count) per ns; the
//              ceiling of a bit-packed scan is 64 pixels per AND of two words
//
// CHECKS, over the whole pool right after timing, on the results the timed loop stored (the
// other side is computed afresh; for Box2D's manifolds the loop keeps the hit, which is what
// is compared): hit/no-hit must agree with Box2D and with the exact double
// evaluation of the same float shapes, except in the touching band (|exact separation| <= 1e-4
// of the scene's size) where either answer is right; jostle's depth and cast/sweep times are
// checked against the exact values, Box2D's cast t against jostle's along the ray, and TOI
// against jostle's time with Box2D's 3-slop target window (box2d_diff_test.cpp explains all
// of these tolerances). Mask results (yes/no, first pixel, count) must equal the lecture's
// exactly. A disagreement is SkipWithError, which prints "ERROR OCCURRED"; the ctest smoke
// test fails on that text.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <new>
#include <numbers>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "collision/box2d_oracle.h"
#include "jostle/collision.h"
#include "jostle/core/rng.h"

namespace {

using namespace jostle;
namespace ex = jostle::oracle::exact;
namespace b2o = jostle::oracle;
using ex::D2;

constexpr std::size_t kPool = 1024;  // pairs per pool
constexpr int kPasses = 64;          // geometric families: passes over the pool per iteration
constexpr double kPi = std::numbers::pi;
// box2d_diff_test.cpp's tolerances
constexpr double kRel = 1e-4;        // distances: kRel * L, L the pair's largest |coordinate| (>= 1)
constexpr double kSlop = static_cast<double>(b2_linearSlop);
constexpr double kToiLo = 2.75 * kSlop;  // b2TimeOfImpact stops at 3 +- 0.25 slop of overlap
constexpr double kToiHi = 3.25 * kSlop;
constexpr double kGrazeCos = 1e-3;   // casts: below this incidence the entry t is not compared

// ---------------------------------------------------------------------------------------
// Helpers
// ---------------------------------------------------------------------------------------

__attribute__((format(printf, 1, 2))) std::string fmt(const char* f, ...) {
    char buf[512];
    va_list ap;
    va_start(ap, f);
    std::vsnprintf(buf, sizeof buf, f, ap);
    va_end(ap);
    return buf;
}

double dd(float f) { return static_cast<double>(f); }
D2 d2(Vec2 v) { return ex::d2(v); }
// The rounding of generated data to float, out of the optimizer's sight (box2d_diff_test.cpp
// explains the GCC 12 SLP bug this guards against).
float to_float(double d) {
    volatile float f = static_cast<float>(d);
    return f;
}
Vec2 f2(D2 v) { return {to_float(v.x), to_float(v.y)}; }

D2 random_dir(Rng& rng) {
    const double a = dd(rng.uniform(-3.14159265f, 3.14159265f));
    return {std::cos(a), std::sin(a)};
}

// Bisection for a separation function f(t) with f(0) < 0 < f(T): the offset at which the pair
// touches.
template <class F>
double touch_offset(F f, double T) {
    if (!(f(0.0) < 0.0)) return 0.0;
    while (f(T) <= 0.0) T *= 2.0;
    double lo = 0.0, hi = T;
    for (int k = 0; k < 60; ++k) {
        const double mid = 0.5 * (lo + hi);
        (f(mid) <= 0.0 ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

// The mix: each pair is drawn overlapping, a near miss or far, about a third each.
enum class Category { overlap, near_miss, far };
Category draw_category(Rng& rng) { return static_cast<Category>(rng.below(3)); }
// How far past first contact a near miss or a far pair is placed, for a scene of size L.
double miss_gap(Category c, Rng& rng, double L) {
    if (c == Category::near_miss) return L * std::pow(10.0, dd(rng.uniform(-3.0f, -1.5f)));
    return L * dd(rng.uniform(0.1f, 1.0f));
}

// Disagreements found by a check: the count, the first few described, and the touching-band
// disagreements the tolerances allow.
class Checker {
public:
    void fail(std::size_t pair, const std::string& why) {
        if (failures_++ < 3) text_ += fmt("pair %zu: ", pair) + why + "; ";
    }
    long band = 0;
    // Reports the result; false (and the benchmark ends with an error) on any disagreement.
    bool report(benchmark::State& state, bool has_band = true) const {
        if (has_band) state.counters["band"] = static_cast<double>(band);
        if (failures_ == 0) return true;
        state.SkipWithError(fmt("%ld disagreement(s) over the pool: ", failures_).append(text_).c_str());
        return false;
    }

private:
    long failures_ = 0;
    std::string text_;
};

// The timed loop shared by every family: `passes` passes over the pool, query(i, out[i]) per
// pair, the result kept (stored, and forced to exist by DoNotOptimize) for the checks. Counts
// ns/query from the loop's wall time (the time tools/bench-ratios reads) and returns that time
// in ns, for the rates of the mask families.
template <class Out, class Query>
double time_pool(benchmark::State& state, std::vector<Out>& out, int passes, Query&& query) {
    const auto start = std::chrono::steady_clock::now();
    for (auto _ : state) {
        for (int pass = 0; pass < passes; ++pass) {
            for (std::size_t i = 0; i < out.size(); ++i) {
                query(i, out[i]);
                benchmark::DoNotOptimize(out[i]);
            }
        }
    }
    const double ns = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start).count();
    const double queries =
        static_cast<double>(passes) * static_cast<double>(out.size()) * static_cast<double>(state.iterations());
    state.counters["ns/query"] = ns / queries;
    return ns;
}

template <class T, class Hit>
void count_hits(benchmark::State& state, const std::vector<T>& out, Hit&& hit) {
    const auto n = std::count_if(out.begin(), out.end(), hit);
    state.counters["hit_frac"] = static_cast<double>(n) / static_cast<double>(out.size());
}

// A result larger than 16 bytes (CastHit, SweepHit, ContactSet) comes back through memory:
// `out = f()` has the callee write a temporary on the stack, which is then copied with 16- and
// 8-byte loads over the callee's 1- and 4-byte stores (a store-forwarding stall on every query).
// Box2D writes its output through a pointer straight into the pool, and so does a caller
// that initialises its result (`const CastHit h = cast(...)`, as the world does): this
// initialises the slot from the call, so the callee writes into the pool too.
template <class T, class Make>
void in_place(T& slot, Make&& make) {
    ::new (static_cast<void*>(&slot)) T(make());
}

b2Transform identity() { return b2o::identity(); }

// ---------------------------------------------------------------------------------------
// Shapes: one description, given to jostle, Box2D and the exact evaluator alike
// ---------------------------------------------------------------------------------------

// A shape before placement, around the origin, in double: an oriented box or a hexagon.
struct Template {
    bool box = false;
    double hx = 0.0, hy = 0.0;  // box
    float angle = 0.0f;         // box
    std::array<D2, 6> local{};  // hexagon
    double bound = 0.0;         // bounding radius about the origin
    double minor = 0.0;         // radius of a disc about the origin inside the shape
};

Template random_box(Rng& rng, double size) {
    Template t;
    t.box = true;
    t.hx = 0.5 * size * dd(rng.uniform(0.25f, 1.0f));
    t.hy = 0.5 * size * dd(rng.uniform(0.25f, 1.0f));
    t.angle = rng.uniform(-3.14159f, 3.14159f);
    t.bound = std::hypot(t.hx, t.hy);
    t.minor = std::min(t.hx, t.hy);
    return t;
}

// A regular hexagon stretched along one axis (0.5..1) and turned: convex, with wide angles.
Template random_hexagon(Rng& rng, double size) {
    Template t;
    const double a = 0.5 * size, stretch = dd(rng.uniform(0.5f, 1.0f)), rot = dd(rng.uniform(-3.14159f, 3.14159f));
    const double c = std::cos(rot), s = std::sin(rot);
    for (std::size_t i = 0; i < 6; ++i) {
        const double th = static_cast<double>(i) * kPi / 3.0;
        const double x = a * std::cos(th), y = a * stretch * std::sin(th);
        t.local[i] = {c * x - s * y, s * x + c * y};
        t.bound = std::max(t.bound, ex::len(t.local[i]));
    }
    t.minor = -ex::signed_distance(ex::make_poly(std::span<const D2>(t.local)), D2{}).d;
    return t;
}

// The template at c, in double (for the bisections that place pairs).
ex::Poly exact_at(const Template& t, D2 c) {
    if (!t.box) {
        std::array<D2, 6> w{};
        for (std::size_t i = 0; i < 6; ++i) w[i] = c + t.local[i];
        return ex::make_poly(std::span<const D2>(w));
    }
    const double co = std::cos(dd(t.angle)), si = std::sin(dd(t.angle));
    const std::array<D2, 4> l{D2{-t.hx, -t.hy}, D2{t.hx, -t.hy}, D2{t.hx, t.hy}, D2{-t.hx, t.hy}};
    std::array<D2, 4> w{};
    for (std::size_t i = 0; i < 4; ++i) w[i] = c + D2{co * l[i].x - si * l[i].y, si * l[i].x + co * l[i].y};
    return ex::make_poly(std::span<const D2>(w));
}

// The template at c rounded to floats, in every view: jostle's Obb (boxes) or Polygon
// (hexagons), Box2D's polygon (written in place: b2PolygonShape leaves unused vertex slots
// uninitialized, so it is never copied) and the exact polygon of the same floats. False when
// a library would not take the shape as given (the caller draws again).
bool place(const Template& t, D2 c, Obb& obb, Polygon& poly, b2PolygonShape& b2, ex::Poly& exact) {
    if (t.box) {
        obb = Obb{f2(c), Vec2{to_float(t.hx), to_float(t.hy)}, t.angle};
        b2.SetAsBox(obb.half.x, obb.half.y, b2o::to_b2(obb.center), obb.angle());
        b2.m_radius = 0.0f;
        exact = ex::make_poly(obb);
        return true;
    }
    std::array<Vec2, 6> pts{};
    for (std::size_t i = 0; i < 6; ++i) pts[i] = f2(c + t.local[i]);
    if (!b2o::make_b2_polygon(pts, &b2)) return false;
    const std::optional<Polygon> p = make_polygon(pts);
    if (!p) return false;
    poly = *p;
    exact = ex::make_poly(std::span<const Vec2>(pts));
    return true;
}

double reach(const ex::Poly& p) {
    double m = 0.0;
    for (int i = 0; i < p.n; ++i) {
        const D2 v = p.v[static_cast<std::size_t>(i)];
        m = std::max({m, std::abs(v.x), std::abs(v.y)});
    }
    return m;
}

// ---------------------------------------------------------------------------------------
// 1. OBB-OBB and hexagon-hexagon MTD
// ---------------------------------------------------------------------------------------

struct PolyPairs {
    bool boxes = false;
    std::vector<std::array<Obb, 2>> obb;          // jostle, boxes
    std::vector<std::array<Polygon, 2>> poly;     // jostle, hexagons
    std::vector<std::array<Shape, 2>> shape;      // jostle, through the variant
    std::vector<std::array<b2PolygonShape, 2>> b2;
    std::vector<std::array<ex::Poly, 2>> exact;
    std::vector<double> L;
};

PolyPairs make_poly_pairs(bool boxes, std::uint64_t seed) {
    Rng rng(seed);
    PolyPairs p;
    p.boxes = boxes;
    p.obb.resize(kPool);
    p.poly.resize(kPool);
    p.shape.resize(kPool);
    p.b2.resize(kPool);
    p.exact.resize(kPool);
    p.L.resize(kPool);
    for (std::size_t i = 0; i < kPool;) {
        const Category cat = draw_category(rng);
        const auto draw = [&] {
            const double size = dd(rng.uniform(1.0f, 10.0f));
            return boxes ? random_box(rng, size) : random_hexagon(rng, size);
        };
        const Template ta = draw();
        const Template tb = draw();
        const D2 ca{dd(rng.uniform(-8.0f, 8.0f)), dd(rng.uniform(-8.0f, 8.0f))};
        const ex::Poly pa = exact_at(ta, ca);
        // B at base + t u: at t = 0 it sits near A's centre, at t0 (going out along u) they touch.
        const D2 u = random_dir(rng);
        const D2 base = ca + dd(rng.uniform(0.0f, 0.5f)) * ta.minor * random_dir(rng);
        const double t0 = touch_offset([&](double t) { return ex::sat(pa, exact_at(tb, base + t * u)).sep; },
                                       ta.bound + tb.bound + 1.0);
        const double scene = std::max(1.0, std::abs(ca.x) + ta.bound + tb.bound);
        const double t = cat == Category::overlap ? t0 * dd(rng.uniform(0.0f, 1.0f)) : t0 + miss_gap(cat, rng, scene);
        if (!place(ta, ca, p.obb[i][0], p.poly[i][0], p.b2[i][0], p.exact[i][0]) ||
            !place(tb, base + t * u, p.obb[i][1], p.poly[i][1], p.b2[i][1], p.exact[i][1]))
            continue;
        for (std::size_t k = 0; k < 2; ++k) p.shape[i][k] = boxes ? Shape{p.obb[i][k]} : Shape{p.poly[i][k]};
        p.L[i] = std::max({1.0, reach(p.exact[i][0]), reach(p.exact[i][1])});
        ++i;
    }
    return p;
}

Manifold jostle_mtd(const PolyPairs& p, std::size_t i) {
    return p.boxes ? collide(p.obb[i][0], p.obb[i][1]) : collide(p.poly[i][0], p.poly[i][1]);
}

bool box2d_hit(const PolyPairs& p, std::size_t i) {
    b2Manifold m{};
    const b2Transform xf = identity();
    b2CollidePolygons(&m, &p.b2[i][0], xf, &p.b2[i][1], xf);
    return m.pointCount > 0;
}

// jostle's MTD and, for jostle_point, its contact set.
struct MtdResult {
    Manifold m;
    ContactSet c;
};

// jostle against the exact SAT (hit, minimum depth, depth along its own normal) and against
// Box2D (hit/no-hit; Box2D's manifold depth is not a penetration depth when clipping cut the
// deepest vertex, see box2d_diff_test.cpp, so depths are judged against the exact values).
// With `points`, a hit's contact point must lie in both shapes up to the depth (it is the
// middle of the overlap).
void check_mtd(benchmark::State& state, const PolyPairs& p, const std::vector<MtdResult>& jostle,
               const std::vector<char>& box2d, bool points) {
    Checker c;
    for (std::size_t i = 0; i < kPool; ++i) {
        const double tol = kRel * p.L[i];
        const ex::Sat sat = ex::sat(p.exact[i][0], p.exact[i][1]);
        const Manifold& m = jostle[i].m;
        // A contact point lies on the incident shape's boundary and at most the depth outside
        // the other (clipping to the reference edge's extent can leave a deep point past the
        // reference shape's other edges, in Box2D as here). Returns the worst excess.
        const auto point_error = [&] {
            double w = 0.0;
            for (int k = 0; k < jostle[i].c.count; ++k) {
                const D2 q = d2(jostle[i].c.points[static_cast<std::size_t>(k)]);
                const double s0 = ex::signed_distance(p.exact[i][0], q).d, s1 = ex::signed_distance(p.exact[i][1], q).d;
                w = std::max({w, std::min(std::abs(s0), std::abs(s1)), std::max(s0, s1) - dd(m.depth)});
            }
            return w;
        };
        const std::string what = fmt("exact sep %.9g, jostle hit %d depth %.9g, box2d hit %d", sat.sep, m.hit,
                                     dd(m.depth), box2d[i]);
        if (m.hit ? sat.sep > tol : sat.sep < -tol) c.fail(i, "jostle's hit/no-hit is wrong: " + what);
        else if (m.hit && std::abs(dd(m.depth) - std::max(0.0, -sat.sep)) > tol)
            c.fail(i, "jostle's depth is not the minimum: " + what);
        else if (m.hit && std::abs(ex::pen_along(p.exact[i][0], p.exact[i][1], d2(m.normal)) - dd(m.depth)) > tol)
            c.fail(i, "jostle's depth is not the overlap along its normal: " + what);
        else if (m.hit != (box2d[i] != 0)) {
            if (std::abs(sat.sep) <= tol) ++c.band;
            else c.fail(i, "jostle and Box2D disagree outside the touching band: " + what);
        } else if (points && m.hit != (jostle[i].c.count > 0)) {
            c.fail(i, fmt("the contact set has %d points: ", jostle[i].c.count) + what);
        } else if (points && m.hit && point_error() > tol) {
            c.fail(i, fmt("a contact point is %.9g off a boundary or past the depth: ", point_error()) + what);
        }
    }
    c.report(state);
}

enum class MtdSide { box2d, jostle, jostle_shape, jostle_point };

void bm_mtd(benchmark::State& state, bool boxes, MtdSide side) {
    const PolyPairs p = make_poly_pairs(boxes, boxes ? 0x2545f4914f6cdd1dull : 0x9e3779b97f4a7c15ull);
    std::vector<MtdResult> jostle(kPool);
    std::vector<char> box2d(kPool);
    switch (side) {
    case MtdSide::box2d: {
        // Box2D writes its manifold into one hot scratch; the hit is what is compared.
        b2Manifold m{};
        const b2Transform xf = identity();
        time_pool(state, box2d, kPasses, [&](std::size_t i, char& hit) {
            b2CollidePolygons(&m, &p.b2[i][0], xf, &p.b2[i][1], xf);
            hit = m.pointCount > 0;
        });
        for (std::size_t i = 0; i < kPool; ++i) jostle[i].m = jostle_mtd(p, i);
        break;
    }
    case MtdSide::jostle:
        if (boxes)
            time_pool(state, jostle, kPasses, [&](std::size_t i, MtdResult& r) { r.m = collide(p.obb[i][0], p.obb[i][1]); });
        else
            time_pool(state, jostle, kPasses, [&](std::size_t i, MtdResult& r) { r.m = collide(p.poly[i][0], p.poly[i][1]); });
        break;
    case MtdSide::jostle_shape:
        time_pool(state, jostle, kPasses, [&](std::size_t i, MtdResult& r) { r.m = collide(p.shape[i][0], p.shape[i][1]); });
        break;
    case MtdSide::jostle_point:
        // The MTD with the 2-point contact set (clipping, as b2CollidePolygons does), the
        // 44-byte ContactSet initialised in its slot (see in_place).
        if (boxes)
            time_pool(state, jostle, kPasses, [&](std::size_t i, MtdResult& r) {
                in_place(r.c, [&] { return contacts(p.obb[i][0], p.obb[i][1]); });
            });
        else
            time_pool(state, jostle, kPasses, [&](std::size_t i, MtdResult& r) {
                in_place(r.c, [&] { return contacts(p.poly[i][0], p.poly[i][1]); });
            });
        for (MtdResult& r : jostle) r.m = r.c.manifold;
        break;
    }
    if (side == MtdSide::box2d) {
        count_hits(state, box2d, [](char h) { return h != 0; });
    } else {
        for (std::size_t i = 0; i < kPool; ++i) box2d[i] = box2d_hit(p, i);
        count_hits(state, jostle, [](const MtdResult& r) { return r.m.hit; });
    }
    check_mtd(state, p, jostle, box2d, side == MtdSide::jostle_point);
}

// ---------------------------------------------------------------------------------------
// 2. Polygon-circle and circle-circle
// ---------------------------------------------------------------------------------------

struct PolyCirclePairs {
    bool boxes = false;
    std::vector<Obb> obb;
    std::vector<Polygon> poly;
    std::vector<Circle> circle;
    std::vector<b2PolygonShape> b2;
    std::vector<b2CircleShape> b2c;
    std::vector<ex::Poly> exact;
    std::vector<double> L;
};

PolyCirclePairs make_poly_circle_pairs(bool boxes, std::uint64_t seed) {
    Rng rng(seed);
    PolyCirclePairs p;
    p.boxes = boxes;
    p.obb.resize(kPool);
    p.poly.resize(kPool);
    p.circle.resize(kPool);
    p.b2.resize(kPool);
    p.b2c.resize(kPool);
    p.exact.resize(kPool);
    p.L.resize(kPool);
    for (std::size_t i = 0; i < kPool;) {
        const Category cat = draw_category(rng);
        const double size = dd(rng.uniform(1.0f, 10.0f));
        const Template ta = boxes ? random_box(rng, size) : random_hexagon(rng, size);
        const D2 ca{dd(rng.uniform(-8.0f, 8.0f)), dd(rng.uniform(-8.0f, 8.0f))};
        if (!place(ta, ca, p.obb[i], p.poly[i], p.b2[i], p.exact[i])) continue;
        const float r = rng.uniform(0.25f, 5.0f);
        const D2 u = random_dir(rng);
        const D2 base = ca + dd(rng.uniform(0.0f, 0.5f)) * ta.minor * random_dir(rng);
        const double t0 = touch_offset([&](double t) { return ex::signed_distance(p.exact[i], base + t * u).d - dd(r); },
                                       ta.bound + dd(r) + 1.0);
        const double scene = std::max(1.0, std::abs(ca.x) + ta.bound + dd(r));
        const double t = cat == Category::overlap ? t0 * dd(rng.uniform(0.0f, 1.0f)) : t0 + miss_gap(cat, rng, scene);
        p.circle[i] = Circle{f2(base + t * u), r};
        p.b2c[i] = b2o::make_b2_circle(p.circle[i]);
        const Vec2 cc = p.circle[i].center;
        p.L[i] = std::max({1.0, reach(p.exact[i]), std::abs(dd(cc.x)) + dd(r), std::abs(dd(cc.y)) + dd(r)});
        ++i;
    }
    return p;
}

// The checks of a round pair: jostle's hit against the exact separation, its depth against
// the exact depth, and hit/no-hit against Box2D outside the touching band. Box2D's depth is
// exact here (no clipping) but the exact one already pins jostle's.
void check_round(Checker& c, std::size_t i, double sep, double L, const Manifold& m, bool box2d) {
    const double tol = kRel * L;
    const std::string what = fmt("exact sep %.9g, jostle hit %d depth %.9g, box2d hit %d", sep, m.hit, dd(m.depth), box2d);
    if (m.hit ? sep > tol : sep < -tol) c.fail(i, "jostle's hit/no-hit is wrong: " + what);
    else if (m.hit && std::abs(dd(m.depth) - std::max(0.0, -sep)) > tol) c.fail(i, "jostle's depth is wrong: " + what);
    else if (m.hit && std::abs(ex::len(d2(m.normal)) - 1.0) > 1e-5)
        c.fail(i, "jostle's normal is not a unit vector: " + what);
    else if (m.hit != box2d) {
        if (std::abs(sep) <= tol) ++c.band;
        else c.fail(i, "jostle and Box2D disagree outside the touching band: " + what);
    }
}

enum class RoundSide { box2d, jostle, jostle_sat, jostle_shape };

void bm_poly_circle(benchmark::State& state, bool boxes, RoundSide side) {
    const PolyCirclePairs p = make_poly_circle_pairs(boxes, boxes ? 0x8f1bbcdcbfa53e0bull : 0x5bd1e9955bd1e995ull);
    const auto jostle_one = [&](std::size_t i) {
        if (side == RoundSide::jostle_sat) return collide_sat(p.poly[i], p.circle[i]);
        return boxes ? collide(p.obb[i], p.circle[i]) : collide(p.poly[i], p.circle[i]);
    };
    std::vector<Manifold> jostle(kPool);
    std::vector<char> box2d(kPool);
    const b2Transform xf = identity();
    if (side == RoundSide::box2d) {
        b2Manifold m{};  // one hot scratch; the hit is what is compared
        time_pool(state, box2d, kPasses, [&](std::size_t i, char& hit) {
            b2CollidePolygonAndCircle(&m, &p.b2[i], xf, &p.b2c[i], xf);
            hit = m.pointCount > 0;
        });
        for (std::size_t i = 0; i < kPool; ++i) jostle[i] = jostle_one(i);
        count_hits(state, box2d, [](char h) { return h != 0; });
    } else {
        if (side == RoundSide::jostle_sat) {
            time_pool(state, jostle, kPasses, [&](std::size_t i, Manifold& m) { m = collide_sat(p.poly[i], p.circle[i]); });
        } else if (side == RoundSide::jostle_shape) {
            // Through the variant dispatch the world calls, shapes built outside the timed loop.
            std::vector<std::array<Shape, 2>> shapes(kPool);
            for (std::size_t i = 0; i < kPool; ++i)
                shapes[i] = {boxes ? Shape{p.obb[i]} : Shape{p.poly[i]}, Shape{p.circle[i]}};
            time_pool(state, jostle, kPasses, [&](std::size_t i, Manifold& m) { m = collide(shapes[i][0], shapes[i][1]); });
        } else if (boxes) {
            time_pool(state, jostle, kPasses, [&](std::size_t i, Manifold& m) { m = collide(p.obb[i], p.circle[i]); });
        } else {
            time_pool(state, jostle, kPasses, [&](std::size_t i, Manifold& m) { m = collide(p.poly[i], p.circle[i]); });
        }
        for (std::size_t i = 0; i < kPool; ++i) {
            b2Manifold m{};
            b2CollidePolygonAndCircle(&m, &p.b2[i], xf, &p.b2c[i], xf);
            box2d[i] = m.pointCount > 0;
        }
        count_hits(state, jostle, [](const Manifold& m) { return m.hit; });
    }
    Checker c;
    for (std::size_t i = 0; i < kPool; ++i) {
        const double sep = ex::signed_distance(p.exact[i], d2(p.circle[i].center)).d - dd(p.circle[i].radius);
        check_round(c, i, sep, p.L[i], jostle[i], box2d[i] != 0);
    }
    c.report(state);
}

struct CirclePairs {
    std::vector<std::array<Circle, 2>> circle;
    std::vector<std::array<b2CircleShape, 2>> b2;
    std::vector<double> L;
};

CirclePairs make_circle_pairs(std::uint64_t seed) {
    Rng rng(seed);
    CirclePairs p;
    for (std::size_t i = 0; i < kPool; ++i) {
        const Category cat = draw_category(rng);
        Circle a{{rng.uniform(-8.0f, 8.0f), rng.uniform(-8.0f, 8.0f)}, rng.uniform(0.25f, 5.0f)};
        const float rb = rng.uniform(0.25f, 5.0f);
        const double R = dd(a.radius) + dd(rb);
        const double scene = std::max(1.0, std::abs(dd(a.center.x)) + R);
        const double d = cat == Category::overlap ? R * dd(rng.uniform(0.0f, 1.0f)) : R + miss_gap(cat, rng, scene);
        const Circle b{f2(d2(a.center) + d * random_dir(rng)), rb};
        p.circle.push_back({a, b});
        p.b2.push_back({b2o::make_b2_circle(a), b2o::make_b2_circle(b)});
        double L = 1.0;
        for (const Circle& s : {a, b})
            L = std::max({L, std::abs(dd(s.center.x)) + dd(s.radius), std::abs(dd(s.center.y)) + dd(s.radius)});
        p.L.push_back(L);
    }
    return p;
}

void bm_circle_circle(benchmark::State& state, bool box2d_side, bool shape = false) {
    const CirclePairs p = make_circle_pairs(0xca5a826395121157ull);
    std::vector<Manifold> jostle(kPool);
    std::vector<char> box2d(kPool);
    const b2Transform xf = identity();
    if (box2d_side) {
        b2Manifold m{};  // one hot scratch; the hit is what is compared
        time_pool(state, box2d, kPasses, [&](std::size_t i, char& hit) {
            b2CollideCircles(&m, &p.b2[i][0], xf, &p.b2[i][1], xf);
            hit = m.pointCount > 0;
        });
        for (std::size_t i = 0; i < kPool; ++i) jostle[i] = collide(p.circle[i][0], p.circle[i][1]);
        count_hits(state, box2d, [](char h) { return h != 0; });
    } else {
        if (shape) {
            std::vector<std::array<Shape, 2>> shapes(kPool);
            for (std::size_t i = 0; i < kPool; ++i) shapes[i] = {Shape{p.circle[i][0]}, Shape{p.circle[i][1]}};
            time_pool(state, jostle, kPasses, [&](std::size_t i, Manifold& m) { m = collide(shapes[i][0], shapes[i][1]); });
        } else {
            time_pool(state, jostle, kPasses, [&](std::size_t i, Manifold& m) { m = collide(p.circle[i][0], p.circle[i][1]); });
        }
        for (std::size_t i = 0; i < kPool; ++i) {
            b2Manifold m{};
            b2CollideCircles(&m, &p.b2[i][0], xf, &p.b2[i][1], xf);
            box2d[i] = m.pointCount > 0;
        }
        count_hits(state, jostle, [](const Manifold& m) { return m.hit; });
    }
    Checker c;
    for (std::size_t i = 0; i < kPool; ++i) {
        const Circle& a = p.circle[i][0];
        const Circle& b = p.circle[i][1];
        const double sep = ex::dist(d2(a.center), d2(b.center)) - dd(a.radius) - dd(b.radius);
        check_round(c, i, sep, p.L[i], jostle[i], box2d[i] != 0);
    }
    c.report(state);
}

// ---------------------------------------------------------------------------------------
// 3. Casts and sweeps
// ---------------------------------------------------------------------------------------

struct CastPairs {
    std::vector<Polygon> poly;
    std::vector<std::array<Vec2, 2>> ray;  // from, to
    std::vector<b2PolygonShape> b2;
    std::vector<b2RayCastInput> b2ray;
    std::vector<ex::Poly> exact;
    std::vector<double> L;
};

// A hexagon and a ray starting outside its bounding circle: a third aimed at a point inside
// and long enough to get there (hits), a third passing 1e-3..3e-2 of the scene outside it
// (near misses, found by bisection on the exact distance), a third passing far outside.
CastPairs make_cast_pairs(std::uint64_t seed) {
    Rng rng(seed);
    CastPairs p;
    p.poly.resize(kPool);
    p.ray.resize(kPool);
    p.b2.resize(kPool);
    p.b2ray.resize(kPool);
    p.exact.resize(kPool);
    p.L.resize(kPool);
    for (std::size_t i = 0; i < kPool;) {
        const Category cat = draw_category(rng);
        const Template t = random_hexagon(rng, dd(rng.uniform(1.0f, 10.0f)));
        const D2 c{dd(rng.uniform(-6.0f, 6.0f)), dd(rng.uniform(-6.0f, 6.0f))};
        Obb unused;
        if (!place(t, c, unused, p.poly[i], p.b2[i], p.exact[i])) continue;
        const D2 u = random_dir(rng);
        const double far = t.bound * (1.0 + dd(rng.uniform(0.05f, 3.0f)));
        const double scene = std::max(1.0, std::abs(c.x) + std::abs(c.y) + t.bound);
        D2 from = c - far * u, to;
        if (cat == Category::overlap) {
            const D2 aim = c + dd(rng.uniform(0.0f, 0.9f)) * t.minor * random_dir(rng);
            to = from + dd(rng.uniform(1.0f, 2.5f)) * (aim - from);
        } else {
            // The line through the centre crosses the hexagon; slide it sideways to where it
            // just touches, then by the gap.
            const D2 w{-u.y, u.x};
            const double side = rng.below(2) ? 1.0 : -1.0;
            const double span = 2.0 * far;
            const auto gap_at = [&](double x) {
                const D2 start = from + side * x * w;
                return ex::segment_min_sd(p.exact[i], start, start + span * u).d;
            };
            const double o = touch_offset(gap_at, t.bound + 1.0);
            from = from + side * (o + miss_gap(cat, rng, scene)) * w;
            to = from + span * u;
        }
        p.ray[i] = {f2(from), f2(to)};
        p.b2ray[i].p1 = b2o::to_b2(p.ray[i][0]);
        p.b2ray[i].p2 = b2o::to_b2(p.ray[i][1]);
        p.b2ray[i].maxFraction = 1.0f;
        double L = std::max(1.0, reach(p.exact[i]));
        for (const Vec2 v : p.ray[i]) L = std::max({L, std::abs(dd(v.x)), std::abs(dd(v.y))});
        p.L[i] = L;
        ++i;
    }
    return p;
}

struct Box2DRay {
    b2RayCastOutput out;
    bool hit = false;
};

void bm_cast_polygon(benchmark::State& state, bool box2d_side, bool shape = false) {
    const CastPairs p = make_cast_pairs(0x5851f42d4c957f2dull);
    std::vector<CastHit> jostle(kPool);
    std::vector<Box2DRay> box2d(kPool);
    const b2Transform xf = identity();
    // Non-virtual, like jostle's free function (RayCast is virtual in b2Shape).
    const auto box2d_one = [&](std::size_t i, Box2DRay& r) {
        r.hit = p.b2[i].b2PolygonShape::RayCast(&r.out, p.b2ray[i], xf, 0);
    };
    if (box2d_side) {
        time_pool(state, box2d, kPasses, box2d_one);
        for (std::size_t i = 0; i < kPool; ++i) jostle[i] = cast(p.ray[i][0], p.ray[i][1], p.poly[i]);
        count_hits(state, box2d, [](const Box2DRay& r) { return r.hit; });
    } else {
        if (shape) {
            std::vector<Shape> shapes(p.poly.begin(), p.poly.end());
            time_pool(state, jostle, kPasses,
                      [&](std::size_t i, CastHit& h) { in_place(h, [&] { return cast(p.ray[i][0], p.ray[i][1], shapes[i]); }); });
        } else {
            time_pool(state, jostle, kPasses,
                      [&](std::size_t i, CastHit& h) { in_place(h, [&] { return cast(p.ray[i][0], p.ray[i][1], p.poly[i]); }); });
        }
        for (std::size_t i = 0; i < kPool; ++i) box2d_one(i, box2d[i]);
        count_hits(state, jostle, [](const CastHit& h) { return h.hit; });
    }
    Checker c;
    for (std::size_t i = 0; i < kPool; ++i) {
        const double tol = kRel * p.L[i];
        const D2 p0 = d2(p.ray[i][0]), p1 = d2(p.ray[i][1]), dir = p1 - p0;
        const double len = ex::len(dir);
        const ex::SegMin m = ex::segment_min_sd(p.exact[i], p0, p1);
        const CastHit& j = jostle[i];
        const Box2DRay& b = box2d[i];
        const std::string what = fmt("exact min distance %.9g, jostle hit %d t %.9g, box2d hit %d t %.9g", m.d, j.hit,
                                     dd(j.t), b.hit, b.hit ? dd(b.out.fraction) : 0.0);
        if (j.hit ? m.d > tol : m.d < -tol) {
            c.fail(i, "jostle's hit/no-hit is wrong: " + what);
        } else if (j.hit && std::abs(ex::signed_distance(p.exact[i], d2(j.point)).d) > tol) {
            c.fail(i, "jostle's hit point is not on the boundary: " + what);
        } else if (j.hit != b.hit) {
            if (std::abs(m.d) <= tol) ++c.band;
            else c.fail(i, "jostle and Box2D disagree outside the grazing band: " + what);
        } else if (j.hit) {
            // t along the ray: an error tol across the surface moves the entry by tol / cos.
            const double cosi = std::abs(ex::dot(d2(b2o::from_b2(b.out.normal)), dir)) / len;
            if (cosi >= kGrazeCos && std::abs(dd(j.t) - dd(b.out.fraction)) * len * cosi > tol)
                c.fail(i, "jostle's and Box2D's t differ: " + what);
        }
    }
    c.report(state);
}

struct SweepPairs {
    std::vector<Circle> a, b;  // A moves by v, B stands still
    std::vector<Vec2> v;
    std::vector<std::array<b2Vec2, 2>> centres;  // the TOI proxies point into these
    std::vector<b2TOIInput> toi;
    std::vector<double> L;
};

b2Sweep linear_sweep(Vec2 v) {
    b2Sweep s;
    s.localCenter.SetZero();
    s.c0.SetZero();
    s.c = b2o::to_b2(v);
    s.a0 = 0.0f;
    s.a = 0.0f;
    s.alpha0 = 0.0f;
    return s;
}

// A circle starting 0.5..8 clear of another and moving by v: a third aimed at a point inside B
// and long enough to get there (hits), a third whose path passes 1e-3..3e-2 of the scene clear
// of contact (near misses), a third passing 1.5..4 combined radii away (far). b2TimeOfImpact
// gets the same circles as one-vertex proxies with their radii and the same linear motion,
// as in box2d_diff_test.cpp.
SweepPairs make_sweep_pairs(std::uint64_t seed) {
    Rng rng(seed);
    SweepPairs p;
    p.a.resize(kPool);
    p.b.resize(kPool);
    p.v.resize(kPool);
    p.centres.resize(kPool);
    p.toi.resize(kPool);
    p.L.resize(kPool);
    for (std::size_t i = 0; i < kPool; ++i) {
        const Category cat = draw_category(rng);
        const Circle b{{rng.uniform(-5.0f, 5.0f), rng.uniform(-5.0f, 5.0f)}, rng.uniform(0.5f, 5.0f)};
        const float ra = rng.uniform(0.25f, 3.0f);
        const double R = dd(ra) + dd(b.radius);
        const D2 cb = d2(b.center), u = random_dir(rng), w{-u.y, u.x};
        const double d_start = R + dd(rng.uniform(0.5f, 8.0f));
        const double scene = std::max(1.0, std::abs(cb.x) + std::abs(cb.y) + R);
        D2 p0 = cb - d_start * u, v;
        if (cat == Category::overlap) {
            const D2 aim = cb + dd(rng.uniform(0.0f, 0.9f)) * dd(b.radius) * random_dir(rng);
            v = dd(rng.uniform(1.0f, 2.0f)) * (aim - p0);
        } else {
            const double side = rng.below(2) ? 1.0 : -1.0;
            const double off = cat == Category::near_miss ? R + miss_gap(cat, rng, scene) : R * dd(rng.uniform(1.5f, 4.0f));
            p0 = p0 + side * off * w;
            v = 2.0 * d_start * u;
        }
        p.a[i] = Circle{f2(p0), ra};
        p.b[i] = b;
        p.v[i] = f2(v);
        p.centres[i] = {b2o::to_b2(p.a[i].center), b2o::to_b2(b.center)};
        b2TOIInput& in = p.toi[i];
        in.proxyA.Set(&p.centres[i][0], 1, ra);
        in.proxyB.Set(&p.centres[i][1], 1, b.radius);
        in.sweepA = linear_sweep(p.v[i]);
        in.sweepB = linear_sweep(Vec2{});
        in.tMax = 1.0f;
        const Vec2 end = p.a[i].center + p.v[i];
        p.L[i] = std::max({1.0, std::abs(cb.x) + dd(b.radius), std::abs(cb.y) + dd(b.radius),
                           std::max(std::abs(dd(p.a[i].center.x)), std::abs(dd(p.a[i].center.y))) + dd(ra),
                           std::max(std::abs(dd(end.x)), std::abs(dd(end.y))) + dd(ra)});
    }
    return p;
}

void bm_sweep_circle(benchmark::State& state, bool box2d_side) {
    const SweepPairs p = make_sweep_pairs(0xd1b54a32d192ed03ull);
    std::vector<SweepHit> jostle(kPool);
    std::vector<b2TOIOutput> box2d(kPool);
    if (box2d_side) {
        time_pool(state, box2d, kPasses, [&](std::size_t i, b2TOIOutput& o) { b2TimeOfImpact(&o, &p.toi[i]); });
        for (std::size_t i = 0; i < kPool; ++i) jostle[i] = sweep(p.a[i], p.v[i], p.b[i]);
        count_hits(state, box2d, [](const b2TOIOutput& o) { return o.state == b2TOIOutput::e_touching; });
    } else {
        time_pool(state, jostle, kPasses,
                  [&](std::size_t i, SweepHit& h) { in_place(h, [&] { return sweep(p.a[i], p.v[i], p.b[i]); }); });
        for (std::size_t i = 0; i < kPool; ++i) b2TimeOfImpact(&box2d[i], &p.toi[i]);
        count_hits(state, jostle, [](const SweepHit& h) { return h.hit; });
    }
    Checker c;
    long box2d_failed = 0;
    for (std::size_t i = 0; i < kPool; ++i) {
        const double tol = kRel * p.L[i];
        const D2 p0 = d2(p.a[i].center), v = d2(p.v[i]), cb = d2(p.b[i].center);
        const double R = dd(p.a[i].radius) + dd(p.b[i].radius);
        const auto gap = [&](double t) { return ex::dist(p0 + t * v, cb) - R; };
        // closing speed along the contact normal at time t: -d gap / dt
        const auto closing = [&](double t) { return -ex::dot(ex::unit(p0 + t * v - cb), v); };
        const double gmin = ex::segment_min_sd(cb, R, p0, p0 + v).d;
        const SweepHit& j = jostle[i];
        const b2TOIOutput& b = box2d[i];
        const bool b_hit = b.state == b2TOIOutput::e_touching || b.state == b2TOIOutput::e_overlapped;
        const std::string what = fmt("exact min gap %.9g, jostle hit %d t %.9g, box2d state %d t %.9g", gmin, j.hit, dd(j.t),
                                     static_cast<int>(b.state), dd(b.t));
        if (j.hit ? gmin > tol : gmin < -tol) {
            c.fail(i, "jostle's hit/no-hit is wrong: " + what);
        } else if (j.hit && std::abs(gap(dd(j.t))) > tol) {
            c.fail(i, "the gap at jostle's t is not 0: " + what);
        } else if (b.state == b2TOIOutput::e_failed || b.state == b2TOIOutput::e_unknown) {
            ++box2d_failed;  // Box2D gave no answer; nothing to compare (none expected)
        } else if (b_hit && !j.hit) {
            c.fail(i, "Box2D hits, jostle misses: " + what);
        } else if (!b_hit && j.hit) {
            // Box2D reports a hit only once the surfaces overlap by ~3 slop.
            if (gmin >= -kToiHi - tol) ++c.band;
            else c.fail(i, "jostle hits, Box2D misses a path deep enough for Box2D: " + what);
        } else if (b_hit) {
            // Box2D's t lies in the 3-slop window after jostle's, converted to time by the
            // closing speed (box2d_diff_test.cpp).
            const double tj = dd(j.t), tb = dd(b.t);
            const double vn_j = closing(tj), vn_b = closing(tb);
            const double lo = tj + (kToiLo - 2.0 * tol) / std::max(vn_j, 1e-300);
            const double hi = vn_b > 0.0 ? tj + (kToiHi + 2.0 * tol) / vn_b : 1e300;
            if (tb < lo || tb > hi) c.fail(i, fmt("Box2D's t is outside [%.9g, %.9g]: ", lo, hi) + what);
        }
    }
    state.counters["box2d_failed"] = static_cast<double>(box2d_failed);
    c.report(state);
}

// ---------------------------------------------------------------------------------------
// 4. Pixel masks
// ---------------------------------------------------------------------------------------

// Row-major index of pixel (x, y) in rows of `width`.
std::size_t pixel_at(int x, int y, int width) {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
}

// An irregular blobby mask, half set: two octaves of smooth value noise (about 5 and 10 cells
// across, smoothstep-interpolated), thresholded at its median. Blobs and holes of many sizes,
// as sprites have, rather than per-pixel noise.
Mask make_blob_mask(int side, Rng& rng) {
    std::vector<float> field(pixel_at(0, side, side), 0.0f);
    for (const auto& [cells, amplitude] : {std::pair{5, 1.0f}, std::pair{10, 0.5f}}) {
        const int n = cells + 1;
        std::vector<float> grid(pixel_at(0, n, n));
        for (float& g : grid) g = rng.uniform(-1.0f, 1.0f) * amplitude;
        const auto at = [&](int gx, int gy) { return grid[pixel_at(gx, gy, n)]; };
        const auto smooth = [](float t) { return t * t * (3.0f - 2.0f * t); };
        for (int y = 0; y < side; ++y) {
            for (int x = 0; x < side; ++x) {
                const float fx = (static_cast<float>(x) + 0.5f) * static_cast<float>(cells) / static_cast<float>(side);
                const float fy = (static_cast<float>(y) + 0.5f) * static_cast<float>(cells) / static_cast<float>(side);
                const int gx = std::min(static_cast<int>(fx), cells - 1), gy = std::min(static_cast<int>(fy), cells - 1);
                const float tx = smooth(fx - static_cast<float>(gx)), ty = smooth(fy - static_cast<float>(gy));
                const float top = at(gx, gy) + (at(gx + 1, gy) - at(gx, gy)) * tx;
                const float bottom = at(gx, gy + 1) + (at(gx + 1, gy + 1) - at(gx, gy + 1)) * tx;
                field[pixel_at(x, y, side)] += top + (bottom - top) * ty;
            }
        }
    }
    std::vector<float> sorted = field;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
    const float median = sorted[sorted.size() / 2];
    Mask m(side, side);
    for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x)
            if (field[pixel_at(x, y, side)] > median) m.set(x, y, true);
    return m;
}

// The byte-per-pixel mask: one uint8 (0 or 1) per pixel, rows of `width` bytes.
struct ByteMask {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> pixels;
    const std::uint8_t* row(int y) const { return pixels.data() + pixel_at(0, y, width); }
};

ByteMask to_bytes(const Mask& m) {
    ByteMask b{m.width(), m.height(), std::vector<std::uint8_t>(pixel_at(0, m.height(), m.width()))};
    for (int y = 0; y < m.height(); ++y)
        for (int x = 0; x < m.width(); ++x) b.pixels[pixel_at(x, y, m.width())] = m.get(x, y) ? 1 : 0;
    return b;
}

struct BytePlaced {
    const ByteMask* mask = nullptr;
    int x = 0;
    int y = 0;
};

// The shared rectangle of two placed masks, in world pixels, [x0, x1) x [y0, y1).
struct Rect {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    bool empty() const { return x0 >= x1 || y0 >= y1; }
};
Rect shared_rect(int ax, int ay, int aw, int ah, int bx, int by, int bw, int bh) {
    return {std::max(ax, bx), std::max(ay, by), std::min(ax + aw, bx + bw), std::min(ay + ah, by + bh)};
}
Rect shared_rect(const BytePlaced& a, const BytePlaced& b) {
    return shared_rect(a.x, a.y, a.mask->width, a.mask->height, b.x, b.y, b.mask->width, b.mask->height);
}

// The straightforward loops over the shared rectangle, rows top to bottom (reading order).
[[gnu::noinline]] bool byte_overlaps(const BytePlaced& a, const BytePlaced& b) {
    const Rect r = shared_rect(a, b);
    for (int y = r.y0; y < r.y1; ++y) {
        const std::uint8_t* pa = a.mask->row(y - a.y) + (r.x0 - a.x);
        const std::uint8_t* pb = b.mask->row(y - b.y) + (r.x0 - b.x);
        for (int i = 0; i < r.x1 - r.x0; ++i)
            if ((pa[i] & pb[i]) != 0) return true;
    }
    return false;
}

[[gnu::noinline]] std::optional<Pixel> byte_first_overlap(const BytePlaced& a, const BytePlaced& b) {
    const Rect r = shared_rect(a, b);
    for (int y = r.y0; y < r.y1; ++y) {
        const std::uint8_t* pa = a.mask->row(y - a.y) + (r.x0 - a.x);
        const std::uint8_t* pb = b.mask->row(y - b.y) + (r.x0 - b.x);
        for (int i = 0; i < r.x1 - r.x0; ++i)
            if ((pa[i] & pb[i]) != 0) return Pixel{r.x0 + i, y};
    }
    return std::nullopt;
}

[[gnu::noinline]] int byte_count_overlap(const BytePlaced& a, const BytePlaced& b) {
    const Rect r = shared_rect(a, b);
    int n = 0;
    for (int y = r.y0; y < r.y1; ++y) {
        const std::uint8_t* pa = a.mask->row(y - a.y) + (r.x0 - a.x);
        const std::uint8_t* pb = b.mask->row(y - b.y) + (r.x0 - b.x);
        for (int i = 0; i < r.x1 - r.x0; ++i) n += pa[i] & pb[i];
    }
    return n;
}

constexpr int kMaskSides[] = {64, 128, 256};
constexpr int kMasksPerSide = 8;

// kMasksPerSide blob masks of one size, both ways, and kPool placed pairs of two different
// masks: A anywhere in [-300, 300)^2, B at an offset of up to side - 1 each way, so the
// rectangles always share at least a pixel (at random alignments to the 64-pixel words).
// The lecture's answers for every pair are kept for the checks, with the pixels a reading-order
// scan of the shared rectangle examines: up to the first shared pixel (or all) for yes/no and
// first, all of them for the count.
struct MaskPool {
    std::vector<Mask> masks;
    std::vector<ByteMask> bytes;
    struct Pair {
        PlacedMask a, b;
        BytePlaced ba, bb;
    };
    std::vector<Pair> pairs;
    std::vector<std::optional<Pixel>> first;
    std::vector<int> count;
    double pixels_to_first = 0.0;
    double pixels_all = 0.0;
};

MaskPool make_mask_pool(int side) {
    Rng rng(0x6a09e667f3bcc908ull + static_cast<std::uint64_t>(side));
    MaskPool p;
    for (int k = 0; k < kMasksPerSide; ++k) p.masks.push_back(make_blob_mask(side, rng));
    for (const Mask& m : p.masks) p.bytes.push_back(to_bytes(m));
    const auto pick = [&](std::uint32_t n) { return static_cast<int>(rng.below(n)); };
    for (std::size_t i = 0; i < kPool; ++i) {
        const auto ia = static_cast<std::size_t>(pick(kMasksPerSide));
        const auto ib = (ia + 1 + static_cast<std::size_t>(pick(kMasksPerSide - 1))) % kMasksPerSide;
        const int ax = pick(600) - 300, ay = pick(600) - 300;
        const auto offset = [&] { return pick(static_cast<std::uint32_t>(2 * side - 1)) - (side - 1); };
        const int bx = ax + offset(), by = ay + offset();
        p.pairs.push_back({{&p.masks[ia], ax, ay}, {&p.masks[ib], bx, by}, {&p.bytes[ia], ax, ay}, {&p.bytes[ib], bx, by}});
        const MaskPool::Pair& q = p.pairs.back();
        p.first.push_back(reference::first_overlap(q.a, q.b));
        p.count.push_back(reference::count_overlap(q.a, q.b));
        const Rect r = shared_rect(q.ba, q.bb);
        const double all = static_cast<double>(r.x1 - r.x0) * static_cast<double>(r.y1 - r.y0);
        const std::optional<Pixel>& f = p.first.back();
        p.pixels_all += all;
        p.pixels_to_first += f ? static_cast<double>(pixel_at(f->x - r.x0, f->y - r.y0, r.x1 - r.x0) + 1) : all;
    }
    return p;
}

// Made on first use and shared by the mask benchmarks (the lecture's answers cost a moment at
// 256 x 256). Owned by main, so nothing is global.
class Inputs {
public:
    const MaskPool& masks(int side) {
        for (const auto& [s, pool] : pools_)
            if (s == side) return *pool;
        pools_.emplace_back(side, std::make_unique<MaskPool>(make_mask_pool(side)));
        return *pools_.back().second;
    }

private:
    std::vector<std::pair<int, std::unique_ptr<MaskPool>>> pools_;
};

enum class MaskQuery { overlaps, first, count };
enum class MaskSide { lecture, bytes, jostle };

// An iteration is one pass over the pool for the count and kMaskPasses for the queries that
// stop at the first shared pixel (so that their times read in the table too). Results are
// checked against the lecture's answers.
constexpr int kMaskPasses = 16;

// Times the chosen implementation of one query; each maps a pair's index to its answer.
template <class Out, class Lecture, class Bytes, class Jostle>
double time_mask(benchmark::State& state, std::vector<Out>& out, int passes, MaskSide impl, Lecture&& lecture,
                 Bytes&& bytes, Jostle&& jostle) {
    switch (impl) {
    case MaskSide::lecture: return time_pool(state, out, passes, [&](std::size_t i, Out& o) { o = lecture(i); });
    case MaskSide::bytes: return time_pool(state, out, passes, [&](std::size_t i, Out& o) { o = bytes(i); });
    case MaskSide::jostle: break;
    }
    return time_pool(state, out, passes, [&](std::size_t i, Out& o) { o = jostle(i); });
}

std::string str(const std::optional<Pixel>& p) { return p ? fmt("(%d, %d)", p->x, p->y) : std::string("none"); }

// jostle's side is the public query (the best kernel the CPU has), or with `pinned` the kernel
// given (BM_MaskKernels: each kernel the CPU has on the same pool).
template <class Count, class First, class Any>
void bm_mask_with(benchmark::State& state, Inputs& inputs, int side, MaskQuery query, MaskSide impl, Count&& count,
                  First&& first, Any&& any) {
    const MaskPool& p = inputs.masks(side);
    const auto& q = p.pairs;
    const int passes = query == MaskQuery::count ? 1 : kMaskPasses;
    Checker c;
    double ns = 0.0;
    double pixels = p.pixels_to_first;
    if (query == MaskQuery::count) {
        std::vector<int> out(kPool);
        ns = time_mask(
            state, out, passes, impl, [&](std::size_t i) { return reference::count_overlap(q[i].a, q[i].b); },
            [&](std::size_t i) { return byte_count_overlap(q[i].ba, q[i].bb); },
            [&](std::size_t i) { return count(q[i].a, q[i].b); });
        for (std::size_t i = 0; i < kPool; ++i)
            if (out[i] != p.count[i]) c.fail(i, fmt("count %d, the lecture's loop counts %d", out[i], p.count[i]));
        pixels = p.pixels_all;
        count_hits(state, out, [](int n) { return n > 0; });
    } else if (query == MaskQuery::first) {
        std::vector<std::optional<Pixel>> out(kPool);
        ns = time_mask(
            state, out, passes, impl, [&](std::size_t i) { return reference::first_overlap(q[i].a, q[i].b); },
            [&](std::size_t i) { return byte_first_overlap(q[i].ba, q[i].bb); },
            [&](std::size_t i) { return first(q[i].a, q[i].b); });
        for (std::size_t i = 0; i < kPool; ++i)
            if (out[i] != p.first[i])
                c.fail(i, "first " + str(out[i]) + ", the lecture's loop finds " + str(p.first[i]));
        count_hits(state, out, [](const std::optional<Pixel>& f) { return f.has_value(); });
    } else {
        std::vector<char> out(kPool);
        ns = time_mask(
            state, out, passes, impl, [&](std::size_t i) -> char { return reference::overlaps(q[i].a, q[i].b); },
            [&](std::size_t i) -> char { return byte_overlaps(q[i].ba, q[i].bb); },
            [&](std::size_t i) -> char { return any(q[i].a, q[i].b); });
        for (std::size_t i = 0; i < kPool; ++i)
            if ((out[i] != 0) != p.first[i].has_value())
                c.fail(i, fmt("overlaps %d, the lecture's loop %d", out[i], p.first[i].has_value()));
        count_hits(state, out, [](char h) { return h != 0; });
    }
    // Pixels a reading-order scan of the shared rectangles examines, per ns of the timed loop
    // (the ceiling of a bit-packed scan is 64 pixels per AND of two words).
    state.counters["px/ns"] = pixels * static_cast<double>(passes) * static_cast<double>(state.iterations()) / ns;
    c.report(state, false);
}

void bm_mask(benchmark::State& state, Inputs& inputs, int side, MaskQuery query, MaskSide impl) {
    bm_mask_with(
        state, inputs, side, query, impl, [](const PlacedMask& a, const PlacedMask& b) { return count_overlap(a, b); },
        [](const PlacedMask& a, const PlacedMask& b) { return first_overlap(a, b); },
        [](const PlacedMask& a, const PlacedMask& b) { return overlaps(a, b); });
}

void bm_mask_kernel(benchmark::State& state, Inputs& inputs, int side, MaskQuery query, detail::MaskKernel k) {
    bm_mask_with(
        state, inputs, side, query, MaskSide::jostle,
        [k](const PlacedMask& a, const PlacedMask& b) { return detail::count_overlap(a, b, k); },
        [k](const PlacedMask& a, const PlacedMask& b) { return detail::first_overlap(a, b, k); },
        [k](const PlacedMask& a, const PlacedMask& b) { return detail::overlaps(a, b, k); });
}

// ---------------------------------------------------------------------------------------
// A mask buried deep in a large convex shape: the MTD search with and without its shortcuts
// ---------------------------------------------------------------------------------------

enum class DeepShape { box, obb, hexagon, circle };

// Eight placements per shape: a 32 px round mask whose centre lies `depth` px inside the
// shape's nearest face, at seeded angles and offsets.
struct DeepPool {
    Mask mask{32, 32};
    std::vector<Shape> shapes;
};

DeepPool make_deep_pool(DeepShape kind, int depth) {
    DeepPool p;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x)
            if ((x - 15.5) * (x - 15.5) + (y - 15.5) * (y - 15.5) <= 16.0 * 16.0) p.mask.set(x, y, true);
    Rng rng(static_cast<std::uint64_t>(depth) * 4 + static_cast<std::uint64_t>(kind));
    const float r = static_cast<float>(depth);
    for (int k = 0; k < 8; ++k) {
        // The mask stays at (0, 0); its centre is (16, 16). The shape's centre is moved off it.
        const Vec2 c{16.0f + rng.uniform(-0.3f, 0.3f) * r, 16.0f + rng.uniform(-0.3f, 0.3f) * r};
        const float reach = r + std::max(std::abs(c.x - 16.0f), std::abs(c.y - 16.0f));  // nearest face >= r away
        switch (kind) {
            case DeepShape::box: p.shapes.push_back(Aabb{{c.x - reach, c.y - 1.3f * reach}, {c.x + 1.2f * reach, c.y + reach}}); break;
            case DeepShape::obb: p.shapes.push_back(Obb{c, {1.5f * reach, 1.5f * reach}, rng.uniform(-3.1f, 3.1f)}); break;
            case DeepShape::hexagon: {
                std::array<Vec2, 6> pts;
                const float a0 = rng.uniform(0.0f, 1.0f);
                for (std::size_t i = 0; i < 6; ++i)
                    pts[i] = {c.x + 1.3f * reach * std::cos(a0 + 1.0471976f * static_cast<float>(i)),
                              c.y + 1.3f * reach * std::sin(a0 + 1.0471976f * static_cast<float>(i))};
                p.shapes.push_back(*make_polygon(pts));
                break;
            }
            case DeepShape::circle: p.shapes.push_back(Circle{c, reach}); break;
        }
    }
    return p;
}

// collide(mask, each shape) timed with the MTD search's shortcuts on or off, then checked
// against the other setting's answers, bit for bit (every pair must hit).
void time_mask_mtd(benchmark::State& state, const Shape& mask, const std::vector<Shape>& shapes, bool shortcuts) {
    std::vector<Manifold> out(shapes.size());
    detail::use_mask_search_shortcuts(shortcuts);
    time_pool(state, out, 1, [&](std::size_t i, Manifold& m) { m = collide(mask, shapes[i]); });
    detail::use_mask_search_shortcuts(!shortcuts);
    Checker c;
    for (std::size_t i = 0; i < out.size(); ++i) {
        const Manifold other = collide(mask, shapes[i]);
        if (!out[i].hit || other.hit != out[i].hit || std::bit_cast<std::uint32_t>(other.depth) != std::bit_cast<std::uint32_t>(out[i].depth) ||
            std::bit_cast<std::uint64_t>(other.normal) != std::bit_cast<std::uint64_t>(out[i].normal))
            c.fail(i, fmt("depth %.9g normal (%.9g, %.9g) against %.9g (%.9g, %.9g)", out[i].depth, out[i].normal.x,
                          out[i].normal.y, other.depth, other.normal.x, other.normal.y));
    }
    detail::use_mask_search_shortcuts(true);
    c.report(state, false);
}

void bm_mask_mtd_deep(benchmark::State& state, DeepShape kind, int depth, bool shortcuts) {
    const DeepPool p = make_deep_pool(kind, depth);
    const Shape mask = PlacedMask{&p.mask, 0, 0};
    time_mask_mtd(state, mask, p.shapes, shortcuts);
}

// ---------------------------------------------------------------------------------------
// A full mask crossed by a thin shape: the MTD search with and without its column jumps
// ---------------------------------------------------------------------------------------

struct ThinPool {
    Mask solid;
    std::vector<Mask> lines;  // the segments as one-pixel masks, the solid's size
    std::vector<Shape> shapes;  // the segments, or the line masks placed at the solid's corner
};

ThinPool make_thin_pool(bool segments, int side) {
    ThinPool p{Mask(side, side), {}, {}};
    for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x) p.solid.set(x, y, true);
    const float n = static_cast<float>(side);
    const std::array<Segment, 4> cuts{Segment{{0, 0}, {n, n}}, Segment{{0, n}, {n, 0}}, Segment{{0, 0.3f * n}, {n, 0.7f * n}},
                                      Segment{{0.2f * n, n}, {0.6f * n, 0}}};
    p.lines.reserve(cuts.size());  // shapes point into it
    for (const Segment& s : cuts) {
        if (segments) {
            p.shapes.push_back(s);
            continue;
        }
        Mask& line = p.lines.emplace_back(side, side);
        for (int k = 0; k <= 4 * side; ++k) {
            const Vec2 q = s.a + (static_cast<float>(k) / (4.0f * n)) * (s.b - s.a);
            line.set(std::min(side - 1, static_cast<int>(q.x)), std::min(side - 1, static_cast<int>(q.y)), true);
        }
        p.shapes.push_back(PlacedMask{&line, 0, 0});
    }
    return p;
}

void bm_mask_mtd_thin(benchmark::State& state, bool segments, int side, bool shortcuts) {
    const ThinPool p = make_thin_pool(segments, side);
    const Shape mask = PlacedMask{&p.solid, 0, 0};
    time_mask_mtd(state, mask, p.shapes, shortcuts);
}

// ---------------------------------------------------------------------------------------
// Registration
// ---------------------------------------------------------------------------------------

// Registers one benchmark; anchors carry the label "anchor" (tools/bench-ratios looks for it).
template <class Fn>
void add(const std::string& name, bool anchor, Fn&& fn) {
    benchmark::RegisterBenchmark(name.c_str(),
                                 [anchor, fn = std::forward<Fn>(fn)](benchmark::State& state) {
                                     fn(state);
                                     if (anchor) state.SetLabel("anchor");
                                 })
        ->Unit(benchmark::kMillisecond);
}

void register_all(Inputs& inputs) {
    for (const bool boxes : {true, false}) {
        const std::string base = boxes ? "BM_ObbMtd/mix/" : "BM_HexMtd/mix/";
        add(base + "box2d", true, [=](benchmark::State& s) { bm_mtd(s, boxes, MtdSide::box2d); });
        add(base + "jostle", false, [=](benchmark::State& s) { bm_mtd(s, boxes, MtdSide::jostle); });
        add(base + "jostle_shape", false, [=](benchmark::State& s) { bm_mtd(s, boxes, MtdSide::jostle_shape); });
        add(base + "jostle_point", false, [=](benchmark::State& s) { bm_mtd(s, boxes, MtdSide::jostle_point); });
    }
    for (const bool boxes : {false, true}) {
        const std::string base = boxes ? "BM_PolyCircle/obb/mix/" : "BM_PolyCircle/hex/mix/";
        add(base + "box2d", true, [=](benchmark::State& s) { bm_poly_circle(s, boxes, RoundSide::box2d); });
        add(base + "jostle", false, [=](benchmark::State& s) { bm_poly_circle(s, boxes, RoundSide::jostle); });
        add(base + "jostle_shape", false, [=](benchmark::State& s) { bm_poly_circle(s, boxes, RoundSide::jostle_shape); });
        if (!boxes)
            add(base + "jostle_sat", false, [=](benchmark::State& s) { bm_poly_circle(s, boxes, RoundSide::jostle_sat); });
    }
    add("BM_CircleCircle/mix/box2d", true, [](benchmark::State& s) { bm_circle_circle(s, true); });
    add("BM_CircleCircle/mix/jostle", false, [](benchmark::State& s) { bm_circle_circle(s, false); });
    add("BM_CircleCircle/mix/jostle_shape", false, [](benchmark::State& s) { bm_circle_circle(s, false, true); });
    add("BM_CastPolygon/hex/mix/box2d", true, [](benchmark::State& s) { bm_cast_polygon(s, true); });
    add("BM_CastPolygon/hex/mix/jostle", false, [](benchmark::State& s) { bm_cast_polygon(s, false); });
    add("BM_CastPolygon/hex/mix/jostle_shape", false, [](benchmark::State& s) { bm_cast_polygon(s, false, true); });
    add("BM_SweepCircle/mix/box2d", true, [](benchmark::State& s) { bm_sweep_circle(s, true); });
    add("BM_SweepCircle/mix/jostle", false, [](benchmark::State& s) { bm_sweep_circle(s, false); });
    struct Query {
        const char* name;
        MaskQuery query;
    };
    for (const Query q : {Query{"BM_MaskOverlaps", MaskQuery::overlaps}, Query{"BM_MaskFirst", MaskQuery::first},
                          Query{"BM_MaskCount", MaskQuery::count}}) {
        for (const int side : kMaskSides) {
            const std::string base = std::string(q.name) + "/" + std::to_string(side) + "/";
            const MaskQuery query = q.query;
            for (const MaskSide baseline : {MaskSide::lecture, MaskSide::bytes}) {
                const std::string group = base + (baseline == MaskSide::lecture ? "vs_lecture/" : "vs_bytes/");
                add(group + (baseline == MaskSide::lecture ? "lecture" : "bytes"), true,
                    [=, &inputs](benchmark::State& s) { bm_mask(s, inputs, side, query, baseline); });
                add(group + "jostle", false,
                    [=, &inputs](benchmark::State& s) { bm_mask(s, inputs, side, query, MaskSide::jostle); });
            }
        }
    }
    // Each mask kernel the CPU has, from bmi2 (the anchor) up, on the 64 and 128 px pools (no
    // target: what the vector kernels give, on the CPU the run is on).
    using detail::MaskKernel;
    for (const Query q : {Query{"overlaps", MaskQuery::overlaps}, Query{"first", MaskQuery::first}, Query{"count", MaskQuery::count}}) {
        for (const int side : {64, 128}) {
            const std::string base = std::string("BM_MaskKernels/") + q.name + "/" + std::to_string(side) + "/";
            const MaskQuery query = q.query;
            for (const auto& kernel : {std::pair{MaskKernel::bmi2, "bmi2"}, std::pair{MaskKernel::avx2, "avx2"},
                                       std::pair{MaskKernel::avx512, "avx512"}}) {
                const MaskKernel k = kernel.first;  // a copy: clang 14 cannot capture a structured binding
                const char* const name = kernel.second;
                if (static_cast<int>(k) > static_cast<int>(detail::best_mask_kernel())) continue;
                add(base + name, k == MaskKernel::bmi2,
                    [=, &inputs](benchmark::State& s) { bm_mask_kernel(s, inputs, side, query, k); });
            }
        }
    }
    struct Deep {
        const char* name;
        DeepShape kind;
    };
    for (const Deep d : {Deep{"box", DeepShape::box}, Deep{"obb", DeepShape::obb}, Deep{"hexagon", DeepShape::hexagon},
                         Deep{"circle", DeepShape::circle}}) {
        for (const int depth : {100, 1000}) {
            const std::string base = std::string("BM_MaskMtdDeep/") + d.name + "/" + std::to_string(depth) + "/";
            const DeepShape kind = d.kind;
            add(base + "plain_scan", true, [=](benchmark::State& s) { bm_mask_mtd_deep(s, kind, depth, false); });
            add(base + "jostle", false, [=](benchmark::State& s) { bm_mask_mtd_deep(s, kind, depth, true); });
        }
    }
    for (const bool segments : {true, false}) {
        for (const int side : {64, 128, 256}) {
            const std::string base = std::string("BM_MaskMtdThin/") + (segments ? "segment/" : "line/") + std::to_string(side) + "/";
            add(base + "plain_scan", true, [=](benchmark::State& s) { bm_mask_mtd_thin(s, segments, side, false); });
            add(base + "jostle", false, [=](benchmark::State& s) { bm_mask_mtd_thin(s, segments, side, true); });
        }
    }
}

}  // namespace

int main(int argc, char** argv) {
    Inputs inputs;
    register_all(inputs);
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
