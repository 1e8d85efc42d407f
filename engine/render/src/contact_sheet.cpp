// Contact sheets (jostle/render/contact_sheet.h): thumbnails by nearest-pixel scaling and
// labels in the built-in font, composed on the CPU.
#include "jostle/render/contact_sheet.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "font.h"

namespace jostle {

namespace {

constexpr int kGap = 4;
constexpr int kLabelHeight = detail::kGlyphHeight + 4;

void put(Image& im, int x, int y, Color c) {
    if (x < 0 || y < 0 || x >= im.width || y >= im.height) return;
    std::uint8_t* p = im.rgba.data() + (static_cast<std::size_t>(y) * static_cast<std::size_t>(im.width) + static_cast<std::size_t>(x)) * 4u;
    p[0] = c.r;
    p[1] = c.g;
    p[2] = c.b;
    p[3] = c.a;
}

void text(Image& im, int x0, int y0, const std::string& s, Color c) {
    for (const detail::PlacedGlyph& g : detail::layout_text(s, nullptr, nullptr)) {
        const detail::Glyph& glyph = detail::glyph(g.c);
        for (int y = 0; y < detail::kGlyphHeight; ++y) {
            for (int x = 0; x < detail::kGlyphWidth; ++x) {
                if ((glyph.rows[y] >> (detail::kGlyphWidth - 1 - x)) & 1u) put(im, x0 + g.x + x, y0 + g.y + y, c);
            }
        }
    }
}

bool usable(const Image* im) {
    return im != nullptr && im->width > 0 && im->height > 0 &&
           im->rgba.size() == static_cast<std::size_t>(im->width) * static_cast<std::size_t>(im->height) * 4u;
}

}  // namespace

Image contact_sheet(std::span<const SheetFrame> frames, const SheetDesc& desc) {
    if (frames.empty()) return {};
    const Image* first = nullptr;
    for (const SheetFrame& f : frames) {
        if (usable(f.image)) { first = f.image; break; }
    }
    const int n = static_cast<int>(frames.size());
    const int columns = desc.columns > 0 ? std::min(desc.columns, n) : static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
    const int rows = (n + columns - 1) / columns;
    const int base_w = first ? first->width : 64;
    const int base_h = first ? first->height : 48;
    const int thumb_w = std::max(1, desc.thumb_width > 0 ? desc.thumb_width : std::min(base_w, 320));
    const int thumb_h = std::max(1, static_cast<int>(std::lround(static_cast<double>(thumb_w) * base_h / base_w)));
    const int cell_w = thumb_w + kGap;
    const int cell_h = thumb_h + kLabelHeight + kGap;

    Image sheet{kGap + columns * cell_w, kGap + rows * cell_h, {}};
    sheet.rgba.resize(static_cast<std::size_t>(sheet.width) * static_cast<std::size_t>(sheet.height) * 4u);
    for (int y = 0; y < sheet.height; ++y) {
        for (int x = 0; x < sheet.width; ++x) put(sheet, x, y, desc.background);
    }
    for (int i = 0; i < n; ++i) {
        const int cx = kGap + (i % columns) * cell_w;
        const int cy = kGap + (i / columns) * cell_h;
        const Image* im = frames[static_cast<std::size_t>(i)].image;
        if (usable(im)) {
            // Fit inside the cell keeping the aspect ratio; nearest pixel keeps edges crisp.
            const double scale = std::min(static_cast<double>(thumb_w) / im->width, static_cast<double>(thumb_h) / im->height);
            const int w = std::max(1, static_cast<int>(std::lround(im->width * scale)));
            const int h = std::max(1, static_cast<int>(std::lround(im->height * scale)));
            const int ox = cx + (thumb_w - w) / 2;
            const int oy = cy + (thumb_h - h) / 2;
            for (int y = 0; y < h; ++y) {
                const int sy = std::min(im->height - 1, static_cast<int>((static_cast<std::int64_t>(y) * im->height) / h));
                for (int x = 0; x < w; ++x) {
                    const int sx = std::min(im->width - 1, static_cast<int>((static_cast<std::int64_t>(x) * im->width) / w));
                    const std::uint8_t* p = im->rgba.data() + (static_cast<std::size_t>(sy) * static_cast<std::size_t>(im->width) + static_cast<std::size_t>(sx)) * 4u;
                    put(sheet, ox + x, oy + y, {p[0], p[1], p[2], p[3]});
                }
            }
        }
        text(sheet, cx, cy + thumb_h + 2, "frame " + std::to_string(frames[static_cast<std::size_t>(i)].frame), desc.label);
    }
    return sheet;
}

}  // namespace jostle
