// tests/fuzz/fuzz_support.h: what the fuzz targets share. A target defines
// LLVMFuzzerTestOneInput; a broken property is reported by fuzz_fail (message, then abort, which
// libFuzzer and the corpus replay both count as a crash). Bad input is expected: the parsers'
// InputError is caught by the target; any other exception escapes and terminates (a crash).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace jostle::fuzz {

[[noreturn]] inline void fuzz_fail(const std::string& what) {
    std::fprintf(stderr, "fuzz property failed: %s\n", what.c_str());
    std::fflush(stderr);
    std::abort();
}

}  // namespace jostle::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);
