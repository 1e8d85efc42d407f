// Image comparison (see jostle/render/image_compare.h): exact fast path, tolerant count, and
// the diff picture.
#include "jostle/render/image_compare.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>

namespace jostle {

namespace {

// The largest channel difference between two RGBA pixels.
int channel_delta(const std::uint8_t* a, const std::uint8_t* b) {
    int d = 0;
    for (int c = 0; c < 4; ++c) d = std::max(d, std::abs(int{a[c]} - int{b[c]}));
    return d;
}

bool well_formed(const Image& im) {
    return im.width >= 0 && im.height >= 0 &&
           im.rgba.size() == static_cast<std::size_t>(im.width) * static_cast<std::size_t>(im.height) * 4u;
}

}  // namespace

CompareResult compare_images(const Image& expected, const Image& actual, const CompareOptions& options) {
    CompareResult r;
    if (!well_formed(expected) || !well_formed(actual)) return r;  // never within tolerance
    r.same_size = expected.width == actual.width && expected.height == actual.height;
    if (r.same_size && expected.rgba == actual.rgba) {
        r.identical = true;
        r.within_tolerance = true;
        return r;
    }
    const int w = std::min(expected.width, actual.width);
    const int h = std::min(expected.height, actual.height);
    for (int y = 0; y < h; ++y) {
        const std::uint8_t* pa = expected.rgba.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(expected.width) * 4u;
        const std::uint8_t* pb = actual.rgba.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(actual.width) * 4u;
        if (std::memcmp(pa, pb, static_cast<std::size_t>(w) * 4u) == 0) continue;
        for (int x = 0; x < w; ++x) {
            const int d = channel_delta(pa + 4 * x, pb + 4 * x);
            r.max_channel_delta = std::max(r.max_channel_delta, d);
            if (d > options.max_channel_delta) ++r.differing_pixels;
        }
    }
    if (!r.same_size) {
        const std::int64_t big_w = std::max(expected.width, actual.width);
        const std::int64_t big_h = std::max(expected.height, actual.height);
        r.differing_pixels += big_w * big_h - std::int64_t{w} * h;
    }
    r.within_tolerance = r.same_size && r.differing_pixels <= options.max_differing_pixels;
    return r;
}

Image diff_image(const Image& expected, const Image& actual, int max_channel_delta) {
    Image out;
    if (!well_formed(expected) || !well_formed(actual)) return out;
    out.width = std::max(expected.width, actual.width);
    out.height = std::max(expected.height, actual.height);
    out.rgba.resize(static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height) * 4u);
    for (int y = 0; y < out.height; ++y) {
        for (int x = 0; x < out.width; ++x) {
            std::uint8_t* o = out.rgba.data() + (static_cast<std::size_t>(y) * static_cast<std::size_t>(out.width) + static_cast<std::size_t>(x)) * 4u;
            const bool in_a = x < expected.width && y < expected.height;
            const bool in_b = x < actual.width && y < actual.height;
            const std::uint8_t* pa = in_a ? expected.rgba.data() + (static_cast<std::size_t>(y) * static_cast<std::size_t>(expected.width) + static_cast<std::size_t>(x)) * 4u : nullptr;
            const std::uint8_t* pb = in_b ? actual.rgba.data() + (static_cast<std::size_t>(y) * static_cast<std::size_t>(actual.width) + static_cast<std::size_t>(x)) * 4u : nullptr;
            if (!in_a || !in_b || channel_delta(pa, pb) > max_channel_delta) {
                o[0] = 255; o[1] = 0; o[2] = 0; o[3] = 255;
                continue;
            }
            // Faded: three quarters of the way to white, opaque, so red stands out.
            for (int c = 0; c < 3; ++c) o[c] = static_cast<std::uint8_t>(255 - (255 - pa[c]) / 4);
            o[3] = 255;
        }
    }
    return out;
}

}  // namespace jostle
