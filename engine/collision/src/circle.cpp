// Circles, slides 09-70 to 09-102: circle-circle by squared distances, polygon-circle by the
// closest point on the boundary and by SAT with the centre-to-vertex axis, box-circle by
// the "push in" clamp, segment-circle.
#include <cmath>

#include "internal.h"

namespace jostle {

using detail::finite;
using detail::hit_with;

Manifold collide(const Circle& a, const Circle& b) {
    // 09-71: compare squared distances, so no square root for a miss.
    if (!finite(a) || !finite(b)) return {};
    const Vec2 d = b.center - a.center;
    const float dist2 = dot(d, d);
    const float r = a.radius + b.radius;
    if (!(dist2 <= r * r)) return {};
    // 09-72: mtd = (c1 - c2)/|c1 - c2| (r1 + r2 - |c1 - c2|) = -depth * normal. Coincident
    // centres have no direction; {1, 0} is the defined one (as in Box2D).
    const float dist = std::sqrt(dist2);
    const Vec2 normal = dist > 0.0f ? Vec2{d.x / dist, d.y / dist} : Vec2{1.0f, 0.0f};
    return hit_with(r - dist, normal);
}

Manifold collide(const Polygon& a, const Circle& b) {
    // 09-90: the closest point p of the polygon's boundary to the centre c; the MTD has
    // direction p - c and length r - |p - c|. The slide assumes c is outside; when it is
    // inside, the shortest way out is through the nearest edge, by r plus c's depth.
    if (!finite(a) || !finite(b)) return {};
    const Vec2 c = b.center;
    float max_sep = -INFINITY;
    int max_edge = 0;
    for (int i = 0; i < a.count; ++i) {
        const float s = dot(a.normals[i], c - a.points[i]);
        if (s > max_sep) { max_sep = s; max_edge = i; }
    }
    if (max_sep > b.radius) return {};  // an edge normal separates: early out
    if (max_sep <= 0.0f) return hit_with(b.radius - max_sep, a.normals[max_edge]);  // centre inside
    // The nearest of the closest points on every edge, kept relative to c (d = c - p) so
    // that shapes far from the origin keep the precision of their size.
    Vec2 d{};
    float dist2 = INFINITY;
    for (int i = 0; i < a.count; ++i) {
        const Vec2 rel = detail::offset_from_segment(a.points[i], a.points[(i + 1) % a.count], c);
        const float d2 = dot(rel, rel);
        if (d2 < dist2) { dist2 = d2; d = rel; }
    }
    if (!(dist2 <= b.radius * b.radius)) return {};
    const float dist = std::sqrt(dist2);
    return hit_with(b.radius - dist, Vec2{d.x / dist, d.y / dist});  // dist >= max_sep > 0
}

Manifold collide_sat(const Polygon& a, const Circle& b) {
    // 09-91 to 09-96: SAT, where a circle projects to its centre's projection +- r, and the
    // edge normals alone are not enough: add the axis from the centre to the nearest vertex.
    if (!finite(a) || !finite(b)) return {};
    const Vec2 c = b.center;
    int nearest = 0;
    float nearest_d2 = INFINITY;
    for (int i = 0; i < a.count; ++i) {
        const float d2 = length_squared(a.points[i] - c);
        if (d2 < nearest_d2) { nearest_d2 = d2; nearest = i; }
    }
    float best = INFINITY;
    Vec2 best_normal{1.0f, 0.0f};
    auto test_axis = [&](Vec2 u) {
        float lo = dot(a.points[0], u), hi = lo;
        for (int i = 1; i < a.count; ++i) {
            const float d = dot(a.points[i], u);
            lo = d < lo ? d : lo;
            hi = d > hi ? d : hi;
        }
        const float cu = dot(c, u);
        const float push_pos = hi - (cu - b.radius);  // normal u
        const float push_neg = (cu + b.radius) - lo;  // normal -u
        if (!(push_pos >= 0.0f && push_neg >= 0.0f)) return false;
        if (push_pos <= push_neg) {
            if (push_pos < best) { best = push_pos; best_normal = u; }
        } else if (push_neg < best) {
            best = push_neg;
            best_normal = -u;
        }
        return true;
    };
    for (int i = 0; i < a.count; ++i)
        if (!test_axis(a.normals[i])) return {};
    const Vec2 to_vertex = a.points[nearest] - c;
    if (to_vertex != Vec2{} && !test_axis(normalize_or(to_vertex, Vec2{1.0f, 0.0f}))) return {};
    return hit_with(best, best_normal);
}

namespace {
// Box [lo, hi] (in its own frame) against a circle centred at c: 09-102 "push in" to find
// the closest point; a centre inside is pushed out through the nearest face.
Manifold box_circle(Vec2 lo, Vec2 hi, Vec2 c, float r) {
    const Vec2 q{detail::clamp(c.x, lo.x, hi.x), detail::clamp(c.y, lo.y, hi.y)};
    if (q != c) {
        const Vec2 d = c - q;
        const float dist2 = dot(d, d);
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
    if (!finite(a) || !finite(b)) return {};
    return box_circle(a.min, a.max, b.center, b.radius);
}

Manifold collide(const Obb& a, const Circle& b) {
    // The clamp in the box's own frame, then the normal turned back.
    if (!finite(a) || !finite(b)) return {};
    const Rot q = Rot::from_angle(a.angle);
    const Vec2 local = inv_rotate(q, b.center - a.center);
    Manifold m = box_circle(-a.half, a.half, local, b.radius);
    if (m.hit) m.normal = rotate(q, m.normal);
    return m;
}

Manifold collide(const Segment& a, const Circle& b) {
    // 09-87/88: the closest point p on the segment to c; hit when |p - c| <= r; the MTD has
    // direction p - c and length r - |p - c|. A centre on the segment leaves by its normal.
    if (!finite(a) || !finite(b)) return {};
    const Vec2 d = detail::offset_from_segment(a.a, a.b, b.center);
    const float dist2 = dot(d, d);
    if (!(dist2 <= b.radius * b.radius)) return {};
    const float dist = std::sqrt(dist2);
    if (dist > 0.0f) return hit_with(b.radius - dist, Vec2{d.x / dist, d.y / dist});
    if (a.a == a.b) return hit_with(b.radius, Vec2{1.0f, 0.0f});  // a point on a point
    const Vec2 dir = normalize_or(a.b - a.a, Vec2{1.0f, 0.0f});
    return hit_with(b.radius, Vec2{dir.y, -dir.x});
}

}  // namespace jostle
