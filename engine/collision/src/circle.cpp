// Circles, slides 09-70 to 09-102: circle-circle by squared distances, polygon-circle by the
// closest point on the boundary and by SAT with the centre-to-vertex axis, box-circle by
// the "push in" clamp, segment-circle. The slides test "< r" (09-71, 09-87); here touching
// (== r) is a hit with depth 0, the convention for every pair.
#include <cfloat>
#include <bit>
#include <cmath>
#include <cstring>

#include "internal.h"

namespace jostle {

using detail::hit_with;
using detail::valid;

namespace {
// collide(Circle, Circle) past its distance test, kept out of line (a tail call) so that the
// miss, the common answer, is a short function whose {} needs no packing of a hit's fields.
[[gnu::noinline]] Manifold circle_circle_near(const Circle& a, const Circle& b, float dx, float dy, float dist2, float r) {
    // The radii as valid(Circle) checks them (r >= 0 and r^2 finite, so r1 + r2 is finite and
    // so is the depth), in one test; an infinite dist2 (r^2 may overflow) is a miss too.
    if (!((a.radius >= 0.0f) & (a.radius * a.radius < INFINITY) & (b.radius >= 0.0f) & (b.radius * b.radius < INFINITY) &
          (dist2 != INFINITY)))
        return {};
    // 09-72: mtd = (c1 - c2)/|c1 - c2| (r1 + r2 - |c1 - c2|) = -depth * normal. Coincident
    // centres have no direction; {1, 0} is the defined one (as in Box2D). One square root for
    // the depth and the normal, in every lane (SQRTPS: each lane std::sqrt's value), so that
    // one DIVPS divides both components (each lane the scalar division's quotient).
    using detail::Float4;
    const Float4 len = detail::sqrt_nonneg(Float4{dist2, dist2, dist2, dist2});
    Float4 n = {1.0f, 0.0f, 1.0f, 0.0f};
    if (len[0] > 0.0f) n = detail::plain_zeros(Float4{dx, dy, dx, dy} / len);
    // hit_with without its finiteness test, which cannot fail here: r is finite (valid
    // radii), so are dist2 (tested), d (d.x^2 <= dist2) and len, and |d.x| / len is at most
    // about 1 (dist2 >= fl(d.x^2); a dist2 rounded to 0 takes the {1, 0} branch).
    const float depth = r - len[0];
    Manifold m;
    m.hit = true;
    m.depth = depth > 0.0f ? depth : 0.0f;
    std::memcpy(static_cast<void*>(&m.normal), &n, sizeof m.normal);  // lanes 0 and 1, kept in a register
    return m;
}
}  // namespace

Manifold collide(const Circle& a, const Circle& b) {
    // 09-71: compare squared distances, so no square root for a miss. The radii are checked
    // only for an answer that would be a hit (an invalid circle is a miss, and the arithmetic
    // on any input is defined): a NaN or infinite centre makes dist2 NaN or infinite, which
    // the comparison here or the test of dist2 there turns into a miss.
    const Vec2 d = b.center - a.center;
    const float dist2 = dot(d, d);
    const float r = a.radius + b.radius;
    if (!(dist2 <= r * r)) return {};
    return circle_circle_near(a, b, d.x, d.y, dist2, r);
}

namespace {
// dot(n_i, c - p_i) for faces 2k and 2k + 1 in lanes 0 and 2 (a Polygon stores its points and
// normals x, y, x, y, so lane 0 + lane 1 and lane 2 + lane 3 are the two faces' dot products,
// summed in the scalar order, x term + y term: each value is the scalar loop's bit for bit).
// An odd count's missing face (slot n, which every Polygon has) is -inf.
inline detail::Float4 face_pair_separation(const Polygon& poly, detail::Float4 cc, int k) {
    detail::Float4 p, u;
    std::memcpy(&p, poly.points().data() + 2 * k, sizeof p);
    std::memcpy(&u, poly.normals().data() + 2 * k, sizeof u);
    const detail::Float4 m = u * (cc - p);
    detail::Float4 s = m + __builtin_shufflevector(m, m, 1, 0, 3, 2);
    if (2 * k + 1 == poly.count()) s[2] = -INFINITY;
    return s;
}

// How far the point is outside the polygon's farthest face (09-90's first step): the max over
// the faces of dot(n_i, c - p_i), lane by lane (MAXPS: a NaN never wins, as in a loop's
// `s > max`); -inf when every face gives NaN (past the limits).
inline float max_face_separation(const Polygon& poly, detail::Float4 cc) {
    detail::Float4 top = {-INFINITY, -INFINITY, -INFINITY, -INFINITY};
    for (int k = 0; k < (poly.count() + 1) / 2; ++k) {
        const detail::Float4 s = face_pair_separation(poly, cc, k);
        top = s > top ? s : top;
    }
    return top[2] > top[0] ? top[2] : top[0];
}

// The first face whose separation is `most` (found from bit masks, with no branch on the
// data): the face a loop keeping the first strict maximum would name. Only the sign of a zero
// separation may differ from that loop's, which no use of it can tell.
inline int first_face_at(const Polygon& poly, detail::Float4 cc, float most) {
    unsigned faces = 0;
    for (int k = 0; k < (poly.count() + 1) / 2; ++k) {
        const unsigned bits = detail::lane_bits(face_pair_separation(poly, cc, k) == most);
        faces |= ((bits & 1u) | ((bits >> 1) & 2u)) << (2 * k);
    }
    return faces == 0 ? 0 : std::countr_zero(faces);  // none: every face NaN
}

// The vertex nearest the point and its squared distance: the first i of least dot(o, o),
// o = c - p_i (a loop keeping the first strict minimum), dist2 = +inf and vertex 0 when every
// distance overflows. Two vertices a step (the face_pair_separation layout: lanes 0 and 2
// are vertices 2k and 2k + 1, each the scalar o.x * o.x + o.y * o.y); each lane keeps its
// own first minimum, so neither a branch per vertex nor a second pass is needed.
struct NearestVertex {
    float dist2 = INFINITY;
    int vertex = 0;
};
inline NearestVertex nearest_vertex(const Polygon& poly, detail::Float4 cc) {
    using detail::Float4;
    using detail::Int4;
    Float4 best = {INFINITY, INFINITY, INFINITY, INFINITY};
    Int4 index = {0, 0, 0, 0};
    for (int k = 0; k < (poly.count() + 1) / 2; ++k) {
        Float4 p;
        std::memcpy(&p, poly.points().data() + 2 * k, sizeof p);
        const Float4 o = cc - p;
        const Float4 m = o * o;
        Float4 d2 = m + __builtin_shufflevector(m, m, 1, 0, 3, 2);
        if (2 * k + 1 == poly.count()) d2[2] = INFINITY;  // no vertex in slot n
        const Int4 closer = d2 < best;
        best = closer ? d2 : best;
        index = closer ? Int4{2 * k, 2 * k, 2 * k + 1, 2 * k + 1} : index;
    }
    // Even vertices in lane 0, odd ones in lane 2: the smaller distance, or on a tie the
    // smaller index.
    const bool odd = best[2] < best[0] || (best[2] == best[0] && index[2] < index[0]);
    return {odd ? best[2] : best[0], odd ? index[2] : index[0]};
}

// collide(Polygon, Circle) past its early out: the centre is within r of every face's line.
// Kept out of line so that the common early out is a short function with nothing to save.
[[gnu::noinline]] Manifold polygon_circle_near(const Polygon& a, const Circle& b, detail::Float4 cc, float max_sep) {
    const Vec2 c = b.center;
    const int max_edge = first_face_at(a, cc, max_sep);
    if (max_sep <= 0.0f) return hit_with(b.radius - max_sep, a.normals()[max_edge]);  // centre inside
    // Beside the edge of greatest separation (c projects inside it, tested from each end so
    // that a long edge rounds neither), that edge is the nearest feature: its own normal and
    // the separation are exact where normalising c - p would round.
    const Vec2 p0 = a.points()[max_edge];
    const Vec2 p1 = a.points()[detail::next_index(max_edge, a.count())];
    const Vec2 e = p1 - p0;
    if (dot(c - p0, e) > 0.0f && dot(c - p1, e) < 0.0f) return hit_with(b.radius - max_sep, a.normals()[max_edge]);
    // Otherwise the nearest feature is a vertex: the direction from it to the centre, as a
    // plain difference of points (exact for nearby floats).
    const NearestVertex nearest = nearest_vertex(a, cc);
    const float dist2 = nearest.dist2;
    if (!(dist2 <= b.radius * b.radius)) return {};
    const int vertex = nearest.vertex;
    const Vec2 d = c - a.points()[vertex];  // used only when dist2 is finite
    // A direction outside the vertex's cone of normals means the centre is on the vertex up
    // to rounding: the nearer of its two faces' normals. (normalize_or(d, ...) with the one
    // square root that the depth needs too.)
    const Vec2 n_prev = a.normals()[detail::prev_index(vertex, a.count())];
    const Vec2 n_next = a.normals()[vertex];
    const float len = detail::sqrt_nonneg(dist2);
    Vec2 n = len > 0.0f && len < INFINITY ? Vec2{d.x / len, d.y / len} : a.normals()[max_edge];
    if (cross(n_prev, n) < 0.0f || cross(n, n_next) < 0.0f) n = dot(n, n_prev) >= dot(n, n_next) ? n_prev : n_next;
    return hit_with(b.radius - len, n);
}
}  // namespace

Manifold collide(const Polygon& a, const Circle& b) {
    // 09-90: the closest point p of the polygon's boundary to the centre c; the MTD has
    // direction p - c and length r - |p - c|. The slide assumes c is outside; when it is
    // inside, the shortest way out is through the nearest edge, by r plus c's depth.
    // The circle is checked only for an answer that would be a hit (an invalid circle is a
    // miss, and the arithmetic on any input is defined); the empty polygon has no faces.
    if (!valid(a)) return {};
    const detail::Float4 cc = {b.center.x, b.center.y, b.center.x, b.center.y};
    const float max_sep = max_face_separation(a, cc);
    if (max_sep > b.radius || !valid(b)) return {};  // an edge normal separates: early out
    return polygon_circle_near(a, b, cc, max_sep);
}

Manifold collide_sat(const Polygon& a, const Circle& b) {
    // 09-91 to 09-96: SAT, where a circle projects to its centre's projection +- r, and the
    // edge normals alone are not enough. The slide adds the axis from the centre to the
    // closest point on the polygon; the nearest vertex gives the same answer (in a vertex's
    // region the closest point is that vertex, elsewhere an edge normal already wins) and
    // needs no closest-point search.
    if (!valid(a) || !valid(b)) return {};
    const Vec2 c = b.center;
    int nearest = 0;
    float nearest_d2 = INFINITY;
    for (int i = 0; i < a.count(); ++i) {
        const float d2 = length_squared(a.points()[i] - c);
        if (d2 < nearest_d2) { nearest_d2 = d2; nearest = i; }
    }
    float best = INFINITY;
    Vec2 best_normal{1.0f, 0.0f};
    auto test_axis = [&](Vec2 u) {
        // Relative to the centre, for precision far from the origin.
        float lo = dot(a.points()[0] - c, u), hi = lo;
        for (int i = 1; i < a.count(); ++i) {
            const float d = dot(a.points()[i] - c, u);
            lo = d < lo ? d : lo;
            hi = d > hi ? d : hi;
        }
        return detail::consider_axis(u, hi + b.radius, b.radius - lo, best, best_normal);
    };
    for (int i = 0; i < a.count(); ++i)
        if (!test_axis(a.normals()[i])) return {};
    const Vec2 to_vertex = a.points()[nearest] - c;
    if (to_vertex != Vec2{} && !test_axis(normalize_or(to_vertex, Vec2{1.0f, 0.0f}))) return {};
    return hit_with(best, best_normal);
}

namespace {
// The circle-vs-box test in the box's own frame, box [lo, hi] (09-102 "push in"). Here, not
// behind a call, so that the box and circle pairs compile into one function each.
inline Manifold box_circle(Vec2 lo, Vec2 hi, Vec2 c, float r) {
    // 09-102: "push in" the centre to find the closest point q of the box. A centre outside
    // leaves along c - q; a centre inside (or on the boundary, where c - q is zero or too
    // small to have a direction) is pushed out through the nearest face.
    // The clamp as a min then a max (MINSS/MAXSS, no branch on where the centre lies). With
    // lo <= hi it gives detail::clamp's value bit for bit, also for -0 and NaN.
    const auto clamp = [](float v, float l, float h) {
        const float t = h < v ? h : v;
        return l > t ? l : t;
    };
    const Vec2 q{clamp(c.x, lo.x, hi.x), clamp(c.y, lo.y, hi.y)};
    const Vec2 d = c - q;
    const float dist2 = dot(d, d);
    if (dist2 > 0.0f) {
        if (!(dist2 <= r * r)) return {};
        const float dist = detail::sqrt_nonneg(dist2);
        return hit_with(r - dist, Vec2{d.x / dist, d.y / dist});
    }
    float depth = c.x - lo.x;
    Vec2 normal{-1.0f, 0.0f};
    if (hi.x - c.x < depth) { depth = hi.x - c.x; normal = {1.0f, 0.0f}; }
    if (c.y - lo.y < depth) { depth = c.y - lo.y; normal = {0.0f, -1.0f}; }
    if (hi.y - c.y < depth) { depth = hi.y - c.y; normal = {0.0f, 1.0f}; }
    return hit_with(depth + r, normal);
}
}  // namespace

Manifold collide(const Aabb& a, const Circle& b) {
    if (!valid(a) || !valid(b)) return {};
    return box_circle(a.min, a.max, b.center, b.radius);
}

Manifold collide(const Obb& a, const Circle& b) {
    // The clamp in the box's own frame, then the normal turned back. The shapes are checked
    // only when the answer would be a hit: an invalid shape is a miss, so a miss needs no
    // check (the arithmetic on any input is defined, only the answer would be wrong).
    const Rot q = a.rotation();
    const Vec2 local = inv_rotate(q, b.center - a.center);
    Manifold m = box_circle(-a.half, a.half, local, b.radius);
    if (!m.hit) return m;
    if (!(valid(a) && valid(b))) return {};
    m.normal = detail::plain_zeros(rotate(q, m.normal));
    return m;
}

Manifold collide(const Segment& a, const Circle& b) {
    // 09-87/88: the closest point p on the segment to c; hit when |p - c| <= r; the MTD has
    // direction p - c and length r - |p - c|. A centre on the segment leaves by its normal.
    if (!valid(a) || !valid(b)) return {};
    const Vec2 d = detail::offset_from_segment(a.a, a.b, b.center);  // c - p
    const float dist2 = dot(d, d);
    if (!(dist2 <= b.radius * b.radius)) return {};
    const Vec2 e = a.b - a.a;
    const Vec2 side = a.a == a.b ? Vec2{1.0f, 0.0f} : normalize_or(Vec2{e.y, -e.x}, Vec2{1.0f, 0.0f});
    // Beside the segment (the closest point inside it), its normal on the centre's side and the
    // distance along it are exact where normalising c - p would round.
    if (dot(b.center - a.a, e) > 0.0f && dot(b.center - a.b, e) < 0.0f) {  // from each end, for precision
        const float along = dot(side, b.center - a.a);
        return hit_with(b.radius - std::fabs(along), along < 0.0f ? -side : side);
    }
    return hit_with(b.radius - std::sqrt(dist2), normalize_or(d, side));
}

}  // namespace jostle
