// apng_reader.h: an independent APNG reader for the tests, written from the APNG spec (not
// from animation.cpp): it checks the signature, every chunk's CRC, the chunk order and the
// sequence numbers, then composes each frame onto the canvas as a viewer would, honouring
// the dispose and blend ops. Each frame's pixels are decoded by building a plain PNG around
// its data (IHDR with the frame's size, its IDAT/fdAT payloads as IDAT) for decode_png.
// Any violation throws std::runtime_error saying what is wrong.
#pragma once

#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "jostle/render/png_io.h"

namespace jostle::test {

struct ApngFrame {
    Image canvas;  // the whole picture after this frame is shown
    int x = 0, y = 0, width = 0, height = 0;
    int delay_num = 0, delay_den = 0;
    int dispose_op = 0, blend_op = 0;
};

struct Apng {
    int width = 0, height = 0;
    std::uint32_t num_frames = 0;  // acTL's count
    std::uint32_t plays = 0;
    bool first_frame_is_idat = false;  // an fcTL came before IDAT: the default image is frame 0
    std::vector<ApngFrame> frames;
};

namespace apng_detail {

inline std::uint32_t u32(const std::uint8_t* p) {
    return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) | p[3];
}
inline int u16(const std::uint8_t* p) { return (p[0] << 8) | p[1]; }

inline void put_chunk(std::vector<std::uint8_t>& out, const char* type, const std::uint8_t* data, std::size_t n) {
    const std::uint32_t len = static_cast<std::uint32_t>(n);
    for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<std::uint8_t>(len >> s));
    const std::size_t start = out.size();
    out.insert(out.end(), type, type + 4);
    out.insert(out.end(), data, data + n);
    const uLong crc = crc32(crc32(0L, Z_NULL, 0), out.data() + start, static_cast<uInt>(n + 4));
    for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<std::uint8_t>(crc >> s));
}

// Decodes a frame's data as a PNG of w x h with the file's other IHDR fields.
inline Image decode_frame(const std::vector<std::uint8_t>& ihdr, int w, int h,
                          const std::vector<std::uint8_t>& data) {
    std::vector<std::uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    std::vector<std::uint8_t> header = ihdr;
    for (int i = 0; i < 4; ++i) header[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(static_cast<std::uint32_t>(w) >> (24 - 8 * i));
    for (int i = 0; i < 4; ++i) header[static_cast<std::size_t>(4 + i)] = static_cast<std::uint8_t>(static_cast<std::uint32_t>(h) >> (24 - 8 * i));
    put_chunk(png, "IHDR", header.data(), header.size());
    put_chunk(png, "IDAT", data.data(), data.size());
    put_chunk(png, "IEND", nullptr, 0);
    return decode_png(png, "APNG frame");
}

}  // namespace apng_detail

inline Apng read_apng_bytes(const std::vector<std::uint8_t>& file) {
    using namespace apng_detail;
    auto fail = [](const std::string& what) -> void { throw std::runtime_error("APNG: " + what); };
    static const std::uint8_t kSig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (file.size() < 8 || std::memcmp(file.data(), kSig, 8) != 0) fail("no PNG signature");

    Apng out;
    std::vector<std::uint8_t> ihdr;
    std::uint32_t next_sequence = 0;
    bool seen_actl = false, seen_idat = false, seen_iend = false;
    ApngFrame pending;             // the fcTL being filled
    bool have_pending = false;
    std::vector<std::uint8_t> pending_data;
    Image canvas;

    auto flush = [&]() {
        if (!have_pending) return;
        if (pending_data.empty()) fail("frame without image data");
        const Image part = decode_frame(ihdr, pending.width, pending.height, pending_data);
        Image before = canvas;
        for (int y = 0; y < pending.height; ++y) {
            for (int x = 0; x < pending.width; ++x) {
                const std::uint8_t* src = &part.rgba[(static_cast<std::size_t>(y) * static_cast<std::size_t>(pending.width) + static_cast<std::size_t>(x)) * 4];
                std::uint8_t* dst = &canvas.rgba[(static_cast<std::size_t>(pending.y + y) * static_cast<std::size_t>(out.width) + static_cast<std::size_t>(pending.x + x)) * 4];
                if (pending.blend_op == 0) {
                    std::memcpy(dst, src, 4);
                } else {
                    // OVER on straight alpha (the spec's formula), rounded.
                    const double sa = src[3] / 255.0, da = dst[3] / 255.0;
                    const double oa = sa + da * (1 - sa);
                    for (int c = 0; c < 3; ++c) {
                        const double v = oa == 0 ? 0 : (src[c] * sa + dst[c] * da * (1 - sa)) / oa;
                        dst[c] = static_cast<std::uint8_t>(v + 0.5);
                    }
                    dst[3] = static_cast<std::uint8_t>(oa * 255 + 0.5);
                }
            }
        }
        pending.canvas = canvas;
        out.frames.push_back(pending);
        // Dispose after showing: 1 clears the region to transparent black, 2 restores it.
        for (int y = 0; y < pending.height; ++y) {
            for (int x = 0; x < pending.width; ++x) {
                const std::size_t at = (static_cast<std::size_t>(pending.y + y) * static_cast<std::size_t>(out.width) + static_cast<std::size_t>(pending.x + x)) * 4;
                if (pending.dispose_op == 1) std::memset(&canvas.rgba[at], 0, 4);
                if (pending.dispose_op == 2) std::memcpy(&canvas.rgba[at], &before.rgba[at], 4);
            }
        }
        have_pending = false;
        pending_data.clear();
    };

    std::size_t at = 8;
    while (!seen_iend) {
        if (at + 12 > file.size()) fail("truncated (no IEND)");
        const std::uint32_t len = u32(&file[at]);
        if (at + 12 + len > file.size()) fail("chunk runs past the end");
        const std::string type(reinterpret_cast<const char*>(&file[at + 4]), 4);
        const std::uint8_t* data = &file[at + 8];
        const uLong crc = crc32(crc32(0L, Z_NULL, 0), &file[at + 4], len + 4);
        if (crc != u32(data + len)) fail("bad CRC in " + type);
        if (at == 8 && type != "IHDR") fail("first chunk is " + type + ", not IHDR");

        if (type == "IHDR") {
            ihdr.assign(data, data + len);
            out.width = static_cast<int>(u32(data));
            out.height = static_cast<int>(u32(data + 4));
            canvas.width = out.width;
            canvas.height = out.height;
            canvas.rgba.assign(static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height) * 4, 0);
        } else if (type == "acTL") {
            if (seen_idat) fail("acTL after IDAT");
            if (len != 8) fail("acTL length");
            seen_actl = true;
            out.num_frames = u32(data);
            out.plays = u32(data + 4);
        } else if (type == "fcTL") {
            if (len != 26) fail("fcTL length");
            if (u32(data) != next_sequence++) fail("fcTL sequence number out of order");
            flush();
            if (!seen_idat) out.first_frame_is_idat = true;
            pending = ApngFrame{};
            pending.width = static_cast<int>(u32(data + 4));
            pending.height = static_cast<int>(u32(data + 8));
            pending.x = static_cast<int>(u32(data + 12));
            pending.y = static_cast<int>(u32(data + 16));
            pending.delay_num = u16(data + 20);
            pending.delay_den = u16(data + 22);
            pending.dispose_op = data[24];
            pending.blend_op = data[25];
            if (pending.width < 1 || pending.height < 1 || pending.x + pending.width > out.width ||
                pending.y + pending.height > out.height) {
                fail("fcTL region outside the image");
            }
            if (out.frames.empty() && out.first_frame_is_idat &&
                (pending.x != 0 || pending.y != 0 || pending.width != out.width || pending.height != out.height)) {
                fail("frame 0 must cover the whole image");
            }
            have_pending = true;
        } else if (type == "IDAT") {
            seen_idat = true;
            if (!out.first_frame_is_idat) fail("IDAT not part of the animation (not supported by this reader)");
            if (!out.frames.empty()) fail("IDAT after frame 0");
            pending_data.insert(pending_data.end(), data, data + len);
        } else if (type == "fdAT") {
            if (!seen_idat) fail("fdAT before IDAT");
            if (u32(data) != next_sequence++) fail("fdAT sequence number out of order");
            if (!have_pending) fail("fdAT without fcTL");
            pending_data.insert(pending_data.end(), data + 4, data + len);
        } else if (type == "IEND") {
            flush();
            seen_iend = true;
        }
        at += 12 + len;
    }
    if (at != file.size()) fail("bytes after IEND");
    if (!seen_actl) fail("no acTL");
    if (out.num_frames != out.frames.size()) fail("acTL says " + std::to_string(out.num_frames) + " frames, found " + std::to_string(out.frames.size()));
    return out;
}

inline Apng read_apng(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error("cannot open " + path);
    std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    return read_apng_bytes(bytes);
}

}  // namespace jostle::test
