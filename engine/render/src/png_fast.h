// png_fast.h: jostle's own PNG encoder for rendered frames (png_fast.cpp), behind encode_png's
// PngEncoder::fast. Rows are filtered, then compressed by a small deflate made for speed:
// greedy LZ77 with one hash probe per position, one dynamic Huffman block per strip of rows.
#pragma once

#include <cstdint>
#include <vector>

#include "jostle/render/png_io.h"

namespace jostle::detail {

// A complete 8-bit RGBA PNG file (signature, IHDR, one IDAT, IEND) of `image`, whose shape
// the caller has checked. Rows are grouped into strips of a fixed number of rows (from the
// image's width alone); each strip is filtered and compressed on its own, so `threads`
// workers can share them, and the bytes never depend on how many did.
std::vector<std::uint8_t> encode_png_fast(const Image& image, PngFilter filter, int threads);

}  // namespace jostle::detail
