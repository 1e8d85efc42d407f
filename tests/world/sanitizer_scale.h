// How much the world tests divide their heaviest counts by: 1 in Release (and Debug), which
// always run the full counts the issues require, and 10 under AddressSanitizer, which runs
// 5-10x slower (GCC defines __SANITIZE_ADDRESS__; clang answers __has_feature).
#pragma once

#if defined(__SANITIZE_ADDRESS__)
#define JOSTLE_TEST_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define JOSTLE_TEST_UNDER_ASAN 1
#endif
#endif

#if defined(JOSTLE_TEST_UNDER_ASAN)
inline constexpr int kSanitizerDivisor = 10;
#else
inline constexpr int kSanitizerDivisor = 1;
#endif
