// Oriented boxes and convex polygons by the separating axis theorem, slides 09-35 to 09-69:
// project both shapes on each candidate axis (the edge normals), stop at the first axis
// with a gap, otherwise push along the axis that needs the least push.
#include <cmath>

#include "internal.h"

namespace jostle {

using detail::valid;

namespace detail {

// Projection of a point set on an axis (09-51: project every point, keep min and max).
// Points are taken relative to `origin` (a vertex of one shape), so that shapes far from the
// world origin are projected with the precision of their size, not of their position.
static void project(const ConvexView& v, Vec2 axis, Vec2 origin, float& lo, float& hi) {
    // (p + offset) first: far from the origin it is the exact difference of nearby floats.
    lo = hi = dot((v.points[0] + v.offset) - origin, axis);
    for (int i = 1; i < v.count; ++i) {
        const float d = dot((v.points[i] + v.offset) - origin, axis);
        lo = d < lo ? d : lo;
        hi = d > hi ? d : hi;
    }
}

Manifold sat_collide(const ConvexView& a, const ConvexView& b) {
    float best = INFINITY;
    Vec2 best_normal{1.0f, 0.0f};
    const Vec2 origin = a.points[0] + a.offset;
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
        if (a.points[0] + a.offset == b.points[0] + b.offset) return hit_with(0.0f, {1.0f, 0.0f});
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
detail::ConvexView view_of(const Polygon& p, Vec2 offset = {}) {
    return {p.points().data(), p.count(), p.normals().data(), p.count(), offset};
}
detail::ConvexView view_of(const detail::SegmentAxes& s, Vec2 offset = {}) {
    return {s.points, 2, s.axes, s.axis_count, offset};
}

// 09-58 with the boxes' own axes: 2 + 2 candidate axes. A box's projection on an axis u is
// its centre's projection plus-minus the projected radius hx |ux.u| + hy |uy.u|, so no
// corner is projected one by one. d is B's centre minus A's centre.
Manifold box_box(Vec2 half_a, Rot qa, Vec2 half_b, Rot qb, Vec2 d) {
    const Vec2 axes[4] = {{qa.c, qa.s}, {-qa.s, qa.c}, {qb.c, qb.s}, {-qb.s, qb.c}};
    float best = INFINITY;
    Vec2 best_normal{1.0f, 0.0f};
    for (const Vec2 u : axes) {
        const float ra = half_a.x * std::fabs(dot(axes[0], u)) + half_a.y * std::fabs(dot(axes[1], u));
        const float rb = half_b.x * std::fabs(dot(axes[2], u)) + half_b.y * std::fabs(dot(axes[3], u));
        const float s = dot(d, u);
        if (!detail::consider_axis(u, ra + rb - s, ra + rb + s, best, best_normal)) return {};
    }
    return detail::hit_with(best, best_normal);
}
}  // namespace

Manifold collide(const Obb& a, const Obb& b) {
    if (!valid(a) || !valid(b)) return {};
    return box_box(a.half, a.rotation(), b.half, b.rotation(), b.center - a.center);
}

Manifold collide(const Aabb& a, const Obb& b) {
    // The AABB as a box at angle 0. Its centre (min + max) / 2 may not be a float far from
    // the origin, so the offset is formed from differences instead.
    if (!valid(a) || !valid(b)) return {};
    const Vec2 half = (a.max - a.min) * 0.5f;
    return box_box(half, Rot{}, b.half, b.rotation(), (b.center - a.min) - half);
}

Manifold collide(const Polygon& a, const Polygon& b) {
    // 09-62: any convex shape, every edge normal of both.
    if (!valid(a) || !valid(b)) return {};
    return detail::sat_collide(view_of(a), view_of(b));
}

Manifold collide(const Obb& a, const Polygon& b) {
    // Solved around the box's centre, where its corners are precise: the polygon is viewed
    // shifted by -centre instead of being copied.
    if (!valid(a) || !valid(b)) return {};
    const Polygon box = detail::centred_polygon(a);
    return detail::sat_collide(view_of(box), view_of(b, -a.center));
}

Manifold collide(const Aabb& a, const Polygon& b) {
    if (!valid(a) || !valid(b)) return {};
    return collide(to_polygon(a), b);
}

Manifold collide(const Aabb& a, const Segment& b) {
    if (!valid(a) || !valid(b)) return {};
    return collide(to_polygon(a), b);
}

Manifold collide(const Polygon& a, const Segment& b) {
    if (!valid(a) || !valid(b)) return {};
    const auto s = detail::segment_axes(b);
    return detail::sat_collide(view_of(a), view_of(s));
}

Manifold collide(const Obb& a, const Segment& b) {
    if (!valid(a) || !valid(b)) return {};
    const Polygon box = detail::centred_polygon(a);
    const auto s = detail::segment_axes(Segment{b.a - a.center, b.b - a.center});
    return detail::sat_collide(view_of(box), view_of(s));
}

Manifold collide(const Segment& a, const Segment& b) {
    if (!valid(a) || !valid(b)) return {};
    const auto sa = detail::segment_axes(a);
    const auto sb = detail::segment_axes(b);
    return detail::sat_collide(view_of(sa), view_of(sb));
}

}  // namespace jostle
