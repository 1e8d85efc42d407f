// Renderer: the sprite atlas, and each frame's sprites and shapes turned into textured
// triangles in image pixels (one batch: the atlas holds every sprite and a white block for
// solid colour). The backends draw the batch (backend.h).
#include "jostle/render/renderer.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numbers>
#include <variant>

#include "backend.h"
#include "font.h"
#include "jostle/core/error.h"

namespace jostle {

using detail::Vertex;

namespace {

constexpr int kMaxAtlasSide = 4096;
constexpr int kPadding = 1;  // clear texels between sprites, so nearest sampling never bleeds
constexpr int kWhite = 2;    // the white block at (0, 0) that solid colour samples

}  // namespace

struct Renderer::Impl {
    RenderBackend kind;
    std::uint64_t serial = 0;
    std::unique_ptr<detail::Backend> backend;

    // The atlas: shelves packed left to right, top to bottom; it doubles (up to 4096) when full.
    struct Rect {
        int x, y, w, h;
    };
    Image atlas;
    std::uint64_t atlas_version = 1;
    std::vector<Rect> sprites;  // SpriteId value - 1
    std::uint32_t first_glyph = 0;  // SpriteId of ' ' (the font is baked in as sprites 32..126)
    int shelf_x = 0, shelf_y = 0, shelf_h = 0;

    // The frame being drawn.
    bool in_frame = false;
    int width = 0, height = 0;
    Color clear;
    Camera camera;
    std::vector<Vertex> vertices;
    Image image;
    int draw_calls = 0;

    Vec2 to_image(Vec2 world) const { return camera.zoom * (world - camera.origin); }

    void grow_atlas(int side) {
        Image bigger{side, side, std::vector<std::uint8_t>(static_cast<std::size_t>(side) * static_cast<std::size_t>(side) * 4u, 0)};
        for (int y = 0; y < atlas.height; ++y) {
            std::copy_n(atlas.rgba.begin() + static_cast<std::ptrdiff_t>(y) * atlas.width * 4, atlas.width * 4,
                        bigger.rgba.begin() + static_cast<std::ptrdiff_t>(y) * side * 4);
        }
        atlas = std::move(bigger);
        ++atlas_version;
    }

    // u, v in texels from the sprite's corner (the backend picks the texel in the sprite's own
    // coordinates, so a sprite draws the same wherever it was packed).
    void vertex(Vec2 p, float u, float v, const Rect& s, Color c) {
        vertices.push_back({p.x, p.y, u, v, static_cast<std::uint16_t>(s.x), static_cast<std::uint16_t>(s.y),
                            static_cast<std::uint16_t>(s.w), static_cast<std::uint16_t>(s.h), c.r, c.g, c.b, c.a});
    }
    void solid_triangle(Vec2 a, Vec2 b, Vec2 c, Color color) {
        // The centre of the white block.
        constexpr Rect white{0, 0, kWhite, kWhite};
        constexpr float w = 0.5f * kWhite;
        vertex(a, w, w, white, color);
        vertex(b, w, w, white, color);
        vertex(c, w, w, white, color);
    }
    void solid_quad(Vec2 a, Vec2 b, Vec2 c, Vec2 d, Color color) {
        solid_triangle(a, b, c, color);
        solid_triangle(a, c, d, color);
    }
    // A line in image pixels, `thickness` wide (a square for a point).
    void image_line(Vec2 a, Vec2 b, Color color, float thickness) {
        const float h = 0.5f * thickness;
        const Vec2 dir = normalize_or(b - a, Vec2{1.0f, 0.0f});
        const Vec2 along = (a == b) ? Vec2{h, 0.0f} : Vec2{};
        const Vec2 side = h * perp(dir);
        const Vec2 a0 = a - along, b0 = b + along;
        solid_quad(a0 + side, b0 + side, b0 - side, a0 - side, color);
    }
    void polygon_fill(std::span<const Vec2> world_points, Color color) {
        if (world_points.size() < 3) return;
        const Vec2 p0 = to_image(world_points[0]);
        for (std::size_t i = 1; i + 1 < world_points.size(); ++i) {
            solid_triangle(p0, to_image(world_points[i]), to_image(world_points[i + 1]), color);
        }
    }
    void polyline(std::span<const Vec2> world_points, bool closed, Color color, float thickness) {
        for (std::size_t i = 0; i + 1 < world_points.size(); ++i) {
            image_line(to_image(world_points[i]), to_image(world_points[i + 1]), color, thickness);
        }
        if (closed && world_points.size() > 2) image_line(to_image(world_points.back()), to_image(world_points.front()), color, thickness);
    }
    // A circle as a polygon with enough sides that its edges stay within ~1/4 px of the curve.
    std::vector<Vec2> circle_points(const Circle& c) const {
        const float r_image = c.radius * camera.zoom;
        const int n = std::clamp(static_cast<int>(std::ceil(std::numbers::pi_v<float> * std::sqrt(std::fmax(r_image, 0.0f) * 8.0f))), 12, 256);
        std::vector<Vec2> points(static_cast<std::size_t>(n));
        for (int i = 0; i < n; ++i) {
            const float t = 2.0f * std::numbers::pi_v<float> * static_cast<float>(i) / static_cast<float>(n);
            points[static_cast<std::size_t>(i)] = c.center + c.radius * Vec2{std::cos(t), std::sin(t)};
        }
        return points;
    }
};

namespace {

// The shape's outline as points (world pixels), for every kind but masks and segments.
bool shape_valid(const Shape& s) {
    const Aabb b = bounds(s);
    return is_finite(b.min) && is_finite(b.max) && b.min.x <= b.max.x && b.min.y <= b.max.y;
}

}  // namespace

Renderer::Renderer(const RendererDesc& desc) : impl_(std::make_unique<Impl>()) {
    impl_->kind = desc.backend;
    static std::atomic<std::uint64_t> next_serial{1};
    impl_->serial = next_serial++;
    impl_->backend = desc.backend == RenderBackend::osmesa ? detail::make_osmesa_backend() : detail::make_null_backend();
    impl_->atlas = Image{256, 256, std::vector<std::uint8_t>(256u * 256u * 4u, 0)};
    for (int y = 0; y < kWhite; ++y) {
        for (int x = 0; x < kWhite; ++x) std::fill_n(impl_->atlas.rgba.begin() + (y * 256 + x) * 4, 4, std::uint8_t{255});
    }
    impl_->shelf_x = kWhite + kPadding;
    impl_->shelf_h = kWhite;
    // The built-in font: each printable glyph as a white sprite with alpha where it is on.
    for (int c = 32; c <= 126; ++c) {
        const detail::Glyph& g = detail::glyph(static_cast<char>(c));
        Image im{detail::kGlyphWidth, detail::kGlyphHeight,
                 std::vector<std::uint8_t>(static_cast<std::size_t>(detail::kGlyphWidth * detail::kGlyphHeight) * 4u, 255)};
        for (int y = 0; y < detail::kGlyphHeight; ++y) {
            for (int x = 0; x < detail::kGlyphWidth; ++x) {
                const bool on = ((g.rows[y] >> (detail::kGlyphWidth - 1 - x)) & 1u) != 0;
                im.rgba[static_cast<std::size_t>(y * detail::kGlyphWidth + x) * 4u + 3u] = on ? 255 : 0;
            }
        }
        const SpriteId id = add_sprite(im);
        if (c == 32) impl_->first_glyph = id.value;
    }
}

Renderer::~Renderer() = default;

RenderBackend Renderer::backend() const { return impl_->kind; }

std::uint64_t Renderer::serial() const { return impl_->serial; }

SpriteId Renderer::add_sprite(const Image& image) {
    Impl& r = *impl_;
    if (image.width < 1 || image.height < 1 || image.width > kMaxSpriteSide || image.height > kMaxSpriteSide ||
        image.rgba.size() != static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 4u) {
        throw InputError("sprite of " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                         " pixels: sides must be 1.." + std::to_string(kMaxSpriteSide) + " with 4 bytes per pixel");
    }
    // Next shelf when this one is full; grow the atlas when the shelves run out.
    for (;;) {
        if (r.shelf_x + image.width > r.atlas.width) {
            r.shelf_y += r.shelf_h + kPadding;
            r.shelf_x = 0;
            r.shelf_h = 0;
        }
        if (r.shelf_x + image.width <= r.atlas.width && r.shelf_y + image.height <= r.atlas.height) break;
        if (r.atlas.width >= kMaxAtlasSide) {
            throw InputError("sprite atlas full: " + std::to_string(r.sprites.size()) + " sprites fill " +
                             std::to_string(kMaxAtlasSide) + "x" + std::to_string(kMaxAtlasSide) + " pixels");
        }
        // Growing keeps every placed sprite where it is; shelves continue below them.
        r.grow_atlas(r.atlas.width * 2);
    }
    const Impl::Rect rect{r.shelf_x, r.shelf_y, image.width, image.height};
    for (int y = 0; y < image.height; ++y) {
        std::copy_n(image.rgba.begin() + static_cast<std::ptrdiff_t>(y) * image.width * 4, image.width * 4,
                    r.atlas.rgba.begin() + (static_cast<std::ptrdiff_t>(rect.y + y) * r.atlas.width + rect.x) * 4);
    }
    r.shelf_x += image.width + kPadding;
    r.shelf_h = std::max(r.shelf_h, image.height);
    ++r.atlas_version;
    r.sprites.push_back(rect);
    return SpriteId{static_cast<std::uint32_t>(r.sprites.size())};
}

Vec2 Renderer::sprite_size(SpriteId id) const {
    if (id.value == 0 || id.value > impl_->sprites.size()) return {};
    const Impl::Rect& rect = impl_->sprites[id.value - 1];
    return {static_cast<float>(rect.w), static_cast<float>(rect.h)};
}

void Renderer::begin_frame(int width, int height, Color clear, Camera camera) {
    JOSTLE_ASSERT(width >= 1 && width <= kMaxFrameSide && height >= 1 && height <= kMaxFrameSide, "frame size must be 1..8192");
    Impl& r = *impl_;
    r.in_frame = true;
    r.width = width;
    r.height = height;
    r.clear = clear;
    r.camera = camera;
    r.vertices.clear();
}

void Renderer::draw_sprite(SpriteId id, Vec2 center, float angle, Vec2 scale, Color tint) {
    Impl& r = *impl_;
    JOSTLE_ASSERT(r.in_frame, "draw_sprite outside begin_frame/end_frame");
    if (id.value == 0 || id.value > r.sprites.size()) return;
    const Impl::Rect& rect = r.sprites[id.value - 1];
    const Vec2 half{0.5f * static_cast<float>(rect.w) * scale.x, 0.5f * static_cast<float>(rect.h) * scale.y};
    const Rot q = Rot::from_angle(angle);
    const Vec2 corner[4] = {{-half.x, -half.y}, {half.x, -half.y}, {half.x, half.y}, {-half.x, half.y}};
    const float w = static_cast<float>(rect.w), h = static_cast<float>(rect.h);
    const float us[4] = {0.0f, w, w, 0.0f};
    const float vs[4] = {0.0f, 0.0f, h, h};
    Vec2 p[4];
    for (int i = 0; i < 4; ++i) p[i] = r.to_image(center + rotate(q, corner[i]));
    for (int i : {0, 1, 2, 0, 2, 3}) r.vertex(p[i], us[i], vs[i], rect, tint);
}

void Renderer::fill_rect(const Aabb& box, Color color) { fill_shape(box, color); }

void Renderer::fill_shape(const Shape& shape, Color color, float thickness) {
    Impl& r = *impl_;
    JOSTLE_ASSERT(r.in_frame, "fill_shape outside begin_frame/end_frame");
    if (!shape_valid(shape)) return;
    struct Visit {
        Impl& r;
        Color color;
        float thickness;
        void operator()(const Aabb& b) const { const auto c = corners(b); r.polygon_fill(c, color); }
        void operator()(const Obb& b) const { const auto c = corners(b); r.polygon_fill(c, color); }
        void operator()(const Polygon& p) const { r.polygon_fill(p.points(), color); }
        void operator()(const Circle& c) const { r.polygon_fill(r.circle_points(c), color); }
        void operator()(const Segment& s) const { r.image_line(r.to_image(s.a), r.to_image(s.b), color, thickness); }
        void operator()(const PlacedMask& m) const {
            if (m.mask == nullptr) return;
            // Runs of set pixels in each row, one quad each.
            for (int y = 0; y < m.mask->height(); ++y) {
                for (int x = 0; x < m.mask->width();) {
                    if (!m.mask->get(x, y)) { ++x; continue; }
                    int end = x;
                    while (end < m.mask->width() && m.mask->get(end, y)) ++end;
                    const Vec2 a{static_cast<float>(m.x + x), static_cast<float>(m.y + y)};
                    const Vec2 b{static_cast<float>(m.x + end), static_cast<float>(m.y + y + 1)};
                    r.solid_quad(r.to_image(a), r.to_image({b.x, a.y}), r.to_image(b), r.to_image({a.x, b.y}), color);
                    x = end;
                }
            }
        }
    };
    std::visit(Visit{r, color, thickness}, shape);
}

void Renderer::outline_shape(const Shape& shape, Color color, float thickness) {
    Impl& r = *impl_;
    JOSTLE_ASSERT(r.in_frame, "outline_shape outside begin_frame/end_frame");
    if (!shape_valid(shape)) return;
    struct Visit {
        Impl& r;
        Color color;
        float thickness;
        void operator()(const Aabb& b) const { const auto c = corners(b); r.polyline(c, true, color, thickness); }
        void operator()(const Obb& b) const { const auto c = corners(b); r.polyline(c, true, color, thickness); }
        void operator()(const Polygon& p) const {
            r.polyline(p.points(), true, color, thickness);
        }
        void operator()(const Circle& c) const { r.polyline(r.circle_points(c), true, color, thickness); }
        void operator()(const Segment& s) const { r.image_line(r.to_image(s.a), r.to_image(s.b), color, thickness); }
        void operator()(const PlacedMask& m) const {
            if (m.mask == nullptr) return;
            // Every side of a set pixel that borders a clear one (or the mask's edge).
            const Mask& k = *m.mask;
            for (int y = 0; y < k.height(); ++y) {
                for (int x = 0; x < k.width(); ++x) {
                    if (!k.get(x, y)) continue;
                    const float x0 = static_cast<float>(m.x + x), y0 = static_cast<float>(m.y + y);
                    const Vec2 tl{x0, y0}, tr{x0 + 1, y0}, br{x0 + 1, y0 + 1}, bl{x0, y0 + 1};
                    if (!k.get(x, y - 1)) r.image_line(r.to_image(tl), r.to_image(tr), color, thickness);
                    if (!k.get(x + 1, y)) r.image_line(r.to_image(tr), r.to_image(br), color, thickness);
                    if (!k.get(x, y + 1)) r.image_line(r.to_image(br), r.to_image(bl), color, thickness);
                    if (!k.get(x - 1, y)) r.image_line(r.to_image(bl), r.to_image(tl), color, thickness);
                }
            }
        }
    };
    std::visit(Visit{r, color, thickness}, shape);
}

void Renderer::draw_line(Vec2 a, Vec2 b, Color color, float thickness) {
    Impl& r = *impl_;
    JOSTLE_ASSERT(r.in_frame, "draw_line outside begin_frame/end_frame");
    if (!is_finite(a) || !is_finite(b)) return;
    r.image_line(r.to_image(a), r.to_image(b), color, thickness);
}

Vec2 Renderer::draw_text(Vec2 image_position, std::string_view text, Color color, int scale) {
    Impl& r = *impl_;
    JOSTLE_ASSERT(r.in_frame, "draw_text outside begin_frame/end_frame");
    JOSTLE_ASSERT(scale >= 1, "text scale must be >= 1");
    int width = 0;
    int height = 0;
    const std::vector<detail::PlacedGlyph> placed = detail::layout_text(text, &width, &height);
    if (!is_finite(image_position)) return {};
    const float s = static_cast<float>(scale);
    for (const detail::PlacedGlyph& p : placed) {
        const auto code = static_cast<unsigned char>(p.c);
        const unsigned index = (code >= 32 && code <= 126) ? code - 32u : static_cast<unsigned>('?' - 32);
        const Impl::Rect& rect = r.sprites[r.first_glyph - 1 + index];
        const Vec2 a = image_position + s * Vec2{static_cast<float>(p.x), static_cast<float>(p.y)};
        const Vec2 b = a + s * Vec2{static_cast<float>(rect.w), static_cast<float>(rect.h)};
        const float w = static_cast<float>(rect.w), h = static_cast<float>(rect.h);
        r.vertex(a, 0.0f, 0.0f, rect, color);
        r.vertex({b.x, a.y}, w, 0.0f, rect, color);
        r.vertex(b, w, h, rect, color);
        r.vertex(a, 0.0f, 0.0f, rect, color);
        r.vertex(b, w, h, rect, color);
        r.vertex({a.x, b.y}, 0.0f, h, rect, color);
    }
    return s * Vec2{static_cast<float>(width), static_cast<float>(height)};
}

Vec2 Renderer::world_to_image(Vec2 world) const { return impl_->to_image(world); }

const Image& Renderer::end_frame() {
    Impl& r = *impl_;
    JOSTLE_ASSERT(r.in_frame, "end_frame without begin_frame");
    r.in_frame = false;
    detail::Frame frame{r.width, r.height, r.clear, &r.vertices, &r.atlas, r.atlas_version};
    r.draw_calls = r.backend->render(frame, r.image);
    return r.image;
}

int Renderer::last_draw_calls() const { return impl_->draw_calls; }

}  // namespace jostle
