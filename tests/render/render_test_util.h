// Helpers the render tests share: reading a pixel as a Color, an image of one colour, and
// printing a Color in gtest failure messages.
#pragma once

#include <cstdint>
#include <ostream>
#include <vector>

#include "jostle/render/renderer.h"

namespace jostle {

inline void PrintTo(Color c, std::ostream* os) {
    *os << "(" << int{c.r} << "," << int{c.g} << "," << int{c.b} << "," << int{c.a} << ")";
}

inline Color pixel_at(const Image& im, int x, int y) {
    const std::uint8_t* p = im.rgba.data() + (static_cast<std::size_t>(y) * static_cast<std::size_t>(im.width) + static_cast<std::size_t>(x)) * 4u;
    return {p[0], p[1], p[2], p[3]};
}

inline Image solid_image(int w, int h, Color c) {
    Image im{w, h, std::vector<std::uint8_t>(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 4u)};
    for (std::size_t i = 0; i < im.rgba.size(); i += 4) {
        im.rgba[i] = c.r;
        im.rgba[i + 1] = c.g;
        im.rgba[i + 2] = c.b;
        im.rgba[i + 3] = c.a;
    }
    return im;
}

}  // namespace jostle
