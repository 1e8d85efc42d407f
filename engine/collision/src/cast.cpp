// Casts for bullets, slide 09-103: a bullet is the segment from its last to its next
// position, and the first place that segment touches a shape is the hit: t, point and the
// shape's outward normal. The slide leaves the "how" to the segment tests before it; here:
// circles by the D/F/G closed form (09-118, the same solver as the sweeps), boxes by slabs,
// polygons by clipping against every edge's half-plane (Cyrus-Beck), segments by the
// parametric crossing of 09-78, masks row band by row band.
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <utility>
#include <variant>

#include "internal.h"

namespace jostle {

using detail::valid;
using detail::valid_motion;

namespace {

CastHit hit_at(Vec2 from, Vec2 d, float t, Vec2 normal) { return {true, t, from + t * d, detail::plain_zeros(normal)}; }
CastHit starts_inside(Vec2 from, Vec2 normal = {}) { return {true, 0.0f, from, detail::plain_zeros(normal)}; }

// The segment from + t d, t in [0, 1], against the closed box [lo, hi]: the times it enters
// and leaves, and the normal of the face it enters by. A start on the boundary gets that
// face's normal; a start strictly inside gets {0, 0}.
struct Slab {
    bool hit = false;
    float t_enter = 0.0f;
    float t_exit = 1.0f;
    Vec2 normal;
};

Slab slab(Vec2 from, Vec2 d, Vec2 lo, Vec2 hi) {
    Slab s;
    const float f[2] = {from.x, from.y};
    const float dd[2] = {d.x, d.y};
    const float l[2] = {lo.x, lo.y};
    const float h[2] = {hi.x, hi.y};
    for (int axis = 0; axis < 2; ++axis) {
        if (dd[axis] == 0.0f) {
            if (f[axis] < l[axis] || f[axis] > h[axis]) return {};
            continue;
        }
        float t_near = (l[axis] - f[axis]) / dd[axis];
        float t_far = (h[axis] - f[axis]) / dd[axis];
        float sign = -1.0f;  // entering through the low face
        if (t_near > t_far) {
            const float tmp = t_near;
            t_near = t_far;
            t_far = tmp;
            sign = 1.0f;
        }
        if (t_near > s.t_enter) {
            s.t_enter = t_near;
            s.normal = axis == 0 ? Vec2{sign, 0.0f} : Vec2{0.0f, sign};
        }
        if (t_far < s.t_exit) s.t_exit = t_far;
        if (!(s.t_enter <= s.t_exit)) return {};
    }
    s.hit = true;
    if (s.t_enter == 0.0f) {  // starts in the box: on a face, or strictly inside
        s.normal = {};
        if (from.x == lo.x) s.normal = {-1.0f, 0.0f};
        else if (from.x == hi.x) s.normal = {1.0f, 0.0f};
        else if (from.y == lo.y) s.normal = {0.0f, -1.0f};
        else if (from.y == hi.y) s.normal = {0.0f, 1.0f};
    }
    return s;
}

CastHit cast_box(Vec2 from, Vec2 to, Vec2 lo, Vec2 hi) {
    const Vec2 d = to - from;
    const Slab s = slab(from, d, lo, hi);
    if (!s.hit) return {};
    if (s.t_enter == 0.0f) return starts_inside(from, s.normal);
    return hit_at(from, d, s.t_enter, s.normal);
}

// A segment as a zero-thickness wall: where the bullet crosses it (09-78's crossing, by
// parameters along both), and the wall's normal on the side the bullet comes from.
CastHit cast_wall(Vec2 from, Vec2 to, Vec2 a, Vec2 b) {
    const Vec2 r = to - from;
    const Vec2 s = b - a;
    const Vec2 qp = a - from;
    Vec2 n = normalize_or(Vec2{s.y, -s.x}, Vec2{});
    const float side = dot(n, from - a);
    if (side < 0.0f || (side == 0.0f && dot(n, r) > 0.0f)) n = -n;  // against the motion if on it
    // from + t r = a + u s by Cramer's rule, as intersect(Segment, Segment) (09-75's det up to
    // its sign).
    const float denom = cross(r, s);
    if (denom != 0.0f) {
        const float t = cross(qp, s) / denom;
        const float u = cross(qp, r) / denom;
        if (!(t >= 0.0f && t <= 1.0f && u >= 0.0f && u <= 1.0f)) return {};
        if (t == 0.0f) return starts_inside(from, n);
        return hit_at(from, r, t, n);
    }
    // Parallel: a hit only when on one line; then the first end the bullet reaches, whose
    // outward normal faces the bullet.
    if (cross(qp, r) != 0.0f) return {};
    const float rr = dot(r, r);
    // A start on the wall (it has no inside) takes the wall's normal, as a start on any face
    // does: moving along it or not at all, either side (n, against the motion's side if any).
    if (rr == 0.0f) return detail::offset_from_segment(a, b, from) == Vec2{} ? starts_inside(from, n) : CastHit{};
    const float ta = dot(qp, r) / rr;
    const float tb = dot(b - from, r) / rr;
    const float lo = ta < tb ? ta : tb;
    const float hi = ta < tb ? tb : ta;
    if (hi < 0.0f || lo > 1.0f) return {};
    if (lo <= 0.0f) return starts_inside(from, n);
    return hit_at(from, r, lo, normalize_or(-r, Vec2{}));
}

}  // namespace

CastHit detail::cast_circle(Vec2 from, Vec2 to, Vec2 center, float radius) {
    const Vec2 f = from - center;
    const float c = dot(f, f) - radius * radius;
    if (c <= 0.0f) {  // starts in the circle: on it (its normal there) or strictly inside
        return starts_inside(from, c == 0.0f ? normalize_or(f, Vec2{}) : Vec2{});
    }
    const CircleContact contact = first_contact_with_circle(-f, to - from, radius);
    if (!contact.hit) return {};
    return hit_at(from, to - from, contact.t, contact.outward);
}

CastHit cast(Vec2 from, Vec2 to, const Circle& c) {
    if (!valid_motion(from, to - from) || !valid(c)) return {};
    return detail::cast_circle(from, to, c.center, c.radius);
}

CastHit cast(Vec2 from, Vec2 to, const Aabb& box) {
    if (!valid_motion(from, to - from) || !valid(box)) return {};
    return cast_box(from, to, box.min, box.max);
}

CastHit cast(Vec2 from, Vec2 to, const Obb& box) {
    // The slab test in the box's own frame; t is the same in both frames.
    if (!valid_motion(from, to - from) || !valid(box)) return {};
    const Rot q = box.rotation();
    CastHit h = cast_box(inv_rotate(q, from - box.center), inv_rotate(q, to - box.center), -box.half, box.half);
    if (!h.hit) return h;
    h.point = h.t == 0.0f ? from : from + h.t * (to - from);
    h.normal = detail::plain_zeros(rotate(q, h.normal));
    return h;
}

namespace {

// Cyrus-Beck's pass over a convex polygon's edges, for cast(Polygon) (not in the lecture: 09-103
// models the bullet as a segment, and the slides' way would be 09-76..09-78 against each edge;
// clipping gives the first edge reached in one pass): every edge's
// half-plane, n.(x - p) <= 0, cuts the segment's parameter range [0, 1] at t = num / den with
// num = n.(p - from) and den = n.d. The segment enters at the latest entering edge (den < 0)
// and leaves at the earliest leaving one (den > 0); an edge it runs parallel to (den == 0)
// misses it when from is outside. hit: some t in [0, 1] is inside every edge.
struct EdgeClip {
    bool hit = false;
    float t_enter = 0.0f;        // max(0, the entering edges' t)
    Vec2 normal{};               // of the first edge giving t_enter > 0, else {0, 0}
    float max_side = -INFINITY;  // the largest -num: how far from is outside its farthest edge
};

// The plain loop. Each t is divided and then compared (NaN, from inputs past the limits,
// moves nothing), so the answer is a max and a min over the edges in any order: the AVX2
// version below finds the same bits lane by lane.
EdgeClip clip_edges(Vec2 from, Vec2 d, const Vec2* points, const Vec2* normals, int count) {
    EdgeClip c;
    float t_exit = 1.0f;
    for (int i = 0; i < count; ++i) {
        const Vec2 n = normals[i];
        const float num = dot(n, points[i] - from);  // < 0: from is outside this edge
        c.max_side = -num > c.max_side ? -num : c.max_side;
        const float den = dot(n, d);
        if (den == 0.0f) {
            if (num < 0.0f) return {};  // parallel to the edge, outside it
            continue;
        }
        const float t = num / den;
        if (den < 0.0f) {
            if (t > c.t_enter) { c.t_enter = t; c.normal = n; }
        } else if (t < t_exit) {
            t_exit = t;
        }
        if (!(c.t_enter <= t_exit)) return {};  // later edges can only narrow the range
    }
    c.hit = true;
    return c;
}

// The answer from the pass over the edges. The motion is checked here, for a hit only: an
// invalid input is a miss and the arithmetic on any input is defined.
[[gnu::always_inline]] inline CastHit polygon_hit(Vec2 from, Vec2 d, const Polygon& poly, const EdgeClip& c) {
    if (!c.hit || !valid_motion(from, d)) return {};
    if (c.max_side <= 0.0f) {  // from is inside every edge: entering edges gave t <= 0
        if (c.max_side < 0.0f) return starts_inside(from);
        // On the boundary: the first edge it lies on gives the normal.
        const Vec2* points = poly.points().data();
        const Vec2* normals = poly.normals().data();
        int on = 0;
        while (on + 1 < poly.count() && !(-dot(normals[on], points[on] - from) == c.max_side)) ++on;
        return starts_inside(from, normals[on]);
    }
    return hit_at(from, d, c.t_enter, c.normal);
}

// The plain version, for polygons of more than 8 vertices and CPUs without AVX2 (not inlined:
// the AVX2 path then needs no registers saved for it).
[[gnu::noinline]] CastHit cast_polygon(Vec2 from, Vec2 to, const Polygon& poly) {
    if (!valid(poly)) return {};
    const Vec2 d = to - from;
    return polygon_hit(from, d, poly, clip_edges(from, d, poly.points().data(), poly.normals().data(), poly.count()));
}

#ifdef JOSTLE_AVX2_PATHS
// The first edge a lane mask in VHADDPS's order names, or 15 when it names none (an unused slot
// for up to 8 vertices, so a zero normal).
constexpr const auto& kFirstEdge = detail::kFirstHaddSlot<15>;

// The most negative lane in every lane, for lanes that are each +0 or a negative float (no NaN):
// their bits read as unsigned integers grow with the magnitude past the sign bit, and +0 is 0,
// so it is the lanes' unsigned maximum (VPMAXUD: one cycle a step, where VMINPS takes four).
[[gnu::target("avx2"), gnu::always_inline]] inline __m256 most_negative8(__m256 v) {
    __m256i m = _mm256_castps_si256(v);
    m = _mm256_max_epu32(m, _mm256_permute2x128_si256(m, m, 1));
    m = _mm256_max_epu32(m, _mm256_shuffle_epi32(m, 0x4e));
    return _mm256_castsi256_ps(_mm256_max_epu32(m, _mm256_shuffle_epi32(m, 0xb1)));
}
// Normal `i` with -0 made +0 (plain_zeros), in lanes 0 and 1: one 8-byte load, and the -0 lanes
// (bits 0x80000000) cleared by integer compare and mask, two cycles where an add of 0 takes four.
inline __m128 plain_normal(const Vec2* normals, int i) {
    const __m128i n = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(normals + i));
    return _mm_castsi128_ps(_mm_andnot_si128(_mm_cmpeq_epi32(n, _mm_set1_epi32(INT32_MIN)), n));
}
// A hit at parameter t (lane 0), point and normal in lanes 0-1 of their registers.
inline CastHit make_hit(__m128 t, __m128 point, __m128 normal) {
    static_assert(offsetof(CastHit, normal) == offsetof(CastHit, point) + sizeof(Vec2));
    CastHit h;
    h.hit = true;
    h.t = _mm_cvtss_f32(t);
    const __m128 both = _mm_movelh_ps(point, normal);  // one 16-byte store for point and normal
    std::memcpy(static_cast<void*>(&h.point), &both, sizeof both);
    return h;
}

// The loop's answer (Cyrus-Beck, above) for 3 to 8 edges, one to a lane of AVX2 (chosen at run
// time): one VDIVPS for every t, one fold over the lanes, lane masks, and a branch on hit or
// miss where the loop branches on every edge. The lanes do the loop's arithmetic with one sign
// turned: side = the sum of n * (from - p) is -num exactly (negating a product or a sum is
// exact), and tn = side / den is -t; every test below is the loop's with the sign of t turned.
// The loop's max and min do not depend on the order of the edges, so they are the same bits,
// and the first edge reaching the max is the first lane equal to it.
// What is tested is arranged for a short chain from the loads to the branch (the queries
// overlap only as far as the chains let them): an edge is taken as entering from its signs,
// den < 0 and num < 0, known before the division, rather than from t > 0 after it; the same
// edges, but for a quotient that underflows to 0 (tn = -0: as the loop, t_enter stays 0 and
// names no edge) and one of inf / inf, which needs |d| past what valid_motion accepts (a miss
// whatever the lanes say). t_enter past 1 is an entering edge's t past 1, tested beside the
// fold, not after it.
// Slots 6-7 of a hexagon hold zero normals (a Polygon keeps its unused slots zero): side and den
// are +-0 there (or NaN), so those lanes enter, leave and stand outside nowhere.
// from and to come in every 64-bit lane (VBROADCASTSD).
[[gnu::target("avx2"), gnu::always_inline]] inline CastHit cast_polygon8(__m256 f, __m256 to, const Polygon& poly) {
    const __m256 d = _mm256_sub_ps(to, f);               // to - from, as the loop's d
    const float* points = &poly.points().data()->x;       // 8 slots read: a Polygon has 16
    const float* normals = &poly.normals().data()->x;
    const __m256 n0 = _mm256_loadu_ps(normals), n1 = _mm256_loadu_ps(normals + 8);
    // Each slot's x term plus its y term, as dot() sums them (VHADDPS adds y + x: the same sum).
    const __m256 side = _mm256_hadd_ps(_mm256_mul_ps(n0, _mm256_sub_ps(f, _mm256_loadu_ps(points))),
                                       _mm256_mul_ps(n1, _mm256_sub_ps(f, _mm256_loadu_ps(points + 8))));
    const __m256 den = _mm256_hadd_ps(_mm256_mul_ps(n0, d), _mm256_mul_ps(n1, d));
    const __m256 tn = _mm256_div_ps(side, den);
    const __m256 zero = _mm256_setzero_ps();
    const __m256 outside = _mm256_cmp_ps(side, zero, _CMP_GT_OQ);
    const __m256 entering = _mm256_and_ps(_mm256_cmp_ps(den, zero, _CMP_LT_OQ), outside);
    const __m256 tn_enter = most_negative8(_mm256_and_ps(entering, tn));  // -t_enter (+0 for none)
    // A miss: parallel to an edge outside it, t_enter past 1, or a leaving edge before t_enter.
    const __m256 parallel_outside = _mm256_and_ps(_mm256_cmp_ps(den, zero, _CMP_EQ_OQ), outside);
    const __m256 past_end = _mm256_and_ps(entering, _mm256_cmp_ps(tn, _mm256_set1_ps(-1.0f), _CMP_LT_OQ));
    if (_mm256_movemask_ps(_mm256_or_ps(parallel_outside, past_end)) != 0) return {};
    const __m256 leaving = _mm256_cmp_ps(den, zero, _CMP_GT_OQ);
    if (!_mm256_testz_ps(leaving, _mm256_cmp_ps(tn, tn_enter, _CMP_GT_OQ))) return {};
    // valid_motion(from, d) for the hit: from + d and dot(d, d) finite (which holds only for a
    // finite d, and then from + d only for a finite from), side by side.
    const __m128 f2 = _mm256_castps256_ps128(f), d2 = _mm256_castps256_ps128(d);
    const __m128 dd = _mm_mul_ps(d2, d2);
    const __m128 length2 = _mm_add_ps(dd, _mm_permute_ps(dd, 0xb1));  // dx^2 + dy^2 in every lane
    const __m128 end = _mm_add_ps(f2, d2);
    const __m128 finite = _mm_add_ps(_mm_sub_ps(end, end), _mm_sub_ps(length2, length2));  // 0, or NaN
    if (_mm_movemask_ps(_mm_cmpeq_ps(finite, _mm_setzero_ps())) != 0xf) return {};
    const Vec2* edge_normals = poly.normals().data();
    if (_mm256_movemask_ps(outside) == 0) [[unlikely]] {
        // from is inside every edge (the loop's max_side <= 0): t = 0, and the normal of the
        // first edge through from, if any.
        const int on = _mm256_movemask_ps(_mm256_cmp_ps(side, zero, _CMP_EQ_OQ));
        return make_hit(_mm_setzero_ps(), f2, plain_normal(edge_normals, kFirstEdge[on]));
    }
    // From outside: t_enter, and the normal of the first entering edge giving it, if t_enter > 0
    // (tn < 0). 0 - tn_enter is +t_enter, +0 when no edge entered.
    const __m256 gives_t = _mm256_and_ps(_mm256_cmp_ps(tn, zero, _CMP_LT_OQ), _mm256_cmp_ps(tn, tn_enter, _CMP_EQ_OQ));
    const int entered_by = _mm256_movemask_ps(_mm256_and_ps(entering, gives_t));
    const __m128 t = _mm_sub_ps(_mm_setzero_ps(), _mm256_castps256_ps128(tn_enter));
    return make_hit(t, _mm_add_ps(f2, _mm_mul_ps(t, d2)), plain_normal(edge_normals, kFirstEdge[entered_by]));
}

// cast(Polygon)'s lanes, for 3 to 8 vertices on a CPU with AVX2: from and to in every 64-bit
// lane (VBROADCASTSD).
[[gnu::target("avx2")]] CastHit cast_polygon_avx2(Vec2 from, Vec2 to, const Polygon& poly) {
    const __m256 f = _mm256_castpd_ps(_mm256_set1_pd(std::bit_cast<double>(from)));
    const __m256 t = _mm256_castpd_ps(_mm256_set1_pd(std::bit_cast<double>(to)));
    return cast_polygon8(f, t, poly);
}
#endif

}  // namespace

CastHit cast(Vec2 from, Vec2 to, const Polygon& poly) {
#ifdef JOSTLE_AVX2_PATHS
    if (static_cast<unsigned>(poly.count() - 3) <= 5u && detail::has_avx2()) return cast_polygon_avx2(from, to, poly);
#endif
    return cast_polygon(from, to, poly);
}

CastHit cast(Vec2 from, Vec2 to, const Segment& seg) {
    if (!valid_motion(from, to - from) || !valid(seg)) return {};
    return cast_wall(from, to, seg.a, seg.b);
}

CastHit cast(Vec2 from, Vec2 to, const PlacedMask& m) {
    // Set pixels are closed unit squares; the answer is the earliest of their slab hits.
    // Row bands are visited in the order the segment reaches them, and the search stops at a
    // band the segment reaches only after the best hit so far. Row and column ranges are
    // widened by one so that a square touched only at its edge or corner is still tried.
    if (!valid_motion(from, to - from) || !m.mask || m.mask->width() == 0 || m.mask->height() == 0) return {};
    const Mask& mask = *m.mask;
    const Vec2 d = to - from;
    const Aabb box = bounds(m);
    const Slab clip = slab(from, d, box.min, box.max);
    if (!clip.hit) return {};
    const Vec2 origin{static_cast<float>(m.x), static_cast<float>(m.y)};
    const float y_a = from.y + clip.t_enter * d.y - origin.y;
    const float y_b = from.y + clip.t_exit * d.y - origin.y;
    const int j_lo = std::max(detail::pixel_index(std::floor(std::fmin(y_a, y_b))) - 1, 0);
    const int j_hi = std::min(detail::pixel_index(std::floor(std::fmax(y_a, y_b))) + 1, mask.height() - 1);
    const bool down = d.y >= 0.0f;
    CastHit best{};
    for (int k = 0; k <= j_hi - j_lo; ++k) {
        const int j = down ? j_lo + k : j_hi - k;
        const float band_lo = origin.y + static_cast<float>(j);
        // The part of the segment in this band's closed rows [band_lo, band_lo + 1].
        float ta = clip.t_enter, tb = clip.t_exit;
        if (d.y != 0.0f) {
            float u0 = (band_lo - from.y) / d.y, u1 = (band_lo + 1.0f - from.y) / d.y;
            if (u0 > u1) std::swap(u0, u1);
            ta = std::fmax(ta, u0);
            tb = std::fmin(tb, u1);
        }
        if (best.hit && ta > best.t) break;  // later bands are reached later still
        if (ta > tb) continue;
        const float x_a = from.x + ta * d.x - origin.x;
        const float x_b = from.x + tb * d.x - origin.x;
        const int i_lo = std::max(detail::pixel_index(std::floor(std::fmin(x_a, x_b))) - 1, 0);
        const int i_hi = std::min(detail::pixel_index(std::floor(std::fmax(x_a, x_b))) + 1, mask.width() - 1);
        for (int i = i_lo; i <= i_hi; ++i) {
            if (!mask.get(i, j)) continue;
            const Vec2 lo = origin + Vec2{static_cast<float>(i), static_cast<float>(j)};
            const CastHit h = cast_box(from, to, lo, lo + Vec2{1.0f, 1.0f});
            if (h.hit && (!best.hit || h.t < best.t)) best = h;
        }
    }
    if (best.hit && best.t == 0.0f) best.normal = {};  // started on a set pixel
    return best;
}

CastHit cast(Vec2 from, Vec2 to, const Shape& s) {
    return std::visit([&](const auto& shape) { return cast(from, to, shape); }, s);
}

}  // namespace jostle
