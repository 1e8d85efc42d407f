// The compiler and flags keep float arithmetic as written: the determinism rules depend on
// it (no contraction into fused multiply-add, no dropped roundings).
#include <gtest/gtest.h>

#include <cmath>

namespace {

struct D2 {
    double x, y;
};
struct F2 {
    float x, y;
};

// A pair of double -> float -> double conversions. GCC 12.2's SLP vectorizer compiles this
// to a plain copy at -O2, losing the rounding; CMakeLists.txt turns that pass off for GCC.
[[gnu::noinline]] D2 round_through_float(D2 p) {
    const F2 f{static_cast<float>(p.x), static_cast<float>(p.y)};
    return {f.x, f.y};
}

// a * b + c with a rounding after the product; contraction into an FMA would skip it.
[[gnu::noinline]] float multiply_add(float a, float b, float c) { return a * b + c; }

}  // namespace

TEST(Compiler, DoubleToFloatRoundTripRounds) {
    volatile double x = 0.1, y = 0.2;  // volatile: computed at run time, not folded
    const D2 r = round_through_float({x, y});
    EXPECT_EQ(r.x, static_cast<double>(0.1f));
    EXPECT_EQ(r.y, static_cast<double>(0.2f));
    EXPECT_NE(r.x, 0.1);
}

TEST(Compiler, NoFusedMultiplyAdd) {
    // 1 + 2^-12 squared is 1 + 2^-11 + 2^-24; the float product rounds the 2^-24 away, so
    // minus (1 + 2^-11) is exactly 0. A fused multiply-add would keep it: 2^-24.
    volatile float a = 1.0f + std::ldexp(1.0f, -12);
    volatile float c = -(1.0f + std::ldexp(1.0f, -11));
    EXPECT_EQ(multiply_add(a, a, c), 0.0f);
}
