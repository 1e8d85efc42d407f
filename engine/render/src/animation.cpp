// animation.cpp: the APNG container around frames encoded by encode_png.
// An APNG is a PNG whose chunks are: signature, IHDR, acTL (frame count, plays), then per
// frame an fcTL (sequence, size, offset, delay, dispose/blend ops) and its image data: IDAT
// chunks for frame 0 (so a plain PNG viewer shows it), fdAT chunks (sequence + IDAT payload)
// for the others; then IEND. Sequence numbers count fcTL and fdAT chunks together from 0.
// Each frame's data is the IDAT payload of a PNG of just its rectangle, which encode_png makes.
#include "jostle/render/animation.h"

#include <zlib.h>

#include <algorithm>
#include <cstring>
#include <optional>
#include <span>
#include <vector>

#include "jostle/core/atomic_file.h"
#include "jostle/core/error.h"

namespace jostle {
namespace {

constexpr std::uint8_t kPngSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
constexpr std::uint8_t kDisposeNone = 0;
constexpr std::uint8_t kBlendSource = 0;

void put_u32(std::vector<std::uint8_t>& out, std::uint32_t v) {
    out.push_back(static_cast<std::uint8_t>(v >> 24));
    out.push_back(static_cast<std::uint8_t>(v >> 16));
    out.push_back(static_cast<std::uint8_t>(v >> 8));
    out.push_back(static_cast<std::uint8_t>(v));
}

void put_u16(std::vector<std::uint8_t>& out, std::uint32_t v) {
    out.push_back(static_cast<std::uint8_t>(v >> 8));
    out.push_back(static_cast<std::uint8_t>(v));
}

std::uint32_t get_u32(const std::uint8_t* p) {
    return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) | p[3];
}

// One chunk: length, type, data, CRC of type and data.
std::vector<std::uint8_t> make_chunk(const char (&type)[5], std::span<const std::uint8_t> data) {
    std::vector<std::uint8_t> chunk;
    chunk.reserve(data.size() + 12);
    put_u32(chunk, static_cast<std::uint32_t>(data.size()));
    chunk.insert(chunk.end(), type, type + 4);
    chunk.insert(chunk.end(), data.begin(), data.end());
    uLong crc = crc32(0L, Z_NULL, 0);
    crc = crc32(crc, chunk.data() + 4, static_cast<uInt>(data.size() + 4));
    put_u32(chunk, static_cast<std::uint32_t>(crc));
    return chunk;
}

// The chunks of a PNG file that encode_png made (trusted: well formed by construction).
struct PngChunks {
    std::vector<std::uint8_t> ihdr;               // IHDR's data
    std::vector<std::vector<std::uint8_t>> idat;  // each IDAT's data, in order
};

PngChunks split_png(const std::vector<std::uint8_t>& png) {
    PngChunks out;
    std::size_t at = sizeof kPngSignature;
    while (at + 12 <= png.size()) {
        const std::uint32_t length = get_u32(png.data() + at);
        const std::uint8_t* type = png.data() + at + 4;
        const std::uint8_t* data = type + 4;
        JOSTLE_ASSERT(at + 12 + length <= png.size(), "split_png: chunk runs past the end");
        if (std::memcmp(type, "IHDR", 4) == 0) out.ihdr.assign(data, data + length);
        if (std::memcmp(type, "IDAT", 4) == 0) out.idat.emplace_back(data, data + length);
        at += 12 + std::size_t{length};
    }
    return out;
}

struct Rect {
    int x = 0;
    int y = 0;
    int width = 0;
    int height = 0;
};

// The smallest rectangle holding every pixel that differs between a and b (same size), or
// nullopt when they are equal.
std::optional<Rect> changed_rect(const Image& a, const Image& b) {
    const std::size_t row_bytes = static_cast<std::size_t>(a.width) * 4;
    int top = -1;
    int bottom = -1;
    for (int y = 0; y < a.height; ++y) {
        const std::size_t row = static_cast<std::size_t>(y) * row_bytes;
        if (std::memcmp(a.rgba.data() + row, b.rgba.data() + row, row_bytes) != 0) {
            if (top < 0) top = y;
            bottom = y;
        }
    }
    if (top < 0) return std::nullopt;
    int left = a.width;
    int right = -1;
    for (int y = top; y <= bottom; ++y) {
        const std::uint8_t* pa = a.rgba.data() + static_cast<std::size_t>(y) * row_bytes;
        const std::uint8_t* pb = b.rgba.data() + static_cast<std::size_t>(y) * row_bytes;
        auto same = [&](int x) { return std::memcmp(pa + 4 * x, pb + 4 * x, 4) == 0; };
        int x = 0;
        while (x < left && same(x)) ++x;
        left = std::min(left, x);
        int r = a.width - 1;
        while (r > right && same(r)) --r;
        right = std::max(right, r);
    }
    return Rect{left, top, right - left + 1, bottom - top + 1};
}

Image crop(const Image& image, const Rect& rect) {
    Image out;
    out.width = rect.width;
    out.height = rect.height;
    const std::size_t out_row = static_cast<std::size_t>(rect.width) * 4;
    out.rgba.resize(out_row * static_cast<std::size_t>(rect.height));
    for (int y = 0; y < rect.height; ++y) {
        const std::size_t from = (static_cast<std::size_t>(rect.y + y) * static_cast<std::size_t>(image.width) +
                                  static_cast<std::size_t>(rect.x)) * 4;
        std::memcpy(out.rgba.data() + static_cast<std::size_t>(y) * out_row, image.rgba.data() + from, out_row);
    }
    return out;
}

}  // namespace

struct AnimationWriter::Impl {
    AtomicFile file;
    AnimationDesc desc;
    Image previous;                 // the last frame added, whole
    std::int64_t added = 0;
    std::int64_t stored = 0;
    bool finished = false;
    std::uint32_t sequence = 0;     // next fcTL/fdAT sequence number
    std::int64_t actl_offset = 0;   // where acTL's data starts, patched by finish()
    // The frame waiting to be written: its rectangle, its data and how many added frames it
    // stands for (equal frames merge into it).
    Rect pending_rect;
    std::vector<std::vector<std::uint8_t>> pending_data;
    int pending_count = 0;

    Impl(std::string path, const AnimationDesc& d) : file(std::move(path)), desc(d) {}

    void write(std::span<const std::uint8_t> bytes) { file.write(bytes.data(), bytes.size()); }

    void write_pending() {
        std::vector<std::uint8_t> fctl;
        put_u32(fctl, sequence++);
        put_u32(fctl, static_cast<std::uint32_t>(pending_rect.width));
        put_u32(fctl, static_cast<std::uint32_t>(pending_rect.height));
        put_u32(fctl, static_cast<std::uint32_t>(pending_rect.x));
        put_u32(fctl, static_cast<std::uint32_t>(pending_rect.y));
        put_u16(fctl, static_cast<std::uint32_t>(desc.delay_num * pending_count));
        put_u16(fctl, static_cast<std::uint32_t>(desc.delay_den));
        fctl.push_back(kDisposeNone);
        fctl.push_back(kBlendSource);
        write(make_chunk("fcTL", fctl));
        for (const std::vector<std::uint8_t>& data : pending_data) {
            if (stored == 0) {
                write(make_chunk("IDAT", data));
            } else {
                std::vector<std::uint8_t> fdat;
                fdat.reserve(data.size() + 4);
                put_u32(fdat, sequence++);
                fdat.insert(fdat.end(), data.begin(), data.end());
                write(make_chunk("fdAT", fdat));
            }
        }
        ++stored;
        pending_data.clear();
        pending_count = 0;
    }

    void start_pending(const Image& frame, const Rect& rect) {
        PngChunks chunks = split_png(encode_png(crop(frame, rect), desc.encoding));
        if (added == 0) {
            write(kPngSignature);
            write(make_chunk("IHDR", chunks.ihdr));
            actl_offset = file.tell() + 8;
            const std::uint8_t actl[8] = {};  // frame count and plays, filled in by finish()
            write(make_chunk("acTL", actl));
        }
        pending_rect = rect;
        pending_data = std::move(chunks.idat);
        pending_count = 1;
    }
};

AnimationWriter::AnimationWriter(std::string path, const AnimationDesc& desc) {
    auto check = [&](const char* what, int value, int low) {
        if (value < low || value > 65535) {
            throw InputError(SourceLocation{path, 0, 0}, std::string(what) + " " + std::to_string(value) +
                                                             ": expected " + std::to_string(low) + "..65535");
        }
    };
    check("delay_num", desc.delay_num, 1);
    check("delay_den", desc.delay_den, 1);
    check("loops", desc.loops, 0);
    impl_ = std::make_unique<Impl>(std::move(path), desc);
}

AnimationWriter::~AnimationWriter() = default;

void AnimationWriter::add(const Image& frame) {
    Impl& m = *impl_;
    JOSTLE_ASSERT(!m.finished, "AnimationWriter::add after finish");
    if (m.added == 0) {
        m.start_pending(frame, Rect{0, 0, frame.width, frame.height});
        m.previous = frame;
        m.added = 1;
        return;
    }
    JOSTLE_ASSERT(frame.width == m.previous.width && frame.height == m.previous.height,
                  "AnimationWriter::add: every frame must have the first frame's size");
    const std::optional<Rect> rect = changed_rect(m.previous, frame);
    // An unchanged frame lengthens the pending one, as long as its delay fits in 16 bits.
    if (!rect && (m.pending_count + 1) * m.desc.delay_num <= 65535) {
        ++m.pending_count;
        ++m.added;
        return;
    }
    m.write_pending();
    // A frame that must be stored although nothing changed (the delay overflowed) redraws one
    // pixel: an fcTL needs a non-empty rectangle.
    m.start_pending(frame, rect.value_or(Rect{0, 0, 1, 1}));
    m.previous = frame;
    ++m.added;
}

void AnimationWriter::finish() {
    Impl& m = *impl_;
    JOSTLE_ASSERT(!m.finished, "AnimationWriter::finish twice");
    if (m.added == 0) {
        throw InputError(SourceLocation{m.file.path(), 0, 0}, "cannot write an animation without frames");
    }
    m.write_pending();
    m.write(make_chunk("IEND", {}));
    std::vector<std::uint8_t> actl;
    put_u32(actl, static_cast<std::uint32_t>(m.stored));
    put_u32(actl, static_cast<std::uint32_t>(m.desc.loops));
    const std::vector<std::uint8_t> chunk = make_chunk("acTL", actl);
    m.file.seek(m.actl_offset - 8);
    m.write(chunk);
    m.file.commit();
    m.finished = true;
}

std::int64_t AnimationWriter::frames_added() const { return impl_->added; }
std::int64_t AnimationWriter::frames_stored() const { return impl_->stored + (impl_->pending_count > 0 ? 1 : 0); }

}  // namespace jostle
