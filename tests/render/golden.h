// Golden-image checks for tests: compare a rendered image with a committed PNG under
// tests/data/golden/, or (re)write that PNG when asked to. Any test suite can use it:
//
//     EXPECT_TRUE(jostle::matches_golden(image, "sprite_rotations"));
//
// JOSTLE_UPDATE_GOLDEN=1       writes the image as the golden (atomically) instead of comparing;
//                              the check passes and says which file it updated. Look at every
//                              updated PNG before committing it.
// JOSTLE_GOLDEN_TOLERANCE=<n>  a pixel differs when one of its channels differs by more than n
//                              (0..255; default kGoldenChannelTolerance, 0: exact). For machines
//                              whose OpenGL rounds differently from the one that made the goldens.
// A missing golden fails, saying how to create it. A mismatch writes the actual image and a
// diff image (differing pixels in red) to $TEST_UNDECLARED_OUTPUTS_DIR, or to the folder
// jostle-golden in gtest's TempDir() when that is not set, and the failure names both files.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <string_view>

#include "jostle/render/image_compare.h"
#include "jostle/render/png_io.h"

#ifndef JOSTLE_TEST_DATA
#error "golden.h needs JOSTLE_TEST_DATA (the tests/data folder) defined for the test binary"
#endif

namespace jostle {

// Exact match by default: the goldens were made with Mesa's llvmpipe on Debian 12, and a
// renderer change that moves any channel of any pixel should be seen and re-blessed.
inline constexpr int kGoldenChannelTolerance = 0;

namespace golden_detail {

inline bool env_is(const char* name, std::string_view value) {
    const char* v = std::getenv(name);
    return v != nullptr && std::string_view(v) == value;
}

// kGoldenChannelTolerance, or JOSTLE_GOLDEN_TOLERANCE when set; nullopt when it is set to
// something other than a whole number 0..255 (a typo must not silently mean "exact").
inline std::optional<int> channel_tolerance() {
    const char* v = std::getenv("JOSTLE_GOLDEN_TOLERANCE");
    if (v == nullptr || *v == '\0') return kGoldenChannelTolerance;
    int n = 0;
    for (const char* p = v; *p != '\0'; ++p) {
        if (*p < '0' || *p > '9' || n > 255) return std::nullopt;
        n = n * 10 + (*p - '0');
    }
    if (n > 255) return std::nullopt;
    return n;
}

inline std::filesystem::path output_dir() {
    const char* v = std::getenv("TEST_UNDECLARED_OUTPUTS_DIR");
    if (v != nullptr && *v != '\0') return v;
    return std::filesystem::path(::testing::TempDir()) / "jostle-golden";
}

}  // namespace golden_detail

// Where the golden called `name` lives: tests/data/golden/<name>.png.
inline std::filesystem::path golden_path(std::string_view name) {
    return std::filesystem::path(JOSTLE_TEST_DATA) / "golden" / (std::string(name) + ".png");
}

// Checks `actual` against the golden `name` (letters, digits, '_' and '-'), as described at
// the top of this file.
inline ::testing::AssertionResult matches_golden(const Image& actual, std::string_view name) {
    if (name.empty() || name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_-") != std::string_view::npos) {
        return ::testing::AssertionFailure() << "golden name \"" << name << "\": use lower-case letters, digits, '_' and '-'";
    }
    const std::filesystem::path path = golden_path(name);
    const std::string update_hint = "run the test with JOSTLE_UPDATE_GOLDEN=1 to write it, then look at " + path.string() +
                                    " and commit it only if the picture is right";

    if (golden_detail::env_is("JOSTLE_UPDATE_GOLDEN", "1")) {
        try {
            std::filesystem::create_directories(path.parent_path());
            write_png_atomic(path.string(), actual, 9);
        } catch (const std::exception& e) {
            return ::testing::AssertionFailure() << "JOSTLE_UPDATE_GOLDEN=1: cannot write " << path.string() << ": " << e.what();
        }
        std::cout << "[ GOLDEN   ] updated " << path.string() << " (" << actual.width << "x" << actual.height << ")\n";
        ::testing::Test::RecordProperty("golden_updated", path.string());
        return ::testing::AssertionSuccess() << "updated " << path.string();
    }

    const std::optional<int> tolerance = golden_detail::channel_tolerance();
    if (!tolerance) {
        return ::testing::AssertionFailure() << "JOSTLE_GOLDEN_TOLERANCE=\"" << std::getenv("JOSTLE_GOLDEN_TOLERANCE")
                                             << "\": expected a whole number 0..255 (the largest channel difference allowed)";
    }
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) {
        return ::testing::AssertionFailure() << "golden " << path.string() << " does not exist; " << update_hint;
    }
    Image expected;
    try {
        expected = read_png(path.string());
    } catch (const std::exception& e) {
        return ::testing::AssertionFailure() << "cannot read golden: " << e.what() << "; " << update_hint;
    }

    const CompareResult result = compare_images(expected, actual, {.max_channel_delta = *tolerance, .max_differing_pixels = 0});
    if (result.within_tolerance) return ::testing::AssertionSuccess() << "matches " << path.string();

    ::testing::AssertionResult failure = ::testing::AssertionFailure();
    failure << "image differs from golden " << path.string() << ": expected " << expected.width << "x" << expected.height
            << ", got " << actual.width << "x" << actual.height << "; " << result.differing_pixels
            << " pixel(s) differ by more than " << *tolerance << " (JOSTLE_GOLDEN_TOLERANCE), largest channel difference "
            << result.max_channel_delta << ".";
    const std::filesystem::path dir = golden_detail::output_dir();
    const std::filesystem::path actual_path = dir / (std::string(name) + ".actual.png");
    const std::filesystem::path diff_path = dir / (std::string(name) + ".diff.png");
    try {
        std::filesystem::create_directories(dir);
        write_png_atomic(actual_path.string(), actual);
        write_png_atomic(diff_path.string(), diff_image(expected, actual, *tolerance));
        failure << "\n  actual: " << actual_path.string() << "\n  diff:   " << diff_path.string() << " (differing pixels in red)";
    } catch (const std::exception& e) {
        failure << "\n  (could not write the actual and diff images to " << dir.string() << ": " << e.what() << ")";
    }
    failure << "\n  If the change is intended, " << update_hint << ".";
    return failure;
}

}  // namespace jostle
