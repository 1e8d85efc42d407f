// FNV-1a over bytes; integers are fed little-endian so the hash does not depend on the host.
#include "jostle/core/hash.h"

namespace jostle {

void Hasher::bytes(const void* data, std::size_t size) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) {
        state_ ^= p[i];
        state_ *= 0x100000001b3ull;
    }
}

void Hasher::u32(std::uint32_t v) {
    unsigned char b[4];
    for (int i = 0; i < 4; ++i) b[i] = static_cast<unsigned char>(v >> (8 * i));
    bytes(b, 4);
}

void Hasher::u64(std::uint64_t v) {
    unsigned char b[8];
    for (int i = 0; i < 8; ++i) b[i] = static_cast<unsigned char>(v >> (8 * i));
    bytes(b, 8);
}

}  // namespace jostle
