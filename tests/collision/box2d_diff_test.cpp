// Differential tests: jostle's collision module against Box2D 2.4.1 as the oracle, on seeded
// random pairs (DESIGN.md, Testing). Every pair is also evaluated exactly (in double, on the
// same float shapes, see box2d_oracle.h) to classify it and to adjudicate disagreements.
//
// PAIRS: 100,000 per pair kind by default; JOSTLE_DIFF_SCALE=10 runs 10x more (read once).
// Each test prints one summary line ("[box2d-diff] ...") and records the same numbers as
// GoogleTest properties, and fails with the first few disagreements, shape data included
// (floats printed with 9 significant digits, so a line is an exact repro).
//
// SCALE: shapes are 0.5..10 units across and lie within about 25 units of the origin, so that
// Box2D's constants (b2_lengthUnitsPerMeter = 1, b2_linearSlop = 0.005) mean what they mean in
// a Box2D world. Every distance tolerance is relative to the pair's length scale
//   L = max(1, the largest |coordinate| any of the pair's shapes reaches over the test)
// because float rounding is relative to the coordinates (an ulp at 25 is 1.9e-6).
//
// TOLERANCES (and why)
//   tol = kRel * L, kRel = 1e-4. The manual promises depths and normals within about 1e-4 of
//       the shapes' size of a double computation; Box2D's float arithmetic is far better than
//       that (jostle and Box2D agree to < 1e-6 L where both are right), so comparing two float
//       results with one 1e-4 budget is the manual's own figure. It is used for: depth
//       differences, hit points, gaps, and the touching band (a pair whose exact separation is
//       within tol of 0 may be a hit in one library and a miss in the other: both are exact
//       tests up to rounding).
//   kNormalTol = 1e-3 (|n_jostle - n_box2d|, ~0.06 degrees), plus kNormalCond * L / len when
//       the normal is a normalized difference of length len (circle centres, centre to vertex):
//       the direction of a float vector of length len has an error of a few ulps(L) / len.
//       Polygon normals are first matched to the exact face axis each stands for; on the same
//       axis they agree to < 1e-5, different axes are ties or failures (below).
//       Sweeps add the slack jostle's own timing error implies: its gap |g(tj)| moves the
//       centre |v| |g(tj)| / vn along the path, turning a centre-to-vertex direction by that
//       over the radius (only glancing hits, vn << |v|, get a visible slack).
//   kTieTol = 0.1 * b2_linearSlop = 5e-4: b2CollidePolygons keeps A's face as the reference
//       unless B's separation is larger by more than k_tol = 0.1 * b2_linearSlop; so Box2D's
//       reference face may be up to kTieTol less separated than the best axis, and a
//       different jostle normal is accepted when it is a true face axis whose overlap is
//       jostle's depth and that depth lies in [box2d - kTieTol - tol, box2d + tol] ("tie").
//   Time of impact: b2TimeOfImpact stops when the core distance (radii excluded) reaches
//       target = max(b2_linearSlop, totalRadius - 3 b2_linearSlop) within tolerance
//       0.25 b2_linearSlop. With a circle of radius >= 0.25 in every pair, the target is
//       totalRadius - 3 slop: Box2D reports the time when the surfaces OVERLAP by
//       3 +- 0.25 slop (0.015 +- 0.00125), not a time before contact. The gap g(t) (signed
//       distance of the surfaces) is convex in t for linear motion, so with jostle's contact
//       time tj (g(tj) = 0) and Box2D's tb (g(tb) in [-3.25, -2.75] slop):
//         tb - tj >= (2.75 slop - 2 tol) / vn(tj)   and   tb - tj <= (3.25 slop + 2 tol) / vn(tb)
//       where vn = -g' is the closing speed along the contact normal: the slop window
//       converted to time by the relative speed, exactly, even for glancing hits.
//   Casts: t is compared along the ray, |tj - tb| |to - from| <= tol / cos(incidence), since an
//       error tol across the surface moves the entry point by tol / cos along the ray.
//       kGrazeCos = 1e-3: below ~0.06 degrees the entry point is undefined in float; there
//       only the hit point is checked (on the boundary, within tol), not t against Box2D.
//
// WHAT IS COMPARED, per pair kind
//   1. polygon-polygon (random convex 3..8 vertices, b2PolygonShape::Set, m_radius = 0) and
//      OBB-OBB (SetAsBox with centre and angle; 15% of the A's are Aabbs): b2CollidePolygons.
//      Box2D with m_radius = 0 is an exact closed overlap test (it returns when a separation is
//      > 0), so hit/no-hit must agree outside the touching band. Box2D's normal is its reference
//      face normal (from b2FindMaxSeparation: the SAT minimum axis up to kTieTol); its depth,
//      max over manifold points of -separation, is the penetration along that face only when
//      the deepest incident vertex survived clipping to the reference face's side planes. When
//      clipping cut it off ("clipped": manifold depth < overlap along Box2D's normal by more
//      than tol) the manifold depth is no penetration depth at all, and jostle's depth is
//      compared with the overlap along Box2D's normal recomputed exactly instead (rare:
//      ~2 in 100,000 random pairs). Box2D also returns no points for rectangles that touch
//      only at a corner (the clipped incident edge has zero length): the exactly touching
//      integer rectangles accept that as Box2D's band, while jostle must report hit, depth 0.
//   2. polygon-circle (polygon, Obb or Aabb vs circle; also collide_sat, which the manual says
//      gives the same result: SAT may return a face axis nearly parallel to the centre-to-
//      vertex axis when their pushes tie within rounding, accepted when the overlap along it
//      is its depth) and circle-circle: b2CollidePolygonAndCircle / b2CollideCircles.
//      Their depth is exact (no clipping): r - signed distance, rA + rB - |d|. Normal ties:
//      a centre inside the polygon at equal distance (within tol) from two faces, or a centre
//      within tol of the boundary (direction undefined) or of the other centre.
//   3. casts: segment vs polygon/Obb/Aabb and vs circle, b2Shape::RayCast with maxFraction 1.
//      Box2D reports nothing for a ray starting inside (or on the boundary going in): those
//      pairs are checked against the manual alone (t = 0, point = from, normal {0,0}).
//      A ray through a vertex may take either face's normal (counted as ties).
//   4. sweeps: moving circle vs circle and vs polygon/Obb/Aabb (B static or moving) against
//      b2TimeOfImpact with linear b2Sweeps, tMax = 1, using the window above. Hits that
//      Box2D cannot see (the surfaces never overlap by 3.25 slop within the frame) are the
//      grazing band; pairs that start overlapping by less than 2.75 slop are not compared
//      (Box2D lets them sink to 3 slop first); jostle must report t = 0 for them.
// Every kind also checks jostle against the exact computation within tol (depth, t, hit
// point, normal), so a wrong answer on which Box2D cannot speak still fails.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
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

constexpr double kPi = 3.14159265358979323846;
constexpr double kRel = 1e-4;
constexpr double kNormalTol = 1e-3;
constexpr double kNormalCond = 8e-7;
constexpr double kSlop = static_cast<double>(b2_linearSlop);
constexpr double kTieTol = 0.1 * kSlop;
constexpr double kToiLo = 2.75 * kSlop;
constexpr double kToiHi = 3.25 * kSlop;
constexpr double kGrazeCos = 1e-3;
constexpr int kShownFailures = 8;

int diff_scale() {
    static const int scale = [] {
        const char* s = std::getenv("JOSTLE_DIFF_SCALE");
        const int v = s ? std::atoi(s) : 1;
        return v >= 1 ? v : 1;
    }();
    return scale;
}
long pair_count() { return 100000L * diff_scale(); }

// ---------------------------------------------------------------------------------------
// Formatting (9 significant digits: a printed float reads back as the same float)
// ---------------------------------------------------------------------------------------

__attribute__((format(printf, 1, 2))) std::string fmt(const char* f, ...) {
    char buf[1024];
    va_list ap;
    va_start(ap, f);
    std::vsnprintf(buf, sizeof buf, f, ap);
    va_end(ap);
    return buf;
}
std::string str(Vec2 v) { return fmt("{%.9g, %.9g}", static_cast<double>(v.x), static_cast<double>(v.y)); }
std::string str(const Circle& c) { return fmt("Circle{%s, %.9g}", str(c.center).c_str(), static_cast<double>(c.radius)); }
std::string str(D2 v) { return fmt("(%.9g, %.9g)", v.x, v.y); }
double dd(float f) { return static_cast<double>(f); }
D2 d2(Vec2 v) { return ex::d2(v); }
// Every double -> float rounding of generated data goes through to_float: GCC 12.2 at -O2/-O3
// SLP-vectorizes a pair of double -> float -> double conversions into the identity (wrong
// code: the float rounding disappears, reproduced in isolation), which made the exact side
// evaluate the unrounded shapes instead of the floats jostle and Box2D were given. The
// volatile store is the rounding the optimizer cannot see through.
float to_float(double d) {
    volatile float f = static_cast<float>(d);
    return f;
}
Vec2 f2(D2 v) { return {to_float(v.x), to_float(v.y)}; }

// ---------------------------------------------------------------------------------------
// Statistics and failure reporting
// ---------------------------------------------------------------------------------------

struct Stats {
    std::string kind;
    long pairs = 0;
    long box2d_hits = 0;
    long jostle_hits = 0;
    long agree = 0;     // compared with Box2D and agreed (ties and clipped included)
    long band = 0;      // disagreed on hit/no-hit or timing inside the touching/grazing band
    long excluded = 0;  // Box2D cannot answer (ray starts inside, shallow start overlap, TOI failed)
    long ties = 0;
    long clipped = 0;
    long failures = 0;
    double max_depth_err = 0.0;   // |jostle - box2d| depth or t-distance, in units of L
    double max_normal_err = 0.0;  // |n_jostle - n_box2d| where compared
    double max_exact_err = 0.0;   // |jostle - exact| depth / gap, in units of L
    double toi_lag_min = 1e30, toi_lag_max = -1e30;  // sweeps: (tb - tj) * vn(tj), in slops
    std::vector<std::pair<std::string, long>> categories;
    std::vector<std::string> shown;

    explicit Stats(std::string k) : kind(std::move(k)) {}

    void count(const char* category) {
        for (auto& [name, n] : categories)
            if (name == category) {
                ++n;
                return;
            }
        categories.emplace_back(category, 1);
    }
    long category(const char* name) const {
        for (const auto& [n, c] : categories)
            if (n == name) return c;
        return 0;
    }
    // why = "reason: details"; failures are counted per reason (the text before the first
    // ':', '(' or digit) and the first two of each reason are shown.
    void fail(const std::string& why) {
        ++failures;
        std::string key = why.substr(0, why.find(':'));
        key = key.substr(0, key.find_first_of("(0123456789"));
        for (auto& [k, n, shown_n] : reasons)
            if (k == key) {
                ++n;
                if (shown_n < 2 && static_cast<int>(shown.size()) < kShownFailures) {
                    ++shown_n;
                    shown.push_back(why);
                }
                return;
            }
        reasons.push_back({key, 1, 0});
        if (static_cast<int>(shown.size()) < kShownFailures) {
            reasons.back().shown = 1;
            shown.push_back(why);
        }
    }
    std::string failure_text() const {
        std::string s = fmt("%ld disagreement(s) in %s:\n", failures, kind.c_str());
        for (const auto& r : reasons) s += fmt("  %6ld x %s\n", r.count, r.key.c_str());
        s += "first ones:\n";
        for (const auto& f : shown) s += "  " + f + "\n";
        return s;
    }
    struct Reason {
        std::string key;
        long count = 0;
        int shown = 0;
    };
    std::vector<Reason> reasons;
    void report() const {
        std::string cats;
        for (const auto& [name, n] : categories) cats += fmt(" %s=%ld", name.c_str(), n);
        std::printf("[box2d-diff] %-20s pairs=%ld box2d_hits=%ld jostle_hits=%ld agree=%ld band=%ld excluded=%ld "
                    "ties=%ld clipped=%ld fail=%ld max_err_vs_box2d=%.3gL max_normal_err=%.3g max_err_vs_exact=%.3gL",
                    kind.c_str(), pairs, box2d_hits, jostle_hits, agree, band, excluded, ties, clipped, failures,
                    max_depth_err, max_normal_err, max_exact_err);
        if (toi_lag_max >= toi_lag_min) std::printf(" box2d_toi_lag=[%.3g, %.3g]slop", toi_lag_min, toi_lag_max);
        std::printf(" |%s\n", cats.c_str());
        std::fflush(stdout);
        auto prop = [&](const char* name, long v) { ::testing::Test::RecordProperty(name, std::to_string(v)); };
        prop("pairs", pairs);
        prop("box2d_hits", box2d_hits);
        prop("agree", agree);
        prop("band", band);
        prop("excluded", excluded);
        prop("ties", ties);
        prop("clipped", clipped);
        prop("failures", failures);
        ::testing::Test::RecordProperty("max_err_vs_box2d_over_L", fmt("%.3g", max_depth_err));
        ::testing::Test::RecordProperty("max_normal_err", fmt("%.3g", max_normal_err));
        ::testing::Test::RecordProperty("max_err_vs_exact_over_L", fmt("%.3g", max_exact_err));
    }
    // The assertions every kind shares: no disagreement outside the documented bands, every
    // pair accounted for, the measured maxima inside the tolerances, each listed category
    // actually generated (at least 1% of the pairs, so a broken generator fails too).
    void expect_clean(std::initializer_list<const char*> required) const {
        report();
        EXPECT_EQ(failures, 0) << failure_text();
        EXPECT_EQ(pairs, pair_count());
        EXPECT_EQ(agree + band + excluded + failures, pairs);
        EXPECT_LE(max_depth_err, kRel * (1.0 + 1e-9)) << kind;  // stored relative to L, see note()
        EXPECT_LE(max_exact_err, kRel * (1.0 + 1e-9)) << kind;
        EXPECT_LE(max_normal_err, kNormalTol * 1.5) << kind;
        EXPECT_GT(box2d_hits, pairs / 10) << kind;
        EXPECT_LT(box2d_hits, pairs - pairs / 10) << kind;
        for (const char* c : required) EXPECT_GE(category(c), pairs / 100) << kind << ": too few '" << c << "' pairs";
    }
};

// Errors are recorded relative to the pair's length scale L (so kRel is the limit).
void note(double& slot, double err, double L) { slot = std::max(slot, err / L); }

// ---------------------------------------------------------------------------------------
// Shapes: one description, given identically to jostle, Box2D and the exact evaluator
// ---------------------------------------------------------------------------------------

enum class PolyKind { polygon, obb, aabb };

struct PolyShape {
    PolyKind kind = PolyKind::polygon;
    int n = 0;
    std::array<Vec2, 8> pts{};  // polygon: the world vertices (positive cross order)
    Obb obb;
    Aabb aabb;
    Polygon jpoly;          // polygon: jostle's, from make_polygon
    b2PolygonShape b2;      // Box2D's, m_radius = 0
    ex::Poly exact;         // the exact shape

    std::string describe() const {
        switch (kind) {
        case PolyKind::obb:
            return fmt("Obb{%s, %s, %.9g}", str(obb.center).c_str(), str(obb.half).c_str(), dd(obb.angle()));
        case PolyKind::aabb: return fmt("Aabb{%s, %s}", str(aabb.min).c_str(), str(aabb.max).c_str());
        case PolyKind::polygon: break;
        }
        std::string s = "Polygon{";
        for (int i = 0; i < n; ++i) s += (i ? ", " : "") + str(pts[static_cast<std::size_t>(i)]);
        return s + "}";
    }
    Shape shape() const {
        switch (kind) {
        case PolyKind::obb: return obb;
        case PolyKind::aabb: return aabb;
        case PolyKind::polygon: break;
        }
        return jpoly;
    }
    double reach() const {  // largest |coordinate|
        double m = 0.0;
        for (int i = 0; i < exact.n; ++i) {
            const D2 v = exact.v[static_cast<std::size_t>(i)];
            m = std::max({m, std::abs(v.x), std::abs(v.y)});
        }
        return m;
    }
};

// Builds the three views. Returns false when Box2D would not keep the vertices as given (the
// caller draws again); a polygon jostle rejects is a failure (the generator only makes
// strictly convex polygons with a wide margin).
bool finish(PolyShape& s, Stats& st) {
    switch (s.kind) {
    case PolyKind::polygon: {
        const std::span<const Vec2> pts(s.pts.data(), static_cast<std::size_t>(s.n));
        if (!b2o::make_b2_polygon(pts, &s.b2)) return false;
        std::string why;
        const auto p = make_polygon(pts, &why);
        if (!p) {
            st.fail("make_polygon rejected a strictly convex polygon: " + s.describe() + " (" + why + ")");
            return false;
        }
        s.jpoly = *p;
        s.exact = ex::make_poly(pts);
        return true;
    }
    case PolyKind::obb:
        s.b2 = b2o::make_b2_box(s.obb);
        s.exact = ex::make_poly(s.obb);
        return true;
    case PolyKind::aabb: {
        const std::array<Vec2, 4> c{s.aabb.min, Vec2{s.aabb.max.x, s.aabb.min.y}, s.aabb.max, Vec2{s.aabb.min.x, s.aabb.max.y}};
        if (!b2o::make_b2_polygon(c, &s.b2)) return false;
        s.exact = ex::make_poly(std::span<const Vec2>(c));
        return true;
    }
    }
    return false;
}

// A shape before placement: local geometry around the origin, in double.
struct Template {
    PolyKind kind = PolyKind::polygon;
    int n = 0;
    std::array<D2, 8> local{};  // polygon: vertices; obb/aabb: unused
    double hx = 0.0, hy = 0.0;  // obb/aabb half extents
    float angle = 0.0f;         // obb
    double bound = 0.0;         // bounding radius about the origin
    double minor = 0.0;         // a radius of a disc about the origin inside the shape
};

// A random convex polygon: n points at sorted random angles on a random ellipse (always in
// convex position), kept only with a wide margin (every edge >= 4% of the size, every turn
// >= 3 degrees), so that float rounding cannot make it non-convex and face normals differ.
Template random_polygon(jostle::Rng& rng, double size) {
    Template t;
    t.kind = PolyKind::polygon;
    for (;;) {
        t.n = 3 + static_cast<int>(rng.below(6));
        const double a = 0.5 * size, b = a * dd(rng.uniform(0.3f, 1.0f));
        const double rot = dd(rng.uniform(-3.14159f, 3.14159f));
        std::array<double, 8> ang{};
        for (int i = 0; i < t.n; ++i) ang[static_cast<std::size_t>(i)] = dd(rng.uniform(0.0f, 6.2831853f));
        for (std::size_t i = 1; i < static_cast<std::size_t>(t.n); ++i)  // insertion sort (std::sort on a prefix trips
            for (std::size_t j = i; j > 0 && ang[j - 1] > ang[j]; --j)       // GCC 12's -Warray-bounds at -O3)
                std::swap(ang[j - 1], ang[j]);
        const double c = std::cos(rot), s = std::sin(rot);
        for (int i = 0; i < t.n; ++i) {
            const double x = a * std::cos(ang[static_cast<std::size_t>(i)]), y = b * std::sin(ang[static_cast<std::size_t>(i)]);
            t.local[static_cast<std::size_t>(i)] = {c * x - s * y, s * x + c * y};
        }
        bool ok = true;
        for (int i = 0; i < t.n && ok; ++i) {
            const D2 p0 = t.local[static_cast<std::size_t>(i)], p1 = t.local[static_cast<std::size_t>((i + 1) % t.n)],
                     p2 = t.local[static_cast<std::size_t>((i + 2) % t.n)];
            const D2 e0 = p1 - p0, e1 = p2 - p1;
            ok = ex::len(e0) >= 0.04 * size && ex::cross(e0, e1) >= std::sin(3.0 * kPi / 180.0) * ex::len(e0) * ex::len(e1);
        }
        if (!ok) continue;
        t.bound = 0.0;
        for (int i = 0; i < t.n; ++i) t.bound = std::max(t.bound, ex::len(t.local[static_cast<std::size_t>(i)]));
        const ex::Poly p = ex::make_poly(std::span<const D2>(t.local.data(), static_cast<std::size_t>(t.n)));
        t.minor = -ex::signed_distance(p, D2{}).d;
        if (t.minor <= 0.02 * size) continue;  // the origin must be well inside
        return t;
    }
}

Template random_box(jostle::Rng& rng, double size, bool axis_aligned) {
    Template t;
    t.kind = axis_aligned ? PolyKind::aabb : PolyKind::obb;
    t.hx = 0.5 * size * dd(rng.uniform(0.25f, 1.0f));
    t.hy = 0.5 * size * dd(rng.uniform(0.25f, 1.0f));
    // 10% exactly axis-aligned Obbs: parallel faces, the reference-face tie of Box2D
    t.angle = axis_aligned || rng.below(10) == 0 ? 0.0f : rng.uniform(-3.14159f, 3.14159f);
    t.bound = std::hypot(t.hx, t.hy);
    t.minor = std::min(t.hx, t.hy);
    return t;
}

Template random_template(jostle::Rng& rng, double size) {
    const auto r = rng.below(100);
    if (r < 60) return random_polygon(rng, size);
    return random_box(rng, size, r >= 85);
}

ex::Poly exact_at(const Template& t, D2 c) {
    if (t.kind == PolyKind::polygon) {
        std::array<D2, 8> w{};
        for (int i = 0; i < t.n; ++i) w[static_cast<std::size_t>(i)] = c + t.local[static_cast<std::size_t>(i)];
        return ex::make_poly(std::span<const D2>(w.data(), static_cast<std::size_t>(t.n)));
    }
    const double co = std::cos(dd(t.angle)), si = std::sin(dd(t.angle));
    const std::array<D2, 4> l{D2{-t.hx, -t.hy}, D2{t.hx, -t.hy}, D2{t.hx, t.hy}, D2{-t.hx, t.hy}};
    std::array<D2, 4> w{};
    for (std::size_t i = 0; i < 4; ++i) w[i] = c + D2{co * l[i].x - si * l[i].y, si * l[i].x + co * l[i].y};
    return ex::make_poly(std::span<const D2>(w));
}

// Rounds the template placed at c to floats. Returns false if it must be drawn again.
bool place(const Template& t, D2 c, PolyShape& out, Stats& st) {
    out.kind = t.kind;  // (reused, not reassigned: b2PolygonShape has uninitialized arrays)
    switch (t.kind) {
    case PolyKind::polygon:
        out.n = t.n;
        for (int i = 0; i < t.n; ++i) out.pts[static_cast<std::size_t>(i)] = f2(c + t.local[static_cast<std::size_t>(i)]);
        break;
    case PolyKind::obb:
        out.obb = Obb{f2(c), Vec2{to_float(t.hx), to_float(t.hy)}, t.angle};
        break;
    case PolyKind::aabb:
        out.aabb = Aabb{f2(c - D2{t.hx, t.hy}), f2(c + D2{t.hx, t.hy})};
        break;
    }
    return finish(out, st);
}

// Exactly touching axis-aligned rectangles with integer corners (the manual: "shapes that
// touch exactly in float arithmetic report hit with depth 0"): B's left side on A's right
// side (or top on bottom), spans overlapping or meeting at a corner.
std::pair<Aabb, Aabb> touching_rects(jostle::Rng& rng) {
    const auto i = [&](int lo, int hi) { return static_cast<float>(lo + static_cast<int>(rng.below(static_cast<std::uint32_t>(hi - lo + 1)))); };
    const float x0 = i(-8, 4), y0 = i(-8, 4), w = i(1, 8), h = i(1, 8);
    const Aabb a{{x0, y0}, {x0 + w, y0 + h}};
    const float w2 = i(1, 8), h2 = i(1, 8);
    Aabb b;
    if (rng.below(2) == 0) {
        const float yb = i(static_cast<int>(y0 - h2), static_cast<int>(y0 + h));  // [y0-h2, y0+h]: overlap or corner
        b = {{a.max.x, yb}, {a.max.x + w2, yb + h2}};
    } else {
        const float xb = i(static_cast<int>(x0 - w2), static_cast<int>(x0 + w));
        b = {{xb, a.max.y}, {xb + w2, a.max.y + h2}};
    }
    return {a, b};
}

// Bisection for the convex separation function f(t) (f(0) < 0 < f(T)): the offset t at which
// the pair touches.
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

// A signed offset for the near-touching category: |eps| from 1e-8 L (below float
// resolution) to 3e-2 L (well outside the band), 10% exactly 0.
double near_eps(jostle::Rng& rng, double L) {
    if (rng.below(10) == 0) return 0.0;
    const double mag = L * std::pow(10.0, dd(rng.uniform(-8.0f, -1.5f)));
    return rng.below(2) ? mag : -mag;
}

D2 random_dir(jostle::Rng& rng) {
    const double a = dd(rng.uniform(-3.14159265f, 3.14159265f));
    return {std::cos(a), std::sin(a)};
}

// Exact classification of an overlap pair by its exact separation s.
const char* overlap_category(double sep, double tol, double L) {
    if (sep > 0.05 * L) return "far";
    if (sep > tol) return "near_miss";
    if (sep >= -tol) return "touch_band";
    return "overlap";
}

double normal_err(Vec2 a, Vec2 b) { return ex::len(d2(a) - d2(b)); }
bool unit_ok(Vec2 n) { return std::abs(ex::len(d2(n)) - 1.0) <= 1e-5; }

std::string str(const Manifold& m) {
    return fmt("hit=%d depth=%.9g normal=%s", m.hit, dd(m.depth), str(m.normal).c_str());
}
std::string str(const b2o::Contact& c) {
    return fmt("hit=%d depth=%.9g normal=%s points=%d ref=%s", c.hit, dd(c.depth), str(c.normal).c_str(), c.points,
               c.face_b ? "B" : "A");
}

// ---------------------------------------------------------------------------------------
// 1. polygon-polygon and OBB-OBB
// ---------------------------------------------------------------------------------------

Manifold jostle_collide(const PolyShape& a, const PolyShape& b) {
    if (a.kind == PolyKind::polygon && b.kind == PolyKind::polygon) return collide(a.jpoly, b.jpoly);
    if (a.kind == PolyKind::obb && b.kind == PolyKind::obb) return collide(a.obb, b.obb);
    if (a.kind == PolyKind::aabb && b.kind == PolyKind::obb) return collide(a.aabb, b.obb);
    ADD_FAILURE() << "unexpected pair";
    return {};
}

// Compares one polygon pair. exact_touch: integer rectangles that touch exactly.
void compare_polygons(const PolyShape& a, const PolyShape& b, bool exact_touch, Stats& st) {
    ++st.pairs;
    const double L = std::max({1.0, a.reach(), b.reach()});
    const double tol = kRel * L;
    const ex::Sat sat = ex::sat(a.exact, b.exact);
    const b2o::Contact bx = b2o::collide_polygons(a.b2, b.b2);
    const Manifold jm = jostle_collide(a, b);
    const auto where = [&] {
        return fmt("A=%s B=%s | box2d %s | jostle %s | exact sep=%.9g axis=%s L=%.3g", a.describe().c_str(),
                   b.describe().c_str(), str(bx).c_str(), str(jm).c_str(), sat.sep, str(sat.axis).c_str(), L);
    };
    st.count(exact_touch ? "exact_touch" : overlap_category(sat.sep, tol, L));
    bool contained = true;
    for (int i = 0; i < b.exact.n && contained; ++i) contained = ex::signed_distance(a.exact, b.exact.v[static_cast<std::size_t>(i)]).d < -tol;
    if (contained) st.count("contained");
    st.box2d_hits += bx.hit;
    st.jostle_hits += jm.hit;

    if (exact_touch) {  // jostle: hit, depth exactly 0 (the manual)
        if (!jm.hit || jm.depth != 0.0f) return st.fail("exactly touching rectangles must be a hit with depth 0: " + where());
        if (!bx.hit) {
            // Box2D clips the incident edge to the reference face's side planes; when the
            // rectangles meet only at a corner the clipped segment has zero length and
            // b2CollidePolygons returns no points. That is Box2D's touching band, not jostle's.
            const auto span = [](const ex::Poly& p, bool y) {
                double lo = 1e300, hi = -1e300;
                for (int i = 0; i < p.n; ++i) {
                    const D2 v = p.v[static_cast<std::size_t>(i)];
                    lo = std::min(lo, y ? v.y : v.x);
                    hi = std::max(hi, y ? v.y : v.x);
                }
                return std::pair{lo, hi};
            };
            const auto [ax0, ax1] = span(a.exact, false);
            const auto [ay0, ay1] = span(a.exact, true);
            const auto [bx0, bx1] = span(b.exact, false);
            const auto [by0, by1] = span(b.exact, true);
            if (std::min(ax1, bx1) - std::max(ax0, bx0) == 0.0 && std::min(ay1, by1) - std::max(ay0, by0) == 0.0) {
                st.count("corner_touch_box2d_miss");
                ++st.band;
                return;
            }
            return st.fail("Box2D misses rectangles touching along an edge (oracle assumption): " + where());
        }
    }
    // The manual, against the exact separation.
    if (jm.hit ? sat.sep > tol : sat.sep < -tol) return st.fail("hit/no-hit wrong (vs exact): " + where());
    if (!jm.hit && (jm.depth != 0.0f || jm.normal != Vec2{})) return st.fail("a miss must be all zeros: " + where());
    if (jm.hit) {
        if (!(jm.depth >= 0.0f) || !unit_ok(jm.normal)) return st.fail("depth < 0 or normal not unit: " + where());
        const double exact_err = std::abs(dd(jm.depth) - std::max(0.0, -sat.sep));
        note(st.max_exact_err, exact_err, L);
        if (exact_err > tol) return st.fail("depth is not the minimum penetration (vs exact): " + where());
        const double own = ex::pen_along(a.exact, b.exact, d2(jm.normal));
        if (std::abs(own - dd(jm.depth)) > tol) return st.fail(fmt("depth is not the overlap along the normal (%.9g): ", own) + where());
    }
    if (bx.hit != jm.hit) {
        if (std::abs(sat.sep) <= tol) {
            ++st.band;
            return;
        }
        return st.fail("hit/no-hit disagrees outside the touching band: " + where());
    }
    if (!bx.hit) {
        ++st.agree;
        return;
    }
    // Box2D's depth: the manifold's, unless clipping removed the deepest incident vertex.
    const double along_b2 = ex::pen_along(a.exact, b.exact, d2(bx.normal));
    double b2_depth = dd(bx.depth);
    if (dd(bx.depth) > along_b2 + tol) return st.fail("Box2D manifold deeper than its axis (oracle assumption): " + where());
    if (dd(bx.depth) < along_b2 - tol) {
        ++st.clipped;
        b2_depth = along_b2;
    }
    // Which exact face axis (a normal of A, or minus a normal of B) each normal stands for:
    // the same axis (or exactly parallel faces of A and B) is a comparison of float results;
    // different axes are a choice between faces.
    const auto nearest_axis = [&](Vec2 n) {
        D2 best{};
        double best_d = 1e300;
        for (int i = 0; i < a.exact.n + b.exact.n; ++i) {
            const D2 ax = i < a.exact.n ? a.exact.nrm[static_cast<std::size_t>(i)] : -b.exact.nrm[static_cast<std::size_t>(i - a.exact.n)];
            const double e = ex::len(d2(n) - ax);
            if (e < best_d) {
                best_d = e;
                best = ax;
            }
        }
        return std::pair{best, best_d};
    };
    const auto [axis_j, off_j] = nearest_axis(jm.normal);
    const auto [axis_b, off_b] = nearest_axis(bx.normal);
    const double nerr = normal_err(jm.normal, bx.normal);
    const double err = std::abs(dd(jm.depth) - b2_depth);
    if (ex::len(axis_j - axis_b) <= 1e-9) {
        st.max_normal_err = std::max(st.max_normal_err, nerr);
        note(st.max_depth_err, err, L);
        if (nerr > kNormalTol) return st.fail(fmt("normal differs on the same face axis (|dn| = %.3g): ", nerr) + where());
        if (err > tol) return st.fail(fmt("depth differs by %.3g (tol %.3g): ", err, tol) + where());
        ++st.agree;
        return;
    }
    // Different axes. Box2D's reference face may be up to kTieTol less separated than the
    // best axis (it keeps A's face unless B's is better by more than k_tol). Accepted:
    // jostle's normal is a face axis whose overlap is jostle's depth (checked above, and
    // minimal: checked against the exact SAT), and that depth is in
    // [box2d - kTieTol - tol, box2d + tol].
    const double d = dd(jm.depth);
    if (off_j <= kNormalTol && d <= b2_depth + tol && d >= b2_depth - kTieTol - tol) {
        ++st.ties;
        ++st.agree;
        return;
    }
    (void)off_b;
    st.fail(fmt("normal differs (|dn| = %.3g) and is not a tied minimum axis: ", nerr) + where());
}

void run_polygon_pairs(Stats& st, bool boxes, std::uint64_t seed) {
    jostle::Rng rng(seed);
    const long n = pair_count();
    PolyShape a, b;
    while (st.pairs < n) {
        const auto cat = rng.below(100);
        if (cat >= 95) {  // exactly touching integer rectangles
            auto [ra, rb] = touching_rects(rng);
            if (rng.below(2)) std::swap(ra, rb);
            if (boxes) {
                a.kind = PolyKind::aabb;
                a.aabb = ra;
                b.kind = PolyKind::obb;
                b.obb = Obb{0.5f * (rb.min + rb.max), 0.5f * (rb.max - rb.min), 0.0f};
            } else {
                for (PolyShape* s : {&a, &b}) {
                    const Aabb& r = s == &a ? ra : rb;
                    s->kind = PolyKind::polygon;
                    s->n = 4;
                    s->pts = {r.min, Vec2{r.max.x, r.min.y}, r.max, Vec2{r.min.x, r.max.y}};
                }
            }
            if (!finish(a, st) || !finish(b, st)) continue;
            compare_polygons(a, b, true, st);
            continue;
        }
        const double size_a = dd(rng.uniform(1.0f, 10.0f));
        double size_b = dd(rng.uniform(1.0f, 10.0f));
        const bool contain = cat >= 85;
        Template ta = boxes ? random_box(rng, size_a, rng.below(100) < 15) : random_polygon(rng, size_a);
        if (contain) size_b = std::max(0.25, ta.minor * dd(rng.uniform(0.2f, 1.6f)));
        Template tb = boxes ? random_box(rng, size_b, false) : random_polygon(rng, size_b);
        const D2 ca{dd(rng.uniform(-8.0f, 8.0f)), dd(rng.uniform(-8.0f, 8.0f))};
        const ex::Poly pa = exact_at(ta, ca);
        const D2 u = random_dir(rng);
        const D2 base = ca + dd(rng.uniform(0.0f, 0.5f)) * ta.minor * random_dir(rng);
        const double t0 = touch_offset([&](double t) { return ex::sat(pa, exact_at(tb, base + t * u)).sep; }, ta.bound + tb.bound + 1.0);
        const double L = std::max(1.0, std::abs(ca.x) + ta.bound + tb.bound);
        double t;
        if (contain) t = t0 * dd(rng.uniform(0.0f, 1.0f));
        else if (cat < 15) t = t0 + L * dd(rng.uniform(0.02f, 1.0f));
        else if (cat < 50) t = t0 * dd(rng.uniform(0.0f, 1.0f));
        else t = t0 + near_eps(rng, L);
        if (!place(ta, ca, a, st) || !place(tb, base + t * u, b, st)) continue;
        compare_polygons(a, b, false, st);
    }
}

TEST(Box2DDiff, PolygonPolygon) {
    Stats st("polygon-polygon");
    run_polygon_pairs(st, false, 0x9e3779b97f4a7c15ull);
    st.expect_clean({"far", "near_miss", "touch_band", "overlap", "contained"});
    EXPECT_GE(st.category("exact_touch"), st.pairs / 50);
}

TEST(Box2DDiff, ObbObb) {
    Stats st("obb-obb");
    run_polygon_pairs(st, true, 0x2545f4914f6cdd1dull);
    st.expect_clean({"far", "near_miss", "touch_band", "overlap", "contained"});
    EXPECT_GE(st.category("exact_touch"), st.pairs / 50);
    EXPECT_GT(st.ties, 0) << "axis-aligned boxes with parallel faces should produce Box2D reference-face ties";
}

// ---------------------------------------------------------------------------------------
// 2. polygon-circle and circle-circle
// ---------------------------------------------------------------------------------------

Manifold jostle_collide(const PolyShape& a, const Circle& b) {
    switch (a.kind) {
    case PolyKind::obb: return collide(a.obb, b);
    case PolyKind::aabb: return collide(a.aabb, b);
    case PolyKind::polygon: break;
    }
    return collide(a.jpoly, b);
}

// The checks shared by every circle pair: depth (exact and Box2D) and normal, where `cond`
// is the length of the vector the normal is normalized from (infinite for face normals) and
// `tied(n)` says whether n is an equally good normal for this pair.
template <class Tied>
void compare_round(const Manifold& jm, const b2o::Contact& bx, double sep, double L, double cond, Tied tied,
                   const std::string& where_text, Stats& st) {
    const double tol = kRel * L;
    const std::string where = where_text + " | box2d " + str(bx) + " | jostle " + str(jm) + fmt(" | exact sep=%.9g L=%.3g", sep, L);
    st.box2d_hits += bx.hit;
    st.jostle_hits += jm.hit;
    if (jm.hit ? sep > tol : sep < -tol) return st.fail("hit/no-hit wrong (vs exact): " + where);
    if (!jm.hit && (jm.depth != 0.0f || jm.normal != Vec2{})) return st.fail("a miss must be all zeros: " + where);
    if (jm.hit) {
        if (!(jm.depth >= 0.0f) || !unit_ok(jm.normal)) return st.fail("depth < 0 or normal not unit: " + where);
        const double e = std::abs(dd(jm.depth) - std::max(0.0, -sep));
        note(st.max_exact_err, e, L);
        if (e > tol) return st.fail("depth wrong (vs exact): " + where);
    }
    if (bx.hit != jm.hit) {
        if (std::abs(sep) <= tol) {
            ++st.band;
            return;
        }
        return st.fail("hit/no-hit disagrees outside the touching band: " + where);
    }
    if (!bx.hit) {
        ++st.agree;
        return;
    }
    const double err = std::abs(dd(jm.depth) - dd(bx.depth));
    note(st.max_depth_err, err, L);
    if (err > tol) return st.fail(fmt("depth differs by %.3g (tol %.3g): ", err, tol) + where);
    const double nerr = normal_err(jm.normal, bx.normal);
    const double ntol = kNormalTol + kNormalCond * L / cond;
    if (nerr <= ntol) {
        if (kNormalCond * L / cond <= 0.5 * kNormalTol) st.max_normal_err = std::max(st.max_normal_err, nerr);
        ++st.agree;
        return;
    }
    if (tied(jm.normal)) {
        ++st.ties;
        ++st.agree;
        return;
    }
    st.fail(fmt("normal differs (|dn| = %.3g, tol %.3g): ", nerr, ntol) + where);
}

void compare_polygon_circle(const PolyShape& a, const Circle& c, Stats& st, bool also_sat, bool exact_touch) {
    ++st.pairs;
    const double L = std::max({1.0, a.reach(), std::abs(dd(c.center.x)) + dd(c.radius), std::abs(dd(c.center.y)) + dd(c.radius)});
    const double tol = kRel * L;
    const D2 cc = d2(c.center);
    const double r = dd(c.radius);
    const ex::Sd sd = ex::signed_distance(a.exact, cc);
    const double sep = sd.d - r;
    st.count(exact_touch ? "exact_touch" : overlap_category(sep, tol, L));
    if (sd.d < -tol) st.count("centre_inside");
    if (sep < 0 && -sd.d > r) st.count("contained");
    const b2CircleShape bc = b2o::make_b2_circle(c);
    const b2o::Contact bx = b2o::collide_polygon_circle(a.b2, bc);
    const Manifold jm = jostle_collide(a, c);
    // A centre-to-boundary normal is normalized from a vector of length sd (face normals are
    // better conditioned; using sd for them too only widens the tolerance near the boundary).
    const double cond = sd.d > 0.0 ? sd.d : 1e300;
    // Equally good normals: any direction when the centre is on the boundary; inside, the
    // normal of any face as near as the nearest (both are minimum translations).
    auto tied = [&](Vec2 n) {
        if (std::abs(sd.d) <= tol) return std::abs(ex::pen_along(a.exact, cc, r, d2(n)) - dd(jm.depth)) <= tol;
        if (sd.d > 0.0) return false;
        for (int i = 0; i < a.exact.n; ++i) {
            const auto k = static_cast<std::size_t>(i);
            const double dist_i = a.exact.off[k] - ex::dot(a.exact.nrm[k], cc);
            if (ex::len(d2(n) - a.exact.nrm[k]) <= kNormalTol && dist_i <= -sd.d + tol) return true;
        }
        return false;
    };
    const std::string where = "A=" + a.describe() + " B=" + str(c);
    if (exact_touch && (!bx.hit || !jm.hit || jm.depth != 0.0f))
        return st.fail("exactly touching box and circle must be a hit with depth 0: " + where + " | box2d " + str(bx) +
                       " | jostle " + str(jm));
    if (also_sat) {
        // The lecture's second method gives the same result: the same hit (except in the
        // touching band), the same depth, and a normal that is a minimum translation too. SAT
        // picks the least push over a finite set of axes, and a face normal nearly parallel
        // to the centre-to-vertex axis can win by rounding (its push exceeds the minimum by
        // depth * angle^2 / 2, far below tol): such a normal is accepted when the overlap
        // along it is its depth within tol.
        const Manifold js = collide_sat(a.jpoly, c);
        const bool same =
            js.hit == jm.hit
                ? !js.hit || (std::abs(dd(js.depth) - dd(jm.depth)) <= tol &&
                              (normal_err(js.normal, jm.normal) <= kNormalTol + kNormalCond * L / cond || tied(js.normal) ||
                               (unit_ok(js.normal) && std::abs(ex::pen_along(a.exact, cc, r, d2(js.normal)) - dd(js.depth)) <= tol)))
                : std::abs(sep) <= tol;
        if (!same)
            return st.fail("collide_sat differs from collide: " + where + " | collide " + str(jm) + " | collide_sat " + str(js) +
                           fmt(" | exact sep=%.9g", sep));
    }
    compare_round(jm, bx, sep, L, cond, tied, where, st);
}

TEST(Box2DDiff, PolygonCircle) {
    Stats st("polygon-circle");
    jostle::Rng rng(0x8f1bbcdcbfa53e0bull);
    PolyShape a;
    while (st.pairs < pair_count()) {
        const auto cat = rng.below(100);
        if (cat >= 95) {  // integer box and integer circle touching a face exactly
            const auto i = [&](int lo, int hi) { return static_cast<float>(lo + static_cast<int>(rng.below(static_cast<std::uint32_t>(hi - lo + 1)))); };
            const float x0 = i(-8, 4), y0 = i(-8, 4), w = i(1, 8), h = i(1, 8), r = i(1, 5);
            a.kind = rng.below(2) ? PolyKind::aabb : PolyKind::polygon;
            a.aabb = Aabb{{x0, y0}, {x0 + w, y0 + h}};
            if (a.kind == PolyKind::polygon) {
                a.n = 4;
                a.pts = {a.aabb.min, Vec2{a.aabb.max.x, a.aabb.min.y}, a.aabb.max, Vec2{a.aabb.min.x, a.aabb.max.y}};
            }
            if (!finish(a, st)) continue;
            const Circle c{{x0 + w + r, i(static_cast<int>(y0), static_cast<int>(y0 + h))}, r};
            compare_polygon_circle(a, c, st, a.kind == PolyKind::polygon, true);
            continue;
        }
        const double size = dd(rng.uniform(1.0f, 10.0f));
        const Template ta = random_template(rng, size);
        const D2 ca{dd(rng.uniform(-8.0f, 8.0f)), dd(rng.uniform(-8.0f, 8.0f))};
        if (!place(ta, ca, a, st)) continue;
        const float r = cat >= 85 ? to_float(std::max(0.1, ta.minor * dd(rng.uniform(0.1f, 1.2f)))) : rng.uniform(0.25f, 5.0f);
        const D2 u = random_dir(rng);
        const D2 base = ca + dd(rng.uniform(0.0f, 0.5f)) * ta.minor * random_dir(rng);
        const double t0 = touch_offset([&](double t) { return ex::signed_distance(a.exact, base + t * u).d - dd(r); }, ta.bound + dd(r) + 1.0);
        const double L = std::max(1.0, std::abs(ca.x) + ta.bound + dd(r));
        double t;
        if (cat >= 85) t = t0 * dd(rng.uniform(0.0f, 1.0f));
        else if (cat < 15) t = t0 + L * dd(rng.uniform(0.02f, 1.0f));
        else if (cat < 50) t = t0 * dd(rng.uniform(0.0f, 1.0f));
        else t = t0 + near_eps(rng, L);
        compare_polygon_circle(a, Circle{f2(base + t * u), r}, st, a.kind == PolyKind::polygon, false);
    }
    st.expect_clean({"far", "near_miss", "touch_band", "overlap", "centre_inside", "contained"});
    EXPECT_GE(st.category("exact_touch"), st.pairs / 50);
}

TEST(Box2DDiff, CircleCircle) {
    Stats st("circle-circle");
    jostle::Rng rng(0xca5a826395121157ull);
    while (st.pairs < pair_count()) {
        const auto cat = rng.below(100);
        Circle a, b;
        a.center = {rng.uniform(-8.0f, 8.0f), rng.uniform(-8.0f, 8.0f)};
        a.radius = rng.uniform(0.25f, 5.0f);
        b.radius = rng.uniform(0.25f, 5.0f);
        if (cat >= 97) {  // exactly touching: integer centres on an axis, integer radii
            const auto i = [&](int lo, int hi) { return static_cast<float>(lo + static_cast<int>(rng.below(static_cast<std::uint32_t>(hi - lo + 1)))); };
            a = Circle{{i(-8, 8), i(-8, 8)}, i(1, 5)};
            b.radius = i(1, 5);
            const float d = a.radius + b.radius;
            const Vec2 offs[4] = {{d, 0}, {-d, 0}, {0, d}, {0, -d}};
            b.center = a.center + offs[rng.below(4)];
        } else if (cat >= 95) {  // coincident centres: the manual's normal {1, 0}
            b.center = a.center;
        } else {
            const D2 u = random_dir(rng);
            const double R = dd(a.radius) + dd(b.radius);
            const double L = std::max(1.0, std::abs(dd(a.center.x)) + R);
            double t;
            if (cat >= 85) t = std::abs(dd(a.radius) - dd(b.radius)) * dd(rng.uniform(0.0f, 1.0f));  // containment
            else if (cat < 15) t = R + L * dd(rng.uniform(0.02f, 1.0f));
            else if (cat < 50) t = R * dd(rng.uniform(0.0f, 1.0f));
            else t = R + near_eps(rng, L);
            b.center = f2(d2(a.center) + t * u);
        }
        ++st.pairs;
        const double L = std::max({1.0, std::abs(dd(a.center.x)) + dd(a.radius), std::abs(dd(a.center.y)) + dd(a.radius),
                                   std::abs(dd(b.center.x)) + dd(b.radius), std::abs(dd(b.center.y)) + dd(b.radius)});
        const double tol = kRel * L;
        const double dist = ex::dist(d2(a.center), d2(b.center));
        const double sep = dist - dd(a.radius) - dd(b.radius);
        if (cat >= 97) st.count("exact_touch");
        else if (cat >= 95) st.count("coincident");
        else st.count(overlap_category(sep, tol, L));
        if (sep < 0 && dist < std::abs(dd(a.radius) - dd(b.radius))) st.count("contained");
        const b2o::Contact bx = b2o::collide_circles(b2o::make_b2_circle(a), b2o::make_b2_circle(b));
        const Manifold jm = collide(a, b);
        const std::string where = "A=" + str(a) + " B=" + str(b);
        if (cat >= 97 && (!jm.hit || jm.depth != 0.0f || !bx.hit)) {
            st.fail("exactly touching circles must be a hit with depth 0: " + where + " | box2d " + str(bx) + " | jostle " + str(jm));
            continue;
        }
        if (cat >= 95 && cat < 97 && (jm.normal != Vec2{1.0f, 0.0f} || bx.normal != Vec2{1.0f, 0.0f})) {
            st.fail("coincident centres must give normal {1, 0}: " + where + " | box2d " + str(bx) + " | jostle " + str(jm));
            continue;
        }
        // Near-coincident centres: any unit normal is a minimum translation.
        compare_round(jm, bx, sep, L, dist, [&](Vec2) { return dist <= tol; }, where, st);
    }
    st.expect_clean({"far", "near_miss", "touch_band", "overlap", "contained", "coincident", "exact_touch"});
}

// ---------------------------------------------------------------------------------------
// 3. casts
// ---------------------------------------------------------------------------------------

struct CastTarget {
    bool is_circle = false;
    PolyShape poly;
    Circle circle;
    b2CircleShape b2c;
    std::string describe() const { return is_circle ? str(circle) : poly.describe(); }
    double sd(D2 p) const { return is_circle ? ex::dist(p, d2(circle.center)) - dd(circle.radius) : ex::signed_distance(poly.exact, p).d; }
    ex::SegMin seg_min(D2 p0, D2 p1) const {
        return is_circle ? ex::segment_min_sd(d2(circle.center), dd(circle.radius), p0, p1) : ex::segment_min_sd(poly.exact, p0, p1);
    }
    CastHit jostle_cast(Vec2 from, Vec2 to) const {
        if (is_circle) return cast(from, to, circle);
        switch (poly.kind) {
        case PolyKind::obb: return cast(from, to, poly.obb);
        case PolyKind::aabb: return cast(from, to, poly.aabb);
        case PolyKind::polygon: break;
        }
        return cast(from, to, poly.jpoly);
    }
    b2o::Ray box2d_cast(Vec2 from, Vec2 to) const {
        return is_circle ? b2o::ray_cast(b2c, from, to) : b2o::ray_cast(poly.b2, from, to);
    }
    double reach() const {
        return is_circle ? std::max(std::abs(dd(circle.center.x)), std::abs(dd(circle.center.y))) + dd(circle.radius) : poly.reach();
    }
    double bound = 0.0, minor = 0.0;
    D2 center;
};

std::string str(const CastHit& h) {
    return fmt("hit=%d t=%.9g point=%s normal=%s", h.hit, dd(h.t), str(h.point).c_str(), str(h.normal).c_str());
}
std::string str(const b2o::Ray& r) { return fmt("hit=%d t=%.9g normal=%s", r.hit, dd(r.t), str(r.normal).c_str()); }

void compare_cast(const CastTarget& s, Vec2 from, Vec2 to, Stats& st) {
    ++st.pairs;
    const double L = std::max({1.0, s.reach(), std::abs(dd(from.x)), std::abs(dd(from.y)), std::abs(dd(to.x)), std::abs(dd(to.y))});
    const double tol = kRel * L;
    const D2 p0 = d2(from), p1 = d2(to), dir = p1 - p0;
    const double len = ex::len(dir);
    const double sd0 = s.sd(p0);
    const ex::SegMin m = s.seg_min(p0, p1);
    const CastHit jh = s.jostle_cast(from, to);
    const b2o::Ray br = s.box2d_cast(from, to);
    st.box2d_hits += br.hit;
    st.jostle_hits += jh.hit;
    const auto where = [&] {
        return fmt("shape=%s from=%s to=%s | box2d %s | jostle %s | exact sd(from)=%.9g min sd=%.9g L=%.3g", s.describe().c_str(),
                   str(from).c_str(), str(to).c_str(), str(br).c_str(), str(jh).c_str(), sd0, m.d, L);
    };
    if (len == 0.0) st.count("zero_length");
    if (sd0 < -tol) st.count("start_inside");
    else if (sd0 <= tol) st.count("start_on");
    else if (std::abs(m.d) <= tol) st.count("graze_band");
    else if (m.d < 0.0) st.count(s.sd(p1) <= 0.0 ? "ends_inside" : "through");
    else st.count("miss");

    // The manual, against the exact geometry.
    if (jh.hit ? m.d > tol : m.d < -tol) return st.fail("hit/no-hit wrong (vs exact): " + where());
    if (!jh.hit && (jh.t != 0.0f || jh.point != Vec2{} || jh.normal != Vec2{})) return st.fail("a miss must be all zeros: " + where());
    if (sd0 < -tol) {  // starts strictly inside: t = 0, point = from, normal {0, 0}; Box2D says nothing
        ++st.excluded;
        if (br.hit) return st.fail("Box2D reports a ray starting inside (oracle assumption): " + where());
        if (!jh.hit || jh.t != 0.0f || jh.point != from || jh.normal != Vec2{}) return st.fail("a cast starting inside must report t = 0, point = from, normal {0,0}: " + where());
        return;
    }
    if (jh.hit) {
        if (!(jh.t >= 0.0f && jh.t <= 1.0f)) return st.fail("t outside the frame: " + where());
        const double pe = ex::dist(d2(jh.point), p0 + dd(jh.t) * dir);
        if (pe > tol) return st.fail("point != from + t (to - from): " + where());
        const double on = std::abs(s.sd(d2(jh.point)));
        if (sd0 > tol) note(st.max_exact_err, on, L);  // (a start within tol of the boundary is its own point)
        if (on > tol) return st.fail(fmt("hit point not on the boundary (|sd| = %.3g): ", on) + where());
    }
    if (sd0 <= tol) {  // starts on the boundary (within tol): Box2D's answer depends on rounding
        ++st.excluded;
        return;
    }
    if (br.hit != jh.hit) {
        if (std::abs(m.d) <= tol) {
            ++st.band;
            return;
        }
        return st.fail("hit/no-hit disagrees outside the grazing band: " + where());
    }
    if (!br.hit) {
        ++st.agree;
        return;
    }
    if (!unit_ok(jh.normal)) return st.fail("normal not unit: " + where());
    const double cosi = len > 0.0 ? std::abs(ex::dot(d2(br.normal), dir)) / len : 0.0;
    if (cosi < kGrazeCos) {  // glancing: the entry point is ill-conditioned; the boundary check above is what holds
        ++st.band;
        st.count("glancing");
        return;
    }
    const double err = std::abs(dd(jh.t) - dd(br.t)) * len;
    note(st.max_depth_err, err * cosi, L);
    if (err * cosi > tol) return st.fail(fmt("t differs by %.3g along the ray (tol %.3g / cos %.3g): ", err, tol, cosi) + where());
    const double nerr = normal_err(jh.normal, br.normal);
    if (nerr <= kNormalTol) {
        st.max_normal_err = std::max(st.max_normal_err, nerr);
        ++st.agree;
        return;
    }
    // A circle hit near tangency: the entry point and its normal are ill-conditioned (an
    // error dF in the path's distance from the centre turns the normal by ~dF / (r cos)), and
    // Box2D's |f|^2 - r^2 form loses more there than jostle's cross-product form. Judge
    // jostle's normal against the exact outward normal at jostle's own (verified) hit point.
    if (s.is_circle) {
        const D2 rel = d2(jh.point) - d2(s.circle.center);
        const double exact_err = ex::len(d2(jh.normal) - (1.0 / ex::len(rel)) * rel);
        const double box2d_err = ex::len(d2(br.normal) - (1.0 / ex::len(rel)) * rel);
        if (exact_err <= kNormalTol && exact_err < box2d_err) {
            st.count("box2d_normal_worse");
            ++st.agree;
            return;
        }
    }
    // Through a vertex (within tol): either face's normal.
    if (!s.is_circle) {
        for (int i = 0; i < s.poly.exact.n; ++i) {
            if (ex::len(d2(jh.normal) - s.poly.exact.nrm[static_cast<std::size_t>(i)]) <= kNormalTol &&
                ex::on_face(s.poly.exact, i, d2(jh.point), tol) && ex::dot(s.poly.exact.nrm[static_cast<std::size_t>(i)], dir) < 0.0) {
                ++st.ties;
                ++st.agree;
                return;
            }
        }
    }
    st.fail(fmt("normal differs (|dn| = %.3g): ", nerr) + where());
}

void run_casts(Stats& st, bool circles, std::uint64_t seed) {
    jostle::Rng rng(seed);
    CastTarget s;
    s.is_circle = circles;
    while (st.pairs < pair_count()) {
        const double size = dd(rng.uniform(1.0f, 10.0f));
        const D2 c{dd(rng.uniform(-6.0f, 6.0f)), dd(rng.uniform(-6.0f, 6.0f))};
        if (circles) {
            s.circle = Circle{f2(c), to_float(0.5 * size)};
            s.b2c = b2o::make_b2_circle(s.circle);
            s.bound = s.minor = dd(s.circle.radius);
        } else {
            const Template t = random_template(rng, size);
            if (!place(t, c, s.poly, st)) continue;
            s.bound = t.bound;
            s.minor = t.minor;
        }
        s.center = c;
        const auto cat = rng.below(100);
        const D2 u = random_dir(rng);
        const double L = std::max(1.0, std::abs(c.x) + std::abs(c.y) + s.bound);
        const double far = s.bound + dd(rng.uniform(0.05f, 3.0f)) * s.bound;
        D2 from = c - far * u, to;
        if (cat < 30) {  // aimed at a point inside; stops short, ends inside or goes through
            const D2 aim = c + dd(rng.uniform(0.0f, 0.9f)) * s.minor * random_dir(rng);
            to = from + dd(rng.uniform(0.5f, 2.5f)) * (aim - from);
        } else if (cat < 45) {  // aimed anywhere near: mostly misses
            const D2 aim = c + dd(rng.uniform(0.5f, 3.0f)) * s.bound * random_dir(rng);
            to = from + dd(rng.uniform(0.5f, 2.5f)) * (aim - from);
        } else if (cat < 75) {  // grazing: the line's closest approach is eps from the surface
            // The line through the centre crosses the shape; slide it sideways (by o along w,
            // one side or the other) to where it just touches, then by eps more.
            const D2 w{-u.y, u.x};
            const double span = 2.0 * far;
            const double side = rng.below(2) ? 1.0 : -1.0;
            const double o = touch_offset([&](double x) { return s.seg_min(from + side * x * w, from + side * x * w + span * u).d; }, s.bound + 1.0);
            from = from + side * (o + near_eps(rng, L)) * w;
            to = from + span * dd(rng.uniform(0.3f, 1.0f)) * u;
        } else if (cat < 85) {  // starts inside
            from = c + dd(rng.uniform(0.0f, 0.9f)) * s.minor * random_dir(rng);
            to = from + dd(rng.uniform(0.0f, 2.0f)) * s.bound * random_dir(rng);
        } else if (cat < 95) {  // starts near the boundary (eps in or out)
            const double t0 = touch_offset([&](double x) { return s.sd(c + x * u); }, s.bound + 1.0);
            from = c + (t0 + near_eps(rng, L)) * u;
            to = from + dd(rng.uniform(0.1f, 2.0f)) * s.bound * random_dir(rng);
        } else {  // zero length, outside or inside
            from = c + dd(rng.uniform(0.0f, 2.0f)) * s.bound * random_dir(rng);
            to = from;
        }
        const Vec2 f = f2(from);
        compare_cast(s, f, cat >= 95 ? f : f2(to), st);
    }
}

TEST(Box2DDiff, CastPolygon) {
    Stats st("cast-polygon");
    run_casts(st, false, 0x5851f42d4c957f2dull);
    st.expect_clean({"start_inside", "start_on", "graze_band", "through", "ends_inside", "miss", "zero_length"});
}

TEST(Box2DDiff, CastCircle) {
    Stats st("cast-circle");
    run_casts(st, true, 0x14057b7ef767814full);
    st.expect_clean({"start_inside", "start_on", "graze_band", "through", "ends_inside", "miss", "zero_length"});
}

// ---------------------------------------------------------------------------------------
// 4. sweeps
// ---------------------------------------------------------------------------------------

// The exact gap between the moving circle A and B: g(t) = sd_B(cA + t (va - vb)) - rA, in
// B's frame at t = 0. Convex in t.
struct SweepExact {
    const CastTarget& b;  // the other shape (a circle or a polygon), at its t = 0 position
    D2 p0, v;
    double ra = 0.0;
    double g(double t) const { return b.sd(p0 + t * v) - ra; }
    // The outward gradient of sd_B at the centre: minus the contact normal (A toward B).
    D2 grad(double t) const {
        const D2 q = p0 + t * v;
        if (b.is_circle) return ex::unit(q - d2(b.circle.center));
        return ex::signed_distance(b.poly.exact, q).grad;
    }
    double closing_speed(double t) const { return -ex::dot(grad(t), v); }
};

std::string str(const SweepHit& h) {
    return fmt("hit=%d t=%.9g point=%s normal=%s", h.hit, dd(h.t), str(h.point).c_str(), str(h.normal).c_str());
}

const char* toi_state(b2TOIOutput::State s) {
    switch (s) {
    case b2TOIOutput::e_unknown: return "unknown";
    case b2TOIOutput::e_failed: return "failed";
    case b2TOIOutput::e_overlapped: return "overlapped";
    case b2TOIOutput::e_touching: return "touching";
    case b2TOIOutput::e_separated: return "separated";
    }
    return "?";
}

void compare_sweep(const Circle& a, Vec2 va, const CastTarget& b, Vec2 vb, Stats& st) {
    ++st.pairs;
    const double L = std::max({1.0, b.reach() + std::max(std::abs(dd(vb.x)), std::abs(dd(vb.y))),
                               std::max(std::abs(dd(a.center.x)), std::abs(dd(a.center.y))) + dd(a.radius) +
                                   std::max(std::abs(dd(va.x)), std::abs(dd(va.y)))});
    const double tol = kRel * L;
    SweepExact x{b, d2(a.center), d2(va) - d2(vb), dd(a.radius)};
    const double g0 = x.g(0.0);
    const ex::SegMin gm = b.seg_min(x.p0, x.p0 + x.v);
    const double gmin = gm.d - x.ra;

    SweepHit jh;
    if (b.is_circle) jh = (vb == Vec2{} && (st.pairs & 1)) ? sweep(a, va, b.circle) : sweep(a, va, b.circle, vb);
    else if (vb == Vec2{} && (st.pairs & 1)) {
        switch (b.poly.kind) {
        case PolyKind::obb: jh = sweep(a, va, b.poly.obb); break;
        case PolyKind::aabb: jh = sweep(a, va, b.poly.aabb); break;
        case PolyKind::polygon: jh = sweep(a, va, b.poly.jpoly); break;
        }
    } else jh = sweep(a, va, b.is_circle ? Shape{b.circle} : b.poly.shape(), vb);

    b2o::Toi bt;
    if (b.is_circle) {
        const Vec2 cb = b.circle.center;
        bt = b2o::time_of_impact(a, va, std::span<const Vec2>(&cb, 1), b.circle.radius, vb);
    } else {
        std::array<Vec2, 8> vs{};
        for (int i = 0; i < b.poly.b2.m_count; ++i) vs[static_cast<std::size_t>(i)] = b2o::from_b2(b.poly.b2.m_vertices[i]);
        bt = b2o::time_of_impact(a, va, std::span<const Vec2>(vs.data(), static_cast<std::size_t>(b.poly.b2.m_count)), 0.0f, vb);
    }
    const bool b_hit = bt.state == b2TOIOutput::e_touching || bt.state == b2TOIOutput::e_overlapped;
    st.box2d_hits += b_hit;
    st.jostle_hits += jh.hit;
    const auto where = [&] {
        return fmt("A=%s va=%s B=%s vb=%s | box2d state=%s t=%.9g | jostle %s | exact g0=%.9g gmin=%.9g at t=%.9g L=%.3g",
                   str(a).c_str(), str(va).c_str(), b.describe().c_str(), str(vb).c_str(), toi_state(bt.state), dd(bt.t),
                   str(jh).c_str(), g0, gmin, gm.t, L);
    };
    if (g0 < -tol) st.count(g0 < -kToiLo - tol ? "start_overlap" : "start_shallow");
    else if (g0 <= tol) st.count("start_touch");
    else if (gmin > tol) st.count(gmin > 0.05 * L ? "miss" : "near_miss");
    else if (gmin >= -kToiHi - tol) st.count("graze_band");
    else st.count("hit");
    if (vb != Vec2{}) st.count("b_moving");

    // The manual, against the exact geometry.
    if (!jh.hit && (jh.t != 0.0f || jh.point != Vec2{} || jh.normal != Vec2{})) return st.fail("a miss must be all zeros: " + where());
    if (jh.hit && !(jh.t >= 0.0f && jh.t <= 1.0f)) return st.fail("t outside the frame: " + where());
    if (g0 <= tol) {
        // Touching or overlapping at t = 0: a contact at t = 0 while A moves into B, none while
        // it moves off or along (the manual's moving-away rule; Box2D reports every overlap,
        // so it is not compared here). "Moving into" is read off the exact gap a moment later.
        // The gap's rate of change at t = 0 (per unit of t) says which way A moves.
        ++st.excluded;
        const double h = 1e-6;
        const double slope = (x.g(h) - g0) / h;
        const double slope_tol = 1e-3 * ex::len(x.v) + tol;
        if (g0 < -tol && jh.hit && jh.t != 0.0f) return st.fail("an overlapping start must report t = 0 or no hit: " + where());
        if (jh.hit && jh.t == 0.0f && !(dot(va - vb, jh.normal) > 0.0f)) return st.fail("t = 0 contact while not moving into B: " + where());
        if (slope < -slope_tol && gmin < -tol && !jh.hit) return st.fail("moving into B from contact, but no hit: " + where());
        if (slope > slope_tol && jh.hit && jh.t == 0.0f) return st.fail("moving off B from contact, but a hit: " + where());
        return;
    }
    if (jh.hit ? gmin > tol : gmin < -tol) return st.fail("hit/no-hit wrong (vs exact): " + where());
    if (jh.hit) {
        const double tj = dd(jh.t);
        const double gj = x.g(tj);
        note(st.max_exact_err, std::abs(gj), L);
        if (std::abs(gj) > tol) return st.fail(fmt("gap at jostle's t is not 0: %.3g | ", gj) + where());
        // the entry root, not the exit: between the true first contact and tj the gap stays ~0
        if (x.g(0.5 * (gm.t + tj)) < -2.0 * tol && tj > gm.t) return st.fail("t is the exit, not the first contact: " + where());
        const D2 ca = d2(a.center) + tj * d2(va);
        const double on_a = std::abs(ex::dist(d2(jh.point), ca) - x.ra);
        const double on_b = std::abs(b.sd(d2(jh.point) - tj * d2(vb)));
        if (on_a > tol || on_b > tol) return st.fail(fmt("contact point not on both surfaces (%.3g, %.3g): ", on_a, on_b) + where());
        // The normal: from the centre at tj toward the closest point of B at tj. jostle's
        // time error shows as its gap |g(tj)|; moving the centre by the corresponding
        // |v| |g(tj)| / vn along the path turns a centre-to-vertex direction by that over ra,
        // which matters for glancing hits (vn << |v|) only.
        const D2 n_exp = -x.grad(tj);
        const double nerr = ex::len(d2(jh.normal) - n_exp);
        const double slack = ex::len(x.v) * (std::abs(gj) + kNormalCond * L) / (std::max(x.closing_speed(tj), 1e-12) * x.ra);
        const double ntol = kNormalTol + kNormalCond * L / x.ra + slack;
        if (!unit_ok(jh.normal) || nerr > ntol) return st.fail(fmt("normal is not centre -> closest point (|dn| = %.3g, tol %.3g): ", nerr, ntol) + where());
        if (slack <= 0.5 * kNormalTol) st.max_normal_err = std::max(st.max_normal_err, nerr);
        if (ex::len(d2(jh.normal) - ex::unit(d2(jh.point) - ca)) > kNormalTol + kNormalCond * L / x.ra)
            return st.fail("normal is not centre -> contact point: " + where());
    }
    if (bt.state == b2TOIOutput::e_failed || bt.state == b2TOIOutput::e_unknown) {
        ++st.excluded;
        st.count("box2d_failed");
        return;
    }
    if (b_hit) {
        const double gb = x.g(dd(bt.t));
        if (gb < -kToiHi - tol || gb > -kToiLo + tol) return st.fail(fmt("Box2D's gap at its t is %.3g, outside its target window (oracle assumption): ", gb) + where());
    }
    if (b_hit && !jh.hit) return st.fail("Box2D hits, jostle misses: " + where());
    if (!b_hit && jh.hit) {
        if (gmin >= -kToiHi - tol) {
            ++st.band;  // never 3.25 slop deep within the frame: Box2D cannot see it
            return;
        }
        return st.fail("jostle hits, Box2D misses, and the overlap would be deep enough for Box2D: " + where());
    }
    if (!b_hit) {
        ++st.agree;
        return;
    }
    // Both hit: Box2D's time must sit in the slop window after jostle's.
    const double tj = dd(jh.t), tb = dd(bt.t);
    const double vn_j = x.closing_speed(tj), vn_b = x.closing_speed(tb);
    const double lo = tj + (kToiLo - 2.0 * tol) / std::max(vn_j, 1e-300);
    const double hi = vn_b > 0.0 ? tj + (kToiHi + 2.0 * tol) / vn_b : 1e300;
    if (vn_j > 0.0) {
        const double lag = (tb - tj) * vn_j / kSlop;
        st.toi_lag_min = std::min(st.toi_lag_min, lag);
        st.toi_lag_max = std::max(st.toi_lag_max, lag);
    }
    // time error in distance: how far outside the window, times the closing speed
    const double out = std::max({0.0, (lo - tb) * vn_j, (tb - hi) * std::max(vn_b, 0.0)});
    note(st.max_depth_err, out, L);
    if (tb < lo || tb > hi) return st.fail(fmt("Box2D's t is outside [%.9g, %.9g] (vn %.3g, %.3g): ", lo, hi, vn_j, vn_b) + where());
    ++st.agree;
}

void run_sweeps(Stats& st, bool circles, std::uint64_t seed) {
    jostle::Rng rng(seed);
    CastTarget b;
    b.is_circle = circles;
    while (st.pairs < pair_count()) {
        const double size = dd(rng.uniform(1.0f, 10.0f));
        const D2 c{dd(rng.uniform(-5.0f, 5.0f)), dd(rng.uniform(-5.0f, 5.0f))};
        if (circles) {
            b.circle = Circle{f2(c), to_float(0.5 * size)};
            b.bound = b.minor = dd(b.circle.radius);
        } else {
            const Template t = random_template(rng, size);
            if (!place(t, c, b.poly, st)) continue;
            b.bound = t.bound;
            b.minor = t.minor;
        }
        const double ra = dd(rng.uniform(0.25f, 3.0f));
        const D2 u = random_dir(rng), w{-u.y, u.x};
        const auto cat = rng.below(100);
        const double L = std::max(1.0, std::abs(c.x) + std::abs(c.y) + b.bound + ra);
        const double d_start = b.bound + ra + dd(rng.uniform(0.02f, 8.0f));
        D2 p0 = c - d_start * u;
        // relative speed for the pairs that start in contact: 0.05 to 30 units per frame
        const double speed = std::pow(10.0, dd(rng.uniform(-1.3f, 1.48f)));
        D2 vrel;
        auto gap_min = [&](D2 q, D2 v) { return b.seg_min(q, q + v).d - ra; };
        if (cat < 35) {  // aimed at the shape: hits if long enough
            const D2 aim = c + dd(rng.uniform(0.0f, 0.9f)) * b.minor * random_dir(rng);
            vrel = dd(rng.uniform(0.3f, 2.0f)) * (aim - p0);
        } else if (cat < 45) {  // aimed past it
            const D2 aim = c + (b.bound + ra) * dd(rng.uniform(1.0f, 3.0f)) * random_dir(rng);
            vrel = dd(rng.uniform(0.3f, 2.0f)) * (aim - p0);
        } else if (cat < 70) {  // grazing: the closest approach is eps from contact
            const double span = 2.0 * d_start;
            const double sgn = rng.below(2) ? 1.0 : -1.0;
            const double off = sgn * touch_offset([&](double o) { return gap_min(p0 + sgn * o * w, span * u); }, b.bound + ra + 1.0);
            p0 = p0 + (off + sgn * near_eps(rng, L)) * w;
            vrel = span * u;
        } else if (cat < 80) {  // the first contact near t = 1 (within eps either side)
            // distance travelled along u to the first contact (the centre path crosses B's centre)
            const double t0 = touch_offset([&](double x) { return -(b.sd(p0 + x * u) - ra); }, d_start);
            vrel = (t0 + near_eps(rng, L)) * u;
        } else if (cat < 90) {  // starts overlapping
            p0 = c + dd(rng.uniform(0.0f, 1.2f)) * (b.minor + ra) * random_dir(rng);
            vrel = speed * random_dir(rng);
        } else {  // starts touching (eps in or out), moving in or away
            const double t0 = touch_offset([&](double x) { return b.sd(c + x * u) - ra; }, b.bound + ra + 1.0);
            // half of them inside Box2D's shallow zone (overlap up to 4 slop)
            const double eps = rng.below(2) ? near_eps(rng, L) : -kSlop * dd(rng.uniform(-1.0f, 4.0f));
            p0 = c + (t0 + eps) * u;
            vrel = speed * random_dir(rng);
        }
        // B moves in half of the pairs; the relative motion is what matters.
        D2 vbd{};
        if (rng.below(2)) vbd = dd(rng.uniform(0.0f, 10.0f)) * random_dir(rng);
        const Circle a{f2(p0), to_float(ra)};
        const Vec2 vb = f2(vbd);
        const Vec2 va = f2(vrel + d2(vb));
        compare_sweep(a, va, b, vb, st);
    }
}

TEST(Box2DDiff, SweepCircleCircle) {
    Stats st("sweep-circle-circle");
    run_sweeps(st, true, 0xd1b54a32d192ed03ull);
    st.expect_clean({"hit", "miss", "near_miss", "graze_band", "start_overlap", "start_shallow", "start_touch", "b_moving"});
}

TEST(Box2DDiff, SweepCirclePolygon) {
    Stats st("sweep-circle-polygon");
    run_sweeps(st, false, 0xaef17502108ef2d9ull);
    st.expect_clean({"hit", "miss", "near_miss", "graze_band", "start_overlap", "start_shallow", "start_touch", "b_moving"});
}

}  // namespace
