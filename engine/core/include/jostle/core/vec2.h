// Vec2 and Rot: the 2D vector and rotation every module uses.
// Coordinates are pixels with y pointing down (as in images); an angle is in radians,
// positive from +x toward +y (clockwise on screen).
#pragma once

#include <cmath>

namespace jostle {

struct Vec2 {
    float x = 0.0f;
    float y = 0.0f;

    constexpr Vec2& operator+=(Vec2 v) { x += v.x; y += v.y; return *this; }
    constexpr Vec2& operator-=(Vec2 v) { x -= v.x; y -= v.y; return *this; }
    constexpr Vec2& operator*=(float s) { x *= s; y *= s; return *this; }
    friend constexpr bool operator==(Vec2, Vec2) = default;
};

constexpr Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
constexpr Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
constexpr Vec2 operator-(Vec2 a) { return {-a.x, -a.y}; }
constexpr Vec2 operator*(float s, Vec2 v) { return {s * v.x, s * v.y}; }
constexpr Vec2 operator*(Vec2 v, float s) { return {s * v.x, s * v.y}; }

constexpr float dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
// z of the 3D cross product: > 0 when b turns from a toward +y (clockwise on screen).
constexpr float cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
// The lecture's perpendicular [-v_y, v_x] (09-57).
constexpr Vec2 perp(Vec2 v) { return {-v.y, v.x}; }
constexpr float length_squared(Vec2 v) { return dot(v, v); }
inline float length(Vec2 v) { return std::sqrt(dot(v, v)); }
// std::fmax and std::fmin, inline: the other argument for a NaN, else the larger (smaller),
// and for two zeros the first argument (where std::fmax's choice between -0 and +0 depends on
// whether GCC expanded it or called libm, these answer the same in every build). GCC calls
// libm for them (for NaN's sake), a call in every turn of the loops that take them per
// vertex or per pair.
constexpr float fmax_inline(float a, float b) { return (b > a || a != a) ? b : a; }
constexpr float fmin_inline(float a, float b) { return (b < a || a != a) ? b : a; }

constexpr Vec2 min(Vec2 a, Vec2 b) { return {a.x < b.x ? a.x : b.x, a.y < b.y ? a.y : b.y}; }
constexpr Vec2 max(Vec2 a, Vec2 b) { return {a.x > b.x ? a.x : b.x, a.y > b.y ? a.y : b.y}; }
inline bool is_finite(Vec2 v) { return std::isfinite(v.x) && std::isfinite(v.y); }

namespace detail {
// v / |v| for a finite, non-zero v whose squared length float cannot hold (a denormal edge
// of a valid polygon, or a vector beyond ~1.8e19): scaled by a power of two first, which
// moves only the exponent, so the direction is what it would be in exact arithmetic.
inline Vec2 normalize_rescaled(Vec2 v, Vec2 fallback) {
    if (!is_finite(v) || (v.x == 0.0f && v.y == 0.0f)) return fallback;
    const int e = std::ilogb(std::fmax(std::fabs(v.x), std::fabs(v.y)));
    const Vec2 s{std::scalbn(v.x, -e), std::scalbn(v.y, -e)};  // largest component in [1, 2)
    const float len = length(s);
    return {s.x / len, s.y / len};
}
}  // namespace detail

// v / |v|, or `fallback` when v is zero or not finite (never NaN). Exact in direction for
// every finite non-zero v, however short or long.
inline Vec2 normalize_or(Vec2 v, Vec2 fallback) {
    const float len2 = dot(v, v);
    // Outside the normal range the square lost bits (or overflowed): rare, so kept in its own
    // function, off the common path.
    if (!(len2 >= 0x1p-126f && len2 <= 0x1p127f)) [[unlikely]] return detail::normalize_rescaled(v, fallback);
    const float len = std::sqrt(len2);
    return {v.x / len, v.y / len};
}

// A rotation as cosine and sine, so a shape's angle is turned into a matrix once.
struct Rot {
    float c = 1.0f;
    float s = 0.0f;

    static Rot from_angle(float radians) { return {std::cos(radians), std::sin(radians)}; }
};

constexpr Vec2 rotate(Rot r, Vec2 v) { return {r.c * v.x - r.s * v.y, r.s * v.x + r.c * v.y}; }
constexpr Vec2 inv_rotate(Rot r, Vec2 v) { return {r.c * v.x + r.s * v.y, -r.s * v.x + r.c * v.y}; }

// A rigid placement: rotate, then translate.
struct Transform {
    Vec2 p;
    Rot q;
};

constexpr Vec2 apply(const Transform& t, Vec2 v) { return rotate(t.q, v) + t.p; }

}  // namespace jostle
