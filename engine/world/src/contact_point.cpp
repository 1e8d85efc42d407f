// Where two overlapping (or touching) shapes meet, for events and the debug overlay: the
// middle of the overlap along the manifold's normal, found from each shape's extreme
// feature (a vertex, an edge, or a circle's deepest point) the way clipping would.
#include <algorithm>
#include <cmath>

#include "internal.h"

namespace jostle::detail {

namespace {

// The part of a shape furthest along a direction: one point (a vertex, a circle's extreme
// point) or two (an edge facing that way). count 0: no such feature (a mask).
struct Feature {
    int count = 0;
    Vec2 p[2];
};

Feature extreme(std::span<const Vec2> points, Vec2 d) {
    float along[kMaxPolygonVertices];  // dot(p, d), each taken once
    float best = -INFINITY;
    float scale = 1.0f;
    for (std::size_t i = 0; i < points.size(); ++i) {
        const Vec2 p = points[i];
        along[i] = dot(p, d);
        best = fmax_inline(best, along[i]);
        scale = fmax_inline(scale, fmax_inline(std::fabs(p.x), std::fabs(p.y)));
    }
    // Vertices within rounding of the extreme form an edge facing d.
    const float tol = 1e-5f * scale;
    Feature f;
    const Vec2 t = perp(d);
    for (std::size_t i = 0; i < points.size(); ++i) {
        const Vec2 p = points[i];
        if (along[i] < best - tol) continue;
        if (f.count < 2) {
            f.p[f.count++] = p;
        } else {  // keep the two furthest apart along the edge
            if (dot(p, t) < dot(f.p[0], t)) f.p[0] = p;
            if (dot(p, t) > dot(f.p[1], t)) f.p[1] = p;
        }
    }
    return f;
}

Feature extreme(const Shape& s, Vec2 d) {
    struct Visit {
        Vec2 d;
        Feature operator()(const Aabb& b) const { const auto c = corners(b); return extreme(c, d); }
        Feature operator()(const Obb& b) const { const auto c = corners(b); return extreme(c, d); }
        Feature operator()(const Polygon& p) const { return extreme(p.points(), d); }
        Feature operator()(const Segment& g) const { const Vec2 c[2] = {g.a, g.b}; return extreme(c, d); }
        Feature operator()(const Circle& c) const { return {1, {c.center + c.radius * d, {}}}; }
        Feature operator()(const PlacedMask&) const { return {}; }
    };
    return std::visit(Visit{d}, s);
}

Vec2 bounds_middle(const Shape& a, const Shape& b) {
    const Aabb ba = bounds(a);
    const Aabb bb = bounds(b);
    const Vec2 lo = max(ba.min, bb.min);
    const Vec2 hi = min(ba.max, bb.max);
    return 0.5f * (lo + hi);
}

}  // namespace

Vec2 contact_point(const Shape& a, const Shape& b, const Manifold& m) {
    const Vec2 n = m.normal;
    if (!m.hit || (n.x == 0.0f && n.y == 0.0f)) return bounds_middle(a, b);
    const Feature fa = extreme(a, n);   // A's part deepest into B
    const Feature fb = extreme(b, -n);  // B's part deepest into A
    if (fa.count == 0 || fb.count == 0) return bounds_middle(a, b);
    const float half = 0.5f * m.depth;
    if (fa.count == 1 && fb.count == 1) return 0.5f * (fa.p[0] + fb.p[0]);
    if (fa.count == 1) return fa.p[0] - half * n;
    if (fb.count == 1) return fb.p[0] + half * n;
    // Edge against edge: the middle of their overlap along the tangent, halfway between them.
    const Vec2 t = perp(n);
    const float a0 = dot(fa.p[0], t), a1 = dot(fa.p[1], t);
    const float b0 = dot(fb.p[0], t), b1 = dot(fb.p[1], t);
    const float lo = fmax_inline(fmin_inline(a0, a1), fmin_inline(b0, b1));
    const float hi = fmin_inline(fmax_inline(a0, a1), fmax_inline(b0, b1));
    const float along = 0.5f * (lo + hi);
    const float across = 0.5f * (dot(fa.p[0], n) + dot(fb.p[0], n));
    return along * t + across * n;
}

bool corner_touch(const Shape& a, const Shape& b, const Manifold& m) {
    if (!m.hit || m.depth != 0.0f) return false;
    const Vec2 n = m.normal;
    const Feature fa = extreme(a, n);
    const Feature fb = extreme(b, -n);
    if (fa.count == 0 || fb.count == 0) return false;  // masks: no touching contacts
    if (std::holds_alternative<Circle>(a) || std::holds_alternative<Circle>(b)) return false;  // unique normal
    // The touching features' extents along the surface: overlapping in a point only means
    // the shapes meet corner to corner.
    const Vec2 t = perp(n);
    const auto range = [&](const Feature& f) {
        const float u = dot(f.p[0], t);
        const float v = dot(f.p[f.count - 1], t);
        return std::pair{fmin_inline(u, v), fmax_inline(u, v)};
    };
    const auto [alo, ahi] = range(fa);
    const auto [blo, bhi] = range(fb);
    const float scale = 1.0f + fmax_inline(fmax_inline(std::fabs(alo), std::fabs(ahi)), fmax_inline(std::fabs(blo), std::fabs(bhi)));
    return fmin_inline(ahi, bhi) - fmax_inline(alo, blo) <= 1e-6f * scale;
}

}  // namespace jostle::detail
