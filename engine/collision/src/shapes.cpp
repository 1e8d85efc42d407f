// Shape construction and bookkeeping: polygon validation (make_polygon), OBB corners,
// conversions to polygons, bounds of every shape, and the shape kind names.
#include <cmath>
#include <string>

#include "internal.h"

namespace jostle {

using detail::finite;
using detail::valid;

std::optional<Polygon> make_polygon(std::span<const Vec2> points, std::string* error) {
    auto fail = [&](std::string why) -> std::optional<Polygon> {
        if (error) *error = std::move(why);
        return std::nullopt;
    };
    const int n = static_cast<int>(points.size());
    if (n < 3 || n > kMaxPolygonVertices)
        return fail("a polygon needs 3 to " + std::to_string(kMaxPolygonVertices) + " vertices, got " +
                    std::to_string(points.size()));
    for (int i = 0; i < n; ++i)
        if (!finite(points[i])) return fail("polygon vertex " + std::to_string(i) + " is not a finite point");
    for (int i = 0; i < n; ++i)
        for (int j = i + 1; j < n; ++j)
            if (points[i] == points[j])
                return fail("polygon vertices " + std::to_string(i) + " and " + std::to_string(j) + " are the same point");

    // Twice the signed area decides the winding; store with positive turns. Summed relative
    // to the first vertex: absolute coordinates far from the origin would drown the area in
    // the rounding of their products.
    float area2 = 0.0f;
    for (int i = 1; i + 1 < n; ++i) area2 += cross(points[i] - points[0], points[i + 1] - points[0]);
    if (!(area2 != 0.0f)) return fail("polygon has zero area (all vertices on one line)");

    Polygon poly;
    poly.count_ = n;
    for (int i = 0; i < n; ++i) poly.points_[i] = area2 > 0.0f ? points[i] : points[n - 1 - i];

    for (int i = 0; i < n; ++i) {
        const Vec2 p0 = poly.points_[i];
        const Vec2 e0 = poly.points_[(i + 1) % n] - p0;
        const Vec2 e1 = poly.points_[(i + 2) % n] - poly.points_[(i + 1) % n];
        const int at = (area2 > 0.0f ? (i + 1) % n : n - 1 - (i + 1) % n);
        if (!finite(e0) || !finite(e1))
            return fail("polygon vertex " + std::to_string(at) + " is farther from a neighbour than a float can hold");
        // The tests work on the edges' directions, not the edges: an edge may be as short as
        // a denormal (distinct floats always differ), and its square would underflow to 0.
        const Vec2 u0 = normalize_or(e0, Vec2{});
        const Vec2 u1 = normalize_or(e1, Vec2{});
        // The sine of the turn: less than ~1e-6 rad is collinear within float precision.
        const float turn = cross(u0, u1);
        if (std::fabs(turn) <= 1e-6f)
            return fail("polygon vertex " + std::to_string(at) + " is collinear with its neighbours");
        if (turn < 0.0f) return fail("polygon is not convex at vertex " + std::to_string(at));
        // Every vertex strictly inside this edge's half-plane: rejects self-intersecting stars,
        // whose turns all have the same sign but which wind around twice.
        for (int j = 0; j < n; ++j) {
            if (j == i || j == (i + 1) % n) continue;
            if (!(cross(u0, poly.points_[j] - p0) > 0.0f))
                return fail("polygon is not convex: it folds over itself at vertex " + std::to_string(at));
        }
        // Outward normal of a positively turning polygon: (e.y, -e.x), normalised.
        poly.normals_[i] = Vec2{u0.y, -u0.x};
    }
    return poly;
}

std::array<Vec2, 4> corners(const Aabb& box) {
    return {box.min, Vec2{box.max.x, box.min.y}, box.max, Vec2{box.min.x, box.max.y}};
}

namespace {
// 09-36 gives an OBB by its 4 corners; jostle keeps centre, half extents and angle and makes
// the corners from them: the centre plus and minus each turned half extent.
std::array<Vec2, 4> box_corners(Vec2 center, Vec2 half, Rot q) {
    const Vec2 ux = rotate(q, Vec2{half.x, 0.0f});
    const Vec2 uy = rotate(q, Vec2{0.0f, half.y});
    // -x-y, +x-y, +x+y, -x+y: positive turns, like the AABB corners.
    return {center - ux - uy, center + ux - uy, center + ux + uy, center - ux + uy};
}
}  // namespace

std::array<Vec2, 4> corners(const Obb& box) { return box_corners(box.center, box.half, box.rotation()); }

namespace {
// A polygon from 4 box corners (possibly degenerate: zero-size boxes are allowed as shapes,
// so no validation; normals come from the box axes).
Polygon box_polygon(const std::array<Vec2, 4>& c, Rot q) {
    const Vec2 normals[4] = {rotate(q, Vec2{0.0f, -1.0f}), rotate(q, Vec2{1.0f, 0.0f}), rotate(q, Vec2{0.0f, 1.0f}),
                             rotate(q, Vec2{-1.0f, 0.0f})};
    return detail::PolygonAccess::make(c, normals);
}
}  // namespace

Polygon to_polygon(const Obb& box) {
    if (!valid(box)) return {};
    const Rot q = box.rotation();
    return box_polygon(box_corners(box.center, box.half, q), q);
}

Polygon detail::centred_polygon(const Obb& box) {
    if (!valid(box)) return {};
    const Rot q = box.rotation();
    return box_polygon(box_corners({}, box.half, q), q);
}
Polygon to_polygon(const Aabb& box) { return valid(box) ? box_polygon(corners(box), Rot{}) : Polygon{}; }

Polygon Polygon::moved(Vec2 d) const {
    Polygon out = *this;
    for (int i = 0; i < count_; ++i) {
        out.points_[i] = points_[i] + d;
        if (!finite(out.points_[i])) return {};
    }
    return out;
}

void Polygon::moved_into(Vec2 d, Polygon& out) const {
    if (out.count_ != count_) {
        out = moved(d);
        return;
    }
    for (int i = 0; i < count_; ++i) {
        out.points_[i] = points_[i] + d;
        out.normals_[i] = normals_[i];
        if (!finite(out.points_[i])) {
            out = Polygon{};
            return;
        }
    }
}

namespace {
// Whether q turns without scaling, to well within float's rounding of cos and sin (and is
// finite: a NaN fails the comparison).
bool is_rotation(Rot q) { return std::fabs((q.c * q.c + q.s * q.s) - 1.0f) <= 1e-4f; }
}  // namespace

Polygon Polygon::transformed(const Transform& xf) const {
    if (!is_rotation(xf.q)) return {};
    Polygon out = *this;
    for (int i = 0; i < count_; ++i) {
        out.points_[i] = apply(xf, points_[i]);
        out.normals_[i] = rotate(xf.q, normals_[i]);
        if (!finite(out.points_[i]) || !finite(out.normals_[i])) return {};
    }
    return out;
}

Polygon Polygon::rotated(Rot q) const {
    if (!is_rotation(q)) return {};
    Polygon out = *this;
    for (int i = 0; i < count_; ++i) {
        out.points_[i] = rotate(q, points_[i]);
        out.normals_[i] = rotate(q, normals_[i]);
        if (!finite(out.points_[i]) || !finite(out.normals_[i])) return {};
    }
    return out;
}

void Polygon::rotated_into(Rot q, Polygon& out) const {
    if (out.count_ != count_ || !is_rotation(q)) {
        out = rotated(q);
        return;
    }
    for (int i = 0; i < count_; ++i) {
        out.points_[i] = rotate(q, points_[i]);
        out.normals_[i] = rotate(q, normals_[i]);
        if (!finite(out.points_[i]) || !finite(out.normals_[i])) {
            out = Polygon{};
            return;
        }
    }
}

namespace {
Aabb bounds_of_points(const Vec2* p, int n) {
    Aabb b{p[0], p[0]};
    for (int i = 1; i < n; ++i) {
        b.min = min(b.min, p[i]);
        b.max = max(b.max, p[i]);
    }
    return b;
}
}  // namespace

Aabb bounds(const Obb& box) {
    // Projected radius on each world axis: |R| * half.
    const Rot q = box.rotation();
    const Vec2 r{std::fabs(q.c) * box.half.x + std::fabs(q.s) * box.half.y,
                 std::fabs(q.s) * box.half.x + std::fabs(q.c) * box.half.y};
    return {box.center - r, box.center + r};
}
Aabb bounds(const Polygon& poly) {
    if (!valid(poly)) return {};
    return bounds_of_points(poly.points().data(), poly.count());
}
Aabb bounds(const Circle& c) {
    const Vec2 r{c.radius, c.radius};
    return {c.center - r, c.center + r};
}
Aabb bounds(const Segment& s) { return {min(s.a, s.b), max(s.a, s.b)}; }
Aabb bounds(const PlacedMask& m) {
    const Vec2 at{static_cast<float>(m.x), static_cast<float>(m.y)};
    if (!m.mask) return {at, at};
    return {at, at + Vec2{static_cast<float>(m.mask->width()), static_cast<float>(m.mask->height())}};
}
Aabb bounds(const Shape& s) {
    return std::visit(
        [](const auto& shape) -> Aabb {
            if constexpr (std::is_same_v<std::decay_t<decltype(shape)>, Aabb>)
                return shape;
            else
                return bounds(shape);
        },
        s);
}

ShapeKind kind_of(const Shape& s) { return static_cast<ShapeKind>(s.index()); }

const char* name_of(ShapeKind k) {
    switch (k) {
        case ShapeKind::aabb: return "aabb";
        case ShapeKind::obb: return "obb";
        case ShapeKind::polygon: return "polygon";
        case ShapeKind::circle: return "circle";
        case ShapeKind::segment: return "segment";
        case ShapeKind::mask: return "mask";
    }
    return "unknown";
}

}  // namespace jostle
