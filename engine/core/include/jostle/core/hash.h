// Hashing of exact bytes (FNV-1a, 64-bit) for state hashes and file fingerprints.
// The same bytes give the same hash on every build; floats are hashed by their bit pattern.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace jostle {

class Hasher {
public:
    void bytes(const void* data, std::size_t size);
    void u32(std::uint32_t v);
    void u64(std::uint64_t v);
    void f32(float v) { u32(std::bit_cast<std::uint32_t>(v)); }
    void str(std::string_view s) { u64(s.size()); bytes(s.data(), s.size()); }
    std::uint64_t value() const { return state_; }

private:
    std::uint64_t state_ = 0xcbf29ce484222325ull;
};

}  // namespace jostle
