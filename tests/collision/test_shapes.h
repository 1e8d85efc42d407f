// Shared helpers for the collision tests: float comparisons, miss checks and seeded random
// shape generators (jostle::Rng), on top of oracle.h (shape translation, the independent
// double-precision oracle, describe).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <numbers>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include "jostle/collision.h"
#include "jostle/core/rng.h"
#include "oracle.h"

namespace jostle::test {

inline constexpr float kPi = std::numbers::pi_v<float>;
inline constexpr float kSqrt2 = std::numbers::sqrt2_v<float>;
inline constexpr float kNan = std::numeric_limits<float>::quiet_NaN();
inline constexpr float kInf = std::numeric_limits<float>::infinity();

// ---------------------------------------------------------------------------------------
// Assertions
// ---------------------------------------------------------------------------------------

inline ::testing::AssertionResult vec_near(Vec2 actual, Vec2 expected, float tol) {
    if (std::fabs(actual.x - expected.x) <= tol && std::fabs(actual.y - expected.y) <= tol) {
        return ::testing::AssertionSuccess();
    }
    return ::testing::AssertionFailure() << "(" << actual.x << ", " << actual.y << ") is not within " << tol
                                         << " of (" << expected.x << ", " << expected.y << ")";
}

#define EXPECT_VEC_NEAR(actual, expected, tol) EXPECT_TRUE(::jostle::test::vec_near((actual), (expected), (tol)))

inline ::testing::AssertionResult is_unit(Vec2 v, float tol = 1e-5f) {
    const float len = std::sqrt(v.x * v.x + v.y * v.y);
    if (std::isfinite(len) && std::fabs(len - 1.0f) <= tol) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "(" << v.x << ", " << v.y << ") has length " << len;
}

inline ::testing::AssertionResult is_miss(const Manifold& m) {
    if (!m.hit && m.depth == 0.0f && m.normal.x == 0.0f && m.normal.y == 0.0f) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "expected a miss with all zeros, got hit=" << m.hit << " depth=" << m.depth
                                         << " normal=(" << m.normal.x << ", " << m.normal.y << ")";
}

inline ::testing::AssertionResult is_miss(const CastHit& h) {
    if (!h.hit && h.t == 0.0f && h.point == Vec2{} && h.normal == Vec2{}) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "expected a miss with all zeros, got hit=" << h.hit << " t=" << h.t
                                         << " point=(" << h.point.x << ", " << h.point.y << ") normal=("
                                         << h.normal.x << ", " << h.normal.y << ")";
}

inline ::testing::AssertionResult is_miss(const SweepHit& h) {
    if (!h.hit && h.t == 0.0f && h.point == Vec2{} && h.normal == Vec2{}) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "expected a miss with all zeros, got hit=" << h.hit << " t=" << h.t
                                         << " point=(" << h.point.x << ", " << h.point.y << ") normal=("
                                         << h.normal.x << ", " << h.normal.y << ")";
}

// A manifold that is a hit with the given depth and normal.
inline ::testing::AssertionResult is_hit(const Manifold& m, float depth, Vec2 normal, float tol = 1e-5f) {
    if (m.hit && std::fabs(m.depth - depth) <= tol && std::fabs(m.normal.x - normal.x) <= tol &&
        std::fabs(m.normal.y - normal.y) <= tol) {
        return ::testing::AssertionSuccess();
    }
    return ::testing::AssertionFailure() << "expected hit depth " << depth << " normal (" << normal.x << ", "
                                         << normal.y << "), got hit=" << m.hit << " depth=" << m.depth << " normal=("
                                         << m.normal.x << ", " << m.normal.y << ")";
}

inline Manifold flipped(Manifold m) {
    m.normal = -m.normal;
    return m;
}

// ---------------------------------------------------------------------------------------
// Building shapes
// ---------------------------------------------------------------------------------------

inline Polygon polygon_or_die(std::initializer_list<Vec2> pts) {
    std::vector<Vec2> v(pts);
    std::string error;
    auto p = make_polygon(v, &error);
    EXPECT_TRUE(p.has_value()) << error;
    return p.value_or(Polygon{});
}

inline Polygon box_polygon(float x0, float y0, float x1, float y1) {
    return polygon_or_die({{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}});
}

// A cast or sweep result with the given t, point and normal (both have hit, t, point, normal).
template <class Contact>
::testing::AssertionResult is_contact(const Contact& h, float t, Vec2 point, Vec2 normal, float tol = 1e-5f,
                                      float point_tol = 1e-4f) {
    if (h.hit && std::fabs(h.t - t) <= tol && vec_near(h.point, point, point_tol) && vec_near(h.normal, normal, tol)) {
        return ::testing::AssertionSuccess();
    }
    return ::testing::AssertionFailure() << "expected t " << t << " point (" << point.x << ", " << point.y
                                         << ") normal (" << normal.x << ", " << normal.y << "), got hit=" << h.hit
                                         << " t=" << h.t << " point=(" << h.point.x << ", " << h.point.y
                                         << ") normal=(" << h.normal.x << ", " << h.normal.y << ")";
}
inline ::testing::AssertionResult is_cast(const CastHit& h, float t, Vec2 point, Vec2 normal, float tol = 1e-5f,
                                          float point_tol = 1e-4f) {
    return is_contact(h, t, point, normal, tol, point_tol);
}
inline ::testing::AssertionResult is_sweep(const SweepHit& h, float t, Vec2 point, Vec2 normal, float tol = 1e-5f,
                                           float point_tol = 1e-4f) {
    return is_contact(h, t, point, normal, tol, point_tol);
}

// ---------------------------------------------------------------------------------------
// Seeded random shapes
// ---------------------------------------------------------------------------------------

inline Vec2 random_point(Rng& rng, float extent) { return {rng.uniform(-extent, extent), rng.uniform(-extent, extent)}; }

inline Aabb random_aabb(Rng& rng, float extent = 20.0f) {
    const Vec2 c = random_point(rng, extent);
    const Vec2 h{rng.uniform(0.5f, 10.0f), rng.uniform(0.5f, 10.0f)};
    return {c - h, c + h};
}

inline Obb random_obb(Rng& rng, float extent = 20.0f) {
    return {random_point(rng, extent), {rng.uniform(0.5f, 10.0f), rng.uniform(0.5f, 10.0f)}, rng.uniform(-kPi, kPi)};
}

inline Circle random_circle(Rng& rng, float extent = 20.0f) {
    return {random_point(rng, extent), rng.uniform(0.5f, 10.0f)};
}

inline Segment random_segment(Rng& rng, float extent = 20.0f) {
    const Vec2 a = random_point(rng, extent);
    const float len = rng.uniform(1.0f, 20.0f);
    const float ang = rng.uniform(-kPi, kPi);
    return {a, a + Vec2{len * std::cos(ang), len * std::sin(ang)}};
}

// A convex polygon: points spread around an ellipse, then rotated and placed; 3..8 vertices.
inline Polygon random_polygon(Rng& rng, float extent = 20.0f) {
    for (int attempt = 0; attempt < 1000; ++attempt) {
        const int n = 3 + static_cast<int>(rng.below(6));
        const float step = 2.0f * kPi / static_cast<float>(n);
        const float base = rng.uniform(0.0f, 2.0f * kPi);
        const float rx = rng.uniform(1.0f, 10.0f);
        const float ry = rx * rng.uniform(0.3f, 1.0f);
        const Rot rot = Rot::from_angle(rng.uniform(-kPi, kPi));
        const Vec2 c = random_point(rng, extent);
        std::vector<Vec2> pts;
        for (int i = 0; i < n; ++i) {
            const float a = base + step * (static_cast<float>(i) + rng.uniform(-0.3f, 0.3f));
            pts.push_back(c + rotate(rot, Vec2{rx * std::cos(a), ry * std::sin(a)}));
        }
        if (rng.below(2) == 0) std::reverse(pts.begin(), pts.end());
        if (auto p = make_polygon(pts)) return *p;
        // Rejection is possible only for nearly collinear points; make_polygon tests cover it.
    }
    ADD_FAILURE() << "make_polygon rejected 1000 random convex polygons in a row";
    return box_polygon(0, 0, 1, 1);
}

// The polygon `base` made again every way the module makes polygons: the box conversions (a
// box of half size `half` at `shift`, turned by `angle`), moved, moved_into and rotated_into
// into a polygon of another count and of the same count (`reused`, whose count the caller
// changes between calls), rotated and transformed. The SIMD paths read the slots past a
// polygon's vertices and count on them being zero, whichever way it was made.
inline std::vector<Polygon> polygons_made_every_way(const Polygon& base, Vec2 shift, float angle, Vec2 half,
                                                    Polygon& reused) {
    const Transform xf{shift, Rot::from_angle(angle)};
    Polygon turned_other_count = to_polygon(Aabb{shift, shift + Vec2{2.0f, 3.0f}});
    base.rotated_into(xf.q, turned_other_count);  // another count, unless base has 4 vertices
    base.moved_into(shift, reused);
    const Polygon moved_other_count = reused;
    base.moved_into(-shift, reused);  // the same count: only the vertices are written
    Polygon turned_same_count = reused;
    base.rotated_into(xf.q, turned_same_count);
    return {base,
            to_polygon(Obb{shift, half, angle}),
            to_polygon(Aabb{shift, shift + Vec2{2.0f, 3.0f}}),
            base.moved(shift),
            moved_other_count,
            reused,
            base.rotated(xf.q),
            turned_other_count,
            turned_same_count,
            base.transformed(xf)};
}

enum class Kind { aabb, obb, polygon, circle, segment };
inline constexpr Kind kAllKinds[] = {Kind::aabb, Kind::obb, Kind::polygon, Kind::circle, Kind::segment};

inline Shape random_shape(Rng& rng, Kind k, float extent = 20.0f) {
    switch (k) {
        case Kind::aabb: return random_aabb(rng, extent);
        case Kind::obb: return random_obb(rng, extent);
        case Kind::polygon: return random_polygon(rng, extent);
        case Kind::circle: return random_circle(rng, extent);
        case Kind::segment: return random_segment(rng, extent);
    }
    return Aabb{};
}

inline const char* kind_name(Kind k) {
    switch (k) {
        case Kind::aabb: return "aabb";
        case Kind::obb: return "obb";
        case Kind::polygon: return "polygon";
        case Kind::circle: return "circle";
        case Kind::segment: return "segment";
    }
    return "?";
}

}  // namespace jostle::test
