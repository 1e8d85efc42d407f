// Dynamic circles, slides 09-103 to 09-130: a circle moving against a static circle by the
// D/F/G closed form, two moving circles by relative velocity, the swept capsule (method #1)
// as an overlap test, and a moving circle against boxes, polygons, segments and masks, so
// that no fast ball passes through a thin wall.
#include <algorithm>
#include <cfloat>
#include <cmath>

#include "internal.h"

namespace jostle {

using detail::valid;

detail::CircleContact detail::first_contact_with_circle(Vec2 offset, Vec2 v, float radius) {
    const float speed = length(v);
    if (!(speed > 0.0f)) return {};
    const Vec2 dir{v.x / speed, v.y / speed};
    // 09-114: moving apart (or sideways) can never close the gap.
    const float D = dot(dir, offset);
    if (D <= 0.0f) return {};
    // 09-118/121: F is the distance from the static centre to the line of motion. The slide's
    // F^2 = |C_s - C_d|^2 - D^2 cancels badly when the line passes close to the centre or the
    // path is long; the cross product gives the same F without the cancellation.
    const float F = cross(dir, offset);
    const float F2 = F * F;
    if (F2 > radius * radius) return {};
    // 09-122: G^2 = (r_s + r_d)^2 - F^2; first contact after travelling D - G.
    const float G = std::sqrt(radius * radius - F2);
    const float travel = D - G;
    if (travel > speed) return {};  // 09-118: ||v|| >= D - G; touching at the end counts
    // With offset = D dir + F perp(dir), the point at contact is -G dir - F perp(dir) from the
    // centre: exact, where forming it from positions would round.
    const Vec2 outward = normalize_or(-G * dir - F * perp(dir), -dir);
    return {true, travel > 0.0f ? travel / speed : 0.0f, outward};
}

namespace {

// The sweep answer once the circle (centre c, radius r, velocity v) touches at time t with
// unit normal n (from the circle toward the other shape).
SweepHit contact_at(Vec2 c, Vec2 v, float r, float t, Vec2 n) {
    return {true, t, c + t * v + r * n, detail::plain_zeros(n)};
}

// Shapes already touching or overlapping at t = 0: a contact at t = 0 only while A moves
// into B (09-114's moving-away early out applies here too). A ball resting against a wall
// and moving off it, or sliding along it, has no contact ahead. `shape_vs_circle` is the
// collide() manifold of (shape, circle), whose normal points from the shape to the circle.
SweepHit contact_at_start(const Circle& moving, Vec2 v, const Manifold& shape_vs_circle) {
    const Vec2 n = -shape_vs_circle.normal;
    if (!(dot(v, n) > 0.0f)) return {};
    // The contact point: where the circle's surface meets the shape along the normal.
    return {true, 0.0f, moving.center + (moving.radius - shape_vs_circle.depth) * n, detail::plain_zeros(n)};
}

// First contact of a circle moving by v with the convex shape given by its vertices and
// outward edge normals (a segment is the 2-gon a->b, b->a); the circle does not touch the
// shape at t = 0. The centre moves against the shape grown by r, whose boundary is every
// face pushed out by r and a circle of radius r at every vertex. The path is clipped
// against the pushed-out half-planes (Cyrus-Beck): where it enters through a face's own
// window, that is the contact; where it enters beside the window, it is in a corner's wedge
// and meets that vertex's circle or nothing. Worked relative to the circle's start, so that
// a shape far from the origin keeps the precision of its size.
SweepHit sweep_rounded(const Circle& moving, Vec2 v, const Vec2* points, const Vec2* normals, int count) {
    const Vec2 from = moving.center;
    const float r = moving.radius;
    // The entering face is tracked even before t = 0: a start within rounding of a face (or
    // in a corner's wedge) entered the pushed-out polygon at a slightly negative time.
    float t_enter = -INFINITY;
    float t_exit = 1.0f;
    int face = -1;
    for (int i = 0; i < count; ++i) {
        const Vec2 n = normals[i];
        const float num = r + dot(n, points[i] - from);  // >= 0: the start is inside this half-plane
        const float den = dot(n, v);                    // < 0: moving inward through the face
        if (den == 0.0f) {
            if (num < 0.0f) return {};  // parallel to the face, outside it
            continue;
        }
        const float t = num / den;
        if (den < 0.0f) {
            if (t > t_enter) { t_enter = t; face = i; }
        } else if (t < t_exit) {
            t_exit = t;
        }
        if (!(t_enter <= t_exit)) return {};
    }
    if (v == Vec2{} || t_exit < 0.0f) return {};  // not moving, or its line passed it before t = 0
    int vertex = -1;
    if (face >= 0 && t_enter >= 0.0f) {
        const Vec2 e = points[(face + 1) % count] - points[face];
        const Vec2 q = t_enter * v - (points[face] - from);  // the entry point, from the face's first vertex
        const float along = dot(q, e);
        // Rounding can put an entry through the face's end just beside its window: allow it.
        const float slack = 8.0f * FLT_EPSILON * (length(q) + length(e)) * length(e);
        if (r == 0.0f || (along >= -slack && along <= dot(e, e) + slack)) {
            return contact_at(from, v, r, t_enter, -normals[face]);
        }
        vertex = along < 0.0f ? face : (face + 1) % count;
    } else {
        // The start is inside every pushed-out half-plane (or, for a segment moving along its
        // own line, inside the strip they form), yet does not overlap the shape: it is in a
        // corner's wedge, or on a face up to rounding. The nearest feature says which.
        int edge = 0;
        float param = 0.0f, best_d2 = INFINITY;
        for (int i = 0; i < count; ++i) {
            const Vec2 a = points[i], b = points[(i + 1) % count];
            const float s = detail::segment_param(a, b, from);
            const float d2 = length_squared((from - a) - s * (b - a));
            if (d2 < best_d2) { best_d2 = d2; edge = i; param = s; }
        }
        if (param > 0.0f && param < 1.0f) {  // touching a face: a contact only when moving into it
            if (!(dot(v, normals[edge]) < 0.0f)) return {};
            return contact_at(from, v, r, 0.0f, -normals[edge]);
        }
        vertex = param <= 0.0f ? edge : (edge + 1) % count;
    }
    // In a corner's wedge: that vertex's circle, or nothing.
    const detail::CircleContact c = detail::first_contact_with_circle(points[vertex] - from, v, r);
    if (!c.hit) return {};
    return contact_at(from, v, r, c.t, -c.outward);
}

}  // namespace

SweepHit sweep(const Circle& moving, Vec2 v, const Circle& fixed) {
    if (!valid(moving) || !valid(fixed) || !detail::valid_motion(moving.center, v)) return {};
    const Vec2 delta = fixed.center - moving.center;  // C_s - C_d
    const float r = moving.radius + fixed.radius;
    if (dot(delta, delta) <= r * r) return contact_at_start(moving, v, detail::flipped(collide(moving, fixed)));
    const detail::CircleContact c = detail::first_contact_with_circle(delta, v, r);
    if (!c.hit) return {};
    return contact_at(moving.center, v, moving.radius, c.t, -c.outward);
}

SweepHit sweep(const Circle& a, Vec2 va, const Circle& b, Vec2 vb) {
    // 09-126/127: in B's frame of reference A moves by va - vb and B stands still.
    if (!detail::finite(va) || !detail::finite(vb)) return {};
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
    if (!valid(moving) || !valid(fixed) || !detail::valid_motion(moving.center, v)) return false;
    const SweptCapsule cap = swept_capsule(moving, v);
    if (collide(cap.start, fixed).hit || collide(cap.end, fixed).hit) return true;
    const float speed = length(v);
    if (!(speed > 0.0f && moving.radius > 0.0f)) {
        // No area: the rectangle is the path itself, against the fixed circle grown by r.
        return collide(Segment{moving.center, moving.center + v}, Circle{fixed.center, fixed.radius + moving.radius}).hit;
    }
    // The rectangle's corners turn negatively (c + d, c + v + d, ...), so they are stored in
    // reverse; its outward normals are +-v/|v| and +-d/r.
    Polygon rect;
    rect.count = 4;
    const Vec2 dir{v.x / speed, v.y / speed};
    for (int i = 0; i < 4; ++i) rect.points[i] = cap.rectangle[3 - i];
    rect.normals = {-perp(dir), dir, perp(dir), -dir};
    return collide(rect, fixed).hit;
}

SweepHit sweep(const Circle& moving, Vec2 v, const Polygon& poly) {
    if (!valid(moving) || !valid(poly) || !detail::valid_motion(moving.center, v)) return {};
    const Manifold start = collide(poly, moving);
    if (start.hit) return contact_at_start(moving, v, start);
    return sweep_rounded(moving, v, poly.points.data(), poly.normals.data(), poly.count);
}

SweepHit sweep(const Circle& moving, Vec2 v, const Aabb& box) {
    if (!valid(box)) return {};
    return sweep(moving, v, to_polygon(box));
}

SweepHit sweep(const Circle& moving, Vec2 v, const Obb& box) {
    // Solved with the box's centre at the origin, where its corners are precise.
    if (!valid(box)) return {};
    SweepHit h = sweep(Circle{moving.center - box.center, moving.radius}, v, detail::centred_polygon(box));
    if (h.hit) h.point += box.center;
    return h;
}

SweepHit sweep(const Circle& moving, Vec2 v, const Segment& seg) {
    // A segment grown by r is a capsule: the 2-gon a->b, b->a with its two normals.
    if (!valid(moving) || !valid(seg) || !detail::valid_motion(moving.center, v)) return {};
    const Manifold start = collide(seg, moving);
    if (start.hit) return contact_at_start(moving, v, start);
    if (seg.a == seg.b) return sweep(moving, v, Circle{seg.a, 0.0f});
    const Vec2 dir = normalize_or(seg.b - seg.a, Vec2{1.0f, 0.0f});
    const Vec2 points[2] = {seg.a, seg.b};
    const Vec2 normals[2] = {Vec2{dir.y, -dir.x}, Vec2{-dir.y, dir.x}};
    return sweep_rounded(moving, v, points, normals, 2);
}

SweepHit sweep(const Circle& moving, Vec2 v, const PlacedMask& m) {
    // Set pixels as closed unit squares: the earliest contact with any square the swept
    // circle can reach (only the pixels inside the path's bounds, widened by one, are tried).
    if (!valid(moving) || !detail::valid_motion(moving.center, v) || !m.mask) return {};
    const Mask& mask = *m.mask;
    const Vec2 origin{static_cast<float>(m.x), static_cast<float>(m.y)};
    const Vec2 reach{moving.radius, moving.radius};
    const Vec2 lo = min(moving.center, moving.center + v) - reach - origin;
    const Vec2 hi = max(moving.center, moving.center + v) + reach - origin;
    const int i0 = std::max(detail::pixel_index(std::floor(lo.x)) - 1, 0);
    const int i1 = std::min(detail::pixel_index(std::floor(hi.x)) + 1, mask.width() - 1);
    const int j0 = std::max(detail::pixel_index(std::floor(lo.y)) - 1, 0);
    const int j1 = std::min(detail::pixel_index(std::floor(hi.y)) + 1, mask.height() - 1);
    SweepHit best{};
    for (int j = j0; j <= j1; ++j) {
        for (int i = i0; i <= i1; ++i) {
            if (!mask.get(i, j)) continue;
            const Vec2 cell = origin + Vec2{static_cast<float>(i), static_cast<float>(j)};
            const SweepHit h = sweep(moving, v, Aabb{cell, cell + Vec2{1.0f, 1.0f}});
            if (h.hit && (!best.hit || h.t < best.t)) best = h;
        }
    }
    return best;
}

SweepHit sweep(const Circle& a, Vec2 va, const Shape& b, Vec2 vb) {
    // Relative motion: B stands still and A moves by va - vb; the contact point then moves
    // with B to where B is at time t.
    if (!detail::finite(va) || !detail::finite(vb)) return {};
    SweepHit h = std::visit([&](const auto& shape) { return sweep(a, va - vb, shape); }, b);
    if (h.hit) h.point += h.t * vb;
    return h;
}

}  // namespace jostle
