// Helpers shared by the collision module's implementation files (not part of the API):
// finiteness checks, result builders, and the convex "point set + axes" view used by SAT.
#pragma once

#include <cmath>

#include "jostle/collision.h"

namespace jostle::detail {

inline bool finite(float v) { return std::isfinite(v); }
inline bool finite(Vec2 v) { return std::isfinite(v.x) && std::isfinite(v.y); }
inline bool finite(const Aabb& b) { return finite(b.min) && finite(b.max); }
inline bool finite(const Obb& b) { return finite(b.center) && finite(b.half) && finite(b.angle); }
inline bool finite(const Circle& c) { return finite(c.center) && finite(c.radius); }
inline bool finite(const Segment& s) { return finite(s.a) && finite(s.b); }
inline bool finite(const Polygon& p) {
    for (int i = 0; i < p.count; ++i)
        if (!finite(p.points[i])) return false;
    return p.count >= 3;
}

// A hit with the given depth and A->B normal; depth is clamped at 0 against rounding.
inline Manifold hit_with(float depth, Vec2 normal) {
    return Manifold{true, depth > 0.0f ? depth : 0.0f, normal};
}

// The same contact seen from B: the normal flips, the depth stays.
inline Manifold flipped(Manifold m) {
    if (m.hit) m.normal = -m.normal;
    return m;
}

inline float clamp(float v, float lo, float hi) { return v < lo ? lo : (v > hi ? hi : v); }

// p minus the closest point of segment a-b to p (09-85), formed from differences so that it
// keeps the precision of the distance even far from the origin.
inline Vec2 offset_from_segment(Vec2 a, Vec2 b, Vec2 p) {
    const Vec2 d = b - a;
    const Vec2 f = p - a;
    const float dd = dot(d, d);
    if (!(dd > 0.0f)) return f;
    const float t = clamp(dot(f, d) / dd, 0.0f, 1.0f);
    return f - t * d;
}

// The polygon moved by `offset` (normals unchanged). Used to work near the origin: an OBB's
// corners far from the origin are not floats, but relative to its centre they are precise.
inline Polygon translated(const Polygon& p, Vec2 offset) {
    Polygon out = p;
    for (int i = 0; i < p.count; ++i) out.points[i] = p.points[i] + offset;
    return out;
}

// The OBB's polygon with its centre at the origin.
inline Polygon centred_polygon(const Obb& box) { return to_polygon(Obb{{}, box.half, box.angle}); }

// A convex point set for SAT: its vertices and the candidate separating axes it brings
// (unit edge normals; a segment also brings its direction, since it has no area).
struct ConvexView {
    const Vec2* points = nullptr;
    int count = 0;
    const Vec2* axes = nullptr;
    int axis_count = 0;
};

// SAT over the axes of both views (09-62): early exit on a separating axis, MTD along the
// axis of least push. Axes need not be unique or oriented.
Manifold sat_collide(const ConvexView& a, const ConvexView& b);

// Segment as a ConvexView: storage for its axes lives in the caller's SegmentAxes.
struct SegmentAxes {
    Vec2 points[2];
    Vec2 axes[2];
    int axis_count = 0;
};
SegmentAxes segment_axes(const Segment& s);

// Cast of a point moving from -> to against a circle (the quadratic); used by sweeps too.
CastHit cast_circle(Vec2 from, Vec2 to, Vec2 center, float radius);
// Cast against a segment as a zero-thickness wall: t, point, and the normal facing `from`.
CastHit cast_segment(Vec2 from, Vec2 to, Vec2 a, Vec2 b);

}  // namespace jostle::detail
