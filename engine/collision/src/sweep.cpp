// Dynamic circles, slides 09-103 to 09-130: a circle moving against a static circle by the
// D/F/G closed form, two moving circles by relative velocity, the swept capsule (method #1)
// as an overlap test, and a moving circle against boxes, polygons, segments and masks, so
// that no fast ball passes through a thin wall.
#include <cfloat>
#include <cmath>

#include "internal.h"

namespace jostle {

using detail::finite;

namespace {

// The sweep answer once the circle (centre c, radius r) is known to touch at time t with
// unit normal n (from the circle toward the other shape).
SweepHit contact_at(Vec2 c, Vec2 v, float r, float t, Vec2 n) { return {true, t, c + t * v + r * n, n}; }

// A circle overlapping at t = 0: the collide() manifold of (shape, circle) gives the normal
// from the shape to the circle; the sweep's normal points the other way.
SweepHit overlap_at_start(const Circle& moving, const Manifold& shape_vs_circle) {
    const Vec2 n = -shape_vs_circle.normal;
    // The contact point: where the circle's surface meets the shape along the normal.
    return {true, 0.0f, moving.center + (moving.radius - shape_vs_circle.depth) * n, n};
}

// First contact of a circle moving by v with the convex shape given by its vertices and
// outward edge normals (a segment is the 2-gon a->b, b->a). The centre moves against the
// shape grown by r: every face pushed out by r, and a circle of radius r at every vertex.
// The caller has checked that the circle does not overlap the shape at t = 0.
SweepHit sweep_rounded(const Circle& moving, Vec2 v, const Vec2* points, const Vec2* normals, int count) {
    // Worked relative to the circle's start (c = 0), so that a shape far from the origin
    // keeps the precision of its size.
    const Vec2 from = moving.center;
    const float r = moving.radius;
    float best_t = INFINITY;
    int best_face = -1;    // a face hit, or
    int best_vertex = -1;  // a vertex hit
    for (int i = 0; i < count; ++i) {
        const Vec2 n = normals[i];
        const float closing = -dot(v, n);
        if (!(closing > 0.0f)) continue;  // only faces the centre moves toward
        const Vec2 p = points[i] - from;
        const Vec2 e = points[(i + 1) % count] - points[i];
        // The gap to the grown face at t = 0 (09-115's "closest approach" along the normal).
        // No overlap at t = 0 means the gap is >= 0 up to the rounding of its terms: a start
        // just behind the face by less than that is a touch at t = 0, not a pass-through.
        const float gap = -dot(n, p) - r;
        const float rounding = 8.0f * FLT_EPSILON * (std::fabs(dot(n, p)) + r);
        if (gap < -rounding) continue;  // already past this face's line: it cannot be the entry
        const float t = gap > 0.0f ? gap / closing : 0.0f;
        if (!(t <= 1.0f) || !(t < best_t)) continue;
        const Vec2 q = t * v - p;  // the centre at t, relative to the face's first vertex
        const float along = dot(q, e);
        if (along >= 0.0f && along <= dot(e, e)) { best_t = t; best_face = i; best_vertex = -1; }
    }
    if (r > 0.0f) {
        for (int i = 0; i < count; ++i) {
            const CastHit h = detail::cast_circle({}, v, points[i] - from, r);
            if (h.hit && h.t < best_t) { best_t = h.t; best_vertex = i; best_face = -1; }
        }
    }
    if (best_face < 0 && best_vertex < 0) return {};
    Vec2 outward;
    if (best_face >= 0) {
        outward = normals[best_face];
    } else {
        // A vertex hit whose contact lies in an adjacent face's region is that face's hit
        // (the two times agree up to rounding there); the face's normal is the exact one.
        const int i = best_vertex;
        const int prev = (i + count - 1) % count;
        const Vec2 q = best_t * v - (points[i] - from);  // centre at t, relative to the vertex
        const Vec2 e_next = points[(i + 1) % count] - points[i];
        const Vec2 e_prev = points[i] - points[prev];
        if (dot(q, e_next) >= 0.0f && dot(q, e_next) <= dot(e_next, e_next)) outward = normals[i];
        else if (dot(q, e_prev) <= 0.0f && -dot(q, e_prev) <= dot(e_prev, e_prev)) outward = normals[prev];
        else outward = normalize_or(q, normals[i]);
    }
    return contact_at(from, v, r, best_t, -outward);
}

}  // namespace

SweepHit sweep(const Circle& moving, Vec2 v, const Circle& fixed) {
    if (!finite(moving) || !finite(fixed) || !finite(v)) return {};
    const Vec2 delta = fixed.center - moving.center;  // C_s - C_d
    const float r = moving.radius + fixed.radius;
    const float dist2 = dot(delta, delta);
    if (dist2 <= r * r) {  // already touching: contact at t = 0
        const float dist = std::sqrt(dist2);
        const Vec2 n = dist > 0.0f ? Vec2{delta.x / dist, delta.y / dist} : Vec2{1.0f, 0.0f};
        return {true, 0.0f, moving.center + (dist - fixed.radius > 0.0f ? dist - fixed.radius : 0.0f) * n, n};
    }
    const float speed = length(v);
    if (!(speed > 0.0f)) return {};
    const Vec2 dir{v.x / speed, v.y / speed};
    // 09-114: moving apart (or sideways) can never close the gap.
    const float D = dot(dir, delta);
    if (D <= 0.0f) return {};
    // 09-118/121: F is the distance from the static centre to the line of motion. The slide's
    // F^2 = |C_s - C_d|^2 - D^2 cancels badly when the line passes close to the centre; the
    // cross product gives the same F without the cancellation.
    const float F = cross(dir, delta);
    const float F2 = F * F;
    if (F2 > r * r) return {};
    // 09-122: G^2 = (r_s + r_d)^2 - F^2; first contact after travelling D - G.
    const float G = std::sqrt(r * r - F2);
    const float travel = D - G;
    if (travel > speed) return {};  // 09-118: ||v|| >= D - G, touching at the end counts
    const float t = travel > 0.0f ? travel / speed : 0.0f;
    const Vec2 c = moving.center + t * v;
    const Vec2 n = normalize_or(fixed.center - c, dir);
    return contact_at(moving.center, v, moving.radius, t, n);
}

SweepHit sweep(const Circle& a, Vec2 va, const Circle& b, Vec2 vb) {
    // 09-126/127: in B's frame of reference A moves by va - vb and B stands still.
    SweepHit h = sweep(a, va - vb, b);
    if (h.hit) h.point += h.t * vb;
    return h;
}

SweptCapsule swept_capsule(const Circle& c, Vec2 v) {
    // 09-110 with the slide's mistake fixed: d = [-v_y, v_x] r / |v| is perpendicular to v;
    // the slide's [-v_x, v_y] is not (it is v mirrored).
    const float speed = length(v);
    const Vec2 d = speed > 0.0f ? (c.radius / speed) * perp(v) : Vec2{};
    return {c, Circle{c.center + v, c.radius}, {c.center + d, c.center + v + d, c.center + v - d, c.center - d}};
}

bool swept_overlaps(const Circle& moving, Vec2 v, const Circle& fixed) {
    // 09-106: the swept circle is a rectangle and two circles; test each "as before".
    if (!finite(moving) || !finite(fixed) || !finite(v)) return false;
    const SweptCapsule cap = swept_capsule(moving, v);
    if (collide(cap.start, fixed).hit || collide(cap.end, fixed).hit) return true;
    std::string ignored;
    if (const auto rect = make_polygon(cap.rectangle, &ignored)) return collide(*rect, fixed).hit;
    // No area (zero radius or no motion): the path itself against the fixed circle grown by
    // the moving one's radius.
    return collide(Segment{moving.center, moving.center + v}, Circle{fixed.center, fixed.radius + moving.radius}).hit;
}

SweepHit sweep(const Circle& moving, Vec2 v, const Polygon& poly) {
    if (!finite(moving) || !finite(v) || !finite(poly)) return {};
    const Manifold start = collide(poly, moving);
    if (start.hit) return overlap_at_start(moving, start);
    return sweep_rounded(moving, v, poly.points.data(), poly.normals.data(), poly.count);
}

SweepHit sweep(const Circle& moving, Vec2 v, const Aabb& box) {
    if (!finite(box)) return {};
    return sweep(moving, v, to_polygon(box));
}

SweepHit sweep(const Circle& moving, Vec2 v, const Obb& box) {
    // Solved with the box's centre at the origin, where its corners are precise.
    if (!finite(box)) return {};
    SweepHit h = sweep(Circle{moving.center - box.center, moving.radius}, v, detail::centred_polygon(box));
    if (h.hit) h.point += box.center;
    return h;
}

SweepHit sweep(const Circle& moving, Vec2 v, const Segment& seg) {
    // A segment grown by r is a capsule: the 2-gon a->b, b->a with its two normals.
    if (!finite(moving) || !finite(v) || !finite(seg)) return {};
    const Manifold start = collide(seg, moving);
    if (start.hit) return overlap_at_start(moving, start);
    if (seg.a == seg.b) return sweep(moving, v, Circle{seg.a, 0.0f});
    const Vec2 dir = normalize_or(seg.b - seg.a, Vec2{1.0f, 0.0f});
    const Vec2 points[2] = {seg.a, seg.b};
    const Vec2 normals[2] = {Vec2{dir.y, -dir.x}, Vec2{-dir.y, dir.x}};
    return sweep_rounded(moving, v, points, normals, 2);
}

SweepHit sweep(const Circle& moving, Vec2 v, const PlacedMask& m) {
    // Set pixels as closed unit squares: the earliest contact with any square the swept
    // circle can reach (only the pixels inside the path's bounds are tried).
    if (!finite(moving) || !finite(v) || !m.mask) return {};
    const Mask& mask = *m.mask;
    const Aabb path{min(moving.center, moving.center + v) - Vec2{moving.radius, moving.radius},
                    max(moving.center, moving.center + v) + Vec2{moving.radius, moving.radius}};
    const auto first = [](float v0, int origin, int size) {
        return static_cast<int>(detail::clamp(std::floor(v0) - static_cast<float>(origin) - 1.0f, 0.0f,
                                              static_cast<float>(size)));
    };
    const int i0 = first(path.min.x, m.x, mask.width()), i1 = first(path.max.x + 2.0f, m.x, mask.width());
    const int j0 = first(path.min.y, m.y, mask.height()), j1 = first(path.max.y + 2.0f, m.y, mask.height());
    SweepHit best{};
    for (int j = j0; j < j1; ++j) {
        for (int i = i0; i < i1; ++i) {
            if (!mask.get(i, j)) continue;
            const Vec2 lo{static_cast<float>(m.x + i), static_cast<float>(m.y + j)};
            const SweepHit h = sweep(moving, v, Aabb{lo, lo + Vec2{1.0f, 1.0f}});
            if (h.hit && (!best.hit || h.t < best.t)) best = h;
        }
    }
    return best;
}

SweepHit sweep(const Circle& a, Vec2 va, const Shape& b, Vec2 vb) {
    // Relative motion: B stands still and A moves by va - vb; the contact point then moves
    // with B to where B is at time t.
    if (!finite(va) || !finite(vb)) return {};
    SweepHit h = std::visit([&](const auto& shape) { return sweep(a, va - vb, shape); }, b);
    if (h.hit) h.point += h.t * vb;
    return h;
}

}  // namespace jostle
