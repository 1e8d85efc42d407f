// Helpers shared by the collision module's implementation files (not part of the API):
// input validity, result builders, the one point-vs-circle contact solver, segment
// parameters, and the convex "point set + axes" view used by SAT.
#pragma once

#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#if defined(__SSE__)
#include <xmmintrin.h>
#endif
#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif

#include "jostle/collision.h"

namespace jostle::detail {

inline bool finite(float v) { return std::isfinite(v); }
inline bool finite(Vec2 v) { return std::isfinite(v.x) && std::isfinite(v.y); }

// A shape every query accepts: finite, and well formed (min <= max, half >= 0, r >= 0,
// 3..16 vertices). Anything else is a miss.
// (Sizes must be finite too: a box or segment from -3e38 to 3e38 has no float length.)
inline bool valid(const Aabb& b) {
    return finite(b.min) && finite(b.max) && b.min.x <= b.max.x && b.min.y <= b.max.y && finite(b.max - b.min);
}
// The hot shapes (boxes and circles) are checked without a branch per field: x - x is 0 for
// every finite x and NaN for NaN and +-inf, so a sum of such differences is 0 exactly when
// all are finite (without -ffast-math no compiler may fold x - x to 0), and the tests are
// combined with & rather than &&. The same answers as finite() field by field.
inline bool all_finite(float a, float b, float c) { return ((a - a) + (b - b)) + (c - c) == 0.0f; }
inline bool all_finite(float a, float b, float c, float d, float e) {
    return (((a - a) + (b - b)) + ((c - c) + (d - d))) + (e - e) == 0.0f;
}
// A box's extent must be finite as well as its fields, as an Aabb's size must: the centre
// plus and minus twice the half extents' sum (beyond every corner) is finite exactly when
// the fields are and no corner or size overflows, give or take a factor of two near FLT_MAX.
inline bool valid(const Obb& b) {
    const float reach = 2.0f * (b.half.x + b.half.y);
    return all_finite(b.center.x + reach, b.center.y + reach, b.center.x - reach, b.center.y - reach, b.angle()) &
           (b.half.x >= 0.0f) & (b.half.y >= 0.0f);
}
// r * r stands for r: it is finite exactly when r is and r^2 does not overflow (r up to about
// 1.8e19), so no distance test compares inf with inf.
inline bool valid(const Circle& c) { return all_finite(c.center.x, c.center.y, c.radius * c.radius) & (c.radius >= 0.0f); }
inline bool valid(const Segment& s) { return finite(s.a) && finite(s.b) && finite(dot(s.b - s.a, s.b - s.a)); }
// A Polygon is well formed by construction (its fields are private); only the empty one is
// not a shape.
inline bool valid(const Polygon& p) { return p.count() >= 3; }

// The module's own way to build a Polygon without make_polygon's checks, for shapes whose
// validity follows from how they are made (box corners and axes, swept rectangles). Callers
// guarantee finite points in positive-turn order and outward unit normals (or degenerate
// boxes of zero size, which SAT handles).
struct PolygonAccess {
    static Polygon make(std::span<const Vec2> points, std::span<const Vec2> normals) {
        Polygon p;
        p.count_ = static_cast<int>(points.size());
        for (std::size_t i = 0; i < points.size(); ++i) {
            p.points_[i] = points[i];
            p.normals_[i] = normals[i];
        }
        return p;
    }
    static Vec2* points(Polygon& p) { return p.points_.data(); }
    static Vec2* normals(Polygon& p) { return p.normals_.data(); }
};

// A motion from `from` by `d` whose end is finite too (a sum can overflow to infinity), and
// whose squared length is finite, as for a Segment (beyond |d| ~ 1.8e19, t = dot / dot(d, d)
// would be inf / inf). One test of the values' x - x (see all_finite), not a branch for each.
inline bool valid_motion(Vec2 from, Vec2 d) {
    const Vec2 end = from + d;
    const float dd = dot(d, d);
    return ((from.x - from.x) + (from.y - from.y)) + ((d.x - d.x) + (d.y - d.y)) +
               ((end.x - end.x) + (end.y - end.y)) + (dd - dd) ==
           0.0f;
}

// -0 becomes +0 (x + 0 is x for every other x): results print and hash the same whichever
// way a zero component was reached.
inline Vec2 plain_zeros(Vec2 v) { return {v.x + 0.0f, v.y + 0.0f}; }

// Four floats side by side: GCC's portable vector extension (clang has it too), one SSE
// instruction for four lanes on x86-64 and plain code elsewhere. Each lane does exactly the
// scalar arithmetic, so results are the same bit for bit as a loop's.
using Float4 = float __attribute__((vector_size(16)));
using Int4 = int __attribute__((vector_size(16)));

// |v| and v with the signs of `signs` flipped, lane by lane (bit operations, as std::fabs and
// negation are).
inline Float4 bit_xor(Float4 v, Float4 signs) {
    return reinterpret_cast<Float4>(reinterpret_cast<Int4>(v) ^ reinterpret_cast<Int4>(signs));
}
inline Float4 abs(Float4 v) {
    const Int4 magnitude = {0x7fffffff, 0x7fffffff, 0x7fffffff, 0x7fffffff};
    return reinterpret_cast<Float4>(reinterpret_cast<Int4>(v) & magnitude);
}

// Bit i set when lane i of a comparison's result is true (one MOVMSKPS on x86).
inline unsigned lane_bits(Int4 m) {
#if defined(__SSE__)
    return static_cast<unsigned>(_mm_movemask_ps(reinterpret_cast<__m128>(m)));
#else
    return static_cast<unsigned>((m[0] & 1) | (m[1] & 2) | (m[2] & 4) | (m[3] & 8));
#endif
}

// Lane i of x and of y in lanes 0 and 1, for an index known only at run time: the lane is
// picked by a mask and the bits gathered by OR, in registers. (v[i] with a variable i makes
// GCC store the vector to the stack and load the lane back, a round trip through memory.)
inline Float4 lane_pair(Float4 x, Float4 y, int i) {
    const Int4 index = {i, i, i, i};
    const Int4 pick = Int4{0, 1, 2, 3} == index;
    const Int4 xs = reinterpret_cast<Int4>(x) & pick, ys = reinterpret_cast<Int4>(y) & pick;
    // {x0, y0, x1, y1} | {x2, y2, x3, y3}, then its two halves ORed.
    const Int4 halves = __builtin_shufflevector(xs, ys, 0, 4, 1, 5) | __builtin_shufflevector(xs, ys, 2, 6, 3, 7);
    return reinterpret_cast<Float4>(halves | __builtin_shufflevector(halves, halves, 2, 3, 2, 3));
}

// Lanes 0 and 1 as a Vec2, moved as one 64-bit value (two lanes read one by one are packed
// into the Vec2's register through the stack by GCC: a store forward that fails).
inline Vec2 low_pair(Float4 v) {
#if defined(__SSE2__)
    return std::bit_cast<Vec2>(_mm_cvtsd_f64(_mm_castps_pd(reinterpret_cast<__m128>(v))));
#else
    return {v[0], v[1]};
#endif
}

// The square root of v >= 0 (or NaN): std::sqrt's value (IEEE's correctly rounded root),
// without the library call that std::sqrt keeps for a negative argument to set errno, whose
// stack frame every caller then pays for, hit or miss.
inline float sqrt_nonneg(float v) {
#if defined(__SSE__)
    return _mm_cvtss_f32(_mm_sqrt_ss(_mm_set_ss(v)));
#else
    return std::sqrt(v);
#endif
}

// The same for four lanes (SQRTPS: each lane IEEE's correctly rounded root, std::sqrt's value).
inline Float4 sqrt_nonneg(Float4 v) {
#if defined(__SSE__)
    return reinterpret_cast<Float4>(_mm_sqrt_ps(reinterpret_cast<__m128>(v)));
#else
    return Float4{std::sqrt(v[0]), std::sqrt(v[1]), std::sqrt(v[2]), std::sqrt(v[3])};
#endif
}
// plain_zeros lane by lane (-0 + 0 is +0, every other x + 0 is x).
inline Float4 plain_zeros(Float4 v) { return v + Float4{0.0f, 0.0f, 0.0f, 0.0f}; }

#if defined(__x86_64__) && defined(__GNUC__)
#define JOSTLE_AVX2_PATHS 1
// Eight floats side by side, for the AVX2 paths chosen at run time (a target attribute on the
// function, never -march: it changes which instructions run, not the rounding; no FMA).
using Float8 = float __attribute__((vector_size(32)));
using Int8 = int __attribute__((vector_size(32)));
// Whether the AVX2 paths run: the CPU's answer, asked once, on first use (no static initialiser:
// one per file would move every function after them and change the world step's timing with
// its code unchanged); detail::use_avx2_paths lets tests turn them off to compare against the
// SSE paths. A plain atomic (relaxed: one MOV to read), -1 until asked, rather than a
// function's static, so that reading it needs no guard (whose call made every dispatching
// function keep registers).
inline std::atomic<signed char> avx2_state{-1};
[[gnu::cold, gnu::noinline]] inline bool ask_cpu_for_avx2() {
    __builtin_cpu_init();
    const bool has = __builtin_cpu_supports("avx2");
    avx2_state.store(has ? 1 : 0, std::memory_order_relaxed);
    return has;
}
inline bool has_avx2() {
    const signed char state = avx2_state.load(std::memory_order_relaxed);
    return state > 0 || (state < 0 && ask_cpu_for_avx2());
}
// Bit i set when lane i of a comparison's result is true (VMOVMSKPS).
[[gnu::target("avx2"), gnu::always_inline]] inline unsigned lane_bits8(Int8 m) {
    return static_cast<unsigned>(_mm256_movemask_ps(reinterpret_cast<__m256>(m)));
}
// Points or normals `first` to `first + 7` (x, y pairs) as x and y lanes in order: the 128-bit
// halves regrouped (items 0, 1, 4, 5 and 2, 3, 6, 7), then x and y picked within each.
[[gnu::target("avx2"), gnu::always_inline]] inline void load_xy8(const Vec2* v, Float8& x, Float8& y) {
    Float8 lo, hi;
    std::memcpy(&lo, v, sizeof lo);
    std::memcpy(&hi, v + 4, sizeof hi);
    const Float8 a = __builtin_shufflevector(lo, hi, 0, 1, 2, 3, 8, 9, 10, 11);
    const Float8 b = __builtin_shufflevector(lo, hi, 4, 5, 6, 7, 12, 13, 14, 15);
    x = __builtin_shufflevector(a, b, 0, 2, 8, 10, 4, 6, 12, 14);
    y = __builtin_shufflevector(a, b, 1, 3, 9, 11, 5, 7, 13, 15);
}
// VHADDPS adds neighbouring floats within each 128-bit half, so per-slot sums over slots 0-3 and
// 4-7 (x, y pairs as a Polygon stores them) come out in lanes as slots 0, 1, 4, 5, 2, 3, 6, 7.
inline constexpr int kSlotOfHaddLane[8] = {0, 1, 4, 5, 2, 3, 6, 7};
// For a lane mask in that order: the first slot it names, or `none` when it names none.
template <int none>
inline constexpr auto kFirstHaddSlot = [] {
    std::array<std::uint8_t, 256> first{};
    for (int bits = 0; bits < 256; ++bits) {
        int slot = none;
        for (int lane = 7; lane >= 0; --lane)
            if ((bits >> lane & 1) != 0 && (slot == none || kSlotOfHaddLane[lane] < slot)) slot = kSlotOfHaddLane[lane];
        first[bits] = static_cast<std::uint8_t>(slot);
    }
    return first;
}();
// The largest lane of m in every lane (VMAXPS over the halves, pairs and neighbours); m must
// hold no NaN.
[[gnu::target("avx2"), gnu::always_inline]] inline Float8 max8(Float8 m) {
    Float8 t = __builtin_shufflevector(m, m, 4, 5, 6, 7, 0, 1, 2, 3);
    m = t > m ? t : m;
    t = __builtin_shufflevector(m, m, 2, 3, 0, 1, 6, 7, 4, 5);
    m = t > m ? t : m;
    t = __builtin_shufflevector(m, m, 1, 0, 3, 2, 5, 4, 7, 6);
    return t > m ? t : m;
}
// The same for the smallest lane.
[[gnu::target("avx2"), gnu::always_inline]] inline Float8 min8(Float8 m) {
    Float8 t = __builtin_shufflevector(m, m, 4, 5, 6, 7, 0, 1, 2, 3);
    m = t < m ? t : m;
    t = __builtin_shufflevector(m, m, 2, 3, 0, 1, 6, 7, 4, 5);
    m = t < m ? t : m;
    t = __builtin_shufflevector(m, m, 1, 0, 3, 2, 5, 4, 7, 6);
    return t < m ? t : m;
}
#endif

// The next and previous index around a polygon of n vertices (i in [0, n)), without the
// integer division that % costs.
inline int next_index(int i, int n) { return i + 1 == n ? 0 : i + 1; }
inline int prev_index(int i, int n) { return i == 0 ? n - 1 : i - 1; }

// A hit with the given depth and A->B normal; depth is clamped at 0 against rounding. Shapes
// far beyond the manual's LIMITS can overflow a projection or a distance (two boxes with
// half extents near FLT_MAX): a depth or normal that is not finite is no answer, so a miss.
inline Manifold hit_with(float depth, Vec2 normal) {
    if (!all_finite(depth, normal.x, normal.y)) return {};
    return Manifold{true, depth > 0.0f ? depth : 0.0f, plain_zeros(normal)};
}
// The same, the normal in lanes 0 and 1 of a vector (kept there up to the result's register).
inline Manifold hit_with(float depth, Float4 normal) {
    if (!all_finite(depth, normal[0], normal[1])) return {};
    return Manifold{true, depth > 0.0f ? depth : 0.0f, low_pair(plain_zeros(normal))};
}

// The same contact seen from B: the normal flips, the depth stays.
inline Manifold flipped(Manifold m) {
    if (m.hit) m.normal = plain_zeros(-m.normal);
    return m;
}

inline float clamp(float v, float lo, float hi) { return v < lo ? lo : (v > hi ? hi : v); }

// SAT bookkeeping for one axis u (09-60): push_pos moves A by -push_pos*u (normal u),
// push_neg moves A by +push_neg*u (normal -u). Taking the smaller push, rather than the
// overlap length, is what makes containment come out right. Returns false on a gap (or
// NaN): the early exit of 09-50.
inline bool consider_axis(Vec2 u, float push_pos, float push_neg, float& best, Vec2& best_normal) {
    if (!(push_pos >= 0.0f && push_neg >= 0.0f)) return false;
    if (push_pos <= push_neg) {
        if (push_pos < best) { best = push_pos; best_normal = u; }
    } else if (push_neg < best) {
        best = push_neg;
        best_normal = -u;
    }
    return true;
}

// The parameter in [0, 1] of the point of segment a + s*(b - a) closest to p (09-85).
inline float segment_param(Vec2 a, Vec2 b, Vec2 p) {
    const Vec2 d = b - a;
    const float dd = dot(d, d);
    if (!(dd > 0.0f)) return 0.0f;
    const float along = dot(p - a, d);
    if (!std::isnan(along)) return clamp(along / dd, 0.0f, 1.0f);
    // p so far from a (near +-FLT_MAX) that the dot product's terms overflow to inf and -inf:
    // the same parameter in double, where they do not.
    const double t = ((static_cast<double>(p.x) - a.x) * d.x + (static_cast<double>(p.y) - a.y) * d.y) / dd;
    return t >= 1.0 ? 1.0f : t > 0.0 ? static_cast<float>(t) : 0.0f;
}

// p minus the closest point of segment a-b to p, formed from differences so that it keeps
// the precision of the distance even far from the origin. A point beside the segment whose
// cross product with it is zero lies on its line: the offset is zero, where
// p - a - t (b - a) is not (t = 3/21 rounds: a point on an integer segment was 2.4e-7 off it,
// so a zero-radius circle there missed).
inline Vec2 offset_from_segment(Vec2 a, Vec2 b, Vec2 p) {
    const float t = segment_param(a, b, p);
    if (t > 0.0f && t < 1.0f && cross(b - a, p - a) == 0.0f) return {};
    return (p - a) - t * (b - a);
}

// p minus the closest point of the polygon's boundary (09-90: the nearest of the closest
// points on every edge), and the edge it lies on.
inline Vec2 offset_from_boundary(const Polygon& poly, Vec2 p, int* edge) {
    Vec2 best{};
    float best_d2 = INFINITY;
    for (int i = 0; i < poly.count(); ++i) {
        const Vec2 rel = offset_from_segment(poly.points()[i], poly.points()[(i + 1) % poly.count()], p);
        const float d2 = dot(rel, rel);
        if (d2 < best_d2) { best_d2 = d2; best = rel; *edge = i; }
    }
    return best;
}

// The lecture's D/F/G closed form (09-111 to 09-122), the one solver for "a point moving by
// v first comes within `radius` of a centre": used by circle-circle sweeps (radius r1 + r2)
// and by casts against circles and rounded corners. `offset` is the centre minus the
// point's start. On a hit, t in [0, 1] and `outward` is the unit vector from the centre to
// the point at contact. Only called with the point outside the circle at t = 0. A path that
// only grazes the circle (F = R) is a hit here, at G = 0: sweeps then drop it by their
// moving-into rule, casts keep it (a bullet that touches a circle hits it). But F comes from
// the rounded direction, and G = sqrt(R^2 - F^2) magnifies its rounding (about sqrt(eps) R):
// an exact graze may come out a hit a little into the motion (a normal 5e-4 past the
// perpendicular for R = 2), which sweeps keep (see LIMITS).
struct CircleContact {
    bool hit = false;
    float t = 0.0f;
    Vec2 outward;
};
CircleContact first_contact_with_circle(Vec2 offset, Vec2 v, float radius);

// The contact of a point cast from `from` to `to` against a circle: t = 0 if it starts in it.
CastHit cast_circle(Vec2 from, Vec2 to, Vec2 center, float radius);

// Shapes relative to a point: used to work near the origin, where floats are dense. An OBB's
// corners far from the origin are not floats, but relative to its centre they are precise.
Polygon centred_polygon(const Obb& box);  // the OBB's polygon with its centre at the origin

// A convex point set for the general SAT (only segment-segment uses it now): its vertices
// and the candidate separating axes it brings (unit edge normals; a segment also brings its
// direction, since it has no area).
struct ConvexView {
    const Vec2* points = nullptr;
    int count = 0;
    const Vec2* axes = nullptr;
    int axis_count = 0;
};

// SAT over the axes of both views (09-62): early exit on a separating axis, MTD along the
// axis of least push. Axes need not be unique or oriented.
Manifold sat_collide(const ConvexView& a, const ConvexView& b);

// Segment as a ConvexView: storage for its axes lives in the SegmentAxes.
struct SegmentAxes {
    Vec2 points[2];
    Vec2 axes[2];
    int axis_count = 0;
};
SegmentAxes segment_axes(const Segment& s);

// floor/ceil results as pixel indices, clamped first so that a far-off float or NaN never
// reaches an int conversion.
inline int pixel_index(float v) {
    if (!(v == v)) return 0;
    return static_cast<int>(clamp(v, -2.0f, 2.0f * static_cast<float>(kMaxMaskSide)));
}

}  // namespace jostle::detail
