// Lines and closest points, slides 09-73 to 09-102: lines in A x + B y = C form and their
// intersection, segment-segment intersection, and the closest point on a line, a segment,
// a circle, in a box and in a polygon.
#include <cmath>

#include "internal.h"

namespace jostle {

using detail::finite;
using detail::valid;

Line line_through(Vec2 p1, Vec2 p2) {
    // 09-77
    const float a = p2.y - p1.y;
    const float b = p1.x - p2.x;
    return {a, b, a * p1.x + b * p1.y};
}

LineIntersection intersect(const Line& l1, const Line& l2) {
    // 09-74/75: det = A2 B1 - B2 A1; zero means the lines never cross once. In double: the
    // product of two floats is exact there and each difference is rounded once, so det (and
    // the same-line test) is zero exactly when it is zero in exact arithmetic. In float, lines
    // whose coefficients are tiny (through points 1e-23 apart) lost det to underflow and were
    // called coincident, and nearly parallel ones could round to parallel.
    const double a1 = l1.a, b1 = l1.b, c1 = l1.c, a2 = l2.a, b2 = l2.b, c2 = l2.c;
    const double det = a2 * b1 - b2 * a1;
    if (det == 0.0 || !std::isfinite(det)) {
        const bool degenerate = (a1 == 0.0 && b1 == 0.0) || (a2 == 0.0 && b2 == 0.0);
        // Same line when (A, B, C) of one is a multiple of the other's.
        const bool same = !degenerate && std::isfinite(det) && a1 * c2 - a2 * c1 == 0.0 && b1 * c2 - b2 * c1 == 0.0;
        return {same ? LineRelation::coincident : LineRelation::parallel, {}};
    }
    // A crossing beyond float's range (lines a rounding away from parallel) has no point to
    // report: parallel, as the header says.
    const Vec2 p{static_cast<float>((c2 * b1 - b2 * c1) / det), static_cast<float>((c1 * a2 - a1 * c2) / det)};
    if (!finite(p)) return {LineRelation::parallel, {}};
    return {LineRelation::point, p};
}

SegmentIntersection intersect(const Segment& s1, const Segment& s2) {
    // 09-78 finds the lines' crossing, then checks its x and y against both segments' ranges.
    // The same test is done here on the crossing's parameters along each segment, computed
    // from cross products: equal in exact arithmetic, but an endpoint that touches the other
    // segment gives a parameter of exactly 0 or 1 instead of a rounded coordinate. The cross
    // and dot products are taken in double (exact products, one rounding per sum), so no
    // underflow turns short segments into points or parallel ones (see intersect(Line, Line)).
    if (!valid(s1) || !valid(s2)) return {};
    const Vec2 r = s1.b - s1.a;
    const Vec2 s = s2.b - s2.a;
    const Vec2 qp = s2.a - s1.a;
    const auto cross_d = [](Vec2 u, Vec2 v) { return double{u.x} * v.y - double{u.y} * v.x; };
    const auto dot_d = [](Vec2 u, Vec2 v) { return double{u.x} * v.x + double{u.y} * v.y; };
    // s1.a + t r = s2.a + u s, solved by Cramer's rule: t = cross(qp, s) / cross(r, s),
    // u = cross(qp, r) / cross(r, s). cross(r, s) is 09-75's det with A = r.y, B = -r.x (09-77),
    // up to its sign.
    const double denom = cross_d(r, s);
    if (denom != 0.0) {
        const double t = cross_d(qp, s) / denom;
        const double u = cross_d(qp, r) / denom;
        if (!(t >= 0.0 && t <= 1.0 && u >= 0.0 && u <= 1.0)) return {};
        return {true, s1.a + static_cast<float>(t) * r};
    }
    // Parallel (09-75's det = 0), or one of them is a point.
    if (r == Vec2{}) {  // s1 is a point
        const Vec2 p = closest_point(s2, s1.a);
        return p == s1.a ? SegmentIntersection{true, s1.a} : SegmentIntersection{};
    }
    if (s == Vec2{}) {  // s2 is a point
        const Vec2 p = closest_point(s1, s2.a);
        return p == s2.a ? SegmentIntersection{true, s2.a} : SegmentIntersection{};
    }
    if (cross_d(qp, r) != 0.0) return {};  // parallel, not on one line
    // Collinear: overlap of the parameter ranges along s1.
    const double rr = dot_d(r, r);
    const double t0 = dot_d(qp, r) / rr;
    const double t1 = dot_d(s2.b - s1.a, r) / rr;
    const double lo = t0 < t1 ? t0 : t1;
    const double hi = t0 < t1 ? t1 : t0;
    if (hi < 0.0 || lo > 1.0) return {};
    if (lo <= 0.0) return {true, s1.a};
    return {true, s1.a + static_cast<float>(lo) * r};
}

namespace {
// The "no answer" of the closest points that answer a bare Vec2: {0, 0}, the point the
// ClosestPoint answers give with distance +inf, for a non-finite input or shape.
bool finite_line(const Line& l) { return std::isfinite(l.a) && std::isfinite(l.b) && std::isfinite(l.c); }
}  // namespace

Vec2 closest_point(const Line& line, Vec2 p) {
    // 09-83: the perpendicular through p is -B x + A y = C2 with C2 = -B px + A py; the
    // closest point is where it crosses the line. A degenerate line (A = B = 0) gives p.
    if (!finite_line(line) || !finite(p)) return {};
    const Line perp{-line.b, line.a, -line.b * p.x + line.a * p.y};
    const LineIntersection x = intersect(line, perp);
    if (x.kind == LineRelation::point) return x.point;
    // No crossing: the line is degenerate (its answer is p), or the foot lies past float's
    // range (no answer: {0, 0}, as for every closest point).
    return line.a == 0.0f && line.b == 0.0f ? p : Vec2{};
}

Vec2 closest_point(const Segment& seg, Vec2 p) {
    // 09-85: the closest point on the line if it lies in the segment, else the nearer
    // endpoint; as a clamped parameter along the segment, which is the same thing.
    if (!valid(seg) || !finite(p)) return {};
    const float t = detail::segment_param(seg.a, seg.b, p);
    // Inside, on the segment's line (a zero cross product): p itself, which a + t (b - a)
    // misses by t's rounding on an integer segment.
    if (t > 0.0f && t < 1.0f && cross(seg.b - seg.a, p - seg.a) == 0.0f) return p;
    return t == 1.0f ? seg.b : seg.a + t * (seg.b - seg.a);
}

Vec2 closest_point_on(const Circle& c, Vec2 q) {
    // 09-98: d = c - q, p = q + (|d| - r)/|d| d. q at the centre: every point is as near;
    // the defined answer is the one in direction +x.
    if (!valid(c) || !finite(q)) return {};
    const Vec2 d = c.center - q;
    const float len = length(d);
    if (!(len > 0.0f)) return c.center + Vec2{c.radius, 0.0f};
    if (std::isfinite(len)) return q + ((len - c.radius) / len) * d;
    // |d| beyond about 1.8e19: its square overflows (inf / inf would be NaN), and d itself may
    // (c and q near +-FLT_MAX). The same point from half of d, scaled by its largest component.
    const Vec2 h{c.center.x * 0.5f - q.x * 0.5f, c.center.y * 0.5f - q.y * 0.5f};
    const float m = std::fmax(std::fabs(h.x), std::fabs(h.y));
    const Vec2 u{h.x / m, h.y / m};
    return c.center - (c.radius / length(u)) * u;
}

namespace {
constexpr ClosestPoint kNoClosestPoint{{0.0f, 0.0f}, INFINITY};

// Far past the manual's LIMITS (a query point and a shape near opposite ends of float's
// range) a difference overflows and the answer would hold NaN or an infinite point: that is
// no answer, the same as for a non-finite input. An infinite distance alone is kept.
ClosestPoint defined(ClosestPoint c) {
    return finite(c.point) && !std::isnan(c.distance) ? c : kNoClosestPoint;
}

ClosestPoint closest_in_box(Vec2 lo, Vec2 hi, Vec2 q) {
    // 09-102: "push in" the point along each axis.
    const Vec2 p{detail::clamp(q.x, lo.x, hi.x), detail::clamp(q.y, lo.y, hi.y)};
    return {p, length(q - p)};
}
}  // namespace

ClosestPoint closest_point(const Aabb& box, Vec2 q) {
    if (!valid(box) || !finite(q)) return kNoClosestPoint;
    return defined(closest_in_box(box.min, box.max, q));
}

ClosestPoint closest_point(const Obb& box, Vec2 q) {
    if (!valid(box) || !finite(q)) return kNoClosestPoint;
    const Rot r = box.rotation();
    const ClosestPoint local = closest_in_box(-box.half, box.half, inv_rotate(r, q - box.center));
    if (local.distance == 0.0f) return {q, 0.0f};
    return defined({rotate(r, local.point) + box.center, local.distance});
}

bool contains(const Polygon& poly, Vec2 q) {
    if (!detail::valid(poly)) return false;
    for (int i = 0; i < poly.count(); ++i)
        if (!(dot(poly.normals()[i], q - poly.points()[i]) <= 0.0f)) return false;
    return poly.count() >= 3;
}

Vec2 closest_point_on_boundary(const Polygon& poly, Vec2 q, int* edge) {
    // 09-90: the nearest of the closest points on every edge. No boundary (the empty
    // Polygon), a non-finite q or an answer past float's range: {0, 0} on edge -1.
    int nearest = -1;
    Vec2 point{};
    if (valid(poly) && finite(q)) {
        point = q - detail::offset_from_boundary(poly, q, &nearest);
        if (!finite(point)) {
            point = {};
            nearest = -1;
        }
    }
    if (edge) *edge = nearest;
    return point;
}

ClosestPoint closest_point(const Polygon& poly, Vec2 q) {
    if (!valid(poly) || !finite(q)) return kNoClosestPoint;
    if (contains(poly, q)) return {q, 0.0f};
    int edge = 0;
    const Vec2 offset = detail::offset_from_boundary(poly, q, &edge);
    return defined({q - offset, length(offset)});
}

ClosestPoint closest_point(const Circle& c, Vec2 q) {
    if (!valid(c) || !finite(q)) return kNoClosestPoint;
    if (length_squared(q - c.center) <= c.radius * c.radius) return {q, 0.0f};
    const Vec2 p = closest_point_on(c, q);
    return defined({p, length(q - p)});
}

ClosestPoint closest_point(const Shape& s, Vec2 q) {
    return std::visit(
        [&](const auto& shape) -> ClosestPoint {
            using T = std::decay_t<decltype(shape)>;
            if constexpr (std::is_same_v<T, Segment>) {
                if (!valid(shape) || !finite(q)) return kNoClosestPoint;
                return defined({closest_point(shape, q), length(detail::offset_from_segment(shape.a, shape.b, q))});
            } else {
                return closest_point(shape, q);
            }
        },
        s);
}

}  // namespace jostle
