// Oriented boxes and convex polygons by the separating axis theorem, slides 09-35 to 09-69:
// project both shapes on each candidate axis (the edge normals), stop at the first axis
// with a gap, otherwise push along the axis that needs the least push.
#include <bit>
#include <cmath>
#include <cstring>

#include "internal.h"

namespace jostle {

using detail::valid;

namespace detail {

// Projection of a point set on an axis (09-51: project every point, keep min and max).
// Points are taken relative to `origin` (a vertex of one shape), so that shapes far from the
// world origin are projected with the precision of their size, not of their position.
static void project(const ConvexView& v, Vec2 axis, Vec2 origin, float& lo, float& hi) {
    lo = hi = dot(v.points[0] - origin, axis);
    for (int i = 1; i < v.count; ++i) {
        const float d = dot(v.points[i] - origin, axis);
        lo = d < lo ? d : lo;
        hi = d > hi ? d : hi;
    }
}

Manifold sat_collide(const ConvexView& a, const ConvexView& b) {
    float best = INFINITY;
    Vec2 best_normal{1.0f, 0.0f};
    const Vec2 origin = a.points[0];
    auto test_axes = [&](const ConvexView& owner) {
        for (int i = 0; i < owner.axis_count; ++i) {
            const Vec2 u = owner.axes[i];
            float a_lo, a_hi, b_lo, b_hi;
            project(a, u, origin, a_lo, a_hi);
            project(b, u, origin, b_lo, b_hi);
            if (!consider_axis(u, a_hi - b_lo, b_hi - a_lo, best, best_normal)) return false;
        }
        return true;
    };
    if (!test_axes(a) || !test_axes(b)) return {};
    if (best == INFINITY) {
        // Neither shape brought an axis: two points. They meet only where they are equal.
        if (a.points[0] == b.points[0]) return hit_with(0.0f, {1.0f, 0.0f});
        return {};
    }
    return hit_with(best, best_normal);
}

SegmentAxes segment_axes(const Segment& s) {
    SegmentAxes out;
    out.points[0] = s.a;
    out.points[1] = s.b;
    const Vec2 d = s.b - s.a;
    const float len = length(d);
    if (len > 0.0f) {
        const Vec2 dir{d.x / len, d.y / len};
        out.axes[0] = Vec2{dir.y, -dir.x};  // the normal
        out.axes[1] = dir;                  // the direction: a segment has no area
        out.axis_count = 2;
    }
    return out;
}

}  // namespace detail

namespace {
detail::ConvexView view_of(const detail::SegmentAxes& s) {
    return {s.points, 2, s.axes, s.axis_count};
}

// 09-58 with the boxes' own axes: 2 + 2 candidate axes. A box's projection on an axis u is
// its centre's projection plus-minus the projected radius hx |ux.u| + hy |uy.u|, so no
// corner is projected one by one. d is B's centre minus A's centre.
//
// The four axes are computed side by side (GCC's portable vector extension, one lane per
// axis, each lane exactly the scalar arithmetic), and one test of the four lanes replaces the
// slides' early exit per axis (09-50): a gap on any axis is a miss. The axis is picked in
// axis order as the loop did (a later axis wins only when strictly smaller), so the results
// are the same bit for bit (axis and positive mean nothing on a miss).
struct BoxBox {
    Manifold manifold;
    int axis = 0;          // the MTD's axis: 0, 1 A's x and y, 2, 3 B's x and y
    bool positive = true;  // the normal is +axis (or -axis)
};

inline BoxBox box_box(Vec2 half_a, Rot qa, Vec2 half_b, Rot qb, Vec2 d) {
    using detail::Float4;
    using detail::Int4;
    // The axes: A's x and y, B's x and y.
    const Float4 q = {qa.c, qa.s, qb.c, qb.s};
    const Float4 flip = {0.0f, -0.0f, 0.0f, -0.0f};  // XOR with -0 negates
    const Float4 ux = detail::bit_xor(__builtin_shufflevector(q, q, 0, 1, 2, 3), flip);  // c, -s, c, -s
    const Float4 uy = __builtin_shufflevector(q, q, 1, 0, 3, 2);                          // s, c, s, c
    // |cos| of the angles between A's axes (rows) and B's (columns), dot(A_i, B_j) lane by
    // lane {00, 01, 10, 11}: a box's projected radius on the other's axis. On its own axes a
    // box's radius is its half extent.
    const Float4 cosines = detail::abs(__builtin_shufflevector(ux, ux, 0, 0, 1, 1) * __builtin_shufflevector(ux, ux, 2, 3, 2, 3) +
                                       __builtin_shufflevector(uy, uy, 0, 0, 1, 1) * __builtin_shufflevector(uy, uy, 2, 3, 2, 3));
    const Float4 ha = {half_a.x, half_a.x, half_a.y, half_a.y}, hb = {half_b.x, half_b.y, half_b.x, half_b.y};
    const Float4 ta = ha * cosines;  // hax c00, hax c01, hay c10, hay c11
    const Float4 tb = hb * cosines;  // hbx c00, hby c01, hbx c10, hby c11
    // A: hax, hay on its own axes, hax c00 + hay c10 and hax c01 + hay c11 on B's; B: hbx c00 +
    // hby c01 and hbx c10 + hby c11 on A's axes, hbx, hby on its own.
    const Float4 radius_a = __builtin_shufflevector(ha, ta + __builtin_shufflevector(ta, ta, 2, 3, 2, 3), 0, 2, 4, 5);
    const Float4 radius_b = __builtin_shufflevector(
        __builtin_shufflevector(tb, tb, 0, 2, 0, 2) + __builtin_shufflevector(tb, tb, 1, 3, 1, 3), hb, 0, 1, 4, 5);
    const Float4 r = radius_a + radius_b;
    const Float4 s = ux * d.x + uy * d.y;  // dot(d, u) per axis
    const Float4 push_pos = r - s;         // moving A by -push_pos u separates (normal u)
    const Float4 push_neg = r + s;         // moving A by +push_neg u separates (normal -u)
    // detail::consider_axis lane by lane: a gap (or NaN) on any axis is a miss.
    if (detail::lane_bits((push_pos >= 0.0f) & (push_neg >= 0.0f)) != 15) return {};
    const Int4 pos = push_pos <= push_neg;
    const Float4 push = pos ? push_pos : push_neg;  // 09-60: the smaller push of each axis
    float best = INFINITY;
    for (int i = 0; i < 4; ++i) best = push[i] < best ? push[i] : best;
    // The first axis whose push is the least (a later one wins only when strictly smaller).
    // (When every push overflowed, best is inf and hit_with makes it a miss.)
    BoxBox out;
    out.axis = std::countr_zero(detail::lane_bits(push == best));
    out.positive = ((detail::lane_bits(pos) >> out.axis) & 1u) != 0;
    // Every axis's normal, +u or -u (a sign flip), then the MTD's: no branch on the sign.
    const Float4 minus_zero = {-0.0f, -0.0f, -0.0f, -0.0f};
    const Float4 signs = pos ? Float4{} : minus_zero;
    const Float4 nx = detail::bit_xor(ux, signs), ny = detail::bit_xor(uy, signs);
    out.manifold = detail::hit_with(best, detail::lane_pair(nx, ny, out.axis));
    return out;
}
}  // namespace

namespace {
// Two convex polygons, B shifted by `offset` (09-62, in the form that needs each face once).
// Of an axis u, SAT's two pushes measure the overlap on either side; for polygons only one
// side of each edge normal can be the answer: the MTD is the distance from the origin to the
// boundary of the Minkowski difference A - B, whose edges are A's edges and B's edges turned
// round, so its outward normals are exactly A's normals and B's normals negated. For A's edge
// i, B's separation from that edge's line is min over B's vertices of dot(n_i, b_j - a_i);
// the largest separation over all faces, if <= 0, is minus the depth (09-60), and a face with
// separation > 0 is a separating axis (09-50's early exit). Every difference is between nearby
// points, so the result keeps the precision of the shapes' size wherever they are.
struct FaceSeparation {
    float separation = -INFINITY;
    int face = 0;
};

// Four faces side by side (detail::Float4): each lane does exactly the scalar arithmetic of
// one face, so the results are the same bit for bit.
using detail::Float4;

// The largest separation of the point set `others` from the faces of a polygon (its points
// and outward normals): for face i, min over the others of dot(n_i, o - p_i) (09-51: the
// lowest projection, measured from the face). Stops at the first group of faces with one
// that separates (or gives NaN: a miss). Of tied faces the first wins.
// The faces are read four at a time as two 16-byte loads each and split into x and y lanes by
// shuffles; a group may run past `count` into the storage's spare slots (every caller's arrays
// have room for a whole group: a Polygon's 16 slots, a box's 4), whose lanes are masked off.
// The gap test and the group's largest separation come from lane masks, not a branch per lane.
[[gnu::noinline]] FaceSeparation max_face_separation_sse(const Vec2* points, const Vec2* normals, int count, const Vec2* others,
                                       int other_count) {
    FaceSeparation best;
    for (int first = 0; first < count; first += 4) {
        Float4 n01, n23, p01, p23;
        std::memcpy(&n01, normals + first, sizeof n01);
        std::memcpy(&n23, normals + first + 2, sizeof n23);
        std::memcpy(&p01, points + first, sizeof p01);
        std::memcpy(&p23, points + first + 2, sizeof p23);
        const Float4 nx = __builtin_shufflevector(n01, n23, 0, 2, 4, 6);
        const Float4 ny = __builtin_shufflevector(n01, n23, 1, 3, 5, 7);
        const Float4 px = __builtin_shufflevector(p01, p23, 0, 2, 4, 6);
        const Float4 py = __builtin_shufflevector(p01, p23, 1, 3, 5, 7);
        Float4 s = nx * (others[0].x - px) + ny * (others[0].y - py);
        for (int j = 1; j < other_count; ++j) {
            const Float4 d = nx * (others[j].x - px) + ny * (others[j].y - py);
            s = d < s ? d : s;
        }
        const int left = count - first;
        const unsigned lanes = left >= 4 ? 15u : (1u << left) - 1u;  // the lanes holding faces
        const unsigned gaps = ~detail::lane_bits(s <= 0.0f) & lanes;  // > 0, or NaN past the limits
        if (gaps != 0) {
            const int lane = std::countr_zero(gaps);
            return {s[lane], first + lane};
        }
        // The group's largest separation and the first lane holding it.
        float most = s[0];
        for (int lane = 1; lane < 4; ++lane) most = (lanes >> lane & 1u) && s[lane] > most ? s[lane] : most;
        const int lane = std::countr_zero(detail::lane_bits(s == most) & lanes);
        if (s[lane] > best.separation) best = {s[lane], first + lane};
    }
    return best;
}

#ifdef JOSTLE_AVX2_PATHS
// The same with eight faces a group (AVX2, chosen at run time): a hexagon's faces are one
// group instead of two. Every lane still does exactly the scalar arithmetic (a target
// attribute changes which instructions run, not the rounding: no FMA, -ffp-contract=off), and
// the first group with a gap and the first of tied faces are the same faces as above, so the
// answers are the same bit for bit. Reads 8 slots a group: only for a Polygon's 16-slot arrays
// (callers pass boxes, whose arrays have 4, to the SSE version).
using detail::Float8;
using detail::Int8;

[[gnu::target("avx2")]] FaceSeparation max_face_separation_avx(const Vec2* points, const Vec2* normals, int count,
                                                              const Vec2* others, int other_count) {
    FaceSeparation best;
    for (int first = 0; first < count; first += 8) {
        Float8 nx, ny, px, py;
        detail::load_xy8(normals + first, nx, ny);
        detail::load_xy8(points + first, px, py);
        Float8 s = nx * (others[0].x - px) + ny * (others[0].y - py);
        for (int j = 1; j < other_count; ++j) {
            const Float8 d = nx * (others[j].x - px) + ny * (others[j].y - py);
            s = d < s ? d : s;
        }
        const Int8 live = Int8{0, 1, 2, 3, 4, 5, 6, 7} < count - first;  // the lanes holding faces
        const unsigned gaps = detail::lane_bits8(live & ~(s <= 0.0f));  // > 0, or NaN past the limits
        if (gaps != 0) {
            const int lane = std::countr_zero(gaps);
            return {s[lane], first + lane};
        }
        // The group's largest separation (a horizontal VMAXPS over the live lanes) and the
        // first lane holding it.
        const Float8 minus_inf = {-INFINITY, -INFINITY, -INFINITY, -INFINITY, -INFINITY, -INFINITY, -INFINITY, -INFINITY};
        const Float8 m = detail::max8(live ? s : minus_inf);
        const int lane = std::countr_zero(detail::lane_bits8(live & (s == m)));
        if (s[lane] > best.separation) best = {s[lane], first + lane};
    }
    return best;
}

// AVX2 for polygons of more than four faces when the CPU has it (checked once).
FaceSeparation max_face_separation(const Vec2* points, const Vec2* normals, int count, const Vec2* others,
                                   int other_count) {
    if (count > 4 && detail::has_avx2()) return max_face_separation_avx(points, normals, count, others, other_count);
    return max_face_separation_sse(points, normals, count, others, other_count);
}
#else
FaceSeparation max_face_separation(const Vec2* points, const Vec2* normals, int count, const Vec2* others,
                                   int other_count) {
    return max_face_separation_sse(points, normals, count, others, other_count);
}
#endif

}  // namespace

bool detail::use_avx2_paths(bool on) {
#ifdef JOSTLE_AVX2_PATHS
    detail::ask_cpu_for_avx2();
    if (!on) detail::avx2_state.store(0, std::memory_order_relaxed);
    return detail::has_avx2();
#else
    (void)on;
    return false;
#endif
}

namespace {

// A convex polygon's vertices and outward normals as the pair code reads them: a Polygon's
// own arrays, or a box's 4 corners built on the stack (no 16-slot Polygon to fill).
struct Convex {
    const Vec2* points = nullptr;
    const Vec2* normals = nullptr;
    int count = 0;
};
Convex convex(const Polygon& p) { return {p.points().data(), p.normals().data(), p.count()}; }

// An OBB around its centre: its rotation and half axes ux = rotate(q, {hx, 0}), uy =
// rotate(q, {0, hy}). Corner i is -ux - uy, ux - uy, ux + uy, -ux + uy (positive turns, like
// to_polygon), formed as (+-ux) + (+-uy) with the signs flipped bit-wise (a - b is a + -b, so
// the same bits); normal i is rotate(q, {0, -1}), ({1, 0}), ({0, 1}), ({-1, 0}).
struct BoxAxes {
    Rot q;
    Vec2 ux, uy;
    explicit BoxAxes(const Obb& box)
        : q(box.rotation()), ux(rotate(q, Vec2{box.half.x, 0.0f})), uy(rotate(q, Vec2{0.0f, box.half.y})) {}
    Vec2 corner(int i) const {
        static constexpr bool kNegX[4] = {true, false, false, true}, kNegY[4] = {true, true, false, false};
        const Vec2 x = kNegX[i] ? -ux : ux, y = kNegY[i] ? -uy : uy;
        return x + y;
    }
    Vec2 normal(int i) const {
        static constexpr Vec2 kNormals[4] = {{0.0f, -1.0f}, {1.0f, 0.0f}, {0.0f, 1.0f}, {-1.0f, 0.0f}};
        return rotate(q, kNormals[i]);
    }
};

// An OBB's corners and normals around its centre, as arrays (a polygon's view).
struct CentredBox {
    Vec2 points[4];
    Vec2 normals[4];
    explicit CentredBox(const Obb& box) {
        const BoxAxes axes(box);
        for (int i = 0; i < 4; ++i) {
            points[i] = axes.corner(i);
            normals[i] = axes.normal(i);
        }
    }
    Convex view() const { return {points, normals, 4}; }
};

// The MTD of two polygons and the face it came from (the reference face of a contact set).
struct PolygonContact {
    Manifold manifold;
    bool a_face = true;  // the face is A's (normal = its normal) or B's (normal = minus its normal)
    int face = 0;
};

[[gnu::noinline]] PolygonContact polygon_polygon(Convex a, Convex b, Vec2 offset) {
    const int na = a.count, nb = b.count;
    // B's points shifted; with no shift, B's own (adding a zero could only turn a -0 into +0,
    // which no separation can tell apart).
    Vec2 shifted[kMaxPolygonVertices];
    const Vec2* pb = b.points;
    if (!(offset == Vec2{})) {
        for (int j = 0; j < nb; ++j) shifted[j] = b.points[j] + offset;
        pb = shifted;
    }
    const FaceSeparation fa = max_face_separation(a.points, a.normals, na, pb, nb);
    if (!(fa.separation <= 0.0f)) return {};
    const FaceSeparation fb = max_face_separation(pb, b.normals, nb, a.points, na);
    if (!(fb.separation <= 0.0f)) return {};
    // Ties go to A's face, as for every SAT pair. A depth that overflowed is past the limits.
    const bool a_face = fa.separation >= fb.separation;
    const float depth = -(a_face ? fa.separation : fb.separation);
    if (!(depth < INFINITY)) return {};
    return {detail::hit_with(depth, a_face ? a.normals[fa.face] : -b.normals[fb.face]), a_face,
            a_face ? fa.face : fb.face};
}

#ifdef JOSTLE_AVX2_PATHS
// polygon_polygon for two Polygons of at most 8 vertices, more than 4 on one (AVX2): each
// one's faces are one group, A's and then B's, in one function (one frame, one VZEROUPPER,
// no call per side). The same separations and answers as polygon_polygon: A's gap returns
// before B's faces are tried, a gap's value is never used, and a group's largest separation
// is a lane's value (VMAXPS returns one of its operands; the first lane equal to it may hold
// -0 for +0, which neither the comparison of the sides nor the clamped depth tells apart).
bool fits_one_group(const Polygon& a, const Polygon& b) {
    return a.count() <= 8 && b.count() <= 8 && (a.count() > 4 || b.count() > 4) && detail::has_avx2();
}

// The smallest separation of the points from each of the 8 faces (n, p): the loop of
// max_face_separation_avx.
[[gnu::target("avx2"), gnu::always_inline]] inline Float8 min_separations8(Float8 nx, Float8 ny, Float8 px,
                                                                          Float8 py, const Vec2* others,
                                                                          int other_count) {
    Float8 s = nx * (others[0].x - px) + ny * (others[0].y - py);
    for (int j = 1; j < other_count; ++j) {
        const Float8 d = nx * (others[j].x - px) + ny * (others[j].y - py);
        s = d < s ? d : s;
    }
    return s;
}

[[gnu::target("avx2"), gnu::always_inline]] inline PolygonContact polygon_polygon8(const Polygon& pa,
                                                                                  const Polygon& pb) {
    const Convex a = convex(pa), b = convex(pb);
    const Int8 lane = {0, 1, 2, 3, 4, 5, 6, 7};
    const float inf = INFINITY;
    const Float8 minus_inf = {-inf, -inf, -inf, -inf, -inf, -inf, -inf, -inf};
    Float8 nx, ny, px, py;
    detail::load_xy8(a.normals, nx, ny);
    detail::load_xy8(a.points, px, py);
    const Float8 sa = min_separations8(nx, ny, px, py, b.points, b.count);
    const Int8 live_a = lane < a.count;
    if (detail::lane_bits8(live_a & ~(sa <= 0.0f)) != 0) return {};  // > 0, or NaN past the limits
    detail::load_xy8(b.normals, nx, ny);
    detail::load_xy8(b.points, px, py);
    const Float8 sb = min_separations8(nx, ny, px, py, a.points, a.count);
    const Int8 live_b = lane < b.count;
    if (detail::lane_bits8(live_b & ~(sb <= 0.0f)) != 0) return {};
    const Float8 ma = detail::max8(live_a ? sa : minus_inf);
    const Float8 mb = detail::max8(live_b ? sb : minus_inf);
    // Ties go to A's face; of tied faces the first.
    const bool a_face = ma[0] >= mb[0];
    const float depth = -(a_face ? ma[0] : mb[0]);
    if (!(depth < INFINITY)) return {};
    const unsigned tied =
        a_face ? detail::lane_bits8(live_a & (sa == ma)) : detail::lane_bits8(live_b & (sb == mb));
    const int face = std::countr_zero(tied);
    return {detail::hit_with(depth, a_face ? a.normals[face] : -b.normals[face]), a_face, face};
}

[[gnu::target("avx2")]] Manifold polygon_mtd8(const Polygon& a, const Polygon& b) {
    return polygon_polygon8(a, b).manifold;
}
[[gnu::target("avx2")]] PolygonContact polygon_contact8(const Polygon& a, const Polygon& b) {
    return polygon_polygon8(a, b);
}
#endif

// The MTD of two Polygons and its face.
PolygonContact polygon_contact(const Polygon& a, const Polygon& b) {
#ifdef JOSTLE_AVX2_PATHS
    if (fits_one_group(a, b)) return polygon_contact8(a, b);
#endif
    return polygon_polygon(convex(a), convex(b), {});
}

// Sutherland-Hodgman against one line: keeps the part of the segment where dot(u, p) <= c;
// false when none is left.
bool clip(Vec2 (&ends)[2], Vec2 u, float c) {
    const float d0 = dot(u, ends[0]) - c, d1 = dot(u, ends[1]) - c;
    if (d0 > 0.0f && d1 > 0.0f) return false;
    if (d0 > 0.0f) ends[0] = ends[0] + (d0 / (d0 - d1)) * (ends[1] - ends[0]);
    else if (d1 > 0.0f) ends[1] = ends[1] + (d1 / (d1 - d0)) * (ends[0] - ends[1]);
    return true;
}

// The contact set of an overlapping pair (the clipping Box2D and most engines use): the
// reference face is the MTD's face; the incident face is the other polygon's face most
// opposed to it; the incident edge is clipped to the reference edge's extent, and the
// clipped ends that lie on or below the reference face are the contacts, each with its own
// depth below that face.
//
// The clipping, given the reference face (normal n, from v1 to v2) and the incident edge's
// ends relative to v1: the contacts in the reference polygon's frame, or none when rounding
// left no clipped end on or below the face (or the incident edge lies beside the reference
// edge); then the caller takes the incident vertex deepest along n.
[[gnu::always_inline]] inline ContactSet clip_edge(const Manifold& m, Vec2 n, Vec2 v1, Vec2 v2, Vec2 e0,
                                                  Vec2 e1) {
    ContactSet out;
    out.manifold = m;
    // The side planes s >= 0 and s <= |v2 - v1| along the edge's direction t.
    const Vec2 t{-n.y, n.x};  // the edge direction of a positively turning polygon
    Vec2 ends[2] = {e0, e1};
    if (clip(ends, -t, 0.0f) && clip(ends, t, dot(t, v2 - v1))) {
        for (const Vec2 p : ends) {
            const float h = dot(n, p);  // height above the reference face
            if (h <= 0.0f) {
                out.points[static_cast<std::size_t>(out.count)] = p + v1;
                out.depths[static_cast<std::size_t>(out.count)] = detail::clamp(-h, 0.0f, m.depth);
                ++out.count;
            }
        }
    }
    if (out.count == 2 && out.points[0] == out.points[1]) out.count = 1;
    return out;
}

// The contact set of polygons `ref` and `inc`, `inc` shifted by `offset`.
ContactSet clip_contacts(const PolygonContact& pc, Convex ref, Convex inc, Vec2 offset) {
    if (!pc.manifold.hit) {
        ContactSet out;
        out.manifold = pc.manifold;
        return out;
    }
    const int nr = ref.count, ni = inc.count;
    const Vec2 n = ref.normals[pc.face];
    const Vec2 v1 = ref.points[pc.face];
    const Vec2 v2 = ref.points[detail::next_index(pc.face, nr)];
    int k = 0;  // the incident face: its normal most opposed to n
    float most = INFINITY;
    for (int i = 0; i < ni; ++i) {
        const float d = dot(inc.normals[i], n);
        if (d < most) { most = d; k = i; }
    }
    ContactSet out = clip_edge(pc.manifold, n, v1, v2, inc.points[k] + offset - v1,
                               inc.points[detail::next_index(k, ni)] + offset - v1);
    if (out.count == 0) {
        // None left (see clip_edge): the incident vertex deepest along n stands for the contact.
        int deepest = 0;
        for (int i = 1; i < ni; ++i)
            if (dot(n, inc.points[i] - inc.points[deepest]) < 0.0f) deepest = i;
        out.points[0] = inc.points[deepest] + offset;
        out.depths[0] = pc.manifold.depth;
        out.count = 1;
    }
    return out;
}

// The contact set of a hit whose reference face pc names.
ContactSet contacts_of(const PolygonContact& pc, Convex a, Convex b, Vec2 offset) {
    if (pc.a_face) return clip_contacts(pc, a, b, offset);
    // B's face is the reference: clip in B's shifted frame (A shifted by -offset), then back.
    ContactSet c = clip_contacts(pc, b, a, -offset);
    for (Vec2& p : c.points) p = p + offset;
    c.manifold = pc.manifold;
    return c;
}

// Past float's range (boxes with half extents near FLT_MAX) a clipped point can overflow even
// when the MTD did not: a contact set with a point or depth that is not finite is a miss.
ContactSet finite_or_miss(const ContactSet& c) {
    for (int k = 0; k < c.count; ++k) {
        const std::size_t i = static_cast<std::size_t>(k);
        if (!detail::finite(c.points[i]) || !detail::finite(c.depths[i])) return {};
    }
    return c;
}
}  // namespace

ContactSet contacts(const Polygon& a, const Polygon& b) {
    if (!valid(a) || !valid(b)) return {};
    return finite_or_miss(contacts_of(polygon_contact(a, b), convex(a), convex(b), {}));
}

ContactSet contacts(const Obb& a, const Obb& b) {
    // The MTD of collide(a, b), then its face on the box that owns the axis: faces 0..3 have
    // normals -y, +x, +y, -x of the box. Solved around A's centre, where both boxes' corners
    // are precise; the points are moved back. The same arithmetic as clip_contacts on the two
    // CentredBoxes (so the same bits), with only the corners and normals it reads computed,
    // and the incident face (the four normals' dot products with n) found side by side.
    const Vec2 d = b.center - a.center;
    const BoxBox bb = box_box(a.half, a.rotation(), b.half, b.rotation(), d);
    if (!bb.manifold.hit || !(valid(a) && valid(b))) return {};
    // A's face has the normal's direction; B's the opposite one.
    const bool a_face = bb.axis < 2;
    const bool outward_positive = bb.positive == a_face;
    static constexpr int kFace[2][2] = {{3, 1}, {0, 2}};  // [y axis][outward along +axis]
    const int face = kFace[bb.axis & 1][outward_positive];
    const BoxAxes ref(a_face ? a : b), inc(a_face ? b : a);
    const Vec2 offset = a_face ? d : -d;  // inc's centre relative to ref's
    const Vec2 n = ref.normal(face);
    const Vec2 v1 = ref.corner(face), v2 = ref.corner(detail::next_index(face, 4));
    // dot(inc.normal(i), n) for the four faces (rotate's arithmetic lane by lane); of tied
    // faces the first, as clip_contacts' loop takes.
    const Float4 c = {inc.q.c, inc.q.c, inc.q.c, inc.q.c}, s = {inc.q.s, inc.q.s, inc.q.s, inc.q.s};
    const Float4 vx = {0.0f, 1.0f, 0.0f, -1.0f}, vy = {-1.0f, 0.0f, 1.0f, 0.0f};
    const Float4 dots = (c * vx - s * vy) * n.x + (s * vx + c * vy) * n.y;
    Float4 least = __builtin_shufflevector(dots, dots, 1, 0, 3, 2);
    least = dots < least ? dots : least;
    const Float4 other_pair = __builtin_shufflevector(least, least, 2, 3, 0, 1);
    least = least < other_pair ? least : other_pair;
    const unsigned first = detail::lane_bits(dots == least);  // not 0: valid boxes give no NaN
    const int k = first != 0 ? std::countr_zero(first) : 0;
    ContactSet out = clip_edge(bb.manifold, n, v1, v2, inc.corner(k) + offset - v1,
                               inc.corner(detail::next_index(k, 4)) + offset - v1);
    if (out.count == 0) {
        // Rounding left no clipped end on or below the face: the deepest incident corner.
        int deepest = 0;
        for (int i = 1; i < 4; ++i)
            if (dot(n, inc.corner(i) - inc.corner(deepest)) < 0.0f) deepest = i;
        out.points[0] = inc.corner(deepest) + offset;
        out.depths[0] = bb.manifold.depth;
        out.count = 1;
    }
    // Back to A's frame (with B's face, both slots, as contacts_of moves them), then to the
    // world.
    if (!a_face) {
        for (Vec2& p : out.points) p = p + d;
    }
    for (int i = 0; i < out.count; ++i) out.points[static_cast<std::size_t>(i)] += a.center;
    return finite_or_miss(out);
}

Manifold collide(const Obb& a, const Obb& b) {
    // The boxes are checked only for an answer that would be a hit: an invalid box is a miss,
    // so a miss needs no check (the arithmetic on any input is defined, only the answer would
    // be wrong).
    const BoxBox bb = box_box(a.half, a.rotation(), b.half, b.rotation(), b.center - a.center);
    if (!bb.manifold.hit || !(valid(a) && valid(b))) return {};
    // Rebuilt from its fields: returning bb.manifold itself, GCC stores its fields and
    // reloads them as words (a failed store forward); rebuilt, only the normal still passes
    // through the stack (3 stack accesses instead of 6; 0.57-0.60 ms against 0.57-0.63).
    return Manifold{true, bb.manifold.depth, bb.manifold.normal};
}

Manifold collide(const Aabb& a, const Obb& b) {
    // The AABB as a box at angle 0. Its centre (min + max) / 2 may not be a float far from
    // the origin, so the offset is formed from differences instead.
    if (!(valid(a) && valid(b))) return {};
    const Vec2 half = (a.max - a.min) * 0.5f;
    return box_box(half, Rot{}, b.half, b.rotation(), (b.center - a.min) - half).manifold;
}

Manifold collide(const Polygon& a, const Polygon& b) {
    // 09-62: any convex shape, every edge normal of both.
    if (!valid(a) || !valid(b)) return {};
#ifdef JOSTLE_AVX2_PATHS
    if (fits_one_group(a, b)) return polygon_mtd8(a, b);
#endif
    return polygon_polygon(convex(a), convex(b), {}).manifold;
}

Manifold collide(const Obb& a, const Polygon& b) {
    // Solved around the box's centre, where its corners are precise: the polygon is viewed
    // shifted by -centre instead of being copied.
    if (!valid(a) || !valid(b)) return {};
    return polygon_polygon(CentredBox(a).view(), convex(b), -a.center).manifold;
}

Manifold collide(const Aabb& a, const Polygon& b) {
    if (!valid(a) || !valid(b)) return {};
    return polygon_polygon(convex(to_polygon(a)), convex(b), {}).manifold;
}

Manifold collide(const Aabb& a, const Segment& b) {
    if (!valid(a) || !valid(b)) return {};
    return collide(to_polygon(a), b);
}

namespace {
// A convex polygon against a segment (09-62 by faces, as polygon_polygon): the Minkowski
// difference of a polygon and a segment has the polygon's faces and the two sides of the
// segment's line as its faces (a segment of zero length adds none: a point), so those are all
// the axes SAT needs: the segment's own direction, which the generic SAT (sat_collide) also
// tries, is never a smaller push than the least of them. Each side's separation is measured
// from one end (n from b.a, -n from b.b; either end lies on both sides' line). Ties go to A's
// face, then side n (the MTD's normal is then -n: from A toward B), then side -n.
Manifold polygon_segment(Convex a, const Segment& b) {
    const Vec2 ends[2] = {b.a, b.b};
    const FaceSeparation fa = max_face_separation(a.points, a.normals, a.count, ends, 2);
    if (!(fa.separation <= 0.0f)) return {};
    float fb = -INFINITY;  // the segment's sides: the largest separation of A's vertices
    Vec2 fb_normal;        // and the MTD's normal for it (minus the side's outward normal)
    const Vec2 d = b.b - b.a;
    const float len = length(d);
    if (len > 0.0f) {
        const Vec2 n{d.y / len, -d.x / len};
        // Side n through b.a: min over A of dot(n, v - b.a); side -n through b.b: min over A of
        // dot(-n, v - b.b). A separation > 0 (or NaN) is a gap.
        float side_a = INFINITY, side_b = INFINITY;
        for (int i = 0; i < a.count; ++i) {
            const float ta = dot(n, a.points[i] - b.a), tb = -dot(n, a.points[i] - b.b);
            side_a = ta < side_a ? ta : side_a;
            side_b = tb < side_b ? tb : side_b;
        }
        if (!(side_a <= 0.0f) || !(side_b <= 0.0f)) return {};
        if (side_b > side_a) {
            fb = side_b;
            fb_normal = n;
        } else {
            fb = side_a;
            fb_normal = -n;
        }
    }
    const bool a_face = fa.separation >= fb;
    const float depth = -(a_face ? fa.separation : fb);
    if (!(depth < INFINITY)) return {};
    return detail::hit_with(depth, a_face ? a.normals[fa.face] : fb_normal);
}
}  // namespace

Manifold collide(const Polygon& a, const Segment& b) {
    if (!valid(a) || !valid(b)) return {};
    return polygon_segment(convex(a), b);
}

Manifold collide(const Obb& a, const Segment& b) {
    // Around the box's centre, where its corners are precise.
    if (!valid(a) || !valid(b)) return {};
    return polygon_segment(CentredBox(a).view(), Segment{b.a - a.center, b.b - a.center});
}

Manifold collide(const Segment& a, const Segment& b) {
    if (!valid(a) || !valid(b)) return {};
    const auto sa = detail::segment_axes(a);
    const auto sb = detail::segment_axes(b);
    return detail::sat_collide(view_of(sa), view_of(sb));
}

}  // namespace jostle
