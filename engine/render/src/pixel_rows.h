// pixel_rows.h: a rectangle of an Image's pixels as the encoders read it, so that a part of a
// frame (an animation frame's changed rectangle) is encoded in place instead of copied out.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "jostle/render/png_io.h"

namespace jostle::detail {

// `height` rows of `width` RGBA pixels, the first at `first`, each `stride` bytes after the one
// before.
struct PixelRows {
    const std::uint8_t* first = nullptr;
    int width = 0;
    int height = 0;
    std::size_t stride = 0;

    const std::uint8_t* row(int y) const { return first + static_cast<std::size_t>(y) * stride; }
};

// The rectangle at (x, y) of w x h pixels of `image` (inside it: the caller's to check).
inline PixelRows rows_of(const Image& image, int x, int y, int w, int h) {
    const std::size_t stride = static_cast<std::size_t>(image.width) * 4;
    return {image.rgba.data() + static_cast<std::size_t>(y) * stride + static_cast<std::size_t>(x) * 4, w, h, stride};
}
inline PixelRows rows_of(const Image& image) { return rows_of(image, 0, 0, image.width, image.height); }

// encode_png of the pixels `rows` (png_io.cpp): the same bytes as encode_png of an Image
// holding just them.
std::vector<std::uint8_t> encode_png_rows(const PixelRows& rows, const PngEncoding& encoding);

}  // namespace jostle::detail
