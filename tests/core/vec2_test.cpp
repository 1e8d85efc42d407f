// Vec2 helpers (core/vec2.h): normalize_or keeps the exact direction of every finite
// non-zero vector, including those whose squared length float cannot hold; the inline
// fmax and fmin answer as the library does.
#include <gtest/gtest.h>

#include <bit>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <limits>

#include "jostle/core/vec2.h"

namespace jostle {
namespace {

bool same_bits(Vec2 a, Vec2 b) {
    return std::bit_cast<std::uint32_t>(a.x) == std::bit_cast<std::uint32_t>(b.x) &&
           std::bit_cast<std::uint32_t>(a.y) == std::bit_cast<std::uint32_t>(b.y);
}

TEST(NormalizeOr, OrdinaryVectorsAreDividedByTheirLength) {
    for (const Vec2 v : {Vec2{3, 4}, Vec2{-1e-3f, 2e-3f}, Vec2{1e15f, -7e14f}, Vec2{0, -5}, Vec2{1e-18f, 0}}) {
        const float len = std::sqrt(v.x * v.x + v.y * v.y);
        EXPECT_TRUE(same_bits(normalize_or(v, Vec2{9, 9}), Vec2{v.x / len, v.y / len})) << v.x << ", " << v.y;
    }
}

TEST(NormalizeOr, DenormalAndHugeVectorsKeepTheirDirection) {
    // The squares of these underflow to 0 (or lose bits as denormals) or overflow to inf.
    // Expected: the direction of the float input, worked out in double.
    const float tiny = std::numeric_limits<float>::denorm_min();
    for (const Vec2 v : {Vec2{0, -1.7937e-41f}, Vec2{tiny, 0}, Vec2{-tiny, -tiny}, Vec2{3e-40f, 4e-40f}, Vec2{3e-22f, -4e-22f},
                         Vec2{FLT_MAX, FLT_MAX}, Vec2{-3e30f, 4e30f}, Vec2{FLT_MAX, tiny}, Vec2{1e-44f, -1e-41f}}) {
        const double x = v.x, y = v.y, len = std::hypot(x, y);
        const Vec2 u = normalize_or(v, Vec2{9, 9});
        EXPECT_NEAR(u.x, x / len, 1.2e-7) << v.x << ", " << v.y;
        EXPECT_NEAR(u.y, y / len, 1.2e-7) << v.x << ", " << v.y;
    }
}

TEST(NormalizeOr, ZeroAndNonFiniteGiveTheFallback) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    for (const Vec2 v : {Vec2{}, Vec2{-0.0f, 0.0f}, Vec2{nan, 1}, Vec2{1, nan}, Vec2{inf, 0}, Vec2{-inf, inf}, Vec2{1, -inf}})
        EXPECT_TRUE(same_bits(normalize_or(v, Vec2{9, 8}), Vec2{9, 8})) << v.x << ", " << v.y;
}

// fmax_inline and fmin_inline answer as std::fmax and std::fmin do (the other argument for a
// NaN), and for two zeros the first argument, whatever their signs.
TEST(InlineMinMax, TheLibrarysAnswersWithTheFirstOfTwoZeros) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float values[] = {0.0f, -0.0f, 1.0f, -1.0f, 2.5f, INFINITY, -INFINITY, nan, 1e-45f};
    const auto bits = [](float v) { return std::bit_cast<std::uint32_t>(v); };
    for (const float a : values) {
        for (const float b : values) {
            volatile float va = a, vb = b;  // the library's answer, not a folded constant
            const float max = std::fmax(va, vb), min = std::fmin(va, vb);
            if (a == 0.0f && b == 0.0f) {
                EXPECT_EQ(bits(fmax_inline(a, b)), bits(a)) << "fmax(" << a << ", " << b << ")";
                EXPECT_EQ(bits(fmin_inline(a, b)), bits(a)) << "fmin(" << a << ", " << b << ")";
                continue;
            }
            if (std::isnan(max)) {
                EXPECT_TRUE(std::isnan(fmax_inline(a, b))) << a << ", " << b;
            } else {
                EXPECT_EQ(bits(fmax_inline(a, b)), bits(max)) << "fmax(" << a << ", " << b << ")";
            }
            if (std::isnan(min)) {
                EXPECT_TRUE(std::isnan(fmin_inline(a, b))) << a << ", " << b;
            } else {
                EXPECT_EQ(bits(fmin_inline(a, b)), bits(min)) << "fmin(" << a << ", " << b << ")";
            }
        }
    }
}

}  // namespace
}  // namespace jostle
