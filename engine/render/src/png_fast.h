// png_fast.h: jostle's own PNG encoder for rendered frames (png_fast.cpp), behind encode_png's
// PngEncoder::fast. Rows are filtered, then compressed by a small deflate made for speed:
// greedy LZ77 with one hash probe per position, one dynamic Huffman block per strip of rows.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "jostle/render/png_io.h"
#include "pixel_rows.h"

namespace jostle::detail {

// A complete 8-bit RGBA PNG file (signature, IHDR, one IDAT, IEND) of `image`'s pixels, whose
// shape the caller has checked. Rows are grouped into strips of a fixed number of rows (from the
// image's width alone); each strip is filtered and compressed on its own, so `threads`
// workers can share them, and the bytes never depend on how many did.
std::vector<std::uint8_t> encode_png_fast(const PixelRows& image, PngFilter filter, int threads);

// Adler-32 of data (RFC 1950), continuing from `adler` (1 to start): zlib's adler32 value,
// computed 16 bytes at a time with SSE2 (every x86-64 has it; other machines take the byte
// loop). The frames' zlib stream needs it over every filtered byte.
std::uint32_t adler32(std::uint32_t adler, const std::uint8_t* data, std::size_t n);

}  // namespace jostle::detail
