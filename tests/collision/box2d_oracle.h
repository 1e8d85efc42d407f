// box2d_oracle.h: Box2D 2.4.1 as an oracle for the collision module, plus an exact
// (double-precision) geometry of the same float shapes, used to classify random pairs
// (separated / touching band / overlapping) and to adjudicate disagreements.
//
// Used by box2d_diff_test.cpp only. Box2D is called with identity transforms on shapes whose
// vertices are already in world space, with m_radius = 0 on polygons, so both libraries see
// the same float numbers. Box2D's polygon convention (counter-clockwise in y-up axes,
// normal = cross(edge, 1)) is the same arithmetic as jostle's (cross(e[i], e[i+1]) > 0,
// outward normals); no coordinate flip is needed.
#pragma once

#include <box2d/b2_circle_shape.h>
#include <box2d/b2_collision.h>
#include <box2d/b2_distance.h>
#include <box2d/b2_polygon_shape.h>
#include <box2d/b2_time_of_impact.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <span>

#include "jostle/collision.h"
#include "oracle.h"

namespace jostle::oracle {

// ---------------------------------------------------------------------------------------
// Box2D side
// ---------------------------------------------------------------------------------------

inline b2Vec2 to_b2(Vec2 v) { return {v.x, v.y}; }
inline Vec2 from_b2(b2Vec2 v) { return {v.x, v.y}; }

inline b2Transform identity() {
    b2Transform xf;
    xf.SetIdentity();
    return xf;
}

// b2PolygonShape::Set (welds points closer than 0.5 * b2_linearSlop and builds a hull; it
// falls back to a 1x1 box on degenerate input), then m_radius = 0. Returns false when Box2D
// did not keep exactly these vertices (the caller then draws another polygon).
inline bool make_b2_polygon(std::span<const Vec2> pts, b2PolygonShape* out) {
    if (pts.size() < 3 || pts.size() > b2_maxPolygonVertices) return false;
    // Set asserts (this libbox2d keeps asserts) when welding leaves fewer than 3 points.
    for (std::size_t i = 0; i < pts.size(); ++i)
        for (std::size_t j = i + 1; j < pts.size(); ++j) {
            const float dx = pts[i].x - pts[j].x, dy = pts[i].y - pts[j].y;
            if (dx * dx + dy * dy < b2_linearSlop * b2_linearSlop) return false;
        }
    std::array<b2Vec2, b2_maxPolygonVertices> v{};
    for (std::size_t i = 0; i < pts.size(); ++i) v[i] = to_b2(pts[i]);
    out->Set(v.data(), static_cast<int32>(pts.size()));
    out->m_radius = 0.0f;
    return out->m_count == static_cast<int32>(pts.size());
}

inline b2PolygonShape make_b2_box(const Obb& box) {
    b2PolygonShape s;
    s.SetAsBox(box.half.x, box.half.y, to_b2(box.center), box.angle());
    s.m_radius = 0.0f;
    return s;
}

inline b2CircleShape make_b2_circle(const Circle& c) {
    b2CircleShape s;
    s.m_p = to_b2(c.center);
    s.m_radius = c.radius;
    return s;
}

// What Box2D says about an overlapping pair, read from b2WorldManifold:
// hit = pointCount > 0, normal = world normal (from A toward B), depth = max over the
// manifold points of -separation (the deepest clipped point along the reference normal).
struct Contact {
    bool hit = false;
    int points = 0;
    bool face_b = false;  // polygons: the reference face was B's (b2Manifold::e_faceB)
    float depth = 0.0f;
    Vec2 normal;
};

inline Contact read_manifold(const b2Manifold& m, float radius_a, float radius_b) {
    Contact c;
    c.points = m.pointCount;
    c.hit = m.pointCount > 0;
    if (!c.hit) return c;
    c.face_b = m.type == b2Manifold::e_faceB;
    b2WorldManifold wm;
    wm.Initialize(&m, identity(), radius_a, identity(), radius_b);
    c.normal = from_b2(wm.normal);
    float deepest = -std::numeric_limits<float>::infinity();
    for (int i = 0; i < m.pointCount; ++i) deepest = std::max(deepest, -wm.separations[i]);
    c.depth = deepest;
    return c;
}

inline Contact collide_polygons(const b2PolygonShape& a, const b2PolygonShape& b) {
    b2Manifold m{};  // Box2D leaves fields unset on a miss
    b2CollidePolygons(&m, &a, identity(), &b, identity());
    return read_manifold(m, a.m_radius, b.m_radius);
}

inline Contact collide_polygon_circle(const b2PolygonShape& a, const b2CircleShape& b) {
    b2Manifold m{};  // Box2D leaves fields unset on a miss
    b2CollidePolygonAndCircle(&m, &a, identity(), &b, identity());
    return read_manifold(m, a.m_radius, b.m_radius);
}

inline Contact collide_circles(const b2CircleShape& a, const b2CircleShape& b) {
    b2Manifold m{};  // Box2D leaves fields unset on a miss
    b2CollideCircles(&m, &a, identity(), &b, identity());
    return read_manifold(m, a.m_radius, b.m_radius);
}

struct Ray {
    bool hit = false;
    float t = 0.0f;
    Vec2 normal;
};

// b2Shape::RayCast with maxFraction 1. Box2D reports no hit for a ray that starts inside
// (or on the boundary going in).
inline Ray ray_cast(const b2Shape& shape, Vec2 from, Vec2 to) {
    b2RayCastInput in;
    in.p1 = to_b2(from);
    in.p2 = to_b2(to);
    in.maxFraction = 1.0f;
    b2RayCastOutput out;
    Ray r;
    if (shape.RayCast(&out, in, identity(), 0)) {
        r.hit = true;
        r.t = out.fraction;
        r.normal = from_b2(out.normal);
    }
    return r;
}

// b2TimeOfImpact for linear motion over [0, 1]: proxy A is the moving circle (one vertex,
// radius a.radius), proxy B is a vertex cloud (a polygon with radius 0, or one centre with a
// circle's radius). Both proxies hold world-space vertices and translate by 0 -> v.
struct Toi {
    b2TOIOutput::State state = b2TOIOutput::e_unknown;
    float t = 0.0f;
};

inline Toi time_of_impact(const Circle& a, Vec2 va, std::span<const Vec2> b_vertices, float b_radius, Vec2 vb) {
    std::array<b2Vec2, b2_maxPolygonVertices> vb2{};
    for (std::size_t i = 0; i < b_vertices.size(); ++i) vb2[i] = to_b2(b_vertices[i]);
    const b2Vec2 ca = to_b2(a.center);
    b2TOIInput in;
    in.proxyA.Set(&ca, 1, a.radius);
    in.proxyB.Set(vb2.data(), static_cast<int32>(b_vertices.size()), b_radius);
    auto linear = [](Vec2 v) {
        b2Sweep s;
        s.localCenter.SetZero();
        s.c0.SetZero();
        s.c = to_b2(v);
        s.a0 = 0.0f;
        s.a = 0.0f;
        s.alpha0 = 0.0f;
        return s;
    };
    in.sweepA = linear(va);
    in.sweepB = linear(vb);
    in.tMax = 1.0f;
    b2TOIOutput out;
    b2TimeOfImpact(&out, &in);
    return {out.state, out.t};
}

// ---------------------------------------------------------------------------------------
// Exact side: the same float shapes, evaluated in double
// ---------------------------------------------------------------------------------------
namespace exact {

// The double-precision vector of the independent oracle (oracle.h), under this file's names.
using test::D2;
using test::d2;
using test::operator+;
using test::operator-;
using test::operator*;
inline double dot(D2 a, D2 b) { return test::ddot(a, b); }
inline double cross(D2 a, D2 b) { return test::dcross(a, b); }
inline double len(D2 v) { return test::dlen(v); }
inline D2 unit(D2 v) {
    const double l = len(v);
    return l > 0.0 ? D2{v.x / l, v.y / l} : D2{0.0, 0.0};
}
inline double dist(D2 a, D2 b) { return len(a - b); }

// A convex polygon with cross(e[i], e[i+1]) > 0, outward unit normals n[i] of edge
// v[i] -> v[i+1] (n = (e.y, -e.x) / |e|, as in Box2D) and offsets off[i] = n[i] . v[i].
struct Poly {
    int n = 0;
    std::array<D2, kMaxPolygonVertices> v{};
    std::array<D2, kMaxPolygonVertices> nrm{};
    std::array<double, kMaxPolygonVertices> off{};
};

inline Poly make_poly(std::span<const D2> pts) {
    Poly p;
    p.n = static_cast<int>(pts.size());
    for (int i = 0; i < p.n; ++i) p.v[static_cast<std::size_t>(i)] = pts[static_cast<std::size_t>(i)];
    for (int i = 0; i < p.n; ++i) {
        const auto a = static_cast<std::size_t>(i);
        const auto b = static_cast<std::size_t>((i + 1) % p.n);
        const D2 e = p.v[b] - p.v[a];
        p.nrm[a] = unit(D2{e.y, -e.x});
        p.off[a] = dot(p.nrm[a], p.v[a]);
    }
    return p;
}

inline Poly make_poly(std::span<const Vec2> pts) {
    std::array<D2, kMaxPolygonVertices> d{};
    for (std::size_t i = 0; i < pts.size(); ++i) d[i] = d2(pts[i]);
    return make_poly(std::span<const D2>(d.data(), pts.size()));
}

// The exact box described by the float parameters (corners in double from the float
// angle), in the same order as SetAsBox: (-hx,-hy), (hx,-hy), (hx,hy), (-hx,hy).
inline Poly make_poly(const Obb& box) {
    const double c = std::cos(static_cast<double>(box.angle()));
    const double s = std::sin(static_cast<double>(box.angle()));
    const double hx = box.half.x, hy = box.half.y;
    const std::array<D2, 4> local{D2{-hx, -hy}, D2{hx, -hy}, D2{hx, hy}, D2{-hx, hy}};
    std::array<D2, 4> w{};
    for (std::size_t i = 0; i < 4; ++i)
        w[i] = D2{box.center.x + c * local[i].x - s * local[i].y, box.center.y + s * local[i].x + c * local[i].y};
    return make_poly(std::span<const D2>(w));
}

inline double max_dot(const Poly& p, D2 n) {
    double m = -std::numeric_limits<double>::infinity();
    for (int i = 0; i < p.n; ++i) m = std::max(m, dot(n, p.v[static_cast<std::size_t>(i)]));
    return m;
}
inline double min_dot(const Poly& p, D2 n) {
    double m = std::numeric_limits<double>::infinity();
    for (int i = 0; i < p.n; ++i) m = std::min(m, dot(n, p.v[static_cast<std::size_t>(i)]));
    return m;
}

// Overlap of A and B along the unit direction n (from A toward B): how far A must move by
// -n to separate; negative when n separates them. pen(n) >= the true penetration depth for
// every n, with equality on the minimum-translation axis.
inline double pen_along(const Poly& a, const Poly& b, D2 n) { return max_dot(a, n) - min_dot(b, n); }
inline double pen_along(const Poly& a, D2 center, double radius, D2 n) {
    return max_dot(a, n) - (dot(n, center) - radius);
}

// SAT over the face normals of both polygons: the largest separation (negative: the
// penetration depth, exactly, since for convex polygons the minimum translation is along a
// face normal) and its axis, from A toward B.
struct Sat {
    double sep = -std::numeric_limits<double>::infinity();
    D2 axis;
};
inline Sat sat(const Poly& a, const Poly& b) {
    Sat r;
    for (int i = 0; i < a.n; ++i) {
        const auto k = static_cast<std::size_t>(i);
        const double s = min_dot(b, a.nrm[k]) - a.off[k];
        if (s > r.sep) r = {s, a.nrm[k]};
    }
    for (int i = 0; i < b.n; ++i) {
        const auto k = static_cast<std::size_t>(i);
        const double s = min_dot(a, b.nrm[k]) - b.off[k];
        if (s > r.sep) r = {s, -b.nrm[k]};
    }
    return r;
}

inline D2 closest_on_segment(D2 a, D2 b, D2 p, double* param = nullptr) {
    const D2 e = b - a;
    const double ee = dot(e, e);
    double t = ee > 0.0 ? dot(p - a, e) / ee : 0.0;
    t = std::clamp(t, 0.0, 1.0);
    if (param) *param = t;
    return a + t * e;
}

// Signed distance from p to the polygon's boundary (negative inside), the closest boundary
// point and the gradient of the signed distance (outward unit vector).
struct Sd {
    double d = 0.0;
    D2 closest;
    D2 grad;
    int face = -1;  // inside: the nearest face
};
inline Sd signed_distance(const Poly& p, D2 q) {
    double smax = -std::numeric_limits<double>::infinity();
    int fmax = 0;
    for (int i = 0; i < p.n; ++i) {
        const auto k = static_cast<std::size_t>(i);
        const double s = dot(p.nrm[k], q) - p.off[k];
        if (s > smax) {
            smax = s;
            fmax = i;
        }
    }
    Sd r;
    if (smax <= 0.0) {
        const auto k = static_cast<std::size_t>(fmax);
        r.d = smax;
        r.grad = p.nrm[k];
        r.closest = q - smax * p.nrm[k];
        r.face = fmax;
        return r;
    }
    double best = std::numeric_limits<double>::infinity();
    for (int i = 0; i < p.n; ++i) {
        const D2 c = closest_on_segment(p.v[static_cast<std::size_t>(i)], p.v[static_cast<std::size_t>((i + 1) % p.n)], q);
        const double d = dist(c, q);
        if (d < best) {
            best = d;
            r.closest = c;
        }
    }
    r.d = best;
    r.grad = unit(q - r.closest);
    return r;
}

// Is q on the polygon's face i, within tol (on its line and within its extent)?
inline bool on_face(const Poly& p, int i, D2 q, double tol) {
    const auto k = static_cast<std::size_t>(i);
    const D2 a = p.v[k], b = p.v[static_cast<std::size_t>((i + 1) % p.n)];
    return dist(closest_on_segment(a, b, q), q) <= tol;
}

// The minimum over t in [0, 1] of the signed distance of p0 + t (p1 - p0), and where.
// The signed distance to a convex set is convex along a line.
struct SegMin {
    double d = 0.0;
    double t = 0.0;
};
inline SegMin segment_min_sd(const Poly& p, D2 p0, D2 p1) {
    const D2 dir = p1 - p0;
    // Inside part: max_i (n_i . p(t) - off_i) is convex piecewise linear; its minimum is at
    // an end or where two of the lines cross.
    auto face_max = [&](double t) {
        const D2 q = p0 + t * dir;
        double m = -std::numeric_limits<double>::infinity();
        for (int i = 0; i < p.n; ++i) {
            const auto k = static_cast<std::size_t>(i);
            m = std::max(m, dot(p.nrm[k], q) - p.off[k]);
        }
        return m;
    };
    SegMin best{face_max(0.0), 0.0};
    auto consider = [&](double t) {
        if (!(t >= 0.0 && t <= 1.0)) return;
        const double m = face_max(t);
        if (m < best.d) best = {m, t};
    };
    consider(1.0);
    for (int i = 0; i < p.n; ++i) {
        for (int j = i + 1; j < p.n; ++j) {
            const auto a = static_cast<std::size_t>(i), b = static_cast<std::size_t>(j);
            // n_i.(p0 + t dir) - off_i = n_j.(p0 + t dir) - off_j
            const double den = dot(p.nrm[a] - p.nrm[b], dir);
            if (den == 0.0) continue;
            consider((p.off[a] - p.off[b] - dot(p.nrm[a] - p.nrm[b], p0)) / den);
        }
    }
    if (best.d <= 0.0) return best;  // the segment reaches the polygon: the face function is the sd
    // Outside all the way: the distance between the segment and the boundary, attained at an
    // end of the segment or at a polygon vertex.
    SegMin out{std::numeric_limits<double>::infinity(), 0.0};
    for (double t : {0.0, 1.0}) {
        const double d = signed_distance(p, p0 + t * dir).d;
        if (d < out.d) out = {d, t};
    }
    for (int i = 0; i < p.n; ++i) {
        double t = 0.0;
        const D2 c = closest_on_segment(p0, p1, p.v[static_cast<std::size_t>(i)], &t);
        const double d = dist(c, p.v[static_cast<std::size_t>(i)]);
        if (d < out.d) out = {d, t};
    }
    return out;
}

// First entry of the segment p0 -> p1 into the closed polygon (Cyrus-Beck in double).
struct SegHit {
    bool hit = false;
    double t = 0.0;
};
inline SegHit segment_first_hit(const Poly& p, D2 p0, D2 p1) {
    const D2 dir = p1 - p0;
    double lo = 0.0, hi = 1.0;
    for (int i = 0; i < p.n; ++i) {
        const auto k = static_cast<std::size_t>(i);
        const double num = p.off[k] - dot(p.nrm[k], p0);
        const double den = dot(p.nrm[k], dir);
        if (den == 0.0) {
            if (num < 0.0) return {};
        } else if (den < 0.0) {
            lo = std::max(lo, num / den);
        } else {
            hi = std::min(hi, num / den);
        }
        if (hi < lo) return {};
    }
    return {true, lo};
}

// Circles: the same quantities.
inline SegMin segment_min_sd(D2 center, double radius, D2 p0, D2 p1) {
    double t = 0.0;
    const D2 c = closest_on_segment(p0, p1, center, &t);
    return {dist(c, center) - radius, t};
}
inline SegHit segment_first_hit(D2 center, double radius, D2 p0, D2 p1) {
    const D2 d = p1 - p0, s = p0 - center;
    const double a = dot(d, d), b = dot(s, d), c = dot(s, s) - radius * radius;
    if (c <= 0.0) return {true, 0.0};
    if (a == 0.0) return {};
    const double disc = b * b - a * c;
    if (disc < 0.0) return {};
    const double t = (-b - std::sqrt(disc)) / a;
    if (t < 0.0 || t > 1.0) return {};
    return {true, t};
}

}  // namespace exact
}  // namespace jostle::oracle
