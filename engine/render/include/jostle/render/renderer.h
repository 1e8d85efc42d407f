// jostle/render/renderer.h: drawing frames off-screen. A Renderer collects one frame's sprites
// and shapes as textured triangles (every sprite and the solid colour live in one texture
// atlas, so a frame is one draw call per atlas page, whatever the number of sprites), then a
// backend turns them into an image: OSMesa (software OpenGL 3.3 core, no window, no GPU) or
// the null backend (no pixels drawn: the image is the clear colour; for tests and runs that
// need no pictures). The image is straight RGBA, top row first, right side up.
//
// Coordinates are world pixels (y down, as everywhere in jostle); the Camera maps them to
// image pixels: image = (world - origin) * zoom.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include "jostle/collision.h"
#include "jostle/core/vec2.h"
#include "jostle/render/png_io.h"

namespace jostle {

// The largest sprite side add_sprite takes.
inline constexpr int kMaxSpriteSide = 2048;
// The largest frame side begin_frame takes.
inline constexpr int kMaxFrameSide = 8192;

struct Color {
    std::uint8_t r = 0;
    std::uint8_t g = 0;
    std::uint8_t b = 0;
    std::uint8_t a = 255;
    friend constexpr bool operator==(Color, Color) = default;
};

struct Camera {
    Vec2 origin;        // the world point at the image's top-left corner
    float zoom = 1.0f;  // image pixels per world pixel
};

// A sprite in the renderer's atlas. 0 is no sprite.
struct SpriteId {
    std::uint32_t value = 0;
    friend constexpr bool operator==(SpriteId, SpriteId) = default;
};

enum class RenderBackend : std::uint8_t { osmesa, null };

struct RendererDesc {
    RenderBackend backend = RenderBackend::osmesa;
};

class Renderer {
public:
    // Throws std::runtime_error when the backend cannot start (no OSMesa, no 3.3 context).
    explicit Renderer(const RendererDesc& desc = {});
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    RenderBackend backend() const;
    // Different for every Renderer made in this process, so callers that cache SpriteIds
    // (a game adding its sprites once per renderer) can tell renderers apart.
    std::uint64_t serial() const;

    // Adds an image (straight RGBA) to the atlas. Throws jostle::InputError when it does not
    // fit (sides up to kMaxSpriteSide px; the atlas is one 4096 x 4096 page).
    SpriteId add_sprite(const Image& image);
    Vec2 sprite_size(SpriteId id) const;  // {0, 0} for an unknown id

    // A frame: begin, draw (painter's order: later draws cover earlier ones), end.
    // width and height in 1..kMaxFrameSide (asserted).
    void begin_frame(int width, int height, Color clear, Camera camera = {});
    // The sprite centred at `center`, turned by `angle` (radians, +x toward +y), scaled, and
    // multiplied by `tint` (white: as it is).
    void draw_sprite(SpriteId id, Vec2 center, float angle = 0.0f, Vec2 scale = {1.0f, 1.0f},
                     Color tint = {255, 255, 255, 255});
    void fill_rect(const Aabb& box, Color color);
    // Any collision shape, filled (a segment as a line `thickness` wide) or outlined by lines
    // `thickness` image pixels wide. Masks fill their set pixels; their outline is the border
    // of their set pixels. Invalid shapes draw nothing.
    void fill_shape(const Shape& shape, Color color, float thickness = 1.0f);
    void outline_shape(const Shape& shape, Color color, float thickness = 1.0f);
    void draw_line(Vec2 a, Vec2 b, Color color, float thickness = 1.0f);
    // Text in the built-in 5x7 pixel font (printable ASCII; anything else shows as '?';
    // '\n' starts a new line), its top-left at `image_position` in image pixels (not moved
    // by the camera: HUDs, frame numbers; use world_to_image for labels on world things),
    // each font pixel `scale` x `scale` image pixels. Returns the text's size in image pixels.
    Vec2 draw_text(Vec2 image_position, std::string_view text, Color color, int scale = 1);
    // Where a world point lands in the current frame's image (the camera's mapping).
    Vec2 world_to_image(Vec2 world) const;
    // Renders what was drawn since begin_frame. The image stays valid until the next end_frame.
    const Image& end_frame();

    // How many draw calls the last frame took (for tests and benchmarks).
    int last_draw_calls() const;

    struct Impl;

private:
    std::unique_ptr<Impl> impl_;
};

}  // namespace jostle
