// Seeded random numbers (PCG32): the world's RNG and the tests' random inputs.
// Same seed, same sequence, on every build. No global state: each user owns its Rng.
#pragma once

#include <cstdint>

namespace jostle {

class Rng {
public:
    explicit Rng(std::uint64_t seed = 0x853c49e6748fea9bull, std::uint64_t stream = 0xda3e39cb94b95bdbull) {
        inc_ = (stream << 1u) | 1u;
        next_u32();
        state_ += seed;
        next_u32();
    }

    std::uint32_t next_u32() {
        const std::uint64_t old = state_;
        state_ = old * 6364136223846793005ull + inc_;
        const auto xorshifted = static_cast<std::uint32_t>(((old >> 18u) ^ old) >> 27u);
        const auto rot = static_cast<std::uint32_t>(old >> 59u);
        return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
    }

    // Uniform in [0, 1): 24 random bits, exact in a float.
    float next_float() { return static_cast<float>(next_u32() >> 8) * (1.0f / 16777216.0f); }
    // Uniform in [lo, hi).
    float uniform(float lo, float hi) { return lo + (hi - lo) * next_float(); }
    // Uniform integer in [0, n), n > 0 (Lemire's method, unbiased).
    std::uint32_t below(std::uint32_t n) {
        std::uint64_t m = std::uint64_t{next_u32()} * n;
        auto low = static_cast<std::uint32_t>(m);
        if (low < n) {
            const std::uint32_t threshold = (0u - n) % n;
            while (low < threshold) {
                m = std::uint64_t{next_u32()} * n;
                low = static_cast<std::uint32_t>(m);
            }
        }
        return static_cast<std::uint32_t>(m >> 32);
    }

    std::uint64_t state() const { return state_; }
    std::uint64_t stream() const { return inc_; }

private:
    std::uint64_t state_ = 0;
    std::uint64_t inc_ = 0;
};

}  // namespace jostle
