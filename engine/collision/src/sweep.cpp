// Dynamic circles, slides 09-103 to 09-130: a circle moving against a static circle by the
// D/F/G closed form, two moving circles by relative velocity, the swept capsule (method #1)
// as an overlap test, and a moving circle against boxes, polygons, segments and masks, so
// that no fast ball passes through a thin wall.
#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>

#include "internal.h"

namespace jostle {

using detail::valid;

detail::CircleContact detail::first_contact_with_circle(Vec2 offset, Vec2 v, float radius) {
    const float speed = length(v);
    if (!(speed > 0.0f)) return {};
    const Vec2 dir{v.x / speed, v.y / speed};
    // D and F are v's dot and cross products with offset, over |v|, the products exact in
    // double: from the rounded unit vector dir, F was off by an ulp of dir times |offset|, and
    // a path that grazes exactly (F = R) got a G of the square root of that and hit at a slant
    // of a few 1e-4. Integer input that grazes now has F = R exactly.
    const double vx = v.x, vy = v.y, ox = offset.x, oy = offset.y;
    // 09-114: moving apart (or sideways) can never close the gap.
    const auto D = static_cast<float>((vx * ox + vy * oy) / speed);
    if (D <= 0.0f) return {};
    // 09-118/121: F is the distance from the static centre to the line of motion. The slide's
    // F^2 = |C_s - C_d|^2 - D^2 cancels badly when the line passes close to the centre or the
    // path is long; the cross product gives the same F without the cancellation.
    const auto F = static_cast<float>((vx * oy - vy * ox) / speed);
    const float F2 = F * F;
    if (F2 > radius * radius) return {};
    // 09-122: G^2 = (r_s + r_d)^2 - F^2; first contact after travelling D - G.
    const float G = std::sqrt(radius * radius - F2);
    const float travel = D - G;
    if (travel > speed) return {};  // 09-118 has ||v|| > D - G; here >=: touching at the end counts
    // Already within R up to rounding (the caller found no overlap): contact at t = 0, seen
    // from where the point is. G is ill-conditioned there (the square root of rounding), so
    // the formula below would tilt the normal toward the motion.
    if (!(travel > 0.0f)) return {true, 0.0f, normalize_or(-offset, -dir)};
    // With offset = D dir + F perp(dir), the point at contact is -G dir - F perp(dir) from the
    // centre: exact, where forming it from positions would round.
    return {true, travel / speed, normalize_or(-G * dir - F * perp(dir), -dir)};
}

namespace {

// A contact counts only while A moves into B: dot(v / |v|, n) > kGrazing (about 0.0006
// degrees). Anything less is a graze, or sliding along B, whose direction is rounding noise:
// a ball left touching a wall by the MTD push, or rolling over a mask's pixel seams, slides on.
constexpr float kGrazing = 1e-5f;

bool moving_into(Vec2 v, Vec2 n) {
    // On v scaled to a largest component of 1, so that tiny or huge speeds neither underflow
    // nor overflow the length.
    const float m = std::fmax(std::fabs(v.x), std::fabs(v.y));
    if (!(m > 0.0f)) return false;
    const Vec2 u{v.x / m, v.y / m};
    return dot(u, n) > kGrazing * length(u);
}

// The sweep answer once the circle (centre c, radius r, velocity v) touches at time t with
// unit normal n (from the circle toward the other shape).
SweepHit contact_at(Vec2 c, Vec2 v, float r, float t, Vec2 n) {
    const Vec2 clean = detail::plain_zeros(n);
    const Vec2 point = c + t * v + r * clean;
    // A contact point beyond float's range (a circle near FLT_MAX) is no hit, as a motion whose
    // end overflows is none: results are finite or a miss.
    if (!detail::finite(point)) return {};
    return {true, t + 0.0f, detail::plain_zeros(point), clean};
}

// The contact point moved with B to where B is at time t (relative motion); a miss if that
// point leaves float's range.
SweepHit moved_with_b(SweepHit h, Vec2 vb) {
    if (!h.hit) return h;
    h.point += h.t * vb;
    return detail::finite(h.point) ? h : SweepHit{};
}

// Shapes already touching or overlapping at t = 0: a contact at t = 0 only while A moves into
// B (09-114's moving-away early out applies here too); moving off or along B is no contact,
// and for a convex B there is none later either. `shape_vs_circle` is the collide() manifold
// of (shape, circle), whose normal points from the shape to the circle.
SweepHit contact_at_start(const Circle& moving, Vec2 v, const Manifold& shape_vs_circle) {
    const Vec2 n = -shape_vs_circle.normal;
    if (!moving_into(v, n)) return {};
    // The contact point: where the circle's surface meets the shape along the normal.
    return contact_at(moving.center + (moving.radius - shape_vs_circle.depth) * n, {}, 0.0f, 0.0f, n);
}

// First contact of a circle moving by v with a convex shape given by its vertices and outward
// edge normals (a segment is the 2-gon a->b, b->a); the caller has checked that they are not in
// contact at t = 0, and passes `entry`, the cast of the centre alone against the shape.
// The contact is the earliest of: the centre coming within r of a face's line inside that
// face's window (the face's analogue of 09-118's first contact), the centre coming within r of a vertex
// (D/F/G, 09-118), and the centre itself entering the shape. The last bounds the others: with
// a radius below the rounding of the first two, it is what stops the ball, so nothing passes
// through. Worked relative to the circle's start, where floats are dense.
SweepHit sweep_convex(const Circle& moving, Vec2 v, const Vec2* points, const Vec2* normals, int count,
                      const CastHit& entry) {
    const Vec2 from = moving.center;
    const float r = moving.radius;
    if (entry.hit && entry.t == 0.0f) {
        // The cast finds the centre in (or on) the shape where the start test found no
        // overlap: both are right up to rounding. A contact at t = 0 through the face the
        // centre is nearest the outside of, if moving into it.
        int face = -1;
        float best_side = -INFINITY;
        for (int i = 0; i < count; ++i) {
            const Vec2 e = points[(i + 1) % count] - points[i];
            const float side = dot(normals[i], from - points[i]);
            if (dot(e, e) > 0.0f && side > best_side) { best_side = side; face = i; }
        }
        if (face < 0 || !moving_into(v, -normals[face])) return {};
        return contact_at(from, v, r, 0.0f, -normals[face]);
    }
    // The contact's feature gives its normal: the entry's face, a face, or a vertex.
    float best_t = entry.hit ? entry.t : INFINITY;
    Vec2 outward = entry.normal;
    int vertex = -1;
    int beyond_end = -1;  // the vertex past which a face hit lies, if only rounding let it in
    for (int i = 0; i < count; ++i) {
        const Vec2 n = normals[i];
        const Vec2 e = points[(i + 1) % count] - points[i];
        const float ee = dot(e, e);
        const float closing = -dot(n, v);
        if (!(ee > 0.0f) || !(closing > 0.0f)) continue;  // a zero-length face is its vertex
        // The face's window runs along the direction its normal gives, u = n turned a quarter
        // back (e / |e| for a face whose ends are exact), over [0, len]: its extent along u.
        // The ends' coordinates are rounded, so for a face only a few of their rounding steps
        // long e's own direction is mostly rounding (a box 1e-5 px thick at x = 160, fuzz),
        // and a window along it, tested a ball's radius away, could pass 70 px from the face;
        // along u it is off by no more than the ends' rounding, wherever the ball is.
        const Vec2 u{-n.y, n.x};
        const float len = dot(e, u);
        if (!(len > 0.0f)) continue;  // rounding turned the face against its normal: its vertices
        const Vec2 f = from - points[i];
        const float gap = dot(n, f) - r;  // from the face's line pushed out by r
        // A start behind that line by more than rounding is not an entry through this face: it
        // is beside the face's window (in a corner's wedge), or the shapes would overlap.
        // (The start test measured from elsewhere on B, so allow for rounding on B's scale.)
        if (gap < -16.0f * FLT_EPSILON * (length(f) + std::sqrt(ee) + r)) continue;
        const float t = gap > 0.0f ? gap / closing : 0.0f;
        if (!(t <= 1.0f) || !(t < best_t)) continue;
        // The window, with room for rounding: a ball sliding in along a face from exactly its
        // end projects just outside it as often as just inside.
        const Vec2 q = f + t * v;
        const float along = dot(q, u);
        const float slack = 16.0f * FLT_EPSILON * (length(q) + len);
        if (along >= -slack && along <= len + slack) {
            best_t = t;
            outward = n;
            vertex = -1;
            beyond_end = along < 0.0f ? i : (along > len ? (i + 1) % count : -1);
            continue;
        }
        // Beside the window, the band within r of the face can still be entered across the
        // window's end. In exact arithmetic the end's vertex circle is met first; when rounding
        // makes that a near-miss, the crossing itself bounds the contact.
        const float toward = along < 0.0f ? dot(v, u) : -dot(v, u);
        if (!(toward > 0.0f)) continue;
        const float t_end = along < 0.0f ? -dot(f, u) / dot(v, u) : (len - dot(f, u)) / dot(v, u);
        if (!(t_end >= t && t_end <= 1.0f && t_end < best_t)) continue;
        const float height = dot(n, f + t_end * v);  // above the face's line at the window's end
        if (!(height >= 0.0f && height <= r)) continue;  // not in the band there
        const int end = along < 0.0f ? i : (i + 1) % count;
        best_t = t_end;
        outward = normalize_or((from - points[end]) + t_end * v, n);
        vertex = end;
        beyond_end = -1;
    }
    if (r > 0.0f) {
        for (int i = 0; i < count; ++i) {
            const detail::CircleContact c = detail::first_contact_with_circle(points[i] - from, v, r);
            if (c.hit && c.t < best_t) {
                best_t = c.t;
                outward = c.outward;
                vertex = i;
                beyond_end = -1;
            }
        }
        // A face hit just past the face's end (let in by the window's rounding room) is that
        // end's vertex when the ball does meet its circle: the corner is the real contact.
        if (beyond_end >= 0) {
            const detail::CircleContact c = detail::first_contact_with_circle(points[beyond_end] - from, v, r);
            if (c.hit) {
                best_t = c.t;
                outward = c.outward;
                vertex = beyond_end;
            }
        }
    }
    if (best_t == INFINITY) return {};
    if (vertex >= 0) {
        // A vertex's contact direction must lie in its cone of normals, between the normals of
        // the nearest faces of non-zero length before and after it (a cone of 180 degrees --
        // a segment's end, a flat box's end -- is the half-plane turning positively from one
        // to the other; a point-sized box has none). Outside it, rounding let this vertex win
        // a tie: with the neighbour across a tiny face (a thin box's other corner), or with any
        // corner of a shape that float sees as a point, whose cone holds the direction; or
        // with a face (an adjacent one, or a thin box's far one), whose exact normal it then takes. "Non-zero length" is the
        // squared length's, on purpose: a face whose square underflows belongs to a shape that
        // float sees as a point, and counting it narrows the cone so that a ball passing over
        // such a box misses it (regression sweep_circle_over_point_sized_box_tunnels.bin).
        auto cone_bounds = [&](int vtx, Vec2& n_prev, Vec2& n_next) {
            int prev = -1, next = -1;
            for (int k = 1; k <= count && prev < 0; ++k) {
                const int i = (vtx + count - k) % count;
                if (length_squared(points[(i + 1) % count] - points[i]) > 0.0f) prev = i;
            }
            for (int k = 0; k < count && next < 0; ++k) {
                const int i = (vtx + k) % count;
                if (length_squared(points[(i + 1) % count] - points[i]) > 0.0f) next = i;
            }
            if (prev < 0 || next < 0) return false;
            n_prev = normals[prev];
            n_next = normals[next];
            return true;
        };
        auto outside_cone = [&](int vtx, Vec2 out) {
            Vec2 n_prev, n_next;
            if (!cone_bounds(vtx, n_prev, n_next)) return false;
            if (cross(n_prev, n_next) > 0.0f) return cross(n_prev, out) < 0.0f || cross(out, n_next) < 0.0f;
            return cross(n_prev, out) < 0.0f;
        };
        if (outside_cone(vertex, outward)) {
            // The neighbours first; then, for a shape so small that float sees a point (every
            // corner meets the ball at the same t), the other corners: the opposite one holds
            // the direction there.
            const int before = (vertex + count - 1) % count, after = (vertex + 1) % count;
            std::array<int, kMaxPolygonVertices> candidates{};
            std::size_t n_candidates = 0;
            candidates[n_candidates++] = before;
            if (after != before) candidates[n_candidates++] = after;
            for (int i = 0; i < count; ++i) {
                if (i != vertex && i != before && i != after) candidates[n_candidates++] = i;
            }
            bool moved = false;
            Vec2 outward_face;
            for (std::size_t k = 0; k < n_candidates; ++k) {
                const int nb = candidates[k];
                const detail::CircleContact c = detail::first_contact_with_circle(points[nb] - from, v, r);
                if (c.hit && c.t <= best_t + 1e-5f * (1.0f + best_t) && !outside_cone(nb, c.outward)) {
                    outward = c.outward;
                    moved = true;
                    break;
                }
            }
            // Else the contact is a face's: the one facing the direction most. That is an
            // adjacent face when rounding let the vertex win a tie with it, and the far face of a
            // thin box when the vertex across its end won one with that face (a box 1.3e-5 px
            // thick, fuzz: its nearer corner's direction, taken from the wrong side's cone, ran
            // along the motion and the ball passed through).
            if (!moved) {
                float facing = -INFINITY;
                for (int i = 0; i < count; ++i) {
                    if (!(length_squared(points[(i + 1) % count] - points[i]) > 0.0f)) continue;
                    const float d = dot(outward, normals[i]);
                    if (d > facing) {
                        facing = d;
                        outward_face = normals[i];
                    }
                }
                if (facing > -INFINITY) outward = outward_face;
            }
        }
    }
    if (!moving_into(v, -outward)) return {};  // only grazes it
    return contact_at(from, v, r, best_t, -outward);
}

}  // namespace

SweepHit sweep(const Circle& moving, Vec2 v, const Circle& fixed) {
    if (!valid(moving) || !valid(fixed) || !detail::valid_motion(moving.center, v)) return {};
    const Vec2 delta = fixed.center - moving.center;  // C_s - C_d
    const float r = moving.radius + fixed.radius;
    if (dot(delta, delta) <= r * r) return contact_at_start(moving, v, detail::flipped(collide(moving, fixed)));
    const detail::CircleContact c = detail::first_contact_with_circle(delta, v, r);
    if (!c.hit || !moving_into(v, -c.outward)) return {};  // a miss, or a graze (F = R)
    return contact_at(moving.center, v, moving.radius, c.t, -c.outward);
}

SweepHit sweep(const Circle& a, Vec2 va, const Circle& b, Vec2 vb) {
    // 09-126/127: in B's frame of reference A moves by va - vb and B stands still.
    if (!detail::finite(va) || !detail::finite(vb)) return {};
    return moved_with_b(sweep(a, va - vb, b), vb);
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
    const Vec2 dir{v.x / speed, v.y / speed};
    const Vec2 points[4] = {cap.rectangle[3], cap.rectangle[2], cap.rectangle[1], cap.rectangle[0]};
    const Vec2 normals[4] = {-perp(dir), dir, perp(dir), -dir};
    return collide(detail::PolygonAccess::make(points, normals), fixed).hit;
}

SweepHit sweep(const Circle& moving, Vec2 v, const Polygon& poly) {
    if (!valid(moving) || !valid(poly) || !detail::valid_motion(moving.center, v)) return {};
    const Manifold start = collide(poly, moving);
    if (start.hit) return contact_at_start(moving, v, start);
    return sweep_convex(moving, v, poly.points().data(), poly.normals().data(), poly.count(),
                        cast(moving.center, moving.center + v, poly));
}

SweepHit sweep(const Circle& moving, Vec2 v, const Aabb& box) {
    // The start is judged by the same box clamp as collide(Aabb, Circle) (called here), so
    // both agree on ties; the motion by the box's polygon (its corners are exact).
    if (!valid(moving) || !valid(box) || !detail::valid_motion(moving.center, v)) return {};
    const Manifold start = collide(box, moving);
    if (start.hit) return contact_at_start(moving, v, start);
    const Polygon p = to_polygon(box);
    return sweep_convex(moving, v, p.points().data(), p.normals().data(), 4, cast(moving.center, moving.center + v, box));
}

SweepHit sweep(const Circle& moving, Vec2 v, const Obb& box) {
    // Solved with the box's centre at the origin, where its corners are precise.
    if (!valid(moving) || !valid(box) || !detail::valid_motion(moving.center, v)) return {};
    const Manifold start = collide(box, moving);
    if (start.hit) return contact_at_start(moving, v, start);
    const Polygon p = detail::centred_polygon(box);
    const Vec2 from = moving.center - box.center;
    SweepHit h = sweep_convex(Circle{from, moving.radius}, v, p.points().data(), p.normals().data(), 4, cast(from, from + v, p));
    if (h.hit) h.point += box.center;
    return h;
}

SweepHit sweep(const Circle& moving, Vec2 v, const Segment& seg) {
    // A segment grown by r is a capsule: the 2-gon a->b, b->a with its two normals.
    if (!valid(moving) || !valid(seg) || !detail::valid_motion(moving.center, v)) return {};
    const Manifold start = collide(seg, moving);
    const Vec2 e = seg.b - seg.a;
    const Vec2 n = normalize_or(Vec2{e.y, -e.x}, Vec2{1.0f, 0.0f});
    if (start.hit) {
        // A centre on the segment up to rounding has no side of its own: it is pushing into the
        // wall on the side it moves toward. Its contact point is the segment's point under the
        // centre: as for any start in contact, r - depth from the centre along the normal, and
        // the depth here is r up to rounding (so the projection itself is taken).
        const Vec2 off = detail::offset_from_segment(seg.a, seg.b, moving.center);
        if (seg.a != seg.b && length(off) <= 16.0f * FLT_EPSILON * (length(moving.center - seg.a) + length(e))) {
            const Vec2 into = dot(v, n) >= 0.0f ? n : -n;
            if (!moving_into(v, into)) return {};
            return contact_at(moving.center - off, {}, 0.0f, 0.0f, into);
        }
        return contact_at_start(moving, v, start);
    }
    if (seg.a == seg.b) return sweep(moving, v, Circle{seg.a, 0.0f});
    const Vec2 points[2] = {seg.a, seg.b};
    const Vec2 normals[2] = {n, -n};
    return sweep_convex(moving, v, points, normals, 2, cast(moving.center, moving.center + v, seg));
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
    return moved_with_b(std::visit([&](const auto& shape) { return sweep(a, va - vb, shape); }, b), vb);
}

}  // namespace jostle
