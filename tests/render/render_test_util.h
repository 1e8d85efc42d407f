// Helpers the render tests share: reading a pixel as a Color, and printing a Color in gtest
// failure messages.
#pragma once

#include <ostream>

#include "jostle/render/renderer.h"

namespace jostle {

inline void PrintTo(Color c, std::ostream* os) {
    *os << "(" << int{c.r} << "," << int{c.g} << "," << int{c.b} << "," << int{c.a} << ")";
}

inline Color pixel_at(const Image& im, int x, int y) {
    const std::uint8_t* p = im.rgba.data() + (static_cast<std::size_t>(y) * static_cast<std::size_t>(im.width) + static_cast<std::size_t>(x)) * 4u;
    return {p[0], p[1], p[2], p[3]};
}

}  // namespace jostle
