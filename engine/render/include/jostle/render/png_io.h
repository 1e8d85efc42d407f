// jostle/render/png_io.h: PNG files as straight (not premultiplied) RGBA8 images, by libpng or
// jostle's fast encoder. read_png accepts every PNG colour type and bit depth and converts it to RGBA8;
// write_png_atomic writes a temporary file in the same folder and renames it over the target;
// encode_png makes the PNG bytes in memory (for animations and benchmarks). Frames are encoded
// by jostle's own fast encoder by default (PngEncoder::fast), or by libpng.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace jostle {

// An image in memory: width * height pixels, row-major, top row first, 4 bytes per pixel
// (R, G, B, A), straight alpha. An empty Image{} has no pixels.
struct Image {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgba;  // width * height * 4 bytes
};

// Limits on the images read_png accepts, checked from the PNG header before any pixel memory
// is allocated: each side at most kMaxImageSide, and at most kMaxImagePixels in total
// (64 Mi pixels = 256 MiB of RGBA).
inline constexpr int kMaxImageSide = 16384;
inline constexpr std::int64_t kMaxImagePixels = std::int64_t{1} << 26;

// Reads a PNG file. Palette, grey, grey + alpha, RGB, 1/2/4/8/16-bit and interlaced images
// are converted to RGBA8: a tRNS chunk becomes alpha, images without alpha get alpha 255,
// 16-bit channels are scaled to 8 bits (rounded). No gamma or colour-space conversion.
// Throws jostle::InputError naming the file when it cannot be opened, is not a PNG, is corrupt
// or truncated (bad CRC in a critical chunk, bad compressed data, missing chunks), or is larger
// than the limits above.
Image read_png(const std::string& path);

// The same, from a PNG file's bytes in memory; `name` says what they are in error messages.
Image decode_png(std::span<const std::uint8_t> bytes, const std::string& name);


// The PNG row filter (each row is predicted from its neighbours before zlib sees it).
enum class PngFilter {
    libpng_default,  // what libpng picks: adaptive over all five filters for RGBA
    none,
    sub,             // from the pixel on the left
    up,              // from the pixel above
    paeth,
    adaptive,        // per row, the filter whose output looks smallest
};

// Who compresses: jostle's own encoder (png_fast.cpp: the rows filtered, then a greedy LZ77
// with one hash probe per position and one dynamic Huffman block per strip of rows, made for
// frames), or libpng with zlib.
enum class PngEncoder : std::uint8_t { fast, libpng };

// How encode_png compresses. The zero value is jostle's frame setting: the fast encoder with
// the "up" filter, on one thread. On the render benchmark's frames (tests/bench/render_bench.cpp,
// BM_PngEncode) it is more than 10x faster than libpng's defaults, and its files are about as
// large as libpng's at zlib level 1 (the size_l1 counter); README.md, "Benchmarks", has figures.
// The output is the same bytes for the same pixels whatever `threads` is.
struct PngEncoding {
    PngEncoder encoder = PngEncoder::fast;
    int compression_level = 1;  // libpng only: zlib 0..9, or -1 for libpng's default (6)
    PngFilter filter = PngFilter::up;  // both; the fast encoder's adaptive is libpng's heuristic
    bool rle = false;           // libpng only: zlib's Z_RLE strategy (run lengths only)
    int threads = 1;            // fast only: threads sharing the strips of rows (1..16)
};

// Encodes `image` as an 8-bit RGBA PNG file in memory. Only memory exhaustion can fail it
// (std::bad_alloc); a malformed image is a programming error (assert), as for write_png_atomic.
std::vector<std::uint8_t> encode_png(const Image& image, const PngEncoding& encoding = {});

// Writes `image` as an 8-bit RGBA PNG, encoded as `encoding` says (by default jostle's fast
// encoder), or by libpng at zlib `compression_level` 0..9 (9: smallest, for files kept in git). The data goes to a temporary file in the same folder, which is flushed,
// synced and then renamed over `path`: a crash leaves either the old file or the complete new
// one, never a half-written file. Throws jostle::InputError naming the path when the file
// cannot be written (the temporary file is removed). A malformed image (a side < 1 or above
// kMaxImageSide, more than kMaxImagePixels, rgba.size() != width * height * 4) or a level
// outside 0..9 is a programming error (assert).
void write_png_atomic(const std::string& path, const Image& image, const PngEncoding& encoding = {});
void write_png_atomic(const std::string& path, const Image& image, int compression_level);

}  // namespace jostle
