// Axis-aligned boxes, slides 09-6 to 09-34: translation, rotation (box of the 4 rotated
// corners, and the tight box of a rotated shape), the overlap test, the intersection region
// and the MTD.
#include "internal.h"

namespace jostle {

using detail::valid;

Aabb translate(const Aabb& box, Vec2 offset) { return {box.min + offset, box.max + offset}; }  // 09-10

Aabb rotated_bounds(std::span<const Vec2> model_points, float angle, Vec2 pivot) {
    // 09-17: rotate every point, keep the min and max. No points: the pivot itself.
    if (model_points.empty()) return {pivot, pivot};
    const Rot q = Rot::from_angle(angle);
    Aabb out{};
    for (std::size_t i = 0; i < model_points.size(); ++i) {
        const Vec2 p = rotate(q, model_points[i] - pivot) + pivot;
        out.min = i == 0 ? p : min(out.min, p);
        out.max = i == 0 ? p : max(out.max, p);
    }
    return out;
}

Aabb rotated_bounds(const Aabb& box, float angle, Vec2 pivot) {
    // 09-13: all 4 corners, since the min and max corners alone do not bound the turned box.
    const auto c = corners(box);
    return rotated_bounds(std::span<const Vec2>(c), angle, pivot);
}

bool overlaps(const Aabb& a, const Aabb& b) {
    // 09-23, written as "all four separations fail" so that NaN compares as no overlap.
    if (!valid(a) || !valid(b)) return false;
    return a.max.x >= b.min.x && a.min.x <= b.max.x && a.max.y >= b.min.y && a.min.y <= b.max.y;
}

std::optional<Aabb> intersection(const Aabb& a, const Aabb& b) {
    // 09-28: max of the mins, min of the maxes.
    if (!overlaps(a, b)) return std::nullopt;
    return Aabb{max(a.min, b.min), min(a.max, b.max)};
}

Manifold collide(const Aabb& a, const Aabb& b) {
    // 09-34 says the MTD is the smaller dimension of the intersection. That holds only when
    // neither box contains the other along the axis; in general A leaves B toward -x by
    // a.max.x - b.min.x (normal +x) and toward +x by b.max.x - a.min.x (normal -x), and the
    // same along y (A inside B needs the whole way out). Take the smallest of the four pushes.
    if (!overlaps(a, b)) return {};
    const float push_left = a.max.x - b.min.x;   // B is to the right: normal +x
    const float push_right = b.max.x - a.min.x;  // B is to the left: normal -x
    const float push_up = a.max.y - b.min.y;     // B is below (y down): normal +y
    const float push_down = b.max.y - a.min.y;
    float depth = push_left;
    Vec2 normal{1.0f, 0.0f};
    if (push_right < depth) { depth = push_right; normal = {-1.0f, 0.0f}; }
    if (push_up < depth) { depth = push_up; normal = {0.0f, 1.0f}; }
    if (push_down < depth) { depth = push_down; normal = {0.0f, -1.0f}; }
    return detail::hit_with(depth, normal);
}

}  // namespace jostle
