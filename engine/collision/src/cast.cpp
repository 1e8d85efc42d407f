// Casts for bullets, slide 09-103: a bullet is the segment from its last to its next
// position, and the first place that segment touches a shape is the hit: t, point and the
// shape's outward normal. Circle by the quadratic, boxes by slabs, polygons by clipping
// against every edge's half-plane (Cyrus-Beck), masks row band by row band.
#include <cmath>

#include "internal.h"

namespace jostle {

using detail::finite;

namespace {

CastHit hit_at(Vec2 from, Vec2 d, float t, Vec2 normal) { return {true, t, from + t * d, normal}; }
CastHit starts_inside(Vec2 from, Vec2 normal = {}) { return {true, 0.0f, from, normal}; }

// floor/ceil results as ints, clamped first so a far-off float never overflows the cast.
int index_of(float v) { return static_cast<int>(detail::clamp(v, -2.0f, 2.0f * kMaxMaskSide)); }

// The closed box [lo, hi] by slabs. A start on the boundary gets that face's normal.
CastHit cast_box(Vec2 from, Vec2 to, Vec2 lo, Vec2 hi) {
    const Vec2 d = to - from;
    const bool in_x = from.x >= lo.x && from.x <= hi.x;
    const bool in_y = from.y >= lo.y && from.y <= hi.y;
    if (in_x && in_y) {
        Vec2 n{};
        if (from.x == lo.x) n = {-1.0f, 0.0f};
        else if (from.x == hi.x) n = {1.0f, 0.0f};
        else if (from.y == lo.y) n = {0.0f, -1.0f};
        else if (from.y == hi.y) n = {0.0f, 1.0f};
        return starts_inside(from, n);
    }
    float t_enter = 0.0f;
    float t_exit = 1.0f;
    Vec2 normal{};
    const float f[2] = {from.x, from.y};
    const float dd[2] = {d.x, d.y};
    const float l[2] = {lo.x, lo.y};
    const float h[2] = {hi.x, hi.y};
    for (int axis = 0; axis < 2; ++axis) {
        if (dd[axis] == 0.0f) {
            if (f[axis] < l[axis] || f[axis] > h[axis]) return {};
            continue;
        }
        float t_near = (l[axis] - f[axis]) / dd[axis];
        float t_far = (h[axis] - f[axis]) / dd[axis];
        float sign = -1.0f;  // entering through the low face
        if (t_near > t_far) {
            const float tmp = t_near;
            t_near = t_far;
            t_far = tmp;
            sign = 1.0f;
        }
        if (t_near > t_enter) {
            t_enter = t_near;
            normal = axis == 0 ? Vec2{sign, 0.0f} : Vec2{0.0f, sign};
        }
        if (t_far < t_exit) t_exit = t_far;
        if (!(t_enter <= t_exit)) return {};
    }
    return hit_at(from, d, t_enter, normal);
}

}  // namespace

namespace detail {

CastHit cast_circle(Vec2 from, Vec2 to, Vec2 center, float radius) {
    const Vec2 d = to - from;
    const Vec2 f = from - center;
    const float c = dot(f, f) - radius * radius;  // > 0: from is outside
    if (c <= 0.0f) {
        const float len = length(f);
        return starts_inside(from, c == 0.0f && len > 0.0f ? Vec2{f.x / len, f.y / len} : Vec2{});
    }
    const float a = dot(d, d);
    const float b = dot(f, d);
    if (!(a > 0.0f) || b >= 0.0f) return {};  // not moving, or moving away from the centre
    const float disc = b * b - a * c;
    if (disc < 0.0f) return {};
    // The smaller root of a t^2 + 2 b t + c = 0, in the form that does not cancel (b < 0).
    const float t = c / (-b + std::sqrt(disc));
    if (!(t <= 1.0f)) return {};
    const Vec2 p = from + t * d;
    return {true, t, p, normalize_or(p - center, Vec2{1.0f, 0.0f})};
}

CastHit cast_segment(Vec2 from, Vec2 to, Vec2 a, Vec2 b) {
    const Vec2 r = to - from;
    const Vec2 s = b - a;
    const Vec2 qp = a - from;
    // The wall's normal on the side the bullet comes from (against the motion if it starts on it).
    Vec2 n = normalize_or(Vec2{s.y, -s.x}, Vec2{});
    const float side = dot(n, from - a);
    if (side < 0.0f || (side == 0.0f && dot(n, r) > 0.0f)) n = -n;
    const float denom = cross(r, s);
    if (denom != 0.0f) {
        const float t = cross(qp, s) / denom;
        const float u = cross(qp, r) / denom;
        if (!(t >= 0.0f && t <= 1.0f && u >= 0.0f && u <= 1.0f)) return {};
        if (t == 0.0f) return starts_inside(from, n);
        return hit_at(from, r, t, n);
    }
    // Parallel: a hit only when on one line; then the first end the bullet reaches.
    if (cross(qp, r) != 0.0f) return {};
    const float rr = dot(r, r);
    if (rr == 0.0f) {  // the bullet does not move: is it on the wall?
        return closest_point(Segment{a, b}, from) == from ? starts_inside(from) : CastHit{};
    }
    const float ta = dot(qp, r) / rr;
    const float tb = dot(b - from, r) / rr;
    const float lo = ta < tb ? ta : tb;
    const float hi = ta < tb ? tb : ta;
    if (hi < 0.0f || lo > 1.0f) return {};
    if (lo <= 0.0f) return starts_inside(from);
    const float len = std::sqrt(rr);
    return hit_at(from, r, lo, Vec2{-r.x / len, -r.y / len});  // the wall's end faces the bullet
}

}  // namespace detail

CastHit cast(Vec2 from, Vec2 to, const Circle& c) {
    if (!finite(from) || !finite(to) || !finite(c)) return {};
    return detail::cast_circle(from, to, c.center, c.radius);
}

CastHit cast(Vec2 from, Vec2 to, const Aabb& box) {
    if (!finite(from) || !finite(to) || !finite(box)) return {};
    return cast_box(from, to, box.min, box.max);
}

CastHit cast(Vec2 from, Vec2 to, const Obb& box) {
    // The slab test in the box's own frame; t is the same in both frames.
    if (!finite(from) || !finite(to) || !finite(box)) return {};
    const Rot q = Rot::from_angle(box.angle);
    CastHit h = cast_box(inv_rotate(q, from - box.center), inv_rotate(q, to - box.center), -box.half, box.half);
    if (!h.hit) return h;
    h.point = h.t == 0.0f ? from : from + h.t * (to - from);
    h.normal = rotate(q, h.normal);
    return h;
}

CastHit cast(Vec2 from, Vec2 to, const Polygon& poly) {
    // Cyrus-Beck: the segment enters the convex polygon at the latest entering edge and
    // leaves it at the earliest leaving edge.
    if (!finite(from) || !finite(to) || !finite(poly)) return {};
    const Vec2 d = to - from;
    float max_side = -INFINITY;
    int max_edge = 0;
    for (int i = 0; i < poly.count; ++i) {
        const float side = dot(poly.normals[i], from - poly.points[i]);
        if (side > max_side) { max_side = side; max_edge = i; }
    }
    if (max_side <= 0.0f) return starts_inside(from, max_side == 0.0f ? poly.normals[max_edge] : Vec2{});
    float t_enter = 0.0f;
    float t_exit = 1.0f;
    Vec2 normal{};
    for (int i = 0; i < poly.count; ++i) {
        const Vec2 n = poly.normals[i];
        const float num = dot(n, poly.points[i] - from);  // < 0: from is outside this edge
        const float den = dot(n, d);
        if (den == 0.0f) {
            if (num < 0.0f) return {};  // parallel to the edge, outside it
            continue;
        }
        const float t = num / den;
        if (den < 0.0f) {
            if (t > t_enter) { t_enter = t; normal = n; }
        } else if (t < t_exit) {
            t_exit = t;
        }
        if (!(t_enter <= t_exit)) return {};
    }
    return hit_at(from, d, t_enter, normal);
}

CastHit cast(Vec2 from, Vec2 to, const Segment& seg) {
    if (!finite(from) || !finite(to) || !finite(seg)) return {};
    if (seg.a == seg.b) {  // a point: hit only when the bullet's path runs through it
        const Vec2 r = to - from;
        const Vec2 qp = seg.a - from;
        if (cross(qp, r) != 0.0f) return {};
        const float rr = dot(r, r);
        if (rr == 0.0f) return qp == Vec2{} ? starts_inside(from) : CastHit{};
        const float t = dot(qp, r) / rr;
        if (!(t >= 0.0f && t <= 1.0f)) return {};
        if (t == 0.0f) return starts_inside(from);
        const float len = std::sqrt(rr);
        return hit_at(from, r, t, Vec2{-r.x / len, -r.y / len});
    }
    return detail::cast_segment(from, to, seg.a, seg.b);
}

CastHit cast(Vec2 from, Vec2 to, const PlacedMask& m) {
    // Set pixels are closed unit squares. The rows the segment crosses are visited in the
    // order it crosses them; within the first row band that holds a hit, the earliest of the
    // set squares the segment touches there wins (a later band cannot hold an earlier t).
    if (!finite(from) || !finite(to) || !m.mask || m.mask->width() == 0 || m.mask->height() == 0) return {};
    const Mask& mask = *m.mask;
    const Aabb box = bounds(m);
    const CastHit clip = cast_box(from, to, box.min, box.max);
    if (!clip.hit) return {};
    const Vec2 d = to - from;
    // The part of the segment inside the mask's rectangle: [t0, t1].
    float t1 = 1.0f;
    if (d.x != 0.0f) t1 = std::fmin(t1, std::fmax((box.min.x - from.x) / d.x, (box.max.x - from.x) / d.x));
    if (d.y != 0.0f) t1 = std::fmin(t1, std::fmax((box.min.y - from.y) / d.y, (box.max.y - from.y) / d.y));
    const float t0 = clip.t;
    const float y_a = from.y + t0 * d.y - static_cast<float>(m.y);
    const float y_b = from.y + t1 * d.y - static_cast<float>(m.y);
    const float y_lo = std::fmin(y_a, y_b), y_hi = std::fmax(y_a, y_b);
    // Rows whose closed band [j, j+1] meets [y_lo, y_hi].
    int j_first = index_of(std::ceil(y_lo)) - 1;
    int j_last = index_of(std::floor(y_hi));
    j_first = j_first < 0 ? 0 : j_first;
    j_last = j_last > mask.height() - 1 ? mask.height() - 1 : j_last;
    const bool down = d.y >= 0.0f;
    const int step = down ? 1 : -1;
    const int j_begin = down ? j_first : j_last;
    const int j_end = down ? j_last + 1 : j_first - 1;
    for (int j = j_begin; j != j_end; j += step) {
        // The segment's part in this band: the x range it covers there.
        float ta = t0, tb = t1;
        if (d.y != 0.0f) {
            const float band_lo = static_cast<float>(m.y + j), band_hi = band_lo + 1.0f;
            float u0 = (band_lo - from.y) / d.y, u1 = (band_hi - from.y) / d.y;
            if (u0 > u1) { const float tmp = u0; u0 = u1; u1 = tmp; }
            ta = std::fmax(ta, u0);
            tb = std::fmin(tb, u1);
            if (ta > tb) continue;
        }
        const float xa = from.x + ta * d.x - static_cast<float>(m.x);
        const float xb = from.x + tb * d.x - static_cast<float>(m.x);
        int i_first = index_of(std::ceil(std::fmin(xa, xb))) - 1;
        int i_last = index_of(std::floor(std::fmax(xa, xb)));
        i_first = i_first < 0 ? 0 : i_first;
        i_last = i_last > mask.width() - 1 ? mask.width() - 1 : i_last;
        CastHit best{};
        for (int i = i_first; i <= i_last; ++i) {
            if (!mask.get(i, j)) continue;
            const Vec2 lo{static_cast<float>(m.x + i), static_cast<float>(m.y + j)};
            const CastHit h = cast_box(from, to, lo, lo + Vec2{1.0f, 1.0f});
            if (h.hit && (!best.hit || h.t < best.t)) best = h;
        }
        if (best.hit) {
            if (best.t == 0.0f) best.normal = {};  // started on a set pixel
            return best;
        }
    }
    return {};
}

CastHit cast(Vec2 from, Vec2 to, const Shape& s) {
    return std::visit([&](const auto& shape) { return cast(from, to, shape); }, s);
}

}  // namespace jostle
