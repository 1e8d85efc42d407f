// Circles, slides 09-70 to 09-102: circle-circle by squared distances, polygon-circle by the
// closest point on the boundary and by SAT with the centre-to-vertex axis, box-circle by
// the "push in" clamp, segment-circle. The slides test "< r" (09-71, 09-87); here touching
// (== r) is a hit with depth 0, the convention for every pair.
#include <cfloat>
#include <cmath>

#include "internal.h"

namespace jostle {

using detail::hit_with;
using detail::valid;

Manifold collide(const Circle& a, const Circle& b) {
    // 09-71: compare squared distances, so no square root for a miss. Only the radii are
    // checked up front: a NaN or infinite centre makes dist2 NaN or infinite, which the
    // comparison below already turns into a miss.
    if (!(a.radius >= 0.0f && a.radius < INFINITY && b.radius >= 0.0f && b.radius < INFINITY)) return {};
    const Vec2 d = b.center - a.center;
    const float dist2 = dot(d, d);
    const float r = a.radius + b.radius;
    if (!(dist2 <= r * r)) return {};
    // 09-72: mtd = (c1 - c2)/|c1 - c2| (r1 + r2 - |c1 - c2|) = -depth * normal. Coincident
    // centres have no direction; {1, 0} is the defined one (as in Box2D).
    const float len = std::sqrt(dist2);  // one square root for the depth and the normal
    return hit_with(r - len, len > 0.0f ? Vec2{d.x / len, d.y / len} : Vec2{1.0f, 0.0f});
}

Manifold collide(const Polygon& a, const Circle& b) {
    // 09-90: the closest point p of the polygon's boundary to the centre c; the MTD has
    // direction p - c and length r - |p - c|. The slide assumes c is outside; when it is
    // inside, the shortest way out is through the nearest edge, by r plus c's depth.
    if (!valid(a) || !valid(b)) return {};
    const Vec2 c = b.center;
    float max_sep = -INFINITY;
    int max_edge = 0;
    for (int i = 0; i < a.count(); ++i) {
        const float s = dot(a.normals()[i], c - a.points()[i]);
        if (s > max_sep) { max_sep = s; max_edge = i; }
    }
    if (max_sep > b.radius) return {};  // an edge normal separates: early out
    if (max_sep <= 0.0f) return hit_with(b.radius - max_sep, a.normals()[max_edge]);  // centre inside
    // Beside the edge of greatest separation (c projects inside it, tested from each end so
    // that a long edge rounds neither), that edge is the nearest feature: its own normal and
    // the separation are exact where normalising c - p would round.
    const Vec2 p0 = a.points()[max_edge];
    const Vec2 p1 = a.points()[(max_edge + 1) % a.count()];
    const Vec2 e = p1 - p0;
    if (dot(c - p0, e) > 0.0f && dot(c - p1, e) < 0.0f) return hit_with(b.radius - max_sep, a.normals()[max_edge]);
    // Otherwise the nearest feature is a vertex: the direction from it to the centre, as a
    // plain difference of points (exact for nearby floats).
    Vec2 d{};
    float dist2 = INFINITY;
    int vertex = 0;
    for (int i = 0; i < a.count(); ++i) {
        const Vec2 o = c - a.points()[i];
        if (dot(o, o) < dist2) { dist2 = dot(o, o); d = o; vertex = i; }
    }
    if (!(dist2 <= b.radius * b.radius)) return {};
    // A direction outside the vertex's cone of normals means the centre is on the vertex up
    // to rounding: the nearer of its two faces' normals.
    const Vec2 n_prev = a.normals()[(vertex + a.count() - 1) % a.count()];
    const Vec2 n_next = a.normals()[vertex];
    Vec2 n = normalize_or(d, a.normals()[max_edge]);
    if (cross(n_prev, n) < 0.0f || cross(n, n_next) < 0.0f) n = dot(n, n_prev) >= dot(n, n_next) ? n_prev : n_next;
    return hit_with(b.radius - std::sqrt(dist2), n);
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
        const float dist = std::sqrt(dist2);
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
