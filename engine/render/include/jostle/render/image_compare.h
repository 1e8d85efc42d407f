// jostle/render/image_compare.h: comparing two images, for golden checks and `jostle imgdiff`.
// An exact byte comparison first (the common case, and the fast path); otherwise a count of
// the pixels whose largest channel difference is over a tolerance, and a diff image.
#pragma once

#include <cstdint>

#include "jostle/render/png_io.h"

namespace jostle {

struct CompareOptions {
    int max_channel_delta = 0;            // a pixel differs when some channel differs by more
    std::int64_t max_differing_pixels = 0;  // the images match when at most this many differ
};

struct CompareResult {
    bool same_size = false;
    bool identical = false;   // same size and the same bytes
    bool within_tolerance = false;
    std::int64_t differing_pixels = 0;  // over max_channel_delta (with sizes that differ: every
                                        // pixel of the larger canvas outside the common area)
    int max_channel_delta = 0;          // largest channel difference over the common area
};

CompareResult compare_images(const Image& expected, const Image& actual, const CompareOptions& options = {});

// The diff picture: `expected` faded toward white, with every differing pixel (as
// compare_images counts them) in solid red. Covers the larger of the two sizes; the area only
// one image has is red.
Image diff_image(const Image& expected, const Image& actual, int max_channel_delta = 0);

}  // namespace jostle
