// tests/collision/oracle.h: an independent double-precision oracle for the collision module
// (vertices, SAT axes, point distance, signed penetration) that does not call the module's
// queries, shape translation written apart from the module, and describe() for messages. No
// GoogleTest here: the property tests (test_shapes.h) and the collision fuzz target
// (tests/fuzz/collision_fuzz.cpp) both check the module against it.
#pragma once

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <string>
#include <variant>
#include <vector>

#include "jostle/collision.h"

namespace jostle::test {

// Translations written here rather than taken from the module, so the tests stay independent.
inline Aabb moved(const Aabb& s, Vec2 d) { return {s.min + d, s.max + d}; }
inline Obb moved(const Obb& s, Vec2 d) { return {s.center + d, s.half, s.angle()}; }
inline Circle moved(const Circle& s, Vec2 d) { return {s.center + d, s.radius}; }
inline Segment moved(const Segment& s, Vec2 d) { return {s.a + d, s.b + d}; }
// Far from the origin the moved vertices round, so the edges turn slightly: the polygon is
// rebuilt so that its normals belong to the rounded edges (as the oracle sees them).
inline Polygon moved(const Polygon& s, Vec2 d) {
    const Polygon p = s.moved(d);
    if (auto rebuilt = make_polygon(p.points())) return *rebuilt;
    return p;
}
inline PlacedMask moved(const PlacedMask& s, Vec2 d) {
    return {s.mask, s.x + static_cast<int>(std::lround(d.x)), s.y + static_cast<int>(std::lround(d.y))};
}
inline Shape moved(const Shape& s, Vec2 d) {
    return std::visit([&](const auto& x) -> Shape { return moved(x, d); }, s);
}

// ---------------------------------------------------------------------------------------
// Independent double-precision oracle (non-mask shapes)
// ---------------------------------------------------------------------------------------

struct D2 {
    double x = 0.0;
    double y = 0.0;
};
inline D2 d2(Vec2 v) { return {v.x, v.y}; }
inline D2 operator+(D2 a, D2 b) { return {a.x + b.x, a.y + b.y}; }
inline D2 operator-(D2 a, D2 b) { return {a.x - b.x, a.y - b.y}; }
inline D2 operator-(D2 a) { return {-a.x, -a.y}; }
inline D2 operator*(double s, D2 a) { return {s * a.x, s * a.y}; }
inline double ddot(D2 a, D2 b) { return a.x * b.x + a.y * b.y; }
inline double dcross(D2 a, D2 b) { return a.x * b.y - a.y * b.x; }
inline double dlen(D2 a) { return std::sqrt(ddot(a, a)); }

// Vertices of a solid shape (Aabb, Obb, Polygon) in double; a Segment gives its 2 points.
inline std::vector<D2> vertices(const Aabb& s) {
    return {{s.min.x, s.min.y}, {s.max.x, s.min.y}, {s.max.x, s.max.y}, {s.min.x, s.max.y}};
}
inline std::vector<D2> vertices(const Obb& s) {
    const double c = std::cos(static_cast<double>(s.angle()));
    const double n = std::sin(static_cast<double>(s.angle()));
    std::vector<D2> out;
    const double sx[4] = {-1, 1, 1, -1};
    const double sy[4] = {-1, -1, 1, 1};
    for (int i = 0; i < 4; ++i) {
        const double lx = sx[i] * s.half.x;
        const double ly = sy[i] * s.half.y;
        out.push_back({s.center.x + c * lx - n * ly, s.center.y + n * lx + c * ly});
    }
    return out;
}
inline std::vector<D2> vertices(const Polygon& s) {
    std::vector<D2> out;
    for (int i = 0; i < s.count(); ++i) out.push_back(d2(s.points()[static_cast<std::size_t>(i)]));
    return out;
}
inline std::vector<D2> vertices(const Segment& s) { return {d2(s.a), d2(s.b)}; }

// Candidate separating axes (unit): perpendiculars of every edge, plus a segment's direction.
inline void add_axes(const std::vector<D2>& v, std::vector<D2>& axes) {
    const std::size_t n = v.size();
    const std::size_t edges = n == 2 ? 1 : n;
    for (std::size_t i = 0; i < edges; ++i) {
        const D2 e = v[(i + 1) % n] - v[i];
        const double len = dlen(e);
        if (len > 0) {
            axes.push_back({-e.y / len, e.x / len});
            if (n == 2) axes.push_back({e.x / len, e.y / len});
        }
    }
}

inline void project(const std::vector<D2>& v, D2 axis, double& lo, double& hi) {
    lo = hi = ddot(v[0], axis);
    for (const D2& p : v) {
        lo = std::min(lo, ddot(p, axis));
        hi = std::max(hi, ddot(p, axis));
    }
}

// The push along `axis` that separates a from b (negative when already separated on it).
inline double axis_push(const std::vector<D2>& a, const std::vector<D2>& b, D2 axis) {
    double alo = 0, ahi = 0, blo = 0, bhi = 0;
    project(a, axis, alo, ahi);
    project(b, axis, blo, bhi);
    return std::min(ahi - blo, bhi - alo);
}

// Signed SAT penetration of two convex vertex sets: > 0 overlap depth, < 0 separation.
inline double sat_penetration(const std::vector<D2>& a, const std::vector<D2>& b) {
    std::vector<D2> axes;
    add_axes(a, axes);
    add_axes(b, axes);
    double best = std::numeric_limits<double>::infinity();
    for (const D2& ax : axes) best = std::min(best, axis_push(a, b, ax));
    return best;
}

inline double dist_point_segment(D2 p, D2 a, D2 b) {
    const D2 ab = b - a;
    const double l2 = ddot(ab, ab);
    double t = l2 > 0 ? ddot(p - a, ab) / l2 : 0.0;
    t = std::clamp(t, 0.0, 1.0);
    return dlen(p - (a + t * ab));
}

// Signed distance from p to a convex polygon given in either winding (negative inside;
// repeated vertices and zero area, as in degenerate boxes, are allowed).
inline double signed_distance_convex(const std::vector<D2>& v, D2 p) {
    const std::size_t n = v.size();
    double area2 = 0;
    for (std::size_t i = 0; i < n; ++i) area2 += dcross(v[i], v[(i + 1) % n]);
    const double orient = area2 >= 0 ? 1.0 : -1.0;
    bool inside = true;
    double inner = std::numeric_limits<double>::infinity();
    double outer = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < n; ++i) {
        const D2 a = v[i];
        const D2 b = v[(i + 1) % n];
        const D2 e = b - a;
        const double len = dlen(e);
        outer = std::min(outer, dist_point_segment(p, a, b));
        if (len == 0) continue;  // a repeated vertex (a degenerate box): no edge line
        // Outward offset of p from the edge's line.
        const double off = -orient * dcross(e, p - a) / len;
        if (off > 0) inside = false;
        inner = std::min(inner, -off);
    }
    // A shape without area (a point or a segment as a box) has no inside; nor does a point
    // of its line beyond it, whose offsets from the edges are all 0 (the area may still come
    // out not quite 0 in double). On a real boundary both answers are 0.
    return inside && area2 != 0 && inner > 0 ? -inner : outer;
}

// Signed distance from p to any non-mask shape (segments and zero-area shapes: >= 0).
inline double signed_distance(const Shape& s, D2 p) {
    if (const auto* c = std::get_if<Circle>(&s)) return dlen(p - d2(c->center)) - c->radius;
    if (const auto* g = std::get_if<Segment>(&s)) return dist_point_segment(p, d2(g->a), d2(g->b));
    std::vector<D2> v;
    if (const auto* a = std::get_if<Aabb>(&s)) v = vertices(*a);
    if (const auto* o = std::get_if<Obb>(&s)) v = vertices(*o);
    if (const auto* q = std::get_if<Polygon>(&s)) v = vertices(*q);
    return signed_distance_convex(v, p);
}

inline std::vector<D2> vertices(const Shape& s) {
    if (const auto* a = std::get_if<Aabb>(&s)) return vertices(*a);
    if (const auto* o = std::get_if<Obb>(&s)) return vertices(*o);
    if (const auto* q = std::get_if<Polygon>(&s)) return vertices(*q);
    if (const auto* g = std::get_if<Segment>(&s)) return vertices(*g);
    return {};
}

// Signed penetration of two non-mask shapes: > 0 is the exact MTD length, < 0 a gap
// (exact for polygons; for a circle against anything the distance from the centre).
inline double penetration(const Shape& a, const Shape& b) {
    const auto* ca = std::get_if<Circle>(&a);
    const auto* cb = std::get_if<Circle>(&b);
    if (ca && cb) return ca->radius + cb->radius - dlen(d2(ca->center) - d2(cb->center));
    if (cb) return cb->radius - signed_distance(a, d2(cb->center));
    if (ca) return ca->radius - signed_distance(b, d2(ca->center));
    return sat_penetration(vertices(a), vertices(b));
}

inline float shape_size(const Shape& s) {
    const Aabb b = bounds(s);
    return std::max(b.max.x - b.min.x, b.max.y - b.min.y);
}

inline std::string describe(const Shape& s) {
    std::string out;
    // Shortest round-trip form, so a printed failure can be pasted back as the same floats.
    auto f = [](float v) {
        char buf[32];
        const auto r = std::to_chars(buf, buf + sizeof buf, v);
        return std::string(buf, r.ptr);
    };
    auto p = [&](Vec2 v) {
        std::string t = "(";  // appended piece by piece: GCC 12 warns (-Wrestrict) on "(" + string
        t += f(v.x);
        t += ", ";
        t += f(v.y);
        return t + ")";
    };
    if (const auto* a = std::get_if<Aabb>(&s)) out = "Aabb{" + p(a->min) + ", " + p(a->max) + "}";
    if (const auto* o = std::get_if<Obb>(&s)) out = "Obb{" + p(o->center) + ", " + p(o->half) + ", " + f(o->angle()) + "}";
    if (const auto* c = std::get_if<Circle>(&s)) out = "Circle{" + p(c->center) + ", " + f(c->radius) + "}";
    if (const auto* g = std::get_if<Segment>(&s)) out = "Segment{" + p(g->a) + ", " + p(g->b) + "}";
    if (const auto* q = std::get_if<Polygon>(&s)) {
        out = "Polygon{";
        for (int i = 0; i < q->count(); ++i) out += p(q->points()[static_cast<std::size_t>(i)]) + " ";
        out += "}";
    }
    if (const auto* m = std::get_if<PlacedMask>(&s)) out = "Mask at (" + std::to_string(m->x) + ", " + std::to_string(m->y) + ")";
    return out;
}

}  // namespace jostle::test
