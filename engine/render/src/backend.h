// The renderer's backends behind one interface: a frame arrives as textured triangles in image
// pixels plus the atlas; a backend turns it into an image. osmesa_backend.cpp is the only file
// that includes GL or OSMesa headers; null_backend draws nothing.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "jostle/render/renderer.h"

namespace jostle::detail {

struct Vertex {
    float x, y;  // image pixels, y down
    float u, v;  // texels from the sprite's top-left corner, 0..w and 0..h
    std::uint16_t rect_x, rect_y, rect_w, rect_h;  // the sprite's texels in the atlas
    std::uint8_t r, g, b, a;
};

struct Frame {
    int width = 0;
    int height = 0;
    Color clear;
    const std::vector<Vertex>* vertices = nullptr;
    const Image* atlas = nullptr;
    std::uint64_t atlas_version = 0;  // changes whenever the atlas's pixels change
};

class Backend {
public:
    virtual ~Backend() = default;
    // Fills `out` (resized to the frame) and returns the number of draw calls made.
    virtual int render(const Frame& frame, Image& out) = 0;
};

std::unique_ptr<Backend> make_osmesa_backend();  // throws std::runtime_error if unavailable
std::unique_ptr<Backend> make_null_backend();

}  // namespace jostle::detail
