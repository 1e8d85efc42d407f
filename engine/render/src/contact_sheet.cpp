// Contact sheets (jostle/render/contact_sheet.h): thumbnails by nearest-pixel scaling and
// labels in the built-in font, composed on the CPU.
#include "jostle/render/contact_sheet.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "font.h"
#include "jostle/core/error.h"

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
    ContactSheetBuilder builder(static_cast<int>(frames.size()), desc);
    const Image none;
    for (const SheetFrame& f : frames) builder.add(f.frame, f.image != nullptr ? *f.image : none);
    return builder.finish();
}

ContactSheetBuilder::ContactSheetBuilder(int count, const SheetDesc& desc) : count_(std::max(count, 0)), desc_(desc) {}

// The grid and the cells' size, from the first whole frame (or 64 x 48 when there is none):
// the background, then the labels of the frames added before it.
void ContactSheetBuilder::start(const Image* first) {
    const int n = count_;
    columns_ = desc_.columns > 0 ? std::min(desc_.columns, n) : static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
    const int rows = (n + columns_ - 1) / columns_;
    const int base_w = first ? first->width : 64;
    const int base_h = first ? first->height : 48;
    thumb_w_ = std::max(1, desc_.thumb_width > 0 ? desc_.thumb_width : std::min(base_w, 320));
    thumb_h_ = std::max(1, static_cast<int>(std::lround(static_cast<double>(thumb_w_) * base_h / base_w)));
    const int cell_w = thumb_w_ + kGap;
    const int cell_h = thumb_h_ + kLabelHeight + kGap;

    sheet_ = Image{kGap + columns_ * cell_w, kGap + rows * cell_h, {}};
    sheet_.rgba.resize(static_cast<std::size_t>(sheet_.width) * static_cast<std::size_t>(sheet_.height) * 4u);
    for (int y = 0; y < sheet_.height; ++y) {
        for (int x = 0; x < sheet_.width; ++x) put(sheet_, x, y, desc_.background);
    }
    for (std::size_t i = 0; i < waiting_.size(); ++i) draw(static_cast<int>(i), waiting_[i], nullptr);
    waiting_.clear();
}

void ContactSheetBuilder::draw(int cell, std::int64_t frame, const Image* im) {
    const int cell_w = thumb_w_ + kGap;
    const int cell_h = thumb_h_ + kLabelHeight + kGap;
    const int cx = kGap + (cell % columns_) * cell_w;
    const int cy = kGap + (cell / columns_) * cell_h;
    if (usable(im)) {
        // Fit inside the cell keeping the aspect ratio; nearest pixel keeps edges crisp.
        const double scale = std::min(static_cast<double>(thumb_w_) / im->width, static_cast<double>(thumb_h_) / im->height);
        const int w = std::max(1, static_cast<int>(std::lround(im->width * scale)));
        const int h = std::max(1, static_cast<int>(std::lround(im->height * scale)));
        const int ox = cx + (thumb_w_ - w) / 2;
        const int oy = cy + (thumb_h_ - h) / 2;
        for (int y = 0; y < h; ++y) {
            const int sy = std::min(im->height - 1, static_cast<int>((static_cast<std::int64_t>(y) * im->height) / h));
            for (int x = 0; x < w; ++x) {
                const int sx = std::min(im->width - 1, static_cast<int>((static_cast<std::int64_t>(x) * im->width) / w));
                const std::uint8_t* p = im->rgba.data() + (static_cast<std::size_t>(sy) * static_cast<std::size_t>(im->width) + static_cast<std::size_t>(sx)) * 4u;
                put(sheet_, ox + x, oy + y, {p[0], p[1], p[2], p[3]});
            }
        }
    }
    text(sheet_, cx, cy + thumb_h_ + 2, "frame " + std::to_string(frame), desc_.label);
}

void ContactSheetBuilder::add(std::int64_t frame, const Image& image) {
    JOSTLE_ASSERT(added_ < count_, "ContactSheetBuilder: more frames added than the sheet was made for");
    const int cell = added_++;
    if (!started()) {
        if (!usable(&image)) {
            waiting_.push_back(frame);  // its label waits for the cell size
            return;
        }
        start(&image);
    }
    draw(cell, frame, &image);
}

Image ContactSheetBuilder::finish() {
    if (count_ == 0) return {};
    if (!started()) start(nullptr);
    return std::move(sheet_);
}

}  // namespace jostle
