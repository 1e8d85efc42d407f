// Shared by the bit-for-bit tests (circle_bits_test, sat_bits_test), which hold the
// lane-parallel collision code to the plain scalar loops it replaced: the scalar side of
// hit_with, the comparison of two Manifolds' bits, and seeded draws that now and then give
// a value past the limits.
#pragma once

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>

#include "test_shapes.h"

namespace jostle::test {

// hit_with: a non-finite answer is a miss; the depth is clamped at 0 and -0 components become +0.
inline Manifold scalar_hit(float depth, Vec2 n) {
    if (!(std::isfinite(depth) && std::isfinite(n.x) && std::isfinite(n.y))) return {};
    return {true, depth > 0.0f ? depth : 0.0f, {n.x + 0.0f, n.y + 0.0f}};
}

inline ::testing::AssertionResult same_bits(const Manifold& got, const Manifold& want) {
    const auto bits = [](float v) { return std::bit_cast<std::uint32_t>(v); };
    if (got.hit == want.hit && bits(got.depth) == bits(want.depth) && bits(got.normal.x) == bits(want.normal.x) &&
        bits(got.normal.y) == bits(want.normal.y))
        return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "got hit " << got.hit << " depth " << got.depth << " normal (" << got.normal.x
                                         << ", " << got.normal.y << "), the scalar loops give hit " << want.hit
                                         << " depth " << want.depth << " normal (" << want.normal.x << ", "
                                         << want.normal.y << ")";
}

// Seeded draws; wild(v) is, one time in `wild_one_in`, a value past the limits instead of v.
struct BitsDraw {
    BitsDraw(std::uint32_t seed, int wild_one_in) : rng(seed), wild_odds(wild_one_in) {}
    float uniform(float lo, float hi) { return std::uniform_real_distribution<float>(lo, hi)(rng); }
    int below(int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng); }
    float wild(float v) {
        constexpr float kValues[] = {kNan, kInf, -kInf, 0.0f, -0.0f, 3e38f, -3e38f, 2e19f, 1e-40f, -1.0f};
        return below(wild_odds) == 0 ? kValues[below(10)] : v;
    }
    std::mt19937 rng;
    int wild_odds;
};

}  // namespace jostle::test
