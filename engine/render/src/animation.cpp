// animation.cpp: the APNG container around frames encoded by encode_png.
// An APNG is a PNG whose chunks are: signature, IHDR, acTL (frame count, plays), then per
// frame an fcTL (sequence, size, offset, delay, dispose/blend ops) and its image data: IDAT
// chunks for frame 0 (so a plain PNG viewer shows it), fdAT chunks (sequence + IDAT payload)
// for the others; then IEND. Sequence numbers count fcTL and fdAT chunks together from 0.
// Each frame's data is the IDAT payload of a PNG of just its rectangle, which encode_png_rows
// makes from the frame in place.
#include "jostle/render/animation.h"

#include <zlib.h>

#include <algorithm>
#include <cstring>
#include <optional>
#include <span>
#include <vector>

#include "jostle/core/atomic_file.h"
#include "jostle/core/error.h"
#include "pixel_rows.h"

namespace jostle {
namespace {

constexpr std::uint8_t kPngSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
constexpr std::uint8_t kDisposeNone = 0;
constexpr std::uint8_t kBlendSource = 0;
constexpr std::uint8_t kBlendOver = 1;

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

// The IDAT payloads of a PNG file that the encoder made (trusted: well formed by
// construction), as spans into the file's bytes (a frame's data is written from there, not
// copied out first), and IHDR's data.
struct PngChunks {
    std::span<const std::uint8_t> ihdr;
    std::vector<std::span<const std::uint8_t>> idat;
};

PngChunks split_png(const std::vector<std::uint8_t>& png) {
    PngChunks out;
    std::size_t at = sizeof kPngSignature;
    while (at + 12 <= png.size()) {
        const std::uint32_t length = get_u32(png.data() + at);
        const std::uint8_t* type = png.data() + at + 4;
        const std::uint8_t* data = type + 4;
        JOSTLE_ASSERT(at + 12 + length <= png.size(), "split_png: chunk runs past the end");
        if (std::memcmp(type, "IHDR", 4) == 0) out.ihdr = {data, length};
        if (std::memcmp(type, "IDAT", 4) == 0) out.idat.emplace_back(data, length);
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

std::uint32_t pixel(const std::uint8_t* row, int x) {
    std::uint32_t p;
    std::memcpy(&p, row + 4 * static_cast<std::size_t>(x), 4);
    return p;
}

// The smallest rectangle holding every pixel that differs between a and b (same size), or
// nullopt when they are equal. Rows are compared whole first; only a row that differs is
// searched, and only outside the columns already in the rectangle (the rows between the first
// and last changed ones are mostly equal in game footage, and pixel by pixel they were most
// of an animation's time).
std::optional<Rect> changed_rect(const Image& a, const Image& b) {
    const std::size_t row_bytes = static_cast<std::size_t>(a.width) * 4;
    int top = -1;
    int bottom = -1;
    int left = a.width;
    int right = -1;
    for (int y = 0; y < a.height; ++y) {
        const std::uint8_t* pa = a.rgba.data() + static_cast<std::size_t>(y) * row_bytes;
        const std::uint8_t* pb = b.rgba.data() + static_cast<std::size_t>(y) * row_bytes;
        if (std::memcmp(pa, pb, row_bytes) == 0) continue;
        if (top < 0) top = y;
        bottom = y;
        int x = 0;
        while (x < left && pixel(pa, x) == pixel(pb, x)) ++x;
        left = std::min(left, x);
        int r = a.width - 1;
        while (r > right && pixel(pa, r) == pixel(pb, r)) --r;
        right = std::max(right, r);
    }
    if (top < 0) return std::nullopt;
    return Rect{left, top, right - left + 1, bottom - top + 1};
}

// The pixels of rect that `frame` changes from `previous`, the others transparent black, for
// a frame drawn with blend op OVER: a transparent pixel leaves the one below it, an opaque
// one replaces it, so the viewer shows `frame` exactly, and the unchanged pixels compress
// to almost nothing. nullopt when a changed pixel is not opaque (OVER would blend it).
std::optional<Image> changes_only(const Image& previous, const Image& frame, const Rect& rect) {
    Image out;
    out.width = rect.width;
    out.height = rect.height;
    out.rgba.assign(static_cast<std::size_t>(rect.width) * static_cast<std::size_t>(rect.height) * 4, 0);
    const std::size_t row_bytes = static_cast<std::size_t>(frame.width) * 4;
    for (int y = 0; y < rect.height; ++y) {
        const std::size_t from = static_cast<std::size_t>(rect.y + y) * row_bytes + static_cast<std::size_t>(rect.x) * 4;
        const std::uint8_t* now = frame.rgba.data() + from;
        const std::uint8_t* before = previous.rgba.data() + from;
        std::uint8_t* to = out.rgba.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(rect.width) * 4;
        for (int x = 0; x < rect.width; ++x) {
            const std::uint32_t p = pixel(now, x);
            if (p == pixel(before, x)) continue;
            if (now[4 * x + 3] != 255) return std::nullopt;
            std::memcpy(to + 4 * static_cast<std::size_t>(x), &p, 4);
        }
    }
    return out;
}

// Copies rect's pixels of `from` into `to` (same size).
void copy_rect(const Image& from, Image& to, const Rect& rect) {
    const std::size_t row_bytes = static_cast<std::size_t>(from.width) * 4;
    for (int y = rect.y; y < rect.y + rect.height; ++y) {
        const std::size_t at = static_cast<std::size_t>(y) * row_bytes + static_cast<std::size_t>(rect.x) * 4;
        std::memcpy(to.rgba.data() + at, from.rgba.data() + at, static_cast<std::size_t>(rect.width) * 4);
    }
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
    // The frame waiting to be written: its rectangle and blend op, its encoded PNG and that
    // PNG's IDAT payloads, and how many added frames it stands for (equal frames merge into it).
    Rect pending_rect;
    std::uint8_t pending_blend = kBlendSource;
    std::vector<std::uint8_t> pending_png;
    std::vector<std::span<const std::uint8_t>> pending_data;
    int pending_count = 0;

    // A target that cannot be patched later (a pipe, `>>`) says so here, before the run that
    // makes the frames, not at the first frame.
    Impl(std::string path, const AnimationDesc& d) : file(std::move(path)), desc(d) { (void)file.tell(); }

    void write(std::span<const std::uint8_t> bytes) { file.write(bytes.data(), bytes.size()); }

    // One chunk: length, type, data, CRC of type and data; the data is `head` then `body`
    // (an fdAT's sequence number, then the IDAT payload it carries), written where they are.
    void write_chunk(const char (&type)[5], std::span<const std::uint8_t> head, std::span<const std::uint8_t> body = {}) {
        std::vector<std::uint8_t> start;
        put_u32(start, static_cast<std::uint32_t>(head.size() + body.size()));
        start.insert(start.end(), type, type + 4);
        uLong crc = crc32(0L, Z_NULL, 0);
        crc = crc32(crc, start.data() + 4, 4);
        // (Not with an empty span: crc32 of a null pointer restarts the CRC.)
        for (const std::span<const std::uint8_t> part : {head, body}) {
            if (!part.empty()) crc = crc32(crc, part.data(), static_cast<uInt>(part.size()));
        }
        std::vector<std::uint8_t> end;
        put_u32(end, static_cast<std::uint32_t>(crc));
        write(start);
        write(head);
        write(body);
        write(end);
    }

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
        fctl.push_back(pending_blend);
        write_chunk("fcTL", fctl);
        for (const std::span<const std::uint8_t> data : pending_data) {
            if (stored == 0) {
                write_chunk("IDAT", data);
            } else {
                std::vector<std::uint8_t> seq;
                put_u32(seq, sequence++);
                write_chunk("fdAT", seq, data);
            }
        }
        ++stored;
        pending_data.clear();
        pending_count = 0;
    }

    // Encodes rect of frame as the pending frame: with `changes`, those pixels drawn OVER the
    // previous frame; else rect of frame, read in place, drawn as the SOURCE.
    void start_pending(const Image& frame, const Rect& rect, const std::optional<Image>& changes = std::nullopt) {
        pending_png = changes ? encode_png(*changes, desc.encoding)
                              : detail::encode_png_rows(detail::rows_of(frame, rect.x, rect.y, rect.width, rect.height), desc.encoding);
        pending_blend = changes ? kBlendOver : kBlendSource;
        const PngChunks chunks = split_png(pending_png);
        if (added == 0) {
            write(kPngSignature);
            write_chunk("IHDR", chunks.ihdr);
            actl_offset = file.tell() + 8;
            const std::uint8_t actl[8] = {};  // frame count and plays, filled in by finish()
            write_chunk("acTL", actl);
        }
        pending_rect = rect;
        pending_data = chunks.idat;
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
    if (rect) {
        m.start_pending(frame, *rect, changes_only(m.previous, frame, *rect));
    } else {
        m.start_pending(frame, Rect{0, 0, 1, 1});
    }
    // The previous frame differs from this one only inside rect.
    if (rect) copy_rect(frame, m.previous, *rect);
    ++m.added;
}

void AnimationWriter::finish() {
    Impl& m = *impl_;
    JOSTLE_ASSERT(!m.finished, "AnimationWriter::finish twice");
    if (m.added == 0) {
        throw InputError(SourceLocation{m.file.path(), 0, 0}, "cannot write an animation without frames");
    }
    m.write_pending();
    m.write_chunk("IEND", {});
    std::vector<std::uint8_t> actl;
    put_u32(actl, static_cast<std::uint32_t>(m.stored));
    put_u32(actl, static_cast<std::uint32_t>(m.desc.loops));
    m.file.seek(m.actl_offset - 8);
    m.write_chunk("acTL", actl);
    m.file.commit();
    m.finished = true;
}

std::int64_t AnimationWriter::frames_added() const { return impl_->added; }
std::int64_t AnimationWriter::frames_stored() const { return impl_->stored + (impl_->pending_count > 0 ? 1 : 0); }

}  // namespace jostle
