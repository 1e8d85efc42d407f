// One entry point for any two shapes: collide(Shape, Shape) and overlaps(Shape, Shape) pick
// the typed function from the header's pair table; the reverse order swaps the arguments
// and flips the normal.
#include <type_traits>
#include <variant>

#include "internal.h"

namespace jostle {

using detail::flipped;

namespace {

// The variant's index is the kind (ShapeKind lists the alternatives in order); read here
// rather than through kind_of, which lives in another file and would be a call per shape.
ShapeKind kind(const Shape& s) { return static_cast<ShapeKind>(s.index()); }
template <ShapeKind K, class T>
constexpr bool kind_is = std::is_same_v<std::variant_alternative_t<static_cast<std::size_t>(K), Shape>, T>;
static_assert(kind_is<ShapeKind::aabb, Aabb> && kind_is<ShapeKind::obb, Obb> && kind_is<ShapeKind::polygon, Polygon> &&
              kind_is<ShapeKind::circle, Circle> && kind_is<ShapeKind::segment, Segment> &&
              kind_is<ShapeKind::mask, PlacedMask>);

// Every unordered pair once, in the pair table's row order (A's kind <= B's kind).
Manifold ordered(const Shape& a, const Shape& b) {
    const ShapeKind ka = kind(a), kb = kind(b);
    using K = ShapeKind;
    switch (ka) {
        case K::aabb: {
            const Aabb& x = std::get<Aabb>(a);
            switch (kb) {
                case K::aabb: return collide(x, std::get<Aabb>(b));
                case K::obb: return collide(x, std::get<Obb>(b));
                case K::polygon: return collide(x, std::get<Polygon>(b));
                case K::circle: return collide(x, std::get<Circle>(b));
                case K::segment: return collide(x, std::get<Segment>(b));
                case K::mask: return flipped(collide(std::get<PlacedMask>(b), x));
            }
            break;
        }
        case K::obb: {
            const Obb& x = std::get<Obb>(a);
            switch (kb) {
                case K::obb: return collide(x, std::get<Obb>(b));
                case K::polygon: return collide(x, std::get<Polygon>(b));
                case K::circle: return collide(x, std::get<Circle>(b));
                case K::segment: return collide(x, std::get<Segment>(b));
                case K::mask: return flipped(collide(std::get<PlacedMask>(b), x));
                default: break;
            }
            break;
        }
        case K::polygon: {
            const Polygon& x = std::get<Polygon>(a);
            switch (kb) {
                case K::polygon: return collide(x, std::get<Polygon>(b));
                case K::circle: return collide(x, std::get<Circle>(b));
                case K::segment: return collide(x, std::get<Segment>(b));
                case K::mask: return flipped(collide(std::get<PlacedMask>(b), x));
                default: break;
            }
            break;
        }
        case K::circle: {
            const Circle& x = std::get<Circle>(a);
            switch (kb) {
                case K::circle: return collide(x, std::get<Circle>(b));
                case K::segment: return flipped(collide(std::get<Segment>(b), x));
                case K::mask: return flipped(collide(std::get<PlacedMask>(b), x));
                default: break;
            }
            break;
        }
        case K::segment: {
            const Segment& x = std::get<Segment>(a);
            switch (kb) {
                case K::segment: return collide(x, std::get<Segment>(b));
                case K::mask: return flipped(collide(std::get<PlacedMask>(b), x));
                default: break;
            }
            break;
        }
        case K::mask:
            if (kb == K::mask) return collide(std::get<PlacedMask>(a), std::get<PlacedMask>(b));
            break;
    }
    return {};  // unreachable: ordered() is only called with kind(a) <= kind(b)
}

}  // namespace

Manifold collide(const Shape& a, const Shape& b) {
    if (kind(a) <= kind(b)) return ordered(a, b);
    return flipped(ordered(b, a));
}

bool overlaps(const Shape& a, const Shape& b) {
    // The cheap yes/no where one exists; otherwise the full test's answer.
    if (const auto* x = std::get_if<Aabb>(&a))
        if (const auto* y = std::get_if<Aabb>(&b)) return overlaps(*x, *y);
    // A mask stops at its first shared pixel instead of searching for the MTD.
    if (const auto* x = std::get_if<PlacedMask>(&a)) return first_overlap(*x, b).has_value();
    if (const auto* y = std::get_if<PlacedMask>(&b)) return first_overlap(*y, a).has_value();
    return collide(a, b).hit;
}

}  // namespace jostle
